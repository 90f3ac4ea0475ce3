// SPDX-License-Identifier: MIT
// measure() computes an executed segment's sweep and length with its plane's axes as constants;
// the values must be those of arc_sweep and segment_length bit for bit, in every plane (17, 18,
// 19 and 17's axes for any other number), both senses, flat and helical, full circles too.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "apci/run/path.h"

namespace apci::run {
namespace {

Point random_point(std::mt19937_64& rng, double span) {
    std::uniform_real_distribution<double> d(-span, span);
    return {d(rng), d(rng), d(rng)};
}

TEST(PathMeasure, ArcsInEveryPlaneHaveTheSweepAndLengthOfThePathFunctions) {
    std::mt19937_64 rng(20261126);
    std::uint64_t arcs = 0;
    for (const int plane : {17, 18, 19, 0, 42}) {
        const PlaneAxes a = plane_axes(plane);
        for (int i = 0; i < 20000; ++i) {
            PathSegment s;
            s.kind = SegmentKind::kArc;
            s.plane = plane;
            s.ccw = (i & 1) != 0;
            s.start = random_point(rng, 100.0);
            s.center = random_point(rng, 100.0);
            s.center[a.third] = s.start[a.third];
            s.end = random_point(rng, 100.0);
            if (i % 3 == 0) s.end[a.third] = s.start[a.third];  // flat
            if (i % 7 == 0) {                                   // a full circle (helical or not)
                s.end[a.first] = s.start[a.first];
                s.end[a.second] = s.start[a.second];
            }
            if (i % 11 == 0) s.end[a.first] = s.start[a.first] + 1e-10;  // within the tolerance
            measure(s);
            ASSERT_EQ(s.sweep, arc_sweep(s)) << plane << " " << i;
            ASSERT_EQ(s.length, segment_length(s)) << plane << " " << i;
            ++arcs;
        }
    }
    EXPECT_EQ(arcs, 100000U);
}

TEST(PathMeasure, LinesAndRapidsHaveNoSweepAndTheirChord) {
    std::mt19937_64 rng(7);
    for (const SegmentKind kind : {SegmentKind::kLine, SegmentKind::kRapid}) {
        for (int i = 0; i < 1000; ++i) {
            PathSegment s;
            s.kind = kind;
            s.start = random_point(rng, 1000.0);
            s.end = random_point(rng, 1000.0);
            measure(s);
            ASSERT_EQ(s.sweep, 0.0);
            ASSERT_EQ(s.length, segment_length(s)) << i;
        }
    }
}

}  // namespace
}  // namespace apci::run
