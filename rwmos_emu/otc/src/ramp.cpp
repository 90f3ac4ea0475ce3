// SPDX-License-Identifier: MIT
#include "rwmos/otc/ramp.h"

#include <algorithm>
#include <cmath>

namespace rwmos::otc {

double weighted_acceleration(double acceleration, int weight_percent) noexcept {
    const int w = std::clamp(weight_percent, kMinAccWeight, kMaxAccWeight);
    return acceleration * static_cast<double>(w) / 100.0;
}

double braking_speed(double distance, double acceleration, double dt) noexcept {
    // Braking from m * a * dt takes m cycles and covers a * dt^2 * m (m + 1) / 2.
    const double adt = acceleration * dt;
    const double m = std::sqrt(0.25 + 2.0 * distance / (adt * dt)) - 0.5;
    return adt * std::max(m, 0.0);
}

RampState ramp_step(const RampState& s, double target, const RampLimits& limits,
                    double dt) noexcept {
    const double error = target - s.position;
    if (error == 0.0 && s.velocity == 0.0) return s;
    const double adt = limits.acceleration * dt;
    const double land = error / dt;  // the speed that ends this cycle on the target
    const double reachable =
        std::min(limits.velocity, braking_speed(std::abs(error), limits.acceleration, dt));
    const double wanted = std::abs(land) <= reachable ? land : std::copysign(reachable, error);
    const double velocity = s.velocity + std::clamp(wanted - s.velocity, -adt, adt);
    if (velocity == land) return {target, velocity};
    const double next = s.position + velocity * dt;
    // Rounding of the braking speed may carry a step a few ulps past the target: land instead.
    if ((error > 0.0 && next > target) || (error < 0.0 && next < target)) return {target, velocity};
    return {next, velocity};
}

}  // namespace rwmos::otc
