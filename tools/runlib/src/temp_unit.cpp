// SPDX-License-Identifier: MIT
#include "temp_unit.h"

#include "run_context.h"

namespace apci::run::exec {

namespace {

namespace tcomp = objif::map::tempcomp;

// The front end checks $SC_TOOL_TEMP_COMP[i] against the range of the board's object.
static_assert(nc::kToolTempCompLimit == tcomp::kMaxValue);
static_assert(nc::kToolTempCompCount == 3);

}  // namespace

// ---- temperature compensation (bus 1320; docs/temperature-compensation.md)

// Only whether the board has it: its setting and machine data are the machine's, kept from
// run to run as on a control (the PLC or the program writes the setting data).
bool TempUnit::setup() {
    auto on = temp_object(tcomp::kIdxToolTempCompOn);
    const auto r = run_.board().read_int(on);
    if (r.status == APCI_NO_SUCH_DEVICE) return true;
    if (!r) return run_.board_failure({}, r.status, "read TOOL_TEMP_COMP_ON");
    present_ = true;
    return true;
}

bool TempUnit::needed(const BlockRef& at, std::string_view what) {
    if (present_) return true;
    return run_.no_module(at, what,
                          "the temperature compensation (bus 1320, firmware option 0x04)");
}

template <typename T>
bool TempUnit::write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what) {
    const auto r = run_.board().write(o, value);
    if (r.ok()) return true;
    return run_.board_failure(at, r.status, what);
}

template bool TempUnit::write(ObjectDescriptor, std::int32_t, const BlockRef&, std::string_view);
template bool TempUnit::write(ObjectDescriptor, double, const BlockRef&, std::string_view);

}  // namespace apci::run::exec
