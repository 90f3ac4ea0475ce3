// SPDX-License-Identifier: MIT
#include "log.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <string>

namespace rwmos_emu {
namespace {

std::atomic<int> g_level{static_cast<int>(Level::kInfo)};
constexpr std::array<std::string_view, 4> kNames{"error", "warn", "info", "debug"};

}  // namespace

void set_log_level(Level level) noexcept {
    g_level = static_cast<int>(level);
}

bool log_enabled(Level level) noexcept {
    return static_cast<int>(level) <= g_level.load();
}

bool parse_level(std::string_view text, Level& out) noexcept {
    for (std::size_t i = 0; i < kNames.size(); ++i) {
        if (kNames[i] == text) {
            out = static_cast<Level>(i);
            return true;
        }
    }
    return false;
}

void log_line(Level level, std::string_view text) noexcept {
    try {
        std::string line = "rwmos-emu: ";
        line += kNames[static_cast<std::size_t>(level)];
        line += ": ";
        line += text;
        line += '\n';
        // One write per line, so lines of different threads never interleave.
        const ssize_t n = ::write(STDERR_FILENO, line.data(), line.size());
        (void)n;
    } catch (...) {
    }
}

}  // namespace rwmos_emu
