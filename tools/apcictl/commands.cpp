// SPDX-License-Identifier: MIT
#include <array>

#include <fmt/format.h>

#include "command.h"

namespace apcictl {
namespace {

// The command table, in help order.
constexpr std::array kCommands{
    CommandSpec{"read", "Read one object, by name or numbers (type follows the object)", true,
                make_read_command},
    CommandSpec{"write", "Write one object, by name or numbers (the value's type follows it)", true,
                make_write_command},
    CommandSpec{"dump",
                "List the readable objects by name (or under a name prefix) with their values; "
                "--json",
                false, make_dump_command},
    CommandSpec{"script", "Run commands from a file (or - for stdin) against one board session",
                false, make_script_command},
    CommandSpec{"shell",
                "Type commands at a prompt against one board session: editing, history, "
                "completion",
                false, make_shell_command},
    CommandSpec{"status", "Show the spooler fill, who holds the motion, and the TC registers ERROR and STATUS per group, by bit name",
                true, make_status_command},
    CommandSpec{"spool", "Spool one profile: G00..G03 with N, F, axis and centre words", true,
                make_spool_command},
    CommandSpec{"direct", "Direct command JA (jog absolute) or JS (stop); discards the spooler",
                true, make_direct_command},
    CommandSpec{"ssf", "Send an SSF command to axes (2001: release the held profile)", true,
                make_ssf_command},
    CommandSpec{"step", "Advance the interpolation clock by N cycles, or --idle", true,
                make_step_command},
    CommandSpec{"run", "Execute an NC program; write its path as JSON, CSV and SVG", false,
                make_run_command},
    CommandSpec{"list", "List the boards found: USB, PCI, running emulator daemons (URI each)",
                false, make_list_command},
    CommandSpec{"diff", "Run a script or NC program on two devices; report the first difference",
                false, make_diff_command},
};

}  // namespace

std::span<const CommandSpec> command_table() noexcept { return kCommands; }

const CommandSpec* find_command(std::string_view name) noexcept {
    for (const auto& row : kCommands)
        if (row.name == name) return &row;
    return nullptr;
}

std::string describe_status(apci::Status status) {
    return fmt::format("{} ({})", apci::status_name(status), apci::status_message(status));
}

std::string describe_failure(const apci::Board& board, apci::Status status) {
    std::string text = describe_status(status);
    // libapci's words are "CALL OBJECT: Name (message)[: detail]": the detail follows the
    // status's own words (a lost link's with apcictl's hint, board_words).
    const std::string said = apci::run::board_words(board);
    const auto at = said.find(text);
    if (at != std::string_view::npos) {
        const std::string_view detail = std::string_view(said).substr(at + text.size());
        if (detail.starts_with(": ")) text += detail;
    }
    return text;
}

std::string Session::reconnect_if_lost() {
    if (!opened_ || !board_ || board_.connected()) return {};
    if (const auto r = board_.reconnect(); !r)
        return fmt::format("the link to {} was closed and cannot be opened again: {}", uri_,
                           board_.last_error());
    return fmt::format(
        "the link to {} had been closed (a daemon closes a link idle for its --idle-timeout); "
        "opened again",
        uri_);
}

Outcome Session::claim_motion(std::string_view command) {
    Outcome failure;
    apci::Board* board = this->board(failure);
    if (board == nullptr) return failure;
    const apci::Status s = board->claim_motion().status;
    if (s == APCI_OK) return Outcome::success();
    if (s == APCI_NOT_SUPPORTED) {
        fmt::print(stderr,
                   "apcictl: warning: {}: {} does not serve motion claims: nothing stops another "
                   "program from moving its axes at the same time\n",
                   command, uri_);
        return Outcome::success();
    }
    if (s != APCI_MOTION_CLAIMED)
        return Outcome::board_error(fmt::format("{}: claim the board's motion: {}", command,
                                                describe_failure(*board, s)));
    // The holder from the board's record, named as libapci names it (apci_motion_claim_holder);
    // released meanwhile, libapci's words of the refusal.
    std::string holder(board->last_error());  // before the query, which clears it
    const auto claim = board->motion_claim();
    std::string what_to_do = "wait until it has finished";
    if (claim.ok() && claim.value.held != 0) {
        holder = "the board's motion is held by " + apci::motion_claim_holder(claim.value);
        if (claim.value.pid > 0) what_to_do += fmt::format(", or stop it (kill {})", claim.value.pid);
    }
    return Outcome::board_error(
        fmt::format("{}: {}: {}; nothing was moved: {}, then run again", command, uri_, holder,
                    what_to_do));
}

apci::Board* Session::board(Outcome& failure) {
    if (!opened_) {
        opened_ = true;
        board_ = apci::Board(uri_);
        if (!board_) {
            // A URI the library cannot parse is the user's typing: a usage error.
            const bool usage = board_.open_status() == APCI_INVALID_ARGUMENT;
            std::string text(board_.last_error());
            open_failure_ = usage ? Outcome::usage_error(text) : Outcome::board_error(text);
        }
    }
    if (!board_) {
        failure = open_failure_;
        return nullptr;
    }
    return &board_;
}

}  // namespace apcictl
