// SPDX-License-Identifier: MIT
// The OTC engine inside the interpolation clock (docs/otc.md, docs/performance.md "OTC"):
//  - while a discrete offset ramps, every cycle is stepped: cycles per second with the ramps of
//    three units running on a moving line;
//  - with only continuous wear (no ramp), a move still runs analytically: the cost of a move
//    does not grow with its cycle count.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "board_bench.h"
#include "objif/descriptor.h"
#include "rwmos/board.h"
#include "rwmos/board_state.h"
#include "rwmos/object_map.h"

namespace {

namespace otc = rwmos::otc;
using rwmos::motion::Profile;
using rwmos::motion::ProfileKind;

constexpr std::uint64_t kChunk = 10'000;

void write(rwmos::EmulatedBoard& b, std::int32_t dev, std::int32_t idx, std::int32_t sub, objif::Value v) {
    objif::Descriptor d{{otc::kBus, dev, idx, sub}, 0};
    (void)b.write(d, v);
}

void grinding_tool_on(rwmos::EmulatedBoard& b, otc::ProcessingType type, otc::Mode mode) {
    write(b, otc::kDevTool, otc::kIdxToolNumber, 0, objif::Value::of_int(1));
    write(b, otc::kDevTool, otc::kIdxToolType, 0, objif::Value::of_int(otc::kGrindingToolType));
    write(b, otc::kDevTool, otc::kIdxToolWearConst, 0, objif::Value::of_double(100000.0));
    write(b, otc::kDevTool, otc::kIdxToolMaxInfeed, 0, objif::Value::of_double(200000.0));
    write(b, otc::kDevChannel, otc::kIdxProcessingType, 0,
          objif::Value::of_int(static_cast<std::int32_t>(type)));
    write(b, otc::kDevChannel, otc::kIdxMode, 0,
          objif::Value::of_int(static_cast<std::int32_t>(mode)));
    write(b, otc::kDevChannel, otc::kIdxActive, 0, objif::Value::of_int(1));
}

Profile line_to(double x, double feed) {
    Profile p;
    p.kind = ProfileKind::kLine;
    p.feed = feed;
    p.axes = 0x07;
    p.target[0] = x;
    p.target[1] = x / 2;
    p.target[2] = 0.0;
    return p;
}

// Ramps that never rest (a slow ramp towards 20 mm on three axes) on a line of 1e9 cycles.
void BM_OtcRampingCycles(benchmark::State& state) {
    rwmos::EmulatedBoard board;
    grinding_tool_on(board, otc::ProcessingType::kLength, otc::Mode::kAuto);
    write(board, otc::kDevChannel, otc::kIdxRampVelocity, 0, objif::Value::of_double(1e-3));
    for (int axis : {0, 1, 2}) {
        write(board, otc::kDevAxisUnits, axis, otc::kSubEnable, objif::Value::of_int(1));
        write(board, otc::kDevAxisUnits, axis, otc::kSubCommand, objif::Value::of_int(200000));
    }
    if (!board.spool(line_to(50000.0, 3.0)).ok()) {
        state.SkipWithError("spool failed");
        return;
    }
    for ([[maybe_unused]] auto _ : state) {
        board.step(kChunk);
        benchmark::DoNotOptimize(board.motion_status().position);
    }
    if (board.state().otc_engine.ramps_settled())
        state.SkipWithError("the ramps rested: not measuring what was meant");
    count_cycles(state, kChunk);
}
BENCHMARK(BM_OtcRampingCycles);

// Continuous wear only: one iteration is a whole move of range(0) cycles, run analytically.
void BM_OtcContinuousWearUnobservedMove(benchmark::State& state) {
    const auto cycles = static_cast<std::uint64_t>(state.range(0));
    rwmos::EmulatedBoard board;
    grinding_tool_on(board, otc::ProcessingType::kLength, otc::Mode::kCont);
    const double length = 100.0 * 1.118033988749895;  // X 100, Y 50
    const double feed = length * 60000.0 / static_cast<double>(cycles);
    run_unobserved_moves(state, board, cycles, [feed](double x) { return line_to(x, feed); });
}
BENCHMARK(BM_OtcContinuousWearUnobservedMove)->Arg(1'000)->Arg(1'000'000)->Arg(1'000'000'000);

}  // namespace

BENCHMARK_MAIN();
