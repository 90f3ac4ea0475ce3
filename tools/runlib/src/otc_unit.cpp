// SPDX-License-Identifier: MIT
#include "otc_unit.h"

#include <fmt/format.h>

#include <utility>

#include "run_context.h"
#include "objif/map/otc_errors.h"
#include "tc_unit.h"

namespace apci::run::exec {

namespace {

namespace tc = objif::map::tc;
namespace otc = objif::map::otc;

}  // namespace

// ---- OTC (bus 1330): #OTC, #KIN, #TRAFO, the tool's grinding data, the PLC script,
// the V.G. variables (docs/apcictl.md "run", docs/otc.md)

// The program's start state: OTC off, LENGTH, AUTO, the tool's wear constant, ACC_WEIGHT
// 100, no kinematics, the control units off; the B head's B on the head's axis (as the 3D
// module's, RunContext::place_head). Without the module (NoSuchDevice) OTC events are refused by name.
bool OtcUnit::setup() {
    auto active = otc_object(otc::kDevChannel, otc::kIdxActive);
    const auto r = run_.board().read_int(active);
    if (r.status == APCI_NO_SUCH_DEVICE) {
        run_.outcome().otc_present = false;
        return true;
    }
    if (!r) return run_.board_failure({}, r.status, "read OTC Active");
    run_.outcome().otc_present = true;
    if (r.value != 0 && !write(active, std::int32_t{0}, {}, "#OTC OFF (start)")) return false;
    // Without a free axis the B head cannot turn (#TRAFO ON is refused); ToolAxisB keeps its
    // default then.
    const std::int32_t b_axis = run_.head().b_axis >= 0 ? run_.head().b_axis : 4;
    const std::pair<std::int32_t, std::int32_t> settings[] = {
        {otc::kIdxTrafo, 0},
        {otc::kIdxKinematics, 0},
        {otc::kIdxToolAxisB, b_axis},
        {otc::kIdxProcessingType, 1},
        {otc::kIdxMode, 2},
        {otc::kIdxWearConstSource, 0},
        {otc::kIdxAccWeight, 100}};
    for (const auto& [index, value] : settings) {
        auto o = otc_object(otc::kDevChannel, index);
        if (!write(o, value, {}, "OTC setup")) return false;
    }
    auto ch_enable = otc_object(otc::kDevChannel, otc::kIdxRadiusOffsetUnit, otc::kSubEnable);
    if (!write(ch_enable, std::int32_t{0}, {}, "OTC setup")) return false;
    for (std::int32_t a = 0; a < APCI_AXIS_COUNT; ++a) {
        auto en = otc_object(otc::kDevAxisUnits, a, otc::kSubEnable);
        if (!write(en, std::int32_t{0}, {}, "OTC setup")) return false;
    }
    return true;
}

bool OtcUnit::needed(const BlockRef& at, std::string_view what) {
    if (run_.outcome().otc_present) return true;
    return run_.no_module(at, what, "the OTC module (bus 1330)");
}

// A refused OTC write is named by the module's LastError (objif/map/otc_errors.h), else by
// the status; LastError is cleared for the next one. Busy (moves queued under #OTC ON/OFF)
// runs the clock and writes again.
template <typename T>
bool OtcUnit::write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what) {
    std::uint64_t busy_clock = ~std::uint64_t{0};  // the clock at this write's last Busy
    for (;;) {
        const auto r = run_.board().write(o, value);
        if (r.ok()) return true;
        if (r.status == APCI_BUSY) {
            // Zero-length moves leave without a cycle: only a second Busy with the clock
            // standing still means the board holds.
            const bool stood_still = busy_clock == run_.cycles_seen();
            busy_clock = run_.cycles_seen();
            if (!run_.run_clock()) return false;
            if (stood_still && run_.cycles_seen() == busy_clock)
                return run_.record(at, "Busy",
                                   fmt::format("{}: moves are queued and the clock does not run "
                                               "them (the board holds)",
                                               what));
            continue;
        }
        const std::string text = run_.failure_words(what);
        auto last = otc_object(otc::kDevChannel, otc::kIdxLastError);
        const auto code = run_.board().read_int(last);
        if (code && code.value != 0) {
            (void)run_.board().write(last, std::int32_t{0});
            const auto e = static_cast<otc::Error>(code.value);
            return run_.record(at, std::string(otc::error_name(e)),
                               fmt::format("{} ({})", text, otc::error_message(e)));
        }
        return run_.record(at, std::string(apci::status_name(r.status)), text);
    }
}

template bool OtcUnit::write(ObjectDescriptor, std::int32_t, const BlockRef&, std::string_view);
template bool OtcUnit::write(ObjectDescriptor, double, const BlockRef&, std::string_view);

bool OtcUnit::setting(const BlockRef& at, std::int32_t index, std::int32_t value,
                      std::string_view what) {
    if (!needed(at, what)) return false;
    auto o = otc_object(otc::kDevChannel, index);
    return write(o, value, at, what);
}

