// SPDX-License-Identifier: MIT
// The TC module's state rules ([APCI-TC]; docs/design.md section 3; the design
// decisions in docs/object-map.md), one test per rule, named after it.
#include <vector>

#include "emu_test_util.h"
#include "objif/map/tc_bits.h"

using namespace emu_test;
namespace tc = rwmos::tc;

namespace {

// A stand-in for the motion layer that records what the TC hooks ask of it.
class RecordingMotion : public rwmos::TcMotion {
public:
    Status release_held_profile(std::int32_t group) override {
        released.push_back(group);
        return release_answer;
    }
    void discard_held_profile(std::int32_t group) override { discarded.push_back(group); }
    void compensation_started(std::int32_t group) override { started.push_back(group); }
    void clear_shift() override { ++shifts_cleared; }

    Status release_answer = Status::kOk;
    std::vector<std::int32_t> released, discarded, started;
    int shifts_cleared = 0;
};

class TcRules : public BoardFixture {
protected:
    rwmos::TcState& tc_state() { return board.state().tc; }
    rwmos::TcGroup& group(std::int32_t n) { return board.state().tc.group(n); }
    std::int32_t error_of(std::int32_t g) { return read_int(tc_group(g, tc::kSubError)); }
    std::int32_t status_of(std::int32_t g) { return read_int(tc_group(g, tc::kSubStatus)); }
    // Motion layer behaviour: a profile held back in group g.
    void hold_profile(std::int32_t g) { group(g).status |= tc::kProfMarked; }
};

// ---- Groups and Index 0.

TEST_F(TcRules, GroupsAreOneToThree) {
    for (std::int32_t g = 1; g <= 3; ++g) EXPECT_EQ(read_status_of(tc_group(g, tc::kSubError), ValueType::kInt32), Status::kOk);
    EXPECT_EQ(read_status_of(tc_group(4, tc::kSubError), ValueType::kInt32), Status::kObjectMissing);
    EXPECT_EQ(read_status_of(tc_group(-1, tc::kSubError), ValueType::kInt32), Status::kObjectMissing);
}

TEST_F(TcRules, GroupsAreIndependent) {
    ASSERT_EQ(write_int(tc_group(2, tc::kSubWkzIndex), 7), Status::kOk);
    ASSERT_EQ(write_double(tc_group(2, tc::kSubRadius), 4.0), Status::kOk);
    EXPECT_EQ(read_int(tc_group(1, tc::kSubWkzIndex)), 0);
    EXPECT_EQ(read_int(tc_group(3, tc::kSubWkzIndex)), 0);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubWkzIndex), 7), Status::kOk);
    EXPECT_EQ(read_double(tc_group(1, tc::kSubRadius)), 0.0) << "group 1 has its own tool table";
}

TEST_F(TcRules, IndexZeroIsTheGroupWhosePlaneTcPlaneSelects) {
    // Group 1 moves off the X-Y plane; group 2 keeps axes 0/1 and becomes the active group.
    ASSERT_EQ(write_int(tc_group(1, tc::kSubXAxis), 5), Status::kOk);
    ASSERT_EQ(write_int(tc_group(2, tc::kSubWkzIndex), 9), Status::kOk);
    EXPECT_EQ(rwmos::active_group(tc_state()), 2);
    EXPECT_EQ(read_int(tc_group(0, tc::kSubWkzIndex)), 9);
    ASSERT_EQ(write_int(tc_group(0, tc::kSubWkzIndex), 11), Status::kOk);
    EXPECT_EQ(group(2).tool_index, 11);
    EXPECT_EQ(group(1).tool_index, 0);
}

TEST_F(TcRules, IndexZeroFollowsTcPlane) {
    // Group 3 compensates in the Z-X plane (board axes 2 and 0).
    ASSERT_EQ(write_int(tc_group(3, tc::kSubXAxis), 2), Status::kOk);
    ASSERT_EQ(write_int(tc_group(3, tc::kSubYAxis), 0), Status::kOk);
    ASSERT_EQ(write_int(tc_group(3, tc::kSubZAxis), 1), Status::kOk);
    ASSERT_EQ(write_int(tc_group(3, tc::kSubWkzIndex), 33), Status::kOk);
    EXPECT_EQ(read_int(tc_group(0, tc::kSubWkzIndex)), 0) << "X-Y plane: group 1";
    ASSERT_EQ(write_int(tc_init(tc::kIdxTcPlane), tc::kPlaneZX), Status::kOk);
    EXPECT_EQ(read_int(tc_group(0, tc::kSubWkzIndex)), 33) << "Z-X plane: group 3";
}

