// SPDX-License-Identifier: MIT
// Serves wire frames (objif/frame.h) from a Board: one request frame in, one
// reply frame out. Every transport's emulator side (daemon socket, dual-port
// RAM mailbox, USB bulk endpoints) goes through here, so every transport
// answers a malformed frame the same way: an Error reply naming the reason,
// and no state change. It also keeps the board's motion claim (rwmos/motion_claim.h): which
// of the hosts sending it frames holds the motion.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "objif/frame.h"
#include "rwmos/board.h"
#include "rwmos/motion_claim.h"

namespace rwmos {

class FrameServer {
public:
    // `alive` tells whether a mailbox host's process still runs (MotionClaim).
    explicit FrameServer(EmulatedBoard& board, HostAlive alive = nullptr)
        : board_(board), claim_(alive) {}

    // A whole request frame (datagram transports: mailbox, USB transfer) from `host`.
    // Appends exactly one reply frame to `reply`. Returns the decode error,
    // kNone when the frame was well-formed (its reply may still carry an
    // error status from the board). Without `host`: the link's one host.
    objif::FrameError serve(std::span<const std::uint8_t> request, const Host& host,
                            std::vector<std::uint8_t>& reply);
    objif::FrameError serve(std::span<const std::uint8_t> request, std::vector<std::uint8_t>& reply) {
        return serve(request, Host{}, reply);
    }

    // An already decoded request. Appends exactly one reply frame. Returns
    // the payload's decode error (or kUnknownOpcode), kNone when it was served.
    // A request that runs out of memory (std::bad_alloc: the daemon under a
    // memory limit) is answered with an Error reply of status NoMemory, what
    // was written of its reply taken back, and counted (out_of_memory()).
    // A request that changes motion from a host that does not hold the motion claim while
    // another does is answered MotionClaimed and not served (objif::guarded_by_motion_claim).
    objif::FrameError handle(const objif::Frame& request, const Host& host,
                             std::vector<std::uint8_t>& reply);
    objif::FrameError handle(const objif::Frame& request, std::vector<std::uint8_t>& reply) {
        return handle(request, Host{}, reply);
    }

    // The board's motion claim: the daemon drops a host's claim when its link closes.
    MotionClaim& claim() noexcept { return claim_; }

    // Requests answered NoMemory so far.
    std::uint64_t out_of_memory() const noexcept { return out_of_memory_; }

    // The Error reply for a frame that could not be decoded; `sequence` is
    // echoed when the header was readable, else 0.
    static void reject(std::uint32_t sequence, objif::FrameError why, std::vector<std::uint8_t>& reply);

private:
    objif::FrameError serve_decoded(const objif::Frame& request, const Host& host,
                                    std::vector<std::uint8_t>& reply);
    // The MotionClaimed reply of a guarded request from a host that does not hold the claim:
    // the opcode's own reply with that status (and, where it carries one, the holder named).
    void refuse_unclaimed(const objif::Frame& request, std::vector<std::uint8_t>& reply);

    EmulatedBoard& board_;
    MotionClaim claim_;
    std::uint64_t out_of_memory_ = 0;
    std::vector<std::uint8_t> payload_;  // scratch, reused between requests
};

}  // namespace rwmos
