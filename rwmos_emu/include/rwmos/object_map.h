// SPDX-License-Identifier: MIT
// The emulator's view of the board's object map: the map itself is shared with the host and
// lives in objif (objif/map/object_map.h, objif/map/objects.h); the emulator's code names its
// numbers as rwmos::board::kBus, rwmos::tc::kSubRadius, ... as before.
#pragma once

#include "objif/map/object_map.h"

namespace rwmos {
namespace board {
using namespace objif::map::board;
}
namespace tc {
using namespace objif::map::tc;
}
namespace comp3d {
using namespace objif::map::comp3d;
}
namespace otc {
using namespace objif::map::otc;
}
namespace tempcomp {
using namespace objif::map::tempcomp;
}
}  // namespace rwmos
