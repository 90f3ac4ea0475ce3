// SPDX-License-Identifier: MIT
// The motion layer keeps the TC settings it reads from the objects between spool calls
// (docs/motion.md section 1, "TC settings kept between calls"): every object access that can
// change them must make the next call read them again. Each test spools once (the settings are
// read), changes an object, and sees the new value act on the next profile; the writes that
// bypass Board::write (straight to a module, as the fuzz harness and the tests do) count too.
#include <cmath>
#include <numbers>

#include "motion_fixture.h"

using namespace motion_test;
namespace tc = rwmos::tc;

namespace {

constexpr double kEps = 1e-9;

void expect_at(const AxisVector& p, double x, double y, double z = 0.0) {
    EXPECT_NEAR(p[0], x, kEps);
    EXPECT_NEAR(p[1], y, kEps);
    EXPECT_NEAR(p[2], z, kEps);
}

// A write straight to the module on `bus`, past Board::write and the dictionary.
Status module_write(rwmos::EmulatedBoard& board, const objif::Address& a, const Value& v) {
    objif::Module* module = board.dictionary().module(a.bus);
    EXPECT_NE(module, nullptr);
    if (module == nullptr) return Status::kNoSuchDevice;
    Status why = Status::kOk;
    const objif::ObjectInfo* info = module->find(a, why);
    EXPECT_NE(info, nullptr) << objif::status_name(why);
    if (info == nullptr) return why;
    return module->write(*info, a, v);
}

class SettingsBetweenSpools : public MotionBoard {};

TEST_F(SettingsBetweenSpools, RotationWrittenBetweenTwoProfilesTurnsTheSecond) {
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(write_double(tc::kBus, tc::kDevInit, tc::kIdxRotAngle, 0, 90.0), Status::kOk);
    spool_ok(line(2, 10, 0));
    run();
    expect_at(position(), 0, 10);
}

TEST_F(SettingsBetweenSpools, PlaneWrittenBetweenTwoProfilesMovesTheRotationToIt) {
    ASSERT_EQ(write_double(tc::kBus, tc::kDevInit, tc::kIdxRotAngle, 0, 90.0), Status::kOk);
    spool_ok(line(1, 10, 0));  // turned in X-Y
    ASSERT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxTcPlane, 0, tc::kPlaneZX), Status::kOk);
    spool_ok(line3(2, 10, 0, 0));  // turned in Z-X
    run();
    // The same profile on a board set up the same way before anything was spooled.
    Rig fresh;
    ASSERT_EQ(fresh.write_double(tc::kBus, tc::kDevInit, tc::kIdxRotAngle, 0, 90.0), Status::kOk);
    ASSERT_EQ(fresh.write_int(tc::kBus, tc::kDevInit, tc::kIdxTcPlane, 0, tc::kPlaneZX),
              Status::kOk);
    fresh.spool_ok(line3(2, 10, 0, 0));
    fresh.run();
    EXPECT_EQ(position(), fresh.position());
    expect_at(position(), 0, 0, -10);  // (Z, X) = (0, 10) turned 90 degrees: Z -10, X 0
}

TEST_F(SettingsBetweenSpools, RsBetweenTwoProfilesLeavesTheSecondUnturned) {
    ASSERT_EQ(write_double(tc::kBus, tc::kDevInit, tc::kIdxRotAngle, 0, 90.0), Status::kOk);
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(write_int(rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxRs, 0, 0),
              Status::kOk);
    spool_ok(line(2, 20, 0));
    run();
    expect_at(position(), 20, 0);
}

// [APCI-TC] section 2.2 "Wichtiger Hinweis": a read is an access too.
TEST_F(SettingsBetweenSpools, ATcReadBetweenTwoProfilesPutsTheNextArcInTheActivePlane) {
    spool_ok(line(1, 10, 0));
    read_int(tc::kBus, tc::kDevInit, tc::kIdxTcPlane, 0);
    Profile p = arc(2, true, 0, 10, 0, 0);  // named Y first, X second: (Y, X) is no TC plane
    p.arc_axes = {1, 0};
    spool_ok(p);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 2u);
    EXPECT_EQ(segs[1].plane, 17);
    EXPECT_EQ(segs[1].end_cycle - segs[1].start_cycle,
              static_cast<std::uint64_t>(std::ceil(5.0 * std::numbers::pi / 0.01)));
}

TEST_F(SettingsBetweenSpools, PuWrittenDuringAContourReinterpretsTheRadiusFromTheNextProfile) {
    setup_group(2.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(write_int(rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxPu, 0,
                        rwmos::board::kPuMicrometre),
              Status::kOk);
    spool_ok(line(2, 20, 0));
    ASSERT_EQ(deactivate(), Status::kOk);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 5u);
    expect_at(segs[1].end, 10, 2);  // profile 1 at 2 mm
    EXPECT_EQ(segs[2].role, SegmentRole::kApproach);
    expect_at(segs[2].end, 10, 0.002);  // profile 2 at 2 um
    expect_at(segs[3].end, 20, 0.002);
}

TEST_F(SettingsBetweenSpools, WkzLenWrittenBetweenTwoProfilesShiftsTheNext) {
    setup_group(0.0);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubLengthMode, tc::kLengthAlways),
              Status::kOk);
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen, 5.0), Status::kOk);
    spool_ok(line(2, 20, 0));
    run();
    expect_at(position(), 20, 0, 5);
}

TEST_F(SettingsBetweenSpools, ATcWriteStraightToTheModuleActsOnTheNextProfile) {
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(
        module_write(board, {tc::kBus, tc::kDevInit, tc::kIdxRotAngle, 0}, Value::of_double(90.0)),
        Status::kOk);
    spool_ok(line(2, 10, 0));
    run();
    expect_at(position(), 0, 10);
}

TEST_F(SettingsBetweenSpools, PuStraightToTheBoardModuleActsOnTheNextProfile) {
    setup_group(2.0);
    activate();
    spool_ok(line(1, 10, 0));
    const objif::Address pu{rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxPu, 0};
    ASSERT_EQ(module_write(board, pu, Value::of_int(rwmos::board::kPuMicrometre)), Status::kOk);
    spool_ok(line(2, 20, 0));
    ASSERT_EQ(deactivate(), Status::kOk);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 5u);
    expect_at(segs[2].end, 10, 0.002);
}

TEST_F(SettingsBetweenSpools, RsStraightToTheBoardModuleActsOnTheNextProfile) {
    ASSERT_EQ(write_double(tc::kBus, tc::kDevInit, tc::kIdxRotAngle, 0, 90.0), Status::kOk);
    spool_ok(line(1, 10, 0));
    const objif::Address rs{rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxRs, 0};
    ASSERT_EQ(module_write(board, rs, Value::of_int(0)), Status::kOk);
    spool_ok(line(2, 20, 0));
    run();
    expect_at(position(), 20, 0);
}

}  // namespace
