// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "objif/frame.h"

using objif::FrameError;
using objif::Status;
using objif::Value;
using objif::ValueType;

namespace {

std::vector<std::uint8_t> frame_of(std::uint16_t op, std::uint32_t seq, const std::vector<std::uint8_t>& payload) {
    std::vector<std::uint8_t> out;
    objif::encode_frame(op, seq, payload, out);
    return out;
}

std::vector<std::uint8_t> write_frame(Value v) {
    objif::WriteRequest req{{{1300, 1, 1, 7}, 0}, v};
    std::vector<std::uint8_t> payload;
    objif::encode(req, payload);
    return frame_of(static_cast<std::uint16_t>(objif::Opcode::kObjectWrite), 5, payload);
}

FrameError decode(const std::vector<std::uint8_t>& bytes, objif::Frame& f, bool& more) {
    std::size_t used = 0;
    return objif::decode_frame(bytes, f, used, more);
}


TEST(WireFrame, RoundTripKeepsOpcodeSequenceAndPayload) {
    const std::vector<std::uint8_t> payload{1, 2, 3, 250};
    auto bytes = frame_of(0x0002, 0xA1B2C3D4, payload);
    ASSERT_EQ(bytes.size(), objif::kFrameOverhead + payload.size());
    objif::Frame f;
    bool more = true;
    std::size_t used = 0;
    ASSERT_EQ(objif::decode_frame(bytes, f, used, more), FrameError::kNone);
    EXPECT_FALSE(more);
    EXPECT_EQ(used, bytes.size());
    EXPECT_EQ(f.opcode, 0x0002);
    EXPECT_EQ(f.sequence, 0xA1B2C3D4u);
    EXPECT_EQ(f.payload, payload);
}

TEST(WireFrame, HeaderIsLittleEndianWithMagicApci) {
    auto bytes = frame_of(0x0001, 1, {});
    EXPECT_EQ(bytes[0], 'A');
    EXPECT_EQ(bytes[1], 'P');
    EXPECT_EQ(bytes[2], 'C');
    EXPECT_EQ(bytes[3], 'I');
    EXPECT_EQ(bytes[4], 2);  // version
    EXPECT_EQ(bytes[5], 0);
}

TEST(WireFrame, EveryPrefixOfAValidFrameAsksForMore) {
    auto bytes = write_frame(Value::of_double(2.5));
    for (std::size_t n = 0; n < bytes.size(); ++n) {
        std::vector<std::uint8_t> prefix(bytes.begin(), bytes.begin() + static_cast<long>(n));
        objif::Frame f;
        bool more = false;
        EXPECT_EQ(decode(prefix, f, more), FrameError::kShort) << n;
        EXPECT_TRUE(more) << n;
    }
}

TEST(WireFrame, BadMagicIsRefusedAtOnce) {
    auto bytes = write_frame(Value::of_int(1));
    bytes[0] = 'X';
    objif::Frame f;
    bool more = true;
    EXPECT_EQ(decode(bytes, f, more), FrameError::kBadMagic);
    EXPECT_FALSE(more);
    // Even a two-byte garbage prefix is refused without waiting for more.
    std::vector<std::uint8_t> garbage{'G', 'E'};
    EXPECT_EQ(decode(garbage, f, more), FrameError::kBadMagic);
}

TEST(WireFrame, BadVersionIsRefused) {
    auto bytes = write_frame(Value::of_int(1));
    for (std::uint8_t v : {1, 3}) {  // the version before (0.1.0's) and the one after
        bytes[4] = v;
        objif::Frame f;
        bool more;
        EXPECT_EQ(decode(bytes, f, more), FrameError::kBadVersion) << int{v};
    }
}

TEST(WireFrame, OversizedLengthIsRefusedBeforeReadingThePayload) {
    auto bytes = write_frame(Value::of_int(1));
    const std::uint32_t len = objif::kMaxPayload + 1;
    std::memcpy(bytes.data() + 12, &len, 4);
    bytes.resize(16);  // the header alone is enough to refuse it
    objif::Frame f;
    bool more = true;
    EXPECT_EQ(decode(bytes, f, more), FrameError::kBadLength);
    EXPECT_FALSE(more);
}

TEST(WireFrame, BadCrcIsRefused) {
    auto bytes = write_frame(Value::of_int(1));
    bytes[18] ^= 0x40;  // flip a payload bit
    objif::Frame f;
    bool more;
    EXPECT_EQ(decode(bytes, f, more), FrameError::kBadCrc);
    auto bytes2 = write_frame(Value::of_int(1));
    bytes2.back() ^= 0x01;  // flip a CRC bit
    EXPECT_EQ(decode(bytes2, f, more), FrameError::kBadCrc);
}

TEST(WireFrame, BadCrcFrameCanBeSkippedInAStream) {
    auto bytes = write_frame(Value::of_int(1));
    bytes[18] ^= 0x40;
    objif::Frame f;
    bool more;
    std::size_t used = 0;
    EXPECT_EQ(objif::decode_frame(bytes, f, used, more), FrameError::kBadCrc);
    EXPECT_EQ(used, bytes.size());
    EXPECT_EQ(f.sequence, 5u) << "the error reply can echo the sequence";
}

TEST(WireFrame, GarbageConsumesNothing) {
    auto bytes = write_frame(Value::of_int(1));
    bytes[4] = 9;
    objif::Frame f;
    bool more;
    std::size_t used = 99;
    EXPECT_EQ(objif::decode_frame(bytes, f, used, more), FrameError::kBadVersion);
    EXPECT_EQ(used, 0u);
}

TEST(WireFrame, UnknownOpcodeIsRefused) {
    auto bytes = frame_of(0x0042, 1, {});
    objif::Frame f;
    bool more;
    EXPECT_EQ(decode(bytes, f, more), FrameError::kUnknownOpcode);
    EXPECT_EQ(objif::frame_error_status(FrameError::kUnknownOpcode), Status::kUnknownOpcode);
}

TEST(WireFrame, TwoFramesBackToBackDecodeOneAtATime) {
    auto a = frame_of(0x0001, 1, {9});
    auto b = frame_of(0x0002, 2, {8, 7});
    std::vector<std::uint8_t> both = a;
    both.insert(both.end(), b.begin(), b.end());
    objif::Frame f;
    bool more;
    std::size_t used;
    ASSERT_EQ(objif::decode_frame(both, f, used, more), FrameError::kNone);
    EXPECT_EQ(used, a.size());
    EXPECT_EQ(f.sequence, 1u);
    std::span<const std::uint8_t> rest(both.data() + used, both.size() - used);
    ASSERT_EQ(objif::decode_frame(rest, f, used, more), FrameError::kNone);
    EXPECT_EQ(f.sequence, 2u);
}

TEST(WirePayload, ReadRequestRoundTrip) {
    objif::ReadRequest req{{{1300, 1, 2, 7}, 0x00010003}, ValueType::kDouble}, back;
    std::vector<std::uint8_t> p;
    objif::encode(req, p);
    ASSERT_EQ(objif::decode(p, back), FrameError::kNone);
    EXPECT_EQ(back.descriptor.address, req.descriptor.address);
    EXPECT_EQ(back.descriptor.handle, req.descriptor.handle);
    EXPECT_EQ(back.want, ValueType::kDouble);
}

TEST(WirePayload, ReadRequestWithBadTypeTagIsRefused) {
    objif::ReadRequest req{{{1300, 1, 2, 7}, 0}, ValueType::kDouble}, back;
    std::vector<std::uint8_t> p;
    objif::encode(req, p);
    p.back() = 9;
    EXPECT_EQ(objif::decode(p, back), FrameError::kBadValueTag);
}

TEST(WirePayload, WriteRequestRoundTripBothTypes) {
    for (Value v : {Value::of_int(-123456), Value::of_double(2.5)}) {
        objif::WriteRequest req{{{1300, 1, 1, 7}, 3}, v}, back;
        std::vector<std::uint8_t> p;
        objif::encode(req, p);
        ASSERT_EQ(objif::decode(p, back), FrameError::kNone);
        EXPECT_EQ(back.value, v);
    }
}

TEST(WirePayload, WrongValueTagIsRefused) {
    objif::WriteRequest req{{{1300, 1, 1, 7}, 0}, Value::of_int(1)}, back;
    std::vector<std::uint8_t> p;
    objif::encode(req, p);
    p[20] = 0;  // tag byte follows the 20-byte descriptor
    EXPECT_EQ(objif::decode(p, back), FrameError::kBadValueTag);
    p[20] = 3;
    EXPECT_EQ(objif::decode(p, back), FrameError::kBadValueTag);
    EXPECT_EQ(objif::frame_error_status(FrameError::kBadValueTag), Status::kTypeMismatch);
}

TEST(WirePayload, TagThatDisagreesWithLengthIsRefused) {
    // An int tag followed by 8 bytes: the payload is too long for its tag.
    objif::WriteRequest req{{{1300, 1, 1, 7}, 0}, Value::of_double(1.0)}, back;
    std::vector<std::uint8_t> p;
    objif::encode(req, p);
    p[20] = static_cast<std::uint8_t>(ValueType::kInt32);
    EXPECT_EQ(objif::decode(p, back), FrameError::kBadPayload);
}

TEST(WirePayload, NanAndInfinityAreRefused) {
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                       -std::numeric_limits<double>::infinity()}) {
        objif::WriteRequest req{{{1300, 1, 1, 7}, 0}, Value::of_double(bad)}, back;
        std::vector<std::uint8_t> p;
        objif::encode(req, p);
        EXPECT_EQ(objif::decode(p, back), FrameError::kNotFinite);
    }
    EXPECT_EQ(objif::frame_error_status(FrameError::kNotFinite), Status::kInvalidValue);
}

