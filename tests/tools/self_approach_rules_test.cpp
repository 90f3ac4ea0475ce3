// SPDX-License-Identifier: MIT
// The self-approach check's rules at their edges (tools/runlib/self_approach.h,
// docs/compensation.md "What counts, pair by pair"): the depth rule on contours and paths that
// ramp (helices), not only flat levels; the grid's reach on long elements listed by samples
// whose nearest point falls between samples and across cell boundaries; every tolerance with a
// path between its two thresholds. The check is fed directly, as the run feeds it (elements,
// then their executed paths), with the paths placed where each rule is to be tried: the rule,
// not the compensation, is under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "apci/run/path.h"
#include "apci/run/self_approach.h"
#include "apci/run/self_approach_sink.h"
#include "test_segments.h"

namespace {

using apci::run::PathSegment;
using apci::run::Role;
using apci::run::SegmentKind;
using apci::run::SelfApproachCheck;
using apci::run::SelfApproachFinding;
using Point = apci::run::Point;

constexpr double kTol = SelfApproachCheck::kTolerance;

// The rules' segments: programmed elements (uncompensated) unless a path's role is named.
PathSegment line(int n, const Point& a, const Point& b, Role role = Role::kUncompensated) {
    return test_segments::line(n, a, b, role);
}

PathSegment arc(int n, const Point& a, const Point& b, const Point& centre, bool ccw,
                Role role = Role::kUncompensated) {
    return test_segments::arc(n, a, b, centre, ccw, role);
}

// One compensated stretch as the run feeds it: each element, and after it the executed path
// of the element before (one element of lookahead); at the end the last one's path. `paths[k]`
// are element k's executed segments (their blocks set to the element's).
struct Stretch {
    double r = 1.0;
    std::vector<PathSegment> elements;
    std::vector<std::vector<PathSegment>> paths;
};

// The findings of the stretches fed in turn. Where `kept` is given, it gets check.kept() after
// every call (the window and the entry budget at work).
std::vector<SelfApproachFinding> run(
    const std::vector<Stretch>& stretches,
    SelfApproachCheck::Candidates candidates = SelfApproachCheck::Candidates::kGrid,
    std::size_t window = SelfApproachCheck::kWindow,
    std::size_t budget = SelfApproachCheck::kEntryBudget,
    std::vector<std::size_t>* kept = nullptr) {
    SelfApproachCheck check(window, budget, candidates);
    std::vector<SelfApproachFinding> found;
    const auto step = [&] {
        if (kept != nullptr) kept->push_back(check.kept());
    };
    for (const Stretch& s : stretches) {
        check.begin(s.r, 17, 1);
        for (std::size_t k = 0; k < s.elements.size(); ++k) {
            check.programmed(s.elements[k], found);
            step();
            if (k > 0)
                for (PathSegment p : s.paths[k - 1]) {
                    p.block = s.elements[k - 1].block;
                    check.executed(p, found);
                    step();
                }
        }
        check.end(found);
        for (PathSegment p : s.paths.back()) {
            p.block = s.elements.back().block;
            check.executed(p, found);
            step();
        }
    }
    // A last segment of another block gives the last path block's findings out.
    check.executed(line(999999, Point(1e4, 1e4, 0), Point(1e4 + 1, 1e4, 0)), found);
    return found;
}

std::set<std::pair<std::int64_t, std::int64_t>> pairs(const std::vector<SelfApproachFinding>& f) {
    std::set<std::pair<std::int64_t, std::int64_t>> out;
    for (const auto& x : f) out.emplace(x.path_block.number, x.contour_block.number);
    return out;
}

// An open contour of three elements along the X axis at height y (blocks n, n+1, n+2): the
// middle one, from x0 to x1, is a wall (the first is the stretch's approach, the last ends the
// program's way). Its paths are its own offsets, r above (G41 along +X).
Stretch wall_line(int n, double x0, double x1, double y, double z0, double z1, double r = 1.0) {
    Stretch s;
    s.r = r;
    s.elements = {line(n, {x0 - 5, y, z0}, {x0, y, z0}), line(n + 1, {x0, y, z0}, {x1, y, z1}),
                  line(n + 2, {x1, y, z1}, {x1 + 5, y, z1})};
    s.paths = {{line(n, {x0 - 5, y + r, z0}, {x0, y + r, z0}, Role::kApproach)},
               {line(n + 1, {x0, y + r, z0}, {x1, y + r, z1}, Role::kContour)},
               {line(n + 2, {x1, y + r, z1}, {x1 + 5, y + r, z1}, Role::kContour)}};
    return s;
}

// Another stretch whose middle element's path is the given segment (its element a line
// elsewhere, far from everything but where the path is put).
Stretch probe(int n, const PathSegment& path, double r = 1.0) {
    Stretch s;
    s.r = r;
    const Point far(-500, -500, 0);
    s.elements = {line(n, far, far + Point(1, 0, 0)), line(n + 1, path.start, path.end),
                  line(n + 2, path.end, path.end + Point(0, -50, 0))};
    PathSegment p = path;
    p.role = Role::kContour;
    s.paths = {{line(n, far, far + Point(1, 0, 0), Role::kApproach)}, {p},
               {line(n + 2, path.end + Point(50, 0, 0), path.end + Point(50, -50, 0),
                     Role::kContour)}};
    return s;
}

TEST(SelfApproachRules, TheDepthRuleLeavesOutOnlyAContourWhollyBelowThePathsLowestPoint) {
    // The wall N11 is half a turn of a helix about (10, 0), radius 10, counter-clockwise from
    // (20, 0) at Z 0 over the top down to (0, 0) at Z -10: its highest point 0, its lowest -10.
    // A probe's path 0.5 beyond its top (r = 1), flat at the height z, or ramping.
    Stretch wall;
    wall.elements = {line(10, {25, 0, 0}, {20, 0, 0}),
                     arc(11, {20, 0, 0}, {0, 0, -10}, {10, 0, 0}, true),
                     line(12, {0, 0, -10}, {0, -5, -10})};
    wall.paths = {{line(10, {25, 1, 0}, {19, 0, 0}, Role::kApproach)},
                  {arc(11, {19, 0, 0}, {1, 0, -10}, {10, 0, 0}, true, Role::kContour)},
                  {line(12, {1, 0, -10}, {1, -5, -10}, Role::kContour)}};
    const auto warned = [&](double z_from, double z_to) {
        const Stretch p = probe(20, line(0, {8, 10.5, z_from}, {12, 10.5, z_to}));
        return pairs(run({wall, p})).count({21, 11}) == 1;
    };
    // Below the wall's highest point, even below its lowest: the tool's flank reaches it.
    EXPECT_TRUE(warned(-5, -5));
    EXPECT_TRUE(warned(-20, -20));
    // At its highest point plus the tolerance, less a hair: checked; plus a hair: not.
    EXPECT_TRUE(warned(kTol - 1e-6, kTol - 1e-6));
    EXPECT_FALSE(warned(kTol + 1e-6, kTol + 1e-6));
    EXPECT_FALSE(warned(5, 5));
    // A path that ramps from above down to Z -1: its lowest point decides, not its highest.
    EXPECT_TRUE(warned(5, -1));
    EXPECT_FALSE(warned(5, 1));
    // Below the helix's end but above where it passes under the path (Z -5 at the top): its
    // highest point decides, not the height of its part nearest the path.
    EXPECT_TRUE(warned(-1, -1));
}

TEST(SelfApproachRules, ThresholdsOfOtherElementsAndNeighboursLieOneToleranceApart) {
    const double r = 1.0;
    // Another stretch's wall: r less the tolerance. A probe between that and twice it is warned;
    // just outside the first, not.
    const Stretch wall = wall_line(10, 0, 20, 0, 0, 0, r);
    const auto other = [&](double d) {
        return pairs(run({wall, probe(20, line(0, {5, d, 0}, {15, d, 0}), r)})).count({21, 11});
    };
    EXPECT_EQ(other(r - 1.5 * kTol), 1U);
    EXPECT_EQ(other(r - 0.5 * kTol), 0U);
    EXPECT_EQ(other(r - kTol + 1e-6), 0U);
    EXPECT_EQ(other(r - kTol - 1e-6), 1U);
    // The element after the path's own (same stretch): r less twice the tolerance. A path of
    // N11 placed beside N12 at the same distances: between the thresholds not warned.
    const auto neighbour = [&](double d) {
        Stretch s = wall_line(10, 0, 20, 0, 0, 0, r);
        // N12 runs from (20, 0) to (25, 0); N11's path is put above its middle.
        s.paths[1] = {line(11, {21, d, 0}, {24, d, 0}, Role::kContour)};
        return pairs(run({s})).count({11, 12});
    };
    EXPECT_EQ(neighbour(r - 1.5 * kTol), 0U);
    EXPECT_EQ(neighbour(r - 2.0 * kTol + 1e-6), 0U);
    EXPECT_EQ(neighbour(r - 2.0 * kTol - 1e-6), 1U);
    EXPECT_EQ(neighbour(r - 2.5 * kTol), 1U);
}

TEST(SelfApproachRules, TheDistanceReportedIsTheLeastToTheBillionthOfAMillimetre) {
    // A probe's path at 0.6 above the wall, from x 5 to 15, and slanting down to 0.4 at x 15.
    const Stretch wall = wall_line(10, 0, 20, 0, 0, 0);
    const auto found = run({wall, probe(20, line(0, {5, 0.6, 0}, {15, 0.4, 0}))});
    ASSERT_EQ(pairs(found).count({21, 11}), 1U);
    for (const auto& f : found)
        if (f.path_block.number == 21 && f.contour_block.number == 11) {
            EXPECT_NEAR(f.distance, 0.4, 1e-9);
            EXPECT_NEAR(f.where.x(), 15, 1e-6);
            EXPECT_EQ(f.radius, 1.0);
        }
}

// Between a line path and a line wall the distance and the marker are exact
// (docs/compensation.md, "Self-approach"): 0 where the path crosses the wall, at the crossing;
// along a parallel wall, where many places are as near, at the first of them (here the foot of
// the wall's start), not wherever a search along the path stopped.
TEST(SelfApproachRules, BetweenTwoLinesTheDistanceAndTheMarkerAreExact) {
    const Stretch wall = wall_line(10, 0, 20, 0, 0, 0);
    const auto finding = [&](const PathSegment& path) {
        const auto found = run({wall, probe(20, path)});
        for (const auto& f : found)
            if (f.path_block.number == 21 && f.contour_block.number == 11) return f;
        ADD_FAILURE() << "no finding of N21 against N11";
        return SelfApproachFinding{};
    };
    // Across the wall at three tenths of the path: 0 there.
    const SelfApproachFinding across = finding(line(0, {5, -0.3, 0}, {6, 0.7, 0}));
    EXPECT_EQ(across.distance, 0.0);
    EXPECT_NEAR(across.where.x(), 5.3, 1e-12);
    EXPECT_NEAR(across.where.y(), 0.0, 1e-12);
    // 0.5 beside the whole wall, from x -10 to 30: as near from x 0 to 20; the marker at x 0.
    const SelfApproachFinding beside = finding(line(0, {-10, 0.5, 0}, {30, 0.5, 0}));
    EXPECT_EQ(beside.distance, 0.5);
    EXPECT_EQ(beside.where.x(), 0.0);
    EXPECT_EQ(beside.where.y(), 0.5);
}

// A closed square loop (0, 0)..(10, 10), tool outside (G41 clockwise), entered at the middle
// of its left side (0, 5) by the approach N10 from `from`; N11..N15 its sides from there.
Stretch entered_square(const Point& from, double r) {
    Stretch s;
    s.r = r;
    s.elements = {line(10, from, {0, 5, 0}),         line(11, {0, 5, 0}, {0, 10, 0}),
                  line(12, {0, 10, 0}, {10, 10, 0}), line(13, {10, 10, 0}, {10, 0, 0}),
                  line(14, {10, 0, 0}, {0, 0, 0}),   line(15, {0, 0, 0}, {0, 5, 0})};
    s.paths = {{line(10, from, {-r, 5, 0}, Role::kApproach)},
               {line(11, {-r, 5, 0}, {-r, 10, 0}, Role::kContour)},
               {line(12, {0, 10 + r, 0}, {10, 10 + r, 0}, Role::kContour)},
               {line(13, {10 + r, 10, 0}, {10 + r, 0, 0}, Role::kContour)},
               {line(14, {10, -r, 0}, {0, -r, 0}, Role::kContour)},
               {line(15, {-r, 0, 0}, {-r, 5, 0}, Role::kContour)}};
    return s;
}

TEST(SelfApproachRules, AnApproachIsHeldToItsOwnStretchButNotWhereItStandsNorAtItsEntry) {
    const double r = 1.0;
    // The approach N10 from (-8, 5) to (0, 5) runs straight into the loop's start.
    const auto square = [&](const Point& from) { return entered_square(from, r); };
    // From outside the part: nothing near.
    EXPECT_TRUE(pairs(run({square({-8, 5, 0})})).empty());
    // From the other side, across the part: the approach's centre crosses N13, and passes
    // through the entry point itself, where N11 and N15 meet (the elements at its entry, where
    // only a crossing counts: this is one).
    const auto across = pairs(run({square({12, 5, 0})}));
    EXPECT_EQ(across.count({10, 13}), 1U);
    EXPECT_EQ(across.count({10, 11}), 1U);
    EXPECT_EQ(across.count({10, 15}), 1U);
    // From above the entry point, beside N11's end: it passes N11 within r without crossing
    // it (the entry move's corner cut), not warned.
    const auto beside = pairs(run({square({-0.6, 12, 0})}));
    EXPECT_EQ(beside.count({10, 11}), 0U);
    EXPECT_EQ(beside.count({10, 12}), 1U);  // but it passes N12's start 0.6 away, on its way
    // Standing within r of N13 already (the uncompensated move that brought the tool there put
    // it there): N13 is not held against it, at the threshold's edge.
    EXPECT_EQ(pairs(run({square({10 + r - kTol - 1e-6, 5, 0})})).count({10, 13}), 0U);
    EXPECT_EQ(pairs(run({square({10 + 3 * r, 3, 0})})).count({10, 13}), 1U);
}

TEST(SelfApproachRules, TheEntryCornerRuleHoldsForEveryStretchsElementAtTheEntryPoint) {
    const double r = 1.0;
    // The square of the test above, entered from above beside N11's end: the approach N10 from
    // (-0.6, 12) onto (-1, 5) passes N11 within r without crossing it (the entry move's corner
    // cut). Another stretch (a later pass over the same contour, as a lathe program runs it
    // from both ends) has an element ending at the same entry point: the same corner cut, not
    // warned, whichever stretch comes first. One ending 0.5 short of it is held to r.
    const Stretch square = entered_square({-0.6, 12, 0}, r);
    const Stretch at_entry = probe(20, line(0, {0, 10, 0}, {0, 5, 0}));
    const Stretch short_of = probe(20, line(0, {0, 10, 0}, {0, 5.5, 0}));
    EXPECT_EQ(pairs(run({square, at_entry})).count({10, 21}), 0U);
    EXPECT_EQ(pairs(run({at_entry, square})).count({10, 21}), 0U);
    EXPECT_EQ(pairs(run({square, short_of})).count({10, 21}), 1U);
    EXPECT_EQ(pairs(run({short_of, square})).count({10, 21}), 1U);
}

// An executed arc's sweep as measure() gave it is taken for its shape (not computed again)
// only where its chord exceeds 2e-9 on an axis: there the check's own sweep and measure()'s
// agree (neither takes the arc for a full circle). A sweep that is not the arc's, which no
// executor gives, shows which one the check took. The probe's path is a near-full circle
// whose bottom passes 0.5 above the wall N11 at y = -3: with the chord d on the plane's second
// axis, counter-clockwise about (10, 0), radius 2.5, from (12.5, 0) to d below it (taken as a
// sliver, sweep 1e-9, it stays 3 away); on its first axis, about the origin from its top
// (0, 2.5) to d right of it (x = 0 makes d its chord exactly; a sliver stays 5.5 away).
TEST(SelfApproachRules, AnExecutedArcsMeasuredSweepIsTakenOnlyWhereItsChordExceedsTwiceTheTolerance) {
    const double edge = 2.0 * apci::run::kSamePointTolerance;
    const double past = std::nextafter(edge, 1.0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const bool first_axis : {false, true}) {
        const Stretch wall =
            first_axis ? wall_line(10, -10, 10, -3, 0, 0) : wall_line(10, 0, 20, -3, 0, 0);
        const auto shape = [&](double d) {
            return first_axis ? arc(0, {0, 2.5, 0}, {d, 2.5, 0}, {0, 0, 0}, true)
                              : arc(0, {12.5, 0, 0}, {12.5, -d, 0}, {10, 0, 0}, true);
        };
        const auto warned = [&](double d, double sweep) {
            PathSegment path = shape(d);
            path.sweep = sweep;
            return pairs(run({wall, probe(20, path)})).count({21, 11}) == 1;
        };
        for (const double d : {edge, past}) {
            EXPECT_TRUE(warned(d, nan)) << first_axis << " " << d;  // not measured: made
            // Measured as measure() does: the same either way.
            PathSegment measured = shape(d);
            apci::run::measure(measured);
            EXPECT_GT(measured.sweep, 6.28) << first_axis << " " << d;
            EXPECT_TRUE(warned(d, measured.sweep)) << first_axis << " " << d;
        }
        EXPECT_TRUE(warned(edge, 1e-9)) << first_axis;   // at the edge the check makes its own
        EXPECT_FALSE(warned(past, 1e-9)) << first_axis;  // one step past: the measured one
    }
}

TEST(SelfApproachRules, TheGridFindsAPathJustInsideTheRadiusOfALongElementWhereverItLies) {
    // Long walls (listed in the grid by samples half a cell apart) at random places and
    // headings, each with a probe's short path r - 3 tolerances from a random point of it, in
    // the wall's plane of the same stretch pattern: the grid must find exactly what comparing
    // every pair finds, and every probe. The probes' nearest points fall between samples and
    // across cell boundaries (the cells are 2 r = 2 mm; the walls 40 mm long).
    std::mt19937_64 rng(20261128);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double r = 1.0;
    std::vector<Stretch> stretches;
    int n = 10;
    for (int k = 0; k < 60; ++k) {
        const double a = 2.0 * 3.141592653589793 * u(rng);
        const Point dir(std::cos(a), std::sin(a), 0), left(-std::sin(a), std::cos(a), 0);
        const Point base(200.0 * k + 10.0 * u(rng), 7.3 * u(rng), 0);
        Stretch w;
        w.r = r;
        const Point& p0 = base;
        const Point p1 = base + 40.0 * dir;
        w.elements = {line(n, p0 - 5.0 * dir, p0), line(n + 1, p0, p1),
                      line(n + 2, p1, p1 + 5.0 * dir)};
        w.paths = {{line(n, p0 - 5.0 * dir + r * left, p0 + r * left, Role::kApproach)},
                   {line(n + 1, p0 + r * left, p1 + r * left, Role::kContour)},
                   {line(n + 2, p1 + r * left, p1 + 5.0 * dir + r * left, Role::kContour)}};
        stretches.push_back(w);
        // The probe: a path 0.3 long across the wall's normal, its nearest point r - 3 tol
        // to the wall's right (the side away from the wall's own path).
        const Point at = p0 + (2.0 + 36.0 * u(rng)) * dir - (r - 3 * kTol) * left;
        stretches.push_back(probe(n + 3, line(0, at, at - 0.3 * left), r));
        n += 10;
    }
    const auto grid = pairs(run(stretches));
    const auto all = pairs(run(stretches, SelfApproachCheck::Candidates::kAll));
    EXPECT_EQ(grid, all);
    for (int k = 0; k < 60; ++k) EXPECT_EQ(grid.count({10 * k + 14, 10 * k + 11}), 1U) << k;
}

// The unit normal to the left of a direction in the X-Y plane (G41's side).
Point left_of(const Point& d) {
    return Point(-d.y(), d.x(), 0);
}

// The grid's reach at its edge, in the two ways the grid looks: cells of 2 mm (r = 1, set by the
// first stretch), an element listed by samples 1 mm apart along it (half a cell). Each point of
// it is within a quarter cell of a sample, so a lookup reaches r and a quarter cell beyond the
// box of what it looks up. Built so that a reach of r alone misses: the element's nearest point
// to the path lies midway between two samples, and both lie in cells beyond r of the path.
TEST(SelfApproachRules, AShortPathFindsALongWallWhoseSamplesLieBeyondRadiusOfIt) {
    const Point dir = Point(1, -1, 0).normalized();
    const Point q(3.7, 3.7, 0);          // the wall's point nearest the path
    const Point a(2.999, 2.999, 0);      // the path: 0.9913 from the wall's line x + y = 7.4
    Stretch wall;
    const Point s0 = q - 10.5 * dir, s1 = q + 10.5 * dir;  // 21 long: samples 1 apart
    wall.elements = {line(10, s0 - Point(0.5, 0, 0), s0), line(11, s0, s1),
                     line(12, s1, s1 + Point(0.5, 0, 0))};
    wall.paths = {{line(10, s0 - Point(0.5, 0, 0), s0, Role::kApproach)},
                  {line(11, s0 + left_of(dir), s1 + left_of(dir), Role::kContour)},
                  {line(12, s1 + Point(0, 1, 0), s1 + Point(0.5, 1, 0), Role::kContour)}};
    const auto found = pairs(run({wall, probe(20, line(0, a, a - Point(1e-3, 1e-3, 0)))}));
    EXPECT_EQ(found.count({21, 11}), 1U);
}

TEST(SelfApproachRules, ALongPathFindsAShortWallBeyondRadiusOfItsSamples) {
    // The mirror: the path is long (looked up sample by sample, 1 apart), the wall short (listed
    // in the one cell of its box, (0, 0)); the wall's point 0.9913 from the path's line, the
    // path's samples either side of its nearest point 1.06 from the wall in each axis. No
    // element is long but the path, so nothing is listed by samples.
    const Point dir = Point(1, -1, 0).normalized();
    const Point q(2.7, 2.7, 0), a(1.999, 1.999, 0);
    // The wall runs towards the path's line and ends at a, all of it (and its neighbours) in
    // the cell (0, 0).
    const Point b = a - 0.3 * Point(1, 1, 0).normalized();
    Stretch wall;
    wall.elements = {line(10, b + Point(-0.3, 0.1, 0), b), line(11, b, a),
                     line(12, a, a + Point(0, -0.5, 0))};
    wall.paths = {{line(10, b + Point(-0.3, 0.1, 0), b, Role::kApproach)},
                  {line(11, b + Point(-0.5, 0.5, 0), a + Point(-0.5, 0.5, 0), Role::kContour)},
                  {line(12, a + Point(-1, 0, 0), a + Point(-1, -0.5, 0), Role::kContour)}};
    // The probe's element is short and far; its executed path is the long line through q.
    Stretch p;
    const Point far(-50, -50, 0);
    p.elements = {line(20, far, far + Point(0.5, 0, 0)), line(21, far + Point(0.5, 0, 0),
                                                             far + Point(1, 0, 0)),
                  line(22, far + Point(1, 0, 0), far + Point(1.5, 0, 0))};
    p.paths = {{line(20, far, far + Point(0.5, 0, 0), Role::kApproach)},
               {line(21, q - 10.5 * dir, q + 10.5 * dir, Role::kContour)},
               {line(22, far + Point(1, 0, 0), far + Point(1.5, 0, 0), Role::kContour)}};
    EXPECT_EQ(pairs(run({wall, p})).count({21, 11}), 1U);
}

TEST(SelfApproachRules, TheElementBeforeThePathsIsANeighbourAndTheOneBeforeThatIsNot) {
    // An open contour along y = 0: the approach N10, N11 from x 0 to 20, N12 and N13 going on
    // to 25 and 30. The path of N12 (the element after N11: N11 is the element before its own)
    // or of N13 (two after) is put above N11's middle, at d. The element before is held to r
    // less twice the tolerance, the one before that to r less once.
    const double r = 1.0;
    const auto near_n11 = [&](int path_block, double d) {
        Stretch s;
        s.r = r;
        s.elements = {line(10, {-5, 0, 0}, {0, 0, 0}), line(11, {0, 0, 0}, {20, 0, 0}),
                      line(12, {20, 0, 0}, {25, 0, 0}), line(13, {25, 0, 0}, {30, 0, 0})};
        s.paths = {{line(10, {-5, r, 0}, {0, r, 0}, Role::kApproach)},
                   {line(11, {0, r, 0}, {20, r, 0}, Role::kContour)},
                   {line(12, {20, r, 0}, {25, r, 0}, Role::kContour)},
                   {line(13, {25, r, 0}, {30, r, 0}, Role::kContour)}};
        s.paths[static_cast<std::size_t>(path_block - 10)] = {
            line(path_block, {5, d, 0}, {15, d, 0}, Role::kContour)};
        return pairs(run({s})).count({path_block, 11});
    };
    EXPECT_EQ(near_n11(12, r - 1.5 * kTol), 0U);
    EXPECT_EQ(near_n11(12, r - 2.0 * kTol + 1e-6), 0U);
    EXPECT_EQ(near_n11(12, r - 2.0 * kTol - 1e-6), 1U);
    EXPECT_EQ(near_n11(13, r - 0.5 * kTol), 0U);
    EXPECT_EQ(near_n11(13, r - kTol + 1e-6), 0U);
    EXPECT_EQ(near_n11(13, r - kTol - 1e-6), 1U);
    EXPECT_EQ(near_n11(13, r - 1.5 * kTol), 1U);
}

TEST(SelfApproachRules, APairIsReportedWithTheLeastDistanceOfAllItsPathBlocksSegments) {
    // The path of N13 in two segments (its contour part and the transition at its end), 0.6 and
    // 0.4 above N11, in either order. Once N11 is the stretch's last element (its findings held
    // until it is known not to be the departure); once an element in the middle (its findings
    // wait for the wall model until the stretch ends, when N13's segments are all done).
    const auto least = [](bool last, bool nearer_first) {
        Stretch s;
        const Point far(-50, -50, 0);
        if (last) {
            // N13 not the element before N11 (a transition is held to that one only where it
            // is an arc of more than half a turn).
            s.elements = {line(10, far, far + Point(1, 0, 0)),
                          line(13, far + Point(1, 0, 0), far + Point(2, 0, 0)),
                          line(12, far + Point(2, 0, 0), {0, 0, 0}),
                          line(11, {0, 0, 0}, {20, 0, 0})};
        } else {
            s.elements = {
                line(10, {-5, 0, 0}, {0, 0, 0}),      line(11, {0, 0, 0}, {20, 0, 0}),
                line(12, {20, 0, 0}, {20, -10, 0}),   line(13, {20, -10, 0}, {30, -10, 0}),
                line(14, {30, -10, 0}, {40, -10, 0}), line(15, {40, -10, 0}, {50, -10, 0})};
        }
        for (const PathSegment& e : s.elements) {
            const Point d = (e.end - e.start).normalized();
            s.paths.push_back({line(static_cast<int>(e.block.number), e.start + left_of(d),
                                    e.end + left_of(d), Role::kContour)});
        }
        s.paths.front().front().role = Role::kApproach;
        std::vector<PathSegment> n13 = {line(13, {5, 0.6, 0}, {10, 0.6, 0}, Role::kContour),
                                        line(13, {10, 0.4, 0}, {15, 0.4, 0}, Role::kTransition)};
        if (nearer_first) std::swap(n13[0], n13[1]);
        for (std::size_t k = 0; k < s.elements.size(); ++k)
            if (s.elements[k].block.number == 13) s.paths[k] = n13;
        double distance = -1.0;
        int count = 0;
        for (const auto& f : run({s}))
            if (f.path_block.number == 13 && f.contour_block.number == 11) {
                distance = f.distance;
                ++count;
            }
        EXPECT_EQ(count, 1) << last << nearer_first;
        return distance;
    };
    for (const bool last : {true, false})
        for (const bool nearer_first : {true, false})
            EXPECT_NEAR(least(last, nearer_first), 0.4, 1e-9) << last << nearer_first;
}

TEST(SelfApproachRules, StoredBoxesRoundOutwardFarFromTheOrigin) {
    // The grid keeps each element's box in floats rounded outward. 1000 mm from the origin a
    // float's step is 6.1e-5 mm, over half the path tolerance: a box rounded the wrong way would
    // keep a path 1.2 tolerances inside r of a wall from being measured. The wall runs along
    // y = Y at a Y a float cannot hold: 1000.7 (its nearest float is above it: the box's low side
    // must step down) with the probe below it, 1000.3 (the nearest float below: the high side
    // must step up) with the probe above.
    const double r = 1.0, d = r - 1.2 * kTol;
    for (const double y : {1000.7, 1000.3}) {
        const bool float_above = static_cast<double>(static_cast<float>(y)) > y;
        ASSERT_EQ(float_above, y > 1000.5) << y;
        const double py = float_above ? y - d : y + d;
        const Stretch wall = wall_line(10, 1000, 1020, y, 0, 0, r);
        const auto found = run({wall, probe(20, line(0, {1005, py, 0}, {1015, py, 0}), r)});
        EXPECT_EQ(pairs(found).count({21, 11}), 1U) << y;
    }
}

TEST(SelfApproachRules, TheGridReachesTheEndsOfLongElements) {
    // Cells of 2 mm (r = 1); a long element is listed (or looked up) by samples 1 mm apart, its
    // end the last of them. Each case is built so that the sample before the end lies in a
    // column of cells beyond the reach of what is near the end.
    const double r = 1.0, d = r - 3 * kTol;
    {
        // A long path along y = 0.3 (20 mm, from x -10.7 to 9.3) whose end comes d from a short
        // wall N11 at x = 9.3 + d (the cell column from x 10), running down from y 0.5 to 0.1.
        // The probe's elements are short and far, so that nothing is listed by samples.
        const double x = 9.3 + d;
        Stretch wall;
        wall.elements = {line(10, {x, 5.5, 0}, {x, 0.5, 0}), line(11, {x, 0.5, 0}, {x, 0.1, 0}),
                         line(12, {x, 0.1, 0}, {x, -5, 0})};
        wall.paths = {{line(10, {x + r, 5.5, 0}, {x + r, 0.5, 0}, Role::kApproach)},
                      {line(11, {x + r, 0.5, 0}, {x + r, 0.1, 0}, Role::kContour)},
                      {line(12, {x + r, 0.1, 0}, {x + r, -5, 0}, Role::kContour)}};
        Stretch p;
        const Point far(-50, -50, 0);
        p.elements = {line(20, far, far + Point(0.5, 0, 0)),
                      line(21, far + Point(0.5, 0, 0), far + Point(1, 0, 0)),
                      line(22, far + Point(1, 0, 0), far + Point(1.5, 0, 0))};
        p.paths = {{line(20, far, far + Point(0.5, 0, 0), Role::kApproach)},
                   {line(21, {-10.7, 0.3, 0}, {9.3, 0.3, 0}, Role::kContour)},
                   {line(22, far + Point(1, 0, 0), far + Point(1.5, 0, 0), Role::kContour)}};
        EXPECT_EQ(pairs(run({wall, p})).count({21, 11}), 1U);
    }
    {
        // A long wall N11 along y = 0.3 (20 mm, to x 10.7), N12 turning down from its end; a
        // probe's short path d beyond N11's end, across its line (the cell column from x 10).
        const Stretch wall = [&] {
            Stretch s;
            s.elements = {line(10, {-14.3, 0.3, 0}, {-9.3, 0.3, 0}),
                          line(11, {-9.3, 0.3, 0}, {10.7, 0.3, 0}),
                          line(12, {10.7, 0.3, 0}, {10.7, -5, 0})};
            s.paths = {{line(10, {-14.3, 1.3, 0}, {-9.3, 1.3, 0}, Role::kApproach)},
                       {line(11, {-9.3, 1.3, 0}, {10.7, 1.3, 0}, Role::kContour)},
                       {line(12, {11.7, 0.3, 0}, {11.7, -5, 0}, Role::kContour)}};
            return s;
        }();
        const double x = 10.7 + d;
        EXPECT_EQ(pairs(run({wall, probe(20, line(0, {x, 0.5, 0}, {x, 0.1, 0}))})).count({21, 11}),
                  1U);
    }
}

// A lookup by the box of what is looked up, where that is more than a few cells: the path
// of AShortPathFindsALongWallWhoseSamplesLieBeyondRadiusOfIt made long, leading away from the
// wall (its box nine cells, in reach of r sixteen).
TEST(SelfApproachRules, ALongPathFindsALongWallWhoseSamplesLieBeyondRadiusOfItsEnd) {
    const Point dir = Point(1, -1, 0).normalized();
    const Point q(3.7, 3.7, 0);
    const Point a(2.999, 2.999, 0);
    Stretch wall;
    const Point s0 = q - 10.5 * dir, s1 = q + 10.5 * dir;
    wall.elements = {line(10, s0 - Point(0.5, 0, 0), s0), line(11, s0, s1),
                     line(12, s1, s1 + Point(0.5, 0, 0))};
    wall.paths = {{line(10, s0 - Point(0.5, 0, 0), s0, Role::kApproach)},
                  {line(11, s0 + left_of(dir), s1 + left_of(dir), Role::kContour)},
                  {line(12, s1 + Point(0, 1, 0), s1 + Point(0.5, 1, 0), Role::kContour)}};
    const auto found = pairs(run({wall, probe(20, line(0, {-1.5, -1.5, 0}, a))}));
    EXPECT_EQ(found.count({21, 11}), 1U);
}

// The window: with `window` W, the check keeps at least the W latest distinct elements. The run
// programs an element before it executes the path of the one before (one element of
// lookahead), so a path is compared with at least the W - 2 elements before its own, wherever
// the letting go falls; much farther back, not.
TEST(SelfApproachRules, APathIsComparedWithTheWindowOfElementsProgrammedBeforeIt) {
    const auto found = [](std::size_t window, int before, int k) {
        SelfApproachCheck check(window);
        std::vector<SelfApproachFinding> out;
        std::vector<PathSegment> elements, paths;
        int n = 1;
        double x = 0.0;
        // Short lines 10 apart along y = 0, each with its offset for path.
        const auto filler = [&] {
            elements.push_back(line(n, {x, 0, 0}, {x + 1, 0, 0}));
            paths.push_back(line(n, {x, 1, 0}, {x + 1, 1, 0}, Role::kContour));
            ++n;
            x += 10.0;
        };
        for (int i = 0; i < before; ++i) filler();
        // A along y = 100; B, k elements later, far away but for its path, 0.5 below A.
        const int a = n;
        elements.push_back(line(n, {0, 100, 0}, {1, 100, 0}));
        paths.push_back(line(n, {0, 101, 0}, {1, 101, 0}, Role::kContour));
        ++n;
        for (int i = 0; i < k - 1; ++i) filler();
        const int b = n;
        elements.push_back(line(n, {x, 0, 0}, {x + 1, 0, 0}));
        paths.push_back(line(n, {0, 99.5, 0}, {1, 99.5, 0}, Role::kContour));
        ++n;
        x += 10.0;
        for (int i = 0; i < 3; ++i) filler();
        paths.front().role = Role::kApproach;
        check.begin(1.0, 17, 1);
        for (std::size_t i = 0; i < elements.size(); ++i) {
            check.programmed(elements[i], out);
            if (i > 0) check.executed(paths[i - 1], out);
        }
        check.end(out);
        check.executed(paths.back(), out);
        check.executed(line(999999, {1e4, 1e4, 0}, {1e4 + 1, 1e4, 0}), out);
        return pairs(out).count({b, a}) == 1;
    };
    for (const std::size_t w : {4U, 5U, 8U}) {
        const int k = static_cast<int>(w) - 2;
        int missed_far = 0;
        for (int before = 1; before < 4 * static_cast<int>(w); ++before) {
            EXPECT_TRUE(found(w, before, k)) << "window " << w << ", " << before << " before";
            missed_far += !found(w, before, static_cast<int>(w) + 1);
        }
        EXPECT_GT(missed_far, 0) << "window " << w;
    }
}

}  // namespace

