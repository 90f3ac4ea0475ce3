// SPDX-License-Identifier: MIT
#include "apci/run/self_approach.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>

#include "apci/run/plane_distance.h"
#include "chunked_array.h"
#include "held_calls.h"
#include "probe_table.h"
#include "wall_model.h"

namespace apci::run {
using detail::cell_key;
namespace {

using Vec2 = Eigen::Vector2d;
// Start and end of an arc closer than this: a full circle (as in path.h).
constexpr double kFullCircle = kSamePointTolerance;
// The most distance evaluations one pair may take (the refinement stops there).
constexpr int kMaxEvaluations = 4096;
// How much farther than the threshold a pair must be proved apart for the search to be skipped:
// far more than the rounding of a distance computed in either way.
constexpr double kApartMargin = 1e-7;

}  // namespace

// A line or arc in the plane's coordinates (first, second): the element the distances take
// (an arc runs from start to end about centre, its radius changing linearly with the angle, as
// the board runs it; its sweep signed, magnitude in (0, 2 pi]; its radii and start angle
// computed once for the shape, set_arc_terms, rather than at every point of a search), with what
// the check asks of it besides.
struct detail::Shape : plane::Parametric {
    double length = 0.0;
    // A box holding every point of it (corners lo, hi).
    Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();
    // Its lowest and highest coordinate on the plane's third axis (the tool's: Z under G17).
    double low = 0.0, high = 0.0;
};

namespace {

using detail::Shape;

// The arc terms of e (radii, start angle) from its start, end and centre.
void set_arc_terms(Shape& e) {
    const Vec2 u0 = e.start - e.centre;
    e.r0 = u0.norm();
    e.r1 = (e.end - e.centre).norm();
    e.phi0 = std::atan2(u0.y(), u0.x());
}

// Widens e's box (its ends) to the arc: where the turn passes an axis direction, out to the
// larger radius there (at every one, for an arc with an end at its centre). Elsewhere a
// coordinate is largest at an end; an arc whose radius changes by d over the turn lies within d
// of the circle through that end, so the box grows by d (and a rounding's width, which also
// covers an axis direction within rounding of an end).
void add_arc_to_box(Shape& e) {
    const double rmax = std::max(e.r0, e.r1);
    const bool ends = e.r0 > 0.0 && e.r1 > 0.0;
    const Vec2 from = ends ? Vec2((e.start - e.centre) / e.r0) : Vec2::Zero();
    const Vec2 to = ends ? Vec2((e.end - e.centre) / e.r1) : Vec2::Zero();
    for (const Vec2& axis : {Vec2(1, 0), Vec2(0, 1), Vec2(-1, 0), Vec2(0, -1)}) {
        if (ends && !plane::within_turn(from, to, e.sweep, axis)) continue;
        const Vec2 p = e.centre + rmax * axis;
        e.lo = e.lo.cwiseMin(p);
        e.hi = e.hi.cwiseMax(p);
    }
    const double pad = std::abs(e.r1 - e.r0) + 1e-9 * (1.0 + e.centre.cwiseAbs().maxCoeff() + rmax);
    e.lo.array() -= pad;
    e.hi.array() += pad;
}

// plane::arc_element(start, end, centre, s.ccw) of an arc segment s in the plane: with the
// sweep measure() gave s where that is arc_element's (an executed segment whose chord exceeds
// 2e-9 on an axis: neither then takes it for a full circle, and both compute geom::arc_sweep of
// the same radii), else all of it made here.
plane::Parametric measured_arc(const PathSegment& s, const Vec2& start, const Vec2& end,
                               const Vec2& centre) {
    const Vec2 chord = end - start;
    const bool long_chord = std::abs(chord.x()) > 2.0 * kSamePointTolerance ||
                            std::abs(chord.y()) > 2.0 * kSamePointTolerance;
    if (std::isnan(s.sweep) || !long_chord) return plane::arc_element(start, end, centre, s.ccw);
    const Vec2 u0 = start - centre;
    return plane::arc_element(start, end, centre, s.ccw, s.sweep, std::atan2(u0.y(), u0.x()));
}

Shape shape_of(const PathSegment& s, int plane) {
    const PlaneAxes a = plane_axes(plane);
    Shape out;
    out.start = {s.start[a.first], s.start[a.second]};
    out.end = {s.end[a.first], s.end[a.second]};
    const bool arc = s.kind == SegmentKind::kArc && s.plane == plane;
    out.lo = out.start.cwiseMin(out.end);
    out.hi = out.start.cwiseMax(out.end);
    out.low = std::min(s.start[a.third], s.end[a.third]);
    out.high = std::max(s.start[a.third], s.end[a.third]);
    if (!arc) {
        out.length = (out.end - out.start).norm();
        return out;
    }
    const Vec2 centre(s.center[a.first], s.center[a.second]);
    static_cast<plane::Parametric&>(out) = measured_arc(s, out.start, out.end, centre);
    out.length = std::abs(out.sweep) * 0.5 * (out.r0 + out.r1);
    add_arc_to_box(out);
    return out;
}

// Whether a programmed move moves in the plane (a plunge in Z under G17, G41 G1 to the point
// the tool stands on, does not): the wall model's elements, and a stretch's first is its
// approach.
bool moves_in(const PathSegment& s, int plane) {
    const PlaneAxes a = plane_axes(plane);
    return (s.kind == SegmentKind::kArc && s.plane == plane) ||
           std::hypot(s.end[a.first] - s.start[a.first], s.end[a.second] - s.start[a.second]) >
               kFullCircle;
}

// A move as the wall model takes it, in the axes of `plane`: an arc's terms those of `e` where
// given (its shape made already), else worked out by the model.
detail::PlaneMove plane_move(const PathSegment& s, int plane, const Shape* e) {
    const PlaneAxes a = plane_axes(plane);
    detail::PlaneMove m;
    m.start = {s.start[a.first], s.start[a.second]};
    m.end = {s.end[a.first], s.end[a.second]};
    m.arc = s.kind == SegmentKind::kArc && s.plane == plane;
    m.ccw = s.ccw;
    m.centre = {s.center[a.first], s.center[a.second]};
    m.terms = e != nullptr;
    m.sweep = e != nullptr ? e->sweep : 0.0;
    m.phi0 = e != nullptr ? e->phi0 : 0.0;
    m.low = std::min(s.start[a.third], s.end[a.third]);
    m.high = std::max(s.start[a.third], s.end[a.third]);
    return m;
}

// An executed segment of a programmed element (the queue moves on to it), and one of those the
// check holds to the elements (not the departure of G237, the board's step back onto the
// programmed end; the departure of a block of its own is, departs_head()).
bool of_element(Role r) {
    return r == Role::kContour || r == Role::kTransition || r == Role::kApproach ||
           r == Role::kDeparture;
}
// A departure of a block with no element of its own (under G139 the G40 block's move, or the
// move after a lone G40; PendingQueue::find() finds none, `at` == `waiting`) leaves the element
// at the queue's head, the last its stretch executed, from its offset end, and is held to the
// elements (a lead-out through the part is a gouge).
bool departs_head(const PathSegment& s, std::size_t at, std::size_t waiting) {
    return s.role == Role::kDeparture && at == waiting && waiting > 0;
}
bool held_to_elements(Role r) {
    return r == Role::kContour || r == Role::kTransition || r == Role::kApproach;
}

// A float no larger (down) or no smaller (up) than v: a box rounded outward still holds every
// point it held (beyond float's range: infinite).
// The float next to f towards minus infinity, f finite and not 0 (a step of its bits: down
// from a positive one, up from a negative one); from 0 the least negative float.
float float_below(float f) {
    if (f == 0.0f) return -std::numeric_limits<float>::denorm_min();
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, sizeof bits);
    bits = f > 0.0f ? bits - 1 : bits + 1;
    std::memcpy(&f, &bits, sizeof bits);
    return f;
}
float down(double v) {
    if (!(std::abs(v) < 1e38)) return v > 0.0 ? 1e38f : -INFINITY;
    const auto f = static_cast<float>(v);
    return static_cast<double>(f) > v ? float_below(f) : f;
}
float up(double v) {
    return -down(-v);
}

// What the cheap tests take of a shape: its box, and its range on the plane's third axis.
struct Extent {
    Vec2 lo, hi;
    double low, high;
};
Extent extent_of(const Shape& e) {
    return {e.lo, e.hi, e.low, e.high};
}

// The least distance between the boxes of a and b: at most that of any of their points.
double box_distance(const Extent& a, const Extent& b) {
    const Vec2 gap = (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(0.0);
    return gap.norm();
}

// False where a path cannot come closer to an element than the threshold, by the cheap tests:
// the depth rule (the element wholly below the tool's tip on all of the path: the tool does not
// reach down to it, it stands on the plane's positive side, its axis the third) and the boxes.
bool near_enough(const Extent& path, const Extent& contour, double threshold) {
    if (contour.high < path.low - SelfApproachCheck::kTolerance) return false;
    return box_distance(path, contour) < threshold + kApartMargin;
}

}  // namespace

// A shape as the grid keeps it, by the hundred thousand: its ends and an arc's centre and
// sense packed (plane::Parametric's vectors are aligned to 16 bytes), an arc's start angle and
// sweep as shape_of() computed them (the two atan2 of plane::arc_element, not made again for
// every pair), its box, range and length in floats rounded outward (the box and range are
// filters, the length counts samples: rounded up, never fewer). shape() gives the element back
// exactly, the box and range no smaller.
namespace detail {
struct StoredShape {
    double start[2], end[2], centre[2];
    double phi0, sweep;  // an arc's (0 for a line)
    float lo[2], hi[2], low, high, length;
    bool arc, ccw;

