// SPDX-License-Identifier: MIT
// `apcictl run`'s errors and usage: the board's errors with block and name, program errors that
// run nothing, exit codes, help, a program from standard input, the progress bar.
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>

#include "apcictl_run.h"

namespace {

using namespace apcictl_run_test;

// ---- Errors from the board: block and Table 4 name

TEST_F(ApcictlRun, KorrErrorIsReportedWithBlockAndNameAndTheRunStops) {
    const std::string prog = write("korr.nc",
                                   "N10 F1000 D1\nN40 G41 G1 X0 Y0\nN50 X60\nN60 Y2\nN70 X0\n"
                                   "N100 G40 G1 X0 Y-20\nN110 M30\n");
    const json doc = run_json(prog, {"--tools", tools(5.0), "--svg", path("k.svg")}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("block"), 60);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "KorrError");
    // The board's own words and what to change; not the driver's call, status or tag.
    EXPECT_EQ(doc.at("errors")[0].at("message"),
              "element is too short for the corner at its start: its offset would reverse "
              "(lengthen it, join it into its neighbour, or use a smaller tool)");
    EXPECT_EQ(doc.at("registers").at("1").at("ERROR_bits"), json::array({"KorrError"}));
    EXPECT_TRUE(contains(last_.out, "errors: 1 (KorrError 1)\n  line 4 (N60): KorrError: ")) << last_.out;
    EXPECT_TRUE(contains(last_.err, "apcictl: run " + prog + ": stopped at line 4 (N60): KorrError\n"))
        << last_.err;
    // The board holds: nothing spooled after the error ran.
    for (const auto& s : doc.at("segments")) EXPECT_LT(s.at("block").get<int>(), 70);
    const std::string svg = read_text(path("k.svg"));
    EXPECT_TRUE(contains(svg, ">N60 KorrError</text>"));
    // The rest of the program is still drawn, so the place of the error is seen.
    EXPECT_TRUE(contains(svg, "L0 20") || contains(svg, "L0 2"));
}

// The step N60 is long enough for the corner at its start (the offsets meet 5 mm up it) but
// not for the one at its end as well (N70's offset lies 3 mm up): the board refuses when N70
// comes, and names N60, the element that is too short, and the corner at its end.
TEST_F(ApcictlRun, AHeldElementTooShortIsNamedWithTheCornerAtItsEnd) {
    const std::string prog = write("korr_held.nc",
                                   "N10 F1000 D1\nN40 G41 G1 X0 Y0\nN50 X60\nN60 Y8\nN70 X0\n"
                                   "N100 G40 G1 X0 Y-20\nN110 M30\n");
    const json doc = run_json(prog, {"--tools", tools(5.0)}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("block"), 60);
    EXPECT_EQ(doc.at("errors")[0].at("message"),
              "element is too short for the corner at its end: its offset would reverse "
              "(lengthen it, join it into its neighbour, or use a smaller tool)");
    EXPECT_TRUE(contains(last_.out,
                         "  line 4 (N60): KorrError: element is too short for the "
                         "corner at its end"))
        << last_.out;
}

TEST_F(ApcictlRun, AnErrorInABlockWithoutNumberNamesItsLineNeverAnInternalTag) {
    // Blocks without N carry their line through the board's tag (2^31 + line): the message
    // names the line, and neither the tag nor the spool call's status.
    const std::string prog = write("korr_lines.nc",
                                   "F1000 D1\nG41 G1 X0 Y0\nX60\nY2\nX0\nG40 G1 X0 Y-20\nM30\n");
    const json doc = run_json(prog, {"--tools", tools(5.0)}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("line"), 4);
    EXPECT_TRUE(contains(last_.out, "\n  line 4: KorrError: element is too short for the corner"))
        << last_.out;
    EXPECT_TRUE(contains(last_.err, "stopped at line 4: KorrError")) << last_.err;
    for (const std::string& text : {last_.out, last_.err, doc.dump()}) {
        EXPECT_FALSE(contains(text, "2147483")) << text;
        EXPECT_FALSE(contains(text, "WrongDeviceState")) << text;
    }
}

