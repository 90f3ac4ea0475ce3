// SPDX-License-Identifier: MIT
// The daemon socket transport ("unix:PATH"): a stream socket to rwmos-emu
// carrying wire frames, one request and its reply at a time.
// Blocking: exchange() polls the socket for a learned spin budget (at most
// 50 us), then blocks in poll(), for at most the timeout in all; open and
// reconnect block in connect() (a local socket answers at once).
// Threading: one caller at a time (the FrameTransport that owns the link).
// errno becomes a status in status_of_errno() and nowhere else.
#include <fmt/format.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <new>

#include "frame_transport.h"
#include "objif/adaptive_spin.h"
#include "rwmos/registry.h"

namespace apci {
namespace {

using objif::Status;
using SteadyClock = std::chrono::steady_clock;

// The one place where this backend turns errno into a status.
Status status_of_errno(int err) noexcept {
    switch (err) {
        case ETIMEDOUT:
        case EAGAIN:
            return Status::kTimeout;
        case ENOMEM:
        case ENOBUFS:
            return Status::kNoMemory;
        case ENAMETOOLONG:
        case EINVAL:
            return Status::kInvalidArgument;
        default:
            return Status::kTransportError;
    }
}

std::string errno_text(std::string_view what, int err) {
    return fmt::format("{}: {}", what, std::strerror(err));
}

int remaining_ms(SteadyClock::time_point deadline) {
    const auto left = std::chrono::ceil<Millis>(deadline - SteadyClock::now()).count();
    return left <= 0 ? 0 : static_cast<int>(std::min<long long>(left, 1 << 30));
}

class UnixLink final : public FrameLink {
  public:
    explicit UnixLink(std::string path) : path_(std::move(path)) {}
    ~UnixLink() override { close_socket(); }
    UnixLink(const UnixLink&) = delete;
    UnixLink& operator=(const UnixLink&) = delete;

    Status open(std::string& why) noexcept {
        close_socket();
        sockaddr_un addr{};
        addr.sun_family = AF_UNIX;
        if (path_.empty() || path_.size() >= sizeof addr.sun_path) {
            why = fmt::format("socket path '{}' is {} (at most {} bytes)", path_,
                              path_.empty() ? "empty" : "too long", sizeof addr.sun_path - 1);
            return Status::kInvalidArgument;
        }
        std::memcpy(addr.sun_path, path_.c_str(), path_.size() + 1);
        const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (fd < 0) return failed(errno, "socket", why);
        if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
            const int err = errno;
            ::close(fd);
            const char* hint =
                err == ENOENT || err == ECONNREFUSED ? " (is rwmos-emu running?)" : "";
            why = fmt::format("connect {}: {}{}", path_, std::strerror(err), hint);
            return status_of_errno(err);
        }
        fd_ = fd;
        pending_.clear();
        lost_.clear();
        return Status::kOk;
    }

    Status exchange(std::span<const std::uint8_t> request, std::uint32_t sequence,
                    std::vector<std::uint8_t>& reply, Millis timeout,
                    std::string& why) noexcept override {
        if (fd_ < 0) {
            why = fmt::format("link lost ({}); apci_reconnect() reopens it", lost_);
            return Status::kTransportError;
        }
        const auto deadline = SteadyClock::now() + timeout;
        Status s = send_all(request, deadline, why);
        if (s != Status::kOk) return s;
        return receive_reply(
            pending_, sequence, reply, deadline,
            [this](std::vector<std::uint8_t>& buffer, SteadyClock::time_point until,
                   std::string& text) { return read_some(buffer, until, text); },
            why);
    }

    Status reconnect(std::string& why) noexcept override { return open(why); }
    bool connected() const noexcept override { return fd_ >= 0; }

  private:
    Status failed(int err, std::string_view what, std::string& why) {
        why = errno_text(what, err);
        return status_of_errno(err);
    }

    // The peer is gone: keep why, close, answer kTransportError from now on.
    Status lose(std::string text, std::string& why) {
        lost_ = std::move(text);
        close_socket();
        why = fmt::format("{}; apci_reconnect() reopens the link", lost_);
        return Status::kTransportError;
    }

    Status wait_for(short events, SteadyClock::time_point deadline, std::string_view what,
                    std::string& why) {
        for (;;) {
            pollfd p{fd_, events, 0};
            const int n = ::poll(&p, 1, remaining_ms(deadline));
            if (n > 0) return Status::kOk;  // ready, or an error the next call reports
            if (n == 0) {
                why = fmt::format("no {} within the timeout", what);
                return Status::kTimeout;
            }
            if (errno != EINTR) return failed(errno, "poll", why);
        }
    }

