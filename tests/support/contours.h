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

#include "rwmos/geometry/element.h"

namespace apci::test {

using rwmos::geom::Element;
using rwmos::geom::Vec2;

inline constexpr double kPi = std::numbers::pi;

// Deterministic random numbers (splitmix64): every run is the same.
class Rng {
  public:
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    double log_uniform(double lo, double hi) {
        return std::exp(uniform(std::log(lo), std::log(hi)));
    }
    bool chance(double p) { return uniform() < p; }
    int integer(int lo, int hi) { return lo + static_cast<int>(next() % (hi - lo + 1)); }
    double sign() { return chance(0.5) ? 1.0 : -1.0; }
    template <typename T, std::size_t N>
    const T& pick(const T (&items)[N]) {
        return items[next() % N];
    }

  private:
    std::uint64_t state_;
};

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
    const int n =
        std::max(16, static_cast<int>(std::ceil(rwmos::geom::length(from) / spacing)) + 1);
    const double len = rwmos::geom::length(from);
    double last = 0;
    bool clear = false;
    for (int i = 1; i <= n; ++i) {
        const double t = outwards_from_end ? 1.0 - double(i) / n : double(i) / n;
        const double d = rwmos::geom::distance_to(other, rwmos::geom::point_at(from, t));
        if (clear) {
            if (d <= 2 * r + spacing) return false;
            // The distance changes no faster than the walk: the rest cannot come back.
            if (d - len * (1.0 - double(i) / n) > 2 * r + spacing) return true;
        } else {
            if (d < last) return false;
            clear = d > 2 * r + spacing;
        }
        last = d;
    }
    return true;
}

inline bool diverge(const Element& a, const Element& b, double r) {
    return walks_away(b, false, a, r) && walks_away(a, true, b, r);
}

// A new element may join a chain: it diverges from its predecessor and stays clear of all
// others. An element shorter than 2r cannot get 2r away from its neighbours: around it the
// rule moves one element on (the element after it diverges from the one before it, as if they
// met), and no two short elements follow each other.
inline bool fits_chain(const std::vector<Element>& chain, const Element& e, double r,
                       double margin = 0.0) {
    if (chain.empty()) return true;
    const auto is_short = [r](const Element& x) { return rwmos::geom::length(x) < 2 * r; };
    const std::size_t n = chain.size();
    const bool after_short = is_short(chain.back());
    if (is_short(e) && after_short) return false;
    if (is_short(e)) {
        // It cannot diverge from its predecessor by 2r; it must not turn back into it.
        if (!walks_away(e, false, chain.back(), 0.0)) return false;
    } else if (after_short) {
        if (n >= 2 && !diverge(chain[n - 2], e, r)) return false;
        if (!walks_away(e, false, chain.back(), 0.0)) return false;
    } else if (!diverge(chain.back(), e, r)) {
        return false;
    }
    const std::size_t skip = after_short ? 2 : 1;  // the neighbours checked above
    for (std::size_t j = 0; j + skip < n; ++j)
        if (!clear_of(e, chain[j], r, margin)) return false;
    return true;
}

}  // namespace apci::test
