// SPDX-License-Identifier: MIT
// A bounded single-producer/single-consumer ring of preallocated slots, handed over in place:
// the producer fills the slot acquire() gives it and commit()s it, the consumer reads the slot
// front() gives it and pop()s it. No slot is copied or allocated after construction, so the
// memory of a stream through it is bounded by its slots, however long the stream.
//
// The two indices are lock-free atomics (one writer each); a side that finds the ring full
// (producer) or empty (consumer) spins briefly, then sleeps on a condition variable until the
// other side has made enough slots ready for it (each side has its own count). The other side
// takes the mutex only to wake a sleeper, so a stream that never waits makes no system call.
// Either end can end the stream:
//
//   close()   the producer has no more: front() returns what is left, then nullptr;
//   cancel()  the consumer takes no more (it failed): acquire() returns nullptr from then on,
//             and what was committed and not taken is never read.
//
// flush() wakes a sleeping consumer for what is committed, however little (a producer that
// waits on the consumer's answer to its last slot).
//
// Used by PipelinedSink (pipeline.h) to hand batches of a run's events to its writer thread,
// and by ReadAhead (read_ahead.h) to hand the NC front end's events to the executor.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

namespace apci::run {

template <typename T>
class SpscRing {
  public:
    // `slots` default-constructed slots (at least 1). A side that went to sleep is woken when
    // `wake_after` slots are ready for it (at most half the slots; at least 1), or the stream
    // ends: one wakeup per several slots, not one per slot.
    explicit SpscRing(std::size_t slots, std::size_t wake_after = 1)
        : SpscRing(slots, wake_after, wake_after) {}
    // The same with a count of its own for each side: a producer asleep on a full ring is woken
    // when `producer_wakes_after` slots are free, a consumer asleep on an empty one when
    // `consumer_wakes_after` are committed (each at most half the slots; at least 1).
    SpscRing(std::size_t slots, std::size_t producer_wakes_after, std::size_t consumer_wakes_after)
        : slots_(slots < 1 ? 1 : slots),
          producer_wake_(clamp_wake(producer_wakes_after)),
          consumer_wake_(clamp_wake(consumer_wakes_after)) {}
    SpscRing(const SpscRing&) = delete;
    SpscRing& operator=(const SpscRing&) = delete;

    std::size_t capacity() const noexcept { return slots_.size(); }
    // Slots committed and not yet popped, as any thread sees them now (a third thread's view
    // may be a little behind either side's).
    std::size_t backlog() const noexcept {
        const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
        const std::uint64_t head = head_.load(std::memory_order_relaxed);
        return head > tail ? static_cast<std::size_t>(head - tail) : 0;
    }

    // ---- producer

    // The next free slot (as the consumer left it), waiting while every slot is committed and
    // not yet popped. nullptr once the consumer cancelled. Call commit() before the next
    // acquire().
    T* acquire() {
        const std::uint64_t head = head_.load(std::memory_order_relaxed);
        const auto room = [&](std::size_t want) {
            return cancelled_.load() || slots_.size() - (head - tail_.load()) >= want;
        };
        wait_for(room, producer_asleep_, producer_wake_, producer_slept_);
        if (cancelled_.load(std::memory_order_acquire)) return nullptr;
        return &slots_[head % slots_.size()];
    }
    // Hands the slot acquire() gave over to the consumer.
    void commit() {
        const std::uint64_t head = head_.load(std::memory_order_relaxed) + 1;
        head_.store(head, std::memory_order_seq_cst);
        if (consumer_asleep_.load() && head - tail_.load() >= consumer_wake_) wake();
    }
    // Wakes a consumer asleep on the ring for what is committed now, however little: for a
    // producer that waits on an answer to its last slot (a wakeup for `wake_after` slots would
    // never come).
    void flush() {
        flushed_.store(head_.load(std::memory_order_relaxed), std::memory_order_seq_cst);
        if (consumer_asleep_.load()) wake();
    }
    // No more slots will come (after the last commit()).
    void close() {
        closed_.store(true, std::memory_order_seq_cst);
        if (consumer_asleep_.load()) wake();
    }

