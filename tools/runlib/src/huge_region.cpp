// SPDX-License-Identifier: MIT
#include "apci/run/huge_region.h"

#include <sys/mman.h>

#include <cstdint>
#include <new>
#include <utility>

namespace apci::run {

HugeRegion::HugeRegion(std::size_t bytes) {
    if (bytes == 0) return;
    if (bytes > (std::size_t{1} << 40)) throw std::bad_alloc();
    const std::size_t size = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    // A huge page backs only an aligned range: one page more is mapped, and what lies outside
    // the aligned range given back.
    const std::size_t mapped = size + kHugePage;
    void* p = ::mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t aligned = (at + kHugePage - 1) & ~(std::uintptr_t{kHugePage} - 1);
    if (aligned > at) ::munmap(p, aligned - at);
    if (const std::uintptr_t tail = at + mapped - (aligned + size); tail > 0)
        ::munmap(reinterpret_cast<void*>(aligned + size), tail);
    data_ = reinterpret_cast<void*>(aligned);
    size_ = size;
    // The whole huge pages the caller asked for, as a hint (refused: 4 KiB pages). The rest, a
    // part of a huge page, stays in 4 KiB pages, touched as used: a huge page is resident
    // whole once touched.
    if (const std::size_t whole = bytes / kHugePage * kHugePage; whole > 0)
        ::madvise(data_, whole, MADV_HUGEPAGE);
}

HugeRegion::HugeRegion(HugeRegion&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}

HugeRegion& HugeRegion::operator=(HugeRegion&& other) noexcept {
    if (this != &other) {
        if (data_ != nullptr) ::munmap(data_, size_);
        data_ = std::exchange(other.data_, nullptr);
        size_ = std::exchange(other.size_, 0);
    }
    return *this;
}

HugeRegion::~HugeRegion() {
    if (data_ != nullptr) ::munmap(data_, size_);
}

}  // namespace apci::run