    explicit StoredShape(const Shape& e)
        : start{e.start.x(), e.start.y()},
          end{e.end.x(), e.end.y()},
          centre{e.centre.x(), e.centre.y()},
          phi0(e.phi0),
          sweep(e.sweep),
          lo{down(e.lo.x()), down(e.lo.y())},
          hi{up(e.hi.x()), up(e.hi.y())},
          low(down(e.low)),
          high(up(e.high)),
          length(up(e.length)),
          arc(is_arc(e)),
          ccw(e.sweep > 0.0) {}
    Extent extent() const {
        return {Vec2(lo[0], lo[1]), Vec2(hi[0], hi[1]), static_cast<double>(low),
                static_cast<double>(high)};
    }
    Shape shape() const {
        Shape e;
        const Vec2 a(start[0], start[1]), b(end[0], end[1]);
        static_cast<plane::Parametric&>(e) =
            arc ? plane::arc_element(a, b, Vec2(centre[0], centre[1]), ccw, sweep, phi0)
                : plane::line_element(a, b);
        const Extent x = extent();
        e.lo = x.lo, e.hi = x.hi, e.low = x.low, e.high = x.high;
        e.length = static_cast<double>(length);
        return e;
    }
};
}  // namespace detail

namespace {

using detail::StoredShape;
using plane::distance_to;
using plane::point_at;

using plane::Nearest;

// The least distance of `contour` from the part [a, b] of `path`, where it has one minimum
// (golden-section search, to 1e-11 mm along the path).
Nearest polish(const Shape& path, const Shape& contour, double a, double b, int& evaluations) {
    constexpr double kInvPhi = 0.6180339887498949;
    const auto at = [&](double t) {
        ++evaluations;
        return distance_to(contour, point_at(path, t));
    };
    double x1 = b - kInvPhi * (b - a), x2 = a + kInvPhi * (b - a);
    double f1 = at(x1), f2 = at(x2);
    for (int i = 0; i < 100 && (b - a) * path.length > 1e-11; ++i) {
        if (f1 <= f2) {
            b = x2, x2 = x1, f2 = f1;
            x1 = b - kInvPhi * (b - a), f1 = at(x1);
        } else {
            a = x1, x1 = x2, f1 = f2;
            x2 = a + kInvPhi * (b - a), f2 = at(x2);
        }
    }
    return f1 <= f2 ? Nearest{f1, x1} : Nearest{f2, x2};
}

// The least distance from `path` to `contour` when it is below `threshold` (within 1e-9 mm, or
// as near as kMaxRefinement evaluations get), else some value >= threshold. A branch and bound
// along the path: the distance is 1-Lipschitz along it, so nothing on a span of length len
// between points at d0 and d1 is closer than (d0 + d1 - len) / 2; spans are split nearest
// bound first until every bound is at least the threshold (nothing is near) or at least the
// least distance found. Once a point below the threshold is found, the minimum near it is
// polished, so the search ends at the minimum rather than at the first point below the
// threshold.
Nearest least_distance(const Shape& path, const Shape& contour, double threshold) {
    // Two lines: exactly, at once (along parallel lines the search below would refine a flat
    // distance to its evaluation cap, 32,768 distances, for every such pair).
    if (!is_arc(path) && !is_arc(contour)) return plane::lines_nearest(path, contour);
    constexpr double kExact = 1e-9;          // mm: the least distance to this
    constexpr int kMaxRefinement = 1 << 15;  // evaluations once a point below is found
    struct Span {
        double t0, t1, d0, d1, bound;
        bool operator<(const Span& o) const { return bound > o.bound; }  // heap: least first
    };
    const auto at = [&](double t) { return distance_to(contour, point_at(path, t)); };
    const double d_start = at(0.0), d_end = at(1.0);
    Nearest best = d_start <= d_end ? Nearest{d_start, 0.0} : Nearest{d_end, 1.0};
    int evaluations = 2;
    const auto span = [&](double t0, double t1, double d0, double d1) {
        return Span{t0, t1, d0, d1, 0.5 * (d0 + d1 - path.length * (t1 - t0))};
    };
    const auto improve = [&](const Nearest& n, double a, double b) {
        if (n.distance >= best.distance) return;
        best = n;
        if (best.distance >= threshold) return;
        const Nearest p = polish(path, contour, a, b, evaluations);
        if (p.distance < best.distance) best = p;
    };
    if (best.distance < threshold)
        improve(best, best.t == 0.0 ? 0.0 : 0.5, best.t == 0.0 ? 0.5 : 1.0);  // at an end
    // The spans' memory is kept by the thread from one search to the next (a search starts
    // with it empty: only the allocation is saved).
    thread_local std::vector<Span> heap;
    heap.clear();
    heap.push_back(span(0.0, 1.0, d_start, d_end));
    while (!heap.empty()) {
        const double limit = best.distance < threshold ? best.distance - kExact : threshold;
        if (evaluations >= (best.distance < threshold ? kMaxRefinement : kMaxEvaluations)) break;
        std::pop_heap(heap.begin(), heap.end());
        const Span s = heap.back();
        heap.pop_back();
        if (s.bound >= limit) break;  // so is every other span's
        if (path.length * (s.t1 - s.t0) < kExact) continue;
        const double tm = 0.5 * (s.t0 + s.t1);
        const double dm = at(tm);
        ++evaluations;
        improve(Nearest{dm, tm}, s.t0, s.t1);
        heap.push_back(span(s.t0, tm, s.d0, dm));
        std::push_heap(heap.begin(), heap.end());
        heap.push_back(span(tm, s.t1, dm, s.d1));
        std::push_heap(heap.begin(), heap.end());
    }
    return best;
}

std::uint64_t bits_of(double v) {
    const double same = v + 0.0;  // -0 + 0 is +0 (rounding to nearest); any other v stays v
    std::uint64_t u = 0;
    std::memcpy(&u, &same, sizeof u);
    return u;  // -0 and +0 alike
}

// h and x mixed through SplitMix64's finaliser: every bit of the result depends on every bit of
// both (a bare multiply after the xor let coordinates 0.5 mm apart in a zigzag collide, one
// pair in 30,000).
std::uint64_t mix(std::uint64_t h, std::uint64_t x) {
    std::uint64_t z = h ^ x;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

// The geometry of an element in the plane (its ends, an arc's centre and sense) and the tool
// radius, as one 64-bit hash of their exact values: the same geometry is checked once (a
// program that repeats a contour repeats its numbers; a hash collision, about one in 2^64 per
// pair, would skip one check).
std::uint64_t key_from(bool arc, bool ccw, const double (&start)[2], const double (&end)[2],
                       const double (&centre)[2], double r) {
    std::uint64_t h = arc ? (ccw ? 3 : 2) : 1;
    h = mix(h, bits_of(start[0]));
    h = mix(h, bits_of(start[1]));
    h = mix(h, bits_of(end[0]));
    h = mix(h, bits_of(end[1]));
    if (arc) {
        h = mix(h, bits_of(centre[0]));
        h = mix(h, bits_of(centre[1]));
    }
    return mix(h, bits_of(r));
}

// key_from of a segment in the axes of `plane` (an arc in another plane is a line in this one,
// as shape_of() takes it), and of an item as the grid keeps it: the same for the same geometry.
std::uint64_t key_of(const PathSegment& s, int plane, double r) {
    const PlaneAxes a = plane_axes(plane);
    const double start[2] = {s.start[a.first], s.start[a.second]};
    const double end[2] = {s.end[a.first], s.end[a.second]};
    const double centre[2] = {s.center[a.first], s.center[a.second]};
    return key_from(s.kind == SegmentKind::kArc && s.plane == plane, s.ccw, start, end, centre, r);
}
std::uint64_t key_of(const StoredShape& e, double r) {
    return key_from(e.arc, e.ccw, e.start, e.end, e.centre, r);
}

// The same block: by N number when both have one (executed segments carry only the N number
// of a block that has one), else by source line.
bool same_block(const BlockRef& a, const BlockRef& b) {
    if (a.number != kNoBlock || b.number != kNoBlock) return a.number == b.number;
    return a.line == b.line;
}

std::string block_name(const BlockRef& b) {
    if (b.number != kNoBlock) return fmt::format("N{}", b.number);
    return fmt::format("line {}", b.line);
}

}  // namespace

std::string describe(const SelfApproachFinding& f) {
    // Why it comes that near, and what to change.
    const char* why = "the contour comes back near itself there, which no corner rule sees";
    const char* change = "use a smaller tool, or give the contour more room there";
    switch (f.kind) {
        case SelfApproachKind::kContour:
            break;
        case SelfApproachKind::kFeatures:
            why = "two features come that close there";
            change = "place them farther apart, or use a smaller tool";
            break;
        case SelfApproachKind::kLeadIn:
            why = "the lead-in runs into the part there";
            change = "start the lead-in clear of the part";
            break;
        case SelfApproachKind::kLeadOut:
            why = "the lead-out runs into the part there";
            change = "end the lead-out clear of the part";
            break;
    }
    return fmt::format(
        "the tool path of {} comes within {:.4f} mm of the contour at {} (tool radius {:.4f} mm): "
        "{}; the path cuts {:.4f} mm into it ({})",
        block_name(f.path_block), f.distance, block_name(f.contour_block), f.radius, why,
        f.radius - f.distance, change);
}

struct SelfApproachCheck::GridItem {
    GridItem(const Shape& e, const BlockRef& b, std::uint64_t i, std::uint64_t s, double radius)
        : shape(e), block(b), index(i), stretch(s), r(radius) {}
    StoredShape shape;
    BlockRef block;
    std::uint64_t index = 0;
    std::uint64_t stretch = 0;
    double r = 0.0;  // the tool's, of a path (the key of its geometry is key_of(shape, r)); 0
                     // for an element
    // The element's loop (WallModel::kNoLoop for none), once its role is known: role_of().
    std::uint64_t loop = detail::WallModel::kNoLoop;
    std::uint32_t entries = 0;  // cells it is listed in (set by index)
    bool sampled = false;       // listed by samples, not by its box (set by index)
    bool transition = false;
    // Contour elements: the path must keep r from it. Not the first and the last element
    // of a stretch: they are its approach and departure in the program's own terms.
    bool protect = true;
    // Paths: the approach (from where the tool stands onto the compensated path; the entry
    // point it leads to is approach_entries_).
    bool approach = false;
    // What the wall model said of its element once it was placed (kUndecided until then):
    // role_of(), placed_of().
    detail::WallRole role = detail::WallRole::kUndecided;
};

struct SelfApproachCheck::Grid {
    using Item = GridItem;
    // Items kept in order, the oldest first: `first` is the number (counted over the plane's
    // whole run) of items[0].
    struct List {
        explicit List(std::size_t i) : id(i) {}
        std::size_t id;  // its list in `cells`
        std::vector<Item> items;
        std::uint64_t first = 0;
        detail::KeySet keys;
        std::size_t entries = 0;  // of its items
        std::size_t sampled = 0;  // items listed by samples (the others by their box)
        std::uint64_t next() const { return first + items.size(); }
        // The item numbered `id`, or null where it was let go.
        Item* at(std::uint64_t id) {
            return id >= first && id < next() ? &items[static_cast<std::size_t>(id - first)]
                                              : nullptr;
        }
    };
    double cell = 0.0;  // set by the plane's first stretch, made larger by a larger tool (begin)
    // The lengths of the plane's first kSizing elements: where most are longer than the cells,
    // the cells are made twice the median (size_by()).
    static constexpr std::size_t kSizing = 256;
    std::vector<double> first_lengths;
    bool sized = false;
    // Once the first kSizing elements are in: cells at least twice their median length, so
    // that most elements are listed in the few cells of their box rather than by samples
    // (a program of long elements, parts of several centimetres milled with a small tool,
    // would list each element in dozens of cells and look each path up in as many).
    void size_by(double length) {
        if (sized) return;
        first_lengths.push_back(length);
        if (first_lengths.size() < kSizing) return;
        sized = true;
        auto mid = first_lengths.begin() + static_cast<std::ptrdiff_t>(kSizing / 2);
        std::nth_element(first_lengths.begin(), mid, first_lengths.end());
        const double median = *mid;
        first_lengths = {};
        if (median > cell) {
            cell = 2.0 * median;
            reindex();
        }
    }
    double max_r = 0.0;  // the largest tool radius of its paths
    std::size_t window = kWindow;
    std::size_t entry_budget = kEntryBudget;
    bool all = false;  // near() answers every item (Candidates::kAll)
    List contour{0}, path{1};
    // The cells of both lists: a cell is looked up once for a path's candidates and its own
    // entry (near_adding).
    detail::CellIndex<2> cells;
    bool truncated = false;       // items were let go
    std::uint64_t kept_from = 0;  // the elements numbered below it were let go
    BlockRef truncated_at{};      // the block whose element or path let the first go
    int plane = 17;

    std::int64_t index_of(double v) const { return detail::floor_index(v / cell); }

    // The samples of e are n + 1 points, from its start to its end.
    int samples(double length) const {
        return std::max(1, static_cast<int>(std::ceil(length / (0.5 * cell))));
    }
    int samples(const Item& x) const { return samples(static_cast<double>(x.shape.length)); }
    template <typename F>
    void for_samples(const Shape& e, F&& f) const {
        const int n = samples(e.length);
        for (int i = 0; i <= n; ++i) f(point_at(e, static_cast<double>(i) / n));
    }

    // The cells a box widened by `reach` touches: columns i0..i1, rows j0..j1.
    struct CellRange {
        std::int64_t i0, i1, j0, j1;
        std::int64_t count() const { return (i1 - i0 + 1) * (j1 - j0 + 1); }
    };
    CellRange cells_of(const Shape& e, double reach) const {
        return {index_of(e.lo.x() - reach), index_of(e.hi.x() + reach), index_of(e.lo.y() - reach),
                index_of(e.hi.y() + reach)};
    }

    // The cells of an item's box (its stored, outward box).
    CellRange cells_of(const Item& item) const {
        const Extent x = item.shape.extent();
        return {index_of(x.lo.x()), index_of(x.hi.x()), index_of(x.lo.y()), index_of(x.hi.y())};
    }
    // A short element is listed in every cell of its box (its samples lie in it), no more
    // than kBoxCells; a longer one in the cells of its samples.
    static constexpr std::int64_t kBoxCells = 4;
    // Calls add(i, j) for each cell the item is listed in (a cell of samples once for a run of
    // samples in it), and returns how many entries it takes.
    template <typename Add>
    std::uint32_t listed_cells(const Item& x, Add&& add) const {
        return listed_cells(x, cells_of(x), add);
    }
    // The same, the cells of x's box given.
    template <typename Add>
    std::uint32_t listed_cells(const Item& x, const CellRange& box, Add&& add) const {
        std::uint32_t n = 0;
        if (box.count() <= kBoxCells) {
            for (std::int64_t i = box.i0; i <= box.i1; ++i)
                for (std::int64_t j = box.j0; j <= box.j1; ++j, ++n) add(i, j);
            return n;
        }
        std::uint64_t last = 0;
        for_samples(x.shape.shape(), [&](const Vec2& p) {
            const std::int64_t i = index_of(p.x()), j = index_of(p.y());
            const std::uint64_t key = cell_key(i, j);
            if (n == 0 || key != last) add(i, j);
            last = key;
            ++n;
        });
        return n;
    }
    // Counts the entries of x, which joins `list`, and whether it is listed by samples: as many
    // as the cells of its box (`box`), or its samples.
    void count(List& list, Item& x, const CellRange& box) {
        x.sampled = box.count() > kBoxCells;
        if (x.sampled) ++list.sampled;
        x.entries = x.sampled ? static_cast<std::uint32_t>(samples(x) + 1)
                              : static_cast<std::uint32_t>(box.count());
        list.entries += x.entries;
    }
    // Lists the item at `at` in its cells (where `into_cells`; an item of a stretch kept out
    // of them is only counted) and counts its entries.
    void index(List& list, std::size_t at, bool into_cells = true) {
        Item& x = list.items[at];
        const CellRange box = cells_of(x);
        count(list, x, box);
        if (!into_cells) return;
        const auto item = static_cast<std::uint32_t>(at);
        listed_cells(x, box, [&](std::int64_t i, std::int64_t j) {
            cells.add(list.id, cell_key(i, j), item);
        });
    }

