// SPDX-License-Identifier: MIT
// The one way a program is run (program_run.h): the inputs loaded in their order, the refusal
// that names an input not given (by the diagnostic's kind), the mode names, a run validated
// first and one validated while it runs, the settings reaching the executor.
#include "apci/run/program_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "apci/apci.hpp"
#include "apci/run/pipeline.h"
#include "apci/run/read_ahead.h"
#include "scratch_dir.h"
#include "text.h"
#include "thread_count.h"

namespace apci::run {
namespace {

using test_support::contains;

const std::string kTool5 = "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n";

std::string write(const test_support::ScratchDir& dir, const std::string& name,
                  const std::string& text) {
    return test_support::write_text(dir.file(name), text);
}

// The executed segments and warnings of a run.
struct Collect final : RunSink {
    std::vector<PathSegment> segments;
    std::vector<RunError> warnings;
    void executed(const PathSegment& s) override { segments.push_back(s); }
    void warning(const RunError& w, const Point&) override { warnings.push_back(w); }
};

TEST(LoadRunInputs, NothingGivenLoadsNothingAndKeepsTheCallersWords) {
    RunInputFiles files;
    files.tools_name = "--tools file";
    files.corrections_name = "--corr file";
    auto in = load_run_inputs(files);
    ASSERT_TRUE(in) << in.error().to_string();
    EXPECT_FALSE(in.value().tools_given);
    EXPECT_FALSE(in.value().corrections_given);
    EXPECT_FALSE(in.value().plc.has_value());
    EXPECT_EQ(in.value().tools_name, "--tools file");
    EXPECT_EQ(in.value().corrections_name, "--corr file");
}

TEST(LoadRunInputs, ToolsAsTextOrAsAFileAreTheSameList) {
    test_support::ScratchDir dir;
    RunInputFiles text;
    text.tools = kTool5;
    text.tools_is_text = true;
    RunInputFiles file;
    file.tools = write(dir, "t.tools", kTool5);
    for (const RunInputFiles& f : {text, file}) {
        auto in = load_run_inputs(f);
        ASSERT_TRUE(in) << in.error().to_string();
        EXPECT_TRUE(in.value().tools_given);
        ASSERT_NE(in.value().tools.find(1), nullptr);
        EXPECT_EQ(in.value().tools.find(1)->radius, 5.0);
    }
    // The text is not a path, nor the path a text.
    text.tools_is_text = false;
    EXPECT_FALSE(load_run_inputs(text));
    file.tools_is_text = true;
    EXPECT_FALSE(load_run_inputs(file));
}

TEST(LoadRunInputs, TheFirstInputThatFailsIsTheErrorInTheOrderToolsCorrectionsPlc) {
    test_support::ScratchDir dir;
    const std::string bad_tools = write(dir, "bad.tools", "wz[1].radius x\n");
    const std::string bad_corr = write(dir, "bad.corr", "corr[1].dl\n");
    const std::string bad_plc = write(dir, "bad.plc", "at\n");
    RunInputFiles f;
    f.tools = bad_tools;
    f.corrections = bad_corr;
    f.plc = bad_plc;
    auto in = load_run_inputs(f);
    ASSERT_FALSE(in);
    EXPECT_TRUE(contains(in.error().to_string(), "bad.tools")) << in.error().to_string();
    f.tools = write(dir, "good.tools", kTool5);
    in = load_run_inputs(f);
    ASSERT_FALSE(in);
    EXPECT_TRUE(contains(in.error().to_string(), "bad.corr")) << in.error().to_string();
    f.corrections.reset();
    in = load_run_inputs(f);
    ASSERT_FALSE(in);
    EXPECT_TRUE(contains(in.error().to_string(), "bad.plc")) << in.error().to_string();
    // A file that is not there cannot be read: an I/O error, not a program one.
    f.plc = dir.file("missing.plc");
    in = load_run_inputs(f);
    ASSERT_FALSE(in);
    EXPECT_EQ(in.error().kind, nc::ErrorKind::kIo);
}

TEST(NameMissingInput, NamesTheInputNotGivenOnlyForItsOwnKind) {
    RunInputs in;
    in.tools_name = "--tools file";
    in.corrections_name = "--corr file";
    nc::Diagnostic tool;
    tool.message = "tool 1 is not defined";
    tool.undefined = nc::Undefined::kTool;
    nc::Diagnostic row = tool;
    row.message = "row 1 is not defined";
    row.undefined = nc::Undefined::kCorrectionRow;
    nc::Diagnostic other = tool;
    other.message = "other";
    other.undefined = nc::Undefined::kNothing;
    EXPECT_EQ(name_missing_input(tool, in).message,
              "tool 1 is not defined (no --tools file given)");
    EXPECT_EQ(name_missing_input(row, in).message, "row 1 is not defined (no --corr file given)");
    EXPECT_EQ(name_missing_input(other, in).message, "other");
    // Given (even if it does not define the tool or row): the message stays as it is.
    in.tools_given = true;
    EXPECT_EQ(name_missing_input(tool, in).message, "tool 1 is not defined");
    EXPECT_EQ(name_missing_input(row, in).message, "row 1 is not defined (no --corr file given)");
    in.corrections_given = true;
    EXPECT_EQ(name_missing_input(row, in).message, "row 1 is not defined");
}

TEST(SelfApproachModeName, TheThreeNamesAndNoOther) {
    EXPECT_EQ(self_approach_mode("warn"), SelfApproachMode::kWarn);
    EXPECT_EQ(self_approach_mode("error"), SelfApproachMode::kError);
    EXPECT_EQ(self_approach_mode("off"), SelfApproachMode::kOff);
    for (const char* bad : {"", "Warn", "warn ", "err", "none"})
        EXPECT_FALSE(self_approach_mode(bad).has_value()) << bad;
}

// The boards whose run is its own dry run (apci_open: NULL, "" or "emu:" with its options) and
// the ones that move a machine (a daemon's, a real one).
TEST(EmbeddedEmulator, NoDeviceAndEmuWithItsOptionsAreEmbeddedEveryOtherSchemeIsNot) {
    for (const char* embedded : {"", "emu:", "emu:?no-option-tc"})
        EXPECT_TRUE(embedded_emulator(embedded)) << '"' << embedded << '"';
    for (const char* other : {"unix:/run/apci/board.sock", "shm:/dev/shm/apci", "pci:0000:03:00.0",
                              "usb:", "emu", "EMU:", " emu:", "unix:emu:"})
        EXPECT_FALSE(embedded_emulator(other)) << '"' << other << '"';
}

const std::string kSquare =
    "N10 G17 G90 F1000 D1\nN20 G41 G1 X0 Y0\nN30 X60\nN40 Y60\nN50 X0\nN60 Y0\n"
    "N70 G40 G1 X-20 Y0\nN80 M30\n";

RunInputs tool5() {
    RunInputFiles f;
    f.tools = kTool5;
    f.tools_is_text = true;
    auto in = load_run_inputs(f);
    EXPECT_TRUE(in);
    return in ? std::move(in.value()) : RunInputs{};
}

TEST(ProgramRun, ValidatedFirstRunsAndCountsTheProgram) {
    apci::Board board("emu:");
    Collect sink;
    const RunInputs in = tool5();
    ProgramRun run(board, sink, in, RunSettings{});
    EXPECT_EQ(run.options().cycle_seconds, 1e-3);  // the board's cycle, read from it
    ASSERT_FALSE(run.open_validated(ProgramSource::in_memory(kSquare, "square.nc")));
    EXPECT_FALSE(run.one_pass());
    EXPECT_EQ(run.validated_blocks(), 8u);
    EXPECT_EQ(run.program_bytes(), 0u);
    RunOutcome out = run.run();
    EXPECT_TRUE(out.errors.empty());
    ASSERT_FALSE(run.finish(out));
    EXPECT_EQ(out.totals.file, "square.nc");
    EXPECT_EQ(out.totals.blocks, 8u);
    EXPECT_GE(sink.segments.size(), 6u);
}

TEST(ProgramRun, OnePassValidatesTheRestAtFinishAndCanBeValidatedFirstInstead) {
    const std::string bad = "N10 G1 X10 F1000\nN20 G1 X20\nN30 G1 Q5\nN40 M30\n";
    const RunInputs in = tool5();
    {
        apci::Board board("emu:");
        Collect sink;
        ProgramRun run(board, sink, in, RunSettings{});
        ASSERT_FALSE(run.open_one_pass(ProgramSource::in_memory(bad, "bad.nc")));
        EXPECT_TRUE(run.one_pass());
        EXPECT_EQ(run.program_bytes(), bad.size());
        EXPECT_EQ(run.validated_blocks(), 0u);
        RunOutcome out = run.run();
        const auto refused = run.finish(out);
        ASSERT_TRUE(refused);
        EXPECT_EQ(refused->line, 3u) << refused->to_string();
    }
    {
        apci::Board board("emu:");
        Collect sink;
        ProgramRun run(board, sink, in, RunSettings{});
        ASSERT_FALSE(run.open_one_pass(ProgramSource::in_memory(bad, "bad.nc")));
        const auto refused = run.validate_first();
        ASSERT_TRUE(refused);
        EXPECT_EQ(refused->line, 3u);
        EXPECT_FALSE(run.one_pass());
    }
    {
        apci::Board board("emu:");
        Collect sink;
        ProgramRun run(board, sink, in, RunSettings{});
        ASSERT_FALSE(run.open_one_pass(ProgramSource::in_memory(kSquare, "square.nc")));
        ASSERT_FALSE(run.validate_first());
        EXPECT_FALSE(run.one_pass());
        EXPECT_EQ(run.validated_blocks(), 8u);
        EXPECT_FALSE(run.validate_first());  // nothing more to do
        RunOutcome out = run.run();
        ASSERT_FALSE(run.finish(out));
        EXPECT_EQ(out.totals.blocks, 8u);
        EXPECT_TRUE(out.errors.empty());
    }
}

TEST(ProgramRun, AFileThatIsNotThereIsRefusedInEitherWay) {
    test_support::ScratchDir dir;
    apci::Board board("emu:");
    Collect sink;
    const RunInputs in = tool5();
    ProgramRun run(board, sink, in, RunSettings{});
    const auto missing = ProgramSource::file(dir.file("missing.nc"));
    auto refused = run.open_validated(missing);
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->kind, nc::ErrorKind::kIo);
    refused = run.open_one_pass(missing);
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->kind, nc::ErrorKind::kIo);
    // A file that is there: its path is its name.
    const auto square = ProgramSource::file(write(dir, "square.nc", kSquare));
    ASSERT_FALSE(run.open_one_pass(square));
    RunOutcome out = run.run();
    ASSERT_FALSE(run.finish(out));
    EXPECT_EQ(out.totals.file, square.path);
    EXPECT_EQ(out.totals.blocks, 8u);
}

