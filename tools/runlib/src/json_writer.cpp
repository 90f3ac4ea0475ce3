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

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "apci/apci.h"
#include "objif/byte_order.h"

namespace apci::run {

namespace {

constexpr std::size_t kNumberMax = 32;   // the longest JSON number below: 24 characters
constexpr std::size_t kIntegerMax = 20;  // the longest 64-bit integer: "-9223372036854775808"

// How many decimal digits v has (1 for 0): log10 from the bit width (1233 / 4096 is just
// above log10(2)), corrected by one comparison.
int digit_count(std::uint64_t v) noexcept {
    static constexpr std::uint64_t kPowers[] = {1ULL,
                                                10ULL,
                                                100ULL,
                                                1000ULL,
                                                10000ULL,
                                                100000ULL,
                                                1000000ULL,
                                                10000000ULL,
                                                100000000ULL,
                                                1000000000ULL,
                                                10000000000ULL,
                                                100000000000ULL,
                                                1000000000000ULL,
                                                10000000000000ULL,
                                                100000000000000ULL,
                                                1000000000000000ULL,
                                                10000000000000000ULL,
                                                100000000000000000ULL,
                                                1000000000000000000ULL,
                                                10000000000000000000ULL};
    const auto log2_up = static_cast<int>(std::bit_width(v | 1));  // floor(log2 v) + 1
    const int t = (log2_up * 1233) >> 12;                          // floor(log10 v) or one more
    return t + ((v | 1) >= kPowers[t] ? 1 : 0);
}

// The 8 decimal digits of n < 10^8, leading zeros included, as the bytes of a word (the first
// digit in the lowest byte): the four pairs of digits computed side by side in the lanes of one
// 64-bit word (divisions by 100 and 10 as multiplications that are exact for these ranges:
// x * 10486 >> 20 is x / 100 for x < 10^4, x * 103 >> 10 is x / 10 for x < 100), then made
// ASCII in one addition.
inline std::uint64_t eight_digits(std::uint32_t n) noexcept {
    const std::uint64_t x = n / 10000 | static_cast<std::uint64_t>(n % 10000) << 32;
    const std::uint64_t hundreds = ((x * 10486) >> 20) & 0x0000007F0000007FULL;
    const std::uint64_t pairs = hundreds | (x - hundreds * 100) << 16;  // four 16-bit lanes < 100
    const std::uint64_t tens = ((pairs * 103) >> 10) & 0x000F000F000F000FULL;
    return (tens | (pairs - tens * 10) << 8) + 0x3030303030303030ULL;
}

// The same for the 4 digits of n < 10^4 in a 32-bit word.
inline std::uint32_t four_digits(std::uint32_t n) noexcept {
    const std::uint32_t hundreds = (n * 10486) >> 20;
    const std::uint32_t pairs = hundreds | (n - hundreds * 100) << 16;  // two 16-bit lanes < 100
    const std::uint32_t tens = ((pairs * 103) >> 10) & 0x000F000FU;
    return (tens | (pairs - tens * 10) << 8) + 0x30303030U;
}

// The digits are laid out from the word's lowest byte: stored little-endian on every host.
template <typename Word>
inline void store(char* out, Word word) noexcept {
    objif::store_little(out, word);
}

#if defined(__SSE2__)
// The 8 decimal digits of n < 10^8, leading zeros included, in the eight 16-bit lanes of the
// result (the first digit in the lowest): n / 10^4 and n % 10^4 (a multiplication by
// ceil(2^45 / 10^4) and a shift, exact below 10^8), each spread over four lanes and divided by
// 1000, 100, 10 and 1 at once (multiplications keeping the high half, exact for 4 digits),
// then each lane less ten times the lane before it.
inline __m128i eight_digit_lanes(std::uint32_t n) noexcept {
    const __m128i value = _mm_cvtsi32_si128(static_cast<int>(n));
    const __m128i high = _mm_srli_epi64(_mm_mul_epu32(value, _mm_set1_epi32(-776530087)), 45);
    const __m128i low = _mm_sub_epi32(value, _mm_mul_epu32(high, _mm_set1_epi32(10000)));
    const __m128i quad = _mm_slli_epi64(_mm_unpacklo_epi16(high, low), 2);  // 4 n/10^4, 4 n%10^4
    const __m128i pairs = _mm_unpacklo_epi16(quad, quad);
    const __m128i spread = _mm_unpacklo_epi32(pairs, pairs);  // each four times, four lanes each
    const __m128i divided = _mm_mulhi_epu16(
        _mm_mulhi_epu16(spread,
                        _mm_setr_epi16(8389, 5243, 13108, -32768, 8389, 5243, 13108, -32768)),
        _mm_setr_epi16(128, 2048, 8192, -32768, 128, 2048, 8192, -32768));  // a, ab, abc, abcd
    return _mm_sub_epi16(divided, _mm_slli_epi64(_mm_mullo_epi16(divided, _mm_set1_epi16(10)), 16));
}

// The `count` last of the 16 decimal digits of v < 10^16 (leading zeros included) at out,
// 9 <= count <= 16: the two halves' digits packed into bytes and made ASCII in one addition,
// stored in one piece (with 16 - count bytes of garbage after them when count < 16).
inline void last_of_sixteen_digits(char* out, std::uint64_t v, int count) noexcept {
    const auto high = static_cast<std::uint32_t>(v / 100000000);
    const auto low = static_cast<std::uint32_t>(v % 100000000);
    const __m128i text = _mm_add_epi8(
        _mm_packus_epi16(eight_digit_lanes(high), eight_digit_lanes(low)), _mm_set1_epi8('0'));
    if (count == 16) {
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out), text);
        return;
    }
    alignas(16) char digits[32];
    _mm_store_si128(reinterpret_cast<__m128i*>(digits), text);
    _mm_store_si128(reinterpret_cast<__m128i*>(digits + 16), _mm_setzero_si128());
    std::memcpy(out, digits + 16 - count, 16);
}
#endif

