// SPDX-License-Identifier: MIT
// The gouge check's model of what a program leaves standing (tools/runlib/src/wall_model.h,
// docs/compensation.md "What is a wall") and the closed-contour geometry under it
// (contour_loop.h): areas, winding, enclosure; loops, leads and the runs beside them, passes
// that clear each other and those that do not, levels, CDOF, each rule at its edge.
#include "wall_model.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "apci/run/plane_distance.h"
#include "apci/run/slab.h"
#include "chunked_array.h"
#include "contour_loop.h"
#include "held_calls.h"
#include "probe_table.h"

namespace {

namespace plane = apci::run::plane;
using apci::run::detail::WallModel;
using apci::run::detail::WallRole;
using plane::Parametric;
using plane::Vec2;

constexpr double kPi = std::numbers::pi;

Parametric line(double x0, double y0, double x1, double y1) {
    return plane::line_element({x0, y0}, {x1, y1});
}
Parametric arc(double x0, double y0, double x1, double y1, double cx, double cy, bool ccw) {
    return plane::arc_element({x0, y0}, {x1, y1}, {cx, cy}, ccw);
}

// A rectangle from (x0, y0) to (x1, y1), counter-clockwise (or clockwise) from (x0, y0).
std::vector<Parametric> rectangle(double x0, double y0, double x1, double y1, bool ccw = true) {
    std::vector<Parametric> r{line(x0, y0, x1, y0), line(x1, y0, x1, y1), line(x1, y1, x0, y1),
                              line(x0, y1, x0, y0)};
    if (!ccw) {
        std::vector<Parametric> back;
        back.reserve(r.size());
        for (std::size_t i = r.size(); i-- > 0;)
            back.push_back(line(r[i].end.x(), r[i].end.y(), r[i].start.x(), r[i].start.y()));
        return back;
    }
    return r;
}

// A circle about (cx, cy) of radius r as one full arc from its right.
std::vector<Parametric> circle(double cx, double cy, double r, bool ccw = true) {
    return {arc(cx + r, cy, cx + r, cy, cx, cy, ccw)};
}

// ---- contour_loop.h

TEST(ContourLoop, SignedAreaIsPositiveCounterClockwiseAndCountsArcSegments) {
    EXPECT_NEAR(plane::signed_area(rectangle(0, 0, 2, 3)), 6.0, 1e-12);
    EXPECT_NEAR(plane::signed_area(rectangle(0, 0, 2, 3, false)), -6.0, 1e-12);
    EXPECT_NEAR(plane::signed_area(circle(5, 5, 2)), 4 * kPi, 1e-12);
    EXPECT_NEAR(plane::signed_area(circle(5, 5, 2, false)), -4 * kPi, 1e-12);
    // A half disc: the arc over the top and the diameter back.
    const std::vector<Parametric> half{arc(1, 0, -1, 0, 0, 0, true), line(-1, 0, 1, 0)};
    EXPECT_NEAR(plane::signed_area(half), kPi / 2, 1e-12);
    // A 4 x 2 rectangle with corners rounded to 0.5: 8 - (4 - pi) 0.25.
    const double f = 0.5;
    const std::vector<Parametric> rounded{
        line(f, 0, 4 - f, 0), arc(4 - f, 0, 4, f, 4 - f, f, true),
        line(4, f, 4, 2 - f), arc(4, 2 - f, 4 - f, 2, 4 - f, 2 - f, true),
        line(4 - f, 2, f, 2), arc(f, 2, 0, 2 - f, f, 2 - f, true),
        line(0, 2 - f, 0, f), arc(0, f, f, 0, f, f, true)};
    EXPECT_NEAR(plane::signed_area(rounded), 8 - (4 - kPi) * f * f, 1e-12);
}

TEST(ContourLoop, WindingNumberInsideOutsideAndInAnArcsBulge) {
    const auto r = rectangle(0, 0, 4, 4);
    EXPECT_EQ(plane::winding_number(r, {2, 2}), 1);
    EXPECT_EQ(plane::winding_number(r, {5, 2}), 0);
    EXPECT_EQ(plane::winding_number(rectangle(0, 0, 4, 4, false), {2, 2}), -1);
    EXPECT_EQ(plane::winding_number(circle(0, 0, 3), {2.9, 0.1}), 1);
    EXPECT_EQ(plane::winding_number(circle(0, 0, 3), {3.1, 0}), 0);
    // A D shape: the diameter along y = 0 and the arc over the top. Points between the chord
    // and the arc, and just beyond the arc, and just below the chord.
    const std::vector<Parametric> d{line(-2, 0, 2, 0), arc(2, 0, -2, 0, 0, 0, true)};
    EXPECT_EQ(plane::winding_number(d, {0, 1.99}), 1);
    EXPECT_EQ(plane::winding_number(d, {1.4, 1.4}), 1);    // 1.98 from the centre
    EXPECT_EQ(plane::winding_number(d, {1.42, 1.42}), 0);  // 2.008 from it
    EXPECT_EQ(plane::winding_number(d, {0, -0.01}), 0);
    // The same D the other way round, the arc below: the region is on the arc's other side.
    const std::vector<Parametric> down{line(2, 0, -2, 0), arc(-2, 0, 2, 0, 0, 0, true)};
    EXPECT_EQ(plane::winding_number(down, {0, -1.99}), 1);
    EXPECT_EQ(plane::winding_number(down, {0, 0.01}), 0);
}

TEST(ContourLoop, BoundsHoldEveryPointOfArcsThatPassAnAxisDirection) {
    const plane::Bounds b = plane::bounds(circle(1, 2, 3));
    EXPECT_NEAR(b.lo.x(), -2, 1e-12);
    EXPECT_NEAR(b.hi.x(), 4, 1e-12);
    EXPECT_NEAR(b.lo.y(), -1, 1e-12);
    EXPECT_NEAR(b.hi.y(), 5, 1e-12);
    // A quarter arc from (1, 0) to (0, 1) about the origin: its box is the unit square.
    const Parametric q = arc(1, 0, 0, 1, 0, 0, true);
    const plane::Bounds qb = plane::bounds(std::vector<Parametric>{q});
    EXPECT_NEAR(qb.lo.x(), 0, 1e-12);
    EXPECT_NEAR(qb.lo.y(), 0, 1e-12);
    EXPECT_NEAR(qb.hi.x(), 1, 1e-12);
    EXPECT_NEAR(qb.hi.y(), 1, 1e-12);
    for (int i = 0; i <= 100; ++i) {
        const Vec2 p = plane::point_at(q, i / 100.0);
        EXPECT_GE(p.x(), qb.lo.x() - 1e-12);
        EXPECT_LE(p.x(), qb.hi.x() + 1e-12);
        EXPECT_GE(p.y(), qb.lo.y() - 1e-12);
        EXPECT_LE(p.y(), qb.hi.y() + 1e-12);
    }
}

TEST(ContourLoop, WithinTellsNestedTouchingSameCrossingAndTheBudget) {
    const auto outer = rectangle(0, 0, 10, 10);
    constexpr double tol = 1e-4;
    EXPECT_EQ(plane::within(outer, rectangle(2, 2, 8, 8), tol, 1 << 20), plane::Within::kWithin);
    EXPECT_EQ(plane::within(rectangle(2, 2, 8, 8), outer, tol, 1 << 20), plane::Within::kNot);
    // The same contour is not within itself.
    EXPECT_EQ(plane::within(outer, rectangle(0, 0, 10, 10), tol, 1 << 20), plane::Within::kNot);
    // Touching along a side (a pass widened on three sides only): within.
    EXPECT_EQ(plane::within(outer, rectangle(0, 2, 8, 8), tol, 1 << 20), plane::Within::kWithin);
    // A side just outside by more than the tolerance: not; by less: within.
    EXPECT_EQ(plane::within(outer, rectangle(2, 2, 10 + 2 * tol, 8), tol, 1 << 20),
              plane::Within::kNot);
    EXPECT_EQ(plane::within(outer, rectangle(2, 2, 10 + 0.5 * tol, 8), tol, 1 << 20),
              plane::Within::kWithin);
    // Crossing: not.
    EXPECT_EQ(plane::within(outer, rectangle(5, 5, 15, 8), tol, 1 << 20), plane::Within::kNot);
    // A C shape (a U opening to the right) whose box holds a square in its gap: not within.
    const std::vector<Parametric> c{line(0, 0, 10, 0),   line(10, 0, 10, 3), line(10, 3, 3, 3),
                                    line(3, 3, 3, 7),    line(3, 7, 10, 7),  line(10, 7, 10, 10),
                                    line(10, 10, 0, 10), line(0, 10, 0, 0)};
    EXPECT_EQ(plane::within(c, rectangle(5, 4, 8, 6), tol, 1 << 20), plane::Within::kNot);
    EXPECT_EQ(plane::within(c, rectangle(0.5, 0.5, 2, 2), tol, 1 << 20), plane::Within::kWithin);
    // Within the C's box, near its sides and partly in its gap: touching its left side (a pass
    // widened on some sides only, but into the gap), or crossing its lower arm: not within.
    EXPECT_EQ(plane::within(c, rectangle(0, 4, 8, 6), tol, 1 << 20), plane::Within::kNot);
    EXPECT_EQ(plane::within(c, rectangle(1, 2, 8, 6), tol, 1 << 20), plane::Within::kNot);
    EXPECT_EQ(plane::within(c, rectangle(0, 4, 2, 6), tol, 1 << 20), plane::Within::kWithin);
    // The budget: 4 x 4 element pairs, at the budget decided, one below it unknown.
    EXPECT_EQ(plane::within(outer, rectangle(2, 2, 8, 8), tol, 16), plane::Within::kWithin);
    EXPECT_EQ(plane::within(outer, rectangle(2, 2, 8, 8), tol, 15), plane::Within::kUnknown);
}

// ---- wall_model.h

// An element as the model takes it (PlaneMove), at the level z.
apci::run::detail::PlaneMove move_of(const Parametric& e, double z) {
    apci::run::detail::PlaneMove m;
    m.start = e.start;
    m.end = e.end;
    m.arc = is_arc(e);
    m.ccw = e.sweep > 0.0;
    m.centre = e.centre;
    m.low = m.high = z;
    return m;
}

// Feeds the elements of one stretch (tool on `side`, at Z `z`), numbering them from `first`.
std::uint64_t feed(WallModel& m, std::uint64_t first, const std::vector<Parametric>& elements,
                   int side = 1, double z = 0.0, bool walls = true, int plane = 17) {
    m.begin(plane, side);
    std::uint64_t n = first;
    for (const Parametric& e : elements) {
        m.element(n, move_of(e, z), (n + 1) * 0x9E3779B97F4A7C15ULL, walls, false);
        ++n;
    }
    m.end();
    return n;
}

// A closed square of side 2a about (cx, cy), from the middle of its top, clockwise (tool
// outside for G41) or counter-clockwise; with `lead` lead-in and lead-out elements (a line
// from above and a line away).
std::vector<Parametric> square_stretch(double cx, double cy, double a, bool clockwise, int lead_in,
                                       int lead_out) {
    std::vector<Parametric> s;
    const double top = cy + a;
    for (int i = lead_in; i > 0; --i)
        s.push_back(line(cx - i, top + 5, cx - (i - 1), i == 1 ? top : top + 5));
    if (clockwise) {
        s.push_back(line(cx, top, cx + a, top));
        s.push_back(line(cx + a, top, cx + a, cy - a));
        s.push_back(line(cx + a, cy - a, cx - a, cy - a));
        s.push_back(line(cx - a, cy - a, cx - a, top));
        s.push_back(line(cx - a, top, cx, top));
    } else {
        s.push_back(line(cx, top, cx - a, top));
        s.push_back(line(cx - a, top, cx - a, cy - a));
        s.push_back(line(cx - a, cy - a, cx + a, cy - a));
        s.push_back(line(cx + a, cy - a, cx + a, top));
        s.push_back(line(cx + a, top, cx, top));
    }
    for (int i = 0; i < lead_out; ++i) s.push_back(line(cx + i, top + i, cx + i + 1, top + i + 1));
    return s;
}

std::vector<WallRole> roles(WallModel& m, std::uint64_t first, std::uint64_t end) {
    std::vector<WallRole> out;
    for (std::uint64_t i = first; i < end; ++i) out.push_back(m.role(i));
    return out;
}

constexpr WallRole W = WallRole::kWall, L = WallRole::kLead, C = WallRole::kCleared,
                   O = WallRole::kOff;

TEST(WallModel, LeadsBesideALoopAreNoWallsAndTheLoopIs) {
    WallModel m;
    const auto s = square_stretch(0, 0, 10, true, 2, 2);
    const std::uint64_t end = feed(m, 0, s);
    EXPECT_EQ(roles(m, 0, end), (std::vector<WallRole>{L, L, W, W, W, W, W, L, L}));
    EXPECT_EQ(m.loops(), 1U);
    EXPECT_TRUE(m.looped(2));
    EXPECT_FALSE(m.looped(1));
}

TEST(WallModel, AtMostTwoElementsBesideALoopAreLeads) {
    // Three before the loop: the first is an open contour's (a wall); three after: the last.
    WallModel m;
    const std::uint64_t end = feed(m, 0, square_stretch(0, 0, 10, true, 3, 3));
    EXPECT_EQ(roles(m, 0, end), (std::vector<WallRole>{W, L, L, W, W, W, W, W, L, L, W}));
}

TEST(WallModel, ARunBetweenTwoLoopsHasLeadsAtBothEndsAndWallsBetween) {
    // Loop, five elements, loop: two leads after the first, one wall, two leads before the
    // second. With four between them every one is a lead.
    for (const int between : {4, 5}) {
        std::vector<Parametric> s = rectangle(0, 0, 10, 10);
        double x = 0, y = 0;
        for (int i = 0; i < between; ++i) {
            s.push_back(line(x, y, x + 5, y - 5));
            x += 5, y -= 5;
        }
        for (const Parametric& e : rectangle(x, y, x + 3, y + 3)) s.push_back(e);
        WallModel m;
        const std::uint64_t end = feed(m, 0, s);
        std::vector<WallRole> want(4, W);
        for (int i = 0; i < between; ++i) want.push_back(between == 5 && i == 2 ? W : L);
        for (int i = 0; i < 4; ++i) want.push_back(W);
        EXPECT_EQ(roles(m, 0, end), want) << between << " between";
        EXPECT_EQ(m.loops(), 2U);
    }
}

TEST(WallModel, AStretchWithoutALoopIsAnOpenContourOfWalls) {
    WallModel m;
    const std::uint64_t end =
        feed(m, 0, {line(0, 0, 10, 0), line(10, 0, 10, 10), line(10, 10, 0, 10.001)});
    EXPECT_EQ(roles(m, 0, end), (std::vector<WallRole>{W, W, W}));
    EXPECT_EQ(m.loops(), 0U);
}

TEST(WallModel, AnEndWithinTheToleranceOfAnEarlierStartClosesALoopAndBeyondItDoesNot) {
    for (const double gap : {0.5 * WallModel::kTolerance, 2 * WallModel::kTolerance}) {
        WallModel m;
        feed(m, 0, {line(0, 0, 10, 0), line(10, 0, 10, 10), line(10, 10, 0, gap)});
        EXPECT_EQ(m.loops(), gap < WallModel::kTolerance ? 1U : 0U) << gap;
    }
}

TEST(WallModel, AnEndExactlyTheToleranceFromAnEarlierStartClosesALoop) {
    // Few elements pending (walked in order) and more than 64 (looked up by cell): the same
    // rule, the distance at most the tolerance.
    for (const int sides : {3, 80}) {
        std::vector<Parametric> s;
        for (int i = 0; i + 1 < sides; ++i) {
            const double a0 = 2 * kPi * i / sides, a1 = 2 * kPi * (i + 1) / sides;
            s.push_back(line(10 * std::sin(a0), 10 - 10 * std::cos(a0), 10 * std::sin(a1),
                             10 - 10 * std::cos(a1)));
        }
        // The last side back to the first start (0, 0), ending exactly the tolerance above it.
        s.push_back(line(s.back().end.x(), s.back().end.y(), 0.0, WallModel::kTolerance));
        WallModel m;
        const std::uint64_t end = feed(m, 0, s);
        EXPECT_EQ(m.loops(), 1U) << sides << " sides";
        EXPECT_EQ(roles(m, 0, end), std::vector<WallRole>(s.size(), W)) << sides << " sides";
        // 1.5 tolerances above it (in the next cell of the lookup): no loop.
        s.back() = line(s.back().start.x(), s.back().start.y(), 0.0, 1.5 * WallModel::kTolerance);
        WallModel open;
        feed(open, 0, s);
        EXPECT_EQ(open.loops(), 0U) << sides << " sides";
    }
}

TEST(WallModel, ALoopClosesAtTheEarliestStartWithinTheTolerance) {
    // A first element 1.5 tolerances long (it does not close on itself): the last end, half way
    // along it, lies within the tolerance of both its start and the next one's. The loop is
    // all four elements (none is a lead).
    const double step = 1.5 * WallModel::kTolerance;
    WallModel m;
    const std::uint64_t end = feed(m, 0,
                                   {line(0, 0, step, 0), line(step, 0, 10, 0), line(10, 0, 10, 10),
                                    line(10, 10, 0.5 * step, 0)});
    EXPECT_EQ(m.loops(), 1U);
    EXPECT_EQ(roles(m, 0, end), (std::vector<WallRole>{W, W, W, W}));
    EXPECT_TRUE(m.looped(0));
}

TEST(WallModel, ALoopsGeometryIsItsOwnElementsNotTheLeadsBeforeIt) {
    // The same rectangle after two different lead-ins: one loop (the leads are not part of its
    // key, which says what geometry it is), and the leads are leads each time.
    const auto r = rectangle(0, 0, 10, 10);
    WallModel m;
    std::uint64_t n = 0;
    for (const double from : {-5.0, -7.0}) {
        m.begin(17, 1);
        m.element(n++, move_of(line(from, -3, 0, 0), -1), 900 + static_cast<int>(-from), true,
                  false);
        for (std::uint64_t i = 0; i < 4; ++i)
            m.element(n++, move_of(r[i], -1), 100 + i, true, from != -5.0);
        m.end();
    }
    EXPECT_EQ(m.loops(), 1U);
    EXPECT_EQ(m.role(0), L);
    EXPECT_EQ(m.role(5), L);
    EXPECT_EQ(m.role(1), W);
}

TEST(WallModel, ElementsArePlacedWhenTheirStretchEnds) {
    WallModel m;
    m.begin(17, 1);
    const auto s = rectangle(0, 0, 10, 10);
    for (std::uint64_t i = 0; i < s.size(); ++i) m.element(i, move_of(s[i], 0), i + 1, true, false);
    // The loop closed, but the stretch runs: a later, larger pass may clear it.
    EXPECT_FALSE(m.placed(0));
    EXPECT_EQ(m.role(0), WallRole::kUndecided);
    const std::uint64_t before = m.generation();
    m.end();
    EXPECT_GT(m.generation(), before);
    EXPECT_TRUE(m.placed(0));
    EXPECT_EQ(m.role(0), W);
}

TEST(WallModel, PocketPassesEnclosedByALargerOneAreClearedAndItIsAWall) {
    // G41 counter-clockwise: the tool inside (pockets). Inside-out and outside-in, one stretch
    // per pass, and all passes in one stretch.
    const auto pass = [](double a) { return square_stretch(0, 0, a, false, 2, 1); };
    {
        WallModel m;
        const std::uint64_t a = feed(m, 0, pass(5));
        const std::uint64_t b = feed(m, a, pass(8));
        EXPECT_EQ(m.role(2), C);  // the small pass's first loop element
        EXPECT_EQ(m.role(a + 2), W);
        (void)b;
    }
    {
        WallModel m;
        const std::uint64_t a = feed(m, 0, pass(8));
        feed(m, a, pass(5));
        EXPECT_EQ(m.role(2), W);
        EXPECT_EQ(m.role(a + 2), C);
    }
    {
        std::vector<Parametric> both = pass(5);
        for (const Parametric& e : pass(8)) both.push_back(e);
        WallModel m;
        feed(m, 0, both);
        EXPECT_EQ(m.role(2), C);
        EXPECT_EQ(m.role(pass(5).size() + 2), W);
    }
}

// An arc's terms given with its move (as the check gives those it made for its grid) are the
// ones the loop takes: round pocket passes (full circles, tool inside) fed with their own terms
// clear as those fed without; fed with the opposite sweep (terms that are not the arc's, which
// no caller gives) the loops turn the other way: bosses, the larger one cleared (a roughing
// pass round the smaller), the smaller a wall.
TEST(WallModel, ALoopTakesTheArcTermsGivenWithItsMoves) {
    const auto feed_circles = [](WallModel& m, int terms) {  // 0 none, 1 its own, -1 reversed
        std::uint64_t n = 0;
        m.begin(17, 1);
        for (const double r : {3.0, 6.0}) {
            const Parametric c = circle(0, 0, r).front();
            apci::run::detail::PlaneMove mv = move_of(c, 0.0);
            mv.terms = terms != 0;
            mv.sweep = terms < 0 ? -c.sweep : c.sweep;
            mv.phi0 = c.phi0;
            m.element(n, mv, (n + 1) * 0x9E3779B97F4A7C15ULL, true, false);
            ++n;
            const Parametric join = line(r, 0, r + 3, 0);
            if (r < 6.0) {
                m.element(n, move_of(join, 0.0), (n + 1) * 0x51ULL, true, false);
                ++n;
            }
        }
        m.end();
    };
    for (const int terms : {0, 1}) {
        WallModel m;
        feed_circles(m, terms);
        EXPECT_EQ(m.role(0), C) << terms;
        EXPECT_EQ(m.role(2), W) << terms;
    }
    WallModel reversed;
    feed_circles(reversed, -1);
    EXPECT_EQ(reversed.role(0), W);
    EXPECT_EQ(reversed.role(2), C);
}

TEST(WallModel, BossPassesEnclosingASmallerOneAreClearedAndTheSmallestIsAWall) {
    // G41 clockwise: the tool outside (bosses); roughing passes round the finished part.
    WallModel m;
    const std::uint64_t a = feed(m, 0, square_stretch(0, 0, 12, true, 2, 1));
    feed(m, a, square_stretch(0, 0, 10, true, 2, 1));
    EXPECT_EQ(m.role(2), C);
    EXPECT_EQ(m.role(a + 2), W);
}

TEST(WallModel, AnIslandAndItsPocketAndSideBySidePartsClearNothing) {
    WallModel m;
    // A pocket (tool inside) with an island (tool outside) in it.
    const std::uint64_t a = feed(m, 0, square_stretch(0, 0, 20, false, 2, 1));
    const std::uint64_t b = feed(m, a, square_stretch(0, 0, 5, true, 2, 1));
    EXPECT_EQ(m.role(2), W);
    EXPECT_EQ(m.role(a + 2), W);
    // Two bosses side by side, two pockets side by side, overlapping bosses.
    const std::uint64_t c = feed(m, b, square_stretch(100, 0, 5, true, 2, 1));
    const std::uint64_t d = feed(m, c, square_stretch(112, 0, 5, true, 2, 1));
    const std::uint64_t e = feed(m, d, square_stretch(200, 0, 5, false, 2, 1));
    const std::uint64_t f = feed(m, e, square_stretch(212, 0, 5, false, 2, 1));
    const std::uint64_t g = feed(m, f, square_stretch(300, 0, 5, true, 2, 1));
    feed(m, g, square_stretch(303, 0, 5, true, 2, 1));
    for (const std::uint64_t at : {b, c, d, e, f, g}) EXPECT_EQ(m.role(at + 2), W) << at;
}

TEST(WallModel, APassClearsOnlyAtItsOwnLevel) {
    // The smaller pocket pass at Z -1, the larger at a level apart by just more than the
    // tolerance (a wider pocket below: an undercut) or just within it.
    for (const double dz : {2 * WallModel::kTolerance, 0.5 * WallModel::kTolerance}) {
        WallModel m;
        const std::uint64_t a = feed(m, 0, square_stretch(0, 0, 5, false, 2, 1), 1, -1.0);
        feed(m, a, square_stretch(0, 0, 8, false, 2, 1), 1, -1.0 - dz);
        EXPECT_EQ(m.role(2), dz > WallModel::kTolerance ? W : C) << dz;
    }
}

TEST(WallModel, APassAboveClearsOnlyWithinTheToleranceOfItsLevel) {
    // The larger pocket pass above the smaller one (a pocket narrower below: a step, whose lower
    // walls stay), apart by just more than the tolerance or just within it.
    for (const double dz : {2 * WallModel::kTolerance, 0.5 * WallModel::kTolerance}) {
        WallModel m;
        const std::uint64_t a = feed(m, 0, square_stretch(0, 0, 5, false, 2, 1), 1, -1.0);
        feed(m, a, square_stretch(0, 0, 8, false, 2, 1), 1, -1.0 + dz);
        EXPECT_EQ(m.role(2), dz > WallModel::kTolerance ? W : C) << dz;
    }
}

TEST(WallModel, ALoopOfManyElementsClosesWithinTheToleranceAcrossCellBoundaries) {
    // More than kScanned pending elements: a start is found by cells of the tolerance. A polygon
    // of 100 sides from (10.00005, 5.00005) (the middle of its cell) whose last side ends 0.7
    // tolerances beside that, in each direction: in the next cell over, or the next row.
    const double step = 0.7 * WallModel::kTolerance;
    for (const Vec2& off : {Vec2(-step, 0), Vec2(step, 0), Vec2(0, -step), Vec2(0, step)}) {
        const Vec2 start(10.00005, 5.00005), centre(10.00005 - 20.0, 5.00005);
        std::vector<Parametric> s;
        Vec2 from = start;
        for (int k = 1; k <= 100; ++k) {
            const double a = 2.0 * kPi * k / 100.0;
            const Vec2 to =
                k == 100 ? Vec2(start + off) : Vec2(centre + 20.0 * Vec2(std::cos(a), std::sin(a)));
            s.push_back(line(from.x(), from.y(), to.x(), to.y()));
            from = to;
        }
        WallModel m;
        feed(m, 0, s);
        EXPECT_EQ(m.loops(), 1U) << off.transpose();
        EXPECT_TRUE(m.looped(0)) << off.transpose();
        EXPECT_TRUE(m.looped(99)) << off.transpose();
    }
}

TEST(WallModel, TheSameContourAgainFromAnotherCornerIsOneLoop) {
    // A depth pass runs the rectangle again from its opposite corner: the same keys (the
    // geometry of each element), in another order: one loop. Other keys: another loop.
    const auto r = rectangle(0, 0, 10, 10);
    for (const bool same : {true, false}) {
        WallModel m;
        m.begin(17, 1);
        for (std::uint64_t i = 0; i < 4; ++i) m.element(i, move_of(r[i], -1), 100 + i, true, false);
        m.end();
        m.begin(17, 1);
        for (std::uint64_t i = 0; i < 4; ++i) {
            const std::uint64_t k = (i + 2) % 4;
            m.element(4 + i, move_of(r[k], -2), (same ? 100 : 200) + k, true, same);
        }
        m.end();
        EXPECT_EQ(m.loops(), same ? 1U : 2U);
    }
}

TEST(WallModel, ElementsUnderCdofAreNoWalls) {
    WallModel m;
    const std::uint64_t end = feed(m, 0, square_stretch(0, 0, 10, true, 2, 2), 1, 0.0, false);
    for (std::uint64_t i = 0; i < end; ++i) EXPECT_EQ(m.role(i), O) << i;
}

TEST(WallModel, AnOpenStretchLongerThanThePendingBoundPlacesItsOldestAtOnce) {
    WallModel m;
    m.begin(17, 1);
    const std::uint64_t n = WallModel::kMaxPending + 1;
    for (std::uint64_t i = 0; i < n; ++i)
        m.element(
            i,
            move_of(line(static_cast<double>(i), 0, static_cast<double>(i) + 1, 0.001 * (i % 2)),
                    0),
            i + 1, true, false);
    EXPECT_TRUE(m.placed(0));   // one past the bound: the oldest is an open contour's
    EXPECT_FALSE(m.placed(1));  // at the bound: still pending
    EXPECT_EQ(m.role(0), W);
    m.end();
    EXPECT_TRUE(m.placed(1));
}

TEST(WallModel, ALoopClosesAtAStartWhoseCellAnElementLetGoStartedInFirst) {
    // A long open stretch from P = (0, 0): its first element is let go (kMaxPending). A line
    // back to P closes nothing (nothing pending starts there); then a triangle from P closes a
    // loop where its last element ends: the start it ends at is P's, which the element let go
    // held first.
    WallModel m;
    m.begin(17, 1);
    const std::uint64_t n = WallModel::kMaxPending + 5;
    std::uint64_t i = 0;
    for (; i < n; ++i)
        m.element(i,
                  move_of(line(static_cast<double>(i), 0.001 * (i % 2), static_cast<double>(i) + 1,
                               0.001 * ((i + 1) % 2)),
                          0),
                  i + 1, true, false);
    EXPECT_TRUE(m.placed(0));
    const double y = 0.001 * (n % 2);
    m.element(i, move_of(line(static_cast<double>(n), y, 0, 0), 0), i + 1, true, false);
    ++i;
    EXPECT_FALSE(m.looped(i - 1));
    const std::uint64_t first = i;
    for (const Parametric& e : {line(0, 0, 0, -5), line(0, -5, -5, -5), line(-5, -5, 0, 0)}) {
        m.element(i, move_of(e, 0), i + 1, true, false);
        ++i;
    }
    m.end();
    EXPECT_TRUE(m.looped(first));
    EXPECT_TRUE(m.looped(first + 2));
    EXPECT_FALSE(m.looped(first - 1));
}

TEST(WallModel, ForgettingLetsGoOfLoopsBelowAndKeepsTheRest) {
    WallModel m;
    const std::uint64_t a = feed(m, 0, square_stretch(0, 0, 5, false, 2, 1));
    const std::uint64_t b = feed(m, a, square_stretch(100, 0, 5, false, 2, 1));
    EXPECT_EQ(m.loops(), 2U);
    m.forget_before(a);
    EXPECT_EQ(m.loops(), 1U);
    EXPECT_EQ(m.role(a + 2), W);
    // A larger pass about the second one still clears it.
    feed(m, b, square_stretch(100, 0, 8, false, 2, 1));
    EXPECT_EQ(m.role(a + 2), C);
}

// A contour run again with the same keys (its levels joined) after each of many other pockets,
// each forgotten before the contour's repeat: the contour's loop is kept, the pockets behind it
// let go (the index remade as they pile up), and what the loops say stays right.
TEST(WallModel, AContourKeptWhileThePocketsAfterItAreLetGo) {
    // Contour A: the same keys each time (its elements' geometry).
    const auto contour = [](WallModel& m, std::uint64_t first, double a) {
        m.begin(17, 1);
        std::uint64_t n = first;
        std::uint64_t key = 1;
        for (const Parametric& e : square_stretch(0, 0, a, false, 0, 0))
            m.element(n++, move_of(e, 0.0), 0xABCDEFULL * key++, true, false);
        m.end();
        return n;
    };
    WallModel m;
    std::uint64_t n = contour(m, 0, 8);
    for (int i = 0; i < 200; ++i) {
        n = feed(m, n, square_stretch(100.0 * (i + 1), 0, 5, false, 2, 1));
        const std::uint64_t repeat = n;
        n = contour(m, n, 8);
        m.forget_before(repeat);  // the pocket before the repeat goes, the contour stays
        ASSERT_EQ(m.loops(), 1U) << i;
    }
    // A smaller pass inside the contour kept is cleared by it.
    const std::uint64_t inner = n;
    n = feed(m, n, square_stretch(0, 0, 5, false, 2, 1));
    EXPECT_EQ(m.role(inner + 2), C);
    m.forget_before(n);
    EXPECT_EQ(m.loops(), 0U);
}

// A contour run again after another loop joins its first run, not the other's: a larger pass
// about it clears the repeat's elements.
TEST(WallModel, AContourRunAgainAfterAnotherLoopIsTheFirstRunsLoop) {
    const auto keyed = [](WallModel& m, std::uint64_t first, double cx, std::uint64_t base) {
        m.begin(17, 1);
        std::uint64_t n = first;
        std::uint64_t key = base;
        for (const Parametric& e : square_stretch(cx, 0, 5, false, 0, 0))
            m.element(n++, move_of(e, 0.0), 0x9E3779B9ULL * key++, true, false);
        m.end();
        return n;
    };
    WallModel m;
    std::uint64_t n = keyed(m, 0, 0, 1);  // A
    n = keyed(m, n, 100, 50);             // B
    const std::uint64_t again = n;
    n = keyed(m, n, 0, 1);  // A again: A's loop
    EXPECT_EQ(m.loops(), 2U);
    feed(m, n, square_stretch(0, 0, 8, false, 2, 1));  // a larger pass about A
    EXPECT_EQ(m.role(again + 1), C);
    EXPECT_EQ(m.role(1), C);
}

// Loops let go at the front (more than 1,024) are forgotten while the last pocket is held: its
// number stays, a smaller pass inside it is cleared by it, it stays a wall, and a larger pass
// about it clears it. Also where every loop was let go first.
TEST(WallModel, LoopsLetGoAtTheFrontAreForgottenAndTheLoopHeldAnswersAsBefore) {
    {
        WallModel m;
        std::uint64_t n = 0, last = 0;
        for (int i = 0; i < 1026; ++i) {
            last = n;
            n = feed(m, n, square_stretch(100.0 * i, 0, 8, false, 2, 1));
            m.forget_before(last);  // the pockets before this one
        }
        EXPECT_EQ(m.loops(), 1U);
        const std::uint64_t inner = n;
        n = feed(m, n, square_stretch(100.0 * 1025, 0, 5, false, 2, 1));
        EXPECT_EQ(m.role(inner + 2), C);
        EXPECT_EQ(m.role(last + 2), W);
        feed(m, n, square_stretch(100.0 * 1025, 0, 12, false, 2, 1));
        EXPECT_EQ(m.role(last + 2), C);
    }
    {
        WallModel m;
        std::uint64_t n = 0, last = 0;
        for (int i = 0; i < 1100; ++i) {
            m.forget_before(n);
            last = n;
            n = feed(m, n, square_stretch(100.0 * i, 0, 5, false, 2, 1));
        }
        EXPECT_EQ(m.loops(), 1U);
        feed(m, n, square_stretch(100.0 * 1099, 0, 8, false, 2, 1));
        EXPECT_EQ(m.role(last + 2), C);
        EXPECT_EQ(m.loops(), 2U);
    }
}

// A boss pass too wide for the index's cells (a box over 256 cells of 16 mm) is found among the
// wide loops: a larger one about it is cleared, behind a loop let go.
TEST(WallModel, AWideBossPassIsFoundAndClearsTheOneAboutIt) {
    WallModel m;
    std::uint64_t n = feed(m, 0, square_stretch(-1000, 0, 5, true, 2, 1));
    m.forget_before(n);  // let go: the wide ones come after it
    const std::uint64_t small = n;
    n = feed(m, n, square_stretch(0, 0, 200, true, 2, 1));  // a boss 400 mm across
    const std::uint64_t large = n;
    feed(m, n, square_stretch(0, 0, 210, true, 2, 1));  // 420 mm about it
    EXPECT_EQ(m.role(large + 2), C);
    EXPECT_EQ(m.role(small + 2), W);
}

// A model asked only where elements are placed (Asks::kPlacement) places every element as one
// asked for roles does: leads, CDOF, a loop's elements and an open contour's. It keeps nothing of
// the loops: no loop number, no clearing (a loop's element is a wall), none held.
TEST(WallModel, AModelAskedOnlyForPlacementPlacesAsTheOtherAndKeepsNoLoop) {
    WallModel roles_model;
    WallModel places(WallModel::Asks::kPlacement);
    std::uint64_t n = 0;
    const auto both = [&](const std::vector<Parametric>& s, bool walls) {
        feed(roles_model, n, s, 1, 0.0, walls);
        n = feed(places, n, s, 1, 0.0, walls);
    };
    both(square_stretch(0, 0, 5, false, 2, 1), true);           // a pocket pass, with leads
    both(square_stretch(0, 0, 8, false, 2, 1), true);           // a larger one clears it
    both(square_stretch(50, 0, 5, true, 1, 2), false);          // under CDOF
    both({line(100, 0, 110, 0), line(110, 0, 110, 10)}, true);  // an open contour
    std::size_t loops = 0, cleared = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
        SCOPED_TRACE(i);
        std::uint64_t loop_r = 0, loop_p = 0;
        const WallRole r = roles_model.placement(i, loop_r);
        EXPECT_EQ(places.placement(i, loop_p), r);
        EXPECT_EQ(places.looped(i), roles_model.looped(i));
        EXPECT_EQ(loop_p, WallModel::kNoLoop);
        if (roles_model.looped(i)) ++loops;
        if (roles_model.role(i) == C) {
            ++cleared;
            EXPECT_EQ(places.role(i), W);
        } else {
            EXPECT_EQ(places.role(i), roles_model.role(i));
        }
    }
    EXPECT_GT(loops, 10U);
    EXPECT_GT(cleared, 3U);
    EXPECT_EQ(places.loops(), 0U);
    EXPECT_FALSE(places.cleared(0));
    EXPECT_GT(roles_model.loops(), 0U);
}

