// SPDX-License-Identifier: MIT
// measure() computes an executed segment's sweep and length with its plane's axes as constants;
// the values must be those of arc_sweep and segment_length bit for bit, in every plane (17, 18,
// 19 and 17's axes for any other number), both senses, flat and helical, full circles too.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include "apci/run/path.h"

namespace apci::run {
namespace {

Point random_point(std::mt19937_64& rng, double span) {
    std::uniform_real_distribution<double> d(-span, span);
    return {d(rng), d(rng), d(rng)};
}

TEST(PathMeasure, ArcsInEveryPlaneHaveTheSweepAndLengthOfThePathFunctions) {
    std::mt19937_64 rng(20261126);
    std::uint64_t arcs = 0;
    for (const int plane : {17, 18, 19, 0, 42}) {
        const PlaneAxes a = plane_axes(plane);
        for (int i = 0; i < 20000; ++i) {
            PathSegment s;
            s.kind = SegmentKind::kArc;
            s.plane = plane;
            s.ccw = (i & 1) != 0;
            s.start = random_point(rng, 100.0);
            s.center = random_point(rng, 100.0);
            s.center[a.third] = s.start[a.third];
            s.end = random_point(rng, 100.0);
            if (i % 3 == 0) s.end[a.third] = s.start[a.third];  // flat
            if (i % 7 == 0) {                                   // a full circle (helical or not)
                s.end[a.first] = s.start[a.first];
                s.end[a.second] = s.start[a.second];
            }
            if (i % 11 == 0) s.end[a.first] = s.start[a.first] + 1e-10;  // within the tolerance
            measure(s);
            ASSERT_EQ(s.sweep, arc_sweep(s)) << plane << " " << i;
            ASSERT_EQ(s.length, segment_length(s)) << plane << " " << i;
            ++arcs;
        }
    }
    EXPECT_EQ(arcs, 100000U);
}

TEST(PathMeasure, AnArcOfAHugeRadiusKeepsItsSmallSweep) {
    // 20 mm of a circle of radius 1e18 about (0, 1e18): the two radii's directions differ by
    // 2e-17 rad, below the rounding of an angle near pi / 2, so the difference of two atan2
    // angles is 0 and became a full turn (2 pi, a length of 6.3e18 mm). The angle between the
    // unit radii keeps it.
    for (const bool ccw : {true, false}) {
        PathSegment s;
        s.kind = SegmentKind::kArc;
        s.plane = 17;
        s.ccw = ccw;
        s.start = Point(0, 0, 0);
        s.end = Point(ccw ? 20 : -20, 0, 0);
        s.center = Point(0, 1e18, 0);
        measure(s);
        EXPECT_NEAR(s.sweep, ccw ? 2e-17 : -2e-17, 1e-30) << ccw;
        EXPECT_NEAR(s.length, 20.0, 1e-9) << ccw;
        EXPECT_EQ(arc_sweep(s), s.sweep);
    }
}

// Ends at most kSamePointTolerance apart in the plane are a full circle, a whole turn in the
// arc's sense; one rounding step past it, the short turn of the chord (chord / 5 rad about a
// centre 5 mm below the start), in every plane.
TEST(PathMeasure, AnArcIsAFullCircleWhereItsEndsLieWithinTheTolerance) {
    const double past = std::nextafter(kSamePointTolerance, 1.0);
    constexpr double kTwoPi = 2 * std::numbers::pi;
    for (const int plane : {17, 18, 19}) {
        const PlaneAxes a = plane_axes(plane);
        for (const bool ccw : {true, false}) {
            PathSegment s;
            s.kind = SegmentKind::kArc;
            s.plane = plane;
            s.ccw = ccw;
            s.start = Point(0, 0, 0);
            s.center = Point(0, 0, 0);
            s.center[a.second] = -5.0;
            s.end = s.start;
            s.end[a.first] = kSamePointTolerance;
            measure(s);
            EXPECT_EQ(s.sweep, ccw ? kTwoPi : -kTwoPi) << plane << ccw;
            EXPECT_NEAR(s.length, 10.0 * std::numbers::pi, 1e-9) << plane << ccw;
            s.end[a.first] = past;
            measure(s);
            EXPECT_NEAR(s.sweep, ccw ? kTwoPi - past / 5 : -past / 5, 1e-15) << plane << ccw;
            EXPECT_EQ(arc_sweep(s), s.sweep);
        }
    }
}

TEST(PathMeasure, LinesAndRapidsHaveNoSweepAndTheirChord) {
    std::mt19937_64 rng(7);
    for (const SegmentKind kind : {SegmentKind::kLine, SegmentKind::kRapid}) {
        for (int i = 0; i < 1000; ++i) {
            PathSegment s;
            s.kind = kind;
            s.start = random_point(rng, 1000.0);
            s.end = random_point(rng, 1000.0);
            measure(s);
            ASSERT_EQ(s.sweep, 0.0);
            ASSERT_EQ(s.length, segment_length(s)) << i;
        }
    }
}

}  // namespace
// A turning tool's segments taken back to the nose centre (docs/compensation.md "Turning
// tools"), as the board carried them over: contour and transition whole (an arc's centre too),
// the approach's end (an approach arc whole), the departure's start; others as they are. In
// G18 the plane's first axis is Z and its second X.
TEST(NoseCentrePath, TakesTheCuttingEdgeOffsetOffWhatTheBoardCarriedOver) {
    const Eigen::Vector2d edge(-1.0, 2.0);  // Z -1, X +2
    const auto seg = [](Role role, SegmentKind kind) {
        PathSegment s;
        s.role = role;
        s.kind = kind;
        s.plane = 18;
        s.start = Point(10, 0, 5);
        s.end = Point(12, 0, 7);
        s.center = Point(10, 0, 7);
        return s;
    };
    const Point back(-2, 0, 1);  // minus the edge on X and Z
    for (Role r : {Role::kContour, Role::kTransition}) {
        const PathSegment a = nose_centre_path(seg(r, SegmentKind::kArc), edge, 18);
        EXPECT_EQ(a.start, Point(10, 0, 5) + back);
        EXPECT_EQ(a.end, Point(12, 0, 7) + back);
        EXPECT_EQ(a.center, Point(10, 0, 7) + back);
    }
    const PathSegment in = nose_centre_path(seg(Role::kApproach, SegmentKind::kLine), edge, 18);
    EXPECT_EQ(in.start, Point(10, 0, 5));
    EXPECT_EQ(in.end, Point(12, 0, 7) + back);
    const PathSegment in_arc = nose_centre_path(seg(Role::kApproach, SegmentKind::kArc), edge, 18);
    EXPECT_EQ(in_arc.start, Point(10, 0, 5) + back);
    const PathSegment out = nose_centre_path(seg(Role::kDeparture, SegmentKind::kLine), edge, 18);
    EXPECT_EQ(out.start, Point(10, 0, 5) + back);
    EXPECT_EQ(out.end, Point(12, 0, 7));
    const PathSegment rapid = nose_centre_path(seg(Role::kUncompensated, SegmentKind::kRapid), edge, 18);
    EXPECT_EQ(rapid.start, Point(10, 0, 5));
    EXPECT_EQ(nose_centre_path(seg(Role::kContour, SegmentKind::kLine), Eigen::Vector2d::Zero(), 18)
                  .end,
              Point(12, 0, 7));
}

}  // namespace apci::run
