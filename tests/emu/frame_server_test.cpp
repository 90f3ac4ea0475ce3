// SPDX-License-Identifier: MIT
// The emulator's side of the wire: every malformed frame class gets an Error
// reply naming the reason, and the board's state does not change.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "objif/frame.h"
#include "rwmos/board.h"
#include "rwmos/frame_server.h"
#include "rwmos/object_map.h"

using objif::FrameError;
using objif::Opcode;
using objif::Status;
using objif::Value;
using objif::ValueType;

namespace {

// Every readable object of every present module, each index of its range.
std::vector<std::pair<std::string, Value>> snapshot(rwmos::EmulatedBoard& board) {
    std::vector<std::pair<std::string, Value>> out;
    for (auto* m : board.dictionary().modules()) {
        if (!m->present()) continue;
        for (std::size_t i = 0; i < m->object_count(); ++i) {
            const auto& info = m->object_at(i);
            if (!objif::can_read(info.access)) continue;
            for (int idx = info.index_first; idx <= info.index_last; ++idx) {
                objif::Descriptor d{{m->bus(), info.device, idx, info.subindex}, 0};
                Value v;
                const Status st = board.read(d, info.type, v);
                out.emplace_back(d.address.to_string() + ":" + std::string(objif::status_name(st)), v);
            }
        }
    }
    return out;
}

std::vector<std::uint8_t> request(Opcode op, std::uint32_t seq, const std::vector<std::uint8_t>& payload) {
    std::vector<std::uint8_t> out;
    objif::encode_frame(static_cast<std::uint16_t>(op), seq, payload, out);
    return out;
}

std::vector<std::uint8_t> write_request(objif::Address a, Value v, std::uint32_t seq = 7) {
    std::vector<std::uint8_t> p;
    objif::encode(objif::WriteRequest{{a, 0}, v}, p);
    return request(Opcode::kObjectWrite, seq, p);
}

struct Reply {
    objif::Frame frame;
    FrameError decode = FrameError::kShort;
};

Reply parse(const std::vector<std::uint8_t>& bytes) {
    Reply r;
    std::size_t used = 0;
    bool more = false;
    r.decode = objif::decode_frame(bytes, r.frame, used, more);
    EXPECT_EQ(used, bytes.size()) << "exactly one reply frame";
    return r;
}

class FrameServerTest : public ::testing::Test {
protected:
    // A board with some non-default state, so "unchanged" means something.
    void SetUp() override {
        rwmos::FrameServer srv(board);
        std::vector<std::uint8_t> reply;
        srv.serve(write_request({rwmos::tc::kBus, rwmos::tc::kDevGroups, 1, rwmos::tc::kSubWkzIndex}, Value::of_int(5)), reply);
        reply.clear();
        srv.serve(write_request({rwmos::tc::kBus, rwmos::tc::kDevGroups, 1, rwmos::tc::kSubRadius}, Value::of_double(2.5)), reply);
        before = snapshot(board);
    }
    // Serves `bytes`, expects an Error reply with `reason`, and an unchanged board.
    void expect_rejected(const std::vector<std::uint8_t>& bytes, FrameError reason, std::uint32_t seq) {
        rwmos::FrameServer srv(board);
        std::vector<std::uint8_t> out;
        EXPECT_EQ(srv.serve(bytes, out), reason);
        const Reply r = parse(out);
        ASSERT_EQ(r.decode, FrameError::kNone);
        EXPECT_EQ(r.frame.opcode, 0xFFFF);
        EXPECT_EQ(r.frame.sequence, seq);
        objif::ErrorReply er;
        ASSERT_EQ(objif::decode(r.frame.payload, er), FrameError::kNone);
        EXPECT_EQ(er.reason, reason) << objif::frame_error_name(er.reason);
        EXPECT_EQ(er.status, objif::frame_error_status(reason));
        EXPECT_EQ(snapshot(board), before) << "a malformed frame changed the board";
    }
    rwmos::EmulatedBoard board;
    std::vector<std::pair<std::string, Value>> before;
    const objif::Address radius{rwmos::tc::kBus, rwmos::tc::kDevGroups, 1, rwmos::tc::kSubRadius};
};

TEST_F(FrameServerTest, WellFormedWriteThenReadRoundTrip) {
    rwmos::FrameServer srv(board);
    std::vector<std::uint8_t> out;
    ASSERT_EQ(srv.serve(write_request(radius, Value::of_double(4.0), 11), out), FrameError::kNone);
    Reply r = parse(out);
    EXPECT_EQ(r.frame.opcode, 0x8002);
    EXPECT_EQ(r.frame.sequence, 11u);
    objif::WriteReply wr;
    ASSERT_EQ(objif::decode(r.frame.payload, wr), FrameError::kNone);
    EXPECT_EQ(wr.status, Status::kOk);
    EXPECT_NE(wr.handle, objif::kNoHandle);

    std::vector<std::uint8_t> p;
    objif::encode(objif::ReadRequest{{radius, wr.handle}, ValueType::kDouble}, p);
    out.clear();
    ASSERT_EQ(srv.serve(request(Opcode::kObjectRead, 12, p), out), FrameError::kNone);
    r = parse(out);
    objif::ReadReply rr;
    ASSERT_EQ(objif::decode(r.frame.payload, rr), FrameError::kNone);
    EXPECT_EQ(rr.status, Status::kOk);
    EXPECT_EQ(rr.value, Value::of_double(4.0));
}

TEST_F(FrameServerTest, BoardRefusalTravelsAsReplyStatus) {
    rwmos::FrameServer srv(board);
    std::vector<std::uint8_t> out;
    ASSERT_EQ(srv.serve(write_request(radius, Value::of_int(4)), out), FrameError::kNone);
    objif::WriteReply wr;
    ASSERT_EQ(objif::decode(parse(out).frame.payload, wr), FrameError::kNone);
    EXPECT_EQ(wr.status, Status::kTypeMismatch);
    EXPECT_EQ(snapshot(board), before);
}

TEST_F(FrameServerTest, ShortFrameIsRejected) {
    auto bytes = write_request(radius, Value::of_double(9.0));
    ASSERT_FALSE(bytes.empty());
    bytes.pop_back();
    expect_rejected(bytes, FrameError::kShort, 0);
    expect_rejected({}, FrameError::kShort, 0);
}

TEST_F(FrameServerTest, BadMagicIsRejected) {
    auto bytes = write_request(radius, Value::of_double(9.0));
    bytes[1] = 'X';
    expect_rejected(bytes, FrameError::kBadMagic, 0);
}

TEST_F(FrameServerTest, BadVersionIsRejected) {
    auto bytes = write_request(radius, Value::of_double(9.0));
    bytes[4] = 7;
    expect_rejected(bytes, FrameError::kBadVersion, 0);
}

TEST_F(FrameServerTest, BadLengthIsRejected) {
    auto bytes = write_request(radius, Value::of_double(9.0));
    const std::uint32_t huge = 0x7FFFFFFF;
    std::memcpy(bytes.data() + 12, &huge, 4);
    expect_rejected(bytes, FrameError::kBadLength, 0);
    // Trailing bytes after a whole frame are a length error in a datagram.
    auto longer = write_request(radius, Value::of_double(9.0));
    longer.push_back(0);
    expect_rejected(longer, FrameError::kBadLength, 7);
}

TEST_F(FrameServerTest, BadCrcIsRejectedEchoingTheSequence) {
    auto bytes = write_request(radius, Value::of_double(9.0), 99);
    bytes[bytes.size() - 6] ^= 0x10;  // a bit of the double
    expect_rejected(bytes, FrameError::kBadCrc, 99);
}

TEST_F(FrameServerTest, UnknownOpcodeIsRejected) {
    expect_rejected(request(static_cast<Opcode>(0x0055), 3, {1, 2, 3}), FrameError::kUnknownOpcode, 3);
    // A reply opcode sent as a request is not served either.
    expect_rejected(request(static_cast<Opcode>(0x8002), 4, {}), FrameError::kUnknownOpcode, 4);
}

TEST_F(FrameServerTest, WrongValueTagIsRejected) {
    std::vector<std::uint8_t> p;
    objif::encode(objif::WriteRequest{{radius, 0}, Value::of_double(9.0)}, p);
    p[20] = 0x33;
    expect_rejected(request(Opcode::kObjectWrite, 5, p), FrameError::kBadValueTag, 5);
}

TEST_F(FrameServerTest, NanAndInfinityAreRejected) {
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
        expect_rejected(write_request(radius, Value::of_double(bad), 6), FrameError::kNotFinite, 6);
}

TEST_F(FrameServerTest, BadPayloadSizeIsRejected) {
    std::vector<std::uint8_t> p;
    objif::encode(objif::ReadRequest{{radius, 0}, ValueType::kDouble}, p);
    p.pop_back();
    expect_rejected(request(Opcode::kObjectRead, 8, p), FrameError::kBadPayload, 8);
    p.push_back(2);
    p.push_back(0);
    expect_rejected(request(Opcode::kObjectRead, 9, p), FrameError::kBadPayload, 9);
}

}  // namespace
