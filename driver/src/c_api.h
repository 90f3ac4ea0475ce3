// SPDX-License-Identifier: MIT
// Internals shared by the C API's source files (apci.cpp, apci_motion.cpp):
// the board handle and the one way a call records its last-error text.
#pragma once

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

#include "apci/apci.h"
#include "objif/status.h"
#include "transport.h"

struct apci_board {
    std::unique_ptr<apci::Transport> transport;
    std::string last_error;     // "" after a successful call
    std::string board_message;  // the board's own words for the last failed motion call
    // This handle holds the board's motion (apci_claim_motion); apci_close releases it.
    bool holds_motion = false;
};

namespace apci {

// Errors of calls that have no board (apci_open, NULL board); apci.cpp.
extern thread_local std::string t_last_error;

constexpr apci_status to_c(objif::Status s) noexcept {
    return static_cast<apci_status>(s);
}

// Stores `text` as the last error; an allocation failure leaves a short text.
inline void record(std::string& slot, std::string_view text) noexcept {
    try {
        slot.assign(text);
    } catch (...) {
        slot.clear();  // never throws, keeps capacity
    }
}

inline std::string& error_slot(apci_board* board) noexcept {
    return board != nullptr ? board->last_error : t_last_error;
}

// The words that follow a failed call's status: for MotionClaimed, who holds the board's
// motion ("the board's motion is held by pid 4242 (apcictl) since ..."; one more request, a
// claim query, made only on that failure), else the transport's failure detail. apci_claim.cpp.
std::string failure_words(apci_board* board, objif::Status s);

// Gives back the motion claim this handle holds, if any, without a word on failure (apci_close,
// apci_reconnect: the claim ends with the handle or its link whatever the board answers).
void drop_motion_claim(apci_board* board) noexcept;

// The words `make()` gives, written into a caller's buffer as snprintf writes (at most size - 1
// bytes and a NUL; nothing where text is NULL or size 0), their whole length returned: the
// C API's calls that hand out words (apci_motion_claim_holder, apci_link_lost). No memory for
// the words: none given (0).
template <class Make>
std::size_t give_words(char* text, std::size_t size, Make&& make) noexcept {
    std::string words;
    try {
        words = make();
    } catch (...) {
        words.clear();
    }
    if (text != nullptr && size > 0) {
        const std::size_t n = std::min(words.size(), size - 1);
        std::memcpy(text, words.data(), n);
        text[n] = '\0';
    }
    return words.size();
}

// Records the text `format()` makes as the last error and returns `s` as a C code.
template <class Format>
apci_status fail(apci_board* board, objif::Status s, Format&& format) noexcept {
    if (board != nullptr) board->board_message.clear();
    try {
        record(error_slot(board), format());
    } catch (...) {
        record(error_slot(board), objif::status_name(s));
    }
    return to_c(s);
}

}  // namespace apci
