// SPDX-License-Identifier: MIT
// The heap as the tests of flat memory see it: a program linked with heap_counter.cpp has the
// global operator new and delete replaced by ones that count every allocation and the bytes
// live, and keep the peak (atomic: the threads of apcictl run allocate too). Link it into a
// program of its own: the replacement holds for everything in that program.
#pragma once

#include <cstddef>

namespace test_support {

// Allocations made since the program started.
std::size_t heap_allocations() noexcept;
// Bytes allocated and not freed.
std::size_t heap_live_bytes() noexcept;
// The most bytes live at once since the last reset_heap_peak().
std::size_t heap_peak_bytes() noexcept;
// Starts a new peak from the bytes live now.
void reset_heap_peak() noexcept;

}  // namespace test_support
