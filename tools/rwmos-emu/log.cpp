// SPDX-License-Identifier: MIT
#include "log.h"

#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace rwmos_emu {
namespace {

std::atomic<int> g_level{static_cast<int>(Level::kInfo)};
constexpr std::array<std::string_view, 4> kNames{"error", "warn", "info", "debug"};
// The syslog priority of each level (LOG_ERR, LOG_WARNING, LOG_INFO, LOG_DEBUG) as the prefix
// the journal reads from a line of a service's stderr (sd-daemon(3)).
constexpr std::array<std::string_view, 4> kJournalPrefix{"<3>", "<4>", "<6>", "<7>"};

// Whether stderr is the journal: systemd sets $JOURNAL_STREAM to "DEVICE:INODE" of the stream
// it connects (systemd.exec(5)); only then are the prefixes written, so a terminal or a file
// never sees them.
bool stderr_is_journal() noexcept {
    const char* stream = std::getenv("JOURNAL_STREAM");
    unsigned long long device = 0;
    unsigned long long inode = 0;
    struct stat st {};
    return stream != nullptr && std::sscanf(stream, "%llu:%llu", &device, &inode) == 2 &&
           ::fstat(STDERR_FILENO, &st) == 0 && st.st_dev == device && st.st_ino == inode;
}

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
        static const bool journal = stderr_is_journal();
        std::string line = journal ? std::string(kJournalPrefix[static_cast<std::size_t>(level)])
                                   : std::string();
        line += "rwmos-emu: ";
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