namespace {

// An element is checked once per geometry: the check keeps it under a 64-bit key of its numbers.
// Distinct elements must get distinct keys, also where their numbers differ in a few bits only:
// a zigzag of teeth 0.5 mm long, written with 4 decimals (a key that only multiplied after each
// xor took the 30,307th and the 25,491st of these for one, and left the later one unchecked).
TEST(SelfApproachRules, DistinctElementsAreEachKept) {
    SelfApproachCheck check;
    std::vector<SelfApproachFinding> found;
    check.begin(0.5, 17, 1);
    constexpr int kElements = 32768;
    const auto y_of = [](int k) {
        return std::round(((k % 2) * 0.5 + (k % 7) * 0.001) / 2.0 * 1e4) / 1e4;
    };
    Point from(0.5, 0.0, 0.0);
    for (int k = 0; k < kElements; ++k) {
        const Point to(1.0 + 0.5 * k, y_of(k), 0.0);
        check.programmed(line(k + 1, from, to, Role::kContour), found);
        from = to;
    }
    EXPECT_EQ(check.kept(), static_cast<std::size_t>(kElements));
    // The same geometry again is kept once.
    check.programmed(line(kElements + 1, Point(0.5, 0.0, 0.0), Point(1.0, y_of(0), 0.0),
                          Role::kContour),
                     found);
    EXPECT_EQ(check.kept(), static_cast<std::size_t>(kElements));
}


// A loop whose arc was programmed before (an element the grid has, its shape not made again)
// is known by that arc's own terms: the pocket pass N11-N13 (the upper half circle of radius 5
// and back under it by (0, 1), the tool inside) has the area of the half disc less the
// triangle, a pocket's sense like the larger pass N31 round it (a full circle of radius 10),
// which clears it: a path 0.5 from N13 is no finding. Without the larger pass N13 is a wall.
// (Taken with no sweep, N11 would leave only the triangle under its chord, turning the other
// way: a boss, which no pocket pass clears.)
TEST(SelfApproachRules, ALoopThroughAnArcProgrammedBeforeTakesThatArcsTerms) {
    const Point o(0, 0, 0);
    const PathSegment half = arc(0, {5, 0, 0}, {-5, 0, 0}, o, true);
    const auto with_block = [](PathSegment s, int n, Role role) {
        s.block.number = n;
        s.role = role;
        return s;
    };
    Stretch first;  // the half circle alone, an open contour
    first.elements = {with_block(half, 1, Role::kUncompensated)};
    first.paths = {{arc(1, {4, 0, 0}, {-4, 0, 0}, o, true, Role::kContour)}};
    Stretch inner;  // the pocket pass through it
    inner.elements = {with_block(half, 11, Role::kUncompensated), line(12, {-5, 0, 0}, {0, 1, 0}),
                      line(13, {0, 1, 0}, {5, 0, 0})};
    inner.paths = {{arc(11, {4, 0.2, 0}, {-4, 0.2, 0}, o, true, Role::kContour)},
                   {line(12, {-4, 0.2, 0}, {0, 1.98, 0}, Role::kContour)},
                   {line(13, {0, 1.98, 0}, {4, 0.2, 0}, Role::kContour)}};
    Stretch outer;  // the larger pocket pass
    outer.elements = {arc(31, {10, 0, 0}, {10, 0, 0}, o, true)};
    outer.paths = {{arc(31, {9, 0, 0}, {9, 0, 0}, o, true, Role::kContour)}};
    // 0.5 under N13 (along its normal), from 1 to 4 on X.
    const Point n = Point(-1, -5, 0).normalized();
    const Stretch near =
        probe(20, line(0, Point(1, 0.8, 0) + 0.5 * n, Point(4, 0.2, 0) + 0.5 * n));
    EXPECT_EQ(pairs(run({first, inner, near})).count({21, 13}), 1u);  // a wall
    EXPECT_EQ(pairs(run({first, inner, outer, near})).count({21, 13}), 0u);  // cleared
}

// The check as a sink (self_approach_sink.h), fed as the run feeds it: an open contour (no loop,
// so its elements' roles are known only when its stretch ends) whose N13 comes back within the
// tool's radius of N11. What the stretch's end gives out reaches the next sink there, before
// anything after it, and the outcome; with kError the first finding is the stop, handed once.
// The findings of two runs, the same in every field and in the same order (distances and
// places to the bit).
void expect_identical(const std::vector<SelfApproachFinding>& a,
                      const std::vector<SelfApproachFinding>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(a[i].path_block.number, b[i].path_block.number);
        EXPECT_EQ(a[i].contour_block.number, b[i].contour_block.number);
        EXPECT_EQ(a[i].distance, b[i].distance);
        EXPECT_EQ(a[i].radius, b[i].radius);
        EXPECT_EQ(a[i].where, b[i].where);
    }
}

