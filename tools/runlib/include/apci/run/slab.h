// SPDX-License-Identifier: MIT
// Memory for the arrays a run makes once and keeps to its end (a pipeline's batches), carved in
// order from blocks of their own, and made ready as carved (docs/performance.md, "Huge pages
// for the memory written once" and "Ordinary pages again").
#pragma once

#include <cstddef>
#include <memory>
#include <type_traits>
#include <vector>

namespace apci::run::detail {

// A huge page of x86-64 and arm64 with 4 KiB pages (2 MiB): the size of the run library's
// blocks of memory written once (map_block, ready_pages.h).
inline constexpr std::size_t kHugePage = std::size_t{2} << 20;

// Blocks of kBlockBytes, each mapped on its own (map_block, ready_pages.h: aligned to a huge
// page, not advised to be backed by one), carved in order; what is carved is made ready
// (make_ready) before it is given. Nothing is given back before the slab goes, with its blocks.
class Slab {
  public:
    static constexpr std::size_t kBlockBytes = kHugePage;
    static constexpr std::size_t kAlign = 64;  // a cache line
    // The most one take() carves: more is left to the heap.
    static constexpr std::size_t kMostTaken = kBlockBytes / 4;

    Slab() = default;
    ~Slab();
    Slab(const Slab&) = delete;
    Slab& operator=(const Slab&) = delete;

    // What a take() of `bytes` carves: `bytes` rounded up to kAlign.
    static constexpr std::size_t carved(std::size_t bytes) noexcept {
        return (bytes + kAlign - 1) / kAlign * kAlign;
    }
    // carved(bytes), aligned to kAlign and made ready; nullptr where `bytes` is 0 or more than
    // kMostTaken. Throws std::bad_alloc where no block can be mapped.
    void* take(std::size_t bytes);
    // Whether p lies in one of its blocks.
    bool holds(const void* p) const noexcept;
    std::size_t blocks() const noexcept { return blocks_.size(); }

  private:
    std::vector<std::byte*> blocks_;
    std::size_t used_ = kBlockBytes;  // bytes carved from the last block
};

// A std::allocator that carves from a slab (none: the heap, as std::allocator), and takes from
// the heap what the slab does not carve. Deallocating memory of the slab does nothing: it goes
// with the slab, which must outlive the containers that use it.
template <class T>
class SlabAllocator {
  public:
    using value_type = T;
    using propagate_on_container_copy_assignment = std::true_type;
    using propagate_on_container_move_assignment = std::true_type;
    using propagate_on_container_swap = std::true_type;
    using is_always_equal = std::false_type;

    SlabAllocator() noexcept = default;
    explicit SlabAllocator(Slab* slab) noexcept : slab_(slab) {}
    template <class U>
    explicit SlabAllocator(const SlabAllocator<U>& other) noexcept : slab_(other.slab()) {}

    T* allocate(std::size_t n) {
        static_assert(alignof(T) <= Slab::kAlign);
        // (take() carves any such n: more than none, no more than kMostTaken.)
        if (slab_ != nullptr && n > 0 && n <= Slab::kMostTaken / sizeof(T))
            return static_cast<T*>(slab_->take(n * sizeof(T)));
        return std::allocator<T>().allocate(n);
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (slab_ != nullptr && slab_->holds(p)) return;
        std::allocator<T>().deallocate(p, n);
    }
    Slab* slab() const noexcept { return slab_; }

    template <class U>
    bool operator==(const SlabAllocator<U>& other) const noexcept {
        return slab_ == other.slab();
    }

  private:
    Slab* slab_ = nullptr;
};

}  // namespace apci::run::detail
