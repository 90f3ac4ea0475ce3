// SPDX-License-Identifier: MIT
// The exact line and arc distances of the self-approach check (apci/run/plane_distance.h),
// against an independent brute force: both curves sampled densely, the least distance of all
// sample pairs. That is at least the true least distance, and at most it plus half of each
// curve's sample spacing; the exact distance must lie in between. Random inputs as programs
// have them: coordinates rounded to 3 or 4 decimals, arcs whose start and end radii differ by
// that rounding, elements that touch, are tangent, cross or are tiny.
#include "apci/run/plane_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

namespace {

using apci::run::plane::Arc;
using apci::run::plane::Parametric;
using apci::run::plane::Vec2;
namespace pd = apci::run::plane;
constexpr double kPi = std::numbers::pi;

// n + 1 points of an element (line or spiral arc) at even steps of its parameter.
std::vector<Vec2> sample(const Parametric& e, int n) {
    std::vector<Vec2> out;
    for (int i = 0; i <= n; ++i) {
        const double t = static_cast<double>(i) / n;
        if (!is_arc(e)) {
            out.emplace_back(e.start + t * (e.end - e.start));
        } else {
            const double phi = e.phi0 + t * e.sweep, r = e.r0 + t * (e.r1 - e.r0);
            out.emplace_back(e.centre + r * Vec2(std::cos(phi), std::sin(phi)));
        }
    }
    return out;
}

double brute(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    double best = INFINITY;
    for (const Vec2& p : a)
        for (const Vec2& q : b) best = std::min(best, (p - q).squaredNorm());
    return std::sqrt(best);
}

// The largest distance between two neighbouring samples.
double spacing(const std::vector<Vec2>& s) {
    double m = 0.0;
    for (std::size_t i = 1; i < s.size(); ++i) m = std::max(m, (s[i] - s[i - 1]).norm());
    return m;
}

Parametric line(const Vec2& a, const Vec2& b) {
    Parametric e;
    e.start = a;
    e.end = b;
    return e;
}

Parametric circular(const Vec2& c, double r, double phi0, double sweep) {
    Parametric e;
    e.kind = geom::ElementKind::kArc;
    e.ccw = sweep > 0.0;
    e.centre = c;
    e.r0 = e.r1 = r;
    e.phi0 = phi0;
    e.sweep = sweep;
    e.start = c + r * Vec2(std::cos(phi0), std::sin(phi0));
    e.end = c + r * Vec2(std::cos(phi0 + sweep), std::sin(phi0 + sweep));
    return e;
}

Arc arc_of(const Parametric& e) {
    return Arc{e.centre, e.r0, e.phi0, e.sweep};
}

double exact(const Parametric& a, const Parametric& b) {
    if (!is_arc(a) && !is_arc(b)) return pd::segment_segment(a.start, a.end, b.start, b.end);
    if (!is_arc(a)) return pd::segment_arc(a.start, a.end, arc_of(b));
    if (!is_arc(b)) return pd::segment_arc(b.start, b.end, arc_of(a));
    return pd::arc_arc(arc_of(a), arc_of(b));
}

double round_to(double v, int decimals) {
    const double s = std::pow(10.0, decimals);
    return std::round(v * s) / s;
}

// A random line or circular arc near the origin, its points rounded as a program writes them;
// now and then tiny, or starting where `from` ends (a join), or tangent to it.
Parametric random_element(std::mt19937_64& rng, int decimals, const Parametric* from) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const auto rp = [&](double scale) {
        return Vec2(round_to(scale * u(rng), decimals), round_to(scale * u(rng), decimals));
    };
    const double size = (rng() % 8 == 0) ? 0.01 : 5.0;  // tiny elements too
    Vec2 start = rp(5.0);
    if (from != nullptr && rng() % 2 == 0) start = from->end;
    if (rng() % 2 == 0) return line(start, start + rp(size));
    const double r = std::max(round_to(std::abs(size * u(rng)), decimals), 0.002);
    const double phi0 = kPi * u(rng);
    const Vec2 centre(round_to(start.x() - r * std::cos(phi0), decimals),
                      round_to(start.y() - r * std::sin(phi0), decimals));
    const double sweep = 2.0 * kPi * u(rng);
    return circular(centre, r, phi0, sweep);
}

