// SPDX-License-Identifier: MIT
#include <fmt/format.h>

#include <optional>
#include <string_view>

#include "apci/nc/correction_table.h"
#include "apci/nc/klartext.h"
#include "apci/nc/lexer.h"

namespace apci::nc {

namespace {

constexpr std::string_view kKnownBlocks =
    "BEGIN PGM, END PGM, TOOL CALL, L, LN, FUNCTION PROG PATH, FUNCTION TCPM, FUNCTION RESET "
    "TCPM, FUNCTION CORRDATA, M functions";
constexpr std::string_view kKnownMFunctions = "M2, M30, M107, M108, M128, M129";
constexpr std::string_view kLineWords = "X Y Z IX IY IZ B C R0 RL RR F FMAX FZ FU F AUTO M";
constexpr std::string_view kVectorLineWords =
    "X Y Z NX NY NZ TX TY TZ R0 RL RR F FMAX FZ FU F AUTO M";
constexpr std::string_view kToolCallWords = "the tool axis Z, S, F, DL, DR, DR2";

constexpr bool is_upper(char c) noexcept {
    return c >= 'A' && c <= 'Z';
}
// Where a word ends: a blank, a comment or the end of the line.
constexpr bool is_word_end(char c) noexcept {
    return c == '\0' || c == ' ' || c == '\t' || c == ';';
}

std::string describe_char(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x21 && u < 0x7F) return fmt::format("'{}'", c);
    return fmt::format("byte 0x{:02X}", u);
}

// The index of an LN coordinate or vector word in the order of [TNC-3D], X Y Z NX NY NZ TX TY TZ.
constexpr std::string_view kVectorLineOrder[] = {"X", "Y", "Z", "NX", "NY", "NZ", "TX", "TY", "TZ"};

class KlartextParser {
  public:
    KlartextParser(std::string_view line, std::uint64_t line_number, std::string_view file,
                   KlartextBlock& out, Diagnostic& err)
        : c_(line), line_(line_number), file_(file), b_(out), err_(err) {}

    bool parse() {
        b_.clear(line_);
        c_.skip_blanks();
        if (is_digit(c_.peek())) {
            if (!block_number()) return false;
            c_.skip_blanks();
        }
        if (c_.at_end() || c_.peek() == ';' || c_.peek() == '*') return true;  // kEmpty
        const std::uint32_t col = c_.column();
        const std::size_t keyword_offset = c_.offset();
        const std::string_view keyword = letters();
        if (keyword.empty()) {
            return fail(ErrorKind::kSyntax, col,
                        fmt::format("unexpected character {}: expected a Klartext block ({})",
                                    describe_char(c_.peek()), kKnownBlocks));
        }
        b_.kind_column = col;
        if (keyword == "BEGIN" || keyword == "END") return program_bracket(keyword == "BEGIN");
        if (keyword == "TOOL") return tool_call();
        if (keyword == "L") return words(KlartextKind::kLine);
        if (keyword == "LN") return words(KlartextKind::kVectorLine);
        if (keyword == "FUNCTION") return function();
        if (keyword == "M") {
            // An M-only block: "M107". Back up so that the word loop reads the M word.
            c_ = LineCursor(c_.line());
            c_.advance(keyword_offset);
            return words(KlartextKind::kMOnly);
        }
        return fail(ErrorKind::kUnsupported, col,
                    fmt::format("Klartext block '{}' is not in the supported subset (known: {})",
                                keyword, kKnownBlocks));
    }

  private:
    bool fail(ErrorKind kind, std::uint32_t column, std::string message) {
        err_.kind = kind;
        err_.file = std::string(file_);
        err_.line = line_;
        err_.column = column;
        err_.block = b_.block_number();
        err_.klartext = true;
        err_.message = std::move(message);
        return false;
    }

    std::string_view letters() {
        const std::size_t begin = c_.offset();
        while (is_upper(c_.peek())) c_.advance();
        return c_.line().substr(begin, c_.offset() - begin);
    }