TEST_F(TcRules, IndexZeroFollowsTheAxisAssignment) {
    // X-Axis-Nr/Y-Axis-Nr of DeviceNumber 0 name the plane's board axes.
    ASSERT_EQ(write_int(tc_group(2, tc::kSubXAxis), 4), Status::kOk);
    ASSERT_EQ(write_int(tc_group(2, tc::kSubYAxis), 5), Status::kOk);
    ASSERT_EQ(write_int(tc_group(2, tc::kSubZAxis), 6), Status::kOk);
    ASSERT_EQ(write_int(tc_init(tc::kIdxAxisNr, tc::kSubX), 4), Status::kOk);
    ASSERT_EQ(write_int(tc_init(tc::kIdxAxisNr, tc::kSubY), 5), Status::kOk);
    EXPECT_EQ(rwmos::active_group(tc_state()), 2);
}

TEST_F(TcRules, IndexZeroWithoutMatchingGroupIsWrongDeviceStateAndChangesNothing) {
    ASSERT_EQ(write_int(tc_init(tc::kIdxTcPlane), tc::kPlaneYZ), Status::kOk);  // axes 1, 2: no group
    const auto before = snapshot(board);
    for (std::int32_t sub : {tc::kSubError, tc::kSubStatus, tc::kSubXAxis, tc::kSubYAxis, tc::kSubWkzIndex,
                             tc::kSubZAxis, tc::kSubCornerMode, tc::kSubSide})
        EXPECT_EQ(read_status_of(tc_group(0, sub), ValueType::kInt32), Status::kWrongDeviceState) << sub;
    for (std::int32_t sub : {tc::kSubRadius, tc::kSubWkzLen})
        EXPECT_EQ(read_status_of(tc_group(0, sub), ValueType::kDouble), Status::kWrongDeviceState) << sub;
    for (std::int32_t sub : {tc::kSubError, tc::kSubStatus, tc::kSubXAxis, tc::kSubLeft, tc::kSubRight,
                             tc::kSubWkzIndex})
        EXPECT_EQ(write_int(tc_group(0, sub), 1), Status::kWrongDeviceState) << sub;
    EXPECT_EQ(write_int(tc_group(0, tc::kSubCornerMode), tc::kCornerLinear), Status::kWrongDeviceState);
    EXPECT_EQ(write_double(tc_group(0, tc::kSubRadius), 1.0), Status::kWrongDeviceState);
    EXPECT_TRUE(unchanged(before, board));
}

TEST_F(TcRules, IndexZeroPicksTheLowestMatchingGroup) {
    // All groups default to axes 0/1/2, so all lie in the X-Y plane.
    EXPECT_EQ(rwmos::active_group(tc_state()), 1);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubYAxis), 6), Status::kOk);
    EXPECT_EQ(rwmos::active_group(tc_state()), 2);
}

TEST_F(TcRules, IndexZeroMatchesThePlaneAxesInEitherOrder) {
    ASSERT_EQ(write_int(tc_group(1, tc::kSubXAxis), 1), Status::kOk);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubYAxis), 0), Status::kOk);
    EXPECT_EQ(rwmos::active_group(tc_state()), 1);
}

// ---- Tool table.

TEST_F(TcRules, RadiusAndWkzLenBelongToTheCurrentWkzIndex) {
    ASSERT_EQ(write_int(tc_group(1, tc::kSubWkzIndex), 5), Status::kOk);
    ASSERT_EQ(write_double(tc_group(1, tc::kSubRadius), 3.0), Status::kOk);
    ASSERT_EQ(write_double(tc_group(1, tc::kSubWkzLen), 40.0), Status::kOk);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubWkzIndex), 1023), Status::kOk);
    ASSERT_EQ(write_double(tc_group(1, tc::kSubRadius), 0.5), Status::kOk);
    ASSERT_EQ(write_double(tc_group(1, tc::kSubWkzLen), -2.0), Status::kOk);
    EXPECT_EQ(read_double(tc_group(1, tc::kSubRadius)), 0.5);
    EXPECT_EQ(read_double(tc_group(1, tc::kSubWkzLen)), -2.0);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubWkzIndex), 5), Status::kOk);
    EXPECT_EQ(read_double(tc_group(1, tc::kSubRadius)), 3.0);
    EXPECT_EQ(read_double(tc_group(1, tc::kSubWkzLen)), 40.0);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubWkzIndex), 0), Status::kOk);
    EXPECT_EQ(read_double(tc_group(1, tc::kSubRadius)), 0.0) << "tool 0 untouched";
}

TEST_F(TcRules, RadiusAndWkzLenMayChangeWhileActive) {
    initialise_group(1, 4, 2.0);
    activate(1);
    EXPECT_EQ(write_double(tc_group(1, tc::kSubRadius), 2.5), Status::kOk);
    EXPECT_EQ(write_double(tc_group(1, tc::kSubWkzLen), 10.0), Status::kOk);
    EXPECT_EQ(group(1).tools[4].radius, 2.5);
    EXPECT_EQ(group(1).tools[4].length, 10.0);
    EXPECT_EQ(error_of(1), 0);
}

// ---- Only while inactive: XAxis, YAxis, ZAxis, WKZINDEX, Left, Right.

class TcWhileActive : public TcRules, public ::testing::WithParamInterface<std::int32_t> {};

