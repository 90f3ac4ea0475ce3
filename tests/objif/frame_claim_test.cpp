// SPDX-License-Identifier: MIT
// The MotionClaim payloads (objif/frame.h, docs/wire-frame.md "MotionClaim") and which requests
// the claim guards (objif::guarded_by_motion_claim, docs/motion-claim.md).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "objif/frame.h"

namespace {

using objif::ClaimAction;
using objif::ClaimReply;
using objif::ClaimRequest;
using objif::FrameError;
using objif::Opcode;

TEST(ClaimPayload, RequestRoundTripsEveryActionAndRefusesOthers) {
    for (const ClaimAction a : {ClaimAction::kClaim, ClaimAction::kRelease, ClaimAction::kQuery}) {
        std::vector<std::uint8_t> bytes;
        objif::encode(ClaimRequest{a}, bytes);
        ClaimRequest back;
        ASSERT_EQ(objif::decode(bytes, back), FrameError::kNone);
        EXPECT_EQ(back.action, a);
    }
    ClaimRequest r;
    const std::vector<std::uint8_t> action3{3};
    EXPECT_EQ(objif::decode(action3, r), FrameError::kBadPayload);
    const std::vector<std::uint8_t> long_payload{0, 0};
    EXPECT_EQ(objif::decode(long_payload, r), FrameError::kBadPayload);
    EXPECT_EQ(objif::decode(std::vector<std::uint8_t>{}, r), FrameError::kBadPayload);
}

ClaimReply holder() {
    ClaimReply m;
    m.status = objif::Status::kMotionClaimed;
    m.held = true;
    m.pid = 4242;
    m.since_ms = 1'714'564'800'000;  // 2024-05-01 12:00:00 UTC
    m.name = "apcictl";
    return m;
}

TEST(ClaimPayload, ReplyRoundTrips) {
    std::vector<std::uint8_t> bytes;
    objif::encode(holder(), bytes);
    ClaimReply back;
    ASSERT_EQ(objif::decode(bytes, back), FrameError::kNone);
    EXPECT_EQ(back.status, objif::Status::kMotionClaimed);
    EXPECT_TRUE(back.held);
    EXPECT_FALSE(back.yours);
    EXPECT_EQ(back.pid, 4242);
    EXPECT_EQ(back.since_ms, 1'714'564'800'000u);
    EXPECT_EQ(back.name, "apcictl");
}

TEST(ClaimPayload, ReplyOfNobodyAndOfAHolderWithoutPidRoundTrip) {
    // Nobody holds the claim: pid 0, no name, no time (a query of a free board).
    std::vector<std::uint8_t> bytes;
    objif::encode(ClaimReply{}, bytes);
    ClaimReply back = holder();
    ASSERT_EQ(objif::decode(bytes, back), FrameError::kNone);
    EXPECT_FALSE(back.held);
    EXPECT_FALSE(back.yours);
    EXPECT_EQ(back.pid, 0);
    EXPECT_EQ(back.since_ms, 0u);
    EXPECT_EQ(back.name, "");
    // A holder the board knows only by name (pid 0).
    ClaimReply m = holder();
    m.pid = 0;
    bytes.clear();
    objif::encode(m, bytes);
    ASSERT_EQ(objif::decode(bytes, back), FrameError::kNone);
    EXPECT_TRUE(back.held);
    EXPECT_EQ(back.pid, 0);
    EXPECT_EQ(back.name, "apcictl");
}

TEST(ClaimPayload, ReplyNameIsCutAtFifteenBytesAndNonPrintableReplaced) {
    ClaimReply m = holder();
    m.name = std::string("a\x01") + std::string(20, 'b');
    std::vector<std::uint8_t> bytes;
    objif::encode(m, bytes);
    ClaimReply back;
    ASSERT_EQ(objif::decode(bytes, back), FrameError::kNone);
    EXPECT_EQ(back.name, "a?" + std::string(13, 'b'));
}

TEST(ClaimPayload, ReplyDecodeRefusesWhatNoBoardSends) {
    std::vector<std::uint8_t> good;
    objif::encode(holder(), good);
    ClaimReply back;
    // Its own, when nobody holds the claim.
    ClaimReply yours_unheld;
    yours_unheld.yours = true;
    std::vector<std::uint8_t> bytes;
    objif::encode(yours_unheld, bytes);
    EXPECT_EQ(objif::decode(bytes, back), FrameError::kBadPayload);
    // A flag byte other than 0 or 1 (held is byte 4).
    bytes = good;
    bytes[4] = 2;
    EXPECT_EQ(objif::decode(bytes, back), FrameError::kBadPayload);
    // A negative pid (bytes 6..9).
    bytes = good;
    bytes[9] = 0x80;
    EXPECT_EQ(objif::decode(bytes, back), FrameError::kBadPayload);
    // A name length past the bytes, or above 15.
    bytes = good;
    bytes[18] = 8;
    EXPECT_EQ(objif::decode(bytes, back), FrameError::kBadPayload);
    bytes = good;
    bytes[18] = 16;
    bytes.resize(19 + 16, 'x');
    EXPECT_EQ(objif::decode(bytes, back), FrameError::kBadPayload);
    // A control character in the name.
    bytes = good;
    bytes[19] = '\n';
    EXPECT_EQ(objif::decode(bytes, back), FrameError::kBadPayload);
}

TEST(ClaimPayload, HolderTextNamesPidNameAndUtcTime) {
    EXPECT_EQ(objif::claim_holder_text(holder()), "pid 4242 (apcictl) since 2024-05-01 12:00:00 UTC");
    ClaimReply m = holder();
    m.name.clear();
    m.since_ms = 0;
    EXPECT_EQ(objif::claim_holder_text(m), "pid 4242");
    m.pid = 0;
    EXPECT_EQ(objif::claim_holder_text(m), "another host");
}

std::vector<std::uint8_t> clock_payload(objif::ClockMode mode) {
    std::vector<std::uint8_t> bytes;
    objif::encode(objif::ClockRequest{mode, 1}, bytes);
    return bytes;
}

TEST(ClaimGuards, EveryRequestThatActsOnMotionOrItsRecordAndNothingElse) {
    auto op = [](Opcode o) { return static_cast<std::uint16_t>(o); };
    const std::vector<std::uint8_t> none;
    EXPECT_TRUE(objif::guarded_by_motion_claim(op(Opcode::kObjectWrite), none));
    EXPECT_TRUE(objif::guarded_by_motion_claim(op(Opcode::kSpoolProfile), none));
    EXPECT_TRUE(objif::guarded_by_motion_claim(op(Opcode::kDirectCommand), none));
    EXPECT_TRUE(objif::guarded_by_motion_claim(op(Opcode::kSsfCommand), none));
    EXPECT_TRUE(objif::guarded_by_motion_claim(op(Opcode::kReadTrace), none));
    for (const auto mode : {objif::ClockMode::kStep, objif::ClockMode::kRunUntilIdle,
                            objif::ClockMode::kTraceOn, objif::ClockMode::kTraceOff})
        EXPECT_TRUE(objif::guarded_by_motion_claim(op(Opcode::kClock), clock_payload(mode)));
    EXPECT_FALSE(objif::guarded_by_motion_claim(op(Opcode::kClock),
                                                clock_payload(objif::ClockMode::kQuery)));
    // A clock request without its mode is guarded too: it is refused before it is decoded.
    EXPECT_TRUE(objif::guarded_by_motion_claim(op(Opcode::kClock), none));
    EXPECT_FALSE(objif::guarded_by_motion_claim(op(Opcode::kObjectRead), none));
    EXPECT_FALSE(objif::guarded_by_motion_claim(op(Opcode::kMotionClaim), none));
    EXPECT_FALSE(objif::guarded_by_motion_claim(0x0009, none));  // no such request
}

TEST(ClaimGuards, MotionClaimIsAKnownOpcodeWithItsName) {
    EXPECT_TRUE(objif::opcode_known(0x0008));
    EXPECT_FALSE(objif::opcode_known(0x0009));
    EXPECT_EQ(objif::opcode_name(0x0008), "MotionClaim");
    EXPECT_EQ(objif::opcode_name(0x8008), "MotionClaimReply");
}

}  // namespace
