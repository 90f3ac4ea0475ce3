// SPDX-License-Identifier: MIT
// The motion calls of apci.h against the embedded emulator: spooling, the
// clock, executed segments and per-cycle samples, TC errors in the result and
// the last-error text, Busy, direct and SSF commands, bad arguments.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "apci/apci.h"
#include "apci/apci.hpp"

namespace {

apci_object_descriptor tc_group(int32_t group, int32_t sub) {
    return {APCI_TC_BUS, APCI_TC_DEVICE_GROUP, group, sub, 0};
}

apci_profile line(uint32_t tag, double x, double y, double feed = 600.0) {
    apci_profile p{};
    p.kind = APCI_PROFILE_LINE;
    p.axes = 0x03;
    p.tag = tag;
    p.feed = feed;
    p.target[0] = x;
    p.target[1] = y;
    return p;
}

class Motion : public ::testing::Test {
  protected:
    void SetUp() override {
        ASSERT_EQ(apci_open("emu:", &board_), APCI_OK) << apci_last_error(nullptr);
    }
    void TearDown() override { apci_close(board_); }
    std::string last_error() const { return apci_last_error(board_); }

    // Group 1 on axes 0/1/2, radius r, left ([APCI-TC] section 2.5), active.
    void compensate(double r) {
        auto reset = tc_group(1, APCI_TC_GROUP_RESET);
        auto radius = tc_group(1, APCI_TC_RADIUS);
        auto left = tc_group(1, APCI_TC_LEFT);
        auto status = tc_group(1, APCI_TC_STATUS);
        ASSERT_EQ(apci_write_int(board_, &reset, 0), APCI_OK) << last_error();
        ASSERT_EQ(apci_write_double(board_, &radius, r), APCI_OK) << last_error();
        ASSERT_EQ(apci_write_int(board_, &left, 0), APCI_OK) << last_error();
        ASSERT_EQ(apci_write_int(board_, &status, 1), APCI_OK) << last_error();
    }
    int32_t tc_status() {
        auto status = tc_group(1, APCI_TC_STATUS);
        int32_t v = -1;
        EXPECT_EQ(apci_read_int(board_, &status, &v), APCI_OK) << last_error();
        return v;
    }
    apci_board* board_ = nullptr;
};

TEST_F(Motion, SpoolRunAndReadTheExecutedSegment) {
    apci_profile p = line(10, 10, 0);
    apci_motion_result result{-1, -1, 99};
    ASSERT_EQ(apci_spool_profile(board_, &p, &result), APCI_OK) << last_error();
    EXPECT_EQ(result.group, 0);
    EXPECT_EQ(result.errors, 0);
    EXPECT_EQ(last_error(), "");
    apci_motion_status st{};
    ASSERT_EQ(apci_run_until_idle(board_, 1'000'000, &st), APCI_OK) << last_error();
    EXPECT_EQ(st.ran, 1000u) << "10 units at 600 units/min, 1 ms cycles";
    EXPECT_EQ(st.now, 1000u);
    EXPECT_NE(st.flags & APCI_MOTION_IDLE, 0u);
    EXPECT_EQ(st.position[0], 10.0);
    EXPECT_EQ(st.segments_pending, 1u);
    apci_segment seg[4];
    size_t n = 0;
    ASSERT_EQ(apci_read_segments(board_, seg, 4, &n), APCI_OK) << last_error();
    ASSERT_EQ(n, 1u);
    EXPECT_EQ(seg[0].tag, 10u);
    EXPECT_EQ(seg[0].kind, APCI_SEGMENT_LINE);
    EXPECT_EQ(seg[0].role, APCI_ROLE_UNCOMPENSATED);
    EXPECT_EQ(seg[0].end[0], 10.0);
    EXPECT_EQ(seg[0].end_cycle, 1000u);
}

// A record read into a buffer full of other bytes: every byte is the board's, the padding
// after plane_axes zero, as if the record had been cleared first (the same bytes whoever
// reads or hashes them).
TEST_F(Motion, ReadSegmentsLeavesNoByteOfTheRecordAsItWas) {
    apci_profile p = line(10, 10, 0);
    ASSERT_EQ(apci_spool_profile(board_, &p, nullptr), APCI_OK) << last_error();
    ASSERT_EQ(apci_run_until_idle(board_, 1'000'000, nullptr), APCI_OK) << last_error();
    apci_segment seg;
    std::array<unsigned char, sizeof(apci_segment)> dirt{};
    dirt.fill(0xA5);
    std::memcpy(&seg, dirt.data(), sizeof seg);
    size_t n = 0;
    ASSERT_EQ(apci_read_segments(board_, &seg, 1, &n), APCI_OK) << last_error();
    ASSERT_EQ(n, 1u);
    apci_segment want{};  // zero everywhere, padding included
    want.tag = 10;
    want.kind = APCI_SEGMENT_LINE;
    want.role = APCI_ROLE_UNCOMPENSATED;
    want.ccw = seg.ccw;
    want.interrupted = seg.interrupted;
    want.plane_axes[0] = seg.plane_axes[0];
    want.plane_axes[1] = seg.plane_axes[1];
    want.plane = seg.plane;
    want.end[0] = 10.0;
    want.feed = 600.0;
    want.end_cycle = 1000;
    // Byte by byte, the padding included.
    std::array<unsigned char, sizeof(apci_segment)> got{}, expected{};
    std::memcpy(got.data(), &seg, sizeof seg);
    std::memcpy(expected.data(), &want, sizeof want);
    EXPECT_EQ(got, expected);
}

TEST_F(Motion, StepAdvancesExactlyTheCyclesAsked) {
    apci_profile p = line(1, 10, 0);
    ASSERT_EQ(apci_spool_profile(board_, &p, nullptr), APCI_OK);
    apci_motion_status st{};
    ASSERT_EQ(apci_step(board_, 250, &st), APCI_OK);
    EXPECT_EQ(st.ran, 250u);
    EXPECT_EQ(st.now, 250u);
    EXPECT_DOUBLE_EQ(st.position[0], 2.5);
    EXPECT_EQ(st.fill, 1u);
    uint32_t fill = 0, capacity = 0;
    ASSERT_EQ(apci_spooler_fill(board_, &fill, &capacity), APCI_OK);
    EXPECT_EQ(fill, 1u);
    EXPECT_GT(capacity, 0u);
}

// The board advances at most 2^20 cycles per Clock request; the C API takes
// any count and sends as many requests as it takes, with the same result as
// one long run of the board.
TEST_F(Motion, StepBeyondOneRequestsBoundAdvancesExactlyTheCyclesAsked) {
    const uint64_t cycles = 3 * (uint64_t{1} << 20) + 5;
    apci_motion_status st{};
    ASSERT_EQ(apci_step(board_, cycles, &st), APCI_OK) << last_error();
    EXPECT_EQ(st.ran, cycles);
    EXPECT_EQ(st.now, cycles);
}

TEST_F(Motion, RunUntilIdleBeyondOneRequestsBoundRunsTheMoveToItsEnd) {
    // 2,500 units at 60 units/min: 2,500,000 cycles, more than two requests' worth.
    apci_profile slow = line(1, 2500, 0, 60.0);
    ASSERT_EQ(apci_spool_profile(board_, &slow, nullptr), APCI_OK) << last_error();
    apci_motion_status st{};
    ASSERT_EQ(apci_run_until_idle(board_, UINT64_MAX, &st), APCI_OK) << last_error();
    EXPECT_EQ(st.ran, 2'500'000u);
    EXPECT_EQ(st.now, 2'500'000u);
    EXPECT_NE(st.flags & APCI_MOTION_IDLE, 0u);
    EXPECT_EQ(st.position[0], 2500.0);
    // A bound that ends mid-move stops there, across requests too.
    apci_profile back = line(2, 0, 0, 60.0);
    ASSERT_EQ(apci_spool_profile(board_, &back, nullptr), APCI_OK) << last_error();
    ASSERT_EQ(apci_run_until_idle(board_, 2'000'000, &st), APCI_OK) << last_error();
    EXPECT_EQ(st.ran, 2'000'000u);
    EXPECT_EQ(st.flags & APCI_MOTION_IDLE, 0u);
    EXPECT_DOUBLE_EQ(st.position[0], 500.0);
}

TEST_F(Motion, HeldProfileAndSsf2001ThroughTheCApi) {
    compensate(1.0);
    apci_profile p = line(1, 10, 0);
    ASSERT_EQ(apci_spool_profile(board_, &p, nullptr), APCI_OK) << last_error();
    EXPECT_EQ(tc_status() & APCI_TC_STATUS_PROF_MARKED, APCI_TC_STATUS_PROF_MARKED);
    apci_motion_status st{};
    ASSERT_EQ(apci_motion_status_get(board_, &st), APCI_OK);
    EXPECT_NE(st.flags & APCI_MOTION_PROFILE_HELD, 0u);
    EXPECT_EQ(st.compensating_group, 1);
    ASSERT_EQ(apci_ssf_command(board_, 0x03, APCI_SSF_RELEASE_HELD_PROFILE, nullptr), APCI_OK)
        << last_error();
    EXPECT_EQ(tc_status() & APCI_TC_STATUS_PROF_MARKED, 0);
}

TEST_F(Motion, TcErrorComesBackInTheResultAndTheLastError) {
    compensate(5.0);
    apci_profile p = line(1, 10, 0);
    ASSERT_EQ(apci_spool_profile(board_, &p, nullptr), APCI_OK);
    apci_profile arc = line(2, 10, 4);
    arc.kind = APCI_PROFILE_ARC_CCW;
    arc.arc_axes[0] = 0;
    arc.arc_axes[1] = 1;
    arc.center[0] = 10;
    arc.center[1] = 2;  // radius 2 < tool radius 5 on the concave side
    apci_motion_result r{};
    EXPECT_EQ(apci_spool_profile(board_, &arc, &r), APCI_WRONG_DEVICE_STATE);
    EXPECT_EQ(r.group, 1);
    EXPECT_EQ(r.errors, static_cast<int32_t>(APCI_TC_ERROR_CALC));
    EXPECT_EQ(r.tag, 2u);
    EXPECT_NE(last_error().find("spool G03 N2"), std::string::npos) << last_error();
    EXPECT_NE(last_error().find("0x04"), std::string::npos) << last_error();
    // The board's own words alone, for a program that shows the reason without the call.
    EXPECT_EQ(std::string(apci_last_board_message(board_)),
              "arc radius is smaller than the tool radius on the concave side: the tool would cut "
              "into the arc (use a tool no larger than the arc's radius)");
    EXPECT_NE(last_error().find(apci_last_board_message(board_)), std::string::npos);
    EXPECT_EQ(tc_status() & APCI_TC_STATUS_RUN, 0) << "Run cleared";
    // Any later call replaces it (the read above succeeded); NULL gives "".
    EXPECT_STREQ(apci_last_board_message(board_), "");
    EXPECT_STREQ(apci_last_board_message(nullptr), "");
    apci_motion_status st{};
    ASSERT_EQ(apci_motion_status_get(board_, &st), APCI_OK);
    EXPECT_NE(st.flags & APCI_MOTION_HELD, 0u);
}

TEST_F(Motion, FullSpoolerAnswersBusy) {
    uint32_t fill = 0, capacity = 0;
    ASSERT_EQ(apci_spooler_fill(board_, &fill, &capacity), APCI_OK);
    for (uint32_t i = 1; i <= capacity; ++i) {
        apci_profile p = line(i, i, 0);
        ASSERT_EQ(apci_spool_profile(board_, &p, nullptr), APCI_OK) << i << ": " << last_error();
    }
    apci_profile p = line(capacity + 1, 0, 0);
    EXPECT_EQ(apci_spool_profile(board_, &p, nullptr), APCI_BUSY);
    EXPECT_NE(last_error().find("Busy"), std::string::npos) << last_error();
    ASSERT_EQ(apci_spooler_fill(board_, &fill, &capacity), APCI_OK);
    EXPECT_EQ(fill, capacity);
}

TEST_F(Motion, DirectCommandJsEmptiesTheSpooler) {
    apci_profile p = line(1, 10, 0);
    ASSERT_EQ(apci_spool_profile(board_, &p, nullptr), APCI_OK);
    apci_direct_command js{};
    js.code = APCI_DIRECT_JS;
    ASSERT_EQ(apci_direct_command_send(board_, &js), APCI_OK) << last_error();
    uint32_t fill = 9, capacity = 0;
    ASSERT_EQ(apci_spooler_fill(board_, &fill, &capacity), APCI_OK);
    EXPECT_EQ(fill, 0u);
    js.axes = 1;
    EXPECT_EQ(apci_direct_command_send(board_, &js), APCI_INVALID_VALUE);
    EXPECT_NE(last_error().find("direct JS"), std::string::npos) << last_error();
}

TEST_F(Motion, DirectCommandJaJogsTheNamedAxes) {
    apci_direct_command ja{};
    ja.code = APCI_DIRECT_JA;
    ja.axes = 0x04;
    ja.target[2] = -3.0;
    ASSERT_EQ(apci_direct_command_send(board_, &ja), APCI_OK) << last_error();
    apci_motion_status st{};
    ASSERT_EQ(apci_run_until_idle(board_, 1'000'000, &st), APCI_OK);
    EXPECT_EQ(st.position[2], -3.0);
}

TEST_F(Motion, TraceSamplesAreReadInAsManyRequestsAsItTakes) {
    ASSERT_EQ(apci_trace_enable(board_, 5000), APCI_OK) << last_error();
    apci_profile p = line(1, 30, 0);  // 3000 cycles: more than one reply frame of samples
    ASSERT_EQ(apci_spool_profile(board_, &p, nullptr), APCI_OK);
    ASSERT_EQ(apci_run_until_idle(board_, 1'000'000, nullptr), APCI_OK);
    std::vector<apci_trace_sample> s(4000);
    size_t n = 0;
    ASSERT_EQ(apci_read_trace(board_, s.data(), s.size(), &n), APCI_OK) << last_error();
    ASSERT_EQ(n, 3000u);
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(s[i].cycle, i + 1);
    EXPECT_EQ(s[2999].position[0], 30.0);
    EXPECT_EQ(apci_trace_enable(board_, 1u << 25), APCI_VALUE_TOO_HIGH);
    ASSERT_EQ(apci_trace_enable(board_, 0), APCI_OK);
    apci_motion_status st{};
    ASSERT_EQ(apci_motion_status_get(board_, &st), APCI_OK);
    EXPECT_EQ(st.flags & APCI_MOTION_TRACING, 0u);
}

TEST_F(Motion, BadProfileNamesWhatWasWrong) {
    apci_profile p = line(3, 10, 0, 0.0);
    EXPECT_EQ(apci_spool_profile(board_, &p, nullptr), APCI_VALUE_TOO_LOW);
    EXPECT_NE(last_error().find("feed"), std::string::npos) << last_error();
    p = line(3, 10, 0);
    p.kind = 7;
    EXPECT_EQ(apci_spool_profile(board_, &p, nullptr), APCI_INVALID_VALUE);
}

TEST_F(Motion, NullArgumentsAreRefusedWithTheirName) {
    apci_profile p = line(1, 1, 1);
    EXPECT_EQ(apci_spool_profile(nullptr, &p, nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_NE(std::string(apci_last_error(nullptr)).find("board is NULL"), std::string::npos);
    EXPECT_EQ(apci_spool_profile(board_, nullptr, nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("profile is NULL"), std::string::npos);
    EXPECT_EQ(apci_direct_command_send(board_, nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_motion_status_get(board_, nullptr), APCI_INVALID_ARGUMENT);
    size_t n = 0;
    EXPECT_EQ(apci_read_trace(board_, nullptr, 5, &n), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_read_segments(board_, nullptr, 0, &n), APCI_OK) << "max 0 needs no buffer";
    apci_segment seg;
    EXPECT_EQ(apci_read_segments(board_, &seg, 1, nullptr), APCI_INVALID_ARGUMENT);
    uint32_t fill = 0;
    EXPECT_EQ(apci_spooler_fill(board_, &fill, nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_step(nullptr, 1, nullptr), APCI_INVALID_ARGUMENT);
}

TEST(MotionNames, SegmentRolesHaveTheirJsonNames) {
    EXPECT_STREQ(apci_segment_role_name(APCI_ROLE_CONTOUR), "contour");
    EXPECT_STREQ(apci_segment_role_name(APCI_ROLE_TRANSITION), "transition");
    EXPECT_STREQ(apci_segment_role_name(APCI_ROLE_APPROACH), "approach");
    EXPECT_STREQ(apci_segment_role_name(APCI_ROLE_DEPARTURE), "departure");
    EXPECT_STREQ(apci_segment_role_name(APCI_ROLE_UNCOMPENSATED), "uncompensated");
    EXPECT_STREQ(apci_segment_role_name(APCI_ROLE_RAPID), "rapid");
    EXPECT_EQ(apci_segment_role_name(6), nullptr);
    EXPECT_EQ(apci_segment_role_name(-1), nullptr);
}

TEST(MotionCpp, WrapperCarriesStatusAndValue) {
    apci::Board board("emu:");
    ASSERT_TRUE(board);
    const apci_profile p = line(4, 1, 0);
    const auto spooled = board.spool(p);
    ASSERT_TRUE(spooled) << board.last_error();
    const auto ran = board.run_until_idle(1'000'000);
    ASSERT_TRUE(ran);
    EXPECT_EQ(ran.value.ran, 100u);
    apci_segment seg[2];
    const auto n = board.read_segments(seg, 2);
    ASSERT_TRUE(n);
    EXPECT_EQ(n.value, 1u);
    EXPECT_EQ(seg[0].tag, 4u);
    EXPECT_FALSE(board.ssf(0, 2001)) << "an SSF command to no axis is refused";
}

}  // namespace

extern "C" int c_motion_round_trip(void);

TEST(MotionFromC, SpoolRunAndReadSegmentsFromC) {
    EXPECT_EQ(c_motion_round_trip(), 0);
}