TEST(PlaneDistance, ExactDistancesLieBetweenTheSampledOnesAndThemLessTheSpacing) {
    std::mt19937_64 rng(20261126);
    int crossing = 0, apart = 0;
    for (int k = 0; k < 400; ++k) {
        const int decimals = 3 + static_cast<int>(rng() % 2);
        const Parametric a = random_element(rng, decimals, nullptr);
        const Parametric b = random_element(rng, decimals, &a);
        const auto sa = sample(a, 700), sb = sample(b, 700);
        const double sampled = brute(sa, sb);
        const double d = exact(a, b);
        SCOPED_TRACE(k);
        // The exact distance is that of two points of the curves, at most the sampled one...
        EXPECT_LE(d, sampled + 1e-12);
        // ...and no less than the sampled one less half of each spacing.
        EXPECT_GE(d, sampled - 0.5 * (spacing(sa) + spacing(sb)) - 1e-12);
        (d == 0.0 ? crossing : apart) += 1;
    }
    EXPECT_GT(crossing, 40);  // the inputs have both kinds
    EXPECT_GT(apart, 40);
}

// The least distance of two segments written independently: 0 where they cross or touch (by
// the signs of four orientations, collinear overlaps included), else the least of the four
// distances from an end of one to the other.
double point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 == 0.0 ? 0.0 : std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
    return (p - (a + t * ab)).norm();
}

