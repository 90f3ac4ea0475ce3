// SPDX-License-Identifier: MIT
// Spooler rules on a Board: the one-profile lookahead ([APCI-TC] section 1),
// SSF 2001, direct commands JA/JS, JOG/G00 re-approach ([APCI-TC] section
// 2.4), a full spooler, bad profiles, and the board objects that show it.
#include <cmath>
#include <limits>

#include "motion_fixture.h"

using namespace motion_test;
namespace tc = rwmos::tc;
namespace board_obj = rwmos::board;

namespace {

class Spooler : public MotionBoard {};

constexpr double kEps = 1e-9;

void expect_at(const AxisVector& p, double x, double y, double z = 0.0) {
    EXPECT_NEAR(p[0], x, kEps);
    EXPECT_NEAR(p[1], y, kEps);
    EXPECT_NEAR(p[2], z, kEps);
}

// ---- The held profile ([APCI-TC] section 1, Table 5 ProfMarked)

TEST_F(Spooler, FirstProfileWhileCompensatingIsHeldAndSetsProfMarked) {
    setup_group(1.0);
    activate();
    EXPECT_FALSE(prof_marked());
    spool_ok(line(1, 10, 0));
    EXPECT_TRUE(prof_marked());
    EXPECT_TRUE(running());
    run();
    // Only the approach to the compensated path ran; the profile itself waits.
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 1u);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[0].tag, 1u);
    expect_at(position(), 0, 1);
    EXPECT_TRUE(prof_marked());
}

TEST_F(Spooler, NextProfileReleasesTheHeldOneCorrectedWithTheTransition) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_TRUE(prof_marked());
    // A right turn: for left compensation an outside corner, bridged by an
    // arc of the tool radius about the programmed corner.
    spool_ok(line(2, 10, -10));
    EXPECT_TRUE(prof_marked()) << "the new profile is held in turn";
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 3u);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);
    EXPECT_EQ(segs[1].tag, 1u);
    expect_at(segs[1].start, 0, 1);
    expect_at(segs[1].end, 10, 1);
    EXPECT_EQ(segs[2].role, SegmentRole::kTransition);
    EXPECT_EQ(segs[2].kind, SegmentKind::kArc);
    EXPECT_EQ(segs[2].tag, 1u);
    EXPECT_FALSE(segs[2].ccw);
    expect_at(segs[2].center, 10, 0);
    expect_at(segs[2].end, 11, 0);
    EXPECT_EQ(segs[2].plane, 17);
}

TEST_F(Spooler, DeactivationReleasesTheLastProfileWithItsDeparture) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    spool_ok(line(2, 10, -10));
    ASSERT_TRUE(prof_marked());
    ASSERT_EQ(deactivate(), Status::kOk);
    EXPECT_FALSE(prof_marked());
    EXPECT_FALSE(running());
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 5u);
    EXPECT_EQ(segs[3].role, SegmentRole::kContour);
    EXPECT_EQ(segs[3].tag, 2u);
    expect_at(segs[3].start, 11, 0);
    expect_at(segs[3].end, 11, -10);
    EXPECT_EQ(segs[4].role, SegmentRole::kDeparture);
    EXPECT_EQ(segs[4].tag, 2u);
    expect_at(position(), 10, -10);
}

// CuttingEdge (docs/compensation.md "Turning tools"): the board carries the nose centre's path
// over to the imaginary tip, by the radius along LinuxCNC's table in the plane (its first axis
// as Z, its second as X: position 2 is (-r, -r)). The approach runs from the tool to the carried
// element, the departure from it back to the programmed end; the contour and its corners whole.
TEST_F(Spooler, CuttingEdgeCarriesTheCompensatedPathOverToTheImaginaryTip) {
    setup_group(1.0);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubCuttingEdge, 2), Status::kOk);
    EXPECT_EQ(read_int(tc::kBus, tc::kDevGroups, 1, tc::kSubCuttingEdge), 2);
    activate();
    spool_ok(line(1, 10, 0));
    spool_ok(line(2, 10, -10));
    ASSERT_EQ(deactivate(), Status::kOk);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 5u);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    expect_at(segs[0].start, 0, 0);  // from the tool
    expect_at(segs[0].end, -1, 0);   // onto N1's offset start (0, 1), carried by (-1, -1)
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);
    expect_at(segs[1].end, 9, 0);
    EXPECT_EQ(segs[2].role, SegmentRole::kTransition);  // the arc about (10, 0), carried
    EXPECT_EQ(segs[2].kind, SegmentKind::kArc);
    expect_at(segs[2].center, 9, -1);
    expect_at(segs[2].end, 10, -1);
    EXPECT_EQ(segs[3].role, SegmentRole::kContour);
    expect_at(segs[3].end, 10, -11);
    EXPECT_EQ(segs[4].role, SegmentRole::kDeparture);  // back to the programmed end
    expect_at(segs[4].end, 10, -10);
}

