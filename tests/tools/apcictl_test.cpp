// SPDX-License-Identifier: MIT
// apcictl run as a process: commands, scripts, status, exit codes, help.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "apcictl.h"
#include "text.h"

namespace {

using test_support::contains;
using test_support::apcictl;
using test_support::ProcessResult;

ProcessResult script(const std::string& text, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{"script", "-"};
    args.insert(args.end(), extra.begin(), extra.end());
    return apcictl(args, text);
}

// ---- the must-show lines

TEST(Apcictl, MustShowScriptWritesTheRadiusAndReadsItBack) {
    const auto r = script("write 1300 1 1 8 5\nwrite 1300 1 1 7 2.5\nread 1300 1 1 7\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "2.5\n");
    EXPECT_EQ(r.err, "");
}

TEST(Apcictl, MustShowStatusNamesTheBits) {
    const auto r = apcictl({"status"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("^board \\(bus 1000\\): spooler 0 of [1-9][0-9]* profiles\n")))
        << r.out;
    EXPECT_TRUE(contains(r.out, "\nmotion: free\n")) << r.out;  // the run's own board: no holder
    EXPECT_TRUE(contains(r.out, "TC module (bus 1300): TcPlane 17 (X-Y)\n")) << r.out;
    for (int g = 1; g <= 3; ++g)
        EXPECT_TRUE(contains(r.out, "group " + std::to_string(g) + ": ERROR 0x")) << r.out;
    EXPECT_TRUE(contains(r.out, "active group: ERROR")) << r.out;
    EXPECT_TRUE(contains(r.out, "(Run off, ProfMarked off)")) << r.out;
}

// ---- read

TEST(ApcictlRead, TypeFollowsTheObject) {
    auto r = apcictl({"read", "1300", "0", "12", "0"});  // TcPlane, int
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "17\n");
    r = script("write 1300 1 1 7 0.125\nread 1300 1 1 7\n");  // RADIUS, double
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "0.125\n");
}

