// SPDX-License-Identifier: MIT
// Helpers shared by the emulator tests: descriptors for the board and TC
// objects, typed read/write through Board, and a snapshot of the device state
// to prove that a refused request changed nothing.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "rwmos/board.h"
#include "rwmos/board_state.h"
#include "rwmos/object_map.h"

namespace emu_test {

using objif::Descriptor;
using objif::Status;
using objif::Value;
using objif::ValueType;

inline Descriptor at(std::int32_t bus, std::int32_t dev, std::int32_t idx, std::int32_t sub) {
    return Descriptor{{bus, dev, idx, sub}, objif::kNoHandle};
}
inline Descriptor board_obj(std::int32_t idx, std::int32_t sub = 0) {
    return at(rwmos::board::kBus, rwmos::board::kDevice, idx, sub);
}
inline Descriptor tc_init(std::int32_t idx, std::int32_t sub = 0) {
    return at(rwmos::tc::kBus, rwmos::tc::kDevInit, idx, sub);
}
inline Descriptor tc_group(std::int32_t group, std::int32_t sub) {
    return at(rwmos::tc::kBus, rwmos::tc::kDevGroups, group, sub);
}

// The device state a request may change, copied so a test can compare before/after.
struct Snapshot {
    std::int32_t interpolation_cycle_us;
    std::int32_t pu;
    std::unique_ptr<rwmos::TcState> tc;
    std::unique_ptr<rwmos::Comp3dState> comp3d;
    rwmos::OtcState otc;
    rwmos::TempCompState temp_comp;
};
inline Snapshot snapshot(const rwmos::EmulatedBoard& board) {
    const auto& s = board.state();
    Snapshot snap{s.interpolation_cycle_us, s.pu, nullptr, nullptr, s.otc, s.temp_comp};
    snap.tc = std::make_unique<rwmos::TcState>(s.tc);
    snap.comp3d = std::make_unique<rwmos::Comp3dState>(s.comp3d);
    return snap;
}

inline bool same_deltas(const rwmos::comp3d::Deltas& a, const rwmos::comp3d::Deltas& b) {
    return a.dl == b.dl && a.dr == b.dr && a.dr2 == b.dr2;
}
inline bool same_comp3d(const rwmos::Comp3dState& a, const rwmos::Comp3dState& b) {
    if (a.tool != b.tool || !same_deltas(a.call, b.call) || !same_deltas(a.pending_call, b.pending_call) ||
        a.correction_row != b.correction_row || a.prog_path != b.prog_path ||
        a.reference != b.reference || a.tcpm != b.tcpm || a.allow_oversize != b.allow_oversize ||
        a.side != b.side || a.head_axis_b != b.head_axis_b || a.head_axis_c != b.head_axis_c ||
        a.normal != b.normal || a.tool_vector != b.tool_vector || a.armed != b.armed ||
        a.armed_normal != b.armed_normal || a.armed_tool_vector != b.armed_tool_vector ||
        a.last_error != b.last_error || a.last_tip != b.last_tip ||
        a.has_last_normal != b.has_last_normal || a.last_normal != b.last_normal)
        return false;
    for (std::size_t i = 0; i < a.tools.size(); ++i)
        if (a.tools[i].r != b.tools[i].r || a.tools[i].r2 != b.tools[i].r2 ||
            !same_deltas(a.tools[i].deltas, b.tools[i].deltas))
            return false;
    for (std::size_t i = 0; i < a.corrections.size(); ++i)
        if (!same_deltas(a.corrections[i], b.corrections[i])) return false;
    return true;
}

// The OTC settings, units, tool and wear (LastError is the refusal's own record, not compared).
inline bool same_otc(const rwmos::OtcState& a, const rwmos::OtcState& b) {
    auto unit_eq = [](const rwmos::OtcControlUnit& x, const rwmos::OtcControlUnit& y) {
        return x.command == y.command && x.enable == y.enable;
    };
    if (a.active != b.active || a.type != b.type || a.mode != b.mode ||
        a.programmed_wear_const != b.programmed_wear_const ||
        a.use_programmed_wear_const != b.use_programmed_wear_const || a.acc_weight != b.acc_weight ||
        a.ramp_velocity != b.ramp_velocity || a.ramp_acceleration != b.ramp_acceleration ||
        a.kinematics != b.kinematics || a.trafo != b.trafo || a.tool_axis_b != b.tool_axis_b)
        return false;
    if (!unit_eq(a.radius_offset_unit, b.radius_offset_unit)) return false;
    for (std::size_t i = 0; i < a.axis_units.size(); ++i)
        if (!unit_eq(a.axis_units[i], b.axis_units[i])) return false;
    if (a.tool.number != b.tool.number || a.tool.type != b.tool.type ||
        a.tool.wear_const != b.tool.wear_const || a.tool.max_infeed != b.tool.max_infeed ||
        a.tool.tilt_angle != b.tool.tilt_angle)
        return false;
    return a.wear.radius == b.wear.radius && a.wear.radius_cont == b.wear.radius_cont &&
           a.wear.axis == b.wear.axis;
}

inline bool same_group(const rwmos::TcGroup& a, const rwmos::TcGroup& b) {
    if (a.error != b.error || a.status != b.status || a.x_axis != b.x_axis || a.y_axis != b.y_axis ||
        a.z_axis != b.z_axis || a.tool_index != b.tool_index || a.side != b.side ||
        a.corner_mode != b.corner_mode || a.offset != b.offset)
        return false;
    for (std::size_t i = 0; i < a.tools.size(); ++i)
        if (a.tools[i].radius != b.tools[i].radius || a.tools[i].length != b.tools[i].length)
            return false;
    return true;
}

// True when nothing of the snapshot differs from the board's state now.
inline ::testing::AssertionResult unchanged(const Snapshot& before, const rwmos::EmulatedBoard& board) {
    const auto& s = board.state();
    const auto& t = *before.tc;
    if (s.interpolation_cycle_us != before.interpolation_cycle_us) return ::testing::AssertionFailure() << "interpolation cycle changed";
    if (s.pu != before.pu) return ::testing::AssertionFailure() << "PU changed";
    if (s.tc.axis_nr != t.axis_nr) return ::testing::AssertionFailure() << "Axis-Nr changed";
    if (s.tc.plane != t.plane) return ::testing::AssertionFailure() << "TcPlane changed";
    if (s.tc.rot_angle != t.rot_angle || s.tc.rot_center_x != t.rot_center_x ||
        s.tc.rot_center_y != t.rot_center_y)
        return ::testing::AssertionFailure() << "rotation changed";
    if (s.tc.objects_accessed != t.objects_accessed) return ::testing::AssertionFailure() << "accessed flag changed";
    for (std::int32_t n = 1; n <= rwmos::tc::kGroupCount; ++n)
        if (!same_group(s.tc.group(n), t.group(n)))
            return ::testing::AssertionFailure() << "group " << n << " changed";
    if (!same_comp3d(*before.comp3d, s.comp3d)) return ::testing::AssertionFailure() << "3D compensation changed";
    const auto& tt = before.temp_comp;
    if (tt.comp != s.temp_comp.comp || tt.on != s.temp_comp.on || tt.type != s.temp_comp.type ||
        tt.tool_holder != s.temp_comp.tool_holder || tt.head_axis_b != s.temp_comp.head_axis_b ||
        tt.head_axis_c != s.temp_comp.head_axis_c || tt.ramp_velocity != s.temp_comp.ramp_velocity)
        return ::testing::AssertionFailure() << "temperature compensation changed";
    if (!same_otc(s.otc, before.otc)) return ::testing::AssertionFailure() << "OTC state changed";
    return ::testing::AssertionSuccess();
}

// Typed access through the board's public read/write.
class BoardFixture : public ::testing::Test {
protected:
    explicit BoardFixture(rwmos::BoardConfig config = {}) : board(config) {}

