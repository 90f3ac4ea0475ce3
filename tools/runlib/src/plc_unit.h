// SPDX-License-Identifier: MIT
// The scripted PLC's unit of the executor (apcictl run --plc; plc_script.h): its writes at
// cycles and at blocks, to the OTC control units and the temperature compensation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

#include "apci/nc/events.h"
#include "apci/run/plc_script.h"
#include "module_unit.h"

namespace apci::run::exec {

class PlcUnit final : public ModuleUnit {
  public:
    PlcUnit(RunContext& run, const PlcScript* plc) noexcept : ModuleUnit(run), plc_(plc) {}

    // The cycle (counted from the run's start) of the next cycle entry; null when none is left.
    const std::uint64_t* next_cycle() const noexcept;
    bool due();
    bool after_end();
    bool block(const nc::BlockOrigin& o);

  private:
    bool write(const PlcWrite& w);

    const PlcScript* plc_;
    std::size_t next_cycle_ = 0;  // next entry of plc_->cycle_writes()
    std::int64_t last_block_ = std::numeric_limits<std::int64_t>::min();
    std::uint64_t last_line_ = 0;
};

}  // namespace apci::run::exec
