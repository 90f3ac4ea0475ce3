// SPDX-License-Identifier: MIT
// Motion payload codecs (SpoolProfile, DirectCommand, SsfCommand, Clock,
// ReadTrace and their replies): round trips, and every malformed case
// refused with its reason.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

#include "objif/frame.h"

using objif::FrameError;
using objif::Status;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

template <class M>
std::vector<std::uint8_t> bytes_of(const M& m) {
    std::vector<std::uint8_t> out;
    objif::encode(m, out);
    return out;
}

// Every prefix of a valid payload is too short, and one byte more is too long.
template <class M>
void expect_exact_size(const std::vector<std::uint8_t>& valid) {
    for (std::size_t n = 0; n < valid.size(); ++n) {
        M m;
        EXPECT_EQ(objif::decode(std::span(valid.data(), n), m), FrameError::kBadPayload)
            << "prefix of " << n << " of " << valid.size() << " bytes";
    }
    auto longer = valid;
    longer.push_back(0);
    M m;
    EXPECT_EQ(objif::decode(longer, m), FrameError::kBadPayload) << "trailing byte";
}

void put_f64(std::vector<std::uint8_t>& b, std::size_t at, double v) {
    std::memcpy(b.data() + at, &v, sizeof v);
}
void put_u32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
    std::memcpy(b.data() + at, &v, sizeof v);
}

objif::SpoolRequest sample_spool() {
    objif::SpoolRequest m;
    m.kind = 3;
    m.axes = 0x07;
    m.arc_axes = {2, 0};
    m.tag = 4711;
    m.feed = 1234.5;
    for (std::size_t i = 0; i < m.target.size(); ++i)
        m.target[i] = 0.5 * static_cast<double>(i) - 1;
    m.center = {-3.25, 7.0};
    return m;
}

objif::WireSegment sample_segment() {
    objif::WireSegment s;
    s.tag = 12;
    s.kind = 1;
    s.role = 1;
    s.ccw = true;
    s.interrupted = false;
    s.plane_axes = {0, 1};
    s.plane = 17;
    s.start[0] = 1;
    s.end[1] = 2;
    s.center[2] = 3;
    s.feed = 600;
    s.start_cycle = 10;
    s.end_cycle = 99;
    s.length_start[2] = 4.5;
    s.length_end[2] = -0.125;
    s.length_end[7] = 2;
    return s;
}

// ---- SpoolProfile

TEST(MotionPayload, SpoolRequestRoundTrips) {
    const auto m = sample_spool();
    const auto b = bytes_of(m);
    EXPECT_EQ(b.size(), 96u);
    objif::SpoolRequest d;
    ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
    EXPECT_EQ(d.kind, 3);
    EXPECT_EQ(d.axes, 0x07);
    EXPECT_EQ(d.arc_axes, m.arc_axes);
    EXPECT_EQ(d.tag, 4711u);
    EXPECT_EQ(d.feed, 1234.5);
    EXPECT_EQ(d.target, m.target);
    EXPECT_EQ(d.center, m.center);
}

TEST(MotionPayload, SpoolRequestOfWrongSizeIsBadPayload) {
    expect_exact_size<objif::SpoolRequest>(bytes_of(sample_spool()));
}

TEST(MotionPayload, SpoolRequestWithANonFiniteNumberIsRefused) {
    for (std::size_t at : {8u, 16u, 16u + 7 * 8, 80u, 88u}) {  // feed, targets, centre
        for (double bad : {kNan, kInf, -kInf}) {
            auto b = bytes_of(sample_spool());
            put_f64(b, at, bad);
            objif::SpoolRequest d;
            EXPECT_EQ(objif::decode(b, d), FrameError::kNotFinite) << "offset " << at;
        }
    }
}

// ---- DirectCommand

TEST(MotionPayload, DirectRequestRoundTrips) {
    objif::DirectRequest m;
    m.code = 1;
    m.axes = 0x81;
    m.feed = 0;
    m.target[7] = -9.5;
    const auto b = bytes_of(m);
    EXPECT_EQ(b.size(), 75u);
    objif::DirectRequest d;
    ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
    EXPECT_EQ(d.code, 1);
    EXPECT_EQ(d.axes, 0x81);
    EXPECT_EQ(d.target, m.target);
    expect_exact_size<objif::DirectRequest>(b);
}

