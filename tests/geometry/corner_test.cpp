// SPDX-License-Identifier: MIT
// Corner joins: classification, inside trims, outside transitions (circular G26, linear
// G25), tangent joins, for line-line, line-arc, arc-line and arc-arc, on both sides.
#include "rwmos/geometry/corner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "rwmos/geometry/intersect.h"
#include "rwmos/geometry/shared.h"

namespace rwmos::geom {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEps = 1e-9;

void expect_near(const Vec2& a, const Vec2& b, double tol = kEps) {
    EXPECT_NEAR(a.x(), b.x(), tol) << "x";
    EXPECT_NEAR(a.y(), b.y(), tol) << "y";
}

Vec2 dir(double degrees) {
    const double a = degrees * kPi / 180;
    return {std::cos(a), std::sin(a)};
}

// ---- Hand-computed corners (tool radius 1, corner at the origin) ----

struct Pair {
    Element a, b;
};
const Element kLineIn = make_line({-10, 0}, {0, 0});                // along +x
const Element kLineUp = make_line({0, 0}, {0, 10});                 // along +y
const Element kArcIn = make_arc({-5, -5}, {0, 0}, {0, -5}, false);  // cw, ends along +x
const Element kArcUp = make_arc({0, 0}, {-5, 5}, {-5, 0}, true);    // ccw, starts along +y

CornerJoin join(const Pair& p, Side side, TransitionMode mode = TransitionMode::kCircular) {
    const OffsetElement a = offset_element(p.a, 1.0, side).element;
    const OffsetElement b = offset_element(p.b, 1.0, side).element;
    return join_corner(a, b, p.a.end, end_tangent(p.a), start_tangent(p.b), side, 1.0, mode,
                       std::min(length(p.a), length(p.b)));
}

TEST(InsideCorner, LineLineTrimsAtTheOffsetLinesIntersection) {
    const CornerJoin j = join({kLineIn, kLineUp}, Side::kLeft);
    ASSERT_EQ(j.reason, Reason::kNone);
    EXPECT_EQ(j.kind, CornerKind::kInside);
    expect_near(j.held.path.end, {-1, 1});
    expect_near(j.next.path.start, {-1, 1});
    EXPECT_EQ(j.transition.count, 0u);
}

TEST(InsideCorner, LineArcTrimsAtTheIntersectionNearestTheCorner) {
    // Offset line y = 1 meets the offset circle about (-5, 0) of radius 4 at x = -5 +- sqrt 15.
    const CornerJoin j = join({kLineIn, kArcUp}, Side::kLeft);
    ASSERT_EQ(j.reason, Reason::kNone);
    EXPECT_EQ(j.kind, CornerKind::kInside);
    expect_near(j.held.path.end, {-5 + std::sqrt(15.0), 1});
    expect_near(j.next.path.start, {-5 + std::sqrt(15.0), 1});
}

TEST(InsideCorner, ArcLineTrimsAtTheIntersectionNearestTheCorner) {
    // Offset circle about (0, -5) of radius 6 meets x = -1 at y = -5 +- sqrt 35.
    const CornerJoin j = join({kArcIn, kLineUp}, Side::kLeft);
    ASSERT_EQ(j.reason, Reason::kNone);
    EXPECT_EQ(j.kind, CornerKind::kInside);
    expect_near(j.held.path.end, {-1, -5 + std::sqrt(35.0)});
    expect_near(j.next.path.start, {-1, -5 + std::sqrt(35.0)});
}

TEST(InsideCorner, ArcArcTrimsAtTheIntersectionNearestTheCorner) {
    // Circles about (0,-5) radius 6 and (-5,0) radius 4 meet at (-3.5,-1.5) -+ h(1,1)/sqrt2.
    const double h = std::sqrt(36 - 24.5);
    const Vec2 nearest = Vec2(-3.5, -1.5) + h * Vec2(1, 1) / std::sqrt(2.0);
    const CornerJoin j = join({kArcIn, kArcUp}, Side::kLeft);
    ASSERT_EQ(j.reason, Reason::kNone);
    EXPECT_EQ(j.kind, CornerKind::kInside);
    expect_near(j.held.path.end, nearest);
    expect_near(j.next.path.start, nearest);
    // The trimmed arcs keep their direction and lose length.
    EXPECT_LT(std::abs(j.held.sweep),
              std::abs(offset_element(kArcIn, 1, Side::kLeft).element.sweep));
    EXPECT_GT(j.held.sweep * offset_element(kArcIn, 1, Side::kLeft).element.sweep, 0.0);
}

TEST(InsideCorner, ChoosesTheValidIntersectionNearestTheCorner) {
    // The offset circle of the half circle (radius 9 about (-10, 0)) crosses the offset
    // line y = 1 twice, both within both elements: at x = -10 + sqrt 80 and -10 - sqrt 80.
    const Element a = make_line({-20, 0}, {0, 0});
    const Element b = make_arc({0, 0}, {-20, 0}, {-10, 0}, true);
    const OffsetElement ao = offset_element(a, 1, Side::kLeft).element;
    const OffsetElement bo = offset_element(b, 1, Side::kLeft).element;
    ASSERT_EQ(intersect_carriers(ao, bo).count, 2u);
    const CornerJoin j = join_corner(ao, bo, {0, 0}, end_tangent(a), start_tangent(b), Side::kLeft,
                                     1, TransitionMode::kCircular, 20);
    ASSERT_EQ(j.reason, Reason::kNone);
    expect_near(j.held.path.end, {-10 + std::sqrt(80.0), 1});
    expect_near(j.next.path.start, {-10 + std::sqrt(80.0), 1});
}

TEST(InsideCorner, ChoosesTheValidIntersectionLatestOnTheHeldElementWhateverTheirOrder) {
    // The mirror image of the case above (travelling -x, tool on the right): the two
    // meetings come in the other order, and the one nearest the corner still wins.
    const Element a = make_line({20, 0}, {0, 0});
    const Element b = make_arc({0, 0}, {20, 0}, {10, 0}, false);
    const OffsetElement ao = offset_element(a, 1, Side::kRight).element;
    const OffsetElement bo = offset_element(b, 1, Side::kRight).element;
    ASSERT_EQ(intersect_carriers(ao, bo).count, 2u);
    const CornerJoin j = join_corner(ao, bo, {0, 0}, end_tangent(a), start_tangent(b),
                                     Side::kRight, 1, TransitionMode::kCircular, 20);
    ASSERT_EQ(j.reason, Reason::kNone);
    expect_near(j.held.path.end, {10 - std::sqrt(80.0), 1});
    expect_near(j.next.path.start, {10 - std::sqrt(80.0), 1});
    // Arc-arc: a circle crossing the concave offset circle twice, both meetings within
    // both elements; again the one nearest the corner, latest on the held arc.
    for (const bool mirrored : {false, true}) {
        const double m = mirrored ? -1.0 : 1.0;
        const Side side = mirrored ? Side::kRight : Side::kLeft;
        const Element held = make_arc({m * -20, 0}, {0, 0}, {m * -10, -40}, mirrored);
        const Element next = make_arc({0, 0}, {m * -20, 0}, {m * -10, 0}, !mirrored);
        const OffsetElement ho = offset_element(held, 1, side).element;
        const OffsetElement no = offset_element(next, 1, side).element;
        ASSERT_EQ(intersect_carriers(ho, no).count, 2u);
        const CornerJoin k = join_corner(ho, no, {0, 0}, end_tangent(held), start_tangent(next),
                                         side, 1, TransitionMode::kCircular, 20);
        ASSERT_EQ(k.reason, Reason::kNone) << mirrored;
        const Intersections both = intersect_carriers(ho, no);
        const Vec2 nearest = both.points[0].norm() < both.points[1].norm() ? both.points[0]
                                                                             : both.points[1];
        expect_near(k.held.path.end, nearest, 1e-9);
        EXPECT_NEAR(distance_to(held, k.held.path.end), 1.0, 1e-9);
        EXPECT_NEAR(distance_to(next, k.held.path.end), 1.0, 1e-9);
    }
}

TEST(OutsideCorner, CircularLineLineIsQuarterArcAboutTheCorner) {
    const CornerJoin j = join({kLineIn, kLineUp}, Side::kRight);
    ASSERT_EQ(j.reason, Reason::kNone);
    EXPECT_EQ(j.kind, CornerKind::kOutside);
    ASSERT_EQ(j.transition.count, 1u);
    const Element& arc = j.transition.elements[0];
    EXPECT_EQ(arc.kind, ElementKind::kArc);
    expect_near(arc.centre, {0, 0});
    expect_near(arc.start, {0, -1});
    expect_near(arc.end, {1, 0});
    EXPECT_TRUE(arc.ccw);
    EXPECT_NEAR(sweep(arc), kPi / 2, kEps);
    // The offset elements keep their untrimmed ends.
    expect_near(j.held.path.end, {0, -1});
    expect_near(j.next.path.start, {1, 0});
}

TEST(OutsideCorner, LinearLineLineMeetsAtTheExtendedOffsetsIntersection) {
    const CornerJoin j = join({kLineIn, kLineUp}, Side::kRight, TransitionMode::kLinear);
    ASSERT_EQ(j.transition.count, 2u);
    expect_near(j.transition.elements[0].start, {0, -1});
    expect_near(j.transition.elements[0].end, {1, -1});
    expect_near(j.transition.elements[1].start, {1, -1});
    expect_near(j.transition.elements[1].end, {1, 0});
}

TEST(OutsideCorner, LinearArcLineExtendsTheArcAlongItsEndTangent) {
    // Right of the cw arc (centre (0,-5)) is its concave side: offset radius 4, end (0,-1).
    const CornerJoin j = join({kArcIn, kLineUp}, Side::kRight, TransitionMode::kLinear);
    ASSERT_EQ(j.transition.count, 2u);
    expect_near(j.transition.elements[0].start, {0, -1});
    expect_near(j.transition.elements[0].end, {1, -1});
    expect_near(j.transition.elements[1].end, {1, 0});
}

// ---- Every combination, both sides, both modes: generic rules ----

enum class Kind { kLine, kConvexArc, kConcaveArc };
const char* name(Kind k) {
    return k == Kind::kLine ? "Line" : k == Kind::kConvexArc ? "ConvexArc" : "ConcaveArc";
}

// An element ending (incoming) or starting (outgoing) at the origin with the given tangent:
// lines of length 8; arcs curving away from the tool (convex for it: radius 8, sweep 60
// degrees) or towards it (concave: radius 30, sweep 30 degrees, flat enough that a tool of
// radius 1 fits into a 150 degree corner).
Element make_piece(Kind kind, const Vec2& tangent, bool incoming, Side side) {
    const Vec2 o = Vec2::Zero();
    if (kind == Kind::kLine)
        return incoming ? make_line(o - 8 * tangent, o) : make_line(o, o + 8 * tangent);
    const double rad = kind == Kind::kConcaveArc ? 30.0 : 8.0;
    // Concave for the tool: the centre lies on the tool side.
    const bool centre_left = (kind == Kind::kConcaveArc) == (side == Side::kLeft);
    const Vec2 centre = o + (centre_left ? rad : -rad) * left_normal(tangent);
    const bool ccw = centre_left;  // left-hand centre: counter-clockwise travel
    const double turn = (ccw ? 1 : -1) * (kind == Kind::kConcaveArc ? kPi / 6 : kPi / 3);
    const Vec2 radial = o - centre;
    auto turned = [&](double a) {
        return Vec2(std::cos(a) * radial.x() - std::sin(a) * radial.y(),
                    std::sin(a) * radial.x() + std::cos(a) * radial.y());
    };
    if (incoming) return make_arc(centre + turned(-turn), o, centre, ccw);
    return make_arc(o, centre + turned(turn), centre, ccw);
}

struct CornerCase {
    Kind a, b;
    double turn_degrees;  // from a's end tangent to b's start tangent
    Side side;
    TransitionMode mode;
};

std::string case_name(const testing::TestParamInfo<CornerCase>& info) {
    const CornerCase& c = info.param;
    std::string s = std::string(name(c.a)) + name(c.b) + "Turn" +
                    (c.turn_degrees < 0 ? "Minus" : "Plus") +
                    std::to_string(static_cast<int>(std::abs(c.turn_degrees))) +
                    (c.side == Side::kLeft ? "Left" : "Right") +
                    (c.mode == TransitionMode::kCircular ? "Circular" : "Linear");
    return s;
}

bool towards_tool(const CornerCase& c) {
    return (c.turn_degrees > 0) == (c.side == Side::kLeft);
}

enum class Filter { kAll, kInside, kOutsideCircular, kOutsideLinear };
std::vector<CornerCase> cases(Filter f) {
    std::vector<CornerCase> out;
    for (Kind a : {Kind::kLine, Kind::kConvexArc, Kind::kConcaveArc})
        for (Kind b : {Kind::kLine, Kind::kConvexArc, Kind::kConcaveArc})
            for (double turn : {-150.0, -90.0, -45.0, 45.0, 90.0, 135.0})
                for (Side side : {Side::kLeft, Side::kRight})
                    for (TransitionMode mode :
                         {TransitionMode::kCircular, TransitionMode::kLinear}) {
                        const CornerCase c{a, b, turn, side, mode};
                        const bool keep = f == Filter::kAll ||
                                          (f == Filter::kInside && towards_tool(c) &&
                                           mode == TransitionMode::kCircular) ||
                                          (f == Filter::kOutsideCircular && !towards_tool(c) &&
                                           mode == TransitionMode::kCircular) ||
                                          (f == Filter::kOutsideLinear && !towards_tool(c) &&
                                           mode == TransitionMode::kLinear);
                        if (keep) out.push_back(c);
                    }
    return out;
}

class CornerRule : public testing::TestWithParam<CornerCase> {
  protected:
    void SetUp() override {
        const CornerCase& c = GetParam();
        a_ = make_piece(c.a, dir(0), true, c.side);
        b_ = make_piece(c.b, dir(c.turn_degrees), false, c.side);
        ASSERT_NEAR((a_.end - b_.start).norm(), 0.0, 1e-12);
        join_ = join_corner(offset_element(a_, r_, c.side).element,
                            offset_element(b_, r_, c.side).element, a_.end, end_tangent(a_),
                            start_tangent(b_), c.side, r_, c.mode,
                            std::min(length(a_), length(b_)));
    }
    // Distance of p from the programmed pair.
    double clearance(const Vec2& p) const {
        return std::min(distance_to(a_, p), distance_to(b_, p));
    }
    bool turns_towards_tool() const { return towards_tool(GetParam()); }

