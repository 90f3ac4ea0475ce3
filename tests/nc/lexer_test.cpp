// SPDX-License-Identifier: MIT
#include "apci/nc/lexer.h"

#include <gtest/gtest.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

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

// ---- scan_number's one-test-a-digit loops against the digit-by-digit scan before them

// The scan as it was before (a copy): every digit tested against 2^53 as it is taken, the
// mantissa divided by a power of ten when every digit was taken, from_chars otherwise.
struct Reference {
    NumberScan scan = NumberScan::kNone;
    double value = 0.0;
    std::size_t offset = 0;
};
Reference reference_scan(std::string_view line) {
    constexpr std::array<double, 23> kPow10 = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                               1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                               1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    constexpr std::uint64_t kExact = std::uint64_t{1} << 53;
    Reference r;
    std::size_t p = 0;
    const std::size_t n = line.size();
    bool negative = false;
    if (p < n && (line[p] == '+' || line[p] == '-')) {
        negative = line[p] == '-';
        ++p;
    }
    const std::size_t digits_begin = p;
    std::uint64_t mantissa = 0;
    bool exact = true;
    std::size_t int_digits = 0, frac_digits = 0;
    auto take = [&](std::size_t& count) {
        while (p < n && is_digit(line[p])) {
            if (mantissa < kExact)
                mantissa = mantissa * 10 + static_cast<std::uint64_t>(line[p] - '0');
            else
                exact = false;
            ++p;
            ++count;
        }
    };
    take(int_digits);
    if (p < n && line[p] == '.') {
        ++p;
        take(frac_digits);
    }
    if (int_digits == 0 && frac_digits == 0) return r;
    r.offset = p;
    if (exact && mantissa <= kExact && frac_digits < kPow10.size()) {
        const double v = static_cast<double>(mantissa) / kPow10[frac_digits];
        r.value = negative ? -v : v;
        r.scan = NumberScan::kOk;
        return r;
    }
    double v = 0.0;
    const auto res =
        std::from_chars(line.data() + digits_begin, line.data() + p, v, std::chars_format::fixed);
    if (res.ec != std::errc() || !std::isfinite(v)) {
        r.scan = NumberScan::kOutOfRange;
        return r;
    }
    r.value = negative ? -v : v;
    r.scan = NumberScan::kOk;
    return r;
}

std::uint64_t bits(double v) {
    std::uint64_t b = 0;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

void expect_as_reference(std::string_view text) {
    const Reference want = reference_scan(text);
    double v = -99.0;
    std::size_t n = 99;
    const NumberScan got = scan(text, v, n);
    ASSERT_EQ(got, want.scan) << text;
    EXPECT_EQ(n, want.offset) << text;
    if (got == NumberScan::kOk) {
        EXPECT_EQ(bits(v), bits(want.value)) << text;
        EXPECT_EQ(v, std::strtod(std::string(text.substr(0, n)).c_str(), nullptr)) << text;
    }
}

TEST(Lexer, NumbersOfEveryLengthAndShapeScanAsTheDigitByDigitScan) {
    // Digits around the limits of the fast loops: 15, 16, 17 significant digits (2^53 has
    // 16), 19 (the most that cannot wrap), 20 and beyond; leading zeros that do not count.
    const std::vector<std::string> digit_runs = {
        "",
        "0",
        "7",
        "00000",
        "123456789012345",       // 15
        "999999999999999",       // 15
        "9007199254740992",      // 2^53
        "9007199254740993",      // 2^53 + 1
        "9999999999999999",      // 16
        "12345678901234567",     // 17
        "99999999999999999",     // 17
        "1234567890123456789",   // 19
        "9999999999999999999",   // 19
        "18446744073709551615",  // 20: 2^64 - 1
        "18446744073709551616",  // 20: 2^64 (would wrap)
        "99999999999999999999",  // 20
        "0000000000000000000000001",
        "3141592653589793238462643383279502884197",
        std::string(30, '0'),
        std::string(330, '9'),
    };
    std::vector<std::string> texts;
    for (const std::string sign : {"", "+", "-"}) {
        for (const std::string& a : digit_runs) {
            texts.push_back(sign + a);
            for (const std::string& b : digit_runs) texts.push_back(sign + a + "." + b);
        }
    }
    // What may follow a number: a word, a blank, a second point, an exponent the dialect does
    // not have, a non-ASCII byte (UTF-8 and a lone high byte), a sign.
    for (const std::string& t : std::vector<std::string>(texts)) {
        for (const char* tail : {"X", " 1", ".5", "e5", "\xC3\x9C", "\xFF", "-", ";"})
            texts.push_back(t + tail);
    }
    for (const std::string& t : texts) expect_as_reference(t);
}

TEST(Lexer, NumbersAtTheEndOfAVeryLongLineScanAsTheDigitByDigitScan) {
    // The number at the very end of a long line (no byte behind it) and at its start.
    const std::string blanks(std::size_t{64} * 1024, ' ');
    for (const std::string number :
         {"1.5", "-.25", "123456789012345.678", "9007199254740993", "12345678901234567890.5"}) {
        const std::string line = blanks + "X" + number;
        LineCursor c(line);
        c.advance(blanks.size() + 1);
        double v = 0.0;
        ASSERT_EQ(c.scan_number(v), NumberScan::kOk) << number;
        EXPECT_EQ(c.offset(), line.size()) << number;
        EXPECT_EQ(bits(v), bits(reference_scan(number).value)) << number;
        expect_as_reference(number + blanks);
    }
}

TEST(Lexer, WholeNumbersScannedWithTheirValueAnswerAsWholeAtMost) {
    const std::vector<std::string> runs = {"",
                                           "0",
                                           "7",
                                           "0000000000000000000000000001023",
                                           "1023",
                                           "1024",
                                           "9999999999999",
                                           "10000000000000",
                                           "999999999999999999",
                                           "1844674407370955161",
                                           "9999999999999999999",
                                           "18446744073709551615",
                                           "18446744073709551616",
                                           std::string(40, '9')};
    for (const std::uint64_t max :
         {std::uint64_t{0}, std::uint64_t{7}, std::uint64_t{1023}, std::uint64_t{9999999999999},
          ~std::uint64_t{0} / 10, ~std::uint64_t{0}}) {
        for (const std::string& r : runs) {
            for (const char* tail : {"", ".5", " X1", "\xC3\x9C"}) {
                const std::string text = r + tail;
                LineCursor plain(text);
                const std::string_view digits = plain.scan_digits();
                LineCursor valued(text);
                std::uint64_t value = 0;
                const std::string_view same = valued.scan_digits(value);
                EXPECT_EQ(same, digits) << text;
                EXPECT_EQ(valued.offset(), plain.offset()) << text;
                EXPECT_EQ(whole_at_most(same, value, max), whole_at_most(digits, max))
                    << text << " <= " << max;
            }
        }
    }
}

}  // namespace
}  // namespace apci::nc
