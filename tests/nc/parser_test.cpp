// SPDX-License-Identifier: MIT
#include "apci/nc/parser.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <iterator>
#include <string>

#include "apci/nc/interpreter.h"
#include "apci/nc/lexer.h"
#include "rng.h"

namespace apci::nc {
namespace {

struct Parsed {
    bool ok = false;
    ParsedLine line;
    Diagnostic err;
};

Parsed parse(std::string_view text, std::uint64_t line_number = 12) {
    Parsed p;
    p.ok = parse_din_line(text, line_number, "prog.nc", p.line, p.err);
    return p;
}

Block block(std::string_view text) {
    Parsed p = parse(text);
    EXPECT_TRUE(p.ok) << p.err.to_string();
    EXPECT_EQ(p.line.kind, LineKind::kBlock) << text;
    return p.line.block;
}

std::string error(std::string_view text) {
    Parsed p = parse(text);
    EXPECT_FALSE(p.ok) << text;
    return p.ok ? std::string() : p.err.to_string();
}

ErrorKind error_kind(std::string_view text) {
    Parsed p = parse(text);
    EXPECT_FALSE(p.ok) << text;
    return p.err.kind;
}

TEST(Parser, ProgramNameLine) {
    Parsed p = parse("%wr_quad_disc.nc");
    ASSERT_TRUE(p.ok);
    EXPECT_EQ(p.line.kind, LineKind::kProgramName);
    EXPECT_EQ(p.line.program_name, "wr_quad_disc.nc");
    Parsed with_comment = parse("  %prog-1 (name) ; more");
    ASSERT_TRUE(with_comment.ok) << with_comment.err.to_string();
    EXPECT_EQ(with_comment.line.program_name, "prog-1");
}

TEST(Parser, ProgramNameErrors) {
    EXPECT_EQ(error("% !"),
              "prog.nc:12:2: expected a program name after '%' (letters, digits, "
              "'_', '.', '-')");
    EXPECT_EQ(error("%abc G1"),
              "prog.nc:12:6: unexpected 'G' after the program name: the '%' line holds only "
              "the name");
}

// '%' alone (with blanks and comments): the tape's start or end mark, not a program name.
TEST(Parser, PercentAloneIsATapeMark) {
    for (std::string_view t : {"%", "  %  ", "% (start of tape)", "%;"}) {
        Parsed p = parse(t);
        ASSERT_TRUE(p.ok) << t << ": " << p.err.to_string();
        EXPECT_EQ(p.line.kind, LineKind::kTapeMark) << t;
    }
    EXPECT_EQ(parse("%a").line.kind, LineKind::kProgramName);
}

TEST(Parser, BlankAndCommentOnlyLinesAreEmpty) {
    for (std::string_view t : {"", "   \t ", "(comment)", "; comment", "  (a) (b) ; c"}) {
        Parsed p = parse(t);
        ASSERT_TRUE(p.ok) << t << ": " << p.err.to_string();
        EXPECT_EQ(p.line.kind, LineKind::kEmpty) << t;
    }
}

TEST(Parser, BlockNumber) {
    const Block b = block("N99999 M30");
    EXPECT_EQ(b.block_number(), 99999);
    EXPECT_EQ(b.number.column, 1U);
    EXPECT_EQ(b.line, 12U);
    EXPECT_EQ(block("G1").block_number(), kNoBlockNumber);
    EXPECT_EQ(block("N10").block_number(), 10);  // a block with only N is still a block
}

TEST(Parser, ErrorsCarryTheBlockNumberWhenKnown) {
    Parsed p = parse("N40 G1 X");
    ASSERT_FALSE(p.ok);
    EXPECT_EQ(p.err.block, 40);
    Parsed q = parse("N41 (open");
    ASSERT_FALSE(q.ok);
    EXPECT_EQ(q.err.block, 41);
    Parsed r = parse("G1 X");
    ASSERT_FALSE(r.ok);
    EXPECT_EQ(r.err.block, kNoBlockNumber);
}

TEST(Parser, BlockNumberMustBeFirstWord) {
    EXPECT_EQ(error("G1 N10"),
              "prog.nc:12:4: the block number 'N' must be the first word of "
              "the block");
}

TEST(Parser, EveryWordAndItsValue) {
    const Block b = block("N5 G1 X1 Y-2 Z3.5 F600 D7 M30");
    EXPECT_EQ(b.motion.value, Motion::kLine);
    EXPECT_EQ(b.axis[0].value, 1.0);
    EXPECT_EQ(b.axis[1].value, -2.0);
    EXPECT_EQ(b.axis[2].value, 3.5);
    EXPECT_EQ(b.feed.value, 600.0);
    EXPECT_EQ(b.tool.value, 7);
    EXPECT_TRUE(b.end_of_program.present());
    const Block arc = block("G2 X1 I2 J3 K4");
    EXPECT_EQ(arc.center[0].value, 2.0);
    EXPECT_EQ(arc.center[1].value, 3.0);
    EXPECT_EQ(arc.center[2].value, 4.0);
    EXPECT_EQ(block("G3 X1 R-5").radius.value, -5.0);
}

TEST(Parser, WordColumnsAreRecorded) {
    const Block b = block("N10 G1 X5");
    EXPECT_EQ(b.number.column, 1U);
    EXPECT_EQ(b.motion.column, 5U);
    EXPECT_EQ(b.axis[0].column, 8U);
    EXPECT_FALSE(b.axis[1].present());
}

TEST(Parser, WordsWithoutSpaces) {
    const Block b = block("N20 G17G90");
    EXPECT_EQ(b.plane.value, Plane::kXY);
    EXPECT_EQ(b.distance.value, DistanceMode::kAbsolute);
    const Block xyz = block("G1 X0Y0Z0 F600");
    EXPECT_TRUE(xyz.axis[0].present() && xyz.axis[1].present() && xyz.axis[2].present());
    const Block tight = block("N40G1X-1.5Y.5Z+2F600");
    EXPECT_EQ(tight.axis[0].value, -1.5);
    EXPECT_EQ(tight.axis[1].value, 0.5);
    EXPECT_EQ(tight.axis[2].value, 2.0);
    EXPECT_EQ(tight.feed.value, 600.0);
}

TEST(Parser, EveryGCodeWithAndWithoutLeadingZero) {
    struct Case {
        std::string_view text;
        int g;
    };
    const Case cases[] = {{"G0", 0},   {"G00", 0},  {"G1", 1},   {"G01", 1},  {"G2", 2},
                          {"G02", 2},  {"G3", 3},   {"G03", 3},  {"G17", 17}, {"G18", 18},
                          {"G19", 19}, {"G25", 25}, {"G26", 26}, {"G40", 40}, {"G41", 41},
                          {"G42", 42}, {"G90", 90}, {"G91", 91}, {"G139", 139},
                          {"G237", 237}};
    for (const Case& c : cases) {
        const Block b = block(c.text);
        int got = -1;
        if (b.motion.present()) got = g_number(b.motion.value);
        if (b.plane.present()) got = g_number(b.plane.value);
        if (b.corner.present()) got = g_number(b.corner.value);
        if (b.compensation.present()) got = g_number(b.compensation.value);
        if (b.distance.present()) got = g_number(b.distance.value);
        if (b.selection.present()) got = g_number(b.selection.value);
        EXPECT_EQ(got, c.g) << c.text;
    }
}

TEST(Parser, LowercaseAddressLetters) {
    const Block b = block("n10 g1 x5 y6 f100");
    EXPECT_EQ(b.block_number(), 10);
    EXPECT_EQ(b.motion.value, Motion::kLine);
    EXPECT_EQ(b.axis[1].value, 6.0);
}

TEST(Parser, CommentsInParenthesesAndAfterSemicolon) {
    const Block b = block("N22 D1 G25 ( Linearer Übergangssatz) X1 ; G1 Y2");
    EXPECT_EQ(b.tool.value, 1);
    EXPECT_EQ(b.corner.value, CornerMode::kLinear);
    EXPECT_TRUE(b.axis[0].present());
    EXPECT_FALSE(b.motion.present());
    EXPECT_FALSE(b.axis[1].present());
}

TEST(Parser, UnclosedCommentIsSyntaxError) {
    EXPECT_EQ(error("N10 G1 (no end"),
              "prog.nc:12:8: N10: comment not closed: expected ')' before "
              "the end of the line");
}

TEST(Parser, ExpectedNumberAfterAddress) {
    EXPECT_EQ(error("N10 G1 X"), "prog.nc:12:9: N10: expected a number after 'X'");
    EXPECT_EQ(error("N10 G1 X Y2"), "prog.nc:12:9: N10: expected a number after 'X'");
    EXPECT_EQ(error("G1 X- Y2"), "prog.nc:12:5: expected a number after 'X'");
    EXPECT_EQ(error("G1 X."), "prog.nc:12:5: expected a number after 'X'");
    EXPECT_EQ(error("G"), "prog.nc:12:2: expected a number after 'G'");
    EXPECT_EQ(error("N"), "prog.nc:12:2: expected a number after 'N'");
    EXPECT_EQ(error("G2 I"), "prog.nc:12:5: expected a number after 'I'");
    EXPECT_EQ(error("F"), "prog.nc:12:2: expected a number after 'F'");
    EXPECT_EQ(error("D"), "prog.nc:12:2: expected a number after 'D'");
    EXPECT_EQ(error("M"), "prog.nc:12:2: expected a number after 'M'");
    EXPECT_EQ(error("G3 R"), "prog.nc:12:5: expected a number after 'R'");
}

TEST(Parser, NumberOutOfRange) {
    const std::string huge = "X" + std::string(400, '9');
    EXPECT_EQ(error(huge), "prog.nc:12:2: the number after 'X' is out of range");
    EXPECT_EQ(error("N99999999999999999999"),
              "prog.nc:12:2: block number N99999999999999999999 out of range 0..9999999999999");
}

// The column of a number's error is the number's own, counted in characters, also where the
// cursor has gone on behind it (out of range) and a comment with an umlaut stands before it.
TEST(Parser, NumberErrorsNameTheNumbersColumnAfterNonAsciiComments) {
    const std::string huge(400, '9');
    const std::string umlaut = "\xC3\x9C";
    EXPECT_EQ(error("N10 (" + umlaut + "bergang) X" + huge),
              "prog.nc:12:17: N10: the number after 'X' is out of range");
    EXPECT_EQ(error("(\xC3\x9C) N99999999999999999999"),
              "prog.nc:12:6: block number N99999999999999999999 out of range 0..9999999999999");
    EXPECT_EQ(error("(\xC3\x9C) G-1"),
              "prog.nc:12:6: 'G' takes a whole number without sign or decimal point");
    EXPECT_EQ(error("(\xC3\x9C) G1 X-"), "prog.nc:12:9: expected a number after 'X'");
    EXPECT_EQ(error("(\xC3\x9C) G1 X" + huge + "Y1"),
              "prog.nc:12:9: the number after 'X' is out of range");
}

// The block loop tells a word's first byte from one table: every byte that is no address
// letter, blank, comment or command start is named as unexpected, every letter is read as a
// word, and '#', '$', V and P go to the ISG command and assignment checks, as one test each.
TEST(Parser, EveryByteStartingAWordIsToldAsBefore) {
    const std::string known = "(N G X Y Z B I J K R F D M, CDON CDOF)";
    for (int c = 0; c < 256; ++c) {
        const char ch = static_cast<char>(c);
        const std::string line = std::string("X1 ") + ch + "1";
        const Parsed p = parse(line);
        const std::string what = p.ok ? std::string() : p.err.to_string();
        if (is_letter(ch)) {
            EXPECT_EQ(what.find("unexpected character"), std::string::npos) << c << ": " << what;
            if (to_upper(ch) == 'V' || to_upper(ch) == 'P' || to_upper(ch) == 'E') {
                EXPECT_EQ(what, fmt::format("prog.nc:12:4: unknown word '{}' (known words: N G X "
                                            "Y Z B I J K R F D M, CDON CDOF)",
                                            ch))
                    << c;
            }
        } else if (ch == '#' || ch == '$') {
            EXPECT_EQ(what,
                      "prog.nc:12:4: ISG commands and assignments stand in a block of their own "
                      "(after an optional N number)")
                << c;
        } else if (ch == ' ' || ch == '\t') {  // skipped: the digit behind is unexpected
            EXPECT_EQ(what, "prog.nc:12:5: unexpected character '1': expected a word " + known)
                << c;
        } else if (ch == ';') {
            EXPECT_TRUE(p.ok) << c << ": " << what;
        } else if (ch == '(') {
            EXPECT_EQ(what,
                      "prog.nc:12:4: comment not closed: expected ')' before the end of the line")
                << c;
        } else {
            const auto u = static_cast<unsigned char>(ch);
            const std::string shown =
                u >= 0x21 && u < 0x7F ? fmt::format("'{}'", ch) : fmt::format("byte 0x{:02X}", u);
            EXPECT_EQ(what, fmt::format("prog.nc:12:4: unexpected character {}: expected a word {}",
                                        shown, known))
                << c;
        }
    }
    // V. and P<digits> = start an assignment, '$' setting data too, also in lower case.
    EXPECT_EQ(error_kind("v.G.WZ_AKT.WEAR_CONST = 1 X1"), ErrorKind::kSyntax);
    EXPECT_TRUE(parse("p12 = 3").ok);
    EXPECT_EQ(parse("p12 = 3").line.kind, LineKind::kAssignment);
}

// A line is looked at eight bytes at a time, its tail in one load of its last eight bytes, and a
// line shorter than eight byte by byte: a non-ASCII byte in any of these places makes the
// columns behind it count characters.
TEST(Parser, ColumnsCountCharactersWhereverTheNonAsciiByteLies) {
    const std::string umlaut = "\xC3\x9C";
    EXPECT_EQ(
        error("(" + umlaut + ")@"),
        "prog.nc:12:4: unexpected character '@': expected a word (N G X Y Z B I J K R F D M, CDON CDOF)");
    for (std::size_t k = 0; k <= 17; ++k) {
        const std::string line = "X1" + std::string(k, ' ') + "(" + umlaut + ") @";
        EXPECT_EQ(error(line), fmt::format("prog.nc:12:{}: unexpected character '@': expected a "
                                           "word (N G X Y Z B I J K R F D M, CDON CDOF)",
                                           k + 7))
            << k;
    }
}

TEST(Parser, WholeNumberWords) {
    EXPECT_EQ(error("G1.5"), "prog.nc:12:3: 'G' takes a whole number without decimal point");
    EXPECT_EQ(error("G-1"), "prog.nc:12:2: 'G' takes a whole number without sign or decimal point");
    EXPECT_EQ(error("D1.0"), "prog.nc:12:3: 'D' takes a whole number without decimal point");
    EXPECT_EQ(error("N1.5"), "prog.nc:12:3: 'N' takes a whole number without decimal point");
    EXPECT_EQ(error("M+30"),
              "prog.nc:12:2: 'M' takes a whole number without sign or decimal point");
    EXPECT_EQ(error_kind("G1.5"), ErrorKind::kValue);
}

TEST(Parser, UnknownWordsAreErrors) {
    EXPECT_EQ(error("N10 E5"),
              "prog.nc:12:5: N10: unknown word 'E' (known words: N G X Y Z B I J K R F D M, CDON CDOF)");
    EXPECT_EQ(error("G1 U45"),
              "prog.nc:12:4: unknown word 'U' (known words: N G X Y Z B I J K R F D M, CDON CDOF)");
    EXPECT_EQ(error_kind("S1000"), ErrorKind::kUnknownWord);
}

// A tool change as other controls write it is answered with the word this dialect takes.
TEST(Parser, ATToolChangeIsAnsweredWithD) {
    EXPECT_EQ(error("T1 M6"),
              "prog.nc:12:1: unknown word 'T': the tool is selected with D (D1 takes tool 1 of the "
              "tool list); T and M6 are not read (known words: N G X Y Z B I J K R F D M, CDON "
              "CDOF)");
    EXPECT_EQ(error("t2"), error("T2"));
    EXPECT_EQ(error_kind("T1"), ErrorKind::kUnknownWord);
    EXPECT_EQ(error("D1 M6"),
              "prog.nc:12:4: unknown M code M6: the tool is selected with D (D1 takes tool 1 of "
              "the tool list), no tool change is programmed (known: M2, M30: the program's end)");
    EXPECT_EQ(error_kind("M06"), ErrorKind::kUnknownWord);
    // M5 and M7 on either side are unknown M codes, without the hint.
    EXPECT_EQ(error("M5"), "prog.nc:12:1: unknown M code M5 (known: M2, M30: the program's end)");
    EXPECT_EQ(error("M7"), "prog.nc:12:1: unknown M code M7 (known: M2, M30: the program's end)");
}

TEST(Parser, CdonAndCdofAreWordsOfTheirOwn) {
    // SINUMERIK's bottleneck detection on/off: here whether the compensated elements from the
    // block on are walls for apcictl run's gouge check (docs/compensation.md).
    const Block on = block("N10 CDON G41 G1 X5");
    EXPECT_TRUE(on.collision.present());
    EXPECT_TRUE(on.collision.value);
    EXPECT_EQ(on.collision.column, 5U);
    const Block off = block("cdof");
    EXPECT_TRUE(off.collision.present());
    EXPECT_FALSE(off.collision.value);
    EXPECT_FALSE(block("G1 X5").collision.present());
    // Anything else after C is an unknown word, named as written; twice is a conflict.
    EXPECT_EQ(error("CDX"),
              "prog.nc:12:1: unknown word 'C' (known words: N G X Y Z B I J K R F D M, CDON CDOF)");
    EXPECT_EQ(error("G1 CD"),
              "prog.nc:12:4: unknown word 'C' (known words: N G X Y Z B I J K R F D M, CDON CDOF)");
    EXPECT_EQ(error("CDON CDOF"), "prog.nc:12:6: CDON or CDOF appears twice in one block");
    EXPECT_EQ(error_kind("CDON CDON"), ErrorKind::kConflict);
}

TEST(Parser, UnknownGCode) {
    EXPECT_EQ(error("N10 G04"),
              "prog.nc:12:5: N10: unknown G code G4 (known: G0-G3, G17-G19, G25, "
              "G26, G40-G42, G70, G71, G90, G91, G138, G139, G237)");
    // Fanuc-style units: this dialect's word named.
    EXPECT_EQ(error("G21 G1 X1"),
              "prog.nc:12:1: unknown G code G21 (known: G0-G3, G17-G19, G25, G26, G40-G42, G70, "
              "G71, G90, G91, G138, G139, G237): this dialect sets millimetres with G71");
    EXPECT_EQ(error("G20"),
              "prog.nc:12:1: unknown G code G20 (known: G0-G3, G17-G19, G25, G26, G40-G42, G70, "
              "G71, G90, G91, G138, G139, G237): this dialect sets inches with G70");
    EXPECT_EQ(error("G22"),
              "prog.nc:12:1: unknown G code G22 (known: G0-G3, G17-G19, G25, G26, G40-G42, G70, "
              "G71, G90, G91, G138, G139, G237)");
}

TEST(Parser, IsgSelectionMethodsAndSpindleFeedsAreRefusedAsNotEmulated) {
    // G139 (indirect, the initial state), G138 (direct) and G237 (perpendicular) are emulated;
    // the others not.
    for (const char* g : {"G236", "G238", "G239", "G05"}) {
        EXPECT_EQ(error_kind(g), ErrorKind::kUnsupported) << g;
        EXPECT_NE(error(g).find("is not emulated"), std::string::npos) << g;
    }
    EXPECT_EQ(error("G1 X1 FZ0.1"),
              "prog.nc:12:7: FZ (feed per tooth) is a feed of Klartext programs (TOOL CALL with "
              "S; docs/nc-programs.md): DIN 66025 programs give F in mm/min");
    EXPECT_EQ(error_kind("G1 X1 FU0.2"), ErrorKind::kUnsupported);
    EXPECT_EQ(error_kind("G1 X1 F AUTO"), ErrorKind::kUnsupported);
}

TEST(Parser, UnknownMCode) {
    EXPECT_EQ(error("M3"), "prog.nc:12:1: unknown M code M3 (known: M2, M30: the program's end)");
    EXPECT_EQ(error_kind("M1"), ErrorKind::kUnknownWord);
    EXPECT_EQ(error_kind("M29"), ErrorKind::kUnknownWord);
    EXPECT_EQ(error_kind("M31"), ErrorKind::kUnknownWord);
}

// M2 (M02) ends the program as M30 does (DIN 66025 defines both).
TEST(Parser, M2AndM30EndTheProgram) {
    for (std::string_view t : {"M2", "M02", "N99 M2", "M30", "m30"}) {
        Parsed p = parse(t);
        ASSERT_TRUE(p.ok) << t << ": " << p.err.to_string();
        EXPECT_TRUE(p.line.block.end_of_program.present()) << t;
    }
}

TEST(Parser, UnexpectedCharacter) {
    EXPECT_EQ(error("G1 X1 @"),
              "prog.nc:12:7: unexpected character '@': expected a word (N G X Y Z B I J K R F D M, CDON CDOF)");
    EXPECT_EQ(error("G1 X1\x01"),
              "prog.nc:12:6: unexpected character byte 0x01: expected a word "
              "(N G X Y Z B I J K R F D M, CDON CDOF)");
    EXPECT_EQ(error("G1 X1.2.3"),
              "prog.nc:12:8: unexpected character '.': expected a word (N G X Y Z B I J K R F D M, CDON CDOF)");
}

TEST(Parser, LeadingNumberHintsAtKlartext) {
    EXPECT_EQ(error("11 L X+36.0084 Y+6.177 R0"),
              "prog.nc:12:1: expected a word (an address letter: N G X Y Z B I J K R F D M, CDON CDOF), found "
              "a number; Klartext programs must begin with 'BEGIN PGM'");
}

TEST(Parser, ConflictingMotionWords) {
    EXPECT_EQ(error("G0 X1 G2"), "prog.nc:12:7: G0 and G2 in one block: both set the motion mode");
    EXPECT_EQ(error_kind("G1 G3"), ErrorKind::kConflict);
}

TEST(Parser, ConflictingCompensationWords) {
    EXPECT_EQ(error("G41 G42"),
              "prog.nc:12:5: G41 and G42 in one block: both set the radius compensation");
    EXPECT_EQ(error_kind("G40 G41"), ErrorKind::kConflict);
}

TEST(Parser, ConflictingPlaneCornerDistanceWords) {
    EXPECT_EQ(error("G17G18"), "prog.nc:12:4: G17 and G18 in one block: both set the plane");
    EXPECT_EQ(error("G25 G26"), "prog.nc:12:5: G25 and G26 in one block: both set the corner mode");
    EXPECT_EQ(error("G139 G237"),
              "prog.nc:12:6: G139 and G237 in one block: both set the selection method");
    EXPECT_EQ(error("G90 G91"),
              "prog.nc:12:5: G90 and G91 in one block: both set the distance mode");
}

TEST(Parser, SameGCodeTwice) {
    EXPECT_EQ(error("G1 X1 G01"), "prog.nc:12:7: G1 appears twice in one block");
}

TEST(Parser, SameWordTwice) {
    EXPECT_EQ(error("G1 X1 X2"), "prog.nc:12:7: 'X' appears twice in one block");
    EXPECT_EQ(error("G2 I1 I2"), "prog.nc:12:7: 'I' appears twice in one block");
    EXPECT_EQ(error("D1 D2"), "prog.nc:12:4: 'D' appears twice in one block");
    EXPECT_EQ(error("F1 F2"), "prog.nc:12:4: 'F' appears twice in one block");
    EXPECT_EQ(error("M30 M30"), "prog.nc:12:5: the program's end (M2 or M30) appears twice in one block");
    EXPECT_EQ(error("M2 M30"), "prog.nc:12:4: the program's end (M2 or M30) appears twice in one block");
}

TEST(Parser, RadiusAndCenterExcludeEachOther) {
    EXPECT_EQ(error("G2 X1 I1 R2"),
              "prog.nc:12:10: R and I/J/K in one block: give the arc centre "
              "or its radius, not both");
    EXPECT_EQ(error("G2 X1 R2 J1"),
              "prog.nc:12:10: R and I/J/K in one block: give the arc centre "
              "or its radius, not both");
}

TEST(Parser, ToolNumberRange) {
    EXPECT_EQ(block("D0").tool.value, 0);
    EXPECT_EQ(block("D1023").tool.value, 1023);
    EXPECT_EQ(error("D1024"), "prog.nc:12:2: tool number D1024 out of range 0..1023");
}

TEST(Parser, FeedMustBePositive) {
    EXPECT_EQ(error("F0"), "prog.nc:12:2: feed rate F must be greater than 0");
    EXPECT_EQ(error("F-5"), "prog.nc:12:2: feed rate F must be greater than 0");
}

TEST(Parser, RadiusMustNotBeZero) {
    EXPECT_EQ(error("G2 X1 R0"), "prog.nc:12:8: arc radius R must not be 0");
}

TEST(Parser, UnknownIsgCommandsAreUnsupportedByName) {
    EXPECT_EQ(error("N50 #CHANNEL INIT"),
              "prog.nc:12:5: N50: ISG command '#CHANNEL' is not supported (known: #OTC, #KIN, #TRAFO, "
              "#HSC, $FOR, $ENDFOR)");
    EXPECT_EQ(error_kind("$IF P1 == 1"), ErrorKind::kUnsupported);
    EXPECT_EQ(error("# ON"), "prog.nc:12:1: expected a command name after '#'");
}

TEST(Parser, ErrorColumnsCountCharactersNotBytes) {
    EXPECT_EQ(error("N22 (Übergang) Q1"),
              "prog.nc:12:16: N22: unknown word 'Q' (known words: N G X Y Z B I J K R F D M, CDON CDOF)");
}

TEST(Parser, DialectDetection) {
    EXPECT_EQ(detect_dialect("0  BEGIN PGM 3DTEST MM").dialect, Dialect::kKlartext);
    EXPECT_EQ(detect_dialect("0  BEGIN PGM 3DTEST MM").offset, 3U);
    EXPECT_EQ(detect_dialect("BEGIN PGM X MM").dialect, Dialect::kKlartext);
    EXPECT_EQ(detect_dialect("  (c) ; x").dialect, Dialect::kUndecided);
    EXPECT_EQ(detect_dialect("").dialect, Dialect::kUndecided);
    EXPECT_EQ(detect_dialect("%wr_quad_disc.nc").dialect, Dialect::kDin66025);
    EXPECT_EQ(detect_dialect("N10 G1 X1").dialect, Dialect::kDin66025);
    EXPECT_EQ(detect_dialect("BEGIN X").dialect, Dialect::kDin66025);
    EXPECT_EQ(detect_dialect("BEGINPGM").dialect, Dialect::kDin66025);
}

}  // namespace
}  // namespace apci::nc