// 0 and 9 are the nose centre: nothing is carried over; a change of the position while the
// group compensates ends the contour and the next profile approaches the carried path anew.
TEST_F(Spooler, CuttingEdgeNineIsTheNoseCentreAndAChangeReApproaches) {
    setup_group(1.0);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubCuttingEdge, 9), Status::kOk);
    activate();
    spool_ok(line(1, 10, 0));
    spool_ok(line(2, 20, 0));
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubCuttingEdge, 8), Status::kOk);
    spool_ok(line(3, 30, 0));
    ASSERT_EQ(deactivate(), Status::kOk);
    run();
    const auto segs = segments();
    ASSERT_GE(segs.size(), 4u);
    expect_at(segs[0].end, 0, 1);  // position 9: the nose centre's offset start
    // N2 ends the contour at its offset end (20, 1); N3 approaches anew, carried by (0, +1).
    bool reapproached = false;
    for (const Segment& s : segs) {
        if (s.tag == 3 && s.role == SegmentRole::kApproach) {
            reapproached = true;
            expect_at(s.start, 20, 1);
        }
        if (s.tag == 3 && s.role == SegmentRole::kContour) expect_at(s.end, 30, 2);
    }
    EXPECT_TRUE(reapproached);
}

// SelectionMode 138 (G138, [ISG-PROG]'s direct selection; docs/compensation.md): the first
// profile runs from the tool straight to the second's offset start, no corner between; STATUS = 0
// and the next profile depart as under 139.
TEST_F(Spooler, SelectionMode138ApproachesTheSecondProfilesOffsetStartDirectly) {
    setup_group(1.0);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubSelectionMode, 138), Status::kOk);
    EXPECT_EQ(read_int(tc::kBus, tc::kDevGroups, 1, tc::kSubSelectionMode), 138);
    activate();
    spool_ok(line(1, 10, 0));
    spool_ok(line(2, 10, 10));
    ASSERT_EQ(deactivate(), Status::kOk);
    spool_ok(line(3, 0, 10));
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 3u);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[0].tag, 1u);
    expect_at(segs[0].end, 9, 0);  // N2's offset start, left of (10, 0) going +Y
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);
    expect_at(segs[1].end, 9, 10);
    EXPECT_EQ(segs[2].role, SegmentRole::kDeparture);
    EXPECT_EQ(segs[2].tag, 3u);
}

// Under 138 an arc as the first profile is KorrError ([ISG-PROG]: approach blocks on lines only).
TEST_F(Spooler, SelectionMode138RefusesAnArcAsTheFirstProfile) {
    setup_group(1.0);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubSelectionMode, 138), Status::kOk);
    activate();
    const MotionResult r = board.spool(arc(4, true, 10, 10, 0, 10));
    EXPECT_EQ(r.status, Status::kWrongDeviceState);
    EXPECT_EQ(r.errors, objif::map::tc::kKorrError);
    EXPECT_EQ(r.tag, 4u);
}

// SelectionMode 139 (docs/compensation.md "Approach and departure"): STATUS = 0 ends the
// contour at its offset end, and the next profile, uncompensated, is the departure: from there
// to its own end, with the contour's side. The one after it is an ordinary move again, and so
// is a profile after a rapid.
TEST_F(Spooler, UnderG139TheProfileAfterDeactivationIsTheDeparture) {
    setup_group(1.0);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubSelectionMode, 139), Status::kOk);
    activate();
    spool_ok(line(1, 10, 0));  // the approach
    spool_ok(line(2, 20, 0));
    ASSERT_EQ(deactivate(), Status::kOk);
    spool_ok(line(3, 30, -5));
    spool_ok(line(4, 40, -5));
    run();
    auto segs = segments();
    ASSERT_EQ(segs.size(), 4u);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);
    EXPECT_EQ(segs[2].role, SegmentRole::kDeparture);
    EXPECT_EQ(segs[2].tag, 3u);
    expect_at(segs[2].start, 20, 1);
    expect_at(segs[2].end, 30, -5);
    EXPECT_EQ(segs[3].role, SegmentRole::kUncompensated);
    // Another stretch, ended by STATUS = 0 and then a rapid: no departure after it.
    activate();
    spool_ok(line(5, 50, -5));
    spool_ok(line(6, 60, -5));
    ASSERT_EQ(deactivate(), Status::kOk);
    spool_ok(rapid(7, 70, 0));
    spool_ok(line(8, 80, 0));
    run();
    segs = segments();
    ASSERT_EQ(segs.size(), 4u);
    EXPECT_EQ(segs[2].role, SegmentRole::kRapid);
    EXPECT_EQ(segs[3].role, SegmentRole::kUncompensated);
}

