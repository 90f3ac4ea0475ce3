// SPDX-License-Identifier: MIT
// Character-level scanning of one line, shared by the DIN 66025 block parser and its ISG
// commands (parser.cpp), the Klartext parser, the expressions (expression.h), the tool list, the
// correction table and the PLC script (tools/runlib's plc_script.cpp): a cursor with primitives
// for blanks, numbers, identifiers and comments. Nothing allocates.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace apci::nc {

// 1-based column of byte offset `offset` in `line`, counting UTF-8 characters (so a comment
// with umlauts before the error does not shift the column) and a tab as one column.
std::uint32_t column_at(std::string_view line, std::size_t offset) noexcept;

enum class NumberScan : std::uint8_t {
    kNone,        // no number at the cursor (cursor unchanged)
    kOk,          // value set, cursor behind the number
    kOutOfRange,  // well-formed but not a finite double (cursor behind the number)
};

// Up to this many decimal digits every value fits in 64 bits (10^19 - 1 < 2^64).
inline constexpr std::size_t kExactWholeDigits = 19;

namespace lexer_detail {

inline constexpr std::array<double, 23> kPow10 = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                  1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                                  1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
inline constexpr std::uint64_t kExactMantissa = std::uint64_t{1} << 53;

// Takes the run of digits at p (before end) into `value` (value times ten to the number of
// digits, plus the digits) and returns the end of the run. `value` wraps beyond 19 digits
// (the callers count the digits and decide otherwise there).
inline const char* take_digits(const char* p, const char* end, std::uint64_t& value) noexcept {
    std::uint64_t v = value;
    for (; p != end; ++p) {
        const unsigned d = static_cast<unsigned char>(*p) - unsigned{'0'};  // a digit: 0..9
        if (d > 9) break;
        v = v * 10 + d;
    }
    value = v;
    return p;
}

// The fixed-notation conversion of [first, last) (digits with an optional point) for what
// one division cannot give exactly, out of the way of the usual numbers.
NumberScan convert_long(const char* first, const char* last, bool negative, double& value) noexcept;

// The value of a scanned number: its digits [digits_begin, last) (with the point), their
// value as one whole number `mantissa` (wrapped beyond kExactWholeDigits digits), how many
// before and after the point, and the sign.
inline NumberScan number_value(std::uint64_t mantissa, std::size_t int_digits,
                               std::size_t frac_digits, bool negative, const char* digits_begin,
                               const char* last, double& value) noexcept {
    // With at most 19 digits the mantissa is exact. Beyond, it may have wrapped: the full
    // conversion, which gives the same double where the division below would (both are
    // the correctly rounded value of the decimal).
    if (int_digits + frac_digits <= kExactWholeDigits && mantissa <= kExactMantissa &&
        frac_digits < kPow10.size()) {
        // Both operands are exact doubles, so one correctly rounded division gives the
        // same double as a full decimal conversion.
        const double v = static_cast<double>(mantissa) / kPow10[frac_digits];
        value = negative ? -v : v;
        return NumberScan::kOk;
    }
    return convert_long(digits_begin, last, negative, value);
}

// LineCursor::scan_number on a pointer: the number at p (before end) into `value`, p behind
// it (unchanged when kNone). Shared with the parser's plain-block path, so that both give the
// same double for the same text.
inline NumberScan scan_number(const char*& pos, const char* end, double& value) noexcept {
    const char* p = pos;
    bool negative = false;
    if (p != end && (*p == '+' || *p == '-')) {
        negative = *p == '-';
        ++p;
    }
    // One test a digit, in one loop over the digits and the first point: the mantissa takes
    // every digit and wraps only beyond kExactWholeDigits digits, where the full conversion
    // decides instead.
    const char* const digits_begin = p;
    const char* point = nullptr;
    std::uint64_t mantissa = 0;
    for (; p != end; ++p) {
        const unsigned d = static_cast<unsigned char>(*p) - unsigned{'0'};  // a digit: 0..9
        if (d <= 9) {
            mantissa = mantissa * 10 + d;
        } else if (*p == '.' && point == nullptr) {
            point = p;
        } else {
            break;
        }
    }
    const auto int_digits = static_cast<std::size_t>((point != nullptr ? point : p) - digits_begin);
    const std::size_t frac_digits = point != nullptr ? static_cast<std::size_t>(p - point - 1) : 0;
    if (int_digits == 0 && frac_digits == 0) return NumberScan::kNone;  // "", "+", "-."
    pos = p;
    return number_value(mantissa, int_digits, frac_digits, negative, digits_begin, p, value);
}

}  // namespace lexer_detail

