// SPDX-License-Identifier: MIT
#include "stock_oracle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

// Boost.Geometry 1.74 under g++ 12 at -O2: -Wmaybe-uninitialized inside its envelope and
// rescaling code (boxes filled by an "assign_inverse" the optimiser does not follow), a known
// false positive of that pair; kept out of our warnings, not of Boost's code paths. (clang has
// no such warning, and under -Werror refuses a pragma naming it.)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/geometry.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace apci::test {
namespace {

namespace bg = boost::geometry;
using BPoint = bg::model::d2::point_xy<double>;
using BPolygon = bg::model::polygon<BPoint>;  // clockwise outer rings, closed
using BMulti = bg::model::multi_polygon<BPolygon>;
using BLine = bg::model::linestring<BPoint>;
using BMultiLine = bg::model::multi_linestring<BLine>;
using BMultiPoint = bg::model::multi_point<BPoint>;
using BBox = bg::model::box<BPoint>;

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Two points this close are one (a full circle, a closed loop).
constexpr double kSamePoint = 1e-9;

double dist(const Pt& a, const Pt& b) {
    return std::hypot(a.x - b.x, a.y - b.y);
}

// The angle an arc turns through from start to end, in (0, 2 pi]: 2 pi for a full circle.
double arc_turn(const Pt& start, const Pt& end, const Pt& centre, bool ccw) {
    if (dist(start, end) <= kSamePoint) return 2 * kPi;
    const double a0 = std::atan2(start.y - centre.y, start.x - centre.x);
    const double a1 = std::atan2(end.y - centre.y, end.x - centre.x);
    double turn = ccw ? a1 - a0 : a0 - a1;
    while (turn <= 0) turn += 2 * kPi;
    while (turn > 2 * kPi) turn -= 2 * kPi;
    return turn;
}

// The arc's points: the radius runs linearly with the angle from the start's to the end's.
std::vector<Pt> densify_arc(const Pt& start, const Pt& end, const Pt& centre, bool ccw) {
    const double r0 = dist(start, centre);
    const double r1 = dist(end, centre);
    const double turn = arc_turn(start, end, centre, ccw);
    const double rmax = std::max(r0, r1);
    // A chord of angle a of a circle of radius R is R (1 - cos(a / 2)) from it.
    const double step = rmax <= StockOracle::kChordError
                            ? turn
                            : 2 * std::acos(1 - StockOracle::kChordError / rmax);
    const auto n = static_cast<std::size_t>(std::max(1.0, std::ceil(turn / step)));
    const double a0 = std::atan2(start.y - centre.y, start.x - centre.x);
    std::vector<Pt> out;
    out.reserve(n + 1);
    out.push_back(start);
    for (std::size_t k = 1; k < n; ++k) {
        const double f = static_cast<double>(k) / static_cast<double>(n);
        const double a = a0 + (ccw ? 1 : -1) * turn * f;
        const double r = r0 + (r1 - r0) * f;
        out.push_back({centre.x + r * std::cos(a), centre.y + r * std::sin(a)});
    }
    out.push_back(end);
    return out;
}

// ---- Least distance between two polylines: a tree of boxes over each one's chords, searched
// pairwise (branch and bound on the distance between boxes).

struct Box2 {
    double lx = kInf, ly = kInf, hx = -kInf, hy = -kInf;
    void add(const Pt& p) {
        lx = std::min(lx, p.x);
        ly = std::min(ly, p.y);
        hx = std::max(hx, p.x);
        hy = std::max(hy, p.y);
    }
    void add(const Box2& b) {
        lx = std::min(lx, b.lx);
        ly = std::min(ly, b.ly);
        hx = std::max(hx, b.hx);
        hy = std::max(hy, b.hy);
    }
    double distance(const Box2& b) const {
        const double dx = std::max({0.0, b.lx - hx, lx - b.hx});
        const double dy = std::max({0.0, b.ly - hy, ly - b.hy});
        return std::hypot(dx, dy);
    }
};

// The closest points of segments pq and rs.
void segment_distance(const Pt& p, const Pt& q, const Pt& r, const Pt& s, PolylineDistance& best) {
    auto consider = [&](const Pt& a, const Pt& b) {
        const double d = dist(a, b);
        if (d < best.distance) best = {d, a, b};
    };
    // Crossing: distance 0 at the crossing.
    const double d1x = q.x - p.x, d1y = q.y - p.y, d2x = s.x - r.x, d2y = s.y - r.y;
    const double den = d1x * d2y - d1y * d2x;
    if (den != 0.0) {
        const double t = ((r.x - p.x) * d2y - (r.y - p.y) * d2x) / den;
        const double u = ((r.x - p.x) * d1y - (r.y - p.y) * d1x) / den;
        if (t >= 0 && t <= 1 && u >= 0 && u <= 1) {
            const Pt x{p.x + t * d1x, p.y + t * d1y};
            consider(x, x);
            return;
        }
    }
    auto project = [](const Pt& a, const Pt& b, const Pt& x) {
        const double dx = b.x - a.x, dy = b.y - a.y;
        const double n2 = dx * dx + dy * dy;
        const double t =
            n2 == 0.0 ? 0.0 : std::clamp(((x.x - a.x) * dx + (x.y - a.y) * dy) / n2, 0.0, 1.0);
        return Pt{a.x + t * dx, a.y + t * dy};
    };
    consider(p, project(r, s, p));
    consider(q, project(r, s, q));
    consider(project(p, q, r), r);
    consider(project(p, q, s), s);
}

class ChordTree {
  public:
    explicit ChordTree(std::vector<Pt> points) : pts_(std::move(points)) {
        if (pts_.empty()) throw std::invalid_argument("least_distance: an empty polyline");
        if (pts_.size() == 1) pts_.push_back(pts_.front());  // a point: a chord of length 0
        nodes_.reserve(2 * (pts_.size() / kLeaf + 1));
        root_ = build(0, pts_.size() - 1);
    }
    const Box2& box() const { return nodes_[root_].box; }

