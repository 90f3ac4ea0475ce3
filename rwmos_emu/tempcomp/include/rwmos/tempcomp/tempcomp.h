// SPDX-License-Identifier: MIT
// Temperature compensation in tool direction ([SIN-TEMP], SINUMERIK 840D FB1 W1, section 2.8):
// the three setting data SD 42960 TOOL_TEMP_COMP[0..2] form one compensation vector on the
// geometry axes (X, Y, Z), enabled by MD 20390 TOOL_TEMP_COMP_ON and per channel axis by bit 2 of
// MD 32750 TEMP_COMP_TYPE; with an orientable tool holder the vector turns with the tool. Pure
// functions; docs/temperature-compensation.md states the rules.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

namespace rwmos::tempcomp {

inline constexpr int kAxisCount = 8;  // the board's axes (channel axes)
using AxisValues = std::array<double, kAxisCount>;

// MD 32750 TEMP_COMP_TYPE bit 2: "Zusätzlich muß für jede betroffene Kanalachse im
// Maschinendatum MD 32750: TEMP_COMP_TYPE[<Achsindex>] das Bit 2 gesetzt sein."
inline constexpr std::int32_t kToolDirectionBit = 0x04;
constexpr bool takes_tool_direction(std::int32_t temp_comp_type) noexcept {
    return (temp_comp_type & kToolDirectionBit) != 0;
}

struct Settings {
    Eigen::Vector3d comp = Eigen::Vector3d::Zero();  // SD 42960 TOOL_TEMP_COMP[0..2]
    bool on = false;                                 // MD 20390 TOOL_TEMP_COMP_ON != 0
    std::array<std::int32_t, kAxisCount> type{};     // MD 32750 TEMP_COMP_TYPE[axis]
    std::array<int, 3> geometry_axes{0, 1, 2};       // channel axes of X, Y, Z
};

// The board axis is one of the three geometry axes.
bool is_geometry_axis(const Settings& s, int axis) noexcept;

// The vector as it acts: in the geometry axes in the basic position; with an orientable tool
// holder turned by its rotation `holder` ([SIN-TEMP], "Orientierbarer Werkzeugträger": "so wird
// der Vektor der Temperaturkompensation bei einer Orientierungsänderung mitgedreht").
Eigen::Vector3d oriented(const Eigen::Vector3d& comp, const Eigen::Matrix3d& holder) noexcept;

// The displacement each board axis takes at once: component k of `vector` on the k-th geometry
// axis, if MD 20390 is on and that axis has bit 2 of MD 32750; 0 elsewhere. An axis without
// the bit gets nothing, silently, and the others are unaffected ([SIN-TEMP]: "kann in dieser
// Achse kein Kompensationswert wirksam werden. Andere Achse bleiben davon jedoch unbeeinflußt.
// Ein Alarm wird in diesem Fall nicht ausgegeben.").
AxisValues targets(const Settings& s, const Eigen::Vector3d& vector) noexcept;

// One interpolation cycle of an axis whose value is reduced to zero ("wird (interpolatorisch)
// auf Null reduziert"): towards 0 by at most `max_step` (> 0), never past it.
double ramp_to_zero(double value, double max_step) noexcept;

}  // namespace rwmos::tempcomp