double segments_apart(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
    const auto orient = [](const Vec2& p, const Vec2& q, const Vec2& r) {
        const double v = (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
        return (v > 0.0) - (v < 0.0);
    };
    const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
              o4 = orient(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0) return 0.0;
    return std::min({point_segment(a, c, d), point_segment(b, c, d), point_segment(c, a, b),
                     point_segment(d, a, b)});
}

// Random pairs of lines as programs have them (3 or 4 decimals): apart, crossing, touching at
// an end, parallel beside each other (overlapping or not), collinear, tiny and of no length.
// The distance is the independent one (to rounding), lies within the sampled bounds, and is
// the distance at the fraction given.
TEST(PlaneDistance, LinesNearestIsTheLeastDistanceBetweenTwoLinesAndWhereItIs) {
    std::mt19937_64 rng(20261129);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int crossing = 0, parallel = 0, apart = 0;
    for (int k = 0; k < 2000; ++k) {
        const int decimals = 3 + static_cast<int>(rng() % 2);
        const auto rp = [&](double scale) {
            return Vec2(round_to(scale * u(rng), decimals), round_to(scale * u(rng), decimals));
        };
        const double size = (rng() % 8 == 0) ? 0.01 : 5.0;
        const Vec2 a = rp(5.0);
        const Vec2 b = rng() % 20 == 0 ? a : a + rp(size);
        Vec2 c = rp(5.0), d = c + rp(size);
        switch (rng() % 4) {
            case 0: {  // parallel beside it (a shifted copy, along and across)
                const Vec2 shift = rp(1.0);
                c = a + shift;
                d = b + shift + round_to(u(rng), decimals) * (b - a);
                break;
            }
            case 1:  // from the path's end or start
                c = rng() % 2 == 0 ? b : a;
                break;
            default:
                break;
        }
        const Parametric path = line(a, b), contour = line(c, d);
        const pd::Nearest n = pd::lines_nearest(path, contour);
        SCOPED_TRACE(::testing::Message()
                     << k << ": " << a.transpose() << " -> " << b.transpose() << " against "
                     << c.transpose() << " -> " << d.transpose());
        const double independent = segments_apart(a, b, c, d);
        EXPECT_NEAR(n.distance, independent, 1e-12);
        ASSERT_GE(n.t, 0.0);
        ASSERT_LE(n.t, 1.0);
        EXPECT_NEAR(pd::distance_to(contour, pd::point_at(path, n.t)), n.distance, 1e-12);
        const auto sa = sample(path, 400), sb = sample(contour, 400);
        EXPECT_LE(n.distance, brute(sa, sb) + 1e-12);
        EXPECT_GE(n.distance, brute(sa, sb) - 0.5 * (spacing(sa) + spacing(sb)) - 1e-12);
        const bool along =
            std::abs(geom::cross(b - a, d - c)) <= 1e-9 * (b - a).norm() * (d - c).norm();
        (n.distance == 0.0 ? crossing : along ? parallel : apart) += 1;
    }
    EXPECT_GT(crossing, 100);  // the inputs have every kind
    EXPECT_GT(parallel, 100);
    EXPECT_GT(apart, 100);
}

// Where the lines cross at their very ends, and one step past them; along parallel lines the
// first of the places as near.
TEST(PlaneDistance, LinesNearestAtTheEdges) {
    // Crossing at the path's end and the contour's start: 0 there.
    const pd::Nearest at_end = pd::lines_nearest(line({0, 0}, {2, 0}), line({2, 0}, {2, 3}));
    EXPECT_EQ(at_end.distance, 0.0);
    EXPECT_EQ(at_end.t, 1.0);
    // The contour's start one step past the path's end: the distance of that step, at the end.
    const double step = 1e-9;
    const pd::Nearest past =
        pd::lines_nearest(line({0, 0}, {2, 0}), line({2 + step, 0}, {2 + step, 3}));
    EXPECT_NEAR(past.distance, step, 1e-15);
    EXPECT_GT(past.distance, 0.0);
    EXPECT_EQ(past.t, 1.0);
    // Crossing at the path's start, inside the contour: t 0.
    const pd::Nearest at_start = pd::lines_nearest(line({1, 0}, {1, 4}), line({0, 0}, {2, 0}));
    EXPECT_EQ(at_start.distance, 0.0);
    EXPECT_EQ(at_start.t, 0.0);
    // Crossing in the middle of both.
    const pd::Nearest middle = pd::lines_nearest(line({0, -1}, {0, 3}), line({-1, 0}, {1, 0}));
    EXPECT_EQ(middle.distance, 0.0);
    EXPECT_DOUBLE_EQ(middle.t, 0.25);
    // Parallel, the contour beside the path's middle: its start's foot (0.2), not its end's.
    const pd::Nearest beside = pd::lines_nearest(line({0, 0}, {10, 0}), line({2, 1}, {5, 1}));
    EXPECT_DOUBLE_EQ(beside.distance, 1.0);
    EXPECT_DOUBLE_EQ(beside.t, 0.2);
    // Parallel and overlapping from the path's start: the start.
    const pd::Nearest overlap = pd::lines_nearest(line({0, 0}, {10, 0}), line({-1, 1}, {5, 1}));
    EXPECT_DOUBLE_EQ(overlap.distance, 1.0);
    EXPECT_EQ(overlap.t, 0.0);
    // Parallel, the contour beside the path's second half: the end (1), not the foot of the
    // contour's start (0.5), which is as near.
    const pd::Nearest end_first = pd::lines_nearest(line({0, 1}, {2, 1}), line({1, 0}, {5, 0}));
    EXPECT_DOUBLE_EQ(end_first.distance, 1.0);
    EXPECT_EQ(end_first.t, 1.0);
    // Parallel, the contour beyond the path's end: the end.
    const pd::Nearest beyond = pd::lines_nearest(line({0, 0}, {1, 0}), line({4, 4}, {5, 4}));
    EXPECT_DOUBLE_EQ(beyond.distance, 5.0);
    EXPECT_EQ(beyond.t, 1.0);
    // A path of no length: its point.
    const pd::Nearest point = pd::lines_nearest(line({1, 1}, {1, 1}), line({0, 0}, {2, 0}));
    EXPECT_DOUBLE_EQ(point.distance, 1.0);
    EXPECT_EQ(point.t, 0.0);
}

// Lines that cross at an end of one of them, where the distance measured at that end is not 0
// but a rounding error: (-0.5, -0.17) lies three tenths along the line from (-0.77, 0.07) to
// (0.13, -0.73) (their cross product is exactly 0), but its distance from that segment rounds
// to 2.8e-17. The crossing is 0 in each of the four ways it can lie: at the path's start, at
// its end, at the contour's start and at its end.
TEST(PlaneDistance, LinesNearestIsZeroAtACrossingAtAnEndWhereTheMeasuredDistanceRounds) {
    const Vec2 p(-0.5, -0.17), q(1.9, 0.73), a(-0.77, 0.07), b(0.13, -0.73);
    ASSERT_GT(pd::point_segment(p, a, b), 0.0);  // else this tests nothing
    const pd::Nearest path_start = pd::lines_nearest(line(p, q), line(a, b));
    EXPECT_EQ(path_start.distance, 0.0);
    EXPECT_EQ(path_start.t, 0.0);
    const pd::Nearest path_end = pd::lines_nearest(line(q, p), line(a, b));
    EXPECT_EQ(path_end.distance, 0.0);
    EXPECT_EQ(path_end.t, 1.0);
    const pd::Nearest contour_start = pd::lines_nearest(line(a, b), line(p, q));
    EXPECT_EQ(contour_start.distance, 0.0);
    EXPECT_NEAR(contour_start.t, 0.3, 1e-15);
    const pd::Nearest contour_end = pd::lines_nearest(line(a, b), line(q, p));
    EXPECT_EQ(contour_end.distance, 0.0);
    EXPECT_NEAR(contour_end.t, 0.3, 1e-15);
}

TEST(PlaneDistance, KnownConfigurations) {
    // Tangent from outside and inside, concentric, a line tangent to an arc, crossing, and
    // pairs whose nearest points are ends.
    const Parametric c1 = circular({0, 0}, 2.0, 0.0, 2 * kPi);
    EXPECT_NEAR(exact(c1, circular({5, 0}, 3.0, kPi / 2, kPi)), 0.0, 1e-12);     // touching
    EXPECT_NEAR(exact(c1, circular({6, 0}, 3.0, kPi / 2, kPi)), 1.0, 1e-12);     // 1 apart
    EXPECT_NEAR(exact(c1, circular({0, 0}, 3.5, 1.0, 0.5)), 1.5, 1e-12);         // concentric
    EXPECT_NEAR(exact(c1, circular({0.5, 0}, 1.0, -kPi / 2, kPi)), 0.5, 1e-12);  // inside
    // Half circle, upper half; a line below it: the nearest points are the arc's ends.
    const Parametric upper = circular({0, 0}, 2.0, 0.0, kPi);
    EXPECT_NEAR(exact(upper, line({-3, -1}, {3, -1})), 1.0, 1e-12);
    EXPECT_NEAR(exact(upper, line({-1, 3}, {1, 3})), 1.0, 1e-12);  // tangent side, 1 above
    EXPECT_NEAR(exact(upper, line({-1, 1}, {1, 1})), 2.0 - std::sqrt(2.0), 1e-12);  // inside
    EXPECT_NEAR(exact(upper, line({-3, 1}, {3, 1})), 0.0, 1e-12);                   // crosses
    EXPECT_NEAR(exact(line({0, 0}, {1, 0}), line({2, 1}, {3, 5})), std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(exact(line({0, 0}, {4, 0}), line({2, 1}, {2, 5})), 1.0, 1e-12);
    EXPECT_EQ(exact(line({0, 0}, {4, 4}), line({0, 4}, {4, 0})), 0.0);
    // Clockwise turn: the lower half from (2, 0) to (-2, 0); a point above is nearest an end.
    const Arc lower{{0, 0}, 2.0, 0.0, -kPi};
    EXPECT_NEAR(pd::point_arc({0, 3}, lower), std::sqrt(13.0), 1e-12);
    EXPECT_NEAR(pd::point_arc({0, -3}, lower), 1.0, 1e-12);
}

// An arc whose ends lie at most 1e-9 apart is a full circle: a whole turn in its sense, so the
// point opposite its start lies on it. One rounding step further apart, a clockwise arc is the
// chord's sliver (chord / 5 rad about a centre 5 below the start), 10 from that point.
TEST(PlaneDistance, AnArcElementIsAFullCircleWhereItsEndsLieWithinTheTolerance) {
    const Vec2 start(0, 0), centre(0, -5), opposite(0, -10);
    for (const double gap : {1e-9, 0.5e-9, 0.0})
        for (const bool ccw : {true, false}) {
            const Parametric e = pd::arc_element(start, {gap, 0}, centre, ccw);
            EXPECT_EQ(e.sweep, ccw ? 2 * kPi : -2 * kPi) << gap << " " << ccw;
            EXPECT_NEAR(pd::distance_to(e, opposite), 0.0, 1e-9) << gap << " " << ccw;
        }
    const double past = std::nextafter(1e-9, 1.0);
    const Parametric cw = pd::arc_element(start, {past, 0}, centre, false);
    EXPECT_NEAR(cw.sweep, -past / 5, 1e-20);
    EXPECT_NEAR(pd::distance_to(cw, opposite), 10.0, 1e-9);
    const Parametric ccw = pd::arc_element(start, {past, 0}, centre, true);
    EXPECT_NEAR(ccw.sweep, 2 * kPi - past / 5, 1e-15);
    EXPECT_NEAR(pd::distance_to(ccw, opposite), 0.0, 1e-9);
}

// Random pairs of spiral arcs (start and end radius differing by up to 2e-3, as rounded
// centres make them) and lines, and a limit near their least distance.
TEST(PlaneDistance, ApartIsNeverClaimedForElementsThatComeWithinTheLimit) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int proved = 0, refused = 0;
    for (int k = 0; k < 400; ++k) {
        Parametric a = random_element(rng, 3, nullptr);
        Parametric b = random_element(rng, 4, &a);
        for (Parametric* e : {&a, &b})
            if (is_arc(*e)) {  // a spiral: its end where the radius has changed
                e->r1 = std::max(1e-3, e->r0 + 2e-3 * u(rng));
                const double phi1 = e->phi0 + e->sweep;
                e->end = e->centre + e->r1 * Vec2(std::cos(phi1), std::sin(phi1));
            }
        const auto sa = sample(a, 700), sb = sample(b, 700);
        const double sampled = brute(sa, sb);
        const double slack = 0.5 * (spacing(sa) + spacing(sb));
        // Limits around the least distance: below it by 1e-4 (should be proved) and above.
        for (const double limit : {sampled - slack - 1e-4, sampled + 1e-9, sampled + 0.1}) {
            if (limit <= 0.0) continue;
            const bool is_apart = pd::apart(a, b, limit);
            SCOPED_TRACE(::testing::Message() << k << " limit " << limit);
            if (limit > sampled) {
                // Two points closer than the limit exist: never proved apart.
                EXPECT_FALSE(is_apart);
                refused += 1;
            } else {
                // 1e-4 below any sample pair's distance: the proof gets there.
                EXPECT_TRUE(is_apart) << "sampled " << sampled;
                proved += is_apart;
            }
        }
    }
    EXPECT_GT(proved, 100);
    EXPECT_GT(refused, 100);
}

// What the check asks most: the path of an arc (its offset, tool radius 1 inside a
// counter-clockwise arc under G41) against the next element, a line leaving the arc's end at a
// convex corner. The path's end is 1 from the corner, nothing is nearer: proved apart at the
// radius less twice the path tolerance, though the arcs are spirals (rounded centres).
TEST(PlaneDistance, ApartProvesTheNextElementAtAConvexCornerKeepsTheRadius) {
    for (const double radius : {1.6, 10.0, 250.0})
        for (const double dr : {-2e-3, -3e-4, 0.0, 5e-4, 2e-3})
            for (const double turn_deg : {5.0, 30.0, 90.0, 170.0})
                for (const double sweep : {0.3, 2.0, 5.5}) {
                    SCOPED_TRACE(::testing::Message()
                                 << radius << " " << dr << " " << turn_deg << " " << sweep);
                    Parametric contour = circular({3.25, -1.5}, radius, 0.4, sweep);
                    contour.r1 = radius + dr;
                    contour.end = contour.centre +
                                  contour.r1 * Vec2(std::cos(0.4 + sweep), std::sin(0.4 + sweep));
                    Parametric path = contour;
                    path.r0 -= 1.0;
                    path.r1 -= 1.0;
                    path.start = path.centre + path.r0 * Vec2(std::cos(0.4), std::sin(0.4));
                    path.end =
                        path.centre + path.r1 * Vec2(std::cos(0.4 + sweep), std::sin(0.4 + sweep));
                    // The tangent at the end, turned right (away from the tool) by the turn.
                    const double phi = 0.4 + sweep + kPi / 2 - turn_deg * kPi / 180.0;
                    const Parametric next =
                        line(contour.end, contour.end + 7.0 * Vec2(std::cos(phi), std::sin(phi)));
                    EXPECT_TRUE(pd::apart(path, next, 1.0 - 2e-4 + 1e-7));
                    EXPECT_FALSE(pd::apart(path, next, 1.0 + 1e-9));  // the end is 1 away
                }
}

// The cheaper proof by one side (apart_by_side) never claims what is not so: on random lines and
// spirals, joined, tangent and apart, a claim at a limit means no pair of sampled points comes
// closer than it (less the sampling's slack). And it proves the pairs it is there for: a line's
// path against an arc rounding the corner after it, an arc's path against the line leaving it.
TEST(PlaneDistance, ApartBySideIsNeverClaimedForElementsThatComeWithinTheLimit) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int claimed = 0;
    for (int k = 0; k < 3000; ++k) {
        Parametric a = random_element(rng, 3, nullptr);
        Parametric b = random_element(rng, 4, &a);
        for (Parametric* e : {&a, &b})
            if (is_arc(*e) && rng() % 2 == 0) {  // a spiral
                e->r1 = std::max(1e-3, e->r0 + 2e-3 * u(rng));
                const double phi1 = e->phi0 + e->sweep;
                e->end = e->centre + e->r1 * Vec2(std::cos(phi1), std::sin(phi1));
            }
        const auto sa = sample(a, 400), sb = sample(b, 400);
        const double sampled = brute(sa, sb);
        const double slack = 0.5 * (spacing(sa) + spacing(sb));
        for (const double limit : {0.05, 0.5, 1.0, 2.0, 5.0}) {
            if (!pd::apart_by_side(a, b, limit)) continue;
            ++claimed;
            EXPECT_GE(sampled + slack, limit) << k << " limit " << limit;
        }
    }
    EXPECT_GT(claimed, 1000);
}