// Under G237 the departure is the board's own, at right angles; the next profile is an ordinary
// move.
TEST_F(Spooler, UnderG237TheProfileAfterTheDepartureIsAnOrdinaryMove) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(deactivate(), Status::kOk);
    spool_ok(line(2, 20, -5));
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 4u);
    EXPECT_EQ(segs[2].role, SegmentRole::kDeparture);
    EXPECT_EQ(segs[2].tag, 1u);
    EXPECT_EQ(segs[3].role, SegmentRole::kUncompensated);
}

TEST_F(Spooler, Ssf2001ReleasesTheHeldProfileAndCompensationGoesOn) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    spool_ok(line(2, 10, -10));
    const MotionResult r = board.ssf(0x03, rwmos::motion::kSsfReleaseHeldProfile);
    ASSERT_EQ(r.status, Status::kOk) << r.message;
    EXPECT_FALSE(prof_marked());
    EXPECT_TRUE(running());
    run();
    auto segs = segments();
    ASSERT_EQ(segs.size(), 4u) << "held contour released, no departure";
    EXPECT_EQ(segs[3].role, SegmentRole::kContour);
    EXPECT_EQ(segs[3].tag, 2u);
    expect_at(position(), 11, -10);
    // The contour ended: the next profile approaches the compensated path anew.
    spool_ok(line(3, 20, -10));
    EXPECT_TRUE(prof_marked());
    run();
    segs = segments();
    ASSERT_EQ(segs.size(), 1u);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[0].tag, 3u);
    expect_at(segs[0].end, 10, -9);
}

TEST_F(Spooler, Ssf2001ToAxesOutsideTheGroupReleasesNothing) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(board.ssf(0x04, rwmos::motion::kSsfReleaseHeldProfile).status, Status::kOk);
    EXPECT_TRUE(prof_marked());
}

TEST_F(Spooler, SsfCommandOtherThan2001IsRefusedAndChangesNothing) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    const MotionResult r = board.ssf(0x03, 2000);
    EXPECT_EQ(r.status, Status::kInvalidValue);
    EXPECT_FALSE(r.message.empty());
    EXPECT_TRUE(prof_marked());
}

TEST_F(Spooler, SsfNamingNoAxisIsRefused) {
    EXPECT_EQ(board.ssf(0x00, rwmos::motion::kSsfReleaseHeldProfile).status, Status::kInvalidValue);
}

// ---- Direct commands ([APCI-TC] section 1: JA, JS discard spooler and held profile)

TEST_F(Spooler, DirectCommandJsDiscardsSpoolerAndHeldProfileAndStopsTheAxes) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    spool_ok(line(2, 10, -10));
    spool_ok(line(3, 0, -10));
    ASSERT_GT(board.motion_status().fill, 0u);
    board.step(50);  // halfway along the approach (0,0) -> (0,1)
    DirectCommand js;
    js.code = DirectCode::kJS;
    ASSERT_EQ(board.direct(js).status, Status::kOk);
    EXPECT_EQ(board.motion_status().fill, 0u);
    EXPECT_FALSE(prof_marked());
    EXPECT_TRUE(running()) << "a direct command does not end compensation";
    expect_at(position(), 0, 0.5);
    run();
    expect_at(position(), 0, 0.5);
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 1u);
    EXPECT_TRUE(segs[0].interrupted);
}

TEST_F(Spooler, DirectCommandJaDiscardsSpoolerAndHeldProfileThenJogsToTheTarget) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    spool_ok(line(2, 10, -10));
    DirectCommand ja;
    ja.code = DirectCode::kJA;
    ja.axes = 0x03;
    ja.target[0] = 5;
    ja.target[1] = 5;
    ASSERT_EQ(board.direct(ja).status, Status::kOk);
    EXPECT_FALSE(prof_marked());
    EXPECT_EQ(board.motion_status().fill, 1u);
    run();
    expect_at(position(), 5, 5);
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 1u);
    EXPECT_EQ(segs[0].role, SegmentRole::kRapid);
}

TEST_F(Spooler, NextProfileAfterADirectCommandReApproachesTheCompensatedPath) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    DirectCommand ja;
    ja.code = DirectCode::kJA;
    ja.axes = 0x03;
    ja.target = xyz(0, -5);
    ASSERT_EQ(board.direct(ja).status, Status::kOk);
    spool_ok(line(2, 10, -5));
    run();
    const auto segs = segments();
    ASSERT_GE(segs.size(), 2u);
    EXPECT_EQ(segs[1].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[1].tag, 2u);
    expect_at(segs[1].start, 0, -5);
    expect_at(segs[1].end, 0, -4);
}

