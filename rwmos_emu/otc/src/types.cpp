// SPDX-License-Identifier: MIT
#include "rwmos/otc/types.h"

#include "objif/enum_names.h"

namespace rwmos::otc {
namespace {

constexpr auto kProcessingTypeNames =
    objif::enum_names<ProcessingType::kRadius, ProcessingType::kSurfNormDir>(
        {"RADIUS", "LENGTH", "TOOL_DIR", "SURF_NORM_DIR"}, "?");
constexpr auto kModeNames =
    objif::enum_names<Mode::kCont, Mode::kAuto>({"CONT", "DISC", "AUTO"}, "?");

}  // namespace

std::string_view processing_type_name(ProcessingType t) noexcept {
    return kProcessingTypeNames(t);
}

std::string_view mode_name(Mode m) noexcept {
    return kModeNames(m);
}

std::optional<ProcessingType> processing_type_from_int(std::int32_t v) noexcept {
    if (v < 0 || v > static_cast<std::int32_t>(ProcessingType::kSurfNormDir)) return std::nullopt;
    return static_cast<ProcessingType>(v);
}

std::optional<Mode> mode_from_int(std::int32_t v) noexcept {
    if (v < 0 || v > static_cast<std::int32_t>(Mode::kAuto)) return std::nullopt;
    return static_cast<Mode>(v);
}

AxisUnitRole axis_unit_role(ProcessingType t, Mode m, int axis_in_sequence) noexcept {
    if (!mode_has_discrete(m) || axis_in_sequence < 0) return AxisUnitRole::kIgnored;
    if (axis_in_sequence >= 3) return AxisUnitRole::kAxis;
    switch (t) {
        case ProcessingType::kRadius:
        case ProcessingType::kLength:
            return AxisUnitRole::kAxis;
        case ProcessingType::kToolDir:
        case ProcessingType::kSurfNormDir:
            return axis_in_sequence == 2 ? AxisUnitRole::kDirection : AxisUnitRole::kIgnored;
    }
    return AxisUnitRole::kIgnored;
}

}  // namespace rwmos::otc
