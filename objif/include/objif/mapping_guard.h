// SPDX-License-Identifier: MIT
// A shared file mapping that survives the file being shrunk under it.
//
// Anyone who may write a file that this process maps MAP_SHARED (the
// emulator's dual-port RAM file, docs/dpram.md) can truncate it; every access
// to the pages past the new end then raises SIGBUS, which kills the process.
// A guarded region does not: a SIGBUS handler (installed once, on the first
// guard) finds the region that holds the faulting address, puts private
// zero-filled memory in place of the whole region (mmap MAP_FIXED, the same
// address range), flags the region lost and returns, so the access is
// retried on the zeros. The owner asks lost() and turns it into an error;
// its accesses cost nothing more than before. A fault outside every guarded
// region goes to the handler that was installed before (the default one
// kills the process as before).
//
// The regions are a fixed table read by the handler without locks: at most
// kMaxGuardedRegions at a time. A program that installs its own SIGBUS handler
// after the first guard replaces this one.
#pragma once

#include <cstddef>

namespace objif {

inline constexpr std::size_t kMaxGuardedRegions = 64;

class MappingGuard {
  public:
    // Guards [base, base + size), which must be a whole mapping made with
    // mmap (page-aligned base). Unguarded (guarded() false) if the table is
    // full or the handler cannot be installed.
    MappingGuard(void* base, std::size_t size) noexcept;
    // Unguards the region; call before unmapping it.
    ~MappingGuard();
    MappingGuard(const MappingGuard&) = delete;
    MappingGuard& operator=(const MappingGuard&) = delete;

    bool guarded() const noexcept { return slot_ >= 0; }
    // Whether a bus error hit the region (the file shrank under it): it now
    // reads as zeros and no longer reaches the file.
    bool lost() const noexcept;

  private:
    int slot_ = -1;
};

}  // namespace objif