TEST_F(Spooler, JsNamingAxesIsRefusedAndChangesNothing) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    const auto fill = board.motion_status().fill;
    DirectCommand js;
    js.code = DirectCode::kJS;
    js.axes = 0x01;
    EXPECT_EQ(board.direct(js).status, Status::kInvalidValue);
    EXPECT_TRUE(prof_marked());
    EXPECT_EQ(board.motion_status().fill, fill);
}

TEST_F(Spooler, BadJaIsRefusedAndChangesNothing) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    const auto fill = board.motion_status().fill;
    DirectCommand ja;
    ja.code = DirectCode::kJA;
    EXPECT_EQ(board.direct(ja).status, Status::kInvalidValue) << "no axis named";
    ja.axes = 0x01;
    ja.target[0] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(board.direct(ja).status, Status::kInvalidValue);
    ja.target[0] = 1.0;
    ja.feed = -1.0;
    EXPECT_EQ(board.direct(ja).status, Status::kValueTooLow);
    ja.feed = 0.0;
    ja.code = static_cast<DirectCode>(9);
    EXPECT_EQ(board.direct(ja).status, Status::kInvalidValue) << "unknown direct command";
    EXPECT_TRUE(prof_marked());
    EXPECT_EQ(board.motion_status().fill, fill);
}

// ---- JOG / G00 ([APCI-TC] section 2.4; section 1: only G01/G02/G03 compensated)

TEST_F(Spooler, RapidMakesCompensationIneffectiveAndTheNextProfileReApproaches) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    spool_ok(rapid(2, 20, 20));
    EXPECT_FALSE(prof_marked()) << "the rapid released the held profile";
    EXPECT_TRUE(running());
    spool_ok(line(3, 30, 20));
    EXPECT_TRUE(prof_marked());
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 4u);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);
    expect_at(segs[1].end, 10, 1);  // untrimmed offset end, no departure
    EXPECT_EQ(segs[2].role, SegmentRole::kRapid);
    EXPECT_EQ(segs[2].tag, 2u);
    expect_at(segs[2].start, 10, 1);
    EXPECT_EQ(segs[2].end, xyz(20, 20)) << "the rapid itself is not compensated";
    EXPECT_EQ(segs[3].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[3].tag, 3u);
    expect_at(segs[3].end, 20, 21);
}

// Design (docs/motion.md section 4): a traverse (a G00 under G41/G42 in NC programs) is
// compensated as a G01 at the rapid feed, the contour goes on through it, and every segment of
// its element is marked as a traverse; the G01 before and after it are not.
TEST_F(Spooler, TraverseIsCompensatedAsALineAtTheRapidFeedAndMarked) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    Profile t = line(2, 10, 20, 0.0);
    t.kind = ProfileKind::kTraverse;
    spool_ok(t);
    EXPECT_TRUE(prof_marked()) << "the traverse is held as a G01 is";
    spool_ok(line(3, 30, 20));
    ASSERT_EQ(deactivate(), Status::kOk);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 6u);
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);  // N1, (0,1) to (9,1): an inside corner
    expect_at(segs[1].end, 9, 1);
    EXPECT_FALSE(segs[1].traverse);
    EXPECT_EQ(segs[2].tag, 2u);
    EXPECT_EQ(segs[2].role, SegmentRole::kContour);  // N2 on its offset, x = 10 - 1
    expect_at(segs[2].start, 9, 1);
    expect_at(segs[2].end, 9, 20);
    EXPECT_EQ(segs[2].feed, rwmos::motion::kDefaultRapidFeed);
    EXPECT_TRUE(segs[2].traverse);
    EXPECT_EQ(segs[3].tag, 2u);  // the outside corner's transition belongs to the traverse
    EXPECT_EQ(segs[3].role, SegmentRole::kTransition);
    EXPECT_TRUE(segs[3].traverse);
    EXPECT_EQ(segs[4].tag, 3u);
    EXPECT_EQ(segs[4].role, SegmentRole::kContour);
    EXPECT_FALSE(segs[4].traverse);
    expect_at(segs[4].end, 30, 21);
}

// A traverse without compensation runs straight to its end at the rapid feed, still marked.
TEST_F(Spooler, TraverseWithoutCompensationIsAStraightRapidMove) {
    Profile t = line(5, 10, 20, 0.0);
    t.kind = ProfileKind::kTraverse;
    spool_ok(t);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 1u);
    EXPECT_EQ(segs[0].role, SegmentRole::kUncompensated);
    EXPECT_EQ(segs[0].end, xyz(10, 20));
    EXPECT_EQ(segs[0].feed, rwmos::motion::kDefaultRapidFeed);
    EXPECT_TRUE(segs[0].traverse);
}

