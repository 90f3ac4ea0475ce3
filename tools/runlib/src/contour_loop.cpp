// SPDX-License-Identifier: MIT
#include "contour_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/element.h"

namespace apci::run::plane {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

using geom::cross;

// The angle from a to b as seen from p, signed, in (-pi, pi].
double seen_angle(const Vec2& p, const Vec2& a, const Vec2& b) {
    return geom::turn_angle(a - p, b - p);
}

// True when p lies in the region an arc and its chord enclose: within the circle of its
// middle radius and on the arc's side of the chord (counter-clockwise arcs bulge to the right
// of start -> end); for a full circle the whole disc.
bool in_arc_region(const Parametric& e, const Vec2& p) {
    const double r = 0.5 * (e.r0 + e.r1);
    if ((p - e.centre).squaredNorm() >= r * r) return false;
    if (std::abs(e.sweep) >= kTwoPi) return true;
    const double side = cross(e.end - e.start, p - e.start);
    return e.sweep > 0.0 ? side < 0.0 : side > 0.0;
}

}  // namespace

// A line by its ends; an arc by its ends and, where its turn passes an axis direction, its
// larger radius there (the radius changes by |r1 - r0| at most along it: that much more).
Bounds bounds(std::span<const Parametric> loop) noexcept {
    Bounds b;
    b.lo = Vec2::Constant(std::numeric_limits<double>::infinity());
    b.hi = Vec2::Constant(-std::numeric_limits<double>::infinity());
    for (const Parametric& e : loop) {
        b.lo = b.lo.cwiseMin(e.start.cwiseMin(e.end));
        b.hi = b.hi.cwiseMax(e.start.cwiseMax(e.end));
        if (!is_arc(e)) continue;
        const double rmax = std::max(e.r0, e.r1);
        const double pad = std::abs(e.r1 - e.r0);
        const bool ends = e.r0 > 0.0 && e.r1 > 0.0;
        const Vec2 from = ends ? Vec2((e.start - e.centre) / e.r0) : Vec2(1, 0);
        const Vec2 to = ends ? Vec2((e.end - e.centre) / e.r1) : Vec2(1, 0);
        for (const Vec2& axis : {Vec2(1, 0), Vec2(0, 1), Vec2(-1, 0), Vec2(0, -1)}) {
            if (ends && !within_turn(from, to, e.sweep, axis)) continue;
            const Vec2 p = e.centre + rmax * axis;
            b.lo = b.lo.cwiseMin(p);
            b.hi = b.hi.cwiseMax(p);
        }
        b.lo.array() -= pad;
        b.hi.array() += pad;
    }
    return b;
}

double signed_area(std::span<const Parametric> loop) noexcept {
    double area = 0.0;
    for (const Parametric& e : loop) {
        area += 0.5 * cross(e.start, e.end);
        if (is_arc(e)) {
            const double r = 0.5 * (e.r0 + e.r1);
            area += 0.5 * r * r * (e.sweep - std::sin(e.sweep));
        }
    }
    return area;
}

int winding_number(std::span<const Parametric> loop, const Vec2& p) noexcept {
    double turned = 0.0;
    for (const Parametric& e : loop) {
        const bool full = is_arc(e) && std::abs(e.sweep) >= kTwoPi;
        if (!full) turned += seen_angle(p, e.start, e.end);
        if (is_arc(e) && in_arc_region(e, p)) turned += e.sweep > 0.0 ? kTwoPi : -kTwoPi;
    }
    return static_cast<int>(std::lround(turned / kTwoPi));
}

double distance_to(std::span<const Parametric> loop, const Vec2& p) noexcept {
    double best = std::numeric_limits<double>::infinity();
    for (const Parametric& e : loop) best = std::min(best, distance_to(e, p));
    return best;
}

Within within(std::span<const Parametric> outer, std::span<const Parametric> inner, double tolerance,
              long budget) noexcept {
    if (outer.empty() || inner.empty()) return Within::kNot;
    return within(outer, bounds(outer), inner, bounds(inner), tolerance, budget);
}

Within within(std::span<const Parametric> outer, const Bounds& outer_box, std::span<const Parametric> inner,
              const Bounds& inner_box, double tolerance, long budget) noexcept {
    if (outer.empty() || inner.empty()) return Within::kNot;
    if ((inner_box.lo.array() < outer_box.lo.array() - tolerance).any() ||
        (inner_box.hi.array() > outer_box.hi.array() + tolerance).any())
        return Within::kNot;
    const long pairs = static_cast<long>(outer.size()) * static_cast<long>(inner.size());
    if (pairs > budget) return Within::kUnknown;
    bool apart_everywhere = true;
    for (const Parametric& a : inner) {
        for (const Parametric& b : outer)
            if (!apart(a, b, tolerance)) {
                apart_everywhere = false;
                break;
            }
        if (!apart_everywhere) break;
    }
    if (apart_everywhere)
        return winding_number(outer, inner.front().start) != 0 ? Within::kWithin : Within::kNot;
    // They come near: every point sampled must lie inside or on outer, and one inside.
    bool some_inside = false;
    constexpr int kSamples = 16;
    for (const Parametric& e : inner)
        for (int i = 0; i <= kSamples; ++i) {
            const Vec2 p = point_at(e, static_cast<double>(i) / kSamples);
            if (distance_to(outer, p) <= tolerance) continue;
            if (winding_number(outer, p) == 0) return Within::kNot;
            some_inside = true;
        }
    return some_inside ? Within::kWithin : Within::kNot;
}

}  // namespace apci::run::plane
