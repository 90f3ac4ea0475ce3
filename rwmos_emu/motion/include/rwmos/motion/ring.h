// SPDX-License-Identifier: MIT
// A bounded FIFO that keeps the newest entries: when full, a push drops the
// oldest and counts it as lost. Used for the per-cycle trace and the executed
// segment log, which the host drains at its own pace.
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
        buf_.assign(capacity, T{});
        head_ = size_ = 0;
        lost_ = 0;
    }
    void clear() noexcept { head_ = size_ = 0; }

    void push(const T& v) {
        if (buf_.empty()) {
            ++lost_;
            return;
        }
        std::size_t slot = head_ + size_;
        if (slot >= buf_.size()) slot -= buf_.size();
        buf_[slot] = v;
        if (size_ < buf_.size()) {
            ++size_;
        } else {
            head_ = head_ + 1 == buf_.size() ? 0 : head_ + 1;
            ++lost_;
        }
    }

    // Moves up to out.size() entries, oldest first, into `out`; returns how many.
    std::size_t take(std::span<T> out) {
        const std::size_t n = out.size() < size_ ? out.size() : size_;
        for (std::size_t i = 0; i < n; ++i) {
            out[i] = buf_[head_];
            head_ = head_ + 1 == buf_.size() ? 0 : head_ + 1;
        }
        size_ -= n;
        return n;
    }
    // The i-th oldest entry (i < size()), without removing it.
    const T& at(std::size_t i) const noexcept {
        std::size_t slot = head_ + i;
        if (slot >= buf_.size()) slot -= buf_.size();
        return buf_[slot];
    }

    std::size_t size() const noexcept { return size_; }
    std::size_t capacity() const noexcept { return buf_.size(); }
    bool empty() const noexcept { return size_ == 0; }
    // Entries dropped because the ring was full since the last set_capacity().
    std::uint64_t lost() const noexcept { return lost_; }

  private:
    std::vector<T> buf_;
    std::size_t head_ = 0;
    std::size_t size_ = 0;
    std::uint64_t lost_ = 0;
};

}  // namespace rwmos::motion
