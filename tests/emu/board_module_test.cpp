// SPDX-License-Identifier: MIT
// Board module (bus 1000) rules: live values come from the device state,
// rs() zeroes the TC rotation, addressing errors are named.
#include "emu_test_util.h"

using namespace emu_test;
namespace board = rwmos::board;
namespace tc = rwmos::tc;

namespace {

class BoardModule : public BoardFixture {};

TEST_F(BoardModule, FirmwareVersionIsTheEmulatorsVersion) {
    EXPECT_EQ(read_int(board_obj(board::kIdxFirmwareVersion)), rwmos::kFirmwareVersion);
    EXPECT_EQ(rwmos::kFirmwareVersion >> 16, 1) << "major version in bits 23..16";
}

TEST_F(BoardModule, AxisCountIsEight) { EXPECT_EQ(read_int(board_obj(board::kIdxAxisCount)), 8); }

TEST_F(BoardModule, OptionsReportOptionTcAndOtc) {
    EXPECT_EQ(read_int(board_obj(board::kIdxOptions)),
              board::kOptionTc | board::kOptionOtc | board::kOptionTempComp);
}

TEST_F(BoardModule, InterpolationCycleDefaultsToOneMillisecondAndIsStored) {
    EXPECT_EQ(read_int(board_obj(board::kIdxInterpolationCycle)), 1000);
    ASSERT_EQ(write_int(board_obj(board::kIdxInterpolationCycle), 500), Status::kOk);
    EXPECT_EQ(board.state().interpolation_cycle_us, 500);
    EXPECT_EQ(read_int(board_obj(board::kIdxInterpolationCycle)), 500);
}

TEST_F(BoardModule, PuSelectsTheLengthUnitAndIsStored) {
    EXPECT_EQ(read_int(board_obj(board::kIdxPu)), board::kPuMillimetre);
    ASSERT_EQ(write_int(board_obj(board::kIdxPu), board::kPuMicrometre), Status::kOk);
    EXPECT_EQ(board.state().pu, board::kPuMicrometre);
    EXPECT_EQ(read_int(board_obj(board::kIdxPu)), board::kPuMicrometre);
}

TEST_F(BoardModule, SpoolerCapacityAndFillReadTheSpoolerState) {
    board.state().spooler.capacity = 64;
    board.state().spooler.fill = 17;
    EXPECT_EQ(read_int(board_obj(board::kIdxSpoolerCapacity)), 64);
    EXPECT_EQ(read_int(board_obj(board::kIdxSpoolerFill)), 17);
}

TEST_F(BoardModule, AxisPositionsReadTheAxisState) {
    for (std::size_t i = 0; i < board.state().axes.size(); ++i)
        board.state().axes[i].position = 1.5 * static_cast<double>(i) - 3.0;
    for (std::int32_t axis = 0; axis < 8; ++axis)
        EXPECT_EQ(read_double(board_obj(board::kIdxAxisPosition, axis)), 1.5 * axis - 3.0) << axis;
}

TEST_F(BoardModule, AxisPositionBeyondTheAxisCountIsSubMissing) {
    EXPECT_EQ(read_status_of(board_obj(board::kIdxAxisPosition, 8), ValueType::kDouble), Status::kSubMissing);
    EXPECT_EQ(read_status_of(board_obj(board::kIdxAxisPosition, -1), ValueType::kDouble), Status::kSubMissing);
}

TEST_F(BoardModule, RsZeroesTheTcRotationOnly) {
    ASSERT_EQ(write_double(tc_init(tc::kIdxRotAngle), 30.0), Status::kOk);
    ASSERT_EQ(write_double(tc_init(tc::kIdxRotCenterX), 10.0), Status::kOk);
    ASSERT_EQ(write_double(tc_init(tc::kIdxRotCenterY), -5.0), Status::kOk);
    ASSERT_EQ(write_int(tc_init(tc::kIdxTcPlane), tc::kPlaneZX), Status::kOk);
    ASSERT_EQ(write_double(tc_group(1, tc::kSubRadius), 2.0), Status::kOk);
    auto expected = snapshot(board);
    expected.tc->rot_angle = expected.tc->rot_center_x = expected.tc->rot_center_y = 0.0;

    ASSERT_EQ(write_int(board_obj(board::kIdxRs), 0), Status::kOk);

    EXPECT_EQ(read_double(tc_init(tc::kIdxRotAngle)), 0.0);
    EXPECT_EQ(read_double(tc_init(tc::kIdxRotCenterX)), 0.0);
    EXPECT_EQ(read_double(tc_init(tc::kIdxRotCenterY)), 0.0);
    EXPECT_TRUE(unchanged(expected, board));
}

TEST_F(BoardModule, RsDoesNotMakeTcHandlesStale) {
    auto angle = tc_init(tc::kIdxRotAngle);
    ASSERT_EQ(board.write(angle, Value::of_double(5.0)), Status::kOk);
    ASSERT_EQ(write_int(board_obj(board::kIdxRs), 1), Status::kOk);
    Value v;
    EXPECT_EQ(board.read(angle, ValueType::kDouble, v), Status::kOk);
}

TEST_F(BoardModule, AddressingErrorsAreNamedInCheckOrder) {
    EXPECT_EQ(read_status_of(at(1234, 0, 1, 0), ValueType::kInt32), Status::kNoSuchDevice);
    EXPECT_EQ(read_status_of(at(board::kBus, 1, 1, 0), ValueType::kInt32), Status::kNoSuchDevice);
    EXPECT_EQ(read_status_of(board_obj(99), ValueType::kInt32), Status::kObjectMissing);
    EXPECT_EQ(read_status_of(board_obj(board::kIdxAxisCount, 1), ValueType::kInt32), Status::kSubMissing);
}

TEST_F(BoardModule, OptionsWithoutOptionTcClearTheBit) {
    rwmos::EmulatedBoard bare(rwmos::BoardConfig{.option_tc = false});
    auto d = board_obj(board::kIdxOptions);
    Value v;
    ASSERT_EQ(bare.read(d, ValueType::kInt32, v), Status::kOk);
    EXPECT_EQ(v.as_int() & board::kOptionTc, 0);
    EXPECT_FALSE(bare.config().option_tc);
}

}  // namespace
