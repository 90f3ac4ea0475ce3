// SPDX-License-Identifier: MIT
// The TC module's state (bus 1300) as plain structs, so the motion layer
// (spooler, held profile, interpolation clock) can read the group
// configuration and set ERROR/STATUS bits directly. The object rules that
// guard these fields live in the TcModule hooks (tc_module.h); this header
// holds data, a few pure queries over it, and the seam to the motion layer.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "geometry/plane.h"
#include "objif/status.h"
#include "rwmos/object_map.h"
#include "objif/map/tc_bits.h"

namespace rwmos {

// One row of a group's tool table ([APCI-TC] Table 3: RADIUS, WkzLen), in PU units.
struct TcTool {
    double radius = 0.0;
    double length = 0.0;
    std::int32_t cutting_edge = 0;  // CuttingEdge (extension): a turning tool's position 1..9
};

// One compensation group (DeviceNumber 1, Index 1..3).
struct TcGroup {
    std::int32_t error = 0;   // ERROR register: tc::kInitError | tc::kKorrError | ...
    std::int32_t status = 0;  // STATUS register: tc::kRun | tc::kProfMarked
    std::int32_t x_axis = 0;  // XAxis: board axis of the first plane axis
    std::int32_t y_axis = 1;  // YAxis: board axis of the second plane axis
    std::int32_t z_axis = 2;  // ZAxis: board axis for tool length compensation
    std::int32_t tool_index = 0;                    // WKZINDEX 0..1023
    std::int32_t side = tc::kSideNone;              // Left/Right selection (41/42), 40 = none
    std::int32_t corner_mode = tc::kCornerCircular;  // outside corners (extension object)
    std::int32_t selection_mode = tc::kSelectionPerpendicular;  // approach/departure (extension)
    std::int32_t length_mode = tc::kLengthWhileCompensating;    // when WkzLen acts (extension)
    // Stored displacement of the correction axes X, Y, Z ("intern gespeicherte
    // Verschiebungswerte der Korrekturachsen", [APCI-TC] Table 2 ReInit/Reset).
    // Written by the motion layer; cleared by ReInit, Reset, RESET, Clean.
    std::array<double, 3> offset{};
    std::array<TcTool, tc::kToolCount> tools{};

    bool running() const noexcept { return (status & tc::kRun) != 0; }
    bool profile_held() const noexcept { return (status & tc::kProfMarked) != 0; }
    const TcTool& tool() const noexcept { return tools[static_cast<std::size_t>(tool_index)]; }
    TcTool& tool() noexcept { return tools[static_cast<std::size_t>(tool_index)]; }
};

// The whole TC module.
struct TcState {
    // DeviceNumber 0 ([APCI-TC] Table 2).
    std::array<std::int32_t, 3> axis_nr{0, 1, 2};  // X-, Y-, Z-Axis-Nr
    std::int32_t plane = tc::kPlaneXY;              // TcPlane 17/18/19
    double rot_angle = 0.0;                         // RotAngle, degrees
    double rot_center_x = 0.0;                      // RotCenterX, interpolation units
    double rot_center_y = 0.0;                      // RotCenterY
    // [APCI-TC] section 2.2 "Wichtiger Hinweis": once a TC object was accessed,
    // arcs run in the active plane, not in the plane of the first axes named.
    // Set by any successful access to bus 1300; cleared by Clean.
    bool objects_accessed = false;
    // DeviceNumber 1: groups[0] is group 1.
    std::array<TcGroup, tc::kGroupCount> groups{};

    TcGroup& group(std::int32_t number) noexcept { return groups[static_cast<std::size_t>(number - 1)]; }
    const TcGroup& group(std::int32_t number) const noexcept {
        return groups[static_cast<std::size_t>(number - 1)];
    }
};

// The board axes of the plane TcPlane selects, in the plane's order:
// 17 (X-Axis-Nr, Y-Axis-Nr, Z-Axis-Nr), 18 (Z-, X-, Y-Axis-Nr), 19 (Y-, Z-, X-Axis-Nr).
geom::PlaneAxes plane_axes(const TcState& tc) noexcept;

// The active group (Index 0): the lowest-numbered group whose {XAxis, YAxis}
// are the two board axes of the plane TcPlane selects (in either order).
// 0 when no group matches. Design reading of [APCI-TC] section 2.2.
std::int32_t active_group(const TcState& tc) noexcept;

// Why a group cannot be activated (STATUS = 1). [APCI-TC] section 2.5 gives the
// initialisation steps; "initialised" is defined in docs/object-map.md.
enum class InitFault : std::uint8_t {
    kNone,
    kAxesNotDistinct,  // XAxis, YAxis, ZAxis name the same board axis twice
    kNoSide,           // neither Left nor Right selected since the last RESET
    kAxisInUse,        // another running group compensates one of these axes
};
InitFault initialisation_fault(const TcState& tc, std::int32_t group) noexcept;
std::string_view init_fault_message(InitFault f) noexcept;

// The seam to the motion layer (spooler, held profile, interpolation clock).
// The TC hooks call these after their own checks passed; with no motion layer
// attached nothing is spooled or held, so there is nothing to release.
class TcMotion {
public:
    virtual ~TcMotion() = default;
    // STATUS = 0 on a running group: correct and spool the held profile
    // ([APCI-TC] section 1). Called before Run is cleared; a non-Ok status (e.g. kBusy:
    // spooler full) refuses the write, and the group stays as it was.
    virtual objif::Status release_held_profile(std::int32_t group) = 0;
    // RESET, Reset (dev 0 idx 14), Clean: drop the held profile unspooled.
    virtual void discard_held_profile(std::int32_t group) = 0;
    // STATUS = 1 accepted: the group starts compensating from the next profile.
    virtual void compensation_started(std::int32_t group) = 0;
    // ReInit, Reset, RESET, Clean: the stored shift of the correction axes is
    // cleared (the programmed position becomes where the queue ends). Called
    // with no profile held (ReInit is refused while one is; the others drop it first).
    virtual void clear_shift() {}
};

}  // namespace rwmos
