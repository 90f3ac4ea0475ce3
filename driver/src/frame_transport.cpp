// SPDX-License-Identifier: MIT
#include "frame_transport.h"
#include "guarded.h"

#include <fmt/format.h>

#include <unistd.h>

#include <cerrno>  // program_invocation_short_name
#include <charconv>
#include <new>

namespace apci {

using objif::FrameError;
using objif::Status;

namespace {

constexpr std::uint16_t reply_opcode(objif::Opcode op) noexcept {
    return static_cast<std::uint16_t>(static_cast<std::uint16_t>(op) | objif::kReplyFlag);
}
constexpr std::uint16_t kErrorReply = reply_opcode(objif::Opcode::kError);
constexpr std::uint16_t kNoticeFrame = reply_opcode(objif::Opcode::kNotice);

}  // namespace

bool notice_of(const objif::Frame& frame, objif::Notice& out) {
    return frame.opcode == kNoticeFrame && objif::decode(frame.payload, out) == FrameError::kNone;
}

bool parse_unsigned(std::string_view text, std::uint32_t max, std::uint32_t& out) noexcept {
    int base = 10;
    if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
        base = 16;
        text.remove_prefix(2);
    }
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v, base);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty() || v > max)
        return false;
    out = static_cast<std::uint32_t>(v);
    return true;
}

Status parse_link_options(const DeviceUri& uri, LinkOptions& out, std::string& why) {
    for (const auto& option : uri.options) {
        constexpr std::string_view kTimeout = "timeout=";
        if (option.starts_with(kTimeout)) {
            std::uint32_t ms = 0;
            if (!parse_unsigned(std::string_view(option).substr(kTimeout.size()), 3'600'000, ms) ||
                ms == 0) {
                why = fmt::format(
                    "option '{}': the timeout is a number of milliseconds, 1 to 3600000", option);
                return Status::kInvalidArgument;
            }
            out.timeout = Millis(ms);
        } else {
            out.rest.push_back(option);
        }
    }
    return Status::kOk;
}

Status check_path_target(const DeviceUri& uri, const LinkOptions& options, std::string_view scheme,
                         std::string_view needs, std::string& why) {
    if (!options.rest.empty()) {
        why = fmt::format("unknown {}: option '{}' (known: timeout=MS)", scheme,
                          options.rest.front());
        return Status::kInvalidArgument;
    }
    if (uri.target.empty()) {
        why = fmt::format("{}: needs {}", scheme, needs);
        return Status::kInvalidArgument;
    }
    return Status::kOk;
}

Status receive_reply(std::vector<std::uint8_t>& pending, std::uint32_t sequence,
                     std::vector<std::uint8_t>& reply,
                     std::chrono::steady_clock::time_point deadline, const ReadSome& read_some,
                     std::string& why, objif::Notice* closing) noexcept {
    try {
        objif::Frame frame;
        for (;;) {
            std::size_t consumed = 0;
            bool need_more = false;
            const FrameError e = objif::decode_frame(pending, frame, consumed, need_more);
            if (need_more || pending.empty()) {
                const Status s = read_some(pending, deadline, why);
                if (s != Status::kOk) return s;
                continue;
            }
            if (consumed == 0) {
                why = fmt::format("the board sent bytes that are not a frame ({})",
                                  objif::frame_error_name(e));
                pending.clear();
                return Status::kTransportError;
            }
            // A whole frame (maybe with a bad CRC: the caller reports that).
            if (objif::Notice notice; e == FrameError::kNone && notice_of(frame, notice)) {
                pending.erase(pending.begin(),
                              pending.begin() + static_cast<std::ptrdiff_t>(consumed));
                if (notice.status == Status::kOk) continue;  // a greeting: nothing to do
                why = notice.text;
                if (closing != nullptr) *closing = std::move(notice);
                return Status::kTransportError;
            }
            const bool ours = frame.sequence == sequence;
            if (ours)
                reply.assign(pending.begin(),
                             pending.begin() + static_cast<std::ptrdiff_t>(consumed));
            pending.erase(pending.begin(), pending.begin() + static_cast<std::ptrdiff_t>(consumed));
            if (ours) return Status::kOk;
            // A late reply to a request that timed out: skip it.
        }
    } catch (const std::bad_alloc&) {
        return Status::kNoMemory;
    } catch (...) {
        why = "internal error while receiving a reply";
        return Status::kGeneralError;
    }
}

