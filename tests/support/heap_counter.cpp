// SPDX-License-Identifier: MIT
// The counting operator new and delete of heap_counter.h.
#include "heap_counter.h"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {

std::atomic<std::size_t> g_allocations{0};
std::atomic<std::size_t> g_live_bytes{0};
std::atomic<std::size_t> g_peak_bytes{0};

void* counted_alloc(std::size_t n) {
    // Room in front for the size, so delete can keep the live byte count.
    auto* p = static_cast<std::size_t*>(std::malloc(n + sizeof(std::max_align_t)));
    if (p == nullptr) throw std::bad_alloc();
    *p = n;
    g_allocations.fetch_add(1);
    const std::size_t live = g_live_bytes.fetch_add(n) + n;
    std::size_t peak = g_peak_bytes.load();
    while (live > peak && !g_peak_bytes.compare_exchange_weak(peak, live)) {
    }
    return reinterpret_cast<char*>(p) + sizeof(std::max_align_t);
}

void counted_free(void* q) noexcept {
    if (q == nullptr) return;
    auto* p = reinterpret_cast<std::size_t*>(static_cast<char*>(q) - sizeof(std::max_align_t));
    g_live_bytes.fetch_sub(*p);
    std::free(p);
}

}  // namespace

namespace test_support {

std::size_t heap_allocations() noexcept { return g_allocations.load(); }
std::size_t heap_live_bytes() noexcept { return g_live_bytes.load(); }
std::size_t heap_peak_bytes() noexcept { return g_peak_bytes.load(); }
void reset_heap_peak() noexcept { g_peak_bytes.store(g_live_bytes.load()); }

}  // namespace test_support

void* operator new(std::size_t n) { return counted_alloc(n); }
void* operator new[](std::size_t n) { return counted_alloc(n); }
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }
