// SPDX-License-Identifier: MIT
// Building blocks of the generated contours that the compensation tests feed the geometry, the
// emulator and LinuxCNC: deterministic random numbers, elements grown from a heading, rounding
// as NC programs write coordinates, and the self-approach checks that keep a contour within
// what any control with one element of lookahead can compensate (docs/compensation.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "rng.h"
#include "rwmos/geometry/shared.h"

namespace apci::test {

using rwmos::geom::Element;
using rwmos::geom::Vec2;

inline constexpr double kPi = std::numbers::pi;

inline Vec2 dir(double angle) {
    return {std::cos(angle), std::sin(angle)};
}
inline Vec2 turned(const Vec2& v, double a) {
    return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()};
}
inline double heading(const Vec2& t) {
    return std::atan2(t.y(), t.x());
}

// The arc starting at `start` along `start_heading`, of `radius`, turning by `turn` radians
// (> 0 counter-clockwise).
inline Element arc_from(const Vec2& start, double start_heading, double radius, double turn) {
    const bool ccw = turn > 0;
    const Vec2 left(-std::sin(start_heading), std::cos(start_heading));
    const Vec2 centre = start + radius * (ccw ? left : Vec2(-left));
    return rwmos::geom::make_arc(start, centre + turned(start - centre, turn), centre, ccw);
}

// Rounds to `decimals` places as an NC program writes a coordinate (half away from zero).
inline double round_to(double v, int decimals) {
    const double scale = std::pow(10.0, decimals);
    return std::round(v * scale) / scale;
}
inline Vec2 round_to(const Vec2& v, int decimals) {
    return {round_to(v.x(), decimals), round_to(v.y(), decimals)};
}

// The bounding box of an element (arcs: of their circle's part they run on, sampled), grown by
// `grow`.
struct Box {
    Vec2 lo, hi;
    bool overlaps(const Box& o) const {
        return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y();
    }
};
inline Box box_of(const Element& e, double grow) {
    Box b{e.start.cwiseMin(e.end), e.start.cwiseMax(e.end)};
    if (rwmos::geom::is_arc(e)) {
        for (int i = 1; i < 32; ++i) {
            const Vec2 p = rwmos::geom::point_at(e, i / 32.0);
            b.lo = b.lo.cwiseMin(p);
            b.hi = b.hi.cwiseMax(p);
        }
        // Between samples an arc bulges by at most r (1 - cos(sweep / 64)).
        grow += rwmos::geom::radius(e) * (1 - std::cos(std::abs(rwmos::geom::sweep(e)) / 64));
    }
    b.lo -= Vec2(grow, grow);
    b.hi += Vec2(grow, grow);
    return b;
}

// ---- Offsets from their definition (independent of the library's offset, intersection and
// trim code): r to the tool's side (left for G41), an arc's radius linear in the angle from
// its start to its end radius (the spiral the board runs from start to end point).

// The tool lies inside the arc (on its concave side).
inline bool concave_for(const Element& arc, bool left) {
    return arc.ccw == left;
}

// The offset of e at fraction t (by angle for arcs); t may lie a little outside [0, 1] (the
// element continued: a line straight on, an arc round its circle at its end radius).
inline Vec2 offset_point(const Element& e, double t, double r, bool left) {
    using namespace rwmos::geom;
    const double side = left ? 1.0 : -1.0;
    if (!is_arc(e)) {
        const Vec2 d = e.end - e.start;
        return e.start + t * d + side * r * left_normal(d.normalized());
    }
    const Vec2 u0 = e.start - e.centre;
    const double r0 = u0.norm(), r1 = end_radius(e);
    const double a = std::atan2(u0.y(), u0.x()) + t * sweep(e);
    const double rad = r0 + std::clamp(t, 0.0, 1.0) * (r1 - r0);
    const double towards = concave_for(e, left) ? -1.0 : 1.0;
    return e.centre + (rad + towards * r) * Vec2(std::cos(a), std::sin(a));
}

// Where p lies with respect to the offset of e: its signed distance from the offset (the line,
// or the spiral at p's angle; < 0 towards the element) and the fraction of e its foot lies at
// (lines unbounded; arcs in [0, 2 pi / sweep)).
struct OffsetReading {
    double residual;
    double fraction;
};
inline OffsetReading read_offset(const Element& e, const Vec2& p, double r, bool left) {
    using namespace rwmos::geom;
    if (!is_arc(e)) {
        const Vec2 t = (e.end - e.start).normalized();
        const Vec2 v = p - e.start;
        return {(left ? 1.0 : -1.0) * cross(t, v) - r, v.dot(t) / length(e)};
    }
    const double turn = std::abs(sweep(e));
    const double fraction = angle_between(e.start - e.centre, p - e.centre, e.ccw) / turn;
    const double t = std::min(fraction, 1.0);
    const double radius_there = radius(e) + t * (end_radius(e) - radius(e));
    const double rho = radius_there + (concave_for(e, left) ? -r : r);
    // Towards the element is inward on the convex side, outward on the concave.
    const double outward = (p - e.centre).norm() - rho;
    return {concave_for(e, left) ? -outward : outward, fraction};
}