    // best.distance on entry is the cut-off: nothing at least that far is looked at.
    void distance(const ChordTree& other, PolylineDistance& best) const {
        search(root_, other, other.root_, best);
    }

  private:
    static constexpr std::size_t kLeaf = 8;  // chords per leaf
    struct Node {
        Box2 box;
        std::size_t first, last;  // chords [first, last): chord i runs from point i to i + 1
        std::size_t left = 0, right = 0;
        bool leaf() const { return last - first <= kLeaf; }
    };
    std::size_t build(std::size_t first, std::size_t last) {
        Node n;
        n.first = first;
        n.last = last;
        for (std::size_t i = first; i <= last; ++i) n.box.add(pts_[i]);
        const std::size_t at = nodes_.size();
        nodes_.push_back(n);
        if (!n.leaf()) {
            const std::size_t mid = first + (last - first) / 2;
            const std::size_t l = build(first, mid);
            const std::size_t r = build(mid, last);
            nodes_[at].left = l;
            nodes_[at].right = r;
        }
        return at;
    }
    void search(std::size_t a, const ChordTree& t, std::size_t b, PolylineDistance& best) const {
        const Node& na = nodes_[a];
        const Node& nb = t.nodes_[b];
        if (na.box.distance(nb.box) >= best.distance) return;
        if (na.leaf() && nb.leaf()) {
            for (std::size_t i = na.first; i < na.last; ++i)
                for (std::size_t j = nb.first; j < nb.last; ++j)
                    segment_distance(pts_[i], pts_[i + 1], t.pts_[j], t.pts_[j + 1], best);
            return;
        }
        // Split the larger one; look at the nearer half first.
        const bool split_a = !na.leaf() && (nb.leaf() || na.last - na.first >= nb.last - nb.first);
        std::size_t c1, c2;
        if (split_a) {
            c1 = na.left;
            c2 = na.right;
            if (nodes_[c2].box.distance(nb.box) < nodes_[c1].box.distance(nb.box))
                std::swap(c1, c2);
            search(c1, t, b, best);
            search(c2, t, b, best);
        } else {
            c1 = nb.left;
            c2 = nb.right;
            if (na.box.distance(t.nodes_[c2].box) < na.box.distance(t.nodes_[c1].box))
                std::swap(c1, c2);
            search(a, t, c1, best);
            search(a, t, c2, best);
        }
    }
    std::vector<Pt> pts_;
    std::vector<Node> nodes_;
    std::size_t root_ = 0;
};

BPoint bp(const Pt& p) {
    return BPoint(p.x, p.y);
}

double signed_area(const std::vector<Pt>& ring) {
    double a = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
        a += ring[i].x * ring[i + 1].y - ring[i + 1].x * ring[i].y;
    return a / 2;
}

BPolygon polygon_of(const std::vector<Pt>& ring) {
    BPolygon poly;
    for (const Pt& p : ring) poly.outer().push_back(bp(p));
    bg::correct(poly);
    return poly;
}

// Block references as keys: by N number where there is one, else by source line.
struct BlockKey {
    std::int64_t number;
    std::uint64_t line;
    bool operator==(const BlockKey&) const = default;
};
BlockKey key_of(const run::BlockRef& b) {
    return b.number != run::kNoBlock ? BlockKey{b.number, 0} : BlockKey{run::kNoBlock, b.line};
}

struct Wall {
    WallElement element;
    ChordTree chords;
};

// One executed segment in the plane: a line (a point when start == end) or an arc.
struct PlaneSegment {
    bool arc = false;
    Pt start, end, centre;
    bool ccw = false;
};

// One executed block with one tool radius: its segments, and its runs of continuous centre
// path (densified).
struct PathBlock {
    run::BlockRef block;
    double radius = 0.0;
    std::vector<PlaneSegment> segments;
    std::vector<std::vector<Pt>> runs;
};

// ---- The area a tool of radius r sweeps along a segment, as polygons whose union it is:
// the points within r of the segment. Built here rather than by Boost's buffer, which
// simplifies its input by r / 1000 (far beyond the chord error), costs tens of milliseconds
// on a densified arc, and backtracks without end where an arc's radius equals the buffer
// distance (every circular transition: an arc of radius r about its corner). A line sweeps a
// capsule; an arc of radius R > r an annular sector R - r .. R + r with a half disc at each
// end; an arc of radius R <= r the sector of radius R + r and the discs at its ends. Every
// point lies on the true boundary (the polygons are inscribed), chords at most kChordError
// from it.

using Ring = std::vector<Pt>;

Pt on_circle(const Pt& c, double r, double a) {
    return {c.x + r * std::cos(a), c.y + r * std::sin(a)};
}

// Points of the circle about c from angle a0 turning by `turn` (signed), the ends included.
void add_circle_points(Ring& ring, const Pt& c, double r, double a0, double turn) {
    const double step = 2 * kPi / static_cast<double>(points_per_circle(r));
    const auto n = static_cast<std::size_t>(std::max(1.0, std::ceil(std::abs(turn) / step)));
    for (std::size_t k = 0; k <= n; ++k)
        ring.push_back(
            on_circle(c, r, a0 + turn * static_cast<double>(k) / static_cast<double>(n)));
}

BPolygon polygon_of_ring(const Ring& ring) {
    BPolygon poly;
    for (const Pt& p : ring) poly.outer().push_back(bp(p));
    poly.outer().push_back(bp(ring.front()));
    bg::correct(poly);
    return poly;
}

BPolygon disc(const Pt& c, double r) {
    Ring ring;
    add_circle_points(ring, c, r, 0.0, 2 * kPi);
    ring.pop_back();  // the start again
    return polygon_of_ring(ring);
}

void sweep_pieces(const PlaneSegment& s, double r, std::vector<BPolygon>& out) {
    if (!s.arc) {
        const double len = dist(s.start, s.end);
        if (len <= kSamePoint) {
            out.push_back(disc(s.start, r));
            return;
        }
        const double h = std::atan2(s.end.y - s.start.y, s.end.x - s.start.x);
        Ring ring;  // the right side forward, the cap round the end, the left side back, the cap
        add_circle_points(ring, s.end, r, h - kPi / 2, kPi);
        add_circle_points(ring, s.start, r, h + kPi / 2, kPi);
        out.push_back(polygon_of_ring(ring));
        return;
    }
    const double r0 = dist(s.start, s.centre);
    const double r1 = dist(s.end, s.centre);
    const double turn = arc_turn(s.start, s.end, s.centre, s.ccw);
    const double sense = s.ccw ? 1.0 : -1.0;
    const double a0 = std::atan2(s.start.y - s.centre.y, s.start.x - s.centre.x);
    // Pieces of at most a quarter turn, so that no piece's caps reach each other.
    const auto pieces = static_cast<int>(std::ceil(turn / (kPi / 2) - 1e-12));
    for (int k = 0; k < pieces; ++k) {
        const double f0 = static_cast<double>(k) / pieces, f1 = static_cast<double>(k + 1) / pieces;
        const double b0 = a0 + sense * turn * f0, b1 = a0 + sense * turn * f1;
        const double q0 = r0 + (r1 - r0) * f0, q1 = r0 + (r1 - r0) * f1;
        const Pt p0 = on_circle(s.centre, q0, b0), p1 = on_circle(s.centre, q1, b1);
        // The radius runs linearly with the angle: the outer and inner edges at R(a) +- r.
        const double rmax = std::max(q0, q1) + r;
        const double step = rmax <= StockOracle::kChordError
                                ? turn
                                : 2 * std::acos(1 - StockOracle::kChordError / rmax);
        const auto n = static_cast<std::size_t>(std::max(1.0, std::ceil(turn * (f1 - f0) / step)));
        auto edge = [&](double offset, bool backwards, Ring& ring) {
            for (std::size_t i = 0; i <= n; ++i) {
                const double f =
                    static_cast<double>(backwards ? n - i : i) / static_cast<double>(n);
                ring.push_back(
                    on_circle(s.centre, q0 + (q1 - q0) * f + offset, b0 + (b1 - b0) * f));
            }
        };
        if (std::min(q0, q1) > r) {
            Ring ring;
            edge(r, false, ring);
            // The cap ahead of the end: from the outer side round the front to the inner side.
            add_circle_points(ring, p1, r, b1, sense * kPi);
            edge(-r, true, ring);
            add_circle_points(ring, p0, r, b0 + kPi, sense * kPi);
            out.push_back(polygon_of_ring(ring));
        } else {
            Ring ring{s.centre};
            edge(r, false, ring);
            out.push_back(polygon_of_ring(ring));
            out.push_back(disc(p0, r));
            out.push_back(disc(p1, r));
        }
    }
}

}  // namespace

