// SPDX-License-Identifier: MIT
// Board and host work in the 2D coordinates of the active plane (TcPlane, [APCI-TC]
// "Tabelle 2": 17 X-Y, 18 Z-X, 19 Y-Z). These pure helpers map 3D points to the plane's
// first and second axis and back, name the third (perpendicular) axis, map the plane to
// board axis numbers (X/Y/Z-Axis-Nr), and rotate plane coordinates (RotAngle,
// RotCenterX/Y, [APCI-TC] "2.1.1 Koordinatendrehung").
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>

namespace geom {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;  // (X, Y, Z)

// The value is the G code and the TcPlane object value.
enum class Plane : std::uint8_t { kXY = 17, kZX = 18, kYZ = 19 };

// 17, 18, 19 -> the plane; anything else -> nullopt (the caller reports PlaneError or a
// range error, as the object demands).
std::optional<Plane> plane_from_code(int code) noexcept;
constexpr int plane_code(Plane p) noexcept {
    return static_cast<int>(p);
}

// Logical axis numbers: 0 = X, 1 = Y, 2 = Z.
// The plane's first and second axis span it; (first, second, third) is right-handed, so
// counter-clockwise (G03) is seen from the positive third axis in every plane:
// 17: (X, Y, Z), 18: (Z, X, Y), 19: (Y, Z, X).
struct PlaneAxes {
    int first;
    int second;
    int third;
};
constexpr PlaneAxes plane_axes(Plane p) noexcept {
    switch (p) {
        case Plane::kXY:
            return {0, 1, 2};
        case Plane::kZX:
            return {2, 0, 1};
        case Plane::kYZ:
            return {1, 2, 0};
    }
    return {0, 1, 2};
}

// Board axis numbers assigned to X, Y and Z (TC Table 2 Index 11, or a group's
// XAxis/YAxis/ZAxis).
struct AxisAssignment {
    int x = 0;
    int y = 1;
    int z = 2;
};
// The board axis numbers of the plane's first, second and third axis.
PlaneAxes board_axes(Plane p, const AxisAssignment& axes) noexcept;

// (X, Y, Z) -> (first, second) of the plane.
Vec2 to_plane(const Vec3& p, Plane plane) noexcept;
// (X, Y, Z) -> the coordinate on the plane's third axis.
double third_coordinate(const Vec3& p, Plane plane) noexcept;
// (first, second) and the third coordinate -> (X, Y, Z).
Vec3 from_plane(const Vec2& q, double third, Plane plane) noexcept;

// p rotated about centre by degrees, counter-clockwise for positive angles (seen from
// the positive third axis, like G03).
Vec2 rotate_about(const Vec2& p, const Vec2& centre, double degrees) noexcept;

}  // namespace geom
