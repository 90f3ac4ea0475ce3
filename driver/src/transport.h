// SPDX-License-Identifier: MIT
// The one interface between the C API (apci.cpp) and the ways to reach a
// board. One file per backend (transport_<scheme>.cpp); each fills one row
// of the scheme table in transport.cpp.
//
// Methods work at the request level (object read, object write, spool,
// direct, ssf, clock, trace), not at the frame level, so
// the in-process backend calls the emulated board directly and pays no frame
// encoding. Backends that cross a process or device boundary (unix, shm, usb,
// pci) encode each request as one objif/frame.h wire frame and decode the
// reply; their errno / libusb codes become objif::Status in exactly one place
// per backend, and the detail text (strerror, libusb_error_name) is kept for
// failure_detail().
//
// Contract for every method of every backend:
//  - noexcept: no exception crosses this boundary; failures are statuses.
//  - Threading: a Transport is owned by one apci_board and called by one
//    thread at a time (the C API does not lock; see apci.h "Threading").
//    Backends need no locking of their own unless they run helper threads.
//  - A failed request changes no board state (the board guarantees this for
//    refused requests; a transport that loses a reply says kTransportError or
//    kTimeout and the caller cannot know whether the board acted).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "apci/apci.h"
#include "objif/descriptor.h"
#include "objif/frame.h"
#include "objif/status.h"
#include "objif/value.h"

namespace apci {

class Transport {
public:
    virtual ~Transport() = default;

    // Reads the object `d` names, expecting type `want`. On kOk `out` holds
    // the value. `d.handle` is filled in when the board resolves the object
    // (also when a later check fails), and kept as is otherwise.
    // Blocking: until the board answers (inproc: returns at once; remote:
    // one round trip, at most the backend's timeout, then kTimeout).
    virtual objif::Status read(objif::Descriptor& d, objif::ValueType want,
                               objif::Value& out) noexcept = 0;

    // Writes `v` to the object `d` names; the board checks the type against
    // the object's. Handle and blocking as for read().
    virtual objif::Status write(objif::Descriptor& d, const objif::Value& v) noexcept = 0;

    // ---- Motion (docs/motion.md). Requests and replies are the wire payload
    // structs of objif/frame.h, so framed backends encode them as they are.
    // Each returns the transport's own failure, or else the board's status
    // (also in the reply); the reply is filled whenever the board answered.
    // Blocking: as read(); a clock request returns when the clock has run
    // (virtual time: as fast as the CPU allows). Backends without motion
    // support keep these defaults: kNotSupported, nothing sent.

    // SpoolProfile: one G00/G01/G02/G03 profile.
    virtual objif::Status spool(const objif::SpoolRequest& req, objif::MotionReply& rep) noexcept {
        (void)req;
        (void)rep;
        return objif::Status::kNotSupported;
    }
    // DirectCommand: JA, JS (discard the spooler and the held profile).
    virtual objif::Status direct(const objif::DirectRequest& req, objif::MotionReply& rep) noexcept {
        (void)req;
        (void)rep;
        return objif::Status::kNotSupported;
    }
    // SsfCommand: e.g. 2001 (release the held profile).
    virtual objif::Status ssf(const objif::SsfRequest& req, objif::MotionReply& rep) noexcept {
        (void)req;
        (void)rep;
        return objif::Status::kNotSupported;
    }
    // Clock: step, run until idle, query, trace on/off.
    virtual objif::Status clock(const objif::ClockRequest& req, objif::ClockReply& rep) noexcept {
        (void)req;
        (void)rep;
        return objif::Status::kNotSupported;
    }
    // ReadTrace: per-cycle samples or executed segments, oldest first.
    virtual objif::Status read_trace(const objif::TraceRequest& req, objif::TraceReply& rep) noexcept {
        (void)req;
        (void)rep;
        return objif::Status::kNotSupported;
    }
    // MotionClaim (docs/motion-claim.md): claims, releases or asks who holds the board's
    // motion for this link; the reply names the holder. The board keeps the claim per link and
    // ends it with the link. Blocking: as read(). Default: kNotSupported, nothing sent.
    virtual objif::Status claim(const objif::ClaimRequest& req, objif::ClaimReply& rep) noexcept {
        (void)req;
        (void)rep;
        return objif::Status::kNotSupported;
    }
    // Executed segments, oldest first, straight into the caller's records (apci_read_segments):
    // up to `max`, `got` of them. A backend that holds the board in this process copies each
    // segment once; the default, kNotSupported, has the caller read them through read_trace
    // (wire records, then converted).
    virtual objif::Status read_segments(apci_segment* out, std::size_t max,
                                        std::size_t& got) noexcept {
        (void)out;
        (void)max;
        got = 0;
        return objif::Status::kNotSupported;
    }

    // Extra words about the most recent failed call when the failure is the
    // transport's own (e.g. "connect /run/apci.sock: No such file or
    // directory"); empty for statuses the board answered. Non-blocking.
    virtual std::string_view failure_detail() const noexcept { return {}; }

    // The longest one request may block before it answers kTimeout.
    // kInvalidArgument for zero. Backends that never block (inproc) keep the
    // value and ignore it. Non-blocking.
    virtual objif::Status set_timeout(std::chrono::milliseconds timeout) noexcept {
        if (timeout.count() <= 0) return objif::Status::kInvalidArgument;
        timeout_ = timeout;
        return objif::Status::kOk;
    }
    virtual std::chrono::milliseconds timeout() const noexcept { return timeout_; }

    // Closes the link to the board and opens it again (after the daemon
    // restarted, the board was re-plugged). Board state is whatever the
    // board kept. Blocking: as open. inproc: nothing to do, kOk.
    virtual objif::Status reconnect() noexcept { return objif::Status::kOk; }

