// SPDX-License-Identifier: MIT
// The daemon's Unix socket: many clients at once, each a byte stream of
// request frames answered in order. Driven by the daemon's epoll loop on one
// thread; requests reach the board through BoardHost (serialised).
// What a client can make the daemon hold is bounded: its incomplete frame
// (at most one frame, kMaxPayload + 20 bytes, plus one read), and replies it
// does not read (above kMaxQueuedReplies the daemon stops reading from it
// until it catches up). A client that sends garbage, or disconnects
// mid-frame, loses its connection and nothing else.
// Connections: every accepted client is greeted with a Notice frame
// (objif/frame.h, docs/wire-frame.md "Notices"); --max-clients counts live
// clients only (clients that hung up are released before a newcomer is
// refused), a refused client is told why, and a client idle for
// --idle-timeout seconds is told and closed.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "board_host.h"
#include "objif/status.h"
#include "rwmos/frame_stream.h"

namespace rwmos_emu {

using SteadyClock = std::chrono::steady_clock;

struct ClientLimits {
    std::size_t max_clients = 64;            // live clients at once
    std::chrono::seconds idle_timeout{300};  // 0: never
};

class SocketServer {
  public:
    SocketServer(BoardHost& host, int epoll_fd, ClientLimits limits)
        : host_(host), epoll_fd_(epoll_fd), limits_(limits) {}
    ~SocketServer();
    SocketServer(const SocketServer&) = delete;
    SocketServer& operator=(const SocketServer&) = delete;

    // Listens on `path` (mode 0660, owned by `group` unless it is -1), bound
    // at that very name. A stale socket (nobody listening) is removed first;
    // a live one, or a path that is not a socket, is refused. Daemons of
    // this user starting in the same directory take turns (start_lock_name),
    // so one never removes the socket of another that is about to listen.
    // False with `why`.
    bool open(const std::string& path, gid_t group, std::string& why);

    int listen_fd() const noexcept { return listen_fd_; }
    // The idle-timeout timer (-1 without --idle-timeout); readable when a
    // client may have been idle too long: call on_idle_timer().
    int idle_timer_fd() const noexcept { return idle_timer_fd_; }
    bool owns(int fd) const { return clients_.count(fd) != 0; }
    std::size_t client_count() const noexcept { return clients_.size(); }

    void on_listen_ready();
    void on_client_ready(int fd, std::uint32_t events);
    void on_idle_timer();

    // Closes every client (telling each `reason` when it is not empty and
    // nothing else is queued for it) and the listener, and removes the
    // socket file (if it is still the one this daemon created).
    void close_all(std::string_view reason = {});

  private:
    struct Client {
        std::uint64_t id = 0;
        rwmos::FrameStream stream;
        std::vector<std::uint8_t> out;  // replies not yet sent
        std::size_t out_pos = 0;
        bool reading = true;  // EPOLLIN armed
        // The epoll events registered now: rearm() changes them only when
        // they differ (each epoll_ctl is a system call per request otherwise).
        std::uint32_t armed = 0;
        SteadyClock::time_point last_active{};  // last byte received or sent
    };

    void drop(int fd, std::string_view why);
    bool flush(int fd, Client& c);  // false: the client is gone
    void rearm(int fd, Client& c) const;
    // Serves and releases every client whose peer has hung up (its EOF not
    // read yet); returns how many were released.
    std::size_t reap_hung_up();
    void accept_one(int fd);
    void arm_idle_timer(SteadyClock::time_point when);

    BoardHost& host_;
    int epoll_fd_;
    ClientLimits limits_;
    int listen_fd_ = -1;
    int idle_timer_fd_ = -1;
    bool idle_timer_armed_ = false;
    std::string path_;
    dev_t dev_ = 0;
    ino_t ino_ = 0;
    std::uint64_t next_id_ = 1;
    std::map<int, Client> clients_;
    std::vector<std::uint8_t> read_buffer_;
};

// Replies a client may leave unread before the daemon stops reading from it.
inline constexpr std::size_t kMaxQueuedReplies = 1 << 20;

// The name of the file in the registry directory (objif/registry.h) whose
// flock is a daemon's turn to start in the socket directory of that device
// and inode.
std::string start_lock_name(dev_t dev, ino_t ino);

// Sends `notice` (a Notice frame, objif/frame.h) on `fd` without blocking;
// false when it could not be sent whole.
bool send_notice(int fd, objif::Status status, std::string_view text);

}  // namespace rwmos_emu