TEST(PlaneDistance, ApartBySideOfASpiralTakesItsLargerRadiusOutsideAndItsSmallerInside) {
    // A spiral arc (rounded centres make its radii differ) about the origin, counter-clockwise
    // a quarter turn from radius 5 at (5, 0) out to 5.002 at (0, 5.002); a short line on the
    // radius through either end, outside or inside, 1e-3 nearer than the limit to that end,
    // or 1e-6 farther than the limit from every radius of the spiral.
    const double limit = 1.0;
    Parametric a = circular({0, 0}, 5.0, 0.0, kPi / 2);
    a.r1 = 5.002;
    a.end = {0.0, 5.002};
    const auto radial = [](double angle, double from, double to) {
        const Vec2 u(std::cos(angle), std::sin(angle));
        return line(from * u, to * u);
    };
    // Outside its end (radius 5.002): 0.999 away, not apart; outside 5.002 + limit: apart.
    EXPECT_FALSE(pd::apart_by_side(a, radial(kPi / 2, 6.001, 6.1), limit));
    EXPECT_TRUE(pd::apart_by_side(a, radial(kPi / 2, 6.002 + 1e-6, 6.1), limit));
    // Inside its start (radius 5): 0.999 away, not apart; inside 5 - limit: apart.
    EXPECT_FALSE(pd::apart_by_side(a, radial(0.0, 3.9, 4.001), limit));
    EXPECT_TRUE(pd::apart_by_side(a, radial(0.0, 3.9, 4.0 - 1e-6), limit));
    for (const Parametric& b : {radial(kPi / 2, 6.001, 6.1), radial(0.0, 3.9, 4.001)}) {
        const double sampled = brute(sample(a, 2000), sample(b, 50));
        EXPECT_LT(sampled, limit);  // what the claims above rest on
    }
}

