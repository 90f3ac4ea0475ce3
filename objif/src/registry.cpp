// SPDX-License-Identifier: MIT
#include "objif/registry.h"

#include <dirent.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <memory>

namespace objif {
namespace {

constexpr std::string_view kPrefix = "rwmos-emu.";

std::string entry_name(pid_t pid) {
    return fmt::format("{}{}", kPrefix, pid);
}

// Whether `pid` names a live process. Only a positive pid names one: kill(0, 0) asks this
// process's group and kill(-N, 0) a group (kill(-1, 0) every process), which answer.
bool alive(pid_t pid) {
    return pid > 0 && (::kill(pid, 0) == 0 || errno == EPERM);
}

// The pid of an entry's file name: "rwmos-emu." and the pid in its plain decimal form (what
// entry_name writes: no sign, no leading zero), greater than 0; else 0.
pid_t pid_of_entry(std::string_view name) {
    if (!name.starts_with(kPrefix)) return 0;
    const std::string_view digits = name.substr(kPrefix.size());
    if (digits.empty() || digits.front() < '1' || digits.front() > '9') return 0;
    pid_t pid = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
    if (ec != std::errc() || end != digits.data() + digits.size()) return 0;
    return pid;
}

// Closes a descriptor when it goes out of scope.
struct Fd {
    int fd = -1;
    explicit Fd(int f) : fd(f) {}
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
};

bool write_all(int fd, std::string_view text) {
    while (!text.empty()) {
        const ssize_t n = ::write(fd, text.data(), text.size());
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        text.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
}

// Reads an entry file (opened relative to the directory, never through a link): a regular
// file of this user's, at most kMaxRegistryEntryBytes. False when it is anything else.
bool read_entry(int dir, const char* name, std::string& text) {
    const Fd f(::openat(dir, name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
    if (f.fd < 0) return false;
    struct stat st {};
    if (::fstat(f.fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != ::geteuid() ||
        st.st_size < 0 || static_cast<std::size_t>(st.st_size) > kMaxRegistryEntryBytes)
        return false;
    text.resize(kMaxRegistryEntryBytes + 1);
    std::size_t got = 0;
    while (got < text.size()) {
        const ssize_t n = ::read(f.fd, text.data() + got, text.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return false;
        if (n == 0) break;
        got += static_cast<std::size_t>(n);
    }
    if (got > kMaxRegistryEntryBytes) return false;  // grew since fstat
    text.resize(got);
    return true;
}

// The lines of an entry; false when one does not parse (the entry is then skipped whole).
bool parse_entry(std::string_view text, RegisteredDaemon& entry) {
    while (!text.empty()) {
        const std::size_t nl = text.find('\n');
        if (nl == std::string_view::npos) return false;  // every line ends: a torn file does not
        const std::string_view line = text.substr(0, nl);
        text.remove_prefix(nl + 1);
        const std::size_t space = line.find(' ');
        if (space == std::string_view::npos) return false;
        const std::string_view key = line.substr(0, space);
        std::string path;
        if (!unescape_registry_path(line.substr(space + 1), path) || path.empty() ||
            path.front() != '/')
            return false;
        if (key == "socket")
            entry.socket = std::move(path);
        else if (key == "shm")
            entry.shm = std::move(path);
        // Other keys (a later version's) are left to that version.
    }
    return true;
}

// Why a directory opened at `dir` is not a private one of ours; "" when it is.
std::string not_private(const std::string& dir, const struct stat& st) {
    if (!S_ISDIR(st.st_mode)) return fmt::format("registry directory {} is not a directory", dir);
    if (st.st_uid != ::geteuid())
        return fmt::format(
            "registry directory {} belongs to uid {}, not to this user (uid {}): it is not "
            "used; remove it, or set APCI_RUNTIME_DIR to a directory of your own",
            dir, st.st_uid, ::geteuid());
    if ((st.st_mode & 077) != 0)
        return fmt::format(
            "registry directory {} has mode {:04o}: other users may reach it, so it is not "
            "used; make it mode 0700 (chmod 700 {})",
            dir, st.st_mode & 07777, dir);
    return {};
}

}  // namespace

std::string registry_dir() {
    if (const char* dir = std::getenv("APCI_RUNTIME_DIR"); dir != nullptr && *dir != '\0')
        return dir;
    if (const char* xdg = std::getenv("XDG_RUNTIME_DIR"); xdg != nullptr && *xdg != '\0')
        return fmt::format("{}/apci", xdg);
    return fmt::format("/tmp/apci-{}", ::getuid());
}

int open_registry_dir(bool create, std::string& why) {
    why.clear();
    const std::string dir = registry_dir();
    if (create && ::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST) {
        why = fmt::format("registry directory {}: {}", dir, std::strerror(errno));
        return -1;
    }
    // A symbolic link is named as one (lstat), and never followed (O_NOFOLLOW): what is
    // checked is the descriptor that is then used (fstat), so nothing can be swapped between.
    struct stat st {};
    if (::lstat(dir.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
        why = fmt::format(
            "registry directory {} is a symbolic link: it is not followed; remove it, or set "
            "APCI_RUNTIME_DIR to a directory of your own",
            dir);
        return -1;
    }
    // O_PATH first: the owner and mode are checked even where this user may not read the
    // directory (another user's), then the directory itself is opened through that descriptor.
    const Fd path(::open(dir.c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    if (path.fd < 0) {
        if (errno != ENOENT || create)
            why = fmt::format("registry directory {}: {}", dir, std::strerror(errno));
        return -1;
    }
    if (::fstat(path.fd, &st) != 0) {
        why = fmt::format("registry directory {}: {}", dir, std::strerror(errno));
        return -1;
    }
    if (std::string bad = not_private(dir, st); !bad.empty()) {
        why = std::move(bad);
        return -1;
    }
    const int fd = ::openat(path.fd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    struct stat opened {};
    if (fd < 0 || ::fstat(fd, &opened) != 0 || opened.st_dev != st.st_dev ||
        opened.st_ino != st.st_ino) {
        why = fmt::format("registry directory {}: {}", dir,
                          fd < 0 ? std::strerror(errno) : "changed while it was opened");
        if (fd >= 0) ::close(fd);
        return -1;
    }
    return fd;
}

std::string escape_registry_path(std::string_view path) {
    std::string out;
    out.reserve(path.size());
    for (const char c : path) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\\')
            out += "\\\\";
        else if (c == '\n')
            out += "\\n";
        else if (u < 0x20 || u == 0x7F)
            out += fmt::format("\\x{:02x}", u);
        else
            out += c;
    }
    return out;
}

bool unescape_registry_path(std::string_view text, std::string& path) {
    path.clear();
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto u = static_cast<unsigned char>(text[i]);
        if (u < 0x20 || u == 0x7F) return false;
        if (text[i] != '\\') {
            path += text[i];
            continue;
        }
        if (++i == text.size()) return false;
        if (text[i] == '\\') {
            path += '\\';
        } else if (text[i] == 'n') {
            path += '\n';
        } else if (text[i] == 'x' && i + 2 < text.size()) {
            unsigned value = 0;
            const char* first = text.data() + i + 1;
            const auto [end, ec] = std::from_chars(first, first + 2, value, 16);
            if (ec != std::errc() || end != first + 2) return false;
            // Only what escape_registry_path writes: a control character other than '\n'.
            if (value == '\n' || (value >= 0x20 && value != 0x7F)) return false;
            path += static_cast<char>(value);
            i += 2;
        } else {
            return false;
        }
    }
    return true;
}

bool register_daemon(const RegisteredDaemon& self, std::string& why) {
    for (const std::string* p : {&self.socket, &self.shm}) {
        if (!p->empty() && p->front() != '/') {
            why = fmt::format("registry entry: path '{}' is not absolute", *p);
            return false;
        }
    }
    const Fd dir(open_registry_dir(true, why));
    if (dir.fd < 0) return false;
    const std::string name = entry_name(self.pid);
    const std::string tmp = name + ".tmp";
    std::string text;
    if (!self.socket.empty()) text += fmt::format("socket {}\n", escape_registry_path(self.socket));
    if (!self.shm.empty()) text += fmt::format("shm {}\n", escape_registry_path(self.shm));
    constexpr int kFlags = O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC;
    int fd = ::openat(dir.fd, tmp.c_str(), kFlags, 0600);
    if (fd < 0 && errno == EEXIST) {
        // Left behind by an earlier process of this pid (in our own directory): replaced.
        ::unlinkat(dir.fd, tmp.c_str(), 0);
        fd = ::openat(dir.fd, tmp.c_str(), kFlags, 0600);
    }
    const std::string dir_name = registry_dir();
    if (fd < 0) {
        why = fmt::format("cannot create {}/{}: {}", dir_name, tmp, std::strerror(errno));
        return false;
    }
    const bool written = write_all(fd, text);
    const int write_errno = errno;
    if (::close(fd) != 0 || !written) {
        why = fmt::format("cannot write {}/{}: {}", dir_name, tmp,
                          std::strerror(written ? errno : write_errno));
        ::unlinkat(dir.fd, tmp.c_str(), 0);
        return false;
    }
    // Atomic: a reader sees all of the entry or nothing.
    if (::renameat(dir.fd, tmp.c_str(), dir.fd, name.c_str()) != 0) {
        why = fmt::format("rename {}/{}: {}", dir_name, name, std::strerror(errno));
        ::unlinkat(dir.fd, tmp.c_str(), 0);
        return false;
    }
    return true;
}

void unregister_daemon(pid_t pid) {
    std::string why;
    const Fd dir(open_registry_dir(false, why));
    if (dir.fd >= 0) ::unlinkat(dir.fd, entry_name(pid).c_str(), 0);
}

bool registered_daemons(std::vector<RegisteredDaemon>& out, std::string& why) {
    const int fd = open_registry_dir(false, why);
    if (fd < 0) return why.empty();  // missing: no daemon registered
    std::unique_ptr<DIR, int (*)(DIR*)> d(::fdopendir(fd), ::closedir);
    if (!d) {
        why = fmt::format("registry directory {}: {}", registry_dir(), std::strerror(errno));
        ::close(fd);
        return false;
    }
    std::string text;
    while (const dirent* e = ::readdir(d.get())) {
        RegisteredDaemon entry;
        entry.pid = pid_of_entry(e->d_name);
        if (!alive(entry.pid)) continue;  // also an entry of no pid (0)
        if (!read_entry(::dirfd(d.get()), e->d_name, text) || !parse_entry(text, entry)) continue;
        out.push_back(std::move(entry));
    }
    return true;
}

}  // namespace objif