// Kinds beyond the traverse (4) are refused; the traverse alone may go without a feed.
TEST_F(Spooler, ProfileKindAboveTheTraverseIsRefused) {
    Profile p = line(1, 10, 0, 600.0);
    p.kind = static_cast<ProfileKind>(5);
    EXPECT_EQ(board.spool(p).status, Status::kInvalidValue);
    Profile g1 = line(1, 10, 0, 0.0);
    EXPECT_EQ(board.spool(g1).status, Status::kValueTooLow);
}

// Design (docs/motion.md section 4): a profile while another group is active does not continue
// the contour under way. The held profile is spooled to its offset end without departure, and
// the new active group's first profile approaches its own compensated path.
TEST_F(Spooler, ChangeOfTheActiveGroupEndsTheContourAndTheNewGroupApproaches) {
    setup_group(1.0);  // group 1: X0 Y1 Z2, left, radius 1
    // Group 2 on axes 3/4/5 with the same radius and side (setup_group's RESET acts on every
    // group, so it is written here object by object).
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 2, tc::kSubXAxis, 3), Status::kOk);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 2, tc::kSubYAxis, 4), Status::kOk);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 2, tc::kSubZAxis, 5), Status::kOk);
    ASSERT_EQ(write_double(tc::kBus, tc::kDevGroups, 2, tc::kSubRadius, 1.0), Status::kOk);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 2, tc::kSubLeft, 0), Status::kOk);
    activate(1);
    activate(2);
    spool_ok(line(1, 10, 0));
    ASSERT_TRUE(prof_marked(1));
    ASSERT_EQ(board.motion_status().compensating_group, 1);
    // X/Y/Z-Axis-Nr name axes 3/4/5: TcPlane's plane is now group 2's.
    ASSERT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxAxisNr, tc::kSubX, 3), Status::kOk);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxAxisNr, tc::kSubY, 4), Status::kOk);
    ASSERT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxAxisNr, tc::kSubZ, 5), Status::kOk);
    Profile p;
    p.kind = ProfileKind::kLine;
    p.tag = 2;
    p.feed = 600.0;
    p.axes = 0x18;  // axes 3 and 4
    p.target[3] = 10.0;
    spool_ok(p);
    EXPECT_FALSE(prof_marked(1)) << "group 1's held profile was spooled";
    EXPECT_TRUE(running(1)) << "group 1 still runs; it is only no longer the active group";
    EXPECT_TRUE(prof_marked(2));
    EXPECT_EQ(board.motion_status().compensating_group, 2);
    EXPECT_EQ(error(1), 0);
    EXPECT_EQ(error(2), 0);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 3u) << "approach 1, contour 1 (no departure), approach 2";
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);
    EXPECT_EQ(segs[1].tag, 1u);
    expect_at(segs[1].end, 10, 1);  // group 1's offset end: the tool does not leave the path
    EXPECT_EQ(segs[2].role, SegmentRole::kApproach);
    EXPECT_EQ(segs[2].tag, 2u);
    EXPECT_EQ(segs[2].start[3], 0.0);
    EXPECT_EQ(segs[2].start[4], 0.0);
    EXPECT_NEAR(segs[2].end[3], 0.0, kEps);
    EXPECT_NEAR(segs[2].end[4], 1.0, kEps);  // onto group 2's path, left of +axis 3
    // Axes outside group 2's plane go to the element's start (docs/motion.md section 5): group
    // 1's axes to their programmed position, which group 1 no longer compensates.
    expect_at(segs[2].end, 10, 0);
    ASSERT_EQ(deactivate(2), Status::kOk);
    run();
    const auto rest = segments();
    ASSERT_EQ(rest.size(), 2u);
    EXPECT_EQ(rest[0].role, SegmentRole::kContour);
    EXPECT_NEAR(rest[0].end[3], 10.0, kEps);
    EXPECT_NEAR(rest[0].end[4], 1.0, kEps);
    EXPECT_EQ(rest[1].role, SegmentRole::kDeparture);
    EXPECT_NEAR(rest[1].end[4], 0.0, kEps);
}

TEST_F(Spooler, RapidWithoutFeedRunsAtTheDefaultRapidFeed) {
    // 60 units at 60000 units/min and 1 ms cycles: 1 unit per cycle.
    spool_ok(rapid(1, 60, 0));
    EXPECT_EQ(board.run_until_idle(1'000'000), 60u);
}

// ---- Feed and clock

TEST_F(Spooler, FeedIsInterpolationUnitsPerMinute) {
    spool_ok(line(1, 10, 0, 600.0));  // 10 units/s, 1 ms cycles
    EXPECT_EQ(board.run_until_idle(1'000'000), 1000u);
    EXPECT_EQ(position(), xyz(10, 0));
}

