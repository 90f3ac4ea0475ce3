// SPDX-License-Identifier: MIT
// The OTC module's unit of the executor (bus 1330; docs/apcictl.md "run", docs/otc.md): #OTC,
// #KIN, the tool's grinding data at D n and its wear checked back into the tool list.
#pragma once

#include <cstdint>
#include <string_view>

#include "apci/apci.hpp"
#include "apci/nc/events.h"
#include "apci/run/executor.h"
#include "module_unit.h"
#include "objif/map/object_map.h"

namespace apci::run::exec {

class OtcUnit final : public ModuleUnit {
  public:
    explicit OtcUnit(RunContext& run) noexcept : ModuleUnit(run) {}

    bool setup();
    // Refuses by name (NoSuchDevice) what needs the module when the board has none.
    bool needed(const BlockRef& at, std::string_view what);
    template <typename T>
    bool write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what);
    bool setting(const BlockRef& at, std::int32_t index, std::int32_t value,
                 std::string_view what);
    bool command(const BlockRef& at, const nc::OtcCommand& c);
    bool change_tool(const BlockRef& at, int index);
    void check_out_tool();

  private:
    bool take_tool(const BlockRef& at, int index);

    // ---- OTC (bus 1330; docs/otc.md, docs/apcictl.md "run")
    double reported_radius_wear_ = 0.0;  // the board's wear variables already in the list
    double reported_cont_wear_ = 0.0;
};

}  // namespace apci::run::exec