// cppcheck-suppress passedByValue ; a sink argument, moved into name_
FrameTransport::FrameTransport(std::unique_ptr<FrameLink> link, std::string name,
                               Millis timeout) noexcept
    : link_(std::move(link)), name_(std::move(name)), timeout_(timeout) {}

Status FrameTransport::fail(Status s, std::string text) noexcept {
    detail_ = std::move(text);
    return s;
}

Status FrameTransport::bad_reply(FrameError e, std::string_view what) noexcept {
    try {
        return fail(Status::kBadFrame, fmt::format("{}: the board's reply {}: {}", name_, what,
                                                   objif::frame_error_name(e)));
    } catch (...) {
        return Status::kBadFrame;
    }
}

Status FrameTransport::set_timeout(Millis timeout) noexcept {
    if (timeout.count() <= 0) return Status::kInvalidArgument;
    timeout_ = timeout;
    return Status::kOk;
}

Status FrameTransport::reconnect() noexcept {
    return guarded([&] {
        std::string why;
        const Status s = link_->reconnect(why);
        exclusive_claim_ = false;  // a claim ends with the link it was made on
        if (s != Status::kOk) return fail(s, fmt::format("{}: reconnect failed: {}", name_, why));
        detail_.clear();
        return Status::kOk;
    });
}

Status FrameTransport::call(objif::Opcode op, std::span<const std::uint8_t> payload,
                            std::vector<std::uint8_t>& reply_payload) noexcept {
    try {
        const std::uint32_t sequence = ++sequence_;
        request_.clear();
        objif::encode_frame(static_cast<std::uint16_t>(op), sequence, payload, request_);
        std::string why;
        const Status s = link_->exchange(request_, sequence, reply_, timeout_, why);
        if (s != Status::kOk) return fail(s, fmt::format("{}: {}", name_, why));

        std::size_t consumed = 0;
        bool need_more = false;
        FrameError e = objif::decode_frame(reply_, frame_, consumed, need_more);
        if (e == FrameError::kNone && consumed != reply_.size()) e = FrameError::kBadLength;
        if (e != FrameError::kNone) return bad_reply(e, "is not a valid frame");
        if (frame_.sequence != sequence)
            return fail(Status::kBadFrame,
                        fmt::format("{}: the board answered sequence {} to request {}", name_,
                                    frame_.sequence, sequence));
        if (frame_.opcode == kErrorReply) {
            objif::ErrorReply error;
            e = objif::decode(frame_.payload, error);
            if (e != FrameError::kNone) return bad_reply(e, "(Error) has a bad payload");
            // No frame error: the board could not serve a well-formed request (NoMemory).
            return fail(error.status,
                        fmt::format("{}: the board refused the {} frame: {}", name_,
                                    objif::opcode_name(static_cast<std::uint16_t>(op)),
                                    error.reason == FrameError::kNone
                                        ? objif::status_message(error.status)
                                        : objif::frame_error_name(error.reason)));
        }
        if (frame_.opcode != reply_opcode(op))
            return fail(Status::kBadFrame,
                        fmt::format("{}: the board answered {} to {}", name_,
                                    objif::opcode_name(frame_.opcode),
                                    objif::opcode_name(static_cast<std::uint16_t>(op))));
        reply_payload.swap(frame_.payload);
        detail_.clear();
        return Status::kOk;
    } catch (const std::bad_alloc&) {
        return Status::kNoMemory;
    } catch (...) {
        return fail(Status::kGeneralError, "internal error in the frame transport");
    }
}