TEST(ProgramRun, ARefusalNamesTheToolListNotGivenInBothWays) {
    RunInputFiles none;
    none.tools_name = "--tools file";
    auto in = load_run_inputs(none);
    ASSERT_TRUE(in);
    apci::Board board("emu:");
    Collect sink;
    ProgramRun run(board, sink, in.value(), RunSettings{});
    auto refused = run.open_validated(ProgramSource::in_memory(kSquare, "square.nc"));
    ASSERT_TRUE(refused);
    EXPECT_TRUE(contains(refused->message, "(no --tools file given)")) << refused->message;
    ASSERT_FALSE(run.open_one_pass(ProgramSource::in_memory(kSquare, "square.nc")));
    RunOutcome out = run.run();
    refused = run.finish(out);
    ASSERT_TRUE(refused);
    EXPECT_TRUE(contains(refused->message, "(no --tools file given)")) << refused->message;
}

// A spike whose N70 cuts into N50 (tool radius 5).
const std::string kSpike =
    "N10 G17 G90 G26 D1 F600\nN20 G0 X-74.257 Y-49.657\nN30 G42 G1 X-35.095 Y-27.491\n"
    "N50 G1 X-4.063 Y-82.318\nN60 G1 X-4.273 Y-81.223\nN70 G1 X-34.475 Y-136.512\n"
    "N80 G1 X-50 Y-150\nN90 G40 G1 X-73.967 Y-114.939\nN100 M30\n";

