// SPDX-License-Identifier: MIT
// `script FILE|-`: one command a line, all against one board session, so
// state carries from line to line (each `apcictl` run on emu: starts a fresh
// embedded board; a script keeps one). Every line is parsed before any runs:
// a script with a malformed line runs nothing, and one longer than its bounds
// (script_reader.h) is refused whole. Then the lines run in order
// and the first failing one stops the script, unless --keep-going.
#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "script_reader.h"

namespace apcictl {
namespace {

class ScriptCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        app.add_option("FILE", file_, "Script file, or - to read standard input")->required();
        app.add_flag("-k,--keep-going", keep_going_,
                     "Run every line even after a failure (exit code: that of the first failure)");
        app.footer(fmt::format(
            "One command a line, with the same arguments as on the command line: {}. "
            "'#' starts a comment; blank lines are ignored. All lines share one board session. "
            "Every line is checked before any runs. A failure is reported as 'line N: "
            "COMMAND: STATUS (message)'.",
            script_command_names()));
    }

    Outcome run(Session& session) override {
        std::vector<ScriptLine> lines;
        Outcome outcome = read_script(file_, lines);
        if (!outcome.ok()) return outcome;

        std::size_t failures = 0;
        for (auto& line : lines) {
            const Outcome result = line.command->run(session);
            if (result.ok()) continue;
            ++failures;
            fmt::print(stderr, "apcictl: line {}: {}\n", line.number, result.error);
            if (outcome.ok()) outcome.exit = result.exit;
            if (!keep_going_) break;
        }
        if (keep_going_ && failures > 0)
            fmt::print(stderr, "apcictl: script: {} of {} lines failed\n", failures, lines.size());
        return outcome;  // errors already printed, line by line
    }

private:
    std::string file_;
    bool keep_going_ = false;
};

}  // namespace

// Reads and parses every line of `file` ("-": standard input) with
// parse_script (script_reader.h). Errors are printed here, one per bad line.
Outcome read_script(const std::string& file, std::vector<ScriptLine>& lines) {
    std::FILE* in = stdin;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> opened(nullptr, std::fclose);
    if (file != "-") {
        opened.reset(std::fopen(file.c_str(), "r"));
        if (!opened) {
            return Outcome::usage_error(
                fmt::format("script: cannot open '{}': {}", file, std::strerror(errno)));
        }
        in = opened.get();
    }
    ParsedScript parsed =
        parse_script([in](std::uint64_t max) { return read_plain_line(in, kMaxLineLength, max); });
    if (!parsed.too_large.empty())
        return Outcome::usage_error(
            fmt::format("script: '{}' is {}; nothing was run", file, parsed.too_large));
    Outcome outcome;
    for (const auto& error : parsed.errors) {
        fmt::print(stderr, "apcictl: line {}: {}\n", error.number, error.outcome.error);
        if (outcome.ok()) outcome.exit = error.outcome.exit;
    }
    if (parsed.read_failed) return Outcome::board_error(fmt::format("script: reading '{}' failed", file));
    lines = std::move(parsed.lines);
    return outcome;
}

std::unique_ptr<Command> make_script_command() { return std::make_unique<ScriptCommand>(); }

}  // namespace apcictl
