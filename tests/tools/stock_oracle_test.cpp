// SPDX-License-Identifier: MIT
// The stock-removal oracle of the gouge tests (tests/support/stock_oracle.h): hand-computed
// cases (a line passing a square at a known distance, an arc, a lead crossing the part, a path
// exactly r away, the path tolerance at its edge, a plunge into the part, segments above the
// top), the design part's rules, and agreement with brute-force point sampling on random parts
// and paths.
#include "stock_oracle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include "rng.h"

namespace apci::test {
namespace {

using run::BlockRef;
using run::PathSegment;
using run::SegmentKind;

constexpr double kPi = std::numbers::pi;

BlockRef line_ref(std::uint64_t line) {
    return {run::kNoBlock, line};
}

WallElement wall_line(Pt a, Pt b, std::uint64_t line, MaterialSide side = MaterialSide::kLeft) {
    WallElement e;
    e.start = a;
    e.end = b;
    e.block = line_ref(line);
    e.material = side;
    return e;
}

WallElement wall_arc(Pt a, Pt b, Pt c, bool ccw, std::uint64_t line,
                     MaterialSide side = MaterialSide::kLeft) {
    WallElement e = wall_line(a, b, line, side);
    e.arc = true;
    e.centre = c;
    e.ccw = ccw;
    return e;
}

// The square [x0, x0 + s] x [y0, y0 + s], counter-clockwise, material inside (left): lines
// `first` (bottom), first + 1 (right), first + 2 (top), first + 3 (left).
DesignLoop square(double x0, double y0, double s, std::uint64_t first) {
    DesignLoop l;
    l.elements = {wall_line({x0, y0}, {x0 + s, y0}, first),
                  wall_line({x0 + s, y0}, {x0 + s, y0 + s}, first + 1),
                  wall_line({x0 + s, y0 + s}, {x0, y0 + s}, first + 2),
                  wall_line({x0, y0 + s}, {x0, y0}, first + 3)};
    return l;
}

// The same loop with the material on its other side (a pocket of the square's shape).
DesignLoop hole(DesignLoop l) {
    for (WallElement& e : l.elements)
        e.material = e.material == MaterialSide::kLeft ? MaterialSide::kRight : MaterialSide::kLeft;
    return l;
}

PathSegment seg_line(Pt a, Pt b, std::uint64_t line, double z = -1.0) {
    PathSegment s;
    s.kind = SegmentKind::kLine;
    s.block = line_ref(line);
    s.start = {a.x, a.y, z};
    s.end = {b.x, b.y, z};
    return s;
}

PathSegment seg_arc(Pt a, Pt b, Pt c, bool ccw, std::uint64_t line, double z = -1.0) {
    PathSegment s = seg_line(a, b, line, z);
    s.kind = SegmentKind::kArc;
    s.center = {c.x, c.y, z};
    s.ccw = ccw;
    return s;
}

OracleReport run_oracle(const DesignPart& part, const std::vector<PathSegment>& path, double r) {
    const StockOracle oracle(part);
    const std::vector<double> radius(path.size(), r);
    return oracle.run(path, radius);
}

const OracleGouge* find_pair(const OracleReport& rep, std::uint64_t path_line,
                             std::uint64_t wall_line) {
    for (const OracleGouge& g : rep.gouges)
        if (same_block(g.path_block, line_ref(path_line)) &&
            same_block(g.wall_block, line_ref(wall_line)))
            return &g;
    return nullptr;
}

DesignPart part_of(std::vector<DesignLoop> loops) {
    DesignPart p;
    p.loops = std::move(loops);
    return p;
}

TEST(StockOracle, LinePassingASquareAtAKnownDistanceCutsTheEdgeAndBothCorners) {
    // Square [0,10]^2; the tool (r = 3) runs along y = 12 from x = 2 to 8: 2 from the top edge
    // (depth 1), sqrt(8) from the corners (0, 10) and (10, 10) that end the side edges.
    const auto rep =
        run_oracle(part_of({square(0, 0, 10, 1)}), {seg_line({2, 12}, {8, 12}, 20)}, 3.0);
    ASSERT_EQ(rep.gouges.size(), 3U) << describe(rep);
    ASSERT_NE(find_pair(rep, 20, 3), nullptr);
    EXPECT_NEAR(find_pair(rep, 20, 3)->depth, 1.0, 1e-9);
    EXPECT_NEAR(find_pair(rep, 20, 3)->distance, 2.0, 1e-9);
    ASSERT_NE(find_pair(rep, 20, 4), nullptr);
    EXPECT_NEAR(find_pair(rep, 20, 4)->depth, 3.0 - std::sqrt(8.0), 1e-9);
    ASSERT_NE(find_pair(rep, 20, 2), nullptr);
    EXPECT_NEAR(find_pair(rep, 20, 2)->depth, 3.0 - std::sqrt(8.0), 1e-9);
    EXPECT_EQ(find_pair(rep, 20, 1), nullptr);
    EXPECT_TRUE(rep.buried.empty());
    // The area it takes from x = 3 to 7 (farther than r from the corners): the band of depth 1
    // between and the two halves of the disc's segment beyond the edge (2 from its centre).
    const auto band =
        run_oracle(part_of({square(0, 0, 10, 1)}), {seg_line({3, 12}, {7, 12}, 20)}, 3.0);
    ASSERT_EQ(band.gouges.size(), 1U) << describe(band);
    ASSERT_EQ(band.blocks.size(), 1U);
    const double cap = 9 * std::acos(2.0 / 3.0) - 2 * std::sqrt(5.0);
    EXPECT_NEAR(band.blocks[0].taken_area, 4.0 + cap, 1e-4);
    EXPECT_NEAR(band.blocks[0].swept_area, 6 * 4 + kPi * 9, 1e-3);
}

TEST(StockOracle, OtherPlanesTakeTheirOwnAxesAndTopOnTheThirdAxis) {
    // The square in the Y-Z plane (G19: first axis Y, second Z, third X, the top on X): the
    // line of the first test, at X = -1 (below the top, cuts) and at X = +1 (above it).
    DesignPart part = part_of({square(0, 0, 10, 1)});
    part.plane = 19;
    PathSegment below = seg_line({0, 0}, {0, 0}, 20);
    below.start = {-1, 2, 12};
    below.end = {-1, 8, 12};
    PathSegment above = below;
    above.block = line_ref(21);
    above.start.x() = above.end.x() = 1;
    const auto rep = run_oracle(part, {below, above}, 3.0);
    ASSERT_EQ(rep.gouges.size(), 3U) << describe(rep);
    EXPECT_NEAR(find_pair(rep, 20, 3)->depth, 1.0, 1e-9);
    EXPECT_EQ(rep.blocks.size(), 1U);
    // An arc of G18 (first Z, second X): centre and sense in that plane.
    DesignPart zx = part_of({square(0, 0, 10, 1)});
    zx.plane = 18;
    PathSegment arc;
    arc.kind = SegmentKind::kArc;
    arc.block = line_ref(30);
    arc.start = {12, -1, 5};  // X = second, Z = first: (z 5, x 12)
    arc.end = {12, -1, 5};    // a full circle about (z 5, x 14.5): 2 from the edge at x = 10
    arc.center = {14.5, -1, 5};
    arc.ccw = true;
    const auto rep2 = run_oracle(zx, {arc}, 3.0);
    ASSERT_EQ(rep2.gouges.size(), 1U) << describe(rep2);
    EXPECT_NEAR(rep2.gouges[0].depth, 1.0, 2 * StockOracle::kChordError);
    EXPECT_TRUE(same_block(rep2.gouges[0].wall_block, line_ref(3)));  // second axis 10: X = 10
}

TEST(StockOracle, ArcPassingACircleAtAKnownDistance) {
    // A disc of radius 10 as two half circles (lines 1 and 2); the tool (r = 3) on an arc of
    // radius 12.5 from 30 to 120 degrees: 2.5 from the first half, farther than 3 from the
    // second (whose ends are at 0 and 180 degrees).
    DesignLoop disc;
    disc.elements = {wall_arc({10, 0}, {-10, 0}, {0, 0}, true, 1),
                     wall_arc({-10, 0}, {10, 0}, {0, 0}, true, 2)};
    const auto at = [](double r, double deg) {
        return Pt{r * std::cos(deg * kPi / 180), r * std::sin(deg * kPi / 180)};
    };
    const auto rep =
        run_oracle(part_of({disc}), {seg_arc(at(12.5, 30), at(12.5, 120), {0, 0}, true, 7)}, 3.0);
    ASSERT_EQ(rep.gouges.size(), 1U) << describe(rep);
    ASSERT_NE(find_pair(rep, 7, 1), nullptr);
    EXPECT_NEAR(find_pair(rep, 7, 1)->depth, 0.5, 2 * StockOracle::kChordError);
    EXPECT_GE(find_pair(rep, 7, 1)->depth, 0.5 - 1e-9);  // chords never make it shallower

    // The same arc run clockwise the long way round (30 -> 120 through 0 and 270): it passes
    // both halves and both of their ends.
    const auto rep2 =
        run_oracle(part_of({disc}), {seg_arc(at(12.5, 30), at(12.5, 120), {0, 0}, false, 7)}, 3.0);
    ASSERT_EQ(rep2.gouges.size(), 2U) << describe(rep2);
    EXPECT_NEAR(find_pair(rep2, 7, 2)->depth, 0.5, 2 * StockOracle::kChordError);
}

TEST(StockOracle, ArcWhoseRadiiDifferRunsAsASpiral) {
    // Radius 12.5 at its start (0 degrees) and 12.3 at its end (180 degrees), the radius linear
    // in the angle: 12.4 at its middle (0, 12.4), about 2.6 below the square [-5, 5] x [15, 25]
    // (the highest point of the spiral lies a little before the middle, 12.40016 high).
    double highest = 0;
    for (int i = 0; i <= 1000000; ++i) {
        const double a = kPi * i / 1000000;
        highest = std::max(highest, (12.5 - 0.2 * a / kPi) * std::sin(a));
    }
    const auto rep = run_oracle(part_of({square(-5, 15, 10, 1)}),
                                {seg_arc({12.5, 0}, {-12.3, 0}, {0, 0}, true, 5)}, 3.0);
    ASSERT_EQ(rep.gouges.size(), 1U) << describe(rep);
    EXPECT_TRUE(same_block(rep.gouges[0].wall_block, line_ref(1)));
    EXPECT_NEAR(rep.gouges[0].depth, 3.0 - (15 - highest), 2 * StockOracle::kChordError);
    EXPECT_NEAR(rep.gouges[0].path_point.y, highest, 2 * StockOracle::kChordError);
    // Nearest its end: radius 12.5 at 0 degrees, 12.4 at 90 degrees, 2.4 from the disc of
    // radius 10.
    DesignLoop disc;
    disc.elements = {wall_arc({10, 0}, {10, 0}, {0, 0}, true, 1)};  // a full circle
    const auto rep2 =
        run_oracle(part_of({disc}), {seg_arc({12.5, 0}, {0, 12.4}, {0, 0}, true, 5)}, 3.0);
    ASSERT_EQ(rep2.gouges.size(), 1U) << describe(rep2);
    EXPECT_NEAR(rep2.gouges[0].depth, 0.6, 2 * StockOracle::kChordError);
}

TEST(StockOracle, LeadCrossingThePartCutsEveryEdgeItCrossesByTheWholeRadius) {
    // A lead-in from above the square straight down through it to below: both horizontal edges
    // crossed (distance 0, depth r); the side edges 5 away.
    const auto rep =
        run_oracle(part_of({square(0, 0, 10, 1)}), {seg_line({5, 20}, {5, -8}, 30)}, 2.0);
    ASSERT_EQ(rep.gouges.size(), 2U) << describe(rep);
    EXPECT_NEAR(find_pair(rep, 30, 1)->depth, 2.0, 1e-12);
    EXPECT_NEAR(find_pair(rep, 30, 3)->depth, 2.0, 1e-12);
    EXPECT_NEAR(find_pair(rep, 30, 3)->distance, 0.0, 1e-12);
}

TEST(StockOracle, PathExactlyTheRadiusAwayLeavesThePartIntact) {
    // Around the square at exactly r: the four sides' offsets and an arc of radius r about each
    // corner (the tool path of a boss milled with circular transitions).
    const double r = 2.5;
    std::vector<PathSegment> path = {seg_line({0, -r}, {10, -r}, 11),
                                     seg_arc({10, -r}, {10 + r, 0}, {10, 0}, true, 11),
                                     seg_line({10 + r, 0}, {10 + r, 10}, 12),
                                     seg_arc({10 + r, 10}, {10, 10 + r}, {10, 10}, true, 12),
                                     seg_line({10, 10 + r}, {0, 10 + r}, 13),
                                     seg_arc({0, 10 + r}, {-r, 10}, {0, 10}, true, 13),
                                     seg_line({-r, 10}, {-r, 0}, 14),
                                     seg_arc({-r, 0}, {0, -r}, {0, 0}, true, 14)};
    const auto rep = run_oracle(part_of({square(0, 0, 10, 1)}), path, r);
    EXPECT_TRUE(rep.gouges.empty()) << describe(rep);
    EXPECT_TRUE(rep.buried.empty()) << describe(rep);
    EXPECT_LE(rep.deepest_intact, 2 * StockOracle::kChordError);
    EXPECT_GE(rep.deepest_intact, -1e-9);  // it touches
    // Inside a pocket the same (a plate [-20, 30]^2 with the square as its pocket): the tool
    // runs r inside the pocket's walls.
    DesignLoop plate = square(-20, -20, 50, 100);
    for (WallElement& e : plate.elements) e.block = {};
    const DesignLoop pocket = hole(square(0, 0, 10, 1));  // material outside
    std::vector<PathSegment> inside = {
        seg_line({r, r}, {10 - r, r}, 21), seg_line({10 - r, r}, {10 - r, 10 - r}, 22),
        seg_line({10 - r, 10 - r}, {r, 10 - r}, 23), seg_line({r, 10 - r}, {r, r}, 24)};
    const auto rep2 = run_oracle(part_of({plate, pocket}), inside, r);
    EXPECT_TRUE(rep2.gouges.empty()) << describe(rep2);
    EXPECT_TRUE(rep2.buried.empty()) << describe(rep2);
    // 0.01 further out it cuts the pocket's bottom wall by 0.01.
    const auto rep3 =
        run_oracle(part_of({plate, pocket}), {seg_line({r, r - 0.01}, {10 - r, r - 0.01}, 21)}, r);
    ASSERT_EQ(rep3.gouges.size(), 1U) << describe(rep3);
    EXPECT_NEAR(find_pair(rep3, 21, 1)->depth, 0.01, 1e-12);
}

TEST(StockOracle, DepthBeyondThePathToleranceIsAGougeAndWithinItIsNot) {
    const double r = 1.0;
    const DesignPart part = part_of({square(0, 0, 10, 1)});
    for (const double depth :
         {StockOracle::kPathTolerance + 3e-5, StockOracle::kPathTolerance - 3e-5}) {
        const auto rep =
            run_oracle(part, {seg_line({3, 10 + r - depth}, {7, 10 + r - depth}, 9)}, r);
        if (depth > StockOracle::kPathTolerance) {
            ASSERT_EQ(rep.gouges.size(), 1U) << describe(rep);
            EXPECT_NEAR(rep.gouges[0].depth, depth, 1e-12);
        } else {
            EXPECT_TRUE(rep.gouges.empty()) << describe(rep);
            EXPECT_TRUE(rep.buried.empty()) << describe(rep);
            EXPECT_NEAR(rep.deepest_intact, depth, 1e-12);
        }
    }
}

TEST(StockOracle, PlungeIntoThePartIsBuriedAndMovesAtOrAboveTheTopCutNothing) {
    DesignPart part = part_of({square(0, 0, 10, 1)});
    part.top = 0.0;
    PathSegment plunge = seg_line({5, 5}, {5, 5}, 40, 0.0);
    plunge.start.z() = 5.0;
    plunge.end.z() = -1.0;
    PathSegment above = seg_line({-5, 5}, {15, 5}, 41, 5.0);
    above.kind = SegmentKind::kRapid;
    PathSegment at_top = seg_line({-5, 6}, {15, 6}, 42, 0.0);  // touches the top, takes nothing
    PathSegment rise = seg_line({5, 5}, {5, 5}, 43, 0.0);      // from the top up
    rise.end.z() = 5.0;
    const auto rep = run_oracle(part, {plunge, above, at_top, rise}, 2.0);
    EXPECT_TRUE(rep.gouges.empty()) << describe(rep);
    ASSERT_EQ(rep.buried.size(), 1U) << describe(rep);
    EXPECT_TRUE(same_block(rep.buried[0].path_block, line_ref(40)));
    EXPECT_NEAR(rep.buried[0].area, kPi * 4, 1e-3);
    ASSERT_EQ(rep.blocks.size(), 1U);  // those at or above the top are not cutting blocks
    // Just below the top it cuts.
    const auto rep2 = run_oracle(part, {seg_line({-5, 6}, {15, 6}, 42, -2e-9)}, 2.0);
    EXPECT_EQ(rep2.gouges.size(), 2U) << describe(rep2);  // crosses the left and right edges
}

TEST(StockOracle, ToolOnTheWrongSideOfItsWallIsBuried) {
    // The tool runs r inside the square (a boss milled as if it were a pocket): it touches no
    // wall closer than r, and takes material all along.
    const double r = 2.0;
    const auto rep =
        run_oracle(part_of({square(0, 0, 10, 1)}), {seg_line({r, r}, {10 - r, r}, 50)}, r);
    EXPECT_TRUE(rep.gouges.empty()) << describe(rep);
    ASSERT_EQ(rep.buried.size(), 1U) << describe(rep);
}

TEST(StockOracle, SegmentsOfOneBlockAreOneBlockAndNNumbersNameIt) {
    PathSegment a = seg_line({2, 12}, {5, 12}, 3);
    PathSegment b = seg_line({5, 12}, {5, 30}, 3);
    PathSegment c = seg_line({5, 30}, {8, 11}, 4);
    a.block = b.block = {70, 0};
    c.block = {80, 0};
    const auto rep = run_oracle(part_of({square(0, 0, 10, 1)}), {a, b, c}, 3.0);
    ASSERT_EQ(rep.blocks.size(), 2U);
    EXPECT_TRUE(same_block(rep.blocks[0].path_block, {70, 999}));  // N numbers decide
    EXPECT_EQ(block_name(rep.blocks[1].path_block), "N80");
    bool n70_top = false;
    for (const OracleGouge& g : rep.gouges)
        n70_top |= same_block(g.path_block, {70, 0}) && same_block(g.wall_block, line_ref(3));
    EXPECT_TRUE(n70_top) << describe(rep);
}

TEST(StockOracle, IslandInAPocketIsMaterialAgain) {
    DesignLoop plate = square(-50, -50, 100, 0);
    for (WallElement& e : plate.elements) e.block = {};
    const DesignLoop pocket = hole(square(-20, -20, 40, 10));
    const DesignLoop island = square(-5, -5, 10, 20);
    const StockOracle oracle(part_of({island, pocket, plate}));  // any order
    EXPECT_NEAR(oracle.area(), 100.0 * 100 - 40 * 40 + 10 * 10, 1e-9);
    EXPECT_TRUE(oracle.contains({0, 0}));
    EXPECT_FALSE(oracle.contains({10, 10}));
    EXPECT_TRUE(oracle.contains({30, 30}));
    // A path between island and pocket wall, 1.5 from the island: r = 2 cuts the island only.
    const std::vector<PathSegment> path = {seg_line({-3, 6.5}, {3, 6.5}, 30)};
    const std::vector<double> radius = {2.0};
    const auto rep = oracle.run(path, radius);
    ASSERT_EQ(rep.gouges.size(), 1U) << describe(rep);
    EXPECT_TRUE(same_block(rep.gouges[0].wall_block, line_ref(22)));
    EXPECT_NEAR(rep.gouges[0].depth, 0.5, 1e-12);
}

TEST(StockOracle, DesignPartsThatAreNotClosedLoopsAreRefused) {
    DesignLoop open = square(0, 0, 10, 1);
    open.elements[2].end.x += 1e-6;
    EXPECT_THROW(StockOracle(part_of({open})), std::invalid_argument);
    DesignLoop mixed = square(0, 0, 10, 1);
    mixed.elements[1].material = MaterialSide::kRight;
    EXPECT_THROW(StockOracle(part_of({mixed})), std::invalid_argument);
    // A pocket with no plate around it: where would the material be?
    EXPECT_THROW(StockOracle(part_of({hole(square(0, 0, 10, 1))})), std::invalid_argument);
    // An island with no pocket around it is material inside material.
    EXPECT_THROW(StockOracle(part_of({square(-50, -50, 100, 0), square(0, 0, 10, 1)})),
                 std::invalid_argument);
    EXPECT_THROW(StockOracle(part_of({DesignLoop{}})), std::invalid_argument);
    // One radius per segment.
    const StockOracle oracle(part_of({square(0, 0, 10, 1)}));
    const std::vector<PathSegment> path = {seg_line({0, 20}, {1, 20}, 1)};
    EXPECT_THROW(oracle.run(path, std::vector<double>{}), std::invalid_argument);
}

TEST(StockOracle, LeastDistanceOfPolylines) {
    const std::vector<Pt> a = {{0, 0}, {10, 0}};
    const std::vector<Pt> b = {{3, 5}, {4, 2}, {6, 7}};
    EXPECT_NEAR(least_distance(a, b).distance, 2.0, 1e-12);
    const std::vector<Pt> c = {{5, -1}, {5, 1}};  // crosses a
    EXPECT_EQ(least_distance(a, c).distance, 0.0);
    const std::vector<Pt> point = {{20, 0}};
    EXPECT_NEAR(least_distance(a, point).distance, 10.0, 1e-12);
    // Densified arcs keep their chords within the chord error of the circle.
    for (const double radius : {0.01, 0.5, 10.0, 500.0}) {
        WallElement e = wall_arc({radius, 0}, {radius, 0}, {0, 0}, true, 1);
        const std::vector<Pt> pts = densify(e);
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
            const Pt m{(pts[i].x + pts[i + 1].x) / 2, (pts[i].y + pts[i + 1].y) / 2};
            ASSERT_LE(radius - std::hypot(m.x, m.y), StockOracle::kChordError * (1 + 1e-9));
        }
        const double step = 2 * kPi / static_cast<double>(points_per_circle(radius));
        EXPECT_LE(radius * (1 - std::cos(step / 2)), StockOracle::kChordError * (1 + 1e-9));
    }
}

// ---- Agreement with brute-force point sampling.

// Exact distance from p to a line segment or a circular arc (constant radius).
double exact_distance(const Pt& p, const WallElement& e) {
    if (!e.arc) {
        const double dx = e.end.x - e.start.x, dy = e.end.y - e.start.y;
        const double n2 = dx * dx + dy * dy;
        const double t =
            std::clamp(((p.x - e.start.x) * dx + (p.y - e.start.y) * dy) / n2, 0.0, 1.0);
        return std::hypot(p.x - e.start.x - t * dx, p.y - e.start.y - t * dy);
    }
    const double R = std::hypot(e.start.x - e.centre.x, e.start.y - e.centre.y);
    const double a0 = std::atan2(e.start.y - e.centre.y, e.start.x - e.centre.x);
    const double a1 = std::atan2(e.end.y - e.centre.y, e.end.x - e.centre.x);
    const double ap = std::atan2(p.y - e.centre.y, p.x - e.centre.x);
    auto ccw_from = [](double from, double to) {
        double d = to - from;
        while (d < 0) d += 2 * kPi;
        while (d >= 2 * kPi) d -= 2 * kPi;
        return d;
    };
    const double sweep = e.ccw ? ccw_from(a0, a1) : ccw_from(a1, a0);
    const double along = e.ccw ? ccw_from(a0, ap) : ccw_from(ap, a0);
    const double dc = std::hypot(p.x - e.centre.x, p.y - e.centre.y);
    if (along <= sweep) return std::abs(dc - R);
    return std::min(std::hypot(p.x - e.start.x, p.y - e.start.y),
                    std::hypot(p.x - e.end.x, p.y - e.end.y));
}

// Points along a path element every `spacing` (exact points of the curve).
std::vector<Pt> samples(const WallElement& e, double spacing) {
    std::vector<Pt> out;
    if (!e.arc) {
        const double len = std::hypot(e.end.x - e.start.x, e.end.y - e.start.y);
        const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
        for (int i = 0; i <= n; ++i) {
            const double t = double(i) / n;
            out.push_back(
                {e.start.x + t * (e.end.x - e.start.x), e.start.y + t * (e.end.y - e.start.y)});
        }
        return out;
    }
    const double R = std::hypot(e.start.x - e.centre.x, e.start.y - e.centre.y);
    const double a0 = std::atan2(e.start.y - e.centre.y, e.start.x - e.centre.x);
    const double a1 = std::atan2(e.end.y - e.centre.y, e.end.x - e.centre.x);
    double sweep = e.ccw ? a1 - a0 : a0 - a1;
    while (sweep <= 0) sweep += 2 * kPi;
    const int n = std::max(1, static_cast<int>(std::ceil(R * sweep / spacing)));
    for (int i = 0; i <= n; ++i) {
        const double a = a0 + (e.ccw ? 1 : -1) * sweep * i / n;
        out.push_back({e.centre.x + R * std::cos(a), e.centre.y + R * std::sin(a)});
    }
    return out;
}

// ---- A scanline measure of the part's area a block takes, independent of Boost: on each row
// of a fine grid, the x intervals the tool sweeps (each chord's capsule meets a row in one
// interval) intersected with the x intervals inside the loop (even-odd crossings).

using Interval = std::pair<double, double>;

std::vector<Interval> merged(std::vector<Interval> v) {
    std::sort(v.begin(), v.end());
    std::vector<Interval> out;
    for (const Interval& i : v) {
        if (!out.empty() && i.first <= out.back().second)
            out.back().second = std::max(out.back().second, i.second);
        else
            out.push_back(i);
    }
    return out;
}

// Where the row y meets the points within r of the chord pq: the union of the discs at both
// ends and the band between, which is one interval (the capsule is convex).
std::optional<Interval> capsule_row(const Pt& p, const Pt& q, double r, double y) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Pt& c : {p, q}) {
        const double dy = y - c.y;
        if (std::abs(dy) < r) {
            const double w = std::sqrt(r * r - dy * dy);
            lo = std::min(lo, c.x - w);
            hi = std::max(hi, c.x + w);
        }
    }
    const double len = std::hypot(q.x - p.x, q.y - p.y);
    if (len > 0) {
        const double ux = (q.x - p.x) / len, uy = (q.y - p.y) / len;
        // Along: (x - p.x) ux + (y - p.y) uy in [0, len]; across: -(x - p.x) uy + (y - p.y) ux
        // in (-r, r). Each is a x + b.
        double blo = -INFINITY, bhi = INFINITY;
        bool empty = false;
        auto clip = [&](double a, double b0, double from, double to) {
            if (a == 0) {
                if (b0 < from || b0 > to) empty = true;
                return;
            }
            double x1 = (from - b0) / a, x2 = (to - b0) / a;
            if (x1 > x2) std::swap(x1, x2);
            blo = std::max(blo, x1);
            bhi = std::min(bhi, x2);
        };
        clip(ux, -p.x * ux + (y - p.y) * uy, 0, len);
        clip(-uy, p.x * uy + (y - p.y) * ux, -r, r);
        if (!empty && blo < bhi) {
            lo = std::min(lo, blo);
            hi = std::max(hi, bhi);
        }
    }
    if (lo < hi) return Interval{lo, hi};
    return std::nullopt;
}

