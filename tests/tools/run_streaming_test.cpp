// SPDX-License-Identifier: MIT
// `apcictl run` keeps memory flat in the program length: this binary counts the live heap
// (global operator new replaced, which the driver and the emulator inside libapci use too) and
// checks that executing a compensated program ten times longer, with the JSON and the SVG
// writers attached, needs no more heap at its peak.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>

#include "heap_counter.h"
#include "plate_program.h"
#include "apci/apci.hpp"
#include "apci/nc/program.h"
#include "apci/run/executor.h"
#include "apci/run/json_writer.h"
#include "apci/run/read_ahead.h"
#include "apci/run/svg_writer.h"

namespace apci::run {
namespace {

std::string program_text(int turns) { return apci::test::plate_program(turns); }

class Writers final : public RunSink {
  public:
    explicit Writers(std::FILE* json) : json_(json) {}
    void programmed(const PathSegment& s) override { svg_.programmed(s); }
    void executed(const PathSegment& s) override {
        json_.segment(s);
        svg_.executed(s);
        ++segments;
    }
    std::uint64_t segments = 0;

  private:
    JsonRunWriter json_;
    SvgPlotWriter svg_;
};

struct Footprint {
    std::size_t peak_bytes = 0;  // above what was live before the run
    std::uint64_t segments = 0;
    bool ok = false;
};

Footprint run_program(const std::string& text, const nc::ToolTable& tools,
                      bool read_ahead = false) {
    Footprint fp;
    std::FILE* null = std::fopen("/dev/null", "w");
    const std::size_t base = test_support::heap_live_bytes();
    test_support::reset_heap_peak();
    {
        apci::Board board("emu:");
        EXPECT_TRUE(board.is_open());
        nc::InterpreterOptions options;
        options.tools = &tools;
        auto program = nc::Program::from_text(text, "flat.nc", options);
        EXPECT_TRUE(program) << program.error().to_string();
        if (!program) return fp;
        auto stream = program.value().events();
        Writers writers(null);
        ProgramExecutor executor(board, writers, &tools);
        executor.set_read_ahead(read_ahead);
        const RunOutcome out = executor.run(stream.value());
        EXPECT_TRUE(out.errors.empty()) << out.errors.front().message;
        fp.segments = writers.segments;
        fp.ok = out.errors.empty();
    }
    fp.peak_bytes = test_support::heap_peak_bytes() - base;
    std::fclose(null);
    return fp;
}

TEST(RunStreaming, TenTimesTheBlocksNeedNoMoreHeap) {
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer brings its own allocator and intercepts operator new and
    // delete in the shared libraries, so this binary's counting replacement does
    // not see every allocation (and frees the runtime's blocks as its own). The
    // measurement runs in every build without ASan.
    GTEST_SKIP() << "heap counting needs the program's own operator new, which ASan replaces";
#endif
    auto tools =
        nc::parse_tool_table("wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 1\n", "t.tools");
    ASSERT_TRUE(tools);
    // The program text itself is the caller's (held here for from_text): not part of the run.
    const std::string small_text = program_text(500);   // 6,005 blocks
    const std::string large_text = program_text(5000);  // 60,005 blocks
    const Footprint small = run_program(small_text, tools.value());
    const Footprint large = run_program(large_text, tools.value());
    ASSERT_TRUE(small.ok && large.ok);
    EXPECT_GT(large.segments, 9 * small.segments);
    RecordProperty("small_peak_bytes", std::to_string(small.peak_bytes));
    RecordProperty("large_peak_bytes", std::to_string(large.peak_bytes));
    std::printf("peak heap: %zu bytes for %llu segments, %zu bytes for %llu segments\n",
                small.peak_bytes, static_cast<unsigned long long>(small.segments), large.peak_bytes,
                static_cast<unsigned long long>(large.segments));
    EXPECT_LE(large.peak_bytes, small.peak_bytes);
}

// The same with the NC front end on a thread of its own (read_ahead.h): its ring is bounded,
// so the peak is the same for ten times the blocks.
TEST(RunStreaming, TenTimesTheBlocksNeedNoMoreHeapWithTheFrontEndReadingAhead) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "heap counting needs the program's own operator new, which ASan replaces";
#endif
    auto tools =
        nc::parse_tool_table("wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 1\n", "t.tools");
    ASSERT_TRUE(tools);
    const std::string small_text = program_text(500);
    const std::string large_text = program_text(5000);
    const Footprint small = run_program(small_text, tools.value(), true);
    const Footprint large = run_program(large_text, tools.value(), true);
    const Footprint direct = run_program(small_text, tools.value(), false);
    ASSERT_TRUE(small.ok && large.ok && direct.ok);
    EXPECT_EQ(small.segments, direct.segments);
    EXPECT_GT(large.segments, 9 * small.segments);
    std::printf(
        "peak heap reading ahead: %zu bytes for %llu segments, %zu bytes for %llu "
        "segments (%zu without; the ring %zu)\n",
        small.peak_bytes, static_cast<unsigned long long>(small.segments), large.peak_bytes,
        static_cast<unsigned long long>(large.segments), direct.peak_bytes,
        ReadAhead::ring_bytes());
    // Two threads allocate side by side, so a few small blocks of either may or may not be live
    // at the peak (16 bytes apart from run to run, seen): 1 KiB of room for that; anything kept
    // per block would be megabytes here.
    EXPECT_LE(large.peak_bytes, small.peak_bytes + 1024);
    // The ring's batches and the reader's thread (its own few small blocks, 2 KiB at most),
    // nothing per block.
    EXPECT_LE(small.peak_bytes, direct.peak_bytes + ReadAhead::ring_bytes() + 2048);
}

}  // namespace
}  // namespace apci::run
