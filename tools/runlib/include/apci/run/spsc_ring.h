// SPDX-License-Identifier: MIT
// A bounded single-producer/single-consumer ring of preallocated slots, handed over in place:
// the producer fills the slot acquire() gives it and commit()s it, the consumer reads the slot
// front() gives it and pop()s it. No slot is copied or allocated after construction, so the
// memory of a stream through it is bounded by its slots, however long the stream.
//
// The two indices are lock-free atomics (one writer each); a side that finds the ring full
// (producer) or empty (consumer) spins briefly, then sleeps on a condition variable until the
// other side moves. The other side takes the mutex only when someone sleeps, so a stream that
// never waits makes no system call. Either end can end the stream:
//
//   close()   the producer has no more: front() returns what is left, then nullptr;
//   cancel()  the consumer takes no more (it failed): acquire() returns nullptr from then on,
//             and what was committed and not taken is never read.
//
// Used by PipelinedSink (pipeline.h) to hand batches of a run's events to its writer thread.
#pragma once

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
    // `slots` default-constructed slots (at least 1).
    explicit SpscRing(std::size_t slots) : slots_(slots < 1 ? 1 : slots) {}
    SpscRing(const SpscRing&) = delete;
    SpscRing& operator=(const SpscRing&) = delete;

    std::size_t capacity() const noexcept { return slots_.size(); }

    // ---- producer

    // The next free slot (as the consumer left it), waiting while every slot is committed and
    // not yet popped. nullptr once the consumer cancelled. Call commit() before the next
    // acquire().
    T* acquire() {
        const std::uint64_t head = head_.load(std::memory_order_relaxed);
        const auto room = [&] { return cancelled_.load() || head - tail_.load() < slots_.size(); };
        wait_for(room);
        if (cancelled_.load(std::memory_order_acquire)) return nullptr;
        return &slots_[head % slots_.size()];
    }
    // Hands the slot acquire() gave over to the consumer.
    void commit() {
        head_.store(head_.load(std::memory_order_relaxed) + 1, std::memory_order_seq_cst);
        wake();
    }
    // No more slots will come (after the last commit()).
    void close() {
        closed_.store(true, std::memory_order_seq_cst);
        wake();
    }

    // ---- consumer

    // The oldest committed slot, waiting while there is none. nullptr once the producer closed
    // and every committed slot was popped.
    T* front() {
        const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
        const auto ready = [&] { return head_.load() != tail || closed_.load(); };
        wait_for(ready);
        if (head_.load(std::memory_order_acquire) == tail) return nullptr;  // closed, drained
        return &slots_[tail % slots_.size()];
    }
    // Gives the slot front() returned back to the producer.
    void pop() {
        tail_.store(tail_.load(std::memory_order_relaxed) + 1, std::memory_order_seq_cst);
        wake();
    }
    // The consumer takes no more: a waiting or later acquire() returns nullptr.
    void cancel() {
        cancelled_.store(true, std::memory_order_seq_cst);
        wake();
    }
    bool cancelled() const noexcept { return cancelled_.load(std::memory_order_acquire); }

    // Times a side went to sleep (for tests and measurements).
    std::uint64_t sleeps() const noexcept { return sleeps_.load(std::memory_order_relaxed); }

  private:
    static constexpr int kSpins = 64;

    // `ready` reads the other side's state with seq_cst loads: with the seq_cst count of
    // sleepers below and the seq_cst stores in commit(), pop(), close() and cancel(), no wakeup
    // is lost.
    template <typename Ready>
    void wait_for(const Ready& ready) {
        for (int i = 0; i < kSpins; ++i)
            if (ready()) return;
        std::unique_lock<std::mutex> lock(mutex_);
        // Announced before the last look: the other side either sees a sleeper (and wakes it
        // under the mutex) or made its move before that look (seq_cst orders the two).
        sleepers_.fetch_add(1, std::memory_order_seq_cst);
        sleeps_.fetch_add(1, std::memory_order_relaxed);
        wakeup_.wait(lock, ready);
        sleepers_.fetch_sub(1, std::memory_order_relaxed);
    }
    void wake() {
        if (sleepers_.load(std::memory_order_seq_cst) == 0) return;
        { const std::lock_guard<std::mutex> lock(mutex_); }
        wakeup_.notify_all();
    }

    std::vector<T> slots_;
    // Producer and consumer counts on lines of their own.
    alignas(64) std::atomic<std::uint64_t> head_{0};  // slots committed
    alignas(64) std::atomic<std::uint64_t> tail_{0};  // slots popped
    alignas(64) std::atomic<bool> closed_{false};
    std::atomic<bool> cancelled_{false};
    std::atomic<int> sleepers_{0};
    std::atomic<std::uint64_t> sleeps_{0};
    std::mutex mutex_;
    std::condition_variable wakeup_;
};

}  // namespace apci::run
