// SPDX-License-Identifier: MIT
// OTC module, bus 1330 ([ISG-OTC], ISG FCT-C20 "Online Werkzeugkompensation", and
// [ISG-OTC-EN], its English radius section; docs/design.md section 4). The table declares every
// object; the hooks below hold the rules, citing the section of [ISG-OTC] each comes from. The
// dictionary has checked address, access, type and range when a hook runs; a hook
// that refuses changes nothing but LastError.
#include "rwmos/otc_module.h"

#include <array>
#include <cmath>
#include <limits>

#include "rwmos/board_state.h"
#include "rwmos/geometry/kinematics.h"

namespace rwmos {

using objif::Access;
using objif::Address;
using objif::Entry;
using objif::ObjectInfo;
using objif::Status;
using objif::Value;
using objif::ValueType;

namespace {
constexpr double kIntMin = objif::kInt32Min;
constexpr double kIntMax = objif::kInt32Max;
constexpr double kDoubleMax = std::numeric_limits<double>::max();
constexpr double kLastAxis = kOtcAxisCount - 1;
// The ramp's limits (design): above 0, at most 1e6 mm/s (or /s^2) like the TC tool sizes.
constexpr double kMinRamp = 1e-9;
constexpr double kMaxRamp = 1.0e6;
// P-TOOL-00138 in 0.0001 degree: [-45, 45] degrees.
constexpr double kMaxTiltUnits = otc::kMaxTiltDegrees / otc::kTiltUnitInDegrees;

constexpr ObjectInfo obj(std::int32_t dev, std::int32_t index, std::int32_t sub,
                         std::string_view name, ValueType type, Access access, double min,
                         double max, Value def, std::string_view rule) {
    return {dev, index, index, sub, name, type, access, min, max, def, rule};
}
constexpr ObjectInfo axis_unit_obj(std::int32_t sub, std::string_view name, ValueType type,
                                   Access access, double min, double max, std::string_view rule) {
    return {otc::kDevAxisUnits, 0,   kOtcAxisCount - 1, sub, name, type, access, min, max,
            Value::of_int(0),   rule};
}
}  // namespace

std::int32_t OtcModule::bus() const noexcept {
    return otc::kBus;
}
bool OtcModule::present() const noexcept {
    return state_.config.option_otc;
}

std::span<const Entry<OtcModule>> OtcModule::table() const noexcept {
    using M = OtcModule;
    constexpr auto kInt = ValueType::kInt32;
    constexpr auto kDouble = ValueType::kDouble;
    constexpr auto kR = Access::kRead;
    constexpr auto kRW = Access::kReadWrite;
    constexpr auto kCh = otc::kDevChannel;
    constexpr auto kTool = otc::kDevTool;
    constexpr auto kUnit = otc::kIdxRadiusOffsetUnit;
    static constexpr std::array<Entry<M>, 36> kTable{{
        // ---- DeviceNumber 0: #OTC ([ISG-OTC] section 2.1), ramp, kinematics, channel unit.
        {obj(kCh, otc::kIdxActive, 0, "Active", kInt, kRW, 0, 1, Value::of_int(0),
             "[ISG-OTC] 2.1/2.8: V.G.OTC_ACTIVE; 1 = #OTC ON (tool type 2, else P-ERR-21391), "
             "0 = #OTC OFF (G40 first in RADIUS; folds the wear); Busy while moves are queued"),
         &M::read_active, &M::write_active},
        {obj(kCh, otc::kIdxProcessingType, 0, "ProcessingType", kInt, kRW, 0, 3, Value::of_int(1),
             "[ISG-OTC] 2.1: 0 RADIUS, 1 LENGTH (default), 2 TOOL_DIR, 3 SURF_NORM_DIR; not while "
             "on"),
         &M::read_type, &M::write_type},
        {obj(kCh, otc::kIdxMode, 0, "Mode", kInt, kRW, 0, 2, Value::of_int(2),
             "[ISG-OTC] 2.1: 0 CONT, 1 DISC, 2 AUTO (default); not while on"),
         &M::read_mode, &M::write_mode},
        {obj(kCh, otc::kIdxWearConst, 0, "WearConst", kDouble, kRW, 0.0, kDoubleMax,
             Value::of_double(0.0),
             "[ISG-OTC] 2.1 WEAR_CONST=..: 0.1 um/m, modal; a write also selects it "
             "(WearConstSource 1)"),
         &M::read_wear_const, &M::write_wear_const},
        {obj(kCh, otc::kIdxWearConstSource, 0, "WearConstSource", kInt, kRW, 0, 1, Value::of_int(0),
             "[ISG-OTC] 2.1: 0 WEAR_CONST_TOOL (default), 1 the programmed WEAR_CONST"),
         &M::read_wear_const_source, &M::write_wear_const_source},
        {obj(kCh, otc::kIdxAccWeight, 0, "AccWeight", kInt, kRW, otc::kMinAccWeight,
             otc::kMaxAccWeight, Value::of_int(otc::kDefaultAccWeight),
             "[ISG-OTC] 2.1 ACC_WEIGHT: percent [1;100] of the ramp acceleration; not while on"),
         &M::read_acc_weight, &M::write_acc_weight},
        {obj(kCh, otc::kIdxLastError, 0, "LastError", kInt, kRW, kIntMin, kIntMax, Value::of_int(0),
             "design: number of the last refused rule (21391 = P-ERR-21391); a write clears it"),
         &M::read_last_error, &M::write_last_error},
        {obj(kCh, otc::kIdxEffectiveWearConst, 0, "EffectiveWearConst", kDouble, kR, 0.0,
             kDoubleMax, Value::of_double(0.0), "design: the wear constant in force, 0.1 um/m"),
         &M::read_effective_wear_const, nullptr},
        {obj(kCh, otc::kIdxRampVelocity, 0, "RampVelocity", kDouble, kRW, kMinRamp, kMaxRamp,
             Value::of_double(kDefaultRampVelocity),
             "design: largest speed of a discrete offset, mm/s ([ISG-OTC]: over several cycles)"),
         &M::read_ramp_velocity, &M::write_ramp_velocity},
        {obj(kCh, otc::kIdxRampAcceleration, 0, "RampAcceleration", kDouble, kRW, kMinRamp,
             kMaxRamp, Value::of_double(kDefaultRampAcceleration),
             "design: largest acceleration of a discrete offset at ACC_WEIGHT 100, mm/s^2"),
         &M::read_ramp_acceleration, &M::write_ramp_acceleration},
        {obj(kCh, otc::kIdxKinematics, 0, "Kinematics", kInt, kRW, 0, geom::kBHeadKinematicsId,
             Value::of_int(0),
             "design: #KIN ID; 0 none, 4 the B head (docs/design.md section 8); not while on"),
         &M::read_kinematics, &M::write_kinematics},
        {obj(kCh, otc::kIdxTrafo, 0, "Trafo", kInt, kRW, 0, 1, Value::of_int(0),
             "design: #TRAFO ON/OFF; with the B head on, TOOL_DIR/SURF_NORM_DIR follow B; not "
             "while on"),
         &M::read_trafo, &M::write_trafo},
        {obj(kCh, otc::kIdxToolAxisB, 0, "ToolAxisB", kInt, kRW, 0, kLastAxis,
             Value::of_int(kDefaultToolAxisB),
             "design: board axis of the B head's B; not while on"),
         &M::read_tool_axis_b, &M::write_tool_axis_b},
        {obj(kCh, kUnit, otc::kSubCommand, "otc_radius_offset.command_w", kInt, kRW, kIntMin,
             kIntMax, Value::of_int(0),
             "[ISG-OTC] 2.7.1: 0.1 um within [-P-TOOL-00031, P-TOOL-00031]; RADIUS or TOOL_DIR, "
             "DISC/AUTO"),
         &M::read_unit_command, &M::write_unit_command},
        {obj(kCh, kUnit, otc::kSubEnable, "otc_radius_offset.enable_w", kInt, kRW, 0, 1,
             Value::of_int(0), "[ISG-OTC] 2.7.1: the PLC enables the unit"),
         &M::read_unit_enable, &M::write_unit_enable},
        {obj(kCh, kUnit, otc::kSubRequest, "otc_radius_offset.request_r", kInt, kR, kIntMin,
             kIntMax, Value::of_int(0),
             "design reading of 2.7.1: the offset the ramp heads for, 0.1 um"),
         &M::read_unit_request, nullptr},
        {obj(kCh, kUnit, otc::kSubState, "otc_radius_offset.state_r", kInt, kR, kIntMin, kIntMax,
             Value::of_int(0), "design reading of 2.7.1: the offset reached, 0.1 um"),
         &M::read_unit_state, nullptr},

        // ---- DeviceNumber 1: otc_offset of every board axis ([ISG-OTC] section 2.7.2).
        {axis_unit_obj(
             otc::kSubCommand, "otc_offset.command_w", kInt, kRW, kIntMin, kIntMax,
             "[ISG-OTC] 2.7.2: 0.1 um within [-P-TOOL-00031, P-TOOL-00031]; RADIUS, LENGTH; "
             "third axis along the direction in TOOL_DIR/SURF_NORM_DIR"),
         &M::read_unit_command, &M::write_unit_command},
        {axis_unit_obj(otc::kSubEnable, "otc_offset.enable_w", kInt, kRW, 0, 1,
                       "[ISG-OTC] 2.7.2: the PLC enables the unit"),
         &M::read_unit_enable, &M::write_unit_enable},
        {axis_unit_obj(otc::kSubRequest, "otc_offset.request_r", kInt, kR, kIntMin, kIntMax,
                       "design reading of 2.7.2: the offset the ramp heads for, 0.1 um"),
         &M::read_unit_request, nullptr},
        {axis_unit_obj(otc::kSubState, "otc_offset.state_r", kInt, kR, kIntMin, kIntMax,
                       "design reading of 2.7.2: the offset reached, 0.1 um"),
         &M::read_unit_state, nullptr},

        // ---- DeviceNumber 2: the current tool (V.G.WZ_AKT; [ISG-OTC] sections 2.6, 2.8, 3.2).
        {obj(kTool, otc::kIdxToolNumber, 0, "ToolNumber", kInt, kRW, 0, tc::kToolCount - 1,
             Value::of_int(0),
             "design: the tool (D n, TC WKZINDEX) the wear folds into; a change starts its wear "
             "from 0 ([ISG-OTC] section 2.9); not while on"),
         &M::read_tool_number, &M::write_tool_number},
        {obj(kTool, otc::kIdxToolType, 0, "typ", kInt, kRW, 0, 3, Value::of_int(0),
             "[ISG-OTC] 3.2 P-TOOL-00001: 0 milling, 1 turning, 2 grinding, 3 wire; not while on"),
         &M::read_tool_type, &M::write_tool_type},
        {obj(kTool, otc::kIdxToolWearConst, 0, "grinding_wear_const", kDouble, kRW, 0.0, kDoubleMax,
             Value::of_double(0.0),
             "[ISG-OTC] 3.2 P-TOOL-00030, 0.1 um/m; V.G.WZ_AKT.WEAR_CONST (2.8: read and write)"),
         &M::read_tool_wear_const, &M::write_tool_wear_const},
        {obj(kTool, otc::kIdxToolMaxInfeed, 0, "grinding_max_infeed", kDouble, kRW, kIntMin,
             kIntMax, Value::of_double(0.0),
             "[ISG-OTC] 3.2 P-TOOL-00031: 0.1 um, SGN32 range; 0: no discrete offset; "
             "not while on"),
         &M::read_tool_max_infeed, &M::write_tool_max_infeed},
        {obj(kTool, otc::kIdxToolTiltAngle, 0, "grinding_disc_tilt_angle", kDouble, kRW,
             -kMaxTiltUnits, kMaxTiltUnits, Value::of_double(0.0),
             "[ISG-OTC] 3.2 P-TOOL-00138: 0.0001 degree within [-45, 45] degrees; not while on"),
         &M::read_tool_tilt, &M::write_tool_tilt},
        {obj(kTool, otc::kIdxWearRadius, 0, "V.G.WZ_AKT.WEAR_RADIUS", kDouble, kR, -kDoubleMax,
             kDoubleMax, Value::of_double(0.0),
             "[ISG-OTC] 2.8: radius wear, discrete + continuous, mm; updated at #OTC OFF"),
         &M::read_wear_radius, nullptr},
        {obj(kTool, otc::kIdxWearRadiusCont, 0, "V.G.WZ_AKT.WEAR_RADIUS_CONT", kDouble, kR,
             -kDoubleMax, kDoubleMax, Value::of_double(0.0),
             "[ISG-OTC] 2.8: continuous radius wear, mm; updated at #OTC OFF"),
         &M::read_wear_radius_cont, nullptr},
        {{kTool, otc::kIdxWear, otc::kIdxWear, 0, "V.G.WZ_AKT.WEAR[0]", kDouble, kR, -kDoubleMax,
          kDoubleMax, Value::of_double(0.0),
          "[ISG-OTC] 2.8: wear on axis 0, mm; updated at #OTC OFF"},
         &M::read_wear,
         nullptr},
        {{kTool, otc::kIdxWear, otc::kIdxWear, 1, "V.G.WZ_AKT.WEAR[1]", kDouble, kR, -kDoubleMax,
          kDoubleMax, Value::of_double(0.0), "[ISG-OTC] 2.8: wear on axis 1"},
         &M::read_wear,
         nullptr},
        {{kTool, otc::kIdxWear, otc::kIdxWear, 2, "V.G.WZ_AKT.WEAR[2]", kDouble, kR, -kDoubleMax,
          kDoubleMax, Value::of_double(0.0), "[ISG-OTC] 2.8: wear on axis 2"},
         &M::read_wear,
         nullptr},
        {{kTool, otc::kIdxWear, otc::kIdxWear, 3, "V.G.WZ_AKT.WEAR[3]", kDouble, kR, -kDoubleMax,
          kDoubleMax, Value::of_double(0.0), "[ISG-OTC] 2.8: wear on axis 3"},
         &M::read_wear,
         nullptr},
        {{kTool, otc::kIdxWear, otc::kIdxWear, 4, "V.G.WZ_AKT.WEAR[4]", kDouble, kR, -kDoubleMax,
          kDoubleMax, Value::of_double(0.0), "[ISG-OTC] 2.8: wear on axis 4"},
         &M::read_wear,
         nullptr},
        {{kTool, otc::kIdxWear, otc::kIdxWear, 5, "V.G.WZ_AKT.WEAR[5]", kDouble, kR, -kDoubleMax,
          kDoubleMax, Value::of_double(0.0), "[ISG-OTC] 2.8: wear on axis 5"},
         &M::read_wear,
         nullptr},
        {{kTool, otc::kIdxWear, otc::kIdxWear, 6, "V.G.WZ_AKT.WEAR[6]", kDouble, kR, -kDoubleMax,
          kDoubleMax, Value::of_double(0.0), "[ISG-OTC] 2.8: wear on axis 6"},
         &M::read_wear,
         nullptr},
        {{kTool, otc::kIdxWear, otc::kIdxWear, 7, "V.G.WZ_AKT.WEAR[7]", kDouble, kR, -kDoubleMax,
          kDoubleMax, Value::of_double(0.0), "[ISG-OTC] 2.8: wear on axis 7"},
         &M::read_wear,
         nullptr},
    }};
    return kTable;
}

// ---- Helpers

Status OtcModule::refuse(otc::Error e, Status s) noexcept {
    state_.otc.last_error = e;
    return s;
}

Status OtcModule::refuse_while_active(otc::Error e) noexcept {
    return refuse(e, Status::kWrongDeviceState);
}

bool OtcModule::queue_busy() const noexcept {
    return state_.motion.executor().fill() != 0;
}

OtcControlUnit* OtcModule::unit_at(const Address& a) noexcept {
    if (a.device == otc::kDevChannel) return &state_.otc.radius_offset_unit;
    return &state_.otc.axis_units[static_cast<std::size_t>(a.index)];
}

// ---- DeviceNumber 0

Status OtcModule::read_active(const Info&, const Address&, Value& out) {
    out = Value::of_int(state_.otc.active ? 1 : 0);
    return Status::kOk;
}

Status OtcModule::write_active(const Info&, const Address&, const Value& v) {
    OtcState& o = state_.otc;
    const bool on = v.as_int() == 1;
    if (on == o.active) return Status::kOk;
    // Design: #OTC ON and OFF act between moves, so they take effect exactly at their place in
    // the program; the host runs the clock until the queue is empty and writes again.
    if (queue_busy()) return Status::kBusy;
    if (on) {
        // [ISG-OTC] section 1 "Eigenschaften": only tool type 2, else P-ERR-21391.
        if (o.tool.type != otc::kGrindingToolType)
            return refuse(otc::Error::kToolNotGrinding, Status::kWrongDeviceState);
        o.active = true;
        state_.otc_engine.start_session();
        return Status::kOk;
    }
    // [ISG-OTC] section 2.2 "Hinweis": "Bei der Abwahl muss zwingend die Sequenz G40 vor
    // #OTC OFF eingehalten werden."
    if (o.type == otc::ProcessingType::kRadius) {
        for (const TcGroup& g : state_.tc.groups)
            if (g.running()) return refuse(otc::Error::kOffBeforeG40, Status::kWrongDeviceState);
    }
    state_.otc_engine.end_session();
    o.active = false;
    return Status::kOk;
}

Status OtcModule::read_type(const Info&, const Address&, Value& out) {
    out = Value::of_int(static_cast<std::int32_t>(state_.otc.type));
    return Status::kOk;
}

// [ISG-OTC] section 2.1: "Die Parametrierung kann vorab oder zusammen mit #OTC ON erfolgen."
Status OtcModule::write_type(const Info&, const Address&, const Value& v) {
    const auto t = static_cast<otc::ProcessingType>(v.as_int());
    if (t == state_.otc.type) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kChangeWhileActive);
    state_.otc.type = t;
    return Status::kOk;
}

