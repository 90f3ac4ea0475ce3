// SPDX-License-Identifier: MIT
#include "socket_server.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/epoll.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/timerfd.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstring>
#include <new>
#include <thread>

#include "log.h"
#include "peer.h"
#include "objif/frame.h"
#include "objif/registry.h"

namespace rwmos_emu {
namespace {

constexpr std::size_t kReadChunk = std::size_t{64} * 1024;
// How long a starting daemon waits for another one starting in the same
// directory (a neighbour holding the turn longer makes it give up).
constexpr std::chrono::seconds kStartTurnWait{2};
constexpr std::chrono::milliseconds kStartTurnPoll{5};
// Reads of a hung-up client served before it is released (its requests
// still reach the board, as they would have on the next turn of the loop).
constexpr int kReapReads = 8;

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

// The directory part of `path` ("." for a bare name).
std::string directory_of(const std::string& path) {
    const auto slash = path.rfind('/');
    if (slash == std::string::npos) return ".";
    if (slash == 0) return "/";
    return path.substr(0, slash);
}

// The turn of a daemon starting in a socket directory: an exclusive flock taken by every
// daemon of this user while it clears, binds and starts listening on a socket there, so that a
// daemon that finds a socket nobody listens on yet knows it is stale, not another daemon's
// between bind and listen. The lock is a file in the user's private registry directory
// (objif/registry.h) named after the socket directory's device and inode, not the socket
// directory itself: any user may hold flock on a shared directory (/tmp, /dev/shm), and did
// stop every daemon from starting there. Released when it goes out of scope.
class StartTurn {
  public:
    StartTurn() = default;
    ~StartTurn() {
        if (fd_ >= 0) ::close(fd_);
    }
    StartTurn(const StartTurn&) = delete;
    StartTurn& operator=(const StartTurn&) = delete;

    bool take(const std::string& dir, std::string& why) {
        struct stat st {};
        const int err = ::stat(dir.c_str(), &st) != 0 ? errno : S_ISDIR(st.st_mode) ? 0 : ENOTDIR;
        if (err != 0) {
            why = fmt::format("socket directory {}: {}", dir, std::strerror(err));
            return false;
        }
        std::string registry_why;
        const int registry = objif::open_registry_dir(true, registry_why);
        if (registry < 0) {
            log(Level::kWarn,
                "cannot take turns with other daemons starting in {} ({}); starting unlocked", dir,
                registry_why);
            return true;
        }
        const std::string name = start_lock_name(st.st_dev, st.st_ino);
        fd_ = ::openat(registry, name.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC,
                       0600);
        const int open_errno = errno;
        ::close(registry);
        struct stat lock {};
        if (fd_ < 0 || ::fstat(fd_, &lock) != 0 || !S_ISREG(lock.st_mode) ||
            lock.st_uid != ::geteuid()) {
            log(Level::kWarn,
                "cannot open the start lock {} in the registry directory ({}); "
                "starting unlocked",
                name, fd_ < 0 ? std::strerror(open_errno) : "not a file of ours");
            return true;
        }
        const auto until = SteadyClock::now() + kStartTurnWait;
        for (;;) {
            if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return true;
            if (errno != EWOULDBLOCK && errno != EINTR) {
                // A file system without flock (ENOLCK, EOPNOTSUPP): start
                // without taking turns rather than not at all.
                log(Level::kWarn, "cannot lock {} ({}); starting unlocked", name,
                    std::strerror(errno));
                return true;
            }
            if (SteadyClock::now() >= until) {
                why = fmt::format(
                    "another rwmos-emu of this user starting in socket directory {} held its "
                    "turn for {} s (the lock {} in {}); try again or choose another --socket "
                    "directory",
                    dir, kStartTurnWait.count(), name, objif::registry_dir());
                return false;
            }
            std::this_thread::sleep_for(kStartTurnPoll);
        }
    }