TEST(MotionPayload, DirectRequestWithANonFiniteNumberIsRefused) {
    objif::DirectRequest m;
    auto b = bytes_of(m);
    put_f64(b, 3, kNan);
    objif::DirectRequest d;
    EXPECT_EQ(objif::decode(b, d), FrameError::kNotFinite);
    b = bytes_of(m);
    put_f64(b, 3 + 8 + 8 * 5, kInf);
    EXPECT_EQ(objif::decode(b, d), FrameError::kNotFinite);
}

// ---- SsfCommand

TEST(MotionPayload, SsfRequestRoundTrips) {
    const objif::SsfRequest m{0x03, 2001};
    const auto b = bytes_of(m);
    EXPECT_EQ(b.size(), 5u);
    objif::SsfRequest d;
    ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
    EXPECT_EQ(d.axes, 0x03);
    EXPECT_EQ(d.command, 2001);
    expect_exact_size<objif::SsfRequest>(b);
}

// ---- Motion reply

TEST(MotionPayload, MotionReplyRoundTripsWithItsMessage) {
    const objif::MotionReply m{Status::kWrongDeviceState, 1, 0x04, 17, "arc radius too small"};
    const auto b = bytes_of(m);
    objif::MotionReply d;
    ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
    EXPECT_EQ(d.status, Status::kWrongDeviceState);
    EXPECT_EQ(d.group, 1);
    EXPECT_EQ(d.errors, 0x04);
    EXPECT_EQ(d.tag, 17u);
    EXPECT_EQ(d.message, m.message);
    expect_exact_size<objif::MotionReply>(b);
}

TEST(MotionPayload, MotionReplyWithAnUnknownStatusIsBadPayload) {
    auto b = bytes_of(objif::MotionReply{});
    put_u32(b, 0, 0x12345678);
    objif::MotionReply d;
    EXPECT_EQ(objif::decode(b, d), FrameError::kBadPayload);
}

TEST(MotionPayload, MotionReplyMessageLongerThanTheLimitIsBadPayload) {
    std::vector<std::uint8_t> b = bytes_of(objif::MotionReply{});
    const std::uint16_t n = objif::kMaxMotionMessage + 1;
    std::memcpy(b.data() + 16, &n, 2);
    b.resize(b.size() + n, 'x');
    objif::MotionReply d;
    EXPECT_EQ(objif::decode(b, d), FrameError::kBadPayload);
}

TEST(MotionPayload, MotionReplyEncodesAtMostTheMessageLimit) {
    objif::MotionReply m;
    m.message.assign(5000, 'y');
    objif::MotionReply d;
    ASSERT_EQ(objif::decode(bytes_of(m), d), FrameError::kNone);
    EXPECT_EQ(d.message.size(), objif::kMaxMotionMessage);
}

// ---- Clock

TEST(MotionPayload, ClockRequestRoundTripsEveryMode) {
    for (auto mode :
         {objif::ClockMode::kStep, objif::ClockMode::kRunUntilIdle, objif::ClockMode::kQuery,
          objif::ClockMode::kTraceOn, objif::ClockMode::kTraceOff}) {
        const objif::ClockRequest m{mode, 0x0102030405060708ull};
        const auto b = bytes_of(m);
        EXPECT_EQ(b.size(), 9u);
        objif::ClockRequest d;
        ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
        EXPECT_EQ(d.mode, mode);
        EXPECT_EQ(d.cycles, m.cycles);
        expect_exact_size<objif::ClockRequest>(b);
    }
}

TEST(MotionPayload, ClockRequestWithAnUnknownModeIsBadPayload) {
    auto b = bytes_of(objif::ClockRequest{});
    b[0] = 5;
    objif::ClockRequest d;
    EXPECT_EQ(objif::decode(b, d), FrameError::kBadPayload);
}

