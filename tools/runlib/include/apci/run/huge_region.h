// SPDX-License-Identifier: MIT
// Memory for data written once as a stream (the calls the self-approach check holds back, the
// segments of a pipeline's batches): mapped on its own, aligned to 2 MiB, its whole huge pages
// offered to the kernel's transparent huge pages (madvise), so that tens of megabytes written
// once take a page fault per 2 MiB instead of one per 4 KiB (docs/performance.md, "Page
// faults"). Where the kernel gives no huge page (transparent huge pages off) the region is
// ordinary memory, zeroed and touched page by page as any other.
#pragma once

#include <cstddef>

namespace apci::run {

class HugeRegion {
  public:
    static constexpr std::size_t kHugePage = std::size_t{2} << 20;

    HugeRegion() = default;
    // At least `bytes` (rounded up to whole huge pages), zeroed; throws std::bad_alloc where
    // the mapping fails. 0 bytes: no memory.
    explicit HugeRegion(std::size_t bytes);
    HugeRegion(HugeRegion&& other) noexcept;
    HugeRegion& operator=(HugeRegion&& other) noexcept;
    HugeRegion(const HugeRegion&) = delete;
    HugeRegion& operator=(const HugeRegion&) = delete;
    ~HugeRegion();

    void* data() const noexcept { return data_; }
    std::size_t size() const noexcept { return size_; }

  private:
    void* data_ = nullptr;
    std::size_t size_ = 0;
};

}  // namespace apci::run
