// SPDX-License-Identifier: MIT
// The bound the spooler checks a programmed move's cycle limit with before it builds the move
// (path_length_bound, surely_within_move_limit): at least twice the move's computed length, and
// never "surely within" for a move beyond the limit. Random lines and arcs over all axes,
// coordinates rounded to 3 to 6 decimals, full circles, tiny moves, feeds around the limit.
// And arc_move's full-circle test without its root where the chord is clearly apart.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "rng.h"
#include "rwmos/motion/interpolator.h"

using namespace rwmos::motion;

namespace {

using apci::test::Rng;

double rounded(double v, int decimals) {
    if (decimals == 0) return v;
    const double scale = std::pow(10.0, decimals);
    return std::round(v * scale) / scale;
}

struct RandomMove {
    AxisVector start{};
    AxisVector end{};
    bool arc = false;
    std::array<std::uint8_t, 2> plane{0, 1};
    double cx = 0.0, cy = 0.0;
    bool ccw = false;
};

RandomMove random_move(Rng& rng) {
    RandomMove m;
    const int decimals = static_cast<int>(rng.next() % 5) + 2;  // 2: not rounded
    const double size = rng.log_uniform(1e-6, 1e5);
    for (std::size_t a = 0; a < m.start.size(); ++a) {
        m.start[a] = rounded(rng.uniform(-1e5 + size, 1e5 - size), decimals == 2 ? 0 : decimals);
        m.end[a] = rng.chance(0.5) ? m.start[a]
                                   : rounded(m.start[a] + rng.uniform(-size, size),
                                             decimals == 2 ? 0 : decimals);
    }
    m.arc = rng.chance(0.6);
    if (!m.arc) return m;
    m.plane[0] = static_cast<std::uint8_t>(rng.next() % 8);
    m.plane[1] = static_cast<std::uint8_t>((m.plane[0] + 1 + rng.next() % 7) % 8);
    m.ccw = rng.chance(0.5);
    const double angle = rng.uniform(-std::numbers::pi, std::numbers::pi);
    m.cx = rounded(m.start[m.plane[0]] + size * std::cos(angle), decimals == 2 ? 0 : decimals);
    m.cy = rounded(m.start[m.plane[1]] + size * std::sin(angle), decimals == 2 ? 0 : decimals);
    const double r = std::hypot(m.start[m.plane[0]] - m.cx, m.start[m.plane[1]] - m.cy);
    if (rng.chance(0.15)) {  // a full circle
        m.end[m.plane[0]] = m.start[m.plane[0]];
        m.end[m.plane[1]] = m.start[m.plane[1]];
    } else {
        const double to = rng.uniform(-std::numbers::pi, std::numbers::pi);
        m.end[m.plane[0]] = rounded(m.cx + r * std::cos(to), decimals == 2 ? 0 : decimals);
        m.end[m.plane[1]] = rounded(m.cy + r * std::sin(to), decimals == 2 ? 0 : decimals);
    }
    return m;
}

Move build(const RandomMove& r, double feed) {
    return r.arc ? arc_move(r.start, r.end, r.plane, r.cx, r.cy, r.ccw, feed,
                            SegmentRole::kUncompensated, 1)
                 : line_move(r.start, r.end, feed, SegmentRole::kUncompensated, 1);
}

double bound_of(const RandomMove& r) {
    return path_length_bound(r.start, r.end, r.arc ? &r.plane : nullptr, r.cx, r.cy);
}

}  // namespace

