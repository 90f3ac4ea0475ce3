// SPDX-License-Identifier: MIT
#include "rwmos/geometry/approach.h"

#include "rwmos/geometry/tolerances.h"

namespace rwmos::geom {

Element approach_move(const Vec2& position, const OffsetElement& first) noexcept {
    return make_line(position, first.path.start);
}

Element departure_move(const OffsetElement& last, const Vec2& programmed_end) noexcept {
    return make_line(last.path.end, programmed_end);
}

bool worth_moving(const Element& move) noexcept {
    return length(move) > kPointTolerance;
}

}  // namespace rwmos::geom
