// SPDX-License-Identifier: MIT
// `shell [--status]`: one board session, one command a line, as in `script`, typed at a
// terminal with line editing, history and TAB completion (libedit, line_editor.h), or read
// plainly from a pipe. A line is parsed and dispatched as a script line (script_reader.h); a
// failing line prints its error and the shell goes on. The shell's own words: help [COMMAND],
// status on|off, quit, exit. docs/apcictl.md, "shell".
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "command.h"
#include "line_editor.h"
#include "objif/names.h"
#include "script_reader.h"
#include "shell_complete.h"
#include "shell_history.h"
#include "suggest.h"

namespace apcictl {
namespace {

constexpr std::string_view kPrompt = "apcictl> ";

// The shell's words that are no command of the table.
constexpr std::array<std::string_view, 3> kShellWords{"help", "quit", "exit"};

// What the first word of a line may be: the script commands, then the shell's words.
std::vector<std::string> shell_command_names() {
    std::vector<std::string> names;
    for (const auto& row : command_table())
        if (row.in_scripts) names.emplace_back(row.name);
    for (const auto word : kShellWords) names.emplace_back(word);
    return names;
}

// The object names TAB completes after a command: the dotted names of the object map.
std::vector<std::string> object_names() {
    std::vector<std::string> names;
    for (const auto& object : objif::named_objects()) names.push_back(object.name);
    return names;
}

class Shell {
  public:
    Shell(Session& session, bool status_after, bool numbered)
        : session_(session), status_after_(status_after), numbered_(numbered) {}

    // Runs one line (`number`: its line number in the input); false when it ends the shell.
    bool handle(const std::string& text, std::uint64_t number) {
        const std::vector<std::string> words = script_words(text);
        if (words.empty()) return true;
        const std::string& first = words.front();
        if (first == "quit" || first == "exit") {
            if (words.size() == 1) return false;
            report(Outcome::usage_error(fmt::format("{}: takes no arguments", first)), number);
            return true;
        }
        if (first == "help") {
            report(help(words), number);
            return true;
        }
        if (first == "status" && words.size() > 1) {
            report(switch_status(words), number);
            return true;
        }
        Outcome outcome = known_command(first);
        ScriptLine line{number, {}, nullptr};
        if (outcome.ok()) outcome = parse_script_line(words, line);
        // A link the daemon closed while the shell waited for this line (its idle timeout) is
        // opened again first, and the user told: every later line failed before.
        if (outcome.ok())
            if (const std::string note = session_.reconnect_if_lost(); !note.empty()) {
                std::fflush(stdout);
                fmt::print(stderr, "apcictl: note: {}\n", note);
            }
        if (outcome.ok()) outcome = line.command->run(session_);
        report(outcome, number);
        if (status_after_ && first != "status")
            report(make_status_command()->run(session_), number);
        return true;
    }

    bool failed() const noexcept { return failed_; }

    // Prints a failed outcome's error (named by its line number when reading a pipe).
    void report(const Outcome& outcome, std::uint64_t number) {
        if (outcome.ok()) return;
        failed_ = true;
        std::fflush(stdout);  // the error after what the line printed
        if (numbered_)
            fmt::print(stderr, "apcictl: line {}: {}\n", number, outcome.error);
        else
            fmt::print(stderr, "apcictl: {}\n", outcome.error);
    }

  private:
    // The first word names a command of the shell, or the error says which was meant.
    static Outcome known_command(const std::string& first) {
        const CommandSpec* spec = find_command(first);
        if (spec != nullptr && spec->in_scripts) return Outcome::success();
        const std::vector<std::string> names = shell_command_names();
        if (spec != nullptr)
            return Outcome::usage_error(fmt::format(
                "'{}' is not a shell command; run 'apcictl {}' outside the shell (shell commands: "
                "{})",
                first, first, fmt::join(names, ", ")));
        const std::string meant = closest_name(first, names);
        if (!meant.empty())
            return Outcome::usage_error(
                fmt::format("unknown command '{}'; did you mean '{}'?", first, meant));
        return Outcome::usage_error(fmt::format("unknown command '{}' (shell commands: {})", first,
                                                fmt::join(names, ", ")));
    }

    // `help`: the commands with their summaries and the shell's words; `help COMMAND`: the
    // command's arguments and options.
    Outcome help(const std::vector<std::string>& words) const {
        if (words.size() > 2)
            return Outcome::usage_error("help: give one command at most ('help read')");
        if (words.size() == 2) {
            const CommandSpec* spec = find_command(words[1]);
            if (std::find(kShellWords.begin(), kShellWords.end(), words[1]) != kShellWords.end()) {
                print_shell_words();
                return Outcome::success();
            }
            if (spec == nullptr || !spec->in_scripts) {
                Outcome unknown = known_command(words[1]);
                unknown.error = "help " + words[1] + ": " + unknown.error;
                return unknown;
            }
            auto command = spec->make();
            CLI::App parser(std::string(spec->summary), std::string(spec->name));
            command->declare(parser);
            fmt::print("{}", parser.help());
            return Outcome::success();
        }
        fmt::print("Commands (as in scripts; 'help COMMAND' shows its arguments):\n");
        for (const auto& row : command_table())
            if (row.in_scripts) fmt::print("  {:<16}{}\n", row.name, row.summary);
        print_shell_words();
        return Outcome::success();
    }

