// SPDX-License-Identifier: MIT
// What the emulated board's benchmarks (motion_bench.cpp, otc_bench.cpp) share: how cycles are
// counted, and the loop of the moves that run analytically.
#pragma once

#include <benchmark/benchmark.h>

#include <cstdint>

#include "rwmos/board.h"

// Each iteration ran `chunk` cycles: the items processed and the counter "cycles/s".
inline void count_cycles(benchmark::State& state, std::uint64_t chunk) {
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * chunk));
    state.counters["cycles/s"] = benchmark::Counter(static_cast<double>(state.iterations() * chunk),
                                                    benchmark::Counter::kIsRate);
}

// Nothing observes the cycles: one iteration spools one move, alternately out to 100 and back to
// 0 (the profile `to(x)` makes), and runs the board until it is idle. The move must take
// `cycles` cycles (one either way); the counter "virtual cycles/s" says how many cycles of board
// time a second of host time runs.
template <class MoveTo>
void run_unobserved_moves(benchmark::State& state, rwmos::EmulatedBoard& board,
                          std::uint64_t cycles, MoveTo to) {
    double x = 0.0;
    std::uint64_t ran = 0;
    for ([[maybe_unused]] auto _ : state) {
        x = x > 0.0 ? 0.0 : 100.0;
        if (!board.spool(to(x)).ok()) {
            state.SkipWithError("spool failed");
            break;
        }
        ran = board.run_until_idle(~std::uint64_t{0});
        benchmark::DoNotOptimize(ran);
    }
    if (ran + 1 < cycles || ran > cycles + 1)
        state.SkipWithError("the move did not take `cycles` cycles");
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
    state.counters["virtual cycles/s"] =
        benchmark::Counter(static_cast<double>(cycles) * static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate);
}
