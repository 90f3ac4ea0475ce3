// SPDX-License-Identifier: MIT
#include "suggest.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <vector>

#include "arguments.h"

namespace apcictl {
namespace {

std::string_view without_dashes(std::string_view name) {
    while (name.starts_with('-')) name.remove_prefix(1);
    return name;
}

// "--" ends the options; it is not one.
bool is_option(std::string_view word) {
    return word.size() > 1 && word.starts_with('-') && word != "--";
}

// The subcommand of `app` that was parsed, else `app` itself.
const CLI::App& active_command(const CLI::App& app) {
    for (const CLI::App* sub : app.get_subcommands({}))
        if (sub->parsed()) return *sub;
    return app;
}

// "apcictl run --help" for the command line's `run` and for a script line's `run` parser.
std::string help_command(const CLI::App& top, const CLI::App& active) {
    std::string command = top.get_name() == "apcictl" ? "apcictl" : "apcictl " + top.get_name();
    if (&active != &top) command += " " + active.get_name();
    return command + " --help";
}

// "--tools", "-d": the option names `app` takes.
void add_option_names(const CLI::App& app, std::vector<std::string>& names) {
    for (const CLI::Option* option : app.get_options()) {
        if (!option->nonpositional()) continue;
        for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
        for (const std::string& name : option->get_snames()) names.push_back("-" + name);
    }
}

// The command whose help an unknown option points to: apcictl's own where the option was
// typed before the command's name (`words`, as typed; empty: not known), else the command's.
const CLI::App& help_for(const CLI::App& top, const CLI::App& active, std::string_view typed,
                         std::span<const std::string> words) {
    if (&active == &top) return top;
    for (const std::string& word : words) {
        if (word == active.get_name()) return active;
        if (word == typed) return top;
    }
    return active;
}

// The command's name before what is said of the words typed after it ("run: "); nothing for
// apcictl's own.
std::string said_of(const CLI::App& top, const CLI::App& command) {
    return &command == &top ? std::string() : command.get_name() + ": ";
}

std::string unknown_option(const CLI::App& top, const CLI::App& active, std::string_view typed,
                           std::span<const std::string> words = {}) {
    const std::string_view name = typed.substr(0, typed.find('='));
    std::vector<std::string> names;
    add_option_names(active, names);
    if (&active != &top) add_option_names(top, names);  // --device may follow the command
    const std::string meant = closest_name(name, names);
    const CLI::App& owner = help_for(top, active, typed, words);
    if (!meant.empty())
        return fmt::format("{}unknown option '{}'; did you mean '{}'?", said_of(top, owner), name,
                           meant);
    return fmt::format("{}unknown option '{}' (see '{}')", said_of(top, owner), name,
                       help_command(top, owner));
}

std::string unknown_command(const CLI::App& top, std::string_view typed) {
    std::vector<std::string> names;
    for (const CLI::App* sub : top.get_subcommands({})) names.push_back(sub->get_name());
    const std::string meant = closest_name(typed, names);
    if (!meant.empty())
        return fmt::format("unknown command '{}'; did you mean '{}'?", typed, meant);
    return fmt::format("unknown command '{}' (commands: {})", typed, fmt::join(names, ", "));
}

}  // namespace

std::string closest_name(std::string_view typed, std::span<const std::string> candidates) {
    const std::string* best = nullptr;
    std::size_t best_distance = 0;
    for (const std::string& candidate : candidates) {
        const std::size_t longer =
            std::max(without_dashes(typed).size(), without_dashes(candidate).size());
        const std::size_t bound = std::min<std::size_t>(2, longer == 0 ? 0 : (longer - 1) / 2);
        const std::size_t distance = edit_distance(typed, candidate);
        if (distance > bound) continue;
        if (best == nullptr || distance < best_distance) {
            best = &candidate;
            best_distance = distance;
        }
    }
    return best == nullptr ? std::string() : *best;
}

namespace {
std::string explain(const CLI::App& app, const CLI::ParseError& error,
                    std::span<const std::string> words) {
    const CLI::App& active = active_command(app);
    // The words no option or positional took; a negative number (marked, arguments.h) is not an
    // option. An unknown option first: the words after it may be its value.
    std::vector<std::string> extras = app.remaining(true);
    std::erase(extras, std::string("--"));
    for (const std::string& word : extras)
        if (is_option(word)) return unknown_option(app, active, word, words);
    for (std::string& word : extras) word = plain_text(word);
    const bool has_commands = !app.get_subcommands({}).empty();
    if (has_commands && &active == &app) {
        if (!extras.empty()) return unknown_command(app, extras.front());
    }
    // The one error CLI11 gives when no command was named at all.
    if (has_commands && &active == &app &&
        dynamic_cast<const CLI::RequiredError*>(&error) != nullptr) {
        std::vector<std::string> names;
        for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
        return fmt::format("no command given (commands: {}; see '{}')", fmt::join(names, ", "),
                           help_command(app, active));
    }
    // Words left over after a command's arguments, in the order typed (CLI11's message has
    // them last first).
    if (!extras.empty() && dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr) {
        return fmt::format("{}The following argument{} not expected: {}", said_of(app, active),
                           extras.size() == 1 ? " was" : "s were", fmt::join(extras, " "));
    }
    return said_of(app, active) + plain_text(error.what());
}
}  // namespace

std::string explain_parse_error(const CLI::App& app, const CLI::ParseError& error) {
    return explain(app, error, {});
}

std::string explain_command_line_error(const CLI::App& app, const CLI::ParseError& error,
                                       std::span<const std::string> words) {
    const CLI::App& active = active_command(app);
    if (&active != &app && dynamic_cast<const CLI::RequiredError*>(&error) != nullptr &&
        app.remaining(true).empty())
        return fmt::format("{}{} (see '{}')", said_of(app, active), plain_text(error.what()),
                           help_command(app, active));
    return explain(app, error, words);
}

}  // namespace apcictl