bool same_block(const run::BlockRef& a, const run::BlockRef& b) noexcept {
    return key_of(a) == key_of(b);
}

std::string block_name(const run::BlockRef& b) {
    if (b.number != run::kNoBlock) return "N" + std::to_string(b.number);
    if (b.line == 0) return "(no block)";
    return "line " + std::to_string(b.line);
}

std::string describe(const OracleReport& report) {
    std::string s;
    char buf[256];
    for (const OracleGouge& g : report.gouges) {
        std::snprintf(buf, sizeof buf,
                      "  gouge: path %s cuts wall %s by %.6f mm (distance %.6f, radius %.4f) "
                      "near (%.4f, %.4f)\n",
                      block_name(g.path_block).c_str(), block_name(g.wall_block).c_str(), g.depth,
                      g.distance, g.radius, g.wall_point.x, g.wall_point.y);
        s += buf;
    }
    for (const OracleBuried& b : report.buried) {
        std::snprintf(buf, sizeof buf,
                      "  buried: path %s takes %.6f mm^2 of the part without coming within its "
                      "radius %.4f of a wall\n",
                      block_name(b.path_block).c_str(), b.area, b.radius);
        s += buf;
    }
    if (s.empty()) s = "  (none)\n";
    return s;
}

std::size_t points_per_circle(double r) {
    if (r <= StockOracle::kChordError) return 8;
    const double step = 2 * std::acos(1 - StockOracle::kChordError / r);
    return std::max<std::size_t>(8, static_cast<std::size_t>(std::ceil(2 * kPi / step)));
}

