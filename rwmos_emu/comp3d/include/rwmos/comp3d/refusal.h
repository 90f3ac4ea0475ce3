// SPDX-License-Identifier: MIT
// Why the 3D compensation refuses an input. Each reason has one name and one line for the
// user, through one table (refusal.cpp); kNone means the input was accepted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace rwmos::comp3d {

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

std::string_view refusal_name(Refusal r) noexcept;     // "PositiveOversize"
std::string_view refusal_message(Refusal r) noexcept;  // one line of English

}  // namespace rwmos::comp3d
