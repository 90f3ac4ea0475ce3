// SPDX-License-Identifier: MIT
// Items kept in order in chunks allocated once each: the self-approach check's hold keeps its
// stretches' zones so (self_approach.cpp, docs/performance.md "Fewer allocations and faults").
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

#include "ready_pages.h"

namespace apci::run::detail {

// Items kept in order, in chunks of ChunkBytes (2 MiB) each mapped once (made ready a step
// ahead of the items: ReadyAhead), or carved from a slab: keeping one never allocates but at a
// chunk's start (a std::deque's chunk holds a few), nor moves the items before it (as a vector's
// growth would). T has nothing to destroy.
template <class T, std::size_t ChunkBytes = kHugePage>
class ChunkedArray {
    static_assert(std::is_trivially_destructible_v<T>);
    static_assert(alignof(T) <= alignof(std::max_align_t));  // a mapping is page-aligned

  public:
    static constexpr std::size_t kPerChunk = ChunkBytes / sizeof(T);
    static_assert(kPerChunk >= 1, "a chunk holds at least one item");

    // Chunks mapped on their own.
    ChunkedArray() = default;
    // Chunks carved from `memory` (made ready as carved), which must outlive the array: a
    // holder's memory shared with its other arrays, so that each takes no block of its own.
    explicit ChunkedArray(Slab& memory) : chunks_(memory) {
        static_assert(ChunkBytes <= Slab::kMostTaken, "a slab carves a chunk of this size");
    }
    ChunkedArray(const ChunkedArray&) = delete;
    ChunkedArray& operator=(const ChunkedArray&) = delete;

    // A new item at the end, value-initialised.
    T& emplace_back() {
        if (size_ == chunks_.size() * kPerChunk) {
            chunks_.add(ChunkBytes);  // mapped on its own (ready_pages.h)
            if (!chunks_.carved()) ready_ = ReadyAhead{};
        }
        if (!chunks_.carved())
            ready_.before_write(chunks_.back(), size_ % kPerChunk * sizeof(T), sizeof(T),
                                kPerChunk * sizeof(T));
        T* const slot = at(size_);
        ::new (static_cast<void*>(slot)) T{};
        ++size_;
        return *slot;
    }
    std::size_t size() const noexcept { return size_; }
    bool empty() const noexcept { return size_ == 0; }
    T& operator[](std::size_t i) noexcept { return *at(i); }

  private:
    T* at(std::size_t i) const noexcept {
        return std::launder(reinterpret_cast<T*>(chunks_[i / kPerChunk]) + i % kPerChunk);
    }
    Chunks chunks_;  // mapped, or carved from a slab (ready_pages.h)
    // The last mapped chunk's pages, made ready ahead of its items (ready_pages.h). A slab's
    // chunks are ready when carved.
    ReadyAhead ready_;
    std::size_t size_ = 0;
};

}  // namespace apci::run::detail