double taken_by_scanlines(const std::vector<Pt>& path, double r, const std::vector<Pt>& ring,
                          double h) {
    double ly = INFINITY, hy = -INFINITY;
    for (const Pt& p : path) {
        ly = std::min(ly, p.y - r);
        hy = std::max(hy, p.y + r);
    }
    // The chords and ring edges each row can meet, in bins of 0.5 mm of y.
    const double bin = 0.5;
    const auto bins = static_cast<std::size_t>((hy - ly) / bin) + 1;
    std::vector<std::vector<std::size_t>> chords(bins), edges(bins);
    auto list = [&](std::vector<std::vector<std::size_t>>& into, std::size_t i, double y0,
                    double y1) {
        const double lo = std::max(std::min(y0, y1), ly), hi = std::min(std::max(y0, y1), hy);
        if (lo > hi) return;
        for (auto k = static_cast<std::size_t>((lo - ly) / bin);
             k <= static_cast<std::size_t>((hi - ly) / bin) && k < bins; ++k)
            into[k].push_back(i);
    };
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
        list(chords, i, std::min(path[i].y, path[i + 1].y) - r,
             std::max(path[i].y, path[i + 1].y) + r);
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) list(edges, i, ring[i].y, ring[i + 1].y);
    double area = 0;
    // Rows at ly + h/2, stepped by h as accumulated, while below hy (at most the height over h,
    // and one for the rounding).
    const auto rows = static_cast<std::size_t>(std::ceil((hy - ly) / h)) + 1;
    double next = ly + h / 2;
    for (std::size_t row = 0; row < rows; ++row) {
        const double y = next;
        next += h;
        if (!(y < hy)) break;
        const auto k = std::min(bins - 1, static_cast<std::size_t>((y - ly) / bin));
        std::vector<Interval> swept;
        for (const std::size_t i : chords[k])
            if (auto iv = capsule_row(path[i], path[i + 1], r, y)) swept.push_back(*iv);
        if (path.size() == 1)
            if (auto iv = capsule_row(path[0], path[0], r, y)) swept.push_back(*iv);
        swept = merged(std::move(swept));
        std::vector<double> xs;
        for (const std::size_t i : edges[k]) {
            const Pt& a = ring[i];
            const Pt& b = ring[i + 1];
            if ((a.y > y) != (b.y > y)) xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
        }
        std::sort(xs.begin(), xs.end());
        for (std::size_t j = 0; j + 1 < xs.size(); j += 2)
            for (const Interval& iv : swept)
                area +=
                    h * std::max(0.0, std::min(xs[j + 1], iv.second) - std::max(xs[j], iv.first));
    }
    return area;
}

