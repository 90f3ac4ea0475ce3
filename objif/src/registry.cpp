// SPDX-License-Identifier: MIT
#include "objif/registry.h"

#include <dirent.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>

namespace objif {
namespace {

constexpr std::string_view kPrefix = "rwmos-emu.";

std::string entry_path(pid_t pid) {
    return fmt::format("{}/{}{}", registry_dir(), kPrefix, pid);
}

bool alive(pid_t pid) {
    return pid > 0 && (::kill(pid, 0) == 0 || errno == EPERM);
}

}  // namespace

std::string registry_dir() {
    if (const char* dir = std::getenv("APCI_RUNTIME_DIR"); dir != nullptr && *dir != '\0')
        return dir;
    if (const char* xdg = std::getenv("XDG_RUNTIME_DIR"); xdg != nullptr && *xdg != '\0')
        return fmt::format("{}/apci", xdg);
    return fmt::format("/tmp/apci-{}", ::getuid());
}

bool register_daemon(const RegisteredDaemon& self, std::string& why) {
    const std::string dir = registry_dir();
    if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST) {
        why = fmt::format("registry directory {}: {}", dir, std::strerror(errno));
        return false;
    }
    const std::string path = entry_path(self.pid);
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::trunc);
        if (!self.socket.empty()) f << "socket " << self.socket << '\n';
        if (!self.shm.empty()) f << "shm " << self.shm << '\n';
        if (!f) {
            why = fmt::format("cannot write {}", tmp);
            return false;
        }
    }
    if (::rename(tmp.c_str(), path.c_str()) != 0) {  // atomic: a reader sees all or nothing
        why = fmt::format("rename {}: {}", path, std::strerror(errno));
        ::unlink(tmp.c_str());
        return false;
    }
    return true;
}

void unregister_daemon(pid_t pid) {
    ::unlink(entry_path(pid).c_str());
}

bool registered_daemons(std::vector<RegisteredDaemon>& out, std::string& why) {
    const std::string dir = registry_dir();
    std::unique_ptr<DIR, int (*)(DIR*)> d(::opendir(dir.c_str()), ::closedir);
    if (!d) {
        if (errno == ENOENT) return true;
        why = fmt::format("registry directory {}: {}", dir, std::strerror(errno));
        return false;
    }
    while (const dirent* e = ::readdir(d.get())) {
        const std::string_view name = e->d_name;
        if (!name.starts_with(kPrefix)) continue;
        const std::string_view digits = name.substr(kPrefix.size());
        RegisteredDaemon entry;
        const auto [end, ec] =
            std::from_chars(digits.data(), digits.data() + digits.size(), entry.pid);
        if (ec != std::errc() || end != digits.data() + digits.size() || !alive(entry.pid))
            continue;
        std::ifstream f(fmt::format("{}/{}", dir, name));
        std::string key, value;
        while (f >> key && std::getline(f >> std::ws, value)) {
            if (key == "socket") entry.socket = value;
            if (key == "shm") entry.shm = value;
        }
        out.push_back(std::move(entry));
    }
    return true;
}

}  // namespace objif