TEST(PathLengthBound, IsAtLeastTwiceTheComputedLengthOfRandomMoves) {
    Rng rng(0xb0'0d);
    for (int i = 0; i < 50000; ++i) {
        const RandomMove r = random_move(rng);
        const double length = path_length(build(r, 1000.0));
        ASSERT_GE(bound_of(r), 2.0 * length) << i;
    }
}

TEST(PathLengthBound, OfAFullCircleCoversItsCircumferenceTwice) {
    AxisVector s{};
    s[0] = 10.0;
    const std::array<std::uint8_t, 2> plane{0, 1};
    const Move m = arc_move(s, s, plane, 0.0, 0.0, true, 1000.0, SegmentRole::kUncompensated, 1);
    EXPECT_NEAR(path_length(m), 20.0 * std::numbers::pi, 1e-12);
    EXPECT_GE(path_length_bound(s, s, &plane, 0.0, 0.0), 40.0 * std::numbers::pi);
}

TEST(SurelyWithinMoveLimit, NeverHoldsForAMoveBeyondTheLimit) {
    // Feeds that put each move's cycle count from far below to far above the limit.
    Rng rng(0xfeed);
    int surely = 0, beyond = 0;
    for (int i = 0; i < 50000; ++i) {
        const RandomMove r = random_move(rng);
        const double cycle = rng.chance(0.5) ? 0.001 : rng.log_uniform(2.5e-4, 0.01);
        const double length = path_length(build(r, 1000.0));
        if (!(length > 0.0)) continue;
        // cycles = length / (feed / 60 * cycle): aim at the limit times a factor of 1e-3 .. 1e3.
        const double feed = length / (static_cast<double>(kMaxMoveCycles) *
                                      rng.log_uniform(1e-3, 1e3) * cycle / 60.0);
        const Move m = build(r, feed);
        const bool within = within_move_limit(m, cycle);
        const bool sure = surely_within_move_limit(r.start, r.end, r.arc ? &r.plane : nullptr, r.cx,
                                                   r.cy, feed, cycle);
        if (sure) {
            ++surely;
            ASSERT_TRUE(within) << i;
        }
        beyond += within ? 0 : 1;
    }
    EXPECT_GT(surely, 10000);
    EXPECT_GT(beyond, 10000);
}

TEST(SurelyWithinMoveLimit, HoldsForOrdinaryMovesAndNotForAZeroFeed) {
    AxisVector s{}, e{};
    e[0] = 10.0;
    e[2] = -3.0;
    EXPECT_TRUE(surely_within_move_limit(s, e, nullptr, 0.0, 0.0, 600.0, 0.001));
    const std::array<std::uint8_t, 2> plane{0, 1};
    EXPECT_TRUE(surely_within_move_limit(s, e, &plane, 5.0, 0.0, 600.0, 0.001));
    EXPECT_FALSE(surely_within_move_limit(s, e, nullptr, 0.0, 0.0, 0.0, 0.001));
    // 10 mm at 1e-6 mm/min takes 6e11 cycles of 1 ms: beyond.
    EXPECT_FALSE(surely_within_move_limit(s, e, nullptr, 0.0, 0.0, 1e-6, 0.001));
    EXPECT_FALSE(within_move_limit(line_move(s, e, 1e-6, SegmentRole::kUncompensated, 1), 0.001));
}

TEST(ArcMove, AFullCircleIsTheChordWithinTheToleranceAsByItsLength) {
    // arc_move reads a chord with a component over twice kFullCircleTolerance as apart without
    // its hypot: the sweep is the one the chord's length gives, near the tolerance too.
    Rng rng(0xc1'4c1e);
    int full = 0, apart = 0;
    for (int i = 0; i < 100000; ++i) {
        AxisVector s{}, e{};
        const double cx = rng.uniform(-1e5, 1e5), cy = rng.uniform(-1e5, 1e5);
        const double r = rng.log_uniform(1e-6, 1e3);
        const double a = rng.uniform(-std::numbers::pi, std::numbers::pi);
        s[0] = cx + r * std::cos(a);
        s[1] = cy + r * std::sin(a);
        const double chord = rng.log_uniform(1e-11, 1e-7);
        const double b = rng.uniform(-std::numbers::pi, std::numbers::pi);
        e[0] = s[0] + chord * std::cos(b);
        e[1] = s[1] + chord * std::sin(b);
        const bool ccw = rng.chance(0.5);
        const Move m = arc_move(s, e, {0, 1}, cx, cy, ccw, 100.0, SegmentRole::kContour, 1);
        const double sx = s[0] - cx, sy = s[1] - cy, ex = e[0] - cx, ey = e[1] - cy;
        // The chord's length decides (hypot), the one sweep (geom::arc_sweep) does the rest.
        const bool whole = !(std::hypot(ex - sx, ey - sy) > kFullCircleTolerance);
        ++(whole ? full : apart);
        ASSERT_EQ(m.sweep, geom::arc_sweep({sx, sy}, {ex, ey}, ccw, whole)) << i;
    }
    EXPECT_GT(full, 10000);
    EXPECT_GT(apart, 10000);
}