TEST_F(Spooler, InterpolationCycleObjectSetsTheCycleLength) {
    ASSERT_EQ(
        write_int(board_obj::kBus, board_obj::kDevice, board_obj::kIdxInterpolationCycle, 0, 2000),
        Status::kOk);
    spool_ok(line(1, 10, 0, 600.0));
    EXPECT_EQ(board.run_until_idle(1'000'000), 500u);
}

TEST_F(Spooler, StepAdvancesVirtualTimeByExactlyTheCyclesAsked) {
    spool_ok(line(1, 10, 0, 600.0));
    board.step(250);
    EXPECT_EQ(board.motion_status().now, 250u);
    EXPECT_DOUBLE_EQ(position()[0], 2.5);
    board.step(5000);
    EXPECT_EQ(board.motion_status().now, 5250u);
    EXPECT_TRUE(board.motion_status().idle);
}

TEST_F(Spooler, SpoolerFillAndPositionObjectsShowTheMotion) {
    spool_ok(line(1, 1, 0));
    spool_ok(line(2, 1, 1));
    spool_ok(line(3, 0, 1));
    EXPECT_EQ(read_int(board_obj::kBus, board_obj::kDevice, board_obj::kIdxSpoolerFill, 0), 3);
    board.step(50);
    EXPECT_DOUBLE_EQ(
        read_double(board_obj::kBus, board_obj::kDevice, board_obj::kIdxAxisPosition, 0), 0.5);
    run();
    EXPECT_EQ(read_int(board_obj::kBus, board_obj::kDevice, board_obj::kIdxSpoolerFill, 0), 0);
    EXPECT_DOUBLE_EQ(
        read_double(board_obj::kBus, board_obj::kDevice, board_obj::kIdxAxisPosition, 1), 1.0);
}

TEST_F(Spooler, UnnamedAxesKeepTheirProgrammedPosition) {
    spool_ok(line3(1, 1, 2, 3));
    Profile only_x = line(2, 5, 0);
    only_x.axes = 0x01;
    spool_ok(only_x);
    run();
    EXPECT_EQ(position(), xyz(5, 2, 3));
}

// ---- A full spooler (busy, nothing dropped)

TEST_F(Spooler, FullSpoolerAnswersBusyAndDropsNoProfile) {
    const std::uint32_t capacity = board.motion_status().capacity;
    ASSERT_GT(capacity, 0u);
    for (std::uint32_t i = 1; i <= capacity; ++i) spool_ok(line(i, 0.1 * i, 0));
    EXPECT_EQ(board.motion_status().fill, capacity);
    const MotionResult busy = board.spool(line(capacity + 1, 0.1 * (capacity + 1), 0));
    EXPECT_EQ(busy.status, Status::kBusy);
    EXPECT_EQ(board.motion_status().fill, capacity);
    board.step(10);  // the first 0.1-unit line takes 10 cycles
    spool_ok(line(capacity + 1, 0.1 * (capacity + 1), 0));
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), capacity + 1);
    for (std::uint32_t i = 0; i < segs.size(); ++i) EXPECT_EQ(segs[i].tag, i + 1);
    EXPECT_NEAR(position()[0], 0.1 * (capacity + 1), kEps);
}

// Zero-length moves take no cycle, however many: a spooler full of them empties when the clock
// runs although no cycle passes, and the clock stands where it was.
TEST_F(Spooler, ASpoolerFullOfZeroLengthMovesEmptiesWithoutACycle) {
    spool_ok(line(1, 1, 0));  // 1 unit at 600/min: 100 cycles
    run();
    const std::uint64_t start = board.motion_status().now;
    ASSERT_EQ(start, 100u);
    const std::uint32_t capacity = board.motion_status().capacity;
    for (int round = 0; round < 3; ++round) {
        for (std::uint32_t i = 0; i < capacity; ++i) spool_ok(line(2 + i, 1, 0));
        EXPECT_EQ(board.spool(line(2 + capacity, 1, 0)).status, Status::kBusy);
        EXPECT_EQ(board.run_until_idle(1000), 0u);
        const auto st = board.motion_status();
        EXPECT_EQ(st.fill, 0u);
        EXPECT_TRUE(st.idle);
        EXPECT_EQ(st.now, start);
    }
    // Stepping consumes them too, and the cycle stepped is an idle one.
    for (std::uint32_t i = 0; i < capacity; ++i) spool_ok(line(2 + i, 1, 0));
    board.step(1);
    EXPECT_EQ(board.motion_status().fill, 0u);
    EXPECT_EQ(board.motion_status().now, start + 1);
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 1 + 4 * std::size_t{capacity});
    for (std::size_t i = 1; i < segs.size(); ++i) {
        EXPECT_EQ(segs[i].start_cycle, start);
        EXPECT_EQ(segs[i].end_cycle, start);
        expect_at(segs[i].start, 1, 0);
        expect_at(segs[i].end, 1, 0);
    }
    expect_at(position(), 1, 0);
}

