// SPDX-License-Identifier: MIT
#include <fmt/format.h>

#include "objif/descriptor.h"
#include "objif/value.h"

namespace objif {

std::string_view value_type_name(ValueType t) noexcept {
    switch (t) {
        case ValueType::kInt32: return "int";
        case ValueType::kDouble: return "double";
    }
    return "?";
}

std::string Value::to_string() const {
    // fmt's default for double is the shortest form that reads back exactly.
    return is_int() ? fmt::format("{}", i_) : fmt::format("{}", d_);
}

std::string Address::to_string() const {
    return fmt::format("{}/{}/{}/{}", bus, device, index, subindex);
}

}  // namespace objif
