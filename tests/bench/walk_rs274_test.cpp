// SPDX-License-Identifier: MIT
// The benchmark's walk (bench/tools/walk_program.h) through LinuxCNC's interpreter rs274 as
// bench_rs274 runs it (its tool table, the rs274 dialect): the whole 100,000-block walk runs
// without an error. And why the walk keeps its corners at 0.06 rad or more: rs274 refuses an
// inside arc after an outside corner of under 0.05 rad (it joins that corner as tangent, so the
// arc's offset starts before the arc), where `apcictl run` compensates it without an error
// (docs/compensation.md, "Agreement with LinuxCNC"). Skipped where rs274 cannot be had.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "linuxcnc.h"
#include "process.h"
#include "scratch_dir.h"
#include "walk_program.h"

namespace {

using apci::bench::Dialect;

const apci::test::Rs274& rs274() {
    return apci::test::test_rs274();
}

TEST(WalkRs274, TheBenchmarksWalkRunsWhole) {
    if (!rs274().why.empty()) GTEST_SKIP() << rs274().why;
    const auto program = apci::bench::walk_program(100'000, Dialect::kLinuxCnc);
    const auto r = apci::test::run_rs274(rs274(), {program.text},
                                         apci::bench::contour_rs274_tool_table(), 17, 1);
    ASSERT_EQ(r.size(), 1u);
    ASSERT_TRUE(r[0].ran);
    EXPECT_EQ(r[0].exit_code, 0) << r[0].error;
    // Every element is a feed move, and the outside corners add their transition arcs.
    EXPECT_GT(r[0].moves.size(), 100'000u - apci::bench::kWalkFrameBlocks);
}

// The smallest such program, in both dialects: a line, a G3 of radius 2.5 mm whose start turns
// 0.045 rad to the right of the line (an outside corner under G41), and a line leaving it at an
// outside corner of 30 degrees. The corner 0.06 rad instead is accepted by both.
std::string slight_corner(double i, double j, const char* arc_end, const char* line_end,
                          Dialect dialect) {
    const bool ours = dialect == Dialect::kApcictl;
    std::string s = ours ? "%slight.nc\nN1 G17 G90 G26 F3000 D1\nN2 G0 X0 Y0 Z0\nN3 G41\n"
                         : "G21 G17 G90 G40 G49 G64\nT1 M6\nF3000\nG0 X0 Y0 Z0\nG41\n";
    char body[160];
    std::snprintf(body, sizeof body, "%sG1 X10 Y0\n%sG3 %s I%.4f J%.4f\n%sG1 %s\n",
                  ours ? "N4 " : "", ours ? "N5 " : "", arc_end, i, j, ours ? "N6 " : "", line_end);
    s += body;
    s += ours ? "N7 G40\nN8 G0 X0 Y-10\nN9 M30\n" : "G40\nG0 X0 Y-10\nM2\n";
    return s;
}


test_support::ProcessResult run_ours(const std::string& program) {
    test_support::ScratchDir scratch("apci-walk-rs274-");
    if (scratch.path().empty()) return {};
    const std::string tools = scratch.path() + "/walk.tools";
    std::FILE* f = std::fopen(tools.c_str(), "w");
    if (f == nullptr) return {};
    std::fputs(apci::bench::contour_tools(), f);
    if (std::fclose(f) != 0) return {};
    return test_support::run_process(
        {APCICTL_PATH, "run", "-", "--tools", tools, "--json", "/dev/null"}, program);
}

TEST(WalkRs274, RefusesAnInsideArcAfterASlightOutsideCorner) {
    if (!rs274().why.empty()) GTEST_SKIP() << rs274().why;
    const std::string table = apci::bench::contour_rs274_tool_table();
    // 0.045 rad: rs274 joins it as tangent and refuses the arc.
    const char* end45 = "X12.219 Y1.151";
    const char* leave45 = "X16.657 Y3.454";
    const auto slight = apci::test::run_rs274(
        rs274(), {slight_corner(0.1125, 2.4975, end45, leave45, Dialect::kLinuxCnc)}, table, 17, 1);
    ASSERT_EQ(slight.size(), 1u);
    EXPECT_NE(slight[0].exit_code, 0);
    EXPECT_NE(slight[0].error.find(
                  "Arc move in concave corner cannot be reached by the tool without gouging"),
              std::string::npos)
        << slight[0].error;
    const auto ours = run_ours(slight_corner(0.1125, 2.4975, end45, leave45, Dialect::kApcictl));
    EXPECT_EQ(ours.exit_code, 0) << ours.err;
    EXPECT_NE(ours.out.find("errors: none"), std::string::npos) << ours.out;
    // 0.06 rad: a corner to both.
    const char* end60 = "X12.236 Y1.118";
    const char* leave60 = "X16.708 Y3.354";
    const auto corner = apci::test::run_rs274(
        rs274(), {slight_corner(0.1499, 2.4955, end60, leave60, Dialect::kLinuxCnc)}, table, 17, 1);
    ASSERT_EQ(corner.size(), 1u);
    EXPECT_EQ(corner[0].exit_code, 0) << corner[0].error;
    const auto ours60 = run_ours(slight_corner(0.1499, 2.4955, end60, leave60, Dialect::kApcictl));
    EXPECT_EQ(ours60.exit_code, 0) << ours60.err;
}

}  // namespace
