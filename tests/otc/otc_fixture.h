// SPDX-License-Identifier: MIT
// A Board with the OTC objects at hand (bus 1330): the grinding tool of [ISG-OTC] (section
// 2.6), #OTC ON/OFF, control-unit writes, and the offset of the axes from the nominal path.
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "motion_fixture.h"
#include "rwmos/otc/errors.h"
#include "rwmos/otc/types.h"

namespace otc_test {

using namespace motion_test;
namespace otc = rwmos::otc;

// [ISG-OTC] section 2.6: typ 2, laenge 500000 and radius 300000 (0.1 um: 50 mm and 30 mm),
// grinding_wear_const 100000 (0.1 um/m), grinding_max_infeed 200000 (0.1 um), tilt 0.
inline constexpr double kGrindingWearConst = 100000.0;
inline constexpr double kGrindingMaxInfeed = 200000.0;
inline constexpr double kGrindingDiscRadius = 30.0;
inline constexpr double kGrindingDiscLength = 50.0;
inline constexpr std::int32_t kTool = 1;

struct OtcRig : Rig {
    Status otc_int(std::int32_t dev, std::int32_t idx, std::int32_t sub, std::int32_t v) {
        return write_int(otc::kBus, dev, idx, sub, v);
    }
    Status otc_double(std::int32_t dev, std::int32_t idx, std::int32_t sub, double v) {
        return write_double(otc::kBus, dev, idx, sub, v);
    }
    std::int32_t otc_read_int(std::int32_t dev, std::int32_t idx, std::int32_t sub = 0) {
        return read_int(otc::kBus, dev, idx, sub);
    }
    double otc_read_double(std::int32_t dev, std::int32_t idx, std::int32_t sub = 0) {
        return read_double(otc::kBus, dev, idx, sub);
    }

    // The tool data the host writes at a tool change: OTC's current tool and TC's tool table
    // (every group, WKZINDEX = the tool number).
    void grinding_tool(std::int32_t type = otc::kGrindingToolType,
                       double wear_const = kGrindingWearConst, double max_infeed = kGrindingMaxInfeed,
                       double tilt_units = 0.0) {
        using namespace rwmos::otc;
        ASSERT_EQ(otc_int(kDevTool, kIdxToolNumber, 0, kTool), Status::kOk);
        ASSERT_EQ(otc_int(kDevTool, kIdxToolType, 0, type), Status::kOk);
        ASSERT_EQ(otc_double(kDevTool, kIdxToolWearConst, 0, wear_const), Status::kOk);
        ASSERT_EQ(otc_double(kDevTool, kIdxToolMaxInfeed, 0, max_infeed), Status::kOk);
        ASSERT_EQ(otc_double(kDevTool, kIdxToolTiltAngle, 0, tilt_units), Status::kOk);
        for (auto& g : board.state().tc.groups) {
            g.tools[kTool].radius = kGrindingDiscRadius;
            g.tools[kTool].length = kGrindingDiscLength;
        }
    }
    Status set_type(otc::ProcessingType t) {
        return otc_int(otc::kDevChannel, otc::kIdxProcessingType, 0, static_cast<std::int32_t>(t));
    }
    Status set_mode(otc::Mode m) {
        return otc_int(otc::kDevChannel, otc::kIdxMode, 0, static_cast<std::int32_t>(m));
    }
    Status otc_on() { return otc_int(otc::kDevChannel, otc::kIdxActive, 0, 1); }
    Status otc_off() { return otc_int(otc::kDevChannel, otc::kIdxActive, 0, 0); }
    bool otc_active() { return otc_read_int(otc::kDevChannel, otc::kIdxActive) == 1; }
    std::int32_t last_error() { return otc_read_int(otc::kDevChannel, otc::kIdxLastError); }

    // The PLC: enable a unit and command an offset (0.1 um). Channel unit: axis < 0.
    Status plc(int axis, std::int32_t tenth_um) {
        const std::int32_t dev = axis < 0 ? otc::kDevChannel : otc::kDevAxisUnits;
        const std::int32_t idx = axis < 0 ? otc::kIdxRadiusOffsetUnit : axis;
        const Status e = otc_int(dev, idx, otc::kSubEnable, 1);
        if (e != Status::kOk) return e;
        return otc_int(dev, idx, otc::kSubCommand, tenth_um);
    }
    std::int32_t unit_state(int axis) {
        return axis < 0 ? otc_read_int(otc::kDevChannel, otc::kIdxRadiusOffsetUnit, otc::kSubState)
                        : otc_read_int(otc::kDevAxisUnits, axis, otc::kSubState);
    }
    std::int32_t unit_request(int axis) {
        return axis < 0
                   ? otc_read_int(otc::kDevChannel, otc::kIdxRadiusOffsetUnit, otc::kSubRequest)
                   : otc_read_int(otc::kDevAxisUnits, axis, otc::kSubRequest);
    }

    double wear(int axis) { return otc_read_double(otc::kDevTool, otc::kIdxWear, axis); }
    double wear_radius() { return otc_read_double(otc::kDevTool, otc::kIdxWearRadius); }
    double wear_radius_cont() { return otc_read_double(otc::kDevTool, otc::kIdxWearRadiusCont); }

    // Axis positions minus the nominal path: what OTC adds now.
    AxisVector offset() {
        const auto& e = board.state().motion.executor();
        AxisVector o{};
        for (std::size_t a = 0; a < o.size(); ++a) o[a] = e.position()[a] - e.nominal_position()[a];
        return o;
    }
    const AxisVector& nominal() { return board.state().motion.executor().nominal_position(); }

    // Runs the clock until the queue is empty and #OTC OFF is taken.
    void run_and_off() {
        run();
        ASSERT_EQ(otc_off(), Status::kOk);
    }
};

class OtcBoard : public ::testing::Test, public OtcRig {};

inline double norm(const AxisVector& v) {
    double s = 0.0;
    for (double x : v) s += x * x;
    return std::sqrt(s);
}

}  // namespace otc_test
