// SPDX-License-Identifier: MIT
// Memory a thread is about to write from start to end, made ready in one call rather than one
// page fault per page (docs/performance.md "Memory made ready before it is written").
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "apci/run/slab.h"  // kHugePage

namespace apci::run::detail {

// A block of memory mapped on its own (anonymous, private, page-aligned), unmapped with it: a
// chunk made ready step by step takes only the pages it is given, none the C library had kept.
struct Unmap {
    std::size_t bytes = 0;
    void operator()(std::byte* p) const noexcept;
};
using MappedBlock = std::unique_ptr<std::byte[], Unmap>;
// `bytes` (at least 1) mapped; throws std::bad_alloc where the kernel maps nothing. A block of
// a whole number of huge pages is aligned to one, so that where the system's policy backs all
// anonymous memory with huge pages (transparent huge pages "always") it is whole huge pages; it
// is not advised either way (no MADV_HUGEPAGE): under the usual policy ("madvise") it has
// ordinary pages, which cost a run less on a virtual machine whose host backs a fresh huge page
// 4 KiB at a time (docs/performance.md, "Ordinary pages again").
MappedBlock map_block(std::size_t bytes);

// Makes the whole pages within [p, p + bytes) of the process's private memory (mapped
// anonymously, or the C library's heap) present and writable in one call
// (madvise(MADV_POPULATE_WRITE)): what is there stays as it is; pages present already are
// passed over. The pages the range only partly covers are left to fault as before. Where the
// kernel cannot (before Linux 5.14) or the memory is short, it does nothing: the writes fault
// the pages in as they would have.
void make_ready(void* p, std::size_t bytes) noexcept;

// A block written once from its start towards its end (a chunk of records or of items), made
// ready kStep bytes ahead of its writer: one make_ready() call per step where the writes would
// take 64 page faults; a block used only in part makes at most one step more ready than it uses.
class ReadyAhead {
  public:
    static constexpr std::size_t kStep = std::size_t{256} << 10;

    // Before `size` bytes are written at offset `at` of the block at `base` (`end` bytes long).
    void before_write(std::byte* base, std::size_t at, std::size_t size, std::size_t end) noexcept {
        if (at + size > ready_) advance(base, at + size, end);
    }

  private:
    void advance(std::byte* base, std::size_t need, std::size_t end) noexcept;
    std::size_t ready_ = 0;  // the block's first bytes made ready
};

// The chunks of an array kept in order (HeldCalls, ChunkedArray): each mapped on its own
// (map_block, to be made ready as it is written: ReadyAhead), or carved from a slab its holder
// shares with its other arrays (made ready as carved: fewer blocks taken in part).
class Chunks {
  public:
    Chunks() = default;
    // Carved from `memory`, which must outlive the chunks' use.
    explicit Chunks(Slab& memory) noexcept : slab_(&memory) {}

    // A new chunk of `bytes` (from a slab at most Slab::kMostTaken) at the end; throws
    // std::bad_alloc, changing nothing, where none can be had.
    std::byte* add(std::size_t bytes);
    std::byte* operator[](std::size_t i) const noexcept { return starts_[i]; }
    std::byte* back() const noexcept { return starts_.back(); }
    std::size_t size() const noexcept { return starts_.size(); }
    bool empty() const noexcept { return starts_.empty(); }
    // Whether the chunks are carved from a slab, ready when added.
    bool carved() const noexcept { return slab_ != nullptr; }
    void swap(Chunks& other) noexcept;

  private:
    Slab* slab_ = nullptr;
    std::vector<std::byte*> starts_;   // where each chunk starts
    std::vector<MappedBlock> mapped_;  // the chunks mapped on their own
};

}  // namespace apci::run::detail