    // The most items `list` keeps: `window` elements; their paths (an element's offset and the
    // transitions at its corners, a few) at most kPathsPerElement times as many.
    static constexpr std::size_t kPathsPerElement = 3;
    std::size_t most(const List& list) const {
        return &list == &contour ? window : kPathsPerElement * window;
    }
    // The element from which on `list` holds at most most(list) items and entry_budget entries
    // (at least its latest item).
    std::uint64_t first_kept(const List& list) const {
        if (list.items.empty()) return 0;
        std::size_t at = list.items.size() - 1;
        std::size_t entries = list.items[at].entries;
        while (at > 0 && list.items.size() - at < most(list) &&
               entries + list.items[at - 1].entries <= entry_budget)
            entries += list.items[--at].entries;
        return list.items[at].index;
    }

    // Adds an item (its geometry's key is in list.keys already). At twice most(list) items or
    // twice entry_budget entries in either list, the items of the oldest elements are let go
    // from both, so that each holds at most most() items and entry_budget entries. An element's
    // contour and its paths go together: a repeat of geometry let go is checked afresh against
    // what remains.
    void add(List& list, const Item& item) {
        const bool into_cells = !lazy || enter(list, item);
        list.items.push_back(item);
        index(list, list.items.size() - 1, into_cells);
        bound(list);
    }
    // After an item was added to `list`: the oldest let go where it holds too many.
    void bound(List& list) {
        if (list.items.size() < 2 * most(list) && list.entries < 2 * entry_budget) return;
        if (!truncated) truncated_at = list.items.back().block;
        keep_from(std::max(first_kept(contour), first_kept(path)));
    }

    void keep_from(std::uint64_t element) {
        truncated = true;
        kept_from = element;
        for (List* l : {&contour, &path}) {
            const auto kept = std::find_if(l->items.begin(), l->items.end(),
                                           [&](const Item& i) { return i.index >= element; });
            l->first += static_cast<std::uint64_t>(kept - l->items.begin());
            l->items.erase(l->items.begin(), kept);
            l->keys.clear();
            for (const Item& i : l->items) l->keys.insert(key_of(i.shape, i.r));
        }
        if (lazy) rebuild_areas();
        reindex();
    }

    // The cells listed again, of every item kept (after some were let go, or for another cell
    // size).
    void reindex() {
        cells.clear();
        for (List* l : {&contour, &path}) {
            l->entries = 0;
            l->sampled = 0;
            for (std::size_t at = 0; at < l->items.size(); ++at)
                index(*l, at, !lazy || area_for(l->items[at].stretch).indexed);
        }
    }

    // Stretches kept out of the cells (Candidates::kGrid). A stretch's items are listed in the
    // cells only once another stretch comes near it; until then its own lookups take its own
    // items in turn, and nothing else would be near enough: its zone (a box holding every item
    // of it) lies at least max_r + kSeparation from every other stretch's zone on one axis, so
    // the box of any other item lies farther than any threshold from the box of its items
    // (near_enough() is false for every such pair, whatever the cells held). Of its own items,
    // a lookup takes exactly those the cells would give (listed_near()), in the same order:
    // what the check asks, and of the wall model, is the same as with every item in the cells.
    struct Area {
        std::uint64_t stretch = 0;
        Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);  // its zone
        // The least box holding its items (the zone less its room to grow).
        Vec2 tight_lo = Vec2::Constant(INFINITY), tight_hi = Vec2::Constant(-INFINITY);
        bool indexed = false;  // its items are in the cells
        // Its items in each list (List::id): numbers from, to (one past the last).
        std::array<std::uint64_t, 2> from{kNoItem, kNoItem}, to{0, 0};
    };
    static constexpr std::uint64_t kNoItem = ~std::uint64_t{0};
    // How much farther apart than max_r two zones must lie (on one axis): more than any
    // rounding of the boxes' distance.
    static constexpr double kSeparation = 1e-3;
    // Zones are listed in the cells of kZoneCell mm they cover; one that would cover more than
    // kZoneCells of them (a stretch spread over a wide area) puts every stretch in the cells.
    static constexpr double kZoneCell = 64.0;
    static constexpr std::int64_t kZoneCells = 256;
    // A stretch with more items than this in a list is put in the cells (a lookup would take
    // too many of its own).
    static constexpr std::uint64_t kScanned = 48;
    bool lazy = true;  // stretches are kept out of the cells while apart (Candidates::kGrid)
    std::vector<Area> areas;
    detail::ProbeTable<std::uint32_t> area_index;  // stretch -> position in areas + 1
    detail::CellIndex<1> zones;                    // positions in areas, by kZoneCell cells
    std::vector<std::uint32_t> zone_found;
    std::uint32_t last_area = 0;  // positions looked up last (+ 1), tried first
    Area* entered = nullptr;      // enter()'s
    std::int64_t zone_index(double v) const { return detail::floor_index(v / kZoneCell); }

    Area& area_for(std::uint64_t stretch) {
        if (last_area > 0 && areas[last_area - 1].stretch == stretch) return areas[last_area - 1];
        std::uint32_t& at = area_index.emplace(stretch).first;
        if (at == 0) {
            areas.push_back(Area{});
            areas.back().stretch = stretch;
            at = static_cast<std::uint32_t>(areas.size());
        }
        last_area = at;
        return areas[at - 1];
    }
    // Its items listed in the cells (counted already).
    void materialize(Area& a) {
        if (a.indexed) return;
        a.indexed = true;
        for (List* l : {&contour, &path})
            for (std::uint64_t n = std::max(a.from[l->id], l->first); n < a.to[l->id]; ++n) {
                Item* x = l->at(n);
                if (x == nullptr) continue;
                const auto item = static_cast<std::uint32_t>(n - l->first);
                listed_cells(*x, [&](std::int64_t i, std::int64_t j) {
                    cells.add(l->id, cell_key(i, j), item);
                });
            }
    }
    // Every stretch in the cells from now on.
    void give_up() {
        for (Area& a : areas) materialize(a);
        lazy = false;
        areas = {};
        area_index.clear();
        zones.clear();
        last_area = 0;
    }
    // The tool radius of a stretch: a larger one than before needs zones farther apart, which
    // those of the stretches so far may not be: they go into the cells.
    void set_max_r(double r) {
        if (r <= max_r) return;
        max_r = r;
        if (lazy)
            for (Area& a : areas) materialize(a);
    }
    // Its zone made to hold [lo, hi] (with room to grow), and every stretch that comes near
    // it then, and it, put in the cells.
    void cover(Area& a, const Vec2& lo, const Vec2& hi) {
        a.tight_lo = a.tight_lo.cwiseMin(lo), a.tight_hi = a.tight_hi.cwiseMax(hi);
        if ((lo.array() >= a.lo.array()).all() && (hi.array() <= a.hi.array()).all()) return;
        const auto self = static_cast<std::uint32_t>(&a - areas.data());
        const double sep = max_r + kSeparation;
        const Vec2 ulo = a.lo.cwiseMin(lo), uhi = a.hi.cwiseMax(hi);
        if (!(std::isfinite(ulo.x()) && std::isfinite(ulo.y()) && std::isfinite(uhi.x()) &&
              std::isfinite(uhi.y()))) {
            give_up();
            return;
        }
        // Room to grow where there is room (fewer zones made again), none where there is not;
        // for a stretch in the cells (one that is never scanned), as much again as it spans,
        // so that a long one is made again a few times, not once every few items.
        Vec2 nlo, nhi;
        const double spans = a.indexed ? 0.5 * (uhi - ulo).maxCoeff() : 0.0;
        for (const double slack : {std::max(cell, spans), 0.25 * cell, 0.0}) {
            nlo = ulo.array() - slack, nhi = uhi.array() + slack;
            const std::int64_t i0 = zone_index(nlo.x() - sep), i1 = zone_index(nhi.x() + sep);
            const std::int64_t j0 = zone_index(nlo.y() - sep), j1 = zone_index(nhi.y() + sep);
            if ((i1 - i0 + 1) * (j1 - j0 + 1) > kZoneCells) {
                if (slack > 0.0) continue;
                give_up();
                return;
            }
            zone_found.clear();
            for (std::int64_t i = i0; i <= i1; ++i)
                for (std::int64_t j = j0; j <= j1; ++j) zones.append(0, cell_key(i, j), zone_found);
            const auto apart = [&](const Vec2& blo, const Vec2& bhi) {
                return blo.x() - nhi.x() >= sep || nlo.x() - bhi.x() >= sep ||
                       blo.y() - nhi.y() >= sep || nlo.y() - bhi.y() >= sep;
            };
            // Near where even its least box is near (its zone shrunk to that otherwise: it
            // still holds every item of it, and lies apart from every other zone).
            const auto near = [&](std::uint32_t k) {
                Area& b = areas[k];
                if (k == self || apart(b.lo, b.hi)) return false;
                if (!apart(b.tight_lo, b.tight_hi)) return true;
                b.lo = b.tight_lo, b.hi = b.tight_hi;
                return false;
            };
            zone_found.erase(std::remove_if(zone_found.begin(), zone_found.end(),
                                            [&](std::uint32_t k) { return !near(k); }),
                             zone_found.end());
            if (zone_found.empty()) break;
        }
        for (const std::uint32_t k : zone_found) materialize(areas[k]);
        if (!zone_found.empty()) materialize(a);
        // Listed in the cells of the new zone it was not listed in.
        const bool had = (a.lo.array() <= a.hi.array()).all();
        const std::int64_t o0 = had ? zone_index(a.lo.x()) : 1, o1 = had ? zone_index(a.hi.x()) : 0;
        const std::int64_t p0 = had ? zone_index(a.lo.y()) : 1, p1 = had ? zone_index(a.hi.y()) : 0;
        a.lo = nlo, a.hi = nhi;
        const std::int64_t k0 = zone_index(nlo.x()), k1 = zone_index(nhi.x());
        const std::int64_t l0 = zone_index(nlo.y()), l1 = zone_index(nhi.y());
        for (std::int64_t i = k0; i <= k1; ++i)
            for (std::int64_t j = l0; j <= l1; ++j)
                if (i < o0 || i > o1 || j < p0 || j > p1) zones.add(0, cell_key(i, j), self);
    }
    // An item about to join `list`: its stretch's zone made to hold it. True where it goes
    // into the cells (its stretch is there, or is now).
    bool enter(const List& list, const Item& item) {
        Area& a = area_for(item.stretch);
        const Extent x = item.shape.extent();
        cover(a, x.lo, x.hi);
        if (!lazy) return true;  // (a is gone)
        entered = &a;
        a.from[list.id] = std::min(a.from[list.id], list.next());
        a.to[list.id] = list.next() + 1;
        if (a.to[list.id] - std::max(a.from[list.id], list.first) > kScanned) materialize(a);
        return a.indexed;
    }
    // After the oldest items were let go: the areas of the stretches with items left, their
    // zones listed again.
    void rebuild_areas() {
        std::vector<Area> kept;
        for (const Area& a : areas)
            if (a.to[0] > contour.first || a.to[1] > path.first) kept.push_back(a);
        areas.swap(kept);
        area_index.clear();
        zones.clear();
        last_area = 0;
        for (std::size_t k = 0; k < areas.size(); ++k) {
            area_index.emplace(areas[k].stretch).first = static_cast<std::uint32_t>(k + 1);
            const Area& a = areas[k];
            if (!(a.lo.array() <= a.hi.array()).all()) continue;
            for (std::int64_t i = zone_index(a.lo.x()); i <= zone_index(a.hi.x()); ++i)
                for (std::int64_t j = zone_index(a.lo.y()); j <= zone_index(a.hi.y()); ++j)
                    zones.add(0, cell_key(i, j), static_cast<std::uint32_t>(k));
        }
    }

