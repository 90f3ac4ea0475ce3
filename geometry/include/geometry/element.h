// SPDX-License-Identifier: MIT
// Elements of a path in the 2D coordinates of the active plane: a line, or a circular
// arc (G02 clockwise / G03 counter-clockwise, seen from the positive third axis).
// Pure functions over them: tangents, length, points, distance.
#pragma once

#include <cstdint>

#include "geometry/plane.h"

namespace geom {

enum class ElementKind : std::uint8_t { kLine, kArc };

// A line from start to end, or an arc from start to end about centre. An arc whose end
// lies within kPointTolerance of its start is a full circle. An arc runs from its start
// point to its end point with its radius changing linearly with the angle, from the
// start radius to the end radius (they may differ by up to kCenterRadiusTolerance, else
// CenterError): a circle when they are equal, a slight spiral when rounding made them
// differ. Its tangents are perpendicular to the radius.
struct Element {
    ElementKind kind = ElementKind::kLine;
    bool ccw = false;  // arcs: true = G03, false = G02
    Vec2 start = Vec2::Zero();
    Vec2 end = Vec2::Zero();
    Vec2 centre = Vec2::Zero();  // arcs only
};

Element make_line(const Vec2& start, const Vec2& end) noexcept;
Element make_arc(const Vec2& start, const Vec2& end, const Vec2& centre, bool ccw) noexcept;

constexpr bool is_arc(const Element& e) noexcept {
    return e.kind == ElementKind::kArc;
}

// v turned by +90 degrees: the left normal of a direction of travel.
inline Vec2 left_normal(const Vec2& v) noexcept {
    return {-v.y(), v.x()};
}
// z of the 3D cross product: > 0 when b lies counter-clockwise of a.
inline double cross(const Vec2& a, const Vec2& b) noexcept {
    return a.x() * b.y() - a.y() * b.x();
}

// Signed angle from direction t1 to t2, in (-pi, pi], counter-clockwise positive.
double turn_angle(const Vec2& t1, const Vec2& t2) noexcept;

// Angle in [0, 2 pi) from direction a to direction b, counted counter-clockwise when
// ccw, clockwise otherwise. Neither needs to be unit length; both must be non-zero.
double angle_between(const Vec2& a, const Vec2& b, bool ccw) noexcept;

// The signed angle an arc turns about its centre, from the radius u0 (centre to start) to u1
// (centre to end), in its sense: in (0, 2 pi] counter-clockwise, [-2 pi, 0) clockwise; a whole
// turn where `full` (the caller found the ends to meet, by its own tolerance) or a radius is 0.
// The angle between the unit radii: exact also for a radius far beyond the chord (a radius of
// 1e18 over 20 mm), where the difference of two atan2 angles vanishes and the raw vectors'
// products lose the turn. Board and host take every arc's sweep from here.
double arc_sweep(const Vec2& u0, const Vec2& u1, bool ccw, bool full) noexcept;
// The same, with the radii r0 = std::hypot(u0.x(), u0.y()) and r1 = std::hypot(u1.x(),
// u1.y()) the caller has already (the same numbers: the same sweep).
double arc_sweep(const Vec2& u0, const Vec2& u1, double r0, double r1, bool ccw,
                 bool full) noexcept;

double radius(const Element& arc) noexcept;      // start radius
double end_radius(const Element& arc) noexcept;  // |end - centre|
bool is_full_circle(const Element& e) noexcept;  // an arc with end == start
// Signed angle the arc turns through: > 0 counter-clockwise, magnitude in (0, 2 pi];
// 0 for lines.
double sweep(const Element& e) noexcept;
double length(const Element& e) noexcept;
// length(e) for the element whose sweep(e) the caller has already: the same value.
double length_with_sweep(const Element& e, double sweep) noexcept;
// A line shorter than kPointTolerance: a move with no motion in the plane.
bool is_plane_free(const Element& e) noexcept;
// All coordinates finite and within kMaxCoordinate.
bool is_valid_coordinate(const Vec2& p) noexcept;
bool has_valid_coordinates(const Element& e) noexcept;

// Unit direction of travel. A plane-free line has none: the zero vector.
Vec2 start_tangent(const Element& e) noexcept;
Vec2 end_tangent(const Element& e) noexcept;
// t in [0, 1] is the fraction of the element travelled (clamped; for arcs, of the
// angle turned, with the radius interpolated from the start to the end radius).
Vec2 point_at(const Element& e, double t) noexcept;
Vec2 tangent_at(const Element& e, double t) noexcept;
// The point of the element nearest p, and its distance.
Vec2 closest_point(const Element& e, const Vec2& p) noexcept;
double distance_to(const Element& e, const Vec2& p) noexcept;

// The element rotated about centre by degrees (coordinate rotation, plane.h).
Element rotate_about(const Element& e, const Vec2& centre, double degrees) noexcept;

}  // namespace geom
