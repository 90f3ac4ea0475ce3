// SPDX-License-Identifier: MIT
// The units of [ISG-OTC]'s tool parameters and control units ([ISG-OTC], FCT-C20, section 3.2
// and 2.7) and their conversion to lengths; the OTC engine converts to mm, the unit the board
// moves in (PU, board object bus 1000 Index 5, applies to the TC tool values only).
#pragma once

#include <cstdint>

namespace rwmos::otc {

// P-TOOL-00030 grinding_wear_const is in 0.1 um per m of path: a ratio of lengths,
// 1e-7 per unit (0.1e-6 m per 1 m), so it needs no PU.
inline constexpr double kWearConstToRatio = 1e-7;

// Control units (DINT) and P-TOOL-00031 grinding_max_infeed are in 0.1 um.
inline constexpr double kTenthMicrometreInMillimetre = 1e-4;
inline constexpr double kMillimetresPerInch = 25.4;

// P-TOOL-00138 grinding_disc_tilt_angle is in 0.0001 degree, within [-45, 45] degrees.
inline constexpr double kTiltUnitInDegrees = 1e-4;
inline constexpr double kMaxTiltDegrees = 45.0;

// PU values of the board module (bus 1000 Index 5): 0 mm, 1 um, 2 inch.
enum class LengthUnit : std::int32_t { kMillimetre = 0, kMicrometre = 1, kInch = 2 };

// Length of one unit of `unit` in mm.
constexpr double millimetres_per_unit(LengthUnit unit) noexcept {
    switch (unit) {
        case LengthUnit::kMillimetre:
            return 1.0;
        case LengthUnit::kMicrometre:
            return 1e-3;
        case LengthUnit::kInch:
            return kMillimetresPerInch;
    }
    return 1.0;
}

// A value in 0.1 um as a length in `unit`.
constexpr double tenth_um_to_length(double tenth_um, LengthUnit unit) noexcept {
    return tenth_um * kTenthMicrometreInMillimetre / millimetres_per_unit(unit);
}
// A length in `unit` in 0.1 um (not rounded).
constexpr double length_to_tenth_um(double length, LengthUnit unit) noexcept {
    return length * millimetres_per_unit(unit) / kTenthMicrometreInMillimetre;
}

// Wear per unit of path for a wear constant in 0.1 um/m.
constexpr double wear_ratio(double wear_const_tenth_um_per_m) noexcept {
    return wear_const_tenth_um_per_m * kWearConstToRatio;
}

// [ISG-OTC] section 2 "Die Verschleißkompensation ist vom zurückgelegten Weg abhängig" and
// section 2.1 CONT: "Vorgabe der Werte nur aus Berechnung des zurückgelegten Weges und der
// Verschleißkonstante": the wear a path of `path_length` (any unit) adds, in the same unit.
constexpr double continuous_wear(double path_length, double wear_const_tenth_um_per_m) noexcept {
    return path_length * wear_ratio(wear_const_tenth_um_per_m);
}

constexpr double tilt_to_degrees(double tilt_units) noexcept {
    return tilt_units * kTiltUnitInDegrees;
}
// [ISG-OTC] section 3.2, P-TOOL-00138: -45 <= angle <= 45 degrees.
constexpr bool tilt_in_range(double tilt_units) noexcept {
    const double deg = tilt_to_degrees(tilt_units);
    return deg >= -kMaxTiltDegrees && deg <= kMaxTiltDegrees;
}

}  // namespace rwmos::otc
