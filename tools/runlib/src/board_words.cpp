// SPDX-License-Identifier: MIT
#include "apci/run/board_words.h"

namespace apci::run {

std::string board_words(const apci::Board& board, std::string_view hint) {
    std::string said(board.last_error());
    if (board.connected()) return said;
    // libapci's words end with the cause, then its hint: the cause kept, the hint ours.
    const std::string cause = board.link_lost();
    const auto at = cause.empty() ? std::string::npos : said.rfind(cause);
    if (at == std::string::npos) return said;
    said.resize(at + cause.size());
    said += "; ";
    said += hint;
    return said;
}

}  // namespace apci::run
