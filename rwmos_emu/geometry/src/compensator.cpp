// SPDX-License-Identifier: MIT
#include "rwmos/geometry/compensator.h"

#include <algorithm>
#include <cmath>

#include "objif/enum_names.h"
#include "rwmos/geometry/approach.h"

namespace rwmos::geom {

std::string_view role_name(SegmentRole role) noexcept {
    static constexpr auto kNames =
        objif::enum_names<SegmentRole::kContour, SegmentRole::kDeparture>(
            {"contour", "transition", "approach", "departure"}, "unknown");
    return kNames(role);
}

Reason check_config(const CompensatorConfig& config) noexcept {
    const double r = config.tool_radius;
    if (!std::isfinite(r) || r < 0.0 || r > kMaxCoordinate) return Reason::kInvalidToolRadius;
    if (config.side != Side::kLeft && config.side != Side::kRight) return Reason::kInvalidSetting;
    if (config.transition != TransitionMode::kCircular &&
        config.transition != TransitionMode::kLinear)
        return Reason::kInvalidSetting;
    if (config.approach != ApproachMode::kPerpendicular &&
        config.approach != ApproachMode::kIndirect && config.approach != ApproachMode::kDirect)
        return Reason::kInvalidSetting;
    return Reason::kNone;
}

StepResult PathCompensator::fail(Reason reason, std::uint32_t index,
                                 SegmentBatch& out) const noexcept {
    out.clear();
    return StepResult{reason, reason_bits(reason), index};
}

void PathCompensator::emit_plane_free(const Vec2& at, SegmentBatch& out) const noexcept {
    for (std::size_t i = 0; i < plane_free_count_; ++i)
        out.add(make_line(at, at), SegmentRole::kContour, plane_free_[i]);
}

Element PathCompensator::held_path(const OffsetElement& held) const noexcept {
    Element approach;
    if (held_role_ == SegmentRole::kApproach &&
        indirect_approach(position_, first_programmed_, held, approach))
        return approach;
    return emitted_path(held);
}

StepResult PathCompensator::begin(const CompensatorConfig& config, const Vec2& position) noexcept {
    if (state_ != State::kIdle)
        return StepResult{Reason::kAlreadyStarted, reason_bits(Reason::kAlreadyStarted), 0};
    if (const Reason r = check_config(config); r != Reason::kNone)
        return StepResult{r, reason_bits(r), 0};
    if (!is_valid_coordinate(position))
        return StepResult{Reason::kInvalidCoordinate, reason_bits(Reason::kInvalidCoordinate), 0};
    config_ = config;
    position_ = position;
    plane_free_count_ = 0;
    state_ = State::kStarted;
    return {};
}

StepResult PathCompensator::push(const Element& programmed, std::uint32_t index,
                                 SegmentBatch& out) noexcept {
    out.clear();
    if (state_ == State::kIdle) return fail(Reason::kNotStarted, index, out);
    if (const Reason r = check_element(programmed); r != Reason::kNone) return fail(r, index, out);
    if (state_ == State::kHolding &&
        (programmed.start - held_corner_).norm() > kContinuityTolerance)
        return fail(Reason::kDiscontinuous, index, out);

    if (is_plane_free(programmed)) {
        if (state_ == State::kStarted) {
            out.add(make_line(position_, position_), SegmentRole::kApproach, index);
            return {};
        }
        if (plane_free_count_ == kMaxPlaneFreeElements)
            return fail(Reason::kTooManyPlaneFreeElements, index, out);
        plane_free_[plane_free_count_++] = index;
        return {};
    }

    const double r = config_.tool_radius;
    OffsetResult offset = offset_element(programmed, r, config_.side);
    if (offset.reason != Reason::kNone) return fail(offset.reason, index, out);
    // The offset arc keeps the programmed sweep (offset_element): measured once. An offset
    // line keeps the programmed line's direction, its tangent at both ends.
    const double programmed_length = length_with_sweep(programmed, offset.element.sweep);
    const bool arc = is_arc(programmed);

    if (state_ == State::kStarted && config_.approach == ApproachMode::kDirect) {
        // [ISG-PROG], direct selection: the selection block (a line) runs from the tool straight
        // to the offset start of the element after it, known when that one arrives; held until
        // then.
        if (arc) return fail(Reason::kDirectSelectionOnAnArc, index, out);
        first_programmed_ = programmed;
        held_ = offset.element;
        held_role_ = SegmentRole::kApproach;
    } else if (state_ == State::kStarted && config_.approach == ApproachMode::kIndirect) {
        // Any length: [ISG-OTC-EN]'s wr_quad_disc.nc selects with a 2 mm block and a 30 mm disc
        // (LinuxCNC asks for more than r). [ISG-PROG] builds approach blocks only on lines; an
        // arc is taken as LinuxCNC takes it, rather than refusing a program that has no gouge
        // (docs/compensation.md).
        Element approach;
        if (!indirect_approach(position_, programmed, offset.element, approach))
            return fail(Reason::kApproachArcNoSolution, index, out);
        first_programmed_ = programmed;
        // Its corner is that of its offset element, parallel to it (as LinuxCNC's entry move,
        // whose corner is taken from the programmed direction); only its start is the tool's.
        held_ = offset.element;
        held_role_ = SegmentRole::kApproach;
        // The approach comes from the tool, not from the offset line's start: an inside corner
        // may trim it anywhere back along that line (a short selection block), so the line
        // reaches back past the tool for the trim.
        if (!is_arc(programmed)) {
            const double back = offset_length(held_) + (programmed.end - position_).norm() + 2 * r;
            const Vec2 start = held_.path.end - back * held_.direction;
            if (is_valid_coordinate(start)) held_.path.start = start;
        }
    } else if (state_ == State::kStarted) {
        const Element approach = approach_move(position_, offset.element);
        if (worth_moving(approach)) out.add(approach, SegmentRole::kApproach, index);
        held_ = offset.element;
        held_role_ = SegmentRole::kContour;
    } else if (held_role_ == SegmentRole::kApproach &&
               config_.approach == ApproachMode::kDirect) {
        // The direct approach ends where the new element's offset starts; no corner.
        const Element approach = make_line(position_, offset.element.path.start);
        if (worth_moving(approach)) out.add(approach, SegmentRole::kApproach, held_index_);
        emit_plane_free(offset.element.path.start, out);
        held_ = offset.element;
        held_role_ = SegmentRole::kContour;
    } else {
        // Joined in place: the held element (a copy: on a failure the compensator stays as it
        // was) and the new one, which becomes the held one.
        OffsetElement held = held_;
        Transition transition;
        const Vec2 start_tangent_now = arc ? start_tangent(programmed) : offset.element.direction;
        const JoinKind join = join_corner_in_place(
            held, offset.element, transition, held_corner_, held_end_tangent_, start_tangent_now,
            config_.side, r, config_.transition, std::min(held_length_, programmed_length));
        if (join.reason != Reason::kNone)
            return fail(join.reason,
                        join.reason == Reason::kHeldElementTooShort ? held_index_ : index, out);
        out.add(held_path(held), held_role_, held_index_);
        emit_plane_free(held.path.end, out);
        for (std::size_t i = 0; i < transition.count; ++i)
            out.add(transition.elements[i], SegmentRole::kTransition, held_index_);
        held_ = offset.element;
        held_role_ = SegmentRole::kContour;
    }
    held_corner_ = programmed.end;
    held_end_tangent_ = arc ? end_tangent(programmed) : offset.element.direction;
    held_length_ = programmed_length;
    held_index_ = index;
    plane_free_count_ = 0;
    state_ = State::kHolding;
    return {};
}

StepResult PathCompensator::finish(SegmentBatch& out) noexcept {
    out.clear();
    if (state_ == State::kIdle) return fail(Reason::kNotStarted, 0, out);
    if (state_ == State::kHolding) {
        out.add(held_path(held_), held_role_, held_index_);
        emit_plane_free(held_.path.end, out);
        const Element departure = departure_move(held_, held_corner_);
        if (worth_moving(departure)) out.add(departure, SegmentRole::kDeparture, held_index_);
    }
    discard();
    return {};
}

Reason PathCompensator::set_transition(TransitionMode mode) noexcept {
    CompensatorConfig changed = config_;
    changed.transition = mode;
    if (const Reason r = check_config(changed); r != Reason::kNone) return r;
    config_ = changed;
    return Reason::kNone;
}

void PathCompensator::discard() noexcept {
    state_ = State::kIdle;
    plane_free_count_ = 0;
}

}  // namespace rwmos::geom