objif::ClockReply sample_clock_reply() {
    objif::ClockReply m;
    m.status = Status::kOk;
    m.ran = 5;
    m.now = 123456789;
    m.flags = objif::kClockIdle | objif::kClockTracing;
    m.fill = 3;
    m.capacity = 256;
    m.compensating_group = 2;
    m.trace_pending = 7;
    m.trace_lost = 1;
    m.segments_pending = 9;
    m.segments_lost = 0;
    m.position[3] = 4.25;
    return m;
}

TEST(MotionPayload, ClockReplyRoundTrips) {
    const auto m = sample_clock_reply();
    const auto b = bytes_of(m);
    objif::ClockReply d;
    ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
    EXPECT_EQ(d.now, m.now);
    EXPECT_EQ(d.flags, m.flags);
    EXPECT_EQ(d.fill, 3u);
    EXPECT_EQ(d.capacity, 256u);
    EXPECT_EQ(d.compensating_group, 2);
    EXPECT_EQ(d.trace_pending, 7u);
    EXPECT_EQ(d.position, m.position);
    expect_exact_size<objif::ClockReply>(b);
}

TEST(MotionPayload, ClockReplyWithAnUnknownFlagOrStatusOrNaNIsRefused) {
    objif::ClockReply d;
    auto b = bytes_of(sample_clock_reply());
    b[20] = 0x10;  // flags: an undefined bit
    EXPECT_EQ(objif::decode(b, d), FrameError::kBadPayload);
    b = bytes_of(sample_clock_reply());
    put_u32(b, 0, 0xDEADBEEF);
    EXPECT_EQ(objif::decode(b, d), FrameError::kBadPayload);
    b = bytes_of(sample_clock_reply());
    put_f64(b, b.size() - 8, kNan);
    EXPECT_EQ(objif::decode(b, d), FrameError::kNotFinite);
}

// ---- ReadTrace

TEST(MotionPayload, TraceRequestRoundTripsAndRefusesAnUnknownKind) {
    const objif::TraceRequest m{objif::TraceKind::kSegments, 300};
    auto b = bytes_of(m);
    EXPECT_EQ(b.size(), 5u);
    objif::TraceRequest d;
    ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
    EXPECT_EQ(d.what, objif::TraceKind::kSegments);
    EXPECT_EQ(d.max, 300u);
    expect_exact_size<objif::TraceRequest>(b);
    b[0] = 2;
    EXPECT_EQ(objif::decode(b, d), FrameError::kBadPayload);
}

TEST(MotionPayload, TraceReplyOfSamplesRoundTrips) {
    objif::TraceReply m;
    m.what = objif::TraceKind::kSamples;
    for (std::uint64_t i = 1; i <= 3; ++i) m.samples.push_back({i, {static_cast<double>(i)}});
    const auto b = bytes_of(m);
    EXPECT_EQ(b.size(), objif::kTraceReplyHeader + 3 * objif::kWireSampleSize);
    objif::TraceReply d;
    ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
    ASSERT_EQ(d.samples.size(), 3u);
    EXPECT_EQ(d.samples[2].cycle, 3u);
    EXPECT_EQ(d.samples[2].position[0], 3.0);
    expect_exact_size<objif::TraceReply>(b);
}