Status OtcModule::read_mode(const Info&, const Address&, Value& out) {
    out = Value::of_int(static_cast<std::int32_t>(state_.otc.mode));
    return Status::kOk;
}

Status OtcModule::write_mode(const Info&, const Address&, const Value& v) {
    const auto m = static_cast<otc::Mode>(v.as_int());
    if (m == state_.otc.mode) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kChangeWhileActive);
    state_.otc.mode = m;
    return Status::kOk;
}

Status OtcModule::read_wear_const(const Info&, const Address&, Value& out) {
    out = Value::of_double(state_.otc.programmed_wear_const);
    return Status::kOk;
}

// [ISG-OTC] section 2.1 WEAR_CONST=..: "wirkt modal"; it may change while OTC is on and acts
// from the next move (design: a move's wear is linear along it).
Status OtcModule::write_wear_const(const Info&, const Address&, const Value& v) {
    state_.otc.programmed_wear_const = v.as_double();
    state_.otc.use_programmed_wear_const = true;
    return Status::kOk;
}

Status OtcModule::read_wear_const_source(const Info&, const Address&, Value& out) {
    out = Value::of_int(state_.otc.use_programmed_wear_const ? 1 : 0);
    return Status::kOk;
}

// [ISG-OTC] section 2.1 WEAR_CONST_TOOL: "Umschalten auf die in den aktuellen Werkzeugdaten
// festgelegte Standardverschleißkonstante; wirkt modal".
Status OtcModule::write_wear_const_source(const Info&, const Address&, const Value& v) {
    state_.otc.use_programmed_wear_const = v.as_int() == 1;
    return Status::kOk;
}

