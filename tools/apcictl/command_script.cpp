// SPDX-License-Identifier: MIT
// `script FILE|-`: one command a line, all against one board session, so
// state carries from line to line (each `apcictl` run on emu: starts a fresh
// embedded board; a script keeps one). Every line is parsed before any runs:
// a script with a malformed line runs nothing. Then the lines run in order
// and the first failing one stops the script, unless --keep-going.
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.h"

namespace apcictl {
namespace {

// Whitespace-separated words of a line, without its `#` comment.
std::vector<std::string> words_of(std::string_view line) {
    line = line.substr(0, line.find('#'));
    std::vector<std::string> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        const std::size_t start = i;
        while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        if (i > start) words.emplace_back(line.substr(start, i - start));
    }
    return words;
}

std::string script_command_names() {
    std::string names;
    for (const auto& row : command_table()) {
        if (!row.in_scripts) continue;
        if (!names.empty()) names += ", ";
        names += row.name;
    }
    return names;
}

std::string joined(const std::vector<std::string>& words) {
    return fmt::format("{}", fmt::join(words, " "));
}

// Parses one non-empty line into a ready command, or a usage error.
Outcome parse_line(const std::vector<std::string>& words, ScriptLine& line) {
    const CommandSpec* spec = find_command(words.front());
    if (spec == nullptr || !spec->in_scripts) {
        return Outcome::usage_error(fmt::format("unknown command '{}' (script commands: {})",
                                                words.front(), script_command_names()));
    }
    auto command = spec->make();
    CLI::App parser(std::string(spec->summary), std::string(spec->name));
    command->declare(parser);
    std::vector<std::string> args(words.rbegin(), words.rend() - 1);  // CLI11 wants them reversed
    try {
        parser.parse(args);
    } catch (const CLI::CallForHelp&) {
        return Outcome::usage_error(
            fmt::format("{}: --help is not a script command; run 'apcictl {} --help'",
                        joined(words), spec->name));
    } catch (const CLI::ParseError& e) {
        return Outcome::usage_error(fmt::format("{}: {}", joined(words), e.what()));
    }
    Outcome prepared = command->prepare();
    if (!prepared.ok()) return prepared;
    line.command = std::move(command);
    return Outcome::success();
}

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
            fmt::print(stderr, "line {}: {}\n", line.number, result.error);
            if (outcome.ok()) outcome.exit = result.exit;
            if (!keep_going_) break;
        }
        if (keep_going_ && failures > 0)
            fmt::print(stderr, "script: {} of {} lines failed\n", failures, lines.size());
        return outcome;  // errors already printed, line by line
    }

private:
    std::string file_;
    bool keep_going_ = false;
};

}  // namespace

// Reads and parses every line of `file` ("-": standard input). Errors are
// printed here, one per bad line.
Outcome read_script(const std::string& file, std::vector<ScriptLine>& lines) {
    std::ifstream stream;
    std::istream* in = &std::cin;
    if (file != "-") {
        stream.open(file);
        if (!stream) {
            return Outcome::usage_error(
                fmt::format("script: cannot open '{}': {}", file, std::strerror(errno)));
        }
        in = &stream;
    }
    Outcome outcome;
    std::string text;
    for (int number = 1; std::getline(*in, text); ++number) {
        const auto words = words_of(text);
        if (words.empty()) continue;
        ScriptLine line{number, joined(words), nullptr};
        const Outcome parsed = parse_line(words, line);
        if (!parsed.ok()) {
            fmt::print(stderr, "line {}: {}\n", number, parsed.error);
            if (outcome.ok()) outcome.exit = parsed.exit;
            continue;
        }
        lines.push_back(std::move(line));
    }
    if (in->bad()) return Outcome::board_error(fmt::format("script: reading '{}' failed", file));
    return outcome;
}

std::unique_ptr<Command> make_script_command() { return std::make_unique<ScriptCommand>(); }

}  // namespace apcictl
