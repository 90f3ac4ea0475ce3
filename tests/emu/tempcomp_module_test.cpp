// SPDX-License-Identifier: MIT
// The temperature compensation module on a Board (bus 1320; docs/object-map.md section 7): each
// rule of [SIN-TEMP] (SINUMERIK FB1 W1 section 2.8) as it shows on the axes, cycle by cycle. The
// nominal path is taken from a twin board without the compensation, driven the same way.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "motion_fixture.h"
#include "objif/map/object_map.h"
#include "rwmos/geometry/kinematics.h"

namespace {

using namespace motion_test;
namespace tcomp = rwmos::tempcomp;
using V = Eigen::Vector3d;

class TempCompBoard : public ::testing::Test {
  protected:
    Rig board;  // with the compensation
    Rig twin;   // the same motion without it

    Status set(std::int32_t idx, std::int32_t sub, std::int32_t v) {
        return board.write_int(tcomp::kBus, tcomp::kDevice, idx, sub, v);
    }
    Status set_d(std::int32_t idx, std::int32_t sub, double v) {
        return board.write_double(tcomp::kBus, tcomp::kDevice, idx, sub, v);
    }
    void comp(double x, double y, double z) {
        ASSERT_EQ(set_d(tcomp::kIdxToolTempComp, 0, x), Status::kOk);
        ASSERT_EQ(set_d(tcomp::kIdxToolTempComp, 1, y), Status::kOk);
        ASSERT_EQ(set_d(tcomp::kIdxToolTempComp, 2, z), Status::kOk);
    }
    // MD 20390 on, bit 2 of MD 32750 on the given axes.
    void enable(std::initializer_list<int> axes) {
        ASSERT_EQ(set(tcomp::kIdxToolTempCompOn, 0, 1), Status::kOk);
        for (const int a : axes) ASSERT_EQ(set(tcomp::kIdxTempCompType, a, 0x04), Status::kOk);
    }
    void spool_both(const Profile& p) {
        board.spool_ok(p);
        twin.spool_ok(p);
    }
    void step_both(std::uint64_t cycles) {
        board.board.step(cycles);
        twin.board.step(cycles);
    }
    // Where the compensation has put the axes: board position minus the twin's.
    AxisVector displacement() {
        const AxisVector a = board.position();
        const AxisVector b = twin.position();
        AxisVector d{};
        for (std::size_t i = 0; i < d.size(); ++i) d[i] = a[i] - b[i];
        return d;
    }
    double offset_object(int axis) {
        return board.read_double(tcomp::kBus, tcomp::kDevice, tcomp::kIdxOffset, axis);
    }
    static Profile head(double b, double c = 0.0, double feed = 0.0) {
        Profile p;
        p.kind = feed > 0.0 ? ProfileKind::kLine : ProfileKind::kRapid;
        p.feed = feed;
        p.axes = 0x30;
        p.target[4] = b;
        p.target[5] = c;
        return p;
    }
};

TEST_F(TempCompBoard, VectorActsOnTheGeometryAxesAtTheNextCycle) {
    enable({0, 1, 2});
    comp(0.01, 0.02, 0.03);
    step_both(1);
    const AxisVector d = displacement();
    EXPECT_EQ(d[0], 0.01);
    EXPECT_EQ(d[1], 0.02);
    EXPECT_EQ(d[2], 0.03);
    for (int a = 3; a < 8; ++a) EXPECT_EQ(d[static_cast<std::size_t>(a)], 0.0);
    EXPECT_EQ(offset_object(2), 0.03);
    EXPECT_EQ(board.read_double(rwmos::board::kBus, rwmos::board::kDevice,
                                rwmos::board::kIdxAxisPosition, 2),
              0.03);
}

// [SIN-TEMP]: "Werteveränderungen in den Settingdaten werden sofort wirksam."
TEST_F(TempCompBoard, WrittenValueTakesEffectAtOnceInTheMiddleOfAProfile) {
    enable({0, 1, 2});
    comp(0.0, 0.0, 0.01);
    spool_both(line3(1, 100, 0, 0, 600));  // 10 s at 1 ms
    step_both(4000);
    EXPECT_NEAR(displacement()[2], 0.01, 1e-15);
    comp(0.0, 0.0, 0.05);
    step_both(1);
    EXPECT_NEAR(displacement()[2], 0.05, 1e-15);
    EXPECT_GT(twin.position()[0], 39.0);  // still in the middle of the profile
    EXPECT_LT(twin.position()[0], 41.0);
}

TEST_F(TempCompBoard, WithoutMd20390NothingActs) {
    ASSERT_EQ(set(tcomp::kIdxTempCompType, 2, 0x04), Status::kOk);
    comp(0.01, 0.02, 0.03);
    step_both(5);
    for (const double d : displacement()) EXPECT_EQ(d, 0.0);
    ASSERT_EQ(set(tcomp::kIdxToolTempCompOn, 0, 1), Status::kOk);
    step_both(1);
    EXPECT_EQ(displacement()[2], 0.03);
    ASSERT_EQ(set(tcomp::kIdxToolTempCompOn, 0, 0), Status::kOk);
    step_both(1);
    EXPECT_EQ(displacement()[2], 0.0);
}

// [SIN-TEMP]: MD 20390 activates the function with any value "ungleich Null"; the object keeps
// the value as written (docs/object-map.md section 7).
TEST_F(TempCompBoard, AnyNonZeroMd20390SwitchesOnAndReadsBackAsWritten) {
    ASSERT_EQ(set(tcomp::kIdxTempCompType, 2, 0x04), Status::kOk);
    comp(0.0, 0.0, 0.03);
    for (const std::int32_t on : {2, -1, 7, std::numeric_limits<std::int32_t>::min(),
                                  std::numeric_limits<std::int32_t>::max()}) {
        ASSERT_EQ(set(tcomp::kIdxToolTempCompOn, 0, on), Status::kOk) << on;
        EXPECT_EQ(board.read_int(tcomp::kBus, tcomp::kDevice, tcomp::kIdxToolTempCompOn, 0), on);
        step_both(1);
        EXPECT_EQ(displacement()[2], 0.03) << "MD 20390 = " << on;
        ASSERT_EQ(set(tcomp::kIdxToolTempCompOn, 0, 0), Status::kOk);
        step_both(1);
        EXPECT_EQ(displacement()[2], 0.0) << "MD 20390 = 0 after " << on;
    }
}

// [SIN-TEMP]: "Ist dieses Bit für eine bestimmte Kanalachse nicht gesetzt, kann in dieser Achse
// kein Kompensationswert wirksam werden. Andere Achse bleiben davon jedoch unbeeinflußt. Ein
// Alarm wird in diesem Fall nicht ausgegeben."
TEST_F(TempCompBoard, AxisWithoutBit2GetsNoValueSilentlyAndTheOthersKeepTheirs) {
    enable({0, 2});
    ASSERT_EQ(set(tcomp::kIdxTempCompType, 1, 0x03), Status::kOk);
    comp(0.01, 0.02, 0.03);
    spool_both(line3(1, 5, 5, 5));
    board.run();
    twin.run();
    const AxisVector d = displacement();
    EXPECT_NEAR(d[0], 0.01, 1e-12);  // positions near 5: the difference rounds
    EXPECT_EQ(d[1], 0.0);
    EXPECT_NEAR(d[2], 0.03, 1e-12);
    EXPECT_EQ(board.board.motion_status().held, false);  // no alarm, nothing stops
}

TEST_F(TempCompBoard, ClearingBit2TakesTheValueOffAtOnce) {
    enable({0, 1, 2});
    comp(0.01, 0.02, 0.03);
    step_both(1);
    ASSERT_EQ(set(tcomp::kIdxTempCompType, 1, 0), Status::kOk);
    step_both(1);
    EXPECT_EQ(displacement()[1], 0.0);
    EXPECT_EQ(displacement()[0], 0.01);
}

// [SIN-TEMP], "Orientierbarer Werkzeugträger": the vector turns with the tool.
TEST_F(TempCompBoard, VectorTurnsWithTheOrientableToolHolder) {
    enable({0, 1, 2});
    ASSERT_EQ(set(tcomp::kIdxToolHolder, 0, 1), Status::kOk);
    comp(0.0, 0.0, 0.05);
    spool_both(head(90.0));
    board.run();
    twin.run();
    step_both(1);
    const AxisVector d = displacement();
    EXPECT_NEAR(d[0], 0.05, 1e-15);
    EXPECT_NEAR(d[1], 0.0, 1e-15);
    EXPECT_NEAR(d[2], 0.0, 1e-15);
    EXPECT_EQ(d[4], 0.0);  // the head itself is not displaced
}

TEST_F(TempCompBoard, WithoutTheToolHolderTheVectorDoesNotTurn) {
    enable({0, 1, 2});
    comp(0.0, 0.0, 0.05);
    spool_both(head(90.0));
    board.run();
    twin.run();
    step_both(1);
    EXPECT_EQ(displacement()[2], 0.05);
    EXPECT_EQ(displacement()[0], 0.0);
}

TEST_F(TempCompBoard, VectorTurnsWithTheHeadsCAxisToo) {
    enable({0, 1, 2});
    ASSERT_EQ(set(tcomp::kIdxToolHolder, 0, 1), Status::kOk);
    ASSERT_EQ(set(tcomp::kIdxHeadAxisC, 0, 5), Status::kOk);
    comp(0.0, 0.0, 0.05);
    spool_both(head(90.0, 90.0));
    board.run();
    twin.run();
    step_both(1);
    const AxisVector d = displacement();
    EXPECT_NEAR(d[0], 0.0, 1e-15);
    EXPECT_NEAR(d[1], 0.05, 1e-15);
}

// [SIN-TEMP]: "Die Temperaturkompensationswerte folgen unmittelbar jeder wirksam werdenden
// Orientierungsänderung": every cycle of a head move, the displacement is the vector turned by
// the head's B at that cycle.
TEST_F(TempCompBoard, DisplacementFollowsEveryCycleOfAnOrientationChange) {
    enable({0, 1, 2});
    ASSERT_EQ(set(tcomp::kIdxToolHolder, 0, 1), Status::kOk);
    comp(0.01, 0.0, 0.05);
    ASSERT_EQ(board.board.set_trace(true, 10000), Status::kOk);
    ASSERT_EQ(twin.board.set_trace(true, 10000), Status::kOk);
    spool_both(head(60.0, 0.0, 6000.0));  // 60 degrees at 6000 deg/min: 600 cycles
    board.run();
    twin.run();
    std::vector<rwmos::motion::TraceSample> a(700), b(700);
    a.resize(board.board.read_trace(a));
    b.resize(twin.board.read_trace(b));
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GE(a.size(), 600U);
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double bdeg = b[i].position[4];
        const V want = rwmos::geom::bc_head_rotation(bdeg, 0.0) * V(0.01, 0.0, 0.05);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(a[i].position[static_cast<std::size_t>(k)] -
                            b[i].position[static_cast<std::size_t>(k)],
                        want[k], 1e-15)
                << "cycle " << a[i].cycle;
        }
    }
}

// The holder switched on or off is an orientation change too: it acts at the next cycle.
TEST_F(TempCompBoard, SwitchingTheToolHolderActsAtTheNextCycle) {
    enable({0, 1, 2});
    comp(0.0, 0.0, 0.05);
    spool_both(head(90.0));
    board.run();
    twin.run();
    ASSERT_EQ(set(tcomp::kIdxToolHolder, 0, 1), Status::kOk);
    step_both(1);
    EXPECT_NEAR(displacement()[0], 0.05, 1e-15);
    ASSERT_EQ(set(tcomp::kIdxToolHolder, 0, 0), Status::kOk);
    step_both(1);
    EXPECT_EQ(displacement()[0], 0.0);
    EXPECT_EQ(displacement()[2], 0.05);
}

// [SIN-TEMP]: the values act along the geometry axes "in Grundstellung bzw. bei ausgeschalteter
// Orientierungstransformation"; with the orientation transformation on (#KIN ID[4], #TRAFO ON:
// the OTC module's B head) they turn with the tool, at once, the switch included. B90 moves a +Z
// value to +X without the tool holder.
TEST_F(TempCompBoard, VectorTurnsWithTheOrientationTransformation) {
    namespace otc = objif::map::otc;
    enable({0, 1, 2});
    comp(0.0, 0.0, 0.05);
    spool_both(head(90.0));
    board.run();
    twin.run();
    step_both(1);
    EXPECT_EQ(displacement()[2], 0.05);  // transformation off: along Z
    ASSERT_EQ(board.write_int(otc::kBus, otc::kDevChannel, otc::kIdxKinematics, 0, 4), Status::kOk);
    step_both(1);
    EXPECT_EQ(displacement()[2], 0.05);  // a kinematics alone turns nothing
    ASSERT_EQ(board.write_int(otc::kBus, otc::kDevChannel, otc::kIdxTrafo, 0, 1), Status::kOk);
    step_both(1);
    EXPECT_NEAR(displacement()[0], 0.05, 1e-15);
    EXPECT_NEAR(displacement()[2], 0.0, 1e-15);
    // With the tool holder as well, the vector takes both turns ([SIN-TEMP]: "beiden Drehungen
    // unterworfen"): B90 twice, +Z to -Z.
    ASSERT_EQ(set(tcomp::kIdxToolHolder, 0, 1), Status::kOk);
    step_both(1);
    EXPECT_NEAR(displacement()[0], 0.0, 1e-15);
    EXPECT_NEAR(displacement()[2], -0.05, 1e-15);
    ASSERT_EQ(set(tcomp::kIdxToolHolder, 0, 0), Status::kOk);
    ASSERT_EQ(board.write_int(otc::kBus, otc::kDevChannel, otc::kIdxTrafo, 0, 0), Status::kOk);
    step_both(1);
    EXPECT_EQ(displacement()[0], 0.0);  // the switch off acts at once
    EXPECT_EQ(displacement()[2], 0.05);
}