// Writers of digits below store whole words: they may write up to this many bytes past the end
// they return (garbage their caller overwrites or leaves out); every buffer leaves that room.
constexpr std::size_t kScribble = 7;
static_assert(kNumberMax >= 24 + kScribble, "a number's text and what its last store may add");

// The `count` last decimal digits of v (1 <= count <= 20), leading zeros included; returns
// their end. The first 8-digit word is shifted so that only its last digits land.
char* exact_digits(char* out, std::uint64_t v, int count) noexcept {
    if (count <= 4) {  // most integer parts, and the decimals of programmed values
        store(out, four_digits(static_cast<std::uint32_t>(v % 10000)) >> (8 * (4 - count)));
        return out + count;
    }
    if (count <= 8) {
        store(out, eight_digits(static_cast<std::uint32_t>(v % 100000000)) >> (8 * (8 - count)));
        return out + count;
    }
#if defined(__SSE2__)
    // The shortest digits of a double have at most 17: the last 16 in one piece.
    if (count <= 16) {
        last_of_sixteen_digits(out, v, count);
        return out + count;
    }
    constexpr std::uint64_t kTen16 = 10000000000000000ULL;
    const int top = count - 16;  // 1 to 4 digits: 1 for a double's 17
    const auto first = static_cast<std::uint32_t>(v / kTen16);
    if (top == 1)
        *out = static_cast<char>('0' + first);
    else
        store(out, four_digits(first) >> (8 * (4 - top)));
    last_of_sixteen_digits(out + top, v % kTen16, 16);
    return out + count;
#else
    const auto low = static_cast<std::uint32_t>(v % 100000000);
    const std::uint64_t above = v / 100000000;
    const auto middle = static_cast<std::uint32_t>(above % 100000000);
    if (count <= 16) {
        const int first = count - 8;
        store(out, eight_digits(middle) >> (8 * (8 - first)));
        store(out + first, eight_digits(low));
        return out + count;
    }
    const int first = count - 16;
    store(out, eight_digits(static_cast<std::uint32_t>(above / 100000000)) >> (8 * (8 - first)));
    store(out + first, eight_digits(middle));
    store(out + first + 8, eight_digits(low));
    return out + count;
#endif
}

// The decimal digits of `v`, at least `width` of them (leading zeros); returns their end.
char* digits(char* out, std::uint64_t v, int width) noexcept {
    return exact_digits(out, v, std::max(width, digit_count(v)));
}