  private:
    int fd_ = -1;
};

// Binds `fd` at `addr` with mode 0660 from the start (umask) and, when
// `group` is not the daemon's own, with that group from the start (the
// effective gid while binding; lchown after listen covers what this cannot).
int bind_socket(int fd, const sockaddr_un& addr, gid_t group) {
    const gid_t own = ::getegid();
    const bool switch_gid =
        group != static_cast<gid_t>(-1) && group != own && ::setegid(group) == 0;
    const mode_t old_mask = ::umask(0117);
    const int rc = ::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
    const int err = errno;
    ::umask(old_mask);
    if (switch_gid && ::setegid(own) != 0) {
        // Cannot happen (the saved set-group-ID is ours); refuse rather than go on wrong.
        return -1;
    }
    errno = err;
    return rc;
}

}  // namespace

std::string start_lock_name(dev_t dev, ino_t ino) {
    return fmt::format("socket-dir.{:x}.{:x}.lock", static_cast<std::uint64_t>(dev),
                       static_cast<std::uint64_t>(ino));
}

bool send_notice(int fd, objif::Status status, std::string_view text) {
    try {
        std::vector<std::uint8_t> payload;
        objif::encode(objif::Notice{status, std::string(text)}, payload);
        std::vector<std::uint8_t> frame;
        objif::encode_frame(
            static_cast<std::uint16_t>(static_cast<std::uint16_t>(objif::Opcode::kNotice) |
                                       objif::kReplyFlag),
            0, payload, frame);
        const ssize_t n = ::send(fd, frame.data(), frame.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
        return n == static_cast<ssize_t>(frame.size());
    } catch (...) {
        return false;
    }
}

SocketServer::~SocketServer() {
    close_all();
    if (idle_timer_fd_ >= 0) ::close(idle_timer_fd_);
    if (spare_fd_ >= 0) ::close(spare_fd_);
}

// Bound at PATH itself (so ss, lsof and /proc/net/unix name the socket by
// its path), in its start turn (StartTurn): clear_path() (lstat, never through a
// symlink; a stale socket removed, anything else refused), bind with mode
// 0660 and the group from the start, listen at once; bind never replaces a
// file, so a socket or file that appeared meanwhile is never displaced.
bool SocketServer::open(const std::string& path, gid_t group, std::string& why) {
    sockaddr_un addr{};
    if (!make_address(path, addr, why)) return false;
    StartTurn turn;
    if (!turn.take(directory_of(path), why)) return false;
    if (!clear_path(path, addr, why)) return false;
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        why = fmt::format("socket: {}", std::strerror(errno));
        return false;
    }
    if (bind_socket(fd, addr, group) != 0) {
        const int err = errno;
        ::close(fd);
        why =
            err == EADDRINUSE
                ? fmt::format("{} appeared while this daemon was starting; not replacing it", path)
                : fmt::format("bind {}: {}", path, std::strerror(err));
        return false;
    }
    // From here on PATH is ours: a failure removes it.
    const auto fail = [&](const std::string& what, int err) {
        why = fmt::format("{}: {}", what, std::strerror(err));
        ::epoll_ctl(epoll_fd_, EPOLL_CTL_DEL, fd, nullptr);
        ::close(fd);
        ::unlink(path.c_str());
        return false;
    };
    if (::listen(fd, 64) != 0) return fail(fmt::format("listen {}", path), errno);
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return fail(path, errno);
    if ((st.st_mode & 07777) != 0660 &&
        ::fchmodat(AT_FDCWD, path.c_str(), 0660, AT_SYMLINK_NOFOLLOW) != 0)
        return fail(fmt::format("{}: setting mode 0660", path), errno);
    if (group != static_cast<gid_t>(-1) && st.st_gid != group &&
        ::lchown(path.c_str(), static_cast<uid_t>(-1), group) != 0)
        return fail(fmt::format("{}: cannot give it group {}", path, group), errno);
    std::string failure;
    if (!listen_on(fd, failure)) {
        ::close(fd);
        ::unlink(path.c_str());
        why = failure;
        return false;
    }
    path_ = path;
    dev_ = st.st_dev;
    ino_ = st.st_ino;
    owns_path_ = true;
    return true;
}

bool SocketServer::listen_on(int fd, std::string& why) {
    epoll_event ev{};
    ev.events = EPOLLIN;
    ev.data.fd = fd;
    if (::epoll_ctl(epoll_fd_, EPOLL_CTL_ADD, fd, &ev) != 0) {
        why = fmt::format("epoll_ctl: {}", std::strerror(errno));
        return false;
    }
    if (limits_.idle_timeout.count() > 0) {
        idle_timer_fd_ = ::timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC | TFD_NONBLOCK);
        ev.data.fd = idle_timer_fd_;
        if (idle_timer_fd_ < 0 || ::epoll_ctl(epoll_fd_, EPOLL_CTL_ADD, idle_timer_fd_, &ev) != 0) {
            why = fmt::format("--idle-timeout timer: {}", std::strerror(errno));
            ::epoll_ctl(epoll_fd_, EPOLL_CTL_DEL, fd, nullptr);
            return false;
        }
    }
    // A descriptor kept in reserve: when accept fails for want of descriptors, it is given up
    // for a moment to take the newcomer, tell it why and close it (on_listen_ready()).
    if (spare_fd_ < 0) spare_fd_ = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    listen_fd_ = fd;
    read_buffer_.resize(kReadChunk);
    return true;
}

