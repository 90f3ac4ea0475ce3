// SPDX-License-Identifier: MIT
// The temperature compensation's unit of the executor (bus 1320;
// docs/temperature-compensation.md).
#pragma once

#include <cstdint>
#include <string_view>

#include "apci/apci.hpp"
#include "apci/run/executor.h"
#include "module_unit.h"
#include "objif/map/object_map.h"

namespace apci::run::exec {

class TempUnit final : public ModuleUnit {
  public:
    explicit TempUnit(RunContext& run) noexcept : ModuleUnit(run) {}

    bool setup();
    bool present() const noexcept { return present_; }
    // Refuses by name (NoSuchDevice) what needs the module when the board has none.
    bool needed(const BlockRef& at, std::string_view what);
    template <typename T>
    bool write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what);

  private:
    bool present_ = false;  // the board has the temperature compensation (bus 1320)
};

}  // namespace apci::run::exec