// ---- chunked_array.h

// Items kept across chunks: each read back where it was put, over many chunk boundaries (chunks
// of three items here, and of 2 MiB), value-initialised when made.
TEST(ChunkedArray, KeepsEveryItemInOrderAcrossChunks) {
    struct Item {
        std::uint64_t a = 7;
        double b = 0.5;
    };
    using Small = apci::run::detail::ChunkedArray<Item, 3 * sizeof(Item)>;
    static_assert(Small::kPerChunk == 3);
    const auto fill = [](auto& array, std::uint64_t count, std::uint64_t base) {
        for (std::uint64_t i = 0; i < count; ++i) {
            Item& x = array.emplace_back();
            EXPECT_EQ(x.a, 7U);  // value-initialised
            EXPECT_EQ(x.b, 0.5);
            x.a = base + i;
            x.b = static_cast<double>(base + i) * 0.25;
        }
    };
    const auto expect_all = [](auto& array, std::uint64_t count, std::uint64_t base) {
        ASSERT_EQ(array.size(), count);
        for (std::uint64_t i = 0; i < count; ++i) {
            ASSERT_EQ(array[i].a, base + i) << i;
            ASSERT_EQ(array[i].b, static_cast<double>(base + i) * 0.25) << i;
        }
    };
    Small s;
    EXPECT_TRUE(s.empty());
    fill(s, 3, 0);  // exactly one chunk
    expect_all(s, 3, 0);
    EXPECT_FALSE(s.empty());
    fill(s, 29, 3);  // then across ten more boundaries
    expect_all(s, 32, 0);
    // The default chunks of 2 MiB: one item past the first chunk, and the first kept.
    apci::run::detail::ChunkedArray<Item> big;
    const std::uint64_t n = decltype(big)::kPerChunk + 2;
    fill(big, n, 0);
    expect_all(big, n, 0);
    // Chunks carved from a slab, two arrays sharing it: their chunks interleave in one block.
    apci::run::detail::Slab memory;
    Small carved(memory);
    using Wide = apci::run::detail::ChunkedArray<Item, apci::run::detail::Slab::kMostTaken>;
    Wide wide(memory);
    fill(carved, 31, 100);
    const std::uint64_t m = Wide::kPerChunk + 1;
    fill(wide, m, 5);
    fill(carved, 1, 131);
    expect_all(carved, 32, 100);
    expect_all(wide, m, 5);
    EXPECT_EQ(memory.blocks(), 1U);
}

