// SPDX-License-Identifier: MIT
// `list`: the boards this machine can reach, one line each, URI first
// (apci_list_devices: USB boards, PCI boards, running emulator daemons):
//
//   usb:1:5                       ADDI-DATA USB board 15b8:8001, port 1-2
//   pci:0000:03:00.0              ADDI-DATA PCI board 15b8:1005, BAR 0 memory 0x40000 bytes
//   unix:/run/user/1000/rwmos-emu.sock  rwmos-emu daemon, pid 4242
//
// A registered socket is a daemon only if it greets as one (libapci waits
// 500 ms for the greeting); anything else listening there is listed as
// "not an rwmos-emu daemon (registered by pid N; what it did)".
//
// One board, one line: a socket path may hold any byte but NUL, so a URI or a description
// is printed with its backslashes, line ends and other control characters escaped as the
// registry writes paths (\\, \n, \xHH); a path with a line end printed a second line.
#include <fmt/format.h>

#include <string>
#include <utility>
#include <vector>

#include "command.h"
#include "objif/registry.h"

namespace apcictl {
namespace {

class ListCommand final : public Command {
  public:
    void declare(CLI::App& app) override {
        app.footer(
            "Prints one line per board: its device URI (for --device) and what it is. "
            "Emulator daemons are found through their registry directory "
            "($APCI_RUNTIME_DIR, else $XDG_RUNTIME_DIR/apci, else /tmp/apci-UID) and "
            "named daemons only when they greet as rwmos-emu (waiting up to 500 ms each); "
            "another program listening on a registered socket is listed as 'not an "
            "rwmos-emu daemon'. Kinds "
            "of board that cannot be enumerated are named on stderr. Prints nothing "
            "when there is no board; exit 0 either way.");
    }

    Outcome run(Session&) override {
        std::vector<std::pair<std::string, std::string>> found;
        const apci::Status s = apci_list_devices(
            [](const char* uri, const char* description, void* user) {
                static_cast<std::vector<std::pair<std::string, std::string>>*>(user)->emplace_back(
                    uri, description);
            },
            &found);
        if (s != APCI_OK)
            return Outcome::board_error(fmt::format("list: {}", apci_last_error(nullptr)));
        for (auto& [uri, description] : found) {
            uri = objif::escape_registry_path(uri);
            description = objif::escape_registry_path(description);
        }
        std::size_t width = 0;
        for (const auto& [uri, description] : found) width = std::max(width, uri.size());
        for (const auto& [uri, description] : found)
            fmt::print("{:<{}}  {}\n", uri, width, description);
        if (const std::string problems = apci_last_error(nullptr); !problems.empty())
            fmt::print(stderr, "apcictl: {}\n", problems);
        return Outcome::success();
    }
};

}  // namespace

std::unique_ptr<Command> make_list_command() {
    return std::make_unique<ListCommand>();
}

}  // namespace apcictl