bool SocketServer::adopt(int fd, const std::string& expected_path, std::string& why) {
    int type = 0;
    int listening = 0;
    socklen_t size = sizeof type;
    sockaddr_un addr{};
    socklen_t addr_size = sizeof addr;
    if (::getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &size) != 0 ||
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &addr_size) != 0) {
        why = fmt::format("the socket passed by systemd (fd {}): {}", fd, std::strerror(errno));
        return false;
    }
    size = sizeof listening;
    if (addr.sun_family != AF_UNIX || type != SOCK_STREAM ||
        ::getsockopt(fd, SOL_SOCKET, SO_ACCEPTCONN, &listening, &size) != 0 || listening == 0) {
        why = fmt::format("the socket passed by systemd (fd {}) is not a listening Unix stream "
                          "socket (ListenStream=PATH in the .socket unit)", fd);
        return false;
    }
    const auto path_size = addr_size - offsetof(sockaddr_un, sun_path);
    const std::string path = addr_size > offsetof(sockaddr_un, sun_path) && addr.sun_path[0] != '\0'
                                 ? std::string(addr.sun_path, ::strnlen(addr.sun_path, path_size))
                                 : std::string();
    if (path.empty()) {
        why = fmt::format("the socket passed by systemd (fd {}) has no path", fd);
        return false;
    }
    if (!expected_path.empty() && path != expected_path) {
        why = fmt::format("the socket passed by systemd is {}, not --socket {}", path,
                          expected_path);
        return false;
    }
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0 ||
        ::fcntl(fd, F_SETFD, FD_CLOEXEC) != 0 || !listen_on(fd, why)) {
        if (why.empty()) why = fmt::format("fd {}: {}", fd, std::strerror(errno));
        return false;
    }
    path_ = path;
    owns_path_ = false;
    return true;
}

void SocketServer::on_listen_ready() {
    if (listen_paused_) return;
    for (;;) {
        // The spare first: a descriptor that came free since the spare was lost (another
        // thread held the last one when it was opened again) goes to the reserve, not to a
        // newcomer, so the next newcomer beyond the limit is still told why.
        if (spare_fd_ < 0) spare_fd_ = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
        const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
        if (fd < 0) {
            if (errno == EAGAIN || errno == EINTR) return;
            if (errno == ECONNABORTED) continue;
            if (errno == EMFILE || errno == ENFILE) {
                if (refuse_for_descriptors(errno)) continue;
                return;
            }
            // Anything else (ENOMEM, ENOBUFS): the listener stays ready, so it is left alone
            // for a moment rather than asked again at once.
            log(Level::kError, "accept: {}; not accepting for {} ms", std::strerror(errno),
                kListenPause.count());
            pause_listening();
            return;
        }
        accept_one(fd);
    }
}