std::vector<Pt> densify(const WallElement& e) {
    if (!e.arc) return {e.start, e.end};
    return densify_arc(e.start, e.end, e.centre, e.ccw);
}

std::vector<Pt> densify(const run::PathSegment& s, int plane) {
    const run::PlaneAxes a = run::plane_axes(plane);
    const Pt start{s.start[a.first], s.start[a.second]};
    const Pt end{s.end[a.first], s.end[a.second]};
    if (s.kind != run::SegmentKind::kArc) return {start, end};
    return densify_arc(start, end, {s.center[a.first], s.center[a.second]}, s.ccw);
}

PolylineDistance least_distance(std::span<const Pt> a, std::span<const Pt> b) {
    const ChordTree ta(std::vector<Pt>(a.begin(), a.end()));
    const ChordTree tb(std::vector<Pt>(b.begin(), b.end()));
    PolylineDistance best{kInf, {}, {}};
    ta.distance(tb, best);
    return best;
}

struct StockOracle::Impl {
    int plane = 17;
    double top = 0.0;
    BMulti part;
    std::vector<Wall> walls;
};

StockOracle::StockOracle(const DesignPart& part) : impl_(std::make_unique<Impl>()) {
    impl_->plane = part.plane;
    impl_->top = part.top;
    struct Loop {
        std::vector<Pt> ring;
        bool material_inside;
        BPolygon polygon;
        int depth = 0;
    };
    std::vector<Loop> loops;
    for (std::size_t li = 0; li < part.loops.size(); ++li) {
        const DesignLoop& loop = part.loops[li];
        const std::string where = "design loop " + std::to_string(li);
        if (loop.elements.empty()) throw std::invalid_argument(where + " has no elements");
        std::vector<Pt> ring;
        for (std::size_t ei = 0; ei < loop.elements.size(); ++ei) {
            const WallElement& e = loop.elements[ei];
            const WallElement& before =
                loop.elements[(ei + loop.elements.size() - 1) % loop.elements.size()];
            if (dist(before.end, e.start) > kSamePoint)
                throw std::invalid_argument(where + ": element " + std::to_string(ei) +
                                            " does not start where the one before it ends");
            if (e.material != loop.elements.front().material)
                throw std::invalid_argument(where + ": element " + std::to_string(ei) +
                                            " has the material on the other side");
            std::vector<Pt> pts = densify(e);
            ring.insert(ring.end(), pts.begin() + (ring.empty() ? 0 : 1), pts.end());
            impl_->walls.push_back({e, ChordTree(std::move(pts))});
        }
        if (ring.size() < 4) throw std::invalid_argument(where + " has fewer than three corners");
        ring.back() = ring.front();  // closed exactly
        const double area = signed_area(ring);
        if (std::abs(area) <= kSamePoint) throw std::invalid_argument(where + " encloses no area");
        const bool ccw = area > 0;
        const bool left = loop.elements.front().material == MaterialSide::kLeft;
        BPolygon polygon = polygon_of(ring);
        std::string why;
        if (!bg::is_valid(polygon, why))
            throw std::invalid_argument(where + " is not a simple closed curve: " + why);
        loops.push_back({ring, ccw == left, std::move(polygon)});
    }
    for (std::size_t i = 0; i < loops.size(); ++i)
        for (std::size_t j = 0; j < loops.size(); ++j)
            if (i != j && bg::within(bp(loops[i].ring.front()), loops[j].polygon)) ++loops[i].depth;
    std::vector<std::size_t> order(loops.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return loops[a].depth < loops[b].depth; });
    for (const std::size_t i : order) {
        const Loop& l = loops[i];
        // Material inside at even depth (a part, an island in a pocket), outside at odd.
        if (l.material_inside != (l.depth % 2 == 0))
            throw std::invalid_argument(
                "design loop " + std::to_string(i) +
                (l.material_inside ? ": material inside, but it lies in material"
                                   : ": material outside, but nothing around it is material"));
        BMulti next;
        if (l.material_inside)
            bg::union_(impl_->part, l.polygon, next);
        else
            bg::difference(impl_->part, l.polygon, next);
        impl_->part = std::move(next);
    }
}

