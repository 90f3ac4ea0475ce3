// SPDX-License-Identifier: MIT
#include "objif/mailbox.h"

#include "objif/byte_order.h"

#include <fmt/format.h>
#include <linux/futex.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <thread>

namespace objif::mailbox {

namespace {

using Clock = std::chrono::steady_clock;

inline void cpu_relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    asm volatile("yield");
#endif
}

// Spins until the word at `offset` leaves `from`, or `spin` passes; returns the last value seen.
std::uint32_t spin_while(Window& w, std::size_t offset, std::uint32_t from,
                         std::chrono::nanoseconds spin) noexcept {
    std::uint32_t now = w.load(offset);
    if (now != from || spin.count() <= 0) return now;
    const auto until = Clock::now() + spin;
    for (unsigned i = 1;; ++i) {
        cpu_relax();
        now = w.load(offset);
        if (now != from) return now;
        if ((i & 63) == 0 && Clock::now() >= until) return now;
    }
}

// Sleeps on the doorbell at `offset` while it holds `seen`, announcing the
// sleep in `sleeping_flag` so the other side knows to wake us. The flag store
// and the doorbell re-load are sequentially consistent, as are the other
// side's doorbell store and flag load: one of the two sides sees the other.
void sleep_on(Window& w, std::size_t offset, std::size_t sleeping_flag, std::uint32_t seen,
              std::chrono::nanoseconds timeout) noexcept {
    w.store_fence(sleeping_flag, 1);
    if (w.load_fence(offset) == seen) w.wait(offset, seen, timeout);
    w.store(sleeping_flag, 0);
}

// Rings a doorbell: publishes the new sequence and wakes the other side if it sleeps.
void ring(Window& w, std::size_t offset, std::uint32_t sequence,
          std::size_t other_sleeping_flag) noexcept {
    w.store_fence(offset, sequence);
    if (w.load_fence(other_sleeping_flag) != 0) w.wake(offset);
}

}  // namespace

// ---- Window

void Window::wait(std::size_t, std::uint32_t, std::chrono::nanoseconds timeout) noexcept {
    // Device memory: nothing to sleep on; poll again soon without burning the CPU.
    std::this_thread::sleep_for(
        std::min<std::chrono::nanoseconds>(timeout, std::chrono::microseconds(20)));
}

// The window's words are little-endian (docs/dpram.md) on every host, as a PCI BAR is: each
// access converts (objif/byte_order.h; nothing to do on a little-endian host).
std::uint32_t MappedWindow::load(std::size_t offset) noexcept {
    return from_little(std::atomic_ref<std::uint32_t>(*reinterpret_cast<std::uint32_t*>(base_ + offset))
                           .load(std::memory_order_acquire));
}
void MappedWindow::store(std::size_t offset, std::uint32_t value) noexcept {
    std::atomic_ref<std::uint32_t>(*reinterpret_cast<std::uint32_t*>(base_ + offset))
        .store(to_little(value), std::memory_order_release);
}
void MappedWindow::store_fence(std::size_t offset, std::uint32_t value) noexcept {
    std::atomic_ref<std::uint32_t>(*reinterpret_cast<std::uint32_t*>(base_ + offset))
        .store(to_little(value), std::memory_order_seq_cst);
}
std::uint32_t MappedWindow::load_fence(std::size_t offset) noexcept {
    return from_little(std::atomic_ref<std::uint32_t>(*reinterpret_cast<std::uint32_t*>(base_ + offset))
                           .load(std::memory_order_seq_cst));
}
bool MappedWindow::compare_exchange(std::size_t offset, std::uint32_t expected,
                                    std::uint32_t desired) noexcept {
    std::uint32_t stored = to_little(expected);
    return std::atomic_ref<std::uint32_t>(*reinterpret_cast<std::uint32_t*>(base_ + offset))
        .compare_exchange_strong(stored, to_little(desired), std::memory_order_acq_rel);
}
void MappedWindow::read(std::size_t offset, std::uint8_t* out, std::size_t size) noexcept {
    std::memcpy(out, base_ + offset, size);
}
void MappedWindow::write(std::size_t offset, const std::uint8_t* in, std::size_t size) noexcept {
    std::memcpy(base_ + offset, in, size);
}

void MappedWindow::wait(std::size_t offset, std::uint32_t expected,
                        std::chrono::nanoseconds timeout) noexcept {
    if (!can_sleep_) return Window::wait(offset, expected, timeout);
    const auto secs = std::chrono::duration_cast<std::chrono::seconds>(timeout);
    timespec ts{static_cast<time_t>(secs.count()), static_cast<long>((timeout - secs).count())};
    // A shared (not FUTEX_PRIVATE) futex: the other side is another process.
    // EAGAIN (value already changed), EINTR and ETIMEDOUT all mean "look again".
    // The kernel compares the word as stored: little-endian.
    ::syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(base_ + offset), FUTEX_WAIT,
              to_little(expected), &ts, nullptr, 0);
}

