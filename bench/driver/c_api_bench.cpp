// SPDX-License-Identifier: MIT
// Cost of one object access through the C API over the in-process transport
// (target: an inproc read under 100 ns median, handle cached).
#include <benchmark/benchmark.h>

#include "apci/apci.h"
#include "apci/apci.hpp"

namespace {

void BM_ReadIntCachedHandle(benchmark::State& state) {
    apci_board* board = nullptr;
    if (apci_open("emu:", &board) != APCI_OK) {
        state.SkipWithError(apci_last_error(nullptr));
        return;
    }
    apci_object_descriptor status{APCI_TC_BUS, APCI_TC_DEVICE_GROUP, 1, APCI_TC_STATUS, 0};
    int32_t v = 0;
    apci_read_int(board, &status, &v);  // resolves the handle
    for ([[maybe_unused]] auto _ : state) {
        benchmark::DoNotOptimize(apci_read_int(board, &status, &v));
        benchmark::DoNotOptimize(v);
    }
    apci_close(board);
}
BENCHMARK(BM_ReadIntCachedHandle);

void BM_ReadIntFirstAccess(benchmark::State& state) {
    apci_board* board = nullptr;
    if (apci_open("emu:", &board) != APCI_OK) {
        state.SkipWithError(apci_last_error(nullptr));
        return;
    }
    int32_t v = 0;
    for ([[maybe_unused]] auto _ : state) {
        apci_object_descriptor status{APCI_TC_BUS, APCI_TC_DEVICE_GROUP, 1, APCI_TC_STATUS, 0};
        benchmark::DoNotOptimize(apci_read_int(board, &status, &v));
    }
    apci_close(board);
}
BENCHMARK(BM_ReadIntFirstAccess);

void BM_WriteDoubleCachedHandle(benchmark::State& state) {
    apci_board* board = nullptr;
    if (apci_open("emu:", &board) != APCI_OK) {
        state.SkipWithError(apci_last_error(nullptr));
        return;
    }
    apci_object_descriptor radius{APCI_TC_BUS, APCI_TC_DEVICE_GROUP, 1, APCI_TC_RADIUS, 0};
    double r = 1.0;
    for ([[maybe_unused]] auto _ : state) {
        benchmark::DoNotOptimize(apci_write_double(board, &radius, r));
        r = r < 100.0 ? r + 0.5 : 1.0;
    }
    apci_close(board);
}
BENCHMARK(BM_WriteDoubleCachedHandle);

void BM_ReadRefusedTypeMismatch(benchmark::State& state) {
    // The error path formats the last-error text: this is its price.
    apci_board* board = nullptr;
    if (apci_open("emu:", &board) != APCI_OK) {
        state.SkipWithError(apci_last_error(nullptr));
        return;
    }
    apci_object_descriptor radius{APCI_TC_BUS, APCI_TC_DEVICE_GROUP, 1, APCI_TC_RADIUS, 0};
    int32_t v = 0;
    for ([[maybe_unused]] auto _ : state) benchmark::DoNotOptimize(apci_read_int(board, &radius, &v));
    apci_close(board);
}
BENCHMARK(BM_ReadRefusedTypeMismatch);

void BM_CppReadDouble(benchmark::State& state) {
    apci::Board board("emu:");
    if (!board) {
        state.SkipWithError(std::string(board.last_error()).c_str());
        return;
    }
    auto radius = apci::object(APCI_TC_BUS, APCI_TC_DEVICE_GROUP, 1, APCI_TC_RADIUS);
    for ([[maybe_unused]] auto _ : state) benchmark::DoNotOptimize(board.read_double(radius));
}
BENCHMARK(BM_CppReadDouble);

void BM_OpenClose(benchmark::State& state) {
    for ([[maybe_unused]] auto _ : state) {
        apci_board* board = nullptr;
        benchmark::DoNotOptimize(apci_open("emu:", &board));
        apci_close(board);
    }
}
BENCHMARK(BM_OpenClose);

}  // namespace

BENCHMARK_MAIN();
