// SPDX-License-Identifier: MIT
// Every tolerance of the 3D tool compensation, in one place, each with the reason for its
// value. Lengths in mm (interpolation units), vectors dimensionless. docs/3d-compensation.md
// lists them with the rules that use them.
#pragma once

#include "objif/map/limits.h"

namespace rwmos::comp3d {

// A programmed N or T vector whose length differs from 1 by more than this is refused
// ([TNC-3D], "Gerade LN", Hinweise: "Das CAM-generierte NC-Programm muss normierte Vektoren
// enthalten"). Every unit vector written with 4 decimals ([TNC-3D]'s own peripheral-milling
// example) is inside it: rounding each component by at most 5e-5 changes the length by at
// most sqrt(3) * 5e-5 = 8.7e-5. A vector within it is divided by its length before use.
inline constexpr double kUnitVectorTolerance = 1e-4;

// The surface normal N may point against the tool vector T by this much (N.T >= -this).
// Further against it, the contact would lie on the upper half of the corner radius, inside
// the shank: no tool can touch the surface from that side. Peripheral milling has N.T = 0,
// which 4-decimal vectors miss by up to about 2e-4; this leaves five times that.
inline constexpr double kNormalAgainstToolTolerance = 1e-3;

// N and T closer to parallel than this (the part of N across T is shorter) touch with the
// flat end face, where every point is a contact: the tip centre is taken. Above double
// rounding of unit vectors (about 1e-16), far below any programmable direction (1e-7).
inline constexpr double kParallelTolerance = 1e-12;

// RL/RR give a side only to a motion: a line shorter than this has no direction (as in the TC
// geometry, geometry/tolerances.h, kPointTolerance) ...
inline constexpr double kMinMotionLength = 1e-9;
// ... and a motion within this angle (radians, as its sine) of the tool vector is a plunge:
// the side across it would follow the rounding of the coordinates, not the program.
inline constexpr double kPlungeAngleTolerance = 1e-6;

// A summed delta value above this is an oversize ([TNC-3D], M107). Far below the finest
// programmable step (0.1 um), far above the rounding of summing three decimal values.
inline constexpr double kOversizeTolerance = 1e-9;

// R2 may exceed R by this much and still be a ball mill (R2 = R), likewise for the effective
// radii R + DR and R2 + DR2: rounding of values written in mm or 0.1 um stays far below it.
inline constexpr double kShapeTolerance = 1e-9;

// Tool dimensions and coordinates beyond this are refused, as in the TC geometry
// (geometry/tolerances.h, kMaxCoordinate): it keeps rounding far below 1e-9.
inline constexpr double kMaxCoordinate = objif::map::kMaxCoordinate;

}  // namespace rwmos::comp3d
