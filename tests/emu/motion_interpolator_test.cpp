// SPDX-License-Identifier: MIT
// The interpolator: cycle counts from feed and cycle length, positions along
// lines and arcs, exact end points.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rwmos/motion/interpolator.h"

using namespace rwmos::motion;

namespace {
AxisVector at(double x, double y, double z = 0.0) {
    AxisVector v{};
    v[0] = x;
    v[1] = y;
    v[2] = z;
    return v;
}
}  // namespace

TEST(Interpolator, FeedIsUnitsPerMinuteSoTenUnitsAt600PerMinuteTakeOneSecond) {
    // 600 units/min = 10 units/s = 0.01 units per 1 ms cycle -> 1000 cycles.
    EXPECT_EQ(cycles_for(10.0, 600.0, 0.001), 1000u);
}

TEST(Interpolator, CycleCountRoundsUpSoSpeedNeverExceedsFeed) {
    // 10.005 units at 0.01 units/cycle: 1000.5 -> 1001 cycles.
    EXPECT_EQ(cycles_for(10.005, 600.0, 0.001), 1001u);
    const double per_cycle = 10.005 / 1001.0;
    EXPECT_LE(per_cycle, 600.0 / 60.0 * 0.001);
}

TEST(Interpolator, ZeroLengthTakesNoCycle) {
    EXPECT_EQ(cycles_for(0.0, 600.0, 0.001), 0u);
}

TEST(Interpolator, CycleCountSaturatesInsteadOfOverflowing) {
    EXPECT_EQ(cycles_for(1e300, 1e-300, 0.001), kCycleCountCeiling);
}

TEST(Interpolator, LastCycleLandsExactlyOnTheEnd) {
    const Move m =
        line_move(at(0.1, 0.2), at(10.3, -7.7, 3.3), 1000.0, SegmentRole::kUncompensated, 1);
    const std::uint64_t n = cycles_for(path_length(m), m.feed, 0.001);
    AxisVector p{};
    position_at(m, n, n, p);
    EXPECT_EQ(p, m.end);
}

TEST(Interpolator, LineMovesAllAxesLinearly) {
    AxisVector end = at(10.0, 20.0, 30.0);
    end[7] = -8.0;
    const Move m = line_move(AxisVector{}, end, 1000.0, SegmentRole::kUncompensated, 1);
    AxisVector p{};
    position_at(m, 1, 4, p);
    EXPECT_DOUBLE_EQ(p[0], 2.5);
    EXPECT_DOUBLE_EQ(p[1], 5.0);
    EXPECT_DOUBLE_EQ(p[2], 7.5);
    EXPECT_DOUBLE_EQ(p[7], -2.0);
}

TEST(Interpolator, ArcKeepsItsRadiusAndTurnsCounterClockwiseForG03) {
    // Quarter circle from (10,0) to (0,10) around the origin, ccw: passes (7.07, 7.07).
    const Move m = arc_move(at(10, 0), at(0, 10), {0, 1}, 0.0, 0.0, true, 1000.0,
                            SegmentRole::kUncompensated, 1);
    EXPECT_NEAR(m.sweep, std::numbers::pi / 2, 1e-15);
    AxisVector p{};
    position_at(m, 1, 2, p);
    EXPECT_NEAR(p[0], 10.0 / std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(p[1], 10.0 / std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(path_length(m), 5.0 * std::numbers::pi, 1e-12);
}

TEST(Interpolator, ArcG02TakesTheClockwiseWayRound) {
    // (10,0) -> (0,10) clockwise is three quarters of the circle, through (0,-10).
    const Move m = arc_move(at(10, 0), at(0, 10), {0, 1}, 0.0, 0.0, false, 1000.0,
                            SegmentRole::kUncompensated, 1);
    EXPECT_NEAR(m.sweep, -1.5 * std::numbers::pi, 1e-15);
    AxisVector p{};
    position_at(m, 1, 3, p);
    EXPECT_NEAR(p[0], 0.0, 1e-12);
    EXPECT_NEAR(p[1], -10.0, 1e-12);
}

TEST(Interpolator, ArcWithEqualStartAndEndIsAFullCircle) {
    const Move m = arc_move(at(10, 0), at(10, 0), {0, 1}, 0.0, 0.0, true, 1000.0,
                            SegmentRole::kUncompensated, 1);
    EXPECT_NEAR(path_length(m), 20.0 * std::numbers::pi, 1e-12);
}

TEST(Interpolator, ArcMovesTheThirdAxisLinearlyAlongThePlaneElement) {
    const Move m = arc_move(at(10, 0, 0), at(-10, 0, 4), {0, 1}, 0.0, 0.0, true, 1000.0,
                            SegmentRole::kUncompensated, 1);
    AxisVector p{};
    position_at(m, 1, 2, p);
    EXPECT_NEAR(p[0], 0.0, 1e-12);
    EXPECT_NEAR(p[1], 10.0, 1e-12);
    EXPECT_DOUBLE_EQ(p[2], 2.0);
    // Helix length: sqrt((10 pi)^2 + 4^2).
    EXPECT_NEAR(path_length(m), std::hypot(10.0 * std::numbers::pi, 4.0), 1e-12);
}

TEST(Interpolator, ArcInTheZxPlaneUsesItsNamedAxes) {
    // Plane (Z, X): first axis 2, second axis 0. From Z=5 to X=5 ccw around the origin.
    AxisVector s{}, e{};
    s[2] = 5.0;
    e[0] = 5.0;
    const Move m = arc_move(s, e, {2, 0}, 0.0, 0.0, true, 1000.0, SegmentRole::kUncompensated, 1);
    AxisVector p{};
    position_at(m, 1, 2, p);
    EXPECT_NEAR(p[2], 5.0 / std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(p[0], 5.0 / std::sqrt(2.0), 1e-12);
    EXPECT_DOUBLE_EQ(p[1], 0.0);
}

TEST(Interpolator, SegmentOfAnArcCarriesCentreSenseAndPlane) {
    const Move m = arc_move(at(10, 0, 1), at(0, 10, 1), {0, 1}, 0.0, 0.0, true, 1000.0,
                            SegmentRole::kContour, 7);
    const Segment s = segment_of(m);
    EXPECT_EQ(s.tag, 7u);
    EXPECT_EQ(s.kind, SegmentKind::kArc);
    EXPECT_EQ(s.role, SegmentRole::kContour);
    EXPECT_TRUE(s.ccw);
    EXPECT_DOUBLE_EQ(s.center[0], 0.0);
    EXPECT_DOUBLE_EQ(s.center[1], 0.0);
    EXPECT_DOUBLE_EQ(s.center[2], 1.0);
}
