// SPDX-License-Identifier: MIT
// A run whose board goes away (the daemon stops): the run has one error, the call that found
// the link lost, and the board is not asked again (the clock run to the end, the registers):
// every later call would fail the same way and name the same cause a second time.
#include <gtest/gtest.h>
#include <signal.h>

#include <string>

#include "apci/apci.hpp"
#include "apci/nc/program.h"
#include "apci/run/board_words.h"
#include "apci/run/executor.h"
#include "apci/run/program_run.h"
#include "daemon.h"

namespace {

using apci::run::board_words;
using apci::run::kLostLinkHint;
using apci::run::ProgramExecutor;
using apci::run::RunOutcome;
using apci::run::RunSink;
using apci_test::Daemon;

// Stops the daemon once, at the first progress call (the run is under way, between two blocks),
// at the program's CDOF (the sink's walls(false): the next block's board call is the first to
// find the link lost) or at the first executed segment given to it (it asks for samples then,
// as a CSV's run does).
class StopsTheDaemon final : public RunSink {
  public:
    enum class At { kProgress, kCdof, kFirstSegment };
    explicit StopsTheDaemon(Daemon& d, At at = At::kProgress) : daemon_(d), at_(at) {}
    bool wants_samples() const override { return at_ == At::kFirstSegment; }
    void progress(std::uint64_t, std::uint64_t) override {
        if (at_ == At::kProgress) stop();
    }
    void walls(bool on) override {
        if (at_ == At::kCdof && !on) stop();
    }
    void executed(const apci::run::PathSegment&) override {
        if (at_ == At::kFirstSegment) stop();
    }
    bool stopped() const { return stopped_; }

  private:
    void stop() {
        if (stopped_) return;
        stopped_ = true;
        (void)daemon_.stop(SIGKILL);
    }
    Daemon& daemon_;
    At at_;
    bool stopped_ = false;
};

std::string back_and_forth(int moves) {
    std::string text = "N1 G1 F60000\n";
    for (int i = 0; i < moves; ++i) text += i % 2 == 0 ? "X1\n" : "X0\n";
    return text + "M30\n";
}

TEST(RunLostLink, TheCallThatFoundTheLinkLostIsTheRunsOneError) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    apci::Board board(d->unix_uri());
    ASSERT_TRUE(board) << board.last_error();
    StopsTheDaemon sink(*d);
    ProgramExecutor executor(board, sink, nullptr);
    apci::nc::InterpreterOptions options;
    options.start_position = executor.position();
    options.cycle_seconds = executor.cycle_seconds();
    const std::string text = back_and_forth(2 * static_cast<int>(ProgramExecutor::kProgressEvery));
    auto program = apci::nc::Program::from_text(text, "p.nc", options);
    ASSERT_TRUE(program) << program.error().to_string();
    auto events = program.value().events();
    ASSERT_TRUE(events);
    const RunOutcome out = executor.run(events.value());
    ASSERT_TRUE(sink.stopped()) << (out.errors.empty() ? "no error" : out.errors[0].message);
    EXPECT_FALSE(board.connected());
    ASSERT_EQ(out.errors.size(), 1u);
    EXPECT_EQ(out.errors[0].code, "TransportError");
    // The block the run was at when it found the link lost: after the progress call.
    EXPECT_GT(out.errors[0].block.line, ProgramExecutor::kProgressEvery);
    // What ended the link, then the tools' hint (board_words), not the C API's.
    const std::string& said = out.errors[0].message;
    EXPECT_NE(said.find(board.link_lost() + "; " + std::string(kLostLinkHint)), std::string::npos)
        << said;
    EXPECT_EQ(said.find("apci_reconnect"), std::string::npos) << said;
}

// Samples recorded (a CSV's run), the link lost while the executed segments of a clock call are
// given to the sink (the daemon stopped at the first one): the segments were read whole (a
// clock call leaves at most the board's 256 queued moves, one read's worth), so the next call,
// the trace's read, finds the link lost, and it is the run's one error.
TEST(RunLostLink, ALinkLostAsTheSegmentsAreGivenIsTheOneErrorWhileTracing) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    apci::Board board(d->unix_uri());
    ASSERT_TRUE(board) << board.last_error();
    StopsTheDaemon sink(*d, StopsTheDaemon::At::kFirstSegment);
    apci::run::RunInputFiles files;
    files.tools = "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 0.2\n";
    files.tools_is_text = true;
    auto inputs = apci::run::load_run_inputs(files);
    ASSERT_TRUE(inputs) << inputs.error().to_string();
    // A compensated square wave, long enough to fill the board's queue.
    std::string text = "N10 D1 F60000\nN20 G41 G1 X0 Y0\n";
    for (int i = 0; i < 1000; ++i)
        text += std::string(i % 2 == 0 ? "X10" : "X0") + " Y" + std::to_string(i + 1) + "\n";
    text += "G40 G1 X-5 Y0\nM30\n";
    auto ran = apci::run::run_program(board, sink, inputs.value(),
                                      apci::run::ProgramSource::in_memory(text, "p.nc"), {});
    ASSERT_TRUE(ran) << ran.error().to_string();
    const RunOutcome& out = ran.value();
    ASSERT_TRUE(sink.stopped());
    EXPECT_FALSE(board.connected());
    ASSERT_EQ(out.errors.size(), 1u) << (out.errors.empty() ? "" : out.errors.back().message);
    EXPECT_EQ(out.errors[0].code, "TransportError");
    EXPECT_EQ(out.errors[0].message.rfind("read trace: ", 0), 0u) << out.errors[0].message;
}

