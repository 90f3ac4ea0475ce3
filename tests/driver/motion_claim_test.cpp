// SPDX-License-Identifier: MIT
// The motion claim through the C API on the embedded board (apci.h "Exclusive use of the
// board's motion", docs/motion-claim.md): the handle's own rules (a second claim and a release
// without a claim are refused), the argument checks, each emu: handle's board its own, and
// the C++ wrapper's scope claim. The daemon's side (two clients of one board) is
// tests/daemon/motion_claim_test.cpp; the wire codec tests/objif/frame_claim_test.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <string>

#include "apci/apci.h"
#include "apci/apci.hpp"

namespace {

struct Handle {
    apci_board* board = nullptr;
    explicit Handle(const char* uri = "emu:") { EXPECT_EQ(apci_open(uri, &board), APCI_OK); }
    ~Handle() { apci_close(board); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
};

apci_motion_claim claim_of(apci_board* board) {
    apci_motion_claim c{};
    EXPECT_EQ(apci_motion_claim_get(board, &c), APCI_OK) << apci_last_error(board);
    return c;
}

std::string last_error(const apci_board* board) {
    return apci_last_error(board);
}

TEST(MotionClaimArguments, NullBoardIsAnInvalidArgumentForEveryCall) {
    EXPECT_EQ(apci_claim_motion(nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(last_error(nullptr), "apci_claim_motion: board is NULL");
    EXPECT_EQ(apci_release_motion(nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(last_error(nullptr), "apci_release_motion: board is NULL");
    apci_motion_claim c{};
    EXPECT_EQ(apci_motion_claim_get(nullptr, &c), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(last_error(nullptr), "apci_motion_claim_get: board is NULL");
}

TEST(MotionClaimArguments, NullClaimRecordIsAnInvalidArgument) {
    Handle h;
    EXPECT_EQ(apci_motion_claim_get(h.board, nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(last_error(h.board), "apci_motion_claim_get: claim is NULL");
}

TEST(MotionClaimArguments, SecondClaimBySameHandleIsRefusedAndTheFirstStays) {
    Handle h;
    ASSERT_EQ(apci_claim_motion(h.board), APCI_OK) << last_error(h.board);
    EXPECT_EQ(last_error(h.board), "");
    EXPECT_EQ(apci_claim_motion(h.board), APCI_WRONG_DEVICE_STATE);
    EXPECT_NE(last_error(h.board).find("holds the board's motion already"), std::string::npos)
        << last_error(h.board);
    const apci_motion_claim c = claim_of(h.board);
    EXPECT_EQ(c.held, 1);
    EXPECT_EQ(c.yours, 1);
    // One release ends it: a claim is not counted.
    EXPECT_EQ(apci_release_motion(h.board), APCI_OK);
    EXPECT_EQ(claim_of(h.board).held, 0);
}

TEST(MotionClaimArguments, ReleaseWithoutClaimIsRefused) {
    Handle h;
    EXPECT_EQ(apci_release_motion(h.board), APCI_WRONG_DEVICE_STATE);
    EXPECT_NE(last_error(h.board).find("holds no claim"), std::string::npos) << last_error(h.board);
    ASSERT_EQ(apci_claim_motion(h.board), APCI_OK);
    ASSERT_EQ(apci_release_motion(h.board), APCI_OK);
    // Released once: a second release is one without a claim.
    EXPECT_EQ(apci_release_motion(h.board), APCI_WRONG_DEVICE_STATE);
}

TEST(MotionClaimEmbedded, ClaimNamesThisProcessAndWhen) {
    Handle h;
    EXPECT_EQ(claim_of(h.board).held, 0);
    ASSERT_EQ(apci_claim_motion(h.board), APCI_OK);
    const apci_motion_claim c = claim_of(h.board);
    EXPECT_EQ(c.held, 1);
    EXPECT_EQ(c.yours, 1);
    EXPECT_EQ(c.pid, static_cast<int32_t>(::getpid()));
    EXPECT_STREQ(c.name, std::string(program_invocation_short_name).substr(0, 15).c_str());
    EXPECT_GT(c.since_ms, 1'600'000'000'000u);  // after September 2020: a real date
}

// The holder named as libapci names it in a refusal (apci_motion_claim_holder): pid and name
// and when (UTC), the pid alone, a host's name, another host; "" when nobody holds it or there
// is no record. Written as snprintf writes: cut short to the room with its NUL, the whole
// length returned, nothing written without room; a name of 16 characters without its NUL read
// no further than the record.
TEST(MotionClaimHolder, NamesTheHolderAsARefusalDoes) {
    const auto holder = [](const apci_motion_claim& c) {
        char text[128];
        const std::size_t n = apci_motion_claim_holder(&c, text, sizeof text);
        EXPECT_EQ(n, std::string(text).size());
        EXPECT_EQ(apci::motion_claim_holder(c), text);
        return std::string(text);
    };
    apci_motion_claim c{};
    EXPECT_EQ(holder(c), "");  // held 0
    c.pid = 4242;
    std::strcpy(c.name, "apcictl");
    c.since_ms = 1'714'564'800'000u;  // 2024-05-01 12:00:00 UTC
    EXPECT_EQ(holder(c), "") << "not held: nobody is named, whatever the record holds";
    c.held = 1;
    EXPECT_EQ(holder(c), "pid 4242 (apcictl) since 2024-05-01 12:00:00 UTC");
    c.since_ms = 0;
    EXPECT_EQ(holder(c), "pid 4242 (apcictl)");
    c.name[0] = '\0';
    EXPECT_EQ(holder(c), "pid 4242");
    c.pid = 0;
    EXPECT_EQ(holder(c), "another host");
    std::memcpy(c.name, "sixteen-letters!", 16);  // no NUL in the record
    EXPECT_EQ(holder(c), "sixteen-letters!");
    EXPECT_EQ(apci_motion_claim_holder(nullptr, nullptr, 0), 0u);
    char text[8] = "unused";
    EXPECT_EQ(apci_motion_claim_holder(nullptr, text, sizeof text), 0u);
    EXPECT_STREQ(text, "");
    // Cut short: the room less one, and the NUL; no room at all: nothing written.
    std::strcpy(c.name, "apcictl");
    c.pid = 4242;
    EXPECT_EQ(apci_motion_claim_holder(&c, text, sizeof text), 18u);
    EXPECT_STREQ(text, "pid 424");
    EXPECT_EQ(apci_motion_claim_holder(&c, text, 1), 18u);
    EXPECT_STREQ(text, "");
    text[0] = 'x';
    EXPECT_EQ(apci_motion_claim_holder(&c, text, 0), 18u);
    EXPECT_EQ(text[0], 'x');
    EXPECT_EQ(apci_motion_claim_holder(&c, nullptr, 0), 18u);
}

// The holder of a board this process claims, named from the board's record.
TEST(MotionClaimHolder, NamesThisProcessWhenItHoldsTheBoard) {
    Handle h;
    ASSERT_EQ(apci_claim_motion(h.board), APCI_OK);
    const std::string name = std::string(program_invocation_short_name).substr(0, 15);
    const std::string holder = apci::motion_claim_holder(claim_of(h.board));
    EXPECT_EQ(holder.rfind("pid " + std::to_string(::getpid()) + " (" + name + ") since 20", 0), 0U)
        << holder;
    EXPECT_EQ(holder.substr(holder.size() - 4), " UTC") << holder;
}

TEST(MotionClaimEmbedded, EachHandleHoldsItsOwnBoard) {
    // Every emu: is a board of its own (apci_open): one handle's claim leaves the other's
    // board free, and the other moves.
    Handle a, b;
    ASSERT_EQ(apci_claim_motion(a.board), APCI_OK);
    EXPECT_EQ(claim_of(b.board).held, 0);
    ASSERT_EQ(apci_claim_motion(b.board), APCI_OK) << last_error(b.board);
    apci_direct_command ja{};
    ja.code = APCI_DIRECT_JA;
    ja.axes = 0x01;
    ja.target[0] = 5.0;
    EXPECT_EQ(apci_direct_command_send(b.board, &ja), APCI_OK) << last_error(b.board);
    apci_motion_status st{};
    EXPECT_EQ(apci_run_until_idle(b.board, 1'000'000, &st), APCI_OK);
    EXPECT_EQ(st.position[0], 5.0);
    EXPECT_EQ(apci_motion_status_get(a.board, &st), APCI_OK);
    EXPECT_EQ(st.position[0], 0.0);
}

TEST(MotionClaimEmbedded, HolderMovesAsWithoutAClaim) {
    Handle h;
    ASSERT_EQ(apci_claim_motion(h.board), APCI_OK);
    apci_profile p{};
    p.kind = APCI_PROFILE_LINE;
    p.axes = 0x03;
    p.feed = 6000.0;
    p.target[0] = 10.0;
    p.target[1] = 5.0;
    ASSERT_EQ(apci_spool_profile(h.board, &p, nullptr), APCI_OK) << last_error(h.board);
    apci_motion_status st{};
    ASSERT_EQ(apci_run_until_idle(h.board, 1'000'000, &st), APCI_OK);
    EXPECT_EQ(st.position[0], 10.0);
    EXPECT_EQ(st.position[1], 5.0);
    apci_segment seg[4];
    size_t n = 0;
    ASSERT_EQ(apci_read_segments(h.board, seg, 4, &n), APCI_OK);
    EXPECT_EQ(n, 1u);
}

TEST(MotionClaimEmbedded, ReconnectEndsTheClaim) {
    Handle h;
    ASSERT_EQ(apci_claim_motion(h.board), APCI_OK);
    ASSERT_EQ(apci_reconnect(h.board), APCI_OK);
    EXPECT_EQ(claim_of(h.board).held, 0);
    EXPECT_EQ(apci_release_motion(h.board), APCI_WRONG_DEVICE_STATE);
    EXPECT_EQ(apci_claim_motion(h.board), APCI_OK);
}

TEST(MotionClaimEmbedded, ClaimAgainAtOnceAfterReconnect) {
    // The handle forgets its claim with the link: its first claim after the reconnect is a
    // new one, not "already held".
    Handle h;
    ASSERT_EQ(apci_claim_motion(h.board), APCI_OK);
    ASSERT_EQ(apci_reconnect(h.board), APCI_OK);
    EXPECT_EQ(apci_claim_motion(h.board), APCI_OK) << last_error(h.board);
    EXPECT_EQ(claim_of(h.board).yours, 1);
}

TEST(MotionClaimEmbedded, ReleaseAfterReconnectIsOneWithoutAClaim) {
    Handle h;
    ASSERT_EQ(apci_claim_motion(h.board), APCI_OK);
    ASSERT_EQ(apci_reconnect(h.board), APCI_OK);
    EXPECT_EQ(apci_release_motion(h.board), APCI_WRONG_DEVICE_STATE);
    EXPECT_NE(last_error(h.board).find("holds no claim"), std::string::npos) << last_error(h.board);
}

TEST(MotionClaimCpp, ScopeClaimHoldsUntilItEnds) {
    apci::Board board("emu:");
    ASSERT_TRUE(board);
    {
        const apci::MotionClaim claim(board);
        ASSERT_TRUE(claim.held()) << board.last_error();
        EXPECT_EQ(board.motion_claim().value.yours, 1);
        // A second scope claim on the same handle is refused and, when it ends, releases
        // nothing.
        {
            const apci::MotionClaim again(board);
            EXPECT_FALSE(again.held());
            EXPECT_EQ(again.status(), APCI_WRONG_DEVICE_STATE);
        }
        EXPECT_EQ(board.motion_claim().value.held, 1);
    }
    EXPECT_EQ(board.motion_claim().value.held, 0);
    EXPECT_TRUE(board.claim_motion());
    EXPECT_TRUE(board.release_motion());
}

}  // namespace
