// SPDX-License-Identifier: MIT
// Exact least distances between lines and circular arcs in a plane, and a proof that two
// elements (a line, or an arc whose radius changes linearly with the angle, as the board runs
// arcs whose start and end radii differ) keep at least a given distance from each other.
// The self-approach check (self_approach.h) asks the proof first: where it holds, no point of
// the one comes within the limit of the other, so the check's search along the path cannot find
// one either and is skipped; where it does not hold, the search runs as before. The findings are
// the same; only their cost changes (docs/compensation.md, "Self-approach").
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "geometry/element.h"

namespace apci::run::plane {

using Vec2 = Eigen::Vector2d;

// A circular arc: about `centre`, radius `radius`, from the angle `phi0` (radians, from the
// first axis) turning by `sweep` (signed: positive counter-clockwise; |sweep| >= 2 pi is the
// whole circle).
struct Arc {
    Vec2 centre = Vec2::Zero();
    double radius = 0.0;
    double phi0 = 0.0;
    double sweep = 0.0;
};
// True when the direction v lies within a turn by `sweep` (signed radians; |sweep| >= 2 pi is
// every direction) that starts in the direction `from` and ends in `to`: on the turning side of
// `from` and not past `to`; for more than half a turn, not within the rest of the circle.
// Decided by signs: a direction within rounding of an end may go either way.
bool within_turn(const Vec2& from, const Vec2& to, double sweep, const Vec2& v) noexcept;

// The least distance between ...
double point_segment(const Vec2& p, const Vec2& a, const Vec2& b) noexcept;
double point_arc(const Vec2& p, const Arc& a) noexcept;
double segment_segment(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) noexcept;
double segment_arc(const Vec2& a0, const Vec2& a1, const Arc& b) noexcept;
double arc_arc(const Arc& a, const Arc& b) noexcept;

// A line from start to end, or an arc about centre from start to end (geom::Element, the element
// board and host share), with the terms the distances take computed once: at the fraction t of
// it, the angle phi0 + t * sweep and the radius r0 + t * (r1 - r0).
struct Parametric : geom::Element {
    double r0 = 0.0, r1 = 0.0, phi0 = 0.0, sweep = 0.0;
};
using geom::is_arc;

// An element from its ends (and an arc's centre and sense): its radii, start angle and sweep
// (geom::arc_sweep: magnitude in (0, 2 pi]; ends closer than 1e-9 make a full circle).
Parametric line_element(const Vec2& start, const Vec2& end) noexcept;
Parametric arc_element(const Vec2& start, const Vec2& end, const Vec2& centre, bool ccw) noexcept;
// The same arc again from the sweep and start angle arc_element gave for these numbers (kept by
// the caller): the same Parametric, bit for bit, without its atan2 and hypot.
Parametric arc_element(const Vec2& start, const Vec2& end, const Vec2& centre, bool ccw,
                       double sweep, double phi0) noexcept;
// The point at the fraction t (0..1) of e: an arc by its angle, the radius linear in it.
Vec2 point_at(const Parametric& e, double t) noexcept;
// The distance from p to e: to a line's nearest point; to an arc along the radius where p's
// direction from the centre lies within its turn (to the arc's radius at that angle), else to
// the nearer end.
double distance_to(const Parametric& e, const Vec2& p) noexcept;

// The least distance from a path to a contour element, and the fraction of the path where it is.
struct Nearest {
    double distance = INFINITY;
    double t = 0.0;
};

// Between two lines, exactly: 0 where they cross, else at an end of one of them (the distance
// from a point moving along a line to a segment is convex in its position). Where several
// places are as near (parallel lines), the first of: `path`'s start, its end, the foot on it of
// `contour`'s start, of its end.
Nearest lines_nearest(const Parametric& path, const Parametric& contour) noexcept;

// True when every point of `a` is at least `limit` from every point of `b`, proved: an arc is
// taken as circular arcs of its middle radius, each within |r1 - r0| / 2 of it, halved where the
// proof needs it (at most kMaxApartSteps distances). False when it is not so or not proved.
inline constexpr int kMaxApartSteps = 64;
bool apart(const Parametric& a, const Parametric& b, double limit) noexcept;

// A cheaper proof of the same, by one side of `a`: where `a` is a line, every point of `b` lies
// at least `limit` to one side of a's line; where `a` is an arc, every point of `b` lies at
// least `limit` inside or outside the circles a's radii span about its centre. True proves
// apart(a, b, limit); false decides nothing.
bool apart_by_side(const Parametric& a, const Parametric& b, double limit) noexcept;

}  // namespace apci::run::plane
