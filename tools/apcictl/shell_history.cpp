// SPDX-License-Identifier: MIT
#include "shell_history.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>

namespace apcictl {
namespace {

constexpr std::string_view kRelative = "apci/apcictl_history";

bool blank(const std::string& line) {
    return std::all_of(line.begin(), line.end(),
                       [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; });
}

// Why a file with this status is not ours to read or write; "" if it is.
std::string not_ours(const struct stat& st) {
    if (!S_ISREG(st.st_mode)) return "it is not a regular file";
    if (st.st_uid != ::geteuid()) return "it belongs to another user";
    return {};
}

std::string warning(const std::string& path, const std::string& why) {
    return fmt::format("history file '{}': {}", path, why);
}

// Creates the directories of `path` (every parent, mode 0700) that are missing.
std::string make_parents(const std::string& path) {
    for (std::size_t slash = path.find('/', 1); slash != std::string::npos;
         slash = path.find('/', slash + 1)) {
        const std::string dir = path.substr(0, slash);
        if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
            return fmt::format("cannot create the directory '{}': {}", dir, std::strerror(errno));
    }
    return {};
}

bool write_all(int fd, const std::string& text) {
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        done += static_cast<std::size_t>(n);
    }
    return true;
}

}  // namespace

std::string history_path(const char* apci_history, const char* xdg_state_home, const char* home) {
    if (apci_history != nullptr) return apci_history;
    if (xdg_state_home != nullptr && xdg_state_home[0] == '/')
        return fmt::format("{}/{}", xdg_state_home, kRelative);
    if (home != nullptr && home[0] != '\0')
        return fmt::format("{}/.local/state/{}", home, kRelative);
    return {};
}

bool remember_line(std::vector<std::string>& entries, const std::string& line, std::size_t limit) {
    if (limit == 0 || blank(line) || line.size() > kHistoryLineLimit) return false;
    if (line.find('\n') != std::string::npos) return false;
    if (!entries.empty() && entries.back() == line) return false;
    entries.push_back(line);
    if (entries.size() > limit)
        entries.erase(entries.begin(),
                      entries.begin() + static_cast<std::ptrdiff_t>(entries.size() - limit));
    return true;
}

HistoryLoad load_history(const std::string& path) {
    HistoryLoad load;
    // O_NOFOLLOW: a link is refused; O_NONBLOCK: a FIFO does not block the open.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT) return load;  // no history yet
        load.writable = false;
        load.warning = warning(path, errno == ELOOP ? std::string("it is a symbolic link")
                                                    : std::string(std::strerror(errno)));
        return load;
    }
    struct stat st {};
    std::string why;
    if (::fstat(fd, &st) != 0)
        why = std::strerror(errno);
    else
        why = not_ours(st);
    if (why.empty() && static_cast<std::size_t>(st.st_size) > kHistoryFileLimit)
        why = fmt::format("it is larger than {} bytes", kHistoryFileLimit);
    std::string text;
    if (why.empty()) {
        text.resize(static_cast<std::size_t>(st.st_size));
        std::size_t done = 0;
        while (done < text.size()) {
            const ssize_t n = ::read(fd, text.data() + done, text.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) {
                why = std::strerror(errno);
                break;
            }
            if (n == 0) break;
            done += static_cast<std::size_t>(n);
        }
        text.resize(done);
    }
    ::close(fd);
    if (!why.empty()) {
        load.writable = false;
        load.warning = warning(path, why + "; it is neither read nor written");
        return load;
    }
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        remember_line(load.entries, text.substr(start, end - start));
        start = end + 1;
    }
    return load;
}

std::string save_history(const std::string& path, std::span<const std::string> entries) {
    if (path.empty()) return {};
    struct stat st {};
    if (::lstat(path.c_str(), &st) == 0) {
        const std::string why = not_ours(st);
        if (!why.empty()) return warning(path, why + "; it is not written");
    } else if (errno != ENOENT) {
        return warning(path, std::strerror(errno));
    }
    const std::string parents = make_parents(path);
    if (!parents.empty()) return warning(path, parents);

    const auto first = entries.size() > kHistoryEntries ? entries.size() - kHistoryEntries : 0;
    std::string text;
    for (const auto& line : entries.subspan(first)) text += line + '\n';

    std::string temp = path + ".XXXXXX";
    const int fd = ::mkstemp(temp.data());
    if (fd < 0)
        return warning(path, fmt::format("cannot create a temporary file next to it: {}",
                                         std::strerror(errno)));
    bool ok = ::fchmod(fd, 0600) == 0 && write_all(fd, text) && ::fsync(fd) == 0;
    const int saved_errno = errno;
    ok = ::close(fd) == 0 && ok;
    if (ok && ::rename(temp.c_str(), path.c_str()) == 0) return {};
    const std::string why = std::strerror(ok ? errno : saved_errno);
    ::unlink(temp.c_str());
    return warning(path, fmt::format("cannot write it: {}", why));
}

}  // namespace apcictl
