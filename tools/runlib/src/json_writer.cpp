// SPDX-License-Identifier: MIT
#include "apci/run/json_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "apci/apci.h"

namespace apci::run {

namespace {

constexpr std::size_t kNumberMax = 32;  // the longest JSON number below: 24 characters

// "00" to "99": two decimal digits a step.
constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// How many decimal digits v has (1 for 0).
int digit_count(std::uint64_t v) noexcept {
    int n = 1;
    for (; v >= 100; v /= 100) n += 2;
    return v >= 10 ? n + 1 : n;
}

// The `count` last decimal digits of v, leading zeros included; returns their end.
char* exact_digits(char* out, std::uint64_t v, int count) noexcept {
    char* const end = out + count;
    char* p = end;
    for (; count >= 2; count -= 2, v /= 100) {
        p -= 2;
        std::memcpy(p, kDigitPairs + 2 * (v % 100), 2);
    }
    if (count == 1) *--p = static_cast<char>('0' + v % 10);
    return end;
}

// The decimal digits of `v`, at least `width` of them (leading zeros); returns their end.
char* digits(char* out, std::uint64_t v, int width) noexcept {
    return exact_digits(out, v, std::max(width, digit_count(v)));
}

// significand * 10^exponent in fixed notation: the digits with the decimal point among or
// before them ("0.00123"), or followed by zeros (exponent >= 0).
char* fixed_notation(char* out, bool negative, std::uint64_t significand, int exponent) noexcept {
    if (negative) *out++ = '-';
    const int n = digit_count(significand);
    if (exponent >= 0) {
        out = exact_digits(out, significand, n);
        return std::fill_n(out, exponent, '0');
    }
    const int whole = n + exponent;  // digits before the point
    if (whole <= 0) {
        *out++ = '0';
        *out++ = '.';
        out = std::fill_n(out, -whole, '0');
        return exact_digits(out, significand, n);
    }
    char text[20];
    exact_digits(text, significand, n);
    out = std::copy_n(text, whole, out);
    *out++ = '.';
    return std::copy_n(text + whole, n - whole, out);
}

// The shortest text that reads back as v (Dragonbox, the algorithm of fmt and std::to_chars),
// in fixed notation: the text of both for 1e-3 <= |v| < 1e15, where both choose it. The digits
// come from fmt's own Dragonbox (fmt::detail, exported by libfmt 9); the JsonNumbers tests
// compare the text with std::to_chars over edge and random values, so a change there shows.
char* shortest_fixed(char* out, double v) noexcept {
    const auto d = fmt::detail::dragonbox::to_decimal(v);
    return fixed_notation(out, std::signbit(v), d.significand, d.exponent);
}

// A value with at most 4 decimals (program coordinates, arc centres), 1e-3 <= |v| < 1e9, as
// the shortest text that reads back exactly: the decimal m / 10^4 nearest v reads back as v
// (a correctly rounded division), and with the decimals' spacing far above v's ulp no other
// such decimal does; without its trailing zeros it has the fewest digits, in fixed notation,
// which std::to_chars also picks for these magnitudes. nullptr when v is not such a value.
char* short_decimal(char* out, double v) {
    const double a = std::fabs(v);
    if (!(a >= 1e-3 && a < 1e9)) return nullptr;
    constexpr double kScale = 1e4;
    const double m = std::nearbyint(a * kScale);
    if (m / kScale != a) return nullptr;
    auto whole = static_cast<std::uint64_t>(m);
    const std::uint64_t integer = whole / 10000;
    std::uint64_t fraction = whole % 10000;
    int decimals = 4;
    while (fraction % 10 == 0) {  // never 0: a whole value is written as an integer
        fraction /= 10;
        --decimals;
    }
    if (v < 0) *out++ = '-';
    out = digits(out, integer, 1);
    *out++ = '.';
    return digits(out, fraction, decimals);
}

// A JSON number: the same text as append_json_number (std::to_chars, the shortest text that
// reads back exactly; whole numbers as integers; null for NaN and infinities), made faster:
// values with few decimals by short_decimal, the rest by the shortest round-trip digits of
// fmt's Dragonbox written in fixed notation, the same text as std::to_chars where that chooses
// fixed notation too: 1e-3 <= |v| < 1e15. Outside that (0.0001 is "1e-04" for std::to_chars),
// std::to_chars itself. Writes at most kNumberMax characters.
char* json_number(char* out, double v) {
    if (!std::isfinite(v)) {
        constexpr std::string_view kNull = "null";
        return std::copy(kNull.begin(), kNull.end(), out);
    }
    constexpr double kExactInteger = 1e15;
    if (v == std::trunc(v) && std::abs(v) < kExactInteger && !(v == 0.0 && std::signbit(v)))
        return std::to_chars(out, out + kNumberMax, static_cast<std::int64_t>(v)).ptr;
    if (char* end = short_decimal(out, v)) return end;
    const double a = std::fabs(v);
    if (a >= 1e-3 && a < kExactInteger) return shortest_fixed(out, v);
    return std::to_chars(out, out + kNumberMax, v).ptr;
}

// "[x,y,z]"; returns its end.
char* point_text(char* out, const Point& p) {
    *out++ = '[';
    out = json_number(out, p.x());
    *out++ = ',';
    out = json_number(out, p.y());
    *out++ = ',';
    out = json_number(out, p.z());
    *out++ = ']';
    return out;
}

// The same bits, not only equal values: -0 and 0 are written differently.
bool same_bits(const Point& a, const Point& b) {
    for (int i = 0; i < 3; ++i)
        if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
    return true;
}

}  // namespace

void JsonRunWriter::begin_segments() {
    if (begun_) return;
    begun_ = true;
    sink_.append("{\"segments\":[");
}

void JsonRunWriter::point(const Point& p) {
    char text[3 * kNumberMax + 4];
    sink_.append(std::string_view(text, static_cast<std::size_t>(point_text(text, p) - text)));
}

void JsonRunWriter::block(const BlockRef& b) {
    sink_.append("\"block\":");
    append_integer(sink_, b.number);
    if (b.number == kNoBlock && b.line != 0) {
        sink_.append(",\"line\":");
        append_integer(sink_, static_cast<std::int64_t>(b.line));
    }
}

// Plain appends rather than format strings: this runs once per executed segment.
void JsonRunWriter::segment(const PathSegment& s) {
    begin_segments();
    sink_.append(count_ == 0 ? "\n{" : ",\n{");
    block(s.block);
    sink_.append(",\"kind\":\"");
    sink_.append(kind_name(s.kind));
    sink_.append("\",\"role\":\"");
    sink_.append(role_name(s.role));
    sink_.append("\",\"start\":");
    // Mostly where the segment before ended (the same bits: the same text).
    if (last_end_size_ != 0 && same_bits(s.start, last_end_))
        sink_.append(std::string_view(last_end_text_.data(), last_end_size_));
    else
        point(s.start);
    sink_.append(",\"end\":");
    static_assert(std::tuple_size_v<decltype(last_end_text_)> >= 3 * kNumberMax + 4);
    last_end_ = s.end;
    last_end_size_ =
        static_cast<std::size_t>(point_text(last_end_text_.data(), s.end) - last_end_text_.data());
    sink_.append(std::string_view(last_end_text_.data(), last_end_size_));
    if (s.kind == SegmentKind::kArc) {
        sink_.append(",\"center\":");
        point(s.center);
        sink_.append(s.ccw ? ",\"ccw\":true,\"plane\":" : ",\"ccw\":false,\"plane\":");
        append_integer(sink_, s.plane);
    }
    sink_.put('}');
    ++count_;
}

namespace {

// ["KorrError","CalcError"]: the names of the set bits in [APCI-TC] Table 4 (bits it does not name as "bitN").
void bit_names(TextSink& sink, std::int32_t value, const char* (*name_of)(int)) {
    sink.put('[');
    bool first = true;
    for (int bit = 0; bit < 32; ++bit) {
        if ((static_cast<std::uint32_t>(value) & (1u << bit)) == 0) continue;
        if (!first) sink.put(',');
        first = false;
        const char* name = name_of(bit);
        if (name != nullptr) {
            append_json_string(sink, name);
        } else {
            sink.print("\"bit{}\"", bit);
        }
    }
    sink.put(']');
}

}  // namespace

bool JsonRunWriter::finish(std::span<const RunError> errors,
                           std::span<const GroupRegisters> registers) {
    return finish(errors, registers, {}, {});
}

void JsonRunWriter::error_list(std::span<const RunError> errors) {
    for (std::size_t i = 0; i < errors.size(); ++i) {
        sink_.append(i == 0 ? "\n{" : ",\n{");
        block(errors[i].block);
        sink_.append(",\"code\":");
        append_json_string(sink_, errors[i].code);
        sink_.append(",\"message\":");
        append_json_string(sink_, errors[i].message);
        sink_.put('}');
    }
}

bool JsonRunWriter::finish(std::span<const RunError> errors,
                           std::span<const GroupRegisters> registers,
                           std::span<const std::pair<std::string, double>> variables,
                           std::span<const RunError> notices,
                           std::span<const RunError> warnings) {
    begin_segments();
    sink_.append("],\n\"errors\":[");
    error_list(errors);
    if (!warnings.empty()) {
        sink_.append("],\n\"warnings\":[");
        error_list(warnings);
    }
    if (!notices.empty()) {
        sink_.append("],\n\"notices\":[");
        error_list(notices);
    }
    sink_.append("],\n\"registers\":{");
    for (std::size_t i = 0; i < registers.size(); ++i) {
        const GroupRegisters& g = registers[i];
        if (i != 0) sink_.put(',');
        sink_.print("\"{}\":", g.group);
        if (!g.readable) {
            sink_.append("null");
            continue;
        }
        sink_.print("{{\"ERROR\":{},\"ERROR_bits\":", g.error);
        bit_names(sink_, g.error, apci_tc_error_bit_name);
        sink_.print(",\"STATUS\":{},\"STATUS_bits\":", g.status);
        bit_names(sink_, g.status, apci_tc_status_bit_name);
        sink_.put('}');
    }
    // The readable NC variables by their names in [ISG-OTC] (the OTC module's; docs/design.md section 7).
    sink_.append("},\n\"variables\":{");
    for (std::size_t i = 0; i < variables.size(); ++i) {
        if (i != 0) sink_.put(',');
        append_json_string(sink_, variables[i].first);
        sink_.put(':');
        char text[kNumberMax];
        sink_.append(std::string_view(
            text, static_cast<std::size_t>(json_number(text, variables[i].second) - text)));
    }
    sink_.append("}}\n");
    return sink_.flush();
}

}  // namespace apci::run
