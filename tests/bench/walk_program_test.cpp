// SPDX-License-Identifier: MIT
// The benchmark's walk (bench/tools/walk_program.h), the program bench_rs274 runs beside the
// repeating star: the two dialects hold the same path, the program is the one whose figures
// docs/performance.md reports (its digest), it keeps the rules its comment states (read back
// from its text as an interpreter reads it: directions within 0.75 rad of +X, corners of 0.06
// rad or more, tangent joins tangent up to rounding, 3 and 4 decimals, Y within 40 mm), and
// its first blocks run through `apcictl run` without an error or a warning.
#include "walk_program.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "process.h"
#include "scratch_dir.h"
#include "text.h"

namespace {

using apci::bench::Dialect;
using apci::bench::walk_program;

// The benchmark's walk: bench_rs274's kBlocks.
constexpr std::size_t kBenchBlocks = 100'000;

using test_support::lines_of;

// A block without its "N<number> ".
std::string without_n(const std::string& line) {
    if (line.empty() || line[0] != 'N') return line;
    const std::size_t space = line.find(' ');
    return space == std::string::npos ? std::string() : line.substr(space + 1);
}

std::uint64_t fnv1a(const std::string& text) {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (const char c : text) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ULL;
    }
    return h;
}

// The value of `letter` in a block ("G2 X.. Y.. I.. J.."), and its decimals.
struct Word {
    bool found = false;
    double value = 0.0;
    int decimals = 0;
};
Word word(const std::string& block, char letter) {
    Word w;
    const std::size_t at = block.find(std::string(" ") + letter);
    if (at == std::string::npos) return w;
    const char* begin = block.c_str() + at + 2;
    char* end = nullptr;
    w.value = std::strtod(begin, &end);
    w.found = end != begin;
    const char* dot = begin;
    while (dot < end && *dot != '.') ++dot;
    w.decimals = dot < end ? static_cast<int>(end - dot - 1) : 0;
    return w;
}

double wrap(double a) {
    while (a > M_PI) a -= 2.0 * M_PI;
    while (a <= -M_PI) a += 2.0 * M_PI;
    return a;
}

TEST(WalkProgram, BothDialectsHoldTheSameElements) {
    const auto ours = walk_program(kBenchBlocks, Dialect::kApcictl);
    const auto theirs = walk_program(kBenchBlocks, Dialect::kLinuxCnc);
    EXPECT_EQ(ours.blocks, kBenchBlocks);
    const auto a = lines_of(ours.text);
    const auto b = lines_of(theirs.text);
    // Ours: %walk.nc, N1 G17 .., N2 G0 .., N3 G41, elements, G40, M30.
    // rs274's: G21 .., T1 M6, F3000, G0 .., G41, elements, G40, M2.
    ASSERT_EQ(a.size(), kBenchBlocks + 1);
    ASSERT_EQ(b.size(), a.size() + 1);
    EXPECT_EQ(a[0], "%walk.nc");
    EXPECT_EQ(a[1], "N1 G17 G90 G26 F3000 D1");
    EXPECT_EQ(b[0], "G21 G17 G90 G40 G49 G64");
    EXPECT_EQ(b[1], "T1 M6");
    EXPECT_EQ(b[2], "F3000");
    EXPECT_EQ(a[2], "N2 G0 X-80000 Y0 Z0");
    EXPECT_EQ(b[3], "G0 X-80000 Y0 Z0");
    EXPECT_EQ(a[3], "N3 G41");
    EXPECT_EQ(b[4], "G41");
    for (std::size_t k = 4; k + 2 < a.size(); ++k) {
        ASSERT_EQ(a[k], "N" + std::to_string(k) + " " + without_n(a[k])) << k;
        ASSERT_EQ(without_n(a[k]), b[k + 1]) << "element " << k - 3;
    }
    EXPECT_EQ(a[a.size() - 2], "N" + std::to_string(kBenchBlocks - 1) + " G40");
    EXPECT_EQ(a.back(), "N" + std::to_string(kBenchBlocks) + " M30");
    EXPECT_EQ(b[b.size() - 2], "G40");
    EXPECT_EQ(b.back(), "M2");
}

