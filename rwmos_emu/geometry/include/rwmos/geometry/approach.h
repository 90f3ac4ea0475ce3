// SPDX-License-Identifier: MIT
// Approach and departure moves (docs/design.md section 3, geometry; docs/compensation.md
// "Approach and departure"): straight lines from the current position to the start of the
// first offset element (perpendicular) or to its end (indirect), and from the last offset end
// to the programmed end point.
#pragma once

#include "rwmos/geometry/offset.h"

namespace rwmos::geom {

// From the tool position to the first offset element's start.
Element approach_move(const Vec2& position, const OffsetElement& first) noexcept;
// The indirect approach (ApproachMode::kIndirect), in place of the first element, to its offset
// end `first.path.end` (trimmed at its corner): a line from the tool position for a line; for an
// arc, LinuxCNC's entry arc: in the programmed direction, about the point on the line from that
// end to the programmed centre that lies as far from the tool position as from the end, so it
// arrives along the offset arc's tangent. False (and `out` untouched) when no such arc exists.
bool indirect_approach(const Vec2& position, const Element& programmed, const OffsetElement& first,
                       Element& out) noexcept;
// From the last offset element's end to the programmed end point of its element.
Element departure_move(const OffsetElement& last, const Vec2& programmed_end) noexcept;
// Approach and departure moves shorter than kPointTolerance are not emitted.
bool worth_moving(const Element& move) noexcept;

}  // namespace rwmos::geom
