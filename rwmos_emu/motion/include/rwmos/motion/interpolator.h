// SPDX-License-Identifier: MIT
// The interpolator: where the axes are at cycle k of a move. Pure functions,
// no state: the executor (executor.h) calls them per cycle when cycles are
// observed, or once at the end of a stretch when nothing observes them, and
// both give the same bits because position_at(k) depends only on k and n.
//
// A move of path length L at feed F (units/min) with cycle length T (s) takes
// n = ceil(L / (F/60 * T)) cycles; cycle k puts the axes at the fraction k/n
// of the path (so the speed never exceeds F and the last cycle lands exactly
// on the end). No acceleration model (docs/motion.md, design).
// Lines: all axes linear in k/n. Arcs: the two plane axes on the arc (angle and
// radius linear in k/n: a circle, or a slight spiral from the start radius to the end
// radius when rounding made them differ, docs/motion.md), every other axis linear in
// k/n (a helix for the third axis).
#pragma once

#include <array>
#include <cstdint>

#include "objif/map/limits.h"
#include "rwmos/geometry/shared.h"
#include "rwmos/motion/types.h"

namespace rwmos::motion {

// (The members are ordered for no padding: the one-byte ones together, then the 4-byte ones.)
struct Move {
    SegmentKind kind = SegmentKind::kLine;
    SegmentRole role = SegmentRole::kUncompensated;
    // Arcs: plane axes (first, second); the centre, radii, start angle and sweep below.
    std::array<std::uint8_t, 2> plane_axes{0, 1};
    std::uint32_t tag = 0;
    bool direct = false;     // started by a direct command (JA), not spooled
    bool traverse = false;   // from a traverse profile: a rapid move on the compensated path
    // From a profile the 3D module compensated (its end moved along the surface normal): the
    // executed segment is a contour element though the spooler ran it uncompensated.
    bool surface = false;
    // Radius compensation the move was computed for: +1 left (G41), -1 right (G42), 0 none
    // (uncompensated moves, rapids). Contour, transition, approach and departure moves carry
    // their group's side (OTC RADIUS wear acts towards it, docs/otc.md).
    std::int8_t side = 0;
    std::int32_t plane = 0;  // arcs: G code of their plane (17, 18, 19), 0 if not a TC plane
    // The number of the profile it came from (Spooler::profiles_taken; 0: a direct command's).
    std::uint64_t profile = 0;
    // The part of end - start that is the tool length compensation coming in or going out
    // (WkzLen added at the end and not at the start, or the reverse), not a programmed motion:
    // OTC grinds nothing along it.
    AxisVector length_change{};
    // The tool length compensation in its end, per axis (WkzLen on the length axis while it
    // acts, zero elsewhere). The executed segment carries it, so the host takes the length off
    // without inferring it.
    AxisVector length_end{};
    AxisVector start{};
    AxisVector end{};
    double feed = 0.0;  // units/min, > 0
    // Arcs: centre on plane_axes, start and end radius, start angle and signed sweep
    // (> 0 counter-clockwise from the first axis to the second). The start angle is taken
    // (atan2 of the start about the centre) when first asked, start_angle_of(): a move the
    // clock runs through in one step never needs it. `angle_due`: not taken yet.
    double cx = 0.0, cy = 0.0;
    double radius = 0.0;
    double end_radius = 0.0;
    mutable double start_angle = 0.0;
    mutable bool angle_due = false;
    double sweep = 0.0;
};

// An arc's start angle about its centre (atan2 of start - centre on its plane axes), the same
// bits whenever it is taken; 0 for a line.
double start_angle_of(const Move& m) noexcept;

// Start and end in plane coordinates closer than this make an arc a full
// circle: the geometry's point tolerance, so both agree on what a full circle is.
inline constexpr double kFullCircleTolerance = geom::kPointTolerance;

Move line_move(const AxisVector& start, const AxisVector& end, double feed, SegmentRole role,
               std::uint32_t tag);
// The arc from `start` to `end` around (cx, cy) on `plane_axes`, turning
// counter-clockwise when `ccw`. Start and end on the same point: a full circle.
Move arc_move(const AxisVector& start, const AxisVector& end,
              std::array<std::uint8_t, 2> plane_axes, double cx, double cy, bool ccw, double feed,
              SegmentRole role, std::uint32_t tag);
// The same written into m whose start and end the caller has set: every other member is set
// (the caller's own storage: no Move built and copied there).
void line_move_into(Move& m, double feed, SegmentRole role, std::uint32_t tag) noexcept;
void arc_move_into(Move& m, std::array<std::uint8_t, 2> plane_axes, double cx, double cy, bool ccw,
                   double feed, SegmentRole role, std::uint32_t tag) noexcept;

// Length of an arc in its plane: |sweep| times the mean of start and end radius.
double arc_plane_length(const Move& m) noexcept;
// Path length over all moving axes (arcs: sqrt(arc length^2 + other axes^2)).
double path_length(const Move& m) noexcept;

// The most interpolation cycles one move may take: 10^9, 11.6 days at the default cycle of
// 1 ms. The spooler refuses a profile or jog with a move longer than that (ValueTooLow: a feed
// too low for its length) instead of running it for weeks or cutting it short; 10^9 is also
// the bound of `apcictl step` and `step --max`, so one command runs any move to its end.
inline constexpr std::uint64_t kMaxMoveCycles = objif::map::kMaxMoveCycles;
// Where cycles_for() saturates: beyond 2^52 a double no longer counts cycles one by one. Only a
// move the spooler would refuse gets there (a queued move runs longer than kMaxMoveCycles only
// when InterpolationCycle is shortened after it was spooled: at most 40 times, 250 us for 10 ms).
inline constexpr std::uint64_t kCycleCountCeiling = std::uint64_t{1} << 52;
// Cycles a path of `length` takes at `feed` units/min with cycles of
// `cycle_seconds`; 0 for a zero length. Saturates at kCycleCountCeiling.
std::uint64_t cycles_for(double length, double feed, double cycle_seconds) noexcept;
// The move fits the board's limit: at most kMaxMoveCycles cycles of `cycle_seconds`.
bool within_move_limit(const Move& m, double cycle_seconds) noexcept;

// An upper bound of path_length() of line_move(start, end, ...) (plane_axes nullptr) or of
// arc_move(start, end, *plane_axes, cx, cy, ...) (either sense), without roots or angles: the
// sum of every axis's change, for an arc plus 4 (more than pi) times the sum of the start's and
// the end's distances from the centre along each plane axis. At least twice the
// computed length when that is not 0, so the rounding of both cannot reverse a comparison
// with a margin of 2.
double path_length_bound(const AxisVector& start, const AxisVector& end,
                         const std::array<std::uint8_t, 2>* plane_axes, double cx,
                         double cy) noexcept;
// Whether the move from start to end (as path_length_bound) at `feed` surely fits the board's
// limit: the bound takes at most half of kMaxMoveCycles. False says nothing: the move may fit
// all the same (within_move_limit of the move itself decides).
bool surely_within_move_limit(const AxisVector& start, const AxisVector& end,
                              const std::array<std::uint8_t, 2>* plane_axes, double cx, double cy,
                              double feed, double cycle_seconds) noexcept;

// Axis positions after cycle k of n (0 <= k <= n, n > 0); k == n is exactly `end`.
void position_at(const Move& m, std::uint64_t k, std::uint64_t n, AxisVector& out) noexcept;

// The path direction at cycle k of n (0 <= k <= n, n > 0): the derivative of the position by
// the fraction k/n of the move (not unit; a line's is end - start, an arc's plane part is
// radius(k/n) * sweep along the circle's tangent plus the radius change along the radius).
void tangent_at(const Move& m, std::uint64_t k, std::uint64_t n, AxisVector& out) noexcept;

// The tool length compensation in the axis positions after cycle k of n (0 <= k <= n) of a
// move that started with `at_start`: it changes along the move as the position does (linearly
// in k/n on the axes outside an arc's plane, where WkzLen acts); k == n is exactly length_end.
void length_at(const Move& m, const AxisVector& at_start, std::uint64_t k, std::uint64_t n,
               AxisVector& out) noexcept;

// The Segment record of a move (start/end cycle and interruption filled by the caller).
Segment segment_of(const Move& m);
// The same written into s, every member set (the caller's own storage: no copy).
void segment_into(const Move& m, Segment& s) noexcept;

}  // namespace rwmos::motion
