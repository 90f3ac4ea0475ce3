// SPDX-License-Identifier: MIT
#include "apci/nc/diagnostic.h"

#include <fmt/format.h>

#include "apci/nc/events.h"
#include "objif/enum_names.h"

namespace apci::nc {

std::string_view error_kind_name(ErrorKind k) noexcept {
    static constexpr auto kNames = objif::enum_names<ErrorKind::kIo, ErrorKind::kUnsupported>(
        {"Io", "Syntax", "UnknownWord", "Conflict", "Value", "Geometry", "ProgramRule",
         "Unsupported"},
        "Unknown");
    return kNames(k);
}

std::string Diagnostic::to_string() const {
    if (line == 0) return fmt::format("{}: {}", file, message);
    // The block's N number too, where it has one: the machinist looks for it in the program.
    if (block != kNoBlockNumber && !klartext)
        return fmt::format("{}:{}:{}: N{}: {}", file, line, column, block, message);
    return fmt::format("{}:{}:{}: {}", file, line, column, message);
}

std::string_view event_name(const EventData& data) noexcept {
    static constexpr std::string_view kNames[] = {
        "rapid", "line",      "arc",  "tool",      "compensation", "corner", "plane",
        "end",   "tool_call", "tcpm", "prog_path", "oversize",     "head",   "vector_line",
        "otc",   "kinematics", "trafo", "not_emulated", "variable_write",
        "correction_row", "selection", "collision"};
    static_assert(std::size(kNames) == std::variant_size_v<EventData>);
    return kNames[data.index()];
}

}  // namespace apci::nc
