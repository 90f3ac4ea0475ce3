// SPDX-License-Identifier: MIT
// The general parser's blocks (block_parser.h): the block loop, its words (N, G, M, D, X Y Z B,
// I J K, R, F, CDON/CDOF) and the "%name" line; parse_din_line_general.
#include <fmt/format.h>

#include <array>
#include <cctype>
#include <optional>
#include <string_view>
#include <utility>

#include "apci/nc/lexer.h"
#include "apci/nc/parser.h"
#include "block_parser.h"

namespace apci::nc {
namespace parser_detail {


// Fills err and returns false, so error paths read `return fail(...)`.
bool fail(Diagnostic& err, ErrorKind kind, std::string_view file, std::uint64_t line,
          std::uint32_t column, std::string message) {
    err.kind = kind;
    err.file = std::string(file);
    err.line = line;
    err.column = column;
    err.block = kNoBlockNumber;
    err.message = std::move(message);
    return false;
}

// A character as an error message names it: 'x', or "byte 0x07".
std::string describe_char(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x21 && u < 0x7F) return fmt::format("'{}'", c);
    return fmt::format("byte 0x{:02X}", u);
}

// Skips blanks and "( ... )" comments (block_parser.h).
bool skip_comments(LineCursor& c, std::string_view file, std::uint64_t line, Diagnostic& err) {
    for (;;) {
        c.skip_blanks();
        if (c.peek() == '(') {
            const std::uint32_t col = c.column();
            if (!c.skip_paren_comment()) {
                return fail(err, ErrorKind::kSyntax, file, line, col,
                            "comment not closed: expected ')' before the end of the line");
            }
            continue;
        }
        if (c.peek() == ';') c.advance(c.rest().size());
        return true;
    }
}

namespace {

constexpr std::string_view kKnownWords = "N G X Y Z B I J K R F D M, CDON CDOF";
// What a tool change written as other controls write it (T1 M6) is told.
constexpr std::string_view kToolByD =
    "the tool is selected with D (D1 takes tool 1 of the tool list)";
constexpr std::string_view kKnownGCodes =
    "G0-G3, G17-G19, G25, G26, G40-G42, G70, G71, G90, G91, G138, G139, G237";

bool is_program_name_char(char c) {
    return is_letter(c) || is_digit(c) || c == '_' || c == '.' || c == '-';
}

// What a character at the start of a word may begin, for the block loop to tell the usual
// word from one lookup: an address letter (is_letter), and the first character of an ISG
// command or an assignment ('#', '$', V, P; is_assignment_start() then tells).
constexpr std::uint8_t kWordLetter = 1;
constexpr std::uint8_t kCommandStart = 2;
constexpr std::array<std::uint8_t, 256> kStarts = [] {
    std::array<std::uint8_t, 256> t{};
    for (int c = 0; c < 256; ++c) {
        const char ch = static_cast<char>(c);
        if (is_letter(ch)) t[static_cast<std::size_t>(c)] |= kWordLetter;
        if (ch == '#' || ch == '$' || to_upper(ch) == 'V' || to_upper(ch) == 'P')
            t[static_cast<std::size_t>(c)] |= kCommandStart;
    }
    return t;
}();

// A block: its words, or an ISG command or an assignment (isg_commands.cpp) standing alone.
class BlockParser : public LineParse {
  public:
    BlockParser(std::string_view line, std::uint64_t line_number, std::string_view file,
                ParsedLine& out, Diagnostic& err, const ExpressionContext* ctx)
        : LineParse(line, line_number, file, out, err, ctx), b_(out.block) {}