Status OtcModule::read_acc_weight(const Info&, const Address&, Value& out) {
    out = Value::of_int(state_.otc.acc_weight);
    return Status::kOk;
}

Status OtcModule::write_acc_weight(const Info&, const Address&, const Value& v) {
    if (v.as_int() == state_.otc.acc_weight) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kChangeWhileActive);
    state_.otc.acc_weight = v.as_int();
    return Status::kOk;
}

Status OtcModule::read_last_error(const Info&, const Address&, Value& out) {
    out = Value::of_int(static_cast<std::int32_t>(state_.otc.last_error));
    return Status::kOk;
}

Status OtcModule::write_last_error(const Info&, const Address&, const Value&) {
    state_.otc.last_error = otc::Error::kNone;
    return Status::kOk;
}

Status OtcModule::read_effective_wear_const(const Info&, const Address&, Value& out) {
    out = Value::of_double(state_.otc.effective_wear_const());
    return Status::kOk;
}

Status OtcModule::read_ramp_velocity(const Info&, const Address&, Value& out) {
    out = Value::of_double(state_.otc.ramp_velocity);
    return Status::kOk;
}

Status OtcModule::write_ramp_velocity(const Info&, const Address&, const Value& v) {
    state_.otc.ramp_velocity = v.as_double();
    return Status::kOk;
}

