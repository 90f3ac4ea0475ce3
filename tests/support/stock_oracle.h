// SPDX-License-Identifier: MIT
// The stock-removal oracle of the gouge tests (docs/testing.md, "The gouge oracle"): a 2D
// material-removal simulation on Boost.Geometry, independent of the compensation and of the
// run's self-approach check. It knows the design part (the material a program must leave
// standing, as exact boundary elements, each tagged with the NC block that programmed it) and
// takes the tool-centre path a run executed with the tool radius of each segment. Each executed
// block sweeps the area of the tool along its centre path (polygons of the points within r of
// each segment, united with Boost.Geometry); where that area enters the part (the
// intersection's area is not 0), the oracle names the walls it cuts and how deep:
//
//   depth = r - (least distance between the block's centre path and the wall element)
//
// and a gouge is a pair (path block, wall block) whose depth exceeds the path tolerance
// (1e-4 mm, the compensation's kPathTolerance). A block whose swept area takes material without
// coming within r of any wall (a plunge into the part, a path on the wrong side of its wall)
// is reported apart as "buried".
//
// Accuracy: arcs are densified with chords whose sagitta is at most kChordError (1e-5 mm), and
// the swept polygons' circles have enough points that they stay within kChordError of the true
// swept area (their points lie on it); a depth is within 2 kChordError of the true one (the
// chords of both curves), and an area within kChordError times the outlines' length.
//
// Arcs are run as the board runs them: from start to end point about the centre, the radius
// changing linearly with the angle where rounding made the start and end radius differ; an arc
// whose end is its start (within 1e-9) is a full circle.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "apci/run/path.h"

namespace apci::test {

// A point of the plane: (first, second) axis of the plane (X, Y under G17).
struct Pt {
    double x = 0.0;
    double y = 0.0;
};

// Which side of a wall element the material lies on, seen along the element's direction.
enum class MaterialSide : std::uint8_t { kLeft, kRight };

// One piece of the design part's boundary, as the program wrote it (rounded coordinates).
struct WallElement {
    bool arc = false;
    Pt start, end;
    Pt centre;         // arcs only
    bool ccw = false;  // arcs only
    // The NC block that programmed it; {kNoBlock, 0} for a boundary no block programmed (the
    // edge of the stock around pockets).
    run::BlockRef block{};
    MaterialSide material = MaterialSide::kLeft;
};

// A closed loop of the boundary: each element starts where the one before it ends (within
// 1e-9 mm), the last ends where the first starts; the material is on the same side of all.
struct DesignLoop {
    std::vector<WallElement> elements;
};

// The material a program must leave standing: loops that do not cross or touch one another.
// A loop with the material inside adds material, one with the material outside takes it away
// from the loop around it (a pocket in a plate, an island in a pocket: the plate's outline,
// the pocket, the island). A loop with the material outside and nothing around it is an error:
// give the stock's outline.
struct DesignPart {
    int plane = 17;    // the plane the loops lie in (17, 18, 19)
    double top = 0.0;  // the part's top on the plane's third axis (Z under G17)
    std::vector<DesignLoop> loops;
};

// One wall the oracle found cut.
struct OracleGouge {
    run::BlockRef path_block;   // the executed block whose swept area cuts it
    run::BlockRef wall_block;   // the block that programmed the wall element
    double depth = 0.0;         // radius - distance
    double distance = 0.0;      // least distance between the block's centre path and the wall
    double radius = 0.0;        // the block's tool radius
    Pt path_point, wall_point;  // where that distance is
};

// An executed block that takes material without coming within its radius of any wall.
struct OracleBuried {
    run::BlockRef path_block;
    double area = 0.0;  // the area of the part it sweeps, mm^2
    double radius = 0.0;
};

// One executed block that can cut (it reaches below the part's top), with one tool radius.
struct OracleBlock {
    run::BlockRef path_block;
    double radius = 0.0;
    double swept_area = 0.0;  // the area its tool sweeps, mm^2
    double taken_area = 0.0;  // of that, the part's, mm^2 (> 0: it enters the part)
    // False where the areas were not computed (both 0): the block's centre path starts outside
    // the part and keeps at least r - 2 kChordError from every wall, so it takes no more of the
    // part than the polygons' own error (see OracleOptions).
    bool measured = false;
};

struct OracleOptions {
    // Compute the areas of every block, also of those that stay outside the part.
    bool measure_every_block = false;
};

struct OracleReport {
    std::vector<OracleGouge> gouges;  // by path block in the order they ran, then wall block
    std::vector<OracleBuried> buried;
    std::vector<OracleBlock> blocks;  // in the order they first ran
    // The deepest pair that is not a gouge (depth <= the path tolerance): how close an intact
    // program comes to the threshold; -infinity when no block comes within its radius of a wall.
    double deepest_intact = -1.0 / 0.0;
    OracleGouge deepest_intact_pair;  // that pair (its blocks, distance, where)
    bool gouged() const { return !gouges.empty() || !buried.empty(); }
};

// "N40/line 12" style names of blocks, and equality of block references (by N number where the
// block has one, else by source line).
bool same_block(const run::BlockRef& a, const run::BlockRef& b) noexcept;
std::string block_name(const run::BlockRef& b);
// A readable list of the report's findings, one per line.
std::string describe(const OracleReport& report);

class StockOracle {
  public:
    static constexpr double kPathTolerance = 1e-4;  // a depth beyond this is a gouge, mm
    static constexpr double kChordError = 1e-5;     // polygon and chord error, mm

    // Builds the part's polygons from its loops. Throws std::invalid_argument naming the loop
    // and element where a loop does not close, mixes material sides or is degenerate, or where
    // a loop with the material outside has nothing around it.
    explicit StockOracle(const DesignPart& part);
    ~StockOracle();
    StockOracle(StockOracle&&) noexcept;
    StockOracle& operator=(StockOracle&&) noexcept;

    // The gouges of an executed path. `radius[i]` is the tool radius of `path[i]` (sizes must
    // agree, else std::invalid_argument). Segments that do not reach below the part's top (by
    // more than 1e-9 mm) cut nothing: rapids at a safe height, the rise from the top where a
    // program starts
    // (rapids at a safe height). Segments are grouped by their block (N number, else source
    // line): a block's area is swept by all of its segments.
    OracleReport run(std::span<const run::PathSegment> path, std::span<const double> radius,
                     const OracleOptions& options = {}) const;

    // The part's area (mm^2), for tests.
    double area() const;
    // True when p lies in the part (on the boundary counts as in), for tests.
    bool contains(const Pt& p) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// ---- The geometry the oracle is built on, exposed for its tests.

// The points of a wall element or of a path segment's projection on `plane`, densified so that
// no chord is farther than kChordError from the curve; the first point is the start, the last
// the end.
std::vector<Pt> densify(const WallElement& e);
std::vector<Pt> densify(const run::PathSegment& s, int plane);
// The least distance between two polylines (each at least one point), and where.
struct PolylineDistance {
    double distance = 0.0;
    Pt a, b;
};
PolylineDistance least_distance(std::span<const Pt> a, std::span<const Pt> b);
// How many points a full circle of radius r needs so that the chord error stays below
// kChordError.
std::size_t points_per_circle(double r);

}  // namespace apci::test
