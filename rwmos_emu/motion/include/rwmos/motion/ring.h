// SPDX-License-Identifier: MIT
// A bounded FIFO that keeps the newest entries: when full, a push drops the
// oldest and counts it as lost. Used for the per-cycle trace and the executed
// segment log, which the host drains at its own pace.
// The storage grows with the content waiting, up to the capacity (an empty ring
// starts again at its first slot, so a log drained as it fills keeps the storage
// it has): a board that never logs many segments never pays for the whole log (a
// fresh board is built per request in the frame fuzzer and per test), and a large
// trace capacity costs memory only once that many samples wait unread. It never
// reserves more than the capacity (a vector doubling on its own could take twice
// the capacity's memory, and then some while it moves).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rwmos::motion {

template <class T>
class Ring {
  public:
    explicit Ring(std::size_t capacity = 0) { set_capacity(capacity); }

    // Changes the capacity; drops the content (and resets the lost count).
    void set_capacity(std::size_t capacity) {
        std::vector<T>().swap(buf_);
        stored_ = 0;
        capacity_ = capacity;
        head_ = size_ = 0;
        lost_ = 0;
    }
    void clear() noexcept { head_ = size_ = 0; }

    void push(const T& v) {
        push_with([&v](T& slot) { slot = v; });
    }

    // As push(v) of the entry fill(T&) writes, in its place (no copy of a large entry); fill
    // must set every member. Not called when the capacity is 0 (the entry is lost).
    template <class Fill>
    void push_with(Fill&& fill) {
        if (capacity_ == 0) {
            ++lost_;
            return;
        }
        if (size_ == capacity_) {  // full (so buf_ has its whole capacity): the oldest goes
            fill(buf_[head_]);
            head_ = head_ + 1 == stored_ ? 0 : head_ + 1;
            ++lost_;
            return;
        }
        // An empty ring starts again at its first slot: a log drained as fast as it fills
        // reuses the storage it has (memory already touched) instead of growing to its
        // capacity.
        if (size_ == 0) head_ = 0;
        // While buf_ is shorter than the capacity the content has never
        // wrapped: it lies at [head_, head_ + size_) with head_ + size_ <= buf_.size().
        std::size_t slot = head_ + size_;
        if (slot == stored_ && stored_ < capacity_) {
            grow();
            buf_.emplace_back();
            ++stored_;
            fill(buf_.back());
        } else {
            if (slot >= stored_) slot -= stored_;
            fill(buf_[slot]);
        }
        ++size_;
    }

    // Moves up to out.size() entries, oldest first, into `out`; returns how many.
    std::size_t take(std::span<T> out) {
        const std::size_t n = out.size() < size_ ? out.size() : size_;
        for (std::size_t i = 0; i < n; ++i) {
            out[i] = buf_[head_];
            head_ = head_ + 1 == stored_ ? 0 : head_ + 1;
        }
        size_ -= n;
        return n;
    }
    // As take() of up to `max` entries, handed to visit(std::span<const T>) where they lie
    // instead of copied out: oldest first, in at most two runs of consecutive slots (the second
    // when the content wraps). Returns how many.
    template <class Visit>
    std::size_t take_runs(std::size_t max, Visit&& visit) {
        const std::size_t n = max < size_ ? max : size_;
        for (std::size_t left = n; left > 0;) {
            // head_ < stored_ while entries wait: the run ends at the storage's end at most.
            const std::size_t run = left < stored_ - head_ ? left : stored_ - head_;
            visit(std::span<const T>(buf_.data() + head_, run));
            head_ += run;
            if (head_ == stored_) head_ = 0;
            left -= run;
        }
        size_ -= n;
        return n;
    }

    // The i-th oldest entry (i < size()), without removing it.
    const T& at(std::size_t i) const noexcept {
        std::size_t slot = head_ + i;
        if (slot >= stored_) slot -= stored_;
        return buf_[slot];
    }

    std::size_t size() const noexcept { return size_; }
    std::size_t capacity() const noexcept { return capacity_; }
    // Entries the storage has room for now (never more than capacity()).
    std::size_t reserved() const noexcept { return buf_.capacity(); }
    bool empty() const noexcept { return size_ == 0; }
    // Entries dropped because the ring was full since the last set_capacity().
    std::uint64_t lost() const noexcept { return lost_; }

  private:
    // Room for one more entry, reserved by doubling as a vector would, but never beyond the
    // capacity.
    void grow() {
        if (buf_.size() < buf_.capacity()) return;
        const std::size_t doubled = buf_.empty() ? 1 : 2 * buf_.size();
        buf_.reserve(doubled < capacity_ ? doubled : capacity_);
    }

    std::vector<T> buf_;  // grows to capacity_, then wraps
    // buf_.size(), kept: the size of a vector of large elements is a division.
    std::size_t stored_ = 0;
    std::size_t capacity_ = 0;
    std::size_t head_ = 0;
    std::size_t size_ = 0;
    std::uint64_t lost_ = 0;
};

}  // namespace rwmos::motion