    // The keyword `want` must follow (after blanks).
    bool expect_keyword(std::string_view want, std::string_view after) {
        c_.skip_blanks();
        const std::uint32_t col = c_.column();
        const std::string_view got = letters();
        if (got != want || !is_word_end(c_.peek())) {
            return fail(ErrorKind::kSyntax, col,
                        fmt::format("expected '{}' after '{}'", want, after));
        }
        return true;
    }

    // Nothing but blanks and a comment may follow.
    bool expect_end(std::string_view what) {
        c_.skip_blanks();
        if (c_.at_end() || c_.peek() == ';') return true;
        return fail(ErrorKind::kSyntax, c_.column(),
                    fmt::format("unexpected {} after {}", describe_char(c_.peek()), what));
    }

    // The digits of a whole number (`what` names it when there are none or it has a sign or a
    // decimal point); the callers check the range and name a number out of it as written.
    bool whole_digits(std::string_view& digits, std::string_view what) {
        const std::uint32_t col = c_.column();
        if (!is_digit(c_.peek())) {
            return fail(ErrorKind::kSyntax, col, fmt::format("expected {}", what));
        }
        digits = c_.scan_digits();
        if (c_.peek() == '.' || c_.peek() == '+' || c_.peek() == '-') {
            return fail(ErrorKind::kValue, col,
                        fmt::format("{} is a whole number without sign or decimal point", what));
        }
        return true;
    }

    // A whole number in 0..max; one beyond is named as written: "`name` <digits> out of range".
    bool whole_number(std::uint64_t& value, std::string_view what, std::string_view name,
                      std::uint64_t max = kMaxWordNumber) {
        const std::uint32_t col = c_.column();
        std::string_view digits;
        if (!whole_digits(digits, what)) return false;
        const std::optional<std::uint64_t> v = whole_at_most(digits, max);
        if (!v) {
            return fail(ErrorKind::kValue, col,
                        fmt::format("{} {} out of range 0..{}", name, digits, max));
        }
        value = *v;
        return true;
    }

    // A blank or the end of the line after `what` ("the block number", "'RL'").
    bool blank_after(std::string_view what) {
        if (is_word_end(c_.peek())) return true;
        return fail(ErrorKind::kSyntax, c_.column(),
                    fmt::format("expected a blank after {}, found {}", what,
                                describe_char(c_.peek())));
    }

    bool block_number() {
        const std::uint32_t col = c_.column();
        std::uint64_t n = 0;
        if (!whole_number(n, "a block number", "block number")) return false;
        if (!blank_after("the block number")) return false;
        b_.number.value = static_cast<std::int64_t>(n);
        b_.number.column = col;
        return true;
    }

    // BEGIN PGM name MM|INCH and END PGM name MM|INCH.
    bool program_bracket(bool begin) {
        const std::string_view what = begin ? "BEGIN" : "END";
        b_.kind = begin ? KlartextKind::kBeginPgm : KlartextKind::kEndPgm;
        if (!expect_keyword("PGM", what)) return false;
        c_.skip_blanks();
        const std::uint32_t name_col = c_.column();
        const std::size_t name_begin = c_.offset();
        while (!is_word_end(c_.peek())) c_.advance();
        b_.program_name = c_.line().substr(name_begin, c_.offset() - name_begin);
        b_.program_name_column = name_col;
        if (b_.program_name.empty()) {
            return fail(ErrorKind::kSyntax, name_col,
                        fmt::format("expected the program name after '{} PGM'", what));
        }
        c_.skip_blanks();
        const std::uint32_t unit_col = c_.column();
        const std::string_view unit = letters();
        if ((unit != "MM" && unit != "INCH") || !is_word_end(c_.peek())) {
            return fail(ErrorKind::kSyntax, unit_col,
                        fmt::format("expected the unit MM or INCH after the program name"));
        }
        b_.inch.value = unit == "INCH";
        b_.inch.column = unit_col;
        return expect_end(fmt::format("'{} PGM {} {}'", what, b_.program_name, unit));
    }