// The least distance from a sampled path to a wall element, polished near the best sample.
double sampled_distance(const WallElement& path, const WallElement& wall) {
    const std::vector<Pt> pts = samples(path, 2e-3);
    std::size_t best = 0;
    for (std::size_t i = 0; i < pts.size(); ++i)
        if (exact_distance(pts[i], wall) < exact_distance(pts[best], wall)) best = i;
    double least = exact_distance(pts[best], wall);
    // Between the neighbours of the best sample, 400 more (chords of 1e-5: the polish).
    for (const std::size_t side : {std::size_t{0}, std::size_t{1}}) {
        const std::size_t i = side == 0 ? (best == 0 ? 0 : best - 1) : best;
        if (i + 1 >= pts.size()) continue;
        for (int k = 0; k <= 200; ++k) {
            const double t = k / 200.0;
            const Pt q{pts[i].x + t * (pts[i + 1].x - pts[i].x),
                       pts[i].y + t * (pts[i + 1].y - pts[i].y)};
            least = std::min(least, exact_distance(q, wall));
        }
    }
    return least;
}

// A random part: a convex-or-not loop of lines and arcs about the origin, counter-clockwise
// (material inside), each element its own block (lines 1..n).
DesignLoop random_loop(Rng& rng) {
    const int n = rng.integer(3, 7);
    std::vector<double> angle(n);
    for (int i = 0; i < n; ++i) angle[i] = 2 * kPi * (i + rng.uniform(0.1, 0.9)) / n;
    std::vector<Pt> v(n);
    for (int i = 0; i < n; ++i) {
        const double rad = rng.uniform(4.0, 10.0);
        v[i] = {rad * std::cos(angle[i]), rad * std::sin(angle[i])};
    }
    DesignLoop loop;
    for (int i = 0; i < n; ++i) {
        const Pt a = v[i], b = v[(i + 1) % n];
        WallElement e = wall_line(a, b, static_cast<std::uint64_t>(i) + 1);
        if (rng.chance(0.4)) {
            // An arc through a and b whose middle lies a sagitta s outwards (s > 0: right of
            // a -> b, outside the loop) or inwards; its centre on the other side (s > 0: the
            // minor arc about a centre on the left runs counter-clockwise).
            const double chord = std::hypot(b.x - a.x, b.y - a.y);
            const double s = rng.uniform(-0.1, 0.35) * chord;
            if (std::abs(s) > 0.05) {
                const double t = std::abs(s);
                const double R = (chord * chord / 4 + t * t) / (2 * t);
                const Pt m{(a.x + b.x) / 2, (a.y + b.y) / 2};
                const Pt out{(b.y - a.y) / chord, -(b.x - a.x) / chord};
                const double k = s > 0 ? -(R - t) : (R - t);
                e.arc = true;
                e.centre = {m.x + k * out.x, m.y + k * out.y};
                e.ccw = s > 0;
            }
        }
        loop.elements.push_back(e);
    }
    return loop;
}

