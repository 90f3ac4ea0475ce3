// SPDX-License-Identifier: MIT
// The one emulated board every client of the daemon shares. The Board is not
// thread-safe; every request from every transport (socket clients, the
// dual-port RAM thread) goes through here and is served under one lock, so
// requests are serialised on one board state. The lock is handed over in the
// order it was asked for (BoardTurns): the socket thread, serving turn after
// turn, cannot take it back before the dual-port RAM thread that waits.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <span>
#include <vector>

#include "rwmos/board.h"
#include "rwmos/frame_server.h"
#include "rwmos/frame_stream.h"

namespace rwmos_emu {

struct ServedCounts {
    std::uint64_t frames = 0;    // request frames answered (Error replies included)
    std::uint64_t rejected = 0;  // of those, answered with an Error reply
};

// A lock granted first come, first served (a ticket lock): a thread that
// releases it and asks again at once queues behind every thread already
// waiting. std::mutex promises no order, and a thread serving back to back
// may take it again before a waiter wakes.
class BoardTurns {
  public:
    void lock();
    void unlock();

  private:
    std::mutex mutex_;
    std::condition_variable turn_;
    std::uint64_t next_ = 0;     // the next ticket handed out
    std::uint64_t serving_ = 0;  // the ticket whose turn it is
};

class BoardHost {
  public:
    // `alive`: whether a mailbox host's process still runs (rwmos::MotionClaim).
    explicit BoardHost(const rwmos::BoardConfig& config, rwmos::HostAlive alive = nullptr)
        : board_(config), server_(board_, alive) {}

    // Serves one turn of a client's buffered byte stream (see
    // rwmos::FrameStream::serve).
    rwmos::FrameStream::Result serve_turn(rwmos::FrameStream& stream,
                                          std::vector<std::uint8_t>& replies,
                                          const rwmos::FrameStream::Turn& turn);
    // Serves one whole request frame (the dual-port RAM mailbox) from `host`.
    void serve_frame(std::span<const std::uint8_t> request, const rwmos::Host& host,
                     std::vector<std::uint8_t>& reply);

    // The host `key`'s link closed: its motion claim, if it held it, ends. True when it did.
    bool drop_claim(std::uint64_t key);

    ServedCounts counts() const;
    // Requests answered NoMemory (the daemon ran out of memory serving them).
    std::uint64_t out_of_memory() const;

    // --realtime: advances the interpolation clock so that the board has
    // run at least one cycle per interpolation cycle of wall time since
    // pacing began (clients may step it further ahead; it then waits).
    // A change of InterpolationCycle re-anchors the pace. Returns the cycles
    // it ran.
    std::uint64_t pace(std::chrono::steady_clock::time_point now);

  private:
    mutable BoardTurns turns_;
    rwmos::EmulatedBoard board_;
    rwmos::FrameServer server_;
    ServedCounts counts_;
    // Pacing anchor: wall time and board cycle when pacing (re)started.
    bool anchored_ = false;
    std::chrono::steady_clock::time_point anchor_time_{};
    std::uint64_t anchor_cycle_ = 0;
    std::int32_t anchor_cycle_us_ = 0;
};

}  // namespace rwmos_emu
