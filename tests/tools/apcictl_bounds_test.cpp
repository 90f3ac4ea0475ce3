// SPDX-License-Identifier: MIT
// `apcictl run` does no work without a bound (docs/hardening.md "Resource limits"): a feed so low
// that one move would take more than 10^9 cycles, a PLC `cycle N` beyond 10^9, a $FOR loop that
// does not end are errors naming their line, found before anything runs; numbers out of range
// are named as written. Each of these ran for minutes or without end before.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <fstream>
#include <string>
#include <vector>

#include "apci/apci.hpp"
#include "apci/nc/program.h"
#include "apci/run/executor.h"
#include "apci/run/plc_script.h"
#include "apcictl.h"
#include "rwmos/object_map.h"
#include "scratch_test.h"
#include "text.h"

namespace {

using test_support::contains;
using test_support::ProcessResult;

class ApcictlBounds : public test_support::ScratchTest {
  protected:
    ApcictlBounds() : ScratchTest("apcictl_bounds_") {}

    // Runs apcictl (cwd: the test's directory, so files are named as written); the seconds it
    // took go to `seconds_`.
    ProcessResult apcictl(const std::vector<std::string>& args) {
        const auto t0 = std::chrono::steady_clock::now();
        ProcessResult r = test_support::apcictl(args, {}, {}, dir());
        seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return r;
    }

    double seconds_ = 0.0;
};

const std::string kForty = "1234567890123456789012345678901234567890";

TEST_F(ApcictlBounds, AFeedTooLowForOneMoveIsAnErrorNamingTheLineBeforeAnyMotion) {
    // It ran for 10 minutes and more, the move capped at 2^52 cycles, exit 0.
    write("p.nc", "N10 G1 X1 F100\nN20 G1 X2 F0.000001\nN30 M30\n");
    const ProcessResult r = apcictl({"run", "p.nc", "--json", "out.json"});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_EQ(r.err,
              "apcictl: p.nc:2:11: N20: feed F1e-06 makes this 1 mm move take 60000000000 "
              "interpolation cycles; at most 1000000000 cycles (11.6 days at 1 ms) are allowed "
              "per move: raise F\n");
    EXPECT_FALSE(std::ifstream(path("out.json")).good()) << "nothing ran, nothing written";
    EXPECT_LT(seconds_, 30.0);
}

TEST_F(ApcictlBounds, APlcCycleBeyondTheLimitIsAnErrorNamingTheLine) {
    // The clock ran on towards cycle 10^18 without end.
    write("p.nc", "N10 G1 X1 F600\nN20 M30\n");
    write("p.plc",
          "cycle 0 otc_radius_offset.enable 1\ncycle 1000000000000000000 "
          "otc_radius_offset.command 5\n");
    const ProcessResult r = apcictl({"run", "p.nc", "--plc", "p.plc"});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_EQ(r.err,
              "apcictl: p.plc:2:7: cycle 1000000000000000000 out of range 0..1000000000 (the "
              "clock runs on to it: at most 11.6 days of board time at 1 ms)\n");
    EXPECT_LT(seconds_, 30.0);
}

TEST_F(ApcictlBounds, APlcCycleAtTheLimitRunsToIt) {
    write("p.nc", "N10 G1 X1 F600\nN20 M30\n");
    write("p.plc", "cycle 1000000000 otc_radius_offset.enable 1\n");
    const ProcessResult r = apcictl({"run", "p.nc", "--plc", "p.plc"});
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_TRUE(contains(r.out, "(1000000000 cycles of 1 ms)")) << r.out;
    EXPECT_LT(seconds_, 60.0);
}

TEST(PlcScriptBounds, CycleAndBlockNumbersOutOfRangeAreNamedAsWritten) {
    auto err = [](const std::string& text) {
        auto s = apci::run::parse_plc_script(text, "p.plc");
        return s ? std::string() : s.error().to_string();
    };
    EXPECT_EQ(err("cycle 1000000000 otc_radius_offset.enable 1"), "");
    EXPECT_EQ(err("cycle 1000000001 otc_radius_offset.enable 1"),
              "p.plc:1:7: cycle 1000000001 out of range 0..1000000000 (the clock runs on to it: "
              "at most 11.6 days of board time at 1 ms)");
    EXPECT_EQ(err("block " + kForty + " otc_radius_offset.enable 1"),
              "p.plc:1:7: block " + kForty +
                  " out of range 0..9999999999999 (an N number of the program)");
    EXPECT_EQ(err("cycle 5 otc_offset[" + kForty + "].command 1"),
              "p.plc:1:9: otc_offset[i]: axis index 0..7");
    EXPECT_EQ(err("cycle 5 otc_offset[x].command 1"),
              "p.plc:1:20: expected a whole number after 'otc_offset['");
}

TEST_F(ApcictlBounds, AForLoopThatDoesNotEndIsAnErrorNamingTheLoop) {
    // It ran for ever.
    write("p.nc",
          "N5 G1 X0 F100\nN10 $FOR P1 = 0, 10, 1\nN20 G1 X[P1]\nN30 P1 = 0\n$ENDFOR\n"
          "N40 M30\n");
    const ProcessResult r = apcictl({"run", "p.nc"});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.err,
                         "apcictl: p.nc:2:5: N10: $FOR P1 does not end: $FOR loops may run "
                         "at most 10000000 blocks in all"))
        << r.err;
    EXPECT_LT(seconds_, 60.0);
}

