// SPDX-License-Identifier: MIT
#include "rwmos/geometry/corner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rwmos/geometry/intersect.h"
#include "rwmos/geometry/tolerances.h"

namespace rwmos::geom {
namespace {

// Where x lies on an offset element, as distance along it, choosing among the readings
// of an arc's angle (x - C, x, x + C for circumference C) the one that lies on the
// element and is nearest the given end (the corner's end). Returns false if none does.
bool locate_on(const OffsetElement& o, const Vec2& x, bool near_end, double& along) noexcept {
    const double len = offset_length(o);
    const double raw = distance_along(o, x);
    const double period = circumference(o);
    const double readings[3] = {raw, raw - period, raw + period};
    const int count = period > 0.0 ? 3 : 1;
    bool found = false;
    for (int i = 0; i < count; ++i) {
        const double v = readings[i];
        if (v < -kTrimTolerance || v > len + kTrimTolerance) continue;
        const double clamped = std::clamp(v, 0.0, len);
        const bool better = near_end ? clamped > along : clamped < along;
        if (!found || better) along = clamped;
        found = true;
    }
    return found;
}

Element line(const Vec2& a, const Vec2& b) noexcept {
    return make_line(a, b);
}

}  // namespace

double turn_angle(const Vec2& t1, const Vec2& t2) noexcept {
    return std::atan2(cross(t1, t2), t1.dot(t2));
}

CornerKind classify_corner(const Vec2& end_tangent, const Vec2& start_tangent, Side side,
                           double r) noexcept {
    const double turn = turn_angle(end_tangent, start_tangent);
    const double magnitude = std::abs(turn);
    if (magnitude <= kTangentAngleTolerance || r * magnitude <= kPointTolerance)
        return CornerKind::kTangent;
    // A reversal has no inside: the tool goes round the end of the element.
    if (magnitude >= std::numbers::pi - kTangentAngleTolerance) return CornerKind::kOutside;
    const bool turns_left = turn > 0.0;
    return turns_left == (side == Side::kLeft) ? CornerKind::kInside : CornerKind::kOutside;
}

InsideTrim trim_inside_corner(const OffsetElement& held, const OffsetElement& next,
                              const Vec2& corner) noexcept {
    InsideTrim out;
    const Intersections meet = intersect_carriers(held, next);
    if (meet.count == 0) {
        out.reason = Reason::kNoCornerSolution;
        return out;
    }
    double best_distance = std::numeric_limits<double>::infinity();
    double nearest_distance = std::numeric_limits<double>::infinity();
    Reason nearest_failure = Reason::kNoCornerSolution;
    for (std::size_t i = 0; i < meet.count; ++i) {
        const Vec2& x = meet.points[i];
        const double to_corner = (x - corner).norm();
        double held_along = 0.0;
        double next_along = 0.0;
        const bool on_held = locate_on(held, x, true, held_along);
        const bool on_next = locate_on(next, x, false, next_along);
        if (!on_held || !on_next) {
            if (to_corner < nearest_distance) {
                nearest_distance = to_corner;
                nearest_failure =
                    on_held ? Reason::kNextElementTooShort : Reason::kHeldElementTooShort;
            }
            continue;
        }
        if (to_corner < best_distance) {
            best_distance = to_corner;
            out.held = trim_end(held, x, held_along);
            out.next = trim_start(next, x, next_along);
        }
    }
    if (best_distance == std::numeric_limits<double>::infinity()) out.reason = nearest_failure;
    return out;
}

Transition outside_transition(const Vec2& corner, const Vec2& held_end, const Vec2& end_tangent,
                              const Vec2& next_start, const Vec2& start_tangent, Side side,
                              double r, TransitionMode mode) noexcept {
    Transition out;
    if (mode == TransitionMode::kCircular) {
        // Outside corners turn away from the tool: right (clockwise) for G41.
        out.elements[0] = make_arc(held_end, next_start, corner, side == Side::kRight);
        out.count = 1;
        return out;
    }
    const double turn = std::abs(turn_angle(end_tangent, start_tangent));
    if (turn <= kLinearCornerMaxTurn) {
        const Intersections meet =
            intersect_lines(held_end, end_tangent, next_start, start_tangent);
        if (meet.count == 1) {
            out.elements[0] = line(held_end, meet.points[0]);
            out.elements[1] = line(meet.points[0], next_start);
            out.count = 2;
            return out;
        }
    }
    const Vec2 extended_end = held_end + r * end_tangent;
    const Vec2 extended_start = next_start - r * start_tangent;
    out.elements[0] = line(held_end, extended_end);
    out.elements[1] = line(extended_end, extended_start);
    out.elements[2] = line(extended_start, next_start);
    out.count = 3;
    return out;
}

CornerJoin join_corner(const OffsetElement& held, const OffsetElement& next, const Vec2& corner,
                       const Vec2& end_tangent, const Vec2& start_tangent, Side side, double r,
                       TransitionMode mode) noexcept {
    CornerJoin out;
    out.kind = classify_corner(end_tangent, start_tangent, side, r);
    out.held = held;
    out.next = next;
    switch (out.kind) {
        case CornerKind::kTangent:
            // The offset ends lie at most r * kTangentAngleTolerance apart: make them one.
            out.next.path.start = held.path.end;
            return out;
        case CornerKind::kInside: {
            const InsideTrim trim = trim_inside_corner(held, next, corner);
            out.reason = trim.reason;
            if (trim.reason == Reason::kNone) {
                out.held = trim.held;
                out.next = trim.next;
            }
            return out;
        }
        case CornerKind::kOutside:
            out.transition = outside_transition(corner, held.path.end, end_tangent, next.path.start,
                                                start_tangent, side, r, mode);
            return out;
    }
    return out;
}

}  // namespace rwmos::geom
