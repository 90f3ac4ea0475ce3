// SPDX-License-Identifier: MIT
// The board side of the motion claim (docs/motion-claim.md): one host at a time may hold the
// board's motion; while one does, the requests of every other host that start or change
// motion (objif::guarded_by_motion_claim) are refused with MotionClaimed, naming the holder.
// As libusb_claim_interface and flock do for a device: the claim belongs to the link it was
// made on and ends with it (the daemon drops a socket client's claim when it disconnects; a
// mailbox host's claim ends when its process does), so a crashed host leaves none behind.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "objif/frame.h"

namespace rwmos {

// A host as the board side of a link knows it.
struct Host {
    // Tells the hosts of a board apart: one per socket connection, one per mailbox process.
    // 0: the one host of a link that has only one (in-process, USB).
    std::uint64_t key = 0;
    std::int32_t pid = 0;  // its process, 0 when the link does not say
    std::string name;      // its command name (/proc/PID/comm), "" when not known
    // Known only by its pid (a mailbox host): its claim ends when that process does, which
    // the board side checks with the liveness function below (pid and start time).
    bool by_pid = false;
    std::uint64_t start_time = 0;  // the process's start time (/proc/PID/stat field 22)
};

// Whether the process of a by_pid host still runs. The emulator does no I/O of its own; the
// daemon passes the check it makes (/proc).
using HostAlive = bool (*)(const Host& host);

class MotionClaim {
public:
    explicit MotionClaim(HostAlive alive = nullptr) : alive_(alive) {}

    // Serves a MotionClaim request of `host`: claim (MotionClaimed naming nobody else's
    // details but the reply's fields when another holds it; WrongDeviceState when `host`
    // already holds it), release (WrongDeviceState when it does not), query.
    objif::ClaimReply serve(const Host& host, const objif::ClaimRequest& request);

    // True when `host` may send a request that changes motion: nobody holds the claim, or
    // `host` does.
    bool allows(const Host& host);

    // "the board's motion is held by pid 4242 (apcictl) since 2024-05-01 12:00:00 UTC"
    // (objif::claim_holder_text), for the refusals; "" when nobody holds it.
    std::string held_text() const;

    // The host `key` is gone (its connection closed): its claim, if it holds it, ends.
    // True when it held it.
    bool drop(std::uint64_t key);

    // The holder, if any (after forgetting one whose process is gone).
    const std::optional<Host>& holder();

private:
    void forget_dead_holder();
    objif::ClaimReply reply_for(const Host& host, objif::Status status) const;

    HostAlive alive_;
    std::optional<Host> holder_;
    std::uint64_t since_ms_ = 0;
};

}  // namespace rwmos