StockOracle::~StockOracle() = default;
StockOracle::StockOracle(StockOracle&&) noexcept = default;
StockOracle& StockOracle::operator=(StockOracle&&) noexcept = default;

double StockOracle::area() const {
    return bg::area(impl_->part);
}

bool StockOracle::contains(const Pt& p) const {
    return bg::covered_by(bp(p), impl_->part);
}

namespace {

// The cutting segments (below the part's top) grouped by block and radius, in the order the
// blocks first ran: their plane segments and their centre paths as connected runs of points.
std::vector<PathBlock> cutting_blocks(std::span<const run::PathSegment> path,
                                      std::span<const double> radius, int plane, double top) {
    const run::PlaneAxes axes = run::plane_axes(plane);
    std::vector<PathBlock> blocks;
    for (std::size_t i = 0; i < path.size(); ++i) {
        const run::PathSegment& s = path[i];
        const double low = std::min(s.start[axes.third], s.end[axes.third]);
        if (low >= top - kSamePoint) continue;  // at or above the part's top
        if (!(radius[i] >= 0.0) || !std::isfinite(radius[i]))
            throw std::invalid_argument("StockOracle::run: a tool radius that is not a length");
        auto it = std::find_if(blocks.begin(), blocks.end(), [&](const PathBlock& b) {
            return same_block(b.block, s.block) && b.radius == radius[i];
        });
        if (it == blocks.end()) {
            blocks.push_back({s.block, radius[i], {}, {}});
            it = blocks.end() - 1;
        }
        PlaneSegment ps;
        ps.arc = s.kind == run::SegmentKind::kArc;
        ps.start = {s.start[axes.first], s.start[axes.second]};
        ps.end = {s.end[axes.first], s.end[axes.second]};
        ps.centre = {s.center[axes.first], s.center[axes.second]};
        ps.ccw = s.ccw;
        it->segments.push_back(ps);
        std::vector<Pt> pts = densify(s, plane);
        if (!it->runs.empty() && dist(it->runs.back().back(), pts.front()) <= kSamePoint)
            it->runs.back().insert(it->runs.back().end(), pts.begin() + 1, pts.end());
        else
            it->runs.push_back(std::move(pts));
    }
    return blocks;
}

// The walls block `b` comes within its radius of, and how deep (the least distance between its
// centre path and each wall element near its box), one gouge per wall block, the deepest;
// `least` gets the least distance to any wall, and the report the deepest touch within the
// tolerance.
std::vector<OracleGouge> walls_cut(const PathBlock& b, const std::vector<Wall>& walls,
                                   double& least, OracleReport& report) {
    Box2 reach;
    std::vector<ChordTree> runs;
    for (const std::vector<Pt>& run : b.runs) {
        runs.emplace_back(run);
        reach.add(runs.back().box());
    }
    reach.lx -= b.radius;
    reach.ly -= b.radius;
    reach.hx += b.radius;
    reach.hy += b.radius;
    least = kInf;
    std::vector<OracleGouge> cut;
    for (const Wall& w : walls) {
        if (reach.distance(w.chords.box()) > 0.0) continue;
        PolylineDistance best{b.radius, {}, {}};  // nothing beyond r matters
        for (const ChordTree& t : runs) t.distance(w.chords, best);
        least = std::min(least, best.distance);
        if (best.distance >= b.radius) continue;
        const double depth = b.radius - best.distance;
        if (depth <= StockOracle::kPathTolerance) {
            if (depth > report.deepest_intact) {
                report.deepest_intact = depth;
                report.deepest_intact_pair = {b.block,  w.element.block, depth, best.distance,
                                              b.radius, best.a,          best.b};
            }
            continue;
        }
        auto same = std::find_if(cut.begin(), cut.end(), [&](const OracleGouge& g) {
            return same_block(g.wall_block, w.element.block);
        });
        const OracleGouge g{b.block,  w.element.block, depth, best.distance,
                            b.radius, best.a,          best.b};
        if (same == cut.end())
            cut.push_back(g);
        else if (depth > same->depth)
            *same = g;
    }
    return cut;
}

// The area block `b` sweeps and the part of it it takes from `part`, into `ob`; a block that
// runs inside the material without cutting a wall goes to the report's buried blocks.
void measure_taken(const PathBlock& b, const BMulti& part, bool cuts, OracleBlock& ob,
                   OracleReport& report) {
    std::vector<BPolygon> pieces;
    for (const PlaneSegment& seg : b.segments) sweep_pieces(seg, b.radius, pieces);
    BMulti swept;
    for (const BPolygon& piece : pieces) {
        BMulti next;
        bg::union_(swept, piece, next);
        swept = std::move(next);
    }
    BMulti taken;
    bg::intersection(swept, part, taken);
    ob.swept_area = bg::area(swept);
    ob.taken_area = bg::area(taken);
    ob.measured = true;
    if (!(ob.swept_area >= 0.99 * kPi * b.radius * b.radius))
        throw std::logic_error("StockOracle: the swept area of " + block_name(b.block) +
                               " is smaller than the tool (" + std::to_string(ob.swept_area) +
                               " mm^2)");
    if (cuts && !(ob.taken_area > 0.0))
        throw std::logic_error("StockOracle: " + block_name(b.block) +
                               " comes deeper than the tolerance into a wall but its swept "
                               "area takes nothing of the part");
    // No wall cut, but the swept area holds more of the part than a touch within the
    // tolerance all round its outline could: the block runs inside the material.
    if (!cuts && ob.taken_area > bg::perimeter(swept) * 1.2 * StockOracle::kPathTolerance)
        report.buried.push_back({b.block, ob.taken_area, b.radius});
}

}  // namespace