// The area a tool sweeps along an arc of any radius against it (an annular sector with round
// ends; a sector and two discs where the arc is no larger than the tool, as every circular
// transition is), against the scanline measure, inside a large part.
TEST(StockOracle, SweptAreaOfArcsOfEveryRadiusAgainstTheTool) {
    const double r = 2.0;
    const DesignLoop big = square(-50, -50, 100, 1);
    const StockOracle oracle(part_of({big}));
    std::vector<Pt> ring;
    for (const WallElement& e : big.elements) {
        const std::vector<Pt> pts = samples(e, INFINITY);
        ring.insert(ring.end(), pts.begin() + (ring.empty() ? 0 : 1), pts.end());
    }
    int measured = 0;
    for (const double radius : {0.3 * r, r, 1.7 * r}) {
        for (const double degrees : {60.0, 200.0, 360.0}) {
            const double a = degrees * kPi / 180;
            const Pt start{radius, 0};
            const Pt end =
                degrees == 360.0 ? start : Pt{radius * std::cos(a), radius * std::sin(a)};
            const std::vector<PathSegment> path = {seg_arc(start, end, {0, 0}, true, 9)};
            const OracleReport rep = oracle.run(path, std::vector<double>{r});
            ASSERT_EQ(rep.blocks.size(), 1U);
            ASSERT_TRUE(rep.blocks[0].measured);  // inside the part: buried
            const WallElement as_wall = wall_arc(start, end, {0, 0}, true, 0);
            const double expected =
                taken_by_scanlines(samples(as_wall, std::sqrt(8 * radius * 2e-6)), r, ring, 0.002);
            EXPECT_NEAR(rep.blocks[0].swept_area, expected, 1e-3)
                << "arc radius " << radius << ", " << degrees << " degrees";
            EXPECT_NEAR(rep.blocks[0].taken_area, rep.blocks[0].swept_area, 1e-6);
            ++measured;
        }
    }
    EXPECT_EQ(measured, 9);
}

