// SPDX-License-Identifier: MIT
// The OTC module's state (bus 1330; [ISG-OTC], ISG FCT-C20; docs/otc.md): what #OTC programs,
// the PLC's control units, the current tool's grinding data and its wear. Plain data in
// Board::State; the rules are in the module's hooks (otc_module.cpp) and the per-cycle
// offsets in the engine (otc_engine.h).
#pragma once

#include <array>
#include <cstdint>

#include "rwmos/object_map.h"
#include "rwmos/otc/errors.h"
#include "rwmos/otc/ramp.h"
#include "rwmos/otc/types.h"

namespace rwmos {

inline constexpr std::int32_t kOtcAxisCount = otc::kAxisCount;  // objif/map/object_map.h

// A PLC control unit of type MC_CONTROL_SGN32_UNIT ([ISG-OTC] section 2.7): the PLC writes
// command_w and enable_w; request_r and state_r are the engine's (OtcEngine).
struct OtcControlUnit {
    std::int32_t command = 0;  // 0.1 um
    bool enable = false;
};

// MC_CONTROL_BOOL_UNIT ManualMvBackToStart of one axis ([ISG-OTC] section 2.7.3).
struct OtcBoolUnit {
    bool command = false;  // X_Command
    bool enable = false;   // X_Enable
};

// The current tool's data ([ISG-OTC] section 2.6 / 3.2, the host writes them at a tool change).
struct OtcTool {
    std::int32_t number = 0;  // the tool (D n, TC WKZINDEX) the wear is folded into
    std::int32_t type = 0;    // P-TOOL-00001 typ; 2 = grinding
    double wear_const = 0.0;  // P-TOOL-00030 grinding_wear_const, 0.1 um/m
    double max_infeed = 0.0;  // P-TOOL-00031 grinding_max_infeed, 0.1 um
    double tilt_angle = 0.0;  // P-TOOL-00138 grinding_disc_tilt_angle, 0.0001 degree
};

// The wear of the current tool since it was changed in ([ISG-OTC] section 2.8), in mm. Updated
// at #OTC OFF only ("Während aktiver OTC sind die V.G.WZ_AKT-Verschleißwerte nicht aktuell").
struct OtcWear {
    double radius = 0.0;                       // V.G.WZ_AKT.WEAR_RADIUS: discrete + continuous
    double radius_cont = 0.0;                  // V.G.WZ_AKT.WEAR_RADIUS_CONT
    std::array<double, kOtcAxisCount> axis{};  // V.G.WZ_AKT.WEAR[i], by board axis
};

// Design defaults of the offset ramp (docs/otc.md "The ramp"): a discrete offset of 2 mm takes
// about 4.5 s, slow enough for the lag [ISG-OTC] describes at wr_quad_disc.nc's G26 corner.
// The ramp's defaults and the B head's axis, as the object map declares them.
inline constexpr double kDefaultRampVelocity = otc::kDefaultRampVelocity;          // PU per second
inline constexpr double kDefaultRampAcceleration = otc::kDefaultRampAcceleration;  // PU per second squared
inline constexpr std::int32_t kDefaultToolAxisB = otc::kDefaultToolAxisB;

struct OtcState {
    bool active = false;  // V.G.OTC_ACTIVE
    otc::ProcessingType type = otc::kDefaultProcessingType;
    otc::Mode mode = otc::kDefaultMode;
    double programmed_wear_const = 0.0;      // WEAR_CONST=.., 0.1 um/m
    bool use_programmed_wear_const = false;  // WEAR_CONST=.. (true) / WEAR_CONST_TOOL (false)
    std::int32_t acc_weight = otc::kDefaultAccWeight;
    double ramp_velocity = kDefaultRampVelocity;
    double ramp_acceleration = kDefaultRampAcceleration;
    std::int32_t kinematics = 0;  // #KIN ID (0 none, 4 the B head)
    bool trafo = false;           // #TRAFO ON
    std::int32_t tool_axis_b = kDefaultToolAxisB;
    otc::Error last_error = otc::Error::kNone;

    OtcControlUnit radius_offset_unit;                       // otc_radius_offset (channel)
    std::array<OtcControlUnit, kOtcAxisCount> axis_units{};  // otc_offset per board axis
    std::array<OtcBoolUnit, kOtcAxisCount> back_to_start{};  // ManualMvBackToStart per axis
    OtcTool tool;
    OtcWear wear;

    // The wear constant in force ([ISG-OTC] section 2.1 WEAR_CONST / WEAR_CONST_TOOL).
    double effective_wear_const() const noexcept {
        return use_programmed_wear_const ? programmed_wear_const : tool.wear_const;
    }
};

}  // namespace rwmos
