// SPDX-License-Identifier: MIT
// The remote half of the Transport interface: every backend that crosses a
// process or device boundary (unix, shm, pci, usb) is a FrameLink that moves
// one request frame out and one reply frame back; FrameTransport turns
// requests into frames and replies into statuses for all of them. A new
// opcode needs its payload codec (objif/frame.h) and one method here, never
// work in a backend.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "guarded.h"
#include "objif/frame.h"
#include "transport.h"

namespace apci {

using Millis = std::chrono::milliseconds;

inline constexpr Millis kDefaultTimeout{2000};
// The largest frame either side may send (header, largest payload, CRC).
inline constexpr std::size_t kMaxFrameSize = objif::kFrameOverhead + objif::kMaxPayload;

// One link to a board that carries whole frames. One file per backend.
// Contract for every method: noexcept; called by one thread at a time (the
// FrameTransport that owns it); `why` receives the words for a failure and is
// left alone on success.
class FrameLink {
  public:
    virtual ~FrameLink() = default;

    // Sends the request frame `request` (sequence number `sequence`) and
    // receives the board's reply to it into `reply` (whole frame, cleared
    // first). Stream links skip replies to earlier sequences (late replies to
    // requests that timed out). Blocking: at most `timeout`, then kTimeout.
    // kTransportError when the link failed; a link that is gone for good
    // (peer closed, device unplugged) marks itself disconnected and answers
    // kTransportError at once until reconnect() succeeds.
    virtual objif::Status exchange(std::span<const std::uint8_t> request, std::uint32_t sequence,
                                   std::vector<std::uint8_t>& reply, Millis timeout,
                                   std::string& why) noexcept = 0;

    // Closes the link and opens it again to the same device. Blocking: as
    // the backend's open.
    virtual objif::Status reconnect(std::string& why) noexcept = 0;

    // False once the link is known to be gone. Non-blocking.
    virtual bool connected() const noexcept = 0;
    // What ended the link, in words, without what to do about it (Transport::lost_reason).
    virtual std::string lost_reason() const { return {}; }

    // True when the link itself is exclusive to this process (USB: the interface claim made
    // at open, libusb_claim_interface), so nobody else can move the board through it: a
    // motion claim is then this link's without asking the board. Non-blocking.
    virtual bool exclusive() const noexcept { return false; }
};

// Reads one reply frame from a byte stream (unix socket, USB bulk IN):
// `read_some` appends at least one byte or fails. Replies to other sequences
// are skipped. kTransportError for bytes that are not a frame. A Notice frame
// (objif/frame.h: the daemon closes the connection and says why) whose
// status is not Ok ends the wait: kTransportError, its text in `why` and, if
// `closing` is not null, in `*closing`; a Notice with status Ok is skipped.
using ReadSome =
    std::function<objif::Status(std::vector<std::uint8_t>& buffer,
                                std::chrono::steady_clock::time_point deadline, std::string& why)>;
objif::Status receive_reply(std::vector<std::uint8_t>& pending, std::uint32_t sequence,
                            std::vector<std::uint8_t>& reply,
                            std::chrono::steady_clock::time_point deadline,
                            const ReadSome& read_some, std::string& why,
                            objif::Notice* closing = nullptr) noexcept;

// The Notice a whole frame carries: true and `out` when `frame` is a Notice
// frame (opcode 0xFFFE) with a valid payload.
bool notice_of(const objif::Frame& frame, objif::Notice& out);

class FrameTransport final : public Transport {
  public:
    // `name` is the URI, used in failure texts.
    FrameTransport(std::unique_ptr<FrameLink> link, std::string name, Millis timeout) noexcept;

    objif::Status read(objif::Descriptor& d, objif::ValueType want,
                       objif::Value& out) noexcept override;
    objif::Status write(objif::Descriptor& d, const objif::Value& v) noexcept override;
    // Motion requests: each is one line over request() below.
    objif::Status spool(const objif::SpoolRequest& req, objif::MotionReply& rep) noexcept override;
    objif::Status direct(const objif::DirectRequest& req,
                         objif::MotionReply& rep) noexcept override;
    objif::Status ssf(const objif::SsfRequest& req, objif::MotionReply& rep) noexcept override;
    objif::Status clock(const objif::ClockRequest& req, objif::ClockReply& rep) noexcept override;
    objif::Status read_trace(const objif::TraceRequest& req,
                             objif::TraceReply& rep) noexcept override;
    // A MotionClaim request; on an exclusive link (FrameLink::exclusive) answered here.
    objif::Status claim(const objif::ClaimRequest& req, objif::ClaimReply& rep) noexcept override;
    std::string_view failure_detail() const noexcept override { return detail_; }

