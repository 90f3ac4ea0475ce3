// SPDX-License-Identifier: MIT
// Approach and departure moves (docs/design.md section 3, geometry): straight lines from the
// current position to the start of the first offset element, and from the last offset
// end to the programmed end point.
#pragma once

#include "rwmos/geometry/offset.h"

namespace rwmos::geom {

// From the tool position to the first offset element's start.
Element approach_move(const Vec2& position, const OffsetElement& first) noexcept;
// From the last offset element's end to the programmed end point of its element.
Element departure_move(const OffsetElement& last, const Vec2& programmed_end) noexcept;
// Approach and departure moves shorter than kPointTolerance are not emitted.
bool worth_moving(const Element& move) noexcept;

}  // namespace rwmos::geom
