// SPDX-License-Identifier: MIT
// Internals shared by the C API's source files (apci.cpp, apci_motion.cpp):
// the board handle and the one way a call records its last-error text.
#pragma once

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
