// SPDX-License-Identifier: MIT
#include "rwmos/comp3d/refusal.h"

#include <array>

namespace rwmos::comp3d {
namespace {

struct RefusalRow {
    Refusal refusal;
    std::string_view name;
    std::string_view message;
};

// The one table; the static_asserts keep it in step with the enum.
constexpr std::array kRefusalTable{
    RefusalRow{Refusal::kNone, "None", "no error"},
    RefusalRow{Refusal::kInvalidCoordinate, "InvalidCoordinate",
               "a coordinate is not finite or lies beyond +-1e5"},
    RefusalRow{Refusal::kVectorNotNormalised, "VectorNotNormalised",
               "vector is not normalised: its length differs from 1 by more than 1e-4"},
    RefusalRow{Refusal::kInvalidToolDimension, "InvalidToolDimension",
               "tool radius R and corner radius R2 must be finite, >= 0 and at most 1e5"},
    RefusalRow{Refusal::kCornerRadiusExceedsRadius, "CornerRadiusExceedsRadius",
               "corner radius R2 is larger than the tool radius R"},
    RefusalRow{Refusal::kInvalidDelta, "InvalidDelta",
               "delta values DL, DR, DR2 must be finite and at most 1e5 in size"},
    RefusalRow{Refusal::kEffectiveRadiusNegative, "EffectiveRadiusNegative",
               "R + DR or R2 + DR2 is negative: the deltas take away more than the tool has"},
    RefusalRow{Refusal::kEffectiveCornerExceedsRadius, "EffectiveCornerExceedsRadius",
               "R2 + DR2 is larger than R + DR: no such tool"},
    RefusalRow{Refusal::kPositiveOversize, "PositiveOversize",
               "tool with a positive oversize (summed DL, DR or DR2 > 0): allow it with M107"},
    RefusalRow{Refusal::kNormalAgainstTool, "NormalAgainstTool",
               "surface normal N points against the tool vector T: the tool cannot touch the "
               "surface from this side"},
    RefusalRow{Refusal::kNoSideFromMotion, "NoSideFromMotion",
               "RL/RR give no side: the motion is zero or parallel to the tool vector"},
    RefusalRow{Refusal::kNoCompensationSide, "NoCompensationSide",
               "peripheral milling needs a side: a surface normal N or RL/RR"},
    RefusalRow{Refusal::kRadiusCompensationRunning, "RadiusCompensationRunning",
               "the TC module's radius compensation runs: 3D compensation and 2D radius "
               "compensation do not combine (STATUS = 0 first)"},
};
static_assert(kRefusalTable.size() == kRefusalCount, "refusal table and enum out of step");

constexpr bool rows_in_enum_order() {
    for (std::size_t i = 0; i < kRefusalTable.size(); ++i) {
        if (static_cast<std::size_t>(kRefusalTable[i].refusal) != i) return false;
    }
    return true;
}
static_assert(rows_in_enum_order(), "refusal table rows must follow the enum order");

}  // namespace

std::string_view refusal_name(Refusal r) noexcept {
    const auto i = static_cast<std::size_t>(r);
    return i < kRefusalTable.size() ? kRefusalTable[i].name : "Unknown";
}

std::string_view refusal_message(Refusal r) noexcept {
    const auto i = static_cast<std::size_t>(r);
    return i < kRefusalTable.size() ? kRefusalTable[i].message : "unknown refusal";
}

}  // namespace rwmos::comp3d