Status OtcModule::read_ramp_acceleration(const Info&, const Address&, Value& out) {
    out = Value::of_double(state_.otc.ramp_acceleration);
    return Status::kOk;
}

Status OtcModule::write_ramp_acceleration(const Info&, const Address&, const Value& v) {
    state_.otc.ramp_acceleration = v.as_double();
    return Status::kOk;
}

Status OtcModule::read_kinematics(const Info&, const Address&, Value& out) {
    out = Value::of_int(state_.otc.kinematics);
    return Status::kOk;
}

// Only the B head (ID 4) is emulated; 1..3 are refused as invalid (design).
Status OtcModule::write_kinematics(const Info&, const Address&, const Value& v) {
    const std::int32_t id = v.as_int();
    if (id != otc::kNoKinematics && id != geom::kBHeadKinematicsId) return Status::kInvalidValue;
    if (id == state_.otc.kinematics) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kChangeWhileActive);
    state_.otc.kinematics = id;
    return Status::kOk;
}

Status OtcModule::read_trafo(const Info&, const Address&, Value& out) {
    out = Value::of_int(state_.otc.trafo ? 1 : 0);
    return Status::kOk;
}

Status OtcModule::write_trafo(const Info&, const Address&, const Value& v) {
    const bool on = v.as_int() == 1;
    if (on == state_.otc.trafo) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kChangeWhileActive);
    // A transformation needs a kinematics (#KIN ID[..] before #TRAFO ON).
    if (on && state_.otc.kinematics == otc::kNoKinematics) return Status::kWrongDeviceState;
    state_.otc.trafo = on;
    return Status::kOk;
}

