// SPDX-License-Identifier: MIT
// TC rules on the moving board: coordinate rotation ([APCI-TC] section 2.1.1),
// the arc plane once TC objects were accessed (section 2.2 "Wichtiger
// Hinweis"), tool length compensation (Table 3 WkzLen), every ERROR bit
// holding the spooler with Run cleared (Table 4, docs/design.md section 3), and
// bit-for-bit determinism of virtual time.
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "motion_fixture.h"

using namespace motion_test;
namespace tc = rwmos::tc;

namespace {

class TcRules : public MotionBoard {
  protected:
    void rotate(double degrees, double cx = 0.0, double cy = 0.0) {
        ASSERT_EQ(write_double(tc::kBus, tc::kDevInit, tc::kIdxRotAngle, 0, degrees), Status::kOk);
        ASSERT_EQ(write_double(tc::kBus, tc::kDevInit, tc::kIdxRotCenterX, 0, cx), Status::kOk);
        ASSERT_EQ(write_double(tc::kBus, tc::kDevInit, tc::kIdxRotCenterY, 0, cy), Status::kOk);
    }
    DirectCommand jog_to(double x, double y) {
        DirectCommand ja;
        ja.code = DirectCode::kJA;
        ja.axes = 0x03;
        ja.target = xyz(x, y);
        return ja;
    }
};

constexpr double kEps = 1e-9;

void expect_at(const AxisVector& p, double x, double y, double z = 0.0) {
    EXPECT_NEAR(p[0], x, kEps);
    EXPECT_NEAR(p[1], y, kEps);
    EXPECT_NEAR(p[2], z, kEps);
}

// ---- Coordinate rotation ([APCI-TC] section 2.1.1)

TEST_F(TcRules, RotationAppliesToInterpolationProfilesWithoutACompensationObject) {
    rotate(90.0);
    spool_ok(line(1, 10, 0));
    run();
    expect_at(position(), 0, 10);
}

TEST_F(TcRules, RotationTurnsAboutRotCenterInTheActivePlane) {
    // Z-X plane: first axis Z (board axis 2), second X (axis 0). Centre Z=0, X=5.
    ASSERT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxTcPlane, 0, tc::kPlaneZX), Status::kOk);
    rotate(90.0, 0.0, 5.0);
    spool_ok(line3(1, 5, 0, 10));
    run();
    // (Z, X) = (10, 5) is (10, 0) from the centre; turned 90 degrees: (0, 10) -> Z 0, X 15.
    expect_at(position(), 15, 0, 0);
}

TEST_F(TcRules, RotationNeverAppliesToRapidMoves) {
    rotate(90.0);
    spool_ok(rapid(1, 10, 0));
    run();
    EXPECT_EQ(position(), xyz(10, 0));
}

TEST_F(TcRules, RotationNeverAppliesToDirectJogMoves) {
    rotate(90.0);
    ASSERT_EQ(board.direct(jog_to(10, 0)).status, Status::kOk);
    run();
    EXPECT_EQ(position(), xyz(10, 0));
}

TEST_F(TcRules, RotationTurnsArcCentresToo) {
    rotate(90.0);
    spool_ok(line(1, 10, 0));             // to (0, 10) on the machine
    spool_ok(arc(2, true, 0, 10, 0, 0));  // quarter circle to (0, 10) -> (-10, 0)
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 2u);
    EXPECT_EQ(segs[1].kind, SegmentKind::kArc);
    EXPECT_TRUE(segs[1].ccw);
    expect_at(segs[1].center, 0, 0);
    expect_at(segs[1].end, -10, 0);
}

TEST_F(TcRules, RsZeroesTheRotationSoProfilesRunUnrotated) {
    rotate(90.0, 3.0, 4.0);
    ASSERT_EQ(write_int(rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxRs, 0, 0),
              Status::kOk);
    spool_ok(line(1, 10, 0));
    run();
    EXPECT_EQ(position(), xyz(10, 0));
}

TEST_F(TcRules, CompensationWorksOnTheRotatedPath) {
    rotate(90.0);
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));  // machine: (0,0) -> (0,10), travel +Y, left is -X
    ASSERT_EQ(deactivate(), Status::kOk);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 3u);
    expect_at(segs[1].start, -1, 0);
    expect_at(segs[1].end, -1, 10);
    expect_at(position(), 0, 10);
}

