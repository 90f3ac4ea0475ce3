// SPDX-License-Identifier: MIT
// apcictl list and apcictl diff (the hardware-in-loop mode) as processes,
// against the emulator daemon, a fake sysfs PCI board and the embedded board.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "apcictl.h"
#include "command.h"
#include "daemon.h"
#include "fake_sysfs.h"
#include "text.h"

namespace {

using test_support::contains;
using apci_test::Daemon;
using apci_test::DaemonOptions;
using apci_test::FakePciSysfs;
using apci_test::TempDir;
using test_support::apcictl;
using test_support::ProcessResult;

const std::string kTools = std::string(APCI_SOURCE_DIR) + "/docs/figures/tc-figures.tools";
const std::string kInsideCorners =
    std::string(APCI_SOURCE_DIR) + "/docs/figures/tc-inside-corners.nc";

// A line of `apcictl list`: the URI, spaces, the description.
bool has_line(const std::string& out, const std::string& uri, const std::string& description) {
    std::size_t at = 0;
    while ((at = out.find(uri, at)) != std::string::npos) {
        const bool line_start = at == 0 || out[at - 1] == '\n';
        const std::size_t text = out.find_first_not_of(' ', at + uri.size());
        if (line_start && text > at + uri.size() + 1 &&
            out.compare(text, description.size(), description) == 0)
            return true;
        ++at;
    }
    return false;
}

// A script (or any text) file in `dir`.
std::string script_file(const TempDir& dir, const std::string& text,
                        const std::string& name = "work.script") {
    std::string path = dir.file(name);
    FILE* f = std::fopen(path.c_str(), "w");
    if (f == nullptr) {
        ADD_FAILURE() << "cannot create " << path;
        return path;
    }
    std::fputs(text.c_str(), f);
    std::fclose(f);
    return path;
}

// ---- list

TEST(ApcictlList, NamesPciBoardsAndDaemonsOneLineEachUriFirst) {
    DaemonOptions o;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    FakePciSysfs sysfs(d->shm_path(), FakePciSysfs::BarKind::kMemory);
    ProcessResult r;
    ASSERT_TRUE(apci_test::eventually([&] {
        r = apcictl({"list"}, {}, {{"APCI_RUNTIME_DIR", d->dir().path()}});
        return contains(r.out, d->unix_uri());
    })) << r.out
        << r.err;
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(has_line(r.out, "pci:0000:01:00.0", "ADDI-DATA PCI board 15b8:8001")) << r.out;
    EXPECT_TRUE(has_line(r.out, d->unix_uri(), "rwmos-emu daemon, pid " + std::to_string(d->pid())))
        << r.out;
    EXPECT_TRUE(has_line(r.out, d->shm_uri(), "rwmos-emu dual-port RAM file")) << r.out;
}

TEST(ApcictlList, NoBoardPrintsNothingAndSucceeds) {
    TempDir empty;
    const auto r = apcictl({"list"}, {},
                           {{"APCI_RUNTIME_DIR", empty.path()}, {"APCI_SYSFS_ROOT", empty.path()}});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "");
}

// ---- diff: scripts

class ApcictlDiff : public ::testing::Test {
  protected:
    void SetUp() override {
        daemon_ = Daemon::start();
        ASSERT_NE(daemon_, nullptr);
    }
    ProcessResult diff(std::vector<std::string> args, const std::string& device = "") {
        std::vector<std::string> all{"--device", device.empty() ? daemon_->unix_uri() : device,
                                     "diff"};
        all.insert(all.end(), args.begin(), args.end());
        return apcictl(all);
    }
    TempDir dir_;
    std::unique_ptr<Daemon> daemon_;
};

TEST_F(ApcictlDiff, SameScriptOnTheDaemonAndTheEmbeddedBoardHasNoDifference) {
    const auto file =
        script_file(dir_, "write 1300 1 1 8 5\nwrite 1300 1 1 7 2.5\nread 1300 1 1 7\nstatus\n");
    const auto r = diff({"--against", "emu:", file});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "no difference between " + daemon_->unix_uri() +
                                    " and emu: (4 script lines compared)"))
        << r.out;
}