    void print_shell_words() const {
        fmt::print("Shell:\n");
        fmt::print("  {:<16}{}\n", "help [COMMAND]", "This list, or the arguments of COMMAND");
        fmt::print("  {:<16}Show the status after each line (now {})\n", "status on|off",
                   status_after_ ? "on" : "off");
        fmt::print("  {:<16}{}\n", "quit, exit", "End the shell (Ctrl-D too)");
    }

    Outcome switch_status(const std::vector<std::string>& words) {
        if (words.size() == 2 && (words[1] == "on" || words[1] == "off")) {
            status_after_ = words[1] == "on";
            return Outcome::success();
        }
        return Outcome::usage_error(fmt::format(
            "{}: give 'on' or 'off' (the status after each line), or nothing (the status now)",
            fmt::join(words, " ")));
    }

    Session& session_;
    bool status_after_;
    bool numbered_;
    bool failed_ = false;
};

void warn(const std::string& text) {
    std::fflush(stdout);
    fmt::print(stderr, "apcictl: warning: {}\n", text);
}

void run_plain(Shell& shell);

// A terminal: prompt, line editing, history (kept in its file), TAB completion; plain lines
// where the line editor cannot be loaded.
void run_on_terminal(Shell& shell) {
    if (const std::string why = LineEditor::unavailable(); !why.empty()) {
        warn("the line editor could not be loaded (" + why +
             "); lines are read as typed, without editing, history or completion");
        run_plain(shell);
        return;
    }
    std::setlocale(LC_CTYPE, "");  // the terminal's characters, for the line editor
    const std::string path = history_path(std::getenv("APCI_HISTORY"),
                                          std::getenv("XDG_STATE_HOME"), std::getenv("HOME"));
    HistoryLoad history;
    if (!path.empty()) history = load_history(path);
    if (!history.warning.empty()) warn(history.warning);
    bool keep_file = !path.empty() && history.writable;

    const std::vector<std::string> commands = shell_command_names();
    const std::vector<std::string> objects = object_names();
    LineEditor editor(
        "apcictl", std::string(kPrompt),
        [&](std::string_view before) { return complete(before, commands, objects); },
        history.entries);
    std::vector<std::string> entries = std::move(history.entries);
    for (;;) {
        const std::optional<std::string> line = editor.read_line();
        if (!line) {
            fmt::print("\n");  // Ctrl-D: the caller's prompt on a line of its own
            break;
        }
        if (remember_line(entries, *line)) {
            editor.add_history(*line);
            if (keep_file) {
                const std::string failure = save_history(path, entries);
                if (!failure.empty()) {
                    warn(failure + "; the history is kept for this session only");
                    keep_file = false;
                }
            }
        }
        if (!shell.handle(*line, 0)) break;
    }
}

// A pipe or a file: plain lines, no prompt, no history; errors are named by line number.
void run_plain(Shell& shell) {
    for (std::uint64_t number = 1;; ++number) {
        const PlainLine line = read_plain_line(stdin, kMaxLineLength);
        if (line.kind == PlainLine::Kind::kEnd) return;
        if (line.kind == PlainLine::Kind::kError) {
            warn("reading standard input failed; the shell ends");
            return;
        }
        if (line.kind == PlainLine::Kind::kTooLong) {
            shell.report(Outcome::usage_error(
                             fmt::format("longer than {} characters; not run (it starts '{}')",
                                         kMaxLineLength, line.text.substr(0, 20))),
                         number);
            continue;
        }
        if (!shell.handle(line.text, number)) return;
        // Each line's answer leaves at once: a program that feeds the shell a line at a time
        // (a coprocess) reads it before it sends the next.
        std::fflush(stdout);
    }
}

class ShellCommand final : public Command {
  public:
    void declare(CLI::App& app) override {
        app.add_flag("--status", status_, "Show the board's status after each line");
        app.footer(fmt::format(
            "One command a line against one board session, as in 'script': {}; and help "
            "[COMMAND], status on|off, quit, exit. On a terminal: line editing, history (file "
            "$APCI_HISTORY, else $XDG_STATE_HOME/apci/apcictl_history, else "
            "~/.local/state/apci/apcictl_history) and TAB completion. A failing line prints "
            "its error and the shell goes on; the exit code is 1 if any line failed.",
            script_command_names()));
    }

    Outcome run(Session& session) override {
        Outcome failure;
        if (session.board(failure) == nullptr) return failure;  // no board: no shell
        const bool terminal = ::isatty(STDIN_FILENO) == 1;
        Shell shell(session, status_, !terminal);
        if (terminal)
            run_on_terminal(shell);
        else
            run_plain(shell);
        std::fflush(stdout);
        // Each failing line was named as it failed.
        return shell.failed() ? Outcome{Exit::kBoard, {}} : Outcome::success();
    }

  private:
    bool status_ = false;
};

}  // namespace

std::unique_ptr<Command> make_shell_command() {
    return std::make_unique<ShellCommand>();
}

}  // namespace apcictl
