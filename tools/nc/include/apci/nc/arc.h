// SPDX-License-Identifier: MIT
// Arc geometry of the program (pure functions): which axes span a plane, the centre of an
// R-programmed arc, and the checks that an arc the program asks for exists.
#pragma once

#include <Eigen/Core>
#include <string>

#include "apci/nc/block.h"
#include "geometry/element.h"
#include "apci/nc/events.h"

namespace apci::nc {

// End points may miss the circle by this much (start radius vs end radius), and an R arc's
// chord may exceed the diameter by this much (then it is a half circle). The board's CenterError
// tolerance (docs/compensation.md, "The tolerance model"): rounding start, end and centre to
// 3 decimals moves the radii apart by up to 0.0021 mm. Such an arc runs from its start to its
// end point, its radius changing linearly with the angle.
inline constexpr double kArcRadiusTolerance = 0.003;  // mm
// An arc radius below this is zero (centre on the start point).
inline constexpr double kMinArcRadius = 1e-6;  // mm

// The axes of a plane (geometry/plane.h): first x second = third, the plane's normal.
using geom::PlaneAxes;
using geom::plane_axes;

struct ArcCenterResult {
    bool ok = false;
    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    std::string message;  // why there is no such arc (when !ok)
};

// Centre of the arc from start to end with radius r in plane p (the normal coordinate is the
// start's). r > 0: the shorter arc (<= 180 degrees); r < 0: the longer one (> 180 degrees), the
// usual DIN 66025 convention. Fails when end equals start in the plane or the chord is longer
// than the diameter (beyond kArcRadiusTolerance).
ArcCenterResult arc_center_from_radius(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                                       double r, bool ccw, Plane p);

// Checks an I/J/K arc: the centre must not sit on the start point and the end must lie on the
// circle through the start (radii equal within kArcRadiusTolerance). Empty string when fine.
std::string check_arc_center(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                             const Eigen::Vector3d& center, Plane p);
// check_arc_center(...).empty() without making the string: the test of every arc, the message
// only for the arc that fails it.
bool arc_center_ok(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                   const Eigen::Vector3d& center, Plane p) noexcept;

// The board takes coordinates within +-`limit` (kBoardCoordinateLimit): an arc's centre, and
// every point the arc passes, whose extent along the plane's axes is where it turns through an
// axis direction (at its larger radius; its end points are the caller's to check). Empty when
// within, else what lies beyond, in words naming the axes. An arc whose centre the board
// refuses ran its earlier blocks first; one whose path leaves the range was not checked at all.
std::string check_arc_range(const ArcMove& arc, double limit);

// The sweep of an arc: geom::arc_sweep (geometry/element.h), the one board and host share.
using geom::arc_sweep;

}  // namespace apci::nc