    bool twice(std::string_view word, std::uint32_t col) {
        return fail(ErrorKind::kConflict, col,
                    fmt::format("'{}' appears twice in one block", word));
    }

    bool number(Word<double>& w, std::string_view word, std::uint32_t col) {
        if (w.present()) return twice(word, col);
        const std::uint32_t num_col = c_.column();
        double v = 0.0;
        switch (c_.scan_number(v)) {
            case NumberScan::kNone:
                return fail(ErrorKind::kSyntax, num_col,
                            fmt::format("expected a number after '{}'", word));
            case NumberScan::kOutOfRange:
                return fail(ErrorKind::kValue, num_col,
                            fmt::format("the number after '{}' is out of range", word));
            case NumberScan::kOk:
                break;
        }
        if (!is_word_end(c_.peek())) {
            return fail(ErrorKind::kSyntax, c_.column(),
                        fmt::format("expected a blank after the value of '{}', found {} (Klartext "
                                    "words are separated by blanks)",
                                    word, describe_char(c_.peek())));
        }
        w.value = v;
        w.column = col;
        return true;
    }

    // TOOL CALL n [X|Y|Z] [S..] [F..] [DL..] [DR..] [DR2..]
    bool tool_call() {
        b_.kind = KlartextKind::kToolCall;
        if (!expect_keyword("CALL", "TOOL")) return false;
        c_.skip_blanks();
        const std::uint32_t tool_col = c_.column();
        if (c_.peek() == '"' || c_.peek() == '\'') {
            return fail(ErrorKind::kUnsupported, tool_col,
                        "tools are called by number (TOOL CALL 5 Z), not by name");
        }
        std::uint64_t n = 0;
        if (!whole_number(n, "the tool number after 'TOOL CALL'", "tool number",
                          static_cast<std::uint64_t>(kMaxToolNumber)))
            return false;
        if (!blank_after("the tool number")) return false;
        b_.tool.value = static_cast<int>(n);
        b_.tool.column = tool_col;
        for (;;) {
            c_.skip_blanks();
            if (c_.at_end() || c_.peek() == ';') return true;
            const std::uint32_t col = c_.column();
            std::string_view word = letters();
            if (word == "X" || word == "Y" || word == "Z") {
                if (!is_word_end(c_.peek())) {
                    return fail(ErrorKind::kSyntax, col,
                                fmt::format("the tool axis '{}' takes no value", word));
                }
                if (b_.tool_axis.present()) return twice("tool axis", col);
                b_.tool_axis.value = word[0];
                b_.tool_axis.column = col;
                continue;
            }
            if (word == "DR" && c_.peek() == '2') {
                if (!dr2_word(col)) return false;
                continue;
            }
            Word<double>* w = word == "S"    ? &b_.spindle_speed
                              : word == "F"  ? &b_.call_feed
                              : word == "DL" ? &b_.dl
                              : word == "DR" ? &b_.dr
                                             : nullptr;
            if (w == nullptr) {
                if (word.empty()) word = c_.rest().substr(0, 1);
                return fail(ErrorKind::kUnknownWord, col,
                            fmt::format("unknown word '{}' in TOOL CALL (known: {})", word,
                                        kToolCallWords));
            }
            if (!number(*w, word, col)) return false;
            if (w == &b_.spindle_speed && b_.spindle_speed.value < 0.0) {
                return fail(ErrorKind::kValue, col, "spindle speed S must not be negative");
            }
            if (w == &b_.call_feed && !(b_.call_feed.value > 0.0)) {
                return fail(ErrorKind::kValue, col, "feed rate F must be greater than 0");
            }
        }
    }

