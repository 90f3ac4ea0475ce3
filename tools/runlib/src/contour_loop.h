// SPDX-License-Identifier: MIT
// Closed contours in a plane, as a run of lines and arcs (plane_distance.h's Parametric) that ends
// where it started: their signed area (which way they run), whether they wind round a point,
// and whether one lies within another. The self-approach check's model of what a program
// leaves standing (wall_model.h, docs/compensation.md "What is a wall") is built on these.
#pragma once

#include <span>

#include "apci/run/plane_distance.h"

namespace apci::run::plane {

// The signed area a closed run of elements encloses: > 0 counter-clockwise. Each arc adds its
// chord's share and the circular segment between chord and arc (of its middle radius).
double signed_area(std::span<const Parametric> loop) noexcept;

// How many times the closed run winds round p (counter-clockwise positive): 0 outside. Exact
// for lines and circular arcs; an arc whose radii differ is taken at its middle radius (a
// point that near the arc is decided by distances, not by this).
int winding_number(std::span<const Parametric> loop, const Vec2& p) noexcept;

// The least distance from p to the run.
double distance_to(std::span<const Parametric> loop, const Vec2& p) noexcept;

// A box holding every point of the run (corners lo, hi).
struct Bounds {
    Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();
};
Bounds bounds(std::span<const Parametric> loop) noexcept;

// Where `inner` lies with respect to `outer`:
//   kWithin: every point of inner is inside outer or within `tolerance` of it, and some point
//            of it farther than that inside (not the same contour run again);
//   kNot:    some point of inner lies outside outer by more than `tolerance` (or the two are
//            the same contour);
//   kUnknown: the test would take more than `budget` element pairs.
// Proved where their elements keep more than `tolerance` apart (apart()): then one point of
// inner decides. Where they come that near (a shared or touching stretch), every element of
// inner is sampled at its ends and 15 points between.
enum class Within { kWithin, kNot, kUnknown };
// The boxes (bounds()) may be given, where the caller keeps them.
Within within(std::span<const Parametric> outer, std::span<const Parametric> inner, double tolerance,
              long budget) noexcept;
Within within(std::span<const Parametric> outer, const Bounds& outer_box,
              std::span<const Parametric> inner, const Bounds& inner_box, double tolerance,
              long budget) noexcept;

}  // namespace apci::run::plane