// A whole number in decimal (the text of std::to_chars); returns its end.
char* integer_text(char* out, std::int64_t v) noexcept {
    auto magnitude = static_cast<std::uint64_t>(v);
    if (v < 0) {
        *out++ = '-';
        magnitude = 0 - magnitude;
    }
    return digits(out, magnitude, 1);
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
    // The digits in place, then the fraction (n - whole <= 16 digits: n <= 17, whole >= 1) moved
    // on by one for the point: one word when it has at most 8 digits (whole <= 15 then), else
    // two (whole <= 8). The words moved may take garbage past the digits' end along (kScribble:
    // at most 1 + 15 + 1 + 8 or 1 + 8 + 1 + 16 bytes from the number's start are written).
    char* const end = exact_digits(out, significand, n);
    char* const point = out + whole;
    std::uint64_t first_word = 0;
    std::memcpy(&first_word, point, sizeof first_word);
    if (n - whole > 8) {
        std::uint64_t second_word = 0;
        std::memcpy(&second_word, point + 8, sizeof second_word);
        std::memcpy(point + 9, &second_word, sizeof second_word);  // bytes moved as they are
    }
    std::memcpy(point + 1, &first_word, sizeof first_word);
    *point = '.';
    return end + 1;
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
    // nearbyint(a * kScale) without a library call: below 2^52, adding 2^52 leaves no fraction
    // bits, so the sum is rounded to a whole number as nearbyint rounds (the current mode,
    // ties to even), and taking 2^52 off again is exact.
    constexpr double kTwo52 = 4503599627370496.0;
    static_assert(1e9 * kScale < kTwo52);
    const double m = (a * kScale + kTwo52) - kTwo52;
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
    // Whole below 1e15: the conversion to an integer and back keeps it (a cheaper test than
    // std::trunc, which is a library call where the CPU baseline has no rounding instruction).
    if (std::abs(v) < kExactInteger && v == static_cast<double>(static_cast<std::int64_t>(v)) &&
        !(v == 0.0 && std::signbit(v)))
        return integer_text(out, static_cast<std::int64_t>(v));
    if (char* end = short_decimal(out, v)) return end;
    const double a = std::fabs(v);
    if (a >= 1e-3 && a < kExactInteger) return shortest_fixed(out, v);
    return std::to_chars(out, out + kNumberMax, v).ptr;
}

// The text of v at out from `last` when v has its bits, else formatted there and kept in `last`;
// returns its end. Writes kNumberMax characters either way (the text, then garbage).
template <typename AxisText>
char* axis_number(char* out, double v, AxisText& last) {
    static_assert(std::tuple_size_v<decltype(last.text)> == kNumberMax);
    const auto bits = std::bit_cast<std::uint64_t>(v);
    if (bits != last.bits) {
        last.size = static_cast<std::size_t>(json_number(last.text.data(), v) - last.text.data());
        last.bits = bits;
    }
    std::memcpy(out, last.text.data(), kNumberMax);
    return out + last.size;
}

}  // namespace

char* JsonRunWriter::point_text(char* out, const Point& p) {
    *out++ = '[';
    out = json_number(out, p.x());
    *out++ = ',';
    out = json_number(out, p.y());
    *out++ = ',';
    out = axis_number(out, p.z(), last_z_);
    *out++ = ']';
    return out;
}

JsonRunWriter::JsonRunWriter(std::FILE* out) : sink_(out) {
    for (std::size_t k = 0; k < kKinds; ++k)
        for (std::size_t r = 0; r < kRoles; ++r) {
            KindRoleText& t = kind_role_texts_[k * kRoles + r];
            const auto end = fmt::format_to_n(
                t.text.begin(), t.text.size(), ",\"kind\":\"{}\",\"role\":\"{}\",\"start\":",
                kind_name(static_cast<SegmentKind>(k)), role_name(static_cast<Role>(r)));
            t.size = std::min(end.size, t.text.size());
        }
}

void JsonRunWriter::begin_segments() {
    if (begun_) return;
    begun_ = true;
    sink_.append("{\"segments\":[");
}

namespace {

// The longest text of a segment: its separator, block and line, kind, role, three points and
// the arc's sense and plane, with room to spare.
constexpr std::size_t kSegmentMax = 160 + 3 * (3 * kNumberMax + 4) + 3 * kIntegerMax;

// `text` at out; returns its end.
char* put(char* out, std::string_view text) noexcept {
    std::memcpy(out, text.data(), text.size());
    return out + text.size();
}

// "block":N, and "line":L for a block without a number; returns its end.
char* block_text(char* out, const BlockRef& b) noexcept {
    out = put(out, "\"block\":");
    out = integer_text(out, b.number);
    if (b.number == kNoBlock && b.line != 0) {
        out = put(out, ",\"line\":");
        out = integer_text(out, static_cast<std::int64_t>(b.line));
    }
    return out;
}

}  // namespace