// ---- The arc plane ([APCI-TC] section 2.2 "Wichtiger Hinweis")

// An arc named Y first, X second from (10, 0) to (0, 10) about the origin,
// G03. In the (Y, X) plane G03 turns from Y towards X: the long way round
// in X-Y terms (270 degrees); in the active plane X-Y, a quarter circle.
Profile arc_named_yx() {
    Profile p = arc(2, true, 0, 10, 0, 0);
    p.arc_axes = {1, 0};
    p.center = {0, 0};
    return p;
}

TEST_F(TcRules, ArcsRunInThePlaneOfTheAxesNamedFirstBeforeAnyTcAccess) {
    ASSERT_EQ(board.direct(jog_to(10, 0)).status, Status::kOk);
    spool_ok(arc_named_yx());
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 2u);
    EXPECT_EQ(segs[1].plane_axes[0], 1);
    EXPECT_EQ(segs[1].plane_axes[1], 0);
    EXPECT_EQ(segs[1].plane, 0) << "(Y, X) is no TC plane";
    // 3/4 of a circle of radius 10 at 0.01 units per cycle.
    EXPECT_EQ(segs[1].end_cycle - segs[1].start_cycle,
              static_cast<std::uint64_t>(std::ceil(15.0 * std::numbers::pi / 0.01)));
}

TEST_F(TcRules, ArcsRunInTheActivePlaneOnceATcObjectWasAccessed) {
    read_int(tc::kBus, tc::kDevInit, tc::kIdxTcPlane, 0);  // any access counts
    ASSERT_EQ(board.direct(jog_to(10, 0)).status, Status::kOk);
    spool_ok(arc_named_yx());
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 2u);
    EXPECT_EQ(segs[1].plane_axes[0], 0);
    EXPECT_EQ(segs[1].plane_axes[1], 1);
    EXPECT_EQ(segs[1].plane, 17);
    EXPECT_TRUE(segs[1].ccw);
    EXPECT_EQ(segs[1].end_cycle - segs[1].start_cycle,
              static_cast<std::uint64_t>(std::ceil(5.0 * std::numbers::pi / 0.01)));
}

TEST_F(TcRules, ArcInTheActivePlaneZxTurnsAboutTheThirdAxisY) {
    ASSERT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxTcPlane, 0, tc::kPlaneZX), Status::kOk);
    Profile start = line3(1, 0, 0, 10);
    spool_ok(start);
    Profile p;
    p.kind = ProfileKind::kArcCcw;
    p.tag = 2;
    p.feed = 600;
    p.axes = 0x05;
    p.target[0] = 10;  // X
    p.target[2] = 0;   // Z
    p.arc_axes = {2, 0};
    p.center = {0, 0};
    spool_ok(p);
    board.run_until_idle(1'000'000);
    // Halfway: Z and X both 10 / sqrt 2 (G03 from Z towards X).
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 2u);
    EXPECT_EQ(segs[1].plane, 18);
    EXPECT_TRUE(segs[1].ccw);
    expect_at(position(), 10, 0, 0);
}

// ---- Settings changed during a contour

TEST_F(TcRules, CornerModeWrittenDuringAContourAppliesFromTheNextCorner) {
    setup_group(1.0, /*left=*/false);  // right: the left turns of a ccw square are outside corners
    activate();
    spool_ok(line(1, 10, 0));
    spool_ok(line(2, 10, 10));  // corner 1: circular (default)
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubCornerMode, tc::kCornerLinear),
              Status::kOk);
    EXPECT_TRUE(prof_marked()) << "the contour goes on";
    spool_ok(line(3, 0, 10));  // corner 2: linear
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 6u);  // approach, contour 1, arc, contour 2, two lines
    EXPECT_EQ(segs[2].role, SegmentRole::kTransition);
    EXPECT_EQ(segs[2].kind, SegmentKind::kArc);
    EXPECT_EQ(segs[4].role, SegmentRole::kTransition);
    EXPECT_EQ(segs[4].kind, SegmentKind::kLine);
    EXPECT_EQ(segs[5].role, SegmentRole::kTransition);
    EXPECT_EQ(segs[5].kind, SegmentKind::kLine);
    expect_at(segs[4].end, 11, 11);  // the extended offsets meet at the corner's diagonal
}

