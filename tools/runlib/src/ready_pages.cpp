// SPDX-License-Identifier: MIT
// Memory made ready before it is written (ready_pages.h).
#include "ready_pages.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>

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

void make_ready(void* p, std::size_t bytes) noexcept {
    const std::uintptr_t page = page_size();
    const auto begin = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t first = (begin + page - 1) / page * page;
    const std::uintptr_t last = (begin + bytes) / page * page;
    if (p == nullptr || bytes == 0 || last <= first) return;
    (void)::madvise(reinterpret_cast<void*>(first), last - first, kPopulateWrite);
}

void ReadyAhead::advance(std::byte* base, std::size_t need, std::size_t end) noexcept {
    const std::size_t to = std::min(end, need + kStep);
    if (to <= ready_) return;
    // From the page the last step ended in (the block's: it holds base + ready_), which that
    // step left as it only partly covered it.
    const auto at = reinterpret_cast<std::uintptr_t>(base + ready_);
    auto* from = reinterpret_cast<std::byte*>(at / page_size() * page_size());
    make_ready(from, static_cast<std::size_t>(base + to - from));
    ready_ = to;
}

}  // namespace apci::run::detail
