// SPDX-License-Identifier: MIT
// apcictl: inspect and drive an APCI-8001/8008 board, or the emulator,
// through libapci's public API only. docs/design.md section 7; docs/apcictl.md.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "arguments.h"
#include "command.h"
#include "suggest.h"

namespace {

constexpr const char* kFooter =
    "Device URIs: emu: (embedded emulator, the default; each run starts a fresh board, "
    "so use 'script' to keep state), emu:?no-option-tc (without optionTC), unix:PATH, "
    "shm:PATH, pci:DOMAIN:BUS:DEV.FN, usb:[BUS:ADDR].\n"
    "Exit codes: 0 ok, 1 board or program error, 2 usage.";

int run(int argc, char** argv) {
    using apcictl::Exit;
    CLI::App app("apcictl - read, write and inspect APCI-8001/8008 objects", "apcictl");
    std::string device = "emu:";
    app.add_option("-d,--device", device, "Device URI (default emu:, or $APCI_DEVICE)")
        ->envname("APCI_DEVICE");
    app.set_version_flag("--version", std::string(apci_version()));
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

    // A negative number (-.5, -inf) is a value, not an option: CLI11 wants the
    // arguments reversed, without the program's name.
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
    apcictl::protect_negative_numbers(args);
    std::reverse(args.begin(), args.end());
    try {
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        // One line naming what is wrong: an unknown command or option with the one meant.
        fmt::print(stderr, "apcictl: {}\n", apcictl::explain_parse_error(app, e));
        return static_cast<int>(Exit::kUsage);
    }

    for (auto& [sub, command] : commands) {
        if (!sub->parsed()) continue;
        apcictl::Outcome outcome = command->prepare();
        if (outcome.ok()) {
            apcictl::Session session(device);
            outcome = command->run(session);
        }
        if (!outcome.error.empty()) fmt::print(stderr, "apcictl: {}\n", outcome.error);
        return static_cast<int>(outcome.exit);
    }
    return static_cast<int>(Exit::kUsage);  // unreachable: require_subcommand(1)
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "apcictl: internal error: %s\n", e.what());
    } catch (...) {
        std::fprintf(stderr, "apcictl: internal error\n");
    }
    return 1;
}