    bool parse() {
        out_.kind = LineKind::kEmpty;
        out_.program_name = {};
        out_.program_name_column = 0;
        b_.clear(line_);
        c_.skip_blanks();
        if (c_.peek() == '%') return parse_program_name();
        bool first = true;
        for (;;) {
            if (!skip_blanks_and_comments(c_, file_, line_, err_)) {
                err_.block = b_.block_number();
                return false;
            }
            if (c_.at_end()) break;
            const char ch = c_.peek();
            const std::uint8_t starts = kStarts[static_cast<unsigned char>(ch)];
            if ((starts & kCommandStart) != 0 &&
                (ch == '#' || ch == '$' || is_assignment_start(c_))) {
                if (!first && !(b_.number.present() && only_number_so_far_)) {
                    return fail_here(ErrorKind::kSyntax, c_.column(),
                                     "ISG commands and assignments stand in a block of their own "
                                     "(after an optional N number)");
                }
                return (ch == '#' || ch == '$') && !at_setting_data(c_) ? parse_isg_command(*this)
                                                                          : parse_assignment(*this);
            }
            if ((starts & kWordLetter) == 0) {  // not is_letter(ch)
                if (first && is_digit(ch)) {
                    return fail_here(ErrorKind::kSyntax, c_.column(),
                                     fmt::format("expected a word (an address letter: {}), found a "
                                                 "number; Klartext programs must begin with "
                                                 "'BEGIN PGM'",
                                                 kKnownWords));
                }
                return fail_here(ErrorKind::kSyntax, c_.column(),
                                 fmt::format("unexpected character {}: expected a word ({})",
                                             describe_char(ch), kKnownWords));
            }
            if (!word(first, ch)) return false;
            only_number_so_far_ = first && b_.number.present();
            first = false;
        }
        if (!first) out_.kind = LineKind::kBlock;
        return true;
    }

  private:
    bool parse_program_name() {
        c_.advance();
        const std::size_t begin = c_.offset();
        const std::uint32_t col = c_.column();
        while (is_program_name_char(c_.peek())) c_.advance();
        const std::string_view name = c_.line().substr(begin, c_.offset() - begin);
        if (!skip_blanks_and_comments(c_, file_, line_, err_)) return false;
        if (name.empty() && c_.at_end()) {  // '%' alone: the tape's start or end mark
            out_.kind = LineKind::kTapeMark;
            out_.program_name_column = col;  // as for a name: the column after the '%'
            return true;
        }
        if (name.empty()) {
            return fail_here(ErrorKind::kSyntax, col,
                             "expected a program name after '%' (letters, digits, '_', '.', '-')");
        }
        if (!c_.at_end()) {
            return fail_here(ErrorKind::kSyntax, c_.column(),
                             fmt::format("unexpected {} after the program name: the '%' line holds "
                                         "only the name",
                                         describe_char(c_.peek())));
        }
        out_.kind = LineKind::kProgramName;
        out_.program_name = name;
        out_.program_name_column = col;
        return true;
    }

    // `raw`: the letter at the cursor.
    bool word(bool first, char raw) {
        const std::uint32_t col = c_.column();
        const char letter = to_upper(raw);
        c_.advance();
        switch (letter) {
            case 'N':
                return block_number(col, first);
            case 'G':
                return g_code(col);
            case 'M':
                return m_code(col);
            case 'D':
                return tool(col);
            case 'X':
                return real(b_.axis[0], 'X', col);
            case 'Y':
                return real(b_.axis[1], 'Y', col);
            case 'Z':
                return real(b_.axis[2], 'Z', col);
            case 'B':
                return real(b_.b_axis, 'B', col);
            case 'I':
                return center(0, 'I', col);
            case 'J':
                return center(1, 'J', col);
            case 'K':
                return center(2, 'K', col);
            case 'R':
                return arc_radius(col);
            case 'F':
                return feed(col);
            case 'C':
                return collision_detection(col);
            case 'T':  // a tool change as other controls write it (T1 M6)
                return fail_here(ErrorKind::kUnknownWord, col,
                                 fmt::format("unknown word 'T': {}; T and M6 are not read "
                                             "(known words: {})",
                                             kToolByD, kKnownWords));
            default:
                return fail_here(
                    ErrorKind::kUnknownWord, col,
                    fmt::format("unknown word '{}' (known words: {})", raw, kKnownWords));
        }
    }

