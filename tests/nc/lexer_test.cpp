// SPDX-License-Identifier: MIT
#include "apci/nc/lexer.h"

#include <gtest/gtest.h>

#include <string>

namespace apci::nc {
namespace {

NumberScan scan(std::string_view text, double& v, std::size_t& consumed) {
    LineCursor c(text);
    const NumberScan s = c.scan_number(v);
    consumed = c.offset();
    return s;
}

TEST(Lexer, NumbersTakeSignDecimalsAndLeadingDot) {
    struct Case {
        std::string_view text;
        double value;
        std::size_t length;
    };
    const Case cases[] = {
        {"0", 0.0, 1},
        {"12", 12.0, 2},
        {"-3", -3.0, 2},
        {"+2", 2.0, 2},
        {"1.5", 1.5, 3},
        {"1.", 1.0, 2},
        {".5", 0.5, 2},
        {"-.25", -0.25, 4},
        {"+.125", 0.125, 5},
        {"0.1", 0.1, 3},
        {"102Y", 102.0, 3},
        {"0Y0", 0.0, 1},
        {"123.456789", 123.456789, 10},
        {"-0.001", -0.001, 6},
    };
    for (const Case& c : cases) {
        double v = -99.0;
        std::size_t n = 0;
        EXPECT_EQ(scan(c.text, v, n), NumberScan::kOk) << c.text;
        EXPECT_EQ(v, c.value) << c.text;
        EXPECT_EQ(n, c.length) << c.text;
    }
}

TEST(Lexer, NumbersAreCorrectlyRoundedLikeStrtod) {
    const char* texts[] = {"0.1",
                           "0.3",
                           "2.675",
                           "123456.789012",
                           "9007199254740993",
                           "0.000000000000000000000000001",
                           "1234567890123456789.5",
                           "3.14159265358979323846264338327950288"};
    for (const char* t : texts) {
        double v = 0.0;
        std::size_t n = 0;
        ASSERT_EQ(scan(t, v, n), NumberScan::kOk) << t;
        EXPECT_EQ(v, std::strtod(t, nullptr)) << t;
    }
}

TEST(Lexer, NoNumberLeavesCursor) {
    for (std::string_view t : {"", "+", "-", ".", "-.", "X1", "e5"}) {
        double v = 0.0;
        std::size_t n = 7;
        EXPECT_EQ(scan(t, v, n), NumberScan::kNone) << t;
        EXPECT_EQ(n, 0U) << t;
    }
}

TEST(Lexer, NumberBeyondDoubleIsOutOfRange) {
    const std::string huge(400, '9');
    double v = 0.0;
    std::size_t n = 0;
    EXPECT_EQ(scan(huge, v, n), NumberScan::kOutOfRange);
    EXPECT_EQ(n, huge.size());
}

TEST(Lexer, NoExponent) {
    double v = 0.0;
    std::size_t n = 0;
    EXPECT_EQ(scan("1e5", v, n), NumberScan::kOk);
    EXPECT_EQ(v, 1.0);
    EXPECT_EQ(n, 1U);
}

TEST(Lexer, ColumnsCountUtf8CharactersAndStartAtOne) {
    const std::string_view line = "N22 (Übergang) X";
    EXPECT_EQ(column_at(line, 0), 1U);
    EXPECT_EQ(column_at(line, 4), 5U);
    // "Ü" is two bytes; the X after it is column 16, byte offset 16.
    EXPECT_EQ(line.find('X'), 16U);
    EXPECT_EQ(column_at(line, 16), 16U);
    EXPECT_EQ(column_at(line, 999), column_at(line, line.size()));
}

TEST(Lexer, ParenCommentNeedsItsClosingParen) {
    LineCursor open("(abc");
    EXPECT_FALSE(open.skip_paren_comment());
    EXPECT_EQ(open.offset(), 0U);
    LineCursor closed("(abc) X");
    EXPECT_TRUE(closed.skip_paren_comment());
    EXPECT_EQ(closed.offset(), 5U);
}

TEST(Lexer, IdentifiersStartWithLetterOrUnderscore) {
    LineCursor c("OTC_2 ON");
    EXPECT_EQ(c.scan_identifier(), "OTC_2");
    LineCursor d("2abc");
    EXPECT_EQ(d.scan_identifier(), "");
}

}  // namespace
}  // namespace apci::nc