    // Positions of the items of `list` that may have a point closer than r to a point of e:
    // every one that has, and others. Ascending; valid until the next call. An item listed by
    // its box is listed in every cell holding a point of it; one listed by its samples (half a
    // cell apart along it) has each point within a quarter cell of a listed one.
    const std::vector<std::uint32_t>& near(const List& list, const Shape& e, double r) {
        found.clear();
        if (all) {
            for (std::size_t i = 0; i < list.items.size(); ++i)
                found.push_back(static_cast<std::uint32_t>(i));
            return found;
        }
        const double box_reach = r + (list.sampled > 0 ? 0.25 * cell : 0.0);
        // A short element: the cells within reach of its box. A long one: the cells within
        // reach of each sample, a quarter cell more (its points are that near a sample), less
        // those of the sample before (a path moves on by half a cell per sample: most of its
        // cells were looked at already).
        const CellRange box = cells_of(e, box_reach);
        const double reach = box_reach + 0.25 * cell;
        if (box.count() <= 16) {
            for (std::int64_t i = box.i0; i <= box.i1; ++i)
                for (std::int64_t j = box.j0; j <= box.j1; ++j)
                    cells.append(list.id, cell_key(i, j), found);
        } else {
            std::int64_t pi0 = 1, pi1 = 0, pj0 = 1, pj1 = 0;  // none
            for_samples(e, [&](const Vec2& p) {
                const std::int64_t i0 = index_of(p.x() - reach), i1 = index_of(p.x() + reach);
                const std::int64_t j0 = index_of(p.y() - reach), j1 = index_of(p.y() + reach);
                for (std::int64_t i = i0; i <= i1; ++i)
                    for (std::int64_t j = j0; j <= j1; ++j)
                        if (i < pi0 || i > pi1 || j < pj0 || j > pj1)
                            cells.append(list.id, cell_key(i, j), found);
                pi0 = i0, pi1 = i1, pj0 = j0, pj1 = j1;
            });
        }
        std::sort(found.begin(), found.end());
        found.erase(std::unique(found.begin(), found.end()), found.end());
        return found;
    }
    // near(list, e, r), and `item` added to `to` (not bound(): the caller does that once it
    // is done with the answer): where both are short, each cell is looked up once for both.
    const std::vector<std::uint32_t>& near_adding(const List& list, const Shape& e, double r,
                                                  List& to, const Item& item) {
        to.items.push_back(item);
        const std::size_t at = to.items.size() - 1;
        const CellRange own = cells_of(to.items[at]);
        const CellRange box = cells_of(e, r + (list.sampled > 0 ? 0.25 * cell : 0.0));
        const bool within =
            box.i0 <= own.i0 && own.i1 <= box.i1 && box.j0 <= own.j0 && own.j1 <= box.j1;
        if (all || own.count() > kBoxCells || box.count() > 16 || !within) {
            index(to, at);
            return near(list, e, r);
        }
        found.clear();
        const auto id = static_cast<std::uint32_t>(at);
        std::uint32_t n = 0;
        for (std::int64_t i = box.i0; i <= box.i1; ++i)
            for (std::int64_t j = box.j0; j <= box.j1; ++j) {
                const bool mine = i >= own.i0 && i <= own.i1 && j >= own.j0 && j <= own.j1;
                if (mine) {
                    cells.append_and_add(list.id, to.id, cell_key(i, j), id, found);
                    ++n;
                } else {
                    cells.append(list.id, cell_key(i, j), found);
                }
            }
        to.items[at].entries = n;
        to.entries += n;
        std::sort(found.begin(), found.end());
        found.erase(std::unique(found.begin(), found.end()), found.end());
        return found;
    }
    // near_adding(), for a stretch kept out of the cells: `item` added to `to`, and of its
    // stretch's own items in `list` those the cells would give (the items of other stretches
    // the cells would give are all too far to be near enough: Area).
    const std::vector<std::uint32_t>& lookup_adding(const List& list, const Shape& e, double r,
                                                    List& to, const Item& item) {
        if (!lazy || enter(to, item)) return near_adding(list, e, r, to, item);
        to.items.push_back(item);
        count(to, to.items.back(), cells_of(to.items.back()));
        found.clear();
        const Area& a = *entered;
        const Lookup look = lookup_of(list, e, r);
        const double lx = e.lo.x(), ly = e.lo.y(), hx = e.hi.x(), hy = e.hi.y();
        for (std::uint64_t n = std::max(a.from[list.id], list.first); n < a.to[list.id]; ++n) {
            const Item& x = list.items[static_cast<std::size_t>(n - list.first)];
            const StoredShape& b = x.shape;
            // At least r apart on an axis: not near enough (near_enough()) whatever the cells
            // give.
            if (static_cast<double>(b.lo[0]) - hx >= r || lx - static_cast<double>(b.hi[0]) >= r ||
                static_cast<double>(b.lo[1]) - hy >= r || ly - static_cast<double>(b.hi[1]) >= r)
                continue;
            // Closer than r on both axes: the cells of its box meet those of e's box widened by
            // r or more (the roundings of both go the same way), so an item listed by its box
            // is given by a lookup of that box's cells.
            if ((look.boxed && !x.sampled) || listed_near(x, e, look))
                found.push_back(static_cast<std::uint32_t>(n - list.first));
        }
        return found;
    }
    // The cells near() looks up for e: a box's (`box`, where `boxed`), or those within `reach`
    // of each sample of e.
    struct Lookup {
        CellRange box;
        bool boxed;
        double reach;
    };
    Lookup lookup_of(const List& list, const Shape& e, double r) const {
        const double box_reach = r + (list.sampled > 0 ? 0.25 * cell : 0.0);
        const CellRange box = cells_of(e, box_reach);
        return {box, box.count() <= 16, box_reach + 0.25 * cell};
    }
    // Whether near() looking up `look` for e would give x: a cell x is listed in is one it
    // looks up.
    bool listed_near(const Item& x, const Shape& e, const Lookup& look) const {
        const auto in = [](const CellRange& c, std::int64_t i, std::int64_t j) {
            return i >= c.i0 && i <= c.i1 && j >= c.j0 && j <= c.j1;
        };
        bool hit = false;
        if (look.boxed) {
            // Every cell x is listed in lies in the cells of its box (its samples lie in it).
            const CellRange own = cells_of(x);
            if (own.i1 < look.box.i0 || own.i0 > look.box.i1 || own.j1 < look.box.j0 ||
                own.j0 > look.box.j1)
                return false;
            if (own.count() <= kBoxCells || (own.i0 >= look.box.i0 && own.i1 <= look.box.i1 &&
                                             own.j0 >= look.box.j0 && own.j1 <= look.box.j1))
                return true;
            listed_cells(x, [&](std::int64_t i, std::int64_t j) { hit |= in(look.box, i, j); });
            return hit;
        }
        std::vector<CellRange> ranges;
        for_samples(e, [&](const Vec2& p) {
            ranges.push_back({index_of(p.x() - look.reach), index_of(p.x() + look.reach),
                              index_of(p.y() - look.reach), index_of(p.y() + look.reach)});
        });
        listed_cells(x, [&](std::int64_t i, std::int64_t j) {
            for (const CellRange& c : ranges) hit |= in(c, i, j);
        });
        return hit;
    }
    std::vector<std::uint32_t> found;  // near()'s answer
};

namespace {

// How a contour element stands to a path item. kOwn: the path is its offset (an offset keeps r
// from the whole element). kHeld, kNext: the path is the transition at the corner where the
// element ends or starts; there the corner rule keeps the path r from it, but an arc of more
// than half a turn comes back round towards that corner (a near-full arc followed by a sharp
// corner): its part more than half a turn away is checked. kBefore, kAfter: the element before
// or after the path's element; at their common corner the corner rule keeps the path r from
// it (trimmed at a point r from both, or bridged round the corner at r), away from it nothing
// does (an arc curling round, a contour that comes back alongside after a reversal).
enum class Relation { kOther, kOwn, kHeld, kNext, kBefore, kAfter };
Relation relation(std::uint64_t contour_index, std::uint64_t contour_stretch,
                  std::uint64_t path_index, std::uint64_t path_stretch, bool transition) {
    if (contour_stretch != path_stretch) return Relation::kOther;
    if (transition) {
        if (contour_index == path_index) return Relation::kHeld;
        if (contour_index == path_index + 1) return Relation::kNext;
        return Relation::kOther;
    }
    if (contour_index == path_index) return Relation::kOwn;
    if (contour_index + 1 == path_index) return Relation::kBefore;
    if (contour_index == path_index + 1) return Relation::kAfter;
    return Relation::kOther;
}

// What a finding of a path is: a lead-in's or a lead-out's first, else between features (the
// path's stretch not the element's) or within one contour.
SelfApproachKind kind_of(bool approach, bool departure, bool other_stretch) {
    if (approach) return SelfApproachKind::kLeadIn;
    if (departure) return SelfApproachKind::kLeadOut;
    return other_stretch ? SelfApproachKind::kFeatures : SelfApproachKind::kContour;
}

// How a contour element stands to an executed path: relation(), but a departure is no offset of
// the element it leaves (the stretch's last, whose offset end it starts from): that element is
// the one before it, met at the exit point (at_entry(): held to it only where it crosses it).
Relation path_relation(std::uint64_t contour_index, std::uint64_t contour_stretch,
                       std::uint64_t path_index, std::uint64_t path_stretch, bool transition,
                       bool departure) {
    const Relation rel =
        relation(contour_index, contour_stretch, path_index, path_stretch, transition);
    return departure && rel == Relation::kOwn ? Relation::kBefore : rel;
}

// An approach starts where the tool stands when the compensation begins; where that is already
// closer to an element than the threshold, the move that brought the tool there (uncompensated,
// not checked) put it there, and the approach is not held to the element. A departure starts
// where the compensated path ends: where that is already near an element, the path before it
// (checked) put the tool there.
bool stands_near(const Shape& approach, const Shape& element, double threshold) {
    return plane::distance_to(element, approach.start) < threshold;
}
// A departure ends at the programmed end of its block, where the program puts the tool's
// centre (ISG's #OTC example returns onto the contour it ground: "G40 X50 (WRK-Abwahl mit
// Verfahrbewegung um WZR abzubauen)"): an element that end is within the threshold of is the
// program's own choice, and the departure is not held to it.
bool ends_near(const Shape& departure, const Shape& element, double threshold) {
    return plane::distance_to(element, departure.end) < threshold;
}

// The elements that meet at an approach's entry point (the one it leads onto, one that closes
// a contour there, those of any other stretch over the same point): a straight approach onto an
// outside corner passes the entry point at L r / sqrt(L^2 + r^2) < r (L its length), the entry move
// every control makes (LinuxCNC's too); it is held to them only where its centre crosses one (a
// lead-in through the part). A departure leaves its exit point (its element's end, the last of
// the stretch) the same way, and is held to the elements that meet there only where it crosses
// one (a lead-out through the part).
bool at_entry(const Shape& element, const Vec2& entry) {
    return (element.start - entry).norm() <= SelfApproachCheck::kTolerance ||
           (element.end - entry).norm() <= SelfApproachCheck::kTolerance;
}
bool crosses(const SelfApproachFinding& f) {
    return f.distance <= SelfApproachCheck::kTolerance;
}

// How much closer than r a path may come: the path tolerance; to a neighbour twice that (a
// tangent join may move the next element's start by up to the path tolerance).
double threshold_for(Relation rel, double r) {
    const bool neighbour = rel == Relation::kBefore || rel == Relation::kAfter;
    return r - (neighbour ? 2.0 : 1.0) * SelfApproachCheck::kTolerance;
}

// The part of `c` a path of relation `rel` is checked against: all of it (c itself), or for a
// transition at its own corner the part of an arc more than half a turn from that corner
// (made in `out`); null: none.
const Shape* checked_part(const Shape& c, Relation rel, Shape& out) {
    if (rel == Relation::kOther || rel == Relation::kBefore || rel == Relation::kAfter) return &c;
    if (rel == Relation::kOwn || !is_arc(c)) return nullptr;
    const double turn = std::abs(c.sweep);
    if (turn <= std::numbers::pi) return nullptr;
    const double cut =
        rel == Relation::kHeld ? (turn - std::numbers::pi) / turn : std::numbers::pi / turn;
    const double t0 = rel == Relation::kHeld ? 0.0 : cut;
    const double t1 = rel == Relation::kHeld ? cut : 1.0;
    out = c;
    out.start = point_at(c, t0);
    out.end = point_at(c, t1);
    out.sweep = c.sweep * (t1 - t0);
    out.length = c.length * (t1 - t0);
    set_arc_terms(out);
    return &out;
}

}  // namespace

// A pair as the grid brings it, its shapes where they are (the grid's items, or a part made for
// it): nothing is copied unless the pair must wait (Candidate).
struct SelfApproachCheck::PairView {
    const Shape& path;
    const BlockRef& path_block;
    double r;
    int plane;
    const Shape& contour;
    const BlockRef& contour_block;
    double threshold;
    std::uint64_t contour_index, path_index, contour_id;
    bool need_cross;
    SelfApproachKind kind;
};

// A pair that waits for the wall model, its shapes copied.
struct SelfApproachCheck::Candidate {
    Shape path;
    BlockRef path_block;
    double r = 0.0;
    int plane = 17;
    Shape contour;
    BlockRef contour_block;
    double threshold = 0.0;
    std::uint64_t contour_index = 0, path_index = 0, contour_id = 0;
    bool need_cross = false;
    SelfApproachKind kind = SelfApproachKind::kContour;
    explicit Candidate(const PairView& v)
        : path(v.path),
          path_block(v.path_block),
          r(v.r),
          plane(v.plane),
          contour(v.contour),
          contour_block(v.contour_block),
          threshold(v.threshold),
          contour_index(v.contour_index),
          path_index(v.path_index),
          contour_id(v.contour_id),
          need_cross(v.need_cross),
          kind(v.kind) {}
    PairView view() const {
        return {path,      path_block,    r,          plane,      contour,    contour_block,
                threshold, contour_index, path_index, contour_id, need_cross, kind};
    }
};

// Calls held back (docs/performance.md, "Stretches held back"). A call is kept, to be worked
// later in its order, where working it now would give nothing out: nothing the check found waits
// to be given out (settled()) and the call brings no pair near. A call that may bring a pair
// near, or whose items could make a grid let items go, has the kept calls worked first
// (release()), in order, and is then worked itself: the check has then had every call in order,
// as if none had been kept, and gives out what it would have, where it would have (the kept
// calls gave nothing out). Calls still kept when the run ends are never worked: they gave
// nothing out, and let nothing go (limits() is the same).
//
// "Brings no pair near" is proved by the check's own tests, over more pairs than it asks:
// - an item against every other stretch: the box of the item, widened by the plane's largest
//   tool radius and kSeparation, meets no other stretch's zone (a box holding the boxes the
//   grid keeps of all of its items): near_enough() is false for every such pair;
// - a path against the elements of its own stretch, and an element against its stretch's paths:
//   each pair check_path() and programmed() would make of them goes as it would go there: left
//   out by the same rules (its relation and part, an approach's start, the wall model's word
//   on a lead), proved apart by consider()'s proofs, measured no nearer than its threshold
//   where settle() would measure it, or waiting, as the check's waiting_, until the model
//   places its elements and review() decides it. The rules that only leave a pair out and ask
//   what the hold does not know (a loop's clearing, a repeat's key, a tiny element, a
//   stretch's first element) are not applied: more pairs are asked than the check asks.
// Of each stretch whose items may still meet more of its own, the hold keeps the elements and
// paths (Record); a stretch with more than kOwn of either ends the holding for the run (a proof
// would take too many), and a call in a plane whose grid could let items go before the kept
// calls were all in it is worked (room()). The hold follows what the check would have been
// given (its own PendingQueue, the stretches' numbers and radii, a wall model given the same
// elements), so that it knows, call by call, the numbers the check would have given the items
// and what its model says.
struct SelfApproachCheck::Hold {
    using Kind = detail::HeldCall::Kind;
    struct Box {
        Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
        bool holds(const Box& b) const {
            return (b.lo.array() >= lo.array()).all() && (b.hi.array() <= hi.array()).all();
        }
    };
    // An element or a path of a stretch as the proofs take it: its shape as shape_of() makes
    // it, and what the model said of its element once placed (kept: it does not change).
    struct Item {
        // Made in place from its shape and its element's number (no copy of a value-initialised
        // one: an item is made for every element and path of a stretch kept).
        Item(const Shape& e, std::uint64_t element)
            : shape(e), extent(extent_for(e)), index(element) {}
        Shape shape;
        Extent extent;              // no smaller than the grid's (StoredShape's, rounded outward)
        std::uint64_t index = 0;    // its element's number
        double r = 0.0;             // a path's tool radius
        Vec2 entry = Vec2::Zero();  // an approach's entry point (its element's end)
        bool transition = false;    // a path's role
        bool approach = false;
        detail::WallRole role = detail::WallRole::kUndecided;
    };
    // A pair the check would ask the model about before it measures it (its elements not
    // placed): it waits, as in the check's waiting_, and is decided when both are.
    struct Waiting {
        Shape path, part;
        double threshold = 0.0;
        bool cross = false;
        std::uint64_t contour = 0, path_index = 0;
    };
    struct Record {
        std::uint64_t stretch = 0;
        int plane = 17;
        bool ended = false;
        std::vector<Item> elements, paths;
        // A box holding the stretch's items, proved apart from every other stretch's zone in
        // the epoch `epoch` (every item since was proved so or lies in it).
        Box clear;
        std::uint64_t epoch = 0;
    };
    // A stretch's zone: a box holding every item of it, and whether it is listed among the
    // plane's wide ones rather than in its cells.
    struct Zone {
        Box box;
        Box items;  // the least box holding its items (box holds it, and the boxes proved)
        int plane = 17;
        bool wide = false;
    };
    struct Counts {
        std::size_t elements = 0, paths = 0, element_entries = 0, path_entries = 0;
    };
    static constexpr std::size_t kOwn = 256;
    static constexpr double kZoneCell = 64.0;        // mm
    static constexpr std::int64_t kZoneCells = 256;  // a zone over more is a wide one
    static constexpr std::size_t kMostWide = 16;     // per plane; more: nothing is kept again
    static constexpr std::size_t kMostStretches = std::size_t{1} << 18;
    static constexpr double kSeparation = 1e-3;      // mm beyond the largest tool radius
    static constexpr double kMostCoordinate = 1e12;  // mm: beyond, nothing is kept again
    static constexpr double kRoom = 4.0;             // mm a stretch's proved box may grow by
    static constexpr std::size_t kCallsPerWindow = 4;
    // Pairs waiting at most (the check's queue takes kMaxDeferred before it measures the
    // oldest as things stand).
    static constexpr std::size_t kMostWaiting = kMaxDeferred / 2;

