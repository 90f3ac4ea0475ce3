// SPDX-License-Identifier: MIT
// The vectors of an LN line ([TNC-3D], "Gerade LN"): the surface normal N and the tool vector
// T, their normalisation check, which T a line runs with, and the directions the compensation
// moves along.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "rwmos/comp3d/refusal.h"

namespace rwmos::comp3d {

struct UnitVector {
    Refusal refusal = Refusal::kNone;
    Eigen::Vector3d v = Eigen::Vector3d::Zero();  // the vector divided by its length
};
// A programmed vector must be normalised ([TNC-3D], "Gerade LN", Hinweise): refused with
// kVectorNotNormalised when not finite or when its length differs from 1 by more than
// kUnitVectorTolerance; otherwise divided by its length.
UnitVector normalised(const Eigen::Vector3d& programmed) noexcept;

// [TNC-3D], "3D-Werkzeugkorrektur beim Stirnfräsen", Funktionsbeschreibung: the tool vector an
// LN line runs with. With M128 / FUNCTION TCPM: the programmed T, or without one N (the tool
// stands perpendicular to the contour). Without TCPM: the machine's current tool axis; a
// programmed T is ignored. All vectors unit; with TCPM the line has N or T.
Eigen::Vector3d effective_tool_vector(bool tcpm, const std::optional<Eigen::Vector3d>& programmed_t,
                                      const std::optional<Eigen::Vector3d>& normal,
                                      const Eigen::Vector3d& machine_axis) noexcept;

// u: the unit direction across the tool axis T from the axis towards the centre CR2 of the
// corner radius that touches a surface with normal N; that is -N projected onto the plane
// perpendicular to T. Zero when N and T are parallel within kParallelTolerance: then the
// flat end face touches, every point of it is a contact, and the tip centre is taken.
Eigen::Vector3d corner_direction(const Eigen::Vector3d& n, const Eigen::Vector3d& t) noexcept;

// RL: the tool runs left of the contour seen along the motion with T pointing at the
// viewer; RR: right ([TNC-3D], peripheral milling: "Korrekturrichtung mit Radiuskorrektur RL
// oder RR").
enum class Side : std::uint8_t { kLeft, kRight };

struct SideNormal {
    Refusal refusal = Refusal::kNone;  // kNoSideFromMotion when the motion gives no side
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
};
// Peripheral milling with RL/RR: the normal of the wall the tool cuts, pointing from the
// wall to the tool, perpendicular to the motion and to the tool vector ([TNC-3D]: "senkrecht
// zur Bewegungsrichtung und senkrecht zur Werkzeugrichtung"): T x D for RL, D x T for RR,
// normalised. Refused when the motion is shorter than kMinMotionLength or within
// kPlungeAngleTolerance of T.
SideNormal side_normal(const Eigen::Vector3d& motion, const Eigen::Vector3d& t, Side side) noexcept;

// Peripheral milling where the motion gives no side (an LN without N at the point of the line
// before: [TNC-3D], peripheral example, block 13 repeats block 12's point): the previous line's
// normal, made perpendicular to T and unit. kNoSideFromMotion when it is within
// kPlungeAngleTolerance of T.
SideNormal previous_side_normal(const Eigen::Vector3d& previous, const Eigen::Vector3d& t) noexcept;

}  // namespace rwmos::comp3d
