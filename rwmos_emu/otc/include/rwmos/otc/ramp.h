// SPDX-License-Identifier: MIT
// The offset ramp: how a discrete wear offset commanded by the PLC reaches the axes. [ISG-OTC],
// FCT-C20, section 2.7.1 "Ändert sich der Verschleißwert, wird diese Änderung auf mehrere
// Interpolationszyklen verteilt, so dass sprunghafte Änderungen vermieden werden", and section
// 2.2: at a change of orientation "der beauftragte Verschleiß [wird] nicht schlagartig auf die
// Achse beaufschlagt ..., sondern über mehrere Takte verteilt".
//
// Each axis follows its target with bounded velocity and acceleration (design: [ISG-OTC] gives
// no numbers; docs/otc.md states ours). A step never moves farther than velocity * dt and never
// changes the velocity by more than acceleration * dt; the ramp brakes in time to stop on the
// target exactly (discrete braking distance), and lands on it bit for bit.
#pragma once

namespace rwmos::otc {

struct RampLimits {
    double velocity = 0.0;      // units per second, > 0
    double acceleration = 0.0;  // units per second squared, > 0
};

struct RampState {
    double position = 0.0;
    double velocity = 0.0;  // units per second
};

// [ISG-OTC] section 2.1 ACC_WEIGHT: "Beschleunigungsgewichtung in Prozent [1;100]": the ramp's
// acceleration is `acceleration * weight_percent / 100`.
inline constexpr int kMinAccWeight = 1;
inline constexpr int kMaxAccWeight = 100;
inline constexpr int kDefaultAccWeight = 100;
double weighted_acceleration(double acceleration, int weight_percent) noexcept;

// One interpolation cycle of `dt` seconds towards `target`.
RampState ramp_step(const RampState& s, double target, const RampLimits& limits,
                    double dt) noexcept;

// On the target and at rest: further steps change nothing.
constexpr bool settled(const RampState& s, double target) noexcept {
    return s.position == target && s.velocity == 0.0;
}

// The largest speed from which the ramp can still stop within `distance`, decelerating by
// acceleration * dt per cycle of dt (exact for the discrete steps of ramp_step).
double braking_speed(double distance, double acceleration, double dt) noexcept;

}  // namespace rwmos::otc
