// SPDX-License-Identifier: MIT
// apcictl: inspect and drive an APCI-8001/8008 board, or the emulator,
// through libapci's public API only. docs/design.md section 7; docs/apcictl.md.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <malloc.h>

#include "arguments.h"
#include "command.h"
#include "completion.h"
#include "objif/names.h"
#include "suggest.h"

namespace {

constexpr const char* kFooter =
    "Device URIs: emu: (embedded emulator, the default; each run starts a fresh board, "
    "so use 'script' to keep state), emu:?no-option-tc (without optionTC), unix:PATH, "
    "shm:PATH, pci:DOMAIN:BUS:DEV.FN, usb:[BUS:ADDR].\n"
    "Exit codes: 0 ok, 1 board or program error (also: the output could not be written), "
    "2 usage.";

// Standard output could not be written (a full disk, a closed descriptor): said once, exit 1,
// as the board errors are, so a script that keeps the output notices. `code` is the error the
// write reported (0: the one in errno).
int output_failed(int code) {
    fmt::print(stderr, "apcictl: cannot write standard output: {}\n",
               std::strerror(code != 0 ? code : errno));
    return static_cast<int>(apcictl::Exit::kBoard);
}

// `apcictl help [COMMAND]`: the help of apcictl or of one command, on standard output.
int print_help(const CLI::App& app, const std::string& command) {
    if (command.empty()) {
        // The formatter itself: app.help() would show the selected subcommand, `help`.
        fmt::print("{}", app.get_formatter()->make_help(&app, app.get_name(),
                                                       CLI::AppFormatMode::Normal));
        return 0;
    }
    // The command table's commands and `help` itself (`help help` is `help --help`).
    std::vector<std::string> names;
    for (const auto& spec : apcictl::command_table()) names.emplace_back(spec.name);
    names.emplace_back("help");
    if (std::find(names.begin(), names.end(), command) == names.end()) {
        const std::string meant = apcictl::closest_name(command, names);
        fmt::print(stderr, "apcictl: help: unknown command '{}'{}\n", command,
                   meant.empty() ? fmt::format(" (commands: {})", fmt::join(names, ", "))
                                 : fmt::format("; did you mean '{}'?", meant));
        return static_cast<int>(apcictl::Exit::kUsage);
    }
    fmt::print("{}", app.get_subcommand(command)->help(app.get_name()));
    return 0;
}

int run(int argc, char** argv) {
    using apcictl::Exit;
    CLI::App app("apcictl - read, write and inspect APCI-8001/8008 objects", "apcictl");
    std::string device = "emu:";
    app.add_option("-d,--device", device, "Device URI (default emu:, or $APCI_DEVICE)")
        ->envname("APCI_DEVICE");
    // "apcictl (apci8001) 0.2.0" (program, package, version, as GNU tools print it), then the
    // version of the libapci it runs with, which a newer library may change.
    app.set_version_flag("--version", fmt::format("apcictl (apci8001) {}\nlibapci {}",
                                                  APCI8001_VERSION, apci_version()));
    app.require_subcommand(1);
    app.fallthrough();  // --device may also follow the command
    app.footer(kFooter);
    apcictl::accept_negative_numbers(app);

    std::vector<std::pair<CLI::App*, std::unique_ptr<apcictl::Command>>> commands;
    for (const auto& spec : apcictl::command_table()) {
        auto command = spec.make();
        CLI::App* sub = app.add_subcommand(std::string(spec.name), std::string(spec.summary));
        command->declare(*sub);
        apcictl::accept_negative_numbers(*sub);
        commands.emplace_back(sub, std::move(command));
    }

    // `help [COMMAND]`: not a row of the command table (no board, no script line).
    std::string help_topic;
    CLI::App* help = app.add_subcommand("help", "Show the help of apcictl or of one command");
    help->add_option("COMMAND", help_topic, "The command whose help to show");
    help->footer("Without COMMAND the same as 'apcictl --help'; with it the same as "
                 "'apcictl COMMAND --help'.");

    // `apcictl __complete WORDS...` (only as the first word): the candidates for the last word,
    // for the bash and zsh scripts of completions/ (completion.h); no command, no help line.
    if (argc >= 2 && std::string_view(argv[1]) == "__complete") {
        const std::vector<std::string> words(argv + 2, argv + argc);
        std::vector<std::string> objects;
        for (const auto& object : objif::named_objects()) objects.push_back(object.name);
        fmt::print("{}", apcictl::completion_output(
                             apcictl::complete_command_line(app, words, objects)));
        return std::fflush(stdout) != 0 ? output_failed(0) : 0;
    }

    // A negative number (-.5, -inf) is a value, not an option: CLI11 wants the
    // arguments reversed, without the program's name.
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
    apcictl::protect_negative_numbers(args);
    const std::vector<std::string> typed = args;  // in order, for the error's help pointer
    std::reverse(args.begin(), args.end());
    try {
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) {  // --help, --version
            const int code = app.exit(e);
            return std::fflush(stdout) != 0 || std::ferror(stdout) ? output_failed(0) : code;
        }
        // One line naming what is wrong: an unknown command or option with the one meant.
        fmt::print(stderr, "apcictl: {}\n", apcictl::explain_command_line_error(app, e, typed));
        return static_cast<int>(Exit::kUsage);
    }

    if (help->parsed()) {
        const int code = print_help(app, help_topic);
        return std::fflush(stdout) != 0 ? output_failed(0) : code;
    }
    for (auto& [sub, command] : commands) {
        if (!sub->parsed()) continue;
        apcictl::Outcome outcome = command->prepare();
        if (outcome.ok()) {
            apcictl::Session session(device);
            outcome = command->run(session);
        }
        if (!outcome.error.empty()) fmt::print(stderr, "apcictl: {}\n", outcome.error);
        // What is still buffered is written now, so a failed write is seen before exit.
        if (std::fflush(stdout) != 0 || std::ferror(stdout)) return output_failed(0);
        return static_cast<int>(outcome.exit);
    }
    return static_cast<int>(Exit::kUsage);  // unreachable: require_subcommand(1)
}

}  // namespace

int main(int argc, char** argv) {
    // Blocks of 1 MiB and more straight from the system and back to it when freed: glibc would
    // otherwise raise this bound to the largest block freed so far and keep the tables a long
    // run outgrows (the self-approach check's, doubling) as holes in its heap.
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    try {
        return run(argc, argv);
    } catch (const std::system_error& e) {
        // fmt::print throws when standard output cannot take the text (a command's result,
        // help, completion candidates): that is the output failing, not apcictl.
        if (std::ferror(stdout)) return output_failed(e.code().value());
        std::fprintf(stderr, "apcictl: internal error: %s\n", e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "apcictl: internal error: %s\n", e.what());
    } catch (...) {
        std::fprintf(stderr, "apcictl: internal error\n");
    }
    return 1;
}