    // "DR2" needs its sign ("DR2+0.1", "DR2-0.1"): "DR20.1" could be DR 20.1 or DR2 0.1.
    bool dr2_word(std::uint32_t col) {
        const char after = c_.peek_at(1);
        if (after != '+' && after != '-') {
            return fail(ErrorKind::kSyntax, col,
                        "ambiguous 'DR2...': write the sign, DR2+0.1 for DR2 or DR+2... for DR");
        }
        c_.advance();
        return number(b_.dr2, "DR2", col);
    }

    // FUNCTION PROG PATH IS CONTOUR | FUNCTION PROG PATH [IS] OFF | FUNCTION TCPM ... |
    // FUNCTION RESET TCPM
    bool function() {
        c_.skip_blanks();
        const std::uint32_t col = c_.column();
        const std::string_view what = letters();
        if (what == "PROG") {
            b_.kind = KlartextKind::kProgPath;
            if (!expect_keyword("PATH", "FUNCTION PROG")) return false;
            c_.skip_blanks();
            const std::uint32_t mode_col = c_.column();
            std::string_view mode = letters();
            if (mode == "IS") {
                c_.skip_blanks();
                mode = letters();
            }
            if ((mode != "CONTOUR" && mode != "OFF") || !is_word_end(c_.peek())) {
                return fail(ErrorKind::kSyntax, mode_col,
                            "expected 'IS CONTOUR' or 'OFF' after 'FUNCTION PROG PATH'");
            }
            b_.prog_path_contour = mode == "CONTOUR";
            return expect_end("FUNCTION PROG PATH");
        }
        if (what == "RESET") {
            b_.kind = KlartextKind::kResetTcpm;
            if (!expect_keyword("TCPM", "FUNCTION RESET")) return false;
            return expect_end("FUNCTION RESET TCPM");
        }
        if (what == "TCPM") {
            b_.kind = KlartextKind::kTcpm;
            return tcpm_options();
        }
        if (what == "CORRDATA") {
            b_.kind = KlartextKind::kCorrData;
            return corrdata();
        }
        return fail(ErrorKind::kUnsupported, col,
                    fmt::format("FUNCTION {} is not in the supported subset (known: FUNCTION PROG "
                                "PATH, FUNCTION TCPM, FUNCTION RESET TCPM, FUNCTION CORRDATA)",
                                what.empty() ? c_.rest().substr(0, 1) : what));
    }

    // FUNCTION CORRDATA TCS #n | FUNCTION CORRDATA RESET TCS: the correction table row in
    // force (the tool's delta values; [TNC-3D] "Korrekturtabellen"). WPL (workpiece
    // corrections) is not emulated.
    bool corrdata() {
        c_.skip_blanks();
        const std::uint32_t col = c_.column();
        std::string_view what = letters();
        const bool reset = what == "RESET";
        if (reset) {
            c_.skip_blanks();
            what = letters();
        }
        if (what == "WPL" && is_word_end(c_.peek())) {
            return fail(ErrorKind::kUnsupported, col,
                        "FUNCTION CORRDATA WPL (workpiece corrections) is not emulated: only TCS, "
                        "the correction table of the tool's delta values");
        }
        if (what != "TCS" || !is_word_end(c_.peek())) {
            return fail(ErrorKind::kSyntax, col,
                        "expected 'TCS #n' or 'RESET TCS' after 'FUNCTION CORRDATA'");
        }
        if (reset) {
            b_.corr_row = Word<int>{0, col};
            return expect_end("FUNCTION CORRDATA RESET TCS");
        }
        c_.skip_blanks();
        if (c_.peek() != '#') {
            return fail(ErrorKind::kSyntax, c_.column(),
                        "expected '#' and the row number after 'FUNCTION CORRDATA TCS'");
        }
        c_.advance();
        const std::uint32_t row_col = c_.column();
        std::string_view digits;
        if (!whole_digits(digits, "the row number after 'FUNCTION CORRDATA TCS #'")) return false;
        const std::optional<std::uint64_t> n =
            whole_at_most(digits, static_cast<std::uint64_t>(kMaxCorrectionRow));
        if (!n || *n < 1) {
            return fail(ErrorKind::kValue, row_col,
                        fmt::format("correction row {} out of range 1..{} (FUNCTION CORRDATA "
                                    "RESET TCS leaves the table)",
                                    digits, kMaxCorrectionRow));
        }
        b_.corr_row = Word<int>{static_cast<int>(*n), row_col};
        return expect_end("FUNCTION CORRDATA TCS #n");
    }

