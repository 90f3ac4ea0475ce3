// SPDX-License-Identifier: MIT
#include "rwmos/motion/interpolator.h"

#include <algorithm>
#include <cmath>

namespace rwmos::motion {

Move line_move(const AxisVector& start, const AxisVector& end, double feed, SegmentRole role,
               std::uint32_t tag) {
    Move m;
    m.start = start;
    m.end = end;
    line_move_into(m, feed, role, tag);
    return m;
}

Move arc_move(const AxisVector& start, const AxisVector& end,
              std::array<std::uint8_t, 2> plane_axes, double cx, double cy, bool ccw, double feed,
              SegmentRole role, std::uint32_t tag) {
    Move m;
    m.start = start;
    m.end = end;
    arc_move_into(m, plane_axes, cx, cy, ccw, feed, role, tag);
    return m;
}

namespace {

// The members a line and an arc set alike, as Move{} and then the move's.
void set_move_head(Move& m, SegmentKind kind, double feed, SegmentRole role,
                   std::uint32_t tag) noexcept {
    m.kind = kind;
    m.role = role;
    m.tag = tag;
    m.direct = false;
    m.traverse = false;
    m.profile = 0;
    m.length_change = {};
    m.length_end = {};
    m.surface = false;
    m.side = 0;
    m.plane = 0;
    m.feed = feed;
}

}  // namespace

void line_move_into(Move& m, double feed, SegmentRole role, std::uint32_t tag) noexcept {
    // Every member but start and end, as Move{} and then the line's.
    set_move_head(m, SegmentKind::kLine, feed, role, tag);
    m.plane_axes = {0, 1};
    m.cx = m.cy = 0.0;
    m.radius = m.end_radius = 0.0;
    m.start_angle = m.sweep = 0.0;
    m.angle_due = false;
}

void arc_move_into(Move& m, std::array<std::uint8_t, 2> plane_axes, double cx, double cy, bool ccw,
                   double feed, SegmentRole role, std::uint32_t tag) noexcept {
    set_move_head(m, SegmentKind::kArc, feed, role, tag);
    m.plane_axes = plane_axes;
    m.cx = cx;
    m.cy = cy;
    const AxisVector& start = m.start;
    const AxisVector& end = m.end;
    const double sx = start[plane_axes[0]] - cx, sy = start[plane_axes[1]] - cy;
    const double ex = end[plane_axes[0]] - cx, ey = end[plane_axes[1]] - cy;
    m.radius = std::hypot(sx, sy);
    m.end_radius = std::hypot(ex, ey);
    m.start_angle = 0.0;
    m.angle_due = true;  // start_angle_of() takes atan2(sy, sx) when it is needed
    // The chord's length is at least its larger component (hypot within a rounding of it):
    // a component over twice the tolerance needs no root.
    const double dx = ex - sx, dy = ey - sy;
    const bool full = !(std::max(std::fabs(dx), std::fabs(dy)) > 2.0 * kFullCircleTolerance ||
                        std::hypot(dx, dy) > kFullCircleTolerance);
    m.sweep = geom::arc_sweep({sx, sy}, {ex, ey}, m.radius, m.end_radius, ccw, full);
}

double start_angle_of(const Move& m) noexcept {
    if (m.angle_due) {
        m.start_angle = std::atan2(m.start[m.plane_axes[1]] - m.cy, m.start[m.plane_axes[0]] - m.cx);
        m.angle_due = false;
    }
    return m.start_angle;
}

double arc_plane_length(const Move& m) noexcept {
    return 0.5 * (m.radius + m.end_radius) * std::fabs(m.sweep);
}

double path_length(const Move& m) noexcept {
    // The squares of the axes' changes summed in axis order, an arc's plane axes left out.
    // (Unrolled: a move's length is taken once per move on the executor's path.)
    double other = 0.0;
    if (m.kind == SegmentKind::kLine) {
#pragma GCC unroll 8
        for (int a = 0; a < kAxisCount; ++a) {
            const double d = m.end[a] - m.start[a];
            other += d * d;
        }
        return std::sqrt(other);
    }
#pragma GCC unroll 8
    for (int a = 0; a < kAxisCount; ++a) {
        if (a == m.plane_axes[0] || a == m.plane_axes[1]) continue;
        const double d = m.end[a] - m.start[a];
        other += d * d;
    }
    const double arc = arc_plane_length(m);
    return std::sqrt(arc * arc + other);
}

std::uint64_t cycles_for(double length, double feed, double cycle_seconds) noexcept {
    if (!(length > 0.0)) return 0;
    const double per_cycle = feed / 60.0 * cycle_seconds;
    if (!(per_cycle > 0.0)) return kCycleCountCeiling;
    const double n = std::ceil(length / per_cycle);
    if (!(n < static_cast<double>(kCycleCountCeiling))) return kCycleCountCeiling;
    return n < 1.0 ? 1 : static_cast<std::uint64_t>(n);
}

bool within_move_limit(const Move& m, double cycle_seconds) noexcept {
    return cycles_for(path_length(m), m.feed, cycle_seconds) <= kMaxMoveCycles;
}

double path_length_bound(const AxisVector& start, const AxisVector& end,
                         const std::array<std::uint8_t, 2>* plane_axes, double cx,
                         double cy) noexcept {
    // Every axis's change (an arc's plane axes too: more than needed, still a bound).
    double bound = 0.0;
#pragma GCC unroll 8
    for (int a = 0; a < kAxisCount; ++a) bound += std::fabs(end[a] - start[a]);
    if (plane_axes == nullptr) return 2.0 * bound;
    // |sweep| <= 2 pi and each radius at most the sum of its two components: the arc is at
    // most pi times the sum of the four; 4 leaves room for every rounding.
    const std::size_t u = (*plane_axes)[0], v = (*plane_axes)[1];
    const double radii = std::fabs(start[u] - cx) + std::fabs(start[v] - cy) +
                         std::fabs(end[u] - cx) + std::fabs(end[v] - cy);
    return 2.0 * (bound + 4.0 * radii);
}

bool surely_within_move_limit(const AxisVector& start, const AxisVector& end,
                              const std::array<std::uint8_t, 2>* plane_axes, double cx, double cy,
                              double feed, double cycle_seconds) noexcept {
    // cycles_for(bound) <= kMaxMoveCycles without its division and ceil: bound <= per_cycle *
    // kMaxMoveCycles puts ceil(bound / per_cycle) within a rounding of kMaxMoveCycles, and the
    // bound's margin of 2 puts the move's own count at about half of it.
    const double bound = path_length_bound(start, end, plane_axes, cx, cy);
    const double per_cycle = feed / 60.0 * cycle_seconds;
    return std::isfinite(bound) && per_cycle > 0.0 &&
           bound <= per_cycle * static_cast<double>(kMaxMoveCycles);
}

void position_at(const Move& m, std::uint64_t k, std::uint64_t n, AxisVector& out) noexcept {
    if (k >= n) {
        out = m.end;
        return;
    }
    const double t = static_cast<double>(k) / static_cast<double>(n);
    for (int a = 0; a < kAxisCount; ++a) out[a] = m.start[a] + (m.end[a] - m.start[a]) * t;
    if (m.kind == SegmentKind::kArc) {
        const double angle = start_angle_of(m) + m.sweep * t;
        const double r = m.radius + (m.end_radius - m.radius) * t;
        out[m.plane_axes[0]] = m.cx + r * std::cos(angle);
        out[m.plane_axes[1]] = m.cy + r * std::sin(angle);
    }
}

void length_at(const Move& m, const AxisVector& at_start, std::uint64_t k, std::uint64_t n,
               AxisVector& out) noexcept {
    if (k >= n) {
        out = m.length_end;
        return;
    }
    const double t = static_cast<double>(k) / static_cast<double>(n);
    for (int a = 0; a < kAxisCount; ++a) out[a] = at_start[a] + (m.length_end[a] - at_start[a]) * t;
}

void tangent_at(const Move& m, std::uint64_t k, std::uint64_t n, AxisVector& out) noexcept {
    for (int a = 0; a < kAxisCount; ++a) out[a] = m.end[a] - m.start[a];
    if (m.kind == SegmentKind::kArc) {
        const double t = n == 0 || k >= n ? 1.0 : static_cast<double>(k) / static_cast<double>(n);
        const double angle = start_angle_of(m) + m.sweep * t;
        const double r = m.radius + (m.end_radius - m.radius) * t;
        const double dr = m.end_radius - m.radius;
        out[m.plane_axes[0]] = dr * std::cos(angle) - r * m.sweep * std::sin(angle);
        out[m.plane_axes[1]] = dr * std::sin(angle) + r * m.sweep * std::cos(angle);
    }
}

Segment segment_of(const Move& m) {
    Segment s;
    segment_into(m, s);
    return s;
}

void segment_into(const Move& m, Segment& s) noexcept {
    // Every member, as Segment{} and then the move's (no zero-fill written over again).
    s.tag = m.tag;
    s.kind = m.kind;
    // A line the 3D module compensated is a contour element (the spooler, which knows only the
    // TC module, ran it uncompensated).
    s.role = m.surface && m.role == SegmentRole::kUncompensated ? SegmentRole::kContour : m.role;
    s.start = m.start;
    s.end = m.end;
    s.length_start = AxisVector{};  // the executor's, where the move began
    s.length_end = m.length_end;
    s.feed = m.feed;
    s.start_cycle = 0;
    s.end_cycle = 0;
    s.interrupted = false;
    s.traverse = m.traverse;
    if (m.kind == SegmentKind::kArc) {
        s.plane_axes = m.plane_axes;
        s.center = m.start;
        s.center[m.plane_axes[0]] = m.cx;
        s.center[m.plane_axes[1]] = m.cy;
        s.ccw = m.sweep > 0.0;
        s.plane = m.plane;
    } else {
        s.plane_axes = {0, 1};
        s.center = AxisVector{};
        s.ccw = false;
        s.plane = 0;
    }
}

}  // namespace rwmos::motion
