// SPDX-License-Identifier: MIT
// A program of any length is processed with flat memory: this binary counts every heap
// allocation (global operator new replaced) and checks that validating and executing a
// 1,000,000-block program allocates exactly as much as a 1,000-block one.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>

#include "apci/nc/program.h"
#include "heap_counter.h"

namespace apci::nc {
namespace {

// Writes a valid program of `blocks` motion blocks: lines and arcs (I/J and R) round a square,
// with comments, so that every part of the reader, parser and interpreter runs.
std::string write_program(const std::string& name, std::size_t blocks) {
    std::string path = ::testing::TempDir() + name;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    EXPECT_NE(f, nullptr);
    std::fputs("%generated.nc\nN1 G17 G90 G25 F1000 (setup)\nN2 D1 G0 X0 Y0 Z0\n", f);
    for (std::size_t i = 0; i < blocks; ++i) {
        const std::size_t n = i + 3;
        switch (i % 4) {
            case 0:
                std::fprintf(f, "N%zu G1 X10 Y0\n", n);
                break;
            case 1:
                std::fprintf(f, "N%zu G3 X20Y10 I0 J10 ; quarter\n", n);
                break;
            case 2:
                std::fprintf(f, "N%zu G2 X10 Y20 R10\n", n);
                break;
            default:
                std::fprintf(f, "N%zu G1 X0 Y0 (back)\n", n);
                break;
        }
    }
    std::fputs("M30\n", f);
    std::fclose(f);
    return path;
}

struct Footprint {
    std::size_t allocations = 0;
    std::size_t peak_bytes = 0;
    std::size_t allocations_after_warmup = 0;  // allocations while pulling events 1001..end
    std::uint64_t events = 0;
    std::uint64_t moves = 0;
};

// Both passes: validation (Program::load) and execution (every event pulled).
Footprint run_both_passes(const std::string& path) {
    Footprint fp;
    const std::size_t base_allocations = test_support::heap_allocations();
    const std::size_t base_live = test_support::heap_live_bytes();
    test_support::reset_heap_peak();
    {
        Result<Program> program = Program::load(path);
        EXPECT_TRUE(program) << program.error().to_string();
        if (!program) return fp;
        Result<EventStream> stream = program.value().events();
        EXPECT_TRUE(stream) << stream.error().to_string();
        if (!stream) return fp;
        Event ev;
        std::size_t at_warmup = 0;
        for (;;) {
            const EventStream::Next n = stream.value().next(ev);
            if (n != EventStream::Next::kEvent) {
                EXPECT_EQ(n, EventStream::Next::kEnd) << stream.value().error().to_string();
                break;
            }
            ++fp.events;
            if (ev.data.index() <= 2) ++fp.moves;
            if (fp.events == 1000) at_warmup = test_support::heap_allocations();
        }
        fp.allocations_after_warmup = test_support::heap_allocations() - at_warmup;
        EXPECT_EQ(fp.events, program.value().summary().events);
    }
    fp.allocations = test_support::heap_allocations() - base_allocations;
    fp.peak_bytes = test_support::heap_peak_bytes() - base_live;
    return fp;
}

TEST(Streaming, MillionBlockProgramUsesFlatMemory) {
    const std::string small_path = write_program("flat_small.nc", 1'000);
    const std::string big_path = write_program("flat_large.nc", 1'000'000);
    const Footprint small = run_both_passes(small_path);
    const Footprint big = run_both_passes(big_path);
    EXPECT_EQ(small.moves, 1'001U);
    EXPECT_EQ(big.moves, 1'000'001U);
    // Same allocations and same peak heap for a thousand times the blocks: nothing is kept per
    // block, in either pass.
    EXPECT_EQ(big.allocations, small.allocations);
    EXPECT_EQ(big.peak_bytes, small.peak_bytes);
    EXPECT_EQ(big.allocations_after_warmup, 0U);
    // And that fixed amount is small: the line buffer (2 x 64 KiB) plus a few strings per pass.
    EXPECT_LT(big.peak_bytes, 256U * 1024U);
    std::remove(small_path.c_str());
    std::remove(big_path.c_str());
}

TEST(Streaming, AllocationCounterSeesAllocations) {
    // Guards the test above: the counter must notice a container that grows.
    const std::size_t before = test_support::heap_allocations();
    std::string grows;
    for (int i = 0; i < 100; ++i) grows += "0123456789";
    EXPECT_GT(test_support::heap_allocations(), before);
}

}  // namespace
}  // namespace apci::nc
