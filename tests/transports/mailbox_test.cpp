// SPDX-License-Identifier: MIT
// The dual-port RAM mailbox protocol (objif/mailbox.h, docs/dpram.md), host
// and board in one process on a window of ordinary memory.
#include "objif/mailbox.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <thread>
#include <vector>

namespace {

namespace mb = objif::mailbox;
using objif::Status;
// Durations spelled out, not as chrono literals: cppcheck 2.10 stops on 20us
// and 20ms in this file ("MathLib::toLongNumber: input was not completely consumed").
using std::chrono::microseconds;
using std::chrono::milliseconds;
using std::chrono::nanoseconds;

class Mailbox : public ::testing::Test {
  protected:
    Mailbox()
        : memory_(mb::kWindowSize / 4 + 1, 0), window_(memory_.data(), mb::kWindowSize, true) {
        mb::format(window_);
    }
    ~Mailbox() override { stop_board(); }

    // A board that answers each request with the request's bytes reversed.
    void start_board() {
        mb::set_board_state(window_, mb::BoardState::kServing);
        board_ = std::thread([this] {
            mb::Request request;
            while (!stop_) {
                if (!mb::take_request(window_, request, microseconds(10), milliseconds(20)))
                    continue;
                ++served_;
                std::vector<std::uint8_t> reply(request.frame.rbegin(), request.frame.rend());
                mb::put_reply(window_, request, reply);
            }
        });
    }
    void stop_board() {
        stop_ = true;
        mb::wake_board(window_);
        if (board_.joinable()) board_.join();
    }

    mb::HostOptions host(std::chrono::milliseconds timeout = milliseconds(2000)) {
        mb::HostOptions o;
        o.token = 4242;
        o.timeout = timeout;
        return o;
    }

