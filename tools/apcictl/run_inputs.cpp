// SPDX-License-Identifier: MIT
#include "run_inputs.h"

#include <utility>

namespace apcictl {

void RunInputOptions::declare(CLI::App& app) {
    app.add_option("--tools", tools, "Tool list file (wz[i].field value), for D words");
    app.add_option("--corr", corr,
                   "Correction table file (corr[n].dl|dr|dr2 value, mm), for Klartext FUNCTION "
                   "CORRDATA TCS #n");
    app.add_option("--plc", plc,
                   "A scripted PLC: writes to the OTC control units and the temperature "
                   "compensation's data at cycles or blocks (docs/apcictl.md)");
}

apci::run::RunInputFiles RunInputOptions::files() const {
    apci::run::RunInputFiles f;
    if (!tools.empty()) f.tools = tools;
    if (!corr.empty()) f.corrections = corr;
    if (!plc.empty()) f.plc = plc;
    f.tools_name = "--tools file";
    f.corrections_name = "--corr file";
    return f;
}

Outcome RunInputOptions::load(apci::run::RunInputs& in) const {
    auto loaded = apci::run::load_run_inputs(files());
    if (!loaded) return nc_failure(loaded.error());
    in = std::move(loaded.value());
    return Outcome::success();
}

Outcome nc_failure(const apci::nc::Diagnostic& d) {
    const std::string text = d.to_string();
    return d.kind == apci::nc::ErrorKind::kIo ? Outcome::usage_error(text)
                                              : Outcome::board_error(text);
}

}  // namespace apcictl
