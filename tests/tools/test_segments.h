// SPDX-License-Identifier: MIT
// Segments for tests: a line or an arc with its block number, ends and role (an arc also its
// centre, sense and plane), every other field PathSegment's default. One way to build them for
// every test of the writers, the plot and the self-approach check; each test names the role and
// block its segments stand for.
#pragma once

#include <cstdint>

#include "apci/run/path.h"

namespace test_segments {

inline apci::run::PathSegment line(std::int64_t block, const apci::run::Point& a,
                                   const apci::run::Point& b, apci::run::Role role) {
    apci::run::PathSegment s;
    s.block.number = block;
    s.kind = apci::run::SegmentKind::kLine;
    s.role = role;
    s.start = a;
    s.end = b;
    return s;
}

inline apci::run::PathSegment arc(std::int64_t block, const apci::run::Point& a,
                                  const apci::run::Point& b, const apci::run::Point& centre,
                                  bool ccw, apci::run::Role role, int plane = 17) {
    apci::run::PathSegment s = line(block, a, b, role);
    s.kind = apci::run::SegmentKind::kArc;
    s.center = centre;
    s.ccw = ccw;
    s.plane = plane;
    return s;
}

}  // namespace test_segments
