// SPDX-License-Identifier: MIT
// Elements of the shared geometry (geometry/element.h): tangents, sweep, length, points and
// distances.
#include "geometry/element.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry/tolerances.h"

namespace geom {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEps = 1e-12;

void expect_near(const Vec2& a, const Vec2& b, double tol = kEps) {
    EXPECT_NEAR(a.x(), b.x(), tol) << "x";
    EXPECT_NEAR(a.y(), b.y(), tol) << "y";
}

TEST(Element, LineTangentIsUnitDirectionOfTravel) {
    const Element e = make_line({1, 1}, {4, 5});
    expect_near(start_tangent(e), {0.6, 0.8});
    expect_near(end_tangent(e), {0.6, 0.8});
    EXPECT_DOUBLE_EQ(length(e), 5.0);
}

TEST(Element, PlaneFreeLineHasNoTangent) {
    const Element e = make_line({2, 3}, {2, 3});
    EXPECT_TRUE(is_plane_free(e));
    expect_near(start_tangent(e), Vec2::Zero());
    EXPECT_FALSE(is_plane_free(make_line({2, 3}, {2, 3 + 10 * kPointTolerance})));
}

TEST(Element, CounterClockwiseArcTangentIsLeftOfRadius) {
    // Quarter circle from (1,0) to (0,1) about the origin, G03.
    const Element e = make_arc({1, 0}, {0, 1}, {0, 0}, true);
    expect_near(start_tangent(e), {0, 1});
    expect_near(end_tangent(e), {-1, 0});
    EXPECT_NEAR(sweep(e), kPi / 2, kEps);
    EXPECT_NEAR(length(e), kPi / 2, kEps);
}

TEST(Element, ClockwiseArcSweepsTheLongWayForTheSameEndPoints) {
    const Element e = make_arc({1, 0}, {0, 1}, {0, 0}, false);
    expect_near(start_tangent(e), {0, -1});
    expect_near(end_tangent(e), {1, 0});
    EXPECT_NEAR(sweep(e), -3 * kPi / 2, kEps);
    EXPECT_NEAR(length(e), 3 * kPi / 2, kEps);
}

TEST(Element, ArcWithEndEqualStartIsFullCircle) {
    const Element ccw = make_arc({3, 0}, {3, 0}, {1, 0}, true);
    EXPECT_TRUE(is_full_circle(ccw));
    EXPECT_NEAR(sweep(ccw), 2 * kPi, kEps);
    EXPECT_NEAR(length(ccw), 4 * kPi, kEps);
    const Element cw = make_arc({3, 0}, {3, 0}, {1, 0}, false);
    EXPECT_NEAR(sweep(cw), -2 * kPi, kEps);
}

TEST(Element, HalfCircleSweepsPiInEitherDirection) {
    EXPECT_NEAR(sweep(make_arc({1, 0}, {-1, 0}, {0, 0}, true)), kPi, kEps);
    EXPECT_NEAR(sweep(make_arc({1, 0}, {-1, 0}, {0, 0}, false)), -kPi, kEps);
}

TEST(Element, PointAtFollowsTheLength) {
    const Element line = make_line({0, 0}, {10, 0});
    expect_near(point_at(line, 0.25), {2.5, 0});
    expect_near(point_at(line, 2.0), {10, 0});  // clamped
    const Element arc = make_arc({1, 0}, {-1, 0}, {0, 0}, true);
    expect_near(point_at(arc, 0.5), {0, 1});
    expect_near(tangent_at(arc, 0.5), {-1, 0});
    const Element cw = make_arc({1, 0}, {-1, 0}, {0, 0}, false);
    expect_near(point_at(cw, 0.5), {0, -1});
}

TEST(Element, DistanceToLineIsPerpendicularInsideAndToEndPointsOutside) {
    const Element e = make_line({0, 0}, {10, 0});
    EXPECT_NEAR(distance_to(e, {5, 3}), 3.0, kEps);
    EXPECT_NEAR(distance_to(e, {-3, 4}), 5.0, kEps);
    EXPECT_NEAR(distance_to(e, {13, -4}), 5.0, kEps);
}

TEST(Element, DistanceToArcIsRadialWithinSweepAndToEndPointsOutside) {
    const Element e = make_arc({1, 0}, {0, 1}, {0, 0}, true);  // first quadrant
    EXPECT_NEAR(distance_to(e, {2, 2}), 2 * std::sqrt(2.0) - 1, kEps);
    EXPECT_NEAR(distance_to(e, {0.5, 0.5}), 1 - std::sqrt(0.5), kEps);
    // Third quadrant lies outside the sweep: nearest are the end points.
    EXPECT_NEAR(distance_to(e, {-1, -1}), std::sqrt(5.0), kEps);
    // The centre is at one radius from every arc point.
    EXPECT_NEAR(distance_to(e, {0, 0}), 1.0, kEps);
}

TEST(Element, DistanceToClockwiseArcUsesItsOwnSweep) {
    const Element e = make_arc({1, 0}, {0, 1}, {0, 0}, false);  // three quadrants
    EXPECT_NEAR(distance_to(e, {-2, -2}), 2 * std::sqrt(2.0) - 1, kEps);
    EXPECT_NEAR(distance_to(e, {2, 2}), std::sqrt(5.0), kEps);
}

TEST(ArcSweep, IsTheAngleBetweenTheRadiiInTheArcsSense) {
    EXPECT_NEAR(arc_sweep({1, 0}, {0, 1}, true, false), kPi / 2, kEps);
    EXPECT_NEAR(arc_sweep({1, 0}, {0, 1}, false, false), -1.5 * kPi, kEps);
    EXPECT_NEAR(arc_sweep({2, 0}, {0, -5}, false, false), -kPi / 2, kEps);  // radii differ
    EXPECT_NEAR(arc_sweep({1, 0}, {-1, 0}, true, false), kPi, kEps);
    EXPECT_NEAR(arc_sweep({1, 0}, {-1, 0}, false, false), -kPi, kEps);
}

TEST(ArcSweep, AWholeTurnWhereTheCallerSaysTheEndsMeetOrARadiusIsZero) {
    EXPECT_EQ(arc_sweep({1, 0}, {0, 1}, true, true), 2 * kPi);
    EXPECT_EQ(arc_sweep({1, 0}, {0, 1}, false, true), -2 * kPi);
    EXPECT_EQ(arc_sweep({0, 0}, {0, 1}, true, false), 2 * kPi);
    EXPECT_EQ(arc_sweep({1, 0}, {0, 0}, false, false), -2 * kPi);
    // Ends on one ray yet apart (rounding): a whole turn in either sense, never 0.
    EXPECT_EQ(arc_sweep({1, 0}, {2, 0}, true, false), 2 * kPi);
    EXPECT_EQ(arc_sweep({1, 0}, {2, 0}, false, false), -2 * kPi);
}

TEST(ArcSweep, AHugeRadiusKeepsTheSmallSweepOfItsChord) {
    // 20 mm of a circle of radius R turns by 20 / R: the difference of two atan2 angles loses it
    // (both round to the same angle), the unit radii keep it; R = 1e200 squares past double.
    for (const double r : {1e6, 1e12, 1e18, 1e200}) {
        const Vec2 u0(r, -10.0), u1(r, 10.0);
        EXPECT_NEAR(arc_sweep(u0, u1, true, false), 20.0 / r, 1e-9 * (20.0 / r)) << r;
        EXPECT_NEAR(arc_sweep(u0, u1, false, false), -2 * kPi + 20.0 / r, 1e-12) << r;
    }
}

TEST(ArcSweep, IsTheElementsSweep) {
    const Element e = make_arc({3, 1}, {1, 3}, {1, 1}, true);
    EXPECT_EQ(sweep(e), arc_sweep(e.start - e.centre, e.end - e.centre, true, false));
    const Element full = make_arc({3, 1}, {3, 1 + 0.5 * kPointTolerance}, {1, 1}, false);
    EXPECT_EQ(sweep(full), -2 * kPi);
    // Ends just beyond the tolerance apart: the small turn counter-clockwise, nearly a whole
    // one clockwise.
    const Element nearly = make_arc({3, 1}, {3, 1 + 2 * kPointTolerance}, {1, 1}, true);
    EXPECT_GT(sweep(nearly), 0.0);
    EXPECT_LT(sweep(nearly), 1e-6);
    const Element back = make_arc({3, 1}, {3, 1 + 2 * kPointTolerance}, {1, 1}, false);
    EXPECT_GT(sweep(back), -2 * kPi);
    EXPECT_LT(sweep(back), -2 * kPi + 1e-6);
}

TEST(Element, TurnAngleIsSignedAndCounterClockwisePositive) {
    EXPECT_NEAR(turn_angle({1, 0}, {0, 3}), kPi / 2, kEps);
    EXPECT_NEAR(turn_angle({1, 0}, {0, -3}), -kPi / 2, kEps);
    EXPECT_NEAR(turn_angle({1, 0}, {-1, 0}), kPi, kEps);  // (-pi, pi]: a reversal is +pi
    EXPECT_EQ(turn_angle({2, 2}, {1, 1}), 0.0);
}

TEST(Element, AngleBetweenCountsInTheGivenDirection) {
    EXPECT_NEAR(angle_between({1, 0}, {0, 1}, true), kPi / 2, kEps);
    EXPECT_NEAR(angle_between({1, 0}, {0, 1}, false), 3 * kPi / 2, kEps);
    EXPECT_EQ(angle_between({1, 0}, {2, 0}, true), 0.0);
}

// [0, 2 pi) at its top: b a hair clockwise of a is, counted counter-clockwise, 2 pi less the
// hair. Where that rounds to 2 pi it is 0 (the same direction); a hair of one rounding step
// more stays just below 2 pi; a small negative turn is always wrapped, never returned.
TEST(Element, AngleBetweenJustShortOfAWholeTurnStaysBelowTwoPi) {
    EXPECT_EQ(angle_between({1, 0}, {1, -1e-300}, true), 0.0);
    EXPECT_EQ(angle_between({1, 0}, {1, 1e-300}, false), 0.0);
    const double kept = angle_between({1, 0}, {1, -1e-15}, true);
    EXPECT_LT(kept, 2 * kPi);
    EXPECT_GT(kept, 2 * kPi - 2e-15);
    EXPECT_NEAR(angle_between({1, 0}, {1, -1e-13}, true), 2 * kPi - 1e-13, 1e-15);
    EXPECT_NEAR(angle_between({1, 0}, {1, 1e-13}, false), 2 * kPi - 1e-13, 1e-15);
    for (const bool ccw : {true, false})
        for (int i = 0; i < 360; ++i) {
            const double a =
                angle_between({1, 0}, {std::cos(i * kPi / 180), std::sin(i * kPi / 180)}, ccw);
            EXPECT_GE(a, 0.0) << i;
            EXPECT_LT(a, 2 * kPi) << i;
        }
}

// A full circle is an arc whose ends lie at most kPointTolerance apart: at the tolerance a whole
// turn in its sense, one rounding step past it the small turn its chord makes.
TEST(ArcSweep, AFullCircleEndsAtMostThePointToleranceApart) {
    // Centre below the start: the end 1e-9 along +X lies clockwise of the start by 2e-10 rad.
    const Vec2 start(0, 0), centre(0, -5);
    const Vec2 at(kPointTolerance, 0), past(std::nextafter(kPointTolerance, 1.0), 0);
    EXPECT_TRUE(is_full_circle(make_arc(start, at, centre, false)));
    EXPECT_FALSE(is_full_circle(make_arc(start, past, centre, false)));
    EXPECT_EQ(sweep(make_arc(start, at, centre, false)), -2 * kPi);
    EXPECT_EQ(sweep(make_arc(start, at, centre, true)), 2 * kPi);
    EXPECT_NEAR(sweep(make_arc(start, past, centre, false)), -kPointTolerance / 5, 1e-20);
    EXPECT_NEAR(sweep(make_arc(start, past, centre, true)), 2 * kPi - kPointTolerance / 5, 1e-15);
}

TEST(Element, CoordinatesBeyondLimitOrNotFiniteAreInvalid) {
    EXPECT_TRUE(has_valid_coordinates(make_line({0, 0}, {kMaxCoordinate, -kMaxCoordinate})));
    EXPECT_FALSE(has_valid_coordinates(make_line({0, 0}, {2 * kMaxCoordinate, 0})));
    EXPECT_FALSE(has_valid_coordinates(make_line({NAN, 0}, {1, 0})));
    EXPECT_FALSE(has_valid_coordinates(make_arc({1, 0}, {0, 1}, {INFINITY, 0}, true)));
    // A line's unused centre is not checked.
    Element line = make_line({0, 0}, {1, 0});
    line.centre = {NAN, NAN};
    EXPECT_TRUE(has_valid_coordinates(line));
}

TEST(Element, RotationTurnsAllPointsAndKeepsDirection) {
    const Element e = make_arc({2, 0}, {1, 1}, {1, 0}, true);
    const Element r = rotate_about(e, {1, 0}, 90.0);
    expect_near(r.start, {1, 1});
    expect_near(r.end, {0, 0});
    expect_near(r.centre, {1, 0});
    EXPECT_TRUE(r.ccw);
    EXPECT_NEAR(sweep(r), sweep(e), kEps);
}

}  // namespace
}  // namespace geom