TEST(MotionPayload, TraceReplyOfSegmentsRoundTrips) {
    objif::TraceReply m;
    m.what = objif::TraceKind::kSegments;
    m.segments = {sample_segment(), sample_segment()};
    m.segments[1].role = 5;
    m.segments[1].interrupted = true;
    m.segments[1].traverse = true;
    const auto b = bytes_of(m);
    EXPECT_EQ(b.size(), objif::kTraceReplyHeader + 2 * objif::kWireSegmentSize);
    // The flags byte (docs/motion.md section 9): 0x01 interrupted, 0x02 traverse.
    EXPECT_EQ(b[objif::kTraceReplyHeader + 7], 0x00);
    EXPECT_EQ(b[objif::kTraceReplyHeader + objif::kWireSegmentSize + 7], 0x03);
    objif::TraceReply d;
    ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
    ASSERT_EQ(d.segments.size(), 2u);
    EXPECT_EQ(d.segments[0].tag, 12u);
    EXPECT_TRUE(d.segments[0].ccw);
    EXPECT_EQ(d.segments[0].plane, 17);
    EXPECT_EQ(d.segments[0].center, m.segments[0].center);
    EXPECT_EQ(d.segments[0].end_cycle, 99u);
    EXPECT_EQ(d.segments[0].length_start, m.segments[0].length_start);
    EXPECT_EQ(d.segments[0].length_end, m.segments[0].length_end);
    EXPECT_TRUE(d.segments[1].interrupted);
    EXPECT_FALSE(d.segments[0].traverse);
    EXPECT_TRUE(d.segments[1].traverse);
    expect_exact_size<objif::TraceReply>(b);
}

TEST(MotionPayload, TraceReplyEncodesAtMostOneFrameOfItems) {
    objif::TraceReply m;
    m.samples.resize(objif::kMaxSamplesPerReply + 10);
    const auto b = bytes_of(m);
    EXPECT_LE(b.size(), objif::kMaxPayload);
    objif::TraceReply d;
    ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
    EXPECT_EQ(d.samples.size(), objif::kMaxSamplesPerReply);
}

TEST(MotionPayload, TraceReplyWithBadContentIsRefused) {
    objif::TraceReply m;
    m.what = objif::TraceKind::kSegments;
    m.segments = {sample_segment()};
    const auto good = bytes_of(m);
    objif::TraceReply d;
    struct Case {
        const char* what;
        std::size_t at;
        std::uint8_t value;
        FrameError want;
    };
    const std::size_t seg = objif::kTraceReplyHeader;
    const Case cases[] = {
        {"unknown trace kind", 4, 2, FrameError::kBadPayload},
        {"count above the items sent", 5, 2, FrameError::kBadPayload},
        {"segment kind 2", seg + 4, 2, FrameError::kBadPayload},
        {"segment role 6", seg + 5, 6, FrameError::kBadPayload},
        {"ccw neither 0 nor 1", seg + 6, 2, FrameError::kBadPayload},
        {"a flag bit other than interrupted and traverse", seg + 7, 4, FrameError::kBadPayload},
        {"flag bits beyond the two", seg + 7, 7, FrameError::kBadPayload},
    };
    for (const Case& c : cases) {
        auto b = good;
        b[c.at] = c.value;
        EXPECT_EQ(objif::decode(b, d), c.want) << c.what;
    }
    auto b = good;
    put_f64(b, seg + 14, kNan);  // start[0]
    EXPECT_EQ(objif::decode(b, d), FrameError::kNotFinite);
    // The lengths close the record: length_start[0] after the cycles, length_end[7] its last.
    const std::size_t lengths = seg + 14 + objif::kWireAxisCount * 3 * 8 + 8 + 16;
    b = good;
    put_f64(b, lengths, kNan);
    EXPECT_EQ(objif::decode(b, d), FrameError::kNotFinite) << "length_start[0]";
    b = good;
    put_f64(b, seg + objif::kWireSegmentSize - 8, std::numeric_limits<double>::infinity());
    EXPECT_EQ(objif::decode(b, d), FrameError::kNotFinite) << "length_end[7]";
    b = good;
    put_f64(b, seg + objif::kWireSegmentSize - 8, 0.5);
    ASSERT_EQ(objif::decode(b, d), FrameError::kNone);
    EXPECT_EQ(d.segments[0].length_end[7], 0.5) << "the last 8 bytes are length_end[7]";
    b = good;
    put_u32(b, 0, 0xFFFFFFFF);
    EXPECT_EQ(objif::decode(b, d), FrameError::kBadPayload) << "unknown status";
    b = good;
    put_u32(b, 5, static_cast<std::uint32_t>(objif::kMaxSegmentsPerReply + 1));
    EXPECT_EQ(objif::decode(b, d), FrameError::kBadPayload) << "count above the frame limit";
}

}  // namespace
