// SPDX-License-Identifier: MIT
// The general parser of one DIN 66025 line (parse_din_line_general, parser.h), in two parts
// that share what is declared here: din_parser.cpp parses blocks and their words (N, G, M, D,
// X Y Z B, I J K, R, F, CDON/CDOF) and the "%name" line; isg_commands.cpp the ISG commands
// ([ISG-OTC] section 2.1 #OTC; docs/design.md section 8 $FOR, #KIN, #TRAFO, #HSC) and the
// assignments (Pn = .., V.G.WZ_AKT.WEAR_CONST = ..), which stand in a block of their own.
// plain_block.cpp holds the fast path tried first; dialect.cpp tells DIN 66025 from Klartext.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "apci/nc/expression.h"
#include "apci/nc/lexer.h"
#include "apci/nc/parser.h"

namespace apci::nc::parser_detail {

// Whether the identifier `id` is `upper` in any case.
inline bool keyword_is(std::string_view id, std::string_view upper) {
    if (id.size() != upper.size()) return false;
    for (std::size_t i = 0; i < id.size(); ++i)
        if (to_upper(id[i]) != upper[i]) return false;
    return true;
}

// Fills err and returns false, so error paths read `return fail(...)`.
bool fail(Diagnostic& err, ErrorKind kind, std::string_view file, std::uint64_t line,
          std::uint32_t column, std::string message);

// A character as an error message names it: 'x', or "byte 0x07".
std::string describe_char(char c);

// Skips blanks and "( ... )" comments; stops at the end, at ';' (rest is a comment) or at the
// next word. False with err on an unclosed comment.
bool skip_comments(LineCursor& c, std::string_view file, std::uint64_t line, Diagnostic& err);

// The same; the blanks between words (the usual case) are skipped here, inline.
inline bool skip_blanks_and_comments(LineCursor& c, std::string_view file, std::uint64_t line,
                                     Diagnostic& err) {
    c.skip_blanks();
    const char ch = c.peek();
    if (ch != '(' && ch != ';') return true;
    return skip_comments(c, file, line, err);
}

// One line under the general parser: the cursor, where the line is (file, line number), what
// it fills, and the context its expressions are evaluated with. The parsers of both parts
// derive from it; the block's parser hands it, cursor and all, to the ISG commands'.
class LineParse {
  public:
    LineParse(std::string_view line, std::uint64_t line_number, std::string_view file,
              ParsedLine& out, Diagnostic& err, const ExpressionContext* ctx)
        : c_(line), line_(line_number), file_(file), out_(out), err_(err), ctx_(ctx) {}

  protected:
    // Parse errors carry the block number when the N word came before the error.
    bool fail_here(ErrorKind kind, std::uint32_t column, std::string message) {
        fail(err_, kind, file_, line_, column, std::move(message));
        const Word<std::int64_t>& number = out_.block.number;
        err_.block = number.present() ? number.value : kNoBlockNumber;
        return false;
    }

    // Evaluates an expression at the cursor into `out`; errors become parse errors.
    bool expression(double& out) {
        ExpressionError e;
        if (evaluate_expression(c_, ctx_, out, e)) return true;
        return fail_here(e.kind, e.column == 0 ? c_.column() : e.column, std::move(e.message));
    }

    // The expression in brackets at the cursor (which stands at '['), evaluated into `out`, the
    // cursor after the ']'; a missing ']' names the column of its '['.
    bool bracketed(double& out) {
        const std::uint32_t open = c_.column();
        c_.advance();
        if (!expression(out)) return false;
        c_.skip_blanks();
        if (c_.peek() != ']') {
            return fail_here(ErrorKind::kSyntax, c_.column(),
                             fmt::format("expected ']' to close the '[' in column {}", open));
        }
        c_.advance();
        return true;
    }

    LineCursor c_;
    std::uint64_t line_;
    std::string_view file_;
    ParsedLine& out_;
    Diagnostic& err_;
    const ExpressionContext* ctx_;
};

// The ISG commands and assignments (isg_commands.cpp). Whether the cursor stands at an
// assignment ("P1 =", "V.", a setting datum); an ISG command at '#' or '$', and an assignment,
// parsed from `at` to the end of the line.
bool is_assignment_start(const LineCursor& c);
bool parse_isg_command(const LineParse& at);
bool parse_assignment(const LineParse& at);

}  // namespace apci::nc::parser_detail