TEST_F(ApcictlRun, CalcErrorForAConcaveArcSmallerThanTheTool) {
    const std::string prog = write("calc.nc",
                                   "N10 F1000 D1\nN40 G41 G1 X0 Y0\nN50 X20\nN60 G3 X24 Y4 I0 J4\n"
                                   "N70 G1 Y20\nN100 G40 G1 X40\nN110 M30\n");
    const json doc = run_json(prog, {"--tools", tools(5.0)}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("block"), 60);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "CalcError");
    // The board's words, and the radii they compare.
    EXPECT_TRUE(doc.at("errors")[0].at("message").get<std::string>().ends_with(
        "concave side: the tool would cut into the arc (use a tool no larger than the arc's "
        "radius); arc radius 4.0000 mm, tool radius 5.0000 mm"))
        << doc.at("errors")[0].at("message");
    EXPECT_TRUE(contains(last_.out, "; arc radius 4.0000 mm, tool radius 5.0000 mm")) << last_.out;
    // G42 on a clockwise arc a thousandth smaller than the tool: as near as a file writes it.
    const std::string near = write("calc42.nc",
                                   "N10 F1000 D1\nN40 G42 G1 X0 Y0\nN50 X20\n"
                                   "N60 G2 X24.999 Y-4.999 I0 J-4.999\nN70 G1 Y-20\n"
                                   "N100 G40 G1 X40\nN110 M30\n");
    const json doc42 = run_json(near, {"--tools", tools(5.0)}, 1);
    ASSERT_EQ(doc42.at("errors").size(), 1u);
    EXPECT_EQ(doc42.at("errors")[0].at("code"), "CalcError");
    EXPECT_TRUE(doc42.at("errors")[0].at("message").get<std::string>().ends_with(
        "; arc radius 4.9990 mm, tool radius 5.0000 mm"))
        << doc42.at("errors")[0].at("message");
}

TEST_F(ApcictlRun, CompensationWithoutTheTcOptionIsAnErrorNamingIt) {
    const std::string prog = write("g41.nc", "N10 F1000\nN20 G1 X5\nN30 G41 X10\nM30\n");
    const json doc = run_json(prog, {"--device", "emu:?no-option-tc"}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("block"), 30);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "NoSuchDevice");
    EXPECT_TRUE(contains(doc.at("errors")[0].at("message").get<std::string>(), "optionTC"));
    EXPECT_EQ(doc.at("registers"), json::object());
}

TEST_F(ApcictlRun, ProgramWithoutCompensationRunsWithoutTheTcOption) {
    const std::string prog = write("plain.nc", "N10 G1 X5 F600\nN20 G2 X10 Y0 I2.5 J0\nM30\n");
    const json doc = run_json(prog, {"--device", "emu:?no-option-tc"});
    EXPECT_EQ(roles(doc), "uncompensated/10 uncompensated/20");
    EXPECT_EQ(doc.at("segments")[1].at("kind"), "arc");
    EXPECT_EQ(doc.at("segments")[1].at("ccw"), false);
}


// ---- Program errors: nothing runs

TEST_F(ApcictlRun, ParseErrorNamesFileLineAndColumnAndRunsNothing) {
    const std::string prog = write("bad.nc", "N10 G1 X1 F100\nN20 G1 X\nM30\n");
    const auto r = apcictl({"run", prog, "--json", path("bad.json"), "--svg", path("bad.svg")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "apcictl: " + prog + ":2:9: N20: expected a number after 'X'\n");
    EXPECT_FALSE(exists(path("bad.json")));
    EXPECT_FALSE(exists(path("bad.svg")));
}

TEST_F(ApcictlRun, ToolNotInTheToolListSaysThatNoneWasGiven) {
    const std::string prog = write("d1.nc", "N10 D1\nM30\n");
    const auto r = apcictl({"run", prog});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err,
                         ":1:5: N10: D1 selects tool 1, which the tool list does not define "
                         "(no --tools file given)"))
        << r.err;
}

TEST_F(ApcictlRun, BadToolListNamesFileAndLine) {
    const std::string t = write("bad.tools", "wz[1].radius 5\nwz[1].typ 9\n");
    const auto r = apcictl({"run", kExamples + "/wr_quad_disc.nc", "--tools", t});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "bad.tools:2:")) << r.err;
}

// ---- Moves an earlier program left in a daemon's spooler

