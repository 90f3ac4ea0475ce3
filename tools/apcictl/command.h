// SPDX-License-Identifier: MIT
// apcictl's commands: one table of rows, each naming a command, whether it
// may appear as a script line, and a factory. The command line offers every
// row as a subcommand; `script` offers the rows marked for scripts, parsing
// each line with the same declaration, so a command behaves the same typed
// on the command line or written in a script. New commands (spool, direct,
// ssf, step) are new rows in commands.cpp.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "apci/apci.hpp"
#include "apci/run/board_words.h"
#include "objif/descriptor.h"

namespace apcictl {

// Process exit codes (docs/design.md section 7).
enum class Exit : int { kOk = 0, kBoard = 1, kUsage = 2 };

// What a command did: kOk, or an exit code and one line saying what failed,
// starting with the command as typed ("write 1300 1 1 4 2: WrongDeviceState (...)").
struct Outcome {
    Exit exit = Exit::kOk;
    std::string error;

    bool ok() const noexcept { return exit == Exit::kOk; }
    static Outcome success() { return {}; }
    static Outcome board_error(std::string text) { return {Exit::kBoard, std::move(text)}; }
    static Outcome usage_error(std::string text) { return {Exit::kUsage, std::move(text)}; }
};

// One board session: every command of one invocation, and every line of a
// script, runs against the same open board, so state carries over.
class Session {
public:
    explicit Session(std::string uri) : uri_(std::move(uri)) {}

    // The open board, opened on first use (so --help and usage errors never
    // open one); nullptr with `failure` set if it cannot be opened.
    apci::Board* board(Outcome& failure);
    const std::string& uri() const noexcept { return uri_; }
    // When the board was opened and its link is known to be lost (the daemon closed it: its
    // idle timeout, a restart), opens it again; returns what happened, for the user ("" when
    // nothing was to be done). `apcictl shell` asks before each line.
    std::string reconnect_if_lost();
    // Claims the board's motion for the rest of the session (apci_claim_motion), which
    // `command` ("run", "diff") needs for itself; the claim ends when the session's board is
    // closed. A board held by another program: a board error naming the holder and what to do,
    // nothing moved. A board that does not serve claims: a warning on stderr, and the command
    // goes on.
    Outcome claim_motion(std::string_view command);

private:
    std::string uri_;
    apci::Board board_;
    bool opened_ = false;
    Outcome open_failure_;
};

class Command {
public:
    virtual ~Command() = default;
    // Declares the positionals and options on `app` (a subcommand of the
    // command line, or the parser of one script line), bound to members.
    virtual void declare(CLI::App& app) = 0;
    // Checks the parsed arguments before anything runs (usage errors).
    virtual Outcome prepare() { return Outcome::success(); }
    // Runs against the session's board and prints its result on stdout.
    virtual Outcome run(Session& session) = 0;
    // The one object the command reads or writes (after prepare), for reports that name it
    // (diff); none for the others.
    virtual std::optional<objif::Address> object() const { return std::nullopt; }
};

struct CommandSpec {
    std::string_view name;
    std::string_view summary;
    bool in_scripts;  // may be a line of `apcictl script`
    std::unique_ptr<Command> (*make)();
};

// One parsed line of a script: its number, its words as typed, the command.
struct ScriptLine {
    std::uint64_t number = 0;
    std::string text;
    std::unique_ptr<Command> command;
};
// Reads and parses every line of a script file ("-": standard input),
// printing one error per bad line on stderr (command_script.cpp). A script
// with a bad line gives a failed outcome; `lines` holds the good ones.
Outcome read_script(const std::string& file, std::vector<ScriptLine>& lines);

// The command table (commands.cpp), in help order.
std::span<const CommandSpec> command_table() noexcept;
const CommandSpec* find_command(std::string_view name) noexcept;

// Factories, one per command file.
std::unique_ptr<Command> make_read_command();
std::unique_ptr<Command> make_write_command();
std::unique_ptr<Command> make_script_command();
std::unique_ptr<Command> make_shell_command();
std::unique_ptr<Command> make_status_command();
std::unique_ptr<Command> make_spool_command();
std::unique_ptr<Command> make_direct_command();
std::unique_ptr<Command> make_ssf_command();
std::unique_ptr<Command> make_step_command();
std::unique_ptr<Command> make_run_command();
std::unique_ptr<Command> make_list_command();
std::unique_ptr<Command> make_diff_command();
std::unique_ptr<Command> make_dump_command();

// "WrongDeviceState (not possible in the present device state)".
std::string describe_status(apci::Status status);
// The same for the last call on `board` that answered `status`, with what libapci knows
// beyond the status (apci_last_error: "TransportError (transport to the board failed): daemon
// PATH closed the connection: idle for 300 s (--idle-timeout 300); ..."), which the status
// name alone drops.
std::string describe_failure(const apci::Board& board, apci::Status status);

}  // namespace apcictl