    const double r_ = 1.0;
    Element a_, b_;
    CornerJoin join_;
};

TEST_P(CornerRule, TurnTowardsTheToolIsInsideAndAwayIsOutside) {
    EXPECT_EQ(join_.kind, turns_towards_tool() ? CornerKind::kInside : CornerKind::kOutside);
}

class InsideCornerRule : public CornerRule {};
class OutsideCornerRule : public CornerRule {};
class CircularTransitionRule : public CornerRule {};
class LinearTransitionRule : public CornerRule {};

TEST_P(InsideCornerRule, TrimsBothOffsetsAtOnePointAtToolRadiusFromBoth) {
    ASSERT_EQ(join_.reason, Reason::kNone) << reason_message(join_.reason);
    const Vec2 x = join_.held.path.end;
    EXPECT_EQ(x, join_.next.path.start);
    EXPECT_NEAR(distance_to(a_, x), r_, 1e-9);
    EXPECT_NEAR(distance_to(b_, x), r_, 1e-9);
    // Both trimmed: shorter than the untrimmed offsets, none reversed.
    const OffsetElement a_full = offset_element(a_, r_, GetParam().side).element;
    const OffsetElement b_full = offset_element(b_, r_, GetParam().side).element;
    EXPECT_LT(offset_length(join_.held), offset_length(a_full));
    EXPECT_LT(offset_length(join_.next), offset_length(b_full));
    EXPECT_GT(offset_length(join_.held), 0.0);
    EXPECT_EQ(join_.transition.count, 0u);
}

TEST_P(OutsideCornerRule, LeavesTheOffsetEndsUntrimmedAndBridgesThem) {
    ASSERT_EQ(join_.reason, Reason::kNone);
    const Side side = GetParam().side;
    EXPECT_EQ(join_.held.path.end, offset_element(a_, r_, side).element.path.end);
    EXPECT_EQ(join_.next.path.start, offset_element(b_, r_, side).element.path.start);
    ASSERT_GE(join_.transition.count, 1u);
    EXPECT_EQ(join_.transition.elements[0].start, join_.held.path.end);
    for (std::size_t i = 1; i < join_.transition.count; ++i)
        EXPECT_EQ(join_.transition.elements[i].start, join_.transition.elements[i - 1].end);
    EXPECT_EQ(join_.transition.elements[join_.transition.count - 1].end, join_.next.path.start);
}

TEST_P(CircularTransitionRule, IsArcOfToolRadiusAboutTheCornerNeverCloser) {
    ASSERT_EQ(join_.transition.count, 1u);
    const Element& arc = join_.transition.elements[0];
    EXPECT_EQ(arc.kind, ElementKind::kArc);
    EXPECT_EQ(arc.centre, a_.end);
    EXPECT_NEAR(std::abs(sweep(arc)), std::abs(GetParam().turn_degrees) * kPi / 180, 1e-9);
    for (int step = 0; step <= 64; ++step) {
        const double t = step / 64.0;
        EXPECT_NEAR((point_at(arc, t) - a_.end).norm(), r_, 1e-12);
        EXPECT_GE(clearance(point_at(arc, t)), r_ - 1e-9) << t;
    }
}

TEST_P(LinearTransitionRule, ExtendsAlongTheTangentsAndNeverGouges) {
    const Transition& t = join_.transition;
    const bool sharp = std::abs(GetParam().turn_degrees) > 90;
    ASSERT_EQ(t.count, sharp ? 3u : 2u);
    const Vec2 t1 = end_tangent(a_);
    const Vec2 t2 = start_tangent(b_);
    EXPECT_NEAR(cross(t.elements[0].end - t.elements[0].start, t1), 0.0, 1e-12);
    EXPECT_GT((t.elements[0].end - t.elements[0].start).dot(t1), 0.0);
    const Element& last = t.elements[t.count - 1];
    EXPECT_NEAR(cross(last.end - last.start, t2), 0.0, 1e-12);
    EXPECT_GT((last.end - last.start).dot(t2), 0.0);
    if (sharp) {  // bounded: each extension is exactly r long
        EXPECT_NEAR(length(t.elements[0]), r_, 1e-12);
        EXPECT_NEAR(length(last), r_, 1e-12);
    }
    for (std::size_t i = 0; i < t.count; ++i)
        for (int step = 0; step <= 64; ++step) {
            const double s = step / 64.0;
            EXPECT_GE(clearance(point_at(t.elements[i], s)), r_ - 1e-9) << i << " " << s;
        }
}

INSTANTIATE_TEST_SUITE_P(EveryCombination, CornerRule, testing::ValuesIn(cases(Filter::kAll)),
                         case_name);
INSTANTIATE_TEST_SUITE_P(EveryCombination, InsideCornerRule,
                         testing::ValuesIn(cases(Filter::kInside)), case_name);
INSTANTIATE_TEST_SUITE_P(EveryCombination, OutsideCornerRule,
                         testing::ValuesIn(cases(Filter::kOutsideCircular)), case_name);
INSTANTIATE_TEST_SUITE_P(EveryLinearCombination, OutsideCornerRule,
                         testing::ValuesIn(cases(Filter::kOutsideLinear)), case_name);
INSTANTIATE_TEST_SUITE_P(EveryCombination, CircularTransitionRule,
                         testing::ValuesIn(cases(Filter::kOutsideCircular)), case_name);
INSTANTIATE_TEST_SUITE_P(EveryCombination, LinearTransitionRule,
                         testing::ValuesIn(cases(Filter::kOutsideLinear)), case_name);

// ---- Classification, tangent joins, failures ----

TEST(CornerClassification, ReversalIsOutsideOnBothSides) {
    EXPECT_EQ(classify_corner(dir(0), dir(180), Side::kLeft, 1, 10), CornerKind::kOutside);
    EXPECT_EQ(classify_corner(dir(0), dir(180), Side::kRight, 1, 10), CornerKind::kOutside);
}

TEST(CornerClassification, NearReversalIsAReversalWhileTheWedgeIsNarrowerThanRounding) {
    // An inside turn of 180 degrees less delta: a wedge shorter_length * sin(delta) wide.
    const double length = 10;
    const double narrow = std::asin(0.9 * kReversalWedgeWidth / length);
    const double wide = std::asin(1.1 * kReversalWedgeWidth / length);
    for (const Side side : {Side::kLeft, Side::kRight}) {
        const double s = side == Side::kLeft ? 1.0 : -1.0;  // inside: towards the tool
        const Vec2 t_narrow(-std::cos(narrow), s * std::sin(narrow));
        const Vec2 t_wide(-std::cos(wide), s * std::sin(wide));
        EXPECT_EQ(classify_corner(dir(0), t_narrow, side, 1, length), CornerKind::kOutside);
        EXPECT_EQ(classify_corner(dir(0), t_wide, side, 1, length), CornerKind::kInside);
        // Turning away from the tool it is an outside corner however wide.
        EXPECT_EQ(classify_corner(dir(0), Vec2(t_wide.x(), -t_wide.y()), side, 1, length),
                  CornerKind::kOutside);
    }
}

TEST(CornerClassification, TangentWhenTheOffsetEndsLieWithinThePathTolerance) {
    // The gap between the offset ends is 2 r sin(turn / 2).
    for (const double r : {0.01, 0.5, 5.0, 50.0}) {
        const double just_in = 2 * std::asin(0.99 * kPathTolerance / (2 * r));
        const double just_out = 2 * std::asin(1.01 * kPathTolerance / (2 * r));
        for (const double sign : {1.0, -1.0}) {
            EXPECT_EQ(classify_corner(dir(0), Vec2(std::cos(just_in), sign * std::sin(just_in)),
                                      Side::kLeft, r, 10),
                      CornerKind::kTangent)
                << r;
            EXPECT_EQ(classify_corner(dir(0), Vec2(std::cos(just_out), sign * std::sin(just_out)),
                                      Side::kLeft, r, 10),
                      sign > 0 ? CornerKind::kInside : CornerKind::kOutside)
                << r;
        }
        EXPECT_NEAR(offset_gap(just_in, r), 0.99 * kPathTolerance, 1e-15);
    }
}

TEST(CornerClassification, ZeroToolRadiusMakesEveryCornerTangent) {
    EXPECT_EQ(classify_corner(dir(0), dir(90), Side::kLeft, 0, 10), CornerKind::kTangent);
    EXPECT_EQ(classify_corner(dir(0), dir(-170), Side::kRight, 0, 10), CornerKind::kTangent);
}

TEST(TangentJoin, LineIntoTangentArcAddsNoElementAndMeetsExactly) {
    const Element line = make_line({-10, 0}, {0, 0});
    for (bool ccw : {true, false}) {
        const Element arc = make_arc({0, 0}, {5, ccw ? 5.0 : -5.0}, {0, ccw ? 5.0 : -5.0}, ccw);
        for (Side side : {Side::kLeft, Side::kRight}) {
            const CornerJoin j = join_corner(offset_element(line, 1, side).element,
                                             offset_element(arc, 1, side).element, {0, 0},
                                             end_tangent(line), start_tangent(arc), side, 1,
                                             TransitionMode::kCircular, 10);
            EXPECT_EQ(j.kind, CornerKind::kTangent);
            EXPECT_EQ(j.transition.count, 0u);
            EXPECT_EQ(j.held.path.end, j.next.path.start);
            expect_near(j.held.path.end, {0, side == Side::kLeft ? 1.0 : -1.0});
        }
    }
}

TEST(TangentJoin, NearlyTangentGapIsJoinedAtTheHeldEnd) {
    // r = 50 and a turn whose offset gap is half the path tolerance, both ways.
    for (const double sign : {1.0, -1.0}) {
        const double a = sign * 2 * std::asin(0.5 * kPathTolerance / 100);
        const Element l1 = make_line({-10, 0}, {0, 0});
        const Element l2 = make_line({0, 0}, {10 * std::cos(a), 10 * std::sin(a)});
        const CornerJoin j = join_corner(offset_element(l1, 50, Side::kLeft).element,
                                         offset_element(l2, 50, Side::kLeft).element, {0, 0},
                                         end_tangent(l1), start_tangent(l2), Side::kLeft, 50,
                                         TransitionMode::kCircular, 10);
        EXPECT_EQ(j.kind, CornerKind::kTangent);
        EXPECT_EQ(j.held.path.end, j.next.path.start);
        // Neither element moved by more than the gap.
        expect_near(j.held.path.end, {0, 50}, 1e-12);
        EXPECT_LT(distance_to(l2, j.next.path.start) - 50, 1e-12);
        EXPECT_GT(distance_to(l2, j.next.path.start) - 50, -kPathTolerance);
    }
}

TEST(TangentJoin, ArcStartMovedToTheHeldEndTurnsByAsMuchLess) {
    // A line into a concave arc whose tangent differs by a turn within the path tolerance:
    // the arc starts at the line's offset end, and its sweep tells the truth about it.
    const double a = 2 * std::asin(0.5 * kPathTolerance / 2);  // r = 1: gap 0.5 kPathTolerance
    const Element l1 = make_line({-10, 0}, {0, 0});
    const Vec2 t(std::cos(a), std::sin(a));
    const Vec2 centre = 10 * left_normal(t);
    const Element arc = make_arc({0, 0}, centre + 10 * Vec2(1, 0), centre, true);
    const OffsetElement ao = offset_element(arc, 1, Side::kLeft).element;
    const CornerJoin j = join_corner(offset_element(l1, 1, Side::kLeft).element, ao, {0, 0},
                                     end_tangent(l1), start_tangent(arc), Side::kLeft, 1,
                                     TransitionMode::kCircular, 10);
    ASSERT_EQ(j.kind, CornerKind::kTangent);
    const Vec2 u0 = j.next.path.start - centre;
    const Vec2 u1 = j.next.path.end - centre;
    EXPECT_NEAR(j.next.sweep, angle_between(u0, u1, true), 1e-12);
    EXPECT_NEAR(offset_length(j.next), offset_length(ao), 2 * kPathTolerance);
}

// The mirror of the above at the held element's end: a concave arc (radius R a little over the
// tool's r = 1, so its offset turns sharply) into a line turning inwards by a hair over the
// tangent bound. Its offset meets the line's just past the arc's offset end (within the trim
// tolerance), and the arc is made to end there: its sweep grows by as much as it turns on.
TEST(InsideCorner, AHeldArcEndedJustPastItsEndTurnsByAsMuchMore) {
    int past_end = 0;
    for (const double radius : {1.05, 1.1, 1.2, 1.3, 1.4})
        for (const double turn : {1.02e-4, 1.05e-4, 1.1e-4, 1.2e-4, 1.5e-4, 2e-4})
            for (const bool mirrored : {false, true}) {
                // Counter-clockwise about (0, R) into the corner at the origin along +x, the
                // tool on the left (inside); mirrored in the x axis: clockwise, on the right.
                const double m = mirrored ? -1.0 : 1.0;
                const Element arc =
                    make_arc({-radius, m * radius}, {0, 0}, {0, m * radius}, !mirrored);
                const Element line =
                    make_line({0, 0}, 5 * Vec2(std::cos(turn), m * std::sin(turn)));
                const Side side = mirrored ? Side::kRight : Side::kLeft;
                const OffsetElement held = offset_element(arc, 1, side).element;
                const CornerJoin j =
                    join_corner(held, offset_element(line, 1, side).element, {0, 0},
                                end_tangent(arc), start_tangent(line), side, 1,
                                TransitionMode::kCircular, 5);
                ASSERT_EQ(j.reason, Reason::kNone) << radius << " " << turn << " " << m;
                ASSERT_EQ(j.kind, CornerKind::kInside) << radius << " " << turn << " " << m;
                const Vec2 u0 = j.held.path.start - j.held.path.centre;
                const Vec2 u1 = j.held.path.end - j.held.path.centre;
                const double told =
                    mirrored ? -angle_between(u0, u1, false) : angle_between(u0, u1, true);
                EXPECT_NEAR(j.held.sweep, told, 1e-12) << radius << " " << turn << " " << m;
                expect_near(j.held.path.end, j.next.path.start, 1e-12);
                if (std::abs(j.held.sweep) > std::abs(held.sweep)) ++past_end;
            }
    EXPECT_GT(past_end, 0);  // some meetings lie past the arc's end
}

TEST(NearlyTangentCorner, TrimsExactlyHoweverSmallTheTurn) {
    // Two lines meeting at turns from 1e-9 rad upwards, written as CAM output rounds them:
    // every one that is not tangent is trimmed at r tan(turn / 2) from the corner, both
    // ways and on both sides, at any orientation, without refusal.
    for (const double heading : {0.0, 15.0, 105.0, 195.0, 285.0})
        for (const double turn : {1e-9, 1e-7, 1e-5, 1e-4, 1e-3, 1e-2, 0.05})
            for (const double r : {0.5, 2.0, 5.0})
                for (const Side side : {Side::kLeft, Side::kRight})
                    for (const double sign : {1.0, -1.0}) {
                        const Vec2 t1 = dir(heading);
                        const Vec2 t2 = dir(heading + sign * turn * 180 / kPi);
                        const Vec2 c(19.318517, 5.176381);
                        const Element a = make_line(c - 20 * t1, c);
                        const Element b = make_line(c, c + 20 * t2);
                        const CornerJoin j = join_corner(
                            offset_element(a, r, side).element, offset_element(b, r, side).element,
                            c, end_tangent(a), start_tangent(b), side, r,
                            TransitionMode::kCircular, 20);
                        ASSERT_EQ(j.reason, Reason::kNone)
                            << heading << " " << turn << " " << r << " " << sign;
                        const Vec2 x = j.held.path.end;
                        if (j.kind == CornerKind::kOutside) {
                            ASSERT_EQ(j.transition.count, 1u);
                            EXPECT_EQ(j.transition.elements[0].start, x);
                            EXPECT_EQ(j.transition.elements[0].end, j.next.path.start);
                        } else {
                            EXPECT_EQ(x, j.next.path.start);
                        }
                        if (j.kind == CornerKind::kInside) {
                            EXPECT_NEAR(distance_to(a, x), r, 1e-9);
                            EXPECT_NEAR(distance_to(b, x), r, 1e-9);
                            EXPECT_NEAR((j.held.path.end - offset_element(a, r, side).element.path.end)
                                            .norm(),
                                        r * std::tan(turn / 2), 1e-9);
                        }
                        EXPECT_EQ(j.kind == CornerKind::kTangent,
                                  offset_gap(turn, r) <= kPathTolerance);
                    }
}

TEST(CornerFailure, KorrErrorWhenHeldLineIsShorterThanTheInsideCornerNeeds) {
    // 90 degree inside corner with r = 1 needs 1 of the held line; it has 0.5.
    const Element a = make_line({-0.5, 0}, {0, 0});
    const CornerJoin j = join_corner(
        offset_element(a, 1, Side::kLeft).element, offset_element(kLineUp, 1, Side::kLeft).element,
        {0, 0}, end_tangent(a), start_tangent(kLineUp), Side::kLeft, 1, TransitionMode::kCircular,
        0.5);
    EXPECT_EQ(j.reason, Reason::kHeldElementTooShort);
    EXPECT_EQ(reason_bits(j.reason), bits(ErrorBit::kKorrError));
}

TEST(CornerFailure, KorrErrorWhenNextLineIsShorterThanTheInsideCornerNeeds) {
    const Element b = make_line({0, 0}, {0, 0.5});
    const CornerJoin j = join_corner(
        offset_element(kLineIn, 1, Side::kLeft).element, offset_element(b, 1, Side::kLeft).element,
        {0, 0}, end_tangent(kLineIn), start_tangent(b), Side::kLeft, 1, TransitionMode::kCircular,
        0.5);
    EXPECT_EQ(j.reason, Reason::kNextElementTooShort);
}

TEST(CornerFailure, KorrErrorWhenToolDoesNotFitBetweenLineAndConcaveArc) {
    // Line along +x, then turning right by 150 degrees into a concave arc of radius 8: the
    // lens between them is 1.07 deep at most, too thin for a tool of radius 1 (right).
    const Element a = make_line({-8, 0}, {0, 0});
    const Vec2 centre = 8 * Vec2(-0.5, std::sqrt(3.0) / 2);
    const Element b = make_arc({0, 0}, centre + Vec2(0, -8), centre, false);
    const CornerJoin j = join_corner(
        offset_element(a, 1, Side::kRight).element, offset_element(b, 1, Side::kRight).element,
        {0, 0}, end_tangent(a), start_tangent(b), Side::kRight, 1, TransitionMode::kCircular, 8);
    EXPECT_EQ(j.kind, CornerKind::kInside);
    EXPECT_EQ(j.reason, Reason::kNoCornerSolution);
}

TEST(CornerFailure, KorrErrorWhenOffsetElementsDoNotMeetAtAnInsideCorner) {
    // Line along +x, then a ccw arc of radius 4 about (-4, 0) turning left: with r = 3.5
    // the offset line is y = 3.5 and the offset circle has radius 0.5: they never meet.
    const Element a = make_line({-10, 0}, {0, 0});
    const Element b = make_arc({0, 0}, {-4, 4}, {-4, 0}, true);  // starts along +y, radius 4
    const OffsetElement ao = offset_element(a, 3.5, Side::kLeft).element;  // y = 3.5
    const OffsetElement bo = offset_element(b, 3.5, Side::kLeft).element;  // radius 0.5
    const CornerJoin j = join_corner(ao, bo, {0, 0}, end_tangent(a), start_tangent(b), Side::kLeft,
                                     3.5, TransitionMode::kCircular, 6);
    EXPECT_EQ(j.kind, CornerKind::kInside);
    EXPECT_EQ(j.reason, Reason::kNoCornerSolution);
    EXPECT_EQ(intersect_carriers(ao, bo).count, 0u);
}

TEST(Intersections, LineCircleNearTangentCountsAsTouching) {
    const Intersections t =
        intersect_line_circle({0, 1 + 0.5 * kPointTolerance}, {1, 0}, {0, 0}, 1);
    ASSERT_EQ(t.count, 1u);
    expect_near(t.points[0], {0, 1}, 1e-9);
    EXPECT_EQ(intersect_line_circle({0, 1.1}, {1, 0}, {0, 0}, 1).count, 0u);
    EXPECT_EQ(intersect_line_circle({0, 0.5}, {1, 0}, {0, 0}, 1).count, 2u);
}

TEST(Intersections, ConcentricOrSeparateCirclesDoNotMeet) {
    EXPECT_EQ(intersect_circles({0, 0}, 1, {0, 0}, 2).count, 0u);
    EXPECT_EQ(intersect_circles({0, 0}, 1, {5, 0}, 2).count, 0u);
    EXPECT_EQ(intersect_circles({0, 0}, 1, {0.5, 0}, 3).count, 0u);  // one inside the other
    EXPECT_EQ(intersect_circles({0, 0}, 1, {3, 0}, 2).count, 1u);    // touching
    EXPECT_EQ(intersect_lines({0, 0}, {1, 0}, {0, 1}, {2, 0}).count, 0u);
}

}  // namespace
}  // namespace rwmos::geom