// A closed polygon of `k` corners round (cx, cy) (each corner at radius rad, jittered), as a
// stretch: its sides (the first one's path the approach), each side's path a line beside it
// outside (to the right), 1.1 r away, or one time in ten a random 0.3 r to 1.1 r (not a true
// offset: such a path comes near the sides before and after, and other sides where the polygon is
// narrow).
Stretch polygon(int& n, double cx, double cy, double rad, int k, double r, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Point> corner;
    for (int i = 0; i < k; ++i) {
        const double a = 2.0 * 3.141592653589793 * (i + 0.4 * u(rng)) / k;
        const double q = rad * (0.7 + 0.6 * u(rng));
        corner.emplace_back(cx + q * std::cos(a), cy + q * std::sin(a), 0);
    }
    Stretch s;
    s.r = r;
    for (int i = 0; i < k; ++i) {
        const Point a = corner[static_cast<std::size_t>(i)];
        const Point b = corner[static_cast<std::size_t>((i + 1) % k)];
        s.elements.push_back(line(n, a, b));
        const double d = u(rng) < 0.1 ? 0.3 + 0.8 * u(rng) : 1.1;
        const Point off = -d * r * left_of((b - a).normalized());
        s.paths.push_back({line(n, a + off, b + off, i == 0 ? Role::kApproach : Role::kContour)});
        ++n;
    }
    return s;
}