// ---- held_calls.h

using apci::run::BlockRef;
using apci::run::PathSegment;
using apci::run::Point;
using apci::run::Role;
using apci::run::SegmentKind;
using apci::run::detail::HeldCall;
using apci::run::detail::HeldCalls;

bool same_bits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// A call as HeldCalls must give it back: the segment's fields the check reads, bit for bit.
void expect_same_call(const HeldCall& got, const HeldCall& want, std::size_t i) {
    ASSERT_EQ(got.kind, want.kind) << i;
    switch (want.kind) {
        case HeldCall::Kind::kBegin:
            EXPECT_TRUE(same_bits(got.radius, want.radius)) << i;
            EXPECT_EQ(got.plane, want.plane) << i;
            EXPECT_EQ(got.side, want.side) << i;
            return;
        case HeldCall::Kind::kEnd:
            return;
        case HeldCall::Kind::kWalls:
            EXPECT_EQ(got.on, want.on) << i;
            return;
        case HeldCall::Kind::kProgrammed:
        case HeldCall::Kind::kExecuted:
            break;
    }
    const PathSegment& g = got.segment;
    const PathSegment& w = want.segment;
    EXPECT_EQ(g.block.number, w.block.number) << i;
    EXPECT_EQ(g.block.line, w.block.line) << i;
    EXPECT_EQ(g.kind, w.kind) << i;
    EXPECT_EQ(g.role, w.role) << i;
    EXPECT_EQ(g.ccw, w.ccw) << i;
    EXPECT_EQ(g.plane, w.plane) << i;
    for (int a = 0; a < 3; ++a) {
        EXPECT_TRUE(same_bits(g.start[a], w.start[a])) << i << " start " << a;
        EXPECT_TRUE(same_bits(g.end[a], w.end[a])) << i << " end " << a;
        EXPECT_TRUE(same_bits(g.center[a], w.center[a])) << i << " centre " << a;
    }
    EXPECT_TRUE(same_bits(g.sweep, w.sweep)) << i;
}

