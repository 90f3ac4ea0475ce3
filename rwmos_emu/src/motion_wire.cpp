// SPDX-License-Identifier: MIT
#include "rwmos/motion_wire.h"

#include <algorithm>
#include <string>
#include <vector>

namespace rwmos {
namespace {

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
    w.traverse = s.traverse;
    w.plane_axes = s.plane_axes;
    w.plane = s.plane;
    w.start = s.start;
    w.end = s.end;
    w.center = s.center;
    w.feed = s.feed;
    w.start_cycle = s.start_cycle;
    w.end_cycle = s.end_cycle;
    w.length_start = s.length_start;
    w.length_end = s.length_end;
    return w;
}
}  // namespace

objif::MotionReply serve_spool(EmulatedBoard& board, const objif::SpoolRequest& req) {
    return motion_reply(board.spool(profile_of(req)));
}

void serve_spool(EmulatedBoard& board, const objif::SpoolRequest& req, objif::MotionReply& rep) {
    const motion::MotionResult r = board.spool(profile_of(req));
    rep.status = r.status;
    rep.group = r.group;
    rep.errors = r.errors;
    rep.tag = r.tag;
    // A call that went well has no message: clear() is two stores, assign() of nothing a call.
    if (r.message.empty())
        rep.message.clear();
    else
        rep.message.assign(r.message);
}

objif::MotionReply serve_direct(EmulatedBoard& board, const objif::DirectRequest& req) {
    return motion_reply(board.direct(direct_of(req)));
}

objif::MotionReply serve_ssf(EmulatedBoard& board, const objif::SsfRequest& req) {
    return motion_reply(board.ssf(req.axes, req.command));
}

objif::ClockReply serve_clock(EmulatedBoard& board, const objif::ClockRequest& req) {
    objif::ClockReply rep;
    switch (req.mode) {
        case objif::ClockMode::kStep:
            if (req.cycles > objif::kMaxClockCycles) {
                rep.status = objif::Status::kValueTooHigh;
                break;
            }
            board.step(req.cycles);
            rep.ran = req.cycles;
            break;
        case objif::ClockMode::kRunUntilIdle:
            if (req.cycles > objif::kMaxClockCycles) {
                rep.status = objif::Status::kValueTooHigh;
                break;
            }
            rep.ran = board.run_until_idle(req.cycles);
            break;
        case objif::ClockMode::kQuery:
            break;
        case objif::ClockMode::kTraceOn:
            rep.status = req.cycles > EmulatedBoard::kMaxTraceCapacity
                             ? objif::Status::kValueTooHigh
                             : board.set_trace(true, static_cast<std::size_t>(req.cycles));
            break;
        case objif::ClockMode::kTraceOff:
            rep.status = board.set_trace(false, 0);
            break;
    }
    const motion::MotionStatus s = board.motion_status();
    rep.now = s.now;
    rep.flags = static_cast<std::uint8_t>(
        (s.idle ? objif::kClockIdle : 0) | (s.held ? objif::kClockHeld : 0) |
        (s.profile_held ? objif::kClockProfileHeld : 0) | (s.tracing ? objif::kClockTracing : 0));
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

objif::TraceReply serve_trace(EmulatedBoard& board, const objif::TraceRequest& req) {
    objif::TraceReply rep;
    rep.what = req.what;
    if (req.what == objif::TraceKind::kSamples) {
        std::vector<motion::TraceSample> samples(
            std::min<std::size_t>(req.max, objif::kMaxSamplesPerReply));
        samples.resize(board.read_trace(samples));
        rep.samples.reserve(samples.size());
        for (const auto& s : samples) rep.samples.push_back({s.cycle, s.position});
    } else {
        std::vector<motion::Segment> segments(
            std::min<std::size_t>(req.max, objif::kMaxSegmentsPerReply));
        segments.resize(board.read_segments(segments));
        rep.segments.reserve(segments.size());
        for (const auto& s : segments) rep.segments.push_back(wire_segment(s));
    }
    return rep;
}

}  // namespace rwmos