TEST(SelfApproachRules, StretchesKeptOutOfTheCellsFindWhatEveryStretchInTheCellsFinds) {
    // The grid keeps a stretch out of its cells while no other stretch comes near it, and takes
    // its own items in turn (self_approach.cpp, Grid::Area): what the check asks, in what order,
    // and so what it finds, must be what it finds with every stretch in the cells. Polygons small
    // and large (sides listed by samples), most placed apart, others beside one placed before (a
    // stretch that was apart, its items taken into the cells then), a larger tool in between
    // (every stretch so far into the cells), walls with another stretch's path just under r
    // below them (found only if the wall is taken into the cells), and one long stretch of close
    // teeth whose pairs wait for the wall model by the thousand (its bounded queue fills,
    // kMaxDeferred).
    for (const std::uint64_t seed : {1u, 2u}) {
        SCOPED_TRACE(seed);
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        std::vector<Stretch> stretches;
        std::vector<Point> centres;
        std::vector<double> radii;
        int n = 10;
        for (int k = 0; k < 240; ++k) {
            const double rad = u(rng) < 0.2 ? 10.0 + 30.0 * u(rng) : 1.5 + 6.0 * u(rng);
            const int column = k % 16, row = k / 16;
            Point c(200.0 * column + 40.0 * u(rng), 200.0 * row + 40.0 * u(rng), 0);
            if (!centres.empty() && u(rng) < 0.3) {  // beside one before, within a few r
                const auto at =
                    static_cast<std::size_t>(u(rng) * static_cast<double>(centres.size()));
                const double a = 6.283185307179586 * u(rng);
                c = centres[at] +
                    (1.3 * (radii[at] + rad) + 3.0 * u(rng)) * Point(std::cos(a), std::sin(a), 0);
            }
            const double r = k == 120 ? 2.0 : 1.0;
            centres.push_back(c);
            radii.push_back(rad);
            stretches.push_back(
                polygon(n, c.x(), c.y(), rad, 3 + static_cast<int>(6 * u(rng)), r, rng));
            n += 10;
        }
        // Walls with another wall's path just below them, g under r away (the two stretches'
        // boxes g apart: the lower one comes near the upper one, which was apart until then).
        for (int k = 0; k < 20; ++k) {
            const double x0 = 4000.0 + 200.0 * k, y = 100.0 * u(rng), g = 0.01 + 0.9 * u(rng);
            stretches.push_back(wall_line(n, x0, x0 + 20.0 + 30.0 * u(rng), y, 0, 0));
            stretches.push_back(wall_line(n + 10, x0 + 5.0 * u(rng), x0 + 30.0, y - 1.0 - g, 0, 0));
            n += 20;
        }
        // The teeth (the first seed): 900 sides 0.4 apart along X, the paths 0.3 to 1.4 r
        // beside them, all in one open stretch (none placed until it ends): some 9,000 pairs
        // come near while it is open, more than twice the queue's bound.
        const int kTeeth = seed == 1 ? 900 : 1;
        Stretch teeth;
        teeth.r = 1.0;
        for (int i = 0; i < kTeeth; ++i) {
            const Point a(9000.0 + 0.4 * i, (i % 2) * 0.8, 0);
            const Point b(9000.4 + 0.4 * i, ((i + 1) % 2) * 0.8, 0);
            teeth.elements.push_back(line(n, a, b));
            const Point off = (0.3 + 1.1 * u(rng)) * left_of((b - a).normalized());
            teeth.paths.push_back(
                {line(n, a + off, b + off, i == 0 ? Role::kApproach : Role::kContour)});
            ++n;
        }
        stretches.push_back(teeth);
        const auto kept_out = run(stretches);
        const auto in_cells = run(stretches, SelfApproachCheck::Candidates::kIndexed);
        EXPECT_GT(kept_out.size(), 100u);  // not a comparison of empty lists
        expect_identical(kept_out, in_cells);
    }
}

