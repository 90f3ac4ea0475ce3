// SPDX-License-Identifier: MIT
// The C API of the link to the board: timeouts, lost links and reconnect,
// and finding boards (apci.h "The link to the board", "Finding boards").
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <string>
#include <vector>

#include "apci/apci.h"
#include "c_api.h"

namespace {

using apci::fail;
using apci::t_last_error;
using objif::Status;

constexpr uint32_t kMaxTimeoutMs = 3'600'000;

std::string describe_link(std::string_view op, Status s, std::string_view detail) {
    std::string text =
        fmt::format("{}: {} ({})", op, objif::status_name(s), objif::status_message(s));
    if (!detail.empty()) text += fmt::format(": {}", detail);
    return text;
}

}  // namespace

extern "C" {

apci_status apci_set_timeout(apci_board* board, uint32_t milliseconds) noexcept {
    if (board == nullptr) {
        return fail(nullptr, Status::kInvalidArgument,
                    [] { return std::string("apci_set_timeout: board is NULL"); });
    }
    if (milliseconds == 0 || milliseconds > kMaxTimeoutMs) {
        return fail(board, Status::kInvalidArgument, [&] {
            return fmt::format("apci_set_timeout: {} ms is outside 1 .. {}", milliseconds,
                               kMaxTimeoutMs);
        });
    }
    const Status s = board->transport->set_timeout(std::chrono::milliseconds(milliseconds));
    if (!objif::ok(s)) {
        return fail(board, s,
                    [&] { return fmt::format("apci_set_timeout: {}", objif::status_name(s)); });
    }
    board->last_error.clear();
    board->board_message.clear();
    return APCI_OK;
}

apci_status apci_get_timeout(const apci_board* board, uint32_t* milliseconds) noexcept {
    if (board == nullptr || milliseconds == nullptr) {
        return fail(nullptr, Status::kInvalidArgument, [&] {
            return fmt::format("apci_get_timeout: {} is NULL",
                               board == nullptr ? "board" : "milliseconds");
        });
    }
    *milliseconds = static_cast<uint32_t>(board->transport->timeout().count());
    return APCI_OK;
}

int apci_is_connected(const apci_board* board) noexcept {
    return board != nullptr && board->transport->connected() ? 1 : 0;
}

size_t apci_link_lost(const apci_board* board, char* text, size_t size) noexcept {
    return apci::give_words(text, size, [&] {
        return board != nullptr && !board->transport->connected()
                   ? board->transport->lost_reason()
                   : std::string();
    });
}

apci_status apci_reconnect(apci_board* board) noexcept {
    if (board == nullptr) {
        return fail(nullptr, Status::kInvalidArgument,
                    [] { return std::string("apci_reconnect: board is NULL"); });
    }
    // The claim ends with the link it was made on; where the board knows its host by process
    // rather than by link (the dual-port RAM), it is given back first.
    apci::drop_motion_claim(board);
    const Status s = board->transport->reconnect();
    if (!objif::ok(s)) {
        return fail(board, s, [&] {
            return describe_link("reconnect", s, board->transport->failure_detail());
        });
    }
    board->last_error.clear();
    board->board_message.clear();
    return APCI_OK;
}

apci_status apci_list_devices(apci_found_fn found, void* user) noexcept {
    if (found == nullptr) {
        return fail(nullptr, Status::kInvalidArgument,
                    [] { return std::string("apci_list_devices: found is NULL"); });
    }
    std::vector<apci::FoundDevice> devices;
    std::vector<std::string> problems;
    const Status s = apci::list_devices(devices, problems);
    if (!objif::ok(s)) {
        return fail(nullptr, s, [&] { return describe_link("list devices", s, {}); });
    }
    for (const auto& d : devices) found(d.uri.c_str(), d.description.c_str(), user);
    if (problems.empty()) {
        t_last_error.clear();
    } else {
        try {
            apci::record(t_last_error, fmt::format("list devices: {}", fmt::join(problems, "; ")));
        } catch (...) {
            apci::record(t_last_error, "list devices: some kinds of board could not be enumerated");
        }
    }
    return APCI_OK;
}

}  // extern "C"
