// SPDX-License-Identifier: MIT
// `apcictl run`'s outputs: an output that names an input is refused, one pass on the embedded
// emulator publishes nothing of an invalid program, a daemon's board sees none of it, a program
// from a pipe.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <thread>

#include "apcictl_run.h"

namespace {

using namespace apcictl_run_test;

// An output that names an input or another output is refused before anything runs (hardening
// issue, item 6): `--json p.nc` overwrote the program, `--json X --csv X` mixed both outputs, and
// both exited 0. The same file is found through `..`, symlinks and hard links.
TEST_F(ApcictlRun, AnOutputThatIsAnInputOrAnotherOutputIsRefusedBeforeAnythingRuns) {
    const std::string program_text = "N10 G1 X3 Y4 F600\nM30\n";
    const std::string prog = write("p.nc", program_text);
    const std::string tools_file = tools(1.0);
    const std::string plc = write("s.plc", "");
    const std::string corr = write("c.corr", "");
    ASSERT_EQ(::symlink(prog.c_str(), path("link.nc").c_str()), 0);
    ASSERT_EQ(::link(tools_file.c_str(), path("hard.tools").c_str()), 0);
    const std::string dotted = dir() + "/../" + std::filesystem::path(dir()).filename().string();
    struct Case {
        std::vector<std::string> args;
        std::string says;
    };
    const std::vector<Case> cases{
        {{"--json", prog}, "--json '" + prog + "' is the same file as PROGRAM '" + prog + "'"},
        {{"--svg", dotted + "/p.nc"}, "--svg '" + dotted + "/p.nc' is the same file as PROGRAM"},
        {{"--csv", path("link.nc")}, "--csv '" + path("link.nc") + "' is the same file as PROGRAM"},
        {{"--tools", tools_file, "--json", tools_file},
         "--json '" + tools_file + "' is the same file as --tools"},
        {{"--tools", tools_file, "--tools-out", path("hard.tools")},
         "--tools-out '" + path("hard.tools") + "' is the same file as --tools"},
        {{"--plc", plc, "--csv", plc}, "--csv '" + plc + "' is the same file as --plc"},
        {{"--corr", corr, "--svg", corr}, "--svg '" + corr + "' is the same file as --corr"},
        {{"--json", path("x"), "--csv", path("x")},
         "--csv '" + path("x") + "' is the same file as --json '" + path("x") + "'"},
        {{"--svg", path("y"), "--tools-out", path("y")},
         "--tools-out '" + path("y") + "' is the same file as --svg"},
    };
    for (const auto& c : cases) {
        std::vector<std::string> args{"run", prog};
        args.insert(args.end(), c.args.begin(), c.args.end());
        const auto r = apcictl(args);
        EXPECT_EQ(r.exit_code, 2) << c.says;
        EXPECT_EQ(r.out, "") << c.says;
        EXPECT_TRUE(contains(r.err, c.says)) << r.err;
    }
    // Nothing ran and nothing was written: the inputs are as they were, no output was made.
    EXPECT_EQ(read_text(prog), program_text);
    EXPECT_TRUE(contains(read_text(tools_file), "wz[1].radius 1.0")) << read_text(tools_file);
    EXPECT_FALSE(exists(path("x")));
    EXPECT_FALSE(exists(path("y")));
    // A program from standard input has no file to clash with; distinct outputs still run.
    const auto ok =
        apcictl({"run", "-", "--json", path("a.json"), "--csv", path("a.csv")}, program_text);
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

// ---- One pass on the embedded emulator, the validation first elsewhere

// A program of `moves` G1 blocks that are valid, then `last` (its last line or lines).
std::string moves_then(int moves, const std::string& last) {
    std::string text = "N1 G17 G90 F3000\nN2 G0 X0 Y0 Z0\n";
    for (int i = 0; i < moves; ++i)
        text += "N" + std::to_string(i + 3) + (i % 2 == 0 ? " G1 X1\n" : " G1 Y1\n");
    return text + last;
}

// The embedded emulator validates while it runs: the moves before the error went to its board,
// but nothing of them is published, and the error is the one the validation pass gave.
TEST_F(ApcictlRun, AnInvalidProgramOnTheEmbeddedBoardPublishesNothingAndNamesItsLine) {
    const std::string prog = write("late.nc", moves_then(6000, "N6010 G1 X\nM30\n"));
    const auto before = names_in(dir());
    const auto r = apcictl({"run", prog, "--json", path("o.json"), "--svg", path("o.svg"), "--csv",
                            path("o.csv"), "--tools-out", path("o.tools")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "apcictl: " + prog + ":6003:11: N6010: expected a number after 'X'\n");
    EXPECT_EQ(names_in(dir()), before);  // no output, no temporary file left behind

    // A rule of the program, with what was not given, as before.
    const std::string d1 = write("d1late.nc", moves_then(5000, "N6000 G40 D1\nM30\n"));
    const auto t = apcictl({"run", d1, "--json", path("d.json")});
    EXPECT_EQ(t.exit_code, 1);
    EXPECT_EQ(t.out, "");
    EXPECT_EQ(t.err, "apcictl: " + d1 +
                         ":5003:11: N6000: D1 selects tool 1, which the tool list does not define "
                         "(no --tools file given)\n");
    EXPECT_FALSE(exists(path("d.json")));
    // From standard input too.
    const auto in =
        apcictl({"run", "-", "--json", path("i.json")}, moves_then(5000, "N6000 G1 X\nM30\n"));
    EXPECT_EQ(in.exit_code, 1);
    EXPECT_EQ(in.err, "apcictl: <stdin>:5003:11: N6000: expected a number after 'X'\n");
    EXPECT_FALSE(exists(path("i.json")));
}

// The last line is read after M30 has run on the board: an error there still publishes nothing
// and leaves every existing target as it was.
TEST_F(ApcictlRun, AnErrorAtTheLastLineLeavesTheExistingOutputsUntouched) {
    const std::string prog = write("after.nc", moves_then(5000, "N5003 M30\nN5004 G1 X2\n"));
    const std::vector<std::string> outputs{"o.json", "o.svg", "o.csv", "o.tools"};
    for (const auto& o : outputs) write(o, "old " + o + "\n");
    const auto before = names_in(dir());
    const auto r = apcictl({"run", prog, "--json", path("o.json"), "--svg", path("o.svg"), "--csv",
                            path("o.csv"), "--tools-out", path("o.tools")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "apcictl: " + prog +
                         ":5004:1: N5004: block after M30: the program has already ended\n");
    for (const auto& o : outputs) EXPECT_EQ(read_text(path(o)), "old " + o + "\n") << o;
    EXPECT_EQ(names_in(dir()), before);
}

// A daemon stands for a board others see (and a real one): there the program is validated
// before anything moves, so its board sees no profile of an invalid program.
TEST_F(ApcictlRun, ADaemonsBoardSeesNoMoveOfAnInvalidProgram) {
    const std::string socket = path("emu.sock");
    const pid_t daemon = start_daemon(socket);
    ASSERT_GT(daemon, 0);
    ASSERT_TRUE(exists(socket));
    const std::string bad = write("bad.nc", moves_then(3000, "N3003 G1 X7\nN3004 G1 X\nM30\n"));
    const std::string good = write("good.nc", "N1 G1 Y1 F1000\nM30\n");
    const std::string device = "unix:" + socket;
    const auto r = apcictl({"--device", device, "run", bad, "--json", path("bad.json")});
    const auto after = apcictl({"--device", device, "run", good, "--json", path("socket.json")});
    ::kill(daemon, SIGTERM);
    ::waitpid(daemon, nullptr, 0);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    // The same words as on the embedded board.
    EXPECT_EQ(r.err, apcictl({"run", bad}).err);
    EXPECT_EQ(r.err, "apcictl: " + bad + ":3004:11: N3004: expected a number after 'X'\n");
    EXPECT_FALSE(exists(path("bad.json")));
    // The next program starts where a fresh board stands: nothing of the invalid one moved it.
    ASSERT_EQ(after.exit_code, 0) << after.err;
    ASSERT_EQ(apcictl({"run", good, "--json", path("emu.json")}).exit_code, 0);
    EXPECT_EQ(read_text(path("socket.json")), read_text(path("emu.json")));
}

// One pass reads the program once, so a program from a pipe (a FIFO, `<(generator)`) runs on
// the embedded board: the same run as from a file.
TEST_F(ApcictlRun, AProgramFromAPipeRunsOnTheEmbeddedBoard) {
    const std::string text = moves_then(5000, "N5003 M30\n");
    const std::string file = write("file.nc", text);
    ASSERT_EQ(apcictl({"run", file, "--json", path("file.json")}).exit_code, 0);
    const std::string fifo = path("pipe.nc");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] {
        // Waits (bounded) for apcictl to open the pipe, then writes the program once.
        int fd = -1;
        for (int i = 0; i < 3000 && fd < 0; ++i) {
            fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
            if (fd < 0) ::usleep(10'000);
        }
        if (fd < 0) return;
        ::fcntl(fd, F_SETFL, 0);
        std::size_t done = 0;
        while (done < text.size()) {
            const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
            if (n <= 0) break;
            done += static_cast<std::size_t>(n);
        }
        ::close(fd);
    });
    // Bounded: a pass that opened the pipe a second time would wait for a writer for ever.
    const auto r = test_support::run_process(
        {"/usr/bin/timeout", "60", APCICTL_PATH, "run", fifo, "--json", path("pipe.json")});
    writer.join();
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, fifo + ": 5003 blocks, 5003 sent to the board")) << r.out;
    EXPECT_EQ(read_text(path("pipe.json")), read_text(path("file.json")));
}

}  // namespace