    Status write_int(Descriptor d, std::int32_t v) { return board.write(d, Value::of_int(v)); }
    Status write_double(Descriptor d, double v) { return board.write(d, Value::of_double(v)); }
    std::int32_t read_int(Descriptor d) {
        Value v;
        const Status st = board.read(d, ValueType::kInt32, v);
        EXPECT_EQ(st, Status::kOk) << "read " << d.address.to_string();
        return v.as_int();
    }
    double read_double(Descriptor d) {
        Value v;
        const Status st = board.read(d, ValueType::kDouble, v);
        EXPECT_EQ(st, Status::kOk) << "read " << d.address.to_string();
        return v.as_double();
    }
    Status read_status_of(Descriptor d, ValueType want) {
        Value v;
        return board.read(d, want, v);
    }

    // [APCI-TC] section 2.5 initialisation of one group in the X-Y plane:
    // axes 0/1/2, tool `tool` with `radius`, right side.
    void initialise_group(std::int32_t group, std::int32_t tool = 1, double radius = 2.0) {
        ASSERT_EQ(write_int(tc_group(group, rwmos::tc::kSubXAxis), 0), Status::kOk);
        ASSERT_EQ(write_int(tc_group(group, rwmos::tc::kSubYAxis), 1), Status::kOk);
        ASSERT_EQ(write_int(tc_group(group, rwmos::tc::kSubZAxis), 2), Status::kOk);
        ASSERT_EQ(write_int(tc_group(group, rwmos::tc::kSubWkzIndex), tool), Status::kOk);
        ASSERT_EQ(write_double(tc_group(group, rwmos::tc::kSubRadius), radius), Status::kOk);
        ASSERT_EQ(write_int(tc_group(group, rwmos::tc::kSubRight), 1), Status::kOk);
    }
    void activate(std::int32_t group) {
        ASSERT_EQ(write_int(tc_group(group, rwmos::tc::kSubStatus), 1), Status::kOk);
    }

    rwmos::EmulatedBoard board;
};

}  // namespace emu_test