TEST_F(ApcictlDiff, ScriptReportsTheFirstDifferingLineWithBothResults) {
    ASSERT_EQ(
        apcictl({"--device", daemon_->unix_uri(), "write", "1300", "1", "1", "7", "4.5"}).exit_code,
        0);
    const auto file = script_file(dir_, "read 1000 0 3 0\n\nread 1300 1 1 7\nread 1300 1 2 7\n");
    const auto r = diff({"--against", "emu:", file});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(contains(r.out, "first difference at line 3: read 1300 1 1 7")) << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("unix:[^ ]+ +4\\.5\n  emu: +0\n"))) << r.out;
    EXPECT_TRUE(contains(r.err, "differ at line 3")) << r.err;
}

// A line that reads or writes one object names it, by its dotted name and its numbers, however
// the line names it.
TEST_F(ApcictlDiff, ScriptDifferenceNamesTheObject) {
    ASSERT_EQ(
        apcictl({"--device", daemon_->unix_uri(), "write", "tc.group[1].radius", "4.5"}).exit_code,
        0);
    auto r = diff({"--against", "emu:", script_file(dir_, "read tc.group[1].radius\n")});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(contains(r.out,
                         "first difference at line 1: read tc.group[1].radius, object "
                         "tc.group[1].radius (1300/1/1/7)\n"))
        << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("unix:[^ ]+ +4\\.5\n  emu: +0\n"))) << r.out;
    r = diff({"--against", "emu:", script_file(dir_, "read 1300 1 1 7\n", "numbers.script")});
    EXPECT_TRUE(contains(r.out,
                         "first difference at line 1: read 1300 1 1 7, object "
                         "tc.group[1].radius (1300/1/1/7)\n"))
        << r.out;
    // A line of another command, or an address the map does not name, is shown as typed.
    r = diff(
        {"--against", "emu:?no-option-tc", script_file(dir_, "read 1300 1 9 3\nstatus\n", "s2")});
    EXPECT_TRUE(contains(r.out, "first difference at line 1: read 1300 1 9 3\n")) << r.out;
}

// dump through the daemon's socket: one session, every readable object, the daemon's values.
TEST(ApcictlDumpOnADaemon, ListsEveryReadableObjectWithTheDaemonsValues) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    ASSERT_EQ(apcictl({"--device", d->unix_uri(), "write", "tc.group[1].radius", "4.5"}).exit_code,
              0);
    const auto group = apcictl({"--device", d->unix_uri(), "dump", "tc.group[1]"});
    EXPECT_EQ(group.exit_code, 0) << group.err;
    EXPECT_TRUE(std::regex_search(
        group.out,
        std::regex("\ntc\\.group\\[1\\]\\.radius +1300/1/1/7 +double +r/w +4\\.5 +PU\n")))
        << group.out;
    const auto all = apcictl({"--device", d->unix_uri(), "dump", "--json"});
    EXPECT_EQ(all.exit_code, 0) << all.err;
    const auto here = nlohmann::json::parse(all.out);
    const auto there = nlohmann::json::parse(apcictl({"dump", "--json"}).out);
    EXPECT_GT(here.size(), 8000u);
    ASSERT_EQ(here.size(), there.size()) << "the same objects as on the embedded board";
    for (std::size_t i = 0; i < here.size(); ++i) {
        EXPECT_EQ(here[i]["name"], there[i]["name"]);
        if (here[i]["name"] == "tc.group[1].radius") {
            EXPECT_EQ(here[i]["value"], 4.5);
        }
    }
    EXPECT_FALSE(contains(all.out, "\"status\"")) << "every object read";
}