TEST(WirePayload, ShortAndLongPayloadsAreRefused) {
    objif::WriteRequest req{{{1300, 1, 1, 7}, 0}, Value::of_int(1)}, back;
    std::vector<std::uint8_t> p;
    objif::encode(req, p);
    for (std::size_t n = 0; n < p.size(); ++n) {
        std::vector<std::uint8_t> cut(p.begin(), p.begin() + static_cast<long>(n));
        EXPECT_NE(objif::decode(cut, back), FrameError::kNone) << n;
    }
    p.push_back(0);
    EXPECT_EQ(objif::decode(p, back), FrameError::kBadPayload);
}

TEST(WirePayload, RepliesRoundTrip) {
    objif::ReadReply rr{Status::kOk, 77, Value::of_double(-0.125)}, rback;
    std::vector<std::uint8_t> p;
    objif::encode(rr, p);
    ASSERT_EQ(objif::decode(p, rback), FrameError::kNone);
    EXPECT_EQ(rback.value, rr.value);
    EXPECT_EQ(rback.handle, 77u);

    objif::ReadReply err{Status::kWriteOnly, 0, {}};
    p.clear();
    objif::encode(err, p);
    EXPECT_EQ(p.size(), 8u) << "an error reply carries no value";
    ASSERT_EQ(objif::decode(p, rback), FrameError::kNone);
    EXPECT_EQ(rback.status, Status::kWriteOnly);

    objif::WriteReply wr{Status::kWrongDeviceState, 5}, wback;
    p.clear();
    objif::encode(wr, p);
    ASSERT_EQ(objif::decode(p, wback), FrameError::kNone);
    EXPECT_EQ(wback.status, Status::kWrongDeviceState);

    objif::ErrorReply er{Status::kBadFrame, FrameError::kBadCrc}, eback;
    p.clear();
    objif::encode(er, p);
    ASSERT_EQ(objif::decode(p, eback), FrameError::kNone);
    EXPECT_EQ(eback.reason, FrameError::kBadCrc);
}

TEST(WirePayload, ReplyWithUnknownStatusCodeIsRefused) {
    std::vector<std::uint8_t> p;
    objif::ByteWriter w(p);
    w.u32(0xDEADBEEF);
    w.u32(0);
    objif::WriteReply back;
    EXPECT_EQ(objif::decode(p, back), FrameError::kBadPayload);
}

TEST(WireFrame, EveryFrameErrorHasAName) {
    for (int e = 0; e <= static_cast<int>(FrameError::kNotFinite); ++e)
        EXPECT_NE(objif::frame_error_name(static_cast<FrameError>(e)), "unknown frame error");
}

}  // namespace
