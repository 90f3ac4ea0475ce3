// SPDX-License-Identifier: MIT
// How long a waiting side spins before it sleeps: the dual-port RAM mailbox
// (objif/mailbox.h) on both sides, the daemon socket's client and the daemon
// (docs/performance.md, "Transports").
#pragma once

#include <algorithm>
#include <chrono>

namespace objif {

// A spin budget that follows how the other side behaves. After each wait the
// waiter tells how long it waited for the change, spinning and sleeping
// together: a change that came within `longest` would have been caught by a
// long enough spin, so the budget grows (doubles, and covers twice that wait,
// up to `longest`); a longer wait halves it (down to `shortest`). While the
// other side runs on another core and answers in microseconds, the waiter
// spins and round trips stay in the microsecond range; on a loaded machine,
// or with a peer that answers slowly, spinning would only take CPU away, so
// the waiter soon sleeps at once and is woken like any blocked process. The
// budget learns from the whole wait, not from whether the spin caught the
// change: a budget that had shrunk below the peer's answer time would never
// catch it again and never grow back.
class AdaptiveSpin {
  public:
    AdaptiveSpin(std::chrono::nanoseconds shortest, std::chrono::nanoseconds longest) noexcept
        : shortest_(shortest), longest_(longest), budget_(longest) {}
    std::chrono::nanoseconds budget() const noexcept { return budget_; }
    std::chrono::nanoseconds shortest() const noexcept { return shortest_; }
    std::chrono::nanoseconds longest() const noexcept { return longest_; }
    // `waited`: from the start of the wait until the change was seen (or the wait gave up).
    void learn(std::chrono::nanoseconds waited) noexcept {
        if (waited <= longest_)
            budget_ = std::min(std::max({budget_ * 2, waited * 2, shortest_ * 2}), longest_);
        else
            budget_ = std::max(budget_ / 2, shortest_);
    }

  private:
    std::chrono::nanoseconds shortest_;
    std::chrono::nanoseconds longest_;
    std::chrono::nanoseconds budget_;
};

}  // namespace objif