// A random part whose oracle can be made (`loop`, `made`): a loop that crosses itself is drawn
// again.
void draw_part(Rng& rng, DesignLoop& loop, std::optional<StockOracle>& made) {
    loop = random_loop(rng);
    while (!made) {
        try {
            made.emplace(part_of({loop}));
        } catch (const std::invalid_argument&) {  // the loop crosses itself: draw again
            loop = random_loop(rng);
        }
    }
}

// A path of 1..3 blocks (lines 100, 101, ...): lines and arcs near the part; `as_walls` the
// same geometry, for the sampling.
void random_path(Rng& rng, std::vector<PathSegment>& path, std::vector<WallElement>& as_walls) {
    Pt at{rng.uniform(-14, 14), rng.uniform(-14, 14)};
    const int blocks = rng.integer(1, 3);
    for (int b = 0; b < blocks; ++b) {
        const Pt to{rng.uniform(-14, 14), rng.uniform(-14, 14)};
        WallElement w = wall_line(at, to, 100 + b);
        if (rng.chance(0.5)) {
            const double chord = std::hypot(to.x - at.x, to.y - at.y);
            const Pt m{(at.x + to.x) / 2, (at.y + to.y) / 2};
            const double off = rng.uniform(-1.0, 1.0) * chord;
            w.arc = true;
            w.centre = {m.x - off * (to.y - at.y) / chord, m.y + off * (to.x - at.x) / chord};
            w.ccw = rng.chance(0.5);
            // Make the end lie exactly on the start's circle.
            const double R = std::hypot(at.x - w.centre.x, at.y - w.centre.y);
            const double ae = std::atan2(to.y - w.centre.y, to.x - w.centre.x);
            w.end = {w.centre.x + R * std::cos(ae), w.centre.y + R * std::sin(ae)};
            path.push_back(seg_arc(w.start, w.end, w.centre, w.ccw, 100 + b));
        } else {
            path.push_back(seg_line(w.start, w.end, 100 + b));
        }
        as_walls.push_back(w);
        at = w.end;
    }
}

