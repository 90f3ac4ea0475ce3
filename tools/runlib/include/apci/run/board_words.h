// SPDX-License-Identifier: MIT
// libapci's words for the last call on a board as the tools show them (apcictl and its runs):
// where the call found the board's link lost, what ended the link (apci_link_lost()) followed by
// the tools' own hint instead of the C API's. A user of apcictl cannot call apci_reconnect():
// its next command opens the link again (the shell before its next line, a new apcictl by
// opening the board). Every other error is libapci's words unchanged.
#pragma once

#include <string>
#include <string_view>

#include "apci/apci.hpp"

namespace apci::run {

inline constexpr std::string_view kLostLinkHint = "the next command opens the link again";

// `hint`: what the tool's user does to open the link again (the Python module's is its own).
std::string board_words(const apci::Board& board, std::string_view hint = kLostLinkHint);

}  // namespace apci::run