Status OtcModule::read_tool_axis_b(const Info&, const Address&, Value& out) {
    out = Value::of_int(state_.otc.tool_axis_b);
    return Status::kOk;
}

Status OtcModule::write_tool_axis_b(const Info&, const Address&, const Value& v) {
    if (v.as_int() == state_.otc.tool_axis_b) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kChangeWhileActive);
    state_.otc.tool_axis_b = v.as_int();
    return Status::kOk;
}

// ---- Control units ([ISG-OTC] section 2.7)

Status OtcModule::read_unit_command(const Info&, const Address& a, Value& out) {
    out = Value::of_int(unit_at(a)->command);
    return Status::kOk;
}

// [ISG-OTC] section 2.7: "Wertebereich [-P-TOOL-00031, P-TOOL-00031]"; section 2.6: "Wenn
// grinding_max_infeed nicht gesetzt wird, kann kein diskreter Versatz beauftragt werden."
Status OtcModule::write_unit_command(const Info&, const Address& a, const Value& v) {
    const double limit = std::fabs(state_.otc.tool.max_infeed);
    const double value = v.as_int();
    if (value > limit) return refuse(otc::Error::kInfeedBeyondLimit, Status::kValueTooHigh);
    if (value < -limit) return refuse(otc::Error::kInfeedBeyondLimit, Status::kValueTooLow);
    unit_at(a)->command = v.as_int();
    return Status::kOk;
}

