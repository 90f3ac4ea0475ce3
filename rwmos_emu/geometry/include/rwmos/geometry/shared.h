// SPDX-License-Identifier: MIT
// The board's compensation works on the 2D geometry it shares with the host (the library in
// geometry/, namespace geom: plane and axes, the line and arc element, the tolerances). Its
// names are the emulator's too: rwmos::geom::Element is geom::Element, one type on both sides.
#pragma once

#include "geometry/element.h"
#include "geometry/plane.h"
#include "geometry/tolerances.h"

namespace rwmos::geom {
using namespace ::geom;  // NOLINT(google-build-using-namespace): one geometry, named in both
}  // namespace rwmos::geom
