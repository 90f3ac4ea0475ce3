// SPDX-License-Identifier: MIT
// apcictl's motion commands (spool, direct, ssf, step) in scripts: one board
// session carries the spooler, the held profile and the clock between lines.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "process.h"
#include "text.h"

namespace {

using test_support::contains;
using test_support::ProcessResult;

ProcessResult script(const std::string& text) {
    return test_support::run_process({APCICTL_PATH, "script", "-"}, text);
}

// Group 1 (axes X Y Z), radius 1, left, active ([APCI-TC] section 2.5).
const std::string kCompensate =
    "write 1300 1 1 7 1\n"
    "write 1300 1 1 9 0\n"
    "write 1300 1 1 3 1\n";

TEST(ApcictlMotion, SpoolAndStepMoveTheAxes) {
    const auto r = script("spool G01 N1 X10 F600\nstep 250\nstep --idle\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out,
              "cycle 250 (+250) fill 1/256 moving X2.5 Y0 Z0 A0 B0 C0 U0 V0\n"
              "cycle 1000 (+750) fill 0/256 idle X10 Y0 Z0 A0 B0 C0 U0 V0\n");
}

TEST(ApcictlMotion, ArcWordsIAndJAreTheCentreOnTheArcAxes) {
    const auto r = script("spool G01 N1 X10 F600\nspool G03 N2 X0 Y10 I0 J0 F600\nstep --idle\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "idle X0 Y10 ")) << r.out;
}

TEST(ApcictlMotion, HeldProfileShowsInStatusAndSsf2001ReleasesIt) {
    const auto r = script(kCompensate + "spool G01 N1 X10 Y0 F600\nstatus\nssf XY 2001\nstatus\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto first = r.out.find("group 1: ERROR 0x00 none; STATUS 0x03 (Run on, ProfMarked on)");
    const auto second =
        r.out.find("group 1: ERROR 0x00 none; STATUS 0x01 (Run on, ProfMarked off)");
    EXPECT_NE(first, std::string::npos) << r.out;
    EXPECT_NE(second, std::string::npos) << r.out;
    EXPECT_LT(first, second);
}

TEST(ApcictlMotion, TcErrorNamesTheLineGroupBitsAndBlock) {
    const auto r = script(kCompensate +
                          "spool G01 N1 X10 Y-10 F600\n"
                          "spool G03 N3 X0 Y10 I0 J0 F600\n"
                          "step --idle\n");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "line 5: spool G03 N3 X0 Y10 I0 J0 F600: WrongDeviceState"))
        << r.err;
    EXPECT_TRUE(contains(r.err, "TC group 1 ERROR bits 0x10, block 3")) << r.err;
    EXPECT_EQ(r.out, "") << "the script stops at the failing line";
}

TEST(ApcictlMotion, DirectJsStopsTheAxesWhereTheyAre) {
    const auto r = script("spool G01 N1 X1 F600\nstep 50\ndirect JS\nstep 10\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "cycle 60 (+10) fill 0/256 idle X0.5 Y0")) << r.out;
}

TEST(ApcictlMotion, DirectJaJogsTheNamedAxes) {
    const auto r = script("direct JA Z-3 F6000\nstep --idle\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "idle X0 Y0 Z-3 ")) << r.out;
}

TEST(ApcictlMotion, BoardRefusalIsABoardError) {
    const auto r = script("spool G01 N1 X10 F0\n");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "line 1: spool G01 N1 X10 F0: ValueTooLow")) << r.err;
    EXPECT_TRUE(contains(r.err, "feed")) << r.err;
}

struct BadLine {
    const char* line;
    const char* says;
};

class ApcictlMotionUsage : public ::testing::TestWithParam<BadLine> {};

TEST_P(ApcictlMotionUsage, IsAUsageErrorAndNothingRuns) {
    // The first line would print; a usage error anywhere means no line runs.
    const auto r = script(std::string("step 1\n") + GetParam().line + "\n");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(contains(r.err, "line 2: ")) << r.err;
    EXPECT_TRUE(contains(r.err, GetParam().says)) << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Lines, ApcictlMotionUsage,
    ::testing::Values(BadLine{"spool G04 X1", "is not G00, G01, G02, G03 or TRAVERSE"},
                      BadLine{"spool G02 X1 Y1 F10", "an arc needs its centre"},
                      BadLine{"spool G01 X1 X2 F10", "'X' is given twice"},
                      BadLine{"spool G01 Xten F10", "is not a number"},
                      BadLine{"spool G01 Q5 F10", "unknown word"},
                      BadLine{"spool G01 N-1 X1 F10", "N needs a block number"},
                      BadLine{"spool G01 I1 X1 F10", "unknown word"},
                      BadLine{"spool G03 X1 I0 J0 F10 --arc-axes XX", "--arc-axes 'XX'"},
                      BadLine{"direct JS X1", "JS takes no words"},
                      BadLine{"direct JA F100", "JA needs an axis target"},
                      BadLine{"direct JX X1", "is not JA or JS"},
                      BadLine{"ssf XQ 2001", "AXES 'XQ'"}, BadLine{"ssf XY two", "COMMAND 'two'"},
                      BadLine{"step", "give CYCLES > 0 or --idle"}));

}  // namespace