template <class Request, class Reply>
Status FrameTransport::request(objif::Opcode op, const Request& req, Reply& rep) noexcept {
    return guarded([&] {
        payload_.clear();
        objif::encode(req, payload_);
        const Status s = call(op, payload_, reply_payload_);
        if (s != Status::kOk) return s;
        Reply decoded;
        const FrameError e = objif::decode(reply_payload_, decoded);
        if (e != FrameError::kNone)
            return bad_reply(e,
                             fmt::format("({}) has a bad payload",
                                         objif::opcode_name(static_cast<std::uint16_t>(
                                             static_cast<std::uint16_t>(op) | objif::kReplyFlag))));
        rep = std::move(decoded);
        return rep.status;
    });
}

Status FrameTransport::read(objif::Descriptor& d, objif::ValueType want,
                            objif::Value& out) noexcept {
    objif::ReadReply reply;
    reply.handle = d.handle;  // kept when no reply decodes
    const Status s = request(objif::Opcode::kObjectRead, objif::ReadRequest{d, want}, reply);
    d.handle = reply.handle;
    if (s == Status::kOk) out = reply.value;
    return s;
}

Status FrameTransport::write(objif::Descriptor& d, const objif::Value& v) noexcept {
    objif::WriteReply reply;
    reply.handle = d.handle;  // kept when no reply decodes
    const Status s = request(objif::Opcode::kObjectWrite, objif::WriteRequest{d, v}, reply);
    d.handle = reply.handle;
    return s;
}

Status FrameTransport::spool(const objif::SpoolRequest& req, objif::MotionReply& rep) noexcept {
    return request(objif::Opcode::kSpoolProfile, req, rep);
}
Status FrameTransport::direct(const objif::DirectRequest& req, objif::MotionReply& rep) noexcept {
    return request(objif::Opcode::kDirectCommand, req, rep);
}
Status FrameTransport::ssf(const objif::SsfRequest& req, objif::MotionReply& rep) noexcept {
    return request(objif::Opcode::kSsfCommand, req, rep);
}
Status FrameTransport::clock(const objif::ClockRequest& req, objif::ClockReply& rep) noexcept {
    return request(objif::Opcode::kClock, req, rep);
}
Status FrameTransport::read_trace(const objif::TraceRequest& req, objif::TraceReply& rep) noexcept {
    return request(objif::Opcode::kReadTrace, req, rep);
}

Status FrameTransport::claim(const objif::ClaimRequest& req, objif::ClaimReply& rep) noexcept {
    return guarded([&] { return claim_unguarded(req, rep); });
}

Status FrameTransport::claim_unguarded(const objif::ClaimRequest& req, objif::ClaimReply& rep) {
    if (link_->exclusive()) {
        // Nobody else reaches the board through this link: the claim is this link's to give.
        if (!link_->connected())
            return fail(Status::kTransportError, fmt::format("{}: link lost", name_));
        const bool claim = req.action == objif::ClaimAction::kClaim;
        const bool release = req.action == objif::ClaimAction::kRelease;
        Status s = Status::kOk;
        if ((claim && exclusive_claim_) || (release && !exclusive_claim_))
            s = Status::kWrongDeviceState;
        else if (claim || release)
            exclusive_claim_ = claim;
        rep = objif::ClaimReply{};
        rep.status = s;
        rep.held = rep.yours = exclusive_claim_;
        if (exclusive_claim_) {
            rep.pid = static_cast<std::int32_t>(::getpid());
            rep.name = std::string(program_invocation_short_name).substr(0, objif::kMaxHolderName);
        }
        detail_.clear();
        return s;
    }
    const Status s = request(objif::Opcode::kMotionClaim, req, rep);
    if (s == Status::kUnknownOpcode)
        return fail(Status::kNotSupported,
                    fmt::format("{}: the board does not serve motion claims (MotionClaim, "
                                "opcode 0x0008; docs/motion-claim.md)",
                                name_));
    return s;
}

}  // namespace apci
