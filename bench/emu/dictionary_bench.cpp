// SPDX-License-Identifier: MIT
// Resolving descriptors (docs/performance.md "Object dictionary"): a client that
// opens every readable object of the map once with a fresh descriptor makes
// the dictionary issue one handle per address. Issuing finds an address's slot
// by hash, so the cost per object stays flat as the number of issued handles
// grows (it was a linear search, quadratic over the whole map).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "objif/descriptor.h"
#include "objif/dictionary.h"
#include "rwmos/board.h"

namespace {

std::vector<objif::Address> readable_addresses(rwmos::EmulatedBoard& board) {
    std::vector<objif::Address> all;
    for (objif::Module* module : board.dictionary().modules()) {
        for (std::size_t i = 0; i < module->object_count(); ++i) {
            const objif::ObjectInfo& info = module->object_at(i);
            if (!objif::can_read(info.access)) continue;
            for (std::int32_t index = info.index_first; index <= info.index_last; ++index)
                all.push_back({module->bus(), info.device, index, info.subindex});
        }
    }
    return all;
}

// Reads the first state.range(0) readable addresses of the map, each with a
// fresh descriptor, on a fresh board: one handle issued per address.
void BM_FirstReadOfEveryObject(benchmark::State& state) {
    rwmos::EmulatedBoard probe;
    std::vector<objif::Address> all = readable_addresses(probe);
    const auto n = std::min<std::size_t>(all.size(), static_cast<std::size_t>(state.range(0)));
    all.resize(n);
    for ([[maybe_unused]] auto _ : state) {
        state.PauseTiming();
        auto board = std::make_unique<rwmos::EmulatedBoard>();
        state.ResumeTiming();
        for (const objif::Address& a : all) {
            objif::Descriptor d{a, objif::kNoHandle};
            const objif::ObjectInfo* info = nullptr;
            objif::Module* module = nullptr;
            benchmark::DoNotOptimize(board->dictionary().resolve(d, info, module));
            benchmark::DoNotOptimize(d.handle);
        }
        state.PauseTiming();
        board.reset();
        state.ResumeTiming();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(n));
    state.counters["objects"] = static_cast<double>(n);
}
BENCHMARK(BM_FirstReadOfEveryObject)->Arg(100)->Arg(1'000)->Arg(1'000'000);  // the last: the whole map

// Building and dropping a board: what a test or a fuzzer input pays before its
// first request (the frame fuzzer builds one per input). The trace and the
// executed-segment log grow with their content, so an idle board costs its
// object state only.
void BM_FreshBoard(benchmark::State& state) {
    for ([[maybe_unused]] auto _ : state) {
        auto board = std::make_unique<rwmos::EmulatedBoard>();
        benchmark::DoNotOptimize(board.get());
    }
}
BENCHMARK(BM_FreshBoard);

}  // namespace

BENCHMARK_MAIN();