// --one-thread: the front end, the board, the check and the writers on the caller's thread; the
// same outputs byte for byte and the same summary, for a milling program, an OTC program with
// its PLC script, a program the check warns on and one where a finding is the run's error.
TEST_F(ApcictlRun, OneThreadWritesTheSameOutputsByteForByte) {
    const std::string spike =
        write("spike.nc",
              "N10 G17 G90 G26 D1 F600\nN20 G0 X-74.257 Y-49.657\nN30 G42 G1 X-35.095 Y-27.491\n"
              "N50 G1 X-4.063 Y-82.318\nN60 G1 X-4.273 Y-81.223\nN70 G1 X-34.475 Y-136.512\n"
              "N80 G1 X-50 Y-150\nN90 G40 G1 X-73.967 Y-114.939\nN100 M30\n");
    const std::string spike_tools = tools(5.0);
    struct Case {
        std::vector<std::string> args;
        int exit;
    };
    const std::vector<Case> cases{
        {{kExamples + "/wr_quad_disc.nc", "--tools", kExamples + "/tools/wr_quad_disc.tools"}, 0},
        {{kExamples + "/otc/wr_quad_disc.nc", "--tools", kExamples + "/tools/wr_quad_disc.tools",
          "--plc", kExamples + "/otc/plc/wr_quad_disc.plc"},
         0},
        {{spike, "--tools", spike_tools}, 0},
        {{spike, "--tools", spike_tools, "--self-approach", "error"}, 1},
    };
    for (const Case& c : cases) {
        std::string outputs[2];
        std::string summaries[2];
        for (const int one : {0, 1}) {
            std::vector<std::string> args{"run"};
            args.insert(args.end(), c.args.begin(), c.args.end());
            const std::string stem = path(one != 0 ? "one" : "threads");
            args.insert(args.end(),
                        {"--json", stem + ".json", "--svg", stem + ".svg", "--csv", stem + ".csv"});
            if (one != 0) args.emplace_back("--one-thread");
            const ProcessResult r = apcictl(args);
            EXPECT_EQ(r.exit_code, c.exit) << c.args[0] << r.err;
            outputs[one] =
                read_text(stem + ".json") + read_text(stem + ".svg") + read_text(stem + ".csv");
            summaries[one] = r.out;
        }
        EXPECT_GT(outputs[0].size(), 1000u) << c.args[0];
        EXPECT_TRUE(outputs[0] == outputs[1]) << c.args[0];
        EXPECT_EQ(summaries[0], summaries[1]) << c.args[0];
    }
    // The warnings and the error are there to compare.
    EXPECT_TRUE(contains(read_text(path("threads.json")), "SelfApproach"));
}
