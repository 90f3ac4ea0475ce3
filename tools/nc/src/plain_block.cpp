// SPDX-License-Identifier: MIT
// The fast path of parse_din_line: the usual block ("N10 G1 X10 Y5 F500") in one pass over its
// bytes; anything else goes to the general parser (block_parser.h), which gives its block or
// its error.
#include <array>
#include <cstdint>
#include <string_view>

#include "apci/nc/lexer.h"
#include "apci/nc/parser.h"

namespace apci::nc {

namespace {

// What a byte is to a plain block (plain_block below): a blank, the ';' of the comment that
// ends it, a word's letter (either case), or anything else.
enum PlainWord : std::uint8_t {
    kNotPlain,
    kPlainBlank,
    kPlainComment,
    kPlainN,
    kPlainG,
    kPlainReal
};
struct PlainSlot {
    PlainWord word = kNotPlain;
    std::uint8_t real = 0;  // kPlainReal: X Y Z I J K F as 0..6
};
constexpr std::array<PlainSlot, 256> kPlainSlots = [] {
    std::array<PlainSlot, 256> t{};
    constexpr std::string_view kReals = "XYZIJKF";
    t[' '].word = kPlainBlank;
    t['\t'].word = kPlainBlank;
    t[';'].word = kPlainComment;
    for (int c = 0; c < 256; ++c) {
        const char up = to_upper(static_cast<char>(c));
        if (!is_letter(static_cast<char>(c))) continue;
        PlainSlot& s = t[static_cast<std::size_t>(c)];
        if (up == 'N') s.word = kPlainN;
        if (up == 'G') s.word = kPlainG;
        const std::size_t r = kReals.find(up);
        if (r != std::string_view::npos) {
            s.word = kPlainReal;
            s.real = static_cast<std::uint8_t>(r);
        }
    }
    return t;
}();
constexpr std::uint8_t kPlainFeed = 6;

// The usual block in one pass over raw bytes: N (first), G0..G3, X Y Z I J K with plain
// numbers, F above 0, blanks between, an optional ';' comment at the end. True with `out` as
// BlockParser::parse would fill it; false at the first thing outside that (anything else, and
// every error), with `out` unspecified: the general parser then parses the line from its start
// and gives its block or its error. The accepted bytes are all ASCII: a word's column is its
// offset plus one.
bool plain_block(std::string_view line, std::uint64_t line_number, ParsedLine& out) noexcept {
    const char* const begin = line.data();
    const char* const end = begin + line.size();
    const char* p = begin;
    Block& b = out.block;
    b.clear(line_number);
    Word<double>* const reals[] = {b.axis.data(), &b.axis[1],   &b.axis[2], b.center.data(),
                                   &b.center[1],  &b.center[2], &b.feed};
    bool any = false;
    while (p != end) {
        const PlainSlot slot = kPlainSlots[static_cast<unsigned char>(*p)];
        if (slot.word == kPlainBlank) {
            ++p;
            continue;
        }
        const auto col = static_cast<std::uint32_t>(p - begin + 1);
        ++p;
        if (slot.word == kPlainReal) {
            Word<double>& w = *reals[slot.real];
            double v = 0.0;
            if (w.present() || lexer_detail::scan_number(p, end, v) != NumberScan::kOk)
                return false;
            if (slot.real == kPlainFeed && !(v > 0.0)) return false;
            w.value = v;
            w.column = col;
            any = true;
            continue;
        }
        if (slot.word == kPlainComment) break;  // the rest of the line is a comment
        if (slot.word == kNotPlain) return false;
        // N and G: digits only, at most kMaxWordNumber (whole()); a point after them is no
        // word's start, so the next round leaves this path.
        if (p == end || !is_digit(*p)) return false;
        const char* const digits = p;
        std::uint64_t v = 0;
        p = lexer_detail::take_digits(p, end, v);
        if (static_cast<std::size_t>(p - digits) > kExactWholeDigits || v > kMaxWordNumber)
            return false;
        if (slot.word == kPlainN) {
            if (any) return false;  // N only as the first word
            b.number.value = static_cast<std::int64_t>(v);
            b.number.column = col;
        } else {
            if (v > 3 || b.motion.present()) return false;  // G0..G3, once
            b.motion.value = static_cast<Motion>(v);
            b.motion.column = col;
        }
        any = true;
    }
    if (!any) return false;
    out.kind = LineKind::kBlock;
    out.program_name = {};
    out.program_name_column = 0;
    return true;
}

}  // namespace

bool parse_din_line(std::string_view line, std::uint64_t line_number, std::string_view file,
                    ParsedLine& out, Diagnostic& err, const ExpressionContext* ctx) {
    if (plain_block(line, line_number, out)) return true;
    return parser_detail::parse_din_line_general(line, line_number, file, out, err, ctx);
}

}  // namespace apci::nc
