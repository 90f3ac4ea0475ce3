// SPDX-License-Identifier: MIT
// Memory made ready before it is written (ready_pages.h).
#include "ready_pages.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <new>

#include "apci/run/slab.h"

namespace apci::run::detail {

namespace {

// MADV_POPULATE_WRITE (Linux 5.14; its number where the C library's headers lack it).
#ifdef MADV_POPULATE_WRITE
constexpr int kPopulateWrite = MADV_POPULATE_WRITE;
#else
constexpr int kPopulateWrite = 23;
#endif

// `bytes` of anonymous private memory, mapped; throws std::bad_alloc where the kernel maps none.
std::byte* map_anonymous(std::size_t bytes) {
    constexpr int kProtection = PROT_READ | PROT_WRITE;
    constexpr int kFlags = MAP_PRIVATE | MAP_ANONYMOUS;
    // cppcheck-suppress invalidFunctionArg ; fd -1 is what MAP_ANONYMOUS takes (mmap(2))
    void* p = ::mmap(nullptr, bytes, kProtection, kFlags, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    return static_cast<std::byte*>(p);
}

std::uintptr_t page_size() noexcept {
    static const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
    return page;
}

}  // namespace

void Unmap::operator()(std::byte* p) const noexcept {
    ::munmap(p, bytes);
}

MappedBlock map_block(std::size_t bytes) {
    if (bytes % kHugePage != 0) return MappedBlock(map_anonymous(bytes), Unmap{bytes});
    // A huge page's more, to cut an aligned block from: the rest is unmapped again.
    std::byte* const mapped = map_anonymous(bytes + kHugePage);
    const std::size_t before =
        (kHugePage - reinterpret_cast<std::uintptr_t>(mapped) % kHugePage) % kHugePage;
    if (before > 0) ::munmap(mapped, before);
    ::munmap(mapped + before + bytes, kHugePage - before);  // never none: before < kHugePage
    std::byte* const block = mapped + before;
    // No MADV_HUGEPAGE: the system's policy decides (docs/performance.md, "Ordinary pages
    // again").
    return MappedBlock(block, Unmap{bytes});
}

void make_ready(void* p, std::size_t bytes) noexcept {
    if (p == nullptr || bytes == 0) return;
    const std::uintptr_t page = page_size();
    const auto begin = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t first = (begin + page - 1) / page * page;
    const std::uintptr_t last = (begin + bytes) / page * page;
    if (last <= first) return;
    (void)::madvise(static_cast<std::byte*>(p) + (first - begin), last - first, kPopulateWrite);
}

std::byte* Chunks::add(std::size_t bytes) {
    starts_.reserve(starts_.size() + 1);  // room first: a chunk had is held
    if (slab_ != nullptr) {
        auto* const p = static_cast<std::byte*>(slab_->take(bytes));
        if (p == nullptr) throw std::bad_alloc();  // more than a slab carves
        starts_.push_back(p);
    } else {
        mapped_.reserve(mapped_.size() + 1);
        mapped_.push_back(map_block(bytes));
        starts_.push_back(mapped_.back().get());
    }
    return starts_.back();
}

void Chunks::swap(Chunks& other) noexcept {
    std::swap(slab_, other.slab_);
    starts_.swap(other.starts_);
    mapped_.swap(other.mapped_);
}

Slab::~Slab() {
    for (std::byte* b : blocks_) Unmap{kBlockBytes}(b);
}

void* Slab::take(std::size_t bytes) {
    if (bytes == 0 || bytes > kMostTaken) return nullptr;
    bytes = carved(bytes);
    if (used_ + bytes > kBlockBytes) {
        blocks_.reserve(blocks_.size() + 1);  // before the mapping, which would leak on a throw
        blocks_.push_back(map_block(kBlockBytes).release());
        used_ = 0;
    }
    std::byte* const p = blocks_.back() + used_;
    used_ += bytes;
    make_ready(p, bytes);
    return p;
}

bool Slab::holds(const void* p) const noexcept {
    const auto* b = static_cast<const std::byte*>(p);
    return std::any_of(blocks_.begin(), blocks_.end(), [b](const std::byte* block) {
        return std::less_equal<>()(block, b) && std::less<>()(b, block + kBlockBytes);
    });
}

void ReadyAhead::advance(std::byte* base, std::size_t need, std::size_t end) noexcept {
    const std::size_t to = std::min(end, need + kStep);
    if (to <= ready_) return;
    // From the start of the page the last step ended in, which that step left as it only
    // partly covered it (not before the block: a page the block starts within is left to fault).
    const auto at = reinterpret_cast<std::uintptr_t>(base + ready_);
    std::byte* from = base + ready_ - std::min<std::size_t>(ready_, at % page_size());
    make_ready(from, static_cast<std::size_t>(base + to - from));
    ready_ = to;
}

}  // namespace apci::run::detail
