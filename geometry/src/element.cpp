// SPDX-License-Identifier: MIT
#include "geometry/element.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/tolerances.h"

namespace geom {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

// Unit vector turned by angle (radians, counter-clockwise positive).
Vec2 turned(const Vec2& u, double angle) noexcept {
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    return {c * u.x() - s * u.y(), s * u.x() + c * u.y()};
}

Vec2 unit_or_zero(const Vec2& v) noexcept {
    const double n = v.norm();
    return n > 0.0 ? Vec2(v / n) : Vec2::Zero();
}

// Direction of travel on an arc at the point whose radial direction is u.
Vec2 arc_tangent(const Vec2& u, bool ccw) noexcept {
    return ccw ? left_normal(u) : Vec2(-left_normal(u));
}

}  // namespace

Element make_line(const Vec2& start, const Vec2& end) noexcept {
    Element e;
    e.kind = ElementKind::kLine;
    e.start = start;
    e.end = end;
    return e;
}

Element make_arc(const Vec2& start, const Vec2& end, const Vec2& centre, bool ccw) noexcept {
    Element e;
    e.kind = ElementKind::kArc;
    e.ccw = ccw;
    e.start = start;
    e.end = end;
    e.centre = centre;
    return e;
}

double turn_angle(const Vec2& t1, const Vec2& t2) noexcept {
    return std::atan2(cross(t1, t2), t1.dot(t2));
}

double angle_between(const Vec2& a, const Vec2& b, bool ccw) noexcept {
    double angle = turn_angle(a, b);
    if (!ccw) angle = -angle;
    if (angle < 0.0) angle += kTwoPi;
    return angle >= kTwoPi ? 0.0 : angle;
}

double radius(const Element& arc) noexcept {
    return (arc.start - arc.centre).norm();
}
double end_radius(const Element& arc) noexcept {
    return (arc.end - arc.centre).norm();
}

bool is_full_circle(const Element& e) noexcept {
    return is_arc(e) && (e.end - e.start).norm() <= kPointTolerance;
}

double arc_sweep(const Vec2& u0, const Vec2& u1, bool ccw, bool full) noexcept {
    // hypot: no overflow of the squares for a radius beyond 1e154 (a program's R1e200).
    return arc_sweep(u0, u1, std::hypot(u0.x(), u0.y()), std::hypot(u1.x(), u1.y()), ccw, full);
}

double arc_sweep(const Vec2& u0, const Vec2& u1, double r0, double r1, bool ccw,
                 bool full) noexcept {
    if (full || !(r0 > 0.0) || !(r1 > 0.0)) return ccw ? kTwoPi : -kTwoPi;
    const Vec2 a = u0 / r0, b = u1 / r1;
    double sweep = turn_angle(a, b);  // between the unit radii
    // An end on the start's ray yet apart from it (rounding): a whole turn.
    if (ccw && sweep <= 0.0) sweep += kTwoPi;
    if (!ccw && sweep >= 0.0) sweep -= kTwoPi;
    return sweep;
}

double sweep(const Element& e) noexcept {
    if (!is_arc(e)) return 0.0;
    return arc_sweep(e.start - e.centre, e.end - e.centre, e.ccw, is_full_circle(e));
}

double length(const Element& e) noexcept {
    return length_with_sweep(e, sweep(e));
}

double length_with_sweep(const Element& e, double sweep) noexcept {
    // An arc's radius changes linearly with the angle: its length is the sweep times the
    // mean radius (exact for the spiral up to (dR / R)^2, far below the path tolerance).
    return is_arc(e) ? std::abs(sweep) * 0.5 * (radius(e) + end_radius(e))
                     : (e.end - e.start).norm();
}

bool is_plane_free(const Element& e) noexcept {
    return !is_arc(e) && (e.end - e.start).norm() <= kPointTolerance;
}

bool is_valid_coordinate(const Vec2& p) noexcept {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::abs(p.x()) <= kMaxCoordinate &&
           std::abs(p.y()) <= kMaxCoordinate;
}

bool has_valid_coordinates(const Element& e) noexcept {
    return is_valid_coordinate(e.start) && is_valid_coordinate(e.end) &&
           (!is_arc(e) || is_valid_coordinate(e.centre));
}

Vec2 start_tangent(const Element& e) noexcept {
    if (is_arc(e)) return arc_tangent(unit_or_zero(e.start - e.centre), e.ccw);
    return is_plane_free(e) ? Vec2::Zero() : unit_or_zero(e.end - e.start);
}

Vec2 end_tangent(const Element& e) noexcept {
    if (is_arc(e)) return arc_tangent(unit_or_zero(e.end - e.centre), e.ccw);
    return is_plane_free(e) ? Vec2::Zero() : unit_or_zero(e.end - e.start);
}

Vec2 point_at(const Element& e, double t) noexcept {
    t = std::clamp(t, 0.0, 1.0);
    if (!is_arc(e)) return e.start + t * (e.end - e.start);
    if (t == 1.0) return e.end;
    const Vec2 r0 = e.start - e.centre;
    const double r_start = r0.norm();
    const double r_t = r_start + t * (end_radius(e) - r_start);
    return e.centre + turned(r0, t * sweep(e)) * (r_start > 0.0 ? r_t / r_start : 0.0);
}

Vec2 tangent_at(const Element& e, double t) noexcept {
    if (!is_arc(e)) return start_tangent(e);
    t = std::clamp(t, 0.0, 1.0);
    return arc_tangent(unit_or_zero(turned(e.start - e.centre, t * sweep(e))), e.ccw);
}

Vec2 closest_point(const Element& e, const Vec2& p) noexcept {
    if (!is_arc(e)) {
        const Vec2 d = e.end - e.start;
        const double len2 = d.squaredNorm();
        if (len2 == 0.0) return e.start;
        return e.start + std::clamp((p - e.start).dot(d) / len2, 0.0, 1.0) * d;
    }
    const Vec2 v = p - e.centre;
    const Vec2 r0 = e.start - e.centre;
    if (v.norm() == 0.0) return e.start;  // every arc point is (about) equally near the centre
    const double along = angle_between(r0, v, e.ccw);
    const double turn = std::abs(sweep(e));
    if (along <= turn) {
        // The point of the arc on the ray through p (the radius there interpolated).
        const double r = r0.norm() + (along / turn) * (end_radius(e) - r0.norm());
        return e.centre + v * (r / v.norm());
    }
    return (p - e.start).norm() <= (p - e.end).norm() ? e.start : e.end;
}

double distance_to(const Element& e, const Vec2& p) noexcept {
    return (p - closest_point(e, p)).norm();
}

Element rotate_about(const Element& e, const Vec2& centre, double degrees) noexcept {
    Element out = e;
    out.start = rotate_about(e.start, centre, degrees);
    out.end = rotate_about(e.end, centre, degrees);
    if (is_arc(e)) out.centre = rotate_about(e.centre, centre, degrees);
    return out;
}

}  // namespace geom
