// SPDX-License-Identifier: MIT
// The history of `apcictl shell`: where its file is, reading it, and writing it safely (never
// through a link, never over a file that is not the user's, always whole: a temporary file
// renamed over the old one). Every failure is a warning for the caller to print, never an error.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace apcictl {

// At most this many entries are kept (the oldest go first).
constexpr std::size_t kHistoryEntries = 1000;
// A line longer than this is run but not remembered; a history file larger than
// kHistoryEntries such lines is not ours to read or write.
constexpr std::size_t kHistoryLineLimit = 4096;
constexpr std::size_t kHistoryFileLimit = kHistoryEntries * (kHistoryLineLimit + 1);

// The history file: $APCI_HISTORY if set (empty: no history file), else
// $XDG_STATE_HOME/apci/apcictl_history (if that is an absolute path), else
// $HOME/.local/state/apci/apcictl_history; "" when none of them gives one. Each argument is
// the variable's value, nullptr when unset.
std::string history_path(const char* apci_history, const char* xdg_state_home, const char* home);

// Adds `line` to `entries` unless it is blank, longer than kHistoryLineLimit or the same as the
// last entry; keeps the last `limit` entries. True if it was added.
bool remember_line(std::vector<std::string>& entries, const std::string& line,
                   std::size_t limit = kHistoryEntries);

struct HistoryLoad {
    std::vector<std::string> entries;  // the file's last kHistoryEntries lines
    std::string warning;               // why the file was not read ("" if it was, or is absent)
    bool writable = true;              // false: the file is not ours; never write it
};

// Reads the history file `path`. An absent file is an empty history. A path that is not a
// regular file owned by this user (a link, a directory, another user's file), or a file larger
// than kHistoryFileLimit, is neither read nor to be written.
HistoryLoad load_history(const std::string& path);

// Writes the last kHistoryEntries of `entries` to `path`, one a line: creates the missing
// directories (mode 0700), writes a temporary file (mode 0600) next to it and renames it over
// `path`. Refuses a `path` that exists and is not a regular file owned by this user. Returns ""
// on success, else a warning naming the path and why.
std::string save_history(const std::string& path, std::span<const std::string> entries);

}  // namespace apcictl
