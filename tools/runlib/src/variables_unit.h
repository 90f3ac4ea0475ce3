// SPDX-License-Identifier: MIT
// The NC variables' unit of the executor: the program reads the board's V.G. variables
// ([ISG-OTC] section 2.8) and $SC_TOOL_TEMP_COMP[i], writes V.G.WZ_AKT.WEAR_CONST and
// $SC_TOOL_TEMP_COMP[i], and the run reports them at its end.
#pragma once

#include <string>

#include "apci/nc/events.h"
#include "apci/nc/program.h"
#include "apci/run/executor.h"
#include "module_unit.h"

namespace apci::run::exec {

class VariablesUnit final : public ModuleUnit, public nc::VariableSource {
  public:
    explicit VariablesUnit(RunContext& run) noexcept : ModuleUnit(run) {}

    bool write(const BlockRef& at, const nc::VariableWrite& e);
    bool read(const nc::VariableRef& v, double& out, std::string& why) override;
    void read_all();
};

}  // namespace apci::run::exec