// The mode the caller chose reaches the run.
TEST(RunProgram, TheSelfApproachModeReachesTheRun) {
    const std::string& spike = kSpike;
    const RunInputs in = tool5();
    const auto source = ProgramSource::in_memory(spike, "spike.nc");
    for (const SelfApproachMode mode :
         {SelfApproachMode::kWarn, SelfApproachMode::kError, SelfApproachMode::kOff}) {
        apci::Board board("emu:");
        Collect sink;
        RunSettings settings;
        settings.self_approach = mode;
        auto out = run_program(board, sink, in, source, settings);
        ASSERT_TRUE(out) << out.error().to_string();
        EXPECT_EQ(out.value().totals.blocks, 9u);
        const bool warned = !out.value().warnings.empty();
        const bool stopped =
            !out.value().errors.empty() && out.value().errors.front().code == "SelfApproach";
        EXPECT_EQ(warned, mode == SelfApproachMode::kWarn);
        EXPECT_EQ(stopped, mode == SelfApproachMode::kError);
    }
    // Bottleneck avoidance: the notch the board refuses without it is left out with it.
    const std::string notch =
        "G17 G90 G26 F1000 D1\nG0 X-10 Y20 Z0\nG41 G1 X-5 Y0\nN10 G1 X10 Y0\nN20 G1 X12 Y-8\n"
        "N30 G1 X14 Y0\nN40 G1 X14 Y10\nN50 G1 X30 Y10\nN60 G40 G1 X30 Y20\nM30\n";
    for (const int blocks : {0, 3}) {
        apci::Board board("emu:");
        Collect sink;
        RunSettings settings;
        settings.bottleneck_blocks = blocks;
        auto out = run_program(board, sink, in, ProgramSource::in_memory(notch, "n.nc"), settings);
        ASSERT_TRUE(out) << out.error().to_string();
        const auto& o = out.value();
        ASSERT_EQ(o.errors.empty(), blocks != 0) << blocks;
        ASSERT_EQ(o.warnings.size(), blocks != 0 ? 1u : 0u) << blocks;
        if (blocks != 0) {
            EXPECT_EQ(o.warnings[0].code, "Bottleneck");
        }
    }
    // A program that does not validate runs nothing.
    apci::Board board("emu:");
    Collect sink;
    auto out = run_program(board, sink, in, ProgramSource::in_memory("N10 G1 Q5\n", "q.nc"),
                           RunSettings{});
    ASSERT_FALSE(out);
    EXPECT_EQ(out.error().line, 1u);
    EXPECT_TRUE(sink.segments.empty());
}