TEST_P(TcWhileActive, WriteWhileActiveIsRefusedWithInitError) {
    const std::int32_t sub = GetParam();
    initialise_group(1);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubLeft), 0), Status::kOk);  // side differs from Right
    activate(1);
    ASSERT_EQ(error_of(1), 0);
    auto before = snapshot(board);
    before.tc->group(1).error |= tc::kInitError;  // the only change [APCI-TC] asks for
    EXPECT_EQ(write_int(tc_group(1, sub), 3), Status::kWrongDeviceState);
    EXPECT_TRUE(unchanged(before, board));
    EXPECT_EQ(error_of(1), tc::kInitError);
    EXPECT_EQ(status_of(1), tc::kRun) << "compensation keeps running";
}

TEST_P(TcWhileActive, WriteWhileActiveThroughIndexZeroIsRefusedWithInitError) {
    const std::int32_t sub = GetParam();
    initialise_group(1);
    activate(1);
    EXPECT_EQ(write_int(tc_group(0, sub), 3), Status::kWrongDeviceState);
    EXPECT_EQ(error_of(1), tc::kInitError);
}

TEST_P(TcWhileActive, WriteWhileInactiveIsAccepted) {
    const std::int32_t sub = GetParam();
    initialise_group(1);
    activate(1);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubStatus), 0), Status::kOk);
    EXPECT_EQ(write_int(tc_group(1, sub), 3), Status::kOk);
    EXPECT_EQ(error_of(1), 0);
}

TEST_P(TcWhileActive, OtherGroupsStayWritableWhileOneIsActive) {
    const std::int32_t sub = GetParam();
    initialise_group(1);
    activate(1);
    EXPECT_EQ(write_int(tc_group(2, sub), 3), Status::kOk);
    EXPECT_EQ(error_of(2), 0);
}

std::string sub_name(const ::testing::TestParamInfo<std::int32_t>& info) {
    switch (info.param) {
        case tc::kSubXAxis: return "XAxis";
        case tc::kSubYAxis: return "YAxis";
        case tc::kSubZAxis: return "ZAxis";
        case tc::kSubWkzIndex: return "WKZINDEX";
        case tc::kSubLeft: return "Left";
        case tc::kSubRight: return "Right";
    }
    return "sub" + std::to_string(info.param);
}

INSTANTIATE_TEST_SUITE_P(OnlyWhileInactive, TcWhileActive,
                         ::testing::Values(tc::kSubXAxis, tc::kSubYAxis, tc::kSubZAxis, tc::kSubWkzIndex,
                                           tc::kSubLeft, tc::kSubRight),
                         sub_name);

TEST_F(TcRules, CheckOrderTypeAndRangeBeforeTheActiveRule) {
    initialise_group(1);
    activate(1);
    const auto before = snapshot(board);
    EXPECT_EQ(write_double(tc_group(1, tc::kSubXAxis), 3.0), Status::kTypeMismatch);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubXAxis), 8), Status::kValueTooHigh);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubWkzIndex), 1024), Status::kValueTooHigh);
    EXPECT_EQ(write_double(tc_group(1, tc::kSubLeft), 1.0), Status::kTypeMismatch);
    EXPECT_TRUE(unchanged(before, board)) << "no InitError for a request refused before the state check";
}

// ---- STATUS: activation needs a complete initialisation.

TEST_F(TcRules, StatusOneWithoutSideSetsInitErrorAndDoesNotActivate) {
    auto before = snapshot(board);
    before.tc->group(1).error |= tc::kInitError;
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 1), Status::kWrongDeviceState);
    EXPECT_TRUE(unchanged(before, board));
    EXPECT_EQ(status_of(1), 0);
    EXPECT_EQ(error_of(1), tc::kInitError);
    EXPECT_EQ(rwmos::initialisation_fault(tc_state(), 1), rwmos::InitFault::kNoSide);
}

TEST_F(TcRules, StatusOneWithAxesNotDistinctSetsInitError) {
    initialise_group(1);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubZAxis), 1), Status::kOk);  // Z = Y
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 1), Status::kWrongDeviceState);
    EXPECT_EQ(status_of(1), 0);
    EXPECT_EQ(error_of(1), tc::kInitError);
    EXPECT_EQ(rwmos::initialisation_fault(tc_state(), 1), rwmos::InitFault::kAxesNotDistinct);
}

TEST_F(TcRules, StatusOneWithAnAxisOfARunningGroupSetsInitError) {
    initialise_group(1);
    activate(1);
    initialise_group(2);  // same axes 0/1/2
    EXPECT_EQ(write_int(tc_group(2, tc::kSubStatus), 1), Status::kWrongDeviceState);
    EXPECT_EQ(error_of(2), tc::kInitError);
    EXPECT_EQ(error_of(1), 0);
    EXPECT_EQ(rwmos::initialisation_fault(tc_state(), 2), rwmos::InitFault::kAxisInUse);
    // On three other axes group 2 may run alongside group 1.
    ASSERT_EQ(write_int(tc_group(2, tc::kSubXAxis), 3), Status::kOk);
    ASSERT_EQ(write_int(tc_group(2, tc::kSubYAxis), 4), Status::kOk);
    ASSERT_EQ(write_int(tc_group(2, tc::kSubZAxis), 5), Status::kOk);
    EXPECT_EQ(write_int(tc_group(2, tc::kSubStatus), 1), Status::kOk);
    EXPECT_EQ(status_of(2), tc::kRun);
}