// A stretch that no other comes near takes its own items in turn (Grid::Area), and gives for a
// long path of its own exactly what the cells would: the cells within a quarter cell more than
// r of each of the path's samples. Where no element is listed by samples, the reach of r alone
// misses: the geometry of ALongPathFindsAShortWallBeyondRadiusOfItsSamples, the wall and the
// long path's element in one stretch (all its elements short, in the cell (0, 0)).
TEST(SelfApproachRules, AStretchKeptOutFindsItsOwnShortWallBeyondRadiusOfItsLongPathsSamples) {
    const Point dir = Point(1, -1, 0).normalized();
    const Point q(2.7, 2.7, 0), a(1.999, 1.999, 0);  // a: 0.9913 from the path's line
    const Point b = a - 0.3 * Point(1, 1, 0).normalized();
    const Point c = a + Point(0, -0.5, 0), d = a + Point(-0.5, -0.5, 0);
    const Point e = a + Point(-0.5, -1.0, 0), f = a + Point(-1.0, -1.0, 0);
    const Point g = a + Point(-1.5, -1.0, 0);
    const Point away(-0.7, -0.7, 0);  // the short paths, beside their elements away from it
    Stretch s;
    s.elements = {line(10, b + Point(-0.3, 0.1, 0), b),
                  line(11, b, a),
                  line(12, a, c),
                  line(13, c, d),
                  line(14, d, e),
                  line(15, e, f),
                  line(16, f, g)};
    s.paths = {{line(10, b + Point(-0.3, 0.1, 0), b, Role::kApproach)},
               {line(11, b + Point(-0.5, 0.5, 0), a + Point(-0.5, 0.5, 0), Role::kContour)},
               {line(12, a + away, c + away, Role::kContour)},
               {line(13, c + away, d + away, Role::kContour)},
               {line(14, d + away, e + away, Role::kContour)},
               {line(15, q - 10.5 * dir, q + 10.5 * dir, Role::kContour)},
               {line(16, f + away, g + away, Role::kContour)}};
    const auto kept_out = run({s});
    const auto in_cells = run({s}, SelfApproachCheck::Candidates::kIndexed);
    EXPECT_EQ(pairs(in_cells).count({15, 11}), 1U);
    expect_identical(kept_out, in_cells);
}