// The same names over the daemon's shared-memory file and over that file seen as a PCI board's
// memory BAR (the PCI path): a write and a read by name, and `dump tc` lists the same objects as
// on the embedded board.
TEST(ApcictlDumpOnADaemon, NamesWorkOverTheSharedMemoryAndPciTransports) {
    DaemonOptions o;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    FakePciSysfs sysfs(d->shm_path(), FakePciSysfs::BarKind::kMemory);
    const auto there = nlohmann::json::parse(apcictl({"dump", "tc", "--json"}).out);
    for (const std::string& uri : {d->shm_uri(), std::string("pci:0000:01:00.0")}) {
        SCOPED_TRACE(uri);
        const auto wrote = apcictl({"--device", uri, "write", "tc.group[2].radius", "1.25"});
        ASSERT_EQ(wrote.exit_code, 0) << wrote.err;
        const auto read = apcictl({"--device", uri, "read", "tc.group[2].radius"});
        EXPECT_EQ(read.exit_code, 0) << read.err;
        EXPECT_EQ(read.out, "1.25\n");
        const auto dump = apcictl({"--device", uri, "dump", "tc", "--json"});
        ASSERT_EQ(dump.exit_code, 0) << dump.err;
        const auto here = nlohmann::json::parse(dump.out);
        ASSERT_EQ(here.size(), there.size());
        for (std::size_t i = 0; i < here.size(); ++i) EXPECT_EQ(here[i]["name"], there[i]["name"]);
    }
}

// A link that fails ends the dump at its first read (every read after would wait for the same
// link), naming the object; nothing is printed. In process: the session opened, then the daemon
// went away.
TEST(ApcictlDumpOnADaemon, ALinkThatFailsEndsTheDumpAtOnce) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    apcictl::Session session(d->unix_uri());
    apcictl::Outcome opened;
    ASSERT_NE(session.board(opened), nullptr) << opened.error;
    d->stop();
    auto dump = apcictl::make_dump_command();
    CLI::App parser("dump", "dump");
    dump->declare(parser);
    parser.parse(std::vector<std::string>{"tc"});
    ASSERT_TRUE(dump->prepare().ok());
    testing::internal::CaptureStdout();
    const apcictl::Outcome r = dump->run(session);
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
    EXPECT_EQ(r.exit, apcictl::Exit::kBoard);
    EXPECT_TRUE(r.error.starts_with("dump: read tc.init.x_axis_nr (1300/0/11/0): TransportError"))
        << r.error;
}

TEST_F(ApcictlDiff, ScriptFailureOnOneBoardOnlyIsADifference) {
    const auto file = script_file(dir_, "read 1300 0 12 0\n");
    const auto r = diff({"--against", "emu:?no-option-tc", file});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.out, "first difference at line 1: read 1300 0 12 0")) << r.out;
    EXPECT_TRUE(contains(r.out, "failed: read 1300 0 12 0: NoSuchDevice")) << r.out;
}

TEST_F(ApcictlDiff, BadScriptLineIsAUsageErrorAndNothingRuns) {
    const auto file = script_file(dir_, "write 1300 1 1 7 2.5\nfrobnicate\n");
    const auto r = diff({"--against", "emu:", file});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "line 2: unknown command 'frobnicate'")) << r.err;
    EXPECT_EQ(apcictl({"--device", daemon_->unix_uri(), "read", "1300", "1", "1", "7"}).out, "0\n")
        << "the good first line did not run either";
}

TEST_F(ApcictlDiff, AgainstIsRequired) {
    const auto file = script_file(dir_, "read 1000 0 3 0\n");
    EXPECT_EQ(diff({file}).exit_code, 2);
}

// ---- diff: NC programs

TEST_F(ApcictlDiff, NcProgramRunsTheSameOnTheDaemonAndTheEmbeddedBoard) {
    const auto r = diff({"--against", "emu:", "--tools", kTools, kInsideCorners});
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_TRUE(std::regex_search(
        r.out, std::regex("no difference .* \\(([1-9][0-9]{3,}) interpolation cycles compared\\)")))
        << r.out;
}

TEST_F(ApcictlDiff, NcProgramReportsTheFirstDifferingPositionWithBlockAndCycle) {
    // A 2 ms interpolation cycle on one board only: the first move (N40; N20 goes nowhere)
    // covers twice the distance per cycle there.
    ASSERT_EQ(apcictl({"--device", daemon_->unix_uri(), "write", "1000", "0", "4", "0", "2000"})
                  .exit_code,
              0);
    const auto r = diff({"--against", "emu:", "--tools", kTools, kInsideCorners});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(std::regex_search(
        r.out, std::regex("first difference at N40, cycle 1: axis [XY] position\n")))
        << r.out;
}