    // What the check would have been given (its fields of the same names).
    bool active = false;
    double r = 0.0;
    int plane = 17;
    std::uint64_t stretch = 0;
    std::uint64_t next_index = 0;
    PendingQueue pending;
    std::array<double, 3> max_r{};
    // What the check's wall model says of the elements of the stretches whose items may be
    // kept: leads are a stretch's own (wall_model.h), so a model given those stretches'
    // elements as the check's is given them places them as the check's does. It is asked
    // about leads and CDOF only (a loop's clearing is left to the pair's geometry): it keeps
    // nothing of the loops (Asks::kPlacement), and every element takes the same key.
    detail::WallModel walls{detail::WallModel::Asks::kPlacement};
    bool walls_on = true;
    std::vector<Waiting> waiting;
    std::uint64_t reviewed = 0;  // the model's generation at the last review
    std::deque<Record> records;  // the stretches whose items may still meet more of their own
    std::vector<Record> spare;   // records let go, their memory kept for the next
    // The memory of the zones and the calls kept, carved from blocks they share: the
    // zones of a long program take a fifth of one (docs/performance.md, "One slab for the
    // hold").
    detail::Slab memory;
    static constexpr std::size_t kZoneChunk = std::size_t{256} << 10;
    detail::ChunkedArray<Zone, kZoneChunk> zones{memory};  // by stretch number - 1
    detail::CellIndex<3> cells;  // per plane (list), the stretches listed in each zone cell
    std::array<std::vector<std::uint32_t>, 3> wide;
    std::vector<std::uint32_t> found;
    // Grows with each call worked: a stretch's box proved clear before is asked again.
    std::uint64_t epoch = 1;
    // The calls kept, and the items they bring per plane.
    detail::HeldCalls calls{memory};
    std::array<Counts, 3> held{};
    bool off = false;  // nothing is kept from now on (too many stretches, or too wide)

    static std::size_t slot(int p) { return p == 18 ? 1 : p == 19 ? 2 : 0; }
    bool holding() const noexcept { return !calls.empty(); }
    // Whether a call that brings no pair near may be kept: the check settled, or calls kept
    // already (fewer than kCallsPerWindow for each element of the window: their memory is
    // bounded as the grid's is).
    bool may_keep(const SelfApproachCheck& c) const {
        return !off && calls.size() < kCallsPerWindow * c.window_ && (holding() || c.settled());
    }

    static bool finite_box(const Box& b) {
        return b.lo.allFinite() && b.hi.allFinite() &&
               b.lo.cwiseAbs().maxCoeff() < kMostCoordinate &&
               b.hi.cwiseAbs().maxCoeff() < kMostCoordinate;
    }
    // More than a float's rounding of v, and of the sums the boxes are made of (the grid keeps
    // boxes in floats, rounded outward: StoredShape).
    static double slack(double v) { return 1e-6 + 4e-7 * std::abs(v); }
    static Box widened(Box b) {
        const double m = slack(std::max(b.lo.cwiseAbs().maxCoeff(), b.hi.cwiseAbs().maxCoeff()));
        b.lo.array() -= m;
        b.hi.array() += m;
        return b;
    }
    static Box box_of(const Shape& e) { return widened(Box{e.lo, e.hi}); }
    // An item's extent: its box, and its range on the third axis, widened by slack().
    static Extent extent_for(const Shape& e) {
        const Box b = box_of(e);
        return Extent{b.lo, b.hi, e.low - slack(e.low), e.high + slack(e.high)};
    }

    // The zone cells of a box.
    using Cells = Grid::CellRange;
    static Cells cells_of(const Vec2& lo, const Vec2& hi) {
        return {detail::floor_index(lo.x() / kZoneCell), detail::floor_index(hi.x() / kZoneCell),
                detail::floor_index(lo.y() / kZoneCell), detail::floor_index(hi.y() / kZoneCell)};
    }

    // The stretch's zone made to hold b, an item's box or (not `item`) a box proved apart
    // (listed in the cells it now covers).
    void grow(std::uint64_t id, const Box& b, bool item = true) {
        if (off) return;
        Zone& z = zones[static_cast<std::size_t>(id - 1)];
        if (item) z.items = Box{z.items.lo.cwiseMin(b.lo), z.items.hi.cwiseMax(b.hi)};
        if (z.box.holds(b)) return;
        if (!finite_box(b)) {
            off = true;
            return;
        }
        const bool had = z.box.lo.x() <= z.box.hi.x();
        const Vec2 lo = z.box.lo.cwiseMin(b.lo), hi = z.box.hi.cwiseMax(b.hi);
        const std::size_t list = slot(z.plane);
        const Cells now = cells_of(lo, hi);
        if (!z.wide && now.count() > kZoneCells) {
            z.wide = true;
            wide[list].push_back(static_cast<std::uint32_t>(id));
            if (wide[list].size() > kMostWide) off = true;
        }
        if (!z.wide) {
            const Cells old = had ? cells_of(z.box.lo, z.box.hi) : Cells{1, 0, 1, 0};
            for (std::int64_t i = now.i0; i <= now.i1; ++i)
                for (std::int64_t j = now.j0; j <= now.j1; ++j)
                    if (i < old.i0 || i > old.i1 || j < old.j0 || j > old.j1)
                        cells.add(list, cell_key(i, j), static_cast<std::uint32_t>(id));
        }
        z.box = Box{lo, hi};
    }
    // True where b lies farther than `reach` from every zone of plane `p` but stretch `id`'s on
    // one axis.
    bool apart_from_others(std::uint64_t id, int p, const Box& b, double reach) {
        const std::size_t list = slot(p);
        const Cells look = cells_of(Vec2(b.lo.array() - reach), Vec2(b.hi.array() + reach));
        if (look.count() > 64) return false;
        found.clear();
        for (std::int64_t i = look.i0; i <= look.i1; ++i)
            for (std::int64_t j = look.j0; j <= look.j1; ++j)
                cells.append(list, cell_key(i, j), found);
        found.insert(found.end(), wide[list].begin(), wide[list].end());
        for (const std::uint32_t other : found) {
            if (other == id) continue;
            const Box& z = zones[other - 1].box;
            if (z.lo.x() - b.hi.x() >= reach || b.lo.x() - z.hi.x() >= reach ||
                z.lo.y() - b.hi.y() >= reach || b.lo.y() - z.hi.y() >= reach)
                continue;
            return false;
        }
        return true;
    }
    // True where the box b of an item of `rec` lies farther than the plane's largest tool radius
    // and kSeparation from every other stretch's zone on one axis: proved now, or lying within
    // a box of the stretch proved so earlier in this epoch (a box proved is made part of the
    // stretch's zone, so every item of another stretch proved since was proved apart from it;
    // an epoch ends with every call worked, whose items nothing proved). A box proved is the
    // stretch's zone and b, with room to grow where that is apart too (fewer proofs).
    bool alone(Record& rec, const Box& b) {
        if (rec.epoch == epoch && rec.clear.holds(b)) return true;
        if (!finite_box(b)) return false;
        const double reach = max_r[slot(rec.plane)] + kSeparation;
        const Box& items = zones[static_cast<std::size_t>(rec.stretch - 1)].items;
        const Box both{items.lo.cwiseMin(b.lo), items.hi.cwiseMax(b.hi)};
        for (const double room : {kRoom, 0.0}) {
            const Box wider{Vec2(both.lo.array() - room), Vec2(both.hi.array() + room)};
            if (apart_from_others(rec.stretch, rec.plane, wider, reach)) {
                rec.clear = wider;
                rec.epoch = epoch;
                grow(rec.stretch, wider, false);
                return true;
            }
        }
        return false;
    }

    Record* record_of(std::uint64_t id) {
        for (Record& rec : records)
            if (rec.stretch == id) return &rec;
        return nullptr;
    }
    // The stretches that ended and whose elements were all executed (or let go) have no more
    // items of their own.
    void prune() {
        bool pruned = false;
        while (!records.empty() && records.front().ended &&
               (pending.waiting() == 0 || records.front().stretch < pending.at(0).stretch)) {
            Record& rec = records.front();
            rec.elements.clear();
            rec.paths.clear();
            spare.push_back(std::move(rec));
            records.pop_front();
            pruned = true;
        }
        // The model lets go of what it knew of their elements (never asked about again).
        if (pruned)
            walls.forget_before(records.empty() || records.front().elements.empty()
                                    ? next_index
                                    : records.front().elements.front().index);
    }
    // A new item of the record's, of shape e and element number `index` (null where it has
    // kOwn already).
    static Item* add(std::vector<Item>& to, const Shape& e, std::uint64_t index) {
        return to.size() < kOwn ? &to.emplace_back(e, index) : nullptr;
    }

