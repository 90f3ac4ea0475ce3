// SPDX-License-Identifier: MIT
#include "completion.h"

#include <algorithm>
#include <string_view>

#include "shell_complete.h"

namespace apcictl {
namespace {

// The commands whose positionals are object names, and those whose positionals are files.
constexpr std::string_view kObjectCommands[] = {"read", "write", "dump"};
constexpr std::string_view kFileCommands[] = {"script", "run", "diff"};
// What --device takes: the URI schemes of docs/transports.md.
constexpr std::string_view kDeviceUris[] = {"emu:", "emu:?no-option-tc", "unix:", "shm:",
                                            "pci:", "usb:"};

bool starts_with(std::string_view text, std::string_view prefix) {
    return text.substr(0, prefix.size()) == prefix;
}

void add_matching(std::vector<std::string>& out, std::string_view typed, std::string_view word) {
    if (starts_with(word, typed) &&
        std::find(out.begin(), out.end(), word) == out.end())
        out.emplace_back(word);
}

// The long and short names of `app`'s options ("--device", "-d"), help included.
std::vector<std::string> option_names(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::Option* option : app.get_options()) {
        if (option->get_positional()) continue;
        for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
        for (const std::string& name : option->get_snames()) names.push_back("-" + name);
    }
    return names;
}

// The option of `app` named by `word` ("--tools", "-d"), or nullptr.
const CLI::Option* option_named(const CLI::App& app, const std::string& word) {
    for (const CLI::Option* option : app.get_options()) {
        if (option->get_positional()) continue;
        if (option->check_name(word)) return option;
    }
    return nullptr;
}

bool takes_value(const CLI::Option* option) {
    return option != nullptr && option->get_items_expected_min() > 0;
}

// The commands of `app`: the command table's rows and help.
std::vector<std::string> command_names(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
    return names;
}

}  // namespace

LineCompletion complete_command_line(const CLI::App& app, std::span<const std::string> words,
                                     std::span<const std::string> objects) {
    LineCompletion result;
    if (words.empty()) return result;
    const std::string& typed = words.back();
    const std::span<const std::string> before = words.first(words.size() - 1);
    // The command: the first word that is not an option or an option's value.
    const CLI::App* command = nullptr;
    std::size_t command_at = before.size();
    for (std::size_t i = 0; i < before.size(); ++i) {
        if (starts_with(before[i], "-")) {
            if (before[i].find('=') == std::string::npos && takes_value(option_named(app, before[i])))
                ++i;  // its value
            continue;
        }
        for (const CLI::App* sub : app.get_subcommands({}))
            if (sub->get_name() == before[i]) command = sub;
        command_at = i;
        break;
    }
    const CLI::App& scope = command != nullptr ? *command : app;
    // The value of an option: a device URI, or a file.
    if (!before.empty() && starts_with(before.back(), "-")) {
        const CLI::Option* option = option_named(scope, before.back());
        if (option == nullptr && command != nullptr) option = option_named(app, before.back());
        if (takes_value(option)) {
            if (option->check_name("--device")) {
                for (const std::string_view uri : kDeviceUris) add_matching(result.words, typed, uri);
            } else {
                result.files = true;
            }
            return result;
        }
    }
    if (starts_with(typed, "-")) {
        for (const std::string& name : option_names(scope)) add_matching(result.words, typed, name);
        if (command != nullptr)
            for (const std::string& name : option_names(app))
                if (name != "--version" && name != "--help" && name != "-h")
                    add_matching(result.words, typed, name);
        return result;
    }
    if (command == nullptr) {
        for (const std::string& name : command_names(app)) add_matching(result.words, typed, name);
        return result;
    }
    const std::string_view name = command->get_name();
    // The positionals typed so far (words after the command that are no option or value).
    std::size_t positionals = 0;
    for (std::size_t i = command_at + 1; i < before.size(); ++i) {
        if (starts_with(before[i], "-")) {
            if (before[i].find('=') == std::string::npos && takes_value(option_named(*command, before[i])))
                ++i;
            continue;
        }
        ++positionals;
    }
    if (name == "help") {
        if (positionals == 0)
            for (const std::string& n : command_names(app))
                if (n != "help") add_matching(result.words, typed, n);
        return result;
    }
    if (std::find(std::begin(kObjectCommands), std::end(kObjectCommands), name) !=
        std::end(kObjectCommands)) {
        // The object name is the first positional (read, write NAME VALUE, dump PREFIX).
        if (positionals == 0) {
            const std::string line = std::string(name) + " " + typed;
            const std::vector<std::string> commands{std::string(name)};
            result.words = complete(line, commands, objects);
        }
        return result;
    }
    if (std::find(std::begin(kFileCommands), std::end(kFileCommands), name) !=
        std::end(kFileCommands))
        result.files = true;
    return result;
}

std::string completion_output(const LineCompletion& completion) {
    if (completion.files) return ":files\n";
    std::string out;
    for (const std::string& word : completion.words) out += word + "\n";
    return out;
}

}  // namespace apcictl
