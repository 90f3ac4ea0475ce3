// SPDX-License-Identifier: MIT
// The NC front end on a thread of its own (read_ahead.h): the executor reads the same events,
// with the same counts, the same end or error at the same place, the board's variables as they
// are after every earlier event, through a bounded ring; an early stop ends the reader (joined,
// no hang) and leaves the stream to nc::SinglePass::finish as it was.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "apci/apci.hpp"
#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "apci/run/executor.h"
#include "apci/run/json_writer.h"
#include "apci/run/read_ahead.h"
#include "memory_file.h"
#include "plate_program.h"
#include "thread_count.h"

namespace apci::run {
namespace {

using namespace std::chrono_literals;
using Next = nc::EventStream::Next;

using apci::test::baseline_thread_count;
using apci::test::thread_count;

// One event as text: its kind, block, line and end point (moves).
std::string describe(const nc::Event& ev) {
    std::string t = std::string(nc::event_name(ev.data)) + " N" + std::to_string(ev.origin.block) +
                    " L" + std::to_string(ev.origin.line);
    std::visit(
        [&](const auto& e) {
            if constexpr (requires { e.end; })
                t += " " + std::to_string(e.end.x()) + "," + std::to_string(e.end.y()) + "," +
                     std::to_string(e.end.z());
        },
        ev.data);
    return t;
}

// Everything the executor reads of a source (an EventStream or a ReadAhead), event by event.
template <typename Source>
std::vector<std::string> read_all(Source& source, Next& last) {
    std::vector<std::string> seen;
    nc::Event ev;
    for (;;) {
        last = source.next(ev);
        if (last != Next::kEvent) break;
        seen.push_back(describe(ev) + " b" + std::to_string(source.blocks_read()) + " o" +
                       std::to_string(source.offset()) + " d" +
                       std::to_string(static_cast<int>(source.dialect())));
    }
    if (last == Next::kError) seen.push_back("error " + source.error().to_string());
    return seen;
}

// What the stream itself gives of `text` (no read-ahead), and how it ends.
std::vector<std::string> read_directly(const std::string& text, const char* name, Next& last) {
    nc::EventStream direct = nc::EventStream::from_text(text, name);
    return read_all(direct, last);
}

std::string many_blocks(int n) {
    std::string text = "%many\nN1 G17 G90 F3000\n";
    for (int i = 0; i < n; ++i)
        text += "N" + std::to_string(i + 2) + (i % 3 == 0 ? " G0" : " G1") + " X" +
                std::to_string(i % 97) + " Y" + std::to_string(i % 13) + "\n";
    return text + "M30\n";
}

TEST(ReadAhead, EveryEventArrivesInOrderWithTheStreamsCounts) {
    const std::string text = many_blocks(5000);  // many batches
    Next direct_last{};
    const std::vector<std::string> expected = read_directly(text, "p.nc", direct_last);
    nc::EventStream stream = nc::EventStream::from_text(text, "p.nc");
    ReadAhead ahead(stream);
    Next last{};
    const std::vector<std::string> got = read_all(ahead, last);
    EXPECT_EQ(direct_last, Next::kEnd);
    EXPECT_EQ(last, Next::kEnd);
    EXPECT_GT(expected.size(), 5000u);
    EXPECT_EQ(got, expected);
    nc::Event ev;
    EXPECT_EQ(ahead.next(ev), Next::kEnd);  // and stays ended
}

TEST(ReadAhead, KlartextComesWithItsDialect) {
    const std::string text =
        "0 BEGIN PGM K MM\n1 L X+0 Y+0 Z+0 R0 F1000\n2 L X+10\n3 L Y+20 FMAX\n4 END PGM K MM\n";
    Next direct_last{};
    const std::vector<std::string> expected = read_directly(text, "k.h", direct_last);
    nc::EventStream stream = nc::EventStream::from_text(text, "k.h");
    ReadAhead ahead(stream);
    Next last{};
    EXPECT_EQ(read_all(ahead, last), expected);
    EXPECT_EQ(last, direct_last);
    EXPECT_EQ(ahead.dialect(), nc::Dialect::kKlartext);
}

// A line that does not parse: every event before it, then the same error; the stream is the
// caller's again.
TEST(ReadAhead, AnErrorLineInTheMiddleComesAfterTheEventsBeforeIt) {
    std::string text = many_blocks(3000);
    text.insert(text.find("N1500 "), "N1499 G1 Q7\n");
    Next direct_last{};
    const std::vector<std::string> expected = read_directly(text, "p.nc", direct_last);
    ASSERT_EQ(direct_last, Next::kError);
    nc::EventStream stream = nc::EventStream::from_text(text, "p.nc");
    ReadAhead ahead(stream);
    Next last{};
    EXPECT_EQ(read_all(ahead, last), expected);
    EXPECT_EQ(last, Next::kError);
    EXPECT_NE(expected.back().find("unknown word 'Q'"), std::string::npos) << expected.back();
}

// The reader runs ahead by the ring's events at most, however long the program.
TEST(ReadAhead, TheReaderWaitsOnTheBoundedRing) {
    const std::string text = many_blocks(100000);
    nc::EventStream stream = nc::EventStream::from_text(text, "p.nc");
    const int threads = baseline_thread_count();
    {
        ReadAhead ahead(stream);
        nc::Event ev;
        ASSERT_EQ(ahead.next(ev), Next::kEvent);
        EXPECT_EQ(thread_count(), threads + 1);
        std::this_thread::sleep_for(300ms);  // the reader fills the ring and waits
        ahead.stop();
        EXPECT_EQ(thread_count(), threads);
        EXPECT_EQ(ahead.next(ev), Next::kEnd);  // stopped
    }
    // Read by the reader (the caller's again after stop()): the ring's batches and the event
    // that waited for room.
    EXPECT_LE(stream.events_read(), ReadAhead::kBatches * ReadAhead::kBatchEvents + 1);
    EXPECT_GT(stream.events_read(), ReadAhead::kBatchEvents);
    nc::Event ev;
    EXPECT_EQ(stream.next(ev), Next::kEvent);  // between two events: it reads on
}

// An executor that waits has the reader 8,192 events ahead (64 batches of 128, docs/apcictl.md):
// a reader woken for room still has milliseconds of the executor's work in the ring to get a
// CPU (docs/performance.md, "A deeper read-ahead").
TEST(ReadAhead, TheReaderFillsItsWholeRingWhileTheExecutorWaits) {
    const std::string text = many_blocks(100000);
    nc::EventStream stream = nc::EventStream::from_text(text, "p.nc");
    {
        ReadAhead ahead(stream);
        nc::Event ev;
        ASSERT_EQ(ahead.next(ev), Next::kEvent);
        // The reader sleeps when every batch is taken.
        for (int i = 0; i < 2000 && ahead.reader_waits() == 0; ++i)
            std::this_thread::sleep_for(5ms);
        ASSERT_GT(ahead.reader_waits(), 0u) << "the reader never found the ring full";
        ahead.stop();
    }
    EXPECT_GE(stream.events_read(), 8192u);
}

// begin() starts the reader before the first next(), once: a second begin(), and the first
// next(), start no other; the events are those of the stream, in order.
TEST(ReadAhead, BeginStartsTheReaderOnce) {
    const std::string text = many_blocks(10000);  // more than the ring holds
    Next direct_last{};
    const std::vector<std::string> expected = read_directly(text, "p.nc", direct_last);
    nc::EventStream stream = nc::EventStream::from_text(text, "p.nc");
    const int threads = baseline_thread_count();
    ReadAhead ahead(stream);
    EXPECT_EQ(thread_count(), threads);  // made, not started
    ahead.begin();
    EXPECT_EQ(thread_count(), threads + 1);
    // The reader reads on its own before the first next(), until the ring is full.
    for (int i = 0; i < 2000 && ahead.reader_waits() == 0; ++i) std::this_thread::sleep_for(5ms);
    EXPECT_GT(ahead.reader_waits(), 0u);
    ahead.begin();
    EXPECT_EQ(thread_count(), threads + 1);
    Next last{};
    EXPECT_EQ(read_all(ahead, last), expected);
    EXPECT_EQ(last, Next::kEnd);
    EXPECT_EQ(thread_count(), threads);  // ended and joined
    ahead.begin();                       // after the end: nothing
    EXPECT_EQ(thread_count(), threads);
}

// Stopped before it began, a read-ahead starts nothing again: begin() makes no thread, next()
// ends, and the stream was not read.
TEST(ReadAhead, BeginAfterStopStartsNothing) {
    nc::EventStream stream = nc::EventStream::from_text(many_blocks(100), "p.nc");
    const int threads = baseline_thread_count();
    ReadAhead ahead(stream);
    ahead.stop();
    ahead.begin();
    EXPECT_EQ(thread_count(), threads);
    nc::Event ev;
    EXPECT_EQ(ahead.next(ev), Next::kEnd);
    EXPECT_EQ(stream.events_read(), 0u);
}

// The variable source is the caller's to set before the reader runs, or after it ended: while
// it may run (begun) it is refused, and the reader goes on as it was.
TEST(ReadAhead, TheVariableSourceIsNotSetWhileTheReaderRuns) {
    const std::string text = many_blocks(300);
    Next direct_last{};
    const std::vector<std::string> expected = read_directly(text, "p.nc", direct_last);
    nc::EventStream stream = nc::EventStream::from_text(text, "p.nc");
    ReadAhead ahead(stream);
    nc::VariableSource* none = nullptr;
    ahead.set_variable_source(none);  // before it runs: taken
    ahead.begin();
    EXPECT_THROW(ahead.set_variable_source(none), std::logic_error);
    Next last{};
    EXPECT_EQ(read_all(ahead, last), expected);
    ahead.set_variable_source(none);  // ended: taken
}

// The ring's items are carved once, the first time round: a program three times the ring's
// events takes the read-ahead one block of memory, as a short one does.
TEST(ReadAhead, TheRingGoesRoundOnTheItemsItCarvedOnce) {
    const int blocks = static_cast<int>(3 * ReadAhead::kBatches * ReadAhead::kBatchEvents);
    const std::string text = many_blocks(blocks);
    Next direct_last{};
    const std::vector<std::string> expected = read_directly(text, "p.nc", direct_last);
    nc::EventStream stream = nc::EventStream::from_text(text, "p.nc");
    ReadAhead ahead(stream);
    Next last{};
    EXPECT_EQ(read_all(ahead, last), expected);
    EXPECT_EQ(last, Next::kEnd);
    EXPECT_EQ(ahead.item_blocks(), 1u);
}

// A board whose variable is what the caller has taken so far, read on the caller's thread.
struct Counting final : nc::VariableSource {
    std::uint64_t taken = 0;
    std::thread::id caller = std::this_thread::get_id();
    int wrong_thread = 0;
    int reads = 0;
    bool read(const nc::VariableRef&, double& out, std::string&) override {
        ++reads;
        if (std::this_thread::get_id() != caller) ++wrong_thread;
        out = static_cast<double>(taken);
        return true;
    }
};

// A variable read waits until every event before it was taken (executed), and is served on the
// caller's thread: the program sees the board as it is after them.
TEST(ReadAhead, AVariableIsReadAfterEveryEarlierEventWasTaken) {
    std::string text = "N1 G1 X1 F100\nN2 G1 X2\nN3 G1 X3\nP1 = V.G.WZ_AKT.WEAR.Z\nN4 G1 X[P1]\n";
    for (int i = 0; i < 400; ++i)
        text += "N" + std::to_string(10 + i) + " G1 Y" + std::to_string(i) + "\n";
    text += "P2 = V.G.WZ_AKT.WEAR.Z\nN999 G1 Z[P2]\nM30\n";
    nc::EventStream stream = nc::EventStream::from_text(text, "v.nc");
    ReadAhead ahead(stream);
    Counting board;
    ahead.set_variable_source(&board);
    nc::Event ev;
    std::vector<double> ends;
    while (ahead.next(ev) == Next::kEvent) {
        ++board.taken;
        if (const auto* l = std::get_if<nc::LineMove>(&ev.data)) {
            if (ev.origin.block == 4) ends.push_back(l->end.x());
            if (ev.origin.block == 999) ends.push_back(l->end.z());
        }
    }
    EXPECT_EQ(board.reads, 2);
    EXPECT_EQ(board.wrong_thread, 0);
    // N4 moves to the number of events taken before it (3), N999 likewise (3 + 1 + 400).
    EXPECT_EQ(ends, (std::vector<double>{3.0, 404.0}));
    ahead.set_variable_source(nullptr);
    EXPECT_TRUE(stream.read_variable_source());
}

// A variable the board cannot give: the same error at the same line as without the read-ahead,
// after the events before it.
TEST(ReadAhead, AVariableTheBoardCannotGiveIsTheSameError) {
    struct Refusing final : nc::VariableSource {
        bool read(const nc::VariableRef&, double&, std::string& why) override {
            why = "not on this board";
            return false;
        }
    };
    std::string text = many_blocks(700);
    text.insert(text.rfind("M30"), "P1 = V.G.WZ_AKT.WEAR_RADIUS\nG0 X[P1]\n");
    Refusing direct_board, board;
    nc::EventStream direct = nc::EventStream::from_text(text, "r.nc");
    direct.set_variable_source(&direct_board);
    Next direct_last{};
    const std::vector<std::string> expected = read_all(direct, direct_last);
    ASSERT_EQ(direct_last, Next::kError);
    EXPECT_NE(expected.back().find("V.G.WZ_AKT.WEAR_RADIUS cannot be read: not on this board"),
              std::string::npos)
        << expected.back();
    nc::EventStream stream = nc::EventStream::from_text(text, "r.nc");
    ReadAhead ahead(stream);
    ahead.set_variable_source(&board);
    Next last{};
    EXPECT_EQ(read_all(ahead, last), expected);
    EXPECT_EQ(last, Next::kError);
}

// ---- through the executor

nc::ToolTable plate_tools(double radius) {
    auto tools = nc::parse_tool_table(
        "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius " + std::to_string(radius) + "\n",
        "t.tools");
    EXPECT_TRUE(tools);
    return tools.value();
}

// The JSON of the executed path, the programmed moves, the progress calls and the errors.
class Everything final : public RunSink {
  public:
    explicit Everything(std::FILE* json) : json_(json) {}
    std::vector<std::string> programmed_moves, progress_calls, errors;
    void programmed(const PathSegment& s) override {
        programmed_moves.push_back(std::to_string(s.block.number) + "@" +
                                   std::to_string(s.end.x()));
    }
    bool wants_programmed() const override { return true; }
    void executed(const PathSegment& s) override { json_.segment(s); }
    void error(const RunError& e, const Point&) override { errors.push_back(e.code + e.message); }
    void progress(std::uint64_t blocks, std::uint64_t offset) override {
        progress_calls.push_back(std::to_string(blocks) + "/" + std::to_string(offset));
    }
    bool finish(const RunOutcome& out) {
        return json_.finish(out.errors, out.registers, out.variables, out.notices, out.warnings);
    }

