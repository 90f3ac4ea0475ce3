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

NumberScan lexer_detail::convert_long(const char* first, const char* last, bool negative,
                                      double& value) noexcept {
    double v = 0.0;
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
