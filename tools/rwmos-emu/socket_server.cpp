// SPDX-License-Identifier: MIT
#include "socket_server.h"

#include <sys/epoll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "log.h"

namespace rwmos_emu {
namespace {

constexpr std::size_t kReadChunk = std::size_t{64} * 1024;
constexpr const char* kStagingSuffix = ".new";

bool make_address(const std::string& path, sockaddr_un& addr, std::string& why) {
    addr = {};
    addr.sun_family = AF_UNIX;
    if (path.empty() || path.size() >= sizeof addr.sun_path) {
        why = fmt::format("socket path '{}' is {} (at most {} bytes)", path,
                          path.empty() ? "empty" : "too long", sizeof addr.sun_path - 1);
        return false;
    }
    std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
    return true;
}

// What is at `path` now: nothing, a stale socket (removed), or a refusal.
bool clear_path(const std::string& path, const sockaddr_un& addr, std::string& why) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) {
        if (errno == ENOENT) return true;
        why = fmt::format("{}: {}", path, std::strerror(errno));
        return false;
    }
    if (!S_ISSOCK(st.st_mode)) {
        why = fmt::format("{} exists and is not a socket; refusing to replace it", path);
        return false;
    }
    const int probe = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (probe < 0) {
        why = fmt::format("socket: {}", std::strerror(errno));
        return false;
    }
    const int rc = ::connect(probe, reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
    const int err = errno;
    ::close(probe);
    if (rc == 0) {
        why = fmt::format(
            "{} is the live socket of another daemon; stop it first or choose "
            "another --socket",
            path);
        return false;
    }
    if (err != ECONNREFUSED) {
        why = fmt::format("{}: cannot tell whether another daemon serves it: {}", path,
                          std::strerror(err));
        return false;
    }
    if (::unlink(path.c_str()) != 0 && errno != ENOENT) {
        why = fmt::format("removing stale socket {}: {}", path, std::strerror(errno));
        return false;
    }
    log(Level::kInfo, "removed stale socket {}", path);
    return true;
}

}  // namespace

SocketServer::~SocketServer() {
    close_all();
}

// The socket is made ready under a staging name (`PATH.new`: bound, mode
// 0660, its group, listening) and only then published at PATH by link(2),
// which never replaces an existing file. A client that sees PATH can connect
// at once: there is no window in which the file exists but nobody listens
// (a client polling for the file would get ECONNREFUSED there), nor one with
// the wrong group; and a daemon that started meanwhile on the same path is
// never displaced.
bool SocketServer::open(const std::string& path, gid_t group, std::string& why) {
    sockaddr_un addr{};
    sockaddr_un staging_addr{};
    const std::string staging = path + kStagingSuffix;
    if (!make_address(path, addr, why)) return false;
    if (!make_address(staging, staging_addr, why)) {
        why = fmt::format("socket path '{}' is too long (at most {} bytes: the socket is made "
                          "ready as '{}' first)",
                          path, sizeof addr.sun_path - 1 - std::strlen(kStagingSuffix), staging);
        return false;
    }
    if (!clear_path(path, addr, why) || !clear_path(staging, staging_addr, why)) return false;
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        why = fmt::format("socket: {}", std::strerror(errno));
        return false;
    }
    const auto fail = [&](const std::string& what, int err) {
        why = fmt::format("{}: {}", what, std::strerror(err));
        ::close(fd);
        ::unlink(staging.c_str());
        return false;
    };
    // Created 0660 from the start (no window with wider permissions).
    const mode_t old_mask = ::umask(0117);
    const int rc = ::bind(fd, reinterpret_cast<const sockaddr*>(&staging_addr), sizeof staging_addr);
    const int err = errno;
    ::umask(old_mask);
    if (rc != 0) {
        ::close(fd);
        why = fmt::format("bind {}: {}", staging, std::strerror(err));
        return false;
    }
    if (::chmod(staging.c_str(), 0660) != 0) return fail(staging, errno);
    if (group != static_cast<gid_t>(-1) && ::lchown(staging.c_str(), static_cast<uid_t>(-1), group) != 0)
        return fail(fmt::format("{}: cannot give it group {}", staging, group), errno);
    if (::listen(fd, 64) != 0) return fail(fmt::format("listen {}", staging), errno);
    epoll_event ev{};
    ev.events = EPOLLIN;
    ev.data.fd = fd;
    if (::epoll_ctl(epoll_fd_, EPOLL_CTL_ADD, fd, &ev) != 0) return fail("epoll_ctl", errno);
    if (::link(staging.c_str(), path.c_str()) != 0) {
        const int link_err = errno;
        ::epoll_ctl(epoll_fd_, EPOLL_CTL_DEL, fd, nullptr);
        if (link_err == EEXIST)
            return fail(fmt::format("{} appeared while this daemon was starting (another daemon?); "
                                    "not replacing it",
                                    path),
                        link_err);
        return fail(fmt::format("publishing {} as {}", staging, path), link_err);
    }
    ::unlink(staging.c_str());
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) {
        const int stat_err = errno;
        ::epoll_ctl(epoll_fd_, EPOLL_CTL_DEL, fd, nullptr);
        ::unlink(path.c_str());
        return fail(path, stat_err);
    }
    listen_fd_ = fd;
    path_ = path;
    dev_ = st.st_dev;
    ino_ = st.st_ino;
    read_buffer_.resize(kReadChunk);
    return true;
}

