// SPDX-License-Identifier: MIT
// apcictl's command line as its users meet it: a mistyped command or option names the one
// meant, and every error line on stderr starts with "apcictl:".
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "apcictl.h"
#include "run_report.h"
#include "suggest.h"
#include "text.h"

namespace {

using apcictl::closest_name;
using apcictl::edit_distance;
using test_support::lines_of;
using test_support::ProcessResult;

// ---- the help an unknown option points to (explain_*: pure functions of a parsed app)

// Parses `typed` (in order) with a command line of one command, `read`; the explanation of
// the error it gives, with the words as typed (or none).
std::string explained(const std::vector<std::string>& typed, bool with_words) {
    CLI::App app("test", "apcictl");
    CLI::App* read = app.add_subcommand("read", "read an object");
    std::string address;
    read->add_option("ADDRESS", address);
    std::vector<std::string> reversed(typed.rbegin(), typed.rend());
    try {
        app.parse(reversed);
    } catch (const CLI::ParseError& e) {
        return with_words ? apcictl::explain_command_line_error(app, e, typed)
                          : apcictl::explain_parse_error(app, e);
    }
    return "parsed";
}

TEST(ApcictlSuggest, AnUnknownOptionPointsToTheHelpOfWhereItWasTyped) {
    EXPECT_EQ(explained({"read", "--zzz", "1300"}, true),
              "read: unknown option '--zzz' (see 'apcictl read --help')");
    EXPECT_EQ(explained({"--zzz", "read", "1300"}, true),
              "unknown option '--zzz' (see 'apcictl --help')");
    // Without the words as typed, the command's.
    EXPECT_EQ(explained({"read", "--zzz", "1300"}, false),
              "read: unknown option '--zzz' (see 'apcictl read --help')");
    EXPECT_EQ(explained({"--zzz"}, false), "unknown option '--zzz' (see 'apcictl --help')");
}

// ---- how `run` names a block in its messages (pure functions)

TEST(ApcictlRunReport, AMessageOfABlockNamesItAndOneOfNoneSaysNothing) {
    using apci::run::BlockRef;
    using apci::run::RunError;
    const BlockRef n60{60, 4}, line_only{apci::run::kNoBlock, 7}, number_only{60, 0}, none{};
    EXPECT_EQ(apcictl::at_block(n60, " at "), " at line 4 (N60)");
    EXPECT_EQ(apcictl::at_block(line_only, "", ": "), "line 7: ");
    EXPECT_EQ(apcictl::at_block(number_only, "<", ">"), "<N60>");
    EXPECT_EQ(apcictl::at_block(none, " at ", ": "), "");
    EXPECT_EQ(apcictl::stopped_run("p.nc", RunError{n60, "KorrError", "x"}),
              "run p.nc: stopped at line 4 (N60): KorrError");
    EXPECT_EQ(apcictl::stopped_run("p.nc", RunError{none, "TransportError", "x"}),
              "run p.nc: stopped: TransportError");
    EXPECT_EQ(apcictl::unfinished_run("p.nc", RunError{n60, "TransportError", "spool: gone"}),
              "run p.nc: no output written (any old ones are kept): the run did not finish, "
              "line 4 (N60): spool: gone");
    EXPECT_EQ(apcictl::unfinished_run("p.nc", RunError{none, "Timeout", "run clock: late"}),
              "run p.nc: no output written (any old ones are kept): the run did not finish: run "
              "clock: late");
    apci::run::RunOutcome out;
    out.warnings.push_back(RunError{n60, "SelfApproach", "near"});
    out.notices.push_back(RunError{none, "Discarded", "held 2 moves"});
    out.notices.push_back(RunError{line_only, "NoRadius", "no tool"});
    char* text = nullptr;
    std::size_t size = 0;
    std::FILE* f = ::open_memstream(&text, &size);
    ASSERT_NE(f, nullptr);
    apcictl::print_warnings_and_notices(f, out);
    std::fclose(f);
    EXPECT_EQ(std::string(text, size),
              "warning: line 4 (N60): SelfApproach: near\nnotice: held 2 moves\n"
              "notice: line 7: no tool\n");
    std::free(text);
}

// ---- the distance and the closest name (pure functions)

TEST(ApcictlSuggest, EditDistanceCountsInsertionsDeletionsSubstitutionsAndSwaps) {
    EXPECT_EQ(edit_distance("read", "read"), 0u);
    EXPECT_EQ(edit_distance("raed", "read"), 1u);  // two neighbours swapped: one edit
    EXPECT_EQ(edit_distance("--tool", "--tools"), 1u);
    EXPECT_EQ(edit_distance("stat", "status"), 2u);
    EXPECT_EQ(edit_distance("", "abc"), 3u);
    EXPECT_EQ(edit_distance("abc", ""), 3u);
    EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
    EXPECT_EQ(edit_distance("READ", "read"), 0u);  // case is not a difference
    EXPECT_EQ(edit_distance("ca", "abc"), 3u);     // optimal string alignment, not unrestricted
}

TEST(ApcictlSuggest, ClosestNameWithinTheBoundOrNone) {
    const std::vector<std::string> commands{"read", "write", "script", "status", "spool", "direct",
                                            "ssf",  "step",  "run",    "list",   "diff"};
    EXPECT_EQ(closest_name("raed", commands), "read");
    EXPECT_EQ(closest_name("wirte", commands), "write");
    EXPECT_EQ(closest_name("stat", commands), "status");
    EXPECT_EQ(closest_name("rn", commands), "run");
    EXPECT_EQ(closest_name("frobnicate", commands), "");
    EXPECT_EQ(closest_name("xyz", commands), "");
    const std::vector<std::string> options{"--tools", "--svg",    "--json", "--csv",
                                           "-d",      "--device", "--help", "-h"};
    EXPECT_EQ(closest_name("--tool", options), "--tools");
    EXPECT_EQ(closest_name("--jsno", options), "--json");
    EXPECT_EQ(closest_name("--devise", options), "--device");
    EXPECT_EQ(closest_name("-tools", options), "--tools");
    // One letter from another is no hint: "-x" is not a typo of "-d".
    EXPECT_EQ(closest_name("-x", options), "");
    EXPECT_EQ(closest_name("--frobnicate", options), "");
    // The closest wins, then the first.
    EXPECT_EQ(closest_name("--sv", options), "--svg");  // --csv is as close: the first wins
    EXPECT_EQ(closest_name("abcd", std::vector<std::string>{"abce", "abcd"}), "abcd");
    EXPECT_EQ(closest_name("abcd", std::vector<std::string>{}), "");
}

// ---- the command line

TEST(ApcictlCli, MistypedCommandSaysWhatWasMeant) {
    const auto r = test_support::apcictl({"raed", "1300", "0", "12", "0"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "apcictl: unknown command 'raed'; did you mean 'read'?\n");
    EXPECT_EQ(test_support::apcictl({"stat"}).err,
              "apcictl: unknown command 'stat'; did you mean 'status'?\n");
}

TEST(ApcictlCli, UnknownCommandWithNothingCloseListsTheCommands) {
    const auto r = test_support::apcictl({"frobnicate"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err,
              "apcictl: unknown command 'frobnicate' (commands: read, write, dump, script, shell, status, "
              "spool, direct, ssf, step, run, list, diff, help)\n");
}

TEST(ApcictlCli, NoCommandSaysSoAndListsThem) {
    const auto r = test_support::apcictl({});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.err.starts_with("apcictl: no command given (commands: read, write,")) << r.err;
    EXPECT_TRUE(r.err.ends_with("see 'apcictl --help')\n")) << r.err;
}

// A command's argument not given: the command named, and its help.
TEST(ApcictlCli, AMissingArgumentNamesItsCommandAndItsHelp) {
    auto r = test_support::apcictl({"run"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "apcictl: run: PROGRAM is required (see 'apcictl run --help')\n");
    r = test_support::apcictl({"run", "--tools", "t.tools"});
    EXPECT_EQ(r.err, "apcictl: run: PROGRAM is required (see 'apcictl run --help')\n");
    r = test_support::apcictl({"read"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "apcictl: read: NAME|BUS is required (see 'apcictl read --help')\n");
    // Other errors of a command's words name what they name, after the command's name.
    r = test_support::apcictl({"run", "--json"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "apcictl: run: --json: 1 required TEXT missing\n");
    r = test_support::apcictl({"run", "p.nc", "--self-approach", "maybe"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "apcictl: run: --self-approach: maybe not in {warn,error,off}\n");
}

TEST(ApcictlCli, AfterTheEndOfOptionsAMistypedCommandIsStillNamed) {
    EXPECT_EQ(test_support::apcictl({"--", "raed"}).err,
              "apcictl: unknown command 'raed'; did you mean 'read'?\n");
}

// An option without its value is that error, not "no command given".
TEST(ApcictlCli, OptionWithoutItsValueSaysSo) {
    const auto r = test_support::apcictl({"--device"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "apcictl: --device: 1 required TEXT missing\n");
}

TEST(ApcictlCli, MistypedOptionSaysWhatWasMeant) {
    auto r = test_support::apcictl({"run", "p.nc", "--tool", "t"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "apcictl: run: unknown option '--tool'; did you mean '--tools'?\n");
    r = test_support::apcictl({"run", "p.nc", "--tool=t"});
    EXPECT_EQ(r.err, "apcictl: run: unknown option '--tool'; did you mean '--tools'?\n");
    r = test_support::apcictl({"step", "--idel"});
    EXPECT_EQ(r.err, "apcictl: step: unknown option '--idel'; did you mean '--idle'?\n");
    // The command line's own options count too: --device may follow the command.
    r = test_support::apcictl({"status", "--devise", "emu:"});
    EXPECT_EQ(r.err, "apcictl: status: unknown option '--devise'; did you mean '--device'?\n");
    // Typed before the command: apcictl's own option, without a command's name.
    r = test_support::apcictl({"--devise", "emu:", "status"});
    EXPECT_EQ(r.err, "apcictl: unknown option '--devise'; did you mean '--device'?\n");
}

TEST(ApcictlCli, UnknownOptionWithNothingCloseNamesTheHelp) {
    const auto r = test_support::apcictl({"read", "--frobnicate", "1300", "0", "12", "0"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "apcictl: read: unknown option '--frobnicate' (see 'apcictl read --help')\n");
    EXPECT_EQ(test_support::apcictl({"-x"}).err, "apcictl: unknown option '-x' (see 'apcictl --help')\n");
    // Typed before the command it is apcictl's option that is unknown, after it the command's.
    EXPECT_EQ(test_support::apcictl({"-x", "read", "1300", "1", "1", "1"}).err,
              "apcictl: unknown option '-x' (see 'apcictl --help')\n");
    EXPECT_EQ(test_support::apcictl({"read", "-x", "1300", "1", "1", "1"}).err,
              "apcictl: read: unknown option '-x' (see 'apcictl read --help')\n");
    // A script line has its command only: that command's help.
    EXPECT_EQ(test_support::apcictl({"script", "-"}, "read --frobnicate 1300 1 1 1\n").err,
              "apcictl: line 1: read --frobnicate 1300 1 1 1: unknown option '--frobnicate' "
              "(see 'apcictl read --help')\n");
}

TEST(ApcictlCli, LeftOverArgumentsAreNamedInTheOrderTyped) {
    const auto r = test_support::apcictl({"read", "1300", "0", "12", "0", "5", "6"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "apcictl: read: The following arguments were not expected: 5 6\n");
}

TEST(ApcictlCli, MistypedScriptLinesSayWhatWasMeantToo) {
    const auto r =
        test_support::apcictl({"script", "-"}, "raed 1300 0 12 0\nstep --idel\nwrite --itn 1300 1 1 8 1\n");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err,
              "apcictl: line 1: unknown command 'raed'; did you mean 'read'?\n"
              "apcictl: line 2: step --idel: unknown option '--idel'; did you mean '--idle'?\n"
              "apcictl: line 3: write --itn 1300 1 1 8 1: unknown option '--itn'; did you mean "
              "'--int'?\n");
}

// Every line apcictl writes on stderr for these inputs is an error starting with "apcictl:".
TEST(ApcictlCli, EveryErrorLineStartsWithTheProgramName) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("apcictl_cli_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string bad_nc = (dir / "bad.nc").string();
    std::ofstream(bad_nc) << "N10 G01 X10 Q5\n";
    const std::string no_tool = (dir / "d.nc").string();
    std::ofstream(no_tool) << "N10 G01 X10 Y0 F600\nN20 G41 D1 X20\nM30\n";
    const std::string bad_tools = (dir / "bad.tools").string();
    std::ofstream(bad_tools) << "wz[1].radius abc\n";

    struct Case {
        std::vector<std::string> args;
        std::string input;
    };
    const std::vector<Case> cases{
        {{"raed"}, {}},                                               // bad command
        {{}, {}},                                                     // no command
        {{"run", no_tool, "--tool", "t"}, {}},                        // bad option
        {{"read", "--int", "--double", "1300", "0", "12", "0"}, {}},  // options that exclude
        {{"run", (dir / "missing.nc").string()}, {}},                 // missing file
        {{"script", (dir / "missing.script").string()}, {}},          // missing script
        {{"run", no_tool, "--plc", (dir / "missing.plc").string()}, {}},
        {{"read", "1300", "one", "1", "7"}, {}},         // bad object address
        {{"read", "9999", "0", "0", "0"}, {}},           // no such device
        {{"read", "1300", "1", "9", "3"}, {}},           // no such object
        {{"read", "1300", "1", "1"}, {}},                // address too short
        {{"write", "1300", "1", "1", "8", "abc"}, {}},   // bad value
        {{"write", "1300", "1", "1", "8", "2000"}, {}},  // value out of range
        {{"step", "0"}, {}},                             // count out of range
        {{"spool", "G01", "Q5"}, {}},                    // bad word
        {{"run", "--plane", "5", no_tool}, {}},
        {{"run", "--plane", "", no_tool}, {}},  // given, but empty
        {{"run", "--avoid-bottlenecks", "1", no_tool}, {}},
        {{"run", "--self-approach", "bogus", no_tool}, {}},
        {{"run", bad_nc}, {}},                                         // bad program
        {{"run", no_tool}, {}},                                        // run error
        {{"run", no_tool, "--tools", bad_tools}, {}},                  // bad tool list
        {{"-d", "unix:" + (dir / "no.sock").string(), "status"}, {}},  // unreachable device
        {{"-d", "bogus:", "status"}, {}},                              // bad device URI
        {{"-d", "usb:9:9", "status"}, {}},
        {{"script", "-"}, "write 1300 1 1 8 2000\nread 1300 1 9 3\n"},  // script line errors
        {{"script", "-", "--keep-going"}, "write 1300 1 1 8 2000\nread 1300 1 9 3\n"},
        {{"script", "-"}, "frobnicate\nwrite 1300 1 1 8\n"},
        {{"diff", "--against", "emu:", (dir / "missing.script").string()}, {}},
    };
    for (const Case& c : cases) {
        const auto r = test_support::apcictl(c.args, c.input);
        std::string typed;
        for (const auto& a : c.args) typed += " " + a;
        EXPECT_NE(r.exit_code, 0) << typed;
        const auto lines = lines_of(r.err);
        EXPECT_FALSE(lines.empty()) << typed;
        for (const std::string& line : lines)
            EXPECT_TRUE(line.starts_with("apcictl: ")) << typed << "\n  stderr line: " << line;
    }
    std::filesystem::remove_all(dir);
}

// The CSV of `run` names the board's axes as `step` (and spool, direct, ssf) names them.
TEST(ApcictlCli, CsvColumnsAreNamedAsTheCommandLineNamesTheAxes) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("apcictl_csv_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string program = (dir / "p.nc").string();
    std::ofstream(program) << "N10 G01 X1 Y0 F600\nM30\n";
    const std::string csv = (dir / "p.csv").string();
    const auto run = test_support::apcictl({"run", program, "--csv", csv});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    std::filesystem::remove_all(dir);

    // "cycle 1 (+1) fill 0/256 idle X0 Y0 Z0 A0 B0 C0 U0 V0": the letters before the numbers.
    const auto step = test_support::apcictl({"step", "1"});
    ASSERT_EQ(step.exit_code, 0) << step.err;
    std::string letters;
    std::istringstream words(step.out);
    for (std::string word; words >> word;)
        if (word.size() >= 2 && std::isupper(static_cast<unsigned char>(word[0])) != 0 &&
            (std::isdigit(static_cast<unsigned char>(word[1])) != 0 || word[1] == '-'))
            letters += std::string(",") + word[0];
    EXPECT_EQ(letters, ",X,Y,Z,A,B,C,U,V") << step.out;
    EXPECT_EQ(header, "cycle,time_s" + letters);
}

}  // namespace
