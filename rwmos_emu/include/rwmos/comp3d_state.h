// SPDX-License-Identifier: MIT
// The 3D tool compensation module's state (bus 1310; docs/object-map.md section 6) and what
// it does to a spooled profile: an LN line is a G01 profile spooled after its surface normal
// N and tool vector T were armed (object Arm); the module moves its end point on the X, Y, Z
// axes (X/Y/Z-Axis-Nr of the TC module) to the commanded tool tip (rwmos_comp3d,
// docs/3d-compensation.md), and the profile runs as an ordinary G01 to there.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "rwmos/comp3d/compensation.h"
#include "rwmos/motion/types.h"
#include "rwmos/object_map.h"
#include "rwmos/tc_state.h"

namespace rwmos {

// One row of the tool table (DeviceNumber 1): R, R2 and the tool table's delta values, mm.
struct Comp3dTool {
    double r = 0.0;
    double r2 = 0.0;
    comp3d::Deltas deltas;
};

struct Comp3dState {
    std::int32_t tool = 0;              // the tool in force (Tool object: TOOL CALL)
    comp3d::Deltas call;                // the deltas of the TOOL CALL in force
    comp3d::Deltas pending_call;        // CallDeltas: taken by the next Tool write
    std::int32_t correction_row = 0;    // the correction table row in force
    std::int32_t prog_path = 0;         // 0 OFF, 1 IS CONTOUR
    std::int32_t reference = 0;         // 0 tip, 1 centre
    std::int32_t tcpm = 0;              // 1: M128 / FUNCTION TCPM
    std::int32_t allow_oversize = 0;    // 1: M107
    std::int32_t side = tc::kSideNone;  // 40 R0, 41 RL, 42 RR
    std::int32_t head_axis_b = 4;       // board axis of the head's B (kinematics.h)
    std::int32_t head_axis_c = comp3d::kNoHeadAxis;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();       // SurfaceNormal as written
    Eigen::Vector3d tool_vector = Eigen::Vector3d::Zero();  // ToolVector as written
    // Armed for the next profile (Arm object): bits and the vectors, normalised when armed.
    std::int32_t armed = 0;
    Eigen::Vector3d armed_normal = Eigen::Vector3d::Zero();
    Eigen::Vector3d armed_tool_vector = Eigen::Vector3d::Zero();
    std::int32_t last_error = 0;  // comp3d::Refusal of the last refusal
    Eigen::Vector3d last_tip = Eigen::Vector3d::Zero();
    // The normal of the last compensated line, while the 3D path goes on: an LN without N
    // whose motion gives no side keeps it. A profile that is not compensated ends the path.
    bool has_last_normal = false;
    Eigen::Vector3d last_normal = Eigen::Vector3d::Zero();
    std::array<Comp3dTool, comp3d::kToolCount> tools{};
    std::array<comp3d::Deltas, comp3d::kCorrectionRows> corrections{};

    comp3d::ToolDimensions dimensions(std::int32_t t) const noexcept {
        const Comp3dTool& row = tools[static_cast<std::size_t>(t)];
        return {row.r, row.r2};
    }
    // Tool table + tool call + correction table ([TNC-3D]: "Summe der Deltawerte").
    comp3d::Deltas summed(std::int32_t t, const comp3d::Deltas& c,
                          std::int32_t row) const noexcept {
        return comp3d::sum_deltas({tools[static_cast<std::size_t>(t)].deltas, c,
                                   corrections[static_cast<std::size_t>(row)]});
    }
    comp3d::Deltas summed() const noexcept { return summed(tool, call, correction_row); }
    // The loaded tool as the TOOL CALL rules see it (check_tool_load with M107).
    comp3d::Refusal check_loaded(std::int32_t t, const comp3d::Deltas& c, std::int32_t row,
                                 bool m107) const noexcept {
        return comp3d::check_tool_load(dimensions(t), summed(t, c, row), m107);
    }
};

// What the module does to one spooled profile, decided before the spooler sees it.
struct Comp3dPlan {
    comp3d::Refusal refusal = comp3d::Refusal::kNone;
    bool consumes = false;     // the armed vectors are used up when the profile is taken
    bool compensated = false;  // the profile's X/Y/Z target was moved to `tip`
    Eigen::Vector3d tip = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // the normal it was compensated along
};

// Plans the 3D compensation of `p` (modified in place when compensated). `program` is the
// spooler's programmed position (where the profile starts). Nothing happens unless the module
// is armed (Arm: N, T, or a line without vectors for peripheral milling with RL/RR); the arming
// is used by the next profile whatever its kind, and only a G01 is compensated (rapids and arcs
// never are). Refusals change nothing.
Comp3dPlan plan_profile(const Comp3dState& s, const TcState& tc, const motion::AxisVector& program,
                        motion::Profile& p) noexcept;
// After the spooler took the profile: the armed vectors are used up, the tip and normal
// remembered (or forgotten, when the profile was not compensated).
void commit_profile(Comp3dState& s, const Comp3dPlan& plan) noexcept;
// The status a refused profile answers with: InvalidValue for geometry the program gives,
// WrongDeviceState for the tool and the module's state.
objif::Status refusal_status(comp3d::Refusal r) noexcept;

}  // namespace rwmos