TEST_F(TcRules, RadiusWrittenDuringAContourAppliesFromTheNextProfile) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubRadius, 2.0), Status::kOk);
    spool_ok(line(2, 20, 0));
    EXPECT_TRUE(prof_marked());
    ASSERT_EQ(deactivate(), Status::kOk);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 5u);
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);
    expect_at(segs[1].end, 10, 1);  // profile 1 at the old radius, to its offset end
    EXPECT_EQ(segs[2].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[2].tag, 2u);
    expect_at(segs[2].end, 10, 2);  // onto the new radius's path
    expect_at(segs[3].end, 20, 2);
    EXPECT_EQ(segs[4].role, SegmentRole::kDeparture);
}

// ---- Tool length compensation ([APCI-TC] Table 3 ZAxis, WkzLen)

// A contour of two lines, the second down to Z -2, with WkzLen 5: approach, contour,
// transition, contour, departure.
std::vector<Segment> two_lines_with_length(TcRules& t) {
    t.setup_group(1.0);
    EXPECT_EQ(t.write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen, 5.0), Status::kOk);
    t.activate();
    t.spool_ok(line3(1, 10, 0, 0));
    t.spool_ok(line3(2, 10, -10, -2));
    EXPECT_EQ(t.deactivate(), Status::kOk);
    t.run();
    return t.segments();
}

TEST_F(TcRules, ToolLengthCompensationAddsWkzLenAlongTheGroupsThirdAxis) {
    const auto segs = two_lines_with_length(*this);
    ASSERT_EQ(segs.size(), 5u);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    EXPECT_NEAR(segs[0].end[2], 5.0, kEps);
    EXPECT_NEAR(segs[1].end[2], 5.0, kEps);  // contour 1 at Z 0 + 5
    EXPECT_NEAR(segs[2].end[2], 5.0, kEps);  // transition at the corner
    EXPECT_NEAR(segs[3].end[2], 3.0, kEps);  // contour 2 down to Z -2 + 5
    EXPECT_EQ(segs[4].role, SegmentRole::kDeparture);
    EXPECT_NEAR(segs[4].end[2], -2.0, kEps);  // compensation removed at the end
}

TEST_F(TcRules, ToolLengthCompensationFollowsTheGroupsZAxis) {
    setup_group(1.0, true, 1, /*z=*/3);
    ASSERT_EQ(write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen, 2.5), Status::kOk);
    activate();
    spool_ok(line(1, 10, 0));
    spool_ok(line(2, 10, -10));
    run();
    EXPECT_NEAR(position()[3], 2.5, kEps);
    EXPECT_NEAR(position()[2], 0.0, kEps);
}

TEST_F(TcRules, NoLengthCompensationWhileTheGroupDoesNotRun) {
    setup_group(1.0);
    ASSERT_EQ(write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen, 5.0), Status::kOk);
    spool_ok(line3(1, 10, 0, 0));
    run();
    EXPECT_EQ(position(), xyz(10, 0, 0));
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 1u);
    EXPECT_EQ(segs[0].role, SegmentRole::kUncompensated);
}

// LengthMode 1 (extension, docs/compensation.md "Tool length"): WkzLen on every profile, the
// uncompensated ones too, and the departure keeps it.
TEST_F(TcRules, LengthModeOneAddsWkzLenToEveryProfile) {
    setup_group(1.0);
    ASSERT_EQ(write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen, 5.0), Status::kOk);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubLengthMode, tc::kLengthAlways),
              Status::kOk);
    spool_ok(line3(1, 10, 0, 0));
    run();
    EXPECT_EQ(position(), xyz(10, 0, 5));
    activate();
    spool_ok(line3(2, 20, 0, 0));
    spool_ok(line3(3, 20, -10, 0));
    ASSERT_EQ(deactivate(), Status::kOk);
    run();
    const auto segs = segments();
    ASSERT_FALSE(segs.empty());
    EXPECT_EQ(segs.back().role, SegmentRole::kDeparture);
    EXPECT_NEAR(segs.back().end[2], 5.0, kEps);  // the departure keeps the length
    for (const auto& s : segs) EXPECT_NEAR(s.end[2], 5.0, kEps);
    // Every segment ends with WkzLen, the uncompensated first one included, and starts with
    // what the one before ended with.
    EXPECT_EQ(segs[0].role, SegmentRole::kUncompensated);
    EXPECT_EQ(segs[0].length_start[2], 0.0);
    for (std::size_t i = 0; i < segs.size(); ++i) {
        EXPECT_EQ(segs[i].length_end[2], 5.0) << i;
        if (i > 0) {
            EXPECT_EQ(segs[i].length_start[2], 5.0) << i;
        }
    }
}

