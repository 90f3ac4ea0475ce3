// SPDX-License-Identifier: MIT
// The one emulated board every client of the daemon shares. The Board is not
// thread-safe; every request from every transport (socket clients, the
// dual-port RAM thread) goes through here and is served under one mutex, so
// requests are serialised on one board state.
#pragma once

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

private:
    mutable std::mutex mutex_;
    rwmos::Board board_;
    rwmos::FrameServer server_;
    ServedCounts counts_;
};

}  // namespace rwmos_emu
