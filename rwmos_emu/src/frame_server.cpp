// SPDX-License-Identifier: MIT
#include "rwmos/frame_server.h"

#include <algorithm>
#include <string>

namespace rwmos {

using objif::FrameError;
using objif::Opcode;

namespace {
constexpr std::uint16_t reply_opcode(Opcode op) {
    return static_cast<std::uint16_t>(static_cast<std::uint16_t>(op) | objif::kReplyFlag);
}

// ---- Motion payloads <-> the board's motion types (docs/motion.md).
// Values with a meaning on the board (kind, code, axes) pass through as they
// are; the board checks them and answers with a status.

motion::Profile profile_of(const objif::SpoolRequest& r) {
    motion::Profile p;
    p.kind = static_cast<motion::ProfileKind>(r.kind);
    p.tag = r.tag;
    p.feed = r.feed;
    p.axes = r.axes;
    p.target = r.target;
    p.arc_axes = r.arc_axes;
    p.center = r.center;
    return p;
}

motion::DirectCommand direct_of(const objif::DirectRequest& r) {
    motion::DirectCommand c;
    c.code = static_cast<motion::DirectCode>(r.code);
    c.axes = r.axes;
    c.target = r.target;
    c.feed = r.feed;
    return c;
}

objif::MotionReply motion_reply(const motion::MotionResult& r) {
    return {r.status, r.group, r.errors, r.tag, std::string(r.message)};
}

objif::WireSegment wire_segment(const motion::Segment& s) {
    objif::WireSegment w;
    w.tag = s.tag;
    w.kind = static_cast<std::uint8_t>(s.kind);
    w.role = static_cast<std::uint8_t>(s.role);
    w.ccw = s.ccw;
    w.interrupted = s.interrupted;
    w.plane_axes = s.plane_axes;
    w.plane = s.plane;
    w.start = s.start;
    w.end = s.end;
    w.center = s.center;
    w.feed = s.feed;
    w.start_cycle = s.start_cycle;
    w.end_cycle = s.end_cycle;
    return w;
}
}  // namespace

objif::ClockReply FrameServer::clock(const objif::ClockRequest& req) {
    objif::ClockReply rep;
    switch (req.mode) {
        case objif::ClockMode::kStep:
            board_.step(req.cycles);
            rep.ran = req.cycles;
            break;
        case objif::ClockMode::kRunUntilIdle: rep.ran = board_.run_until_idle(req.cycles); break;
        case objif::ClockMode::kQuery: break;
        case objif::ClockMode::kTraceOn:
            rep.status = req.cycles > Board::kMaxTraceCapacity
                             ? objif::Status::kValueTooHigh
                             : board_.set_trace(true, static_cast<std::size_t>(req.cycles));
            break;
        case objif::ClockMode::kTraceOff: rep.status = board_.set_trace(false, 0); break;
    }
    const motion::MotionStatus s = board_.motion_status();
    rep.now = s.now;
    rep.flags = static_cast<std::uint8_t>((s.idle ? objif::kClockIdle : 0) |
                                          (s.held ? objif::kClockHeld : 0) |
                                          (s.profile_held ? objif::kClockProfileHeld : 0) |
                                          (s.tracing ? objif::kClockTracing : 0));
    rep.fill = s.fill;
    rep.capacity = s.capacity;
    rep.compensating_group = s.compensating_group;
    rep.trace_pending = s.trace_pending;
    rep.trace_lost = s.trace_lost;
    rep.segments_pending = s.segments_pending;
    rep.segments_lost = s.segments_lost;
    rep.position = s.position;
    return rep;
}

objif::TraceReply FrameServer::read_trace(const objif::TraceRequest& req) {
    objif::TraceReply rep;
    rep.what = req.what;
    if (req.what == objif::TraceKind::kSamples) {
        samples_.resize(std::min<std::size_t>(req.max, objif::kMaxSamplesPerReply));
        samples_.resize(board_.read_trace(samples_));
        rep.samples.reserve(samples_.size());
        for (const auto& s : samples_) rep.samples.push_back({s.cycle, s.position});
    } else {
        segments_.resize(std::min<std::size_t>(req.max, objif::kMaxSegmentsPerReply));
        segments_.resize(board_.read_segments(segments_));
        rep.segments.reserve(segments_.size());
        for (const auto& s : segments_) rep.segments.push_back(wire_segment(s));
    }
    return rep;
}

void FrameServer::reject(std::uint32_t sequence, FrameError why, std::vector<std::uint8_t>& reply) {
    std::vector<std::uint8_t> payload;
    objif::encode(objif::ErrorReply{objif::frame_error_status(why), why}, payload);
    objif::encode_frame(reply_opcode(Opcode::kError), sequence, payload, reply);
}

FrameError FrameServer::serve(std::span<const std::uint8_t> request, std::vector<std::uint8_t>& reply) {
    objif::Frame frame;
    std::size_t used = 0;
    bool need_more = false;
    FrameError e = objif::decode_frame(request, frame, used, need_more);
    if (e == FrameError::kNone && used != request.size()) e = FrameError::kBadLength;  // trailing bytes
    if (e != FrameError::kNone) {
        reject(used != 0 ? frame.sequence : 0, e, reply);
        return e;
    }
    return handle(frame, reply);
}

FrameError FrameServer::handle(const objif::Frame& request, std::vector<std::uint8_t>& reply) {
    payload_.clear();
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
            objif::encode(motion_reply(board_.spool(profile_of(req))), payload_);
            break;
        }
        case Opcode::kDirectCommand: {
            objif::DirectRequest req;
            if (const FrameError e = objif::decode(request.payload, req); e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::encode(motion_reply(board_.direct(direct_of(req))), payload_);
            break;
        }
        case Opcode::kSsfCommand: {
            objif::SsfRequest req;
            if (const FrameError e = objif::decode(request.payload, req); e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::encode(motion_reply(board_.ssf(req.axes, req.command)), payload_);
            break;
        }
        case Opcode::kClock: {
            objif::ClockRequest req;
            if (const FrameError e = objif::decode(request.payload, req); e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::encode(clock(req), payload_);
            break;
        }
        case Opcode::kReadTrace: {
            objif::TraceRequest req;
            if (const FrameError e = objif::decode(request.payload, req); e != FrameError::kNone) {
                reject(request.sequence, e, reply);
                return e;
            }
            objif::encode(read_trace(req), payload_);
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
