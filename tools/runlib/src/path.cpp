// SPDX-License-Identifier: MIT
#include "apci/run/path.h"

#include <cmath>
#include <numbers>

#include "apci/nc/arc.h"
#include "apci/nc/move_time.h"
#include "geometry/element.h"
#include "objif/enum_names.h"

namespace apci::run {

std::string_view kind_name(SegmentKind k) noexcept {
    static constexpr auto kNames =
        objif::enum_names<SegmentKind::kRapid, SegmentKind::kArc>({"rapid", "line", "arc"}, "line");
    return kNames(k);
}

std::string_view role_name(Role r) noexcept {
    static constexpr auto kNames = objif::enum_names<Role::kContour, Role::kUncompensated>(
        {"contour", "transition", "approach", "departure", "uncompensated"}, "uncompensated");
    return kNames(r);
}

std::string_view plane_name(int plane) noexcept {
    switch (plane) {
        case 18:
            return "Z-X";
        case 19:
            return "Y-Z";
        default:
            return "X-Y";
    }
}

char axis_letter(int axis) noexcept {
    static constexpr char kLetters[] = {'X', 'Y', 'Z'};
    return axis >= 0 && axis < 3 ? kLetters[axis] : '?';
}

namespace {

// Angle of p about c in the plane (first, second).
double angle_about(const Point& p, const Point& c, const PlaneAxes& a) noexcept {
    return std::atan2(p[a.second] - c[a.second], p[a.first] - c[a.first]);
}

}  // namespace

namespace {

// arc_sweep in the plane of axes First, Second (constants: no index looked up per coordinate),
// with its radii r0 and r1 (std::hypot of the start's and the end's radius vectors).
template <int First, int Second>
double sweep_in(const PathSegment& arc, double r0, double r1) noexcept {
    const double du = arc.end[First] - arc.start[First];
    const double dv = arc.end[Second] - arc.start[Second];
    // A chord with a component over twice the tolerance is longer than it: no hypot needed.
    const bool long_chord =
        std::abs(du) > 2.0 * kSamePointTolerance || std::abs(dv) > 2.0 * kSamePointTolerance;
    const bool full = !long_chord && std::hypot(du, dv) <= kSamePointTolerance;
    return geom::arc_sweep({arc.start[First] - arc.center[First], arc.start[Second] - arc.center[Second]},
                           {arc.end[First] - arc.center[First], arc.end[Second] - arc.center[Second]},
                           r0, r1, arc.ccw, full);
}

template <int First, int Second>
double start_radius_in(const PathSegment& s) noexcept {
    return std::hypot(s.start[First] - s.center[First], s.start[Second] - s.center[Second]);
}
template <int First, int Second>
double end_radius_in(const PathSegment& s) noexcept {
    return std::hypot(s.end[First] - s.center[First], s.end[Second] - s.center[Second]);
}

template <int First, int Second>
double sweep_in(const PathSegment& arc) noexcept {
    return sweep_in<First, Second>(arc, start_radius_in<First, Second>(arc),
                                   end_radius_in<First, Second>(arc));
}

// measure() of an arc in the plane of axes First, Second with Third its normal: the formulas of
// arc_sweep, arc_radius, arc_end_radius and segment_length, with the axes as constants (the
// radii taken once, for the sweep and the length).
template <int First, int Second, int Third>
void measure_arc(PathSegment& s) noexcept {
    const double r0 = start_radius_in<First, Second>(s);
    const double r1 = end_radius_in<First, Second>(s);
    s.sweep = sweep_in<First, Second>(s, r0, r1);
    const double planar = std::abs(s.sweep) * 0.5 * (r0 + r1);
    const double normal = s.end[Third] - s.start[Third];
    // hypot(planar, 0) is |planar| exactly (planar >= 0): a flat arc needs no root.
    s.length = normal == 0.0 ? planar : std::hypot(planar, normal);
}

}  // namespace

double arc_sweep(const PathSegment& arc) noexcept {
    return with_plane_axes(arc.plane, [&](auto first, auto second, auto) {
        return sweep_in<decltype(first)::value, decltype(second)::value>(arc);
    });
}

double arc_radius(const PathSegment& arc) noexcept {
    const PlaneAxes a = plane_axes(arc.plane);
    return std::hypot(arc.start[a.first] - arc.center[a.first],
                      arc.start[a.second] - arc.center[a.second]);
}

double arc_end_radius(const PathSegment& arc) noexcept {
    const PlaneAxes a = plane_axes(arc.plane);
    return std::hypot(arc.end[a.first] - arc.center[a.first],
                      arc.end[a.second] - arc.center[a.second]);
}

Point point_along(const PathSegment& s, double t) noexcept {
    if (s.kind != SegmentKind::kArc) return s.start + t * (s.end - s.start);
    const PlaneAxes a = plane_axes(s.plane);
    const double r = arc_radius(s) + t * (arc_end_radius(s) - arc_radius(s));
    const double phi = angle_about(s.start, s.center, a) + t * arc_sweep(s);
    Point p;
    p[a.first] = s.center[a.first] + r * std::cos(phi);
    p[a.second] = s.center[a.second] + r * std::sin(phi);
    p[a.third] = s.start[a.third] + t * (s.end[a.third] - s.start[a.third]);
    return p;
}

namespace {

double length_with_sweep(const PathSegment& s, double sweep) noexcept {
    if (s.kind != SegmentKind::kArc) return (s.end - s.start).norm();
    const PlaneAxes a = plane_axes(s.plane);
    const double planar = std::abs(sweep) * 0.5 * (arc_radius(s) + arc_end_radius(s));
    const double normal = s.end[a.third] - s.start[a.third];
    // hypot(planar, 0) is |planar| exactly (planar >= 0): a flat arc needs no root.
    return normal == 0.0 ? planar : std::hypot(planar, normal);
}

}  // namespace

double segment_length(const PathSegment& s) noexcept {
    return length_with_sweep(s, s.kind == SegmentKind::kArc ? arc_sweep(s) : 0.0);
}

void measure(PathSegment& s) noexcept {
    if (s.kind != SegmentKind::kArc) {
        s.sweep = 0.0;
        s.length = (s.end - s.start).norm();
        return;
    }
    with_plane_axes(s.plane, [&](auto first, auto second, auto third) {
        measure_arc<decltype(first)::value, decltype(second)::value, decltype(third)::value>(s);
    });
}

double measured_sweep(const PathSegment& s) noexcept {
    return std::isnan(s.sweep) ? arc_sweep(s) : s.sweep;
}

double measured_length(const PathSegment& s) noexcept {
    return std::isnan(s.length) ? segment_length(s) : s.length;
}

// A bound on segment_length(s) (for an arc: its sweep, at most a turn, times its mean radius,
// with the travel along the normal) is what nc::surely_within_move_cycles bounds for the front
// end's moves: a line's chord, an arc's whole turn of its larger radius plus that travel.
bool surely_within_move_cycles(const PathSegment& s, double feed, double cycle_seconds) noexcept {
    if (s.kind != SegmentKind::kArc)
        return nc::surely_within_move_cycles(s.start, s.end, feed, cycle_seconds);
    nc::ArcMove a;
    a.start = s.start;
    a.end = s.end;
    a.center = s.center;
    a.ccw = s.ccw;
    a.plane = s.plane == 18 ? nc::Plane::kZX : s.plane == 19 ? nc::Plane::kYZ : nc::Plane::kXY;
    a.feed = feed;
    return nc::surely_within_move_cycles(a, cycle_seconds);
}

PathSegment nose_centre_path(const PathSegment& s, const Eigen::Vector2d& edge, int plane) noexcept {
    if (edge.isZero(0.0)) return s;
    const PlaneAxes a = plane_axes(plane);
    const auto back = [&](Point& p) {
        p[a.first] -= edge.x();
        p[a.second] -= edge.y();
    };
    PathSegment out = s;
    const bool arc = s.kind == SegmentKind::kArc;
    switch (s.role) {
        case Role::kContour:
        case Role::kTransition:
            back(out.start);
            back(out.end);
            if (arc) back(out.center);
            break;
        case Role::kApproach:
            back(out.end);
            if (arc) {
                back(out.start);
                back(out.center);
            }
            break;
        case Role::kDeparture:
            back(out.start);
            break;
        default:
            break;
    }
    if (!std::isnan(out.length)) measure(out);
    return out;
}

}  // namespace apci::run