    // F TCP|CONT, AXIS POS|SPAT, PATHCTRL AXIS|VECTOR are accepted (feed and rotary-axis
    // interpolation are not emulated); REFPNT sets where the programmed points lie.
    bool tcpm_options() {
        for (;;) {
            c_.skip_blanks();
            if (c_.at_end() || c_.peek() == ';') return true;
            const std::uint32_t col = c_.column();
            const std::string_view option = letters();
            c_.skip_blanks();
            const std::uint32_t value_col = c_.column();
            const std::size_t begin = c_.offset();
            while (!is_word_end(c_.peek())) c_.advance();
            const std::string_view value = c_.line().substr(begin, c_.offset() - begin);
            const bool ok = (option == "F" && (value == "TCP" || value == "CONT")) ||
                            (option == "AXIS" && (value == "POS" || value == "SPAT")) ||
                            (option == "PATHCTRL" && (value == "AXIS" || value == "VECTOR"));
            if (ok) continue;
            if (option == "REFPNT") {
                if (!refpnt(value, value_col)) return false;
                continue;
            }
            return fail(ErrorKind::kSyntax, col,
                        fmt::format("unknown FUNCTION TCPM option '{}{}{}' (known: F TCP|CONT, "
                                    "AXIS POS|SPAT, PATHCTRL AXIS|VECTOR, REFPNT "
                                    "TIP-TIP|TIP-CENTER|CENTER-CENTER)",
                                    option, value.empty() ? "" : " ", value));
        }
    }

    bool refpnt(std::string_view value, std::uint32_t col) {
        const std::size_t dash = value.find('-');
        const std::string_view guide = value.substr(0, dash);
        const std::string_view pivot = dash == std::string_view::npos ? "" : value.substr(dash + 1);
        auto tip = [](std::string_view s) { return s == "TIP"; };
        auto centre = [](std::string_view s) { return s == "CENTER" || s == "CNT"; };
        if (!(tip(guide) || centre(guide)) || !(tip(pivot) || centre(pivot)) ||
            (centre(guide) && tip(pivot))) {
            return fail(ErrorKind::kSyntax, col,
                        fmt::format("unknown REFPNT '{}' (known: TIP-TIP, TIP-CENTER, "
                                    "CENTER-CENTER; CNT for CENTER)",
                                    value));
        }
        b_.reference = centre(guide) ? ToolReference::kCentre : ToolReference::kTip;
        return true;
    }

    // The words of L, LN and M-only blocks.
    bool words(KlartextKind kind) {
        b_.kind = kind;
        int last_order = -1;  // LN: index of the last coordinate or vector word
        for (;;) {
            c_.skip_blanks();
            if (c_.at_end() || c_.peek() == ';') return true;
            const std::uint32_t col = c_.column();
            const std::string_view word = letters();
            if (word.empty()) {
                return fail(ErrorKind::kSyntax, col,
                            fmt::format("unexpected character {}: expected a word ({})",
                                        describe_char(c_.peek()), known_words(kind)));
            }
            if (kind == KlartextKind::kVectorLine) {
                for (int i = 0; i < 9; ++i) {
                    if (word != kVectorLineOrder[static_cast<std::size_t>(i)]) continue;
                    if (i < last_order) {
                        return fail(
                            ErrorKind::kSyntax, col,
                            fmt::format("'{}' after '{}': LN words must come in the order "
                                        "X Y Z NX NY NZ TX TY TZ",
                                        word,
                                        kVectorLineOrder[static_cast<std::size_t>(last_order)]));
                    }
                    last_order = i;
                }
            }
            if (!word_of(kind, word, col)) return false;
        }
    }