Status OtcModule::read_unit_enable(const Info&, const Address& a, Value& out) {
    out = Value::of_int(unit_at(a)->enable ? 1 : 0);
    return Status::kOk;
}

Status OtcModule::write_unit_enable(const Info&, const Address& a, const Value& v) {
    unit_at(a)->enable = v.as_int() == 1;
    return Status::kOk;
}

Status OtcModule::read_unit_request(const Info&, const Address& a, Value& out) {
    out = Value::of_int(a.device == otc::kDevChannel ? state_.otc_engine.channel_request()
                                                     : state_.otc_engine.axis_request(a.index));
    return Status::kOk;
}

Status OtcModule::read_unit_state(const Info&, const Address& a, Value& out) {
    out = Value::of_int(a.device == otc::kDevChannel ? state_.otc_engine.channel_state()
                                                     : state_.otc_engine.axis_state(a.index));
    return Status::kOk;
}

// ---- DeviceNumber 2

Status OtcModule::read_tool_number(const Info&, const Address&, Value& out) {
    out = Value::of_int(state_.otc.tool.number);
    return Status::kOk;
}

Status OtcModule::write_tool_number(const Info&, const Address&, const Value& v) {
    if (v.as_int() == state_.otc.tool.number) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kToolChangeWhileActive);
    state_.otc.tool.number = v.as_int();
    state_.otc_engine.tool_changed();
    return Status::kOk;
}