TEST(PlaneDistance, ApartBySideProvesTheRoundedCornerNeighboursOfAPath) {
    // A line along +X to the origin under G41 (tool above, radius 1): its path at y = 1. The
    // corner rounded by an arc of radius 3 turning right (down) away from the tool: every point
    // of it lies at least 1 below the path.
    const Parametric path = line({-10, 1}, {0, 1});
    const Parametric fillet = circular({0, -3}, 3.0, kPi / 2, -kPi / 2);
    EXPECT_TRUE(pd::apart_by_side(path, fillet, 1.0 - 2e-4));
    EXPECT_FALSE(pd::apart_by_side(path, fillet, 1.0 + 1e-9));
    // The fillet's path (radius 4 about (0, -3)) against the line leaving its end (3, -3)
    // straight down: the path lies wholly behind that line's start, whose distance decides.
    const Parametric fillet_path = circular({0, -3}, 4.0, kPi / 2, -kPi / 2);
    const Parametric leaving = line({3, -3}, {3, -20});
    EXPECT_TRUE(pd::apart_by_side(fillet_path, leaving, 1.0 - 2e-4));
    EXPECT_FALSE(pd::apart_by_side(fillet_path, leaving, 1.0 + 1e-9));
    // A line that comes back under the path is not proved apart by its side.
    const Parametric back = line({0, -0.5}, {-5, 0.2});
    EXPECT_FALSE(pd::apart_by_side(path, back, 1.0 - 2e-4));
}

