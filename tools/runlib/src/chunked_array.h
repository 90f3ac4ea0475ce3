// SPDX-License-Identifier: MIT
// Items kept in order in chunks allocated once each: the calls the self-approach check holds
// back and its stretches' zones (self_approach.cpp, docs/performance.md "Fewer allocations and
// faults").
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace apci::run::detail {

// Items kept in order, in chunks of ChunkBytes (2 MiB) each allocated once (untouched until
// used) and kept when the array is cleared. The calls held back are written one after the
// other and read once, if at all: keeping one never allocates but at a chunk's start (a
// std::deque's chunk holds four of them), nor moves the items before it (as a vector's growth
// would). T has nothing to destroy.
template <class T, std::size_t ChunkBytes = (std::size_t{2} << 20)>
class ChunkedArray {
    static_assert(std::is_trivially_destructible_v<T>);
    static_assert(alignof(T) <= __STDCPP_DEFAULT_NEW_ALIGNMENT__);

  public:
    static constexpr std::size_t kPerChunk = ChunkBytes / sizeof(T);
    static_assert(kPerChunk >= 1, "a chunk holds at least one item");

    // A new item at the end, value-initialised.
    T& emplace_back() {
        if (size_ == chunks_.size() * kPerChunk)
            chunks_.push_back(std::make_unique_for_overwrite<std::byte[]>(kPerChunk * sizeof(T)));
        T* const slot = at(size_);
        ::new (static_cast<void*>(slot)) T{};
        ++size_;
        return *slot;
    }
    void push_back(const T& t) { emplace_back() = t; }
    std::size_t size() const noexcept { return size_; }
    bool empty() const noexcept { return size_ == 0; }
    T& operator[](std::size_t i) noexcept { return *at(i); }
    // Empties it; its chunks stay for the next items.
    void clear() noexcept { size_ = 0; }
    void swap(ChunkedArray& other) noexcept {
        chunks_.swap(other.chunks_);
        std::swap(size_, other.size_);
    }
    template <class F>
    void for_each(F&& f) const {
        for (std::size_t i = 0; i < size_; ++i) f(*at(i));
    }

  private:
    T* at(std::size_t i) const noexcept {
        return std::launder(reinterpret_cast<T*>(chunks_[i / kPerChunk].get()) + i % kPerChunk);
    }
    std::vector<std::unique_ptr<std::byte[]>> chunks_;
    std::size_t size_ = 0;
};

}  // namespace apci::run::detail
