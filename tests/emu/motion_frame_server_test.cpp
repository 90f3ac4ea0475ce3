// SPDX-License-Identifier: MIT
// The motion opcodes over wire frames: SpoolProfile, DirectCommand,
// SsfCommand, Clock and ReadTrace are served from the board, and every
// malformed motion payload gets an Error reply with no state change.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "motion_fixture.h"
#include "objif/frame.h"
#include "rwmos/frame_server.h"
#include "rwmos/motion_wire.h"

using namespace motion_test;
using objif::FrameError;
using objif::Opcode;
namespace tc = rwmos::tc;

namespace {

template <class M>
std::vector<std::uint8_t> frame(Opcode op, const M& m, std::uint32_t seq = 1) {
    std::vector<std::uint8_t> payload, out;
    objif::encode(m, payload);
    objif::encode_frame(static_cast<std::uint16_t>(op), seq, payload, out);
    return out;
}

std::vector<std::uint8_t> raw_frame(Opcode op, const std::vector<std::uint8_t>& payload) {
    std::vector<std::uint8_t> out;
    objif::encode_frame(static_cast<std::uint16_t>(op), 9, payload, out);
    return out;
}

objif::SpoolRequest wire_line(std::uint32_t tag, double x, double y) {
    objif::SpoolRequest r;
    r.kind = 1;
    r.axes = 0x03;
    r.tag = tag;
    r.feed = 600;
    r.target[0] = x;
    r.target[1] = y;
    return r;
}

class MotionFrames : public MotionBoard {
  protected:
    rwmos::FrameServer server{board};

    // Serves one well-formed request and decodes its reply payload as M.
    template <class M, class R>
    M call(Opcode op, const R& req) {
        std::vector<std::uint8_t> out;
        EXPECT_EQ(server.serve(frame(op, req), out), FrameError::kNone);
        objif::Frame f;
        std::size_t used = 0;
        bool more = false;
        EXPECT_EQ(objif::decode_frame(out, f, used, more), FrameError::kNone);
        EXPECT_EQ(f.opcode,
                  static_cast<std::uint16_t>(static_cast<std::uint16_t>(op) | objif::kReplyFlag));
        M m;
        EXPECT_EQ(objif::decode(f.payload, m), FrameError::kNone);
        return m;
    }
    objif::ClockReply clock(objif::ClockMode mode, std::uint64_t cycles = 0) {
        return call<objif::ClockReply>(Opcode::kClock, objif::ClockRequest{mode, cycles});
    }
    // Serves a malformed request: an Error reply with `reason`, nothing changed.
    void expect_rejected(const std::vector<std::uint8_t>& bytes, FrameError reason) {
        const auto before = board.motion_status();
        std::vector<std::uint8_t> out;
        EXPECT_EQ(server.serve(bytes, out), reason);
        objif::Frame f;
        std::size_t used = 0;
        bool more = false;
        ASSERT_EQ(objif::decode_frame(out, f, used, more), FrameError::kNone);
        EXPECT_EQ(f.opcode, 0xFFFF);
        objif::ErrorReply er;
        ASSERT_EQ(objif::decode(f.payload, er), FrameError::kNone);
        EXPECT_EQ(er.reason, reason);
        const auto after = board.motion_status();
        EXPECT_EQ(after.now, before.now);
        EXPECT_EQ(after.fill, before.fill);
        EXPECT_EQ(after.position, before.position);
        EXPECT_EQ(after.tracing, before.tracing);
        EXPECT_EQ(after.segments_pending, before.segments_pending);
    }
};

TEST_F(MotionFrames, SpoolProfileFrameSpoolsAndRepliesOk) {
    const auto r = call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(5, 1, 0));
    EXPECT_EQ(r.status, Status::kOk);
    EXPECT_TRUE(r.message.empty());
    EXPECT_EQ(board.motion_status().fill, 1u);
}

TEST_F(MotionFrames, SpoolProfileReplyNamesTheTcErrorGroupBitsAndBlock) {
    setup_group(5.0);
    activate();
    ASSERT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(1, 10, 0)).status,
              Status::kOk);
    objif::SpoolRequest bad_arc = wire_line(2, 10, 4);
    bad_arc.kind = 3;
    bad_arc.center = {10, 2};
    const auto r = call<objif::MotionReply>(Opcode::kSpoolProfile, bad_arc);
    EXPECT_EQ(r.status, Status::kWrongDeviceState);
    EXPECT_EQ(r.group, 1);
    EXPECT_EQ(r.errors, tc::kCalcError);
    EXPECT_EQ(r.tag, 2u);
    EXPECT_FALSE(r.message.empty());
}