    // Whether the grid of plane `p` keeps every item the kept calls would bring, and this one
    // (an element, or a path) whose length is at most `length`, without letting any go: at
    // most as many items as the grid takes before it lets some go, and entries counted as the
    // most such an item takes (every item counted, its cells at the grid's cell size now, which
    // only grows). Where the grid has not sized its cells yet, the kept elements stay fewer
    // than it sizes them by (a cost, not a proof: its cells are then sized).
    std::size_t entries_of(const SelfApproachCheck& c, int p, double length) const {
        const Grid* g = c.grids_[slot(p)].get();
        const double cell = g != nullptr && g->cell > 0.0 ? g->cell : 0.5;
        const double samples = std::max(1.0, std::ceil(length / (0.5 * cell)));
        return samples < 1e9 ? std::max<std::size_t>(4, static_cast<std::size_t>(samples) + 1)
                             : std::numeric_limits<std::size_t>::max() / 4;
    }
    bool room(const SelfApproachCheck& c, int p, bool element, std::size_t entries) const {
        const std::size_t list = slot(p);
        const Grid* g = c.grids_[list].get();
        const Counts& h = held[list];
        const std::size_t most = element ? c.window_ : Grid::kPathsPerElement * c.window_;
        const Grid::List* kept = g == nullptr ? nullptr : element ? &g->contour : &g->path;
        const std::size_t items = kept == nullptr ? 0 : kept->items.size();
        const std::size_t kept_entries = kept == nullptr ? 0 : kept->entries;
        if (items + (element ? h.elements : h.paths) + 1 >= 2 * most) return false;
        if (kept_entries + (element ? h.element_entries : h.path_entries) + entries >=
            2 * c.entry_budget_)
            return false;
        return !element || (g != nullptr && g->sized) ||
               (g == nullptr ? 0 : g->first_lengths.size()) + h.elements + 1 < Grid::kSizing;
    }
    void count(int p, bool element, std::size_t entries) {
        Counts& h = held[slot(p)];
        (element ? h.elements : h.paths) += 1;
        (element ? h.element_entries : h.path_entries) += entries;
    }

    // What the model says of an item's element, kept once it is placed.
    detail::WallRole role_of(Item& x) const {
        if (x.role == detail::WallRole::kUndecided) {
            std::uint64_t loop = 0;
            x.role = walls.placement(x.index, loop);
        }
        return x.role;
    }
    detail::WallRole placement(std::uint64_t index) const {
        std::uint64_t loop = 0;
        return walls.placement(index, loop);
    }
    // No wall by its placement alone (the check's model says so too; a loop's element may be
    // cleared as well, which the hold leaves to the geometry).
    static bool no_wall(detail::WallRole role) {
        return role == detail::WallRole::kLead || role == detail::WallRole::kOff;
    }

    // Whether consider() proves the pair apart (an approach at its entry point held only to a
    // crossing).
    static bool proved(const Shape& path, const Shape& part, double threshold, bool cross) {
        if (cross && plane::apart(path, part, SelfApproachCheck::kTolerance + kApartMargin))
            return true;
        return plane::apart_by_side(path, part, threshold + kApartMargin) ||
               plane::apart(path, part, threshold + kApartMargin);
    }
    // Whether settle() finds nothing of a pair it measures.
    static bool measured_clear(const Shape& path, const Shape& part, double threshold, bool cross) {
        const double d = least_distance(path, part, threshold).distance;
        return d >= threshold || (cross && d > SelfApproachCheck::kTolerance);
    }
    // A pair consider() is given, as it goes on there: proved apart, or (both its elements
    // placed) measured clear, or (not placed) waiting for the model. False where the check may
    // find something of it now.
    bool pair_clear(const Shape& path, const Shape& part, double threshold, bool cross, bool placed,
                    std::uint64_t contour, std::uint64_t path_index) {
        if (proved(path, part, threshold, cross)) return true;
        if (placed) return measured_clear(path, part, threshold, cross);
        waiting.push_back(Waiting{path, part, threshold, cross, contour, path_index});
        return waiting.size() < kMostWaiting;
    }
    // The pairs waiting whose elements the model has placed now, decided as review() decides
    // them: left out (no wall) or measured. False where one may be found.
    bool review() {
        if (walls.generation() == reviewed) return true;
        reviewed = walls.generation();
        bool clear = true;
        std::erase_if(waiting, [&](const Waiting& w) {
            if (!clear) return false;
            const detail::WallRole role = placement(w.contour);
            if (role == detail::WallRole::kUndecided ||
                placement(w.path_index) == detail::WallRole::kUndecided)
                return false;
            clear = no_wall(role) || measured_clear(w.path, w.part, w.threshold, w.cross);
            return clear;
        });
        return clear;
    }
    // The pairs programmed() makes of element e (number `index`) and its stretch's paths, each
    // gone on with as there.
    bool clear_of_paths(Record& rec, const Shape& e, std::uint64_t index) {
        if (rec.paths.empty()) return true;
        Shape scratch;
        const detail::WallRole self = placement(index);
        for (Item& p : rec.paths) {
            const Relation rel = relation(index, rec.stretch, p.index, rec.stretch, p.transition);
            const Shape* part = checked_part(e, rel, scratch);
            if (part == nullptr) continue;
            const double threshold = threshold_for(rel, p.r);
            // The path as the grid keeps it (its length rounded up).
            const detail::StoredShape stored(p.shape);
            if (!near_enough(stored.extent(), extent_of(*part), threshold)) continue;
            const bool placed =
                role_of(p) != detail::WallRole::kUndecided && self != detail::WallRole::kUndecided;
            if (placed && no_wall(self)) continue;
            const Shape path = stored.shape();
            if (p.approach && stands_near(path, *part, threshold)) continue;
            const bool cross = p.approach && at_entry(e, p.entry);
            if (!pair_clear(path, *part, threshold, cross, placed, index, p.index)) return false;
        }
        return true;
    }
    // The pairs check_path() makes of path e (of element p) and its stretch's elements, each
    // gone on with as there.
    bool clear_of_elements(Record& rec, const Shape& e, const Pending& p, bool transition,
                           bool approach, bool departure) {
        const Extent extent = extent_of(e);
        bool self_placed = !(active && rec.stretch == stretch);
        if (!self_placed) self_placed = placement(p.index) != detail::WallRole::kUndecided;
        Shape scratch;
        for (Item& c : rec.elements) {
            // Farther than r on an axis: farther than every threshold.
            if (c.extent.lo.x() - extent.hi.x() >= p.r || extent.lo.x() - c.extent.hi.x() >= p.r ||
                c.extent.lo.y() - extent.hi.y() >= p.r || extent.lo.y() - c.extent.hi.y() >= p.r)
                continue;
            const Relation rel =
                path_relation(c.index, rec.stretch, p.index, rec.stretch, transition, departure);
            if (rel == Relation::kOwn ||
                ((rel == Relation::kHeld || rel == Relation::kNext) && !is_arc(c.shape)))
                continue;
            const double threshold = threshold_for(rel, p.r);
            if (!near_enough(extent, c.extent, threshold)) continue;
            const detail::WallRole role = role_of(c);
            const bool placed = self_placed && role != detail::WallRole::kUndecided;
            if (placed && no_wall(role)) continue;  // whatever part of it is asked
            const Shape* part = checked_part(c.shape, rel, scratch);
            if (part == nullptr) continue;
            if (part != &c.shape && !near_enough(extent, extent_of(*part), threshold)) continue;
            if ((approach || departure) && stands_near(e, *part, threshold)) continue;
            if (departure && ends_near(e, *part, threshold)) continue;
            const bool cross = (approach || departure) && at_entry(c.shape, p.end);
            if (!pair_clear(e, *part, threshold, cross, placed, c.index, p.index)) return false;
        }
        return true;
    }

