// SPDX-License-Identifier: MIT
// Temperature compensation in tool direction, per interpolation cycle ([SIN-TEMP],
// SINUMERIK 840D FB1 W1 section 2.8; docs/temperature-compensation.md).
#include "rwmos/board_state.h"
#include "rwmos/geometry/kinematics.h"
#include "rwmos/tempcomp_state.h"

namespace rwmos {

namespace {
std::array<int, 3> geometry_axes(const TcState& tc) noexcept {
    return {tc.axis_nr[0], tc.axis_nr[1], tc.axis_nr[2]};
}
}  // namespace

tempcomp::Settings TempCompEngine::settings() const noexcept {
    const TempCompState& t = state_.temp_comp;
    tempcomp::Settings s;
    s.comp = t.comp;
    s.on = state_.config.option_temp_comp && t.on != 0;
    s.type = t.type;
    s.geometry_axes = geometry_axes(state_.tc);
    return s;
}

Eigen::Vector3d TempCompEngine::vector_at(const motion::AxisVector& pos) const noexcept {
    const TempCompState& t = state_.temp_comp;
    Eigen::Vector3d v = t.comp;
    // [SIN-TEMP]: the values act along the geometry axes "in Grundstellung bzw. bei
    // ausgeschalteter Orientierungstransformation"; with the orientation transformation on (the
    // OTC module's #TRAFO ON with the B head, #KIN ID[4]) they turn with the tool it orients,
    // following every orientation change and the switch itself at once.
    const OtcState& o = state_.otc;
    if (state_.config.option_otc && o.trafo && o.kinematics == geom::kBHeadKinematicsId) {
        const double b = pos[static_cast<std::size_t>(o.tool_axis_b)];
        v = tempcomp::oriented(v, geom::bc_head_rotation(b, 0.0));
    }
    if (t.tool_holder == 0) return v;
    // [SIN-TEMP]: the vector turns with every orientation change of the tool holder, at once,
    // "unabhängig von einer eventuell aktiven Orientierungstransformation"; with both, it is
    // "beiden Drehungen unterworfen".
    const double b = pos[static_cast<std::size_t>(t.head_axis_b)];
    const double c =
        t.head_axis_c == tempcomp::kNoHeadAxis ? 0.0 : pos[static_cast<std::size_t>(t.head_axis_c)];
    return tempcomp::oriented(v, geom::bc_head_rotation(b, c));
}

void TempCompEngine::follow_assignment() const noexcept {
    const std::array<int, 3> now = geometry_axes(state_.tc);
    if (now == assignment_) return;
    // [SIN-TEMP]: "Der Temperaturkompensationswert für eine Achse, die ... nicht mehr
    // Geometrieachse ist, wird (interpolatorisch) auf Null reduziert. Umgekehrt baut sich in
    // einer Achse, die nach einer Umschaltung zur Geometrieachse wird, ... sofort auf."
    for (int a = 0; a < tempcomp::kAxisCount; ++a) {
        const auto i = static_cast<std::size_t>(a);
        bool was = false, is = false;
        for (int k = 0; k < 3; ++k) {
            was = was || assignment_[static_cast<std::size_t>(k)] == a;
            is = is || now[static_cast<std::size_t>(k)] == a;
        }
        if (is) {
            ramping_[i] = false;
        } else if (was && applied_[i] != 0.0) {
            ramping_[i] = true;
            may_ramp_ = true;
        }
    }
    assignment_ = now;
}

bool TempCompEngine::ramping() const noexcept {
    if (!may_ramp_) return false;
    for (std::size_t i = 0; i < ramping_.size(); ++i) {
        if (ramping_[i] && applied_[i] != 0.0) return true;
    }
    return false;
}

bool TempCompEngine::off() const noexcept {
    return !state_.config.option_temp_comp || state_.temp_comp.on == 0;
}

void TempCompEngine::rest(motion::AxisVector& pos) const noexcept {
    // Every axis gets 0 at once (apply's else branch with targets of 0), without evaluating
    // the vector and the targets: no ramp, nothing applied, pos + 0.0.
    ramping_.fill(false);
    may_ramp_ = false;
    applied_.fill(0.0);
    for (std::size_t i = 0; i < applied_.size(); ++i) pos[i] += 0.0;
}

void TempCompEngine::apply(const motion::AxisVector& nominal, double max_step,
                           motion::AxisVector& pos) const noexcept {
    if (off()) {
        rest(pos);
        return;
    }
    const tempcomp::Settings s = settings();
    const tempcomp::AxisValues target = tempcomp::targets(s, vector_at(nominal));
    for (std::size_t i = 0; i < applied_.size(); ++i) {
        if (ramping_[i] && s.on) {
            applied_[i] = tempcomp::ramp_to_zero(applied_[i], max_step);
            if (applied_[i] == 0.0) ramping_[i] = false;
        } else {
            // Written values act at once ([SIN-TEMP]: "Werteveränderungen in den Settingdaten
            // werden sofort wirksam"); an axis without bit 2 or with MD 20390 off gets 0.
            ramping_[i] = false;
            applied_[i] = target[i];
        }
        pos[i] += applied_[i];
    }
}

bool TempCompEngine::inert() const noexcept {
    // Off, every applied value 0: follow_assignment starts no ramp (it ramps only an axis with
    // a value), per_cycle is false, and at() rests every axis at 0 (pos + 0.0).
    if (!off()) return false;
    for (const double v : applied_)
        if (v != 0.0) return false;
    return true;
}

bool TempCompEngine::per_cycle(const motion::Move*, std::uint64_t, std::uint64_t) const noexcept {
    follow_assignment();
    return ramping();
}

void TempCompEngine::step(const motion::Move*, std::uint64_t, std::uint64_t, double dt,
                          motion::AxisVector& pos) noexcept {
    follow_assignment();
    const motion::AxisVector nominal = pos;
    apply(nominal, state_.temp_comp.ramp_velocity * dt, pos);
}

void TempCompEngine::at(const motion::Move*, std::uint64_t, std::uint64_t,
                        motion::AxisVector& pos) const noexcept {
    follow_assignment();
    if (off()) {  // apply() off, without the copy of pos it does not read
        rest(pos);
        return;
    }
    const motion::AxisVector nominal = pos;
    // Only while nothing ramps (per_cycle false): a ramp does not advance here.
    apply(nominal, 0.0, pos);
}

}  // namespace rwmos
