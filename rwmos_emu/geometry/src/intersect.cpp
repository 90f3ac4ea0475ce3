// SPDX-License-Identifier: MIT
#include "rwmos/geometry/intersect.h"

#include <algorithm>
#include <cmath>

#include "rwmos/geometry/shared.h"

namespace rwmos::geom {

Intersections intersect_lines(const Vec2& p1, const Vec2& d1, const Vec2& p2,
                              const Vec2& d2) noexcept {
    Intersections out;
    const double denom = cross(d1, d2);
    if (denom == 0.0) return out;
    out.points[0] = p1 + (cross(p2 - p1, d2) / denom) * d1;
    out.count = 1;
    return out;
}

Intersections intersect_line_circle(const Vec2& p, const Vec2& d, const Vec2& c,
                                    double rho) noexcept {
    Intersections out;
    const Vec2 foot = p + (c - p).dot(d) * d;  // the point of the line nearest the centre
    const double h = (foot - c).norm();
    if (h > rho + kPointTolerance) return out;
    const double half_chord = std::sqrt(std::max(0.0, (rho - h) * (rho + h)));
    if (half_chord == 0.0) {
        out.points[0] = foot;
        out.count = 1;
        return out;
    }
    out.points[0] = foot - half_chord * d;
    out.points[1] = foot + half_chord * d;
    out.count = 2;
    return out;
}

Intersections intersect_circles(const Vec2& c1, double rho1, const Vec2& c2, double rho2) noexcept {
    Intersections out;
    const Vec2 between = c2 - c1;
    const double dist = between.norm();
    if (dist == 0.0) return out;
    if (dist > rho1 + rho2 + kPointTolerance || dist < std::abs(rho1 - rho2) - kPointTolerance)
        return out;
    const Vec2 u = between / dist;
    // Distance from c1 to the common chord, along u.
    const double a = (dist * dist + rho1 * rho1 - rho2 * rho2) / (2 * dist);
    const double h = std::sqrt(std::max(0.0, rho1 * rho1 - a * a));
    const Vec2 mid = c1 + a * u;
    if (h == 0.0) {
        out.points[0] = mid;
        out.count = 1;
        return out;
    }
    out.points[0] = mid + h * left_normal(u);
    out.points[1] = mid - h * left_normal(u);
    out.count = 2;
    return out;
}

Intersections intersect_carriers(const OffsetElement& held, const OffsetElement& next) noexcept {
    const bool a_arc = is_arc(held.path);
    const bool b_arc = is_arc(next.path);
    if (!a_arc && !b_arc)
        return intersect_lines(held.path.start, held.direction, next.path.start, next.direction);
    if (!a_arc)
        return intersect_line_circle(held.path.start, held.direction, next.path.centre,
                                     radius(next.path));
    if (!b_arc)
        return intersect_line_circle(next.path.start, next.direction, held.path.centre,
                                     end_radius(held.path));
    return intersect_circles(held.path.centre, end_radius(held.path), next.path.centre,
                             radius(next.path));
}

}  // namespace rwmos::geom
