// SPDX-License-Identifier: MIT
// The OTC module's error numbers and names under the emulator's namespace (rwmos::otc::Error,
// error_name, ...). The table is the value set of the module's LastError object, part of the
// object contract between a host and a board: it lives in objif (objif/map/otc_errors.h), which
// host tools include directly. Emulator-internal: code outside rwmos_emu includes the objif header.
#pragma once

#include "objif/map/otc_errors.h"

namespace rwmos::otc {
using namespace objif::map::otc;
}  // namespace rwmos::otc
