// SPDX-License-Identifier: MIT
// The executor: move queue, interpolation clock, analytic advance, trace and
// segment log, discard by direct commands, halt on TC errors.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

#include "rwmos/motion/cycle_offsets.h"
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

// A segment starts with the tool length its move began with (the last move's end, or what
// shift_nominal folded into the standing point since) and ends with its move's.
TEST(Executor, SegmentsCarryTheLengthFromMoveToMoveAndShiftsOfTheNominalPoint) {
    Executor e;
    Move in = line(at(0, 0, 0), at(1, 0, 5), 1);
    in.length_end[2] = 5.0;
    Move keep = line(at(1, 0, 5), at(2, 0, 5), 2);
    keep.length_end[2] = 5.0;
    e.push(in);
    e.push(keep);
    e.run_until_idle(1'000'000, kCycle);
    EXPECT_EQ(e.nominal_length()[2], 5.0);
    ASSERT_TRUE(e.shift_nominal(2, -0.25));  // a fold: the nominal point and its length move
    EXPECT_EQ(e.nominal_length()[2], 4.75);
    EXPECT_EQ(e.nominal_position()[2], 4.75);
    e.push(line(at(2, 0, 4.75), at(3, 0, 0), 3));  // takes the length out
    e.run_until_idle(1'000'000, kCycle);
    const auto segs = drain_segments(e);
    ASSERT_EQ(segs.size(), 3u);
    EXPECT_EQ(segs[0].length_start[2], 0.0);
    EXPECT_EQ(segs[0].length_end[2], 5.0);
    EXPECT_EQ(segs[1].length_start[2], 5.0);
    EXPECT_EQ(segs[1].length_end[2], 5.0);
    EXPECT_EQ(segs[2].length_start[2], 4.75);
    EXPECT_EQ(segs[2].length_end[2], 0.0);
    EXPECT_EQ(e.nominal_length()[2], 0.0);
}

// A shift refused while moves are queued moves no length either.
TEST(Executor, ARefusedShiftLeavesTheLengthAsItIs) {
    Executor e;
    e.push(line(at(0, 0), at(1, 0)));
    EXPECT_FALSE(e.shift_nominal(2, 1.0));
    EXPECT_FALSE(e.shift_nominal(-1, 1.0));
    EXPECT_EQ(e.nominal_length(), AxisVector{});
}

// The length is followed even when the segment log keeps nothing (capacity 0).
TEST(Executor, TheLengthIsFollowedWhenTheLogHasNoRoom) {
    Executor e;
    e.segments().set_capacity(0);
    Move m = line(at(0, 0), at(1, 0, 3), 1);
    m.length_end[2] = 3.0;
    e.push(m);
    e.run_until_idle(1'000'000, kCycle);
    EXPECT_EQ(e.segments().lost(), 1u);
    EXPECT_EQ(e.nominal_length()[2], 3.0);
}

