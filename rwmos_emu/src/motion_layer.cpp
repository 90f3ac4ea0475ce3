// SPDX-License-Identifier: MIT
#include "rwmos/motion_layer.h"

#include <algorithm>

#include "rwmos/board_state.h"

namespace rwmos {

static_assert(motion::kAxisCount == kAxisCount, "the motion layer drives every board axis");

using motion::MotionResult;
using motion::TcSettings;

namespace {
geom::ApproachMode approach_mode(const TcGroup& g) noexcept {
    switch (g.selection_mode) {
        case tc::kSelectionIndirect:
            return geom::ApproachMode::kIndirect;
        case tc::kSelectionDirect:
            return geom::ApproachMode::kDirect;
        default:
            return geom::ApproachMode::kPerpendicular;
    }
}

// Some group's ERROR is set: every group's bits or'ed, no branch per group. Inlined into the
// calls made at every spool call.
inline bool any_group_error(const TcState& tc) noexcept {
    std::int32_t any = 0;
    for (const TcGroup& g : tc.groups) any |= g.error;
    return any != 0;
}
}  // namespace

double MotionLayer::cycle_seconds() const noexcept {
    return static_cast<double>(state_.interpolation_cycle_us) * 1e-6;
}

bool MotionLayer::error_pending() const noexcept {
    return state_.config.option_tc && any_group_error(state_.tc);
}

const motion::TcSettings& MotionLayer::settings() const noexcept {
    if (!settings_valid_) {
        settings_ = read_settings();
        settings_valid_ = true;
        return settings_;
    }
    // What the board itself changes between object accesses: ERROR (record(), a spooler
    // error) and Run (cleared with it).
    TcSettings& s = settings_;
    if (!s.present) return s;
    s.error_pending = any_group_error(state_.tc);  // present: the option is there
    if (s.active_group != 0) s.run = state_.tc.group(s.active_group).running();
    return s;
}

motion::TcSettings MotionLayer::read_settings() const noexcept {
    motion::TcSettings s;
    const TcState& tc = state_.tc;
    s.present = state_.config.option_tc;
    if (!s.present) return s;
    s.objects_accessed = tc.objects_accessed;
    // The board axes of TcPlane's plane.
    const geom::PlaneAxes plane = plane_axes(tc);
    s.plane_axes = {static_cast<std::uint8_t>(plane.first), static_cast<std::uint8_t>(plane.second)};
    s.plane = tc.plane;
    s.axis_nr = {static_cast<std::uint8_t>(tc.axis_nr[0]), static_cast<std::uint8_t>(tc.axis_nr[1]),
                 static_cast<std::uint8_t>(tc.axis_nr[2])};
    s.rot_angle = tc.rot_angle;
    s.rot_center_first = tc.rot_center_x;
    s.rot_center_second = tc.rot_center_y;
    s.error_pending = error_pending();
    s.active_group = plane.first == plane.second ? 0 : active_group(tc);
    if (s.active_group != 0) {
        const TcGroup& g = tc.group(s.active_group);
        s.run = g.running();
        s.side = g.side == tc::kSideRight ? geom::Side::kRight : geom::Side::kLeft;
        // RADIUS and WkzLen are kept as written, in the unit PU selects ([APCI-TC]
        // Table 3); the board moves in mm.
        s.radius = board::pu_to_millimetres(g.tool().radius, state_.pu);
        s.length = board::pu_to_millimetres(g.tool().length, state_.pu);
        s.cutting_edge = g.tool().cutting_edge;
        s.transition = g.corner_mode == tc::kCornerLinear ? geom::TransitionMode::kLinear
                                                          : geom::TransitionMode::kCircular;
        s.length_axis = static_cast<std::uint8_t>(g.z_axis);
        s.approach = approach_mode(g);
        s.length_always = g.length_mode == tc::kLengthAlways;
    }
    return s;
}

std::uint64_t MotionLayer::oldest_profile_in_flight() const noexcept {
    std::uint64_t oldest = next_profile();
    // The queue runs in the order profiles were taken (a direct command's move, number 0, only
    // after the queue was discarded): its first numbered move is its oldest.
    for (std::size_t i = 0; i < exec_.fill(); ++i) {
        const std::uint64_t n = exec_.queued(i).profile;
        if (n == 0) continue;
        oldest = std::min(oldest, n);
        break;
    }
    if (const std::uint64_t held = spooler_.oldest_pending_profile(); held != 0)
        oldest = std::min(oldest, held);
    return oldest;
}

int MotionLayer::length_axis_of(std::int32_t tool) const noexcept {
    // Asked by OTC's OFF, inside an object write.
    const TcSettings s = read_settings();
    if (!s.present || s.active_group == 0) return -1;
    const TcGroup& g = state_.tc.group(s.active_group);
    if (g.tool_index != tool || !(s.length_always || g.running())) return -1;
    return s.length_axis;
}

void MotionLayer::record(const MotionResult& r) noexcept {
    if (r.errors == 0 || r.group < 1 || r.group > tc::kGroupCount) return;
    TcGroup& g = state_.tc.group(r.group);
    g.error |= r.errors;
    g.status &= ~tc::kRun;
}

void MotionLayer::sync() noexcept {
    sync(error_pending());
}

void MotionLayer::sync(bool errors) noexcept {
    const std::int32_t comp = spooler_.compensating_group();
    // Read once: the group writes below cannot change the spooler.
    const std::int32_t marked = spooler_.holds_profile() ? comp : 0;
    // The compensating group, or, with none, the group whose contour ended
    // last: its shift stays until a profile, a direct command or ReInit removes it.
    const std::int32_t shifted = comp != 0 ? comp : spooler_.last_group();
    for (TcGroup& g : state_.tc.groups) g.status &= ~tc::kProfMarked;
    if (marked >= 1 && marked <= tc::kGroupCount) state_.tc.group(marked).status |= tc::kProfMarked;
    if (shifted >= 1 && shifted <= tc::kGroupCount) {
        // The stored displacement of the correction axes: where the queue
        // ends against where the programmed path ends.
        TcGroup& g = state_.tc.group(shifted);
        const auto& end = exec_.planned_end();
        const auto& path = spooler_.path_position();
        const auto x = static_cast<std::size_t>(g.x_axis);
        const auto y = static_cast<std::size_t>(g.y_axis);
        const auto z = static_cast<std::size_t>(g.z_axis);
        // All three computed before the store: g.offset could alias end or path (all doubles).
        g.offset = {end[x] - path[x], end[y] - path[y], end[z] - path[z]};
    }
    // [APCI-TC] Table 4 via docs/design.md section 3: on any TC error the spooler
    // holds until ERROR is written.
    exec_.set_halted(errors);
    state_.spooler.fill = static_cast<std::int32_t>(exec_.fill());
    const motion::AxisVector position = exec_.position();  // once: the stores could alias it
    for (std::size_t a = 0; a < state_.axes.size(); ++a) state_.axes[a].position = position[a];
}

MotionResult MotionLayer::spool(const motion::Profile& p) {
    const TcSettings& s = settings();
    const MotionResult r = spooler_.spool(
        p, s, exec_, static_cast<std::size_t>(state_.spooler.capacity), cycle_seconds());
    if (r.ok()) manual_ = false;
    record(r);
    // A call without TC errors leaves every group's ERROR as settings() read it.
    sync(r.errors == 0 ? s.error_pending : error_pending());
    return r;
}

MotionResult MotionLayer::direct(const motion::DirectCommand& c) {
    const motion::AxisVector before = exec_.nominal_position();
    const MotionResult r = spooler_.direct(c, exec_, cycle_seconds());
    if (r.ok()) {
        if (!manual_) manual_start_ = before;
        manual_ = true;
        moving_back_ = 0;
    }
    sync();
    return r;
}

double MotionLayer::manual_offset(int axis) const noexcept {
    if (!manual_ || axis < 0 || axis >= motion::kAxisCount) return 0.0;
    const auto a = static_cast<std::size_t>(axis);
    return exec_.nominal_position()[a] - manual_start_[a];
}

bool MotionLayer::move_back_to_manual_start(int axis) {
    if (!manual_ || exec_.fill() != 0 || manual_offset(axis) == 0.0) return false;
    motion::DirectCommand back;
    back.code = motion::DirectCode::kJA;
    back.axes = static_cast<motion::AxisMask>(1u << axis);
    back.target[static_cast<std::size_t>(axis)] = manual_start_[static_cast<std::size_t>(axis)];
    back.feed = 0.0;  // the rapid feed
    if (!spooler_.direct(back, exec_, cycle_seconds()).ok()) return false;
    moving_back_ = back.axes;
    sync();
    return true;
}

bool MotionLayer::moving_back(int axis) const noexcept {
    return exec_.fill() != 0 && (moving_back_ & (1u << axis)) != 0;
}

MotionResult MotionLayer::ssf(motion::AxisMask axes, std::int32_t command) {
    const MotionResult r = spooler_.ssf(axes, command, settings(), exec_,
                                        static_cast<std::size_t>(state_.spooler.capacity));
    record(r);
    sync();
    return r;
}

void MotionLayer::step(std::uint64_t cycles) {
    sync();
    exec_.advance(cycles, cycle_seconds());
    sync();
}

std::uint64_t MotionLayer::run_until_idle(std::uint64_t max_cycles) {
    sync();
    const std::uint64_t ran = exec_.run_until_idle(max_cycles, cycle_seconds());
    sync();
    return ran;
}

objif::Status MotionLayer::release_held_profile(std::int32_t group) {
    // The departure follows the mode of the group that ends (docs/compensation.md).
    TcSettings s = read_settings();
    s.approach = approach_mode(state_.tc.group(group));
    const MotionResult r = spooler_.release_for_deactivation(
        group, s, exec_, static_cast<std::size_t>(state_.spooler.capacity));
    record(r);
    sync();
    return r.status;
}

void MotionLayer::discard_held_profile(std::int32_t group) {
    spooler_.discard_held(group);
    sync();
}

void MotionLayer::compensation_started(std::int32_t) {
    sync();
}

void MotionLayer::clear_shift() {
    spooler_.clear_shift(read_settings(), exec_);
    sync();
}

}  // namespace rwmos
