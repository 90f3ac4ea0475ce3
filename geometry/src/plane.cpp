// SPDX-License-Identifier: MIT
#include "geometry/plane.h"

#include <cmath>
#include <numbers>

namespace geom {

std::optional<Plane> plane_from_code(int code) noexcept {
    switch (code) {
        case 17:
            return Plane::kXY;
        case 18:
            return Plane::kZX;
        case 19:
            return Plane::kYZ;
        default:
            return std::nullopt;
    }
}

PlaneAxes board_axes(Plane p, const AxisAssignment& axes) noexcept {
    const int by_logical[3] = {axes.x, axes.y, axes.z};
    const PlaneAxes logical = plane_axes(p);
    return {by_logical[logical.first], by_logical[logical.second], by_logical[logical.third]};
}

Vec2 to_plane(const Vec3& p, Plane plane) noexcept {
    const PlaneAxes a = plane_axes(plane);
    return {p[a.first], p[a.second]};
}

double third_coordinate(const Vec3& p, Plane plane) noexcept {
    return p[plane_axes(plane).third];
}

Vec3 from_plane(const Vec2& q, double third, Plane plane) noexcept {
    const PlaneAxes a = plane_axes(plane);
    Vec3 p;
    p[a.first] = q.x();
    p[a.second] = q.y();
    p[a.third] = third;
    return p;
}

Vec2 rotate_about(const Vec2& p, const Vec2& centre, double degrees) noexcept {
    const double rad = degrees * (std::numbers::pi / 180.0);
    const double c = std::cos(rad);
    const double s = std::sin(rad);
    const Vec2 d = p - centre;
    return centre + Vec2{c * d.x() - s * d.y(), s * d.x() + c * d.y()};
}

}  // namespace geom
