// SPDX-License-Identifier: MIT
// All device state of the emulated board in one struct (Board::State), plus
// the modules that serve it through the object dictionary. The motion layer
// reaches the state through Board::state().
#pragma once

#include <array>
#include <cstdint>

#include "objif/dictionary.h"
#include "rwmos/board.h"
#include "rwmos/board_module.h"
#include "rwmos/comp3d_module.h"
#include "rwmos/comp3d_state.h"
#include "rwmos/motion_layer.h"
#include "rwmos/object_map.h"
#include "rwmos/otc_engine.h"
#include "rwmos/otc_module.h"
#include "rwmos/otc_state.h"
#include "rwmos/tempcomp_module.h"
#include "rwmos/tempcomp_state.h"
#include "rwmos/tc_module.h"
#include "rwmos/tc_state.h"

namespace rwmos {

// The board's sizes and limits, as the object map declares them (objif/map/object_map.h).
inline constexpr std::int32_t kAxisCount = board::kAxisCount;
inline constexpr std::int32_t kSpoolerCapacity = board::kSpoolerCapacity;
inline constexpr std::int32_t kDefaultInterpolationCycleUs = board::kDefaultInterpolationCycleUs;
inline constexpr std::int32_t kMinInterpolationCycleUs = board::kMinInterpolationCycleUs;
inline constexpr std::int32_t kMaxInterpolationCycleUs = board::kMaxInterpolationCycleUs;
inline constexpr std::int32_t kFirmwareVersion = board::kFirmwareVersion;

struct AxisState {
    double position = 0.0;  // interpolation units (mm)
};

// Placeholders the motion layer serves: SpoolerCapacity and SpoolerFill read these fields.
struct SpoolerState {
    std::int32_t capacity = kSpoolerCapacity;
    std::int32_t fill = 0;
};

struct EmulatedBoard::State {
    explicit State(const BoardConfig& cfg);
    State(const State&) = delete;
    State& operator=(const State&) = delete;

    BoardConfig config;
    // Board module (bus 1000).
    std::int32_t interpolation_cycle_us = kDefaultInterpolationCycleUs;
    std::int32_t pu = board::kPuMillimetre;
    std::array<AxisState, kAxisCount> axes{};
    SpoolerState spooler;
    // TC module (bus 1300).
    TcState tc;
    TcMotion* tc_motion = nullptr;  // the motion layer, if attached (not owned)
    // Motion: spooler, held profile, move queue, interpolation clock, trace.
    MotionLayer motion;
    // 3D tool compensation module (bus 1310): applied to profiles before the spooler.
    Comp3dState comp3d;
    // OTC module (bus 1330): its objects' state and the per-cycle wear offsets.
    OtcState otc;
    OtcEngine otc_engine;
    // Temperature compensation in tool direction (bus 1320), per interpolation cycle.
    TempCompState temp_comp;
    TempCompEngine temp_comp_engine;
    // The executor's cycle-offset modules, in order: OTC wear, then temperature.
    motion::CycleOffsetsChain cycle_offsets;

    // The modules serve the fields above; the dictionary routes to them.
    BoardModule board_module;
    TcModule tc_module;
    Comp3dModule comp3d_module;
    OtcModule otc_module;
    TempCompModule temp_comp_module;
    objif::Dictionary dictionary;
};

}  // namespace rwmos
