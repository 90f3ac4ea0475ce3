// SPDX-License-Identifier: MIT
// How long a move takes on the board, and the board's limit on it: a feed so low that one move
// would take more than kMaxMoveCycles interpolation cycles is refused by the front end, naming
// its block, before anything moves (docs/nc-programs.md "Limits"). The board refuses such a
// profile too (rwmos/motion/interpolator.h, the same value); the front end says it first and in
// the program's words.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "apci/nc/events.h"
#include "objif/map/limits.h"

namespace apci::nc {

// The most interpolation cycles one move may take: 10^9, 11.6 days at the board's default
// cycle of 1 ms (InterpolationCycle 1000 us). The bound of `apcictl step` and `step --max`, so
// any move the board takes can be run to its end by one command; a move longer than that is a
// mistyped feed (F0.000001 for F0.1), not a machining step.
inline constexpr std::uint64_t kMaxMoveCycles = objif::map::kMaxMoveCycles;
// The board's interpolation cycle when the caller does not know it (the InterpolationCycle
// object's default, docs/object-map.md).
inline constexpr double kDefaultCycleSeconds = 0.001;

// Path length in mm: a line's, and an arc's as the board counts it (its sweep times the mean of
// start and end radius, the helix axis added: docs/motion.md section 2).
double move_length(const Eigen::Vector3d& start, const Eigen::Vector3d& end) noexcept;
double move_length(const ArcMove& arc) noexcept;

// The interpolation cycles a path of `length` mm takes at `feed` mm/min with cycles of
// `cycle_seconds` (docs/motion.md section 3: ceil(L / (F/60 * T))), as a double: it can be far
// beyond any integer (F0.000...1); infinity for a feed of 0.
double move_cycles(double length, double feed, double cycle_seconds) noexcept;

// True when the move certainly takes at most kMaxMoveCycles cycles at `feed` (the arc's own
// feed), told from a bound on its length that needs no root or angle: a line's squared length;
// for an arc, a whole turn of its larger radius plus its travel along the normal axis. The bound
// must lie within half the limit, so rounding cannot matter. False decides nothing: then
// check_move_cycles() with move_length() does. Every move of a real program is far inside the
// limit, so the exact length (three hypot and an atan2 for an arc) is only computed near it.
bool surely_within_move_cycles(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                               double feed, double cycle_seconds) noexcept;
bool surely_within_move_cycles(const ArcMove& arc, double cycle_seconds) noexcept;

// Empty when a move of `length` mm at `feed` mm/min takes at most kMaxMoveCycles cycles of
// `cycle_seconds`; else the message that says how long it would take and what is allowed.
std::string check_move_cycles(double length, double feed, double cycle_seconds);

}  // namespace apci::nc