TEST_F(ApcictlDiff, ToleranceAbsorbsDifferencesBelowIt) {
    ASSERT_EQ(apcictl({"--device", daemon_->unix_uri(), "write", "1300", "0", "20", "0", "1e-9"})
                  .exit_code,
              0);
    EXPECT_EQ(diff({"--against", "emu:", "--tools", kTools, kInsideCorners}).exit_code, 1);
    // The axes are back at the start of the program after the first run: a fresh daemon board.
    auto fresh = Daemon::start();
    ASSERT_NE(fresh, nullptr);
    ASSERT_EQ(
        apcictl({"--device", fresh->unix_uri(), "write", "1300", "0", "20", "0", "1e-9"}).exit_code,
        0);
    const auto r =
        diff({"--against", "emu:", "--tolerance", "1e-6", "--tools", kTools, kInsideCorners},
             fresh->unix_uri());
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
}

TEST_F(ApcictlDiff, NcProgramReportsTheFirstDifferingError) {
    const auto r =
        diff({"--against", "emu:?no-option-tc", "--tools", kTools, kInsideCorners}, "emu:");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.out, "first difference at line 7 (N30): error 1")) << r.out;
    EXPECT_TRUE(contains(r.out, "NoSuchDevice at line 7 (N30)")) << r.out;
}

TEST_F(ApcictlDiff, DifferentStartPositionsAreReportedFirst) {
    ASSERT_EQ(diff({"--against", "emu:", "--tools", kTools, kInsideCorners}).exit_code, 0);
    // The daemon's axes stay where the first run left them; a fresh embedded board starts at 0.
    const auto r = diff({"--against", "emu:", "--tools", kTools, kInsideCorners});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.out, "first difference at the start of the run: axis X position"))
        << r.out;
}

// --json: the --device board's run as `run --json` writes it, byte for byte, whether or not the
// boards differ (the second run does not touch it).
TEST_F(ApcictlDiff, JsonIsTheDeviceBoardsRunAsRunWritesIt) {
    const std::string run_json = dir_.file("run.json"), diff_json = dir_.file("diff.json");
    const auto run = apcictl({"run", "--tools", kTools, kInsideCorners, "--json", run_json});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    auto r =
        diff({"--against", "emu:", "--tools", kTools, kInsideCorners, "--json", diff_json}, "emu:");
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_EQ(test_support::read_text(diff_json), test_support::read_text(run_json));
    // Against a board that differs (no TC module): the --device board's run all the same.
    r = diff(
        {"--against", "emu:?no-option-tc", "--tools", kTools, kInsideCorners, "--json", diff_json},
        "emu:");
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_EQ(test_support::read_text(diff_json), test_support::read_text(run_json));
    // The other way round: the run that stopped at its first error, as run writes that one.
    const auto stopped = apcictl({"--device", "emu:?no-option-tc", "run", "--tools", kTools,
                                  kInsideCorners, "--json", run_json});
    ASSERT_EQ(stopped.exit_code, 1) << stopped.err;
    r = diff({"--against", "emu:", "--tools", kTools, kInsideCorners, "--json", diff_json},
             "emu:?no-option-tc");
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_EQ(test_support::read_text(diff_json), test_support::read_text(run_json));
    EXPECT_TRUE(contains(test_support::read_text(diff_json), "NoSuchDevice"));
}

// A program that does not validate writes nothing: an existing --json file stays as it was,
// and no temporary file is left beside it.
TEST_F(ApcictlDiff, JsonOfAProgramThatDoesNotValidateLeavesTheOldFile) {
    const std::string json = dir_.file("old.json");
    const std::string program =
        script_file(dir_, "N10 G1 X10 F100\nN20 G1 Q5\nN30 M30\n", "bad.nc");
    ASSERT_EQ(std::system(("printf 'kept' > " + json).c_str()), 0);
    const auto r = diff({"--against", "emu:", program, "--json", json}, "emu:");
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.err, "bad.nc:2")) << r.err;
    EXPECT_EQ(test_support::read_text(json), "kept");
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir_.path()))
        ++entries;
    EXPECT_EQ(entries, 2u) << "bad.nc and old.json only";
}

