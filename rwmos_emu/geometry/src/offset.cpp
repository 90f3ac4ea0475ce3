// SPDX-License-Identifier: MIT
#include "rwmos/geometry/offset.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rwmos/geometry/shared.h"

namespace rwmos::geom {

Reason check_element(const Element& e) noexcept {
    if (e.kind != ElementKind::kLine && e.kind != ElementKind::kArc)
        return Reason::kInvalidElementKind;
    if (!has_valid_coordinates(e)) return Reason::kInvalidCoordinate;
    if (!is_arc(e)) return Reason::kNone;
    const double r_start = radius(e);
    const double r_end = end_radius(e);
    if (r_start <= kPointTolerance || r_end <= kPointTolerance) return Reason::kArcCentreOnEndPoint;
    // [APCI-TC] "Tabelle 4": CenterError, the radii at start and end point differ.
    if (std::abs(r_start - r_end) > kCenterRadiusTolerance) return Reason::kArcRadiiDiffer;
    return Reason::kNone;
}

Vec2 offset_point(const Vec2& p, const Vec2& tangent, double r, Side side) noexcept {
    return p + (side_sign(side) * r) * left_normal(tangent);
}

double offset_radius(const Element& arc, double r, Side side) noexcept {
    return offset_radius(radius(arc), arc.ccw, r, side);
}

double offset_radius(double arc_radius, bool ccw, double r, Side side) noexcept {
    // The left normal of a counter-clockwise arc points at its centre.
    const double towards_centre = ccw ? 1.0 : -1.0;
    return arc_radius - side_sign(side) * towards_centre * r;
}

OffsetResult offset_element(const Element& e, double r, Side side) noexcept {
    OffsetResult out;
    OffsetElement& o = out.element;
    o.path = e;
    if (!is_arc(e)) {
        const Vec2 t = start_tangent(e);
        o.path.start = offset_point(e.start, t, r, side);
        o.path.end = offset_point(e.end, t, r, side);
        o.direction = t;
        return out;
    }
    // The offset of the arc (a spiral when its radii differ) keeps its centre, sweep and
    // direction; each radius moves by r: rho = R - r on the concave side.
    const double r_start = radius(e);
    const double r_end = end_radius(e);
    const double shift = r_start - offset_radius(r_start, e.ccw, r, side);
    const double rho_start = r_start - shift;
    const double rho_end = r_end - shift;
    // [APCI-TC] "Tabelle 4": CalcError, the radius of the arc is smaller than the tool
    // radius. A tool that fits it (within the path tolerance) keeps its centre there.
    if (std::min(rho_start, rho_end) < -kOffsetRadiusTolerance) {
        out.reason = Reason::kOffsetRadiusNotPositive;
        return out;
    }
    const Vec2 u_start = (e.start - e.centre) / r_start;
    const Vec2 u_end = (e.end - e.centre) / r_end;
    o.sweep = sweep(e);
    o.path.start = e.centre + std::max(rho_start, kMinOffsetRadius) * u_start;
    o.path.end =
        is_full_circle(e) ? o.path.start : Vec2(e.centre + std::max(rho_end, kMinOffsetRadius) * u_end);
    return out;
}

namespace {
// Mean of an offset arc's start and end radius: lengths along it are angles times this.
double mean_radius(const OffsetElement& o) noexcept {
    return 0.5 * (radius(o.path) + end_radius(o.path));
}
}  // namespace

double circumference(const OffsetElement& o) noexcept {
    return is_arc(o.path) ? 2 * std::numbers::pi * mean_radius(o) : 0.0;
}

double offset_length(const OffsetElement& o) noexcept {
    if (!is_arc(o.path)) return (o.path.end - o.path.start).norm();
    return std::abs(o.sweep) * mean_radius(o);
}

double distance_along(const OffsetElement& o, const Vec2& x) noexcept {
    if (!is_arc(o.path)) return (x - o.path.start).dot(o.direction);
    return angle_between(o.path.start - o.path.centre, x - o.path.centre, o.path.ccw) *
           mean_radius(o);
}

OffsetElement trim_end(const OffsetElement& o, const Vec2& x, double along) noexcept {
    OffsetElement out = o;
    trim_end_in_place(out, x, along);
    return out;
}

OffsetElement trim_start(const OffsetElement& o, const Vec2& x, double along) noexcept {
    OffsetElement out = o;
    trim_start_in_place(out, x, along);
    return out;
}

void trim_end_in_place(OffsetElement& o, const Vec2& x, double along) noexcept {
    // The turn from the element as it was (its mean radius), then its new end.
    if (is_arc(o.path)) {
        const double turned = std::clamp(along / mean_radius(o), 0.0, std::abs(o.sweep));
        o.sweep = std::copysign(turned, o.sweep);
    }
    o.path.end = x;
}

void trim_start_in_place(OffsetElement& o, const Vec2& x, double along) noexcept {
    if (is_arc(o.path)) {
        const double turned = std::clamp(along / mean_radius(o), 0.0, std::abs(o.sweep));
        o.sweep = std::copysign(std::abs(o.sweep) - turned, o.sweep);
    }
    o.path.start = x;
}

Element emitted_path(const OffsetElement& o) noexcept {
    if (!is_arc(o.path)) return o.path;
    if (std::abs(o.sweep) < std::numbers::pi && (o.path.end - o.path.start).norm() <= kMinArcChord)
        return make_line(o.path.start, o.path.end);
    if (!is_full_circle(o.path) && std::max(radius(o.path), end_radius(o.path)) < kPathTolerance)
        return make_line(o.path.start, o.path.end);
    return o.path;
}

}  // namespace rwmos::geom