// The in-process transport's form: the reply written into one the caller keeps, every field of
// the call before overwritten.
TEST_F(MotionFrames, SpoolIntoAKeptReplyOverwritesEveryFieldOfTheLastOne) {
    setup_group(5.0);
    activate();
    objif::MotionReply rep;
    rwmos::serve_spool(board, wire_line(1, 10, 0), rep);
    ASSERT_EQ(rep.status, Status::kOk);
    objif::SpoolRequest bad_arc = wire_line(2, 10, 4);
    bad_arc.kind = 3;
    bad_arc.center = {10, 2};
    rwmos::serve_spool(board, bad_arc, rep);
    EXPECT_EQ(rep.status, Status::kWrongDeviceState);
    EXPECT_EQ(rep.group, 1);
    EXPECT_EQ(rep.errors, tc::kCalcError);
    EXPECT_EQ(rep.tag, 2u);
    EXPECT_FALSE(rep.message.empty());
    ASSERT_EQ(write_int(tc::kBus, tc::kDevGroups, 1, tc::kSubError, 0), Status::kOk);
    rwmos::serve_spool(board, wire_line(3, 20, 0), rep);
    EXPECT_EQ(rep.status, Status::kOk);
    EXPECT_EQ(rep.group, 0);
    EXPECT_EQ(rep.errors, 0);
    EXPECT_EQ(rep.tag, 0u);
    EXPECT_TRUE(rep.message.empty()) << rep.message;
}

TEST_F(MotionFrames, BadProfileTravelsAsReplyStatus) {
    objif::SpoolRequest r = wire_line(1, 1, 1);
    r.kind = 9;
    EXPECT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, r).status, Status::kInvalidValue);
    EXPECT_EQ(board.motion_status().fill, 0u);
}

TEST_F(MotionFrames, SpoolerFullTravelsAsBusy) {
    board.state().spooler.capacity = 1;
    ASSERT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(1, 1, 0)).status,
              Status::kOk);
    EXPECT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(2, 2, 0)).status,
              Status::kBusy);
}

TEST_F(MotionFrames, DirectCommandFrameDiscardsTheSpooler) {
    ASSERT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(1, 1, 0)).status,
              Status::kOk);
    objif::DirectRequest js;
    js.code = static_cast<std::uint16_t>(DirectCode::kJS);
    EXPECT_EQ(call<objif::MotionReply>(Opcode::kDirectCommand, js).status, Status::kOk);
    EXPECT_EQ(board.motion_status().fill, 0u);
}

TEST_F(MotionFrames, SsfCommandFrameReleasesTheHeldProfile) {
    setup_group(1.0);
    activate();
    ASSERT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(1, 10, 0)).status,
              Status::kOk);
    ASSERT_TRUE(prof_marked());
    EXPECT_EQ(call<objif::MotionReply>(Opcode::kSsfCommand, objif::SsfRequest{0x03, 2001}).status,
              Status::kOk);
    EXPECT_FALSE(prof_marked());
    EXPECT_EQ(call<objif::MotionReply>(Opcode::kSsfCommand, objif::SsfRequest{0x03, 7}).status,
              Status::kInvalidValue);
}

TEST_F(MotionFrames, ClockFrameStepsRunsAndReports) {
    ASSERT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(1, 1, 0)).status,
              Status::kOk);
    auto r = clock(objif::ClockMode::kStep, 30);
    EXPECT_EQ(r.status, Status::kOk);
    EXPECT_EQ(r.ran, 30u);
    EXPECT_EQ(r.now, 30u);
    EXPECT_EQ(r.fill, 1u);
    EXPECT_EQ(r.flags & objif::kClockIdle, 0);
    EXPECT_DOUBLE_EQ(r.position[0], 0.3);
    r = clock(objif::ClockMode::kRunUntilIdle, 1'000'000);
    EXPECT_EQ(r.ran, 70u);
    EXPECT_EQ(r.now, 100u);
    EXPECT_NE(r.flags & objif::kClockIdle, 0);
    EXPECT_EQ(r.segments_pending, 1u);
    r = clock(objif::ClockMode::kQuery);
    EXPECT_EQ(r.ran, 0u);
    EXPECT_EQ(r.now, 100u);
    EXPECT_EQ(r.capacity, board.motion_status().capacity);
}

TEST_F(MotionFrames, ClockFrameAdvancesAtMostMaxClockCyclesPerRequest) {
    ASSERT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(1, 1, 0)).status,
              Status::kOk);
    const auto before = board.motion_status();
    for (const auto mode : {objif::ClockMode::kStep, objif::ClockMode::kRunUntilIdle}) {
        const auto r = clock(mode, objif::kMaxClockCycles + 1);
        EXPECT_EQ(r.status, Status::kValueTooHigh);
        EXPECT_EQ(r.ran, 0u);
        EXPECT_EQ(r.now, before.now) << "a refused request runs nothing";
        EXPECT_EQ(r.fill, before.fill);
    }
    EXPECT_EQ(board.motion_status().position, before.position);
    const auto r = clock(objif::ClockMode::kStep, objif::kMaxClockCycles);
    EXPECT_EQ(r.status, Status::kOk);
    EXPECT_EQ(r.ran, objif::kMaxClockCycles);
    EXPECT_EQ(r.now, before.now + objif::kMaxClockCycles);
}