// Out of descriptors, the listening socket stays ready with the newcomer in its backlog: asked
// again and again, the loop spun (and logged a line each time), and the newcomer waited for a
// greeting that never came. The spare descriptor makes room to take it off the backlog, tell
// it why and close it.
bool SocketServer::refuse_for_descriptors(int err) {
    if (spare_fd_ < 0) {
        log(Level::kError,
            "accept: {}; no spare descriptor to tell a newcomer why; not accepting "
            "for {} ms",
            std::strerror(err), kListenPause.count());
        pause_listening();
        return false;
    }
    ::close(spare_fd_);
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    const int accept_errno = errno;
    if (fd >= 0) {
        rlimit limit{};
        ::getrlimit(RLIMIT_NOFILE, &limit);
        send_notice(fd, objif::Status::kTransportError,
                    err == EMFILE
                        ? fmt::format("out of file descriptors ({} clients connected, limit {} "
                                      "open files); try again later",
                                      clients_.size(), limit.rlim_cur)
                        : std::string("the system is out of file descriptors; try again later"));
        ::close(fd);
        ++refused_for_descriptors_;
    }
    spare_fd_ = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    // One line at the first refusal, then at most one a second with the count.
    const auto now = SteadyClock::now();
    if (refused_for_descriptors_ != 0 && now - refusal_logged_ >= std::chrono::seconds(1)) {
        log(Level::kWarn,
            "refused {} client(s): {} (--max-clients {}; raise the open-files limit, "
            "ulimit -n)",
            refused_for_descriptors_, std::strerror(err), limits_.max_clients);
        refused_for_descriptors_ = 0;
        refusal_logged_ = now;
    }
    if (spare_fd_ < 0) {
        pause_listening();
        return false;
    }
    // Taken: there may be more. Nobody (EAGAIN), or still none (ENFILE: the system's limit
    // and no descriptor came free): done for now.
    if (fd < 0 && accept_errno != EAGAIN && accept_errno != EINTR) pause_listening();
    return fd >= 0;
}

void SocketServer::pause_listening() {
    if (listen_paused_ || listen_fd_ < 0) return;
    epoll_event ev{};
    ev.events = 0;
    ev.data.fd = listen_fd_;
    if (::epoll_ctl(epoll_fd_, EPOLL_CTL_MOD, listen_fd_, &ev) != 0) return;
    listen_paused_ = true;
    listen_resume_ = SteadyClock::now() + kListenPause;
}

int SocketServer::wait_ms() const {
    if (!left_over_.empty()) return 0;
    if (!listen_paused_) return -1;
    const auto left =
        std::chrono::ceil<std::chrono::milliseconds>(listen_resume_ - SteadyClock::now());
    return static_cast<int>(std::max<std::chrono::milliseconds::rep>(0, left.count()));
}

void SocketServer::after_events() {
    if (listen_paused_ && SteadyClock::now() >= listen_resume_ && listen_fd_ >= 0) {
        epoll_event ev{};
        ev.events = EPOLLIN;
        ev.data.fd = listen_fd_;
        if (::epoll_ctl(epoll_fd_, EPOLL_CTL_MOD, listen_fd_, &ev) == 0) listen_paused_ = false;
    }
    // Every client with requests left over gets one more turn, in the order they were left,
    // unless it was served this round already.
    const std::vector<int> waiting = std::move(left_over_);
    left_over_.clear();
    for (const int fd : waiting) {
        auto it = clients_.find(fd);
        if (it == clients_.end()) continue;
        Client& c = it->second;
        if (c.round == round_) {
            left_over_.push_back(fd);
            continue;
        }
        c.awaits_turn = false;
        if (serve_turn(fd, c)) rearm(fd, c);
    }
    ++round_;
}