// A run's own hint (RunSettings::lost_link_hint, the Python module's) in place of apcictl's: the
// settings reach the executor's errors.
TEST(RunLostLink, TheRunsSettingsNameItsOwnHint) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    apci::Board board(d->unix_uri());
    ASSERT_TRUE(board) << board.last_error();
    StopsTheDaemon sink(*d);
    const apci::run::RunInputs inputs;
    apci::run::RunSettings settings;
    settings.lost_link_hint = "open it again by hand";
    const std::string text = back_and_forth(2 * static_cast<int>(ProgramExecutor::kProgressEvery));
    auto ran = apci::run::run_program(board, sink, inputs,
                                      apci::run::ProgramSource::in_memory(text, "p.nc"), settings);
    ASSERT_TRUE(ran) << ran.error().to_string();
    const RunOutcome& out = ran.value();
    ASSERT_TRUE(sink.stopped());
    ASSERT_EQ(out.errors.size(), 1u);
    EXPECT_EQ(out.errors[0].code, "TransportError");
    const std::string& said = out.errors[0].message;
    EXPECT_NE(said.find(board.link_lost() + "; open it again by hand"), std::string::npos) << said;
    EXPECT_EQ(said.find(kLostLinkHint), std::string::npos) << said;
    EXPECT_EQ(said.find("apci_reconnect"), std::string::npos) << said;
}

// Every place a run words a board call that found the link lost names the run's hint: a spool,
// the clock run, an object write (the TC's side, a variable written, OTC switched on), a
// variable read.
TEST(RunLostLink, EveryBoardCallOfARunNamesTheRunsHint) {
    // A grinding tool (type 2): #OTC ON needs one.
    const char* const kTools = "wz[1].gueltig 1\nwz[1].typ 2\nwz[1].mass_einheit 1\n"
                               "wz[1].radius 2\nwz[1].laenge 10\nwz[2].gueltig 1\n"
                               "wz[2].mass_einheit 1\nwz[2].radius 3\n";
    struct Probe {
        const char* what;
        const char* lines;  // after N10 D1 / N20 CDOF
    };
    for (const Probe& probe : {Probe{"a move", "N30 G1 X10 F1000\n"},
                               Probe{"the clock run before a tool change", "N30 D2\n"},
                               Probe{"a TC object written (G41's side)", "N30 G41\n"},
                               Probe{"a variable written", "N30 V.G.WZ_AKT.WEAR_CONST = 200000\n"},
                               Probe{"OTC switched on", "N30 #OTC ON [LENGTH]\nN40 G1 X10 F1000\n"},
                               Probe{"a variable read", "N30 P1 = V.G.OTC_ACTIVE\nN40 G1 X[P1 + 1] F1000\n"}}) {
        SCOPED_TRACE(probe.what);
        auto d = Daemon::start();
        ASSERT_NE(d, nullptr);
        apci::Board board(d->unix_uri());
        ASSERT_TRUE(board) << board.last_error();
        StopsTheDaemon sink(*d, StopsTheDaemon::At::kCdof);
        apci::run::RunInputFiles files;
        files.tools = kTools;
        files.tools_is_text = true;
        auto inputs = apci::run::load_run_inputs(files);
        ASSERT_TRUE(inputs) << inputs.error().to_string();
        apci::run::RunSettings settings;
        settings.lost_link_hint = "open it again by hand";
        const std::string text = std::string("N10 D1\nN20 CDOF\n") + probe.lines + "N90 M30\n";
        auto ran = apci::run::run_program(
            board, sink, inputs.value(), apci::run::ProgramSource::in_memory(text, "p.nc"),
            settings);
        ASSERT_TRUE(sink.stopped());
        std::string said;
        if (ran) {
            ASSERT_FALSE(ran.value().errors.empty());
            said = ran.value().errors[0].message;
        } else {
            said = ran.error().to_string();
        }
        EXPECT_NE(said.find(board.link_lost() + "; open it again by hand"), std::string::npos)
            << said;
        EXPECT_EQ(said.find(kLostLinkHint), std::string::npos) << said;
    }
}

// board_words: libapci's words unchanged while the link works (a refusal's own words).
TEST(RunLostLink, BoardWordsAreLibapcisWhileTheLinkWorks) {
    apci::Board board("emu:");
    ASSERT_TRUE(board) << board.last_error();
    auto bad = apci::object(1000, 0, 3, 0);
    EXPECT_EQ(board.write_int(bad, 1).status, APCI_READ_ONLY);
    EXPECT_FALSE(board.last_error().empty());
    EXPECT_EQ(board_words(board), std::string(board.last_error()));
}

}  // namespace
