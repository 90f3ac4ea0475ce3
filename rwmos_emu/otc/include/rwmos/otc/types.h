// SPDX-License-Identifier: MIT
// The processing types and modes of the online tool compensation ([ISG-OTC], FCT-C20,
// "2 Beschreibung", "Betriebsarten" and "Modi"; section 2.1 "#OTC ON | OFF [ RADIUS | LENGTH |
// TOOL_DIR | SURF_NORM_DIR  DISC | CONT | AUTO ... ]"), and which PLC control units act in which
// of them (section 2.7). The numeric values are the OTC module's object values (bus 1330,
// docs/object-map.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace rwmos::otc {

enum class ProcessingType : std::int32_t {
    kRadius = 0,       // RADIUS: wear of the disc radius, only with tool radius compensation
    kLength = 1,       // LENGTH (default): along the third main axis, split by the disc tilt
    kToolDir = 2,      // TOOL_DIR: along the tool orientation (head kinematics)
    kSurfNormDir = 3,  // SURF_NORM_DIR: along the surface normal (tool direction, path tangent)
};
inline constexpr ProcessingType kDefaultProcessingType = ProcessingType::kLength;

enum class Mode : std::int32_t {
    kCont = 0,  // CONT: wear = path length x wear constant
    kDisc = 1,  // DISC: wear only from the PLC's control units
    kAuto = 2,  // AUTO (default): the sum of both
};
inline constexpr Mode kDefaultMode = Mode::kAuto;

// "RADIUS", "LENGTH", "TOOL_DIR", "SURF_NORM_DIR"; "CONT", "DISC", "AUTO" (the NC keywords).
std::string_view processing_type_name(ProcessingType t) noexcept;
std::string_view mode_name(Mode m) noexcept;
std::optional<ProcessingType> processing_type_from_int(std::int32_t v) noexcept;
std::optional<Mode> mode_from_int(std::int32_t v) noexcept;

// Continuous wear accrues in CONT and AUTO; the control units act in DISC and AUTO.
constexpr bool mode_has_continuous(Mode m) noexcept {
    return m != Mode::kDisc;
}
constexpr bool mode_has_discrete(Mode m) noexcept {
    return m != Mode::kCont;
}

// [ISG-OTC] section 2.7.1: the channel unit otc_radius_offset is used "nur mit den Betriebsarten
// RADIUS oder TOOL_DIR und dem Modus DISC oder AUTO".
constexpr bool channel_unit_acts(ProcessingType t, Mode m) noexcept {
    return mode_has_discrete(m) && (t == ProcessingType::kRadius || t == ProcessingType::kToolDir);
}

// What the per-axis unit otc_offset of one axis does ([ISG-OTC] sections 2.7.1 and 2.7.2).
enum class AxisUnitRole : std::uint8_t {
    kIgnored = 0,    // no effect in this type/mode
    kAxis = 1,       // wear along this axis
    kDirection = 2,  // the third axis: wear along the type's direction (tool or surface normal)
};
// `axis` is the position of the board axis in the channel's axis sequence: 0, 1, 2 for the
// axes assigned to X, Y, Z (TC X/Y/Z-Axis-Nr), 3 for every other axis.
//   RADIUS, LENGTH: every axis carries its own wear ("sowohl bei ... RADIUS als auch ... LENGTH").
//   TOOL_DIR: "In der dritten Achse (axis_idx = 2) kann ein Offsetwert in Werkzeugrichtung
//     geschrieben werden, die ersten zwei Achsen werden bzgl. SPS-Input ignoriert."
//   SURF_NORM_DIR: "muss der Offsetwert in der dritten Achse beauftragt werden"; "Die ersten
//     drei Achsen werden bzgl. SPS-Input ignoriert" (as axis offsets: the third is the normal's).
//   Axes after the first three act "wie gewohnt" in every type.
AxisUnitRole axis_unit_role(ProcessingType t, Mode m, int axis_in_sequence) noexcept;

}  // namespace rwmos::otc
