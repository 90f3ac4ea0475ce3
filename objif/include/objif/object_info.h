// SPDX-License-Identifier: MIT
// The static description of an object of the universal object interface: where it lives,
// its type, access, range, default, the rule it follows and its name. The board's object map
// (objif/map/objects.h) is a table of these, shared by the host and the emulator; the
// emulator's modules attach the hooks that hold their rules (objif/dictionary.h).
#pragma once

#include <cstdint>
#include <string_view>

#include "objif/descriptor.h"
#include "objif/value.h"

namespace objif {

enum class Access : std::uint8_t { kRead = 1, kWrite = 2, kReadWrite = 3 };
constexpr bool can_read(Access a) noexcept {
    return (static_cast<int>(a) & 1) != 0;
}
constexpr bool can_write(Access a) noexcept {
    return (static_cast<int>(a) & 2) != 0;
}
std::string_view access_name(Access a) noexcept;  // "r", "w", "r/w"

inline constexpr double kInt32Min = -2147483648.0;
inline constexpr double kInt32Max = 2147483647.0;

// The static description of one object (or of a row of objects over an index
// range, e.g. compensation groups 0..3).
struct ObjectInfo {
    std::int32_t device = 0;
    std::int32_t index_first = 0;
    std::int32_t index_last = 0;
    std::int32_t subindex = 0;
    std::string_view name;
    ValueType type = ValueType::kInt32;
    Access access = Access::kReadWrite;
    double min = kInt32Min;  // inclusive range checked on write
    double max = kInt32Max;
    Value default_value;
    std::string_view rule;  // where the rule comes from ("[APCI-TC] Table 2", "design: ...")
    // The last part of the object's dotted name (objif/names.h): "radius", "x_axis_nr",
    // "position[3]". Empty for an object the map does not name.
    std::string_view key;
    std::string_view unit;  // of the value: "mm", "deg", "us", "PU", "0.1 um"; empty if none

    constexpr bool covers(const Address& a) const noexcept {
        return a.device == device && a.index >= index_first && a.index <= index_last &&
               a.subindex == subindex;
    }
};

}  // namespace objif