// The part's boundary as points for the scanline measure: lines by their ends, arcs in chords
// of sagitta 2e-6.
std::vector<Pt> sampled_ring(const DesignLoop& loop) {
    std::vector<Pt> ring;
    for (const WallElement& e : loop.elements) {
        const std::vector<Pt> pts = samples(
            e,
            e.arc ? std::sqrt(8 * std::hypot(e.start.x - e.centre.x, e.start.y - e.centre.y) * 2e-6)
                  : INFINITY);
        ring.insert(ring.end(), pts.begin() + (ring.empty() ? 0 : 1), pts.end());
    }
    return ring;
}

// Block b (`block`, line 100 + b) of case c: its depth against each wall element, sampled,
// is the oracle's pair (or there is none); `any_gouge` whether it cuts a wall, `pairs` counts
// the pairs compared.
void check_depths(int c, int b, const WallElement& block, double r, const DesignLoop& loop,
                  const OracleReport& rep, bool& any_gouge, int& pairs) {
    for (const WallElement& wall : loop.elements) {
        const double depth = r - sampled_distance(block, wall);
        const OracleGouge* g = find_pair(rep, 100 + b, wall.block.line);
        if (std::abs(depth - StockOracle::kPathTolerance) < 5e-5) continue;  // too close to call
        if (depth > StockOracle::kPathTolerance) {
            any_gouge = true;
            ASSERT_NE(g, nullptr) << "case " << c << " block " << b << " wall " << wall.block.line
                                  << " sampled depth " << depth << "\n"
                                  << describe(rep);
            EXPECT_NEAR(g->depth, depth, 3e-5) << "case " << c;
            ++pairs;
        } else {
            EXPECT_EQ(g, nullptr) << "case " << c << " block " << b << " wall " << wall.block.line
                                  << " sampled depth " << depth << "\n"
                                  << describe(rep);
        }
    }
}

