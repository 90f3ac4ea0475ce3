// SPDX-License-Identifier: MIT
#include "script_reader.h"

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "arguments.h"
#include "suggest.h"

namespace apcictl {
namespace {

std::string joined(const std::vector<std::string>& words) {
    return fmt::format("{}", fmt::join(words, " "));
}

}  // namespace

// Whitespace-separated words of a line, without its `#` comment.
std::vector<std::string> script_words(std::string_view line) {
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

// Parses one non-empty line into a ready command, or a usage error.
Outcome parse_script_line(const std::vector<std::string>& words, ScriptLine& line) {
    const CommandSpec* spec = find_command(words.front());
    if (spec == nullptr || !spec->in_scripts) {
        std::vector<std::string> names;
        for (const auto& row : command_table())
            if (row.in_scripts) names.emplace_back(row.name);
        const std::string meant = closest_name(words.front(), names);
        if (!meant.empty())
            return Outcome::usage_error(
                fmt::format("unknown command '{}'; did you mean '{}'?", words.front(), meant));
        return Outcome::usage_error(fmt::format("unknown command '{}' (script commands: {})",
                                                words.front(), script_command_names()));
    }
    auto command = spec->make();
    CLI::App parser(std::string(spec->summary), std::string(spec->name));
    command->declare(parser);
    accept_negative_numbers(parser);
    // A negative number (-.5, -inf) is a value, not an option (arguments.h).
    std::vector<std::string> args(words.begin() + 1, words.end());
    protect_negative_numbers(args);
    std::reverse(args.begin(), args.end());  // CLI11 wants them reversed
    try {
        parser.parse(args);
    } catch (const CLI::CallForHelp&) {
        return Outcome::usage_error(
            fmt::format("{}: --help is not a script command; run 'apcictl {} --help'",
                        joined(words), spec->name));
    } catch (const CLI::ParseError& e) {
        return Outcome::usage_error(
            fmt::format("{}: {}", joined(words), explain_parse_error(parser, e)));
    }
    Outcome prepared = command->prepare();
    if (!prepared.ok()) return prepared;
    line.text = joined(words);
    line.command = std::move(command);
    return Outcome::success();
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

ParsedScript parse_script(const std::function<PlainLine(std::uint64_t max_consumed)>& next) {
    ParsedScript script;
    std::uint64_t bytes = 0;
    for (std::uint64_t number = 1;; ++number) {
        // One byte past the bound is enough to refuse (a line without end is not read on).
        const PlainLine text = next(kMaxScriptBytes + 1 - bytes);
        if (text.kind == PlainLine::Kind::kEnd) break;
        if (text.kind == PlainLine::Kind::kError) {
            script.read_failed = true;
            break;
        }
        bytes += text.consumed;
        if (number > kMaxScriptLines || bytes > kMaxScriptBytes) {
            script.too_large = fmt::format(
                "longer than {} at line {}: a script is checked whole before it runs, so it may "
                "hold at most {} lines and {} MiB; split it, or pipe it into 'apcictl shell', "
                "which runs each line as it reads it",
                number > kMaxScriptLines ? fmt::format("{} lines", kMaxScriptLines)
                                         : fmt::format("{} MiB", kMaxScriptBytes >> 20),
                number, kMaxScriptLines, kMaxScriptBytes >> 20);
            break;
        }
        if (text.kind == PlainLine::Kind::kTooLong) {
            script.errors.push_back(
                {number, Outcome::usage_error(
                             fmt::format("longer than {} characters; not run (it starts '{}')",
                                         kMaxLineLength, text.text.substr(0, 20)))});
            continue;
        }
        const auto words = script_words(text.text);
        if (words.empty()) continue;
        ScriptLine line{number, {}, nullptr};
        Outcome parsed = parse_script_line(words, line);
        if (parsed.ok())
            script.lines.push_back(std::move(line));
        else
            script.errors.push_back({number, std::move(parsed)});
    }
    return script;
}

ParsedScript parse_script(std::istream& in) {
    ParsedScript script =
        parse_script([&in](std::uint64_t max) { return read_plain_line(in, kMaxLineLength, max); });
    script.read_failed = script.read_failed || in.bad();
    return script;
}

}  // namespace apcictl