TEST(ApcictlRead, ForcedTypeThatDoesNotMatchIsABoardError) {
    const auto r = apcictl({"read", "--int", "1300", "1", "1", "7"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(contains(r.err, "apcictl: read --int 1300 1 1 7: TypeMismatch (")) << r.err;
}

TEST(ApcictlRead, ForcedTypeThatMatchesReads) {
    const auto r = apcictl({"read", "--double", "1300", "0", "20", "0"});  // RotAngle
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "0\n");
}

TEST(ApcictlRead, MissingObjectIsABoardErrorNamingIt) {
    const auto r = apcictl({"read", "1300", "1", "9", "3"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "read 1300 1 9 3: ObjectMissing (object index does not exist)"))
        << r.err;
}

TEST(ApcictlRead, NonNumericAddressIsUsage) {
    const auto r = apcictl({"read", "1300", "one", "1", "7"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "DEV")) << r.err;
}

TEST(ApcictlRead, MissingArgumentIsUsage) {
    const auto r = apcictl({"read", "1300", "1", "1"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "SUB")) << r.err;
}

TEST(ApcictlRead, IntAndDoubleFlagsExcludeEachOther) {
    const auto r = apcictl({"read", "--int", "--double", "1300", "1", "1", "7"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
}

// ---- write

TEST(ApcictlWrite, IntegerToADoubleObjectIsWrittenAsThatDouble) {
    const auto r = script("write 1300 1 1 7 3\nread 1300 1 1 7\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "3\n");
}

TEST(ApcictlWrite, FractionToAnIntObjectIsAClearError) {
    const auto r = apcictl({"write", "1300", "1", "1", "8", "2.5"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "write 1300 1 1 8 2.5: TypeMismatch (")) << r.err;
    EXPECT_TRUE(contains(r.err, "object 1300/1/1/8 holds an int32, and 2.5 is not an int32 value"))
        << r.err;
}

TEST(ApcictlWrite, FractionToAnIntObjectChangesNothing) {
    const auto r = script("write 1300 1 1 8 5\nwrite 1300 1 1 8 2.5\nread 1300 1 1 8\n",
                          {"--keep-going"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "5\n");
}

TEST(ApcictlWrite, HexIntegersAreInts) {
    const auto r = script("write 1300 1 1 8 0x10\nread 1300 1 1 8\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "16\n");
}

TEST(ApcictlWrite, NegativeValueReachesTheBoard) {
    const auto r = apcictl({"write", "1300", "1", "1", "8", "-1"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "write 1300 1 1 8 -1: ValueTooLow")) << r.err;
}

TEST(ApcictlWrite, NotANumberIsUsage) {
    const auto r = apcictl({"write", "1300", "1", "1", "8", "five"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "VALUE 'five' is not a number")) << r.err;
}

TEST(ApcictlWrite, ForcedIntWithAFractionIsUsage) {
    const auto r = apcictl({"write", "--int", "1300", "1", "1", "8", "2.5"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "VALUE '2.5' is not an int32 (--int)")) << r.err;
}

TEST(ApcictlWrite, ForcedDoubleOnAnIntObjectIsABoardError) {
    const auto r = apcictl({"write", "--double", "1300", "1", "1", "8", "3"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "write --double 1300 1 1 8 3: TypeMismatch")) << r.err;
}

TEST(ApcictlWrite, NanIsRefusedByTheBoard) {
    const auto r = apcictl({"write", "1300", "1", "1", "7", "nan"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "InvalidValue")) << r.err;
}

TEST(ApcictlWrite, IntegerOutOfInt32RangeToAnIntObjectIsAClearError) {
    const auto r = apcictl({"write", "1300", "1", "1", "8", "3000000000"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "3000000000 is not an int32 value")) << r.err;
}

// ---- script

TEST(ApcictlScript, StateCarriesFromLineToLine) {
    const auto r = script("write 1300 1 2 8 12\nwrite 1300 1 2 7 1.5\nwrite 1300 1 2 8 13\n"
                          "write 1300 1 2 7 0.5\nwrite 1300 1 2 8 12\nread 1300 1 2 7\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "1.5\n");  // RADIUS belongs to the tool WKZINDEX selects
}

TEST(ApcictlScript, CommentsAndBlankLinesAreIgnoredButCounted) {
    const auto r = script("# set up\n\n   \nwrite 1300 1 1 8 4   # tool 4\nread 1300 1 1 8\n"
                          "read 1300 1 9 3\n");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "4\n");
    EXPECT_TRUE(contains(r.err, "line 6: read 1300 1 9 3: ObjectMissing")) << r.err;
}

TEST(ApcictlScript, StopsAtTheFirstFailingLineAndNamesIt) {
    const auto r = script("read 1300 1 1 8\nwrite 1300 1 1 8 2000\nread 1300 1 1 8\n");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "0\n");  // the third line did not run
    EXPECT_EQ(r.err,
              "apcictl: line 2: write 1300 1 1 8 2000: ValueTooHigh (value above the object's range)\n");
}

TEST(ApcictlScript, StateRuleFailureStopsTheScriptAndNamesTheLine) {
    // XAxis may change only while compensation is inactive ([APCI-TC] Table 3).
    const auto r = script("write 1300 1 1 8 1\nwrite 1300 1 1 7 2\nwrite 1300 1 1 9 1\n"
                          "write 1300 1 1 3 1\nwrite 1300 1 1 4 2\nread 1300 1 1 3\n");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err,
              "apcictl: line 5: write 1300 1 1 4 2: WrongDeviceState (not possible in the present device "
              "state); group 1's ERROR now reads 0x01 (InitError); this object changes only while "
              "the group is inactive: write STATUS = 0 first ([APCI-TC] Table 3) (clear it: write "
              "1300 1 1 1 0)\n");
}

// A refusal of the OTC module names what its LastError records ([ISG-OTC] section 1: #OTC ON
// with a tool that is not a grinding tool is P-ERR-21391), as `apcictl run` does; a refusal
// without a LastError says nothing more.
TEST(ApcictlWrite, AnOtcRefusalNamesTheModulesLastError) {
    const auto r = apcictl({"write", "otc.channel.active", "1"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err,
              "apcictl: write otc.channel.active 1: WrongDeviceState (not possible in the present "
              "device state); the OTC module's LastError (1330 0 7 0) reads 21391: P-ERR-21391 "
              "(OTC needs a grinding tool (tool type 2, P-TOOL-00001); OTC stays off)\n");
    const auto s = script("write otc.axis[1].command 10\n");
    EXPECT_EQ(s.err,
              "apcictl: line 1: write otc.axis[1].command 10: ValueTooHigh (value above the "
              "object's range); the OTC module's LastError (1330 0 7 0) reads 21904: "
              "OTC_INFEED_BEYOND_LIMIT (discrete offset beyond grinding_max_infeed (P-TOOL-00031) "
              "of the current tool)\n");
    const auto range = apcictl({"write", "otc.channel.acc_weight", "101"});
    EXPECT_EQ(range.err,
              "apcictl: write otc.channel.acc_weight 101: ValueTooHigh (value above the object's "
              "range)\n");
}

TEST(ApcictlWrite, StatusOneOnAGroupNotInitialisedSaysThatErrorNowReadsInitErrorAndWhatItNeeds) {
    const auto r = apcictl({"write", "1300", "1", "2", "3", "1"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err,
              "apcictl: write 1300 1 2 3 1: WrongDeviceState (not possible in the present device "
              "state); group 2's ERROR now reads 0x01 (InitError); STATUS = 1 needs the group "
              "initialised: XAxis, YAxis and ZAxis distinct and on no axis of a running group, and "
              "Left or Right written ([APCI-TC] Table 3) (clear it: write 1300 1 2 1 0)\n");
    // A refusal that sets no TC bit says nothing more.
    const auto high = apcictl({"write", "1300", "1", "1", "8", "2000"});
    EXPECT_EQ(high.err,
              "apcictl: write 1300 1 1 8 2000: ValueTooHigh (value above the object's range)\n");
}

// ReInit mid-contour is not emulated (docs/object-map.md 3.4): the refusal says so and what to do.
TEST(ApcictlScript, ReInitWhileAProfileIsHeldSaysItIsNotEmulatedAndWhatToDo) {
    const auto r = script("write 1300 1 1 9 1\nwrite 1300 1 1 3 1\nspool G01 N1 X10 Y0 F600\n"
                          "write 1300 0 13 0 0\n");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err,
              "apcictl: line 4: write 1300 0 13 0 0: WrongDeviceState (not possible in the present device "
              "state); ReInit while a contour is under way (a profile held, STATUS bit ProfMarked) "
              "is not emulated: [APCI-TC] gives it for before a re-reference and does not say what "
              "it does to a contour; end the contour first (STATUS = 0, or SSF 2001 to its axes), "
              "or write Reset (1300 0 14) to drop it\n");
}

TEST(ApcictlScript, KeepGoingRunsEveryLineAndExitsWithTheFirstFailure) {
    const auto r = script("write 1300 1 1 8 2000\nread 1300 1 1 8\nread 1300 1 9 3\nread 1300 0 12 0\n",
                          {"--keep-going"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "0\n17\n");
    EXPECT_TRUE(contains(r.err, "line 1: write 1300 1 1 8 2000: ValueTooHigh")) << r.err;
    EXPECT_TRUE(contains(r.err, "line 3: read 1300 1 9 3: ObjectMissing")) << r.err;
    EXPECT_TRUE(contains(r.err, "script: 2 of 4 lines failed")) << r.err;
}

TEST(ApcictlScript, AMalformedLineRunsNothing) {
    const auto r = script("read 1300 0 12 0\nwrite 1300 1 1 8\nread 1300 0 12 0\n");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(contains(r.err, "line 2: write 1300 1 1 8: VALUE is required")) << r.err;
}

TEST(ApcictlScript, UnknownCommandNamesTheScriptCommands) {
    const auto r = script("frobnicate 1\n");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "line 1: unknown command 'frobnicate' (script commands: read, "
                                "write, status, spool, direct, ssf, step)"))
        << r.err;
}

TEST(ApcictlScript, ScriptInAScriptIsNotACommand) {
    const auto r = script("script -\n");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "unknown command 'script'")) << r.err;
}

TEST(ApcictlScript, LineOptionsWorkAsOnTheCommandLine) {
    const auto r = script("read --double 1300 0 21 0\nwrite --int 1300 1 1 8 7\nread 1300 1 1 8\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "0\n7\n");
}

TEST(ApcictlScript, StatusIsAScriptCommand) {
    const auto r = script("status\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "group 1: ERROR")) << r.out;
}

TEST(ApcictlScript, ReadsAFile) {
    const std::string path = ::testing::TempDir() + "apcictl_script_test.txt";
    FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("write 1300 1 3 8 9\nread 1300 1 3 8\n", f);
    std::fclose(f);
    const auto r = apcictl({"script", path});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "9\n");
}

TEST(ApcictlScript, MissingFileIsUsage) {
    const auto r = apcictl({"script", "/nonexistent/script.txt"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "cannot open '/nonexistent/script.txt'")) << r.err;
}

TEST(ApcictlScript, EmptyScriptSucceeds) {
    const auto r = script("# nothing\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "");
}

// ---- status

TEST(ApcictlStatus, NamesInitErrorAfterAnActivationWithoutInitialisation) {
    const auto r = script("write 1300 1 1 3 1\nstatus\n", {"--keep-going"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.out, "group 1: ERROR 0x01 InitError; STATUS 0x00 (Run off, ProfMarked off)\n"))
        << r.out;
    EXPECT_TRUE(contains(r.out, "group 2: ERROR 0x00 none; STATUS 0x00 (Run off, ProfMarked off)\n"))
        << r.out;
}

TEST(ApcictlStatus, WithoutOptionTcSaysSo) {
    const auto r = apcictl({"--device", "emu:?no-option-tc", "status"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::regex_match(r.out, std::regex("board \\(bus 1000\\): spooler 0 of [1-9][0-9]* profiles\n"
                                                   "motion: free\n"
                                                   "TC module \\(bus 1300\\): absent, the firmware "
                                                   "has no optionTC\n")))
        << r.out;
}

TEST(ApcictlStatus, DeviceComesFromTheEnvironment) {
    const auto r = apcictl({"status"}, {}, {{"APCI_DEVICE", "emu:?no-option-tc"}});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "absent")) << r.out;
}

TEST(ApcictlStatus, NamesTheRunBitOfAnActiveGroup) {
    const auto r = script("write 1300 1 1 2 0\nwrite 1300 1 1 4 0\nwrite 1300 1 1 5 1\n"
                          "write 1300 1 1 11 2\nwrite 1300 1 1 8 1\nwrite 1300 1 1 7 2\n"
                          "write 1300 1 1 9 1\nwrite 1300 1 1 3 1\nstatus\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "group 1: ERROR 0x00 none; STATUS 0x01 (Run on, ProfMarked off)"))
        << r.out;
}

// ---- devices and exit codes

TEST(ApcictlDevice, UnreachableBoardIsABoardError) {
    const auto r = apcictl({"--device", "unix:/nonexistent/apci8001.sock", "read", "1300", "0", "12", "0"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "TransportError")) << r.err;
    EXPECT_TRUE(contains(r.err, "connect /nonexistent/apci8001.sock")) << r.err;
}

TEST(ApcictlDevice, MalformedUriIsUsage) {
    const auto r = apcictl({"--device", "emu:?turbo", "status"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "unknown emu: option 'turbo'")) << r.err;
}

TEST(ApcictlDevice, DeviceMayFollowTheCommand) {
    const auto r = apcictl({"status", "--device", "emu:?no-option-tc"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "absent")) << r.out;
}

TEST(ApcictlUsage, NoCommandIsUsage) {
    const auto r = apcictl({});
    EXPECT_EQ(r.exit_code, 2);
}

TEST(ApcictlUsage, UnknownCommandIsUsage) {
    const auto r = apcictl({"launch"});
    EXPECT_EQ(r.exit_code, 2);
}

TEST(ApcictlUsage, UnknownOptionIsUsage) {
    const auto r = apcictl({"read", "--float", "1300", "1", "1", "7"});
    EXPECT_EQ(r.exit_code, 2);
}

TEST(ApcictlUsage, VersionPrintsTheLibraryVersion) {
    const auto r = apcictl({"--version"});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out, "apcictl (apci8001) 0.2.0\nlibapci 0.2.0\n");
}

class ApcictlHelp : public ::testing::TestWithParam<const char*> {};

TEST_P(ApcictlHelp, EveryCommandHasHelp) {
    std::vector<std::string> args;
    if (!std::string(GetParam()).empty()) args.emplace_back(GetParam());
    args.emplace_back("--help");
    const auto r = apcictl(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "Usage:")) << r.out;
    EXPECT_TRUE(contains(r.out, "apcictl")) << r.out;
    EXPECT_TRUE(contains(r.out, GetParam())) << r.out;
}

INSTANTIATE_TEST_SUITE_P(Commands, ApcictlHelp,
                         ::testing::Values("", "read", "write", "script", "status"));

// ---- numbers: parsed with their range checked (hardening issue, item 4)

TEST(ApcictlNumbers, NegativeOrWrappingCyclesAreUsageErrorsNamingTheRange) {
    // `step -- -1` was 2^64-1 cycles and `step 2^64` wrapped: both ran the clock for hours.
    for (const char* cycles :
         {"-1", "18446744073709551616", "18446744073709551615", "0", "1000000001", "1e3", "5x"}) {
        const auto r = apcictl({"step", "--", cycles});
        EXPECT_EQ(r.exit_code, 2) << cycles;
        EXPECT_EQ(r.out, "") << cycles;
        EXPECT_TRUE(contains(
            r.err, std::string("CYCLES '") + cycles + "' is not a whole number in 1..1000000000"))
            << r.err;
    }
    const auto max = apcictl({"step", "--idle", "--max", "-1"});
    EXPECT_EQ(max.exit_code, 2);
    EXPECT_TRUE(contains(max.err, "--max '-1' is not a whole number in 1..1000000000")) << max.err;
    const auto ok = apcictl({"step", "1000000000"});
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
    EXPECT_TRUE(contains(ok.out, "cycle 1000000000 (+1000000000)")) << ok.out;
}

TEST(ApcictlNumbers, ObjectAddressesAreInt32s) {
    const auto r = apcictl({"read", "1300", "1", "1", "99999999999"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err,
                         "read 1300 1 1 99999999999: SUB '99999999999' is not a whole "
                         "number in -2147483648..2147483647"))
        << r.err;
    const auto w = apcictl({"write", "4294968596", "1", "1", "7", "1"});  // 2^32 + 1300
    EXPECT_EQ(w.exit_code, 2);
    EXPECT_TRUE(contains(w.err, "BUS '4294968596' is not a whole number")) << w.err;
    // In range but no such bus: the board says so.
    const auto b = apcictl({"read", "--", "-1", "1", "1", "1"});
    EXPECT_EQ(b.exit_code, 1);
    EXPECT_TRUE(contains(b.err, "NoSuchDevice")) << b.err;
    // Hexadecimal as for VALUE.
    const auto hex = apcictl({"read", "0x514", "0", "12", "0"});  // TcPlane
    EXPECT_EQ(hex.exit_code, 0) << hex.err;
    EXPECT_EQ(hex.out, "17\n");
}

TEST(ApcictlNumbers, ScriptLinesCheckTheirNumbersBeforeAnyRuns) {
    const auto r = script("step 1\nstep -1\nread 1300 1 1 -99999999999\n");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(contains(r.err, "line 2: step -1: CYCLES '-1' is not a whole number")) << r.err;
    EXPECT_TRUE(contains(r.err, "line 3: read 1300 1 1 -99999999999: SUB")) << r.err;
}

TEST(ApcictlNumbers, DiffToleranceMustBeFiniteAndNotNegative) {
    for (const char* t : {"nan", "inf", "-1", "-.5", "x"}) {
        const auto r = apcictl({"diff", "--against", "emu:", "--tolerance", t, "no-such.nc"});
        EXPECT_EQ(r.exit_code, 2) << t;
        EXPECT_TRUE(
            contains(r.err, std::string("--tolerance '") + t + "' is not a finite number >= 0"))
            << r.err;
    }
}

// ---- negative values reach the write (hardening issue, item 10)

TEST(ApcictlNegativeValues, ReachTheWriteAndTheObjectsOwnRangeCheck) {
    // RADIUS (1300 1 1 7) refuses a negative value; CLI11 took -.5 for an option.
    const auto half = apcictl({"write", "1300", "1", "1", "7", "-.5"});
    EXPECT_EQ(half.exit_code, 1) << half.err;
    EXPECT_TRUE(contains(half.err, "write 1300 1 1 7 -.5: ValueTooLow")) << half.err;
    for (const char* v : {"-inf", "-nan"}) {
        const auto r = apcictl({"write", "1300", "1", "1", "7", v});
        EXPECT_EQ(r.exit_code, 1) << v;
        EXPECT_TRUE(contains(r.err, std::string("write 1300 1 1 7 ") + v + ": InvalidValue"))
            << r.err;
    }
    // `--` still works, and options may still follow the value.
    const auto mark = apcictl({"write", "1300", "1", "1", "7", "--", "-.5"});
    EXPECT_EQ(mark.exit_code, 1);
    EXPECT_TRUE(contains(mark.err, "write 1300 1 1 7 -.5: ValueTooLow")) << mark.err;
    const auto forced = apcictl({"write", "1300", "1", "1", "7", "-.5", "--int"});
    EXPECT_EQ(forced.exit_code, 2);
    EXPECT_TRUE(contains(forced.err, "VALUE '-.5' is not an int32 (--int)")) << forced.err;
    // A negative value an object takes: RotAngle (1300 0 20 0, double).
    const auto angle = script("write 1300 0 20 0 -.5\nread 1300 0 20 0\n");
    EXPECT_EQ(angle.exit_code, 0) << angle.err;
    EXPECT_EQ(angle.out, "-0.5\n");
}

TEST(ApcictlNegativeValues, InScriptLinesToo) {
    const auto r = script("write 1300 1 1 7 -.5\nwrite 1300 1 1 7 -inf\nwrite 1300 1 1 7 -nan\n",
                          {"--keep-going"});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "line 1: write 1300 1 1 7 -.5: ValueTooLow")) << r.err;
    EXPECT_TRUE(contains(r.err, "line 2: write 1300 1 1 7 -inf: InvalidValue")) << r.err;
    EXPECT_TRUE(contains(r.err, "line 3: write 1300 1 1 7 -nan: InvalidValue")) << r.err;
    EXPECT_FALSE(contains(r.err, "is required")) << r.err;
    // An unexpected negative number is named as typed.
    const auto extra = apcictl({"step", "5", "-.5"});
    EXPECT_EQ(extra.exit_code, 2);
    EXPECT_TRUE(contains(extra.err, "not expected: -.5\n")) << extra.err;
}

}  // namespace
