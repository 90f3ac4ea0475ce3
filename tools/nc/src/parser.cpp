// SPDX-License-Identifier: MIT
#include "apci/nc/parser.h"

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

#include "apci/nc/lexer.h"

namespace apci::nc {

namespace {

constexpr std::string_view kKnownWords = "N G X Y Z B I J K R F D M, CDON CDOF";
constexpr std::string_view kKnownIsg = "#OTC, #KIN, #TRAFO, #HSC, $FOR, $ENDFOR";

bool keyword_is(std::string_view id, std::string_view upper) {
    if (id.size() != upper.size()) return false;
    for (std::size_t i = 0; i < id.size(); ++i)
        if (to_upper(id[i]) != upper[i]) return false;
    return true;
}
constexpr std::string_view kKnownGCodes =
    "G0-G3, G17-G19, G25, G26, G40-G42, G70, G71, G90, G91";

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

// The same; the blanks between words (the usual case) are skipped here, inline.
inline bool skip_blanks_and_comments(LineCursor& c, std::string_view file, std::uint64_t line,
                                     Diagnostic& err) {
    c.skip_blanks();
    const char ch = c.peek();
    if (ch != '(' && ch != ';') return true;
    return skip_comments(c, file, line, err);
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

class BlockParser {
  public:
    BlockParser(std::string_view line, std::uint64_t line_number, std::string_view file,
                ParsedLine& out, Diagnostic& err, const ExpressionContext* ctx)
        : c_(line), line_(line_number), file_(file), out_(out), b_(out.block), err_(err), ctx_(ctx) {}

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
                (ch == '#' || ch == '$' || is_assignment_start())) {
                if (!first && !(b_.number.present() && only_number_so_far_)) {
                    return fail_here(ErrorKind::kSyntax, c_.column(),
                                     "ISG commands and assignments stand in a block of their own "
                                     "(after an optional N number)");
                }
                return (ch == '#' || ch == '$') && !at_setting_data(c_) ? isg_command()
                                                                          : assignment();
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

    // ---- ISG commands ([ISG-OTC] section 2.1 #OTC; docs/design.md section 8 $FOR, #KIN, #TRAFO, #HSC)

    bool is_assignment_start() const {
        const char ch = to_upper(c_.peek());
        if (ch == 'V' && c_.peek_at(1) == '.') return true;
        if (at_setting_data(c_)) return true;
        if (ch != 'P' || !is_digit(c_.peek_at(1))) return false;
        std::size_t i = 1;
        while (is_digit(c_.peek_at(i))) ++i;
        while (c_.peek_at(i) == ' ' || c_.peek_at(i) == '\t') ++i;
        return c_.peek_at(i) == '=';
    }

    // Evaluates an expression at the cursor into `out`; errors become parse errors.
    bool expression(double& out) {
        ExpressionError e;
        if (evaluate_expression(c_, ctx_, out, e)) return true;
        return fail_here(e.kind, e.column == 0 ? c_.column() : e.column, std::move(e.message));
    }

    // The rest of the line must be empty (blanks, comments).
    bool end_of_command(std::string_view what) {
        if (!skip_blanks_and_comments(c_, file_, line_, err_)) {
            err_.block = b_.block_number();
            return false;
        }
        if (!c_.at_end()) {
            return fail_here(ErrorKind::kSyntax, c_.column(),
                             fmt::format("unexpected {} after {}", describe_char(c_.peek()), what));
        }
        return true;
    }

    bool assignment() {
        Assignment& a = out_.assignment;
        a = Assignment{};
        a.column = c_.column();
        if (to_upper(c_.peek()) == 'P') {
            c_.advance();
            const std::string_view digits = c_.scan_digits();
            const std::optional<std::uint64_t> v =
                whole_at_most(digits, static_cast<std::uint64_t>(kParameterCount - 1));
            if (!v) {
                return fail_here(ErrorKind::kValue, a.column,
                                 fmt::format("P parameter number P{} out of range 0..{}", digits,
                                             kParameterCount - 1));
            }
            const int n = static_cast<int>(*v);
            a.to_parameter = true;
            a.parameter = n;
        } else {
            ExpressionError e;
            if (!scan_variable(c_, a.variable, e)) return fail_here(e.kind, e.column, e.message);
            if (!variable_writable(a.variable)) {
                return fail_here(ErrorKind::kProgramRule, a.column,
                                 fmt::format("{} is read-only (only V.G.WZ_AKT.WEAR_CONST and "
                                             "$SC_TOOL_TEMP_COMP[i] are written by programs)",
                                             variable_name(a.variable)));
            }
            a.to_parameter = false;
        }
        c_.skip_blanks();
        if (c_.peek() != '=') {
            return fail_here(ErrorKind::kSyntax, c_.column(), "expected '=' in the assignment");
        }
        c_.advance();
        if (!expression(a.value)) return false;
        if (!a.to_parameter && a.variable.variable == NcVariable::kWearConst && a.value < 0.0) {
            return fail_here(ErrorKind::kValue, a.column,
                             "V.G.WZ_AKT.WEAR_CONST must not be negative (0.1 um/m, P-TOOL-00030)");
        }
        if (!a.to_parameter && a.variable.variable == NcVariable::kToolTempComp &&
            !(std::fabs(a.value) <= kToolTempCompLimit)) {
            return fail_here(ErrorKind::kValue, a.column,
                             fmt::format("{} = {} out of range: SD 42960 takes -{:g}..{:g} mm",
                                         variable_name(a.variable), a.value, kToolTempCompLimit,
                                         kToolTempCompLimit));
        }
        if (!end_of_command("the assignment")) return false;
        out_.kind = LineKind::kAssignment;
        return true;
    }

    bool isg_command() {
        IsgLine& isg = out_.isg;
        isg = IsgLine{};
        isg.column = c_.column();
        const char sigil = c_.peek();
        c_.advance();
        const std::string_view name = c_.scan_identifier();
        if (name.empty()) {
            return fail_here(ErrorKind::kSyntax, isg.column,
                             fmt::format("expected a command name after '{}'", sigil));
        }
        bool ok = false;
        if (sigil == '#' && keyword_is(name, "OTC")) {
            isg.kind = IsgKind::kOtc;
            ok = otc(isg.otc);
        } else if (sigil == '#' && keyword_is(name, "KIN")) {
            isg.kind = IsgKind::kKin;
            ok = kin(isg);
        } else if (sigil == '#' && keyword_is(name, "TRAFO")) {
            isg.kind = IsgKind::kTrafo;
            ok = on_off("#TRAFO", isg.on, /*optional=*/false) && end_of_command("#TRAFO ON|OFF");
        } else if (sigil == '#' && keyword_is(name, "HSC")) {
            isg.kind = IsgKind::kHsc;
            ok = hsc(isg);
        } else if (sigil == '$' && keyword_is(name, "FOR")) {
            isg.kind = IsgKind::kFor;
            ok = for_loop(isg.loop);
        } else if (sigil == '$' && keyword_is(name, "ENDFOR")) {
            isg.kind = IsgKind::kEndFor;
            ok = end_of_command("$ENDFOR");
        } else {
            return fail_here(ErrorKind::kUnsupported, isg.column,
                             fmt::format("ISG command '{}{}' is not supported (known: {})", sigil,
                                         name, kKnownIsg));
        }
        if (!ok) return false;
        out_.kind = LineKind::kIsg;
        return true;
    }

    // ON or OFF at the cursor (after blanks); `optional`: neither is fine (value unchanged).
    bool on_off(std::string_view command, bool& on, bool optional, bool* seen = nullptr) {
        c_.skip_blanks();
        const std::size_t at = c_.offset();
        const std::uint32_t col = c_.column();
        const std::string_view word = c_.scan_identifier();
        if (keyword_is(word, "ON") || keyword_is(word, "OFF")) {
            on = keyword_is(word, "ON");
            if (seen != nullptr) *seen = true;
            return true;
        }
        if (optional) {
            c_ = LineCursor(c_.line());
            c_.advance(at);
            return true;
        }
        return fail_here(ErrorKind::kSyntax, col,
                         word.empty() ? fmt::format("expected ON or OFF after {}", command)
                                      : fmt::format("expected ON or OFF after {}, found '{}'",
                                                    command, word));
    }

    // "#OTC ON", "#OTC OFF", "#OTC ON [LENGTH]", "#OTC ON[RADIUS DISC]", "#OTC[RADIUS, AUTO]",
    // "#OTC ON [TOOL_DIR, DISC]": [ISG-OTC] writes all of these.
    bool otc(OtcCommand& cmd) {
        bool on = false, seen = false;
        if (!on_off("#OTC", on, /*optional=*/true, &seen)) return false;
        if (seen) cmd.on = on;
        c_.skip_blanks();
        if (c_.peek() == '[') {
            const std::uint32_t open = c_.column();
            c_.advance();
            if (!otc_parameters(cmd, open)) return false;
        } else if (!seen) {
            return fail_here(ErrorKind::kSyntax, c_.column(),
                             "expected ON, OFF or '[' after #OTC (#OTC ON | OFF [ RADIUS | LENGTH "
                             "| TOOL_DIR | SURF_NORM_DIR  DISC | CONT | AUTO  WEAR_CONST=.. | "
                             "WEAR_CONST_TOOL  ACC_WEIGHT=.. ])");
        }
        return end_of_command("#OTC");
    }

    bool otc_parameters(OtcCommand& cmd, std::uint32_t open) {
        for (;;) {
            c_.skip_blanks();
            if (c_.peek() == ',') {
                c_.advance();
                continue;
            }
            if (c_.peek() == ']') {
                c_.advance();
                return true;
            }
            if (c_.at_end() || c_.peek() == ';' || c_.peek() == '(') {
                return fail_here(ErrorKind::kSyntax, c_.column(),
                                 fmt::format("expected ']' to close the '[' in column {}", open));
            }
            const std::uint32_t col = c_.column();
            const std::string_view word = c_.scan_identifier();
            if (word.empty()) {
                return fail_here(ErrorKind::kSyntax, col,
                                 fmt::format("unexpected {} in #OTC [...]", describe_char(c_.peek())));
            }
            if (!otc_word(cmd, word, col)) return false;
        }
    }

    bool otc_conflict(std::uint32_t col, std::string_view a, std::string_view b) {
        return fail_here(ErrorKind::kConflict, col,
                         a == b ? fmt::format("{} appears twice in #OTC", a)
                                : fmt::format("{} and {} in one #OTC: both set the {}", a, b,
                                              a == "WEAR_CONST" || a == "WEAR_CONST_TOOL"
                                                  ? "wear constant"
                                                  : "same setting"));
    }

    bool otc_word(OtcCommand& cmd, std::string_view word, std::uint32_t col) {
        static constexpr std::pair<std::string_view, OtcType> kTypes[] = {
            {"RADIUS", OtcType::kRadius},
            {"LENGTH", OtcType::kLength},
            {"TOOL_DIR", OtcType::kToolDir},
            {"SURF_NORM_DIR", OtcType::kSurfNormDir}};
        static constexpr std::pair<std::string_view, OtcMode> kModes[] = {
            {"CONT", OtcMode::kCont}, {"DISC", OtcMode::kDisc}, {"AUTO", OtcMode::kAuto}};
        for (const auto& [name, type] : kTypes) {
            if (!keyword_is(word, name)) continue;
            if (cmd.type) {
                return fail_here(ErrorKind::kConflict, col,
                                 fmt::format("{} and {} in one #OTC: both set the processing type",
                                             otc_type_name(*cmd.type), name));
            }
            cmd.type = type;
            return true;
        }
        for (const auto& [name, mode] : kModes) {
            if (!keyword_is(word, name)) continue;
            if (cmd.mode) {
                return fail_here(ErrorKind::kConflict, col,
                                 fmt::format("{} and {} in one #OTC: both set the mode",
                                             otc_mode_name(*cmd.mode), name));
            }
            cmd.mode = mode;
            return true;
        }
        if (keyword_is(word, "WEAR_CONST_TOOL")) {
            if (cmd.wear_const != WearConstChoice::kUnchanged) {
                return otc_conflict(col, cmd.wear_const == WearConstChoice::kTool ? "WEAR_CONST_TOOL"
                                                                                 : "WEAR_CONST",
                                    "WEAR_CONST_TOOL");
            }
            cmd.wear_const = WearConstChoice::kTool;
            return true;
        }
        if (keyword_is(word, "WEAR_CONST")) {
            if (cmd.wear_const != WearConstChoice::kUnchanged) {
                return otc_conflict(col, cmd.wear_const == WearConstChoice::kTool ? "WEAR_CONST_TOOL"
                                                                                 : "WEAR_CONST",
                                    "WEAR_CONST");
            }
            double v = 0.0;
            if (!equals_value("WEAR_CONST", v)) return false;
            // [ISG-OTC] section 3.2, P-TOOL-00030: 0 <= grinding_wear_const.
            if (v < 0.0) {
                return fail_here(ErrorKind::kValue, col,
                                 fmt::format("WEAR_CONST={} must not be negative (0.1 um/m)", v));
            }
            cmd.wear_const = WearConstChoice::kProgrammed;
            cmd.wear_const_value = v;
            return true;
        }
        if (keyword_is(word, "ACC_WEIGHT")) {
            if (cmd.acc_weight) return otc_conflict(col, "ACC_WEIGHT", "ACC_WEIGHT");
            double v = 0.0;
            if (!equals_value("ACC_WEIGHT", v)) return false;
            // [ISG-OTC] section 2.1: "Beschleunigungsgewichtung in Prozent [1;100]".
            if (v < 1.0 || v > 100.0 || v != std::floor(v)) {
                return fail_here(ErrorKind::kValue, col,
                                 fmt::format("ACC_WEIGHT={} out of range: a whole percentage "
                                             "1..100",
                                             v));
            }
            cmd.acc_weight = static_cast<int>(v);
            return true;
        }
        return fail_here(ErrorKind::kUnknownWord, col,
                         fmt::format("unknown #OTC parameter '{}' (known: RADIUS LENGTH TOOL_DIR "
                                     "SURF_NORM_DIR DISC CONT AUTO WEAR_CONST= WEAR_CONST_TOOL "
                                     "ACC_WEIGHT=)",
                                     word));
    }

    bool equals_value(std::string_view name, double& v) {
        c_.skip_blanks();
        if (c_.peek() != '=') {
            return fail_here(ErrorKind::kSyntax, c_.column(), fmt::format("expected '=' after {}", name));
        }
        c_.advance();
        return expression(v);
    }

    // #KIN ID[n] ([ISG-OTC] sections 2.4 and 2.5: "#KIN ID[4]").
    bool kin(IsgLine& isg) {
        c_.skip_blanks();
        const std::uint32_t col = c_.column();
        if (!keyword_is(c_.scan_identifier(), "ID")) {
            return fail_here(ErrorKind::kSyntax, col, "expected ID[n] after #KIN");
        }
        c_.skip_blanks();
        if (c_.peek() != '[') return fail_here(ErrorKind::kSyntax, c_.column(), "expected '[' after #KIN ID");
        const std::uint32_t open = c_.column();
        c_.advance();
        double v = 0.0;
        if (!expression(v)) return false;
        c_.skip_blanks();
        if (c_.peek() != ']') {
            return fail_here(ErrorKind::kSyntax, c_.column(),
                             fmt::format("expected ']' to close the '[' in column {}", open));
        }
        c_.advance();
        if (v != std::floor(v) || v < 0.0 || v > 1e6) {
            return fail_here(ErrorKind::kValue, col, fmt::format("#KIN ID[{}]: expected a whole number", v));
        }
        isg.kinematics = static_cast<int>(v);
        return end_of_command("#KIN ID[..]");
    }

    // #HSC ON [..] / OFF / [..]: accepted (its text is not interpreted; the executor reports it
    // as not emulated). The brackets must close.
    bool hsc(IsgLine& isg) {
        bool seen = false;
        if (!on_off("#HSC", isg.on, /*optional=*/true, &seen)) return false;
        c_.skip_blanks();
        if (c_.peek() == '[') {
            const std::uint32_t open = c_.column();
            int depth = 0;
            do {
                if (c_.peek() == '[') ++depth;
                if (c_.peek() == ']') --depth;
                c_.advance();
            } while (depth > 0 && !c_.at_end());
            if (depth > 0) {
                return fail_here(ErrorKind::kSyntax, open,
                                 "the '[' of #HSC is not closed before the end of the line");
            }
        } else if (!seen) {
            return fail_here(ErrorKind::kSyntax, c_.column(), "expected ON, OFF or '[' after #HSC");
        }
        return end_of_command("#HSC");
    }

    // $FOR Pn = start, end, step
    bool for_loop(ForLoop& loop) {
        c_.skip_blanks();
        const std::uint32_t col = c_.column();
        if (to_upper(c_.peek()) != 'P' || !is_digit(c_.peek_at(1))) {
            return fail_here(ErrorKind::kSyntax, col, "expected a P parameter after $FOR ($FOR P1 = 0, 10, 1)");
        }
        c_.advance();
        const std::string_view digits = c_.scan_digits();
        const std::optional<std::uint64_t> v =
            whole_at_most(digits, static_cast<std::uint64_t>(kParameterCount - 1));
        if (!v) {
            return fail_here(ErrorKind::kValue, col,
                             fmt::format("P parameter number P{} out of range 0..{}", digits,
                                         kParameterCount - 1));
        }
        const int n = static_cast<int>(*v);
        loop.parameter = n;
        c_.skip_blanks();
        if (c_.peek() != '=') return fail_here(ErrorKind::kSyntax, c_.column(), "expected '=' after the $FOR parameter");
        c_.advance();
        if (!expression(loop.start)) return false;
        for (double* bound : {&loop.end, &loop.step}) {
            c_.skip_blanks();
            if (c_.peek() != ',') {
                return fail_here(ErrorKind::kSyntax, c_.column(),
                                 "expected ',' in $FOR Pn = start, end, step");
            }
            c_.advance();
            if (!expression(*bound)) return false;
        }
        if (loop.step == 0.0) {
            return fail_here(ErrorKind::kValue, col, "the $FOR step must not be 0 (the loop would never end)");
        }
        return end_of_command("$FOR Pn = start, end, step");
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
            const std::uint32_t open = c_.column();
            c_.advance();
            if (!expression(v)) return false;
            c_.skip_blanks();
            if (c_.peek() != ']') {
                return fail_here(ErrorKind::kSyntax, c_.column(),
                                 fmt::format("expected ']' to close the '[' in column {}", open));
            }
            c_.advance();
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
            default:
                return fail_here(ErrorKind::kUnknownWord, col,
                                 fmt::format("unknown G code G{} (known: {})", g, kKnownGCodes));
        }
    }

    bool m_code(std::uint32_t col) {
        std::uint64_t m = 0;
        if (!whole('M', m, "M code")) return false;
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

    LineCursor c_;
    std::uint64_t line_;
    std::string_view file_;
    ParsedLine& out_;
    Block& b_;
    Diagnostic& err_;
    const ExpressionContext* ctx_;
    bool only_number_so_far_ = false;
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

bool parser_detail::parse_din_line_general(std::string_view line, std::uint64_t line_number,
                                           std::string_view file, ParsedLine& out, Diagnostic& err,
                                           const ExpressionContext* ctx) {
    BlockParser p(line, line_number, file, out, err, ctx);
    return p.parse();
}

LoopMarker loop_marker(std::string_view line) noexcept {
    LineCursor c(line);
    c.skip_blanks();
    if (to_upper(c.peek()) == 'N' && is_digit(c.peek_at(1))) {
        c.advance();
        while (is_digit(c.peek())) c.advance();
        c.skip_blanks();
    }
    if (c.peek() != '$') return LoopMarker::kNone;
    c.advance();
    const std::string_view name = c.scan_identifier();
    if (keyword_is(name, "FOR")) return LoopMarker::kFor;
    if (keyword_is(name, "ENDFOR")) return LoopMarker::kEndFor;
    return LoopMarker::kNone;
}

std::string_view otc_type_name(OtcType t) noexcept {
    switch (t) {
        case OtcType::kRadius: return "RADIUS";
        case OtcType::kLength: return "LENGTH";
        case OtcType::kToolDir: return "TOOL_DIR";
        case OtcType::kSurfNormDir: return "SURF_NORM_DIR";
    }
    return "?";
}

std::string_view otc_mode_name(OtcMode m) noexcept {
    switch (m) {
        case OtcMode::kCont: return "CONT";
        case OtcMode::kDisc: return "DISC";
        case OtcMode::kAuto: return "AUTO";
    }
    return "?";
}

}  // namespace apci::nc