void put_call(HeldCalls& calls, const HeldCall& c) {
    switch (c.kind) {
        case HeldCall::Kind::kBegin:
            calls.begin(c.radius, c.plane, c.side);
            break;
        case HeldCall::Kind::kEnd:
            calls.end();
            break;
        case HeldCall::Kind::kWalls:
            calls.walls(c.on);
            break;
        case HeldCall::Kind::kProgrammed:
        case HeldCall::Kind::kExecuted:
            calls.segment(c.kind, c.segment);
            break;
    }
}

void expect_calls(const HeldCalls& calls, const std::vector<HeldCall>& want) {
    ASSERT_EQ(calls.size(), want.size());
    std::size_t i = 0;
    calls.for_each([&](const HeldCall& c) {
        ASSERT_LT(i, want.size());
        expect_same_call(c, want[i], i);
        ++i;
    });
    EXPECT_EQ(i, want.size());
}

// Random calls of every kind, the segments drawn so that each shortcut of the writing is taken
// and not: a start that is (or is not) the last end of the same kind of segment (the other
// kind's end between), the block the last one's, the next one or another (no N number, line 0,
// the largest numbers), a coordinate the same as the start's or not (the end's and the
// centre's), zeros of both signs, a centre of zeros or of -0, a sweep NaN (the quiet one and
// another), 0, -0 or a number, planes 17 to 19 and others; in chunks of 200 bytes (a record
// never split), then cleared and refilled, then swapped.
TEST(HeldCalls, GiveBackEveryCallBitForBit) {
    std::mt19937_64 rng(20261130);
    const auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double other_nan = std::bit_cast<double>(std::uint64_t{0x7ff8'0000'dead'beefULL});
    const double values[] = {0.0, -0.0, 1.5, -2.25, 1e-300, 1e300, 12.3456, -0.001, nan};
    const auto value = [&]() {
        return pick(4) == 0 ? values[pick(9)] : std::uniform_real_distribution<>(-500, 500)(rng);
    };
    const auto make = [&](std::size_t n) {
        std::vector<HeldCall> calls;
        Point last_end[2] = {Point::Zero(), Point::Zero()};
        BlockRef last_blocks[2]{};  // each kind's, as the records are written against them
        for (std::size_t i = 0; i < n; ++i) {
            HeldCall c;
            const int k = pick(10);
            if (k == 0) {
                c.kind = HeldCall::Kind::kBegin;
                c.radius = value();
                c.plane = pick(4) == 0 ? pick(41) - 20 : 17 + pick(3);
                c.side = pick(2) == 0 ? -1 : 1;
            } else if (k == 1) {
                c.kind = HeldCall::Kind::kEnd;
            } else if (k == 2) {
                c.kind = HeldCall::Kind::kWalls;
                c.on = pick(2) == 0;
            } else {
                c.kind = k < 6 ? HeldCall::Kind::kProgrammed : HeldCall::Kind::kExecuted;
                const int slot = c.kind == HeldCall::Kind::kExecuted ? 1 : 0;
                const BlockRef& last_block = last_blocks[slot];
                PathSegment& s = c.segment;
                // The next block (past the largest numbers: the smallest, as if they wrapped).
                const bool largest =
                    last_block.number == std::numeric_limits<std::int64_t>::max() ||
                    last_block.line == std::numeric_limits<std::uint64_t>::max();
                const BlockRef next = largest
                                          ? BlockRef{std::numeric_limits<std::int64_t>::min(), 0}
                                          : BlockRef{last_block.number + 1, last_block.line + 1};
                switch (pick(6)) {
                    case 0:
                        s.block = last_block;
                        break;
                    case 1:
                        s.block = next;
                        break;
                    case 2:
                        s.block = {next.number, next.line + 1};
                        break;
                    case 5:
                        s.block = {next.number, last_block.line};
                        break;  // its number alone
                    case 3:
                        s.block = {apci::run::kNoBlock, static_cast<std::uint64_t>(pick(3))};
                        break;
                    default:
                        s.block = pick(2) == 0
                                      ? BlockRef{std::numeric_limits<std::int64_t>::max(),
                                                 std::numeric_limits<std::uint64_t>::max()}
                                      : BlockRef{pick(1000), static_cast<std::uint64_t>(pick(9))};
                }
                s.kind = static_cast<SegmentKind>(pick(3));
                s.role = static_cast<Role>(pick(5));
                s.ccw = pick(2) == 0;
                s.plane = pick(5) == 0 ? 1000 - pick(2000) : 17 + pick(3);
                for (int a = 0; a < 3; ++a) s.start[a] = value();
                if (pick(2) == 0) s.start = last_end[slot];
                for (int a = 0; a < 3; ++a) {
                    s.end[a] = pick(2) == 0 ? s.start[a] : value();
                    s.center[a] = pick(2) == 0 ? s.start[a] : value();
                }
                const int centre = pick(4);
                if (centre == 0) s.center = Point::Zero();
                if (centre == 1) s.center = Point(-0.0, 0.0, 0.0);
                const double sweeps[] = {nan, other_nan, 0.0, -0.0, value()};
                s.sweep = sweeps[pick(5)];
                last_end[slot] = s.end;
                last_blocks[slot] = s.block;
            }
            calls.push_back(c);
        }
        return calls;
    };
    HeldCalls held(200);
    EXPECT_TRUE(held.empty());
    const std::vector<HeldCall> first = make(5000);
    for (const HeldCall& c : first) put_call(held, c);
    expect_calls(held, first);
    held.clear();
    EXPECT_TRUE(held.empty());
    EXPECT_EQ(held.bytes(), 0U);
    const std::vector<HeldCall> second = make(3000);
    for (const HeldCall& c : second) put_call(held, c);
    expect_calls(held, second);
    HeldCalls other;
    const std::vector<HeldCall> third = make(10);
    for (const HeldCall& c : third) put_call(other, c);
    held.swap(other);
    expect_calls(held, third);
    expect_calls(other, second);
    // Chunks carved from a slab (of 512 KiB: 40,000 calls take several), given back the same;
    // emptied, the same chunks are written again, and swapped, they go with the calls.
    apci::run::detail::Slab memory;
    HeldCalls carved(memory);
    const std::vector<HeldCall> many = make(40000);
    for (const HeldCall& c : many) put_call(carved, c);
    ASSERT_GT(carved.bytes(), 2 * apci::run::detail::Slab::kMostTaken);
    expect_calls(carved, many);
    const std::size_t blocks = memory.blocks();
    EXPECT_EQ(blocks, (carved.bytes() + apci::run::detail::Slab::kBlockBytes - 1) /
                          apci::run::detail::Slab::kBlockBytes);
    carved.clear();
    for (const HeldCall& c : many) put_call(carved, c);
    expect_calls(carved, many);
    EXPECT_EQ(memory.blocks(), blocks);
    HeldCalls mapped;
    mapped.swap(carved);
    expect_calls(mapped, many);
    EXPECT_TRUE(carved.empty());
    for (const HeldCall& c : third) put_call(carved, c);  // its own chunk, mapped
    expect_calls(carved, third);
    EXPECT_EQ(memory.blocks(), blocks);
    // Mapped chunks go with the calls swapped out of a holder that then ends.
    HeldCalls outer;
    {
        HeldCalls inner(4096);
        for (const HeldCall& c : second) put_call(inner, c);
        outer.swap(inner);
    }
    expect_calls(outer, second);
}

// The programmed elements run ahead of the executed segments, so the two kinds interleave:
// each record's block is written against the last of its own kind (the same, the next, or the
// next number on the same line: an executed segment carries a block's number alone), and in
// full where it is none of those.
TEST(HeldCalls, EachKindFollowsItsOwnBlocks) {
    HeldCalls held;
    const auto line = [](BlockRef b, Point start, Point end) {
        PathSegment s;
        s.block = b;
        s.kind = SegmentKind::kLine;
        s.role = Role::kContour;
        s.start = start;
        s.end = end;
        s.sweep = 0.0;
        return s;
    };
    const Point o(0, 0, -2);
    std::vector<HeldCall> want;
    std::size_t was = 0;
    const auto put = [&](HeldCall::Kind kind, const PathSegment& s) {
        was = held.bytes();
        held.segment(kind, s);
        HeldCall c;
        c.kind = kind;
        c.segment = s;
        want.push_back(c);
        return held.bytes() - was;
    };
    using K = HeldCall::Kind;
    // The first of each kind: its block, start, and the end's X.
    EXPECT_EQ(put(K::kProgrammed, line({20, 21}, o, Point(1, 0, -2))), 6U + 16U + 24U + 8U);
    EXPECT_EQ(put(K::kExecuted, line({10, 0}, o, Point(2, 0, -2))), 6U + 16U + 24U + 8U);
    // Programmed 21 (line 22) after 20 (21): the next block; executed 11 (line 0) after 10 (0):
    // the next number; each from its kind's last end, the end's X.
    EXPECT_EQ(put(K::kProgrammed, line({21, 22}, Point(1, 0, -2), Point(3, 0, -2))), 6U + 8U);
    EXPECT_EQ(put(K::kExecuted, line({11, 0}, Point(2, 0, -2), Point(4, 0, -2))), 6U + 8U);
    EXPECT_EQ(put(K::kExecuted, line({11, 0}, Point(4, 0, -2), Point(5, 0, -2))), 6U + 8U);
    // The next number two lines on, a number two on, the largest number's next: written.
    EXPECT_EQ(put(K::kProgrammed, line({22, 24}, Point(3, 0, -2), Point(6, 0, -2))), 6U + 16U + 8U);
    EXPECT_EQ(put(K::kExecuted, line({13, 0}, Point(5, 0, -2), Point(7, 0, -2))), 6U + 16U + 8U);
    constexpr std::int64_t kLargest = std::numeric_limits<std::int64_t>::max();
    EXPECT_EQ(put(K::kExecuted, line({kLargest, 0}, Point(7, 0, -2), Point(8, 0, -2))),
              6U + 16U + 8U);
    EXPECT_EQ(put(K::kExecuted, line({kLargest, 0}, Point(8, 0, -2), Point(9, 0, -2))), 6U + 8U);
    EXPECT_EQ(put(K::kExecuted, line({std::numeric_limits<std::int64_t>::min(), 0}, Point(9, 0, -2),
                                     Point(10, 0, -2))),
              6U + 16U + 8U);
    // The largest line's next: written (the number one on, the line past its largest).
    constexpr std::uint64_t kLastLine = std::numeric_limits<std::uint64_t>::max();
    EXPECT_EQ(put(K::kProgrammed, line({30, kLastLine}, Point(6, 0, -2), Point(7, 0, -2))),
              6U + 16U + 8U);
    EXPECT_EQ(put(K::kProgrammed, line({31, 0}, Point(7, 0, -2), Point(8, 0, -2))), 6U + 16U + 8U);
    expect_calls(held, want);
}

// What a record takes: the header of six bytes and the numbers not found from the record before
// it. A contour traced as it is run: each element starts where the last of its kind ended, in
// the block after it or the same, the end's and the centre's coordinates that are the start's
// left out, a line's sweep (0, or NaN) too; a call with no segment the header (a begin its
// radius).
TEST(HeldCalls, WriteOnlyWhatTheRecordBeforeDoesNotGive) {
    HeldCalls held;
    const auto segment = [](std::int64_t n, Point start, Point end) {
        PathSegment s;
        s.block = {n, static_cast<std::uint64_t>(n + 1)};
        s.kind = SegmentKind::kLine;
        s.role = Role::kContour;
        s.start = start;
        s.end = end;
        return s;
    };
    held.begin(1.5, 17, -1);
    EXPECT_EQ(held.bytes(), 6U + 8U);
    held.walls(false);
    EXPECT_EQ(held.bytes(), 6U + 8U + 6U);
    PathSegment a = segment(10, Point(0, 0, -2), Point(10, 0, -2));
    a.sweep = 0.0;
    held.segment(HeldCall::Kind::kProgrammed, a);  // the first: block, start, end's X
    std::size_t was = held.bytes();
    EXPECT_EQ(was, 20U + 6U + 16U + 24U + 8U);  // Y and Z the start's
    PathSegment b = segment(11, Point(10, 0, -2), Point(12, 5, -2));
    b.sweep = std::numeric_limits<double>::quiet_NaN();
    held.segment(HeldCall::Kind::kProgrammed, b);  // the next block, from the last end: X, Y
    EXPECT_EQ(held.bytes() - was, 6U + 16U);
    was = held.bytes();
    PathSegment e = segment(10, Point(0, 1.5, -2), Point(10, 1.5, -2));
    e.role = Role::kContour;
    e.sweep = 0.0;
    held.segment(HeldCall::Kind::kExecuted, e);  // the first executed: block, start, end's X
    EXPECT_EQ(held.bytes() - was, 6U + 16U + 24U + 8U);
    was = held.bytes();
    PathSegment f = segment(10, Point(10, 1.5, -2), Point(11.5, 0, -2));
    f.kind = SegmentKind::kArc;
    f.role = Role::kTransition;
    f.center = Point(10, 0, -2);
    f.sweep = -std::numbers::pi / 2;
    // The same block, from the last end: the end's X and Y, the centre's Y, the sweep.
    held.segment(HeldCall::Kind::kExecuted, f);
    EXPECT_EQ(held.bytes() - was, 6U + 16U + 8U + 8U);
    was = held.bytes();
    PathSegment g = segment(11, Point(11.5, 0, -2), Point(11.5, 5, -2));
    g.sweep = 0.0;
    held.segment(HeldCall::Kind::kExecuted, g);  // the next block, X unchanged: Y only
    EXPECT_EQ(held.bytes() - was, 6U + 8U);
    was = held.bytes();
    held.end();
    EXPECT_EQ(held.bytes() - was, 6U);
    PathSegment h = segment(12, Point(12, 5, -2), Point(12, 5, 3));
    h.block = {12, 40};  // another line: the block written; from b's end, up in Z
    held.segment(HeldCall::Kind::kProgrammed, h);
    EXPECT_EQ(held.bytes() - was - 6U, 6U + 16U + 8U);
    expect_calls(held, [&] {
        std::vector<HeldCall> want(10);
        want[0].kind = HeldCall::Kind::kBegin;
        want[0].radius = 1.5;
        want[0].side = -1;
        want[1].kind = HeldCall::Kind::kWalls;
        const PathSegment* segs[] = {&a, &b, &e, &f, &g};
        for (int i = 0; i < 5; ++i) {
            want[2 + i].kind = i < 2 ? HeldCall::Kind::kProgrammed : HeldCall::Kind::kExecuted;
            want[2 + i].segment = *segs[i];
        }
        want[7].kind = HeldCall::Kind::kEnd;
        want[8].kind = HeldCall::Kind::kProgrammed;
        want[8].segment = h;
        want.pop_back();
        return want;
    }());
}

// ---- probe_table.h

// A grid cell's index: the floor of the coordinate over the cell size, as an integer, the same
// as std::floor gives at every integer, one step of rounding either side of it, zero of both
// signs, halves, and out to 2^62 (where every double is an integer) on both sides.
TEST(FloorIndex, IsTheFloorAtEveryIntegerAndOneRoundingStepEitherSide) {
    std::vector<double> at{0.0,    -0.0,    0.5,    -0.5,    1e-300, -1e-300,
                           0x1p52, -0x1p52, 0x1p53, -0x1p53, 0x1p62, -0x1p62};
    for (const double k :
         {1.0, -1.0, 2.0, -2.0, 3.0, -3.0, 1e6, -1e6, 1e15, -1e15, 0x1p52 - 1, -(0x1p52 - 1)}) {
        at.push_back(k);
        at.push_back(std::nextafter(k, -INFINITY));
        at.push_back(std::nextafter(k, INFINITY));
    }
    for (const double q : at)
        EXPECT_EQ(apci::run::detail::floor_index(q), static_cast<std::int64_t>(std::floor(q))) << q;
    EXPECT_EQ(apci::run::detail::floor_index(std::nextafter(-1.0, 0.0)), -1);
    EXPECT_EQ(apci::run::detail::floor_index(std::nextafter(-1.0, -2.0)), -2);
    EXPECT_EQ(apci::run::detail::floor_index(std::nextafter(1.0, 0.0)), 0);
    EXPECT_EQ(apci::run::detail::floor_index(-0.0), 0);
}

// After a clear (the grid lists its items again, reindex()), a key added again is new with no
// value, and a cell's chains hold only what was added since: a stale chain would run into the
// nodes cleared (and could run round them). The table is asserted first, so that the cells
// are not walked where it keeps stale values.
TEST(ProbeTable, AfterAClearAKeyIsNewWithNoValueAndACellHoldsOnlyItsNewItems) {
    apci::run::detail::ProbeTable<std::uint64_t> t;
    const std::uint64_t keys[] = {0, 7, ~std::uint64_t{0}};
    for (const std::uint64_t key : keys) {
        auto [value, fresh] = t.emplace(key);
        ASSERT_TRUE(fresh) << key;
        value = key + 100;
        ASSERT_FALSE(t.emplace(key).second) << key;
        ASSERT_NE(t.get(key), nullptr) << key;
        ASSERT_EQ(*t.get(key), key + 100) << key;
    }
    ASSERT_EQ(t.get(8), nullptr);
    t.clear();
    for (const std::uint64_t key : keys) {
        ASSERT_EQ(t.get(key), nullptr) << key;
        const auto [value, fresh] = t.emplace(key);
        ASSERT_TRUE(fresh) << key;
        ASSERT_EQ(value, 0U) << key;
    }
    // The cells of a grid (the cell (0, 0) has the key 0).
    apci::run::detail::CellIndex<2> cells;
    for (const std::uint64_t cell : {std::uint64_t{0}, std::uint64_t{42}}) {
        cells.add(0, cell, 1);
        cells.add(0, cell, 2);
        cells.add(1, cell, 3);
    }
    std::vector<std::uint32_t> found;
    cells.append(0, 42, found);
    EXPECT_EQ(found, (std::vector<std::uint32_t>{2, 1}));
    cells.clear();
    for (const std::uint64_t cell : {std::uint64_t{0}, std::uint64_t{42}}) {
        found.clear();
        cells.append(0, cell, found);
        EXPECT_TRUE(found.empty()) << cell;
        cells.add(0, cell, 5);
        found.clear();
        cells.append(0, cell, found);
        EXPECT_EQ(found, (std::vector<std::uint32_t>{5})) << cell;
        found.clear();
        cells.append_and_add(1, 0, cell, 6, found);
        EXPECT_TRUE(found.empty()) << cell;
        found.clear();
        cells.append(0, cell, found);
        EXPECT_EQ(found, (std::vector<std::uint32_t>{6, 5})) << cell;
    }
}

}  // namespace