// A run that stopped at a compensation error leaves what it spooled before the error in the
// board's spooler, held. The next program on that board must not run them as its own (they ran
// under its block numbers, from a start it never programmed): its setup discards them, as a
// reset does, and says so.
TEST_F(ApcictlRun, MovesAnErrorLeftInADaemonsSpoolerAreDiscardedBeforeTheNextProgram) {
    const std::string socket = path("emu.sock");
    const pid_t daemon = start_daemon(socket);
    ASSERT_GT(daemon, 0);
    const std::string device = "unix:" + socket;
    const std::string calc = write("calc.nc",
                                   "N10 G17 G90 D1\nN20 G0 X-20 Y10\nN30 G1 G41 X0 Y10 F600\n"
                                   "N40 G1 X20\nN50 G3 X26 Y10 I3 J0\nN60 G1 X50\n"
                                   "N70 G40 G1 X70 Y30\nN90 M30\n");
    const std::string next =
        write("next.nc", "N10 D1\nN20 G1 G41 X20 F100\nN30 X40\nN40 G40 X50\nM30\n");
    const auto stopped = apcictl({"--device", device, "run", calc, "--tools", tools(5.0)});
    EXPECT_EQ(stopped.exit_code, 1) << stopped.err;
    EXPECT_TRUE(contains(stopped.out, "CalcError")) << stopped.out;
    const auto held = apcictl({"--device", device, "status"});
    EXPECT_TRUE(contains(held.out, "spooler 2 of 256 profiles")) << held.out;
    const json doc = run_json(next, {"--tools", tools(5.0), "--device", device});
    const std::string summary = last_.out;
    const auto after = apcictl({"--device", device, "status"});
    ::kill(daemon, SIGTERM);
    ::waitpid(daemon, nullptr, 0);
    // Its own moves only, from where the axes stood: the embedded board's run, segment for
    // segment.
    const json fresh = run_json(next, {"--tools", tools(5.0)});
    EXPECT_EQ(doc.at("segments"), fresh.at("segments"));
    ASSERT_EQ(doc.at("notices").size(), 1u) << doc.at("notices");
    EXPECT_EQ(doc.at("notices")[0].at("code"), "Discarded");
    EXPECT_TRUE(contains(summary,
                         "notice: the board's spooler held 2 moves of an earlier program that "
                         "stopped at a compensation error: discarded before this run, as a reset "
                         "discards them (the axes stay where they stood)\n"))
        << summary;
    EXPECT_TRUE(contains(after.out, "spooler 0 of 256 profiles")) << after.out;
}

// Moves another program spooled and has not run (the board does not hold them) are not this
// program's to run or to discard: the run is refused before it changes anything.
TEST_F(ApcictlRun, MovesAnotherProgramSpooledAndDidNotRunRefuseTheRunAndStay) {
    const std::string socket = path("emu.sock");
    const pid_t daemon = start_daemon(socket);
    ASSERT_GT(daemon, 0);
    const std::string device = "unix:" + socket;
    const auto spooled = apcictl({"--device", device, "spool", "G01", "N7", "F600", "X10"});
    EXPECT_EQ(spooled.exit_code, 0) << spooled.err;
    const std::string prog = write("p.nc", "N10 G1 X5 F600\nM30\n");
    const auto r = apcictl({"--device", device, "run", prog, "--json", path("p.json")});
    const auto after = apcictl({"--device", device, "status"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.out,
                         "SpoolerInUse: the board's spooler holds 1 move that another program "
                         "spooled and the board has not run to its end: it would run as this "
                         "program's. Let it run to its end (apcictl step) or discard it (apcictl "
                         "direct js), then run again; nothing was moved"))
        << r.out << r.err;
    EXPECT_TRUE(contains(r.err, "stopped: SpoolerInUse")) << r.err;
    EXPECT_TRUE(contains(after.out, "spooler 1 of 256 profiles")) << after.out;
    // Part of the way run is not to its end: still refused, and the board goes on as it was.
    const auto stepped = apcictl({"--device", device, "script", "-"},
                                 "spool G01 N8 F600 X20\nstep 500\n");
    EXPECT_EQ(stepped.exit_code, 0) << stepped.err;
    const auto again = apcictl({"--device", device, "run", prog, "--json", "-"});
    EXPECT_EQ(again.exit_code, 1);
    EXPECT_TRUE(contains(again.out, "\"code\":\"SpoolerInUse\"")) << again.out;
    EXPECT_TRUE(contains(again.err, "spooler holds 2 moves that another program spooled and the "
                                    "board has not run to their end: they would run"))
        << again.err;
    ::kill(daemon, SIGTERM);
    ::waitpid(daemon, nullptr, 0);
}

