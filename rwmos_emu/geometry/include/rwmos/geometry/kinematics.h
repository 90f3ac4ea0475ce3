// SPDX-License-Identifier: MIT
// The one head kinematics the emulator knows (docs/design.md section 8, design): a B axis that
// tilts the tool in the Z-X plane, optionally turned about Z by a C axis (bc_head_*; C = 0 is
// the B head). Shared by OTC (tool direction for TOOL_DIR and SURF_NORM_DIR), 3D tool
// compensation and temperature compensation in tool direction.
//
// B is in degrees. B = 0: the tool points along +Z (from the tool tip towards the spindle).
// Positive B turns it about +Y (right-handed), from +Z towards +X:
//   tool direction t(B) = (sin B, 0, cos B).
// The pivot (the point the machine's X, Y, Z axes position) sits on the tool axis, one tool
// length behind the tip: pivot = tip + length * t(B). With the transformation on (#TRAFO ON)
// the program gives the tip; without it the program gives the pivot directly.
// docs/otc.md ("Head kinematics") shows the figure.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace rwmos::geom {

// #KIN ID[4] of the TOOL_DIR and SURF_NORM_DIR examples of [ISG-OTC] (sections 2.4 and
// 2.5, "OTC-Schleifen mit Kinematiktyp 4") names this kinematics.
inline constexpr int kBHeadKinematicsId = 4;

inline double degrees_to_radians(double deg) noexcept {
    return deg * (std::numbers::pi / 180.0);
}

// Unit tool direction (X, Y, Z) at tilt b_deg.
inline Eigen::Vector3d b_head_tool_direction(double b_deg) noexcept {
    const double b = degrees_to_radians(b_deg);
    return {std::sin(b), 0.0, std::cos(b)};
}

// Machine (pivot) position of a tool tip at tilt b_deg with a tool of `length`.
inline Eigen::Vector3d b_head_pivot_from_tip(const Eigen::Vector3d& tip, double b_deg,
                                             double length) noexcept {
    return tip + length * b_head_tool_direction(b_deg);
}

// A C axis that turns the B head about +Z (a head-head kinematics, as in the [TNC-3D]
// peripheral-milling example "C-267.9784 B-20.0115"): the head is first tilted by B, then turned
// by C, so t(B, C) = Rz(C) t(B) = (cos C sin B, sin C sin B, cos B). C = 0 is the B head alone.
inline Eigen::Matrix3d bc_head_rotation(double b_deg, double c_deg) noexcept {
    const double b = degrees_to_radians(b_deg);
    const double c = degrees_to_radians(c_deg);
    Eigen::Matrix3d rz;
    rz << std::cos(c), -std::sin(c), 0.0, std::sin(c), std::cos(c), 0.0, 0.0, 0.0, 1.0;
    Eigen::Matrix3d ry;
    ry << std::cos(b), 0.0, std::sin(b), 0.0, 1.0, 0.0, -std::sin(b), 0.0, std::cos(b);
    return rz * ry;
}

// Unit tool direction at tilt b_deg and turn c_deg: the rotation applied to +Z.
inline Eigen::Vector3d bc_head_tool_direction(double b_deg, double c_deg) noexcept {
    const double b = degrees_to_radians(b_deg);
    const double c = degrees_to_radians(c_deg);
    return {std::cos(c) * std::sin(b), std::sin(c) * std::sin(b), std::cos(b)};
}

// The inverse: the tool tip of a machine (pivot) position.
inline Eigen::Vector3d b_head_tip_from_pivot(const Eigen::Vector3d& pivot, double b_deg,
                                             double length) noexcept {
    return pivot - length * b_head_tool_direction(b_deg);
}

}  // namespace rwmos::geom
