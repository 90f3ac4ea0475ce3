// SPDX-License-Identifier: MIT
#include "objif/mapping_guard.h"

#include <signal.h>
#include <sys/mman.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdint>

namespace objif {
namespace {

// One guarded region. The handler reads begin, then end; a region is
// published end first and withdrawn begin first, so the handler never sees
// a begin without its end.
struct Region {
    std::atomic<bool> used{false};
    std::atomic<std::uint8_t*> begin{nullptr};
    std::atomic<std::uint8_t*> end{nullptr};
    std::atomic<bool> lost{false};
};
static_assert(std::atomic<std::uint8_t*>::is_always_lock_free &&
                  std::atomic<bool>::is_always_lock_free,
              "the signal handler reads the table without locks");

std::array<Region, kMaxGuardedRegions> regions;
struct sigaction previous {};

// Hands a fault that is not ours to the handler installed before ours; the
// default one (or an ignored SIGBUS) is restored, so the access faults again
// and the process dies as it would have without the guard.
void pass_on(int sig, siginfo_t* info, void* context) {
    if ((previous.sa_flags & SA_SIGINFO) != 0 && previous.sa_sigaction != nullptr) {
        previous.sa_sigaction(sig, info, context);
        return;
    }
    if (previous.sa_handler != SIG_DFL && previous.sa_handler != SIG_IGN) {
        previous.sa_handler(sig);
        return;
    }
    struct sigaction fallback {};
    fallback.sa_handler = SIG_DFL;
    sigemptyset(&fallback.sa_mask);
    ::sigaction(SIGBUS, &fallback, nullptr);
    // Sent with kill() rather than raised by an access: send it again, to the default.
    if (info->si_code <= 0) ::raise(SIGBUS);
}

void on_sigbus(int sig, siginfo_t* info, void* context) {
    const int saved_errno = errno;
    const auto address = reinterpret_cast<std::uintptr_t>(info->si_addr);
    if (info->si_code > 0) {
        for (Region& r : regions) {
            std::uint8_t* begin = r.begin.load(std::memory_order_acquire);
            if (begin == nullptr || address < reinterpret_cast<std::uintptr_t>(begin)) continue;
            const std::uint8_t* end = r.end.load(std::memory_order_acquire);
            if (address >= reinterpret_cast<std::uintptr_t>(end)) continue;
            // Zeros in place of the pages the file no longer has; the access is retried on them.
            const auto length = static_cast<std::size_t>(end - begin);
            constexpr int kFlags = MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED;
            // cppcheck-suppress invalidFunctionArg ; fd -1 is what MAP_ANONYMOUS takes (mmap(2))
            void* zeros = ::mmap(begin, length, PROT_READ | PROT_WRITE, kFlags, -1, 0);
            if (zeros == MAP_FAILED) break;
            r.lost.store(true, std::memory_order_release);
            errno = saved_errno;
            return;
        }
    }
    pass_on(sig, info, context);
    errno = saved_errno;
}

bool install_handler() noexcept {
    static const bool installed = [] {
        if (::sigaction(SIGBUS, nullptr, &previous) != 0) return false;
        struct sigaction ours {};
        ours.sa_sigaction = on_sigbus;
        ours.sa_flags = SA_SIGINFO | SA_ONSTACK;
        sigemptyset(&ours.sa_mask);
        return ::sigaction(SIGBUS, &ours, nullptr) == 0;
    }();
    return installed;
}

}  // namespace

MappingGuard::MappingGuard(void* base, std::size_t size) noexcept {
    if (base == nullptr || size == 0 || !install_handler()) return;
    auto* begin = static_cast<std::uint8_t*>(base);
    for (std::size_t i = 0; i < regions.size(); ++i) {
        Region& r = regions[i];
        bool free = false;
        if (!r.used.compare_exchange_strong(free, true, std::memory_order_acq_rel)) continue;
        r.lost.store(false, std::memory_order_relaxed);
        r.end.store(begin + size, std::memory_order_release);
        r.begin.store(begin, std::memory_order_release);
        slot_ = static_cast<int>(i);
        return;
    }
}

MappingGuard::~MappingGuard() {
    if (slot_ < 0) return;
    Region& r = regions[static_cast<std::size_t>(slot_)];
    r.begin.store(nullptr, std::memory_order_release);
    r.end.store(nullptr, std::memory_order_release);
    r.used.store(false, std::memory_order_release);
}

bool MappingGuard::lost() const noexcept {
    return slot_ >= 0 &&
           regions[static_cast<std::size_t>(slot_)].lost.load(std::memory_order_acquire);
}

}  // namespace objif