TEST_F(Spooler, BusyWhileCompensatingLeavesTheHeldProfileAsItWas) {
    // Two boards get the same program; one of them is made to refuse a
    // profile with Busy first. Both must execute the same path.
    auto program = [](Rig& b, bool provoke_busy) {
        b.setup_group(1.0);
        b.activate();
        b.spool_ok(line(1, 10, 0));
        if (provoke_busy) {
            // A queue exactly full: the next profile's moves do not fit.
            b.board.state().spooler.capacity =
                static_cast<std::int32_t>(b.board.motion_status().fill);
            EXPECT_EQ(b.board.spool(line(2, 10, -10)).status, Status::kBusy);
            EXPECT_TRUE(b.prof_marked());
            b.board.state().spooler.capacity = rwmos::kSpoolerCapacity;
        }
        b.spool_ok(line(2, 10, -10));
        b.spool_ok(line(3, 0, -10));
        EXPECT_EQ(b.deactivate(), Status::kOk);
        b.run();
    };
    Rig plain, refused;
    program(plain, false);
    program(refused, true);
    const auto a = plain.segments();
    const auto b = refused.segments();
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].tag, b[i].tag);
        EXPECT_EQ(a[i].role, b[i].role);
        EXPECT_EQ(a[i].end, b[i].end);
    }
}

TEST_F(Spooler, AProfileRefusedAfterItsCallEndedTheContourLeavesTheHeldProfileAsItWas) {
    // The radius changed while a profile is held: the next profile's call ends the contour
    // (the held profile's departure) and begins another, whose first element the compensator
    // refuses (an arc whose centre is not as far from its end as from its start). The call
    // takes nothing: the held profile is still held, nothing was added to the queue.
    using namespace rwmos::tc;
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_TRUE(prof_marked());
    const std::uint32_t fill = board.motion_status().fill;
    ASSERT_EQ(write_double(kBus, kDevGroups, 1, kSubRadius, 2.0), Status::kOk);
    const MotionResult r = board.spool(arc(2, true, 20, 10, 10, 3));
    EXPECT_NE(r.status, Status::kOk);
    EXPECT_TRUE(prof_marked()) << "the held profile is still held";
    EXPECT_EQ(board.motion_status().fill, fill);
}

// ---- Bad profiles: refused with a named reason, nothing changes

TEST_F(Spooler, BadProfilesAreRefusedAndChangeNothing) {
    spool_ok(line(1, 1, 1));
    const auto before = board.motion_status();
    struct Case {
        const char* what;
        Profile p;
        Status want;
    };
    auto with = [](auto change) {
        Profile p = arc(9, true, 2, 2, 1, 2);
        change(p);
        return p;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const Case cases[] = {
        {"unknown kind (above the traverse, 4)",
         with([](Profile& p) { p.kind = static_cast<ProfileKind>(5); }),
         Status::kInvalidValue},
        {"feed NaN", with([&](Profile& p) { p.feed = nan; }), Status::kInvalidValue},
        {"feed negative", with([](Profile& p) { p.feed = -1; }), Status::kValueTooLow},
        {"G02 without feed", with([](Profile& p) { p.feed = 0; }), Status::kValueTooLow},
        {"feed too high", with([](Profile& p) { p.feed = 2e9; }), Status::kValueTooHigh},
        {"target too high", with([](Profile& p) { p.target[1] = 1e6; }), Status::kValueTooHigh},
        {"target too low", with([](Profile& p) { p.target[0] = -1e6; }), Status::kValueTooLow},
        {"target infinite", with([&](Profile& p) { p.target[0] = inf; }), Status::kInvalidValue},
        {"arc axes equal", with([](Profile& p) {
             p.arc_axes = {1, 1};
         }),
         Status::kInvalidValue},
        {"arc axis 8", with([](Profile& p) {
             p.arc_axes = {0, 8};
         }),
         Status::kValueTooHigh},
        {"arc centre NaN", with([&](Profile& p) { p.center[0] = nan; }), Status::kInvalidValue},
        {"arc end not on the circle", with([](Profile& p) {
             p.center = {1.5, 1.0};
         }),
         Status::kInvalidValue},
    };
    for (const Case& c : cases) {
        const MotionResult r = board.spool(c.p);
        EXPECT_EQ(r.status, c.want) << c.what;
        EXPECT_FALSE(r.message.empty()) << c.what;
        const auto now = board.motion_status();
        EXPECT_EQ(now.fill, before.fill) << c.what;
        EXPECT_EQ(now.held, false) << c.what;
    }
    run();
    EXPECT_EQ(position(), xyz(1, 1)) << "only the good profile moved";
    EXPECT_EQ(segments().size(), 1u);
}

// ---- Reset objects drop the held profile

TEST_F(Spooler, ResetClearsTheHeldProfile) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_TRUE(prof_marked());
    ASSERT_EQ(write_int(tc::kBus, tc::kDevInit, tc::kIdxReset, 0, 0), Status::kOk);
    EXPECT_FALSE(prof_marked());
    EXPECT_FALSE(running());
    EXPECT_EQ(board.motion_status().compensating_group, 0);
    run();
    const auto segs = segments();
    ASSERT_EQ(segs.size(), 1u) << "only the approach ran; the held profile is gone";
    EXPECT_EQ(segs[0].role, SegmentRole::kApproach);
}