// [SIN-TEMP]: an axis that stops being a geometry axis is brought to zero "interpolatorisch";
// one that becomes a geometry axis takes its value at once.
TEST_F(TempCompBoard, AxisLeavingTheGeometryAxesRampsToZeroAndTheNewOneTakesItAtOnce) {
    enable({0, 1, 2, 3});
    comp(0.01, 0.02, 0.03);
    step_both(1);
    ASSERT_EQ(displacement()[2], 0.03);
    // Z moves to board axis 3 (TC Device 0 Index 11).
    ASSERT_EQ(board.write_int(rwmos::tc::kBus, rwmos::tc::kDevInit, rwmos::tc::kIdxAxisNr,
                              rwmos::tc::kSubZ, 3),
              Status::kOk);
    // 1 unit/s at 1 ms: 0.001 per cycle.
    for (int cycle = 1; cycle <= 35; ++cycle) {
        step_both(1);
        const AxisVector d = displacement();
        EXPECT_EQ(d[3], 0.03) << cycle;
        EXPECT_NEAR(d[2], std::max(0.0, 0.03 - 0.001 * cycle), 1e-12) << cycle;
        EXPECT_EQ(d[0], 0.01);
    }
    EXPECT_EQ(displacement()[2], 0.0);
    EXPECT_EQ(offset_object(2), 0.0);
}