void SocketServer::on_listen_ready() {
    for (;;) {
        const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
        if (fd < 0) {
            if (errno == EAGAIN || errno == EINTR) return;
            if (errno == EMFILE || errno == ENFILE) {
                log(Level::kWarn, "accept: {} (clients wait in the backlog)", std::strerror(errno));
                return;
            }
            if (errno == ECONNABORTED) continue;
            log(Level::kError, "accept: {}", std::strerror(errno));
            return;
        }
        if (clients_.size() >= max_clients_) {
            log(Level::kWarn, "refused a client: {} clients connected (--max-clients {})",
                clients_.size(), max_clients_);
            ::close(fd);
            continue;
        }
        epoll_event ev{};
        ev.events = EPOLLIN | EPOLLRDHUP;
        ev.data.fd = fd;
        if (::epoll_ctl(epoll_fd_, EPOLL_CTL_ADD, fd, &ev) != 0) {
            log(Level::kError, "epoll_ctl: {}", std::strerror(errno));
            ::close(fd);
            continue;
        }
        Client& c = clients_[fd];
        c.id = next_id_++;
        c.armed = ev.events;
        log(Level::kDebug, "client {} connected ({} connected)", c.id, clients_.size());
    }
}

void SocketServer::on_client_ready(int fd, std::uint32_t events) {
    auto it = clients_.find(fd);
    if (it == clients_.end()) return;
    Client& c = it->second;
    if ((events & EPOLLOUT) != 0 && !flush(fd, c)) return;
    if (!c.reading && (events & (EPOLLHUP | EPOLLERR)) != 0)
        return drop(fd, "hung up with replies unread");
    if ((events & (EPOLLIN | EPOLLRDHUP | EPOLLHUP | EPOLLERR)) == 0 || !c.reading) {
        rearm(fd, c);
        return;
    }
    const ssize_t n = ::recv(fd, read_buffer_.data(), read_buffer_.size(), 0);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
        const std::size_t partial = c.stream.pending();
        if (partial != 0)
            return drop(
                fd, fmt::format("disconnected mid-frame ({} bytes of a frame unread)", partial));
        if (n < 0) return drop(fd, fmt::format("recv: {}", std::strerror(errno)));
        log(Level::kDebug, "client {} disconnected", c.id);
        return drop(fd, {});
    }
    if (n < 0) return;
    const auto result =
        host_.serve_stream(c.stream, {read_buffer_.data(), static_cast<std::size_t>(n)}, c.out);
    if (result.rejected != 0)
        log(Level::kDebug, "client {}: {} malformed frame(s) answered with Error", c.id,
            result.rejected);
    if (!flush(fd, c)) return;
    if (!result.keep) {
        log(Level::kWarn, "client {} sent garbage ({}): connection dropped", c.id,
            objif::frame_error_name(result.garbage));
        return drop(fd, {});
    }
    rearm(fd, c);
}

bool SocketServer::flush(int fd, Client& c) {
    while (c.out_pos < c.out.size()) {
        const ssize_t n = ::send(fd, c.out.data() + c.out_pos, c.out.size() - c.out_pos,
                                 MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n > 0) {
            c.out_pos += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && errno == EAGAIN) break;
        drop(fd, fmt::format("send: {}", std::strerror(errno)));
        return false;
    }
    if (c.out_pos == c.out.size()) {
        c.out.clear();
        c.out_pos = 0;
    }
    return true;
}

void SocketServer::rearm(int fd, Client& c) const {
    const std::size_t queued = c.out.size() - c.out_pos;
    // Backpressure: a client that does not read its replies is not read from.
    c.reading = queued < kMaxQueuedReplies;
    const std::uint32_t events =
        (c.reading ? EPOLLIN | EPOLLRDHUP : 0u) | (queued != 0 ? EPOLLOUT : 0u);
    if (events == c.armed) return;
    epoll_event ev{};
    ev.events = events;
    ev.data.fd = fd;
    if (::epoll_ctl(epoll_fd_, EPOLL_CTL_MOD, fd, &ev) == 0) c.armed = events;
}

void SocketServer::drop(int fd, std::string_view why) {
    auto it = clients_.find(fd);
    if (it == clients_.end()) return;
    if (!why.empty()) log(Level::kInfo, "client {} {}: connection closed", it->second.id, why);
    ::epoll_ctl(epoll_fd_, EPOLL_CTL_DEL, fd, nullptr);
    ::close(fd);
    clients_.erase(it);
}

void SocketServer::close_all() {
    while (!clients_.empty()) drop(clients_.begin()->first, {});
    if (listen_fd_ >= 0) {
        ::epoll_ctl(epoll_fd_, EPOLL_CTL_DEL, listen_fd_, nullptr);
        ::close(listen_fd_);
        listen_fd_ = -1;
        // Remove the socket only if it is still ours (not replaced meanwhile).
        struct stat st {};
        if (::lstat(path_.c_str(), &st) == 0 && st.st_dev == dev_ && st.st_ino == ino_)
            ::unlink(path_.c_str());
    }
}

}  // namespace rwmos_emu
