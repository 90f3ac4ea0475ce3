// SPDX-License-Identifier: MIT
#include "apci/nc/interpreter.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <bit>
#include <cmath>
#include <iterator>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>

#include "apci/nc/arc.h"
#include "apci/nc/parser.h"
#include "apci/nc/tools.h"
#include "nc_test_util.h"
#include "rng.h"
#include "rwmos/geometry/offset.h"
#include "rwmos/geometry/shared.h"

namespace apci::nc {
namespace {

using test::error_of;
using test::undefined_of;
using test::events_of;
using test::only;

using V = Eigen::Vector3d;

void expect_near(const V& got, const V& want, const char* what = "") {
    EXPECT_NEAR((got - want).norm(), 0.0, 1e-9)
        << what << ": got " << got.transpose() << ", want " << want.transpose();
}

ArcMove single_arc(std::string_view text) {
    const auto arcs = only<ArcMove>(events_of(text));
    EXPECT_EQ(arcs.size(), 1U) << text;
    return arcs.empty() ? ArcMove{} : arcs.front();
}

TEST(Interpreter, MotionModeIsModal) {
    const auto ev = events_of("G1 X1 F100\nY2\nG0 X5\nZ1\nM30\n");
    const auto lines = only<LineMove>(ev);
    const auto rapids = only<RapidMove>(ev);
    ASSERT_EQ(lines.size(), 2U);
    ASSERT_EQ(rapids.size(), 2U);
    expect_near(lines[1].end, V(1, 2, 0));
    expect_near(rapids[1].end, V(5, 2, 1));
}

TEST(Interpreter, MoveStartsWhereThePreviousEnded) {
    const auto lines = only<LineMove>(events_of("G1 X1 F100\nY2\nX3 Y4 Z5\nM30"));
    ASSERT_EQ(lines.size(), 3U);
    expect_near(lines[0].start, V(0, 0, 0));
    expect_near(lines[1].start, V(1, 0, 0));
    expect_near(lines[2].start, V(1, 2, 0));
    expect_near(lines[2].end, V(3, 4, 5));
}

TEST(Interpreter, FeedIsModalAndCarriedByMoves) {
    const auto ev = events_of("G1 X1 F100\nX2\nX3 F250\nG2 X5 I1 \nM30");
    const auto lines = only<LineMove>(ev);
    ASSERT_EQ(lines.size(), 3U);
    EXPECT_EQ(lines[0].feed, 100.0);
    EXPECT_EQ(lines[1].feed, 100.0);
    EXPECT_EQ(lines[2].feed, 250.0);
    EXPECT_EQ(only<ArcMove>(ev).at(0).feed, 250.0);
}

TEST(Interpreter, RapidNeedsNoFeed) {
    EXPECT_EQ(only<RapidMove>(events_of("G0 X1\nM30")).size(), 1U);
}

TEST(Interpreter, NoFeedBeforeFirstFeedMoveIsError) {
    EXPECT_EQ(error_of("N10 G1 X1\nM30"),
              "prog.nc:1:8: N10: no feed rate: program F before the first G1 move");
    EXPECT_EQ(error_of("G0 X1\nG2 X2 I.5\nM30"),
              "prog.nc:2:4: no feed rate: program F before the first G2 move");
}

TEST(Interpreter, NoMotionModeBeforeFirstMoveIsError) {
    EXPECT_EQ(error_of("F100\nN20 X1\nM30"),
              "prog.nc:2:5: N20: no motion mode: program G0, G1, G2 or G3 before the first move");
}

TEST(Interpreter, AbsoluteAndIncrementalDistance) {
    const auto rapids = only<RapidMove>(events_of("G90 G0 X10 Y10\nG91 X5 Y-5\nZ2\nG90 X1\nM30"));
    ASSERT_EQ(rapids.size(), 4U);
    expect_near(rapids[0].end, V(10, 10, 0));
    expect_near(rapids[1].end, V(15, 5, 0));
    expect_near(rapids[2].end, V(15, 5, 2));
    expect_near(rapids[3].end, V(1, 5, 2));
}

TEST(Interpreter, DistanceModeDefaultsToAbsolute) {
    const auto rapids = only<RapidMove>(events_of("G0 X10\nX10\nM30"));
    expect_near(rapids[1].end, V(10, 0, 0));
}

TEST(Interpreter, StartPositionOption) {
    InterpreterOptions o;
    o.start_position = V(1, 2, 3);
    const auto lines = only<LineMove>(events_of("G91 G1 X1 F10\nM30", o));
    ASSERT_EQ(lines.size(), 1U);
    expect_near(lines[0].start, V(1, 2, 3));
    expect_near(lines[0].end, V(2, 2, 3));
}

TEST(Interpreter, CenterWordsAreIncrementalFromStartInG90) {
    const ArcMove a = single_arc("G0 X10 Y5\nG2 X20 Y5 I5 J0 F100\nM30");
    expect_near(a.start, V(10, 5, 0));
    expect_near(a.end, V(20, 5, 0));
    expect_near(a.center, V(15, 5, 0));
    EXPECT_FALSE(a.ccw);
    EXPECT_EQ(a.plane, Plane::kXY);
}

TEST(Interpreter, CenterWordsAreIncrementalFromStartInG91) {
    const ArcMove a = single_arc("G0 X10 Y5\nG91 G3 X10 I5 F100\nM30");
    expect_near(a.end, V(20, 5, 0));
    expect_near(a.center, V(15, 5, 0));
    EXPECT_TRUE(a.ccw);
}

TEST(Interpreter, ArcWithIJInG17) {
    const ArcMove q = single_arc("G0 X10\nG17 G3 X0 Y10 I-10 J0 F100\nM30");
    expect_near(q.center, V(0, 0, 0));
    EXPECT_TRUE(q.ccw);
    EXPECT_EQ(q.plane, Plane::kXY);
}

TEST(Interpreter, ArcWithKIInG18) {
    const ArcMove a = single_arc("G18\nG0 Z10\nG2 Z0 X10 K-10 F100\nM30");
    expect_near(a.start, V(0, 0, 10));
    expect_near(a.end, V(10, 0, 0));
    expect_near(a.center, V(0, 0, 0));
    EXPECT_EQ(a.plane, Plane::kZX);
    EXPECT_FALSE(a.ccw);
}

TEST(Interpreter, ArcWithJKInG19) {
    const ArcMove a = single_arc("G19\nG0 Y10\nG3 Y0 Z10 J-10 F100\nM30");
    expect_near(a.center, V(0, 0, 0));
    expect_near(a.end, V(0, 0, 10));
    EXPECT_EQ(a.plane, Plane::kYZ);
    EXPECT_TRUE(a.ccw);
}

TEST(Interpreter, CenterWordOfTheWrongPlaneIsError) {
    EXPECT_EQ(error_of("G17 G2 X1 K1 F1\nM30"),
              "prog.nc:1:11: K is not a centre word in the G17 plane (use I and J)");
    EXPECT_EQ(error_of("G18 G2 X1 J1 F1\nM30"),
              "prog.nc:1:11: J is not a centre word in the G18 plane (use K and I)");
    EXPECT_EQ(error_of("G19 G2 Y1 I1 F1\nM30"),
              "prog.nc:1:11: I is not a centre word in the G19 plane (use J and K)");
}

// R > 0: the shorter arc; R < 0: the longer one. From (0,0) to (10,0) with |R| = 10 the centre
// is (5, +-8.660): left of the chord for the shorter counter-clockwise arc.
TEST(Interpreter, RadiusArcSignSelectsShorterOrLongerArcInG17) {
    const double h = std::sqrt(75.0);
    expect_near(single_arc("G3 X10 R10 F1\nM30").center, V(5, h, 0), "G3 R10");
    expect_near(single_arc("G2 X10 R10 F1\nM30").center, V(5, -h, 0), "G2 R10");
    expect_near(single_arc("G3 X10 R-10 F1\nM30").center, V(5, -h, 0), "G3 R-10");
    expect_near(single_arc("G2 X10 R-10 F1\nM30").center, V(5, h, 0), "G2 R-10");
}

TEST(Interpreter, RadiusArcInG18) {
    const double h = std::sqrt(75.0);
    // Z-X plane: first axis Z, second X; "left" of a chord along +Z is +X.
    expect_near(single_arc("G18 G3 Z10 R10 F1\nM30").center, V(h, 0, 5), "G18 G3 R10");
    expect_near(single_arc("G18 G2 Z10 R10 F1\nM30").center, V(-h, 0, 5), "G18 G2 R10");
    expect_near(single_arc("G18 G3 Z10 R-10 F1\nM30").center, V(-h, 0, 5), "G18 G3 R-10");
}

TEST(Interpreter, RadiusArcInG19) {
    const double h = std::sqrt(75.0);
    // Y-Z plane: first axis Y, second Z; "left" of a chord along +Y is +Z.
    expect_near(single_arc("G19 G3 Y10 R10 F1\nM30").center, V(0, 5, h), "G19 G3 R10");
    expect_near(single_arc("G19 G2 Y10 R10 F1\nM30").center, V(0, 5, -h), "G19 G2 R10");
    expect_near(single_arc("G19 G2 Y10 R-10 F1\nM30").center, V(0, 5, h), "G19 G2 R-10");
}

TEST(Interpreter, RadiusArcCenterIsOnBothEndPoints) {
    // Every R arc's centre lies at |R| from start and end.
    for (const char* text : {"G0 X3 Y-2\nG2 X7 Y4 R-6 F1\nM30", "G0 X3 Y-2\nG3 X7 Y4 R6 F1\nM30"}) {
        const ArcMove a = single_arc(text);
        EXPECT_NEAR((a.center - a.start).norm(), 6.0, 1e-9) << text;
        EXPECT_NEAR((a.center - a.end).norm(), 6.0, 1e-9) << text;
    }
}

TEST(Interpreter, RadiusArcOverHalfCircleChordIsMidpoint) {
    expect_near(single_arc("G2 X20 R10 F1\nM30").center, V(10, 0, 0));
    // Within the tolerance, a chord a little longer than the diameter is a half circle.
    expect_near(single_arc("G2 X20.001 R10 F1\nM30").center, V(10.0005, 0, 0));
}

// R beyond 1e154 squares to infinity; the centre must still be the finite point
// R away from both ends (fuzzer nc, tests/fuzz/crashes/nc/). A program with such an arc is
// refused: its centre lies beyond the board's coordinate range.
TEST(Interpreter, RadiusTooLargeToSquareStillGivesItsFiniteCentre) {
    const double r = 1e200;
    const ArcCenterResult arc =
        arc_center_from_radius(V(0, 0, 0), V(20, 0, 0), r, false, Plane::kXY);
    ASSERT_TRUE(arc.ok) << arc.message;
    const Eigen::Vector3d c = arc.center;
    ASSERT_TRUE(c.allFinite()) << c.transpose();
    EXPECT_NEAR(c.x(), 10.0, 1e-9);
    EXPECT_NEAR(-c.y() / r, 1.0, 1e-12);  // G2, the shorter arc: centre right of the chord
    EXPECT_EQ(c.z(), 0.0);
    const std::string program = "G2 X20 R1" + std::string(200, '0') + " F1\nM30";
    EXPECT_EQ(error_of(program),
              "prog.nc:1:8: arc centre X 10.0000 Y -1e+200 mm is beyond the board's coordinate "
              "range of +-100000 mm");
}

TEST(Interpreter, RadiusArcImpossibleForChordIsError) {
    EXPECT_EQ(error_of("N10 G0 X0 Y0\nN20 G2 X20.01 R10 F100\nM30"),
              "prog.nc:2:15: N20: R arc impossible: the chord from start to end is 20.0100 mm long, "
              "more than the diameter 20.0000 mm of R10");
    const test::RunResult r = test::run("N10 G0 X0 Y0\nN20 G2 X20.01 R10 F100\nM30");
    ASSERT_TRUE(r.error);
    EXPECT_EQ(r.error->kind, ErrorKind::kGeometry);
    EXPECT_EQ(r.error->block, 20);
}

TEST(Interpreter, RadiusArcToItsStartIsError) {
    EXPECT_EQ(error_of("G2 Z5 R10 F1\nM30"),
              "prog.nc:1:7: R arc impossible: its end point equals the start point in the plane "
              "(program a full circle with I/J/K)");
}

TEST(Interpreter, CenterArcEndOffCircleIsError) {
    EXPECT_EQ(error_of("G2 X10 Y1 I5 F1\nM30"),
              "prog.nc:1:1: arc end point is not on the circle: radius 5.0000 mm at the start, "
              "5.0990 mm at the end (tolerance 0.003 mm)");
    // Within the tolerance it runs: the board's CenterError tolerance, 0.003 mm (three decimals
    // of rounding on start, end and centre make up to 0.0021 mm).
    EXPECT_EQ(error_of("G2 X10.0015 I5 F1\nM30"), "");
    EXPECT_EQ(error_of("G2 X10.0029 I5 F1\nM30"), "");
    EXPECT_NE(error_of("G2 X10.0031 I5 F1\nM30"), "");
}

// The front end refuses the arcs the board's TC module would refuse with CenterError, no more:
// the same tolerance, and on either side of it both answer alike.
TEST(Interpreter, ArcToleranceIsTheBoardsCenterErrorTolerance) {
    EXPECT_EQ(kArcRadiusTolerance, rwmos::geom::kCenterRadiusTolerance);
    for (const double part : {0.5, 0.99, 1.01, 2.0}) {
        const double d = part * kArcRadiusTolerance;
        const bool front_end_runs =
            check_arc_center(V(5, 0, 0), V(0, 5 + d, 0), V(0, 0, 0), Plane::kXY).empty();
        const rwmos::geom::Reason board =
            rwmos::geom::check_element(rwmos::geom::make_arc({5, 0}, {0, 5 + d}, {0, 0}, true));
        EXPECT_EQ(front_end_runs, part < 1.0) << "radii differ by " << d;
        EXPECT_EQ(board == rwmos::geom::Reason::kNone, part < 1.0) << "radii differ by " << d;
    }
}

TEST(Interpreter, CenterOnStartIsError) {
    EXPECT_EQ(error_of("G2 X0 I0 J0 F1\nM30"),
              "prog.nc:1:1: arc radius is 0: the centre (I/J/K) is the start point");
}

TEST(Interpreter, FullCircleWithCenterOnly) {
    const ArcMove a = single_arc("G0 X1 Y1\nG2 I5 F1\nM30");
    expect_near(a.start, V(1, 1, 0));
    expect_near(a.end, V(1, 1, 0));
    expect_near(a.center, V(6, 1, 0));
}

TEST(Interpreter, HelixKeepsCenterOnStartLevel) {
    const ArcMove a = single_arc("G0 Z2\nG3 X10 Z7 I5 F1\nM30");
    expect_near(a.end, V(10, 0, 7));
    expect_near(a.center, V(5, 0, 2));
}

TEST(Interpreter, ArcNeedsCenterOrRadius) {
    EXPECT_EQ(error_of("G2 X10 F1\nM30"),
              "prog.nc:1:4: G2 arc needs its centre (I J) or its radius (R)");
    EXPECT_EQ(error_of("G18 G3 X10 F1\nM30"),
              "prog.nc:1:8: G3 arc needs its centre (K I) or its radius (R)");
}

TEST(Interpreter, CenterOrRadiusWithoutArcIsError) {
    EXPECT_EQ(error_of("G1 X10 I5 F1\nM30"), "prog.nc:1:8: I belongs to arcs (G2/G3), not to G1");
    EXPECT_EQ(error_of("G0 X10 R5\nM30"), "prog.nc:1:8: R belongs to arcs (G2/G3), not to G0");
    const test::RunResult r = test::run("G1 X1 F1\nJ5\nM30");
    ASSERT_TRUE(r.error);
    EXPECT_EQ(r.error->kind, ErrorKind::kConflict);
}

TEST(Interpreter, ModalOnlyBlockMakesNoMove) {
    const auto ev = events_of("G2\nG1 F100\nM30");
    EXPECT_TRUE(only<LineMove>(ev).empty());
    EXPECT_TRUE(only<ArcMove>(ev).empty());
}

TEST(Interpreter, CompensationSideEventsOnChange) {
    const auto ev = events_of("G41\nG41\nG42\nG40\nG40\nM30");
    const auto comp = only<CompensationChange>(ev);
    ASSERT_EQ(comp.size(), 3U);
    EXPECT_EQ(comp[0].side, Compensation::kLeft);
    EXPECT_EQ(comp[1].side, Compensation::kRight);
    EXPECT_EQ(comp[2].side, Compensation::kOff);
}

TEST(Interpreter, CornerModeDefaultsToLinearAndEventsOnChange) {
    // G25 is the start state (the ISG kernel's modal default): a G25 first is no change.
    EXPECT_EQ(kStartCornerMode, CornerMode::kLinear);
    const auto ev = events_of("G25\nG26\nG26\nG25\nM30");
    const auto corner = only<CornerModeChange>(ev);
    ASSERT_EQ(corner.size(), 2U);
    EXPECT_EQ(corner[0].mode, CornerMode::kCircular);
    EXPECT_EQ(corner[1].mode, CornerMode::kLinear);
}

TEST(Interpreter, CdonIsTheStartAndCdofCdonAreEventsOnChangeBeforeTheMove) {
    // CDON is the start state: a CDON first is no change; the change comes before the block's
    // move (it holds for that move).
    const auto ev = events_of("CDON\nG0 X1 CDOF\nCDOF\nCDON\nM30");
    const auto walls = only<CollisionDetectionChange>(ev);
    ASSERT_EQ(walls.size(), 2U);
    EXPECT_FALSE(walls[0].on);
    EXPECT_TRUE(walls[1].on);
    std::size_t change = ev.size(), move = ev.size();
    for (std::size_t i = 0; i < ev.size(); ++i) {
        if (std::holds_alternative<CollisionDetectionChange>(ev[i].data) && change == ev.size())
            change = i;
        if (std::holds_alternative<RapidMove>(ev[i].data) && move == ev.size()) move = i;
    }
    EXPECT_LT(change, move);
}

TEST(Interpreter, G70TakesLengthsAndFeedInInchesUntilG71) {
    // [ISG-PROG]: G70 inch input, G71 metric (the initial state). Events are in mm.
    const auto ev = events_of(
        "G70 G1 X1 Y2 Z-0.5 F10\nG91 X1\nG90 G3 X3 Y3 I0 J1\nG2 X4 Y2 R1\nG71 G1 X100 F600\nM30");
    const auto lines = only<LineMove>(ev);
    ASSERT_EQ(lines.size(), 3U);
    EXPECT_EQ(lines[0].end, V(25.4, 50.8, -12.7));
    EXPECT_DOUBLE_EQ(lines[0].feed, 254.0);
    EXPECT_DOUBLE_EQ(lines[1].end.x(), 50.8);  // incremental inches too
    EXPECT_EQ(lines[2].end.x(), 100.0);        // G71: mm again
    EXPECT_DOUBLE_EQ(lines[2].feed, 600.0);
    const auto arcs = only<ArcMove>(ev);
    ASSERT_EQ(arcs.size(), 2U);
    EXPECT_DOUBLE_EQ(arcs[0].center.y(), 3 * 25.4);  // J1: one inch from the start
    EXPECT_DOUBLE_EQ(arcs[0].end.x(), 3 * 25.4);
    EXPECT_NEAR((arcs[1].center - arcs[1].start).norm(), 25.4, 1e-12);  // R1: one inch
    EXPECT_EQ(error_of("G70 G71 X1\nM30"),
              "prog.nc:1:5: G70 and G71 in one block: both set the input units");
}

TEST(Interpreter, PlaneDefaultsToG17AndEventsOnChange) {
    const auto planes = only<PlaneChange>(events_of("G17\nG18\nG18\nG19\nG17\nM30"));
    ASSERT_EQ(planes.size(), 3U);
    EXPECT_EQ(planes[0].plane, Plane::kZX);
    EXPECT_EQ(planes[1].plane, Plane::kYZ);
    EXPECT_EQ(planes[2].plane, Plane::kXY);
}

TEST(Interpreter, ToolSelectOnEveryDWord) {
    const auto tools = only<ToolSelect>(events_of("D1\nD1\nD0\nM30"));
    ASSERT_EQ(tools.size(), 3U);
    EXPECT_EQ(tools[0].tool, 1);
    EXPECT_EQ(tools[1].tool, 1);
    EXPECT_EQ(tools[2].tool, 0);
}

TEST(Interpreter, EventOrderWithinBlock) {
    // The corner mode comes after the block's move: it acts on the corners after it.
    const auto ev = events_of("N5 D1 G18 G26 G1 X1 F1\nN6 G42 G1 Z1 M30");
    ASSERT_EQ(ev.size(), 7U);
    EXPECT_EQ(event_name(ev[0].data), "tool");
    EXPECT_EQ(event_name(ev[1].data), "plane");
    EXPECT_EQ(event_name(ev[2].data), "line");
    EXPECT_EQ(event_name(ev[3].data), "corner");
    EXPECT_EQ(event_name(ev[4].data), "compensation");
    EXPECT_EQ(event_name(ev[5].data), "line");
    EXPECT_EQ(event_name(ev[6].data), "end");
    EXPECT_EQ(ev[0].origin.block, 5);
    EXPECT_EQ(ev[0].origin.line, 1U);
    EXPECT_EQ(ev[6].origin.block, 6);
    EXPECT_EQ(ev[6].origin.line, 2U);
}

TEST(Interpreter, BlockWithoutNumberHasNoBlockNumber) {
    const auto ev = events_of("G0 X1\nM30");
    EXPECT_EQ(ev[0].origin.block, kNoBlockNumber);
}

TEST(Interpreter, PlaneChangeWithCompensationOnIsError) {
    EXPECT_EQ(error_of("G41\nN20 G18\nM30"),
              "prog.nc:2:5: N20: G18 changes the plane while radius compensation is on: program G40 "
              "before changing the plane");
    EXPECT_EQ(error_of("G18 G42\nM30"),
              "prog.nc:1:1: G18 changes the plane while radius compensation is on: program G40 "
              "before changing the plane");
    // Repeating the active plane is no change.
    EXPECT_EQ(error_of("G41\nG17\nG40\nG18\nM30"), "");
}

TEST(Interpreter, ToolChangeWithCompensationOnIsError) {
    EXPECT_EQ(error_of("G42\nD2\nM30"),
              "prog.nc:2:1: D2 while radius compensation G42 is on: program G40 in an earlier "
              "block before selecting a tool");
    EXPECT_EQ(error_of("G42\nG40 D2\nM30").empty(), false);
    // Selecting the tool and switching compensation on in one block is allowed: the tool comes
    // first, as [APCI-TC] section 2.5 writes WKZINDEX before Left/Right and STATUS.
    EXPECT_EQ(error_of("D1 G41\nM30"), "");
}

TEST(Interpreter, CompensationSwitchInArcBlockIsError) {
    EXPECT_EQ(error_of("G0 X10\nG41 G2 X0 I-5 F1\nM30"),
              "prog.nc:2:1: G41 switched in an arc block: switch radius compensation with G0/G1 "
              "or in a block without a move");
    EXPECT_EQ(error_of("G0 X10\nG41 G1 X0 F1\nG2 X-10 I-5\nG40 G1 X-20\nM30"), "");
}

TEST(Interpreter, AnArcRightAfterALoneG40IsRefusedUnderG139) {
    // The move after a lone G40 departs from the compensated point (G139): an arc would not
    // start where it is programmed. A line first, or G237, and the arc runs.
    EXPECT_EQ(error_of("G0 X10\nG41 G1 X0 F1\nG40\nG2 X-10 I-5\nM30"),
              "prog.nc:4:1: G2 right after G40: under G139 this move departs from the compensated "
              "point, r beside the contour, not from the arc's programmed start; program a G1 (or "
              "G0) first, or G40 with G237");
    EXPECT_EQ(error_of("G0 X10\nG41 G1 X0 F1\nG40\nG1 X-1\nG2 X-11 I-5\nM30"), "");
    EXPECT_EQ(error_of("G237\nG0 X10\nG41 G1 X0 F1\nG40\nG2 X-10 I-5\nM30"), "");
}

// The selection word in the lone G40's own block decides ([ISG-PROG]: the method acts on the
// G40 of its block): G237 G40 departs at G40 itself, so an arc may follow; G139 G40 and G138 G40
// leave the departure to the next move, which must then be straight. Both ways round, from
// either method in force.
// G138, G139, G237 ([ISG-PROG]): modal, each a SelectionModeChange when it changes.
TEST(Interpreter, SelectionMethodsAreModalEvents) {
    const auto ev = events_of("G138\nG138 G0 X1\nG139\nG237\nM30");
    std::vector<int> modes;
    for (const Event& e : ev)
        if (const auto* m = std::get_if<SelectionModeChange>(&e.data)) modes.push_back(g_number(m->mode));
    EXPECT_EQ(modes, (std::vector<int>{138, 139, 237}));
}

TEST(Interpreter, ALoneG40TakesTheSelectionMethodOfItsOwnBlock) {
    EXPECT_EQ(error_of("G0 X10\nG41 G1 X0 F1\nG237 G40\nG2 X-10 I-5\nM30"), "");
    EXPECT_EQ(error_of("G138\nG0 X10\nG41 G1 X0 F1\nG237 G40\nG2 X-10 I-5\nM30"), "");
    EXPECT_EQ(error_of("G237\nG0 X10\nG41 G1 X0 F1\nG139 G40\nG2 X-10 I-5\nM30"),
              "prog.nc:5:1: G2 right after G40: under G139 this move departs from the compensated "
              "point, r beside the contour, not from the arc's programmed start; program a G1 (or "
              "G0) first, or G40 with G237");
    EXPECT_EQ(error_of("G237\nG0 X10\nG41 G1 X0 F1\nG138 G40\nG2 X-10 I-5\nM30"),
              "prog.nc:5:1: G2 right after G40: under G138 this move departs from the compensated "
              "point, r beside the contour, not from the arc's programmed start; program a G1 (or "
              "G0) first, or G40 with G237");
    // A selection word after the lone G40 changes nothing of its departure.
    EXPECT_NE(error_of("G0 X10\nG41 G1 X0 F1\nG40\nG237\nG2 X-10 I-5\nM30"), "");
}

TEST(Interpreter, ACoordinateBeyondTheBoardsRangeIsRefusedWithItsWord) {
    EXPECT_EQ(error_of("G1 X99999999999 F1\nM30"),
              "prog.nc:1:4: X 1e+11 mm is beyond the board's coordinate range of +-100000 mm");
    EXPECT_EQ(error_of("G91\nG0 Z60000\nG0 Z60000\nM30"),
              "prog.nc:3:4: Z 120000 mm is beyond the board's coordinate range of +-100000 mm");
    EXPECT_EQ(error_of("G0 X100000 Y-100000\nM30"), "");
}

// An arc's centre beyond the board's range passed validation, and the board refused the arc
// after the blocks before it had run; now it is refused with its I/J/K or R word before
// anything moves, as an end point is. At the limit it is taken.
TEST(Interpreter, AnArcCentreBeyondTheBoardsRangeIsRefusedWithItsWord) {
    // Centre (100000, 10), radius 14.1: the arc turns on the side away from the limit.
    EXPECT_EQ(error_of("G0 X99990 Y0\nG2 X99990 Y20 I10 J10 F100\nM30"), "");
    EXPECT_EQ(error_of("G0 X99990 Y0\nG2 X99990 Y20 I10.001 J10 F100\nM30"),
              "prog.nc:2:15: arc centre X 100000.0010 Y 10.0000 mm is beyond the board's "
              "coordinate range of +-100000 mm");
    EXPECT_EQ(error_of("G18\nG0 X0 Z-99990\nG3 X20 Z-99990 K-10.001 I10 F100\nM30"),
              "prog.nc:3:16: arc centre Z -100000.0010 X 10.0000 mm is beyond the board's "
              "coordinate range of +-100000 mm");
    // R: a centre 100000.99 mm off the chord.
    EXPECT_EQ(error_of("G2 X10 R100001 F100\nM30"),
              "prog.nc:1:8: arc centre X 5.0000 Y -100000.9999 mm is beyond the board's "
              "coordinate range of +-100000 mm");
    EXPECT_EQ(error_of("G2 X10 R99999 F100\nM30"), "");
}

// Its path too (start, end and centre within, the circle between them beyond): refused where
// it turns through an axis direction beyond the range, in either direction; at the limit taken.
TEST(Interpreter, AnArcWhosePathLeavesTheBoardsRangeIsRefused) {
    EXPECT_EQ(error_of("G2 I50000 F100\nM30"), "");  // a whole turn reaching X 100000
    EXPECT_EQ(error_of("G2 I50001 F100\nM30"),
              "prog.nc:1:4: the arc reaches X 100002.0000 mm (centre X 50001.0000 Y 0.0000, "
              "radius 50001.0000 mm), beyond the board's coordinate range of +-100000 mm");
    // Counter-clockwise from below the centre to above it turns through +X; clockwise, -X.
    EXPECT_EQ(error_of("G0 X99990 Y-10\nG3 X99990 Y10 J10 F100\nM30"), "");
    EXPECT_EQ(error_of("G0 X99991 Y-10\nG3 X99991 Y10 J10 F100\nM30"),
              "prog.nc:2:15: the arc reaches X 100001.0000 mm (centre X 99991.0000 Y 0.0000, "
              "radius 10.0000 mm), beyond the board's coordinate range of +-100000 mm");
    EXPECT_EQ(error_of("G0 X99991 Y-10\nG2 X99991 Y10 J10 F100\nM30"), "");
    EXPECT_EQ(error_of("G0 X-99991 Y-10\nG2 X-99991 Y10 J10 F100\nM30"),
              "prog.nc:2:16: the arc reaches X -100001.0000 mm (centre X -99991.0000 Y 0.0000, "
              "radius 10.0000 mm), beyond the board's coordinate range of +-100000 mm");
    EXPECT_EQ(error_of("G0 Y99991 X10\nG3 X-10 Y99991 I-10 F100\nM30"),
              "prog.nc:2:16: the arc reaches Y 100001.0000 mm (centre X 0.0000 Y 99991.0000, "
              "radius 10.0000 mm), beyond the board's coordinate range of +-100000 mm");
    // Exactly at the limit where the circle's bounding box is not (it passes +Y's limit, where
    // the arc does not turn): centre (99995, 99997), radius 5, counter-clockwise from (4, -3)
    // to (4, 3) about it through +X, reaching X 100000 and no more; one micrometre further, beyond.
    EXPECT_EQ(error_of("G0 X99999 Y99994\nG3 X99999 Y100000 I-4 J3 F100\nM30"), "");
    EXPECT_EQ(error_of("G0 X99999.001 Y99994\nG3 X99999.001 Y100000 I-4 J3 F100\nM30"),
              "prog.nc:2:23: the arc reaches X 100000.0010 mm (centre X 99995.0010 Y 99997.0000, "
              "radius 5.0000 mm), beyond the board's coordinate range of +-100000 mm");
}

// The range check counts an arc whose ends lie at most 1e-9 apart as a whole turn (as the board
// runs it): a circle about X 50001 reaches X 100002. One rounding step further apart, a
// clockwise arc turns only the chord's 2e-14 rad about X 0 and stays within; counter-clockwise
// it turns nearly the whole way and reaches +X.
TEST(Interpreter, TheRangeCheckTakesEndsWithinTheToleranceAsAWholeTurn) {
    for (const double gap : {1e-9, 0.5e-9, 0.0}) {
        for (const bool ccw : {false, true}) {
            ArcMove arc;
            arc.start = V(0, 0, 0);
            arc.end = V(0, gap, 0);
            arc.center = V(50001, 0, 0);
            arc.ccw = ccw;
            EXPECT_NE(check_arc_range(arc, kBoardCoordinateLimit), "") << gap << " " << ccw;
        }
    }
    ArcMove arc;
    arc.start = V(0, 0, 0);
    arc.end = V(0, std::nextafter(1e-9, 1.0), 0);
    arc.center = V(50001, 0, 0);
    arc.ccw = false;
    EXPECT_EQ(check_arc_range(arc, kBoardCoordinateLimit), "");
    arc.ccw = true;
    EXPECT_NE(check_arc_range(arc, kBoardCoordinateLimit), "");
}

TEST(Interpreter, ProgramEndEvent) {
    const auto ev = events_of("G0 X1 M30");
    ASSERT_EQ(ev.size(), 2U);
    EXPECT_EQ(event_name(ev[0].data), "rapid");
    EXPECT_EQ(event_name(ev[1].data), "end");
}

TEST(Interpreter, BlockAfterM30IsError) {
    EXPECT_EQ(error_of("M30\n\n; comment\n(c)\nG0 X1\n"),
              "prog.nc:5:1: block after M30: the program has already ended");
    EXPECT_EQ(error_of("M30\n\n; trailing comments are fine\n"), "");
}

TEST(Interpreter, ProgramWithoutM30IsError) {
    EXPECT_EQ(error_of("G0 X1\nG0 X2\n"), "prog.nc:2:1: the program ends without M30");
    // No block at all (an empty file, blank lines): nothing to run, said so.
    EXPECT_EQ(error_of(""),
              "prog.nc:1:1: the program has no blocks: nothing to run (a program's blocks end "
              "with M30)");
    EXPECT_EQ(error_of("\n\n"),
              "prog.nc:2:1: the program has no blocks: nothing to run (a program's blocks end "
              "with M30)");
    EXPECT_EQ(error_of("G17\n"), "prog.nc:1:1: the program ends without M30");
}

TEST(Interpreter, FailedBlockChangesNoState) {
    Interpreter in;
    EventBatch out;
    Diagnostic err;
    ParsedLine p;
    ASSERT_TRUE(parse_din_line("D1 G25 G1 X1 F100", 1, "p", p, err));
    ASSERT_TRUE(in.apply(p.block, "p", out, err)) << err.to_string();
    const ModalState before = in.state();
    // Good words (G42, F, G91, G18 ...) before a bad arc: nothing of it may stick.
    ASSERT_TRUE(parse_din_line("G91 G26 F5 G2 X100 R10", 2, "p", p, err));
    EXPECT_FALSE(in.apply(p.block, "p", out, err));
    EXPECT_EQ(err.kind, ErrorKind::kGeometry);
    EXPECT_TRUE(out.empty());
    const ModalState& after = in.state();
    EXPECT_EQ(after.motion, before.motion);
    EXPECT_EQ(after.distance, before.distance);
    EXPECT_EQ(after.corner, before.corner);
    EXPECT_EQ(after.feed, before.feed);
    EXPECT_EQ(after.tool, before.tool);
    EXPECT_EQ(after.position, before.position);
}

// A turning tool's cutting edge position (srk_lage 1..8, ISG P-TOOL-00002) is given in the
// turning plane: G41/G42 with it only in G18, as LinuxCNC ("G41 with lathe tool, but plane is
// not G18"); and only a turning tool (typ 1) has one. 0 and 9 (the nose centre) in any plane.
TEST(Interpreter, ATurningToolsCuttingEdgeCompensatesInG18Only) {
    Result<ToolTable> tools = parse_tool_table(
        "wz[2].gueltig 1\nwz[2].typ 1\nwz[2].radius 5\nwz[2].srk_lage 2\n"
        "wz[3].gueltig 1\nwz[3].typ 0\nwz[3].srk_lage 3\n"
        "wz[9].gueltig 1\nwz[9].typ 1\nwz[9].srk_lage 9\n",
        "t.tools");
    ASSERT_TRUE(tools) << tools.error().to_string();
    InterpreterOptions o;
    o.tools = &tools.value();
    EXPECT_EQ(error_of("D2\nG18\nG42 G1 X1 F100\nG40 X2\nM30", o), "");
    EXPECT_EQ(error_of("D2\nG42 G1 X1 F100\nM30", o),
              "prog.nc:2:1: G42 with the turning tool D2 (cutting edge position 2) in G17: the "
              "cutting edge position is given in the turning plane; program G18 (Z-X) before G42");
    EXPECT_EQ(error_of("D2\nG19\nG41\nM30", o),
              "prog.nc:3:1: G41 with the turning tool D2 (cutting edge position 2) in G19: the "
              "cutting edge position is given in the turning plane; program G18 (Z-X) before G41");
    EXPECT_EQ(error_of("D3\nG18\nG41\nM30", o),
              "prog.nc:3:1: G41 with D3: its cutting edge position (srk_lage 3) is a turning "
              "tool's, and D3 is type 0: set wz[3].typ 1 (P-TOOL-00001) or srk_lage 0");
    EXPECT_EQ(error_of("D9\nG41 G1 X1 F100\nG40 X2\nM30", o), "");
}

TEST(Interpreter, ToolTableRequiresDefinedValidTool) {
    Result<ToolTable> tools = parse_tool_table("wz[1].gueltig 1\nwz[2].radius 5\n", "t.tools");
    ASSERT_TRUE(tools) << tools.error().to_string();
    InterpreterOptions o;
    o.tools = &tools.value();
    EXPECT_EQ(error_of("D1\nD0\nM30", o), "");
    EXPECT_EQ(error_of("N7 D3\nM30", o),
              "prog.nc:1:4: N7: D3 selects tool 3, which the tool list does not define");
    EXPECT_EQ(error_of("D2\nM30", o),
              "prog.nc:1:1: D2 selects tool 2, which is not valid (wz[2].gueltig is 0, not 1; "
              "unset data is 0)");
    // Callers add what to give by the kind (apcictl run: "no --tools file given"): a tool the
    // list does not hold, not one it holds as not valid.
    EXPECT_EQ(undefined_of("N7 D3\nM30", o), Undefined::kTool);
    EXPECT_EQ(undefined_of("D2\nM30", o), Undefined::kNothing);
    EXPECT_EQ(undefined_of("D1\nM30", o), Undefined::kNothing);
    // Without a table any D is accepted.
    EXPECT_EQ(error_of("D3\nM30"), "");
}

TEST(ArcGeometry, PlaneAxesAreRightHanded) {
    for (Plane p : {Plane::kXY, Plane::kZX, Plane::kYZ}) {
        const PlaneAxes a = plane_axes(p);
        const V e1 = V::Unit(a.first), e2 = V::Unit(a.second), n = V::Unit(a.third);
        expect_near(e1.cross(e2), n);
    }
}

// ---- The plain-move path of Interpreter::apply against the general rule checks

std::uint64_t bits(double v) {
    return std::bit_cast<std::uint64_t>(v);
}

void expect_same_vector(const V& a, const V& b, const std::string& what) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(bits(a[k]), bits(b[k])) << what << " [" << k << "]";
}

// The same event, every field bit for bit.
void expect_same_event(const Event& a, const Event& b, const std::string& what) {
    EXPECT_EQ(a.origin.block, b.origin.block) << what;
    EXPECT_EQ(a.origin.line, b.origin.line) << what;
    ASSERT_EQ(a.data.index(), b.data.index()) << what;
    std::visit(
        [&](const auto& x) {
            using T = std::decay_t<decltype(x)>;
            const T& y = std::get<T>(b.data);
            if constexpr (std::is_same_v<T, RapidMove>) {
                expect_same_vector(x.start, y.start, what + " start");
                expect_same_vector(x.end, y.end, what + " end");
            } else if constexpr (std::is_same_v<T, LineMove>) {
                expect_same_vector(x.start, y.start, what + " start");
                expect_same_vector(x.end, y.end, what + " end");
                EXPECT_EQ(bits(x.feed), bits(y.feed)) << what;
            } else if constexpr (std::is_same_v<T, ArcMove>) {
                expect_same_vector(x.start, y.start, what + " start");
                expect_same_vector(x.end, y.end, what + " end");
                expect_same_vector(x.center, y.center, what + " center");
                EXPECT_EQ(x.ccw, y.ccw) << what;
                EXPECT_EQ(x.plane, y.plane) << what;
                EXPECT_EQ(bits(x.feed), bits(y.feed)) << what;
            } else if constexpr (std::is_same_v<T, ToolSelect>) {
                EXPECT_EQ(x.tool, y.tool) << what;
            } else if constexpr (std::is_same_v<T, CompensationChange>) {
                EXPECT_EQ(x.side, y.side) << what;
            } else if constexpr (std::is_same_v<T, CornerModeChange> ||
                                 std::is_same_v<T, SelectionModeChange>) {
                EXPECT_EQ(x.mode, y.mode) << what;
            } else if constexpr (std::is_same_v<T, PlaneChange>) {
                EXPECT_EQ(x.plane, y.plane) << what;
            } else if constexpr (std::is_same_v<T, CollisionDetectionChange>) {
                EXPECT_EQ(x.on, y.on) << what;
            } else if constexpr (std::is_same_v<T, HeadOrientation>) {
                EXPECT_EQ(bits(x.b), bits(y.b)) << what;
                EXPECT_EQ(bits(x.c), bits(y.c)) << what;
            } else if constexpr (!std::is_same_v<T, ProgramEnd>) {
                ADD_FAILURE() << what << ": a DIN block gave a " << event_name(a.data) << " event";
            }
        },
        a.data);
}

void expect_same_state(const ModalState& a, const ModalState& b, const std::string& what) {
    EXPECT_EQ(a.motion, b.motion) << what;
    EXPECT_EQ(a.plane, b.plane) << what;
    EXPECT_EQ(a.distance, b.distance) << what;
    EXPECT_EQ(a.compensation, b.compensation) << what;
    EXPECT_EQ(a.corner, b.corner) << what;
    EXPECT_EQ(a.selection, b.selection) << what;
    EXPECT_EQ(a.units, b.units) << what;
    EXPECT_EQ(bits(a.feed), bits(b.feed)) << what;
    EXPECT_EQ(a.tool, b.tool) << what;
    expect_same_vector(a.position, b.position, what + " position");
    EXPECT_EQ(bits(a.b), bits(b.b)) << what;
    EXPECT_EQ(a.ended, b.ended) << what;
    EXPECT_EQ(a.departure_pending, b.departure_pending) << what;
    EXPECT_EQ(a.tool_wear_const, b.tool_wear_const) << what;
}

// Random blocks, plain moves among every other kind of block (modal words, tools, R arcs, B,
// M30, coordinates beyond the board's range, arcs whose end is off the circle, feeds too slow
// for the move's cycles): apply() and apply_general() give the same result, error, events and
// state after every block.
TEST(Interpreter, RandomBlocksApplyAsTheGeneralRuleChecks) {
    apci::test::Rng rng(0x2545F4914F6CDD1DULL);
    auto next = [&rng]() { return rng.next(); };
    auto chance = [&next](unsigned percent) { return next() % 100 < percent; };
    auto real = [&next](double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(next() % 1000001) / 1e6;
    };
    int moves = 0;  // blocks whose only event is their move: the plain path's blocks among them
    int errors = 0;
    for (int program = 0; program < 300; ++program) {
        Interpreter fast;
        Interpreter general;
        EventBatch fast_out;
        EventBatch general_out;
        for (std::uint64_t line = 1; line <= 40; ++line) {
            Block b;
            b.clear(line);
            std::uint32_t col = 1;
            auto put = [&col](auto& word, auto value) {
                word.value = value;
                word.column = col;
                col += 4;
            };
            if (chance(30)) put(b.number, static_cast<std::int64_t>(line * 10));
            if (chance(40)) put(b.motion, static_cast<Motion>(next() % 4));
            const ModalState& st = general.state();
            const bool moving = chance(80);  // else a block of modal words only
            if (moving && chance(30)) {
                // An arc in the XY plane whose end lies on its circle, however the state reads.
                if (!b.motion.present())
                    put(b.motion, chance(50) ? Motion::kArcCw : Motion::kArcCcw);
                const double i = real(-5, 5), j = real(-5, 5), turn = real(0.1, 3);
                const double cx = st.position.x() + i, cy = st.position.y() + j;
                const double ex = cx + std::cos(turn) * -i - std::sin(turn) * -j;
                const double ey = cy + std::sin(turn) * -i + std::cos(turn) * -j;
                const bool incremental = st.distance == DistanceMode::kIncremental;
                put(b.axis[0], incremental ? ex - st.position.x() : ex);
                put(b.axis[1], incremental ? ey - st.position.y() : ey);
                put(b.center[0], i);
                put(b.center[1], j);
            } else if (moving) {
                for (std::size_t k = 0; k < 3; ++k) {
                    if (chance(45)) put(b.axis[k], chance(2) ? 2e5 : real(-50, 50));
                }
                for (std::size_t k = 0; k < 3; ++k) {
                    if (chance(8)) put(b.center[k], real(-5, 5));
                }
            }
            if (chance(20)) put(b.feed, chance(3) ? 1e-9 : real(1, 5000));
            // Every other word, now and then.
            if (chance(3)) put(b.plane, static_cast<Plane>(17 + next() % 3));
            if (chance(3))
                put(b.distance, chance(50) ? DistanceMode::kAbsolute : DistanceMode::kIncremental);
            if (chance(moving ? 4 : 30)) {
                put(b.compensation, static_cast<Compensation>(40 + next() % 3));
            }
            if (chance(3)) put(b.corner, chance(50) ? CornerMode::kLinear : CornerMode::kCircular);
            if (chance(3)) {
                put(b.selection,
                    chance(50) ? SelectionMode::kIndirect : SelectionMode::kPerpendicular);
            }
            if (chance(2)) put(b.units, chance(50) ? Units::kInch : Units::kMetric);
            if (chance(3)) put(b.tool, static_cast<int>(next() % 3));
            if (chance(3)) put(b.radius, real(-20, 20));
            if (chance(3)) put(b.b_axis, real(-30, 30));
            if (chance(1)) put(b.end_of_program, true);

            const std::string what = fmt::format("program {} line {}", program, line);
            Diagnostic fast_err;
            Diagnostic general_err;
            const bool fast_ok = fast.apply(b, "prog.nc", fast_out, fast_err);
            const bool general_ok = general.apply_general(b, "prog.nc", general_out, general_err);
            ASSERT_EQ(fast_ok, general_ok) << what << ": " << general_err.to_string();
            if (!fast_ok) {
                ++errors;
                EXPECT_EQ(fast_err.to_string(), general_err.to_string()) << what;
                EXPECT_EQ(fast_err.kind, general_err.kind) << what;
            } else {
                ASSERT_EQ(fast_out.size(), general_out.size()) << what;
                for (std::size_t e = 0; e < fast_out.size(); ++e)
                    expect_same_event(fast_out[e], general_out[e], what);
                if (fast_out.size() == 1 && !std::holds_alternative<ProgramEnd>(fast_out[0].data))
                    ++moves;
            }
            expect_same_state(fast.state(), general.state(), what);
            if (HasFatalFailure()) return;
        }
    }
    // Both kinds occur many times: moves that may take the plain path, and errors.
    EXPECT_GT(moves, 2000);
    EXPECT_GT(errors, 1000);
}

// arc_center_ok is check_arc_center's test without the message: the same answer for centres on
// and off the circle, at the start point, within and just beyond the tolerance, in every plane,
// and for values that are not finite.
TEST(Interpreter, ArcCenterOkAnswersAsCheckArcCenter) {
    apci::test::Rng rng(0x94D049BB133111EBULL);
    auto next = [&rng]() { return rng.next(); };
    auto real = [&next]() { return static_cast<double>(next() % 2001) / 100.0 - 10.0; };
    const double odd[] = {0.0,
                          kArcRadiusTolerance,
                          -kArcRadiusTolerance,
                          1e-12,
                          1e300,
                          std::numeric_limits<double>::infinity(),
                          std::numeric_limits<double>::quiet_NaN()};
    int fine = 0;
    int refused = 0;
    for (int i = 0; i < 20000; ++i) {
        const Plane plane = static_cast<Plane>(17 + next() % 3);
        const V start(real(), real(), real());
        V center = start + V(real(), real(), real());
        if (next() % 10 == 0) center = start;  // the centre on the start point
        // The end on the circle through the start, or off it by a little or a lot.
        const PlaneAxes a = plane_axes(plane);
        const double r =
            std::hypot(start[a.first] - center[a.first], start[a.second] - center[a.second]);
        const double turn = real();
        const double off = next() % 3 == 0 ? odd[next() % std::size(odd)] : 0.0;
        V end = center;
        end[a.first] += (r + off) * std::cos(turn);
        end[a.second] += (r + off) * std::sin(turn);
        end[a.third] = real();
        const bool ok = arc_center_ok(start, end, center, plane);
        EXPECT_EQ(ok, check_arc_center(start, end, center, plane).empty())
            << start.transpose() << " / " << end.transpose() << " / " << center.transpose();
        ++(ok ? fine : refused);
    }
    EXPECT_GT(fine, 1000);
    EXPECT_GT(refused, 1000);
}

}  // namespace
}  // namespace apci::nc