    // The calls: each follows what the check would do with it, and answers whether it is kept
    // (true: not to be worked now).
    bool begin(const SelfApproachCheck& c, double radius, int p, int side) {
        active = true;
        r = std::max(0.0, radius);
        plane = p;
        ++stretch;
        max_r[slot(p)] = std::max(max_r[slot(p)], r);
        if (stretch > kMostStretches) off = true;
        if (!off) {
            zones.emplace_back().plane = p;
            Record rec;
            if (!spare.empty()) {
                rec = std::move(spare.back());
                spare.pop_back();
            }
            rec.stretch = stretch;
            rec.plane = p;
            rec.ended = false;
            rec.epoch = 0;
            records.push_back(std::move(rec));
            walls.begin(p, side);
        }
        // A begin gives nothing out: kept while calls are (they come before it), or to start.
        if (!holding() && (off || !c.settled())) return false;
        calls.begin(radius, p, side);
        return true;
    }
    bool set_walls(const SelfApproachCheck& c, bool on) {
        walls_on = on;
        if (!holding() && (off || !c.settled())) return false;
        calls.walls(on);
        return true;
    }
    bool end(const SelfApproachCheck& c) {
        if (!active) return true;  // the check does nothing with it
        active = false;
        if (!records.empty() && records.back().stretch == stretch) records.back().ended = true;
        walls.end();
        const bool clear = review();
        prune();
        if (!clear || !may_keep(c)) return false;
        calls.end();
        return true;
    }
    bool programmed(const SelfApproachCheck& c, const PathSegment& s) {
        if (!active || r <= 0.0 || c.done()) return true;  // the check does nothing with it
        if (s.kind != SegmentKind::kLine && s.kind != SegmentKind::kArc) return true;
        const std::uint64_t index = next_index++;
        const PlaneAxes a = plane_axes(plane);
        pending.push(
            Pending{s.block, index, stretch, r, plane, Vec2(s.end[a.first], s.end[a.second])});
        if (off) return false;
        Record& rec = records.back();
        Item* x = add(rec.elements, shape_of(s, plane), index);
        if (x == nullptr) {  // a large stretch: nothing is kept from now on
            off = true;
            return false;
        }
        const Shape& e = x->shape;
        bool keep = may_keep(c);
        // The model is given the element as programmed() gives the check's.
        if (moves_in(s, plane)) walls.element(index, plane_move(s, plane, &e), 0, walls_on, false);
        const Box b = box_of(e);
        // What the model placed now decides the pairs waiting for it (the check's review()
        // after its model is given the element), then the element's own pairs.
        if (!review()) keep = false;
        if (keep) {
            const std::size_t entries = entries_of(c, plane, static_cast<double>(up(e.length)));
            keep = room(c, plane, true, entries) && alone(rec, b) && clear_of_paths(rec, e, index);
            if (keep) count(plane, true, entries);
        }
        grow(stretch, b);
        if (!keep || off) return false;
        calls.segment(Kind::kProgrammed, s);
        return true;
    }
    bool executed(const SelfApproachCheck& c, const PathSegment& s) {
        if (c.done()) return false;
        const std::size_t waiting_now = pending.waiting();
        const std::size_t at = pending.find(s);
        const bool leaves_head = departs_head(s, at, waiting_now);
        if (of_element(s.role) && (at != waiting_now || leaves_head)) {
            pending.advance(leaves_head ? 0 : at);
            prune();
            const Pending p = pending.at(0);
            if ((held_to_elements(s.role) || leaves_head) && !off && !path(c, s, p)) return false;
        }
        if (!may_keep(c) || off) return false;
        calls.segment(Kind::kExecuted, s);
        return true;
    }
    // An executed path of element p: its stretch's zone holds it, its record too while the
    // stretch may have more elements; true where it brings no pair near (and may be kept).
    bool path(const SelfApproachCheck& c, const PathSegment& s, const Pending& p) {
        Record* rec = record_of(p.stretch);
        if (rec == nullptr) {  // nothing is kept from now on
            off = true;
            return false;
        }
        const bool transition = s.role == Role::kTransition;
        const bool approach = s.role == Role::kApproach;
        const bool departure = s.role == Role::kDeparture;
        const bool store = !rec->ended;  // its stretch's later elements are held to it
        bool keep = may_keep(c);
        if (!keep && !store) {
            grow(p.stretch, outer_box(s, p.plane));
            return false;
        }
        const Shape e = shape_of(s, p.plane);
        const Box b = box_of(e);
        if (keep) {
            const std::size_t entries = entries_of(c, p.plane, e.length * (1.0 + 1e-6));
            keep = room(c, p.plane, false, entries) && alone(*rec, b) &&
                   clear_of_elements(*rec, e, p, transition, approach, departure);
            if (keep) count(p.plane, false, entries);
        }
        if (store) {
            Item* x = add(rec->paths, e, p.index);
            if (x == nullptr) {  // a large stretch: nothing is kept from now on
                off = true;
                return false;
            }
            x->r = p.r;
            x->transition = transition;
            x->approach = approach;
            x->entry = p.end;
        }
        grow(p.stretch, b);
        return keep;
    }
    // A box no smaller than the one the grid keeps of s in `p` (shape_of()'s, rounded outward),
    // without making its shape: a line's ends; an arc's circle at its larger radius, widened by
    // the change of radius as add_arc_to_box() widens it.
    static Box outer_box(const PathSegment& s, int p) {
        const PlaneAxes a = plane_axes(p);
        const Vec2 start(s.start[a.first], s.start[a.second]), end(s.end[a.first], s.end[a.second]);
        Box b{start.cwiseMin(end), start.cwiseMax(end)};
        if (s.kind == SegmentKind::kArc && s.plane == p) {
            const Vec2 centre(s.center[a.first], s.center[a.second]);
            const double r0 = (start - centre).norm(), r1 = (end - centre).norm();
            const double rmax = std::max(r0, r1);
            const double reach =
                rmax + std::abs(r1 - r0) + 1e-9 * (1.0 + centre.cwiseAbs().maxCoeff() + rmax);
            b.lo = b.lo.cwiseMin(Vec2(centre.array() - reach));
            b.hi = b.hi.cwiseMax(Vec2(centre.array() + reach));
        }
        return widened(b);
    }
};

SelfApproachCheck::SelfApproachCheck(std::size_t window, std::size_t entry_budget,
                                     Candidates candidates, Schedule schedule)
    : window_(std::max<std::size_t>(window, 1)),
      entry_budget_(entry_budget),
      walls_(std::make_unique<detail::WallModel>()),
      candidates_(candidates) {
    if (schedule == Schedule::kHoldApart) hold_ = std::make_unique<Hold>();
}
SelfApproachCheck::~SelfApproachCheck() = default;

void SelfApproachCheck::begin(double r, int plane, int side) {
    if (hold_ && hold_->begin(*this, r, plane, side)) return;
    begin_now(r, plane, side);
}

void SelfApproachCheck::set_walls(bool on) {
    if (hold_ && hold_->set_walls(*this, on)) return;
    walls_on_ = on;
}

void SelfApproachCheck::end(std::vector<SelfApproachFinding>& out) {
    if (hold_) {
        if (hold_->end(*this)) return;
        release(out);
    }
    end_now(out);
}

void SelfApproachCheck::programmed(const PathSegment& s, std::vector<SelfApproachFinding>& out) {
    if (hold_) {
        if (hold_->programmed(*this, s)) return;
        release(out);
    }
    programmed_now(s, out);
}

void SelfApproachCheck::executed(const PathSegment& s, std::vector<SelfApproachFinding>& out) {
    if (hold_) {
        if (hold_->executed(*this, s)) return;
        release(out);
    }
    executed_now(s, out);
}

void SelfApproachCheck::release(std::vector<SelfApproachFinding>& out) {
    ++hold_->epoch;  // a call is worked: what was proved of the zones is asked again
    if (!hold_->holding() && !hold_->off) {
        hold_->waiting.clear();
        return;
    }
    detail::HeldCalls calls;
    calls.swap(hold_->calls);
    hold_->held = {};
    hold_->waiting.clear();
    calls.for_each([&](const detail::HeldCall& k) {
        switch (k.kind) {
            case Hold::Kind::kBegin:
                begin_now(k.radius, k.plane, k.side);
                break;
            case Hold::Kind::kEnd:
                end_now(out);
                break;
            case Hold::Kind::kProgrammed:
                programmed_now(k.segment, out);
                break;
            case Hold::Kind::kExecuted:
                executed_now(k.segment, out);
                break;
            case Hold::Kind::kWalls:
                walls_on_ = k.on;
                break;
        }
    });
    // Nothing is kept from now on: the hold lets its records go.
    if (hold_->off) {
        hold_.reset();
        return;
    }
    calls.clear();
    hold_->calls.swap(calls);  // its memory, for the next calls kept
}

std::size_t SelfApproachCheck::held() const noexcept {
    return hold_ ? hold_->calls.size() : 0;
}

bool SelfApproachCheck::settled() const {
    if (done() || !open_.empty() || !held_.empty() || !deferred_.empty() || !waiting_.empty())
        return false;
    return std::all_of(undecided_.begin(), undecided_.end(),
                       [](const Undecided& u) { return u.held.empty(); });
}

namespace {

// A plane's grid at its first use: out of line, so that grid() is a load and a test.
template <typename G>
[[gnu::noinline]] G& create(std::unique_ptr<G>& grid, int plane, std::size_t window,
                            std::size_t budget, SelfApproachCheck::Candidates candidates) {
    grid = std::make_unique<G>();
    grid->plane = plane;
    grid->window = window;
    grid->entry_budget = budget;
    grid->all = candidates == SelfApproachCheck::Candidates::kAll;
    grid->lazy = candidates == SelfApproachCheck::Candidates::kGrid;
    // The most each list holds, at once: memory a list does not fill is never touched (not
    // resident), and none is copied as it grows.
    grid->contour.items.reserve(2 * grid->most(grid->contour));
    grid->path.items.reserve(2 * grid->most(grid->path));
    return *grid;
}

}  // namespace

// Inline where it is called (once or twice a segment): a load and a test.
[[gnu::always_inline]] inline SelfApproachCheck::Grid& SelfApproachCheck::grid(int plane) {
    std::unique_ptr<Grid>& g = grids_[plane == 18 ? 1 : plane == 19 ? 2 : 0];
    if (!g) return create(g, plane, window_, entry_budget_, candidates_);
    return *g;
}

SelfApproachLimits SelfApproachCheck::limits() const {
    SelfApproachLimits l;
    for (const auto& g : grids_)
        if (g && g->truncated && !l.truncated) {
            l.truncated = true;
            l.truncated_at = g->truncated_at;
            l.truncated_plane = g->plane;
        }
    l.capped = capped_;
    return l;
}

std::size_t SelfApproachCheck::kept() const noexcept {
    std::size_t n = 0;
    for (const auto& g : grids_)
        if (g) n += g->contour.items.size() + g->path.items.size();
    if (hold_)
        for (const Hold::Counts& h : hold_->held) n += h.elements + h.paths;
    return n;
}

void SelfApproachCheck::begin_now(double r, int plane, int side) {
    active_ = true;
    walls_->begin(plane, side);
    latest_ = kNone;
    first_in_stretch_ = true;
    r_ = std::max(0.0, r);
    plane_ = plane;
    ++stretch_;
    Grid& g = grid(plane);
    // Cells of twice the first stretch's tool radius; a tool more than twice as large as that
    // makes them twice its radius, so that a lookup stays within a few cells.
    if (g.cell == 0.0) {
        g.cell = std::max(2.0 * r_, 0.5);
    } else if (r_ > 2.0 * g.cell) {
        g.cell = 2.0 * r_;
        g.reindex();
    }
    g.set_max_r(r_);
}

void SelfApproachCheck::end_now(std::vector<SelfApproachFinding>& out) {
    if (!active_) return;
    active_ = false;
    // Whether the stretch's last element is its departure is known from the first segment
    // after its own (leave()); until then what came near it stays held.
    if (latest_ != kNone && next_index_ > 0) {
        if (undecided_.size() >= 64) {  // never executed: taken as departed
            for (const Found& f : undecided_.front().held) give(f, false, out);
            undecided_.erase(undecided_.begin());
        }
        undecided_.push_back(Undecided{latest_, next_index_ - 1, plane_, false, {}});
        undecided_.back().held.swap(held_);
    }
    held_.clear();
    latest_ = kNone;
    walls_->end();
    review(out);
}

// The first segment after a stretch whose last element is held: a move in the plane (the G40
// block's move, the move after a lone G40, G237's departure, the next approach) departs from
// the last element's offset end, so the last element is contour and what came near it goes
// out; a lift (G0 Z.. under G41/G42) or no move at all leaves it as the program's own way out
// (a lead-out arc, as LinuxCNC's examples write it): not contour.
void SelfApproachCheck::leave(const PathSegment& s, std::vector<SelfApproachFinding>& out) {
    Undecided& u = undecided_.front();
    const PlaneAxes a = plane_axes(u.plane);
    const Vec2 d(s.end[a.first] - s.start[a.first], s.end[a.second] - s.start[a.second]);
    const bool departs =
        d.norm() > kSamePointTolerance || (s.kind == SegmentKind::kArc && s.plane == u.plane);
    // A loop's last element is the loop's, whatever follows it (wall_model.h).
    const Grid::Item* last = grid(u.plane).contour.at(u.id);
    const bool looped = last != nullptr && walls_->looped(last->index);
    if (departs || looped) {
        for (const Found& f : u.held) give(f, false, out);
    } else {
        if (Grid::Item* c = grid(u.plane).contour.at(u.id)) c->protect = false;
    }
    undecided_.erase(undecided_.begin());
}

SelfApproachCheck::Undecided* SelfApproachCheck::undecided_of(int plane, std::uint64_t id) {
    for (Undecided& u : undecided_)
        if (u.id == id && u.plane == plane) return &u;
    return nullptr;
}

template <typename Held>
void SelfApproachCheck::hold(Held& held, const Found& f) {
    for (Found& h : held)
        if (same_block(h.f.path_block, f.f.path_block) &&
            same_block(h.f.contour_block, f.f.contour_block) && h.contour == f.contour &&
            h.path == f.path) {
            if (f.f.distance < h.f.distance) h = f;
            return;
        }
    held.push_back(f);
}

void SelfApproachCheck::forget_let_go() {
    std::uint64_t below = kNone;
    for (const auto& g : grids_)
        if (g) below = std::min(below, g->kept_from);
    if (below != kNone && below > forgotten_) {
        forgotten_ = below;
        walls_->forget_before(below);
        while (!approach_entries_.empty() && approach_entries_.front().index < below)
            approach_entries_.pop_front();
    }
}

// The entry point of the approach that is element `index`'s, where it was executed and kept.
const Eigen::Vector2d* SelfApproachCheck::approach_entry(std::uint64_t index) const {
    const auto at = std::lower_bound(approach_entries_.begin(), approach_entries_.end(), index,
                                     [](const Entry& e, std::uint64_t i) { return e.index < i; });
    return at != approach_entries_.end() && at->index == index ? &at->point : nullptr;
}

// The wall model's answer for an item, kept in it once its element is placed (one lookup per
// item, not per pair): its role, a loop's clearing asked each time (it changes once at most).
detail::WallRole SelfApproachCheck::role_of(GridItem& item) {
    if (item.role == detail::WallRole::kUndecided)
        item.role = walls_->placement(item.index, item.loop);
    if (item.role == detail::WallRole::kWall && item.loop != detail::WallModel::kNoLoop &&
        walls_->cleared(item.loop))
        return detail::WallRole::kCleared;
    return item.role;
}

bool SelfApproachCheck::placed_of(GridItem& item) {
    if (item.role == detail::WallRole::kUndecided)
        item.role = walls_->placement(item.index, item.loop);
    return item.role != detail::WallRole::kUndecided;
}

void SelfApproachCheck::give(const Found& f, bool running, std::vector<SelfApproachFinding>& out) {
    if (walls_->placed(f.contour) && walls_->placed(f.path)) {
        if (walls_->role(f.contour) == detail::WallRole::kWall) take(f.f, running, out);
        return;
    }
    if (deferred_.size() >= kMaxDeferred) {  // the oldest decided as things stand
        const Found oldest = deferred_.front();
        deferred_.pop_front();
        const detail::WallRole role = walls_->role(oldest.contour);
        if (role == detail::WallRole::kWall || role == detail::WallRole::kUndecided)
            take(oldest.f, false, out);
    }
    hold(deferred_, f);
}

void SelfApproachCheck::review(std::vector<SelfApproachFinding>& out) {
    if (walls_->generation() == reviewed_ || (deferred_.empty() && waiting_.empty())) {
        reviewed_ = walls_->generation();
        return;
    }
    reviewed_ = walls_->generation();
    // A path block's segments (its contour part, a transition) come near an element each with
    // its own distance: the findings are taken open, so that a pair keeps the least of them,
    // and those of blocks whose segments are all done go out after the review.
    std::deque<Candidate> candidates;
    candidates.swap(waiting_);
    for (const Candidate& k : candidates) {
        if (!walls_->placed(k.contour_index) || !walls_->placed(k.path_index)) {
            waiting_.push_back(k);
            continue;
        }
        if (walls_->role(k.contour_index) == detail::WallRole::kWall) settle(k.view(), true, out);
    }
    std::deque<Found> waiting;
    for (const Found& f : deferred_) {
        if (!walls_->placed(f.contour) || !walls_->placed(f.path)) {
            waiting.push_back(f);
            continue;
        }
        if (walls_->role(f.contour) == detail::WallRole::kWall) take(f.f, true, out);
    }
    deferred_.swap(waiting);
    // What stays open: the findings of the block whose segments are coming (current_).
    const auto finished = std::stable_partition(
        open_.begin(), open_.end(),
        [&](const SelfApproachFinding& f) { return seen_ && same_block(f.path_block, current_); });
    out.insert(out.end(), finished, open_.end());
    open_.erase(finished, open_.end());
}

SelfApproachCheck::Pair SelfApproachCheck::pair_of(const BlockRef& path, const BlockRef& contour) {
    return {static_cast<std::uint64_t>(path.number), path.line,
            static_cast<std::uint64_t>(contour.number), contour.line};
}

SelfApproachFinding* SelfApproachCheck::open_finding(const Pair& pair) {
    for (SelfApproachFinding& f : open_)
        if (pair_of(f.path_block, f.contour_block) == pair) return &f;
    return nullptr;
}

bool SelfApproachCheck::closed(const Pair& pair) {
    if (open_finding(pair) != nullptr) return false;
    return reported_.size() >= kMaxFindings ||
           std::find(reported_.begin(), reported_.end(), pair) != reported_.end();
}

void SelfApproachCheck::take(const SelfApproachFinding& f, bool running,
                             std::vector<SelfApproachFinding>& out) {
    const Pair pair = pair_of(f.path_block, f.contour_block);
    if (SelfApproachFinding* o = open_finding(pair)) {
        if (f.distance < o->distance) *o = f;
        return;
    }
    if (closed(pair)) return;
    reported_.push_back(pair);
    if (running)
        open_.push_back(f);
    else
        out.push_back(f);
}

void SelfApproachCheck::flush(std::vector<SelfApproachFinding>& out) {
    out.insert(out.end(), open_.begin(), open_.end());
    open_.clear();
}

void SelfApproachCheck::programmed_now(const PathSegment& s,
                                       std::vector<SelfApproachFinding>& out) {
    if (!active_ || r_ <= 0.0 || done()) return;
    if (s.kind != SegmentKind::kLine && s.kind != SegmentKind::kArc) return;
    const std::uint64_t index = next_index_++;
    const PlaneAxes axes = plane_axes(plane_);
    pending_.push(
        Pending{s.block, index, stretch_, r_, plane_, Vec2(s.end[axes.first], s.end[axes.second])});
    Grid& g = grid(plane_);
    // A move that stays where it is in the plane (a plunge in Z under G17, G41 G1 to the point
    // the tool stands on) is no element of the contour; the stretch's first element, its
    // approach, is the first that moves in the plane (as the board runs it).
    const bool moves = moves_in(s, plane_);
    const bool first = first_in_stretch_ && moves;
    if (moves) first_in_stretch_ = false;
    // The element before is not the last: what came near it counts.
    for (const Found& f : held_) give(f, seen_ && same_block(f.f.path_block, current_), out);
    held_.clear();
    latest_ = kNone;
    const std::uint64_t key = key_of(s, plane_, 0.0);
    const bool fresh = g.contour.keys.insert(key);
    // Its shape, made once for the grid and the wall model (an arc's terms).
    const Shape e = fresh ? shape_of(s, plane_) : Shape{};
    // Every element that moves in the plane, repeats too: the loops are the program's.
    if (moves) {
        walls_->element(index, plane_move(s, plane_, fresh ? &e : nullptr), key, walls_on_, !fresh);
        review(out);
    }
    if (!fresh) return;  // programmed before
    if (e.length <= kFullCircle) return;
    latest_ = g.contour.next();
    g.size_by(e.length);
    Grid::Item item(e, s.block, index, stretch_, 0.0);
    item.protect = !first;
    if (first) {
        g.add(g.contour, item);
        forget_let_go();
        return;
    }
    // Paths executed before it that come near it (the contour comes back later).
    const std::vector<std::uint32_t>& near = g.lookup_adding(g.path, e, g.max_r, g.contour, item);
    Grid::Item& self = g.contour.items.back();
    Shape scratch;
    for (const std::uint32_t pid : near) {
        Grid::Item& p = g.path.items[pid];
        const Relation rel = relation(index, stretch_, p.index, p.stretch, p.transition);
        const Shape* part = checked_part(e, rel, scratch);
        if (part == nullptr) continue;
        const double threshold = threshold_for(rel, p.r);
        if (!near_enough(p.shape.extent(), extent_of(*part), threshold)) continue;
        const bool placed = placed_of(p) && role_of(self) != detail::WallRole::kUndecided;
        if (placed && role_of(self) != detail::WallRole::kWall) continue;
        const Shape path = p.shape.shape();
        if (p.approach && stands_near(path, *part, threshold)) continue;
        const Eigen::Vector2d* entry = p.approach ? approach_entry(p.index) : nullptr;
        const bool cross = entry != nullptr && at_entry(e, *entry);
        consider(PairView{path, p.block, p.r, plane_, *part, s.block, threshold, index, p.index,
                          latest_, cross, kind_of(p.approach, false, p.stretch != stretch_)},
                 placed, false, out);
    }
    g.bound(g.contour);
    forget_let_go();
}

void SelfApproachCheck::executed_now(const PathSegment& s, std::vector<SelfApproachFinding>& out) {
    // A segment of another block: the findings of the one before are final.
    if (!seen_ || !same_block(current_, s.block)) {
        if (!open_.empty()) flush(out);
        current_ = s.block;
        seen_ = true;
    }
    if (done()) return;
    const std::size_t waiting = pending_.waiting();
    const std::size_t at = pending_.find(s);
    leave_undecided(s, at, out);
    const bool leaves_head = departs_head(s, at, waiting);
    if (!of_element(s.role) || (at == waiting && !leaves_head)) return;
    pending_.advance(leaves_head ? 0 : at);
    const Pending p = pending_.at(0);
    // The last element of a stretch that has ended: no segment of its block is checked after
    // this one (G139: the G40 block departs; G237: the board's departure, not checked), and
    // none of another block may come to give its findings out.
    const bool running = active_ || pending_.waiting() > 1;
    // The approach cuts as the contour does (under G139 it is the first element's whole move),
    // and so does the G40 block's departure.
    if (!held_to_elements(s.role) && !leaves_head) return;
    check_path(s, p, running, out);
}

// The programmed element an executed segment belongs to, as a position after the head
// (the number waiting where it has none): the first pending one of its block (executed segments
// come in program order; transitions and the departure belong to the element before, the
// approach to the first). A rapid or an uncompensated move has none (the programmed elements
// are compensated ones): only the first is looked at, not the elements the run has programmed
// ahead.
std::size_t SelfApproachCheck::PendingQueue::find(const PathSegment& s) const {
    const std::size_t n = waiting();
    const std::size_t looked = s.role == Role::kUncompensated ? 1 : 64;
    for (std::size_t i = 0; i < n && i < looked; ++i)
        if (same_block(items_[head_ + i].block, s.block)) return i;
    return n;
}

void SelfApproachCheck::PendingQueue::push(const Pending& p) {
    items_.push_back(p);
    if (waiting() > kMost) ++head_;  // never executed: not checked
    compact();
}

void SelfApproachCheck::PendingQueue::advance(std::size_t n) {
    head_ += n;
    compact();
}

// Now and then: the elements before the head are done.
void SelfApproachCheck::PendingQueue::compact() {
    if (head_ > 1024 && 2 * head_ > items_.size()) {
        items_.erase(items_.begin(), items_.begin() + static_cast<std::ptrdiff_t>(head_));
        head_ = 0;
    }
}

// The stretches that ended undecided and whose last element the run has left: the first
// segment after it (of a later element, or of none) gives their findings out.
void SelfApproachCheck::leave_undecided(const PathSegment& s, std::size_t at,
                                        std::vector<SelfApproachFinding>& out) {
    const std::size_t waiting = pending_.waiting();
    while (!undecided_.empty()) {
        Undecided& u = undecided_.front();
        const bool found = at != waiting;
        const std::uint64_t index = found ? pending_.at(at).index : 0;
        if (found && index == u.last_index) {
            u.reached = true;
            break;
        }
        if (!(u.reached || (found && index > u.last_index))) break;
        leave(s, out);
    }
}

// An executed segment of the programmed element `p` held to the elements the grid brings near
// it (its own element's offset and its own corner's line left out).
void SelfApproachCheck::check_path(const PathSegment& s, const Pending& p, bool running,
                                   std::vector<SelfApproachFinding>& out) {
    Grid& g = grid(p.plane);
    if (s.role == Role::kApproach &&
        (approach_entries_.empty() || approach_entries_.back().index != p.index))
        approach_entries_.push_back(Entry{p.index, p.end});
    const std::uint64_t key = key_of(s, p.plane, p.r);
    if (!g.path.keys.insert(key)) return;  // the same path checked before
    const Shape e = shape_of(s, p.plane);
    if (e.length <= kFullCircle) return;
    const bool transition = s.role == Role::kTransition;
    const bool approach = s.role == Role::kApproach;
    const bool departure = s.role == Role::kDeparture;
    Grid::Item self(e, s.block, p.index, p.stretch, p.r);
    self.transition = transition;
    self.approach = approach;
    // Its element is placed once its stretch ended (or, an open contour's, at once).
    const bool self_placed = !(active_ && p.stretch == stretch_) || placed_of(self);
    const Extent extent = extent_of(e);
    Shape scratch;
    for (const std::uint32_t at : g.lookup_adding(g.contour, e, p.r, g.path, self)) {
        Grid::Item& c = g.contour.items[at];
        if (!c.protect) continue;
        const Relation rel =
            path_relation(c.index, c.stretch, p.index, p.stretch, transition, departure);
        // What checked_part() leaves out whatever the shape: the path's own element, and a
        // line at the path's own corner.
        if (rel == Relation::kOwn ||
            ((rel == Relation::kHeld || rel == Relation::kNext) && !c.shape.arc))
            continue;
        const double threshold = threshold_for(rel, p.r);
        // The box of the whole element first: a part of it lies within it.
        if (!near_enough(extent, c.shape.extent(), threshold)) continue;
        // What the wall model says: where the whole element is checked, before its shape is
        // made (asked for the same pairs, in the same order, as after).
        bool placed = false;
        const auto no_wall = [&] {
            const detail::WallRole role = role_of(c);
            placed = self_placed && role != detail::WallRole::kUndecided;
            return placed && role != detail::WallRole::kWall;
        };
        const bool whole =
            rel == Relation::kOther || rel == Relation::kBefore || rel == Relation::kAfter;
        if (whole && no_wall()) continue;
        const Shape contour = c.shape.shape();
        const Shape* part = checked_part(contour, rel, scratch);
        if (part == nullptr) continue;
        if (part != &contour && !near_enough(extent, extent_of(*part), threshold)) continue;
        if (!whole && no_wall()) continue;
        if ((approach || departure) && stands_near(e, *part, threshold)) continue;
        if (departure && ends_near(e, *part, threshold)) continue;
        const bool cross = (approach || departure) && at_entry(contour, p.end);
        consider(PairView{e, s.block, p.r, p.plane, *part, c.block, threshold, c.index, p.index,
                          g.contour.first + at, cross,
                          kind_of(approach, departure, c.stretch != p.stretch)},
                 placed, running, out);
    }
    if (!running) flush(out);
    g.bound(g.path);
    forget_let_go();
}

void SelfApproachCheck::consider(const PairView& k, bool placed, bool running,
                                 std::vector<SelfApproachFinding>& out) {
    // Only a crossing counts (an approach and an element at its entry point): proved not to
    // cross, nothing to measure.
    if (k.need_cross && plane::apart(k.path, k.contour, kTolerance + kApartMargin)) return;
    // Proved apart: no point of the path is as near as the threshold, so the search would find
    // none (every distance it computes is that of a point of the path to a point of the
    // element, at least the least distance). Most pairs end here (an element's neighbours),
    // before the findings are looked at.
    if (plane::apart_by_side(k.path, k.contour, k.threshold + kApartMargin) ||
        plane::apart(k.path, k.contour, k.threshold + kApartMargin))
        return;
    if (!unreported(k.path_block, k.contour_block)) return;
    if (!placed) {
        if (waiting_.size() >= kMaxDeferred) {  // the oldest measured as things stand
            const Candidate oldest = waiting_.front();
            waiting_.pop_front();
            settle(oldest.view(), false, out);
        }
        waiting_.emplace_back(k);
        return;
    }
    settle(k, running, out);
}

void SelfApproachCheck::settle(const PairView& k, bool running,
                               std::vector<SelfApproachFinding>& out) {
    Found f{{}, k.contour_index, k.path_index};
    if (!measure(k, f.f)) return;
    if (k.need_cross && !crosses(f.f)) return;
    // Against a stretch's last element, perhaps its departure: held.
    if (active_ && k.plane == plane_ && k.contour_id == latest_)
        hold(held_, f);
    else if (Undecided* u = undecided_of(k.plane, k.contour_id))
        hold(u->held, f);
    else
        give(f, running, out);
}

// False for a pair given out already (or, at kMaxFindings pairs given out, a new pair once one
// more was found: the check then stops).
bool SelfApproachCheck::unreported(const BlockRef& path_block, const BlockRef& contour_block) {
    const Pair pair = pair_of(path_block, contour_block);
    const bool beyond = reported_.size() >= kMaxFindings && open_finding(pair) == nullptr &&
                        std::find(reported_.begin(), reported_.end(), pair) == reported_.end();
    return !closed(pair) || (beyond && !capped_);
}

bool SelfApproachCheck::measure(const PairView& k, SelfApproachFinding& f) {
    const Pair pair = pair_of(k.path_block, k.contour_block);
    const bool beyond = reported_.size() >= kMaxFindings && open_finding(pair) == nullptr &&
                        std::find(reported_.begin(), reported_.end(), pair) == reported_.end();
    if (closed(pair) && !(beyond && !capped_)) return false;
    const Nearest n = least_distance(k.path, k.contour, k.threshold);
    if (n.distance >= k.threshold) return false;
    if (beyond) {
        capped_ = true;
        return false;
    }
    f = SelfApproachFinding{};
    f.path_block = k.path_block;
    f.contour_block = k.contour_block;
    f.kind = k.kind;
    f.distance = n.distance;
    f.radius = k.r;
    // The point of the path nearest the element, for the plot's marker (the third axis at
    // the plane's origin: the plot shows the plane).
    const Vec2 q = point_at(k.path, n.t);
    const PlaneAxes a = plane_axes(k.plane);
    f.where = Point::Zero();
    f.where[a.first] = q.x();
    f.where[a.second] = q.y();
    return true;
}

}  // namespace apci::run
