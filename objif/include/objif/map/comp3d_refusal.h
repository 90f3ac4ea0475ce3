// SPDX-License-Identifier: MIT
// Why the 3D compensation refuses an input. Each reason has one name and one line for the
// user, through one table (below); kNone means the input was accepted. The numbers are the
// values of the 3D compensation module's LastError object: part of the object contract between
// a host and a board, so they live in objif (docs/design.md section 2, "Shared declarations").
// Header-only, so that host tools (apcictl run) name the board's LastError codes without the
// emulator; the emulator's 3D compensation includes it as rwmos/comp3d/refusal.h. The limits
// the comments name (kMaxCoordinate, kUnitVectorTolerance, ...) are the emulator's
// (rwmos/comp3d/tolerances.h); the messages state their values.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace objif::map::comp3d {

enum class Refusal : std::uint8_t {
    kNone = 0,
    kInvalidCoordinate,             // a point is not finite or lies beyond kMaxCoordinate
    kVectorNotNormalised,           // | |v| - 1 | > kUnitVectorTolerance (or not finite)
    kInvalidToolDimension,          // R or R2 negative, not finite or beyond kMaxCoordinate
    kCornerRadiusExceedsRadius,     // R2 > R: no such tool
    kInvalidDelta,                  // a delta value not finite or beyond kMaxCoordinate
    kEffectiveRadiusNegative,       // R + DR < 0 or R2 + DR2 < 0
    kEffectiveCornerExceedsRadius,  // R2 + DR2 > R + DR
    kPositiveOversize,              // a summed delta > 0 without M107
    kNormalAgainstTool,             // N.T < -kNormalAgainstToolTolerance
    kNoSideFromMotion,              // RL/RR, but the motion is zero or parallel to T
    kNoCompensationSide,            // peripheral milling without N and without RL/RR
    kRadiusCompensationRunning,     // the TC module's 2D radius compensation runs
};

inline constexpr std::size_t kRefusalCount = 13;

namespace detail {
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

}  // namespace detail

// "PositiveOversize"; "Unknown" for a value that is no Refusal.
constexpr std::string_view refusal_name(Refusal r) noexcept {
    const auto i = static_cast<std::size_t>(r);
    return i < detail::kRefusalTable.size() ? detail::kRefusalTable[i].name : "Unknown";
}
// One line of English.
constexpr std::string_view refusal_message(Refusal r) noexcept {
    const auto i = static_cast<std::size_t>(r);
    return i < detail::kRefusalTable.size() ? detail::kRefusalTable[i].message : "unknown refusal";
}

}  // namespace objif::map::comp3d
