// SPDX-License-Identifier: MIT
#include "apci/nc/parser.h"

#include <fmt/format.h>

#include "apci/nc/lexer.h"

namespace apci::nc {

namespace {

constexpr std::string_view kKnownWords = "N G X Y Z I J K R F D M";
constexpr std::string_view kKnownGCodes = "G0-G3, G17-G19, G25, G26, G40-G42, G90, G91";

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

std::string describe_char(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x21 && u < 0x7F) return fmt::format("'{}'", c);
    return fmt::format("byte 0x{:02X}", u);
}

bool is_program_name_char(char c) {
    return is_letter(c) || is_digit(c) || c == '_' || c == '.' || c == '-';
}

// Skips blanks and "( ... )" comments; stops at the end, at ';' (rest is a comment) or at the
// next word. False with err on an unclosed comment.
bool skip_blanks_and_comments(LineCursor& c, std::string_view file, std::uint64_t line,
                              Diagnostic& err) {
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

class BlockParser {
  public:
    BlockParser(std::string_view line, std::uint64_t line_number, std::string_view file,
                ParsedLine& out, Diagnostic& err)
        : c_(line), line_(line_number), file_(file), out_(out), b_(out.block), err_(err) {}

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
            if (ch == '#' || ch == '$') return isg_command();
            if (!is_letter(ch)) {
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
            if (!word(first)) return false;
            first = false;
        }
        if (!first) out_.kind = LineKind::kBlock;
        return true;
    }

  private:
    // Parse errors carry the block number when the N word came before the error.
    bool fail_here(ErrorKind kind, std::uint32_t column, std::string message) {
        fail(err_, kind, file_, line_, column, std::move(message));
        err_.block = b_.number.present() ? b_.number.value : kNoBlockNumber;
        return false;
    }

    bool parse_program_name() {
        c_.advance();
        const std::size_t begin = c_.offset();
        const std::uint32_t col = c_.column();
        while (is_program_name_char(c_.peek())) c_.advance();
        const std::string_view name = c_.line().substr(begin, c_.offset() - begin);
        if (name.empty()) {
            return fail_here(ErrorKind::kSyntax, col,
                             "expected a program name after '%' (letters, digits, '_', '.', '-')");
        }
        if (!skip_blanks_and_comments(c_, file_, line_, err_)) return false;
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

    // ISG commands ("#OTC ...", "$FOR ...") are recognised so that they get a precise error now
    // and a parser of their own later; they slot in here.
    bool isg_command() {
        const std::uint32_t col = c_.column();
        const char sigil = c_.peek();
        c_.advance();
        const std::string_view name = c_.scan_identifier();
        if (name.empty()) {
            return fail_here(ErrorKind::kSyntax, col,
                             fmt::format("expected a command name after '{}'", sigil));
        }
        return fail_here(ErrorKind::kUnsupported, col,
                         fmt::format("ISG command '{}{}' is not supported yet", sigil, name));
    }

    bool word(bool first) {
        const std::uint32_t col = c_.column();
        const char raw = c_.peek();
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
            default:
                return fail_here(
                    ErrorKind::kUnknownWord, col,
                    fmt::format("unknown word '{}' (known words: {})", raw, kKnownWords));
        }
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
        const std::uint32_t num_col = c_.column();
        switch (c_.scan_number(v)) {
            case NumberScan::kNone:
                return fail_here(ErrorKind::kSyntax, num_col,
                                 fmt::format("expected a number after '{}'", letter));
            case NumberScan::kOutOfRange:
                return fail_here(ErrorKind::kValue, num_col,
                                 fmt::format("the number after '{}' is out of range", letter));
            case NumberScan::kOk:
                break;
        }
        w.value = v;
        w.column = col;
        return true;
    }

    // Digits only: G, M, D and N take whole numbers without sign or decimal point.
    bool whole(char letter, std::uint64_t& value) {
        const std::uint32_t num_col = c_.column();
        const char ch = c_.peek();
        if (!is_digit(ch)) {
            if (ch == '+' || ch == '-' || ch == '.') {
                return fail_here(
                    ErrorKind::kValue, num_col,
                    fmt::format("'{}' takes a whole number without sign or decimal point", letter));
            }
            return fail_here(ErrorKind::kSyntax, num_col,
                             fmt::format("expected a number after '{}'", letter));
        }
        value = 0;
        bool overflow = false;
        while (is_digit(c_.peek())) {
            if (value > 999'999'999'999ULL) overflow = true;
            value = value * 10 + static_cast<std::uint64_t>(c_.peek() - '0');
            c_.advance();
        }
        if (c_.peek() == '.') {
            return fail_here(
                ErrorKind::kValue, c_.column(),
                fmt::format("'{}' takes a whole number without decimal point", letter));
        }
        if (overflow) {
            return fail_here(ErrorKind::kValue, num_col,
                             fmt::format("the number after '{}' is out of range", letter));
        }
        return true;
    }

    bool block_number(std::uint32_t col, bool first) {
        if (!first) {
            return fail_here(ErrorKind::kSyntax, col,
                             "the block number 'N' must be the first word of the block");
        }
        std::uint64_t v = 0;
        if (!whole('N', v)) return false;
        b_.number.value = static_cast<std::int64_t>(v);
        b_.number.column = col;
        return true;
    }

    template <typename E>
    bool set_group(Word<E>& w, E value, std::uint32_t col, std::string_view group) {
        if (w.present()) {
            if (w.value == value) {
                return fail_here(ErrorKind::kConflict, col,
                                 fmt::format("G{} appears twice in one block", g_number(value)));
            }
            return fail_here(ErrorKind::kConflict, col,
                             fmt::format("G{} and G{} in one block: both set the {}",
                                         g_number(w.value), g_number(value), group));
        }
        w.value = value;
        w.column = col;
        return true;
    }

    bool g_code(std::uint32_t col) {
        std::uint64_t g = 0;
        if (!whole('G', g)) return false;
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
            case 90:
                return set_group(b_.distance, DistanceMode::kAbsolute, col, "distance mode");
            case 91:
                return set_group(b_.distance, DistanceMode::kIncremental, col, "distance mode");
            default:
                return fail_here(ErrorKind::kUnknownWord, col,
                                 fmt::format("unknown G code G{} (known: {})", g, kKnownGCodes));
        }
    }

    bool m_code(std::uint32_t col) {
        std::uint64_t m = 0;
        if (!whole('M', m)) return false;
        if (m != 30) {
            return fail_here(ErrorKind::kUnknownWord, col,
                             fmt::format("unknown M code M{} (known: M30)", m));
        }
        if (b_.end_of_program.present()) {
            return fail_here(ErrorKind::kConflict, col, "M30 appears twice in one block");
        }
        b_.end_of_program.value = true;
        b_.end_of_program.column = col;
        return true;
    }

    bool tool(std::uint32_t col) {
        if (b_.tool.present()) return twice('D', col);
        const std::uint32_t num_col = c_.column();
        std::uint64_t d = 0;
        if (!whole('D', d)) return false;
        if (d > static_cast<std::uint64_t>(kMaxToolNumber)) {
            return fail_here(ErrorKind::kValue, num_col,
                             fmt::format("tool number D{} out of range 0..{}", d, kMaxToolNumber));
        }
        b_.tool.value = static_cast<int>(d);
        b_.tool.column = col;
        return true;
    }

    bool feed(std::uint32_t col) {
        const std::uint32_t num_col = c_.column();
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

    LineCursor c_;
    std::uint64_t line_;
    std::string_view file_;
    ParsedLine& out_;
    Block& b_;
    Diagnostic& err_;
};

}  // namespace

DialectProbe detect_dialect(std::string_view line) noexcept {
    LineCursor c(line);
    for (;;) {
        c.skip_blanks();
        if (c.peek() == '(') {
            if (!c.skip_paren_comment()) return {Dialect::kDin66025, 0};  // the parser reports it
            continue;
        }
        break;
    }
    if (c.at_end() || c.peek() == ';') return {Dialect::kUndecided, 0};
    // Klartext blocks carry a bare block number: "0  BEGIN PGM 3DTEST MM".
    while (is_digit(c.peek())) c.advance();
    c.skip_blanks();
    const std::size_t begin = c.offset();
    if (c.scan_identifier() == "BEGIN") {
        c.skip_blanks();
        if (c.scan_identifier() == "PGM") return {Dialect::kKlartext, begin};
    }
    return {Dialect::kDin66025, 0};
}

bool parse_din_line(std::string_view line, std::uint64_t line_number, std::string_view file,
                    ParsedLine& out, Diagnostic& err) {
    BlockParser p(line, line_number, file, out, err);
    return p.parse();
}

}  // namespace apci::nc
