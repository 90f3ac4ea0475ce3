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
#include <thread>

#include "frame_transport.h"
#include "objif/adaptive_spin.h"
#include "objif/byte_order.h"
#include "objif/registry.h"
#include "guarded.h"

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

// What answered a connection: nothing (connect failed), the daemon's
// greeting, its refusal, or something that is not an rwmos-emu daemon (it
// said something else, or nothing in time).
enum class Greeting { kNone, kWelcome, kRefused, kStranger };

// A connect() refused by a socket file that exists is retried this long: a
// daemon binds its socket at the path and listens right after, and a client
// that saw the file appear may be that quick.
constexpr int kRefusedRetries = 10;
constexpr auto kRefusedRetryPause = std::chrono::milliseconds(1);

class UnixLink final : public FrameLink {
  public:
    UnixLink(std::string path, Millis greeting_timeout)
        : path_(std::move(path)), greeting_timeout_(greeting_timeout) {}
    ~UnixLink() override { close_socket(); }
    UnixLink(const UnixLink&) = delete;
    UnixLink& operator=(const UnixLink&) = delete;

    // Connects and reads the daemon's greeting (docs/wire-frame.md
    // "Notices"): the link is open only once the daemon has accepted it.
    Status open(std::string& why) noexcept { return open(why, greeting_); }

    // As open(); `greeting` tells who answered (apci_list_devices tells an
    // rwmos-emu daemon from anything else listening).
    Status open(std::string& why, Greeting& greeting) noexcept {
        greeting = Greeting::kNone;
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
        int rc = -1;
        int err = 0;
        for (int attempt = 0;; ++attempt) {
            rc = ::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
            err = errno;
            if (rc == 0 || err != ECONNREFUSED || attempt == kRefusedRetries) break;
            std::this_thread::sleep_for(kRefusedRetryPause);
        }
        if (rc != 0) {
            ::close(fd);
            const char* hint =
                err == ENOENT || err == ECONNREFUSED ? " (is rwmos-emu running?)" : "";
            why = fmt::format("connect {}: {}{}", path_, std::strerror(err), hint);
            return status_of_errno(err);
        }
        fd_ = fd;
        pending_.clear();
        lost_.clear();
        const Status s = read_greeting(why, greeting);
        if (s != Status::kOk) close_socket();
        return s;
    }

    Status exchange(std::span<const std::uint8_t> request, std::uint32_t sequence,
                    std::vector<std::uint8_t>& reply, Millis timeout,
                    std::string& why) noexcept override {
        if (fd_ < 0) {
            why = still_lost_words(lost_);
            return Status::kTransportError;
        }
        const auto deadline = SteadyClock::now() + timeout;
        Status s = send_all(request, deadline, why);
        if (s != Status::kOk) return s;
        objif::Notice closing;
        closing.status = Status::kOk;
        s = receive_reply(
            pending_, sequence, reply, deadline,
            [this](std::vector<std::uint8_t>& buffer, SteadyClock::time_point until,
                   std::string& text) { return read_some(buffer, until, text); },
            why, &closing);
        if (s == Status::kTransportError && closing.status != Status::kOk && fd_ >= 0)
            return closed_by_daemon(closing.text, why);
        return s;
    }

    // A link the daemon closed without a request (connected() false) has its parting words in
    // the socket still: they are kept as why the link was lost, should the new one fail too
    // (a later request said "link lost ()").
    Status reconnect(std::string& why) noexcept override {
        try {
            std::string reason = lost_at_first_.empty() ? lost_ : lost_at_first_;
            if (fd_ >= 0)
                if (std::string words = parting_words(); !words.empty())
                    reason = fmt::format("daemon {} closed the connection: {}", path_, words);
            const Status s = open(why);
            lost_at_first_ = s == Status::kOk ? std::string() : reason;
            if (s != Status::kOk)
                lost_ = reason.empty() ? why : fmt::format("{}; opening it again: {}", reason, why);
            return s;
        } catch (...) {
            return open(why);
        }
    }
    // Open, and not hung up by the daemon: one that closed the link (its idle timeout, a
    // shutdown) is seen here at once, without a request (poll, no waiting); its parting words
    // are read by the next request, which fails with them.
    bool connected() const noexcept override {
        if (fd_ < 0) return false;
        pollfd p{fd_, POLLRDHUP, 0};
        return ::poll(&p, 1, 0) <= 0 || (p.revents & (POLLRDHUP | POLLHUP | POLLERR)) == 0;
    }
    // Known once a request found the link lost (a hang-up not yet read says nothing yet).
    std::string lost_reason() const override { return fd_ < 0 ? lost_ : std::string(); }
    // After open() was refused, or found a peer that is not a daemon: what
    // the peer did instead of greeting.
    const std::string& answer() const noexcept { return answer_; }