TEST_F(MotionFrames, ClockFrameTurnsTheTraceOnAndReadTraceFetchesTheSamples) {
    auto r = clock(objif::ClockMode::kTraceOn, 1000);
    ASSERT_EQ(r.status, Status::kOk);
    EXPECT_NE(r.flags & objif::kClockTracing, 0);
    ASSERT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(1, 0.05, 0)).status,
              Status::kOk);
    clock(objif::ClockMode::kStep, 5);
    const auto t = call<objif::TraceReply>(Opcode::kReadTrace,
                                           objif::TraceRequest{objif::TraceKind::kSamples, 3});
    ASSERT_EQ(t.samples.size(), 3u);
    EXPECT_EQ(t.samples[0].cycle, 1u);
    EXPECT_DOUBLE_EQ(t.samples[2].position[0], 0.03);
    EXPECT_EQ(clock(objif::ClockMode::kQuery).trace_pending, 2u);
    EXPECT_EQ(clock(objif::ClockMode::kTraceOn, rwmos::EmulatedBoard::kMaxTraceCapacity + 1).status,
              Status::kValueTooHigh);
    EXPECT_EQ(clock(objif::ClockMode::kTraceOn, 0).status, Status::kValueTooLow);
    r = clock(objif::ClockMode::kTraceOff);
    EXPECT_EQ(r.flags & objif::kClockTracing, 0);
}

TEST_F(MotionFrames, ReadTraceFetchesExecutedSegmentsWithRoleAndTag) {
    ASSERT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(7, 1, 0)).status,
              Status::kOk);
    objif::SpoolRequest arc = wire_line(8, 0, 1);
    arc.kind = 3;
    arc.center = {0, 0};
    ASSERT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, arc).status, Status::kOk);
    clock(objif::ClockMode::kRunUntilIdle, 1'000'000);
    const auto t = call<objif::TraceReply>(Opcode::kReadTrace,
                                           objif::TraceRequest{objif::TraceKind::kSegments, 100});
    ASSERT_EQ(t.segments.size(), 2u);
    EXPECT_EQ(t.segments[0].tag, 7u);
    EXPECT_EQ(t.segments[0].role, static_cast<std::uint8_t>(SegmentRole::kUncompensated));
    EXPECT_EQ(t.segments[1].tag, 8u);
    EXPECT_EQ(t.segments[1].kind, static_cast<std::uint8_t>(SegmentKind::kArc));
    EXPECT_TRUE(t.segments[1].ccw);
    EXPECT_EQ(t.segments[1].plane, 17);
    EXPECT_EQ(clock(objif::ClockMode::kQuery).segments_pending, 0u);
}

TEST_F(MotionFrames, EveryTruncatedOrOverlongMotionPayloadIsRejected) {
    ASSERT_EQ(call<objif::MotionReply>(Opcode::kSpoolProfile, wire_line(1, 1, 0)).status,
              Status::kOk);
    std::vector<std::pair<Opcode, std::vector<std::uint8_t>>> valid;
    auto add = [&](Opcode op, const auto& m) {
        std::vector<std::uint8_t> p;
        objif::encode(m, p);
        valid.emplace_back(op, p);
    };
    add(Opcode::kSpoolProfile, wire_line(2, 2, 0));
    add(Opcode::kDirectCommand, objif::DirectRequest{});
    add(Opcode::kSsfCommand, objif::SsfRequest{1, 2001});
    add(Opcode::kClock, objif::ClockRequest{objif::ClockMode::kStep, 10});
    add(Opcode::kReadTrace, objif::TraceRequest{objif::TraceKind::kSegments, 10});
    for (const auto& [op, payload] : valid) {
        for (std::size_t n = 0; n < payload.size(); ++n)
            expect_rejected(
                raw_frame(op, {payload.begin(), payload.begin() + static_cast<long>(n)}),
                FrameError::kBadPayload);
        auto longer = payload;
        longer.push_back(1);
        expect_rejected(raw_frame(op, longer), FrameError::kBadPayload);
    }
}

TEST_F(MotionFrames, NonFiniteNumbersAndUnknownModesAreRejected) {
    objif::SpoolRequest r = wire_line(2, 2, 0);
    r.feed = std::numeric_limits<double>::quiet_NaN();
    expect_rejected(frame(Opcode::kSpoolProfile, r), FrameError::kNotFinite);
    objif::DirectRequest ja;
    ja.code = 1;
    ja.axes = 1;
    ja.target[0] = std::numeric_limits<double>::infinity();
    expect_rejected(frame(Opcode::kDirectCommand, ja), FrameError::kNotFinite);
    std::vector<std::uint8_t> p;
    objif::encode(objif::ClockRequest{objif::ClockMode::kStep, 5}, p);
    p[0] = 9;
    expect_rejected(raw_frame(Opcode::kClock, p), FrameError::kBadPayload);
    p.clear();
    objif::encode(objif::TraceRequest{}, p);
    p[0] = 3;
    expect_rejected(raw_frame(Opcode::kReadTrace, p), FrameError::kBadPayload);
}

}  // namespace