// A move under way when the board came to hold (a compensation error refused a later profile
// before the clock ran it to its end): discarding stops it where it is, and what the board
// logs of it is the earlier program's, not this run's. The summary goes to standard error with
// the JSON on standard output, the notice with it.
TEST_F(ApcictlRun, AMoveUnderWayWhenTheBoardHeldIsStoppedAndItsSegmentIsNotThisRuns) {
    const std::string socket = path("emu.sock");
    const pid_t daemon = start_daemon(socket);
    ASSERT_GT(daemon, 0);
    const std::string device = "unix:" + socket;
    // N5 under way at X10; group 1 compensating (radius 1, left), N3's centre off its circle.
    const auto held = apcictl({"--device", device, "script", "-"},
                              "spool G01 N5 X100 F600\nstep 1000\nwrite 1300 1 1 7 1\n"
                              "write 1300 1 1 9 0\nwrite 1300 1 1 3 1\n"
                              "spool G01 N1 X110 Y-10 F600\nspool G03 N3 X100 Y10 I100 J0 F600\n");
    EXPECT_EQ(held.exit_code, 1);
    EXPECT_TRUE(contains(held.err, "TC group 1 ERROR bits 0x10, block 3")) << held.err;
    const std::string prog = write("p.nc", "N10 G1 X20 F600\nM30\n");
    const auto r = apcictl({"--device", device, "run", prog, "--json", "-"});
    ::kill(daemon, SIGTERM);
    ::waitpid(daemon, nullptr, 0);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json doc = json::parse(r.out);  // standard output is the JSON alone
    ASSERT_EQ(doc.at("segments").size(), 1u) << doc.at("segments");
    EXPECT_EQ(doc.at("segments")[0].at("block"), 10);
    // From where N5 stopped.
    EXPECT_EQ(doc.at("segments")[0].at("start"), json::array({10, 0, 0}));
    EXPECT_TRUE(contains(r.err,
                         "notice: the board's spooler held 2 moves of an earlier program that "
                         "stopped at a compensation error: discarded before this run, as a reset "
                         "discards them (the axes stay where they stood)\n"))
        << r.err;
}

// ---- Exit codes and usage

TEST_F(ApcictlRun, UsageErrorsExitTwo) {
    EXPECT_EQ(apcictl({"run"}).exit_code, 2);
    EXPECT_EQ(apcictl({"run", "x.nc", "--bogus"}).exit_code, 2);
    // --avoid-bottlenecks: 0 (off) or 2..64 moves back.
    const std::string wr = kExamples + "/wr_quad_disc.nc", wr_tools = kExamples + "/tools/wr_quad_disc.tools";
    for (const char* bad : {"1", "65", "-1", "x", "2.5", ""}) {
        const auto r = apcictl({"run", wr, "--tools", wr_tools, "--avoid-bottlenecks", bad});
        EXPECT_EQ(r.exit_code, 2) << bad;
        EXPECT_EQ(r.out, "") << bad;  // nothing ran
        // The option, the value and what it may be; not the parser's words.
        EXPECT_EQ(r.err, "apcictl: run: --avoid-bottlenecks '" + std::string(bad) +
                             "' is not 0 (never) or a number of moves to look back, 2..64\n")
            << bad;
    }
    for (const char* good : {"0", "2", "64"})
        EXPECT_EQ(apcictl({"run", wr, "--tools", wr_tools, "--avoid-bottlenecks", good}).exit_code, 0)
            << good;
    // --plane given empty is no plane (it was taken as not given).
    const auto empty_plane =
        apcictl({"run", wr, "--tools", wr_tools, "--svg", path("e.svg"), "--plane", ""});
    EXPECT_EQ(empty_plane.exit_code, 2);
    EXPECT_EQ(empty_plane.err, "apcictl: run: --plane '' is not 17, 18 or 19\n");
    // The plot's options without a plot: refused, not taken and ignored.
    for (const std::vector<std::string>& plot_only :
         {std::vector<std::string>{"--svg-cycles"}, std::vector<std::string>{"--plane", "18"}}) {
        std::vector<std::string> args{"run", wr, "--tools", wr_tools};
        args.insert(args.end(), plot_only.begin(), plot_only.end());
        const auto r = apcictl(args);
        EXPECT_EQ(r.exit_code, 2) << plot_only[0];
        EXPECT_EQ(r.out, "") << plot_only[0];
        EXPECT_EQ(r.err, "apcictl: run: " + plot_only[0] +
                             " is an option of the plot: give --svg FILE too\n");
        args.insert(args.end(), {"--svg", path("plot.svg")});
        EXPECT_EQ(apcictl(args).exit_code, 0) << plot_only[0];
    }
    const auto missing = apcictl({"run", path("missing.nc")});
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_TRUE(contains(missing.err, "missing.nc: cannot open")) << missing.err;
    const auto unwritable =
        apcictl({"run", kExamples + "/wr_quad_disc.nc", "--tools",
                 kExamples + "/tools/wr_quad_disc.tools", "--json", path("no/such/dir.json")});
    EXPECT_EQ(unwritable.exit_code, 2);
    EXPECT_EQ(unwritable.out, "");  // nothing ran
    EXPECT_TRUE(contains(unwritable.err, "cannot write " + path("no/such/dir.json")))
        << unwritable.err;
}

