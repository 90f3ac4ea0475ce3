// SPDX-License-Identifier: MIT
// The radii a CalcError names (exec::concave_arc_radii, run_context.h): the arc's and the
// tool's where the move at fault is an arc under compensation whose concave side is the tool's
// and which is smaller than the tool; nothing for anything else.
#include <gtest/gtest.h>

#include <cmath>

#include "run_context.h"

namespace apci::run::exec {
namespace {

// An arc in G17 from angle 0 to 90 degrees about the origin, radius r0 at its start and r1 at
// its end, counter-clockwise or not.
PathSegment arc(double r0, double r1, bool ccw) {
    PathSegment s;
    s.kind = SegmentKind::kArc;
    s.plane = 17;
    s.ccw = ccw;
    s.center = Point(0.0, 0.0, 0.0);
    s.start = Point(r0, 0.0, 0.0);
    s.end = ccw ? Point(0.0, r1, 0.0) : Point(0.0, -r1, 0.0);
    return s;
}

TcUnit::State compensating(int side, double radius) {
    TcUnit::State tc;
    tc.comp_on = true;
    tc.comp_plane = 17;
    tc.comp_side = side;
    tc.radius = radius;
    return tc;
}

TEST(CalcErrorRadii, AConcaveArcSmallerThanTheToolNamesBothRadii) {
    EXPECT_EQ(concave_arc_radii(arc(4.0, 4.0, true), compensating(1, 5.0)),
              "; arc radius 4.0000 mm, tool radius 5.0000 mm");  // G41 on a G3
    EXPECT_EQ(concave_arc_radii(arc(4.999, 4.999, false), compensating(-1, 5.0)),
              "; arc radius 4.9990 mm, tool radius 5.0000 mm");  // G42 on a G2
}

TEST(CalcErrorRadii, TheConvexSideNamesNothing) {
    EXPECT_EQ(concave_arc_radii(arc(4.0, 4.0, false), compensating(1, 5.0)), "");
    EXPECT_EQ(concave_arc_radii(arc(4.0, 4.0, true), compensating(-1, 5.0)), "");
}

// Smaller than the tool: at its edge (as large) nothing, a hair below it named.
TEST(CalcErrorRadii, OnlyAnArcSmallerThanTheToolIsNamed) {
    EXPECT_EQ(concave_arc_radii(arc(6.0, 6.0, true), compensating(1, 5.0)), "");
    EXPECT_EQ(concave_arc_radii(arc(5.0, 5.0, true), compensating(1, 5.0)), "");
    EXPECT_NE(concave_arc_radii(arc(5.0 - 1e-9, 5.0 - 1e-9, true), compensating(1, 5.0)), "");
    // A spiral whose smaller radius is below the tool's.
    EXPECT_NE(concave_arc_radii(arc(6.0, 4.9, true), compensating(1, 5.0)), "");
}

// A spiral (rounded centre words) names both of its radii, past half a unit of the last digit.
TEST(CalcErrorRadii, ASpiralNamesItsStartAndEndRadius) {
    EXPECT_EQ(concave_arc_radii(arc(4.0, 4.001, true), compensating(1, 5.0)),
              "; arc radius 4.0000 to 4.0010 mm, tool radius 5.0000 mm");
    EXPECT_EQ(concave_arc_radii(arc(4.0, 4.00005, true), compensating(1, 5.0)),
              "; arc radius 4.0000 mm, tool radius 5.0000 mm");
    EXPECT_EQ(concave_arc_radii(arc(4.0, 4.00006, true), compensating(1, 5.0)),
              "; arc radius 4.0000 to 4.0001 mm, tool radius 5.0000 mm");
}

TEST(CalcErrorRadii, NothingWithoutCompensationForALineOrInAnotherPlane) {
    TcUnit::State off = compensating(1, 5.0);
    off.comp_on = false;
    EXPECT_EQ(concave_arc_radii(arc(4.0, 4.0, true), off), "");
    PathSegment line = arc(4.0, 4.0, true);
    line.kind = SegmentKind::kLine;
    EXPECT_EQ(concave_arc_radii(line, compensating(1, 5.0)), "");
    PathSegment other = arc(4.0, 4.0, true);
    other.plane = 18;
    EXPECT_EQ(concave_arc_radii(other, compensating(1, 5.0)), "");
}

}  // namespace
}  // namespace apci::run::exec