// Initialised, condition 1 (design, docs/object-map.md STATUS): XAxis, YAxis and ZAxis name three
// different board axes; ZAxis counts like the other two (the length correction acts on it).
TEST_F(TcRules, StatusOneWithAnyTwoOfTheThreeAxesEqualSetsInitError) {
    const std::int32_t subs[3] = {tc::kSubXAxis, tc::kSubYAxis, tc::kSubZAxis};
    for (int a = 0; a < 3; ++a) {
        for (int b = a + 1; b < 3; ++b) {
            initialise_group(1);
            ASSERT_EQ(write_int(tc_group(1, tc::kSubError), 0), Status::kOk);
            // Axis b on axis a's board axis.
            ASSERT_EQ(write_int(tc_group(1, subs[b]), a), Status::kOk);
            EXPECT_EQ(rwmos::initialisation_fault(tc_state(), 1),
                      rwmos::InitFault::kAxesNotDistinct)
                << "axis " << b << " = axis " << a;
            EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 1), Status::kWrongDeviceState);
            EXPECT_EQ(status_of(1), 0);
            EXPECT_EQ(error_of(1), tc::kInitError);
        }
    }
}

// Initialised, condition 3 (design, docs/object-map.md STATUS): no other running group uses any
// of its three axes. Each of the three axes of the group to activate, ZAxis included, against
// each of the running group's three, ZAxis included.
TEST_F(TcRules, StatusOneWithAnyAxisOnAnyAxisOfARunningGroupSetsInitError) {
    initialise_group(1);  // X0 Y1 Z2
    activate(1);
    const std::int32_t subs[3] = {tc::kSubXAxis, tc::kSubYAxis, tc::kSubZAxis};
    for (int mine = 0; mine < 3; ++mine) {
        for (std::int32_t theirs = 0; theirs < 3; ++theirs) {
            // Group 2 on axes 3/4/5, save one that lands on group 1's axis `theirs`.
            std::int32_t axes[3] = {3, 4, 5};
            axes[mine] = theirs;
            for (int i = 0; i < 3; ++i)
                ASSERT_EQ(write_int(tc_group(2, subs[i]), axes[i]), Status::kOk);
            ASSERT_EQ(write_int(tc_group(2, tc::kSubLeft), 0), Status::kOk);
            ASSERT_EQ(write_int(tc_group(2, tc::kSubError), 0), Status::kOk);
            EXPECT_EQ(rwmos::initialisation_fault(tc_state(), 2), rwmos::InitFault::kAxisInUse)
                << "group 2 axis " << mine << " on board axis " << theirs;
            EXPECT_EQ(write_int(tc_group(2, tc::kSubStatus), 1), Status::kWrongDeviceState);
            EXPECT_EQ(status_of(2), 0);
            EXPECT_EQ(error_of(2), tc::kInitError);
            EXPECT_EQ(error_of(1), 0);
            EXPECT_EQ(status_of(1), tc::kRun);
        }
    }
}

TEST_F(TcRules, StatusOneWhenInitialisedSetsRun) {
    RecordingMotion motion;
    board.state().tc_motion = &motion;
    initialise_group(1);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 1), Status::kOk);
    EXPECT_EQ(status_of(1), tc::kRun);
    EXPECT_EQ(error_of(1), 0);
    EXPECT_EQ(motion.started, std::vector<std::int32_t>{1});
}

TEST_F(TcRules, StatusOneWhileRunningChangesNothing) {
    RecordingMotion motion;
    board.state().tc_motion = &motion;
    initialise_group(1);
    activate(1);
    const auto before = snapshot(board);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 1), Status::kOk);
    EXPECT_TRUE(unchanged(before, board));
    EXPECT_EQ(motion.started.size(), 1u);
}

TEST_F(TcRules, StatusOneAfterFixingTheInitialisationActivates) {
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 1), Status::kWrongDeviceState);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubLeft), 0), Status::kOk);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 1), Status::kOk);
    EXPECT_EQ(status_of(1), tc::kRun);
    EXPECT_EQ(error_of(1), tc::kInitError) << "the earlier InitError stays until ERROR is written";
}

TEST_F(TcRules, StatusZeroDeactivates) {
    initialise_group(1);
    activate(1);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 0), Status::kOk);
    EXPECT_EQ(status_of(1), 0);
}