// A line leaving a spiral radially from a point within its turn: the spiral's lower bound there
// is the radial distance a hair less (its slope k against c, the curvature's term), not that
// distance less the radius's whole change. The quarter turn from radius 10 to 10.5 about the
// origin; the line starts 1 outside it at 45 degrees and leaves straight out: apart by 0.99
// (0.999 of the radial distance is proved), with the whole change (0.5) taken off it is not.
TEST(PlaneDistance, ApartBySideTakesASpiralsRadialDistanceWithinItsTurn) {
    const Parametric spiral = pd::arc_element({10, 0}, {0, 10.5}, {0, 0}, true);
    const Vec2 u(std::sqrt(0.5), std::sqrt(0.5));
    const Vec2 start = 11.25 * u;  // the spiral's radius at 45 degrees is 10.25
    const Parametric leaving = line(start, start + 5.0 * u);
    EXPECT_GT(brute(sample(spiral, 20000), sample(leaving, 50)), 0.99);  // what the claim rests on
    EXPECT_TRUE(pd::apart_by_side(spiral, leaving, 0.99));
    EXPECT_FALSE(pd::apart_by_side(spiral, leaving, 1.0 + 1e-9));
}

// An arc whose radii differ by a rounding (less than 1e-9: its ends and centre written with a
// few decimals) is taken as lying within the annulus of its two radii, without the angle of the
// direction asked: looser by that difference, never nearer than it is. A quarter turn about the
// origin from radius 5 out to 5 + 8e-10, 45 to 135 degrees; at 90 degrees its radius is 5 + 4e-10.
TEST(PlaneDistance, ApartBySideOfAnArcWithRoundedRadiiTakesItsLargerRadiusOutsideAndSmallerInside) {
    const Vec2 u45(std::sqrt(0.5), std::sqrt(0.5)), u135(-std::sqrt(0.5), std::sqrt(0.5));
    const Parametric arc = pd::arc_element(5.0 * u45, (5.0 + 8e-10) * u135, {0, 0}, true);
    ASSERT_GT(arc.r1 - arc.r0, 5e-10);
    ASSERT_LT(arc.r1 - arc.r0, 1e-9);
    const double limit = 1.0;
    // A line across the top, 1 - 2e-10 above the arc's radius at 90 degrees: nearer than the
    // limit, never proved apart; 1 + 1e-9 above its larger radius: apart.
    const auto across = [](double y) { return line({-1.0, y}, {1.0, y}); };
    EXPECT_FALSE(pd::apart_by_side(across(6.0 + 2e-10), arc, limit));
    EXPECT_TRUE(pd::apart_by_side(across(6.0 + 8e-10 + 1e-9), arc, limit));
    // A line leaving the arc radially at 90 degrees from 1 - 2e-10 beyond its radius there: not
    // proved; from 1 + 4e-10 beyond its larger radius: apart.
    const auto leaving = [](double from) { return line({0.0, from}, {0.0, from + 5.0}); };
    EXPECT_FALSE(pd::apart_by_side(arc, leaving(6.0 + 2e-10), limit));
    EXPECT_TRUE(pd::apart_by_side(arc, leaving(6.0 + 1.2e-9), limit));
    // Inside: a line rising along the radius to 1 + 4e-10 below the smaller radius is apart; one
    // rising to 1 - 4e-10 below it is not proved (all the proof knows is the annulus).
    const auto rising = [](double to) { return line({0.0, to - 2.0}, {0.0, to}); };
    EXPECT_TRUE(pd::apart_by_side(arc, rising(4.0 - 4e-10), limit));
    EXPECT_FALSE(pd::apart_by_side(arc, rising(4.0 + 4e-10), limit));
    // What the first claims rest on: nearer than the limit (samples at 90 degrees on both).
    for (const Parametric& b : {across(6.0 + 2e-10), leaving(6.0 + 2e-10)})
        EXPECT_LT(brute(sample(arc, 20000), sample(b, 50)), limit);
}