TEST_F(TempCompBoard, RampRunsDuringAMoveAtTheRampVelocity) {
    enable({0, 1, 2, 3});
    ASSERT_EQ(set_d(tcomp::kIdxRampVelocity, 0, 2.0), Status::kOk);  // 0.002 per cycle
    comp(0.0, 0.0, 0.02);
    spool_both(line3(1, 100, 0, 0, 600));
    step_both(10);
    ASSERT_EQ(board.write_int(rwmos::tc::kBus, rwmos::tc::kDevInit, rwmos::tc::kIdxAxisNr,
                              rwmos::tc::kSubZ, 3),
              Status::kOk);
    step_both(5);
    EXPECT_NEAR(displacement()[2], 0.01, 1e-12);
    step_both(5);
    EXPECT_EQ(displacement()[2], 0.0);
    step_both(100);
    EXPECT_EQ(displacement()[2], 0.0);
}

TEST_F(TempCompBoard, AxisBecomingAGeometryAxisAgainStopsItsRampAndTakesTheValue) {
    enable({0, 1, 2, 3});
    comp(0.0, 0.0, 0.03);
    step_both(1);
    ASSERT_EQ(board.write_int(rwmos::tc::kBus, rwmos::tc::kDevInit, rwmos::tc::kIdxAxisNr,
                              rwmos::tc::kSubZ, 3),
              Status::kOk);
    step_both(10);
    EXPECT_NEAR(displacement()[2], 0.02, 1e-12);
    ASSERT_EQ(board.write_int(rwmos::tc::kBus, rwmos::tc::kDevInit, rwmos::tc::kIdxAxisNr,
                              rwmos::tc::kSubZ, 2),
              Status::kOk);
    step_both(1);
    EXPECT_EQ(displacement()[2], 0.03);
    EXPECT_NEAR(displacement()[3], 0.029, 1e-12);  // axis 3 left in turn: its ramp starts
}