// --json is refused before anything runs: on a script, on standard output, over an input.
TEST_F(ApcictlDiff, JsonRefusedForAScriptStandardOutputOrAnInput) {
    const std::string script = script_file(dir_, "read 1300 1 1 7\n");
    auto r = diff({"--against", "emu:", script, "--json", dir_.file("s.json")}, "emu:");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "is a script")) << r.err;
    r = diff({"--against", "emu:", "--tools", kTools, kInsideCorners, "--json", "-"}, "emu:");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--json needs a file")) << r.err;
    // Every input: the program, the tool list, the correction table and the PLC script, also
    // through a symbolic link and under another name of the same file (a hard link).
    const std::string program = dir_.file("p.nc"), tools = dir_.file("p.tools");
    const std::string corr = dir_.file("p.corr");
    std::filesystem::copy_file(kInsideCorners, program);
    std::filesystem::copy_file(kTools, tools);
    std::filesystem::copy_file(std::string(APCI_SOURCE_DIR) + "/examples/tools/3d_corrections.corr",
                               corr);
    const std::string plc_text = "cycle 300 tool_temp_comp[2] 0.5\n";
    const std::string plc = script_file(dir_, plc_text, "p.plc");
    std::filesystem::create_symlink(tools, dir_.file("link.json"));
    std::filesystem::create_hard_link(program, dir_.file("hard.json"));
    for (const std::string& target :
         {program, dir_.file("link.json"), dir_.file("hard.json"), corr, plc}) {
        r = diff({"--against", "emu:", "--tools", tools, "--corr", corr, "--plc", plc, program,
                  "--json", target},
                 "emu:");
        EXPECT_EQ(r.exit_code, 2) << target;
        EXPECT_TRUE(contains(r.err, "is the same file as the input")) << target << ": " << r.err;
    }
    EXPECT_EQ(test_support::read_text(program), test_support::read_text(kInsideCorners));
    EXPECT_EQ(test_support::read_text(tools), test_support::read_text(kTools));
    EXPECT_EQ(test_support::read_text(corr),
              test_support::read_text(std::string(APCI_SOURCE_DIR) +
                                      "/examples/tools/3d_corrections.corr"));
    EXPECT_EQ(test_support::read_text(plc), plc_text);
}

// An output that cannot be opened is a usage error, and nothing runs.
TEST_F(ApcictlDiff, JsonInADirectoryThatIsNotThereIsAUsageError) {
    const auto r = diff({"--against", "emu:", "--tools", kTools, kInsideCorners, "--json",
                         dir_.file("no/such/dir.json")},
                        "emu:");
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_TRUE(contains(r.err, "cannot write")) << r.err;
    EXPECT_TRUE(contains(r.err, "No such file or directory")) << r.err;
}

// A --json file that cannot be written whole is an error that names it and its cause, and
// nothing is published: on a full device (written in place), and past the file size limit (the
// write fails with EFBIG): the old file stays as it was, and no temporary file is left beside it.
TEST_F(ApcictlDiff, JsonThatCannotBeWrittenIsReportedAndLeavesTheOldFile) {
    auto r = diff({"--against", "emu:", "--tools", kTools, kInsideCorners, "--json", "/dev/full"},
                  "emu:");
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.err, "diff: cannot write /dev/full: No space left on device")) << r.err;
    const std::string json = script_file(dir_, "kept", "old.json");
    // ulimit -f counts blocks of 512 bytes (dash); SIGXFSZ ignored stays ignored across exec.
    r = test_support::run_process({"/bin/sh", "-c", "trap '' XFSZ; ulimit -f 2; exec \"$@\"",
                                   "sh", APCICTL_PATH, "--device", "emu:", "diff", "--against",
                                   "emu:", "--tools", kTools, kInsideCorners, "--json", json});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.err, "diff: cannot write " + json + ": File too large")) << r.err;
    EXPECT_EQ(test_support::read_text(json), "kept");
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir_.path()))
        ++entries;
    EXPECT_EQ(entries, 1u) << "old.json only";
}