// Teeth 0.4 r apart along X, 0.8 r high, every sixth element a run of 8 r (listed by samples),
// as one stretch; the paths 0.3 r to 1.4 r beside them (they come near the elements two and
// more before).
Stretch teeth(int& n, double x0, double y0, int count, double r, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Stretch s;
    s.r = r;
    Point a(x0, y0, 0);
    for (int i = 0; i < count; ++i) {
        const Point b = i % 6 == 5 ? a + Point(8.0 * r, 0, 0)
                                   : Point(a.x() + 0.4 * r, y0 + ((i + 1) % 2) * 0.8 * r, 0);
        s.elements.push_back(line(n, a, b));
        const Point off = (0.3 + 1.1 * u(rng)) * r * left_of((b - a).normalized());
        s.paths.push_back({line(n, a + off, b + off, i == 0 ? Role::kApproach : Role::kContour)});
        a = b;
        ++n;
    }
    return s;
}

// The window and the entry budget let the oldest items go all the time (a window of 12
// elements, and 48 entries, or 16, where the entries bind before the window): a stretch kept
// out of the cells keeps what the grid with every stretch in its cells keeps, after every call,
// and finds what it finds. Its items are counted though they are in no cell, its area outlives
// a let-go that leaves it items in one list only (a stretch just begun has no path yet), and
// each stretch's items stay its own.
TEST(SelfApproachRules, StretchesKeptOutOfTheCellsKeepAndFindWhatTheCellsDoWhereTheBudgetBinds) {
    for (const auto& [seed, budget] :
         {std::pair<std::uint64_t, std::size_t>{1u, 48}, {2u, 48}, {3u, 16}, {4u, 16}}) {
        SCOPED_TRACE(seed);
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        std::vector<Stretch> stretches;
        int n = 10;
        for (int k = 0; k < 25; ++k) {
            const int column = k % 8, row = k / 8;  // 8 stretches a row
            const double x0 = 300.0 * column + 20.0 * u(rng), y0 = 300.0 * row + 20.0 * u(rng);
            stretches.push_back(teeth(n, x0, y0, 4 + static_cast<int>(30 * u(rng)), 1.0, rng));
            n += 10;
        }
        std::vector<std::size_t> kept_out_kept, in_cells_kept;
        const auto kept_out =
            run(stretches, SelfApproachCheck::Candidates::kGrid, 12, budget, &kept_out_kept);
        const auto in_cells =
            run(stretches, SelfApproachCheck::Candidates::kIndexed, 12, budget, &in_cells_kept);
        EXPECT_GT(kept_out.size(), 10u);  // not a comparison of empty lists
        expect_identical(kept_out, in_cells);
        EXPECT_EQ(kept_out_kept, in_cells_kept);
        // The budget binds: far fewer items are kept than were fed.
        ASSERT_FALSE(kept_out_kept.empty());
        EXPECT_LT(*std::max_element(kept_out_kept.begin(), kept_out_kept.end()), 150u);
    }
}