  private:
    // The first frame on a new connection: the daemon's Notice. Welcome:
    // kOk. Refusal (too many clients): kTransportError naming the reason.
    // Anything else, or nothing within the greeting timeout: not a daemon.
    Status read_greeting(std::string& why, Greeting& greeting) {
        const auto deadline = SteadyClock::now() + greeting_timeout_;
        const auto not_a_daemon = [&](std::string what) {
            greeting = Greeting::kStranger;
            why = fmt::format("{} is not an rwmos-emu daemon ({})", path_, what);
            answer_ = std::move(what);
            return Status::kTransportError;
        };
        for (;;) {
            objif::Frame frame;
            std::size_t consumed = 0;
            bool need_more = false;
            const objif::FrameError e = objif::decode_frame(pending_, frame, consumed, need_more);
            if (e == objif::FrameError::kNone) {
                objif::Notice notice;
                if (!notice_of(frame, notice))
                    return not_a_daemon(fmt::format("its first frame is {}, not the greeting",
                                                    objif::opcode_name(frame.opcode)));
                pending_.erase(pending_.begin(),
                               pending_.begin() + static_cast<std::ptrdiff_t>(consumed));
                if (notice.status != Status::kOk) {
                    greeting = Greeting::kRefused;
                    why = fmt::format("daemon {} refused the connection: {}", path_, notice.text);
                    answer_ = "refused the connection: " + notice.text;
                    return Status::kTransportError;
                }
                if (notice.text != objif::kDaemonGreeting)
                    return not_a_daemon(fmt::format("it greets as '{}'", notice.text));
                greeting = Greeting::kWelcome;
                return Status::kOk;
            }
            if (e == objif::FrameError::kBadVersion) {
                // A daemon of another release: its greeting is a frame of its version.
                greeting = Greeting::kRefused;
                answer_ = fmt::format(
                    "it speaks wire-frame version {}, this library {}: run the rwmos-emu of "
                    "libapci's release",
                    objif::load_little<std::uint16_t>(pending_.data() + 4), objif::kFrameVersion);
                why = fmt::format("daemon {} {}", path_, answer_);
                return Status::kTransportError;
            }
            if (!need_more)
                return not_a_daemon(fmt::format("it sent bytes that are not a frame: {}",
                                                objif::frame_error_name(e)));
            pollfd p{fd_, POLLIN, 0};
            const int n = ::poll(&p, 1, remaining_ms(deadline));
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) return failed(errno, "poll", why);
            if (n == 0)
                return not_a_daemon(
                    fmt::format("no greeting within {} ms", greeting_timeout_.count()));
            const ssize_t got = ::recv(fd_, chunk_.data(), chunk_.size(), MSG_DONTWAIT);
            if (got > 0) {
                pending_.insert(pending_.end(), chunk_.begin(), chunk_.begin() + got);
            } else if (got == 0 || errno == ECONNRESET) {
                return not_a_daemon("it closed the connection without a greeting");
            } else if (errno != EAGAIN && errno != EINTR) {
                return failed(errno, "recv", why);
            }
        }
    }

    // The daemon went away during a send: it may have said why (a Notice
    // waiting in the socket, e.g. the idle timeout). Its text, or "".
    std::string parting_words() {
        for (int reads = 0; reads < 64; ++reads) {
            const ssize_t n = ::recv(fd_, chunk_.data(), chunk_.size(), MSG_DONTWAIT);
            if (n <= 0) break;
            pending_.insert(pending_.end(), chunk_.begin(), chunk_.begin() + n);
        }
        std::span<const std::uint8_t> rest(pending_);
        objif::Frame frame;
        for (;;) {
            std::size_t consumed = 0;
            bool need_more = false;
            const objif::FrameError e = objif::decode_frame(rest, frame, consumed, need_more);
            if (consumed == 0) return {};
            objif::Notice notice;
            if (e == objif::FrameError::kNone && notice_of(frame, notice) &&
                notice.status != Status::kOk)
                return notice.text;
            rest = rest.subspan(consumed);
        }
    }

    // The daemon closed the connection after telling why.
    Status closed_by_daemon(std::string_view reason, std::string& why) {
        return lose(fmt::format("daemon {} closed the connection: {}", path_, reason), why);
    }

    Status failed(int err, std::string_view what, std::string& why) {
        why = errno_text(what, err);
        return status_of_errno(err);
    }

    // The peer is gone: keep why, close, answer kTransportError from now on.
    Status lose(std::string text, std::string& why) {
        lost_ = std::move(text);
        close_socket();
        why = lost_link_words(lost_);
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
            if (err == EPIPE || err == ECONNRESET) {
                if (const std::string reason = parting_words(); !reason.empty())
                    return closed_by_daemon(reason, why);
                return lose(
                    fmt::format("{} closed the connection (send: {})", path_, std::strerror(err)),
                    why);
            }
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
    Millis greeting_timeout_;
    Greeting greeting_ = Greeting::kNone;  // who answered the last open()
    std::string answer_;  // what the peer did instead of greeting (refusal, or not a daemon)
    int fd_ = -1;
    std::vector<std::uint8_t> chunk_ = std::vector<std::uint8_t>(kReadChunk);  // one recv()
    objif::AdaptiveSpin spin_{kShortestSpin, kLongestSpin};
    std::vector<std::uint8_t> pending_;  // received bytes not yet a whole frame
    std::string lost_;                   // why the link was lost
    std::string lost_at_first_;          // before reconnecting failed (lost_ says both)
};

