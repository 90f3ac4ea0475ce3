// SPDX-License-Identifier: MIT
// Request frames arriving as a byte stream (the daemon's socket, USB bulk
// OUT transfers): splits the stream into frames and serves each through a
// FrameServer, following docs/wire-frame.md "Malformed input": a frame whose
// boundary is known (bad CRC, unknown opcode, bad payload) gets an Error
// reply and the stream goes on; garbage (bad magic, version or length) means
// the framing is lost and the caller drops the connection. The buffer never
// holds more than one frame plus the bytes of one feed() or append() call
// (a caller that serves in turns appends only once a turn left nothing).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "objif/frame.h"
#include <utility>

#include "rwmos/frame_server.h"

namespace rwmos {

class FrameStream {
  public:
    struct Result {
        bool keep = true;                                      // false: drop the connection
        objif::FrameError garbage = objif::FrameError::kNone;  // why, when !keep
        std::size_t frames = 0;    // frames answered (Error replies included)
        std::size_t rejected = 0;  // of those, answered with an Error reply
        bool more = false;         // the turn ended with bytes of whole frames still buffered
    };

    // How much one client's turn may serve (the daemon serves its clients in
    // turns, so that one client's pipelined requests do not keep the others
    // waiting): frames in order until none is left whole, or until a frame
    // ends at or past `until`, or until `replies` has grown by `reply_bytes`;
    // at least one frame.
    struct Turn {
        std::chrono::steady_clock::time_point until = std::chrono::steady_clock::time_point::max();
        std::size_t reply_bytes = std::numeric_limits<std::size_t>::max();
    };

    // Appends `bytes` and serves every complete frame now buffered, appending
    // one reply frame per request to `replies`.
    Result feed(std::span<const std::uint8_t> bytes, FrameServer& server,
                std::vector<std::uint8_t>& replies);

    // Appends `bytes` without serving them.
    void append(std::span<const std::uint8_t> bytes);
    // Serves buffered frames for one turn; Result::more when whole frames
    // (or garbage) are left for the next.
    Result serve(FrameServer& server, std::vector<std::uint8_t>& replies, const Turn& turn);

    // The host at the other end of the stream (a daemon's socket client): every frame is
    // served as its request (FrameServer::handle). Host{} until set.
    void set_host(Host host) { host_ = std::move(host); }
    const Host& host() const noexcept { return host_; }

    // Bytes buffered and not yet served: an incomplete frame waiting for the
    // rest, or what a turn left.
    std::size_t pending() const noexcept { return buffer_.size() - start_; }
    void clear() noexcept {
        buffer_.clear();
        start_ = 0;
    }

  private:
    std::vector<std::uint8_t> buffer_;
    std::size_t start_ = 0;  // first byte not yet consumed
    objif::Frame frame_;     // scratch, reused
    Host host_;
};

}  // namespace rwmos