// A Klartext program (*.h) with its correction table (--corr, as for run) on both boards.
TEST_F(ApcictlDiff, KlartextProgramTakesItsCorrectionTable) {
    const std::string examples = std::string(APCI_SOURCE_DIR) + "/examples";
    const std::string program = examples + "/3d_correction_table.h";
    const std::string tools = examples + "/tools/3d_tools.tools";
    // Without the table its FUNCTION CORRDATA TCS #1 is refused before anything runs.
    const auto without = diff({"--against", "emu:", "--tools", tools, program});
    EXPECT_EQ(without.exit_code, 1) << without.out;
    EXPECT_TRUE(contains(without.err, "correction table does not define")) << without.err;
    const auto r = diff({"--against", "emu:", "--tools", tools, "--corr",
                         examples + "/tools/3d_corrections.corr", program});
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_TRUE(std::regex_search(
        r.out, std::regex("no difference .* \\(([1-9][0-9]{2,}) interpolation cycles compared\\)")))
        << r.out;
}

// --plc writes the script in both runs at the same cycle: on the daemon, whose machine data
// switch the temperature compensation on for Z, the write at cycle 300 lifts Z from cycle 301;
// on the fresh embedded board it displaces nothing. Without the script nothing differs.
TEST_F(ApcictlDiff, PlcScriptIsWrittenInBothRunsAtItsCycle) {
    for (const auto& w : std::vector<std::vector<std::string>>{{"1320", "0", "2", "0", "1"},
                                                               {"1320", "0", "3", "2", "4"}}) {
        std::vector<std::string> args{"--device", daemon_->unix_uri(), "write"};
        args.insert(args.end(), w.begin(), w.end());
        ASSERT_EQ(apcictl(args).exit_code, 0);
    }
    const std::string program =
        script_file(dir_, "N10 G1 X10 F600\nN20 G1 X0\nN30 M30\n", "back.nc");
    const std::string plc = script_file(dir_, "cycle 300 tool_temp_comp[2] 0.5\n", "lift.plc");
    const auto same = diff({"--against", "emu:", program});
    EXPECT_EQ(same.exit_code, 0) << same.out << same.err;
    const auto r = diff({"--against", "emu:", "--plc", plc, program});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.out, "first difference at N10, cycle 301: axis Z position")) << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("unix:[^ ]+ +0\\.5\n  emu: +0\n"))) << r.out;
    // A script that does not parse runs nothing, on either board.
    const std::string bad_plc = script_file(dir_, "cycle 300 tool_holder 2\n", "bad.plc");
    const auto bad = diff({"--against", "emu:", "--plc", bad_plc, program});
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_TRUE(contains(bad.err, "bad.plc:1:23: tool_holder takes 0, 1, TRUE or FALSE"))
        << bad.err;
}

TEST_F(ApcictlDiff, NcProgramFromStandardInputIsAUsageError) {
    EXPECT_EQ(diff({"--against", "emu:", "--nc", "-"}).exit_code, 2);
}

}  // namespace

