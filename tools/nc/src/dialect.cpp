// SPDX-License-Identifier: MIT
// Which language a program is in, from its first line that is not blank or a comment.
#include <string_view>

#include "apci/nc/lexer.h"
#include "apci/nc/parser.h"

namespace apci::nc {


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

}  // namespace apci::nc
