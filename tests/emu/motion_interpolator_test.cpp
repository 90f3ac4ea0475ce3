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

// Ends at most kFullCircleTolerance apart are a full circle (the board runs the whole turn in
// the arc's sense); one rounding step past it, the short turn the chord makes. The centre lies
// below the start, so the end along +X is clockwise of it by chord / 5 rad; a chord of 0.6 of
// the tolerance (below twice it, the shortcut's bound, yet over it) is a full circle too.
TEST(Interpolator, AnArcIsAFullCircleWhereItsEndsLieWithinTheTolerance) {
    const double at_tol = kFullCircleTolerance;
    const double past = std::nextafter(kFullCircleTolerance, 1.0);
    for (const bool ccw : {true, false}) {
        const double whole = ccw ? 2 * std::numbers::pi : -2 * std::numbers::pi;
        for (const double chord : {at_tol, 0.6 * at_tol, 0.0}) {
            const Move m = arc_move(at(0, 0), at(chord, 0), {0, 1}, 0.0, -5.0, ccw, 1000.0,
                                    SegmentRole::kUncompensated, 1);
            EXPECT_EQ(m.sweep, whole) << ccw << " " << chord;
            EXPECT_NEAR(path_length(m), 10.0 * std::numbers::pi, 1e-9) << ccw << " " << chord;
        }
        const Move m = arc_move(at(0, 0), at(past, 0), {0, 1}, 0.0, -5.0, ccw, 1000.0,
                                SegmentRole::kUncompensated, 1);
        EXPECT_NEAR(m.sweep, ccw ? whole - past / 5 : -past / 5, 1e-15) << ccw;
    }
    // The same chord along the second axis (the first's component 0).
    const Move m = arc_move(at(0, 0), at(0, past), {0, 1}, 5.0, 0.0, true, 1000.0,
                            SegmentRole::kUncompensated, 1);
    EXPECT_NEAR(m.sweep, 2 * std::numbers::pi - past / 5, 1e-15);
    const Move full = arc_move(at(0, 0), at(0, at_tol), {0, 1}, 5.0, 0.0, true, 1000.0,
                               SegmentRole::kUncompensated, 1);
    EXPECT_EQ(full.sweep, 2 * std::numbers::pi);
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

TEST(Interpolator, SegmentIntoSetsEveryMemberAsSegmentOf) {
    // Written over a segment with every member set otherwise: the same as a fresh segment_of.
    AxisVector s{}, e{};
    for (std::size_t a = 0; a < s.size(); ++a) {
        s[a] = 0.5 * static_cast<double>(a);
        e[a] = -1.25 * static_cast<double>(a) + 3.0;
    }
    const Move moves[] = {
        line_move(s, e, 600.0, SegmentRole::kRapid, 7),
        arc_move(s, e, {2, 5}, 1.0, -2.0, true, 300.0, SegmentRole::kContour, 8),
        arc_move(s, e, {1, 0}, 0.5, 0.25, false, 30.0, SegmentRole::kApproach, 9)};
    for (const Move& m : moves) {
        Segment dirty;
        dirty.tag = 99;
        dirty.kind = SegmentKind::kArc;
        dirty.role = SegmentRole::kDeparture;
        dirty.start.fill(7.0);
        dirty.end.fill(8.0);
        dirty.plane_axes = {6, 7};
        dirty.center.fill(9.0);
        dirty.ccw = true;
        dirty.plane = 19;
        dirty.feed = 1.0;
        dirty.start_cycle = 11;
        dirty.end_cycle = 12;
        dirty.interrupted = true;
        segment_into(m, dirty);
        const Segment fresh = segment_of(m);
        Segment reference;  // segment_of as it was: a default Segment, then the move's members
        reference.tag = m.tag;
        reference.kind = m.kind;
        reference.role = m.role;
        reference.start = m.start;
        reference.end = m.end;
        reference.feed = m.feed;
        if (m.kind == SegmentKind::kArc) {
            reference.plane_axes = m.plane_axes;
            reference.center = m.start;
            reference.center[m.plane_axes[0]] = m.cx;
            reference.center[m.plane_axes[1]] = m.cy;
            reference.ccw = m.sweep > 0.0;
            reference.plane = m.plane;
        }
        for (const Segment* got : {static_cast<const Segment*>(&dirty), &fresh}) {
            EXPECT_EQ(got->tag, reference.tag);
            EXPECT_EQ(got->kind, reference.kind);
            EXPECT_EQ(got->role, reference.role);
            EXPECT_EQ(got->start, reference.start);
            EXPECT_EQ(got->end, reference.end);
            EXPECT_EQ(got->plane_axes, reference.plane_axes);
            EXPECT_EQ(got->center, reference.center);
            EXPECT_EQ(got->ccw, reference.ccw);
            EXPECT_EQ(got->plane, reference.plane);
            EXPECT_EQ(got->feed, reference.feed);
            EXPECT_EQ(got->start_cycle, 0u);
            EXPECT_EQ(got->end_cycle, 0u);
            EXPECT_FALSE(got->interrupted);
        }
    }
}

// A move the 3D module compensated (Move::surface) is a contour element where the spooler ran
// it uncompensated; every other role is its own, marked or not.
TEST(Interpolator, AMarkedMoveIsAContourElementOnlyWhereItRanUncompensated) {
    for (const SegmentRole role :
         {SegmentRole::kContour, SegmentRole::kTransition, SegmentRole::kApproach,
          SegmentRole::kDeparture, SegmentRole::kUncompensated, SegmentRole::kRapid}) {
        SCOPED_TRACE(static_cast<int>(role));
        Move m = line_move(at(0, 0), at(1, 0), 600.0, role, 3);
        EXPECT_EQ(segment_of(m).role, role) << "not marked";
        m.surface = true;
        EXPECT_EQ(segment_of(m).role,
                  role == SegmentRole::kUncompensated ? SegmentRole::kContour : role);
    }
}

// length_at: the tool length compensation changes linearly along a move, from the length it
// started with to its length_end, which the last cycle gives exactly (and one cycle before the
// last does not).
TEST(Interpolator, LengthAtRunsLinearlyFromTheStartsLengthToExactlyTheEndsAtTheLastCycle) {
    Move m = line_move(at(0, 0, 0), at(10, 0, 0), 600.0, SegmentRole::kContour, 1);
    m.length_end = at(0, 0, 0.3);
    const AxisVector from = at(0, 0, 10.1);
    AxisVector out{};
    length_at(m, from, 0, 7, out);
    EXPECT_EQ(out, from);
    length_at(m, from, 3, 7, out);
    EXPECT_NEAR(out[2], 10.1 + (0.3 - 10.1) * 3.0 / 7.0, 1e-12);
    EXPECT_EQ(out[0], 0.0);
    length_at(m, from, 6, 7, out);
    EXPECT_NEAR(out[2], 10.1 + (0.3 - 10.1) * 6.0 / 7.0, 1e-12);
    EXPECT_GT(out[2], 0.3 + 1.0);  // a seventh of the change still to come
    length_at(m, from, 7, 7, out);
    EXPECT_EQ(out, m.length_end);
    length_at(m, from, 0, 0, out);  // a move of no cycle: its end
    EXPECT_EQ(out, m.length_end);
}