namespace apci::nc {
namespace {

// Bad input of every kind gets an error with a position inside the line, never a crash: random
// lines over the characters NC programs are made of, parsed and then interpreted.
TEST(Parser, RandomLinesGiveErrorsWithinTheLineNeverACrash) {
    const std::string_view alphabet = "NGXYZIJKRFDMEQ%#$0123456789+-.() ;\t\xC3\x9C";
    apci::test::Rng rng(0x9E3779B97F4A7C15ULL);
    auto next = [&rng]() { return rng.next(); };
    Interpreter interpreter;
    EventBatch batch;
    int parsed = 0;
    for (int i = 0; i < 20000; ++i) {
        std::string line;
        const std::size_t len = next() % 24;
        for (std::size_t k = 0; k < len; ++k) line += alphabet[next() % alphabet.size()];
        ParsedLine out;
        Diagnostic err;
        if (parse_din_line(line, 1, "fuzz.nc", out, err)) {
            ++parsed;
            if (out.kind == LineKind::kBlock &&
                !interpreter.apply(out.block, "fuzz.nc", batch, err)) {
                EXPECT_GE(err.column, 1U) << line;
                EXPECT_LE(err.column, column_at(line, line.size())) << line;
            }
        } else {
            EXPECT_FALSE(err.message.empty()) << line;
            EXPECT_EQ(err.line, 1U) << line;
            EXPECT_GE(err.column, 1U) << line;
            EXPECT_LE(err.column, column_at(line, line.size())) << line;
        }
    }
    EXPECT_GT(parsed, 100);  // the generator also makes valid lines
}

// ---- The plain-block path of parse_din_line against the general parser

// The same outcome, bit for bit: success, line kind, every word's column and value (the double's
// bits), or the same error with the same column, block and message.
void expect_same_as_general(std::string_view text) {
    ParsedLine fast;
    Diagnostic fast_err;
    ParsedLine general;
    Diagnostic general_err;
    const bool fast_ok = parse_din_line(text, 7, "prog.nc", fast, fast_err);
    const bool general_ok =
        parser_detail::parse_din_line_general(text, 7, "prog.nc", general, general_err);
    ASSERT_EQ(fast_ok, general_ok) << "'" << text << "'";
    if (!fast_ok) {
        EXPECT_EQ(fast_err.to_string(), general_err.to_string()) << "'" << text << "'";
        EXPECT_EQ(fast_err.kind, general_err.kind) << "'" << text << "'";
        EXPECT_EQ(fast_err.block, general_err.block) << "'" << text << "'";
        return;
    }
    ASSERT_EQ(fast.kind, general.kind) << "'" << text << "'";
    if (fast.kind != LineKind::kBlock) return;
    const Block& a = fast.block;
    const Block& b = general.block;
    EXPECT_EQ(a.line, b.line);
    auto same_real = [&text](const Word<double>& x, const Word<double>& y, char letter) {
        EXPECT_EQ(x.column, y.column) << letter << " in '" << text << "'";
        if (x.present() && y.present()) {
            EXPECT_EQ(std::bit_cast<std::uint64_t>(x.value), std::bit_cast<std::uint64_t>(y.value))
                << letter << " in '" << text << "'";
        }
    };
    for (std::size_t k = 0; k < 3; ++k) {
        same_real(a.axis[k], b.axis[k], "XYZ"[k]);
        same_real(a.center[k], b.center[k], "IJK"[k]);
    }
    same_real(a.feed, b.feed, 'F');
    same_real(a.radius, b.radius, 'R');
    same_real(a.b_axis, b.b_axis, 'B');
    EXPECT_EQ(a.number.column, b.number.column) << "'" << text << "'";
    if (a.number.present()) {
        EXPECT_EQ(a.number.value, b.number.value) << "'" << text << "'";
    }
    EXPECT_EQ(a.motion.column, b.motion.column) << "'" << text << "'";
    if (a.motion.present()) {
        EXPECT_EQ(a.motion.value, b.motion.value) << "'" << text << "'";
    }
    EXPECT_EQ(a.plane.column, b.plane.column);
    EXPECT_EQ(a.distance.column, b.distance.column);
    EXPECT_EQ(a.compensation.column, b.compensation.column);
    EXPECT_EQ(a.corner.column, b.corner.column);
    EXPECT_EQ(a.selection.column, b.selection.column);
    EXPECT_EQ(a.units.column, b.units.column);
    EXPECT_EQ(a.tool.column, b.tool.column);
    EXPECT_EQ(a.end_of_program.column, b.end_of_program.column);
}

// The edges of the plain-block path: every line either takes it and gives the general parser's
// block, or leaves it and gets the general parser's result or error.
TEST(Parser, PlainBlocksParseAsTheGeneralParserAtEveryEdge) {
    const std::string_view lines[] = {
        "N7 G2 X71.615 Y87.782 I39.3567 J28.2347",
        "n7 g2 x71.615 y87.782 i39.3567 j28.2347 f100",
        "N1X1Y2Z3I4J5K6F7",
        "\tN1\t G1 \tX-.5 Y+2 Z1. F.5  ",
        "G1 X1 ; the rest is a comment with \xC3\x9C",
        "G1 X1;",
        "; only a comment",
        "   ",
        "",
        "N1",
        "G0",
        "G3",
        "G4 X1",
        "G01 X1",
        "G0000000000000000001 X1",       // 19 digits: G1
        "G00000000000000000001 X1",      // 20 digits
        "N9999999999999 G1 X1",          // kMaxWordNumber
        "N10000000000000 G1 X1",         // one beyond
        "N123456789012345678901234 G1",  // far beyond
        "G1 N5 X1",                      // N not first
        "N5 N6",
        "G1 G2 X1",
        "G1 G1 X1",
        "X1 X2",
        "F1 F2",
        "I1 I2",
        "G1 X1.5.3",
        "G1 X-",
        "G1 X+",
        "G1 X.",
        "G1 X",
        "G1 X ",
        "G1 X 5",
        "G1 X[1+2]",
        "G1 F0",
        "G1 F-5",
        "G1 F-0",
        "G1 F 100",
        "G1 FZ 1",
        "G1 F AUTO",
        "G1 FU",
        "G1 Fa",
        "N1.5 G1",
        "N+1 G1",
        "G-1",
        "G.5",
        "G1.0 X1",
        "G",
        "N",
        "G1 X12345678901234567890.5",  // beyond 19 digits: the long conversion
        "G1 X0.12345678901234567890123",
        "G1 X9007199254740993",  // beyond 2^53
        "G1 X123456789012345678901234567890123456789012345678901234567890e",
        "G1 X1e5",
        "G1 X1 (comment) Y2",
        "G1 X1 (unclosed",
        "G1 X1 R5",
        "G2 X1 Y1 R5",
        "G1 X1 B5",
        "G1 X1 D1",
        "G1 X1 M30",
        "M30",
        "G17 G90 G1 X1",
        "G1 X1 \xC3\x9C",
        "\xC3\x9C G1 X1",
        "G1 X1\r",
        "%prog",
        "P1 = 5",
        "N1 P1 = 5",
        "V.G.WZ_AKT.WEAR_CONST = 1",
        "#OTC ON",
        "N2 $FOR P1 = 1, 2, 1",
        "1 G1",
        "G1 X1 Q2",
        "G1 X1 E2",
        "G1 X1 ,",
        "X1 N2",
    };
    for (const std::string_view line : lines) expect_same_as_general(line);
}

// Random lines of words (a letter, a number, a separator) and of what lies just outside plain
// blocks: the plain-block path and the general parser agree on every one.
TEST(Parser, RandomLinesParseAsTheGeneralParser) {
    const std::string_view letters[] = {
        "N", "G", "X", "Y", "Z", "I", "J", "K", "F", "x", "g", "n", "f", "X",        "Y", "G",
        "I", "J", "R", "B", "D", "M", "P", "V", "%", "#", "$", "(", "[", "\xC3\x9C", "1"};
    const std::string_view numbers[] = {"0",
                                        "1",
                                        "2",
                                        "3",
                                        "17",
                                        "12.5",
                                        "-.5",
                                        "+2",
                                        "3.",
                                        "0.001",
                                        "-7.25",
                                        "",
                                        ".",
                                        "-",
                                        "1.2.",
                                        "99999999999999999999",
                                        "0.000000000000000000001",
                                        "9999999999999",
                                        "10000000000000",
                                        "1234567.891"};
    const std::string_view separators[] = {" ", " ", " ", "", "\t", "  ", " ;", ")", "=", ","};
    apci::test::Rng rng(0xD1B54A32D192ED03ULL);
    auto next = [&rng]() { return rng.next(); };
    auto pick = [&next](const auto& from) { return from[next() % std::size(from)]; };
    int blocks = 0;
    for (int i = 0; i < 40000; ++i) {
        std::string line;
        const std::size_t words = next() % 7;
        // Mostly the usual letters and numbers, so that many lines are blocks.
        for (std::size_t k = 0; k < words; ++k) {
            line += next() % 4 != 0 ? letters[next() % 13] : pick(letters);
            line += next() % 4 != 0 ? numbers[next() % 10] : pick(numbers);
            line += next() % 4 != 0 ? separators[next() % 3] : pick(separators);
        }
        expect_same_as_general(line);
        if (HasFatalFailure()) return;
        ParsedLine out;
        Diagnostic err;
        if (parse_din_line(line, 7, "prog.nc", out, err) && out.kind == LineKind::kBlock) ++blocks;
    }
    EXPECT_GT(blocks, 2000);  // the generator makes many blocks, not only errors
}

}  // namespace
}  // namespace apci::nc