    // CDON / CDOF (the C is read): the gouge check's walls on or off from this block on.
    bool collision_detection(std::uint32_t col) {
        const auto upper_at = [&](std::size_t k) { return to_upper(c_.peek_at(k)); };
        const bool on = upper_at(0) == 'D' && upper_at(1) == 'O' && upper_at(2) == 'N';
        const bool off = upper_at(0) == 'D' && upper_at(1) == 'O' && upper_at(2) == 'F';
        if (!on && !off) {
            return fail_here(ErrorKind::kUnknownWord, col,
                             fmt::format("unknown word 'C' (known words: {})", kKnownWords));
        }
        if (b_.collision.present()) {
            return fail_here(ErrorKind::kConflict, col, "CDON or CDOF appears twice in one block");
        }
        for (int i = 0; i < 3; ++i) c_.advance();
        b_.collision.value = on;
        b_.collision.column = col;
        return true;
    }

    bool center(std::size_t k, char letter, std::uint32_t col) {
        if (!real(b_.center[k], letter, col)) return false;
        if (b_.radius.present()) return r_with_center(col);
        return true;
    }

    bool twice(char letter, std::uint32_t col) {
        return fail_here(ErrorKind::kConflict, col,
                         fmt::format("'{}' appears twice in one block", letter));
    }

    bool real(Word<double>& w, char letter, std::uint32_t col) {
        if (w.present()) return twice(letter, col);
        double v = 0.0;
        const std::size_t num_at = c_.offset();  // its column only for an error
        if (c_.peek() == '[') {  // X[P1*2]: an expression
            if (!bracketed(v)) return false;
            w.value = v;
            w.column = col;
            return true;
        }
        switch (c_.scan_number(v)) {
            case NumberScan::kNone:
                return fail_here(ErrorKind::kSyntax, c_.column_of(num_at),
                                 fmt::format("expected a number after '{}'", letter));
            case NumberScan::kOutOfRange:
                return fail_here(ErrorKind::kValue, c_.column_of(num_at),
                                 fmt::format("the number after '{}' is out of range", letter));
            case NumberScan::kOk:
                break;
        }
        w.value = v;
        w.column = col;
        return true;
    }

    // Digits only: G, M, D and N take whole numbers without sign or decimal point.
    // A whole number after `letter`, at most `max`; one beyond is named as written with its
    // range ("tool number D<40 digits> out of range 0..1023"), never clamped or wrapped.
    bool whole(char letter, std::uint64_t& value, std::string_view what,
               std::uint64_t max = kMaxWordNumber) {
        const std::size_t num_at = c_.offset();  // its column only for an error
        const char ch = c_.peek();
        if (!is_digit(ch)) {
            if (ch == '+' || ch == '-' || ch == '.') {
                return fail_here(
                    ErrorKind::kValue, c_.column_of(num_at),
                    fmt::format("'{}' takes a whole number without sign or decimal point", letter));
            }
            return fail_here(ErrorKind::kSyntax, c_.column_of(num_at),
                             fmt::format("expected a number after '{}'", letter));
        }
        std::uint64_t value_if_short = 0;
        const std::string_view digits = c_.scan_digits(value_if_short);
        if (c_.peek() == '.') {
            return fail_here(
                ErrorKind::kValue, c_.column(),
                fmt::format("'{}' takes a whole number without decimal point", letter));
        }
        const std::optional<std::uint64_t> v = whole_at_most(digits, value_if_short, max);
        if (!v) {
            return fail_here(ErrorKind::kValue, c_.column_of(num_at),
                             fmt::format("{} {}{} out of range 0..{}", what, letter, digits, max));
        }
        value = *v;
        return true;
    }