// The executed segments say how much tool length the board added in their start and end
// (Segment::length_start, length_end): the approach brings WkzLen in, the contour and the
// transition keep it, the departure takes it out; the programmed path is the position less it.
TEST_F(TcRules, ExecutedSegmentsCarryTheLengthTheBoardAddedAtTheirEnds) {
    const auto segs = two_lines_with_length(*this);
    ASSERT_EQ(segs.size(), 5u);
    const double starts[] = {0, 5, 5, 5, 5}, ends[] = {5, 5, 5, 5, 0};
    for (std::size_t i = 0; i < segs.size(); ++i) {
        EXPECT_EQ(segs[i].length_start[2], starts[i]) << i;
        EXPECT_EQ(segs[i].length_end[2], ends[i]) << i;
        for (std::size_t a : {0u, 1u, 3u, 7u}) {
            EXPECT_EQ(segs[i].length_start[a], 0.0) << i << " axis " << a;
            EXPECT_EQ(segs[i].length_end[a], 0.0) << i << " axis " << a;
        }
    }
    EXPECT_NEAR(segs[3].end[2] - segs[3].length_end[2], -2.0, kEps) << "contour 2 at Z -2";
}

// A jog stops the approach where it is: the interrupted segment ends with the part of the
// length the axes carry there, the jog starts with it and ends without (the programmed path is
// where the axes are after a direct command).
TEST_F(TcRules, AnInterruptedSegmentEndsWithTheLengthWhereItStopped) {
    setup_group(1.0);
    ASSERT_EQ(write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen, 8.0), Status::kOk);
    activate();
    spool_ok(line3(1, 0, 10, 0));
    spool_ok(line3(2, 10, 10, 0));  // releases the approach to (-1, 10) and the first element
    board.step(50);                 // into the approach
    ASSERT_EQ(board.direct(jog_to(0, 0)).status, Status::kOk);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 2u);
    ASSERT_TRUE(segs[0].interrupted);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    const double z = segs[0].end[2];
    EXPECT_GT(z, 0.0);
    EXPECT_LT(z, 8.0);
    EXPECT_EQ(segs[0].length_end[2], z) << "all of Z's motion so far is the length";
    EXPECT_EQ(segs[1].length_start[2], z);
    EXPECT_EQ(segs[1].length_end[2], 0.0);
    EXPECT_EQ(segs[1].end[2], z) << "the jog names X and Y only";
}

TEST_F(TcRules, LengthModeTakesOnlyItsTwoValues) {
    EXPECT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubLengthMode, 2), Status::kValueTooHigh);
    EXPECT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubLengthMode, -1), Status::kValueTooLow);
}

// ---- Errors: the spooler holds, Run clears, ERROR stays until written

// After a TC error: the call names group, bit and block; ERROR shows the bit,
// Run is clear, the earlier held profile is still held, nothing spooled
// before the error starts, and new profiles are refused until ERROR is written.
void expect_held_after(Rig& rig, const MotionResult& r, std::int32_t bit, std::uint32_t tag) {
    EXPECT_EQ(r.status, Status::kWrongDeviceState);
    EXPECT_EQ(r.group, 1);
    EXPECT_EQ(r.errors, bit);
    EXPECT_EQ(r.tag, tag);
    EXPECT_FALSE(r.message.empty());
    EXPECT_EQ(rig.error() & bit, bit);
    EXPECT_FALSE(rig.running());
    EXPECT_TRUE(rig.board.motion_status().held);
    const AxisVector before = rig.position();
    EXPECT_EQ(rig.board.run_until_idle(1'000'000), 0u) << "the spooler holds";
    EXPECT_EQ(rig.position(), before);
    EXPECT_EQ(rig.board.spool(line(99, 1, 1)).status, Status::kWrongDeviceState);
    EXPECT_EQ(rig.error() & bit, bit) << "the bit stays until ERROR is written";
}

TEST_F(TcRules, CalcErrorHoldsTheSpoolerAndClearsRun) {
    setup_group(5.0);
    activate();
    spool_ok(line(1, 10, 0));
    // G03 of radius 2 with the tool (radius 5) on its concave side.
    const MotionResult r = board.spool(arc(2, true, 10, 4, 10, 2));
    expect_held_after(*this, r, tc::kCalcError, 2);
    EXPECT_TRUE(prof_marked()) << "the earlier profile is still held";
}

