// SPDX-License-Identifier: MIT
// The one emulated board every client of the daemon shares. The Board is not
// thread-safe; every request from every transport (socket clients, the
// dual-port RAM thread) goes through here and is served under one mutex, so
// requests are serialised on one board state.
#pragma once

#include <chrono>
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

class BoardHost {
  public:
    explicit BoardHost(const rwmos::BoardConfig& config) : board_(config), server_(board_) {}

    // Serves a chunk of a client's byte stream (see rwmos::FrameStream).
    rwmos::FrameStream::Result serve_stream(rwmos::FrameStream& stream,
                                            std::span<const std::uint8_t> bytes,
                                            std::vector<std::uint8_t>& replies);
    // Serves one whole request frame (the dual-port RAM mailbox).
    void serve_frame(std::span<const std::uint8_t> request, std::vector<std::uint8_t>& reply);

    ServedCounts counts() const;

    // --realtime: advances the interpolation clock so that the board has
    // run at least one cycle per interpolation cycle of wall time since
    // pacing began (clients may step it further ahead; it then waits).
    // A change of InterpolationCycle re-anchors the pace. Returns the cycles
    // it ran.
    std::uint64_t pace(std::chrono::steady_clock::time_point now);

  private:
    mutable std::mutex mutex_;
    rwmos::Board board_;
    rwmos::FrameServer server_;
    ServedCounts counts_;
    // Pacing anchor: wall time and board cycle when pacing (re)started.
    bool anchored_ = false;
    std::chrono::steady_clock::time_point anchor_time_{};
    std::uint64_t anchor_cycle_ = 0;
    std::int32_t anchor_cycle_us_ = 0;
};

}  // namespace rwmos_emu
