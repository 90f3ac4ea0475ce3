// SPDX-License-Identifier: MIT
// rwmos::FrameStream: request frames from a byte stream, served in order,
// malformed ones answered or the stream dropped (docs/wire-frame.md).
#include "rwmos/frame_stream.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <limits>
#include <vector>

#include "objif/frame.h"
#include "rwmos/board.h"

namespace {

using objif::FrameError;

std::vector<std::uint8_t> read_frame(std::uint32_t seq) {
    std::vector<std::uint8_t> payload, out;
    objif::encode(
        objif::ReadRequest{objif::Descriptor{{1000, 0, 3, 0}, 0}, objif::ValueType::kInt32},
        payload);
    objif::encode_frame(static_cast<std::uint16_t>(objif::Opcode::kObjectRead), seq, payload, out);
    return out;
}

std::vector<objif::Frame> frames_in(const std::vector<std::uint8_t>& bytes) {
    std::vector<objif::Frame> frames;
    std::size_t at = 0;
    while (at < bytes.size()) {
        objif::Frame f;
        std::size_t used = 0;
        bool more = false;
        if (objif::decode_frame(std::span(bytes).subspan(at), f, used, more) != FrameError::kNone)
            break;
        frames.push_back(f);
        at += used;
    }
    return frames;
}

class FrameStreamTest : public ::testing::Test {
  protected:
    rwmos::EmulatedBoard board;
    rwmos::FrameServer server{board};
    rwmos::FrameStream stream;
    std::vector<std::uint8_t> replies;
};

TEST_F(FrameStreamTest, FrameSplitAcrossFeedsIsServedOnceComplete) {
    const auto f = read_frame(7);
    for (std::size_t i = 0; i + 1 < f.size(); ++i) {
        const auto r = stream.feed(std::span(f).subspan(i, 1), server, replies);
        EXPECT_TRUE(r.keep);
        EXPECT_EQ(r.frames, 0u);
    }
    EXPECT_EQ(stream.pending(), f.size() - 1);
    const auto r = stream.feed(std::span(f).last(1), server, replies);
    EXPECT_EQ(r.frames, 1u);
    EXPECT_EQ(stream.pending(), 0u);
    const auto out = frames_in(replies);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].sequence, 7u);
    EXPECT_EQ(out[0].opcode, 0x8001);
}

TEST_F(FrameStreamTest, SeveralFramesInOneFeedAreAnsweredInOrder) {
    std::vector<std::uint8_t> bytes;
    for (std::uint32_t s = 1; s <= 5; ++s) {
        const auto f = read_frame(s);
        bytes.insert(bytes.end(), f.begin(), f.end());
    }
    const auto r = stream.feed(bytes, server, replies);
    EXPECT_EQ(r.frames, 5u);
    const auto out = frames_in(replies);
    ASSERT_EQ(out.size(), 5u);
    for (std::uint32_t s = 1; s <= 5; ++s) EXPECT_EQ(out[s - 1].sequence, s);
}

TEST_F(FrameStreamTest, BadCrcIsAnsweredWithErrorAndTheStreamGoesOn) {
    auto bad = read_frame(1);
    bad.back() ^= 0xFF;
    auto bytes = bad;
    const auto good = read_frame(2);
    bytes.insert(bytes.end(), good.begin(), good.end());
    const auto r = stream.feed(bytes, server, replies);
    EXPECT_TRUE(r.keep);
    EXPECT_EQ(r.frames, 2u);
    EXPECT_EQ(r.rejected, 1u);
    const auto out = frames_in(replies);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].opcode, 0xFFFF);
    EXPECT_EQ(out[0].sequence, 1u);
    EXPECT_EQ(out[1].opcode, 0x8001);
}

TEST_F(FrameStreamTest, GarbageDropsTheStreamAfterAnsweringWhatCameBefore) {
    auto bytes = read_frame(1);
    bytes.insert(bytes.end(), {'G', 'E', 'T', ' ', '/'});
    const auto r = stream.feed(bytes, server, replies);
    EXPECT_FALSE(r.keep);
    EXPECT_EQ(r.garbage, FrameError::kBadMagic);
    EXPECT_EQ(frames_in(replies).size(), 1u);
    EXPECT_EQ(stream.pending(), 0u) << "nothing kept of a dropped stream";
}

TEST_F(FrameStreamTest, OversizedLengthIsGarbageBeforeThePayloadArrives) {
    auto f = read_frame(1);
    const std::uint32_t huge = objif::kMaxPayload + 1;
    std::memcpy(f.data() + 12, &huge, 4);
    const auto r = stream.feed(std::span(f).first(16), server, replies);
    EXPECT_FALSE(r.keep);
    EXPECT_EQ(r.garbage, FrameError::kBadLength);
}

// Served in turns (the daemon's fairness): a turn ends once its replies reach the bound, with
// at least one frame served and the rest left buffered (Result::more) for the next turn, in
// order; a turn whose time is over serves one frame.
TEST_F(FrameStreamTest, ATurnEndsAtItsReplyBoundAndLeavesTheRestInOrder) {
    std::vector<std::uint8_t> bytes;
    for (std::uint32_t s = 1; s <= 10; ++s) {
        const auto f = read_frame(s);
        bytes.insert(bytes.end(), f.begin(), f.end());
    }
    stream.append(bytes);
    const std::size_t one_reply = [&] {
        rwmos::FrameStream probe;
        std::vector<std::uint8_t> r;
        probe.feed(read_frame(99), server, r);
        return r.size();
    }();
    rwmos::FrameStream::Turn turn;
    turn.reply_bytes = 3 * one_reply;  // three replies reach it: the turn ends there
    auto r = stream.serve(server, replies, turn);
    EXPECT_EQ(r.frames, 3u);
    EXPECT_TRUE(r.more);
    turn.reply_bytes = 3 * one_reply - 1;  // the third reaches it
    r = stream.serve(server, replies, turn);
    EXPECT_EQ(r.frames, 3u);
    EXPECT_TRUE(r.more);
    turn.reply_bytes = 0;  // at least one frame a turn
    r = stream.serve(server, replies, turn);
    EXPECT_EQ(r.frames, 1u);
    EXPECT_TRUE(r.more);
    turn.reply_bytes = std::numeric_limits<std::size_t>::max();
    turn.until = std::chrono::steady_clock::now();  // over at once: one frame
    r = stream.serve(server, replies, turn);
    EXPECT_EQ(r.frames, 1u);
    EXPECT_TRUE(r.more);
    r = stream.serve(server, replies, rwmos::FrameStream::Turn{});
    EXPECT_EQ(r.frames, 2u);
    EXPECT_FALSE(r.more);
    EXPECT_EQ(stream.pending(), 0u);
    const auto out = frames_in(replies);
    ASSERT_EQ(out.size(), 10u);
    for (std::uint32_t s = 1; s <= 10; ++s) EXPECT_EQ(out[s - 1].sequence, s);
    // Nothing whole left (half a frame): no more.
    const auto half = read_frame(11);
    stream.append(std::span(half).first(half.size() / 2));
    r = stream.serve(server, replies, turn);
    EXPECT_EQ(r.frames, 0u);
    EXPECT_FALSE(r.more);
    EXPECT_EQ(stream.pending(), half.size() / 2);
}

}  // namespace
