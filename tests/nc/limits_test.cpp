// SPDX-License-Identifier: MIT
// The front end's bounds on work (docs/nc-programs.md "Limits"): a feed so low that one move
// would take more than kMaxMoveCycles interpolation cycles, $FOR loops that do not end, and
// whole numbers out of range named as written (never clamped or wrapped).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "apci/nc/correction_table.h"
#include "apci/nc/lexer.h"
#include "apci/nc/move_time.h"
#include "apci/nc/tools.h"
#include "nc_test_util.h"
#include "text.h"

namespace apci::nc {
namespace {

using test_support::contains;
using test::error_of;
using test::events_of;
using test::only;

const std::string kForty = "1234567890123456789012345678901234567890";

// ---- Cycles per move

TEST(MoveLimit, CyclesAreTheBoardsCount) {
    EXPECT_EQ(move_cycles(10.0, 600.0, 0.001), 1000.0);  // 10 mm/s, 1 ms cycles
    EXPECT_EQ(move_cycles(10.005, 600.0, 0.001), 1001.0);
    EXPECT_EQ(move_cycles(0.0, 600.0, 0.001), 0.0);
    EXPECT_TRUE(std::isinf(move_cycles(1.0, 0.0, 0.001)));
    EXPECT_TRUE(check_move_cycles(1.0, 7e-5, 0.001).empty());   // 8.6e8 cycles
    EXPECT_FALSE(check_move_cycles(1.0, 5e-5, 0.001).empty());  // 1.2e9 cycles
    ArcMove half;
    half.start = {0, 0, 0};
    half.end = {2, 0, 0};
    half.center = {1, 0, 0};
    EXPECT_NEAR(move_length(half), std::numbers::pi, 1e-12);
    ArcMove full = half;
    full.end = full.start;
    full.ccw = true;
    EXPECT_NEAR(move_length(full), 2.0 * std::numbers::pi, 1e-12);
    // A radius far beyond the chord: nearly the chord, not a full circle of that radius.
    ArcMove flat;
    flat.start = {0, 0, 0};
    flat.end = {20, 0, 0};
    flat.center = {10, -1e200, 0};
    EXPECT_NEAR(move_length(flat), 20.0, 1e-9);
}

// The bound that spares the exact length (surely_within_move_cycles) never passes a move the
// exact count refuses, and passes the moves of real programs.
TEST(MoveLimit, TheBoundWithoutRootsPassesOnlyMovesTheExactCountTakes) {
    std::uint64_t state = 12345;
    auto uniform = [&state](double lo, double hi) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return lo + (hi - lo) * static_cast<double>(state >> 11) * 0x1.0p-53;
    };
    int surely = 0, refused = 0;
    for (int i = 0; i < 200000; ++i) {
        const double feed = std::pow(10.0, uniform(-7.0, 5.0));
        const double cycle = i % 3 == 0 ? 0.01 : 0.001;
        const double scale = std::pow(10.0, uniform(-3.0, 5.0));
        const Eigen::Vector3d a(uniform(-scale, scale), uniform(-scale, scale), uniform(-1, 1));
        const Eigen::Vector3d b(uniform(-scale, scale), uniform(-scale, scale), uniform(-1, 1));
        if (surely_within_move_cycles(a, b, feed, cycle)) {
            ++surely;
            EXPECT_TRUE(check_move_cycles(move_length(a, b), feed, cycle).empty()) << i;
        }
        ArcMove arc;
        arc.start = a;
        arc.center = Eigen::Vector3d(uniform(-scale, scale), uniform(-scale, scale), a.z());
        const double r = std::hypot(a.x() - arc.center.x(), a.y() - arc.center.y());
        const double t = uniform(0.0, 2.0 * std::numbers::pi);
        arc.end = arc.center + Eigen::Vector3d(r * std::cos(t), r * std::sin(t), b.z() - a.z());
        arc.ccw = i % 2 == 0;
        arc.plane = Plane::kXY;
        arc.feed = feed;
        const bool exact_ok = check_move_cycles(move_length(arc), feed, cycle).empty();
        if (!exact_ok) ++refused;
        if (surely_within_move_cycles(arc, cycle)) {
            ++surely;
            EXPECT_TRUE(exact_ok) << i;
        }
    }
    EXPECT_GT(surely, 100000);  // most of them: the exact length is rarely needed
    EXPECT_GT(refused, 1000);   // and the limit was reached often
    // A move of the benchmark contour (docs/performance.md) at F3000, 1 ms cycles.
    EXPECT_TRUE(surely_within_move_cycles({0, 0, 0}, {40, 0, 0}, 3000.0, 0.001));
    EXPECT_FALSE(surely_within_move_cycles({0, 0, 0}, {1, 0, 0}, 0.0, 0.001));
    EXPECT_FALSE(surely_within_move_cycles({0, 0, 0}, {1, 0, 0}, 1e308, 1.0));  // no finite bound
}

TEST(MoveLimit, AFeedTooLowForOneMoveIsAnErrorNamingTheBlockBeforeAnythingRuns) {
    // F0.000001 over 1 mm: 6e10 cycles of 1 ms. The validation pass refuses the program, so
    // nothing of it reaches a board (it ran for minutes, capped at 2^52 cycles, exit 0).
    const char* text = "N10 G1 X1 F100\nN20 G1 X2 F0.000001\nN30 M30\n";
    Result<Program> p = Program::from_text(text, "p.nc");
    ASSERT_FALSE(p);
    EXPECT_EQ(p.error().to_string(),
              "p.nc:2:11: N20: feed F1e-06 makes this 1 mm move take 60000000000 interpolation "
              "cycles; at most 1000000000 cycles (11.6 days at 1 ms) are allowed per move: "
              "raise F");
    // The feed is modal: a later move at the same feed is measured too, the block named.
    EXPECT_EQ(error_of("N10 G1 X0.000001 F0.000001\nN20 X5\nN30 M30\n").substr(0, 25),
              "prog.nc:2:5: N20: feed F1");
    // Arcs by their arc length: a half circle of radius 1 at F0.0002 is 9.4e8 cycles (taken),
    // the full circle 1.9e9 (refused).
    EXPECT_EQ(error_of("G2 X2 Y0 I1 J0 F0.0002\nM30\n"), "");
    EXPECT_TRUE(contains(error_of("G2 X0 Y0 I1 J0 F0.0002\nM30\n"),
                         "prog.nc:1:16: feed F0.0002 "
                         "makes this 6.28319 mm"));
    // Rapid moves have no feed of their own; G0 after a tiny F is fine.
    EXPECT_EQ(error_of("G1 X0 F0.000001\nG0 X100\nM30\n"), "");
}

TEST(MoveLimit, TheCycleTimeOfTheBoardDecides) {
    InterpreterOptions o;
    o.cycle_seconds = 0.01;  // 10 ms: F0.00005 over 1 mm is 1.2e8 cycles
    EXPECT_EQ(error_of("G1 X1 F0.00005\nM30\n", o), "");
    EXPECT_TRUE(contains(error_of("G1 X1 F0.00005\nM30\n"), "(11.6 days at 1 ms)"));
    o.cycle_seconds = 0.00025;
    EXPECT_TRUE(contains(error_of("G1 X1 F0.0002\nM30\n", o), "(2.9 days at 0.25 ms)"));
}

TEST(MoveLimit, KlartextLinesAreMeasuredToo) {
    const std::string text =
        "0 BEGIN PGM T MM\n1 L X+0 Y+0 Z+0 R0 F1000\n2 L X+1 F0.000001\n3 END PGM T MM\n";
    EXPECT_TRUE(contains(error_of(text),
                         "prog.nc:3:9: feed F1e-06 makes this 1 mm move take "
                         "60000000000 interpolation cycles"));
    EXPECT_EQ(error_of("0 BEGIN PGM T MM\n1 L X+0 Y+0 Z+0 R0 F0.000001\n2 L X+100 FMAX\n"
                       "3 END PGM T MM\n"),
              "");
}

// ---- $FOR loops

TEST(LoopLimit, ALoopWhoseBodyResetsItsParameterEndsWithAnErrorNamingTheLoop) {
    // It ran for ever. At the default limit (10^7 blocks) the error comes within seconds.
    const auto t0 = std::chrono::steady_clock::now();
    const std::string e =
        error_of("N5 G1 X0 F100\nN10 $FOR P1 = 0, 10, 1\nN20 P1 = 0\n$ENDFOR\nM30\n");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(e,
              "prog.nc:2:5: N10: $FOR P1 does not end: $FOR loops may run at most 10000000 "
              "blocks in all, every repetition counted, and this loop has repeated its body "
              "5000000 times: does the body set P1 back, or is the end value too far?");
    EXPECT_LT(seconds, 30.0);
}

TEST(LoopLimit, EveryRepetitionCountsAndBlocksOutsideLoopsDoNot) {
    InterpreterOptions o;
    o.max_loop_blocks = 100;
    // 50 repetitions of a one-block body plus its $ENDFOR: 100 blocks in the loop.
    EXPECT_EQ(error_of("$FOR P1 = 1, 50, 1\nP2 = P1\n$ENDFOR\nM30\n", o), "");
    // 51: one block too many.
    EXPECT_TRUE(contains(error_of("$FOR P1 = 1, 51, 1\nP2 = P1\n$ENDFOR\nM30\n", o),
                         "prog.nc:1:1: $FOR P1 does not end"));
    // A far end value is the same mistake.
    EXPECT_TRUE(contains(error_of("$FOR P1 = 0, 1000000000000000, 1\n$ENDFOR\nM30\n", o),
                         "has repeated its body 100 times"));
    // 200 blocks outside any loop: not counted.
    std::string flat;
    for (int i = 0; i < 200; ++i) flat += "P2 = 1\n";
    EXPECT_EQ(error_of(flat + "M30\n", o), "");
}

TEST(LoopLimit, TheLoopThatDoesNotEndIsNamedNotTheOneInsideIt) {
    InterpreterOptions o;
    o.max_loop_blocks = 1000;
    // The outer loop resets its parameter; the inner one ends every time.
    EXPECT_TRUE(contains(error_of("$FOR P1 = 0, 3, 1\n$FOR P2 = 0, 3, 1\n$ENDFOR\nP1 = 0\n"
                                  "$ENDFOR\nM30\n",
                                  o),
                         "prog.nc:1:1: $FOR P1 does not end"));
    // The inner loop resets its parameter inside a finite outer one.
    EXPECT_TRUE(contains(error_of("$FOR P1 = 0, 3, 1\n$FOR P2 = 0, 3, 1\nP2 = 0\n$ENDFOR\n"
                                  "$ENDFOR\nM30\n",
                                  o),
                         "prog.nc:2:1: $FOR P2 does not end"));
}

// ---- Whole numbers out of range, as written

TEST(NumbersAsWritten, WholeAtMostNeverWrapsOrClamps) {
    EXPECT_EQ(whole_at_most("18446744073709551615", std::numeric_limits<std::uint64_t>::max()),
              std::numeric_limits<std::uint64_t>::max());
    EXPECT_FALSE(whole_at_most("18446744073709551616", std::numeric_limits<std::uint64_t>::max()));
    EXPECT_FALSE(whole_at_most(kForty, std::numeric_limits<std::uint64_t>::max()));
    EXPECT_EQ(whole_at_most("000000000000000000000000000001023", 1023), 1023u);
    EXPECT_FALSE(whole_at_most("1024", 1023));
    EXPECT_FALSE(whole_at_most("9", 7));
    EXPECT_EQ(whole_at_most("", 7), 0u);
}

// The fast path (bounds below 2^64 / 10, one comparison a digit) answers as the digit-by-digit
// check of v * 10 + d > max does, around every bound and for every length.
TEST(NumbersAsWritten, WholeAtMostAnswersAsTheCarefulCheckForEveryBound) {
    auto careful = [](std::string_view digits, std::uint64_t max) -> std::optional<std::uint64_t> {
        std::uint64_t v = 0;
        for (const char c : digits) {
            const auto d = static_cast<std::uint64_t>(c - '0');
            if (d > max || v > (max - d) / 10) return std::nullopt;
            v = v * 10 + d;
        }
        return v;
    };
    constexpr std::uint64_t kTop = std::numeric_limits<std::uint64_t>::max();
    const std::uint64_t no_wrap = (kTop - 9) / 10;
    for (const std::uint64_t max : {std::uint64_t{0}, std::uint64_t{7}, std::uint64_t{9},
                                    std::uint64_t{10}, std::uint64_t{1023}, kMaxWordNumber,
                                    no_wrap - 1, no_wrap, no_wrap + 1, kTop / 10, kTop - 1, kTop}) {
        std::vector<std::string> texts{"", "0", "00000000000000000000000000000", kForty};
        for (const std::uint64_t near : {max - 1, max, max + 1, max / 10, max * 10 + 9}) {
            texts.push_back(std::to_string(near));
            texts.push_back("000" + std::to_string(near));
            texts.push_back(std::to_string(near) + "0");
        }
        for (const std::string& t : texts)
            EXPECT_EQ(whole_at_most(t, max), careful(t, max)) << t << " <= " << max;
    }
}

TEST(NumbersAsWritten, AFortyDigitToolNumberIsShownAsWritten) {
    // The tool list showed "tool number 9999999".
    const Result<ToolTable> t = parse_tool_table("wz[" + kForty + "].typ 1\n", "t.tools");
    ASSERT_FALSE(t);
    EXPECT_EQ(t.error().to_string(),
              "t.tools:1:4: tool number " + kForty + " out of range 1..1023");
    const Result<ToolTable> a = parse_tool_table("wz[1].ax_ersatz[" + kForty + "] 0\n", "t.tools");
    ASSERT_FALSE(a);
    EXPECT_EQ(a.error().to_string(), "t.tools:1:17: axis index " + kForty + " out of range 0..7");
    EXPECT_EQ(error_of("N10 D" + kForty + "\nM30\n"),
              "prog.nc:1:6: N10: tool number D" + kForty + " out of range 0..1023");
    EXPECT_EQ(error_of("0 BEGIN PGM T MM\n1 TOOL CALL " + kForty + " Z\n2 END PGM T MM\n"),
              "prog.nc:2:13: tool number " + kForty + " out of range 0..1023");
}

TEST(NumbersAsWritten, OtherWholeNumbersToo) {
    const Result<CorrectionTable> c =
        parse_correction_table("corr[" + kForty + "].dr 1\n", "t.corr");
    ASSERT_FALSE(c);
    EXPECT_TRUE(
        contains(c.error().to_string(), "correction row " + kForty + " out of range 1..1023"));
    EXPECT_EQ(error_of("N" + kForty + " G1 X1 F100\nM30\n"),
              "prog.nc:1:2: block number N" + kForty + " out of range 0..9999999999999");
    EXPECT_EQ(error_of("G" + kForty + "\nM30\n"),
              "prog.nc:1:2: G code G" + kForty + " out of range 0..9999999999999");
    EXPECT_EQ(error_of("P" + kForty + " = 1\nM30\n"),
              "prog.nc:1:1: P parameter number P" + kForty + " out of range 0..999");
    EXPECT_EQ(error_of("P1 = P" + kForty + "\nM30\n"),
              "prog.nc:1:6: P parameter number P" + kForty + " out of range 0..999");
    EXPECT_EQ(error_of("$FOR P" + kForty + " = 0, 1, 1\n$ENDFOR\nM30\n"),
              "prog.nc:1:6: P parameter number P" + kForty + " out of range 0..999");
    EXPECT_EQ(
        error_of("0 BEGIN PGM T MM\n1 FUNCTION CORRDATA TCS #" + kForty + "\n2 END PGM T MM\n"),
        "prog.nc:2:26: correction row " + kForty +
            " out of range 1..1023 (FUNCTION CORRDATA RESET TCS leaves the table)");
}

}  // namespace
}  // namespace apci::nc