    std::vector<std::uint32_t> memory_;
    mb::MappedWindow window_;
    std::thread board_;
    std::atomic<bool> stop_{false};
    std::atomic<int> served_{0};
};

std::vector<std::uint8_t> bytes(std::size_t n, std::uint8_t first = 1) {
    std::vector<std::uint8_t> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::uint8_t>(first + i);
    return v;
}

TEST_F(Mailbox, FormatWritesAValidHeaderWithTheBoardStopped) {
    EXPECT_EQ(mb::check_layout(window_), "");
    EXPECT_EQ(window_.load(mb::kOffBoardState), 0u);
    EXPECT_EQ(window_.load(mb::kOffRequestSequence), 0u);
    EXPECT_EQ(window_.load(mb::kOffReplySequence), 0u) << "no request pending";
}

TEST_F(Mailbox, CheckLayoutNamesAWrongSignature) {
    window_.store(mb::kOffSignature, 0x12345678);
    EXPECT_NE(mb::check_layout(window_).find("signature is 0x12345678"), std::string::npos);
}

TEST_F(Mailbox, CheckLayoutNamesAWrongVersion) {
    window_.store(mb::kOffVersion, 9);
    EXPECT_NE(mb::check_layout(window_).find("layout version 9"), std::string::npos);
}

TEST_F(Mailbox, ExchangeCarriesTheRequestAndReturnsTheReply) {
    start_board();
    std::vector<std::uint8_t> reply;
    std::string why;
    const auto request = bytes(41);
    ASSERT_EQ(mb::exchange(window_, host(), request, reply, why), Status::kOk) << why;
    EXPECT_EQ(reply, std::vector<std::uint8_t>(request.rbegin(), request.rend()));
    EXPECT_EQ(window_.load(mb::kOffRequestSequence), 1u);
    EXPECT_EQ(window_.load(mb::kOffReplySequence), 1u) << "answered: nothing pending";
    EXPECT_EQ(window_.load(mb::kOffHostLock), 0u) << "the lock is free again";
}

TEST_F(Mailbox, ExchangeCarriesAWholeRecord) {
    start_board();
    std::vector<std::uint8_t> reply;
    std::string why;
    const auto request = bytes(mb::kRecordCapacity, 7);
    ASSERT_EQ(mb::exchange(window_, host(), request, reply, why), Status::kOk) << why;
    EXPECT_EQ(reply.size(), mb::kRecordCapacity);
    EXPECT_EQ(reply.front(), request.back());
}

TEST_F(Mailbox, ManyExchangesInARowEachGetTheirOwnReply) {
    start_board();
    for (std::uint8_t i = 0; i < 200; ++i) {
        std::vector<std::uint8_t> reply;
        std::string why;
        const auto request = bytes(20 + i % 7, i);
        ASSERT_EQ(mb::exchange(window_, host(), request, reply, why), Status::kOk) << why;
        ASSERT_EQ(reply, std::vector<std::uint8_t>(request.rbegin(), request.rend()));
    }
    EXPECT_EQ(served_.load(), 200);
}

TEST_F(Mailbox, RequestLargerThanARecordIsRefused) {
    start_board();
    std::vector<std::uint8_t> reply;
    std::string why;
    EXPECT_EQ(mb::exchange(window_, host(), bytes(mb::kRecordCapacity + 1), reply, why),
              Status::kInvalidArgument);
    EXPECT_NE(why.find("exceeds the mailbox record"), std::string::npos) << why;
    EXPECT_EQ(served_.load(), 0);
}

TEST_F(Mailbox, NoBoardServingIsATransportError) {
    std::vector<std::uint8_t> reply;
    std::string why;
    EXPECT_EQ(mb::exchange(window_, host(), bytes(20), reply, why), Status::kTransportError);
    EXPECT_NE(why.find("not serving"), std::string::npos) << why;
}

TEST_F(Mailbox, BoardThatNeverAnswersIsATimeout) {
    mb::set_board_state(window_, mb::BoardState::kServing);  // serving, but nobody takes requests
    std::vector<std::uint8_t> reply;
    std::string why;
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(mb::exchange(window_, host(milliseconds(100)), bytes(20), reply, why),
              Status::kTimeout);
    EXPECT_GE(std::chrono::steady_clock::now() - t0, milliseconds(100));
    EXPECT_NE(why.find("no reply from the board within 100 ms"), std::string::npos) << why;
    EXPECT_EQ(window_.load(mb::kOffHostLock), 0u);
}

TEST_F(Mailbox, RequestLeftByATimedOutHostIsSettledBeforeTheNext) {
    mb::set_board_state(window_, mb::BoardState::kServing);
    std::vector<std::uint8_t> reply;
    std::string why;
    ASSERT_EQ(mb::exchange(window_, host(milliseconds(20)), bytes(20, 1), reply, why),
              Status::kTimeout);
    start_board();  // the board comes back and answers the old request first
    const auto request = bytes(24, 50);
    ASSERT_EQ(mb::exchange(window_, host(), request, reply, why), Status::kOk) << why;
    EXPECT_EQ(reply, std::vector<std::uint8_t>(request.rbegin(), request.rend()))
        << "not the stale reply";
    EXPECT_EQ(served_.load(), 2);
}

TEST_F(Mailbox, LockHeldByALiveHostIsATimeout) {
    start_board();
    window_.store(mb::kOffHostLock, 99);
    auto o = host(milliseconds(50));
    o.lock_holder_gone = [](std::uint32_t, std::chrono::nanoseconds, const void*) { return false; };
    std::vector<std::uint8_t> reply;
    std::string why;
    EXPECT_EQ(mb::exchange(window_, o, bytes(20), reply, why), Status::kTimeout);
    EXPECT_NE(why.find("held by another host (token 99)"), std::string::npos) << why;
    EXPECT_EQ(served_.load(), 0);
}

TEST_F(Mailbox, LockLeftByADeadHostIsTakenOver) {
    start_board();
    window_.store(mb::kOffHostLock, 99);
    auto o = host();
    o.lock_holder_gone = [](std::uint32_t token, std::chrono::nanoseconds, const void*) {
        return token == 99;
    };
    std::vector<std::uint8_t> reply;
    std::string why;
    EXPECT_EQ(mb::exchange(window_, o, bytes(20), reply, why), Status::kOk) << why;
    EXPECT_EQ(window_.load(mb::kOffHostLock), 0u);
}

TEST_F(Mailbox, ReplyRecordLengthOutOfRangeIsATransportError) {
    mb::set_board_state(window_, mb::BoardState::kServing);
    std::thread liar([this] {
        mb::Request request;
        while (!mb::take_request(window_, request, microseconds(10), milliseconds(20))) {
        }
        window_.store(mb::kOffReply, static_cast<std::uint32_t>(mb::kRecordCapacity + 1));
        window_.store(mb::kOffReplySequence, request.sequence);
        window_.wake(mb::kOffReplySequence);
    });
    std::vector<std::uint8_t> reply;
    std::string why;
    EXPECT_EQ(mb::exchange(window_, host(), bytes(20), reply, why), Status::kTransportError);
    EXPECT_NE(why.find("exceeds the record capacity"), std::string::npos) << why;
    liar.join();
}

TEST_F(Mailbox, RequestRecordLengthOutOfRangeReachesTheBoardAsNoBytes) {
    mb::set_board_state(window_, mb::BoardState::kServing);
    window_.store(mb::kOffRequest, 3);  // shorter than any frame
    window_.store(mb::kOffRequestSequence, 1);
    mb::Request request{{1, 2, 3}, 0};
    ASSERT_TRUE(mb::take_request(window_, request, microseconds(10), milliseconds(20)));
    EXPECT_TRUE(request.frame.empty());
    EXPECT_EQ(request.sequence, 1u);
}

TEST_F(Mailbox, NoRequestPendingMeansTheBoardTakesNothing) {
    mb::set_board_state(window_, mb::BoardState::kServing);
    window_.store(mb::kOffRequestSequence, 7);
    window_.store(mb::kOffReplySequence, 7);  // request 7 was answered
    mb::Request request;
    EXPECT_FALSE(mb::take_request(window_, request, microseconds(10), milliseconds(5)));
    window_.store(mb::kOffRequest, 20);
    window_.store(mb::kOffRequestSequence, 8);
    ASSERT_TRUE(mb::take_request(window_, request, microseconds(10), milliseconds(5)));
    EXPECT_EQ(request.sequence, 8u);
    EXPECT_EQ(request.frame.size(), 20u);
}

TEST_F(Mailbox, SequencesWrapAround) {
    window_.store(mb::kOffRequestSequence, 0xFFFFFFFFu);
    window_.store(mb::kOffReplySequence, 0xFFFFFFFFu);
    start_board();
    for (std::uint8_t i = 0; i < 3; ++i) {
        std::vector<std::uint8_t> reply;
        std::string why;
        const auto request = bytes(20, i);
        ASSERT_EQ(mb::exchange(window_, host(), request, reply, why), Status::kOk) << why;
        ASSERT_EQ(reply, std::vector<std::uint8_t>(request.rbegin(), request.rend()));
    }
    EXPECT_EQ(window_.load(mb::kOffRequestSequence), 2u);
    EXPECT_EQ(window_.load(mb::kOffReplySequence), 2u);
}

TEST_F(Mailbox, SequencesOutOfStepAreATransportErrorAndNothingIsSent) {
    mb::set_board_state(window_, mb::BoardState::kServing);
    window_.store(mb::kOffRequestSequence, 9);
    window_.store(mb::kOffReplySequence, 3);  // neither answered nor one request pending
    std::vector<std::uint8_t> reply;
    std::string why;
    EXPECT_EQ(mb::exchange(window_, host(milliseconds(100)), bytes(20), reply, why),
              Status::kTransportError);
    EXPECT_NE(why.find("out of step: request 9, reply 3"), std::string::npos) << why;
    EXPECT_EQ(window_.load(mb::kOffRequestSequence), 9u);
    EXPECT_EQ(window_.load(mb::kOffHostLock), 0u);
}

TEST_F(Mailbox, BoardStoppingWhileAHostWaitsEndsTheWait) {
    mb::set_board_state(window_, mb::BoardState::kServing);
    std::thread stopper([this] {
        std::this_thread::sleep_for(milliseconds(30));
        mb::set_board_state(window_, mb::BoardState::kStopped);
    });
    std::vector<std::uint8_t> reply;
    std::string why;
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(mb::exchange(window_, host(milliseconds(5000)), bytes(20), reply, why),
              Status::kTransportError);
    EXPECT_LT(std::chrono::steady_clock::now() - t0, milliseconds(1000));
    EXPECT_NE(why.find("stopped serving"), std::string::npos) << why;
    stopper.join();
}

TEST_F(Mailbox, SetBoardStateServingBumpsTheGeneration) {
    const auto g = window_.load(mb::kOffGeneration);
    mb::set_board_state(window_, mb::BoardState::kServing);
    EXPECT_EQ(window_.load(mb::kOffGeneration), g + 1);
}

TEST(AdaptiveSpin, StartsAtTheLongestHalvesOnEachLongWaitGrowsOnEachShortOne) {
    mb::AdaptiveSpin spin(microseconds(1), microseconds(16));
    EXPECT_EQ(spin.budget(), microseconds(16));
    spin.learn(microseconds(17));
    EXPECT_EQ(spin.budget(), microseconds(8)) << "a wait beyond the longest spin halves it";
    for (int i = 0; i < 10; ++i) spin.learn(milliseconds(1));
    EXPECT_EQ(spin.budget(), microseconds(1)) << "never below the shortest";
    spin.learn(nanoseconds(300));
    EXPECT_EQ(spin.budget(), microseconds(2)) << "a short wait doubles it";
    spin.learn(microseconds(6));
    EXPECT_EQ(spin.budget(), microseconds(12)) << "and makes it cover twice that wait";
    for (int i = 0; i < 10; ++i) spin.learn(microseconds(1));
    EXPECT_EQ(spin.budget(), microseconds(16)) << "never above the longest";
    spin.learn(microseconds(16));
    EXPECT_EQ(spin.budget(), microseconds(16)) << "a wait of exactly the longest still counts";
}

TEST(AdaptiveSpin, ABudgetThatShrankBelowThePeersAnswerTimeGrowsBack) {
    // The peer answers in 10 us; the budget had shrunk to 1 us, so the spin
    // misses and the waiter sleeps: the wait still shows that a longer spin
    // would have caught the answer.
    mb::AdaptiveSpin spin(microseconds(1), microseconds(50));
    for (int i = 0; i < 10; ++i) spin.learn(milliseconds(5));
    ASSERT_EQ(spin.budget(), microseconds(1));
    spin.learn(microseconds(10) + microseconds(25));  // answer time + a wake-up
    EXPECT_EQ(spin.budget(), microseconds(50));
    spin.learn(microseconds(10));
    EXPECT_EQ(spin.budget(), microseconds(50)) << "caught: it stays";
}

TEST_F(Mailbox, HostStopsSpinningForABoardThatAnswersSlowly) {
    mb::set_board_state(window_, mb::BoardState::kServing);
    std::thread slow_board([this] {  // 2 ms per request: far beyond any spin
        mb::Request request;
        for (int served = 0; served < 8;) {
            if (!mb::take_request(window_, request, microseconds(0), milliseconds(20))) continue;
            std::this_thread::sleep_for(milliseconds(2));
            mb::put_reply(window_, request, request.frame);
            ++served;
        }
    });
    mb::AdaptiveSpin spin(microseconds(1), microseconds(20));
    auto o = host();
    o.adaptive = &spin;
    std::vector<std::uint8_t> reply;
    std::string why;
    for (int i = 0; i < 8; ++i)
        ASSERT_EQ(mb::exchange(window_, o, bytes(20), reply, why), Status::kOk) << why;
    slow_board.join();
    EXPECT_EQ(spin.budget(), microseconds(1))
        << "eight misses: 20 -> 10 -> 5 -> 2.5 -> 1.25 -> 1 us";
}

}  // namespace
