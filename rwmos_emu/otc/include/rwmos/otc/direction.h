// SPDX-License-Identifier: MIT
// The directions the wear acts in, one pure function per processing type ([ISG-OTC], FCT-C20,
// sections 2.2 to 2.5). Every direction is a unit vector pointing from the work piece towards
// the tool, so the axes are displaced by -wear * direction: the worn (smaller) tool is moved
// towards the work by as much as it lost. Vectors are (X, Y, Z) in program axes.
#pragma once

#include <Eigen/Core>

#include "rwmos/geometry/shared.h"

namespace rwmos::otc {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// Below this length a vector has no direction (the same tolerance as the geometry's points).
inline constexpr double kDirectionTolerance = 1e-9;

// LENGTH (section 2.3): along the third main axis of `plane`; a disc tilted by `tilt_deg`
// (P-TOOL-00138, section 2.3.1) splits the wear over the third and the first main axis:
//   d = cos(tilt) * e_third + sin(tilt) * e_first.
// G17: Z and X ("In obiger Skizze würde der Verschleiß in der X- und Z-Achse eingerechnet");
// G18: Y and Z; G19: X and Y. Positive angles tilt from the third axis towards the first
// (for G17 the same sense as the B head's B, rwmos/geometry/kinematics.h).
Vec3 length_direction(double tilt_deg, geom::Plane plane) noexcept;

// Side of radius compensation: the tool centre is left (G41) or right (G42) of the contour.
enum class Side : int { kLeft = 1, kRight = -1 };

// RADIUS (section 2.2): perpendicular to the contour in the plane, "senkrecht zur programmierten
// Kontur": the unit normal from the contour towards the tool centre, for a path going along
// `tangent` (plane coordinates, need not be unit; zero length gives zero).
Vec2 contour_normal(const Vec2& tangent, Side side) noexcept;

// SURF_NORM_DIR (section 2.5): "Die Flächennormalenrichtung wird ... auf Basis der
// Werkzeugrichtungsvektors und des Bahntangentenvektors berechnet": the part of the tool
// direction perpendicular to the path tangent, normalised (it lies in the plane of the two and
// points to the tool's side). When the tool moves along its own axis there is no such part; the
// caller's `fallback` (the last normal) is returned.
Vec3 surface_normal(const Vec3& tool_direction, const Vec3& tangent, const Vec3& fallback) noexcept;

}  // namespace rwmos::otc