    bool block_number(std::uint32_t col, bool first) {
        if (!first) {
            return fail_here(ErrorKind::kSyntax, col,
                             "the block number 'N' must be the first word of the block");
        }
        std::uint64_t v = 0;
        if (!whole('N', v, "block number")) return false;
        b_.number.value = static_cast<std::int64_t>(v);
        b_.number.column = col;
        return true;
    }

    template <typename E>
    bool set_group(Word<E>& w, E value, std::uint32_t col, std::string_view group) {
        if (w.present()) return group_conflict(g_number(w.value), g_number(value), col, group);
        w.value = value;
        w.column = col;
        return true;
    }

    // Out of set_group's way (a G code of a group the block already has is rare).
    [[gnu::noinline]] bool group_conflict(int had, int g, std::uint32_t col,
                                          std::string_view group) {
        if (had == g) {
            return fail_here(ErrorKind::kConflict, col,
                             fmt::format("G{} appears twice in one block", g));
        }
        return fail_here(ErrorKind::kConflict, col,
                         fmt::format("G{} and G{} in one block: both set the {}", had, g, group));
    }

    bool g_code(std::uint32_t col) {
        std::uint64_t g = 0;
        if (!whole('G', g, "G code")) return false;
        switch (g) {
            case 0:
                return set_group(b_.motion, Motion::kRapid, col, "motion mode");
            case 1:
                return set_group(b_.motion, Motion::kLine, col, "motion mode");
            case 2:
                return set_group(b_.motion, Motion::kArcCw, col, "motion mode");
            case 3:
                return set_group(b_.motion, Motion::kArcCcw, col, "motion mode");
            case 17:
                return set_group(b_.plane, Plane::kXY, col, "plane");
            case 18:
                return set_group(b_.plane, Plane::kZX, col, "plane");
            case 19:
                return set_group(b_.plane, Plane::kYZ, col, "plane");
            case 25:
                return set_group(b_.corner, CornerMode::kLinear, col, "corner mode");
            case 26:
                return set_group(b_.corner, CornerMode::kCircular, col, "corner mode");
            case 40:
                return set_group(b_.compensation, Compensation::kOff, col, "radius compensation");
            case 41:
                return set_group(b_.compensation, Compensation::kLeft, col, "radius compensation");
            case 42:
                return set_group(b_.compensation, Compensation::kRight, col, "radius compensation");
            case 70:
                return set_group(b_.units, Units::kInch, col, "input units");
            case 71:
                return set_group(b_.units, Units::kMetric, col, "input units");
            case 138:
                return set_group(b_.selection, SelectionMode::kDirect, col, "selection method");
            case 139:
                return set_group(b_.selection, SelectionMode::kIndirect, col, "selection method");
            case 237:
                return set_group(b_.selection, SelectionMode::kPerpendicular, col,
                                 "selection method");
            case 5:
            case 236:
            case 238:
            case 239:
                // [ISG-PROG]'s other selection and deselection methods of the radius compensation.
                return fail_here(ErrorKind::kUnsupported, col,
                                 fmt::format("G{} (a selection method of the radius compensation) "
                                             "is not emulated: G139 (indirect, the initial state: "
                                             "the G41/G42 block is the approach and the G40 block "
                                             "the departure), G138 (direct) and G237 "
                                             "(perpendicular approach and departure) are "
                                             "(docs/compensation.md)",
                                             g));
            case 90:
                return set_group(b_.distance, DistanceMode::kAbsolute, col, "distance mode");
            case 91:
                return set_group(b_.distance, DistanceMode::kIncremental, col, "distance mode");
            case 20:
            case 21:
                // What Fanuc-style posts write first: name this dialect's word for it.
                return fail_here(ErrorKind::kUnknownWord, col,
                                 fmt::format("unknown G code G{} (known: {}): this dialect "
                                             "sets {} with {}",
                                             g, kKnownGCodes, g == 20 ? "inches" : "millimetres",
                                             g == 20 ? "G70" : "G71"));
            default:
                return fail_here(ErrorKind::kUnknownWord, col,
                                 fmt::format("unknown G code G{} (known: {})", g, kKnownGCodes));
        }
    }

