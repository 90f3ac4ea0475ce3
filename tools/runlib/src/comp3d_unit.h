// SPDX-License-Identifier: MIT
// The Klartext 3D compensation's unit of the executor (bus 1310; docs/apcictl.md "run",
// docs/object-map.md 6): TOOL CALL, TCPM, PROG PATH, M107/M108, R0/RL/RR, FUNCTION CORRDATA,
// the head's B and C, and LN lines.
#pragma once

#include <cstdint>
#include <string_view>

#include "apci/apci.hpp"
#include "apci/nc/correction_table.h"
#include "apci/nc/events.h"
#include "apci/run/executor.h"
#include "module_unit.h"

namespace apci::run::exec {

class Comp3dUnit final : public ModuleUnit {
  public:
    Comp3dUnit(RunContext& run, const nc::CorrectionTable* corrections) noexcept
        : ModuleUnit(run), corrections_(corrections) {}

    bool setting(const BlockRef& at, std::int32_t index, std::int32_t value,
                 std::string_view what);
    bool tool_call(const BlockRef& at, const nc::ToolCallDeltas& e);
    bool tcpm(const BlockRef& at, const nc::TcpmChange& e);
    bool compensation(const BlockRef& at, nc::Compensation side);
    bool head(const BlockRef& at, const nc::HeadOrientation& e);
    bool vector_line(const BlockRef& at, const nc::VectorLineMove& e);
    bool spool(const BlockRef& at, const PathSegment& programmed, const apci_profile& p);
    // An L line with RL/RR under TCPM: the module's (peripheral milling).
    bool peripheral() const noexcept { return tcpm_ && side_ != nc::Compensation::kOff; }

  private:
    bool setup(const BlockRef& at);
    bool correction_row(const BlockRef& at, const nc::CorrectionRow& r);
    template <typename T>
    bool write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what);
    bool failure(const BlockRef& at, apci::Status status, std::string_view what);

    // Klartext (3D compensation module, bus 1310).
    const nc::CorrectionTable* corrections_;  // --corr, may be null
    bool ready_ = false;
    bool tcpm_ = false;
    nc::Compensation side_ = nc::Compensation::kOff;
};

}  // namespace apci::run::exec
