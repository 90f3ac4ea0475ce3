// SPDX-License-Identifier: MIT
// The general parser of one DIN 66025 line (parse_din_line_general, parser.h): BlockParser and
// the helpers its two parts share. din_parser.cpp parses blocks and their words (N, G, M, D,
// X Y Z B, I J K, R, F, CDON/CDOF) and the "%name" line; isg_commands.cpp parses the ISG
// commands ([ISG-OTC] section 2.1 #OTC; docs/design.md section 8 $FOR, #KIN, #TRAFO, #HSC) and
// assignments (Pn = .., V.G.WZ_AKT.WEAR_CONST = ..). plain_block.cpp holds the fast path tried
// first; dialect.cpp tells DIN 66025 from Klartext.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

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

// The fast path for the usual block (plain_block.cpp); false where the general parser must
// parse the line.
bool plain_block(std::string_view line, std::uint64_t line_number, ParsedLine& out) noexcept;

class BlockParser {
  public:
    BlockParser(std::string_view line, std::uint64_t line_number, std::string_view file,
                ParsedLine& out, Diagnostic& err, const ExpressionContext* ctx)
        : c_(line), line_(line_number), file_(file), out_(out), b_(out.block), err_(err), ctx_(ctx) {}

    // The line into `out`; false with `err` filled on an error.
    bool parse();

  private:
    // ---- Blocks and their words (din_parser.cpp)
    bool fail_here(ErrorKind kind, std::uint32_t column, std::string message);
    bool parse_program_name();
    bool expression(double& out);
    bool word(bool first, char raw);
    bool collision_detection(std::uint32_t col);
    bool center(std::size_t k, char letter, std::uint32_t col);
    bool twice(char letter, std::uint32_t col);
    bool real(Word<double>& w, char letter, std::uint32_t col);
    bool whole(char letter, std::uint64_t& value, std::string_view what,
               std::uint64_t max = kMaxWordNumber);
    bool block_number(std::uint32_t col, bool first);
    [[gnu::noinline]] bool group_conflict(int had, int g, std::uint32_t col,
                                          std::string_view group);
    bool g_code(std::uint32_t col);
    bool m_code(std::uint32_t col);
    bool tool(std::uint32_t col);
    bool feed(std::uint32_t col);
    bool arc_radius(std::uint32_t col);
    bool r_with_center(std::uint32_t col);
    template <typename E>
    bool set_group(Word<E>& w, E value, std::uint32_t col, std::string_view group) {
        if (w.present()) return group_conflict(g_number(w.value), g_number(value), col, group);
        w.value = value;
        w.column = col;
        return true;
    }

    // ---- ISG commands and assignments (isg_commands.cpp)
    bool is_assignment_start() const;
    bool end_of_command(std::string_view what);
    bool assignment();
    bool isg_command();
    bool on_off(std::string_view command, bool& on, bool optional, bool* seen = nullptr);
    bool otc(OtcCommand& cmd);
    bool otc_parameters(OtcCommand& cmd, std::uint32_t open);
    bool otc_conflict(std::uint32_t col, std::string_view a, std::string_view b);
    bool otc_word(OtcCommand& cmd, std::string_view word, std::uint32_t col);
    bool equals_value(std::string_view name, double& v);
    bool kin(IsgLine& isg);
    bool hsc(IsgLine& isg);
    bool for_loop(ForLoop& loop);

    LineCursor c_;
    std::uint64_t line_;
    std::string_view file_;
    ParsedLine& out_;
    Block& b_;
    Diagnostic& err_;
    const ExpressionContext* ctx_;
    bool only_number_so_far_ = false;
};

}  // namespace apci::nc::parser_detail
