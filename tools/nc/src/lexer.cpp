// SPDX-License-Identifier: MIT
#include "apci/nc/lexer.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstring>

namespace apci::nc {

std::uint32_t column_at(std::string_view line, std::size_t offset) noexcept {
    if (offset > line.size()) offset = line.size();
    std::uint32_t col = 1;
    for (std::size_t i = 0; i < offset; ++i) {
        // UTF-8 continuation bytes (10xxxxxx) do not start a character.
        if ((static_cast<unsigned char>(line[i]) & 0xC0U) != 0x80U) ++col;
    }
    return col;
}

bool LineCursor::is_ascii(std::string_view s) noexcept {
    // Eight bytes at a time: any byte with its top bit set is not ASCII.
    std::uint64_t any = 0;
    std::size_t i = 0;
    for (; i + 8 <= s.size(); i += 8) {
        std::uint64_t w = 0;
        std::memcpy(&w, s.data() + i, 8);
        any |= w;
    }
    if (i < s.size() && s.size() >= 8) {
        // The last eight bytes, overlapping those already seen: the tail in one load.
        std::uint64_t w = 0;
        std::memcpy(&w, s.data() + s.size() - 8, 8);
        any |= w;
        i = s.size();
    }
    for (; i < s.size(); ++i) any |= static_cast<unsigned char>(s[i]);
    return (any & 0x8080808080808080ULL) == 0;
}

NumberScan LineCursor::convert_long(const char* first, const char* last, bool negative,
                                    double& value) noexcept {
    double v = 0.0;
    const auto res = std::from_chars(first, last, v, std::chars_format::fixed);
    if (res.ec != std::errc() || !std::isfinite(v)) return NumberScan::kOutOfRange;
    value = negative ? -v : v;
    return NumberScan::kOk;
}

// The scan before the one-test-a-digit loops of scan_number, kept for numbers of more than
// kExactWholeDigits digits (tests/nc/lexer_test.cpp compares scan_number with a copy of it
// on every length and shape).
NumberScan LineCursor::scan_number_digit_by_digit(double& value) noexcept {
    using lexer_detail::kExactMantissa;
    using lexer_detail::kPow10;
    std::size_t p = pos_;
    const std::size_t n = line_.size();
    bool negative = false;
    if (p < n && (line_[p] == '+' || line_[p] == '-')) {
        negative = line_[p] == '-';
        ++p;
    }
    const std::size_t digits_begin = p;
    std::uint64_t mantissa = 0;
    bool exact = true;  // mantissa still below 2^53 (every digit taken)
    std::size_t int_digits = 0;
    while (p < n && is_digit(line_[p])) {
        if (mantissa < kExactMantissa) {
            mantissa = mantissa * 10 + static_cast<std::uint64_t>(line_[p] - '0');
        } else {
            exact = false;
        }
        ++p;
        ++int_digits;
    }
    std::size_t frac_digits = 0;
    if (p < n && line_[p] == '.') {
        ++p;
        while (p < n && is_digit(line_[p])) {
            if (mantissa < kExactMantissa) {
                mantissa = mantissa * 10 + static_cast<std::uint64_t>(line_[p] - '0');
            } else {
                exact = false;
            }
            ++p;
            ++frac_digits;
        }
    }
    if (int_digits == 0 && frac_digits == 0) return NumberScan::kNone;  // "", "+", ".", "-."
    pos_ = p;
    if (exact && mantissa <= kExactMantissa && frac_digits < kPow10.size()) {
        // Both operands are exact doubles, so one correctly rounded division gives the same
        // double as a full decimal conversion.
        const double v = static_cast<double>(mantissa) / kPow10[frac_digits];
        value = negative ? -v : v;
        return NumberScan::kOk;
    }
    double v = 0.0;
    const char* first = line_.data() + digits_begin;
    const char* last = line_.data() + p;
    const auto res = std::from_chars(first, last, v, std::chars_format::fixed);
    if (res.ec != std::errc() || !std::isfinite(v)) return NumberScan::kOutOfRange;
    value = negative ? -v : v;
    return NumberScan::kOk;
}

std::string_view LineCursor::scan_identifier() noexcept {
    const std::size_t begin = pos_;
    if (pos_ < line_.size() && (is_letter(line_[pos_]) || line_[pos_] == '_')) {
        ++pos_;
        while (pos_ < line_.size() &&
               (is_letter(line_[pos_]) || is_digit(line_[pos_]) || line_[pos_] == '_')) {
            ++pos_;
        }
    }
    return line_.substr(begin, pos_ - begin);
}

std::string_view LineCursor::scan_digits() noexcept {
    const std::size_t begin = pos_;
    while (pos_ < line_.size() && is_digit(line_[pos_])) ++pos_;
    return line_.substr(begin, pos_ - begin);
}

std::optional<std::uint64_t> whole_at_most(std::string_view digits, std::uint64_t max) noexcept {
    std::uint64_t v = 0;
    // Every bound of the front end is far below 2^64 / 10: while v <= max, v * 10 + 9 cannot
    // wrap, so one comparison a digit does (no division a digit).
    constexpr std::uint64_t kNoWrap = (~std::uint64_t{0} - 9) / 10;
    if (max <= kNoWrap) {
        for (const char c : digits) {
            v = v * 10 + static_cast<std::uint64_t>(c - '0');
            if (v > max) return std::nullopt;
        }
        return v;
    }
    for (const char c : digits) {
        const auto d = static_cast<std::uint64_t>(c - '0');
        if (d > max || v > (max - d) / 10) return std::nullopt;  // v * 10 + d > max
        v = v * 10 + d;
    }
    return v;
}

bool LineCursor::skip_paren_comment() noexcept {
    const std::size_t close = line_.find(')', pos_ + 1);
    if (close == std::string_view::npos) return false;
    pos_ = close + 1;
    return true;
}

}  // namespace apci::nc
