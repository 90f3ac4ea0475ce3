// SPDX-License-Identifier: MIT
// TC module, bus 1300 ([APCI-TC], the APCI-8001 TC
// document; docs/design.md section 3). The table declares every object; the hooks
// below it hold the state rules, each citing the section of [APCI-TC] it comes from.
// The dictionary has already checked bus/device, index, subindex, handle,
// access, type and range when a hook runs, so a hook only checks state, and
// changes nothing when it refuses (save the InitError bit [APCI-TC] asks for).
#include "rwmos/tc_module.h"

#include <array>

#include "objif/map/objects.h"
#include <limits>

#include "rwmos/board_state.h"
#include "rwmos/module_table.h"

namespace rwmos {

namespace {
// Run and ProfMarked cleared, stored offsets gone: the group no longer compensates.
void end_compensation(TcGroup& g) noexcept {
    g.status = 0;
    g.offset = {};
}

// The programmed values of a group back to their defaults (RESET, Clean):
// axes, tool index, side, corner mode, the whole tool table, and ERROR.
void discard_programming(TcGroup& g) noexcept {
    g.error = 0;
    g.x_axis = 0;
    g.y_axis = 1;
    g.z_axis = 2;
    g.tool_index = 0;
    g.side = tc::kSideNone;
    g.corner_mode = tc::kCornerCircular;
    g.selection_mode = tc::kSelectionPerpendicular;
    g.length_mode = tc::kLengthWhileCompensating;
    g.tools.fill(TcTool{});
}
}  // namespace

std::int32_t TcModule::bus() const noexcept { return tc::kBus; }
bool TcModule::present() const noexcept { return state_.config.option_tc; }
TcState& TcModule::tc() noexcept { return state_.tc; }

std::span<const Entry<TcModule>> TcModule::table() const noexcept {
    using M = TcModule;
    static constexpr std::array<Hooks<M>, 26> kHooks{{
        // ---- DeviceNumber 0: initialisation ([APCI-TC] Table 2).
        {"Clean", nullptr, &M::write_clean},
        {"X-Axis-Nr", &M::read_axis_nr, &M::write_axis_nr},
        {"Y-Axis-Nr", &M::read_axis_nr, &M::write_axis_nr},
        {"Z-Axis-Nr", &M::read_axis_nr, &M::write_axis_nr},
        // The range 17..19 leaves 17, 18, 19: every value in range is a plane.
        {"TcPlane", &M::read_field<&State::tc, &TcState::plane>,
         &M::write_field<&State::tc, &TcState::plane>},
        {"ReInit", nullptr, &M::write_reinit},
        {"Reset", nullptr, &M::write_reset},
        {"RotAngle", &M::read_field<&State::tc, &TcState::rot_angle>,
         &M::write_field<&State::tc, &TcState::rot_angle>},
        {"RotCenterX", &M::read_field<&State::tc, &TcState::rot_center_x>,
         &M::write_field<&State::tc, &TcState::rot_center_x>},
        {"RotCenterY", &M::read_field<&State::tc, &TcState::rot_center_y>,
         &M::write_field<&State::tc, &TcState::rot_center_y>},
        // ---- DeviceNumber 1: compensation groups ([APCI-TC] Table 3), Index 0..3.
        {"ERROR", &M::read_group_field<&TcGroup::error>, &M::write_error},
        {"RESET", nullptr, &M::write_group_reset},
        {"STATUS", &M::read_group_field<&TcGroup::status>, &M::write_status},
        {"XAxis", &M::read_group_field<&TcGroup::x_axis>,
         &M::write_group_while_inactive<&TcGroup::x_axis>},
        {"YAxis", &M::read_group_field<&TcGroup::y_axis>,
         &M::write_group_while_inactive<&TcGroup::y_axis>},
        {"RADIUS", &M::read_tool_field<&TcTool::radius>, &M::write_tool_field<&TcTool::radius>},
        {"WKZINDEX", &M::read_group_field<&TcGroup::tool_index>,
         &M::write_group_while_inactive<&TcGroup::tool_index>},
        {"Left", nullptr, &M::write_left},
        {"Right", nullptr, &M::write_right},
        {"ZAxis", &M::read_group_field<&TcGroup::z_axis>,
         &M::write_group_while_inactive<&TcGroup::z_axis>},
        {"WkzLen", &M::read_tool_field<&TcTool::length>, &M::write_tool_field<&TcTool::length>},
        {"CornerMode", &M::read_group_field<&TcGroup::corner_mode>,
         &M::write_group_mode<&TcGroup::corner_mode>},
        {"Side", &M::read_group_field<&TcGroup::side>, nullptr},
        {"SelectionMode", &M::read_group_field<&TcGroup::selection_mode>,
         &M::write_group_mode<&TcGroup::selection_mode>},
        {"LengthMode", &M::read_group_field<&TcGroup::length_mode>,
         &M::write_group_mode<&TcGroup::length_mode>},
        {"CuttingEdge", &M::read_tool_field<&TcTool::cutting_edge>,
         &M::write_tool_field<&TcTool::cutting_edge>},
    }};
    static constexpr auto kTable = objif::attach(objif::map::tc::kObjects, kHooks);
    return kTable;
}

// ---- Lookup and access bookkeeping.

const ObjectInfo* TcModule::find(const Address& a, Status& why) const noexcept {
    if (a.device == tc::kDevInit && (a.index == tc::kIdxReInit || a.index == tc::kIdxReset)) {
        Address any_sub = a;
        any_sub.subindex = 0;
        return TableModule<TcModule>::find(any_sub, why);
    }
    return TableModule<TcModule>::find(a, why);
}

Status TcModule::read(const ObjectInfo& info, const Address& a, Value& out) {
    const Status st = TableModule<TcModule>::read(info, a, out);
    if (objif::ok(st)) tc().objects_accessed = true;
    state_.motion.settings_changed();
    return st;
}

Status TcModule::write(const ObjectInfo& info, const Address& a, const Value& v) {
    const Status st = TableModule<TcModule>::write(info, a, v);
    // Clean discards the objects, so it leaves them un-accessed.
    const bool clean = a.device == tc::kDevInit && a.index == tc::kIdxClean;
    if (objif::ok(st) && !clean) tc().objects_accessed = true;
    state_.motion.settings_changed();
    return st;
}

Status TcModule::group_at(const Address& a, TcGroup*& g, std::int32_t& number) noexcept {
    // [APCI-TC] section 2.2: Index 0 addresses the active group, the one whose
    // plane TcPlane selects. With no such group there is nothing to address.
    number = a.index == tc::kActiveGroupIndex ? active_group(tc()) : a.index;
    if (number == 0) return Status::kWrongDeviceState;
    g = &tc().group(number);
    return Status::kOk;
}

Status TcModule::with_group(const Address& a, TcGroup*& g) noexcept {
    std::int32_t number = 0;
    return group_at(a, g, number);
}

void TcModule::discard_held_profile(std::int32_t number) {
    if (state_.tc_motion != nullptr && tc().group(number).profile_held())
        state_.tc_motion->discard_held_profile(number);
}

void TcModule::clear_shift() {
    if (state_.tc_motion != nullptr) state_.tc_motion->clear_shift();
    for (auto& g : tc().groups) g.offset = {};
}

// ---- DeviceNumber 0.

// [APCI-TC] Table 2 Clean: "Mit diesem Kommando werden alle vorhandenen Objekte
// des TC-Interface ... verworfen. In PCAP-Programmen muss deshalb bei allen
// initialisierten Object-Descriptor-Elementen des TC-Interface das Handle
// abgenullt werden." Every TC value returns to its power-on default (design:
// discarded objects come back as new ones), and every handle goes stale.
Status TcModule::write_clean(const ObjectInfo&, const Address&, const Value&) {
    for (std::int32_t n = 1; n <= tc::kGroupCount; ++n) {
        discard_held_profile(n);
        end_compensation(tc().group(n));
        discard_programming(tc().group(n));
    }
    clear_shift();  // before the rotation goes: the programmed position was rotated with it
    TcState& s = tc();
    s.axis_nr = {0, 1, 2};
    s.plane = tc::kPlaneXY;
    s.rot_angle = s.rot_center_x = s.rot_center_y = 0.0;
    s.objects_accessed = false;
    discard_handles();
    return Status::kOk;
}

Status TcModule::read_axis_nr(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_int(tc().axis_nr[static_cast<std::size_t>(a.subindex)]);
    return Status::kOk;
}

Status TcModule::write_axis_nr(const ObjectInfo&, const Address& a, const Value& v) {
    tc().axis_nr[static_cast<std::size_t>(a.subindex)] = v.as_int();
    return Status::kOk;
}

// [APCI-TC] Table 2 ReInit: "Intern gespeicherte Verschiebungswerte der
// Korrekturachsen werden gelöscht. Dieses Kommando sollte vor einer
// System-Reinitialisierung, z.B. erneute Referenzfahrt aufgerufen werden. Die
// programmierten Werkzeuge bleiben aber aktiv." The shift a contour left (the
// radius offset after SSF 2001 or an indirect deselection, WkzLen on the length
// axis) is forgotten: where the queue ends becomes the programmed position.
// Run, tools and every setting stay. While a profile is held a contour is under
// way whose geometry starts from the shifted point; what ReInit does to it the
// source does not say (it names the command for before a re-reference), so that
// is refused as not emulated (WrongDeviceState, nothing changes; docs/object-map.md 3.4).
Status TcModule::write_reinit(const ObjectInfo&, const Address&, const Value&) {
    for (const auto& g : tc().groups)
        if (g.profile_held()) return Status::kWrongDeviceState;
    clear_shift();
    return Status::kOk;
}

// [APCI-TC] Table 2 Reset: "Alle aktiven Korrekturen werden gestoppt, intern
// gespeicherte Verschiebungswerte der Korrekturachsen und Zwischenprofile
// werden gelöscht ... Die programmierten Werkzeuge bleiben erhalten."
// Configuration (axes, side, WKZINDEX, tools) and ERROR stay.
Status TcModule::write_reset(const ObjectInfo&, const Address&, const Value&) {
    for (std::int32_t n = 1; n <= tc::kGroupCount; ++n) {
        discard_held_profile(n);
        end_compensation(tc().group(n));
    }
    clear_shift();
    return Status::kOk;
}

// ---- DeviceNumber 1.

// [APCI-TC] Table 3 ERROR: "Fehlerstatus ... lesen / rücksetzen". Any written
// value clears every bit ([APCI-TC] gives the value no meaning).
Status TcModule::write_error(const ObjectInfo&, const Address& a, const Value&) {
    TcGroup* g = nullptr;
    const Status st = with_group(a, g);
    if (!objif::ok(st)) return st;
    g->error = 0;
    return Status::kOk;
}

// [APCI-TC] Table 3 RESET: "beendet die Tool-Kompensation und verwirft die
// programmierten Werte. Diese können nun reprogrammiert werden. Der Index und
// der Übergabewert sind bei dieser Funktion bedeutungslos." Since the Index is
// meaningless, RESET acts on the whole tool compensation: every group ends
// compensating (held profile dropped, offsets cleared) and its programmed
// values (axes, WKZINDEX, side, corner mode, tool table, ERROR) return to
// their defaults. The TcPlane settings of DeviceNumber 0 stay.
Status TcModule::write_group_reset(const ObjectInfo&, const Address&, const Value&) {
    for (std::int32_t n = 1; n <= tc::kGroupCount; ++n) {
        discard_held_profile(n);
        end_compensation(tc().group(n));
        discard_programming(tc().group(n));
    }
    clear_shift();
    return Status::kOk;
}

// [APCI-TC] Table 3 STATUS: "Schreiben von 1 aktiviert den Korrekturmodus,
// vorausgesetzt alle anderen Parameter sind richtig initialisiert. Durch
// Schreiben von 0 wird der Korrekturmodus abgeschaltet. Bei fehlerhafter
// Initialisierung der Parameter wird InitError angezeigt."
// [APCI-TC] section 1: deactivating spools the held profile.
Status TcModule::write_status(const ObjectInfo&, const Address& a, const Value& v) {
    TcGroup* g = nullptr;
    std::int32_t number = 0;
    const Status st = group_at(a, g, number);
    if (!objif::ok(st)) return st;
    if (v.as_int() == 1) {
        if (g->running()) return Status::kOk;
        if (initialisation_fault(tc(), number) != InitFault::kNone) {
            g->error |= tc::kInitError;
            return Status::kWrongDeviceState;
        }
        g->status |= tc::kRun;
        if (state_.tc_motion != nullptr) state_.tc_motion->compensation_started(number);
        return Status::kOk;
    }
    if (g->profile_held() && state_.tc_motion != nullptr) {
        const Status released = state_.tc_motion->release_held_profile(number);
        if (!objif::ok(released)) return released;
    }
    g->status &= ~(tc::kRun | tc::kProfMarked);
    return Status::kOk;
}

// [APCI-TC] Table 3 XAxis, YAxis, ZAxis: "Dieser Wert darf nur verändert
// werden, wenn die Werkzeugradius-Korrektur nicht aktiv ist, ansonsten wird
// InitError angezeigt"; WKZINDEX, Left, Right likewise. The write is refused
// (kWrongDeviceState, value unchanged) and InitError is set in the group's ERROR.
Status TcModule::write_while_inactive(const Address& a, std::int32_t TcGroup::*field,
                                      std::int32_t value) {
    TcGroup* g = nullptr;
    const Status st = with_group(a, g);
    if (!objif::ok(st)) return st;
    if (g->running()) {
        g->error |= tc::kInitError;
        return Status::kWrongDeviceState;
    }
    g->*field = value;
    return Status::kOk;
}
template <std::int32_t TcGroup::*Field>
Status TcModule::write_group_while_inactive(const ObjectInfo&, const Address& a, const Value& v) {
    return write_while_inactive(a, Field, v.as_int());
}

// [APCI-TC] Table 3 Left/Right: "die Auswahl erfolgt nur durch den Aufruf, der
// Übergabeparameter ist unerheblich"; section 2.5: only while no compensation is active.
Status TcModule::write_left(const ObjectInfo&, const Address& a, const Value&) {
    return write_while_inactive(a, &TcGroup::side, tc::kSideLeft);
}
Status TcModule::write_right(const ObjectInfo&, const Address& a, const Value&) {
    return write_while_inactive(a, &TcGroup::side, tc::kSideRight);
}

// The current tool's values, any time:
// - [APCI-TC] Table 3 RADIUS: "Korrekturwert für den aktuellen Werkzeugindex". Not restricted
//   to an inactive group by [APCI-TC]: a new radius applies from the next profile the motion
//   layer compensates.
// - [APCI-TC] Table 3 WkzLen: the length of the current tool, like RADIUS.
// - CuttingEdge (extension, docs/compensation.md "Turning tools"): the cutting edge position of
//   the current tool, like RADIUS and WkzLen; it acts from the next contour (a change while the
//   group compensates ends the contour under way and the next profile approaches anew, as a
//   RADIUS change does).
template <auto Field>
Status TcModule::read_tool_field(const ObjectInfo&, const Address& a, Value& out) {
    TcGroup* g = nullptr;
    const Status st = with_group(a, g);
    if (!objif::ok(st)) return st;
    out = value_of(g->tool().*Field);
    return Status::kOk;
}
template <auto Field>
Status TcModule::write_tool_field(const ObjectInfo&, const Address& a, const Value& v) {
    TcGroup* g = nullptr;
    const Status st = with_group(a, g);
    if (!objif::ok(st)) return st;
    assign(g->tool().*Field, v);
    return Status::kOk;
}

// A group's int fields as they are: ERROR and STATUS (written by hooks of their own), XAxis,
// YAxis, ZAxis, WKZINDEX, Side and the modes.
template <std::int32_t TcGroup::*Field>
Status TcModule::read_group_field(const ObjectInfo&, const Address& a, Value& out) {
    TcGroup* g = nullptr;
    const Status st = with_group(a, g);
    if (!objif::ok(st)) return st;
    out = Value::of_int(g->*Field);
    return Status::kOk;
}

// The extension objects that hold a group's mode as written (docs/design.md section 3):
// CornerMode (like G25/G26, applies from the next transition computed), SelectionMode (like
// G237/G139: the mode at activation shapes the approach, the mode at deactivation the
// departure), LengthMode (from the next profile) and Side (read only). All may change at any
// time; the table's range checks them, SelectionMode's two values below.
template <std::int32_t TcGroup::*Field>
Status TcModule::write_group_mode(const ObjectInfo&, const Address& a, const Value& v) {
    if constexpr (Field == &TcGroup::selection_mode) {
        if (v.as_int() != tc::kSelectionDirect && v.as_int() != tc::kSelectionIndirect &&
            v.as_int() != tc::kSelectionPerpendicular)
            return Status::kInvalidValue;
    }
    TcGroup* g = nullptr;
    const Status st = with_group(a, g);
    if (!objif::ok(st)) return st;
    g->*Field = v.as_int();
    return Status::kOk;
}

}  // namespace rwmos