void SocketServer::accept_one(int fd) {
    // Clients that hung up but whose EOF the loop has not read yet are not
    // counted: released first.
    if (clients_.size() >= limits_.max_clients) reap_hung_up();
    if (clients_.size() >= limits_.max_clients) {
        log(Level::kWarn, "refused a client: {} clients connected (--max-clients {})",
            clients_.size(), limits_.max_clients);
        send_notice(fd, objif::Status::kTransportError,
                    fmt::format("too many clients ({})", limits_.max_clients));
        ::close(fd);
        return;
    }
    // A client that hung up already misses its greeting, but what it sent
    // before is still served (and a half frame still logged), as for any client.
    send_notice(fd, objif::Status::kOk, objif::kDaemonGreeting);
    epoll_event ev{};
    ev.events = EPOLLIN | EPOLLRDHUP;
    ev.data.fd = fd;
    if (::epoll_ctl(epoll_fd_, EPOLL_CTL_ADD, fd, &ev) != 0) {
        log(Level::kError, "epoll_ctl: {}", std::strerror(errno));
        ::close(fd);
        return;
    }
    Client& c = clients_[fd];
    c.id = next_id_++;
    c.stream.set_host(socket_host(fd, c.id));
    c.armed = ev.events;
    c.last_active = SteadyClock::now();
    if (limits_.idle_timeout.count() > 0 && !idle_timer_armed_)
        arm_idle_timer(c.last_active + limits_.idle_timeout);
    log(Level::kDebug, "client {} connected ({} connected)", c.id, clients_.size());
}

std::size_t SocketServer::reap_hung_up() {
    std::vector<pollfd> polled;
    polled.reserve(clients_.size());
    for (const auto& [fd, c] : clients_) polled.push_back(pollfd{fd, POLLIN | POLLRDHUP, 0});
    if (::poll(polled.data(), polled.size(), 0) <= 0) return 0;
    std::size_t released = 0;
    for (const pollfd& p : polled) {
        // POLLHUP: the peer closed both directions (a client that only shut
        // down its sending side still waits for replies: kept).
        if ((p.revents & (POLLHUP | POLLERR)) == 0) continue;
        constexpr std::uint32_t kHungUp = EPOLLIN | EPOLLRDHUP | EPOLLHUP;
        for (int i = 0; i < kReapReads && owns(p.fd); ++i) on_client_ready(p.fd, kHungUp);
        if (owns(p.fd)) drop(p.fd, "hung up");
        ++released;
    }
    return released;
}

