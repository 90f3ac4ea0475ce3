// SPDX-License-Identifier: MIT
// The 3D tool compensation of one programmed point ([TNC-3D]): where the tool tip must go so
// that the tool, as dimensioned by the delta values, touches the same surface point along the
// surface normal N as the programmed tool did. docs/3d-compensation.md derives the formulas.
//
// The tool: axis T (unit, from the tip towards the holder), radius R, corner radius R2. Its
// lower end is the disc of radius R - R2 around the axis at height R2 above the tip, grown by
// R2 in every direction (a ball for R2 = R, a torus with its flat end face for 0 < R2 < R,
// a flat end face for R2 = 0). Touching a surface point S with normal N (pointing from the
// surface to the tool), the centre of the corner radius is CR2 = S + R2 N ([TNC-3D]: "Der
// Flächennormalenvektor zeigt immer auf das Zentrum Werkzeugradius 2 CR2"), and
//     tip = S + R2 N - R2 T - (R - R2) u,     u = corner_direction(N, T).
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "rwmos/comp3d/refusal.h"
#include "rwmos/comp3d/tool.h"

namespace rwmos::comp3d {

// FUNCTION PROG PATH ([TNC-3D], "3D-Werkzeugkorrektur mit gesamtem Werkzeugradius"): OFF (the
// default) - the programmed points are tool positions of the tool in the tool table, only the
// deltas DR, DR2 are applied; IS CONTOUR - the programmed points are contour points, the full
// radii R + DR and R2 + DR2 are applied. Modal until switched off.
enum class ProgPath : std::uint8_t { kOff, kContour };

// Where on the tool the programmed points lie (TCPM REFPNT): the tip (TIP-TIP, the default) or
// the centre on the axis at height R2 above the tip (CNT-CNT: the ball centre of a ball mill).
// [TNC-3D]: with REFPNT CNT-CNT the delta values for tip and centre output are the same.
enum class ReferencePoint : std::uint8_t { kTip, kCentre };

// ---- Geometry of a tool touching a surface (exact for every shape) ----

// The tip of a tool (dimensions d, axis t) that touches surface point s with normal n.
Eigen::Vector3d tip_touching(const Eigen::Vector3d& s, const Eigen::Vector3d& n,
                             const Eigen::Vector3d& t, const ToolDimensions& d) noexcept;
// The surface point with normal n that a tool (dimensions d, axis t) with its tip at `tip`
// touches: the inverse of tip_touching.
Eigen::Vector3d contact_point(const Eigen::Vector3d& tip, const Eigen::Vector3d& n,
                              const Eigen::Vector3d& t, const ToolDimensions& d) noexcept;
// The centre of the corner radius CR2 that touches a surface with normal n.
Eigen::Vector3d corner_centre(const Eigen::Vector3d& tip, const Eigen::Vector3d& n,
                              const Eigen::Vector3d& t, const ToolDimensions& d) noexcept;
// The centre reference point: on the axis at height R2 above the tip.
inline Eigen::Vector3d centre_of(const Eigen::Vector3d& tip, const Eigen::Vector3d& t,
                                 const ToolDimensions& d) noexcept {
    return tip + d.r2 * t;
}

// ---- One LN point ----

struct Settings {
    ToolDimensions tool;  // R, R2 from the tool table
    Deltas deltas;        // summed: tool table + tool call + correction table
    ProgPath prog_path = ProgPath::kOff;
    ReferencePoint reference = ReferencePoint::kTip;
};

struct Compensated {
    Refusal refusal = Refusal::kNone;
    // The commanded tool tip (TCP): where the tip of the tool of the tool table's length L
    // goes, which is where the machine's length compensation with L carries it. The tool as
    // dimensioned (length L + DL, radii R + DR, R2 + DR2) has its tip DL further along -T.
    Eigen::Vector3d tip = Eigen::Vector3d::Zero();
    // The design surface point the tool touches.
    Eigen::Vector3d contact = Eigen::Vector3d::Zero();
};

// Compensates one programmed point with surface normal n and tool vector t (the vector the
// line runs with: effective_tool_vector()). Face milling and all three peripheral variants
// use it; for peripheral milling with RL/RR pass side_normal() as n.
//   1. the contact point S: the programmed point (IS CONTOUR), or the point the tool table's
//      tool (R, R2) touches when its tip (or centre) is at the programmed point (OFF);
//   2. tip = tip_touching(S, n, t, (R + DR, R2 + DR2)) + DL t.
// With OFF and the tip as reference this is
//   tip = P + DR2 (N - T) - (DR - DR2) u + DL T.
// Refusals: coordinates (kInvalidCoordinate), n or t not unit (kVectorNotNormalised), the
// tool and the effective tool (check_tool, check_deltas, check_effective_tool), N against T
// (kNormalAgainstTool). The oversize rule belongs to loading the tool (check_tool_load).
Compensated compensate(const Eigen::Vector3d& programmed, const Eigen::Vector3d& n,
                       const Eigen::Vector3d& t, const Settings& s) noexcept;

}  // namespace rwmos::comp3d
