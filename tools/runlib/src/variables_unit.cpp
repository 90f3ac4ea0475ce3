// SPDX-License-Identifier: MIT
#include "variables_unit.h"

#include <fmt/format.h>

#include <utility>

#include "run_context.h"
#include "otc_unit.h"
#include "temp_unit.h"

namespace apci::run::exec {

namespace {

namespace otc = objif::map::otc;
namespace tcomp = objif::map::tempcomp;

// A read's value, or why the board could not give it.
template <typename T>
bool value_of(const apci::Result<T>& r, const RunContext& run, double& out, std::string& why) {
    if (!r) {
        why = run.board_words();
        return false;
    }
    out = r.value;
    return true;
}

}  // namespace

// V.G.WZ_AKT.WEAR_CONST = value: the tool's wear constant, on the board and in the list.
// $SC_TOOL_TEMP_COMP[i] = value: the setting datum on the board, after the moves before it
// have run (the axes stop: it takes effect at its place in the program).
bool VariablesUnit::write(const BlockRef& at, const nc::VariableWrite& e) {
    if (e.variable.variable == nc::NcVariable::kToolTempComp) {
        const std::string what = nc::variable_name(e.variable);
        TempUnit& temp = run_.temp_unit();
        if (!temp.needed(at, what) || !run_.run_clock()) return false;
        return temp.write(temp_object(tcomp::kIdxToolTempComp, e.variable.index), e.value, at,
                          what);
    }
    OtcUnit& otc_unit = run_.otc_unit();
    if (!otc_unit.needed(at, "V.G.WZ_AKT.WEAR_CONST")) return false;
    auto o = otc_object(otc::kDevTool, otc::kIdxToolWearConst);
    if (!otc_unit.write(o, e.value, at, "V.G.WZ_AKT.WEAR_CONST")) return false;
    if (nc::ToolData* t =
            run_.tc_unit().state().current_tool > 0 ? run_.tool_list().find_mutable(run_.tc_unit().state().current_tool) : nullptr)
        t->grinding_wear_const = e.value;
    return true;
}

bool VariablesUnit::read(const nc::VariableRef& v, double& out, std::string& why) {
    apci::Board& board = run_.board();
    if (v.variable == nc::NcVariable::kToolTempComp) {
        if (!run_.temp_unit().present()) {
            why = "the board has no temperature compensation (bus 1320)";
            return false;
        }
        auto o = temp_object(tcomp::kIdxToolTempComp, v.index);
        return value_of(board.read_double(o), run_, out, why);
    }
    if (!run_.outcome().otc_present) {
        why = "the board has no OTC module (bus 1330)";
        return false;
    }
    ObjectDescriptor o{};
    bool is_int = false;
    switch (v.variable) {
        case nc::NcVariable::kWearRadius:
            o = otc_object(otc::kDevTool, otc::kIdxWearRadius);
            break;
        case nc::NcVariable::kWearRadiusCont:
            o = otc_object(otc::kDevTool, otc::kIdxWearRadiusCont);
            break;
        case nc::NcVariable::kWear:
            o = otc_object(otc::kDevTool, otc::kIdxWear, run_.channel_axis(v.index));
            break;
        case nc::NcVariable::kWearConst:
            o = otc_object(otc::kDevTool, otc::kIdxToolWearConst);
            break;
        case nc::NcVariable::kOtcActive:
            o = otc_object(otc::kDevChannel, otc::kIdxActive);
            is_int = true;
            break;
        case nc::NcVariable::kToolTempComp:
            break;  // above
    }
    if (is_int) return value_of(board.read_int(o), run_, out, why);
    return value_of(board.read_double(o), run_, out, why);
}

// The variables at the end of the run, by their names in [ISG-OTC] (docs/design.md section 7 JSON).
void VariablesUnit::read_all() {
    auto add = [&](std::string name, nc::VariableRef v) {
        double value = 0.0;
        std::string why;
        if (read(v, value, why)) run_.outcome().variables.emplace_back(std::move(name), value);
    };
    if (run_.outcome().otc_present) {
        add("V.G.OTC_ACTIVE", {nc::NcVariable::kOtcActive, 0});
        add("V.G.WZ_AKT.WEAR_CONST", {nc::NcVariable::kWearConst, 0});
        add("V.G.WZ_AKT.WEAR_RADIUS", {nc::NcVariable::kWearRadius, 0});
        add("V.G.WZ_AKT.WEAR_RADIUS_CONT", {nc::NcVariable::kWearRadiusCont, 0});
        for (int i = 0; i < APCI_AXIS_COUNT; ++i)
            add(fmt::format("V.G.WZ_AKT.WEAR[{}]", i), {nc::NcVariable::kWear, i});
    }
    for (int i = 0; i < nc::kToolTempCompCount; ++i) {
        const nc::VariableRef v{nc::NcVariable::kToolTempComp, i};
        add(nc::variable_name(v), v);
    }
}

}  // namespace apci::run::exec