// #OTC: the parameters first, then ON/OFF (the board answers Busy until the moves before
// it have run: OTC switches at its place in the program).
bool OtcUnit::command(const BlockRef& at, const nc::OtcCommand& c) {
    if (!needed(at, "#OTC")) return false;
    if (c.type && !setting(at, otc::kIdxProcessingType, static_cast<std::int32_t>(*c.type),
                           "#OTC processing type"))
        return false;
    if (c.mode && !setting(at, otc::kIdxMode, static_cast<std::int32_t>(*c.mode), "#OTC mode"))
        return false;
    if (c.acc_weight && !setting(at, otc::kIdxAccWeight, *c.acc_weight, "#OTC ACC_WEIGHT"))
        return false;
    if (c.wear_const == nc::WearConstChoice::kProgrammed) {
        auto o = otc_object(otc::kDevChannel, otc::kIdxWearConst);
        if (!write(o, c.wear_const_value, at, "#OTC WEAR_CONST")) return false;
    } else if (c.wear_const == nc::WearConstChoice::kTool &&
               !setting(at, otc::kIdxWearConstSource, 0, "#OTC WEAR_CONST_TOOL")) {
        return false;
    }
    if (!c.on) return true;
    if (!setting(at, otc::kIdxActive, *c.on ? 1 : 0, *c.on ? "#OTC ON" : "#OTC OFF"))
        return false;
    // The wear folded into the tool's length: the segments read back from here on carry
    // the new length.
    if (!*c.on && run_.outcome().tc_present) (void)run_.tc_unit().read_length();
    return true;
}

// [ISG-OTC] section 2.9: the wear of the tool going out reaches the tool list.
bool OtcUnit::change_tool(const BlockRef& at, int index) {
    if (!run_.run_clock()) return false;
    check_out_tool();
    if (index != run_.tc_unit().state().current_tool) reported_radius_wear_ = reported_cont_wear_ = 0.0;
    return take_tool(at, index);
}

// D n: the grinding data of wz[n] ([ISG-OTC] section 2.6) become the OTC module's current
// tool. A new ToolNumber starts the tool's wear from 0 on the board (section 2.9).
bool OtcUnit::take_tool(const BlockRef& at, int index) {
    const nc::ToolData* t = index > 0 ? run_.tool_list().find(index) : nullptr;
    auto number = otc_object(otc::kDevTool, otc::kIdxToolNumber);
    auto typ = otc_object(otc::kDevTool, otc::kIdxToolType);
    auto wear = otc_object(otc::kDevTool, otc::kIdxToolWearConst);
    auto infeed = otc_object(otc::kDevTool, otc::kIdxToolMaxInfeed);
    auto tilt = otc_object(otc::kDevTool, otc::kIdxToolTiltAngle);
    return write(number, std::int32_t{index}, at, "OTC ToolNumber") &&
           write(typ, std::int32_t{t != nullptr ? t->typ : 0}, at, "OTC typ") &&
           write(wear, t != nullptr ? t->grinding_wear_const : 0.0, at,
                 "OTC grinding_wear_const") &&
           write(infeed, t != nullptr ? t->grinding_max_infeed : 0.0, at,
                 "OTC grinding_max_infeed") &&
           write(tilt, t != nullptr ? t->grinding_disc_tilt_angle : 0.0, at,
                 "OTC grinding_disc_tilt_angle");
}

// [ISG-OTC] section 2.9: "Beim Auswechseln des Werkzeugs wird der externen
// Werkzeugverwaltung der Verschleiß durch die CNC mitgeteilt" (wear_radius,
// wear_radius_cont); the tool management folds it into the tool's geometry. The board has
// folded it into its tool table at #OTC OFF: the tool list takes the board's radius and
// length of the tool and adds the wear to its wear fields.
void OtcUnit::check_out_tool() {
    if (run_.tc_unit().state().current_tool <= 0) return;
    nc::ToolData* t = run_.tool_list().find_mutable(run_.tc_unit().state().current_tool);
    if (t == nullptr) return;
    auto wr = otc_object(otc::kDevTool, otc::kIdxWearRadius);
    auto wc = otc_object(otc::kDevTool, otc::kIdxWearRadiusCont);
    const auto radius_wear = run_.board().read_double(wr);
    const auto cont_wear = run_.board().read_double(wc);
    if (radius_wear && cont_wear) {
        t->set_wear_radius_mm(t->wear_radius_mm() + radius_wear.value - reported_radius_wear_);
        t->set_wear_radius_cont_mm(t->wear_radius_cont_mm() + cont_wear.value -
                                   reported_cont_wear_);
        reported_radius_wear_ = radius_wear.value;
        reported_cont_wear_ = cont_wear.value;
    }
    if (run_.outcome().tc_present) {
        auto r = group_object(1, tc::kSubRadius);
        auto l = group_object(1, tc::kSubWkzLen);
        const auto radius = run_.board().read_double(r);
        const auto length = run_.board().read_double(l);
        if (radius && length) {
            t->set_radius_mm(radius.value);
            t->set_length_mm(length.value);
        }
    }
}

}  // namespace apci::run::exec