TEST_F(ApcictlBounds, AFortyDigitToolNumberIsNamedAsWritten) {
    // The tool list said "tool number 9999999".
    write("p.nc", "N10 G1 X1 F600\nN20 M30\n");
    write("t.tools", "wz[" + kForty + "].typ 1\n");
    ProcessResult r = apcictl({"run", "p.nc", "--tools", "t.tools"});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_EQ(r.err, "apcictl: t.tools:1:4: tool number " + kForty + " out of range 1..1023\n");
    write("d.nc", "N10 D" + kForty + "\nN20 M30\n");
    r = apcictl({"run", "d.nc"});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_EQ(r.err, "apcictl: d.nc:1:6: N10: tool number D" + kForty + " out of range 0..1023\n");
}

TEST(RunBounds, TheCycleLimitIsCountedInTheBoardsInterpolationCycleNamingTheBlock) {
    // F0.0002 over 1 mm: 3e8 cycles of 1 ms (the front end takes it), 1.2e9 of 250 us: the
    // executor refuses it in the board's cycle, in the program's words, before the board does.
    apci::Board board("emu:");
    ASSERT_TRUE(board.is_open());
    auto cycle = apci::object(rwmos::board::kBus, rwmos::board::kDevice,
                              rwmos::board::kIdxInterpolationCycle, 0);
    ASSERT_TRUE(board.write_int(cycle, 250));
    auto program = apci::nc::Program::from_text("N10 G1 X1 F0.0002\nN20 M30\n", "p.nc");
    ASSERT_TRUE(program) << program.error().to_string();
    auto stream = program.value().events();
    ASSERT_TRUE(stream);
    apci::run::RunSink sink;
    apci::run::ProgramExecutor executor(board, sink, nullptr);
    const apci::run::RunOutcome out = executor.run(stream.value());
    ASSERT_EQ(out.errors.size(), 1u);
    EXPECT_EQ(out.errors[0].code, "Value");
    EXPECT_EQ(out.errors[0].block.number, 10);
    EXPECT_EQ(out.errors[0].message,
              "feed F0.0002 makes this 1 mm move take 1200000000 interpolation cycles; at most "
              "1000000000 cycles (2.9 days at 0.25 ms) are allowed per move: raise F");
    EXPECT_EQ(out.totals.cycles, 0u) << "nothing moved";
}

TEST(RunBounds, TheValidationPassCountsInTheBoardsInterpolationCycle) {
    // apcictl run and diff and the Python module give the interpreter the options of
    // ProgramExecutor::interpreter_options: the board's cycle, so the same F0.0002 move is
    // refused before anything runs, not only when it is spooled; where the axes stand; the
    // executor's tool list and correction table.
    apci::Board board("emu:");
    ASSERT_TRUE(board.is_open());
    auto cycle = apci::object(rwmos::board::kBus, rwmos::board::kDevice,
                              rwmos::board::kIdxInterpolationCycle, 0);
    ASSERT_TRUE(board.write_int(cycle, 250));
    apci_direct_command ja{};
    ja.code = APCI_DIRECT_JA;
    ja.axes = 0x1;
    ja.target[0] = 3.5;
    ASSERT_TRUE(board.direct(ja));
    ASSERT_TRUE(board.run_until_idle(1'000'000));
    apci::run::RunSink sink;
    const apci::nc::ToolTable tools;
    const apci::nc::CorrectionTable corrections;
    apci::run::ProgramExecutor executor(board, sink, &tools, nullptr, &corrections);
    EXPECT_DOUBLE_EQ(executor.cycle_seconds(), 250e-6);
    const apci::nc::InterpreterOptions options = executor.interpreter_options();
    EXPECT_DOUBLE_EQ(options.cycle_seconds, 250e-6);
    EXPECT_DOUBLE_EQ(options.start_position.x(), 3.5);
    EXPECT_EQ(options.tools, &tools);
    EXPECT_EQ(options.corrections, &corrections);
    auto program = apci::nc::Program::from_text("N10 G1 X1 F0.0002\nN20 M30\n", "p.nc", options);
    ASSERT_FALSE(program);
    // From X3.5, where the axes stand: 2.5 mm.
    EXPECT_NE(program.error().message.find("2.5 mm move take 3000000000 interpolation cycles"),
              std::string::npos)
        << program.error().message;
}

}  // namespace
