// SPDX-License-Identifier: MIT
#include "mailbox_link.h"

#include <fmt/format.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <new>

namespace apci {

namespace mb = objif::mailbox;
using objif::Status;

namespace {

// A host lock whose token is the pid of a process that no longer exists
// belongs to a host that died mid-exchange.
bool holder_process_gone(std::uint32_t token) {
    return ::kill(static_cast<pid_t>(token), 0) != 0 && errno == ESRCH;
}

// The host lock's token: this process's pid. getpid() is a system call on
// every exchange otherwise (glibc does not cache it), and a system call costs
// as much as the whole shared-memory round trip in a virtual machine
// (docs/performance.md); the cache is refreshed in a forked child.
std::atomic<pid_t> cached_pid{0};

void refresh_pid() noexcept {
    cached_pid.store(::getpid(), std::memory_order_relaxed);
}

std::uint32_t process_token() noexcept {
    static const bool registered = [] {
        refresh_pid();
        return ::pthread_atfork(nullptr, nullptr, refresh_pid) == 0;
    }();
    pid_t pid = cached_pid.load(std::memory_order_relaxed);
    if (!registered) pid = ::getpid();  // no fork hook: ask every time
    return static_cast<std::uint32_t>(pid);
}

}  // namespace

Status MailboxLink::open(std::string& why) noexcept {
    try {
        window_.reset();
        std::unique_ptr<mb::Window> window;
        Status s = open_(window, why);
        if (s != Status::kOk) return s;
        if (std::string bad = mb::check_layout(*window); !bad.empty()) {
            why = std::move(bad);
            return window->error() != Status::kOk ? window->error() : Status::kTransportError;
        }
        if (window->load(mb::kOffBoardState) !=
            static_cast<std::uint32_t>(mb::BoardState::kServing)) {
            why = "no board serves this mailbox (is the emulator running?)";
            return Status::kTransportError;
        }
        generation_ = window->load(mb::kOffGeneration);
        window_ = std::move(window);
        lost_.clear();
        return Status::kOk;
    } catch (const std::bad_alloc&) {
        return Status::kNoMemory;
    } catch (...) {
        return Status::kGeneralError;
    }
}

Status MailboxLink::exchange(std::span<const std::uint8_t> request, std::uint32_t,
                             std::vector<std::uint8_t>& reply, Millis timeout,
                             std::string& why) noexcept {
    try {
        if (!window_) {
            why = fmt::format("link lost ({}); apci_reconnect() reopens it", lost_);
            return Status::kTransportError;
        }
        if (window_->load(mb::kOffGeneration) != generation_) {
            lost_ = window_->error() != Status::kOk
                        ? window_->error_text()
                        : "the board restarted since the link was opened";
            window_.reset();
            why = fmt::format("{}; apci_reconnect() reopens the link", lost_);
            return Status::kTransportError;
        }
        mb::HostOptions options;
        options.token = process_token();
        options.timeout = timeout;
        options.adaptive = &spin_;
        options.lock_holder_gone = holder_process_gone;
        const Status s = mb::exchange(*window_, options, request, reply, why);
        if (s == Status::kOk) return s;
        // A board that stopped, or restarted (another generation), has lost
        // what this link knew: say so once and require a reconnect.
        const bool stopped = window_->load(mb::kOffBoardState) !=
                             static_cast<std::uint32_t>(mb::BoardState::kServing);
        const bool restarted = window_->load(mb::kOffGeneration) != generation_;
        const bool failed = window_->error() != Status::kOk;  // e.g. a shrunk file
        if (stopped || restarted || failed) {
            lost_ = failed                  ? window_->error_text()
                    : restarted && !stopped ? "the board restarted"
                                            : why;
            window_.reset();
            why = fmt::format("{}; apci_reconnect() reopens the link", lost_);
            return Status::kTransportError;
        }
        return s;
    } catch (const std::bad_alloc&) {
        return Status::kNoMemory;
    } catch (...) {
        return Status::kGeneralError;
    }
}

}  // namespace apci
