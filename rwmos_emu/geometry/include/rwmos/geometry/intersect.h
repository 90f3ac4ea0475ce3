// SPDX-License-Identifier: MIT
// Intersections of the unbounded carriers of offset elements: lines and full circles.
// Near-tangent meetings within kPointTolerance count as touching (one point), so that
// rounding cannot lose an intersection that the geometry has.
#pragma once

#include <array>
#include <cstddef>

#include "rwmos/geometry/offset.h"

namespace rwmos::geom {

struct Intersections {
    std::array<Vec2, 2> points{Vec2::Zero(), Vec2::Zero()};
    std::size_t count = 0;
};

// Line through p1 with direction d1, line through p2 with direction d2 (non-zero). No
// point when they are parallel.
Intersections intersect_lines(const Vec2& p1, const Vec2& d1, const Vec2& p2,
                              const Vec2& d2) noexcept;
// Line through p with unit direction d, circle about c with radius rho.
Intersections intersect_line_circle(const Vec2& p, const Vec2& d, const Vec2& c,
                                    double rho) noexcept;
// Circles about c1 and c2; none when concentric.
Intersections intersect_circles(const Vec2& c1, double rho1, const Vec2& c2, double rho2) noexcept;
// The carriers of a held offset element at its end and the next one at its start (lines;
// arcs: the circle through that end). trim_inside_corner (corner.h) computes the same
// meetings relative to the corner, where these absolute formulas lose precision.
Intersections intersect_carriers(const OffsetElement& held, const OffsetElement& next) noexcept;

}  // namespace rwmos::geom