// The annulus bound of an arc with rounded radii is taken however short its turn: an arc of
// 2e-6 rad at radius 5 whose radii differ by 5e-10 has a slope k = 2.5e-4 per radian, whose
// spiral term (pi^2 k^2 / 8 rmin, 1.5e-8) would make the bound looser than the annulus. A
// line across its top 1 + 5e-9 beyond its larger radius is proved apart.
TEST(PlaneDistance, ApartBySideTakesTheAnnulusOfRoundedRadiiHoweverShortTheTurn) {
    const double a0 = kPi / 2 - 1e-6, a1 = kPi / 2 + 1e-6;
    const Parametric arc = pd::arc_element(5.0 * Vec2(std::cos(a0), std::sin(a0)),
                                           (5.0 + 5e-10) * Vec2(std::cos(a1), std::sin(a1)),
                                           {0, 0}, true);
    ASSERT_LT(std::abs(arc.r1 - arc.r0), 1e-9);
    ASSERT_GT(std::abs(arc.r1 - arc.r0), 1e-10);
    const double top = std::max(arc.r0, arc.r1) + 1.0 + 5e-9;
    EXPECT_TRUE(pd::apart_by_side(line({-1.0, top}, {1.0, top}), arc, 1.0));
    EXPECT_FALSE(pd::apart_by_side(line({-1.0, top - 1e-8}, {1.0, top - 1e-8}), arc, 1.0));
}