    Status send_all(std::span<const std::uint8_t> bytes, SteadyClock::time_point deadline,
                    std::string& why) {
        std::size_t sent = 0;
        while (sent < bytes.size()) {
            const ssize_t n =
                ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
            if (n > 0) {
                sent += static_cast<std::size_t>(n);
                continue;
            }
            const int err = errno;
            if (err == EINTR) continue;
            if (err == EAGAIN) {
                const Status s = wait_for(POLLOUT, deadline, "room to send the request", why);
                if (s != Status::kOk) return s;
                continue;
            }
            if (err == EPIPE || err == ECONNRESET)
                return lose(
                    fmt::format("{} closed the connection (send: {})", path_, std::strerror(err)),
                    why);
            return failed(err, "send", why);
        }
        return Status::kOk;
    }

    // Appends what the socket holds to `buffer`. Nothing there yet: polls the
    // socket for the spin budget first (the daemon answers an object request in
    // a few microseconds, while a blocked caller's wake-up costs tens of them on
    // a virtual machine), then sleeps in poll().
    Status read_some(std::vector<std::uint8_t>& buffer, SteadyClock::time_point deadline,
                     std::string& why) {
        const auto start = SteadyClock::now();
        const auto spin_end = start + spin_.budget();
        bool spinning = true;
        for (;;) {
            const ssize_t n = ::recv(fd_, chunk_.data(), chunk_.size(), MSG_DONTWAIT);
            const int err = errno;
            if (n > 0) {
                spin_.learn(SteadyClock::now() - start);
                buffer.insert(buffer.end(), chunk_.begin(), chunk_.begin() + n);
                return Status::kOk;
            }
            if (n == 0) return lose(fmt::format("{} closed the connection", path_), why);
            if (err == EINTR) continue;
            if (err == EAGAIN) {
                if (spinning && SteadyClock::now() < spin_end) continue;
                spinning = false;
                const Status s = wait_for(POLLIN, deadline, "reply from the board", why);
                if (s != Status::kOk) return s;
                continue;
            }
            if (err == ECONNRESET)
                return lose(
                    fmt::format("{} closed the connection (recv: {})", path_, std::strerror(err)),
                    why);
            return failed(err, "recv", why);
        }
    }

    void close_socket() noexcept {
        if (fd_ >= 0) ::close(fd_);
        fd_ = -1;
        pending_.clear();
    }

    static constexpr std::size_t kReadChunk = std::size_t{64} * 1024;
    // How long read_some() polls before it sleeps (objif/adaptive_spin.h).
    static constexpr std::chrono::microseconds kShortestSpin{1};
    static constexpr std::chrono::microseconds kLongestSpin{50};
    std::string path_;
    int fd_ = -1;
    std::vector<std::uint8_t> chunk_ = std::vector<std::uint8_t>(kReadChunk);  // one recv()
    objif::AdaptiveSpin spin_{kShortestSpin, kLongestSpin};
    std::vector<std::uint8_t> pending_;  // received bytes not yet a whole frame
    std::string lost_;                   // why the link was lost
};

// A socket answers connect() only when something listens on it.
bool socket_is_live(const std::string& path) {
    sockaddr_un addr{};
    if (path.size() >= sizeof addr.sun_path) return false;
    addr.sun_family = AF_UNIX;
    std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return false;
    const bool live = ::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0;
    ::close(fd);
    return live;
}

}  // namespace

Status open_unix(const DeviceUri& uri, std::unique_ptr<Transport>& out, std::string& why) noexcept {
    try {
        LinkOptions options;
        Status s = parse_link_options(uri, options, why);
        if (s != Status::kOk) return s;
        if (!options.rest.empty()) {
            why =
                fmt::format("unknown unix: option '{}' (known: timeout=MS)", options.rest.front());
            return Status::kInvalidArgument;
        }
        if (uri.target.empty()) {
            why = "unix: needs the daemon's socket path, e.g. unix:/run/user/1000/rwmos-emu.sock";
            return Status::kInvalidArgument;
        }
        auto link = std::make_unique<UnixLink>(uri.target);
        s = link->open(why);
        if (s != Status::kOk) return s;
        out = std::make_unique<FrameTransport>(std::move(link), "unix:" + uri.target,
                                               options.timeout);
        return Status::kOk;
    } catch (const std::bad_alloc&) {
        return Status::kNoMemory;
    } catch (...) {
        return Status::kGeneralError;
    }
}

Status list_unix(std::vector<FoundDevice>& out, std::string& why) noexcept {
    try {
        std::vector<rwmos::RegisteredDaemon> daemons;
        if (!rwmos::registered_daemons(daemons, why)) return Status::kTransportError;
        for (const auto& d : daemons) {
            if (!d.socket.empty() && socket_is_live(d.socket))
                out.push_back({"unix:" + d.socket, fmt::format("rwmos-emu daemon, pid {}", d.pid)});
        }
        return Status::kOk;
    } catch (const std::bad_alloc&) {
        return Status::kNoMemory;
    } catch (...) {
        return Status::kGeneralError;
    }
}

}  // namespace apci
