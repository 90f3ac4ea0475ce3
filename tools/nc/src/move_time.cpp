// SPDX-License-Identifier: MIT
#include "apci/nc/move_time.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "apci/nc/arc.h"

namespace apci::nc {

namespace {

// Start and end closer than this in the plane make an arc a full circle (the board's point
// tolerance is finer; a full circle here only makes the move longer, never shorter).
constexpr double kSamePoint = 1e-9;

// "60000000000" while the count is a whole number a double holds exactly, else "6.0e+43".
std::string cycles_text(double cycles) {
    if (cycles < 1e15) return fmt::format("{:.0f}", cycles);
    return fmt::format("{:.1e}", cycles);
}

}  // namespace

double move_length(const Eigen::Vector3d& start, const Eigen::Vector3d& end) noexcept {
    return (end - start).norm();
}

double move_length(const ArcMove& arc) noexcept {
    const PlaneAxes a = plane_axes(arc.plane);
    const double sx = arc.start[a.first] - arc.center[a.first];
    const double sy = arc.start[a.second] - arc.center[a.second];
    const double ex = arc.end[a.first] - arc.center[a.first];
    const double ey = arc.end[a.second] - arc.center[a.second];
    const double rs = std::hypot(sx, sy);
    const double re = std::hypot(ex, ey);
    const double sweep =
        arc_sweep({sx, sy}, {ex, ey}, arc.ccw, !(std::hypot(ex - sx, ey - sy) > kSamePoint));
    const double planar = 0.5 * (rs + re) * std::fabs(sweep);
    return std::hypot(planar, arc.end[a.third] - arc.start[a.third]);
}

double move_cycles(double length, double feed, double cycle_seconds) noexcept {
    if (!(length > 0.0)) return 0.0;
    const double per_cycle = feed / 60.0 * cycle_seconds;
    if (!(per_cycle > 0.0)) return HUGE_VAL;
    return std::ceil(length / per_cycle);
}

namespace {

// Half the path the cycle limit allows at `feed`; NaN or 0 for a feed or cycle that is not
// positive (every comparison with it then fails, or holds only for a move of length 0, which
// takes 0 cycles).
double half_limit_length(double feed, double cycle_seconds) noexcept {
    return 0.5 * static_cast<double>(kMaxMoveCycles) * (feed / 60.0 * cycle_seconds);
}

}  // namespace

bool surely_within_move_cycles(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                               double feed, double cycle_seconds) noexcept {
    const double half = half_limit_length(feed, cycle_seconds);
    const double half2 = half * half;  // a finite bound only: beyond, the exact check decides
    return std::isfinite(half2) && (end - start).squaredNorm() <= half2;
}

bool surely_within_move_cycles(const ArcMove& arc, double cycle_seconds) noexcept {
    const PlaneAxes a = plane_axes(arc.plane);
    const double sx = arc.start[a.first] - arc.center[a.first];
    const double sy = arc.start[a.second] - arc.center[a.second];
    const double ex = arc.end[a.first] - arc.center[a.first];
    const double ey = arc.end[a.second] - arc.center[a.second];
    const double dz = arc.end[a.third] - arc.start[a.third];
    // length = hypot(planar, dz) <= planar + |dz|, planar = 0.5 (rs + re) |sweep| <= 2 pi
    // max(rs, re): each part at most a quarter of the limit's path.
    const double quarter = 0.5 * half_limit_length(arc.feed, cycle_seconds);
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    const double r2 = std::max(sx * sx + sy * sy, ex * ex + ey * ey);
    const double quarter2 = quarter * quarter;
    return std::isfinite(quarter2) && kTwoPi * kTwoPi * r2 <= quarter2 && dz * dz <= quarter2;
}

std::string check_move_cycles(double length, double feed, double cycle_seconds) {
    const double cycles = move_cycles(length, feed, cycle_seconds);
    if (cycles <= static_cast<double>(kMaxMoveCycles)) return {};
    const double limit = static_cast<double>(kMaxMoveCycles);
    return fmt::format(
        "feed F{:g} makes this {:g} mm move take {} interpolation cycles; at most {} cycles "
        "({:.1f} days at {:g} ms) are allowed per move: raise F",
        feed, length, cycles_text(cycles), kMaxMoveCycles, limit * cycle_seconds / 86400.0,
        cycle_seconds * 1000.0);
}

}  // namespace apci::nc
