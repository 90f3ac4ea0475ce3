// SPDX-License-Identifier: MIT
#include "rwmos/geometry/approach.h"

#include <cmath>

#include "rwmos/geometry/shared.h"

namespace rwmos::geom {

Element approach_move(const Vec2& position, const OffsetElement& first) noexcept {
    return make_line(position, first.path.start);
}

bool indirect_approach(const Vec2& position, const Element& programmed, const OffsetElement& first,
                       Element& out) noexcept {
    const Vec2 end = first.path.end;
    if (!is_arc(programmed)) {
        out = make_line(position, end);
        return true;
    }
    const Vec2 toward_centre = programmed.centre - end;
    const Vec2 chord = position - end;
    const double a = toward_centre.norm();
    const double b = chord.norm();
    if (a <= kPointTolerance || b <= kPointTolerance) return false;
    const double cos_angle = chord.dot(toward_centre) / (a * b);
    if (std::abs(cos_angle) < 1e-9) return false;
    const Vec2 centre = end + (0.5 * b / cos_angle) * (toward_centre / a);
    if (!is_valid_coordinate(centre)) return false;
    out = make_arc(position, end, centre, programmed.ccw);
    return true;
}

Element departure_move(const OffsetElement& last, const Vec2& programmed_end) noexcept {
    return make_line(last.path.end, programmed_end);
}

bool worth_moving(const Element& move) noexcept {
    return length(move) > kPointTolerance;
}

}  // namespace rwmos::geom
