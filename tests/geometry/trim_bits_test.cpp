// SPDX-License-Identifier: MIT
// The corner trim keeps what it has computed instead of computing it again: the carriers'
// meetings of a round of the spiral correction whose corrections have the bits of the round
// before, and no reading of the next element at a meeting that is off the held element. The
// path must stay the same bit for bit: a kept meeting or reading that belongs to other
// corrections or another meeting would move the trim by a few ulp. The digests below were taken
// with the trim that computed everything at every use, over contours whose arcs are spirals
// (coordinates rounded to three decimals, so each arc's start and end radius differ): the
// benchmark contour of bench_contour_gen (docs/performance.md) at several tool radii, both
// sides and both transitions, and random contours of rounded lines and arcs meeting at inside
// and outside corners. The compensator joins its corners in place (join_corner_in_place, the
// trims in place): the same elements as join_corner's copies, and a refused corner changes
// nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "rng.h"
#include "rwmos/geometry/compensator.h"
#include "rwmos/geometry/corner.h"
#include "rwmos/geometry/offset.h"

namespace rwmos::geom {
namespace {

using apci::test::Rng;

// FNV-1a over 64-bit words.
struct Digest {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    int contour_arcs = 0;  // contour segments that are arcs (trimmed spirals among them)
    void word(std::uint64_t w) {
        for (int i = 0; i < 8; ++i) {
            h ^= (w >> (8 * i)) & 0xFF;
            h *= 0x100000001b3ULL;
        }
    }
    void number(double v) { word(std::bit_cast<std::uint64_t>(v)); }
    void point(const Vec2& p) {
        number(p.x());
        number(p.y());
    }
    void step(const StepResult& r, const SegmentBatch& out) {
        word(static_cast<std::uint64_t>(r.reason));
        word(r.index);
        for (const Segment& s : out) {
            word(static_cast<std::uint64_t>(s.role) << 8 | static_cast<std::uint64_t>(s.path.kind));
            word(s.index);
            point(s.path.start);
            point(s.path.end);
            if (is_arc(s.path)) {
                point(s.path.centre);
                word(s.path.ccw ? 1 : 0);
                if (s.role == SegmentRole::kContour) ++contour_arcs;
            }
        }
    }
};

// Runs the elements through a compensator (restarted after a refusal) into the digest.
void compensate(const std::vector<Element>& elements, const CompensatorConfig& config, Digest& d) {
    PathCompensator comp;
    SegmentBatch out;
    ASSERT_TRUE(comp.begin(config, elements.front().start).ok());
    std::uint32_t index = 1;
    for (const Element& e : elements) {
        const StepResult r = comp.push(e, index++, out);
        d.step(r, out);
        if (!r.ok()) {
            comp.discard();
            ASSERT_TRUE(comp.begin(config, e.end).ok());
        }
    }
    d.step(comp.finish(out), out);
}

// One lap of the benchmark contour (bench_contour_gen): lines and arcs written with three
// decimals, arcs by their start-relative centre (I, J).
std::vector<Element> benchmark_lap() {
    struct Block {
        int g;
        double x, y, i, j;
    };
    const Block blocks[] = {
        {1, 93.267, 61.261, 0, 0},
        {3, 83.562, 69.339, -6.6166, 1.9196},
        {1, 76.596, 79.049, 0, 0},
        {2, 71.615, 87.782, 39.3567, 28.2347},
        {2, 60.728, 90.775, -2.9082, 10.7185},
        {1, 51.495, 93.112, 0, 0},
        {3, 41.63, 83.089, -1.9992, -7.8985},
        {2, 31.14, 85.777, -2.3344, 12.7025},
        {3, 21.119, 80.436, -1.8161, -8.6639},
        {2, 12.099, 73.592, -12.6329, 7.2835},
        {2, 14.537, 58.163, -3.4459, -8.4516},
        {1, 14.071, 50.901, 0, 0},
        {3, 12.578, 37.981, 12.0391, -7.9375},
        {1, 15.02, 29.982, 0, 0},
        {2, 19.51, 18.063, -2.823, -7.8687},
        {1, 28.561, 15.655, 0, 0},
        {1, 41.608, 16.414, 0, 0},
        {1, 48.829, 13.78, 0, 0},
        {3, 60.908, 12.947, 7.4829, 20.5141},
        {1, 68.063, 16.046, 0, 0},
        {1, 73.035, 24.45, 0, 0},
        {3, 84.888, 31.483, 0.3745, 12.8735},
        {3, 86.234, 41.071, -7.38, 5.9245},
        {3, 90, 50, -5.2013, 7.4525},
    };
    std::vector<Element> out;
    Vec2 at(90, 50);
    for (const Block& b : blocks) {
        const Vec2 end(b.x, b.y);
        out.push_back(b.g == 1 ? make_line(at, end)
                               : make_arc(at, end, at + Vec2(b.i, b.j), b.g == 3));
        at = end;
    }
    return out;
}

double rounded(double v) {
    return std::round(v * 1000) / 1000;
}
Vec2 rounded(const Vec2& p) {
    return {rounded(p.x()), rounded(p.y())};
}

// A closed-free chain of rounded lines and arcs turning by up to 150 degrees at each join.
std::vector<Element> random_chain(std::uint64_t draw, int count) {
    Rng rng(draw);
    std::vector<Element> out;
    // Each draw a statement of its own: the order of two draws in one expression is the
    // compiler's (gcc and clang differ), and the contours, with the digest, would be too.
    const double x0 = rounded(rng.uniform(-50, 50));
    const double y0 = rounded(rng.uniform(-50, 50));
    Vec2 at(x0, y0);
    double heading = rng.uniform(0, 2 * std::numbers::pi);
    for (int k = 0; k < count; ++k) {
        const double sense = rng.sign();
        heading += sense * rng.uniform(0.05, 2.6);
        const Vec2 t(std::cos(heading), std::sin(heading));
        if (rng.chance(0.4)) {
            const Vec2 end = rounded(at + rng.uniform(2, 20) * t);
            out.push_back(make_line(at, end));
            at = end;
            continue;
        }
        const double radius = rng.uniform(3, 30);
        const double turn_sense = rng.sign();
        const double turn = turn_sense * rng.uniform(0.2, 2.5);
        const bool ccw = turn > 0;
        const Vec2 left(-t.y(), t.x());
        const Vec2 centre = rounded(at + radius * (ccw ? left : Vec2(-left)));
        const Vec2 r0 = at - centre;
        const Vec2 r1(std::cos(turn) * r0.x() - std::sin(turn) * r0.y(),
                      std::sin(turn) * r0.x() + std::cos(turn) * r0.y());
        const Vec2 end = rounded(centre + r1);
        out.push_back(make_arc(at, end, centre, ccw));
        heading += turn;
        at = end;
    }
    return out;
}

TEST(TrimBits, BenchmarkContourGivesTheBitsOfTheTrimWithoutKeptValues) {
    const std::vector<Element> lap = benchmark_lap();
    Digest d;
    for (const double r : {0.5, 1.0, 1.5, 2.0})
        for (const Side side : {Side::kLeft, Side::kRight})
            for (const TransitionMode mode : {TransitionMode::kCircular, TransitionMode::kLinear})
                compensate(lap, CompensatorConfig{side, r, mode, ApproachMode::kPerpendicular}, d);
    EXPECT_GT(d.contour_arcs, 100);
    EXPECT_EQ(d.h, 0x7a289d8c1a417c89ULL);
}

TEST(TrimBits, RandomRoundedContoursGiveTheBitsOfTheTrimWithoutKeptValues) {
    Digest d;
    for (std::uint64_t draw = 1; draw <= 200; ++draw)
        for (const Side side : {Side::kLeft, Side::kRight})
            compensate(random_chain(draw, 40),
                       CompensatorConfig{side, 1.0 + 0.25 * static_cast<double>(draw % 5),
                                         TransitionMode::kCircular, ApproachMode::kPerpendicular},
                       d);
    EXPECT_GT(d.contour_arcs, 5000);
    EXPECT_EQ(d.h, 0x894153726f5fa46ULL);
}

bool same(const OffsetElement& a, const OffsetElement& b) {
    const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
    const auto same_point = [&](const Vec2& p, const Vec2& q) {
        return bits(p.x()) == bits(q.x()) && bits(p.y()) == bits(q.y());
    };
    return a.path.kind == b.path.kind && a.path.ccw == b.path.ccw &&
           same_point(a.path.start, b.path.start) && same_point(a.path.end, b.path.end) &&
           same_point(a.path.centre, b.path.centre) && bits(a.sweep) == bits(b.sweep) &&
           same_point(a.direction, b.direction);
}

TEST(JoinInPlace, ARefusedInsideCornerLeavesBothElementsAndTheTransitionAsTheyWere) {
    // A 90 degree inside corner with r = 1 needs 1 of the next line; it has 0.5.
    const OffsetElement a = offset_element(make_line({-10, 0}, {0, 0}), 1, Side::kLeft).element;
    const OffsetElement b = offset_element(make_line({0, 0}, {0, 0.5}), 1, Side::kLeft).element;
    OffsetElement held = a, next = b;
    Transition transition;
    transition.count = 7;  // marks it: a refused or inside corner leaves it alone
    const JoinKind j = join_corner_in_place(held, next, transition, {0, 0}, {1, 0}, {0, 1},
                                            Side::kLeft, 1, TransitionMode::kCircular, 0.5);
    EXPECT_EQ(j.kind, CornerKind::kInside);
    EXPECT_EQ(j.reason, Reason::kNextElementTooShort);
    EXPECT_TRUE(same(held, a));
    EXPECT_TRUE(same(next, b));
    EXPECT_EQ(transition.count, 7u);
}

TEST(JoinInPlace, EveryCornerOfTheBenchmarkContourJoinsAsJoinCornerJoinsIt) {
    // The in-place join against join_corner's copies, corner by corner: the same elements, the
    // same transition, bit for bit.
    const std::vector<Element> lap = benchmark_lap();
    int inside = 0;
    for (const double r : {0.5, 1.0, 2.0})
        for (const Side side : {Side::kLeft, Side::kRight})
            for (std::size_t k = 0; k < lap.size(); ++k) {
                const Element& e1 = lap[k];
                const Element& e2 = lap[(k + 1) % lap.size()];
                const OffsetResult o1 = offset_element(e1, r, side);
                const OffsetResult o2 = offset_element(e2, r, side);
                if (o1.reason != Reason::kNone || o2.reason != Reason::kNone) continue;
                const double shorter = std::min(length(e1), length(e2));
                const CornerJoin copied =
                    join_corner(o1.element, o2.element, e1.end, end_tangent(e1), start_tangent(e2),
                                side, r, TransitionMode::kLinear, shorter);
                OffsetElement held = o1.element, next = o2.element;
                Transition transition;
                const JoinKind j = join_corner_in_place(held, next, transition, e1.end,
                                                        end_tangent(e1), start_tangent(e2), side, r,
                                                        TransitionMode::kLinear, shorter);
                ASSERT_EQ(j.kind, copied.kind) << k;
                ASSERT_EQ(j.reason, copied.reason) << k;
                EXPECT_TRUE(same(held, copied.held)) << k;
                EXPECT_TRUE(same(next, copied.next)) << k;
                ASSERT_EQ(transition.count, copied.transition.count) << k;
                for (std::size_t i = 0; i < transition.count; ++i) {
                    EXPECT_EQ(transition.elements[i].start, copied.transition.elements[i].start);
                    EXPECT_EQ(transition.elements[i].end, copied.transition.elements[i].end);
                }
                inside += j.kind == CornerKind::kInside && j.reason == Reason::kNone;
            }
    EXPECT_GT(inside, 20);
}

TEST(TrimInPlace, AnArcTrimmedInPlaceTurnsByTheAlongOverTheMeanRadiusItHadBefore) {
    // A quarter circle whose radius grows from 10 to 10.002 (a spiral): trimmed to end 3 along
    // from its start, it turns by 3 / 10.001 whatever its new end does to its radii.
    OffsetElement o;
    o.path = make_arc({10, 0}, {0, 10.002}, {0, 0}, true);
    o.sweep = std::numbers::pi / 2;
    const Vec2 x(7, 7);
    OffsetElement in_place = o;
    trim_end_in_place(in_place, x, 3.0);
    EXPECT_EQ(in_place.sweep, std::clamp(3.0 / (0.5 * (10.0 + 10.002)), 0.0, o.sweep));
    EXPECT_EQ(in_place.path.end, x);
    EXPECT_TRUE(same(in_place, trim_end(o, x, 3.0)));
    OffsetElement started = o;
    trim_start_in_place(started, x, 3.0);
    EXPECT_EQ(started.sweep, o.sweep - 3.0 / (0.5 * (10.0 + 10.002)));
    EXPECT_EQ(started.path.start, x);
    EXPECT_TRUE(same(started, trim_start(o, x, 3.0)));
}

}  // namespace
}  // namespace rwmos::geom
