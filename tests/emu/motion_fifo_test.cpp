// SPDX-License-Identifier: MIT
// The motion layer's FIFO (rwmos/motion/fifo.h): first in, first out across the wrap of its
// circular buffer and across growth, both ends, indexing, iteration, and no growth while the
// queue's length stays within what it held before.
#include <gtest/gtest.h>

#include <deque>
#include <random>
#include <vector>

#include "rwmos/motion/fifo.h"

using rwmos::motion::Fifo;

namespace {

TEST(MotionFifo, BehavesAsADequeUnderRandomPushesAndPops) {
    Fifo<int> q;
    std::deque<int> ref;
    std::mt19937 rng(7);
    int next = 0;
    for (int step = 0; step < 100000; ++step) {
        const auto op = rng() % 10;
        if (op < 5 || ref.empty()) {
            q.push_back(next);
            ref.push_back(next++);
        } else if (op < 8) {
            ASSERT_EQ(q.front(), ref.front());
            q.pop_front();
            ref.pop_front();
        } else if (op < 9) {
            ASSERT_EQ(q.back(), ref.back());
            q.pop_back();
            ref.pop_back();
        } else if (rng() % 100 == 0) {
            q.clear();
            ref.clear();
        }
        ASSERT_EQ(q.size(), ref.size());
        ASSERT_EQ(q.empty(), ref.empty());
        if (!ref.empty()) {
            const std::size_t i = rng() % ref.size();
            ASSERT_EQ(q[i], ref[i]);
        }
    }
    std::vector<int> seen;
    for (int v : q) seen.push_back(v);
    EXPECT_EQ(seen, std::vector<int>(ref.begin(), ref.end()));
}

TEST(MotionFifo, GrowsKeepingTheOrderWhenWrapped) {
    Fifo<int> q;
    for (int i = 0; i < 16; ++i) q.push_back(i);
    for (int i = 0; i < 10; ++i) q.pop_front();    // head at 10: the next pushes wrap
    for (int i = 16; i < 40; ++i) q.push_back(i);  // grows while wrapped
    ASSERT_EQ(q.size(), 30u);
    for (std::size_t i = 0; i < q.size(); ++i) EXPECT_EQ(q[i], static_cast<int>(i) + 10);
}

TEST(MotionFifo, ASlidingQueueOfBoundedLengthNeverGrows) {
    Fifo<int> q;
    for (int i = 0; i < 256; ++i) q.push_back(i);
    const std::size_t capacity = q.capacity();
    for (int i = 256; i < 1000000; ++i) {
        q.pop_front();
        q.push_back(i);
    }
    EXPECT_EQ(q.capacity(), capacity);
    EXPECT_EQ(q.front(), 1000000 - 256);
    EXPECT_EQ(q.back(), 999999);
}

}  // namespace