// A spiral whose radii differ by more than a rounding (1e-7) keeps its radius at the direction
// asked: a quarter turn from radius 5 to 5 + 1e-7 is 5 + 5e-8 at its top, and a line across
// 1 + 2e-8 above that (less than 1 beyond its larger radius) is proved apart.
TEST(PlaneDistance, ApartBySideTakesTheRadiusAtTheDirectionOfASpiralBeyondARounding) {
    const Vec2 u45(std::sqrt(0.5), std::sqrt(0.5)), u135(-std::sqrt(0.5), std::sqrt(0.5));
    const Parametric spiral = pd::arc_element(5.0 * u45, (5.0 + 1e-7) * u135, {0, 0}, true);
    const double top = 5.0 + 5e-8 + 1.0 + 2e-8;
    EXPECT_TRUE(pd::apart_by_side(line({-1.0, top}, {1.0, top}), spiral, 1.0));
    EXPECT_FALSE(pd::apart_by_side(line({-1.0, top - 4e-8}, {1.0, top - 4e-8}), spiral, 1.0));
}

// A spiral of more than half a turn bounds a point's distance by the radial distance less the
// radius's whole change: three quarters of a turn from radius 10 to 10.5; a line leaving it
// radially at 135 degrees (radius 10.25 there) from 0.8 beyond it is not proved apart by 1.
TEST(PlaneDistance, ApartBySideOfASpiralOfMoreThanHalfATurnTakesOffTheWholeChange) {
    const Parametric spiral = pd::arc_element({10, 0}, {0, -10.5}, {0, 0}, true);
    ASSERT_NEAR(spiral.sweep, 1.5 * kPi, 1e-12);
    const Vec2 u(-std::sqrt(0.5), std::sqrt(0.5));
    const Parametric leaving = line(11.05 * u, 16.0 * u);
    EXPECT_LT(brute(sample(spiral, 30000), sample(leaving, 50)), 0.81);  // what it rests on
    EXPECT_FALSE(pd::apart_by_side(spiral, leaving, 1.0));
    // 1.6 beyond it (1.1 once the change is taken off): apart.
    EXPECT_TRUE(pd::apart_by_side(spiral, line(11.85 * u, 16.0 * u), 1.0));
}

// An arc made again from the sweep and start angle arc_element gave (as the check keeps them
// for its stored elements and the wall model for its loops) is the same element bit for bit:
// spirals, near-full arcs, full circles, both senses, radii over six orders of magnitude.
TEST(PlaneDistance, AnArcMadeAgainFromItsTermsIsTheSameBitForBit) {
    std::mt19937_64 rng(27);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int i = 0; i < 2000; ++i) {
        const double scale = std::pow(10.0, 3.0 * unit(rng));
        const Vec2 centre(100 * unit(rng), 100 * unit(rng));
        const double a0 = kPi * unit(rng), a1 = i % 10 == 0 ? a0 : kPi * unit(rng);
        const double r0 = scale * (1.5 + unit(rng)), r1 = r0 * (1.0 + 1e-4 * unit(rng));
        const Vec2 start = centre + r0 * Vec2(std::cos(a0), std::sin(a0));
        const Vec2 end = i % 10 == 0 ? start : Vec2(centre + r1 * Vec2(std::cos(a1), std::sin(a1)));
        for (const bool ccw : {true, false}) {
            const Parametric e = pd::arc_element(start, end, centre, ccw);
            const Parametric again = pd::arc_element(start, end, centre, ccw, e.sweep, e.phi0);
            EXPECT_TRUE(pd::is_arc(again));
            EXPECT_EQ(again.ccw, e.ccw);
            EXPECT_EQ(again.start, e.start);
            EXPECT_EQ(again.end, e.end);
            EXPECT_EQ(again.centre, e.centre);
            // Bit for bit (a -0.0 or another NaN would differ).
            EXPECT_EQ(std::bit_cast<std::uint64_t>(again.r0), std::bit_cast<std::uint64_t>(e.r0))
                << i;
            EXPECT_EQ(std::bit_cast<std::uint64_t>(again.r1), std::bit_cast<std::uint64_t>(e.r1))
                << i;
            EXPECT_EQ(std::bit_cast<std::uint64_t>(again.phi0),
                      std::bit_cast<std::uint64_t>(e.phi0))
                << i;
            EXPECT_EQ(std::bit_cast<std::uint64_t>(again.sweep),
                      std::bit_cast<std::uint64_t>(e.sweep))
                << i;
        }
    }
}

}  // namespace
