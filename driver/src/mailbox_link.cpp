// SPDX-License-Identifier: MIT
#include "mailbox_link.h"
#include "guarded.h"

#include <fmt/format.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <new>

namespace apci {

namespace mb = objif::mailbox;
using objif::Status;

namespace {

// The largest pid Linux hands out (PID_MAX_LIMIT on 64-bit kernels): a larger token is no
// process's, and kill(2) takes 0xFFFFFFFF (-1) for every process it may signal.
constexpr std::uint32_t kPidMaxLimit = std::uint32_t{1} << 22;
// A live process that has held the host lock this long is asked whether it maps the mailbox.
constexpr std::chrono::milliseconds kHolderCheckAfter{50};

// The (device, inode) of the mapping of /proc/PID/maps that contains `address` (any when
// null) and that matches `want` (any when its inode is 0); found or not, or unreadable.
enum class MapsAnswer { kFound, kNotFound, kUnreadable };
MapsAnswer find_mapping(pid_t pid, const void* address, const MailboxLink::MappedFileId& want,
                        MailboxLink::MappedFileId* found) {
    std::FILE* maps = std::fopen(fmt::format("/proc/{}/maps", pid).c_str(), "re");
    if (maps == nullptr) return MapsAnswer::kUnreadable;
    MapsAnswer answer = MapsAnswer::kNotFound;
    char line[512];
    while (std::fgets(line, sizeof line, maps) != nullptr) {
        unsigned long start = 0, end = 0, offset = 0;
        char perms[8] = {}, device[32] = {};
        unsigned long long inode = 0;
        if (std::sscanf(line, "%lx-%lx %7s %lx %31s %llu", &start, &end, perms, &offset, device,
                        &inode) != 6 ||
            inode == 0)
            continue;
        const auto at = reinterpret_cast<std::uintptr_t>(address);
        if (address != nullptr && (at < start || at >= end)) continue;
        if (want.inode != 0 && (inode != want.inode || want.device != device)) continue;
        if (found != nullptr) *found = {device, inode};
        answer = MapsAnswer::kFound;
        break;
    }
    // A line longer than the buffer is read on in pieces that do not parse: skipped.
    std::fclose(maps);
    return answer;
}

// A host lock whose token is the pid of a process that no longer exists belongs to a host that
// died mid-exchange; so does a token that is no pid at all. A live process of that pid that has
// held the lock a while and does not map this mailbox is another program that got the pid
// later: gone too. One this process may not look into (another user's) counts as the holder.
bool holder_process_gone(std::uint32_t token, std::chrono::nanoseconds held_for,
                         const void* context) {
    if (token > kPidMaxLimit) return true;
    const auto pid = static_cast<pid_t>(token);
    if (::kill(pid, 0) != 0 && errno == ESRCH) return true;
    const auto* mapped = static_cast<const MailboxLink::MappedFileId*>(context);
    if (held_for < kHolderCheckAfter || mapped == nullptr || mapped->inode == 0) return false;
    return find_mapping(pid, nullptr, *mapped, nullptr) == MapsAnswer::kNotFound;
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
    return guarded([&] {
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
        mapped_ = {};
        if (const auto* mapping = dynamic_cast<const mb::MappedWindow*>(window.get()))
            find_mapping(::getpid(), mapping->base(), {}, &mapped_);
        window_ = std::move(window);
        lost_.clear();
        return Status::kOk;
    });
}

Status MailboxLink::exchange(std::span<const std::uint8_t> request, std::uint32_t,
                             std::vector<std::uint8_t>& reply, Millis timeout,
                             std::string& why) noexcept {
    try {
        if (!window_) {
            why = still_lost_words(lost_);
            return Status::kTransportError;
        }
        if (window_->load(mb::kOffGeneration) != generation_) {
            lost_ = window_->error() != Status::kOk
                        ? window_->error_text()
                        : "the board restarted since the link was opened";
            window_.reset();
            why = lost_link_words(lost_);
            return Status::kTransportError;
        }
        mb::HostOptions options;
        options.token = process_token();
        options.timeout = timeout;
        options.adaptive = &spin_;
        options.lock_holder_gone = holder_process_gone;
        options.holder_context = &mapped_;
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
            why = lost_link_words(lost_);
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