    // ---- consumer

    // The oldest committed slot, waiting while there is none. nullptr once the producer closed
    // and every committed slot was popped.
    T* front() {
        const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
        const auto ready = [&](std::size_t want) {
            return head_.load() - tail >= want || closed_.load() || flushed_.load() > tail;
        };
        wait_for(ready, consumer_asleep_, consumer_wake_, consumer_slept_);
        if (head_.load(std::memory_order_acquire) == tail) return nullptr;  // closed, drained
        return &slots_[tail % slots_.size()];
    }
    // Gives the slot front() returned back to the producer.
    void pop() {
        const std::uint64_t tail = tail_.load(std::memory_order_relaxed) + 1;
        tail_.store(tail, std::memory_order_seq_cst);
        if (producer_asleep_.load() && slots_.size() - (head_.load() - tail) >= producer_wake_)
            wake();
    }
    // The consumer takes no more: a waiting or later acquire() returns nullptr.
    void cancel() {
        cancelled_.store(true, std::memory_order_seq_cst);
        if (producer_asleep_.load()) wake();
    }
    bool cancelled() const noexcept { return cancelled_.load(std::memory_order_acquire); }

    // Times a side went to sleep, both together and each (for tests and measurements).
    std::uint64_t sleeps() const noexcept { return producer_sleeps() + consumer_sleeps(); }
    std::uint64_t producer_sleeps() const noexcept {
        return producer_slept_.load(std::memory_order_relaxed);
    }
    std::uint64_t consumer_sleeps() const noexcept {
        return consumer_slept_.load(std::memory_order_relaxed);
    }

  private:
    static constexpr int kSpins = 64;

    std::size_t clamp_wake(std::size_t n) const noexcept {
        return std::max<std::size_t>(1, std::min(n, slots_.size() / 2));
    }

    // Spins while ready(1) is false, then sleeps until ready(wake) and counts the sleep in
    // `slept`. `ready` reads the other side's index with seq_cst loads: with the seq_cst store
    // of `sleeping` here and the seq_cst index stores and `sleeping` loads of commit(), pop(),
    // close() and cancel(), the other side either sees the sleeper (and wakes it, under the
    // mutex, once enough is ready) or moved before this side's last look: no wakeup is lost.
    template <typename Ready>
    void wait_for(const Ready& ready, std::atomic<bool>& sleeping, std::size_t wake,
                  std::atomic<std::uint64_t>& slept) {
        for (int i = 0; i < kSpins; ++i)
            if (ready(1)) return;
        std::unique_lock<std::mutex> lock(mutex_);
        sleeping.store(true, std::memory_order_seq_cst);
        slept.fetch_add(1, std::memory_order_relaxed);
        wakeup_.wait(lock, [&] { return ready(wake); });
        sleeping.store(false, std::memory_order_relaxed);
    }
    void wake() {
        { const std::lock_guard<std::mutex> lock(mutex_); }
        wakeup_.notify_all();
    }

    // The producer's line: what commit() writes, what both only read, and its sleeps.
    alignas(64) std::atomic<std::uint64_t> head_{0};  // slots committed
    std::atomic<bool> producer_asleep_{false};
    std::atomic<std::uint64_t> flushed_{0};  // flush(): the consumer wakes for slots below
    std::vector<T> slots_;
    std::size_t producer_wake_;  // free slots that wake a sleeping producer
    std::size_t consumer_wake_;  // committed slots that wake a sleeping consumer
    std::atomic<std::uint64_t> producer_slept_{0};
    // The consumer's line: what pop() writes, and what is written once or on a sleep.
    alignas(64) std::atomic<std::uint64_t> tail_{0};  // slots popped
    std::atomic<bool> consumer_asleep_{false};
    std::atomic<bool> closed_{false};
    std::atomic<bool> cancelled_{false};
    std::atomic<std::uint64_t> consumer_slept_{0};
    std::mutex mutex_;
    std::condition_variable wakeup_;
};

}  // namespace apci::run