    objif::Status set_timeout(Millis timeout) noexcept override;
    Millis timeout() const noexcept override { return timeout_; }
    objif::Status reconnect() noexcept override;
    bool connected() const noexcept override { return link_->connected(); }
    std::string lost_reason() const override { return link_->lost_reason(); }

    // One request of any opcode: sends `payload` as opcode `op` and returns
    // the reply's payload. An Error reply becomes its status (detail names
    // the frame error); a reply with the wrong opcode or sequence, or one
    // that does not decode, is kBadFrame.
    objif::Status call(objif::Opcode op, std::span<const std::uint8_t> payload,
                       std::vector<std::uint8_t>& reply_payload) noexcept;

  private:
    // One request whose reply payload struct carries the board's status:
    // encodes `req`, call()s, decodes `rep`; returns the transport's failure
    // or else the board's status.
    template <class Request, class Reply>
    objif::Status request(objif::Opcode op, const Request& req, Reply& rep) noexcept;

    objif::Status claim_unguarded(const objif::ClaimRequest& req, objif::ClaimReply& rep);
    objif::Status fail(objif::Status s, std::string text) noexcept;
    objif::Status bad_reply(objif::FrameError e, std::string_view what) noexcept;

    std::unique_ptr<FrameLink> link_;
    std::string name_;
    Millis timeout_;
    std::uint32_t sequence_ = 0;
    bool exclusive_claim_ = false;  // an exclusive link's motion claim, kept here
    std::string detail_;
    // Scratch buffers, reused so a round trip allocates nothing once warm.
    std::vector<std::uint8_t> payload_;
    std::vector<std::uint8_t> request_;
    std::vector<std::uint8_t> reply_;
    std::vector<std::uint8_t> reply_payload_;
    objif::Frame frame_;
};

// Options every remote scheme takes after '?': "timeout=MS". Options it does
// not know are left in `rest` for the backend. kInvalidArgument with `why`
// for a malformed value.
struct LinkOptions {
    Millis timeout = kDefaultTimeout;
    std::vector<std::string> rest;
};
objif::Status parse_link_options(const DeviceUri& uri, LinkOptions& out, std::string& why);

// For a scheme whose target is a path and whose only option is timeout=MS (shm:, unix:):
// kInvalidArgument with `why` naming the first other option in `options.rest`, or, for an empty
// path, saying what the path `needs` to be ("shm: needs " + needs).
objif::Status check_path_target(const DeviceUri& uri, const LinkOptions& options,
                                std::string_view scheme, std::string_view needs, std::string& why);

// The frame of each remote scheme's open: under guarded(), the options after '?' parsed, then
// `open(options)`, the scheme's own part, which returns a status.
template <class Open>
objif::Status open_with_options(const DeviceUri& uri, std::string& why, Open&& open) noexcept {
    return guarded([&] {
        LinkOptions options;
        const objif::Status s = parse_link_options(uri, options, why);
        return s != objif::Status::kOk ? s : open(options);
    });
}

// The last step of each remote scheme's open: opens `link` (its open(why)) and, once it is open,
// makes `out` the FrameTransport over it, named `name`.
template <class Link>
objif::Status open_framed(std::unique_ptr<Link> link, std::string name, Millis timeout,
                          std::unique_ptr<Transport>& out, std::string& why) {
    const objif::Status s = link->open(why);
    if (s != objif::Status::kOk) return s;
    out = std::make_unique<FrameTransport>(std::move(link), std::move(name), timeout);
    return objif::Status::kOk;
}

// "0x15B8", "5560" -> value. False for anything else or out of range.
bool parse_unsigned(std::string_view text, std::uint32_t max, std::uint32_t& out) noexcept;

}  // namespace apci
