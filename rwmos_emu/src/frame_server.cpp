// SPDX-License-Identifier: MIT
#include "rwmos/frame_server.h"

#include <new>

#include "rwmos/motion_wire.h"

namespace rwmos {

using objif::FrameError;
using objif::Opcode;

namespace {
constexpr std::uint16_t reply_opcode(Opcode op) {
    return static_cast<std::uint16_t>(static_cast<std::uint16_t>(op) | objif::kReplyFlag);
}
}  // namespace

void FrameServer::reject(std::uint32_t sequence, FrameError why, std::vector<std::uint8_t>& reply) {
    std::vector<std::uint8_t> payload;
    objif::encode(objif::ErrorReply{objif::frame_error_status(why), why}, payload);
    objif::encode_frame(reply_opcode(Opcode::kError), sequence, payload, reply);
}

FrameError FrameServer::serve(std::span<const std::uint8_t> request, const Host& host,
                              std::vector<std::uint8_t>& reply) {
    objif::Frame frame;
    std::size_t used = 0;
    bool need_more = false;
    FrameError e = objif::decode_frame(request, frame, used, need_more);
    if (e == FrameError::kNone && used != request.size()) e = FrameError::kBadLength;  // trailing bytes
    if (e != FrameError::kNone) {
        reject(used != 0 ? frame.sequence : 0, e, reply);
        return e;
    }
    return handle(frame, host, reply);
}

FrameError FrameServer::handle(const objif::Frame& request, const Host& host,
                               std::vector<std::uint8_t>& reply) {
    const std::size_t before = reply.size();
    try {
        return serve_decoded(request, host, reply);
    } catch (const std::bad_alloc&) {
        reply.resize(before);
        ++out_of_memory_;
        std::vector<std::uint8_t> payload;
        objif::encode(objif::ErrorReply{objif::Status::kNoMemory, FrameError::kNone}, payload);
        objif::encode_frame(reply_opcode(Opcode::kError), request.sequence, payload, reply);
        return FrameError::kNone;
    }
}

void FrameServer::refuse_unclaimed(const objif::Frame& request, std::vector<std::uint8_t>& reply) {
    const objif::Status refused = objif::Status::kMotionClaimed;
    switch (static_cast<Opcode>(request.opcode)) {
        case Opcode::kObjectWrite: {
            objif::WriteRequest req;
            objif::WriteReply rep;
            rep.status = refused;
            // The handle is echoed as sent: nothing was resolved.
            if (objif::decode(request.payload, req) == FrameError::kNone)
                rep.handle = req.descriptor.handle;
            objif::encode(rep, payload_);
            break;
        }
        case Opcode::kSpoolProfile:
        case Opcode::kDirectCommand:
        case Opcode::kSsfCommand: {
            objif::MotionReply rep;
            rep.status = refused;
            rep.message = claim_.held_text();
            objif::encode(rep, payload_);
            break;
        }
        case Opcode::kClock: {
            objif::ClockReply rep;
            rep.status = refused;
            objif::encode(rep, payload_);
            break;
        }
        default: {  // kReadTrace, the last opcode guarded_by_motion_claim names
            objif::TraceRequest req;
            objif::TraceReply rep;
            rep.status = refused;
            if (objif::decode(request.payload, req) == FrameError::kNone) rep.what = req.what;
            objif::encode(rep, payload_);
            break;
        }
    }
    objif::encode_frame(static_cast<std::uint16_t>(request.opcode | objif::kReplyFlag),
                        request.sequence, payload_, reply);
}

FrameError FrameServer::serve_decoded(const objif::Frame& request, const Host& host,
                                      std::vector<std::uint8_t>& reply) {
    payload_.clear();
    // The claim is checked before the payload is decoded: a guarded request of a host that
    // does not hold it never reaches the board, malformed or not.
    if (objif::guarded_by_motion_claim(request.opcode, request.payload) && !claim_.allows(host)) {
        refuse_unclaimed(request, reply);
        return FrameError::kNone;
    }
    switch (static_cast<Opcode>(request.opcode)) {
        case Opcode::kObjectRead: {
            objif::ReadRequest req;
            const FrameError e = objif::decode(request.payload, req);
            if (e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::ReadReply rep;
            rep.status = board_.read(req.descriptor, req.want, rep.value);
            rep.handle = req.descriptor.handle;
            objif::encode(rep, payload_);
            break;
        }
        case Opcode::kObjectWrite: {
            objif::WriteRequest req;
            const FrameError e = objif::decode(request.payload, req);
            if (e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::WriteReply rep;
            rep.status = board_.write(req.descriptor, req.value);
            rep.handle = req.descriptor.handle;
            objif::encode(rep, payload_);
            break;
        }
        case Opcode::kSpoolProfile: {
            objif::SpoolRequest req;
            if (const FrameError e = objif::decode(request.payload, req); e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::encode(serve_spool(board_, req), payload_);
            break;
        }
        case Opcode::kDirectCommand: {
            objif::DirectRequest req;
            if (const FrameError e = objif::decode(request.payload, req); e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::encode(serve_direct(board_, req), payload_);
            break;
        }
        case Opcode::kSsfCommand: {
            objif::SsfRequest req;
            if (const FrameError e = objif::decode(request.payload, req); e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::encode(serve_ssf(board_, req), payload_);
            break;
        }
        case Opcode::kClock: {
            objif::ClockRequest req;
            if (const FrameError e = objif::decode(request.payload, req); e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::encode(serve_clock(board_, req), payload_);
            break;
        }
        case Opcode::kReadTrace: {
            objif::TraceRequest req;
            if (const FrameError e = objif::decode(request.payload, req); e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::encode(serve_trace(board_, req), payload_);
            break;
        }
        case Opcode::kMotionClaim: {
            objif::ClaimRequest req;
            if (const FrameError e = objif::decode(request.payload, req); e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::encode(claim_.serve(host, req), payload_);
            break;
        }
        default:
            // A reply opcode, the Error opcode, or a request this board does not serve.
            reject(request.sequence, FrameError::kUnknownOpcode, reply);
            return FrameError::kUnknownOpcode;
    }
    objif::encode_frame(static_cast<std::uint16_t>(request.opcode | objif::kReplyFlag), request.sequence,
                        payload_, reply);
    return FrameError::kNone;
}

}  // namespace rwmos