TEST_F(TcRules, StatusZeroSpoolsTheHeldProfile) {
    RecordingMotion motion;
    board.state().tc_motion = &motion;
    initialise_group(1);
    activate(1);
    hold_profile(1);
    ASSERT_EQ(status_of(1), tc::kRun | tc::kProfMarked);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 0), Status::kOk);
    EXPECT_EQ(motion.released, std::vector<std::int32_t>{1});
    EXPECT_TRUE(motion.discarded.empty());
    EXPECT_EQ(status_of(1), 0);
}

TEST_F(TcRules, StatusZeroRefusedByTheSpoolerChangesNothing) {
    RecordingMotion motion;
    motion.release_answer = Status::kBusy;
    board.state().tc_motion = &motion;
    initialise_group(1);
    activate(1);
    hold_profile(1);
    const auto before = snapshot(board);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 0), Status::kBusy);
    EXPECT_TRUE(unchanged(before, board));
    EXPECT_EQ(status_of(1), tc::kRun | tc::kProfMarked);
}

TEST_F(TcRules, StatusZeroWithoutHeldProfileAsksNothingOfTheSpooler) {
    RecordingMotion motion;
    board.state().tc_motion = &motion;
    initialise_group(1);
    activate(1);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 0), Status::kOk);
    EXPECT_TRUE(motion.released.empty());
}

// ---- ERROR.

TEST_F(TcRules, WritingErrorClearsIt) {
    group(2).error = tc::kInitError | tc::kCalcError | tc::kCenterError;  // as the motion layer sets them
    EXPECT_EQ(error_of(2), 0x15);
    EXPECT_EQ(write_int(tc_group(2, tc::kSubError), 0x04), Status::kOk);
    EXPECT_EQ(error_of(2), 0) << "any written value clears every bit";
}

TEST_F(TcRules, WritingErrorClearsOnlyThatGroup) {
    group(1).error = tc::kKorrError;
    group(2).error = tc::kPlaneError;
    ASSERT_EQ(write_int(tc_group(2, tc::kSubError), 0), Status::kOk);
    EXPECT_EQ(error_of(1), tc::kKorrError);
    EXPECT_EQ(error_of(2), 0);
}

TEST_F(TcRules, WritingErrorLeavesRunAlone) {
    initialise_group(1);
    activate(1);
    group(1).error = tc::kInitError;
    ASSERT_EQ(write_int(tc_group(1, tc::kSubError), 0), Status::kOk);
    EXPECT_EQ(status_of(1), tc::kRun);
}

// ---- RESET (DeviceNumber 1, SubIndex 2).

TEST_F(TcRules, GroupResetEndsCompensationAndDiscardsProgrammedValuesOfEveryGroup) {
    RecordingMotion motion;
    board.state().tc_motion = &motion;
    initialise_group(1, 7, 3.0);
    ASSERT_EQ(write_double(tc_group(1, tc::kSubWkzLen), 25.0), Status::kOk);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubCornerMode), tc::kCornerLinear), Status::kOk);
    activate(1);
    hold_profile(1);
    group(1).offset = {1.0, 2.0, 3.0};
    group(1).error = tc::kCalcError;
    ASSERT_EQ(write_int(tc_group(3, tc::kSubXAxis), 4), Status::kOk);
    ASSERT_EQ(write_int(tc_init(tc::kIdxTcPlane), tc::kPlaneZX), Status::kOk);
    ASSERT_EQ(write_double(tc_init(tc::kIdxRotAngle), 30.0), Status::kOk);

    EXPECT_EQ(write_int(tc_group(2, tc::kSubReset), 0), Status::kOk) << "the Index is meaningless";

    EXPECT_EQ(motion.discarded, std::vector<std::int32_t>{1});
    EXPECT_TRUE(motion.released.empty()) << "RESET drops the held profile, it does not spool it";
    const rwmos::TcGroup fresh;
    for (std::int32_t n = 1; n <= 3; ++n) EXPECT_TRUE(same_group(group(n), fresh)) << "group " << n;
    // DeviceNumber 0 settings are machine setup, not programmed values: they stay.
    EXPECT_EQ(tc_state().plane, tc::kPlaneZX);
    EXPECT_EQ(tc_state().rot_angle, 30.0);
}

TEST_F(TcRules, GroupResetWorksThroughIndexZeroWithoutAnActiveGroup) {
    ASSERT_EQ(write_int(tc_group(1, tc::kSubWkzIndex), 12), Status::kOk);
    ASSERT_EQ(write_int(tc_init(tc::kIdxTcPlane), tc::kPlaneYZ), Status::kOk);
    ASSERT_EQ(rwmos::active_group(tc_state()), 0);
    EXPECT_EQ(write_int(tc_group(0, tc::kSubReset), 1), Status::kOk);
    EXPECT_EQ(group(1).tool_index, 0);
}

TEST_F(TcRules, GroupResetAllowsReprogramming) {
    initialise_group(1);
    activate(1);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubReset), 0), Status::kOk);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubXAxis), 3), Status::kOk);
    EXPECT_EQ(error_of(1), 0);
}

// ---- Reset (DeviceNumber 0, Index 14) and ReInit (Index 13).

