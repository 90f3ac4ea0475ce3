// SPDX-License-Identifier: MIT
// Compensation throughput of PathCompensator over a steady line/arc mix: a closed contour
// of 13 elements (8 lines, 5 arcs; inside, outside and tangent corners on either side)
// pushed round and round. Target: at least 5 million compensated elements per second on
// one core. docs/performance.md records the figure and the command.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>

#include "rwmos/geometry/compensator.h"

namespace {

using namespace rwmos::geom;

// A 100 x 60 plate with rounded corners, a rectangular notch and a circular dip,
// counter-clockwise from (0, 0).
const std::array<Element, 13> kContour = {
    make_line({0, 0}, {40, 0}),      make_line({40, 0}, {40, 10}),
    make_line({40, 10}, {60, 10}),   make_line({60, 10}, {60, 0}),
    make_line({60, 0}, {90, 0}),     make_arc({90, 0}, {100, 10}, {90, 10}, true),
    make_line({100, 10}, {100, 50}), make_arc({100, 50}, {90, 60}, {90, 50}, true),
    make_line({90, 60}, {60, 60}),   make_arc({60, 60}, {40, 60}, {50, 60}, false),
    make_line({40, 60}, {10, 60}),   make_arc({10, 60}, {0, 50}, {10, 50}, true),
    make_line({0, 50}, {0, 0}),
};

void compensate_contour(benchmark::State& state, Side side, TransitionMode mode) {
    PathCompensator compensator;
    SegmentBatch batch;
    if (!compensator.begin({side, 2.0, mode}, {-10, -10}).ok()) {
        state.SkipWithError("begin failed");
        return;
    }
    std::uint32_t index = 0;
    std::size_t emitted = 0;
    for ([[maybe_unused]] auto _ : state) {
        const StepResult r = compensator.push(kContour[index % kContour.size()], index, batch);
        if (!r.ok()) {
            state.SkipWithError("push failed");
            break;
        }
        emitted += batch.size();
        benchmark::DoNotOptimize(batch);
        ++index;
    }
    state.SetItemsProcessed(state.iterations());
    state.counters["segments_per_element"] =
        benchmark::Counter(static_cast<double>(emitted) / static_cast<double>(state.iterations()));
}

void BM_CompensateLeftCircular(benchmark::State& s) {
    compensate_contour(s, Side::kLeft, TransitionMode::kCircular);
}
void BM_CompensateRightCircular(benchmark::State& s) {
    compensate_contour(s, Side::kRight, TransitionMode::kCircular);
}
void BM_CompensateLeftLinear(benchmark::State& s) {
    compensate_contour(s, Side::kLeft, TransitionMode::kLinear);
}
void BM_CompensateRightLinear(benchmark::State& s) {
    compensate_contour(s, Side::kRight, TransitionMode::kLinear);
}
BENCHMARK(BM_CompensateLeftCircular);
BENCHMARK(BM_CompensateRightCircular);
BENCHMARK(BM_CompensateLeftLinear);
BENCHMARK(BM_CompensateRightLinear);

}  // namespace

BENCHMARK_MAIN();
