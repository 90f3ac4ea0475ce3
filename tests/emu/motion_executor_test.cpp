// SPDX-License-Identifier: MIT
// The executor: move queue, interpolation clock, analytic advance, trace and
// segment log, discard by direct commands, halt on TC errors.
#include <gtest/gtest.h>

#include <vector>

#include "rwmos/motion/executor.h"

using namespace rwmos::motion;

namespace {
constexpr double kCycle = 0.001;

AxisVector at(double x, double y, double z = 0.0) {
    AxisVector v{};
    v[0] = x;
    v[1] = y;
    v[2] = z;
    return v;
}

// 600 units/min at 1 ms: 0.01 units per cycle.
Move line(AxisVector from, AxisVector to, std::uint32_t tag = 1) {
    return line_move(from, to, 600.0, SegmentRole::kUncompensated, tag);
}

std::vector<Segment> drain_segments(Executor& e) {
    std::vector<Segment> out(e.segments().size());
    e.segments().take(out);
    return out;
}
}  // namespace

TEST(Executor, MovesRunOneAfterTheOtherAndLogTheirSegments) {
    Executor e;
    e.push(line(at(0, 0), at(1, 0), 10));  // 100 cycles
    e.push(line(at(1, 0), at(1, 2), 20));  // 200 cycles
    EXPECT_EQ(e.fill(), 2u);
    EXPECT_EQ(e.run_until_idle(1'000'000, kCycle), 300u);
    EXPECT_EQ(e.now(), 300u);
    EXPECT_EQ(e.position(), at(1, 2));
    EXPECT_EQ(e.fill(), 0u);
    const auto segs = drain_segments(e);
    ASSERT_EQ(segs.size(), 2u);
    EXPECT_EQ(segs[0].tag, 10u);
    EXPECT_EQ(segs[0].start_cycle, 0u);
    EXPECT_EQ(segs[0].end_cycle, 100u);
    EXPECT_EQ(segs[1].tag, 20u);
    EXPECT_EQ(segs[1].end_cycle, 300u);
    EXPECT_FALSE(segs[1].interrupted);
}

TEST(Executor, AdvanceCountsIdleCyclesToo) {
    Executor e;
    e.push(line(at(0, 0), at(1, 0)));
    e.advance(250, kCycle);
    EXPECT_EQ(e.now(), 250u);
    EXPECT_TRUE(e.idle());
}

TEST(Executor, PositionMidMoveIsTheFractionOfCyclesDone) {
    Executor e;
    e.push(line(at(0, 0), at(1, 0)));
    e.advance(25, kCycle);
    EXPECT_DOUBLE_EQ(e.position()[0], 0.25);
    EXPECT_EQ(e.fill(), 1u);
}

TEST(Executor, AnalyticAdvanceGivesTheSameBitsAsCycleByCycle) {
    auto program = [](Executor& e) {
        e.push(line(at(0, 0), at(3.3, 1.7, 0.9)));
        e.push(arc_move(at(3.3, 1.7, 0.9), at(-1.1, 2.2, 2.0), {0, 1}, 1.0, 1.0, true, 777.0,
                        SegmentRole::kUncompensated, 2));
    };
    Executor stepped, analytic;
    stepped.set_trace(true, 16);
    program(stepped);
    program(analytic);
    for (std::uint64_t chunk : {1u, 7u, 333u, 1000u, 5u, 100000u}) {
        stepped.advance(chunk, kCycle);
        analytic.advance(chunk, kCycle);
        ASSERT_EQ(stepped.position(), analytic.position()) << "after chunk " << chunk;
        ASSERT_EQ(stepped.now(), analytic.now());
    }
}

TEST(Executor, TraceRecordsEveryCycleWithItsPosition) {
    Executor e;
    e.set_trace(true, 1000);
    e.push(line(at(0, 0), at(0.05, 0)));  // 5 cycles
    e.advance(7, kCycle);
    ASSERT_EQ(e.trace().size(), 7u);
    std::vector<TraceSample> s(7);
    e.trace().take(s);
    for (std::uint64_t i = 0; i < 7; ++i) EXPECT_EQ(s[i].cycle, i + 1);
    EXPECT_DOUBLE_EQ(s[0].position[0], 0.01);
    EXPECT_DOUBLE_EQ(s[4].position[0], 0.05);
    EXPECT_DOUBLE_EQ(s[6].position[0], 0.05);  // idle cycles hold the position
}

TEST(Executor, FullTraceDropsTheOldestAndCountsThem) {
    Executor e;
    e.set_trace(true, 4);
    e.push(line(at(0, 0), at(0.1, 0)));  // 10 cycles
    e.run_until_idle(100, kCycle);
    EXPECT_EQ(e.trace().size(), 4u);
    EXPECT_EQ(e.trace().lost(), 6u);
    EXPECT_EQ(e.trace().at(0).cycle, 7u);
}

TEST(Executor, DiscardStopsTheMoveUnderWayWhereItIsAndDropsTheRest) {
    Executor e;
    e.push(line(at(0, 0), at(1, 0), 1));
    e.push(line(at(1, 0), at(1, 1), 2));
    e.advance(40, kCycle);
    e.discard();
    EXPECT_EQ(e.fill(), 0u);
    EXPECT_DOUBLE_EQ(e.position()[0], 0.4);
    e.advance(100, kCycle);
    EXPECT_DOUBLE_EQ(e.position()[0], 0.4);
    const auto segs = drain_segments(e);
    ASSERT_EQ(segs.size(), 1u);
    EXPECT_TRUE(segs[0].interrupted);
    EXPECT_DOUBLE_EQ(segs[0].end[0], 0.4);
    EXPECT_EQ(segs[0].end_cycle, 40u);
}

TEST(Executor, HaltLetsTheMoveUnderWayEndButStartsNoSpooledMove) {
    Executor e;
    e.push(line(at(0, 0), at(1, 0), 1));
    e.push(line(at(1, 0), at(2, 0), 2));
    e.advance(50, kCycle);
    e.set_halted(true);
    EXPECT_EQ(e.run_until_idle(100000, kCycle), 50u);
    EXPECT_EQ(e.position(), at(1, 0));
    EXPECT_EQ(e.fill(), 1u);
    EXPECT_TRUE(e.idle());
    e.set_halted(false);
    EXPECT_EQ(e.run_until_idle(100000, kCycle), 100u);
    EXPECT_EQ(e.position(), at(2, 0));
}

TEST(Executor, HaltDoesNotStopDirectMoves) {
    Executor e;
    e.set_halted(true);
    Move jog = line(at(0, 0), at(0, 1), 0);
    jog.direct = true;
    e.push(jog);
    EXPECT_EQ(e.run_until_idle(100000, kCycle), 100u);
    EXPECT_EQ(e.position(), at(0, 1));
}

TEST(Executor, ZeroLengthMoveCompletesWithoutTakingACycle) {
    Executor e;
    e.push(line(at(0, 0), at(0, 0), 3));
    EXPECT_EQ(e.run_until_idle(10, kCycle), 0u);
    EXPECT_EQ(e.fill(), 0u);
    EXPECT_EQ(drain_segments(e).size(), 1u);
}

TEST(Executor, PlannedEndIsTheLastQueuedMovesEnd) {
    Executor e;
    EXPECT_EQ(e.planned_end(), AxisVector{});
    e.push(line(at(0, 0), at(1, 0)));
    e.push(line(at(1, 0), at(1, 5)));
    EXPECT_EQ(e.planned_end(), at(1, 5));
}