TEST_F(TcRules, KorrErrorHoldsTheSpoolerAndClearsRun) {
    setup_group(2.0);
    activate();
    spool_ok(line(1, 10, 0));
    // An inside corner onto an element shorter than the tool radius.
    const MotionResult r = board.spool(line(2, 10, 1));
    expect_held_after(*this, r, tc::kKorrError, 2);
    EXPECT_TRUE(prof_marked());
}

TEST_F(TcRules, CenterErrorHoldsTheSpoolerAndClearsRun) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    // Start radius 4, end radius 6 about (14, 0).
    const MotionResult r = board.spool(arc(2, true, 20, 0, 14, 0));
    expect_held_after(*this, r, tc::kCenterError, 2);
}

TEST_F(TcRules, PlaneErrorForAnArcOutsideTheActivePlane) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    Profile p = arc(2, true, 10, 0, 10, 0);
    p.arc_axes = {0, 2};
    p.axes = 0x05;
    p.target[2] = 0;
    const MotionResult r = board.spool(p);
    expect_held_after(*this, r, tc::kPlaneError, 2);
}

TEST_F(TcRules, InitErrorHoldsTheSpoolerUntilErrorIsWritten) {
    spool_ok(line(1, 10, 0));
    // Activation without a side selected: InitError ([APCI-TC] Table 3 STATUS).
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubXAxis, 0), Status::kOk);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubStatus, 1), Status::kWrongDeviceState);
    ASSERT_EQ(error() & tc::kInitError, tc::kInitError);
    EXPECT_EQ(board.run_until_idle(1'000'000), 0u);
    EXPECT_EQ(board.spool(line(2, 0, 0)).status, Status::kWrongDeviceState);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubError, 0), Status::kOk);
    EXPECT_EQ(board.run_until_idle(1'000'000), 1000u);
    EXPECT_EQ(position(), xyz(10, 0));
}

TEST_F(TcRules, WritingErrorLetsTheSpoolerGoOnAndStatus0ReleasesTheHeldProfile) {
    setup_group(5.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(board.spool(arc(2, true, 10, 4, 10, 2)).status, Status::kWrongDeviceState);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubError, 0), Status::kOk);
    EXPECT_FALSE(board.motion_status().held);
    ASSERT_TRUE(prof_marked());
    ASSERT_EQ(deactivate(), Status::kOk);
    EXPECT_FALSE(prof_marked());
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 3u);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);
    EXPECT_EQ(segs[1].tag, 1u);
    EXPECT_EQ(segs[2].role, SegmentRole::kDeparture);
    EXPECT_EQ(position(), xyz(10, 0));
}

// The spool call mirrors the ERROR bits into the executor itself: it holds from the call that
// sets one, before any clock, and the first call after ERROR was written reads it anew.
TEST_F(TcRules, SpoolCallsHoldTheExecutorFromTheErrorOnAndReadErrorWrittenBetweenThem) {
    setup_group(5.0);
    activate();
    spool_ok(line(1, 10, 0));
    const rwmos::motion::Executor& exec = board.state().motion.executor();
    EXPECT_FALSE(exec.halted());
    ASSERT_EQ(board.spool(arc(2, true, 10, 4, 10, 2)).status, Status::kWrongDeviceState);
    EXPECT_TRUE(exec.halted()) << "held by the call that set ERROR";
    EXPECT_EQ(board.spool(line(3, 20, 0)).status, Status::kWrongDeviceState);
    EXPECT_TRUE(exec.halted());
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubError, 0), Status::kOk);
    spool_ok(line(3, 20, 0));
    EXPECT_FALSE(exec.halted()) << "the call after ERROR was written no longer holds";
}

TEST_F(TcRules, ArcWithWrongCentreOnAnActiveTcBoardSetsCenterErrorEvenUncompensated) {
    setup_group(1.0);  // TC accessed, group 1 active (not running)
    const MotionResult r = board.spool(arc(1, true, 20, 0, 14, 0));
    EXPECT_EQ(r.status, Status::kWrongDeviceState);
    EXPECT_EQ(error() & tc::kCenterError, tc::kCenterError);
    EXPECT_EQ(board.motion_status().fill, 0u);
}

