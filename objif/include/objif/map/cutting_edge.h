// SPDX-License-Identifier: MIT
// The cutting edge position of a turning tool (ISG P-TOOL-00002 "Schneidenlage", 1..9;
// LinuxCNC's tool orientation Q), the values of the TC group object CuttingEdge (bus 1300,
// DeviceNumber 1, SubIndex 24): where the tool's imaginary tip lies from the centre of its nose
// radius. The board's radius compensation moves the nose centre along the offset path and
// carries it over by this offset to the tip, the point the machine controls; the host takes it
// back off where it needs the nose centre (the self-approach check). Shared by both sides
// (docs/design.md section 2, "Shared declarations"; docs/compensation.md "Turning tools").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace objif::map::tc {

// Positions 1..8; 9, and 0 (none given): the nose centre itself is the controlled point.
inline constexpr std::int32_t kCuttingEdgeNone = 0;
inline constexpr std::int32_t kCuttingEdgeCentre = 9;
inline constexpr std::int32_t kMaxCuttingEdge = 9;

// The imaginary tip from the nose centre, in units of the nose radius, on the turning plane's
// X (G18's second axis) and Z (its first axis), for positions 0..9: LinuxCNC's table
// (interp_queue.cc, latheorigin_x / latheorigin_z), which its lathe programs are written for.
struct EdgeDirection {
    std::int8_t x = 0;
    std::int8_t z = 0;
};
inline constexpr std::array<EdgeDirection, 10> kCuttingEdgeDirections{{
    {0, 0},    // 0: none given: the nose centre
    {-1, +1},  // 1
    {-1, -1},  // 2
    {+1, -1},  // 3
    {+1, +1},  // 4
    {0, +1},   // 5
    {-1, 0},   // 6
    {0, -1},   // 7
    {+1, 0},   // 8
    {0, 0},    // 9: the nose centre
}};

// The offset from the nose centre to the imaginary tip of `position` with nose radius `radius`,
// in the compensation plane's coordinates {first, second}: the first axis takes the turning
// plane's Z, the second its X (G18: Z, X). Outside 0..9: none.
constexpr std::array<double, 2> cutting_edge_offset(std::int32_t position, double radius) noexcept {
    if (position < 0 || position > kMaxCuttingEdge) return {0.0, 0.0};
    const EdgeDirection d = kCuttingEdgeDirections[static_cast<std::size_t>(position)];
    return {radius * d.z, radius * d.x};
}

}  // namespace objif::map::tc
