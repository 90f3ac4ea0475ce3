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

// kTangent: the offset elements meet (within kPathTolerance) and are joined as they are.
// kInside: the path turns towards the tool; the offset elements overlap and are trimmed.
// kOutside: it turns away; they leave a gap that a transition bridges.
enum class CornerKind : std::uint8_t { kTangent, kInside, kOutside };


// The distance between the two offset ends at a corner of tool radius r that turns by
// `turn`: 2 r |sin(turn / 2)| (the chord of the circular transition).
double offset_gap(double turn, double r) noexcept;

// The corner between an element ending with unit tangent end_tangent and the next one
// starting with start_tangent (docs/compensation.md, "The tolerance model"):
// - tangent when the offset ends lie at most kPathTolerance apart (offset_gap);
// - outside when it turns away from the tool;
// - an inside turn of nearly 180 degrees is a reversal, outside too, when the wedge
//   between the elements is at most kMaxReversalWedgeAngle and narrower than
//   kReversalWedgeWidth over shorter_length (the length of the shorter of the two
//   programmed elements): an exact reversal written with rounded coordinates;
// - inside otherwise.
CornerKind classify_corner(const Vec2& end_tangent, const Vec2& start_tangent, Side side,
                           double r, double shorter_length) noexcept;

struct InsideTrim {
    Reason reason = Reason::kNone;  // KorrError reasons, or kNone
    OffsetElement held;             // ends at the intersection
    OffsetElement next;             // starts at the intersection
};
// Trims the held offset element's end and the next one's start at the intersection of
// their carriers (at the corner: the held one's at its end, the next one's at its start)
// that lies on both, within kTrimTolerance of their ends, and is latest on the held
// element (nearest its end). The intersections are computed relative to the corner, so
// nearly tangent corners lose no precision. No such point: kHeldElementTooShort /
// kNextElementTooShort when the intersection nearest the corner lies beyond the held /
// the next element, kNoCornerSolution when the carriers do not meet.
InsideTrim trim_inside_corner(const OffsetElement& held, const OffsetElement& next,
                              const Vec2& corner) noexcept;
// The same trim made on held and next themselves (no copies): the reason, and on a failure
// both are left as they were.
Reason trim_inside_corner_in_place(OffsetElement& held, OffsetElement& next,
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
// and a line of length r arriving along start_tangent (r tan(turn / 4) for a reversal read
// from a wedge, whose turn round the corner is a little over 180 degrees: the chamfer then
// touches the circle of radius r about the corner).
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
// The corner's kind and its failure (KorrError reasons, or kNone).
struct JoinKind {
    Reason reason = Reason::kNone;
    CornerKind kind = CornerKind::kTangent;
};
// join_corner made on held and next themselves (no copies; the compensator's): held's end and
// next's start made final, `transition` set for an outside corner (left as it was otherwise).
// On a failure held and next are left as they were.
JoinKind join_corner_in_place(OffsetElement& held, OffsetElement& next, Transition& transition,
                              const Vec2& corner, const Vec2& end_tangent,
                              const Vec2& start_tangent, Side side, double r, TransitionMode mode,
                              double shorter_length) noexcept;

// The whole corner: classify, then join (tangent), trim (inside) or bridge (outside).
// end_tangent / start_tangent are the programmed unit tangents at the corner;
// shorter_length the length of the shorter programmed element (classify_corner).
CornerJoin join_corner(const OffsetElement& held, const OffsetElement& next, const Vec2& corner,
                       const Vec2& end_tangent, const Vec2& start_tangent, Side side, double r,
                       TransitionMode mode, double shorter_length) noexcept;

}  // namespace rwmos::geom