// ---- Determinism (docs/design.md section 5: same input, same output bits)

// A rounded pocket (tangent arcs, one inside corner), a rapid, and a second
// contour, rotated by 17 degrees, with length compensation and odd feeds.
void program(Rig& r) {
    r.setup_group(1.5);
    ASSERT_EQ(r.write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen, 0.25), Status::kOk);
    ASSERT_EQ(r.write_double(tc::kBus, tc::kDevInit, tc::kIdxRotAngle, 0, 17.0), Status::kOk);
    r.activate();
    r.spool_ok(line3(1, 20, 0, -1, 1234.5));
    r.spool_ok(arc(2, true, 30, 10, 20, 10, 800));
    r.spool_ok(line(3, 30, 20, 999));
    r.spool_ok(arc(4, true, 20, 30, 20, 20, 700));
    r.spool_ok(line(5, 0, 30, 2000));
    r.spool_ok(line(6, 0, 0, 2000));
    r.spool_ok(rapid(7, -10, -10));
    r.spool_ok(line(8, -10, 0, 1500));
    r.spool_ok(line(9, -20, 0, 1500));
    ASSERT_EQ(r.deactivate(), Status::kOk);
}

std::vector<rwmos::motion::TraceSample> traced_run(Rig& r) {
    EXPECT_EQ(r.board.set_trace(true, 1 << 20), Status::kOk);
    program(r);
    r.run();
    std::vector<rwmos::motion::TraceSample> out(r.board.motion_status().trace_pending);
    out.resize(r.board.read_trace(out));
    return out;
}

TEST_F(TcRules, SameInputGivesBitIdenticalPerCycleSamples) {
    Rig a, b;
    const auto ta = traced_run(a);
    const auto tb = traced_run(b);
    ASSERT_GT(ta.size(), 1000u);
    ASSERT_EQ(ta.size(), tb.size());
    EXPECT_EQ(std::memcmp(ta.data(), tb.data(), ta.size() * sizeof ta[0]), 0);
}

TEST_F(TcRules, UnobservedRunsGiveTheSameBitsAsTracedOnes) {
    Rig traced, fast;
    const auto samples = traced_run(traced);
    program(fast);
    // The unobserved board runs in uneven chunks; at every chunk's end its
    // axes must sit exactly where the traced board was at that cycle.
    std::uint64_t cycle = 0;
    for (std::uint64_t chunk : {1ull, 2ull, 377ull, 1000ull, 2048ull, 999ull}) {
        fast.board.step(chunk);
        cycle += chunk;
        ASSERT_LE(cycle, samples.size());
        EXPECT_EQ(fast.position(), samples[cycle - 1].position) << "cycle " << cycle;
    }
    fast.run();
    EXPECT_EQ(fast.position(), traced.position());
    EXPECT_EQ(fast.board.motion_status().now, traced.board.motion_status().now);
}

TEST_F(TcRules, TraceSamplesEveryCycleOnce) {
    ASSERT_EQ(board.set_trace(true, 100), Status::kOk);
    spool_ok(line(1, 0.5, 0));  // 50 cycles
    board.step(60);
    std::vector<rwmos::motion::TraceSample> s(100);
    s.resize(board.read_trace(s));
    ASSERT_EQ(s.size(), 60u);
    for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(s[i].cycle, i + 1);
    EXPECT_DOUBLE_EQ(s[24].position[0], 0.25);
    EXPECT_EQ(board.set_trace(true, 0), Status::kValueTooLow);
    EXPECT_EQ(board.set_trace(true, rwmos::EmulatedBoard::kMaxTraceCapacity + 1), Status::kValueTooHigh);
}

// BoardConfig::trace_memory bounds the ring (a daemon's --trace-memory): a ring of exactly as
// many samples as fit is taken, one more is NoMemory and changes nothing (the trace stays on
// with its samples).
TEST(TraceMemory, ARingOneSampleLargerThanTheTraceMemoryIsRefusedAndChangesNothing) {
    rwmos::BoardConfig config;
    constexpr std::size_t kFit = 1000;
    config.trace_memory =
        kFit * sizeof(rwmos::motion::TraceSample) + sizeof(rwmos::motion::TraceSample) - 1;
    rwmos::EmulatedBoard board(config);
    ASSERT_EQ(board.set_trace(true, kFit), Status::kOk);
    board.step(5);
    EXPECT_EQ(board.set_trace(true, kFit + 1), Status::kNoMemory);
    EXPECT_TRUE(board.motion_status().tracing);
    EXPECT_EQ(board.motion_status().trace_pending, 5u);
    EXPECT_EQ(board.set_trace(false, 0), Status::kOk);  // off needs no memory
    // Without a limit the board's own bound applies.
    rwmos::EmulatedBoard unbounded;
    EXPECT_EQ(unbounded.set_trace(true, rwmos::EmulatedBoard::kMaxTraceCapacity), Status::kOk);
}

