// SPDX-License-Identifier: MIT
// The bounded FIFO behind the trace and the executed-segment log: it keeps
// the newest entries, counts the dropped ones, and grows its storage with the
// content. Checked against a reference model (std::deque) on random sequences
// of pushes (by value and written in place) and takes (copied out and visited in place), at
// every capacity from 0 to 9.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <random>
#include <span>
#include <vector>

#include "rwmos/motion/ring.h"

namespace {

using rwmos::motion::Ring;

void expect_same(const Ring<int>& ring, const std::deque<int>& model, std::uint64_t lost) {
    ASSERT_EQ(ring.size(), model.size());
    ASSERT_EQ(ring.empty(), model.empty());
    ASSERT_EQ(ring.lost(), lost);
    for (std::size_t i = 0; i < model.size(); ++i) ASSERT_EQ(ring.at(i), model[i]) << "entry " << i;
}

TEST(MotionRing, MatchesAFifoThatKeepsTheNewestOnRandomPushesAndTakes) {
    std::mt19937 rng(7);
    for (std::size_t capacity = 0; capacity < 10; ++capacity) {
        Ring<int> ring(capacity);
        EXPECT_EQ(ring.capacity(), capacity);
        std::deque<int> model;
        std::uint64_t lost = 0;
        int next = 0;
        for (int step = 0; step < 2000; ++step) {
            if (rng() % 3 != 0) {
                // push_with (the entry written in place) is push.
                if (rng() % 2 == 0)
                    ring.push(next);
                else
                    ring.push_with([&](int& slot) { slot = next; });
                model.push_back(next++);
                if (model.size() > capacity) {
                    model.pop_front();
                    ++lost;
                }
            } else {
                std::vector<int> out(rng() % 5);
                // take_runs (the entries handed over where they lie, run by run) is take.
                std::size_t n = 0;
                if (rng() % 2 == 0) {
                    n = ring.take(out);
                } else {
                    std::size_t visited = 0;
                    int runs = 0;
                    n = ring.take_runs(out.size(), [&](std::span<const int> run) {
                        EXPECT_FALSE(run.empty());
                        ++runs;
                        for (const int v : run) out[visited++] = v;
                    });
                    EXPECT_EQ(visited, n);
                    EXPECT_LE(runs, 2) << "at most where the storage wraps";
                }
                const std::size_t expected = std::min(out.size(), model.size());
                ASSERT_EQ(n, expected);
                for (std::size_t i = 0; i < n; ++i) {
                    ASSERT_EQ(out[i], model.front());
                    model.pop_front();
                }
            }
            expect_same(ring, model, lost);
        }
    }
}

TEST(MotionRing, NewCapacityDropsTheContentAndTheLostCount) {
    Ring<int> ring(2);
    for (int i = 0; i < 5; ++i) ring.push(i);
    expect_same(ring, {3, 4}, 3);
    ring.set_capacity(3);
    EXPECT_EQ(ring.capacity(), 3U);
    expect_same(ring, {}, 0);
    for (int i = 10; i < 14; ++i) ring.push(i);
    expect_same(ring, {11, 12, 13}, 1);
    ring.clear();
    expect_same(ring, {}, 1);
}

TEST(MotionRing, ZeroCapacityKeepsNothingAndCountsEveryPush) {
    Ring<int> ring;
    ring.push(1);
    ring.push(2);
    expect_same(ring, {}, 2);
}

// The storage grows with the content and never beyond the capacity (a vector doubling on its
// own reserved up to twice the capacity: the trace's memory limit would not have held).
TEST(MotionRing, StorageNeverExceedsTheCapacity) {
    for (const std::size_t capacity :
         {std::size_t{1}, std::size_t{3}, std::size_t{100}, std::size_t{1000}, std::size_t{1025}}) {
        rwmos::motion::Ring<int> ring(capacity);
        for (std::size_t i = 0; i < 3 * capacity; ++i) {
            ring.push(static_cast<int>(i));
            ASSERT_LE(ring.reserved(), capacity) << capacity << " after " << i + 1;
        }
        EXPECT_EQ(ring.reserved(), capacity);
        int v = 0;
        ring.push_with([&](int& slot) { slot = ++v; });
        EXPECT_EQ(ring.reserved(), capacity);
    }
}

// A ring drained as fast as it fills (the executed-segment log read back after every clock
// run) starts again at its first slot: its storage stays what the most entries waiting at once
// need, not the capacity (memory touched once, no page faults for entries long taken). Drained
// with its content in the middle of the storage (3 taken of a storage of 4), the next pushes
// would otherwise reach the storage's end and grow it although its first slots are free.
TEST(MotionRing, StorageFollowsWhatWaitsNotWhatPassedThrough) {
    Ring<int> ring(4096);
    int next = 0;
    std::vector<int> out(4);
    for (int round = 0; round < 1000; ++round) {
        const std::size_t n = round % 2 == 0 ? 4 : 3;  // 4, 3, 4, 3, ...
        for (std::size_t i = 0; i < n; ++i) ring.push(next++);
        ASSERT_EQ(ring.take(std::span<int>(out.data(), n)), n);
        EXPECT_EQ(out[0], next - static_cast<int>(n));
        EXPECT_EQ(out[n - 1], next - 1);
        ASSERT_TRUE(ring.empty());
        ASSERT_EQ(ring.reserved(), 4U) << "round " << round << ": 4 waiting at most";
    }
    // Drained in place too (take_runs): 3, 4, 3, 4, ...
    for (int round = 0; round < 1000; ++round) {
        const std::size_t n = round % 2 == 0 ? 3 : 4;
        for (std::size_t i = 0; i < n; ++i) ring.push(next++);
        int first = -1;
        EXPECT_EQ(ring.take_runs(n,
                                 [&](std::span<const int> run) {
                                     if (first < 0) first = run.front();
                                 }),
                  n);
        EXPECT_EQ(first, next - static_cast<int>(n));
        ASSERT_EQ(ring.reserved(), 4U) << "round " << round;
    }
}

}  // namespace
