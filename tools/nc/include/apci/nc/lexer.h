// SPDX-License-Identifier: MIT
// Character-level scanning of one line, shared by the DIN 66025 block parser, the tool file
// parser and (later) the ISG # command and Klartext parsers: a cursor with primitives for
// blanks, numbers, identifiers and comments. Nothing allocates.
#pragma once

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

class LineCursor {
  public:
    explicit LineCursor(std::string_view line) noexcept : line_(line), ascii_(is_ascii(line)) {}

    std::string_view line() const noexcept { return line_; }
    std::size_t offset() const noexcept { return pos_; }
    // Columns are needed for every word; a pure ASCII line (the usual case) needs no counting.
    std::uint32_t column() const noexcept {
        return ascii_ ? static_cast<std::uint32_t>(pos_ + 1) : column_at(line_, pos_);
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
    NumberScan scan_number(double& value) noexcept;
    // Letters, digits and '_' starting with a letter or '_'; empty when none at the cursor.
    std::string_view scan_identifier() noexcept;
    // The run of decimal digits at the cursor, cursor behind it; empty when none. Whole numbers
    // (N, G, M, D, indexes, PLC cycles) are scanned as text first, so that one out of range is
    // named as written (whole_at_most), never clamped or wrapped.
    std::string_view scan_digits() noexcept;
    // The same, with `value` the digits' value when there are at most kExactWholeDigits of them
    // (unspecified beyond): whole_at_most(digits, value, max) then needs no second pass.
    std::string_view scan_digits(std::uint64_t& value) noexcept;
    // At '(': skips to behind the matching ')' and returns true; false (cursor unchanged) when
    // the line ends first.
    bool skip_paren_comment() noexcept;

  private:
    static bool is_ascii(std::string_view s) noexcept;
    NumberScan scan_number_digit_by_digit(double& value) noexcept;

    std::string_view line_;
    bool ascii_;
    std::size_t pos_ = 0;
};

// The value of `digits` (decimal digits only, as scan_digits() gives them) when it is at most
// `max`; nullopt when it is above, however many digits it has (leading zeros count for nothing).
std::optional<std::uint64_t> whole_at_most(std::string_view digits, std::uint64_t max) noexcept;

// Up to this many decimal digits every value fits in 64 bits (10^19 - 1 < 2^64).
inline constexpr std::size_t kExactWholeDigits = 19;

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