// Where f (a function of t whose sign differs at lo and hi) changes sign, by bisection to
// double precision.
template <typename F>
double bisect_sign_change(F&& f, double lo, double hi) {
    const bool lo_negative = f(lo) <= 0;
    for (int m = 0; m < 200 && std::abs(hi - lo) > 1e-16; ++m) {
        const double mid = 0.5 * (lo + hi);
        ((f(mid) <= 0) == lo_negative ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// Sampled minimum distance from a to b; at most spacing / 2 above the true minimum.
inline double sampled_distance(const Element& a, const Element& b, double spacing) {
    const int n =
        std::max(8, static_cast<int>(std::ceil(rwmos::geom::length(a) / spacing)) + 1);
    double best = INFINITY;
    for (int i = 0; i <= n; ++i)
        best = std::min(best, rwmos::geom::distance_to(b, rwmos::geom::point_at(a, double(i) / n)));
    return best;
}

// True when no point of a comes closer to b than `threshold`: the distance changes no faster
// than the walk along a, so a stretch whose ends are far enough apart from b, for its length,
// needs no look inside; the others are halved (down to 1e-6 long).
inline bool farther_than(const Element& a, const Element& b, double threshold) {
    struct Span {
        double t0, t1, d0, d1;
    };
    const double len = rwmos::geom::length(a);
    const auto d = [&](double t) { return rwmos::geom::distance_to(b, rwmos::geom::point_at(a, t)); };
    std::vector<Span> stack{{0.0, 1.0, d(0.0), d(1.0)}};
    if (stack[0].d0 <= threshold || stack[0].d1 <= threshold) return false;
    while (!stack.empty()) {
        const Span s = stack.back();
        stack.pop_back();
        const double piece = len * (s.t1 - s.t0);
        if ((s.d0 + s.d1 - piece) / 2 > threshold || piece < 1e-6) continue;
        const double tm = 0.5 * (s.t0 + s.t1);
        const double dm = d(tm);
        if (dm <= threshold) return false;
        stack.push_back({s.t0, tm, s.d0, dm});
        stack.push_back({tm, s.t1, dm, s.d1});
    }
    return true;
}

// Non-adjacent elements stay more than 2r (plus `margin`) apart.
inline bool clear_of(const Element& e, const Element& other, double r, double margin = 0.0) {
    const double reach = 2 * r + margin;
    if (!box_of(e, reach).overlaps(box_of(other, 0.0))) return true;
    return farther_than(e, other, reach);
}

// Adjacent elements may come close only at their common corner: walking away from the
// corner along `from`, the distance to `other` grows until it exceeds 2r and stays above it.
// (An arc can curl back towards its neighbour far from the corner: self-approach as much as
// between non-adjacent elements.)
inline bool walks_away(const Element& from, bool outwards_from_end, const Element& other,
                       double r) {
    const double spacing = std::max(r, 1e-3) / 8;
    const double len = rwmos::geom::length(from);
    const double step = len / std::max(16.0, std::ceil(len / spacing) + 1);
    const double reach = 2 * r + spacing;
    const auto at = [&](double s) {
        const double t = std::min(s / len, 1.0);
        return rwmos::geom::distance_to(other, rwmos::geom::point_at(from, outwards_from_end ? 1.0 - t : t));
    };
    double last = 0;
    double s = step;
    // Until it is 2r away the distance must grow at every step.
    for (; s < len + 0.5 * step; s += step) {
        const double d = at(s);
        if (d < last) return false;
        last = d;
        if (d > reach) break;
    }
    // Then it must stay beyond 2r: the distance changes no faster than the walk, so the next
    // look is as far on as it has room to fall.
    while (s < len) {
        const double d = at(s);
        if (d <= reach) return false;
        if (d - (len - s) > reach) return true;
        s += std::max(step, d - reach);
    }
    return len <= 0 || at(len) > reach || last <= reach;
}

inline bool diverge(const Element& a, const Element& b, double r) {
    return walks_away(b, false, a, r) && walks_away(a, true, b, r);
}

// A new element may join a chain: it walks away from its predecessor (and the predecessor from
// it) and stays clear of all others. An element shorter than 2r cannot get 2r away from its
// neighbours: around it the rule is relaxed to "moves away" (the element after it moves away
// from the one before it, which it cannot be 2r from), and no two short elements follow each
// other. With may_come_back the contour may come back near itself (the self-approach no
// corner rule sees): between neighbours the rule is "moves away" throughout (an arc may curl
// back within 2r of its neighbour, a contour come back alongside after a sharp turn), and
// other elements need only stay r / 2 apart (a path r from one then comes closer than r to
// the other).
inline bool fits_chain(const std::vector<Element>& chain, const Element& e, double r,
                       double margin = 0.0, bool may_come_back = false) {
    if (chain.empty()) return true;
    const auto is_short = [r](const Element& x) { return rwmos::geom::length(x) < 2 * r; };
    const std::size_t n = chain.size();
    const Element& before = chain.back();
    const bool after_short = is_short(before);
    if (is_short(e) && after_short) return false;
    const double apart = may_come_back ? 0.0 : r;
    if (!walks_away(e, false, before, is_short(e) ? 0.0 : apart)) return false;
    if (!walks_away(before, true, e, after_short ? 0.0 : apart)) return false;
    if (after_short && n >= 2 && !walks_away(e, false, chain[n - 2], 0.0)) return false;
    const std::size_t skip = after_short ? 2 : 1;  // the neighbours checked above
    for (std::size_t j = 0; j + skip < n; ++j)
        if (!clear_of(e, chain[j], may_come_back ? r / 4 : r, margin)) return false;
    return true;
}

}  // namespace apci::test