void SocketServer::arm_idle_timer(SteadyClock::time_point when) {
    const auto since_epoch =
        std::chrono::duration_cast<std::chrono::nanoseconds>(when.time_since_epoch()).count();
    itimerspec at{};
    at.it_value.tv_sec = static_cast<time_t>(since_epoch / 1'000'000'000);
    at.it_value.tv_nsec = static_cast<long>(since_epoch % 1'000'000'000);
    if (at.it_value.tv_sec == 0 && at.it_value.tv_nsec == 0) at.it_value.tv_nsec = 1;
    idle_timer_armed_ = ::timerfd_settime(idle_timer_fd_, TFD_TIMER_ABSTIME, &at, nullptr) == 0;
    if (!idle_timer_armed_) log(Level::kError, "--idle-timeout timer: {}", std::strerror(errno));
}

void SocketServer::on_idle_timer() {
    std::uint64_t expirations = 0;
    if (::read(idle_timer_fd_, &expirations, sizeof expirations) < 0 && errno == EAGAIN) return;
    idle_timer_armed_ = false;
    const auto now = SteadyClock::now();
    const auto limit = limits_.idle_timeout;
    std::vector<int> idle;
    auto next = SteadyClock::time_point::max();
    for (const auto& [fd, c] : clients_) {
        if (now - c.last_active >= limit)
            idle.push_back(fd);
        else
            next = std::min(next, c.last_active + limit);
    }
    const std::string reason =
        fmt::format("idle for {} s (--idle-timeout {})", limit.count(), limit.count());
    for (const int fd : idle) {
        const Client& c = clients_.at(fd);
        if (c.out_pos == c.out.size()) send_notice(fd, objif::Status::kTransportError, reason);
        drop(fd, reason);
    }
    if (next != SteadyClock::time_point::max()) arm_idle_timer(next);
}

void SocketServer::on_client_ready(int fd, std::uint32_t events) {
    auto it = clients_.find(fd);
    if (it == clients_.end()) return;
    Client& c = it->second;
    if ((events & EPOLLOUT) != 0 && !flush(fd, c)) return;
    if (!c.reading && (events & (EPOLLHUP | EPOLLERR)) != 0)
        return drop(fd, "hung up with replies unread");
    // A client with requests left over is not read from: its turn comes in after_events(),
    // once it has read enough of its replies.
    if (c.backlog) {
        if (!c.awaits_turn && c.out.size() - c.out_pos < kMaxQueuedReplies) {
            c.awaits_turn = true;
            left_over_.push_back(fd);
        }
        rearm(fd, c);
        return;
    }
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
        // ECONNRESET: the client closed with bytes unread (its greeting, a
        // late reply): a disconnect like any other.
        if (n < 0 && errno != ECONNRESET)
            return drop(fd, fmt::format("recv: {}", std::strerror(errno)));
        log(Level::kDebug, "client {} disconnected", c.id);
        return drop(fd, {});
    }
    if (n < 0) return;
    c.last_active = SteadyClock::now();
    c.stream.append({read_buffer_.data(), static_cast<std::size_t>(n)});
    if (serve_turn(fd, c)) rearm(fd, c);
}

bool SocketServer::serve_turn(int fd, Client& c) {
    c.round = round_;
    const std::size_t queued = c.out.size() - c.out_pos;
    rwmos::FrameStream::Result result;
    if (queued < kMaxQueuedReplies) {
        try {
            result = host_.serve_turn(c.stream, c.out,
                                      rwmos::FrameStream::Turn{SteadyClock::now() + kTurnTime,
                                                               kMaxQueuedReplies - queued});
        } catch (const std::bad_alloc&) {
            // Not even the NoMemory reply could be made: this client goes, the others stay.
            drop(fd, "could not be served: the daemon is out of memory");
            return false;
        }
    } else {
        result.more = true;  // its replies wait to be read first
    }
    if (result.rejected != 0)
        log(Level::kDebug, "client {}: {} malformed frame(s) answered with Error", c.id,
            result.rejected);
    if (!flush(fd, c)) return false;
    if (!result.keep) {
        log(Level::kWarn, "client {} sent garbage ({}): connection dropped", c.id,
            objif::frame_error_name(result.garbage));
        drop(fd, {});
        return false;
    }
    // Requests left over wait for the next round, unless the client's unread replies hold it
    // back: then it is served again once it has read them (EPOLLOUT, on_client_ready).
    c.backlog = result.more;
    if (c.backlog && !c.awaits_turn && c.out.size() - c.out_pos < kMaxQueuedReplies) {
        c.awaits_turn = true;
        left_over_.push_back(fd);
    }
    return true;
}

bool SocketServer::flush(int fd, Client& c) {
    while (c.out_pos < c.out.size()) {
        const ssize_t n = ::send(fd, c.out.data() + c.out_pos, c.out.size() - c.out_pos,
                                 MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n > 0) {
            c.out_pos += static_cast<std::size_t>(n);
            c.last_active = SteadyClock::now();
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
    // Backpressure: a client that does not read its replies is not read from,
    // nor one whose requests wait for their next turn.
    c.reading = queued < kMaxQueuedReplies && !c.backlog;
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
    // A client that is gone, however it went (closed, crashed, killed), leaves no claim behind.
    if (host_.drop_claim(it->second.id))
        log(Level::kInfo, "client {} (pid {}) closed while it held the board's motion: released",
            it->second.id, it->second.stream.host().pid);
    if (it->second.awaits_turn) std::erase(left_over_, fd);
    ::epoll_ctl(epoll_fd_, EPOLL_CTL_DEL, fd, nullptr);
    ::close(fd);
    clients_.erase(it);
}

void SocketServer::close_all(std::string_view reason) {
    while (!clients_.empty()) {
        const auto& [fd, c] = *clients_.begin();
        if (!reason.empty() && c.out_pos == c.out.size())
            send_notice(fd, objif::Status::kTransportError, reason);
        drop(fd, {});
    }
    if (listen_fd_ >= 0) {
        ::epoll_ctl(epoll_fd_, EPOLL_CTL_DEL, listen_fd_, nullptr);
        ::close(listen_fd_);
        listen_fd_ = -1;
        // Remove the socket only if it is still ours (not replaced meanwhile); one systemd
        // passed stays, for the next activation.
        struct stat st {};
        if (owns_path_ && ::lstat(path_.c_str(), &st) == 0 && st.st_dev == dev_ &&
            st.st_ino == ino_)
            ::unlink(path_.c_str());
    }
}

}  // namespace rwmos_emu
