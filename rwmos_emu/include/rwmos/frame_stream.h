// SPDX-License-Identifier: MIT
// Request frames arriving as a byte stream (the daemon's socket, USB bulk
// OUT transfers): splits the stream into frames and serves each through a
// FrameServer, following docs/wire-frame.md "Malformed input": a frame whose
// boundary is known (bad CRC, unknown opcode, bad payload) gets an Error
// reply and the stream goes on; garbage (bad magic, version or length) means
// the framing is lost and the caller drops the connection. The buffer never
// holds more than one frame plus the bytes of one feed() call.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "objif/frame.h"
#include "rwmos/frame_server.h"

namespace rwmos {

class FrameStream {
  public:
    struct Result {
        bool keep = true;                                      // false: drop the connection
        objif::FrameError garbage = objif::FrameError::kNone;  // why, when !keep
        std::size_t frames = 0;    // frames answered (Error replies included)
        std::size_t rejected = 0;  // of those, answered with an Error reply
    };

    // Appends `bytes` and serves every complete frame now buffered, appending
    // one reply frame per request to `replies`.
    Result feed(std::span<const std::uint8_t> bytes, FrameServer& server,
                std::vector<std::uint8_t>& replies);

    // Bytes of an incomplete frame waiting for the rest.
    std::size_t pending() const noexcept { return buffer_.size() - start_; }
    void clear() noexcept {
        buffer_.clear();
        start_ = 0;
    }

  private:
    std::vector<std::uint8_t> buffer_;
    std::size_t start_ = 0;  // first byte not yet consumed
    objif::Frame frame_;     // scratch, reused
};

}  // namespace rwmos
