// SPDX-License-Identifier: MIT
// The daemon's Unix socket: many clients at once, each a byte stream of
// request frames answered in order. Driven by the daemon's epoll loop on one
// thread; requests reach the board through BoardHost (serialised).
// What a client can make the daemon hold is bounded: its incomplete frame
// (at most one frame, kMaxPayload + 20 bytes, plus one read), and replies it
// does not read (above kMaxQueuedReplies the daemon stops serving and
// reading it until it catches up). A client that sends garbage, or
// disconnects mid-frame, loses its connection and nothing else.
// Fairness: the clients' requests are served in turns (kTurnTime of board
// work, at least one request, at most until kMaxQueuedReplies of replies
// wait); a client with requests left over waits for the next round, after
// every other ready client, and is not read from until they are served.
// Out of file descriptors (EMFILE, ENFILE) a newcomer is accepted on a
// spare descriptor kept for that, told why and closed: the listening socket
// does not stay ready with nobody taken off it.
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
    // Serves `fd`, a listening Unix stream socket handed over by systemd
    // (socket activation: the .socket unit made and owns the file, so it is
    // never removed here). `expected_path`, when not empty, is the path the
    // socket must be bound at. False with `why` (the fd is then left open).
    bool adopt(int fd, const std::string& expected_path, std::string& why);
    // The path clients connect to (after open or adopt).
    const std::string& path() const noexcept { return path_; }

    int listen_fd() const noexcept { return listen_fd_; }
    // How long the event loop may sleep in epoll_wait for this server's sake:
    // 0 while clients have requests left over from their turn, the time until
    // the listener is watched again after it was paused, else -1 (no limit).
    int wait_ms() const;
    // Once per turn of the event loop, after its events: serves one turn of
    // every client with requests left over (that had none this round), and
    // watches the listener again when its pause is over.
    void after_events();
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
        // Whole requests buffered that its last turn left (not read from meanwhile).
        bool backlog = false;
        bool awaits_turn = false;  // in left_over_: served in after_events()
        std::uint64_t round = 0;   // the round of the event loop it was last served in
    };

    void drop(int fd, std::string_view why);
    bool flush(int fd, Client& c);  // false: the client is gone
    void rearm(int fd, Client& c) const;
    // Serves and releases every client whose peer has hung up (its EOF not
    // read yet); returns how many were released.
    std::size_t reap_hung_up();
    void accept_one(int fd);
    // One turn of the client's buffered requests; false when the client is gone.
    bool serve_turn(int fd, Client& c);
    // EMFILE/ENFILE from accept: takes one newcomer on the spare descriptor,
    // tells it why and closes it. False when there is nobody left to take or
    // no spare (the listener is then paused).
    bool refuse_for_descriptors(int err);
    void pause_listening();
    void arm_idle_timer(SteadyClock::time_point when);

    BoardHost& host_;
    int epoll_fd_;
    ClientLimits limits_;
    bool listen_on(int fd, std::string& why);  // epoll and idle timer for a listening fd
    int listen_fd_ = -1;
    bool owns_path_ = false;  // open() made the socket file; adopt() did not
    int idle_timer_fd_ = -1;
    bool idle_timer_armed_ = false;
    std::string path_;
    dev_t dev_ = 0;
    ino_t ino_ = 0;
    std::uint64_t next_id_ = 1;
    std::map<int, Client> clients_;
    std::vector<std::uint8_t> read_buffer_;
    std::vector<int> left_over_;  // clients with requests left from their turn, in order
    std::uint64_t round_ = 1;     // the event loop's rounds, counted by after_events
    // A descriptor held in reserve, given up for a moment to accept a newcomer
    // when the process is out of descriptors (EMFILE), so it can be told why.
    int spare_fd_ = -1;
    bool listen_paused_ = false;
    SteadyClock::time_point listen_resume_{};
    std::uint64_t refused_for_descriptors_ = 0;  // since the last log line about it
    SteadyClock::time_point refusal_logged_{};
};

// One client's turn: this much board work (a request that ends past it ends
// the turn; one Clock request is at most about 50 ms, objif/frame.h).
inline constexpr std::chrono::milliseconds kTurnTime{2};
// How long the listener is not watched when accept fails and nobody can be
// taken off it (no spare descriptor, an error other than EMFILE).
inline constexpr std::chrono::milliseconds kListenPause{100};

// Replies a client may leave unread before the daemon stops serving and reading it.
inline constexpr std::size_t kMaxQueuedReplies = 1 << 20;

// The name of the file in the registry directory (objif/registry.h) whose
// flock is a daemon's turn to start in the socket directory of that device
// and inode.
std::string start_lock_name(dev_t dev, ino_t ino);

// Sends `notice` (a Notice frame, objif/frame.h) on `fd` without blocking;
// false when it could not be sent whole.
bool send_notice(int fd, objif::Status status, std::string_view text);

}  // namespace rwmos_emu