// The analytic path (no trace) and the stepped one (trace on) give the same bits.
TEST_F(TempCompBoard, UntracedRunGivesTheSameBitsAsATracedOne) {
    for (Rig* r : {&board, &twin}) {
        ASSERT_EQ(r->write_int(tcomp::kBus, tcomp::kDevice, tcomp::kIdxToolTempCompOn, 0, 1),
                  Status::kOk);
        for (int a = 0; a < 3; ++a)
            ASSERT_EQ(r->write_int(tcomp::kBus, tcomp::kDevice, tcomp::kIdxTempCompType, a, 4),
                      Status::kOk);
        ASSERT_EQ(r->write_int(tcomp::kBus, tcomp::kDevice, tcomp::kIdxToolHolder, 0, 1),
                  Status::kOk);
        ASSERT_EQ(r->write_double(tcomp::kBus, tcomp::kDevice, tcomp::kIdxToolTempComp, 2, 0.05),
                  Status::kOk);
    }
    ASSERT_EQ(twin.board.set_trace(true, 100000), Status::kOk);
    Profile p = line3(1, 30, 20, 10, 600);
    p.axes |= 0x10;
    p.target[4] = 45.0;
    spool_both(p);
    step_both(1234);
    EXPECT_EQ(board.position(), twin.position());
    board.run();
    twin.run();
    EXPECT_EQ(board.position(), twin.position());
}

TEST(TempCompOption, WithoutTheOptionTheModuleIsAbsent) {
    rwmos::BoardConfig cfg;
    cfg.option_temp_comp = false;
    Rig r(cfg);
    EXPECT_EQ(r.write_int(tcomp::kBus, tcomp::kDevice, tcomp::kIdxToolTempCompOn, 0, 1),
              Status::kNoSuchDevice);
    objif::Descriptor d{{rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxOptions, 0},
                        0};
    Value v;
    ASSERT_EQ(r.board.read(d, objif::ValueType::kInt32, v), Status::kOk);
    EXPECT_EQ(v.as_int() & rwmos::board::kOptionTempComp, 0);
}

}  // namespace