namespace {

// ---- run --self-approach error on a board that moves a machine: a dry run first

class ApcictlRunDryRun : public ::testing::Test {
  protected:
    void SetUp() override {
        daemon_ = Daemon::start();
        ASSERT_NE(daemon_, nullptr);
        tools_ = script_file(dir_, "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n",
                             "r5.tools");
        // A square inside which G41 runs, entered from where the tool stands, left by G40: its
        // last element's path ends perpendicular at the corner, 5 mm into the first one's wall
        // where the tool came from outside the square (from (0, 0), the first move is no
        // approach and the square's first element is: no wall, no finding).
        square_ = script_file(dir_,
                              "N10 D1 F600\nN20 G41 G1 X0 Y0\nN30 G1 X50\nN40 G1 Y50\n"
                              "N50 G1 X0\nN60 G1 Y0\nN70 G40 G1 X-10 Y-10\nN80 M30\n",
                              "square.nc");
    }
    ProcessResult on_daemon(std::vector<std::string> args) {
        std::vector<std::string> all{"--device", daemon_->unix_uri()};
        all.insert(all.end(), args.begin(), args.end());
        return apcictl(all);
    }
    // The daemon's clock and axes after one more cycle ("cycle N (+1) ... X.. Y.."), less the
    // cycle count's own step.
    std::string where() {
        const ProcessResult r = on_daemon({"step", "1"});
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return r.out;
    }
    TempDir dir_;
    std::unique_ptr<Daemon> daemon_;
    std::string tools_, square_;
};

TEST_F(ApcictlRunDryRun, AFindingOfTheDryRunStopsTheRunBeforeAnythingMoves) {
    ASSERT_EQ(on_daemon({"direct", "JA", "X-20", "Y-20"}).exit_code, 0);
    ASSERT_EQ(on_daemon({"step", "--idle"}).exit_code, 0);
    const std::string before = where();
    EXPECT_TRUE(contains(before, " X-20 Y-20 ")) << before;
    const std::string json = dir_.file("square.json");
    const ProcessResult r = on_daemon(
        {"run", square_, "--tools", tools_, "--self-approach", "error", "--json", json});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.err, square_ + ":6:1: N60: the tool path of N60 comes within 0.0000 mm "
                                          "of the contour at N30"))
        << r.err;
    EXPECT_TRUE(contains(r.err, "(found by a dry run on the embedded emulator set up as the board "
                                "stands, before anything moved: --self-approach error)"))
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(json));
    // Nothing moved: one cycle later than before (the step of where()), the axes where they were.
    const std::string after = where();
    const auto cycle = [](const std::string& s) { return std::stoull(s.substr(s.find(' ') + 1)); };
    EXPECT_EQ(cycle(after), cycle(before) + 1) << before << after;
    EXPECT_EQ(after.substr(after.find(" fill")), before.substr(before.find(" fill")));
}

TEST_F(ApcictlRunDryRun, TheDryRunStartsWhereTheBoardsAxesStandAndOnlyStopsAnError) {
    // From (0, 0) (where the embedded emulator starts) the square has no finding: on a board
    // whose axes stand at (-20, -20) the dry run finds N60 only if it starts there too.
    EXPECT_EQ(apcictl({"run", square_, "--tools", tools_, "--self-approach", "error"}).exit_code, 0);
    ASSERT_EQ(on_daemon({"direct", "JA", "X-20", "Y-20"}).exit_code, 0);
    ASSERT_EQ(on_daemon({"step", "--idle"}).exit_code, 0);
    // Only warned: no dry run, the board runs it and the warning follows.
    const ProcessResult warned = on_daemon({"run", square_, "--tools", tools_});
    EXPECT_EQ(warned.exit_code, 0) << warned.err;
    EXPECT_TRUE(contains(warned.out, "warning: N60: SelfApproach: the tool path of N60"))
        << warned.out;
    EXPECT_FALSE(contains(warned.out + warned.err, "dry run"));
}

TEST_F(ApcictlRunDryRun, TheDryRunTakesTheBoardsAxisNumbers) {
    // X and Y on board axes 3 and 4 (A, B), which stand at -20; axes 0 and 1 stay at 0, where
    // the square has no finding.
    ASSERT_EQ(on_daemon({"write", "1300", "0", "11", "0", "3"}).exit_code, 0);
    ASSERT_EQ(on_daemon({"write", "1300", "0", "11", "1", "4"}).exit_code, 0);
    ASSERT_EQ(on_daemon({"direct", "JA", "A-20", "B-20"}).exit_code, 0);
    ASSERT_EQ(on_daemon({"step", "--idle"}).exit_code, 0);
    const ProcessResult r =
        on_daemon({"run", square_, "--tools", tools_, "--self-approach", "error"});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.err, "N60: the tool path of N60 comes within 0.0000 mm")) << r.err;
    EXPECT_TRUE(contains(r.err, "found by a dry run")) << r.err;
}

