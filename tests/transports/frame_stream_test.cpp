// SPDX-License-Identifier: MIT
// rwmos::FrameStream: request frames from a byte stream, served in order,
// malformed ones answered or the stream dropped (docs/wire-frame.md).
#include "rwmos/frame_stream.h"

#include <gtest/gtest.h>

#include <cstring>
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
    rwmos::Board board;
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

}  // namespace