// ---- Without optionTC there is no rotation and no compensation

TEST(MotionWithoutOptionTc, ProfilesRunAsProgrammed) {
    Rig r(rwmos::BoardConfig{false});
    Profile p = arc(1, true, 0, 10, 0, 0);
    ASSERT_EQ(r.board
                  .direct([] {
                      DirectCommand ja;
                      ja.code = DirectCode::kJA;
                      ja.axes = 0x01;
                      ja.target[0] = 10;
                      return ja;
                  }())
                  .status,
              Status::kOk);
    r.spool_ok(p);
    r.run();
    expect_at(r.position(), 0, 10);
    const auto segs = r.segments();
    ASSERT_EQ(segs.size(), 2u);
    EXPECT_EQ(segs[1].role, SegmentRole::kUncompensated);
}


// ---- ReInit: the stored shift of the correction axes ([APCI-TC] Table 2; docs/motion.md 5)

Profile line_x(std::uint32_t tag, double x) {
    Profile p = line(tag, x, 0.0);
    p.axes = 0x01;  // X only: Y and Z keep their programmed values
    return p;
}

// A contour ended by SSF 2001 leaves the tool 1 to the left of the path and WkzLen 5 up. ReInit
// forgets that shift: the board takes (10, 1, 5) as programmed, so a profile naming only X runs
// its contour at Y 1 + 1 and Z 5 + 5, and the departure ends at (20, 1, 5), not (20, 0, 0).
TEST_F(TcRules, ReInitForgetsTheShiftAContourLeftAndToolsStayActive) {
    Rig twin;  // the same without ReInit
    for (Rig* r : {static_cast<Rig*>(this), &twin}) {
        r->setup_group(1.0);
        ASSERT_EQ(r->write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen, 5.0), Status::kOk);
        r->activate();
        r->spool_ok(line3(1, 10, 0, 0));
        ASSERT_EQ(r->board.ssf(0x03, rwmos::motion::kSsfReleaseHeldProfile).status, Status::kOk);
        r->run();
        expect_at(r->position(), 10, 1, 5);
    }
    const auto& g = board.state().tc.group(1);
    EXPECT_EQ(g.offset, (std::array<double, 3>{0.0, 1.0, 5.0})) << "the stored shift";

    ASSERT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxReInit, 0, 0), Status::kOk);
    EXPECT_EQ(g.offset, (std::array<double, 3>{})) << "cleared";
    expect_at(position(), 10, 1, 5);  // nothing moves
    EXPECT_TRUE(running()) << "the programmed tools stay active";
    EXPECT_EQ(read_double(tc::kBus, tc::kDevGroups, 1, tc::kSubRadius), 1.0);
    EXPECT_EQ(read_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen), 5.0);

    for (Rig* r : {static_cast<Rig*>(this), &twin}) {
        r->segments();
        r->spool_ok(line_x(2, 20));
        ASSERT_EQ(r->deactivate(), Status::kOk);
        r->run();
    }
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 3u);
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);
    expect_at(segs[1].end, 20, 2, 10);
    expect_at(position(), 20, 1, 5);
    expect_at(twin.position(), 20, 0, 0);  // without ReInit the shift comes out at the departure
}

// Mid-contour the held profile's geometry starts from the shifted point; [APCI-TC] names ReInit
// for before a re-reference only, so this is refused as not emulated and changes nothing.
TEST_F(TcRules, ReInitWhileAProfileIsHeldIsRefusedAndChangesNothing) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_TRUE(prof_marked());
    EXPECT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxReInit, 0, 0), Status::kWrongDeviceState);
    EXPECT_TRUE(prof_marked());
    EXPECT_TRUE(running());
    EXPECT_EQ(error(), 0) << "no InitError: ReInit is no group setting";
    ASSERT_EQ(deactivate(), Status::kOk);
    run();
    expect_at(position(), 10, 0);
    // With the contour ended, ReInit is accepted.
    EXPECT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxReInit, 3, 1), Status::kOk);
}