    static std::string_view known_words(KlartextKind kind) {
        switch (kind) {
            case KlartextKind::kLine:
                return kLineWords;
            case KlartextKind::kVectorLine:
                return kVectorLineWords;
            default:
                return "M";
        }
    }

    bool not_here(std::string_view word, KlartextKind kind, std::uint32_t col) {
        const std::string_view block = kind == KlartextKind::kLine         ? "an L block"
                                       : kind == KlartextKind::kVectorLine ? "an LN block"
                                                                           : "an M block";
        return fail(
            ErrorKind::kUnknownWord, col,
            fmt::format("'{}' is not a word of {} (known: {})", word, block, known_words(kind)));
    }

    bool word_of(KlartextKind kind, std::string_view word, std::uint32_t col) {
        const bool line = kind == KlartextKind::kLine;
        const bool vector_line = kind == KlartextKind::kVectorLine;
        const bool move = line || vector_line;
        if (word == "M") return m_function(col);
        if (!move) return not_here(word, kind, col);
        if (word.size() == 1 && (word[0] == 'X' || word[0] == 'Y' || word[0] == 'Z')) {
            return axis_word(static_cast<std::size_t>(word[0] - 'X'), false, word, col);
        }
        if (word.size() == 2 && word[0] == 'I' && word[1] >= 'X' && word[1] <= 'Z') {
            if (!line) {
                return fail(ErrorKind::kProgramRule, col,
                            fmt::format("'{}': LN takes absolute coordinates only", word));
            }
            return axis_word(static_cast<std::size_t>(word[1] - 'X'), true, word, col);
        }
        if (word.size() == 2 && (word[0] == 'N' || word[0] == 'T') && word[1] >= 'X' &&
            word[1] <= 'Z') {
            if (!vector_line) return not_here(word, kind, col);
            auto& vec = word[0] == 'N' ? b_.normal : b_.tool_vector;
            return number(vec[static_cast<std::size_t>(word[1] - 'X')], word, col);
        }
        if (word == "B" || word == "C") {
            if (!line) return not_here(word, kind, col);
            return number(word == "B" ? b_.b : b_.c, word, col);
        }
        if (word == "A") {
            return fail(ErrorKind::kUnsupported, col,
                        "the emulated head has no A axis (B tilts the tool in the Z-X plane, C "
                        "turns the head about Z)");
        }
        if (word == "R") return radius_zero(col);
        if (word == "RL" || word == "RR") {
            return radius_comp(word == "RL" ? Compensation::kLeft : Compensation::kRight, word,
                               col);
        }
        // [TNC-3D], "Gerade LN": "F, FMAX, FZ, FU oder F AUTO": one feed a block.
        if (word == "FMAX") {
            if (!is_word_end(c_.peek())) return not_here(word, kind, col);
            if (b_.fmax.present()) return twice(word, col);
            if (has_feed()) return feed_conflict(col);
            b_.fmax.value = true;
            b_.fmax.column = col;
            return true;
        }
        if (word == "F") {
            if (b_.feed.present() || b_.feed_auto.present()) return twice(word, col);
            if (has_feed()) return feed_conflict(col);
            // F AUTO: the word AUTO after blanks.
            LineCursor look = c_;
            look.skip_blanks();
            if (look.peek() == 'A') {
                const std::uint32_t auto_col = look.column();
                c_ = look;
                if (letters() != "AUTO" || !is_word_end(c_.peek()))
                    return fail(ErrorKind::kSyntax, auto_col,
                                "expected a number or AUTO after 'F'");
                b_.feed_auto.value = true;
                b_.feed_auto.column = col;
                return true;
            }
            return positive_feed(b_.feed, "F", col);
        }
        if (word == "FZ" || word == "FU") {
            if (has_feed()) return feed_conflict(col);
            return positive_feed(word == "FZ" ? b_.feed_per_tooth : b_.feed_per_rev, word, col);
        }
        return not_here(word, kind, col);
    }