TEST_F(TcRules, ResetStopsAllCorrectionsAndClearsOffsetsAndHeldProfilesToolsStay) {
    RecordingMotion motion;
    board.state().tc_motion = &motion;
    initialise_group(1, 7, 3.0);
    activate(1);
    hold_profile(1);
    group(1).offset = {0.5, -0.5, 1.0};
    group(1).error = tc::kKorrError;
    ASSERT_EQ(write_int(tc_group(2, tc::kSubXAxis), 3), Status::kOk);
    ASSERT_EQ(write_int(tc_group(2, tc::kSubYAxis), 4), Status::kOk);
    ASSERT_EQ(write_int(tc_group(2, tc::kSubZAxis), 5), Status::kOk);
    ASSERT_EQ(write_int(tc_group(2, tc::kSubLeft), 0), Status::kOk);
    activate(2);
    group(2).offset = {1.0, 1.0, 0.0};

    EXPECT_EQ(write_int(tc_init(tc::kIdxReset), 0), Status::kOk);

    EXPECT_EQ(motion.discarded, std::vector<std::int32_t>{1});
    EXPECT_EQ(motion.shifts_cleared, 1);
    for (std::int32_t n : {1, 2}) {
        EXPECT_EQ(status_of(n), 0) << "group " << n;
        EXPECT_EQ(group(n).offset, (std::array<double, 3>{})) << "group " << n;
    }
    // Tools and the rest of the programming stay.
    EXPECT_EQ(group(1).tools[7].radius, 3.0);
    EXPECT_EQ(group(1).tool_index, 7);
    EXPECT_EQ(group(1).side, tc::kSideRight);
    EXPECT_EQ(group(2).x_axis, 3);
    EXPECT_EQ(error_of(1), tc::kKorrError) << "ERROR is cleared only by writing it";
    // Ready to run again without reprogramming.
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 1), Status::kOk);
}

TEST_F(TcRules, ReInitClearsStoredOffsetsOnlyToolsStayActive) {
    RecordingMotion motion;
    board.state().tc_motion = &motion;
    initialise_group(1, 7, 3.0);
    activate(1);
    group(1).offset = {0.5, -0.5, 1.0};
    group(3).offset = {2.0, 0.0, 0.0};
    EXPECT_EQ(write_int(tc_init(tc::kIdxReInit), 0), Status::kOk);
    EXPECT_EQ(motion.shifts_cleared, 1) << "the motion layer forgets the shift";
    EXPECT_EQ(group(1).offset, (std::array<double, 3>{}));
    EXPECT_EQ(group(3).offset, (std::array<double, 3>{}));
    EXPECT_EQ(status_of(1), tc::kRun) << "compensation stays";
    EXPECT_EQ(group(1).tools[7].radius, 3.0);
    EXPECT_TRUE(motion.discarded.empty());
}

// While a profile is held (a contour under way) ReInit is not emulated: [APCI-TC] names it for
// before a re-reference and does not say what it does to a contour. Refused, nothing changes,
// no InitError.
TEST_F(TcRules, ReInitIsRefusedWhileAProfileIsHeld) {
    RecordingMotion motion;
    board.state().tc_motion = &motion;
    initialise_group(1, 7, 3.0);
    activate(1);
    hold_profile(1);
    group(1).offset = {0.5, -0.5, 1.0};
    const auto before = snapshot(board);
    EXPECT_EQ(write_int(tc_init(tc::kIdxReInit), 0), Status::kWrongDeviceState);
    EXPECT_TRUE(unchanged(before, board));
    EXPECT_EQ(motion.shifts_cleared, 0);
    EXPECT_EQ(status_of(1), tc::kRun | tc::kProfMarked);
    EXPECT_EQ(error_of(1), 0);
}

TEST_F(TcRules, ReInitAndResetIgnoreSubIndexAndParameter) {
    group(1).offset = {1.0, 1.0, 1.0};
    EXPECT_EQ(write_int(tc_init(tc::kIdxReInit, 7), -3), Status::kOk);
    EXPECT_EQ(group(1).offset, (std::array<double, 3>{}));
    initialise_group(1);
    activate(1);
    EXPECT_EQ(write_int(tc_init(tc::kIdxReset, 99), 12345), Status::kOk);
    EXPECT_EQ(status_of(1), 0);
    // Other DeviceNumber 0 objects keep their exact SubIndex.
    EXPECT_EQ(write_int(tc_init(tc::kIdxTcPlane, 1), 17), Status::kSubMissing);
}

// ---- Clean (DeviceNumber 0, Index 1).

TEST_F(TcRules, CleanRequiresParameterOne) {
    ASSERT_EQ(write_int(tc_group(1, tc::kSubWkzIndex), 12), Status::kOk);
    const auto before = snapshot(board);
    EXPECT_EQ(write_int(tc_init(tc::kIdxClean), 0), Status::kValueTooLow);
    EXPECT_EQ(write_int(tc_init(tc::kIdxClean), 2), Status::kValueTooHigh);
    EXPECT_TRUE(unchanged(before, board));
}