OracleReport StockOracle::run(std::span<const run::PathSegment> path,
                              std::span<const double> radius, const OracleOptions& options) const {
    if (path.size() != radius.size())
        throw std::invalid_argument("StockOracle::run: one radius per segment");
    OracleReport report;
    for (const PathBlock& b : cutting_blocks(path, radius, impl_->plane, impl_->top)) {
        OracleBlock ob{b.block, b.radius, 0.0, 0.0, false};
        if (b.radius <= 0.0) {  // a point tool sweeps no area
            report.blocks.push_back(ob);
            continue;
        }
        double least = kInf;
        const std::vector<OracleGouge> cut = walls_cut(b, impl_->walls, least, report);
        // The area it takes from the part. A block whose centre path keeps at least r less the
        // polygons' error from every wall, and starts outside the part, stays outside it (each
        // run is connected and crosses no wall): it takes nothing the polygons could tell from
        // their own error, and is not measured unless asked.
        bool inside = false;
        for (const std::vector<Pt>& run : b.runs) inside |= contains(run.front());
        if (options.measure_every_block || inside || least < b.radius - 2 * kChordError)
            measure_taken(b, impl_->part, !cut.empty(), ob, report);
        report.blocks.push_back(ob);
        report.gouges.insert(report.gouges.end(), cut.begin(), cut.end());
    }
    return report;
}

}  // namespace apci::test
