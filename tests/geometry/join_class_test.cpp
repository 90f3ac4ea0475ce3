// SPDX-License-Identifier: MIT
// One regression test per join class of the tolerance model (docs/compensation.md, "The
// tolerance model"), each written as a program writes it (coordinates rounded to 3 or 6
// decimals): nearly tangent and nearly collinear joins, tiny elements down to 1 um, arcs of
// nearly 0 and nearly 360 degrees, a full circle, concave arcs whose offset radius nearly
// vanishes, a reversal written with rounding, and an inside corner whose offsets meet twice.
// Each gives a path every point of which lies r from its own element within the path
// tolerance and no closer than that to any element, or the refusal the model names.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "contours.h"
#include "rwmos/geometry/compensator.h"

namespace rwmos::geom {
namespace {

using apci::test::arc_from;
using apci::test::dir;
using apci::test::round_to;

constexpr double kPi = std::numbers::pi;

// The chain as written with `decimals`: every end point and every centre (from its start)
// rounded, each start taken from the previous end.
std::vector<Element> written(const std::vector<Element>& exact, int decimals) {
    std::vector<Element> out;
    Vec2 from = round_to(exact.front().start, decimals);
    for (const Element& e : exact) {
        Element w = e;
        w.start = from;
        w.end = is_full_circle(e) ? from : round_to(e.end, decimals);
        if (is_arc(e)) w.centre = from + round_to(e.centre - e.start, decimals);
        out.push_back(w);
        from = w.end;
    }
    return out;
}

// A chain from `at` heading `h`: lines (turn, length) and arcs (turn, radius, sweep), each
// turning by `turn` from the previous end tangent.
struct Piece {
    double turn;
    double length_or_radius;
    double sweep = 0.0;  // 0: a line
};
std::vector<Element> chain(Vec2 at, double h, const std::vector<Piece>& pieces) {
    std::vector<Element> out;
    for (const Piece& p : pieces) {
        h += p.turn;
        const Element e = p.sweep == 0.0 ? make_line(at, at + p.length_or_radius * dir(h))
                                         : arc_from(at, h, p.length_or_radius, p.sweep);
        out.push_back(e);
        at = e.end;
        const Vec2 t = end_tangent(e);
        h = std::atan2(t.y(), t.x());
    }
    return out;
}

struct Outcome {
    StepResult error;
    int failing_push = -1;
    std::vector<Segment> path;
};

Outcome compensate(const std::vector<Element>& contour, double r, Side side,
                   TransitionMode mode = TransitionMode::kCircular) {
    Outcome o;
    PathCompensator c;
    SegmentBatch batch;
    const Vec2 from = contour.front().start - 3 * r * start_tangent(contour.front());
    EXPECT_TRUE(c.begin({side, r, mode}, from).ok());
    for (std::size_t k = 0; k < contour.size(); ++k) {
        const StepResult s = c.push(contour[k], static_cast<std::uint32_t>(k), batch);
        if (!s.ok()) {
            o.error = s;
            o.failing_push = static_cast<int>(k);
            return o;
        }
        o.path.insert(o.path.end(), batch.begin(), batch.end());
    }
    c.finish(batch);
    o.path.insert(o.path.end(), batch.begin(), batch.end());
    return o;
}

// Every contour segment r from its own element, every circular transition r from its corner,
// nothing closer than r to any element (all within the path tolerance), and continuous.
// Without `others` only the first two: where the contour comes back round to itself (a circle
// entered tangentially comes back to the line that entered it) offsets come near other
// elements whatever the corner rule (self-approach, which `apcictl run` reports).
void expect_clean_path(const Outcome& o, const std::vector<Element>& contour, double r,
                       const std::string& what, bool others = true) {
    ASSERT_EQ(o.failing_push, -1) << what << ": " << reason_name(o.error.reason) << " at push "
                                  << o.failing_push;
    const double tol = kPathTolerance + 1e-9;
    int contour_segments = 0;
    for (std::size_t i = 0; i < o.path.size(); ++i) {
        const Segment& s = o.path[i];
        if (i > 0) {
            EXPECT_LT((s.path.start - o.path[i - 1].path.end).norm(), 1e-9) << what << " gap " << i;
        }
        if (s.role != SegmentRole::kContour && s.role != SegmentRole::kTransition) continue;
        contour_segments += s.role == SegmentRole::kContour;
        const Element& own = contour[s.index];
        const int n = 200;
        for (int j = 0; j <= n; ++j) {
            const Vec2 p = point_at(s.path, double(j) / n);
            if (s.role == SegmentRole::kContour) {
                EXPECT_NEAR(distance_to(own, p), r, tol) << what << " segment " << i;
            } else if (s.path.kind == ElementKind::kArc) {
                EXPECT_NEAR((p - own.end).norm(), r, tol) << what << " transition " << i;
            }
            for (std::size_t k = 0; others && k < contour.size(); ++k) {
                EXPECT_GE(distance_to(contour[k], p), r - tol) << what << " segment " << i;
            }
        }
    }
    EXPECT_GE(contour_segments, static_cast<int>(contour.size())) << what;
}

TEST(JoinClass, NearlyTangentLineJoinsTurningEitherWayCompensateOnBothSides) {
    for (const double turn : {1e-9, 1e-7, 1e-5, 1e-3, 0.05})
        for (const double sign : {1.0, -1.0})
            for (const Side side : {Side::kLeft, Side::kRight})
                for (const int decimals : {3, 6}) {
                    const auto c = written(
                        chain({1.234567, -2.345678}, 0.3,
                              {{0, 20}, {sign * turn, 20}, {0.5, 15}}),
                        decimals);
                    expect_clean_path(compensate(c, 2.0, side), c, 2.0,
                                      "turn " + std::to_string(sign * turn));
                }
}

TEST(JoinClass, CollinearLinesWrittenWithRoundingCompensateAtAnyHeading) {
    for (int deg = 0; deg < 360; deg += 7)
        for (const Side side : {Side::kLeft, Side::kRight}) {
            const auto c = written(chain({0, 0}, deg * kPi / 180, {{0, 19.3}, {0, 21.7}}), 3);
            expect_clean_path(compensate(c, 0.5, side), c, 0.5, "heading " + std::to_string(deg));
        }
}

TEST(JoinClass, TinyElementsDownToOneMicrometreBetweenNearlyTangentNeighbours) {
    // Written to 6 decimals a 1 um element keeps its direction within a milliradian: a line,
    // a tiny line, a line; a line, a tiny arc, an arc.
    for (const double tiny : {1e-3, 1e-2})  // 1 um and 10 um, in mm
        for (const Side side : {Side::kLeft, Side::kRight}) {
            auto c = written(chain({3, 4}, 1.0, {{0, 10}, {2e-4, tiny}, {-1e-4, 10}}), 6);
            expect_clean_path(compensate(c, 1.0, side), c, 1.0, "tiny line");
            c = written(chain({3, 4}, 1.0, {{0, 10}, {0, 50, tiny / 50}, {0, 8, 1.0}}), 6);
            expect_clean_path(compensate(c, 1.0, side), c, 1.0, "tiny arc");
        }
}

TEST(JoinClass, TinyElementTurnedByRoundingIntoAnInsideCornerItCannotHostIsRefusedByName) {
    // Written to 3 decimals a 1 um step lies along an axis or a diagonal: here 12 degrees off
    // its neighbours, so one of its two corners is an inside corner on either side, whose trim
    // (r tan(6 deg), 0.1 mm) the step cannot host. The board holds one profile, so the
    // neighbours' offsets cannot be joined past it: KorrError naming the step, at its first
    // corner (the step too short) or its second (the held step too short).
    const auto c = written(chain({3, 4}, 1.0, {{0, 10}, {0, 1e-3}, {0, 10}}), 3);
    ASSERT_LT(length(c[1]), 1.5e-3);
    const double turn = std::atan2(cross(end_tangent(c[0]), start_tangent(c[1])),
                                   end_tangent(c[0]).dot(start_tangent(c[1])));
    ASSERT_GT(std::abs(turn), 0.1);
    const Side inside_first = turn > 0 ? Side::kLeft : Side::kRight;
    const Outcome first = compensate(c, 1.0, inside_first);
    EXPECT_EQ(first.failing_push, 1);
    EXPECT_EQ(first.error.reason, Reason::kNextElementTooShort);
    EXPECT_EQ(first.error.errors, bits(ErrorBit::kKorrError));
    EXPECT_EQ(first.error.index, 1u);
    const Outcome second =
        compensate(c, 1.0, inside_first == Side::kLeft ? Side::kRight : Side::kLeft);
    EXPECT_EQ(second.failing_push, 2);
    EXPECT_EQ(second.error.reason, Reason::kHeldElementTooShort);
    EXPECT_EQ(second.error.errors, bits(ErrorBit::kKorrError));
    EXPECT_EQ(second.error.index, 1u);
}

TEST(JoinClass, TinyElementAtAnOutsideCornerGetsItsTransitions) {
    // 1 um across a corner turning away from the tool: two transitions, nothing refused.
    for (const TransitionMode mode : {TransitionMode::kCircular, TransitionMode::kLinear}) {
        const auto c = written(chain({0, 0}, 0.0, {{0, 10}, {-0.6, 0.001}, {-0.6, 10}}), 6);
        const Outcome o = compensate(c, 1.0, Side::kLeft, mode);
        if (mode == TransitionMode::kCircular) expect_clean_path(o, c, 1.0, "outside, tiny");
        ASSERT_EQ(o.failing_push, -1);
        // Linear transitions are no closer than r, never at r: the rest of the check.
        for (const Segment& s : o.path)
            for (int j = 0; j <= 50 && s.role != SegmentRole::kApproach &&
                            s.role != SegmentRole::kDeparture;
                 ++j)
                for (const Element& e : c)
                    EXPECT_GE(distance_to(e, point_at(s.path, j / 50.0)), 1.0 - kPathTolerance);
    }
}

TEST(JoinClass, ArcsOfNearlyZeroDegreesBetweenTangentLines) {
    for (const Side side : {Side::kLeft, Side::kRight})
        for (const double sweep : {1e-4, 1e-3, 0.05})
            for (const double dirn : {1.0, -1.0})
                for (const int decimals : {3, 6}) {
                    if (decimals == 3 && sweep < 0.05) continue;  // a sliver: no direction
                    const auto c = written(
                        chain({-20, 1}, 0.2, {{0, 10}, {0, 12, dirn * sweep}, {0, 10}}), decimals);
                    expect_clean_path(compensate(c, 1.5, side), c, 1.5,
                                      "sweep " + std::to_string(dirn * sweep));
                }
}

// A full circle, or nearly one, entered tangentially from a line: the circle comes back round
// to the line, and their offsets come within r of each other there (self-approach, whichever
// side the tool is on); the join is what is checked: each offset r from its element, the path
// continuous, the circle whole.
TEST(JoinClass, ArcsOfNearlyThreeHundredSixtyDegreesEnteredTangentially) {
    for (const double sweep : {2 * kPi - 1e-3, 2 * kPi - 0.05})
        for (const double dirn : {1.0, -1.0})
            for (const Side side : {Side::kLeft, Side::kRight})
                for (const int decimals : {3, 6}) {
                    const auto c =
                        written(chain({-20, 1}, 0.2, {{0, 10}, {0, 12, dirn * sweep}}), decimals);
                    expect_clean_path(compensate(c, 1.5, side), c, 1.5,
                                      "sweep " + std::to_string(dirn * sweep), false);
                }
}

TEST(JoinClass, FullCircleAfterATangentLineStaysAFullCircle) {
    for (const double dirn : {1.0, -1.0})
        for (const Side side : {Side::kLeft, Side::kRight})
            for (const int decimals : {3, 6}) {
                const auto c =
                    written(chain({0, 0}, 0.7, {{0, 10}, {0, 6, dirn * 2 * kPi}}), decimals);
                ASSERT_TRUE(is_full_circle(c[1]));
                const Outcome o = compensate(c, 1.0, side);
                expect_clean_path(o, c, 1.0, "full circle", false);
                bool full = false;
                for (const Segment& s : o.path) full |= s.index == 1 && is_full_circle(s.path);
                EXPECT_TRUE(full);
            }
}

TEST(JoinClass, ConcaveArcWhoseOffsetRadiusNearlyVanishes) {
    // The tool on the arc's concave side (G41 on a ccw arc): R - r from +1e-6 (the tool just
    // fits) down to the path tolerance below zero runs; beyond it, CalcError.
    const double r = 4.0;
    for (const double slack : {1e-6, 0.0, -5e-5, -1e-4 + 1e-6}) {
        const auto c = chain({0, 0}, 0.0, {{0, 10}, {0, r + slack, kPi / 2}, {0, 10}});
        const Outcome o = compensate(c, r, Side::kLeft);
        ASSERT_EQ(o.failing_push, -1) << slack;
        // Every point no closer than the path tolerance to the contour.
        for (const Segment& s : o.path)
            for (int j = 0; j <= 100 && s.role != SegmentRole::kApproach &&
                            s.role != SegmentRole::kDeparture;
                 ++j)
                for (const Element& e : c)
                    EXPECT_GE(distance_to(e, point_at(s.path, j / 100.0)), r - kPathTolerance - 1e-9)
                        << slack;
    }
    const auto c = chain({0, 0}, 0.0, {{0, 10}, {0, r - 2e-4, kPi / 2}, {0, 10}});
    const Outcome o = compensate(c, r, Side::kLeft);
    EXPECT_EQ(o.failing_push, 1);
    EXPECT_EQ(o.error.errors, bits(ErrorBit::kCalcError));
}

TEST(JoinClass, ReversalWrittenWithRoundingGoesRoundTheEnd) {
    // Out and back along the same line, the way back written to 3 decimals: within a degree
    // and narrower than rounding it is a reversal on both sides (a half circle round the end).
    for (const Side side : {Side::kLeft, Side::kRight}) {
        const auto c = written(chain({0, 0}, 0.4, {{0, 12}, {kPi - 3e-5, 12}}), 3);
        const Outcome o = compensate(c, 1.0, side);
        ASSERT_EQ(o.failing_push, -1);
        bool half_circle = false;
        for (const Segment& s : o.path)
            half_circle |= s.role == SegmentRole::kTransition && is_arc(s.path) &&
                           std::abs(std::abs(sweep(s.path)) - kPi) < 1e-3;
        EXPECT_TRUE(half_circle);
    }
}

TEST(JoinClass, InsideCornerWhoseOffsetsMeetTwiceTrimsAtTheMeetingNearestTheCorner) {
    // Two arcs bending towards the tool: their offset circles meet twice; the trim is the
    // meeting nearest the corner, and the path keeps r from both arcs.
    const auto c = written(chain({0, 0}, 0.0, {{0, 10, 1.2}, {1.0, 10, 1.2}}), 3);
    const Outcome o = compensate(c, 1.0, Side::kLeft);
    expect_clean_path(o, c, 1.0, "meets twice");
    ASSERT_GE(o.path.size(), 3u);
    // The held arc ends near the corner (within a few r), not at the far meeting.
    for (const Segment& s : o.path) {
        if (s.role == SegmentRole::kContour && s.index == 0) {
            EXPECT_LT((s.path.end - c[0].end).norm(), 3.0);
        }
    }
}

}  // namespace
}  // namespace rwmos::geom