// The spike run on a fresh board where a finding is the run's error, with or without threads.
nc::Result<RunOutcome> run_spike_stopping(const RunInputs& in, bool threads, Collect& sink) {
    apci::Board board("emu:");
    RunSettings settings;
    settings.self_approach = SelfApproachMode::kError;
    settings.threads = threads;
    return run_program(board, sink, in, ProgramSource::in_memory(kSpike, "spike.nc"), settings);
}

// --self-approach error: the run's error is the first finding, at the block whose path came
// near (not the contour's block), in the finding's words, and the only one; no warning. The
// same with threads (the check before the pipeline) and without.
TEST(RunProgram, ASelfApproachErrorIsTheFirstFindingAtItsPathsBlockAndTheLast) {
    const RunInputs in = tool5();
    for (const bool threads : {false, true}) {
        Collect sink;
        auto out = run_spike_stopping(in, threads, sink);
        ASSERT_TRUE(out) << out.error().to_string();
        const RunOutcome& o = out.value();
        ASSERT_EQ(o.errors.size(), 1u) << "threads " << threads;
        ASSERT_EQ(o.self_approach.size(), 1u) << "threads " << threads;
        const SelfApproachFinding& f = o.self_approach[0];
        // The path of N50 comes within the radius of N70's contour (programmed ahead of it).
        EXPECT_EQ(f.path_block.number, 50);
        EXPECT_EQ(f.contour_block.number, 70);
        EXPECT_EQ(o.errors[0].code, "SelfApproach");
        EXPECT_EQ(o.errors[0].block.number, 50);
        EXPECT_EQ(o.errors[0].block.line, 4u);
        EXPECT_EQ(o.errors[0].message, describe(f));
        EXPECT_TRUE(o.warnings.empty());
        EXPECT_TRUE(sink.warnings.empty());
    }
}

// Where the run stops at a finding, the segments the board still runs of the move under way
// (here the temperature compensation switched off at N80 keeps the clock going) are not
// checked into a second error: the run has one error, its first finding.
TEST(RunProgram, ASelfApproachErrorIsTheOnlyErrorWhileTheAxesFinishTheMove) {
    test_support::ScratchDir dir;
    RunInputFiles files;
    files.tools = kTool5;
    files.tools_is_text = true;
    files.plc = test_support::write_text(dir.file("p.plc"), "block 80 tool_temp_comp_on 0\n");
    auto in = load_run_inputs(files);
    ASSERT_TRUE(in) << in.error().to_string();
    for (const bool threads : {false, true}) {
        Collect sink;
        auto out = run_spike_stopping(in.value(), threads, sink);
        ASSERT_TRUE(out) << out.error().to_string();
        const RunOutcome& o = out.value();
        ASSERT_EQ(o.errors.size(), 1u) << "threads " << threads;
        EXPECT_EQ(o.errors[0].code, "SelfApproach");
        EXPECT_EQ(o.errors[0].block.number, 50);
        ASSERT_EQ(o.self_approach.size(), 1u) << "threads " << threads;
        EXPECT_EQ(o.self_approach[0].contour_block.number, 70);
    }
}