class LineCursor {
  public:
    explicit LineCursor(std::string_view line) noexcept : line_(line), ascii_(is_ascii(line)) {}

    std::string_view line() const noexcept { return line_; }
    std::size_t offset() const noexcept { return pos_; }
    // Columns are needed for every word; a pure ASCII line (the usual case) needs no counting.
    std::uint32_t column() const noexcept { return column_of(pos_); }
    // The column of an earlier offset (kept where the column is needed only for an error).
    std::uint32_t column_of(std::size_t offset) const noexcept {
        return ascii_ ? static_cast<std::uint32_t>(offset + 1) : column_at(line_, offset);
    }
    bool at_end() const noexcept { return pos_ >= line_.size(); }
    // The character at the cursor, '\0' at the end.
    char peek() const noexcept { return pos_ < line_.size() ? line_[pos_] : '\0'; }
    char peek_at(std::size_t ahead) const noexcept {
        return pos_ + ahead < line_.size() ? line_[pos_ + ahead] : '\0';
    }
    void advance(std::size_t n = 1) noexcept {
        pos_ = pos_ + n < line_.size() ? pos_ + n : line_.size();
    }
    void skip_blanks() noexcept {
        while (pos_ < line_.size() && (line_[pos_] == ' ' || line_[pos_] == '\t')) ++pos_;
    }
    std::string_view rest() const noexcept { return line_.substr(pos_); }

    // Number syntax of NC programs and tool files: [+-] then digits with an optional decimal
    // point and fraction, or a leading point ("X.5", "X-.5", "X1.", "X+2"). No exponent.
    // Inline: the usual number (at most 19 digits) costs no call.
    NumberScan scan_number(double& value) noexcept {
        const char* p = line_.data() + pos_;
        const NumberScan r = lexer_detail::scan_number(p, line_.data() + line_.size(), value);
        pos_ = static_cast<std::size_t>(p - line_.data());
        return r;
    }
    // Letters, digits and '_' starting with a letter or '_'; empty when none at the cursor.
    std::string_view scan_identifier() noexcept;
    // The run of decimal digits at the cursor, cursor behind it; empty when none. Whole numbers
    // (N, G, M, D, indexes, PLC cycles) are scanned as text first, so that one out of range is
    // named as written (whole_at_most), never clamped or wrapped.
    std::string_view scan_digits() noexcept;
    // The same, with `value` the digits' value when there are at most kExactWholeDigits of them
    // (unspecified beyond): whole_at_most(digits, value, max) then needs no second pass.
    std::string_view scan_digits(std::uint64_t& value) noexcept {
        const char* const begin = line_.data() + pos_;
        std::uint64_t v = 0;
        const char* const p = lexer_detail::take_digits(begin, line_.data() + line_.size(), v);
        pos_ += static_cast<std::size_t>(p - begin);
        value = v;
        return {begin, static_cast<std::size_t>(p - begin)};
    }
    // At '(': skips to behind the matching ')' and returns true; false (cursor unchanged) when
    // the line ends first.
    bool skip_paren_comment() noexcept;

  private:
    static bool is_ascii(std::string_view s) noexcept;

    std::string_view line_;
    bool ascii_;
    std::size_t pos_ = 0;
};

// The value of `digits` (decimal digits only, as scan_digits() gives them) when it is at most
// `max`; nullopt when it is above, however many digits it has (leading zeros count for nothing).
std::optional<std::uint64_t> whole_at_most(std::string_view digits, std::uint64_t max) noexcept;

// whole_at_most(digits, max) for digits and value as scan_digits(value) gave them: the value
// already taken when it is exact, the digits read again only when there are more.
inline std::optional<std::uint64_t> whole_at_most(std::string_view digits, std::uint64_t value,
                                                  std::uint64_t max) noexcept {
    if (digits.size() > kExactWholeDigits) return whole_at_most(digits, max);
    if (value > max) return std::nullopt;
    return value;
}

constexpr bool is_digit(char c) noexcept {
    return c >= '0' && c <= '9';
}
constexpr bool is_letter(char c) noexcept {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}
constexpr char to_upper(char c) noexcept {
    return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c;
}

}  // namespace apci::nc
