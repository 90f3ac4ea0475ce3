// SPDX-License-Identifier: MIT
// A bare socket client for the daemon tests: sends any bytes (well-formed
// frames or not) and reads back whole reply frames, or notices that the
// daemon closed the connection.
#pragma once

#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "objif/frame.h"

namespace daemon_test {

class RawClient {
  public:
    explicit RawClient(const std::string& socket_path);
    ~RawClient();
    RawClient(const RawClient&) = delete;
    RawClient& operator=(const RawClient&) = delete;

    bool connected() const noexcept { return fd_ >= 0; }
    bool send(std::span<const std::uint8_t> bytes);
    // Reads one whole frame, skipping the daemon's greeting (a Notice with
    // status Ok); false on timeout, close or garbage.
    bool receive(objif::Frame& frame, std::chrono::milliseconds timeout = std::chrono::seconds(5));
    // As receive(), the greeting included.
    bool receive_any(objif::Frame& frame,
                     std::chrono::milliseconds timeout = std::chrono::seconds(5));
    // True when the daemon closed the connection within `timeout` (EOF).
    bool closed_by_peer(std::chrono::milliseconds timeout = std::chrono::seconds(5));
    void close();
    // Shuts both directions down without closing the descriptor: a send()
    // blocked in another thread returns, and the descriptor stays this
    // client's until close() (closing it under a concurrent send() would be
    // a race, and the number could be reused meanwhile).
    void shutdown();

  private:
    int fd_ = -1;
    std::vector<std::uint8_t> pending_;
};

// The daemon's greeting: a Notice frame with status Ok.
bool is_greeting(const objif::Frame& frame);

// Frames for the tests.
std::vector<std::uint8_t> frame_bytes(objif::Opcode op, std::uint32_t sequence,
                                      std::span<const std::uint8_t> payload);
std::vector<std::uint8_t> write_double_frame(std::uint32_t sequence, objif::Address a, double v);

}  // namespace daemon_test