// Block b (`block`, line 100 + b) of case c: the part's area it takes is the scanline
// measure's, and a block that takes material is named (a wall it cuts, or buried);
// `compared_areas` counts the areas compared.
void check_taken_area(int c, int b, const WallElement& block, double r, const std::vector<Pt>& ring,
                      const OracleReport& rep, bool any_gouge, int& compared_areas) {
    const OracleBlock* ob = nullptr;
    for (const OracleBlock& x : rep.blocks)
        if (same_block(x.path_block, line_ref(100 + b))) ob = &x;
    ASSERT_NE(ob, nullptr);
    // Lines need their ends; arcs chords of sagitta 2e-6 (spacing sqrt(8 R 2e-6)).
    const double spacing =
        block.arc
            ? std::sqrt(8 *
                        std::hypot(block.start.x - block.centre.x, block.start.y - block.centre.y) *
                        2e-6)
            : INFINITY;
    const double taken = taken_by_scanlines(samples(block, spacing), r, ring, 0.005);
    EXPECT_NEAR(ob->taken_area, taken, 2e-3 + 1e-4 * taken) << "case " << c;
    ++compared_areas;
    const bool named =
        any_gouge || std::any_of(rep.buried.begin(), rep.buried.end(), [&](const OracleBuried& x) {
            return same_block(x.path_block, line_ref(100 + b));
        });
    if (taken > 1e-2) {
        EXPECT_TRUE(named) << "case " << c << "\n" << describe(rep);
    }
    if (taken < 1e-6) {
        EXPECT_FALSE(named) << "case " << c << "\n" << describe(rep);
    }
}

