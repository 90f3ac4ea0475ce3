// SPDX-License-Identifier: MIT
// The Board's motion calls: thin wrappers over the motion layer in its state.
#include "rwmos/board.h"
#include "rwmos/board_state.h"

namespace rwmos {

// The 3D compensation module (bus 1310) acts on a profile before the spooler sees it: an armed
// LN profile gets its compensated end point (docs/object-map.md section 6).
motion::MotionResult EmulatedBoard::spool(const motion::Profile& p) {
    if (state_->comp3d.armed == 0) {
        // Nothing armed: plan_profile would leave the profile as it is and plan nothing.
        const motion::MotionResult r = state_->motion.spool(p);
        if (r.ok()) commit_profile(state_->comp3d, Comp3dPlan{});
        return r;
    }
    motion::Profile q = p;
    const Comp3dPlan plan =
        plan_profile(state_->comp3d, state_->tc, state_->motion.spooler().program_position(), q);
    if (plan.refusal != comp3d::Refusal::kNone) {
        state_->comp3d.last_error = static_cast<std::int32_t>(plan.refusal);
        motion::MotionResult r;
        r.status = refusal_status(plan.refusal);
        r.tag = p.tag;
        r.message = comp3d::refusal_message(plan.refusal);
        return r;
    }
    const motion::MotionResult r = state_->motion.spool(q);
    if (r.ok()) {
        commit_profile(state_->comp3d, plan);
        if (plan.compensated) state_->motion.mark_surface();
    }
    return r;
}

motion::MotionResult EmulatedBoard::direct(const motion::DirectCommand& c) {
    return state_->motion.direct(c);
}

motion::MotionResult EmulatedBoard::ssf(motion::AxisMask axes, std::int32_t command) {
    return state_->motion.ssf(axes, command);
}

void EmulatedBoard::step(std::uint64_t cycles) {
    state_->motion.step(cycles);
}

std::uint64_t EmulatedBoard::run_until_idle(std::uint64_t max_cycles) {
    return state_->motion.run_until_idle(max_cycles);
}

motion::MotionStatus EmulatedBoard::motion_status() const noexcept {
    const MotionLayer& m = state_->motion;
    const motion::Executor& e = m.executor();
    motion::MotionStatus s;
    s.now = e.now();
    s.idle = e.idle();
    s.held = m.error_pending();
    s.fill = static_cast<std::uint32_t>(e.fill());
    s.capacity = static_cast<std::uint32_t>(state_->spooler.capacity);
    s.compensating_group = m.spooler().compensating_group();
    s.profile_held = m.spooler().holds_profile();
    s.tracing = e.tracing();
    s.trace_pending = e.trace().size();
    s.trace_lost = e.trace().lost();
    s.segments_pending = e.segments().size();
    s.segments_lost = e.segments().lost();
    s.position = e.position();
    return s;
}

objif::Status EmulatedBoard::set_trace(bool on, std::size_t capacity) {
    if (on && capacity == 0) return objif::Status::kValueTooLow;
    if (on && capacity > kMaxTraceCapacity) return objif::Status::kValueTooHigh;
    if (on && capacity > config().trace_memory / sizeof(motion::TraceSample))
        return objif::Status::kNoMemory;
    state_->motion.executor().set_trace(on, capacity);
    return objif::Status::kOk;
}

std::size_t EmulatedBoard::read_trace(std::span<motion::TraceSample> out) {
    return state_->motion.executor().trace().take(out);
}

std::size_t EmulatedBoard::read_segments(std::span<motion::Segment> out) {
    return state_->motion.executor().segments().take(out);
}

std::size_t EmulatedBoard::take_segments(std::size_t max, SegmentVisitor visit, void* context) {
    return state_->motion.executor().segments().take_runs(
        max, [visit, context](std::span<const motion::Segment> run) { visit(run, context); });
}

}  // namespace rwmos
