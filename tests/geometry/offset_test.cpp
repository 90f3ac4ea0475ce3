// SPDX-License-Identifier: MIT
// Offsetting elements by the tool radius, the element checks ([APCI-TC] "Tabelle 4":
// CalcError, CenterError), trimming and emission.
#include "rwmos/geometry/offset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rwmos/geometry/shared.h"

namespace rwmos::geom {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEps = 1e-12;

void expect_near(const Vec2& a, const Vec2& b, double tol = kEps) {
    EXPECT_NEAR(a.x(), b.x(), tol) << "x";
    EXPECT_NEAR(a.y(), b.y(), tol) << "y";
}

TEST(Offset, LeftOfLineIsLeftOfTheDirectionOfTravel) {
    const OffsetResult o = offset_element(make_line({0, 0}, {10, 0}), 2.0, Side::kLeft);
    ASSERT_EQ(o.reason, Reason::kNone);
    expect_near(o.element.path.start, {0, 2});
    expect_near(o.element.path.end, {10, 2});
    expect_near(o.element.direction, {1, 0});
}

TEST(Offset, RightOfLineIsRightOfTheDirectionOfTravel) {
    const OffsetResult o = offset_element(make_line({0, 0}, {0, 10}), 2.0, Side::kRight);
    expect_near(o.element.path.start, {2, 0});
    expect_near(o.element.path.end, {2, 10});
}

TEST(Offset, LeftOfCounterClockwiseArcIsTheConcaveSide) {
    const Element arc = make_arc({5, 0}, {0, 5}, {0, 0}, true);
    EXPECT_DOUBLE_EQ(offset_radius(arc, 1.0, Side::kLeft), 4.0);
    EXPECT_DOUBLE_EQ(offset_radius(arc, 1.0, Side::kRight), 6.0);
    const OffsetResult o = offset_element(arc, 1.0, Side::kLeft);
    ASSERT_EQ(o.reason, Reason::kNone);
    expect_near(o.element.path.start, {4, 0});
    expect_near(o.element.path.end, {0, 4});
    expect_near(o.element.path.centre, {0, 0});
    EXPECT_TRUE(o.element.path.ccw);
    EXPECT_NEAR(o.element.sweep, kPi / 2, kEps);
}

TEST(Offset, LeftOfClockwiseArcIsTheConvexSide) {
    const Element arc = make_arc({0, 5}, {5, 0}, {0, 0}, false);
    EXPECT_DOUBLE_EQ(offset_radius(arc, 1.0, Side::kLeft), 6.0);
    EXPECT_DOUBLE_EQ(offset_radius(arc, 1.0, Side::kRight), 4.0);
}

TEST(Offset, FullCircleStaysFullCircle) {
    const OffsetResult o =
        offset_element(make_arc({3, 0}, {3, 0}, {0, 0}, true), 1.0, Side::kRight);
    ASSERT_EQ(o.reason, Reason::kNone);
    EXPECT_EQ(o.element.path.start, o.element.path.end);
    EXPECT_NEAR(o.element.sweep, 2 * kPi, kEps);
    EXPECT_NEAR(offset_length(o.element), 8 * kPi, 1e-12);
}

TEST(Offset, CalcErrorWhenConcaveArcRadiusIsSmallerThanToolRadius) {
    // TC Table 4: CalcError when the radius of the arc is smaller than the tool radius,
    // beyond the path tolerance. A tool that fits the arc keeps its centre on the arc's.
    const Element arc = make_arc({5, 0}, {0, 5}, {0, 0}, true);
    EXPECT_EQ(offset_element(arc, 5.0 + 2 * kOffsetRadiusTolerance, Side::kLeft).reason,
              Reason::kOffsetRadiusNotPositive);
    EXPECT_EQ(offset_element(arc, 6.0, Side::kLeft).reason, Reason::kOffsetRadiusNotPositive);
    EXPECT_EQ(offset_element(arc, 4.999, Side::kLeft).reason, Reason::kNone);
    for (const double r : {5.0 - 0.5 * kOffsetRadiusTolerance, 5.0, 5.0 + 0.5 * kOffsetRadiusTolerance}) {
        const OffsetResult fits = offset_element(arc, r, Side::kLeft);
        ASSERT_EQ(fits.reason, Reason::kNone) << r;
        EXPECT_LT((fits.element.path.start - arc.centre).norm(), kOffsetRadiusTolerance) << r;
        EXPECT_LT((fits.element.path.end - arc.centre).norm(), kOffsetRadiusTolerance) << r;
        EXPECT_NEAR(fits.element.sweep, kPi / 2, kEps);
        EXPECT_LT(length(emitted_path(fits.element)), kOffsetRadiusTolerance);
    }
    // The convex side has no such limit.
    EXPECT_EQ(offset_element(arc, 6.0, Side::kRight).reason, Reason::kNone);
    EXPECT_EQ(reason_bits(Reason::kOffsetRadiusNotPositive), bits(ErrorBit::kCalcError));
}

TEST(Offset, CenterErrorWhenStartAndEndRadiusDifferBeyondTolerance) {
    const Element bad = make_arc({5, 0}, {0, 5 + 2 * kCenterRadiusTolerance}, {0, 0}, true);
    EXPECT_EQ(check_element(bad), Reason::kArcRadiiDiffer);
    EXPECT_EQ(reason_bits(Reason::kArcRadiiDiffer), bits(ErrorBit::kCenterError));
    const Element within = make_arc({5, 0}, {0, 5 + 0.5 * kCenterRadiusTolerance}, {0, 0}, true);
    EXPECT_EQ(check_element(within), Reason::kNone);
}

TEST(Offset, CenterErrorWhenCentreLiesOnStartOrEndPoint) {
    EXPECT_EQ(check_element(make_arc({0, 0}, {0, 0}, {0, 0}, true)), Reason::kArcCentreOnEndPoint);
    EXPECT_EQ(check_element(make_arc({0.001, 0}, {0, 0}, {0, 0}, true)),
              Reason::kArcCentreOnEndPoint);
    EXPECT_EQ(reason_bits(Reason::kArcCentreOnEndPoint), bits(ErrorBit::kCenterError));
}

TEST(Offset, CalcErrorForCoordinatesNotFiniteOrOutOfRange) {
    EXPECT_EQ(check_element(make_line({0, 0}, {NAN, 1})), Reason::kInvalidCoordinate);
    EXPECT_EQ(check_element(make_line({0, 0}, {1, 1e6})), Reason::kInvalidCoordinate);
    EXPECT_EQ(check_element(make_arc({1, 0}, {0, 1}, {0, -INFINITY}, true)),
              Reason::kInvalidCoordinate);
    EXPECT_EQ(reason_bits(Reason::kInvalidCoordinate), bits(ErrorBit::kCalcError));
}

TEST(Offset, CalcErrorForAnElementKindThatIsNeitherLineNorArc) {
    Element e = make_line({0, 0}, {1, 0});
    e.kind = static_cast<ElementKind>(7);
    EXPECT_EQ(check_element(e), Reason::kInvalidElementKind);
    EXPECT_EQ(reason_bits(Reason::kInvalidElementKind), bits(ErrorBit::kCalcError));
}

TEST(Offset, ArcWithRadiiDifferingWithinToleranceRunsFromStartToEndAndSoDoesItsOffset) {
    // Rounding made the end radius 5.002: the arc runs from its start to its programmed
    // end, its radius changing linearly with the angle; its offset keeps that shape.
    const Element arc = make_arc({5, 0}, {0, 5.002}, {0, 0}, true);
    EXPECT_EQ(point_at(arc, 1.0), arc.end);
    EXPECT_NEAR((point_at(arc, 0.5) - arc.centre).norm(), 5.001, 1e-12);
    EXPECT_NEAR(length(arc), kPi / 2 * 5.001, 1e-12);
    const OffsetResult o = offset_element(arc, 1.0, Side::kRight);
    expect_near(o.element.path.start, {6, 0});
    expect_near(o.element.path.end, {0, 6.002});
    EXPECT_NEAR(offset_length(o.element), kPi / 2 * 6.001, 1e-12);
    // Every point of the offset is r from the arc (the spiral's normal tilts by
    // dR / (R dphi), here 4e-4: its distance differs from r by about r * 8e-8).
    for (int i = 0; i <= 16; ++i) {
        const Vec2 p = point_at(o.element.path, i / 16.0);
        EXPECT_NEAR(distance_to(arc, p), 1.0, 1e-6) << i;
    }
}

TEST(Offset, DistanceAlongCountsFromStartInTheDirectionOfTravel) {
    const OffsetElement line = offset_element(make_line({0, 0}, {10, 0}), 1, Side::kLeft).element;
    EXPECT_NEAR(distance_along(line, {4, 1}), 4.0, kEps);
    EXPECT_NEAR(distance_along(line, {-1, 1}), -1.0, kEps);
    const OffsetElement arc =
        offset_element(make_arc({0, 5}, {5, 0}, {0, 0}, false), 1, Side::kLeft).element;
    EXPECT_NEAR(distance_along(arc, {6 * std::sqrt(0.5), 6 * std::sqrt(0.5)}), 6 * kPi / 4, 1e-12);
}

TEST(Offset, TrimmingAnArcKeepsItsSweepExplicit) {
    const OffsetElement arc =
        offset_element(make_arc({1, 0}, {-1, 0}, {0, 0}, true), 1, Side::kRight).element;
    // Offset radius 2, half circle. Trim the start by a quarter, the end to the start.
    const OffsetElement a = trim_start(arc, {0, 2}, kPi);
    EXPECT_NEAR(a.sweep, kPi / 2, kEps);
    const OffsetElement b = trim_end(a, {0, 2}, 0.0);
    EXPECT_EQ(b.sweep, 0.0);
    // An arc trimmed to nothing is emitted as a zero-length line, not a full circle.
    EXPECT_EQ(emitted_path(b).kind, ElementKind::kLine);
}

TEST(Offset, TinyArcIsEmittedAsLineAndFullCircleAsArc) {
    OffsetElement tiny;
    tiny.path = make_arc({1, 0}, {1, 1e-10}, {0, 0}, true);
    tiny.sweep = 1e-10;
    EXPECT_EQ(emitted_path(tiny).kind, ElementKind::kLine);
    OffsetElement full;
    full.path = make_arc({1, 0}, {1, 0}, {0, 0}, true);
    full.sweep = 2 * kPi;
    EXPECT_EQ(emitted_path(full).kind, ElementKind::kArc);
}

}  // namespace
}  // namespace rwmos::geom
