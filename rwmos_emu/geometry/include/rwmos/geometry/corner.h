// SPDX-License-Identifier: MIT
// Joining two consecutive offset elements at the programmed corner between them:
// classify the corner from the tangents and the side, trim inside corners at the
// intersection of the offset elements, bridge outside corners with a transition
// (circular G26 or linear G25). docs/compensation.md states the rules.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "rwmos/geometry/offset.h"

namespace rwmos::geom {

// Outside-corner transition: kCircular (G26, default) an arc of radius r about the
// programmed corner; kLinear (G25) the offset elements extended along their tangents to
// their intersection (bounded beyond kLinearCornerMaxTurn, see tolerances.h).
enum class TransitionMode : std::uint8_t { kCircular, kLinear };

// kTangent: no transition, the offset elements meet. kInside: the path turns towards the
// tool; the offset elements overlap and are trimmed. kOutside: it turns away; they leave
// a gap that a transition bridges.
enum class CornerKind : std::uint8_t { kTangent, kInside, kOutside };

// Signed angle from direction t1 to t2, in (-pi, pi], counter-clockwise positive.
double turn_angle(const Vec2& t1, const Vec2& t2) noexcept;

// The corner between an element ending with unit tangent end_tangent and the next one
// starting with start_tangent. Tangent when it turns by at most kTangentAngleTolerance
// or the gap r * |turn| is at most kPointTolerance; a reversal (|turn| = pi) is outside.
CornerKind classify_corner(const Vec2& end_tangent, const Vec2& start_tangent, Side side,
                           double r) noexcept;

struct InsideTrim {
    Reason reason = Reason::kNone;  // KorrError reasons, or kNone
    OffsetElement held;             // ends at the intersection
    OffsetElement next;             // starts at the intersection
};
// Trims the held offset element's end and the next one's start at the intersection of
// their carriers that lies on both (within kTrimTolerance) and is nearest the programmed
// corner. No such point: kHeldElementTooShort / kNextElementTooShort when the nearest
// intersection lies outside the held / the next element, kNoCornerSolution when the
// carriers do not meet.
InsideTrim trim_inside_corner(const OffsetElement& held, const OffsetElement& next,
                              const Vec2& corner) noexcept;

// At most three elements bridge an outside corner.
struct Transition {
    std::array<Element, 3> elements{};
    std::size_t count = 0;
};
// The transition from held_end (the held offset element's end, leaving along
// end_tangent) to next_start (the next one's start, arriving along start_tangent) around
// the programmed corner, for an outside corner of tool radius r.
// kCircular: one arc about the corner of radius r.
// kLinear: turns up to kLinearCornerMaxTurn: two lines along the tangents meeting at
// their intersection; sharper turns: a line along end_tangent of length r, a chamfer line,
// and a line of length r arriving along start_tangent.
Transition outside_transition(const Vec2& corner, const Vec2& held_end, const Vec2& end_tangent,
                              const Vec2& next_start, const Vec2& start_tangent, Side side,
                              double r, TransitionMode mode) noexcept;

struct CornerJoin {
    Reason reason = Reason::kNone;
    CornerKind kind = CornerKind::kTangent;
    OffsetElement held;     // the held offset element, its end final
    OffsetElement next;     // the next offset element, its start final
    Transition transition;  // outside corners only
};
// The whole corner: classify, then snap (tangent), trim (inside) or bridge (outside).
// end_tangent / start_tangent are the programmed unit tangents at the corner.
CornerJoin join_corner(const OffsetElement& held, const OffsetElement& next, const Vec2& corner,
                       const Vec2& end_tangent, const Vec2& start_tangent, Side side, double r,
                       TransitionMode mode) noexcept;

}  // namespace rwmos::geom