    // False once the link is known to be lost (peer closed, device
    // unplugged); requests then answer kTransportError until reconnect()
    // succeeds. Non-blocking.
    virtual bool connected() const noexcept { return true; }
    // What ended the link, in words, without what to do about it (apci_link_lost()): "" while
    // it works, or where the transport cannot lose it.
    virtual std::string lost_reason() const { return {}; }

private:
    std::chrono::milliseconds timeout_{2000};
};

// The words of a call that finds the link lost (apci_last_error()): what ended it, then how a
// program opens it again (`once_back`: a device that must come back first). The cause comes
// first and whole, so that a tool that opens links itself can put its own hint after it
// (apci_link_lost() gives the cause alone).
std::string lost_link_words(std::string_view cause, bool once_back = false);
// The words of a later call on a link already lost.
std::string still_lost_words(std::string_view cause);

// From `start` on an apci_segment is doubles and 64-bit counters with no gap or tail: only its
// head has padding (segment_to_c zeroes the head).
static_assert(sizeof(apci_segment) == offsetof(apci_segment, start) +
                                          5 * sizeof(double[APCI_AXIS_COUNT]) + sizeof(double) +
                                          2 * sizeof(std::uint64_t));

// An executed segment as the C API hands it out, from the wire's record (objif::WireSegment)
// or, in the in-process transport, straight from the emulator's log: both name their members
// as apci_segment does.
template <class Segment>
void segment_to_c(const Segment& m, apci_segment& s) noexcept {
    // Every member is written below; only the padding after plane_axes is not. Zeroing the
    // head up to `start` leaves no byte undefined without clearing the whole record first.
    // cppcheck-suppress memsetClassFloat ; only the integer head is cleared, no double
    std::memset(&s, 0, offsetof(apci_segment, start));
    s.tag = m.tag;
    s.kind = static_cast<std::uint8_t>(m.kind);
    s.role = static_cast<std::uint8_t>(m.role);
    s.ccw = m.ccw ? 1 : 0;
    s.interrupted = m.interrupted ? 1 : 0;
    s.traverse = m.traverse ? 1 : 0;
    s.plane_axes[0] = m.plane_axes[0];
    s.plane_axes[1] = m.plane_axes[1];
    s.plane = m.plane;
    // Fixed-size copies the compiler does in place (std::copy of the arrays was a memmove call
    // each, three a segment).
    static_assert(sizeof m.start == sizeof s.start && sizeof m.end == sizeof s.end &&
                  sizeof m.center == sizeof s.center &&
                  sizeof m.length_start == sizeof s.length_start &&
                  sizeof m.length_end == sizeof s.length_end);
    std::memcpy(s.start, m.start.data(), sizeof s.start);
    std::memcpy(s.end, m.end.data(), sizeof s.end);
    std::memcpy(s.center, m.center.data(), sizeof s.center);
    s.feed = m.feed;
    s.start_cycle = m.start_cycle;
    s.end_cycle = m.end_cycle;
    std::memcpy(s.length_start, m.length_start.data(), sizeof s.length_start);
    std::memcpy(s.length_end, m.length_end.data(), sizeof s.length_end);
}

// A board found by list_devices(): its URI and one line about it.
struct FoundDevice {
    std::string uri;
    std::string description;
};

// A device URI split into its parts: "scheme:target?opt1&opt2".
struct DeviceUri {
    std::string scheme;                // "emu", "unix", "shm", "pci", "usb"
    std::string target;                // what follows "scheme:" up to '?'
    std::vector<std::string> options;  // the '&'-separated items after '?'
};

// Parses a device URI. NULL-equivalent (empty) means "emu:". kInvalidArgument
// with `why` set for a string without "scheme:" or with an empty option.
objif::Status parse_device_uri(std::string_view text, DeviceUri& out, std::string& why) noexcept;

// Opens the transport the URI names (scheme table in transport.cpp).
// kInvalidArgument for an unknown scheme or bad target/options, kNotSupported
// for a known scheme whose backend is not built yet, or the backend's own
// status; `why` says what was wrong. Blocking: as the backend's connect.
objif::Status open_transport(const DeviceUri& uri, std::unique_ptr<Transport>& out,
                             std::string& why) noexcept;

// Every board the backends can find (scheme table order): USB boards,
// PCI boards, running emulator daemons. Backends that cannot enumerate are
// skipped; a backend that fails says why in `problems` (one line each).
// Blocking: enumeration and one probe per candidate.
objif::Status list_devices(std::vector<FoundDevice>& out, std::vector<std::string>& problems) noexcept;

// Backend constructors and enumerators, one pair per transport_<scheme>.cpp.
// An enumerator appends what it finds; it returns kOk, or a status with
// `why` when it could not look.
objif::Status open_inproc(const DeviceUri& uri, std::unique_ptr<Transport>& out,
                          std::string& why) noexcept;
objif::Status open_unix(const DeviceUri& uri, std::unique_ptr<Transport>& out,
                        std::string& why) noexcept;
objif::Status list_unix(std::vector<FoundDevice>& out, std::string& why) noexcept;
objif::Status open_shm(const DeviceUri& uri, std::unique_ptr<Transport>& out,
                       std::string& why) noexcept;
objif::Status list_shm(std::vector<FoundDevice>& out, std::string& why) noexcept;
objif::Status open_pci(const DeviceUri& uri, std::unique_ptr<Transport>& out,
                       std::string& why) noexcept;
objif::Status list_pci(std::vector<FoundDevice>& out, std::string& why) noexcept;
objif::Status open_usb(const DeviceUri& uri, std::unique_ptr<Transport>& out,
                       std::string& why) noexcept;
objif::Status list_usb(std::vector<FoundDevice>& out, std::string& why) noexcept;

}  // namespace apci
