// SPDX-License-Identifier: MIT
// An unbounded FIFO on one circular buffer: push at the back, pop at either end, index from
// the front. It grows (doubling) while the queue is longer than ever before and then reuses its
// storage, so a queue whose length stays bounded (the executor's moves, the spooler's pending
// profiles, both bounded by the spooler's capacity) allocates nothing per element: a
// std::deque frees and allocates a node every few elements as the queue slides along.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace rwmos::motion {

template <class T>
class Fifo {
  public:
    std::size_t size() const noexcept { return size_; }
    bool empty() const noexcept { return size_ == 0; }
    // The elements it holds without allocating.
    std::size_t capacity() const noexcept { return buf_.empty() ? 0 : mask_ + 1; }
    void clear() noexcept { head_ = size_ = 0; }

    void push_back(const T& v) {
        if (size_ == capacity()) grow();
        buf_[slot(size_)] = v;
        ++size_;
    }
    // A new element at the back, left as it was for the caller to write (no copy of a T).
    T& push_back_slot() {
        if (size_ == capacity()) grow();
        return buf_[slot(size_++)];
    }
    void pop_front() noexcept {
        head_ = slot(1);
        --size_;
    }
    void pop_back() noexcept { --size_; }

    T& front() noexcept { return buf_[head_]; }
    const T& front() const noexcept { return buf_[head_]; }
    T& back() noexcept { return buf_[slot(size_ - 1)]; }
    const T& back() const noexcept { return buf_[slot(size_ - 1)]; }
    T& operator[](std::size_t i) noexcept { return buf_[slot(i)]; }
    const T& operator[](std::size_t i) const noexcept { return buf_[slot(i)]; }

    // Front to back, for range-for.
    class const_iterator {
      public:
        const_iterator(const Fifo* q, std::size_t i) noexcept : q_(q), i_(i) {}
        const T& operator*() const noexcept { return (*q_)[i_]; }
        const_iterator& operator++() noexcept {
            ++i_;
            return *this;
        }
        bool operator==(const const_iterator& o) const noexcept { return i_ == o.i_; }

      private:
        const Fifo* q_;
        std::size_t i_;
    };
    const_iterator begin() const noexcept { return {this, 0}; }
    const_iterator end() const noexcept { return {this, size_}; }

  private:
    // The storage index of the i-th element from the front (the capacity is a power of two).
    // (mask_, not buf_.size() - 1: the size of a vector of large elements is a division.)
    std::size_t slot(std::size_t i) const noexcept { return (head_ + i) & mask_; }
    void grow() {
        std::vector<T> bigger(buf_.empty() ? 16 : buf_.size() * 2);
        for (std::size_t i = 0; i < size_; ++i) bigger[i] = std::move(buf_[slot(i)]);
        buf_.swap(bigger);
        head_ = 0;
        mask_ = buf_.size() - 1;
    }

    std::vector<T> buf_;  // size: 0 or a power of two
    std::size_t mask_ = 0;  // buf_.size() - 1 once it has storage
    std::size_t head_ = 0;
    std::size_t size_ = 0;
};

}  // namespace rwmos::motion
