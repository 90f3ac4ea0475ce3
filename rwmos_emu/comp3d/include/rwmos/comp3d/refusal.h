// SPDX-License-Identifier: MIT
// Why the 3D compensation refuses an input, under the emulator's namespace
// (rwmos::comp3d::Refusal, refusal_name, ...). The codes are the value set of the module's
// LastError object, part of the object contract between a host and a board: they live in objif
// (objif/map/comp3d_refusal.h), which host tools include directly. Emulator-internal: code
// outside rwmos_emu includes the objif header.
#pragma once

#include "objif/map/comp3d_refusal.h"

namespace rwmos::comp3d {
using namespace objif::map::comp3d;
}  // namespace rwmos::comp3d