    bool has_feed() const noexcept {
        return b_.feed.present() || b_.fmax.present() || b_.feed_per_tooth.present() ||
               b_.feed_per_rev.present() || b_.feed_auto.present();
    }

    bool positive_feed(Word<double>& w, std::string_view word, std::uint32_t col) {
        const std::uint32_t num_col = c_.column();
        if (!number(w, word, col)) return false;
        if (!(w.value > 0.0)) {
            return fail(ErrorKind::kValue, num_col,
                        fmt::format("feed rate {} must be greater than 0", word));
        }
        return true;
    }

    bool feed_conflict(std::uint32_t col) {
        return fail(ErrorKind::kConflict, col,
                    "two feeds in one block (F, FMAX, FZ, FU, F AUTO): give one");
    }

    bool axis_word(std::size_t k, bool incremental, std::string_view word, std::uint32_t col) {
        if (b_.axis[k].present()) {
            if (b_.axis_incremental[k] != incremental) {
                return fail(ErrorKind::kConflict, col,
                            fmt::format("{} and I{} in one block: give the axis once",
                                        static_cast<char>('X' + k), static_cast<char>('X' + k)));
            }
            return twice(word, col);
        }
        b_.axis_incremental[k] = incremental;
        return number(b_.axis[k], word, col);
    }

    // R0: radius compensation off. (Klartext L has no radius value.)
    bool radius_zero(std::uint32_t col) {
        if (c_.peek() == '0' && is_word_end(c_.peek_at(1))) {
            c_.advance();
            return radius_comp(Compensation::kOff, "R0", col);
        }
        return fail(ErrorKind::kUnknownWord, col,
                    "expected R0, RL or RR (radius compensation); 'R' takes no value here");
    }

    bool radius_comp(Compensation side, std::string_view word, std::uint32_t col) {
        if (!blank_after(fmt::format("'{}'", word))) return false;
        if (b_.radius_comp.present()) {
            return fail(ErrorKind::kConflict, col,
                        "R0, RL and RR in one block: give the radius compensation once");
        }
        b_.radius_comp.value = side;
        b_.radius_comp.column = col;
        return true;
    }

    bool m_function(std::uint32_t col) {
        std::uint64_t m = 0;
        if (!whole_number(m, "a number after 'M'", "M function")) return false;
        if (!blank_after("the M function")) return false;
        if (m != 2 && m != 30 && m != 107 && m != 108 && m != 128 && m != 129) {
            return fail(ErrorKind::kUnknownWord, col,
                        fmt::format("unknown M function M{} (known: {})", m, kKnownMFunctions));
        }
        const int code = static_cast<int>(m);
        if (b_.has_m(code)) return twice(fmt::format("M{}", code), col);
        for (const auto& [a, b] : {std::pair{107, 108}, std::pair{128, 129}, std::pair{2, 30}}) {
            if ((code == a && b_.has_m(b)) || (code == b && b_.has_m(a))) {
                return fail(ErrorKind::kConflict, col,
                            fmt::format("M{} and M{} in one block: they exclude each other", a, b));
            }
        }
        if (b_.m_count == kMaxMFunctions) {
            return fail(ErrorKind::kConflict, col,
                        fmt::format("more than {} M functions in one block", kMaxMFunctions));
        }
        b_.m[b_.m_count].value = code;
        b_.m[b_.m_count].column = col;
        ++b_.m_count;
        return true;
    }

    LineCursor c_;
    std::uint64_t line_;
    std::string_view file_;
    KlartextBlock& b_;
    Diagnostic& err_;
};

}  // namespace

bool parse_klartext_line(std::string_view line, std::uint64_t line_number, std::string_view file,
                         KlartextBlock& out, Diagnostic& err) {
    KlartextParser p(line, line_number, file, out, err);
    return p.parse();
}

}  // namespace apci::nc
