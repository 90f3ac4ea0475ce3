// SPDX-License-Identifier: MIT
#include "apci/nc/diagnostic.h"

#include <fmt/format.h>

#include "apci/nc/events.h"

namespace apci::nc {

std::string_view error_kind_name(ErrorKind k) noexcept {
    switch (k) {
        case ErrorKind::kIo:
            return "Io";
        case ErrorKind::kSyntax:
            return "Syntax";
        case ErrorKind::kUnknownWord:
            return "UnknownWord";
        case ErrorKind::kConflict:
            return "Conflict";
        case ErrorKind::kValue:
            return "Value";
        case ErrorKind::kGeometry:
            return "Geometry";
        case ErrorKind::kProgramRule:
            return "ProgramRule";
        case ErrorKind::kUnsupported:
            return "Unsupported";
    }
    return "Unknown";
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