namespace {

// The decimal text of a number one more, in place; false when every digit is 9 (one more
// digit: the text is left with zeros).
bool count_up(char* text, std::size_t size) noexcept {
    for (std::size_t i = size; i-- > 0;) {
        if (text[i] != '9') {
            ++text[i];
            return true;
        }
        text[i] = '0';
    }
    return false;
}

}  // namespace

char* JsonRunWriter::segment_block_text(char* out, std::int64_t number) {
    out = put(out, "\"block\":");
    if (last_block_size_ == 0 || number != last_block_) {
        char* const text = last_block_text_.data();
        // Both are >= 0: their difference cannot overflow.
        const bool next = last_block_size_ != 0 && number - last_block_ == 1;
        if (!next || !count_up(text, last_block_size_))
            last_block_size_ = static_cast<std::size_t>(integer_text(text, number) - text);
        last_block_ = number;
    }
    static_assert(std::tuple_size_v<decltype(last_block_text_)> >= kIntegerMax + kScribble);
    std::memcpy(out, last_block_text_.data(), last_block_text_.size());
    return out + last_block_size_;
}

void JsonRunWriter::block(const BlockRef& b) {
    char text[2 * kIntegerMax + 20 + kScribble];
    sink_.append(std::string_view(text, static_cast<std::size_t>(block_text(text, b) - text)));
}

// Plain copies into the sink's buffer rather than format strings: this runs once per executed
// segment, and the whole record is written in place.
void JsonRunWriter::segment(const PathSegment& s) {
    begin_segments();
    char* const first = sink_.reserve(kSegmentMax);
    char* out = put(first, count_ == 0 ? "\n{" : ",\n{");
    // A block's N number comes mostly again or one more; one without (-1) names its line.
    out = s.block.number >= 0 ? segment_block_text(out, s.block.number) : block_text(out, s.block);
    const auto kind = static_cast<std::size_t>(s.kind), role = static_cast<std::size_t>(s.role);
    if (kind < kKinds && role < kRoles) {
        const KindRoleText& t = kind_role_texts_[kind * kRoles + role];
        std::memcpy(out, t.text.data(), t.text.size());
        out += t.size;
    } else {  // not an enumerator: the names kind_name and role_name give it
        out = put(out, ",\"kind\":\"");
        out = put(out, kind_name(s.kind));
        out = put(out, "\",\"role\":\"");
        out = put(out, role_name(s.role));
        out = put(out, "\",\"start\":");
    }
    // Mostly where the segment before ended (the same bits: the same text). The point's text
    // is copied in one piece of fixed size, kPointMax (what point_text may write, garbage after
    // the text included), as json_number writes kNumberMax for each number.
    constexpr std::size_t kPointMax = 3 * kNumberMax + 4;
    static_assert(std::tuple_size_v<decltype(last_end_text_)> >= kPointMax);
    if (last_end_size_ != 0 && same_bits(s.start, last_end_)) {
        std::memcpy(out, last_end_text_.data(), kPointMax);
        out += last_end_size_;
    } else {
        out = point_text(out, s.start);
    }
    out = put(out, ",\"end\":");
    char* const end_text = out;
    out = point_text(out, s.end);
    last_end_ = s.end;
    last_end_size_ = static_cast<std::size_t>(out - end_text);
    std::memcpy(last_end_text_.data(), end_text, kPointMax);
    if (s.kind == SegmentKind::kArc) {
        out = put(out, ",\"center\":");
        out = point_text(out, s.center);
        out = put(out, s.ccw ? ",\"ccw\":true,\"plane\":" : ",\"ccw\":false,\"plane\":");
        if (s.plane >= 17 && s.plane <= 19) {  // the planes there are: two digits known
            *out++ = '1';
            *out++ = static_cast<char>('0' + s.plane - 10);
        } else {
            out = integer_text(out, s.plane);
        }
    }
    *out++ = '}';
    sink_.commit(out);
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
