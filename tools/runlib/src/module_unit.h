// SPDX-License-Identifier: MIT
// The interface of the executor's units (apcictl run, executor.h): one unit per board module
// whose events the program drives, as the emulator keeps one module each (tc_module.cpp,
// otc_module.cpp, comp3d_module.cpp, tempcomp_engine.cpp). A unit keeps its module's state and
// reaches the board, the clock, the spooler and the run's record through the shared context
// (RunContext, run_context.h); which unit handles which event is decided in one place,
// RunContext::dispatch (executor.cpp).
#pragma once

#include <cstdint>

#include "apci/apci.hpp"
#include "objif/map/object_map.h"

namespace apci::run::exec {

class RunContext;

// The objects more than one unit reaches: the TC module's groups and init data, the OTC
// module's and the temperature compensation's.
inline ObjectDescriptor group_object(std::int32_t group, std::int32_t sub) noexcept {
    return apci::object(objif::map::tc::kBus, objif::map::tc::kDevGroups, group, sub);
}
inline ObjectDescriptor init_object(std::int32_t index, std::int32_t sub = 0) noexcept {
    return apci::object(objif::map::tc::kBus, objif::map::tc::kDevInit, index, sub);
}
inline ObjectDescriptor otc_object(std::int32_t dev, std::int32_t index,
                                   std::int32_t sub = 0) noexcept {
    return apci::object(objif::map::otc::kBus, dev, index, sub);
}
inline ObjectDescriptor temp_object(std::int32_t index, std::int32_t sub = 0) noexcept {
    return apci::object(objif::map::tempcomp::kBus, objif::map::tempcomp::kDevice, index, sub);
}

class ModuleUnit {
  public:
    ModuleUnit(const ModuleUnit&) = delete;
    ModuleUnit& operator=(const ModuleUnit&) = delete;

  protected:
    explicit ModuleUnit(RunContext& run) noexcept : run_(run) {}
    ~ModuleUnit() = default;

    RunContext& run_;  // the shared context: board, clock, spooler, record, shared state
};

}  // namespace apci::run::exec