Status OtcModule::read_tool_type(const Info&, const Address&, Value& out) {
    out = Value::of_int(state_.otc.tool.type);
    return Status::kOk;
}

Status OtcModule::write_tool_type(const Info&, const Address&, const Value& v) {
    if (v.as_int() == state_.otc.tool.type) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kToolChangeWhileActive);
    state_.otc.tool.type = v.as_int();
    return Status::kOk;
}

Status OtcModule::read_tool_wear_const(const Info&, const Address&, Value& out) {
    out = Value::of_double(state_.otc.tool.wear_const);
    return Status::kOk;
}

// [ISG-OTC] section 2.8: "Sie kann auch im NC-Programm über die Variable V.G.WZ_AKT.WEAR_CONST
// ... geschrieben bzw. gelesen werden": writable while OTC is on, from the next move.
Status OtcModule::write_tool_wear_const(const Info&, const Address&, const Value& v) {
    state_.otc.tool.wear_const = v.as_double();
    return Status::kOk;
}

Status OtcModule::read_tool_max_infeed(const Info&, const Address&, Value& out) {
    out = Value::of_double(state_.otc.tool.max_infeed);
    return Status::kOk;
}

Status OtcModule::write_tool_max_infeed(const Info&, const Address&, const Value& v) {
    if (v.as_double() == state_.otc.tool.max_infeed) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kToolChangeWhileActive);
    state_.otc.tool.max_infeed = v.as_double();
    return Status::kOk;
}

Status OtcModule::read_tool_tilt(const Info&, const Address&, Value& out) {
    out = Value::of_double(state_.otc.tool.tilt_angle);
    return Status::kOk;
}

Status OtcModule::write_tool_tilt(const Info&, const Address&, const Value& v) {
    if (v.as_double() == state_.otc.tool.tilt_angle) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kToolChangeWhileActive);
    state_.otc.tool.tilt_angle = v.as_double();
    return Status::kOk;
}

Status OtcModule::read_wear_radius(const Info&, const Address&, Value& out) {
    out = Value::of_double(state_.otc.wear.radius);
    return Status::kOk;
}

Status OtcModule::read_wear_radius_cont(const Info&, const Address&, Value& out) {
    out = Value::of_double(state_.otc.wear.radius_cont);
    return Status::kOk;
}

Status OtcModule::read_wear(const Info&, const Address& a, Value& out) {
    out = Value::of_double(state_.otc.wear.axis[static_cast<std::size_t>(a.subindex)]);
    return Status::kOk;
}

}  // namespace rwmos
