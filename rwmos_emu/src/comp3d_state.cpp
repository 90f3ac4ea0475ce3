// SPDX-License-Identifier: MIT
#include "rwmos/comp3d_state.h"

#include "rwmos/comp3d/vectors.h"
#include "rwmos/geometry/kinematics.h"

namespace rwmos {

namespace {

using comp3d::Refusal;

// An axis the profile names takes its target, the others keep the programmed position.
double axis_target(const motion::Profile& p, const motion::AxisVector& program, std::int32_t axis) {
    const auto i = static_cast<std::size_t>(axis);
    return (p.axes & (1U << axis)) != 0 ? p.target[i] : program[i];
}

// The tool axis of the machine (without TCPM): the head at the profile's B and C
// (rwmos/geometry/kinematics.h).
Eigen::Vector3d machine_tool_axis(const Comp3dState& s, const motion::Profile& p,
                                  const motion::AxisVector& program) {
    const double b = axis_target(p, program, s.head_axis_b);
    const double c =
        s.head_axis_c == comp3d::kNoHeadAxis ? 0.0 : axis_target(p, program, s.head_axis_c);
    return geom::bc_head_tool_direction(b, c);
}

bool tc_compensating(const TcState& tc) noexcept {
    for (const TcGroup& g : tc.groups) {
        if (g.running()) return true;
    }
    return false;
}

// Peripheral milling without N ([TNC-3D]): the side from RL/RR and the motion; where that
// gives none (no motion, a plunge, or R0), the normal of the line before, while the 3D path
// goes on ([TNC-3D]'s block 13 repeats block 12's point with T only, "Kompensation möglich").
comp3d::SideNormal peripheral_normal(const Comp3dState& s, const Eigen::Vector3d& motion,
                                     const Eigen::Vector3d& tool_axis) noexcept {
    comp3d::SideNormal side{Refusal::kNoCompensationSide, Eigen::Vector3d::Zero()};
    if (s.side != tc::kSideNone) {
        side = comp3d::side_normal(
            motion, tool_axis,
            s.side == tc::kSideLeft ? comp3d::Side::kLeft : comp3d::Side::kRight);
        if (side.refusal == Refusal::kNone) return side;
    }
    if (s.has_last_normal) {
        comp3d::SideNormal kept = comp3d::previous_side_normal(s.last_normal, tool_axis);
        if (kept.refusal == Refusal::kNone) return kept;
    }
    return side;
}

}  // namespace

Comp3dPlan plan_profile(const Comp3dState& s, const TcState& tc, const motion::AxisVector& program,
                        motion::Profile& p) noexcept {
    Comp3dPlan plan;
    if (s.armed == 0) return plan;
    plan.consumes = true;
    if (p.kind != motion::ProfileKind::kLine) return plan;
    if (tc_compensating(tc)) {
        plan.refusal = Refusal::kRadiusCompensationRunning;
        return plan;
    }
    Eigen::Vector3d start;
    Eigen::Vector3d end;
    for (int k = 0; k < 3; ++k) {
        const std::int32_t axis = tc.axis_nr[static_cast<std::size_t>(k)];
        start[k] = program[static_cast<std::size_t>(axis)];
        end[k] = axis_target(p, program, axis);
    }
    const bool has_n = (s.armed & comp3d::kArmNormal) != 0;
    const bool has_t = (s.armed & comp3d::kArmToolVector) != 0;
    const std::optional<Eigen::Vector3d> n =
        has_n ? std::optional<Eigen::Vector3d>(s.armed_normal) : std::nullopt;
    const std::optional<Eigen::Vector3d> t =
        has_t ? std::optional<Eigen::Vector3d>(s.armed_tool_vector) : std::nullopt;
    const Eigen::Vector3d tool_axis =
        comp3d::effective_tool_vector(s.tcpm != 0, t, n, machine_tool_axis(s, p, program));
    Eigen::Vector3d normal = s.armed_normal;
    if (!has_n) {
        const comp3d::SideNormal side = peripheral_normal(s, end - start, tool_axis);
        if (side.refusal != Refusal::kNone) {
            plan.refusal = side.refusal;
            return plan;
        }
        normal = side.n;
    }
    const Refusal load = s.check_loaded(s.tool, s.call, s.correction_row, s.allow_oversize != 0);
    if (load != Refusal::kNone) {
        plan.refusal = load;
        return plan;
    }
    comp3d::Settings settings;
    settings.tool = s.dimensions(s.tool);
    settings.deltas = s.summed();
    settings.prog_path = s.prog_path != 0 ? comp3d::ProgPath::kContour : comp3d::ProgPath::kOff;
    settings.reference =
        s.reference != 0 ? comp3d::ReferencePoint::kCentre : comp3d::ReferencePoint::kTip;
    const comp3d::Compensated c = comp3d::compensate(end, normal, tool_axis, settings);
    if (c.refusal != Refusal::kNone) {
        plan.refusal = c.refusal;
        return plan;
    }
    for (int k = 0; k < 3; ++k) {
        const std::int32_t axis = tc.axis_nr[static_cast<std::size_t>(k)];
        p.axes = static_cast<motion::AxisMask>(p.axes | (1U << axis));
        p.target[static_cast<std::size_t>(axis)] = c.tip[k];
    }
    plan.compensated = true;
    plan.tip = c.tip;
    plan.normal = normal;
    return plan;
}

void commit_profile(Comp3dState& s, const Comp3dPlan& plan) noexcept {
    if (plan.consumes) s.armed = 0;
    s.has_last_normal = plan.compensated;
    if (plan.compensated) {
        s.last_tip = plan.tip;
        s.last_normal = plan.normal;
    }
}

objif::Status refusal_status(comp3d::Refusal r) noexcept {
    switch (r) {
        case Refusal::kNone:
            return objif::Status::kOk;
        case Refusal::kInvalidCoordinate:
        case Refusal::kVectorNotNormalised:
        case Refusal::kNormalAgainstTool:
        case Refusal::kNoSideFromMotion:
            return objif::Status::kInvalidValue;
        default:
            return objif::Status::kWrongDeviceState;
    }
}

}  // namespace rwmos
