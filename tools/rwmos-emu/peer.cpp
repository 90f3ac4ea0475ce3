// SPDX-License-Identifier: MIT
#include "peer.h"

#include <sys/socket.h>
#include <sys/types.h>

#include <fstream>
#include <sstream>
#include <string>

namespace rwmos_emu {
namespace {

// The key bit of mailbox hosts: socket clients count up from 1 and never reach it.
constexpr std::uint64_t kMailboxKey = std::uint64_t{1} << 63;

std::string process_name(std::int32_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/comm");
    std::string name;
    if (!std::getline(in, name)) return {};
    return name;
}

// Field 22 of /proc/PID/stat, the process's start time in clock ticks after boot; 0 when the
// process is gone. The command name (field 2) is in parentheses and may hold spaces and ')':
// the fields after it start after the last ')'.
std::uint64_t process_start_time(std::int32_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(in, line)) return 0;
    const std::size_t close = line.rfind(')');
    if (close == std::string::npos) return 0;
    std::istringstream fields(line.substr(close + 1));
    std::string field;
    // Fields 3 .. 21, then 22.
    for (int i = 3; i <= 21; ++i)
        if (!(fields >> field)) return 0;
    std::uint64_t start = 0;
    if (!(fields >> start)) return 0;
    return start;
}

}  // namespace

rwmos::Host socket_host(int fd, std::uint64_t id) {
    rwmos::Host host;
    host.key = id;
    ucred peer{};
    socklen_t size = sizeof peer;
    if (::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &peer, &size) == 0 && peer.pid > 0) {
        host.pid = peer.pid;
        host.name = process_name(peer.pid);
    }
    return host;
}

rwmos::Host mailbox_host(std::uint32_t token) {
    rwmos::Host host;
    host.key = kMailboxKey | token;
    host.by_pid = true;
    if (token > 0 && token <= 0x7FFF'FFFFu) {
        host.pid = static_cast<std::int32_t>(token);
        host.name = process_name(host.pid);
        host.start_time = process_start_time(host.pid);
    }
    return host;
}

bool host_process_alive(const rwmos::Host& host) {
    if (host.pid <= 0) return false;
    const std::uint64_t start = process_start_time(host.pid);
    return start != 0 && start == host.start_time;
}

}  // namespace rwmos_emu