// Under a rotation the programmed position is turned back with the shift: the rotated path
// then starts where the tool stands. Rotation 90: program X runs along board Y; the left offset
// of 1 is board -X. After ReInit a G01 naming only X stays at board X -1.
TEST_F(TcRules, ReInitUnderARotationKeepsTheToolWhereItStands) {
    rotate(90.0);
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(board.ssf(0x03, rwmos::motion::kSsfReleaseHeldProfile).status, Status::kOk);
    run();
    expect_at(position(), -1, 10);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxReInit, 0, 0), Status::kOk);
    ASSERT_EQ(deactivate(), Status::kOk);
    spool_ok(line_x(2, 20));
    run();
    expect_at(position(), -1, 20);
}

// Reset clears the shift as well ([APCI-TC] Table 2: "intern gespeicherte Verschiebungswerte
// der Korrekturachsen ... werden gelöscht"): the uncompensated profile after it keeps Y and Z.
TEST_F(TcRules, ResetForgetsTheShiftToo) {
    setup_group(1.0);
    ASSERT_EQ(write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen, 5.0), Status::kOk);
    activate();
    spool_ok(line3(1, 10, 0, 0));
    ASSERT_EQ(board.ssf(0x03, rwmos::motion::kSsfReleaseHeldProfile).status, Status::kOk);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxReset, 0, 0), Status::kOk);
    EXPECT_FALSE(running());
    spool_ok(line_x(2, 20));
    run();
    expect_at(position(), 20, 1, 5);
}

// ---- PU: RADIUS and WkzLen in the unit PU selects, the board moves in mm (object-map 2)

TEST_F(TcRules, RadiusInMicrometresCompensatesByItsMillimetreValue) {
    Rig mm;
    ASSERT_EQ(write_int(rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxPu, 0,
                        rwmos::board::kPuMicrometre),
              Status::kOk);
    setup_group(500.0);
    EXPECT_EQ(read_double(tc::kBus, tc::kDevGroups, 1, tc::kSubRadius), 500.0) << "as written";
    mm.setup_group(0.5);
    for (Rig* r : {static_cast<Rig*>(this), &mm}) {
        r->activate();
        r->spool_ok(line(1, 10, 0));
        r->spool_ok(line(2, 10, -10));
        ASSERT_EQ(r->deactivate(), Status::kOk);
        r->run();
    }
    const auto segs = segments();
    const auto want = mm.segments();
    ASSERT_EQ(segs.size(), want.size());
    for (std::size_t i = 0; i < segs.size(); ++i) {
        EXPECT_EQ(segs[i].role, want[i].role) << i;
        EXPECT_EQ(segs[i].end, want[i].end) << i;
    }
    expect_at(segs[0].end, 0, 0.5);  // the approach: 0.5 mm to the left
}

TEST_F(TcRules, WkzLenInInchesShiftsZByItsMillimetreValue) {
    ASSERT_EQ(write_int(rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxPu, 0,
                        rwmos::board::kPuInch),
              Status::kOk);
    setup_group(0.0);
    ASSERT_EQ(write_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen, 0.5), Status::kOk);
    EXPECT_EQ(read_double(tc::kBus, tc::kDevGroups, 1, tc::kSubWkzLen), 0.5) << "as written";
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(board.ssf(0x03, rwmos::motion::kSsfReleaseHeldProfile).status, Status::kOk);
    run();
    EXPECT_NEAR(position()[2], 12.7, kEps);
}

// The stored numbers are in the unit PU selects when they are used: a PU change reinterprets
// them from the next profile (set PU with the machine setup, before the tool table).
TEST_F(TcRules, PuChangeReinterpretsTheStoredToolValues) {
    setup_group(2.0);
    ASSERT_EQ(write_int(rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxPu, 0,
                        rwmos::board::kPuMicrometre),
              Status::kOk);
    EXPECT_EQ(read_double(tc::kBus, tc::kDevGroups, 1, tc::kSubRadius), 2.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(deactivate(), Status::kOk);
    run();
    const auto segs = segments();
    ASSERT_FALSE(segs.empty());
    expect_at(segs[0].end, 0, 0.002);
}

}  // namespace