// Interrupted at 200 of 500 cycles, the move from 1 of length to 5 ends with 2.6.
TEST(Executor, AnInterruptedSegmentEndsWithThePartOfTheLengthItBroughtIn) {
    Executor e;
    ASSERT_TRUE(e.shift_nominal(2, 1.0));  // standing with 1 of length, at Z 1
    Move m = line(at(0, 0, 1), at(0, 0, 6), 1);  // 500 cycles
    m.length_end[2] = 5.0;
    e.push(m);
    e.advance(200, kCycle);
    e.discard();
    const auto segs = drain_segments(e);
    ASSERT_EQ(segs.size(), 1u);
    EXPECT_TRUE(segs[0].interrupted);
    EXPECT_DOUBLE_EQ(segs[0].length_start[2], 1.0);
    EXPECT_DOUBLE_EQ(segs[0].length_end[2], 1.0 + 4.0 * 0.4);
    EXPECT_DOUBLE_EQ(e.nominal_length()[2], 2.6);
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

namespace {
// Offsets that add a fixed vector and count what the executor asks of them; inert() as told.
class FixedOffsets final : public CycleOffsets {
  public:
    explicit FixedOffsets(bool inert) : inert_(inert) {}
    void move_started(const Move&, const Move*) noexcept override { ++told; }
    void move_finished(const Move&, std::uint64_t, std::uint64_t) noexcept override { ++told; }
    bool per_cycle(const Move*, std::uint64_t, std::uint64_t) const noexcept override {
        return false;
    }
    void step(const Move*, std::uint64_t, std::uint64_t, double,
              AxisVector& pos) noexcept override {
        ++stepped;
        add(pos);
    }
    void at(const Move*, std::uint64_t, std::uint64_t, AxisVector& pos) const noexcept override {
        ++evaluated;
        add(pos);
    }
    bool inert() const noexcept override { return inert_; }

    int told = 0;
    int stepped = 0;
    mutable int evaluated = 0;

  private:
    static void add(AxisVector& pos) noexcept {
        pos[0] += 0.125;
        pos[1] += -0.0;
        pos[2] += 1e-7;
    }
    bool inert_;
};

// Lines, arcs and zero-length moves, fed to an executor whose offsets are or are not inert.
void queue_moves(Executor& e) {
    AxisVector from = at(0.0, 0.0);
    for (int i = 0; i < 40; ++i) {
        const AxisVector to = at(0.37 * (i % 7), -0.21 * (i % 5), 0.013 * i);
        if (i % 9 == 0) {
            e.push(line(from, from, 100 + i));  // zero length
        } else if (i % 3 == 0) {
            e.push(arc_move(from, to, {0, 1}, 0.5 * (from[0] + to[0]) + 0.3,
                            0.5 * (from[1] + to[1]) - 0.2, i % 2 == 0, 600.0, SegmentRole::kContour,
                            100 + i));
        } else {
            e.push(line(from, to, 100 + i));
        }
        from = to;
    }
}
}  // namespace

TEST(Executor, InertOffsetsAreEvaluatedOnceAStretchWithTheSameBitsAsAfterEveryMove) {
    FixedOffsets every(/*inert=*/false), once(/*inert=*/true);
    Executor a, b;
    a.set_offsets(&every);
    b.set_offsets(&once);
    queue_moves(a);
    queue_moves(b);
    // Stretches that end inside moves, between them, and at the end of the queue.
    int stretches = 0;
    for (std::uint64_t budget : {37u, 1u, 250u, 0u, 999u, 5000u, 100000u}) {
        a.advance(budget, kCycle);
        b.advance(budget, kCycle);
        ++stretches;
        for (std::size_t i = 0; i < a.position().size(); ++i)
            ASSERT_EQ(std::bit_cast<std::uint64_t>(a.position()[i]),
                      std::bit_cast<std::uint64_t>(b.position()[i]))
                << "budget " << budget << " axis " << i;
        ASSERT_EQ(a.nominal_position(), b.nominal_position());
        ASSERT_EQ(a.fill(), b.fill());
    }
    const std::vector<Segment> sa = drain_segments(a), sb = drain_segments(b);
    ASSERT_EQ(sa.size(), 40u);
    ASSERT_EQ(sb.size(), sa.size());
    for (std::size_t i = 0; i < sa.size(); ++i) {
        EXPECT_EQ(sa[i].tag, sb[i].tag);
        EXPECT_EQ(sa[i].end, sb[i].end);
        EXPECT_EQ(sa[i].start_cycle, sb[i].start_cycle);
        EXPECT_EQ(sa[i].end_cycle, sb[i].end_cycle);
    }
    EXPECT_EQ(every.told, 80);  // started and finished, each move
    EXPECT_EQ(once.told, 0);
    EXPECT_GE(every.evaluated, 40);
    EXPECT_LE(once.evaluated, stretches);
    EXPECT_GT(once.evaluated, 0);
}

TEST(Executor, InertOffsetsAreStillSteppedEveryCycleWhileTracing) {
    FixedOffsets once(/*inert=*/true);
    Executor e;
    e.set_offsets(&once);
    e.set_trace(true, 16);
    e.push(line(at(0, 0), at(0.1, 0)));  // 10 cycles
    e.advance(10, kCycle);
    EXPECT_EQ(once.stepped, 10);
    EXPECT_EQ(once.told, 2);
    EXPECT_EQ(e.position()[0], 0.1 + 0.125);
}
