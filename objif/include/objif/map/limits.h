// SPDX-License-Identifier: MIT
// The board's limits that the host needs to refuse, by name and before anything moves, what
// the board would refuse: declared once here and used by both sides, the emulator (geometry,
// motion, 3D compensation) and the host (the NC front end, the executor). docs/design.md
// section 2, "Shared declarations"; docs/motion.md.
#pragma once

#include <cstdint>

namespace objif::map {

// Coordinates and tool dimensions beyond +-1e5 (mm) are refused: no machine is 100 m long,
// and the bound keeps double rounding (about 1.5e-11 there) far below the compensation
// geometry's point tolerance of 1e-9.
inline constexpr double kMaxCoordinate = 1e5;

// The most interpolation cycles one move may take: 10^9, 11.6 days at the default cycle of
// 1 ms. The spooler refuses a move longer than that (a feed too low for its length), and it is
// the bound of `apcictl step` and `step --max`, so one command runs any move to its end.
inline constexpr std::uint64_t kMaxMoveCycles = 1'000'000'000;

// The feed of a rapid (G00, a JA jog) that names none, in units per minute: one unit per
// millisecond. The host spools a rapid that must be compensated (a G0 under G41/G42) at it.
inline constexpr double kRapidFeed = 60000.0;

}  // namespace objif::map