TEST(StockOracle, AgreesWithBruteForceSamplingOnRandomPartsAndPaths) {
    Rng rng(20261127);
    int cases = 0, pairs = 0, compared_areas = 0;
    for (int c = 0; c < 40; ++c) {
        DesignLoop loop;
        std::optional<StockOracle> made;
        draw_part(rng, loop, made);
        const StockOracle& oracle = *made;
        const double r = rng.log_uniform(0.3, 4.0);
        std::vector<PathSegment> path;
        std::vector<WallElement> as_walls;  // the same geometry, for the sampling
        random_path(rng, path, as_walls);
        const std::vector<double> radius(path.size(), r);
        OracleOptions every;
        every.measure_every_block = true;
        const OracleReport rep = oracle.run(path, radius, every);
        ++cases;
        const std::vector<Pt> ring = sampled_ring(loop);
        for (int b = 0; b < static_cast<int>(as_walls.size()); ++b) {
            bool any_gouge = false;
            ASSERT_NO_FATAL_FAILURE(
                check_depths(c, b, as_walls[b], r, loop, rep, any_gouge, pairs));
            ASSERT_NO_FATAL_FAILURE(
                check_taken_area(c, b, as_walls[b], r, ring, rep, any_gouge, compared_areas));
        }
    }
    EXPECT_EQ(cases, 40);
    EXPECT_GT(pairs, 25);  // the random cases do cut walls
    EXPECT_GT(compared_areas, 40);
}

}  // namespace
}  // namespace apci::test