void MappedWindow::wake(std::size_t offset) noexcept {
    // Harmless on memory that no one sleeps on (device memory answers EFAULT).
    ::syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(base_ + offset), FUTEX_WAKE, INT_MAX,
              nullptr, nullptr, 0);
}

// ---- Layout

std::string check_layout(Window& w) {
    const std::uint32_t signature = w.load(kOffSignature);
    if (w.error() != Status::kOk) return w.error_text();
    if (signature != kSignature)
        return fmt::format("no mailbox here: signature is {:#010x}, expected {:#010x} (\"DRPM\")",
                           signature, kSignature);
    if (const auto v = w.load(kOffVersion); v != kLayoutVersion)
        return fmt::format("mailbox layout version {} (this driver speaks {})", v, kLayoutVersion);
    if (const auto size = w.load(kOffWindowSize); size != kWindowSize)
        return fmt::format("mailbox window size {:#x} (expected {:#x})", size, kWindowSize);
    if (const auto cap = w.load(kOffRecordCapacity); cap != kRecordCapacity)
        return fmt::format("mailbox record capacity {} (expected {})", cap, kRecordCapacity);
    if (w.error() != Status::kOk) return w.error_text();
    return {};
}

// ---- Board side

void format(Window& w) {
    w.store(kOffBoardState, static_cast<std::uint32_t>(BoardState::kStopped));
    w.store(kOffHostLock, 0);
    w.store(kOffRequestSequence, 0);
    w.store(kOffReplySequence, 0);
    w.store(kOffBoardSleeping, 0);
    w.store(kOffHostSleeping, 0);
    w.store(kOffRequest, 0);
    w.store(kOffReply, 0);
    w.store(kOffVersion, kLayoutVersion);
    w.store(kOffWindowSize, static_cast<std::uint32_t>(kWindowSize));
    w.store(kOffRecordCapacity, static_cast<std::uint32_t>(kRecordCapacity));
    w.store_fence(kOffSignature, kSignature);  // last: the header is complete
}

void set_board_state(Window& w, BoardState state) {
    if (state == BoardState::kServing) w.store(kOffGeneration, w.load(kOffGeneration) + 1);
    w.store_fence(kOffBoardState, static_cast<std::uint32_t>(state));
    // A host sleeping on the reply doorbell must notice a board that stops.
    w.wake(kOffReplySequence);
}

bool take_request(Window& w, Request& request, std::chrono::nanoseconds spin,
                  std::chrono::nanoseconds timeout) {
    // The reply sequence is the board's own word: the last request it answered.
    const std::uint32_t answered = w.load(kOffReplySequence);
    std::uint32_t s = spin_while(w, kOffRequestSequence, answered, spin);
    if (s == answered) {
        sleep_on(w, kOffRequestSequence, kOffBoardSleeping, answered, timeout);
        s = w.load(kOffRequestSequence);
    }
    if (s == answered) return false;
    request.sequence = s;
    const std::uint32_t length = w.load(kOffRequest);
    request.frame.clear();
    // An impossible length is the host's garbage: the caller answers it as a
    // short frame (empty bytes) and goes on.
    if (length < kFrameOverhead || length > kRecordCapacity) return true;
    request.frame.resize(length);
    w.read(kOffRequest + 4, request.frame.data(), length);
    return true;
}

bool take_request(Window& w, Request& request, AdaptiveSpin& spin,
                  std::chrono::nanoseconds timeout) {
    const auto start = Clock::now();
    const bool got = take_request(w, request, spin.budget(), timeout);
    spin.learn(Clock::now() - start);
    return got;
}

void put_reply(Window& w, const Request& request, std::span<const std::uint8_t> reply) {
    const std::size_t n = std::min(reply.size(), kRecordCapacity);
    w.write(kOffReply + 4, reply.data(), n);
    w.store(kOffReply, static_cast<std::uint32_t>(n));
    ring(w, kOffReplySequence, request.sequence, kOffHostSleeping);
}

void wake_board(Window& w) {
    w.wake(kOffRequestSequence);
}

// ---- Host side

namespace {

struct Exchange {
    Window& w;
    const HostOptions& options;
    Clock::time_point deadline;
    std::string& why;

    std::chrono::nanoseconds left() const {
        return std::max(deadline - Clock::now(), Clock::duration::zero());
    }

    Status window_failed() {
        why = w.error_text();
        return w.error();
    }

    Status board_stopped() {
        why = "the board stopped serving the mailbox";
        return Status::kTransportError;
    }

    bool serving() {
        return w.load(kOffBoardState) == static_cast<std::uint32_t>(BoardState::kServing);
    }