    bool m_code(std::uint32_t col) {
        std::uint64_t m = 0;
        if (!whole('M', m, "M code")) return false;
        // M2 (M02) and M30: the program's end (DIN 66025 defines both; the emulated board has
        // no spindle or tape to tell them apart).
        if (m == 6) {
            return fail_here(ErrorKind::kUnknownWord, col,
                             fmt::format("unknown M code M6: {}, no tool change is programmed "
                                         "(known: M2, M30: the program's end)",
                                         kToolByD));
        }
        if (m != 2 && m != 30) {
            return fail_here(ErrorKind::kUnknownWord, col,
                             fmt::format("unknown M code M{} (known: M2, M30: the program's end)", m));
        }
        if (b_.end_of_program.present()) {
            return fail_here(ErrorKind::kConflict, col,
                             "the program's end (M2 or M30) appears twice in one block");
        }
        b_.end_of_program.value = true;
        b_.end_of_program.column = col;
        return true;
    }

    bool tool(std::uint32_t col) {
        if (b_.tool.present()) return twice('D', col);
        std::uint64_t d = 0;
        if (!whole('D', d, "tool number", static_cast<std::uint64_t>(kMaxToolNumber))) return false;
        b_.tool.value = static_cast<int>(d);
        b_.tool.column = col;
        return true;
    }

    bool feed(std::uint32_t col) {
        const std::uint32_t num_col = c_.column();
        // FZ, FU and F AUTO are the feeds of Klartext programs ([TNC-3D], "Gerade LN"), with the
        // TOOL CALL's S and the tool's teeth; DIN 66025 programs here have no S word and take F
        // in mm/min.
        const char next = static_cast<char>(std::toupper(static_cast<unsigned char>(c_.peek())));
        const bool auto_after_blank =
            next == ' ' && std::toupper(static_cast<unsigned char>(c_.peek_at(1))) == 'A';
        if (next == 'Z' || next == 'U' || next == 'A' || auto_after_blank) {
            const std::string_view word = next == 'Z' ? "FZ (feed per tooth)"
                                          : next == 'U' ? "FU (feed per revolution)"
                                                        : "F AUTO (the feed of the tool call)";
            return fail_here(ErrorKind::kUnsupported, col,
                             fmt::format("{} is a feed of Klartext programs (TOOL CALL with S; "
                                         "docs/nc-programs.md): DIN 66025 programs give F in "
                                         "mm/min",
                                         word));
        }
        if (!real(b_.feed, 'F', col)) return false;
        if (!(b_.feed.value > 0.0)) {
            return fail_here(ErrorKind::kValue, num_col, "feed rate F must be greater than 0");
        }
        return true;
    }

    bool arc_radius(std::uint32_t col) {
        const std::uint32_t num_col = c_.column();
        if (!real(b_.radius, 'R', col)) return false;
        if (b_.radius.value == 0.0) {
            return fail_here(ErrorKind::kValue, num_col, "arc radius R must not be 0");
        }
        if (b_.has_center_word()) return r_with_center(col);
        return true;
    }

    bool r_with_center(std::uint32_t col) {
        return fail_here(ErrorKind::kConflict, col,
                         "R and I/J/K in one block: give the arc centre or its radius, not both");
    }

    Block& b_;
    bool only_number_so_far_ = false;
};

}  // namespace

}  // namespace parser_detail

bool parser_detail::parse_din_line_general(std::string_view line, std::uint64_t line_number,
                                           std::string_view file, ParsedLine& out, Diagnostic& err,
                                           const ExpressionContext* ctx) {
    BlockParser p(line, line_number, file, out, err, ctx);
    return p.parse();
}

}  // namespace apci::nc
