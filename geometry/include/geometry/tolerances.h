// SPDX-License-Identifier: MIT
// Every tolerance and limit of the compensation geometry, in one place, each with
// the reason for its value. Lengths are in interpolation units (think mm), angles
// in radians. docs/compensation.md ("The tolerance model") derives them and lists
// the rules that use them.
//
// The model has two lengths. The program's resolution: NC programs are written with
// at least three decimals of a millimetre, so each coordinate may be off by half a
// micrometre and a point by kPointRounding. The path tolerance: how far the
// compensated path may stray from the exact construction (every point at the tool
// radius from its element) because of how a join was read. Every tolerance below is
// one of these two, or a consequence of them, or (kPointTolerance) far below both.
#pragma once

#include <cstddef>
#include <numbers>

namespace geom {

// Two points closer than this are one point: a line this short has no direction,
// an arc whose end is this close to its start is a full circle. Far below any
// programmable resolution (0.1 um), far above double rounding at kMaxCoordinate.
inline constexpr double kPointTolerance = 1e-9;

// Coordinates and tool radii beyond this are refused: no machine is 100 m long, and
// the bound keeps double rounding (about 1.5e-11 here) far below kPointTolerance.
inline constexpr double kMaxCoordinate = 1e5;

// The coarsest resolution a program may be written with: three decimals of a mm.
inline constexpr double kCoordinateResolution = 1e-3;
// How far rounding to kCoordinateResolution can move a point: half a step in each of
// its two plane coordinates.
inline constexpr double kPointRounding = 0.5 * kCoordinateResolution * std::numbers::sqrt2;

// How far the compensated path may stray from the exact construction because of how a
// join was read (0.1 um: the finest resolution controls work with, far below what a
// machine cuts). It sets the tangent joins, the trim tolerance and the offset-radius
// limit below.
inline constexpr double kPathTolerance = 1e-4;

// An emitted arc whose chord is at most this (and that turns less than half a circle)
// is emitted as a line, so no emitted arc can be mistaken for a full circle.
inline constexpr double kMinArcChord = 2 * kPointTolerance;

// How far a pushed element may start from the end of the held one: the spooler builds
// each start from the previous end, so only rounding of composed coordinates is allowed.
inline constexpr double kContinuityTolerance = 1e-6;

// A join is tangent when its two offset ends lie at most kPathTolerance apart: 2 r
// |sin(turn / 2)| (offset_gap, classify_corner in corner.h). The next element then starts
// where the held one ends, which moves its start by at most that much.

// Start and end radius of an arc may differ by this much before CenterError: rounding
// start, end and centre to kCoordinateResolution moves each radius by up to
// kPointRounding per point, 3 * 0.00071 = 0.0021 in all. Within it the arc runs from
// its start to its end point with the radius changing linearly with the angle (a
// spiral, as LinuxCNC runs such arcs), so it ends exactly where it was programmed.
inline constexpr double kCenterRadiusTolerance = 0.003;
static_assert(kCenterRadiusTolerance >= 3 * kPointRounding);

// An inside turn of nearly 180 degrees is a reversal (the tool goes round the end of the
// element) when the wedge between the two elements, over the shorter of them, is
// narrower than two rounded points can make it (a program that goes back along the line
// it came, written with rounded coordinates) and its angle is at most
// kMaxReversalWedgeAngle (rounding tilts no element of a useful length further; an
// element so short that rounding could tilt it more has no direction to read). Wider
// wedges are inside corners. Read as a reversal, the path comes closer to the contour
// than r by at most the wedge's width.
inline constexpr double kReversalWedgeWidth = 2 * kPointRounding;
inline constexpr double kMaxReversalWedgeAngle = std::numbers::pi / 180;

// On the concave side of an arc the offset radius is R - r. The tool is too large for
// the arc (CalcError, TC Table 4) only when it would cut into the arc by more than the
// path tolerance; a tool that fits the arc's radius exactly keeps its centre on the arc's
// centre. Offset radii are kept at least kMinOffsetRadius so that an offset arc keeps
// its angles.
inline constexpr double kOffsetRadiusTolerance = kPathTolerance;
inline constexpr double kMinOffsetRadius = 10 * kPointTolerance;

// An inside-corner intersection may lie this far (along the element) beyond either end of
// an offset element and still trim it; the element is then left with zero length at
// that end. The path tolerance: the path backs up by at most that much.
inline constexpr double kTrimTolerance = kPathTolerance;

// Linear (G25) outside transitions extend both offset elements to their intersection for
// turns up to this angle (each extension at most r). Sharper turns would put the
// intersection r / cos(turn / 2) away, unbounded at 180 degrees, so they are bounded:
// each offset element is extended by r and the two ends are joined by a chamfer line.
inline constexpr double kLinearCornerMaxTurn = std::numbers::pi / 2;

// Elements without motion in the plane (pure third-axis moves) that may follow the held
// element before the next plane move; they wait with it, as common controls allow a
// small, fixed number of blocks without motion in the compensation plane.
inline constexpr std::size_t kMaxPlaneFreeElements = 8;

}  // namespace geom
