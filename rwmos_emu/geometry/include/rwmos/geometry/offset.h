// SPDX-License-Identifier: MIT
// Offsetting a programmed element by the tool radius, left (G41) or right (G42) of the
// direction of travel, and the trimming of offset elements at corners.
#pragma once

#include <cstdint>

#include "rwmos/geometry/shared.h"
#include "rwmos/geometry/errors.h"

namespace rwmos::geom {

// G41: tool left of the direction of travel; G42: right. (TC Left / Right objects.)
enum class Side : std::uint8_t { kLeft, kRight };

// +1 for Left, -1 for Right: the offset point is p + side_sign * r * left_normal(t).
constexpr double side_sign(Side s) noexcept {
    return s == Side::kLeft ? 1.0 : -1.0;
}

// An element of the offset path. Its sweep is kept explicitly: trimming can leave an arc
// almost full or almost empty, and start == end alone would not tell which.
struct OffsetElement {
    Element path;
    double sweep = 0.0;             // arcs: signed, counter-clockwise > 0; lines: 0
    Vec2 direction = Vec2::Zero();  // lines: unit direction, kept when trimmed to nothing
};

// The checks every programmed element passes before it is offset: its kind and coordinates
// (CalcError), and for arcs the centre (CenterError). kNone when fine.
Reason check_element(const Element& e) noexcept;

// The point at distance r beside p, on the given side of the direction tangent.
Vec2 offset_point(const Vec2& p, const Vec2& tangent, double r, Side side) noexcept;
// An arc's offset radius: its radius minus r on the concave side, plus r on the convex.
double offset_radius(const Element& arc, double r, Side side) noexcept;
// The same for an arc of radius arc_radius (radius(arc)) turning counter-clockwise when ccw.
double offset_radius(double arc_radius, bool ccw, double r, Side side) noexcept;

struct OffsetResult {
    Reason reason = Reason::kNone;  // kOffsetRadiusNotPositive (CalcError) or kNone
    OffsetElement element;
};
// The element moved sideways by r. Expects check_element(e) == kNone and a line that is
// not plane-free. An arc keeps its centre, direction and sweep; its start and end radius
// each move by r (rho = R - r on the concave side). CalcError when rho < 0 by more than
// kOffsetRadiusTolerance (the tool is larger than the arc); a rho within it is kept at
// kMinOffsetRadius (the tool fits the arc: its centre stays at the arc's centre). A full
// circle stays a full circle (its offset end is its offset start).
OffsetResult offset_element(const Element& e, double r, Side side) noexcept;

// Length of an offset element (trimmed arcs by their explicit sweep).
double offset_length(const OffsetElement& o) noexcept;
// Circumference of an offset arc, 0 for a line.
double circumference(const OffsetElement& o) noexcept;
// Distance travelled from the start to x, for x on the element's line or circle:
// lines by projection (negative before the start); arcs in [0, circumference).
double distance_along(const OffsetElement& o, const Vec2& x) noexcept;

// The element ending at x, where x lies `along` from its start (0 <= along <= length).
OffsetElement trim_end(const OffsetElement& o, const Vec2& x, double along) noexcept;
// The element starting at x, where x lies `along` from its start (0 <= along <= length).
OffsetElement trim_start(const OffsetElement& o, const Vec2& x, double along) noexcept;
// The same, changing o itself (no copy of the element).
void trim_end_in_place(OffsetElement& o, const Vec2& x, double along) noexcept;
void trim_start_in_place(OffsetElement& o, const Vec2& x, double along) noexcept;

// What the spooler receives: arcs turning less than half a circle with a chord of at
// most kMinArcChord become lines (so no emitted arc reads as a full circle), a full
// offset circle ends exactly at its start, and an offset arc whose radius is below the path
// tolerance at both ends (a tool that just fits a concave arc: its centre stays at the arc's
// centre) becomes a line, because its angles say nothing once a tangent join has moved one of
// its ends by as much as its radius.
Element emitted_path(const OffsetElement& o) noexcept;

}  // namespace rwmos::geom