TEST(SelfApproachSink, WhatAStretchsEndGivesOutGoesOnThere) {
    using apci::run::SelfApproachMode;
    using apci::run::SelfApproachSink;
    struct Calls final : apci::run::RunSink {
        std::vector<std::string> calls;
        void executed(const PathSegment& s) override {
            calls.push_back("e" + std::to_string(s.block.number));
        }
        void stretch_end() override { calls.emplace_back("end"); }
        void warning(const apci::run::RunError& w, const Point&) override {
            calls.push_back("warning " + std::to_string(w.block.number));
        }
    };
    // The elements and their paths, one element behind (r = 1, the tool on the left).
    const std::vector<PathSegment> elements{
        line(10, {-5, 0, 0}, {0, 0, 0}), line(11, {0, 0, 0}, {20, 0, 0}),
        line(12, {20, 0, 0}, {20, 1.5, 0}), line(13, {20, 1.5, 0}, {0, 1.5, 0}),
        line(14, {0, 1.5, 0}, {0, 30, 0})};
    const std::vector<PathSegment> paths{
        line(10, {-5, 1, 0}, {0, 1, 0}, Role::kApproach),
        line(11, {0, 1, 0}, {19, 1, 0}, Role::kContour),
        line(12, {19, 1, 0}, {19, 0.5, 0}, Role::kContour),
        line(13, {19, 0.5, 0}, {-1, 0.5, 0}, Role::kContour),
        line(14, {-1, 0.5, 0}, {-1, 30, 0}, Role::kContour)};
    const auto feed = [&](SelfApproachSink& sink) {
        sink.stretch_begin(apci::run::CompensatedStretch{1.0, 17, 1, Eigen::Vector2d::Zero()});
        for (std::size_t k = 0; k < elements.size(); ++k) {
            sink.programmed(elements[k]);
            if (k > 0) sink.executed(paths[k - 1]);
        }
        sink.executed(paths.back());
        sink.stretch_end();
    };
    const std::vector<std::string> before{"e10", "e11", "e12", "e13", "e14", "end"};
    Calls next;
    SelfApproachSink warn(next, SelfApproachMode::kWarn);
    feed(warn);
    ASSERT_GT(next.calls.size(), before.size());
    const auto first = static_cast<std::ptrdiff_t>(before.size());
    EXPECT_EQ(std::vector<std::string>(next.calls.begin(), next.calls.begin() + first), before);
    for (std::size_t i = before.size(); i < next.calls.size(); ++i)
        EXPECT_EQ(next.calls[i].rfind("warning ", 0), 0u) << next.calls[i];
    EXPECT_NE(std::find(next.calls.begin(), next.calls.end(), "warning 13"), next.calls.end());
    EXPECT_EQ(next.calls[before.size()], "warning 10");
    apci::run::RunOutcome out;
    warn.results(out);
    EXPECT_EQ(out.warnings.size(), next.calls.size() - before.size());
    EXPECT_EQ(out.self_approach.size(), out.warnings.size());
    Calls quiet;
    SelfApproachSink error(quiet, SelfApproachMode::kError);
    feed(error);
    EXPECT_EQ(quiet.calls, before);
    const auto stop = error.take_stop();
    ASSERT_TRUE(stop.has_value());
    EXPECT_EQ(stop->code, "SelfApproach");
    EXPECT_EQ(stop->block.number, 10);
    EXPECT_FALSE(error.take_stop().has_value());
}

}  // namespace