TEST_F(TcRules, CleanMakesEveryTcHandleStale) {
    auto plane = tc_init(tc::kIdxTcPlane);
    auto radius = tc_group(1, tc::kSubRadius);
    auto active_error = tc_group(0, tc::kSubError);
    auto clean = tc_init(tc::kIdxClean);
    auto axis_count = board_obj(rwmos::board::kIdxAxisCount);
    Value v;
    ASSERT_EQ(board.read(plane, ValueType::kInt32, v), Status::kOk);
    ASSERT_EQ(board.read(radius, ValueType::kDouble, v), Status::kOk);
    ASSERT_EQ(board.read(active_error, ValueType::kInt32, v), Status::kOk);
    ASSERT_EQ(board.read(axis_count, ValueType::kInt32, v), Status::kOk);

    ASSERT_EQ(board.write(clean, Value::of_int(1)), Status::kOk);

    const auto before = snapshot(board);
    EXPECT_EQ(board.read(plane, ValueType::kInt32, v), Status::kStaleHandle);
    EXPECT_EQ(board.write(radius, Value::of_double(1.0)), Status::kStaleHandle);
    EXPECT_EQ(board.read(active_error, ValueType::kInt32, v), Status::kStaleHandle);
    EXPECT_EQ(board.write(clean, Value::of_int(1)), Status::kStaleHandle);
    EXPECT_TRUE(unchanged(before, board)) << "a stale handle changes nothing";
    EXPECT_EQ(board.read(axis_count, ValueType::kInt32, v), Status::kOk) << "bus 1000 handles stay";
}

TEST_F(TcRules, CleanedDescriptorWorksAgainOnceItsHandleIsZeroed) {
    auto radius = tc_group(1, tc::kSubRadius);
    ASSERT_EQ(board.write(radius, Value::of_double(1.0)), Status::kOk);
    ASSERT_EQ(write_int(tc_init(tc::kIdxClean), 1), Status::kOk);
    radius.handle = objif::kNoHandle;
    Value v;
    ASSERT_EQ(board.read(radius, ValueType::kDouble, v), Status::kOk);
    EXPECT_EQ(v, Value::of_double(0.0));
    EXPECT_NE(radius.handle, objif::kNoHandle);
}

TEST_F(TcRules, CleanDiscardsAllTcDataBackToDefaults) {
    RecordingMotion motion;
    board.state().tc_motion = &motion;
    initialise_group(2, 100, 6.0);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubXAxis), 5), Status::kOk);
    activate(2);
    hold_profile(2);
    group(2).offset = {1.0, 2.0, 3.0};
    group(3).error = tc::kPlaneError;
    ASSERT_EQ(write_int(tc_init(tc::kIdxAxisNr, tc::kSubZ), 6), Status::kOk);
    ASSERT_EQ(write_int(tc_init(tc::kIdxTcPlane), tc::kPlaneYZ), Status::kOk);
    ASSERT_EQ(write_double(tc_init(tc::kIdxRotAngle), 90.0), Status::kOk);
    ASSERT_EQ(write_double(tc_init(tc::kIdxRotCenterX), 1.0), Status::kOk);
    ASSERT_EQ(write_double(tc_init(tc::kIdxRotCenterY), 2.0), Status::kOk);

    ASSERT_EQ(write_int(tc_init(tc::kIdxClean), 1), Status::kOk);

    EXPECT_EQ(motion.discarded, std::vector<std::int32_t>{2});
    const rwmos::TcGroup fresh;
    for (std::int32_t n = 1; n <= 3; ++n) EXPECT_TRUE(same_group(group(n), fresh)) << "group " << n;
    EXPECT_EQ(tc_state().axis_nr, (std::array<std::int32_t, 3>{0, 1, 2}));
    EXPECT_EQ(tc_state().plane, tc::kPlaneXY);
    EXPECT_EQ(tc_state().rot_angle, 0.0);
    EXPECT_EQ(tc_state().rot_center_x, 0.0);
    EXPECT_EQ(tc_state().rot_center_y, 0.0);
}

// ---- Accessed flag ([APCI-TC] section 2.2 "Wichtiger Hinweis").

TEST_F(TcRules, AnyTcAccessMarksTheObjectsAccessed) {
    EXPECT_FALSE(tc_state().objects_accessed);
    (void)read_int(tc_init(tc::kIdxTcPlane));
    EXPECT_TRUE(tc_state().objects_accessed);
}

TEST_F(TcRules, RefusedTcAccessDoesNotMarkTheObjectsAccessed) {
    EXPECT_EQ(read_status_of(tc_init(tc::kIdxTcPlane), ValueType::kDouble), Status::kTypeMismatch);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubStatus), 1), Status::kWrongDeviceState);
    EXPECT_FALSE(tc_state().objects_accessed);
}

