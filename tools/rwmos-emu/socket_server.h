// SPDX-License-Identifier: MIT
// The daemon's Unix socket: many clients at once, each a byte stream of
// request frames answered in order. Driven by the daemon's epoll loop on one
// thread; requests reach the board through BoardHost (serialised).
// What a client can make the daemon hold is bounded: its incomplete frame
// (at most one frame, kMaxPayload + 20 bytes, plus one read), and replies it
// does not read (above kMaxQueuedReplies the daemon stops reading from it
// until it catches up). A client that sends garbage, or disconnects
// mid-frame, loses its connection and nothing else.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "board_host.h"
#include "rwmos/frame_stream.h"

namespace rwmos_emu {

class SocketServer {
  public:
    SocketServer(BoardHost& host, int epoll_fd, std::size_t max_clients)
        : host_(host), epoll_fd_(epoll_fd), max_clients_(max_clients) {}
    ~SocketServer();
    SocketServer(const SocketServer&) = delete;
    SocketServer& operator=(const SocketServer&) = delete;

    // Listens on `path` (mode 0660, owned by `group` unless it is -1). A
    // stale socket (nobody listening) is removed first; a live one, or a path
    // that is not a socket, is refused. The file appears only once the
    // daemon listens. False with `why`.
    bool open(const std::string& path, gid_t group, std::string& why);

    int listen_fd() const noexcept { return listen_fd_; }
    bool owns(int fd) const { return clients_.count(fd) != 0; }
    std::size_t client_count() const noexcept { return clients_.size(); }

    void on_listen_ready();
    void on_client_ready(int fd, std::uint32_t events);

    // Closes every client and the listener and removes the socket file (if
    // it is still the one this daemon created).
    void close_all();

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
    };

    void drop(int fd, std::string_view why);
    bool flush(int fd, Client& c);  // false: the client is gone
    void rearm(int fd, Client& c) const;

    BoardHost& host_;
    int epoll_fd_;
    std::size_t max_clients_;
    int listen_fd_ = -1;
    std::string path_;
    dev_t dev_ = 0;
    ino_t ino_ = 0;
    std::uint64_t next_id_ = 1;
    std::map<int, Client> clients_;
    std::vector<std::uint8_t> read_buffer_;
};

// Replies a client may leave unread before the daemon stops reading from it.
inline constexpr std::size_t kMaxQueuedReplies = 1 << 20;

}  // namespace rwmos_emu
