// SPDX-License-Identifier: MIT
// The TC module's unit of the executor (bus 1300; docs/apcictl.md "run"): the three
// compensation groups, the tool (D n), the plane (G17..G19), the corner mode (G25/G26) and the
// radius compensation (G40..G42).
#pragma once

#include <array>
#include <cstdint>

#include "apci/apci.hpp"
#include "apci/nc/events.h"
#include "apci/run/executor.h"
#include "module_unit.h"
#include "objif/map/object_map.h"

namespace apci::run::exec {

inline constexpr std::int32_t kGroups = objif::map::tc::kGroupCount;

class TcUnit final : public ModuleUnit {
  public:
    explicit TcUnit(Execution& run) noexcept : ModuleUnit(run) {}

    bool setup();
    bool tool(const BlockRef& at, int index);
    bool plane(const BlockRef& at, nc::Plane p);
    bool corner(const BlockRef& at, nc::CornerMode m);
    bool selection(const BlockRef& at, nc::SelectionMode m);
    bool compensation(const BlockRef& at, nc::Compensation side);
    bool compensation_off(const BlockRef& at);
    // When WkzLen acts (LengthMode): on every move (`always`, as NC programs run, from setup on)
    // or only while a group compensates (under #TRAFO, whose transformation carries the
    // length). The axes stop first: the segments read back so far ran in the old mode.
    bool length_mode(const BlockRef& at, bool always);
    void read_registers();

  private:
    // Writes value to sub of every group (CornerMode, SelectionMode: the program's modes).
    bool every_group(const BlockRef& at, std::int32_t sub, std::int32_t value,
                     std::string_view what);
};

}  // namespace apci::run::exec