TEST_F(TcRules, CleanLeavesTheObjectsUnaccessed) {
    (void)read_int(tc_init(tc::kIdxTcPlane));
    ASSERT_EQ(write_int(tc_init(tc::kIdxClean), 1), Status::kOk);
    EXPECT_FALSE(tc_state().objects_accessed);
}

// ---- Extension objects.

TEST_F(TcRules, SideReadsBackTheLeftOrRightSelection) {
    EXPECT_EQ(read_int(tc_group(1, tc::kSubSide)), tc::kSideNone);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubLeft), 0), Status::kOk);
    EXPECT_EQ(read_int(tc_group(1, tc::kSubSide)), tc::kSideLeft);
    ASSERT_EQ(write_int(tc_group(1, tc::kSubRight), 0), Status::kOk);
    EXPECT_EQ(read_int(tc_group(1, tc::kSubSide)), tc::kSideRight);
}

TEST_F(TcRules, CornerModeDefaultsToCircularAndMayChangeWhileActive) {
    EXPECT_EQ(read_int(tc_group(1, tc::kSubCornerMode)), tc::kCornerCircular);
    initialise_group(1);
    activate(1);
    EXPECT_EQ(write_int(tc_group(1, tc::kSubCornerMode), tc::kCornerLinear), Status::kOk);
    EXPECT_EQ(read_int(tc_group(1, tc::kSubCornerMode)), tc::kCornerLinear);
    EXPECT_EQ(error_of(1), 0);
}

// ---- Option gating.

class TcAbsent : public BoardFixture {
protected:
    TcAbsent() : BoardFixture(rwmos::BoardConfig{.option_tc = false}) {}
};

TEST_F(TcAbsent, WithoutOptionTcEveryTcAccessIsNoSuchDevice) {
    const auto before = snapshot(board);
    auto* module = board.dictionary().module(tc::kBus);
    ASSERT_NE(module, nullptr);
    for (std::size_t i = 0; i < module->object_count(); ++i) {
        const auto& info = module->object_at(i);
        for (std::int32_t idx = info.index_first; idx <= info.index_last; ++idx) {
            auto d = at(tc::kBus, info.device, idx, info.subindex);
            Value v;
            EXPECT_EQ(board.read(d, info.type, v), Status::kNoSuchDevice) << info.name;
            EXPECT_EQ(board.write(d, info.default_value), Status::kNoSuchDevice) << info.name;
            EXPECT_EQ(d.handle, objif::kNoHandle) << info.name;
        }
    }
    EXPECT_EQ(write_int(tc_init(tc::kIdxClean), 1), Status::kNoSuchDevice);
    EXPECT_TRUE(unchanged(before, board));
}

TEST_F(TcAbsent, WithoutOptionTcTheBoardModuleStillAnswers) {
    EXPECT_EQ(read_int(board_obj(rwmos::board::kIdxAxisCount)), 8);
    EXPECT_EQ(read_int(board_obj(rwmos::board::kIdxOptions)) & rwmos::board::kOptionTc, 0);
    EXPECT_EQ(write_int(board_obj(rwmos::board::kIdxRs), 0), Status::kOk);
}

}  // namespace

namespace {

// ---- Pure queries over TcState.

TEST(TcState, PlaneAxesFollowTcPlaneAndTheAxisAssignment) {
    rwmos::TcState s;
    s.axis_nr = {4, 5, 6};
    s.plane = tc::kPlaneXY;
    EXPECT_EQ(rwmos::plane_axes(s).first, 4);
    EXPECT_EQ(rwmos::plane_axes(s).second, 5);
    s.plane = tc::kPlaneZX;
    EXPECT_EQ(rwmos::plane_axes(s).first, 6);
    EXPECT_EQ(rwmos::plane_axes(s).second, 4);
    s.plane = tc::kPlaneYZ;
    EXPECT_EQ(rwmos::plane_axes(s).first, 5);
    EXPECT_EQ(rwmos::plane_axes(s).second, 6);
}

TEST(TcState, NoActiveGroupWhenThePlaneAxesCoincide) {
    rwmos::TcState s;
    s.axis_nr = {1, 1, 2};
    s.group(2).x_axis = 1;
    s.group(2).y_axis = 1;
    EXPECT_EQ(rwmos::active_group(s), 0);
}

TEST(TcState, EveryInitFaultHasItsOwnMessage) {
    using rwmos::InitFault;
    const std::array faults{InitFault::kNone, InitFault::kAxesNotDistinct, InitFault::kNoSide,
                            InitFault::kAxisInUse};
    for (std::size_t i = 0; i < faults.size(); ++i) {
        EXPECT_FALSE(rwmos::init_fault_message(faults[i]).empty());
        for (std::size_t j = i + 1; j < faults.size(); ++j)
            EXPECT_NE(rwmos::init_fault_message(faults[i]), rwmos::init_fault_message(faults[j]));
    }
    EXPECT_NE(rwmos::init_fault_message(InitFault::kNoSide).find("Left or Right"), std::string_view::npos);
}

}  // namespace