  private:
    JsonRunWriter json_;
};

struct RunResult {
    std::string json, summary;
    std::vector<std::string> programmed, progress, errors;
    bool read_variables = false;
    std::string finished;  // SinglePass::finish(): the summary or the error
};

RunResult run_one_pass(const std::string& text, const nc::ToolTable& tools, bool read_ahead) {
    apci::Board board("emu:");
    apci_test::MemoryFile json;
    Everything sink(json.get());
    ProgramExecutor executor(board, sink, &tools);
    executor.set_read_ahead(read_ahead);
    nc::InterpreterOptions options;
    options.tools = &tools;
    options.start_position = executor.position();
    options.cycle_seconds = executor.cycle_seconds();
    nc::SinglePass pass = nc::SinglePass::from_text(text, "p.nc", options);
    const RunOutcome out = executor.run(pass.events());
    EXPECT_TRUE(sink.finish(out));
    RunResult r;
    r.json = json.text();
    r.summary = std::to_string(out.totals.blocks_executed) + " " +
                std::to_string(out.totals.segments) + " " + std::to_string(out.totals.cycles);
    r.programmed = sink.programmed_moves;
    r.progress = sink.progress_calls;
    r.errors = sink.errors;
    r.read_variables = pass.events().read_variable_source();
    auto finished = pass.finish();
    r.finished = finished ? std::to_string(finished.value().blocks) + " blocks " +
                                std::to_string(finished.value().events) + " events"
                          : finished.error().to_string();
    return r;
}

void expect_same(const RunResult& a, const RunResult& b) {
    EXPECT_EQ(a.json, b.json);
    EXPECT_EQ(a.summary, b.summary);
    EXPECT_EQ(a.programmed, b.programmed);
    EXPECT_EQ(a.progress, b.progress);
    EXPECT_EQ(a.errors, b.errors);
    EXPECT_EQ(a.read_variables, b.read_variables);
    EXPECT_EQ(a.finished, b.finished);
}

TEST(ReadAheadRun, AProgramRunsTheSameWithTheFrontEndOnItsOwnThread) {
    const nc::ToolTable tools = plate_tools(1.0);
    const std::string text = apci::test::plate_program(800);  // > kProgressEvery events
    const RunResult direct = run_one_pass(text, tools, false);
    const RunResult ahead = run_one_pass(text, tools, true);
    EXPECT_GT(direct.json.size(), 500000u);
    EXPECT_GE(direct.progress.size(), 2u);
    expect_same(ahead, direct);
}

TEST(ReadAheadRun, AnErrorLineInTheMiddleStopsTheRunWhereItDid) {
    const nc::ToolTable tools = plate_tools(1.0);
    std::string text = apci::test::plate_program(300);
    text.insert(text.find("N2000 "), "N1999 G1 X10 Q3\n");
    const RunResult direct = run_one_pass(text, tools, false);
    const RunResult ahead = run_one_pass(text, tools, true);
    ASSERT_EQ(direct.errors.size(), 1u);
    EXPECT_NE(direct.errors[0].find("unknown word 'Q'"), std::string::npos) << direct.errors[0];
    EXPECT_NE(direct.finished.find("unknown word 'Q'"), std::string::npos) << direct.finished;
    expect_same(ahead, direct);
}

// [ISG-OTC] section 2.8: the program reads the wear the move before it made (on the board, on
// the caller's thread, after the move ran): P1 * 10 = 50 mm.
TEST(ReadAheadRun, AProgramReadsTheWearAMoveBeforeItMade) {
    auto tools =
        nc::load_tool_table(std::string(APCI_SOURCE_DIR) + "/examples/tools/wr_quad_disc.tools");
    ASSERT_TRUE(tools) << tools.error().to_string();
    const std::string text =
        "N10 D1\nN15 G0 Z0\nN20 #OTC ON\nN30 G1 X500 F10000\nN40 #OTC OFF\n"
        "N50 P1 = V.G.WZ_AKT.WEAR.Z\nN60 P2 = V.G.OTC_ACTIVE\nN70 G0 X[P1 * 10] Y[P2]\nM30\n";
    const RunResult direct = run_one_pass(text, tools.value(), false);
    const RunResult ahead = run_one_pass(text, tools.value(), true);
    EXPECT_TRUE(direct.read_variables);
    EXPECT_TRUE(direct.errors.empty()) << direct.errors.front();
    ASSERT_FALSE(direct.programmed.empty());
    const std::string& last = direct.programmed.back();
    ASSERT_EQ(last.substr(0, 3), "70@");
    EXPECT_NEAR(std::stod(last.substr(3)), 50.0, 1e-6);
    expect_same(ahead, direct);
}

// A board error early in a long program: the reader, still producing (or waiting on a
// variable read right after the error), is stopped and joined; the run ends as without it, and
// SinglePass::finish reads the rest.
TEST(ReadAheadRun, AnEarlyBoardErrorStopsTheReaderWithoutAHang) {
    const nc::ToolTable tools = plate_tools(5.0);
    std::string tail;
    for (int i = 0; i < 20000; ++i)
        tail += "N" + std::to_string(200 + i) + " G1 X" + std::to_string(i % 50) + "\n";
    for (const std::string& after_error :
         {std::string(), std::string("N65 P1 = V.G.WZ_AKT.WEAR.Z\nN66 G1 X[P1 + 1]\n")}) {
        const std::string text = "N10 F1000 D1\nN40 G41 G1 X0 Y0\nN50 X60\nN60 Y2\n" + after_error +
                                 "N70 X0\nN100 G40 G1 X0 Y-20\n" + tail + "M30\n";
        const int threads = baseline_thread_count();
        const RunResult direct = run_one_pass(text, tools, false);
        const auto start = std::chrono::steady_clock::now();
        const RunResult ahead = run_one_pass(text, tools, true);
        EXPECT_LT(std::chrono::steady_clock::now() - start, 20s);
        EXPECT_EQ(thread_count(), threads);
        ASSERT_EQ(direct.errors.size(), 1u);
        EXPECT_EQ(direct.errors[0].substr(0, 9), "KorrError");
        // The plot draws the rest reading the board's variables, as it always did.
        EXPECT_EQ(direct.read_variables, !after_error.empty());
        EXPECT_NE(direct.finished.find(" blocks "), std::string::npos) << direct.finished;
        expect_same(ahead, direct);
    }
}

// The same with no plot: the rest is not drawn, the reader is stopped at once; a variable read
// it waits on right after the error is withdrawn (the stream reads it with its own view, as
// SinglePass::finish reads the rest without the read-ahead), so the pass does not count as one
// that read the board.
TEST(ReadAheadRun, AnEarlyBoardErrorWithoutAPlotStopsTheReader) {
    const nc::ToolTable tools = plate_tools(5.0);
    std::string tail;
    for (int i = 0; i < 50000; ++i)
        tail += "N" + std::to_string(200 + i) + " G1 X" + std::to_string(i % 50) + "\n";
    for (const std::string& after_error :
         {std::string(), std::string("N65 P1 = V.G.WZ_AKT.WEAR.Z\nN66 G1 X[P1 + 1]\n")}) {
        const std::string text = "N10 F1000 D1\nN40 G41 G1 X0 Y0\nN50 X60\nN60 Y2\n" + after_error +
                                 "N70 X0\nN100 G40 G1 X0 Y-20\n" + tail + "M30\n";
        class Quiet final : public RunSink {
        } quiet;
        const int threads = baseline_thread_count();
        std::vector<std::string> finished;
        for (const bool read_ahead : {false, true}) {
            apci::Board board("emu:");
            ProgramExecutor executor(board, quiet, &tools);
            executor.set_read_ahead(read_ahead);
            nc::InterpreterOptions options;
            options.tools = &tools;
            nc::SinglePass pass = nc::SinglePass::from_text(text, "p.nc", options);
            const RunOutcome out = executor.run(pass.events());
            EXPECT_EQ(thread_count(), threads);
            ASSERT_EQ(out.errors.size(), 1u);
            EXPECT_EQ(out.errors[0].code, "KorrError");
            EXPECT_LE(pass.events().events_read(),
                      20u + ReadAhead::kBatches * ReadAhead::kBatchEvents);
            EXPECT_FALSE(pass.events().read_variable_source()) << read_ahead;
            auto s = pass.finish();
            ASSERT_TRUE(s) << s.error().to_string();
            EXPECT_EQ(s.value().blocks, 50007u + (after_error.empty() ? 0u : 2u));
            finished.push_back(std::to_string(s.value().events) + " " +
                               std::to_string(s.value().lines));
        }
        EXPECT_EQ(finished[0], finished[1]);
    }
}

}  // namespace
}  // namespace apci::run
