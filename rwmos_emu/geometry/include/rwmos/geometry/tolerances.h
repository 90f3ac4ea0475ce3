// SPDX-License-Identifier: MIT
// Every tolerance and limit of the compensation geometry, in one place, each with
// the reason for its value. Lengths are in interpolation units (think mm), angles
// in radians. docs/compensation.md lists them with the rules that use them.
#pragma once

#include <cstddef>
#include <numbers>

namespace rwmos::geom {

// Two points closer than this are one point: a line this short has no direction,
// an arc whose end is this close to its start is a full circle. Far below any
// programmable resolution (0.1 um), far above double rounding at kMaxCoordinate.
inline constexpr double kPointTolerance = 1e-9;

// Coordinates and tool radii beyond this are refused: no machine is 100 m long, and
// the bound keeps double rounding (about 1.5e-11 here) far below kPointTolerance.
inline constexpr double kMaxCoordinate = 1e5;

// An emitted arc whose chord is at most this (and that turns less than half a circle)
// is emitted as a line, so no emitted arc can be mistaken for a full circle.
inline constexpr double kMinArcChord = 2 * kPointTolerance;

// How far a pushed element may start from the end of the held one: the spooler builds
// each start from the previous end, so only rounding of composed coordinates is allowed.
inline constexpr double kContinuityTolerance = 1e-6;

// Corners turning less than this are tangent joins (no transition element): the two
// offset end points then lie at most r * 1e-9 apart (5e-8 at r = 50), and are snapped.
inline constexpr double kTangentAngleTolerance = 1e-9;

// Start and end radius of an arc may differ by this much before CenterError:
// rounding start, end and centre to 0.001 mm alone can make them differ by 0.0028 mm.
inline constexpr double kCenterRadiusTolerance = 0.003;

// An offset arc radius at or below this is no arc (CalcError): the tool radius is at
// least the programmed radius on the concave side.
inline constexpr double kMinOffsetRadius = kPointTolerance;

// An inside-corner intersection may lie this far beyond either end of an offset element
// and still trim it: the intersection formulas round to about 1e-13 at 100 mm.
inline constexpr double kTrimTolerance = 1e-9;

// Linear (G25) outside transitions extend both offset elements to their intersection for
// turns up to this angle (each extension at most r). Sharper turns would put the
// intersection r / cos(turn / 2) away, unbounded at 180 degrees, so they are bounded:
// each offset element is extended by r and the two ends are joined by a chamfer line.
inline constexpr double kLinearCornerMaxTurn = std::numbers::pi / 2;

// Elements without motion in the plane (pure third-axis moves) that may follow the held
// element before the next plane move; they wait with it, as common controls allow a
// small, fixed number of blocks without motion in the compensation plane.
inline constexpr std::size_t kMaxPlaneFreeElements = 8;

}  // namespace rwmos::geom
