// SPDX-License-Identifier: MIT
// Memory made ready before it is written (ready_pages.h).
#include "ready_pages.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <new>

namespace apci::run::detail {

namespace {

// MADV_POPULATE_WRITE (Linux 5.14; its number where the C library's headers lack it).
#ifdef MADV_POPULATE_WRITE
constexpr int kPopulateWrite = MADV_POPULATE_WRITE;
#else
constexpr int kPopulateWrite = 23;
#endif

std::uintptr_t page_size() noexcept {
    static const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
    return page;
}

}  // namespace

void Unmap::operator()(std::byte* p) const noexcept {
    ::munmap(p, bytes);
}

MappedBlock map_block(std::size_t bytes) {
    // cppcheck-suppress invalidFunctionArg ; fd -1 is what MAP_ANONYMOUS takes (mmap(2))
    void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    return MappedBlock(static_cast<std::byte*>(p), Unmap{bytes});
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