TEST_F(ApcictlRun, HelpNamesTheOptions) {
    const auto r = apcictl({"run", "--help"});
    EXPECT_EQ(r.exit_code, 0);
    for (const char* opt : {"--tools", "--svg", "--json", "--csv"})
        EXPECT_TRUE(contains(r.out, opt)) << opt;
    // A number's option shows what it takes in its text, not the parser's validator terms.
    EXPECT_TRUE(contains(r.out, "--avoid-bottlenecks N ")) << r.out;
    EXPECT_FALSE(contains(r.out, "AND")) << r.out;
}

TEST_F(ApcictlRun, ProgramFromStandardInput) {
    const auto r = apcictl({"run", "-", "--json", path("in.json")}, "N10 G1 X3 Y4 F600\nM30\n");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "<stdin>: 2 blocks, 2 sent to the board, 1 segment executed\npath 5.000 mm"))
        << r.out;
    const auto bad = apcictl({"run", "-"}, "N10 G1 X\n");
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_TRUE(contains(bad.err, "<stdin>:1:9: N10: expected a number after 'X'")) << bad.err;
}

// Runs apcictl with standard error on a pseudo-terminal; returns what it wrote there.
// The pseudo-terminal is not the child's controlling terminal, and this process keeps the
// terminal's other end open until the child has ended and every byte is read: a terminal whose
// last other end closes may still be moving the last bytes written towards this end when a
// read sees it closed (EIO), and the text would lose its end (seen about once in 5,000 runs on a
// loaded machine). Reads are bounded: the child is killed after 60 s.
std::string stderr_on_a_terminal(const std::vector<std::string>& args, int& exit_code) {
    exit_code = -1;
    int master = -1;
    int slave = -1;
    if (::openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) return "openpty failed";
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 1);  // only standard error is on the terminal
        ::dup2(slave, 2);
        ::close(master);
        ::close(slave);
        std::vector<char*> argv{const_cast<char*>(APCICTL_PATH)};
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    std::string text;
    char buf[4096];
    const auto read_ready = [&](int timeout_ms) {
        pollfd p{master, POLLIN, 0};
        while (::poll(&p, 1, timeout_ms) > 0) {
            const ssize_t n = ::read(master, buf, sizeof buf);
            if (n <= 0) return;
            text.append(buf, static_cast<std::size_t>(n));
            timeout_ms = 0;
        }
    };
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    int status = 0;
    while (pid > 0 && ::waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            break;
        }
        read_ready(20);  // the child never waits for room on the terminal
    }
    // The child has ended and this end is still open: a read that finds nothing waiting first
    // lets the terminal hand over what is still on its way, and then says so (EAGAIN).
    ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
    for (;;) {
        const ssize_t n = ::read(master, buf, sizeof buf);
        if (n <= 0) break;
        text.append(buf, static_cast<std::size_t>(n));
    }
    ::close(slave);
    ::close(master);
    if (pid > 0 && WIFEXITED(status)) exit_code = WEXITSTATUS(status);
    return text;
}

TEST_F(ApcictlRun, ProgressBarOnlyOnATerminalAndClearedAtTheEnd) {
    std::string text = "N1 G1 F60000\n";
    for (int i = 0; i < 10000; ++i) text += (i % 2 == 0 ? "X1\n" : "X0\n");
    text += "M30\n";
    const std::string prog = write("long.nc", text);
    int exit_code = -1;
    const std::string terminal = stderr_on_a_terminal({"run", prog}, exit_code);
    EXPECT_EQ(exit_code, 0) << terminal;
    EXPECT_TRUE(contains(terminal, "\r[")) << terminal;
    EXPECT_TRUE(contains(terminal, " of 10002 blocks")) << terminal;
    EXPECT_TRUE(terminal.size() >= 4 && terminal.substr(terminal.size() - 4) == "\r\x1b[K")
        << terminal;
    const auto piped = apcictl({"run", prog});  // standard error is a pipe here
    EXPECT_EQ(piped.exit_code, 0);
    EXPECT_EQ(piped.err, "");
}

TEST_F(ApcictlRun, BlocksWithoutNumberCarryTheirLine) {
    const std::string prog = write("nonum.nc", "F600\n\nG1 X1\nN7 X2\nM30\n");
    const json doc = run_json(prog);
    ASSERT_EQ(doc.at("segments").size(), 2u);
    EXPECT_EQ(doc.at("segments")[0].at("block"), -1);
    EXPECT_EQ(doc.at("segments")[0].at("line"), 3);
    EXPECT_EQ(doc.at("segments")[1].at("block"), 7);
    EXPECT_FALSE(doc.at("segments")[1].contains("line"));
}

}  // namespace
