// SPDX-License-Identifier: MIT
// The daemon's log: one line per event on stderr, "rwmos-emu: LEVEL: text",
// filtered by --log-level. Thread-safe (one write(2) per line).
#pragma once

#include <fmt/format.h>

#include <string_view>

namespace rwmos_emu {

enum class Level { kError = 0, kWarn = 1, kInfo = 2, kDebug = 3 };

void set_log_level(Level level) noexcept;
bool log_enabled(Level level) noexcept;
// "error", "warn", "info", "debug" -> level; false for anything else.
bool parse_level(std::string_view text, Level& out) noexcept;
void log_line(Level level, std::string_view text) noexcept;

template <class... Args>
void log(Level level, fmt::format_string<Args...> format, Args&&... args) noexcept {
    if (!log_enabled(level)) return;
    try {
        log_line(level, fmt::format(format, std::forward<Args>(args)...));
    } catch (...) {
        log_line(level, "(log message could not be formatted)");
    }
}

}  // namespace rwmos_emu