TEST_F(Spooler, GroupResetDiscardsTheHeldProfile) {
    setup_group(1.0);
    activate();
    spool_ok(line(1, 10, 0));
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubReset, 0), Status::kOk);
    EXPECT_FALSE(prof_marked());
    EXPECT_EQ(board.motion_status().compensating_group, 0);
}

// ---- The limit on one move's duration (kMaxMoveCycles): refused, not cut short

TEST_F(Spooler, AMoveLongerThanTheCycleLimitIsRefusedAndChangesNothing) {
    spool_ok(line(1, 1, 0));
    const auto before = board.motion_status();
    // 1 unit at 1e-6 units/min: 6e10 cycles of 1 ms (it ran capped at 2^52 cycles).
    MotionResult r = board.spool(line(2, 2, 0, 1e-6));
    EXPECT_EQ(r.status, Status::kValueTooLow);
    EXPECT_NE(r.message.find("raise the feed"), std::string_view::npos) << r.message;
    // Arcs and rapids with a feed are measured too.
    EXPECT_EQ(board.spool(arc(3, true, 1, 0, 1, 1, 1e-9)).status, Status::kValueTooLow);
    Profile rapid = line(4, 5, 0, 1e-7);
    rapid.kind = ProfileKind::kRapid;
    EXPECT_EQ(board.spool(rapid).status, Status::kValueTooLow);
    EXPECT_EQ(board.motion_status().fill, before.fill);
    run();
    EXPECT_EQ(position(), xyz(1, 0)) << "only the good profile moved";
}

TEST_F(Spooler, AMoveWithinTheCycleLimitRunsItsExactCycleCount) {
    // 1 unit at 7e-5 units/min: 857142858 cycles of 1 ms, below 10^9; analytic, so fast.
    spool_ok(line(1, 1, 0, 7e-5));
    const std::uint64_t ran = board.run_until_idle(rwmos::motion::kMaxMoveCycles);
    EXPECT_EQ(ran, rwmos::motion::cycles_for(1.0, 7e-5, 0.001));
    EXPECT_NEAR(static_cast<double>(ran), 857142858.0, 1.0);
    EXPECT_EQ(position(), xyz(1, 0));
}

TEST_F(Spooler, TheCycleLimitIsCountedInTheBoardsInterpolationCycle) {
    // 1 unit at 5e-5 units/min: 1.2e9 cycles of 1 ms (refused), 1.2e8 of 10 ms (taken).
    EXPECT_EQ(board.spool(line(1, 1, 0, 5e-5)).status, Status::kValueTooLow);
    ASSERT_EQ(
        write_int(board_obj::kBus, board_obj::kDevice, board_obj::kIdxInterpolationCycle, 0, 10000),
        Status::kOk);
    spool_ok(line(1, 1, 0, 5e-5));
    const std::uint64_t ran = board.run_until_idle(rwmos::motion::kMaxMoveCycles);
    EXPECT_EQ(ran, rwmos::motion::cycles_for(1.0, 5e-5, 0.01));
    EXPECT_NEAR(static_cast<double>(ran), 1.2e8, 1.0);
}

TEST_F(Spooler, AJogLongerThanTheCycleLimitIsRefusedAndKeepsTheQueue) {
    spool_ok(line(1, 10, 0));
    const auto fill = board.motion_status().fill;
    DirectCommand ja;
    ja.code = DirectCode::kJA;
    ja.axes = 0x01;
    ja.target[0] = 1.0;
    ja.feed = 1e-9;
    EXPECT_EQ(board.direct(ja).status, Status::kValueTooLow);
    EXPECT_EQ(board.motion_status().fill, fill) << "a refused jog discards nothing";
}

}  // namespace
