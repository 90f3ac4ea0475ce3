// SPDX-License-Identifier: MIT
#include "rwmos/tempcomp/tempcomp.h"

#include <cmath>

namespace rwmos::tempcomp {

bool is_geometry_axis(const Settings& s, int axis) noexcept {
    for (const int g : s.geometry_axes) {
        if (g == axis) return true;
    }
    return false;
}

Eigen::Vector3d oriented(const Eigen::Vector3d& comp, const Eigen::Matrix3d& holder) noexcept {
    return holder * comp;
}

AxisValues targets(const Settings& s, const Eigen::Vector3d& vector) noexcept {
    AxisValues out{};
    if (!s.on) return out;
    for (int k = 0; k < 3; ++k) {
        const int axis = s.geometry_axes[static_cast<std::size_t>(k)];
        if (axis < 0 || axis >= kAxisCount) continue;
        if (!takes_tool_direction(s.type[static_cast<std::size_t>(axis)])) continue;
        out[static_cast<std::size_t>(axis)] += vector[k];
    }
    return out;
}

double ramp_to_zero(double value, double max_step) noexcept {
    if (std::abs(value) <= max_step) return 0.0;
    return value > 0.0 ? value - max_step : value + max_step;
}

}  // namespace rwmos::tempcomp
