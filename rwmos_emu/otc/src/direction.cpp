// SPDX-License-Identifier: MIT
#include "rwmos/otc/direction.h"

#include <cmath>

#include "rwmos/geometry/kinematics.h"

namespace rwmos::otc {

Vec3 length_direction(double tilt_deg, geom::Plane plane) noexcept {
    const geom::PlaneAxes a = geom::plane_axes(plane);
    const double t = geom::degrees_to_radians(tilt_deg);
    Vec3 d = Vec3::Zero();
    d[a.third] = std::cos(t);
    d[a.first] = std::sin(t);
    return d;
}

Vec2 contour_normal(const Vec2& tangent, Side side) noexcept {
    const double len = tangent.norm();
    if (len <= kDirectionTolerance) return Vec2::Zero();
    const Vec2 left{-tangent.y() / len, tangent.x() / len};
    return side == Side::kLeft ? left : Vec2(-left);
}

Vec3 surface_normal(const Vec3& tool_direction, const Vec3& tangent,
                    const Vec3& fallback) noexcept {
    const double tlen = tangent.norm();
    if (tlen <= kDirectionTolerance) return fallback;
    const Vec3 tau = tangent / tlen;
    const Vec3 n = tool_direction - tool_direction.dot(tau) * tau;
    const double nlen = n.norm();
    if (nlen <= kDirectionTolerance) return fallback;
    return n / nlen;
}

}  // namespace rwmos::otc