// The walk whose figures docs/performance.md reports: a change of the generator shows here
// (and then the figures must be measured again).
TEST(WalkProgram, IsTheBenchmarksWalk) {
    const auto ours = walk_program(kBenchBlocks, Dialect::kApcictl);
    const auto theirs = walk_program(kBenchBlocks, Dialect::kLinuxCnc);
    EXPECT_EQ(ours.text, walk_program(kBenchBlocks, Dialect::kApcictl).text);
    EXPECT_EQ(ours.text.size(), 4'217'209u);
    EXPECT_EQ(fnv1a(ours.text), 8720324586500621677ULL);
    EXPECT_EQ(fnv1a(theirs.text), 4022553872006457168ULL);
    // A shorter walk is the longer one's beginning.
    const auto shorter = lines_of(walk_program(1'000, Dialect::kLinuxCnc).text);
    const auto longer = lines_of(theirs.text);
    for (std::size_t k = 0; k + 2 < shorter.size(); ++k) ASSERT_EQ(shorter[k], longer[k]) << k;
    // Another seed, another walk.
    EXPECT_NE(walk_program(1'000, Dialect::kApcictl, 12).text,
              walk_program(1'000, Dialect::kApcictl).text);
}

TEST(WalkProgram, LengthsOutsideItsRangeGiveNoProgram) {
    EXPECT_TRUE(walk_program(apci::bench::kWalkFrameBlocks, Dialect::kApcictl).text.empty());
    EXPECT_TRUE(walk_program(apci::bench::kWalkMaxBlocks + 1, Dialect::kApcictl).text.empty());
    EXPECT_EQ(walk_program(apci::bench::kWalkMaxBlocks, Dialect::kApcictl).blocks,
              apci::bench::kWalkMaxBlocks);
}

// Read back from the rs274 program's text, element by element.
TEST(WalkProgram, KeepsItsRules) {
    const auto lines = lines_of(walk_program(apci::bench::kWalkMaxBlocks, Dialect::kLinuxCnc).text);
    double x = -80000.0, y = 0.0, heading = 0.0;
    double min_corner = 10.0, max_tangent_turn = 0.0, max_heading = 0.0, max_y = 0.0;
    double min_radius = 1e9;
    int lines_count = 0, cw = 0, ccw = 0, corners = 0, tangents = 0;
    double last_z = 0.0;
    for (std::size_t k = 5; k + 2 < lines.size(); ++k) {
        const std::string& b = lines[k];
        const Word wx = word(b, 'X'), wy = word(b, 'Y');
        ASSERT_TRUE(wx.found && wy.found) << b;
        EXPECT_LE(wx.decimals, 3) << b;
        EXPECT_LE(wy.decimals, 3) << b;
        double start = 0.0, end = 0.0;
        if (b.rfind("G1 ", 0) == 0) {
            const Word wz = word(b, 'Z');
            ASSERT_TRUE(wz.found) << b;
            EXPECT_LE(wz.value, 0.0);
            EXPECT_GT(wz.value, -1.0);
            // Lowered 0.001 mm a step, back to 0 after -0.999.
            const bool wraps = last_z < -0.998 && wz.value == 0.0;
            EXPECT_TRUE(wraps || std::fabs(wz.value - last_z) <= 1e-3 + 1e-9) << b;
            last_z = wz.value;
            start = end = std::atan2(wy.value - y, wx.value - x);
            ++lines_count;
        } else {
            const bool is_ccw = b.rfind("G3 ", 0) == 0;
            ASSERT_TRUE(is_ccw || b.rfind("G2 ", 0) == 0) << b;
            const Word wi = word(b, 'I'), wj = word(b, 'J');
            ASSERT_TRUE(wi.found && wj.found) << b;
            EXPECT_LE(wi.decimals, 4) << b;
            EXPECT_LE(wj.decimals, 4) << b;
            const double cx = x + wi.value, cy = y + wj.value;
            const double quarter = is_ccw ? M_PI / 2 : -M_PI / 2;
            start = wrap(std::atan2(y - cy, x - cx) + quarter);
            end = wrap(std::atan2(wy.value - cy, wx.value - cx) + quarter);
            const double r0 = std::hypot(wi.value, wj.value);
            const double r1 = std::hypot(wx.value - cx, wy.value - cy);
            EXPECT_LT(std::fabs(r1 - r0), 2e-3) << b;
            min_radius = std::fmin(min_radius, r0);
            ++(is_ccw ? ccw : cw);
        }
        // Along +X only: never back near itself.
        EXPECT_GT(wx.value, x + 0.5) << b;
        max_heading = std::fmax(max_heading, std::fmax(std::fabs(start), std::fabs(end)));
        if (k > 5) {
            const double turn = std::fabs(wrap(start - heading));
            if (turn < 0.05) {
                max_tangent_turn = std::fmax(max_tangent_turn, turn);
                ++tangents;
            } else {
                min_corner = std::fmin(min_corner, turn);
                ++corners;
            }
        }
        max_y = std::fmax(max_y, std::fabs(wy.value));
        x = wx.value;
        y = wy.value;
        heading = end;
    }
    EXPECT_LT(x, 100000.0);  // inside the board's range
    EXPECT_LE(max_heading, 0.75 + 1e-9);
    EXPECT_LE(max_y, 40.0);
    EXPECT_GE(min_radius, 3.0 - 1e-3);
    // No join in LinuxCNC's band of turns it reads as tangent that is more than rounding.
    EXPECT_GE(min_corner, 0.06 - 1e-9);
    EXPECT_LT(max_tangent_turn, 2e-3);
    // All kinds, in about the stated shares.
    const double elements = static_cast<double>(lines_count + cw + ccw);
    EXPECT_NEAR(lines_count / elements, 0.40, 0.05);
    EXPECT_NEAR(cw / elements, 0.30, 0.05);
    EXPECT_NEAR(ccw / elements, 0.30, 0.05);
    EXPECT_NEAR(tangents / elements, 0.35, 0.08);
    EXPECT_NEAR(corners / elements, 0.65, 0.08);
}


TEST(WalkProgram, FirstBlocksRunInApcictl) {
    test_support::ScratchDir scratch("apci-walk-test-");
    ASSERT_FALSE(scratch.path().empty());
    const std::string tools = scratch.path() + "/walk.tools";
    std::FILE* f = std::fopen(tools.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs(apci::bench::contour_tools(), f);
    ASSERT_EQ(std::fclose(f), 0);
    const auto program = walk_program(3'000, Dialect::kApcictl);
    const auto r = test_support::run_process(
        {APCICTL_PATH, "run", "-", "--tools", tools, "--json", "-", "--self-approach", "error"},
        program.text);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("3000 blocks, 3000 sent to the board"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("errors: none"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("\"errors\":[]"), std::string::npos) << r.out.substr(0, 200);
    EXPECT_EQ(r.out.find("\"warnings\""), std::string::npos);
}

}  // namespace