// How long apci_list_devices waits for a registered socket's greeting.
constexpr Millis kListGreetingTimeout{500};

}  // namespace

Status open_unix(const DeviceUri& uri, std::unique_ptr<Transport>& out, std::string& why) noexcept {
    return open_with_options(uri, why, [&](const LinkOptions& options) {
        const Status s = check_path_target(
            uri, options, "unix",
            "the daemon's socket path, e.g. unix:/run/user/1000/rwmos-emu.sock", why);
        if (s != Status::kOk) return s;
        return open_framed(std::make_unique<UnixLink>(uri.target, options.timeout),
                           "unix:" + uri.target, options.timeout, out, why);
    });
}

Status list_unix(std::vector<FoundDevice>& out, std::string& why) noexcept {
    return guarded([&] {
        std::vector<objif::RegisteredDaemon> daemons;
        if (!objif::registered_daemons(daemons, why)) return Status::kTransportError;
        // Only a socket that greets as rwmos-emu is listed as a daemon; one
        // that accepts but answers otherwise (another program listening
        // there now) is listed as not one, one nobody listens on is left out.
        for (const auto& d : daemons) {
            if (d.socket.empty()) continue;
            UnixLink probe(d.socket, kListGreetingTimeout);
            std::string probe_why;
            Greeting greeting = Greeting::kNone;
            probe.open(probe_why, greeting);
            if (greeting == Greeting::kWelcome || greeting == Greeting::kRefused)
                out.push_back(
                    {"unix:" + d.socket,
                     greeting == Greeting::kWelcome
                         ? fmt::format("rwmos-emu daemon, pid {}", d.pid)
                         : fmt::format("rwmos-emu daemon, pid {} ({})", d.pid, probe.answer())});
            else if (greeting == Greeting::kStranger)
                out.push_back({"unix:" + d.socket,
                               fmt::format("not an rwmos-emu daemon (registered by pid {}; {})",
                                           d.pid, probe.answer())});
        }
        return Status::kOk;
    });
}

}  // namespace apci
