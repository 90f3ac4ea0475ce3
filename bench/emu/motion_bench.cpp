// SPDX-License-Identifier: MIT
// The emulator's interpolation clock. Targets (docs/performance.md, "Motion"):
//  - at least 5 million interpolation cycles per second, 8 axes moving, when
//    every cycle is sampled (trace on);
//  - virtual time costs nothing per cycle when nothing observes the cycles:
//    the cost of a move does not grow with its cycle count.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "board_bench.h"
#include "rwmos/board.h"
#include "rwmos/board_state.h"

namespace {

using rwmos::motion::Profile;
using rwmos::motion::ProfileKind;
using rwmos::motion::TraceSample;

constexpr std::uint64_t kChunk = 10'000;  // cycles per benchmark iteration

// A line moving all 8 axes that takes 8e9 cycles (5e-6 units per cycle and axis).
Profile long_line() {
    Profile p;
    p.kind = ProfileKind::kLine;
    p.tag = 1;
    p.feed = 0.3 * 2.8284271247461903;  // 5e-6 units per cycle on each of the 8 axes
    p.axes = 0xFF;
    for (double& t : p.target) t = 40000.0;
    return p;
}

// A helix: a full circle in X-Y of radius 1e4 with the six other axes moving
// linearly; about 6e9 cycles at 0.01 units per second.
Profile long_helix() {
    Profile p;
    p.kind = ProfileKind::kArcCcw;
    p.tag = 2;
    p.feed = 0.6;
    p.axes = 0xFF;
    p.arc_axes = {0, 1};
    p.center = {0.0, 0.0};
    p.target[0] = 10000.0;  // back to the start: a full circle
    p.target[1] = 0.0;
    for (int a = 2; a < 8; ++a) p.target[a] = 100.0 * a;
    return p;
}

void start_at(rwmos::EmulatedBoard& board, double x) {
    rwmos::motion::DirectCommand ja;
    ja.code = rwmos::motion::DirectCode::kJA;
    ja.axes = 0x01;
    ja.target[0] = x;
    ja.feed = 1e9;
    board.direct(ja);
    board.run_until_idle(1'000'000);
}

// Every cycle sampled into the board's trace ring (the ring keeps the newest).
void sampled(benchmark::State& state, const Profile& p, double start_x) {
    rwmos::EmulatedBoard board;
    start_at(board, start_x);
    board.set_trace(true, 1 << 16);
    if (!board.spool(p).ok()) {
        state.SkipWithError("spool failed");
        return;
    }
    for ([[maybe_unused]] auto _ : state) {
        board.step(kChunk);
        benchmark::DoNotOptimize(board.motion_status().position);
    }
    if (board.motion_status().idle) state.SkipWithError("the move ended during the run");
    count_cycles(state, kChunk);
}

void BM_SampledCyclesLine8Axes(benchmark::State& state) {
    sampled(state, long_line(), 0.0);
}
BENCHMARK(BM_SampledCyclesLine8Axes);

void BM_SampledCyclesHelix8Axes(benchmark::State& state) {
    sampled(state, long_helix(), 10000.0);
}
BENCHMARK(BM_SampledCyclesHelix8Axes);

// Sampled and read out by a consumer after every chunk (what `apcictl run --csv` does).
void BM_SampledCyclesLineDrained(benchmark::State& state) {
    rwmos::EmulatedBoard board;
    board.set_trace(true, kChunk);
    if (!board.spool(long_line()).ok()) {
        state.SkipWithError("spool failed");
        return;
    }
    std::vector<TraceSample> out(kChunk);
    for ([[maybe_unused]] auto _ : state) {
        board.step(kChunk);
        benchmark::DoNotOptimize(board.read_trace(out));
    }
    if (board.motion_status().idle) state.SkipWithError("the move ended during the run");
    count_cycles(state, kChunk);
}
BENCHMARK(BM_SampledCyclesLineDrained);

// Nothing observes the cycles: a move runs analytically. One iteration is a
// whole move of range(0) cycles; the time per move must not grow with it.
void BM_UnobservedMove(benchmark::State& state) {
    const auto cycles = static_cast<std::uint64_t>(state.range(0));
    rwmos::EmulatedBoard board;
    // 100 units on each of the 8 axes, at the feed that makes it `cycles` cycles of 1 ms.
    const double feed = 2.8284271247461903 * 100.0 * 60000.0 / static_cast<double>(cycles);
    run_unobserved_moves(state, board, cycles, [feed](double x) {
        Profile p;
        p.kind = ProfileKind::kLine;
        p.feed = feed;
        p.axes = 0xFF;
        for (double& t : p.target) t = x;
        return p;
    });
}
BENCHMARK(BM_UnobservedMove)->Arg(1'000)->Arg(1'000'000)->Arg(1'000'000'000);

// The spooler with compensation on: G01/G03 profiles through the one-profile
// lookahead, the moves run analytically. One iteration is one profile.
void BM_SpoolCompensatedProfiles(benchmark::State& state) {
    rwmos::EmulatedBoard board;
    auto write = [&](std::int32_t idx, std::int32_t sub, objif::Value v) {
        objif::Descriptor d{{1300, 1, idx, sub}, 0};
        return board.write(d, v);
    };
    write(1, 7, objif::Value::of_double(1.0));  // RADIUS
    write(1, 9, objif::Value::of_int(0));       // Left
    write(1, 3, objif::Value::of_int(1));       // STATUS = 1
    // A 40 x 20 rectangle with rounded corners, round and round.
    Profile contour[8];
    auto line = [](double x, double y) {
        Profile p;
        p.kind = ProfileKind::kLine;
        p.feed = 6000;
        p.axes = 0x03;
        p.target[0] = x;
        p.target[1] = y;
        return p;
    };
    auto arc = [&](double x, double y, double cx, double cy) {
        Profile p = line(x, y);
        p.kind = ProfileKind::kArcCcw;
        p.center = {cx, cy};
        return p;
    };
    contour[0] = line(35, 0);
    contour[1] = arc(40, 5, 35, 5);
    contour[2] = line(40, 15);
    contour[3] = arc(35, 20, 35, 15);
    contour[4] = line(5, 20);
    contour[5] = arc(0, 15, 5, 15);
    contour[6] = line(0, 5);
    contour[7] = arc(5, 0, 5, 5);
    board.spool(line(5, 0));
    std::uint32_t i = 0;
    for ([[maybe_unused]] auto _ : state) {
        Profile p = contour[i % 8];
        p.tag = i++;
        const auto r = board.spool(p);
        if (r.status == objif::Status::kBusy) {
            board.run_until_idle(~std::uint64_t{0});
            board.spool(p);
        } else if (!r.ok()) {
            state.SkipWithError("spool failed");
            break;
        }
        if (board.motion_status().segments_pending > 1000) {
            state.PauseTiming();
            std::vector<rwmos::motion::Segment> drain(2000);
            board.read_segments(drain);
            state.ResumeTiming();
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_SpoolCompensatedProfiles);

}  // namespace

BENCHMARK_MAIN();
