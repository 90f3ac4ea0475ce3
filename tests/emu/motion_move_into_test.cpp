// SPDX-License-Identifier: MIT
// line_move_into / arc_move_into write a move into storage that held another one (the back of
// the executor's queue, reused as the queue slides along), whose start and end the caller has
// set: every other member is the new move's, nothing of the old is left.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "rwmos/motion/interpolator.h"

using namespace rwmos::motion;

namespace {

AxisVector filled(double v) {
    AxisVector a{};
    a.fill(v);
    return a;
}

// A move whose every member differs from what a new line or arc has.
Move stale() {
    Move m;
    m.kind = SegmentKind::kArc;
    m.role = SegmentRole::kRapid;
    m.tag = 77;
    m.direct = true;
    m.traverse = true;
    m.profile = 12;
    m.length_change = filled(0.25);
    m.length_end = filled(-10.5);
    m.surface = true;
    m.side = -1;
    m.plane = 19;
    m.start = filled(-3.0);
    m.end = filled(-4.0);
    m.feed = 123.0;
    m.plane_axes = {5, 6};
    m.cx = m.cy = 9.0;
    m.radius = m.end_radius = 8.0;
    m.start_angle = 1.5;
    m.sweep = -2.5;
    return m;
}

void expect_same(const Move& a, const Move& b) {
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.role, b.role);
    EXPECT_EQ(a.tag, b.tag);
    EXPECT_EQ(a.direct, b.direct);
    EXPECT_EQ(a.traverse, b.traverse);
    EXPECT_EQ(a.profile, b.profile);
    EXPECT_EQ(a.length_change, b.length_change);
    EXPECT_EQ(a.length_end, b.length_end);  // a batch sets it; a direct move has none
    EXPECT_EQ(a.surface, b.surface);        // not the 3D module's unless it marks it
    EXPECT_EQ(a.side, b.side);
    EXPECT_EQ(a.plane, b.plane);
    EXPECT_EQ(a.start, b.start);
    EXPECT_EQ(a.end, b.end);
    EXPECT_EQ(a.feed, b.feed);
    EXPECT_EQ(a.plane_axes, b.plane_axes);
    for (const auto& [x, y] :
         {std::pair{a.cx, b.cx}, std::pair{a.cy, b.cy}, std::pair{a.radius, b.radius},
          std::pair{a.end_radius, b.end_radius}, std::pair{start_angle_of(a), start_angle_of(b)},
          std::pair{a.sweep, b.sweep}})
        EXPECT_EQ(std::bit_cast<std::uint64_t>(x), std::bit_cast<std::uint64_t>(y));
}

}  // namespace

TEST(MoveInto, LineOverAnOldMoveIsANewLine) {
    Move expected;  // Move{} and then the line's members
    expected.kind = SegmentKind::kLine;
    expected.role = SegmentRole::kContour;
    expected.tag = 5;
    expected.start = filled(1.0);
    expected.end = filled(2.0);
    expected.feed = 600.0;
    Move m = stale();
    m.start = filled(1.0);
    m.end = filled(2.0);
    line_move_into(m, 600.0, SegmentRole::kContour, 5);
    expect_same(m, expected);
}

TEST(MoveInto, ArcOverAnOldMoveIsANewArc) {
    // A quarter circle of radius 5 about (1, 2) on axes 3 and 4, counter-clockwise from +x.
    AxisVector start = filled(0.5), end = filled(0.75);
    start[3] = 6.0;
    start[4] = 2.0;
    end[3] = 1.0;
    end[4] = 7.0;
    Move expected;
    expected.kind = SegmentKind::kArc;
    expected.role = SegmentRole::kTransition;
    expected.tag = 9;
    expected.start = start;
    expected.end = end;
    expected.feed = 1200.0;
    expected.plane_axes = {3, 4};
    expected.cx = 1.0;
    expected.cy = 2.0;
    expected.radius = 5.0;
    expected.end_radius = 5.0;
    expected.start_angle = 0.0;
    expected.sweep = std::numbers::pi / 2;
    Move m = stale();
    m.start = start;
    m.end = end;
    arc_move_into(m, {3, 4}, 1.0, 2.0, true, 1200.0, SegmentRole::kTransition, 9);
    expect_same(m, expected);
    // The same as the move arc_move returns, and a full circle's sweep when it closes.
    expect_same(m,
                arc_move(start, end, {3, 4}, 1.0, 2.0, true, 1200.0, SegmentRole::kTransition, 9));
    Move full = stale();
    full.start = full.end = start;
    arc_move_into(full, {3, 4}, 1.0, 2.0, false, 1200.0, SegmentRole::kContour, 1);
    EXPECT_EQ(full.sweep, -2 * std::numbers::pi);
    EXPECT_EQ(full.plane, 0);
    EXPECT_EQ(full.side, 0);
    EXPECT_FALSE(full.direct);
}

TEST(MoveInto, AnArcsStartAngleIsTakenWhenFirstAskedWithTheSameBits) {
    // An arc whose start lies off the axes: atan2 of the start about the centre, taken only
    // when position_at or tangent_at (or anyone) first asks, and then kept.
    AxisVector start = filled(0.0), end = filled(0.0);
    start[0] = 1.0 + 3.0 * std::cos(0.7);
    start[1] = -2.0 + 3.0 * std::sin(0.7);
    end[0] = 1.0 + 3.0 * std::cos(2.1);
    end[1] = -2.0 + 3.0 * std::sin(2.1);
    Move m = stale();
    m.start = start;
    m.end = end;
    arc_move_into(m, {0, 1}, 1.0, -2.0, true, 600.0, SegmentRole::kContour, 3);
    EXPECT_TRUE(m.angle_due);
    const double angle = std::atan2(start[1] - -2.0, start[0] - 1.0);
    AxisVector mid{};
    position_at(m, 1, 2, mid);  // half way: asks for the angle
    EXPECT_FALSE(m.angle_due);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(m.start_angle), std::bit_cast<std::uint64_t>(angle));
    const double half = angle + m.sweep * 0.5;
    const double r = m.radius + (m.end_radius - m.radius) * 0.5;
    EXPECT_EQ(mid[0], 1.0 + r * std::cos(half));
    EXPECT_EQ(mid[1], -2.0 + r * std::sin(half));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(start_angle_of(m)), std::bit_cast<std::uint64_t>(angle));
    // A line over it: no angle due, 0 (also over an arc whose angle was never asked).
    line_move_into(m, 600.0, SegmentRole::kContour, 4);
    EXPECT_FALSE(m.angle_due);
    EXPECT_EQ(start_angle_of(m), 0.0);
    arc_move_into(m, {0, 1}, 1.0, -2.0, true, 600.0, SegmentRole::kContour, 3);
    ASSERT_TRUE(m.angle_due);
    line_move_into(m, 600.0, SegmentRole::kContour, 4);
    EXPECT_FALSE(m.angle_due);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(start_angle_of(m)), std::bit_cast<std::uint64_t>(0.0));
    // tangent_at asks as well.
    arc_move_into(m, {0, 1}, 1.0, -2.0, true, 600.0, SegmentRole::kContour, 3);
    EXPECT_TRUE(m.angle_due);
    AxisVector t{};
    tangent_at(m, 0, 2, t);
    EXPECT_FALSE(m.angle_due);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(m.start_angle), std::bit_cast<std::uint64_t>(angle));
}