TEST_F(ApcictlRunDryRun, TheDryRunTakesTheBoardsInterpolationCycle) {
    // After the square, 100 mm at F0.001: 6e8 cycles of 10 ms, within the limit of 1e9 cycles
    // a move; 6e9 of the emulator's own 1 ms, beyond it. The dry run finds N60 only on an
    // emulator with the board's cycle (with its own it refuses the program and finds nothing).
    const std::string slow = script_file(dir_,
                                         "N10 D1 F600\nN20 G41 G1 X0 Y0\nN30 G1 X50\nN40 G1 Y50\n"
                                         "N50 G1 X0\nN60 G1 Y0\nN70 G40 G1 X-10 Y-10\n"
                                         "N75 G1 F0.001 X90\nN80 M30\n",
                                         "slow.nc");
    const ProcessResult embedded = apcictl({"run", slow, "--tools", tools_});
    EXPECT_EQ(embedded.exit_code, 1) << embedded.out << embedded.err;
    EXPECT_TRUE(contains(embedded.err, "N75: feed F0.001 makes this 100 mm move take")) << embedded.err;
    ASSERT_EQ(on_daemon({"write", "1000", "0", "4", "0", "10000"}).exit_code, 0);
    ASSERT_EQ(on_daemon({"direct", "JA", "X-20", "Y-20"}).exit_code, 0);
    ASSERT_EQ(on_daemon({"step", "--idle"}).exit_code, 0);
    const std::string before = where();
    const ProcessResult r = on_daemon({"run", slow, "--tools", tools_, "--self-approach", "error"});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.err, "N60: the tool path of N60 comes within 0.0000 mm")) << r.err;
    EXPECT_TRUE(contains(r.err, "found by a dry run")) << r.err;
    const std::string after = where();
    EXPECT_EQ(after.substr(after.find(" fill")), before.substr(before.find(" fill")));
}

TEST_F(ApcictlRunDryRun, ACorrectProgramRunsAfterItsDryRunAsWithoutOne) {
    const std::string examples = std::string(APCI_SOURCE_DIR) + "/examples";
    const std::vector<std::string> run{"run", examples + "/wr_quad_disc.nc", "--tools",
                                       examples + "/tools/wr_quad_disc.tools", "--json"};
    const ProcessResult checked = on_daemon(
        {run[0], run[1], run[2], run[3], run[4], dir_.file("a.json"), "--self-approach", "error"});
    EXPECT_EQ(checked.exit_code, 0) << checked.err;
    EXPECT_TRUE(contains(checked.out, "11 blocks, 11 sent to the board, 11 segments executed")) << checked.out;
    // The same program once more from where the first run left the axes, only warned: the same
    // segments (the dry run moved nothing of the daemon's board).
    auto fresh = Daemon::start();
    ASSERT_NE(fresh, nullptr);
    const ProcessResult plain = apcictl({"--device", fresh->unix_uri(), run[0], run[1], run[2],
                                         run[3], run[4], dir_.file("b.json")});
    EXPECT_EQ(plain.exit_code, 0) << plain.err;
    EXPECT_EQ(test_support::read_text(dir_.file("a.json")),
              test_support::read_text(dir_.file("b.json")));
}

TEST(ApcictlRunWithoutTc, ABoardWithoutTheTcModuleHasNoDryRunAndRefusesG41Itself) {
    DaemonOptions o;
    o.option_tc = false;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    TempDir dir;
    // A spike whose path cuts into itself on any board that compensates (the embedded
    // emulator's dry run would refuse it): this board refuses G42 first.
    const std::string prog = script_file(
        dir,
        "N10 G17 G90 G26 D1 F600\nN20 G0 X-74.257 Y-49.657\nN30 G42 G1 X-35.095 Y-27.491\n"
        "N50 G1 X-4.063 Y-82.318\nN60 G1 X-4.273 Y-81.223\nN70 G1 X-34.475 Y-136.512\n"
        "N80 G1 X-50 Y-150\nN90 G40 G1 X-73.967 Y-114.939\nN100 M30\n",
        "spike.nc");
    const std::string tools =
        script_file(dir, "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n", "r5.tools");
    EXPECT_EQ(apcictl({"run", prog, "--tools", tools, "--self-approach", "error"}).exit_code, 1);
    const ProcessResult r = apcictl(
        {"--device", d->unix_uri(), "run", prog, "--tools", tools, "--self-approach", "error"});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.out, "line 3 (N30): NoSuchDevice: G42 needs the TC module")) << r.out;
    EXPECT_FALSE(contains(r.out + r.err, "dry run"));
}

}  // namespace