// A turning tool (docs/compensation.md "Turning tools"): the board reports the imaginary tip's
// path, the check measures the nose centre's. The spike turned into G18 (Z-X, mirrored, so G41
// for its G42) with cutting edge 3 (the tip carried by +r on X and -r on Z: unlike on the two
// axes) has the findings of the same tool with the nose centre as its path (cutting edge 9), at
// the same distances.
TEST(RunProgram, TheCheckMeasuresATurningToolsNoseCentreNotItsTip) {
    std::string turned = kSpike;
    std::replace(turned.begin(), turned.end(), 'Y', 'Z');
    turned.replace(turned.find("G17"), 3, "G18");
    turned.replace(turned.find("G42"), 3, "G41");  // Z-X mirrors X-Y: the same side of it
    const auto findings = [&](int edge) {
        RunInputFiles f;
        f.tools =
            "wz[1].gueltig 1\nwz[1].typ 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n"
            "wz[1].srk_lage " +
            std::to_string(edge) + "\n";
        f.tools_is_text = true;
        auto in = load_run_inputs(f);
        EXPECT_TRUE(in) << in.error().to_string();
        if (!in) return std::vector<SelfApproachFinding>{};
        apci::Board board("emu:");
        Collect sink;
        auto out = run_program(board, sink, in.value(),
                               ProgramSource::in_memory(turned, "turned.nc"), RunSettings{});
        EXPECT_TRUE(out) << out.error().to_string();
        if (out) {
            for (const RunError& e : out.value().errors) ADD_FAILURE() << e.message;
        }
        return out ? out.value().self_approach : std::vector<SelfApproachFinding>{};
    };
    const std::vector<SelfApproachFinding> centre = findings(9);
    const std::vector<SelfApproachFinding> tip = findings(3);
    ASSERT_FALSE(centre.empty());
    ASSERT_EQ(tip.size(), centre.size());
    for (std::size_t i = 0; i < tip.size(); ++i) {
        EXPECT_EQ(tip[i].path_block.number, centre[i].path_block.number) << i;
        EXPECT_EQ(tip[i].contour_block.number, centre[i].contour_block.number) << i;
        EXPECT_NEAR(tip[i].distance, centre[i].distance, 1e-9) << i;
        EXPECT_LT((tip[i].where - centre[i].where).norm(), 1e-9) << i;
    }
}

// With threads the NC front end runs on a thread of its own and the caller's sink on another
// while the board runs; without, everything on the caller's thread. The program is longer than
// the reader may run ahead (read_ahead.h) beyond all that the two pipelines' rings hold
// (pipeline.h; a line gives at least one event), so the reader is still there when the first
// segment comes back, however late the helper threads get their turn.
TEST(RunProgram, ThreadsRunTheFrontEndTheCheckAndTheSinkOnThreadsOfTheirOwn) {
    struct Threads final : RunSink {
        int most = 0;
        std::thread::id thread;
        void executed(const PathSegment&) override {
            most = std::max(most, apci::test::thread_count());
            thread = std::this_thread::get_id();
        }
    };
    const int before = apci::test::baseline_thread_count();
    const RunInputs in = tool5();
    constexpr std::size_t kLines = ReadAhead::kBatches * ReadAhead::kBatchEvents +
                                   2 * PipelinedSink::kBatches * PipelinedSink::kBatchEvents +
                                   2 * PipelinedSink::kBatchEvents;
    std::string zigzag = "N1 G17 G90 G1 F60000\n";
    for (std::size_t i = 0; i < kLines; ++i)
        zigzag += "G1 X" + std::to_string(i % 2) + " Y" + std::to_string(i) + "\n";
    zigzag += "M30\n";
    // The reader and the writers; with the check warning (the default), the check on a third
    // (ProgramRun::chain). With the check stopping the run, it runs on the caller's thread.
    for (const SelfApproachMode mode :
         {SelfApproachMode::kWarn, SelfApproachMode::kOff, SelfApproachMode::kError}) {
        for (const bool threads : {false, true}) {
            apci::Board board("emu:");
            Threads sink;
            RunSettings settings;
            settings.threads = threads;
            settings.self_approach = mode;
            auto out = run_program(board, sink, in, ProgramSource::in_memory(zigzag, "zigzag.nc"),
                                   settings);
            ASSERT_TRUE(out) << out.error().to_string();
            const int helpers = !threads ? 0 : mode == SelfApproachMode::kWarn ? 3 : 2;
            EXPECT_EQ(sink.most, before + helpers)
                << "threads " << threads << " mode " << static_cast<int>(mode);
            EXPECT_EQ(sink.thread == std::this_thread::get_id(), !threads);
        }
    }
}

}  // namespace
}  // namespace apci::run
