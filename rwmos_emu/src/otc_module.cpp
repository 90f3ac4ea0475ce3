// SPDX-License-Identifier: MIT
// OTC module, bus 1330 ([ISG-OTC], ISG FCT-C20 "Online Werkzeugkompensation", and
// [ISG-OTC-EN], its English radius section; docs/design.md section 4). The table declares every
// object; the hooks below hold the rules, citing the section of [ISG-OTC] each comes from. The
// dictionary has checked address, access, type and range when a hook runs; a hook
// that refuses changes nothing but LastError.
#include "rwmos/otc_module.h"

#include <array>

#include "objif/map/objects.h"
#include <cmath>
#include <limits>

#include "rwmos/board_state.h"
#include "rwmos/geometry/kinematics.h"
#include "rwmos/module_table.h"

namespace rwmos {

namespace {
// The map's declarations (objif/map/object_map.h) are the engine's limits too.
static_assert(otc::kBHeadKinematics == geom::kBHeadKinematicsId);
static_assert(otc::kAxisCount == kOtcAxisCount);
static_assert(otc::kMinAccWeight == objif::map::otc::kMinAccWeight);
static_assert(otc::kMaxAccWeight == objif::map::otc::kMaxAccWeight);
static_assert(otc::kDefaultAccWeight == objif::map::otc::kDefaultAccWeight);
static_assert(otc::kTiltUnitInDegrees == objif::map::otc::kTiltUnitInDegrees);
static_assert(otc::kMaxTiltDegrees == objif::map::otc::kMaxTiltDegrees);
}  // namespace

std::int32_t OtcModule::bus() const noexcept {
    return otc::kBus;
}
bool OtcModule::present() const noexcept {
    return state_.config.option_otc;
}

std::span<const Entry<OtcModule>> OtcModule::table() const noexcept {
    using M = OtcModule;
    // What a write while OTC is on answers (write_while_off).
    constexpr otc::Error kFixed = otc::Error::kChangeWhileActive;
    constexpr otc::Error kToolFixed = otc::Error::kToolChangeWhileActive;
    static constexpr std::array<Hooks<M>, 40> kHooks{{
        // ---- DeviceNumber 0: #OTC ([ISG-OTC] section 2.1), ramp, kinematics, channel unit.
        {"Active", &M::read_active, &M::write_active},
        {"ProcessingType", &M::read_field<&State::otc, &OtcState::type>,
         &M::write_while_off<kFixed, &State::otc, &OtcState::type>},
        {"Mode", &M::read_field<&State::otc, &OtcState::mode>,
         &M::write_while_off<kFixed, &State::otc, &OtcState::mode>},
        {"WearConst", &M::read_field<&State::otc, &OtcState::programmed_wear_const>,
         &M::write_wear_const},
        {"WearConstSource", &M::read_wear_const_source, &M::write_wear_const_source},
        {"AccWeight", &M::read_field<&State::otc, &OtcState::acc_weight>,
         &M::write_while_off<kFixed, &State::otc, &OtcState::acc_weight>},
        {"LastError", &M::read_field<&State::otc, &OtcState::last_error>, &M::write_last_error},
        {"EffectiveWearConst", &M::read_effective_wear_const, nullptr},
        {"RampVelocity", &M::read_field<&State::otc, &OtcState::ramp_velocity>,
         &M::write_field<&State::otc, &OtcState::ramp_velocity>},
        {"RampAcceleration", &M::read_field<&State::otc, &OtcState::ramp_acceleration>,
         &M::write_field<&State::otc, &OtcState::ramp_acceleration>},
        {"Kinematics", &M::read_field<&State::otc, &OtcState::kinematics>, &M::write_kinematics},
        {"Trafo", &M::read_trafo, &M::write_trafo},
        {"ToolAxisB", &M::read_field<&State::otc, &OtcState::tool_axis_b>,
         &M::write_while_off<kFixed, &State::otc, &OtcState::tool_axis_b>},
        {"otc_radius_offset.command_w", &M::read_unit_command, &M::write_unit_command},
        {"otc_radius_offset.enable_w", &M::read_unit_enable, &M::write_unit_enable},
        {"otc_radius_offset.request_r", &M::read_unit_request, nullptr},
        {"otc_radius_offset.state_r", &M::read_unit_state, nullptr},
        // ---- DeviceNumber 1: otc_offset of every board axis ([ISG-OTC] section 2.7.2).
        {"otc_offset.command_w", &M::read_unit_command, &M::write_unit_command},
        {"otc_offset.enable_w", &M::read_unit_enable, &M::write_unit_enable},
        {"otc_offset.request_r", &M::read_unit_request, nullptr},
        {"otc_offset.state_r", &M::read_unit_state, nullptr},
        {"ManualMvBackToStart.X_Command", &M::read_back_command, &M::write_back_command},
        {"ManualMvBackToStart.X_Enable", &M::read_back_enable, &M::write_back_enable},
        {"ManualMvBackToStart.X_Request", &M::read_back_request, nullptr},
        {"ManualMvBackToStart.X_State", &M::read_back_state, nullptr},
        // ---- DeviceNumber 2: the current tool (V.G.WZ_AKT; [ISG-OTC] sections 2.6, 2.8, 3.2).
        {"ToolNumber", &M::read_field<&State::otc, &OtcState::tool, &OtcTool::number>,
         &M::write_tool_number},
        {"typ", &M::read_field<&State::otc, &OtcState::tool, &OtcTool::type>,
         &M::write_while_off<kToolFixed, &State::otc, &OtcState::tool, &OtcTool::type>},
        {"grinding_wear_const", &M::read_field<&State::otc, &OtcState::tool, &OtcTool::wear_const>,
         &M::write_tool_wear_const},
        {"grinding_max_infeed", &M::read_field<&State::otc, &OtcState::tool, &OtcTool::max_infeed>,
         &M::write_while_off<kToolFixed, &State::otc, &OtcState::tool, &OtcTool::max_infeed>},
        {"grinding_disc_tilt_angle",
         &M::read_field<&State::otc, &OtcState::tool, &OtcTool::tilt_angle>,
         &M::write_while_off<kToolFixed, &State::otc, &OtcState::tool, &OtcTool::tilt_angle>},
        {"V.G.WZ_AKT.WEAR_RADIUS", &M::read_field<&State::otc, &OtcState::wear, &OtcWear::radius>,
         nullptr},
        {"V.G.WZ_AKT.WEAR_RADIUS_CONT",
         &M::read_field<&State::otc, &OtcState::wear, &OtcWear::radius_cont>, nullptr},
        {"V.G.WZ_AKT.WEAR[0]", &M::read_wear, nullptr},
        {"V.G.WZ_AKT.WEAR[1]", &M::read_wear, nullptr},
        {"V.G.WZ_AKT.WEAR[2]", &M::read_wear, nullptr},
        {"V.G.WZ_AKT.WEAR[3]", &M::read_wear, nullptr},
        {"V.G.WZ_AKT.WEAR[4]", &M::read_wear, nullptr},
        {"V.G.WZ_AKT.WEAR[5]", &M::read_wear, nullptr},
        {"V.G.WZ_AKT.WEAR[6]", &M::read_wear, nullptr},
        {"V.G.WZ_AKT.WEAR[7]", &M::read_wear, nullptr},
    }};
    static constexpr auto kTable = objif::attach(objif::map::otc::kObjects, kHooks);
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

// A setting OTC fixes while it is on ([ISG-OTC] section 2.1: "Die Parametrierung kann vorab
// oder zusammen mit #OTC ON erfolgen"; the tool data likewise): writing the value it holds
// changes nothing and is accepted any time; another value is refused with `E` while OTC is on.
template <otc::Error E, auto... Path>
Status OtcModule::write_while_off(const Info&, const Address&, const Value& v) {
    auto& field = field_of<Path...>(state_);
    auto value = field;
    assign(value, v);
    if (value == field) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(E);
    field = value;
    return Status::kOk;
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

// [ISG-OTC] section 2.1 WEAR_CONST=..: "wirkt modal"; it may change while OTC is on and acts
// from the next profile spooled on: the profiles spooled before it, queued or held, keep the
// constant they were programmed under (OtcEngine::wear_const_changed).
Status OtcModule::write_wear_const(const Info&, const Address&, const Value& v) {
    const double before = state_.otc.effective_wear_const();
    state_.otc.programmed_wear_const = v.as_double();
    state_.otc.use_programmed_wear_const = true;
    state_.otc_engine.wear_const_changed(before);
    return Status::kOk;
}

Status OtcModule::read_wear_const_source(const Info&, const Address&, Value& out) {
    out = Value::of_int(state_.otc.use_programmed_wear_const ? 1 : 0);
    return Status::kOk;
}

// [ISG-OTC] section 2.1 WEAR_CONST_TOOL: "Umschalten auf die in den aktuellen Werkzeugdaten
// festgelegte Standardverschleißkonstante; wirkt modal".
Status OtcModule::write_wear_const_source(const Info&, const Address&, const Value& v) {
    const double before = state_.otc.effective_wear_const();
    state_.otc.use_programmed_wear_const = v.as_int() == 1;
    state_.otc_engine.wear_const_changed(before);
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

// ---- ManualMvBackToStart ([ISG-OTC] section 2.7.3, "Handbetriebsoffset zurück fahren")

Status OtcModule::read_back_command(const Info&, const Address& a, Value& out) {
    out = Value::of_int(state_.otc.back_to_start[static_cast<std::size_t>(a.index)].command ? 1 : 0);
    return Status::kOk;
}

// "Ist der Handbetrieb im Kanal aktiv und bewegt sich die beauftragte Achse nicht, wird die
// Achse durch dieses Kommando so bewegt, dass der Handbetriebsoffset anschließend 0 ist. ...
// Eine steigende Flanke (FALSE -> TRUE) an X_Command löst den Vorgang aus. Das Signal wird
// ignoriert, wenn noch eine Handbetriebsbewegung aktiv ist oder der Handbetriebsoffset bereits 0
// ist." Manual mode and its offset are the motion layer's (MotionLayer::manual_offset).
Status OtcModule::write_back_command(const Info&, const Address& a, const Value& v) {
    OtcBoolUnit& u = state_.otc.back_to_start[static_cast<std::size_t>(a.index)];
    const bool rising = !u.command && v.as_int() == 1;
    u.command = v.as_int() == 1;
    if (rising && u.enable) (void)state_.motion.move_back_to_manual_start(a.index);
    return Status::kOk;
}

Status OtcModule::read_back_enable(const Info&, const Address& a, Value& out) {
    out = Value::of_int(state_.otc.back_to_start[static_cast<std::size_t>(a.index)].enable ? 1 : 0);
    return Status::kOk;
}

Status OtcModule::write_back_enable(const Info&, const Address& a, const Value& v) {
    state_.otc.back_to_start[static_cast<std::size_t>(a.index)].enable = v.as_int() == 1;
    return Status::kOk;
}

Status OtcModule::read_back_request(const Info&, const Address& a, Value& out) {
    const OtcBoolUnit& u = state_.otc.back_to_start[static_cast<std::size_t>(a.index)];
    out = Value::of_int(u.enable && u.command ? 1 : 0);
    return Status::kOk;
}

Status OtcModule::read_back_state(const Info&, const Address& a, Value& out) {
    out = Value::of_int(state_.motion.moving_back(a.index) ? 1 : 0);
    return Status::kOk;
}

// ---- DeviceNumber 2

Status OtcModule::write_tool_number(const Info&, const Address&, const Value& v) {
    if (v.as_int() == state_.otc.tool.number) return Status::kOk;
    if (state_.otc.active) return refuse_while_active(otc::Error::kToolChangeWhileActive);
    state_.otc.tool.number = v.as_int();
    state_.otc_engine.tool_changed();
    return Status::kOk;
}

// [ISG-OTC] section 2.8: "Sie kann auch im NC-Programm über die Variable V.G.WZ_AKT.WEAR_CONST
// ... geschrieben bzw. gelesen werden": writable while OTC is on, from the next profile spooled.
Status OtcModule::write_tool_wear_const(const Info&, const Address&, const Value& v) {
    const double before = state_.otc.effective_wear_const();
    state_.otc.tool.wear_const = v.as_double();
    state_.otc_engine.wear_const_changed(before);
    return Status::kOk;
}

Status OtcModule::read_wear(const Info&, const Address& a, Value& out) {
    out = Value::of_double(state_.otc.wear.axis[static_cast<std::size_t>(a.subindex)]);
    return Status::kOk;
}

}  // namespace rwmos