    Status lock() {
        std::uint32_t seen = 0;  // the holder this exchange has seen, and since when
        Clock::time_point seen_since{};
        for (;;) {
            if (w.compare_exchange(kOffHostLock, 0, options.token)) return Status::kOk;
            if (w.error() != Status::kOk) return window_failed();
            const std::uint32_t holder = w.load(kOffHostLock);
            const Clock::time_point now = Clock::now();
            if (holder != seen) {
                seen = holder;
                seen_since = now;
            }
            if (holder != 0 && options.lock_holder_gone != nullptr &&
                options.lock_holder_gone(holder, now - seen_since, options.holder_context) &&
                w.compare_exchange(kOffHostLock, holder, options.token))
                return Status::kOk;  // taken over from a host that died holding it
            if (left().count() == 0) {
                why = fmt::format(
                    "mailbox held by another host (token {}) for longer than the timeout", holder);
                return Status::kTimeout;
            }
            std::this_thread::sleep_for(std::chrono::microseconds(20));
        }
    }

    void unlock() { w.store(kOffHostLock, 0); }

    std::chrono::nanoseconds spin() const {
        return options.adaptive != nullptr ? options.adaptive->budget() : options.spin;
    }

    // Waits until the reply sequence reaches `sequence` (from the one before it).
    Status wait_reply(std::uint32_t sequence) {
        const std::uint32_t before = sequence - 1;
        const auto start = Clock::now();
        std::uint32_t s = spin_while(w, kOffReplySequence, before, spin());
        for (;;) {
            if (s == sequence) {
                if (options.adaptive != nullptr) options.adaptive->learn(Clock::now() - start);
                return Status::kOk;
            }
            if (w.error() != Status::kOk) return window_failed();
            if (s != before) {
                why = fmt::format("mailbox reply sequence jumped to {} while waiting for {}", s,
                                  sequence);
                return Status::kTransportError;
            }
            if (!serving()) return board_stopped();
            const auto remaining = left();
            if (remaining.count() == 0) {
                why = fmt::format("no reply from the board within {} ms (request {} pending)",
                                  options.timeout.count(), sequence);
                return Status::kTimeout;
            }
            // Wake now and then to notice a board that stopped without waking us.
            sleep_on(w, kOffReplySequence, kOffHostSleeping, s,
                     std::min<std::chrono::nanoseconds>(remaining, std::chrono::milliseconds(50)));
            s = spin_while(w, kOffReplySequence, before, spin());
        }
    }

    // A host that timed out left a request behind: let the board answer it (the reply is
    // dropped). Returns the request sequence the next request follows.
    Status settle(std::uint32_t& last) {
        last = w.load(kOffRequestSequence);
        const std::uint32_t answered = w.load(kOffReplySequence);
        if (answered == last) return Status::kOk;
        if (answered != last - 1) {
            why =
                fmt::format("mailbox sequences out of step: request {}, reply {}", last, answered);
            return Status::kTransportError;
        }
        return wait_reply(last);
    }

    Status run(std::span<const std::uint8_t> request, std::vector<std::uint8_t>& reply) {
        if (!serving()) {
            if (w.error() != Status::kOk) return window_failed();
            why = "the board is not serving the mailbox (is the emulator running?)";
            return Status::kTransportError;
        }
        std::uint32_t last = 0;
        Status st = settle(last);
        if (st != Status::kOk) return st;
        const std::uint32_t sequence = last + 1;
        w.write(kOffRequest + 4, request.data(), request.size());
        w.store(kOffRequest, static_cast<std::uint32_t>(request.size()));
        ring(w, kOffRequestSequence, sequence, kOffBoardSleeping);
        st = wait_reply(sequence);
        if (st != Status::kOk) return st;
        const std::uint32_t length = w.load(kOffReply);
        if (length > kRecordCapacity) {
            why = fmt::format("reply record length {} exceeds the record capacity {}", length,
                              kRecordCapacity);
            return Status::kTransportError;
        }
        reply.resize(length);
        w.read(kOffReply + 4, reply.data(), length);
        if (w.error() != Status::kOk) return window_failed();
        return Status::kOk;
    }
};

}  // namespace

Status exchange(Window& w, const HostOptions& options, std::span<const std::uint8_t> request,
                std::vector<std::uint8_t>& reply, std::string& why) {
    if (request.size() > kRecordCapacity) {
        why = fmt::format("request frame of {} bytes exceeds the mailbox record ({} bytes)",
                          request.size(), kRecordCapacity);
        return Status::kInvalidArgument;
    }
    Exchange x{w, options, Clock::now() + options.timeout, why};
    Status st = x.lock();
    if (st != Status::kOk) return st;
    st = x.run(request, reply);
    x.unlock();
    return st;
}

}  // namespace objif::mailbox
