// SPDX-License-Identifier: MIT
// The spooler writes a call's moves where they will run, at the back of the executor's queue,
// and drops them again when the call does not keep them: a call refused after it had already
// ended the contour under way (its held profile's moves built), and a call that finds the
// queue full, leave the queue and the held profile exactly as before. And a profile's targets
// are checked as they always were.
#include <gtest/gtest.h>

#include <limits>

#include "rwmos/motion/executor.h"
#include "rwmos/motion/spooler.h"

using namespace rwmos::motion;
using objif::Status;

namespace {

constexpr double kCycle = 0.001;

Profile line_to(double x, double y) {
    Profile p;
    p.kind = ProfileKind::kLine;
    p.feed = 600.0;
    p.axes = 0b11;
    p.target[0] = x;
    p.target[1] = y;
    return p;
}

TcSettings compensating() {
    TcSettings tc;
    tc.present = true;
    tc.run = true;
    tc.active_group = 1;
    tc.radius = 1.0;
    return tc;
}

struct Queue {
    std::size_t fill;
    AxisVector end;
};
Queue queue_of(const Executor& exec) {
    return {exec.fill(), exec.planned_end()};
}

}  // namespace

TEST(SpoolerBatch, ARefusalAfterTheContourWasEndedLeavesQueueAndHeldProfile) {
    Spooler s;
    Executor exec;
    const TcSettings tc = compensating();
    ASSERT_TRUE(s.spool(line_to(10, 0), tc, exec, 64, kCycle).ok());
    ASSERT_TRUE(s.spool(line_to(10, 10), tc, exec, 64, kCycle).ok());
    ASSERT_TRUE(s.holds_profile());
    const Queue before = queue_of(exec);
    ASSERT_GT(before.fill, 0u);
    // Without compensation the call first ends the contour (the held profile's moves are
    // built), then finds the arc's end off its circle: refused.
    TcSettings off = tc;
    off.run = false;
    Profile bad = line_to(0, 10);
    bad.kind = ProfileKind::kArcCcw;
    bad.center = {5.0, 12.0};
    const MotionResult r = s.spool(bad, off, exec, 64, kCycle);
    EXPECT_EQ(r.status, Status::kInvalidValue);
    EXPECT_EQ(exec.fill(), before.fill);
    EXPECT_EQ(exec.planned_end(), before.end);
    EXPECT_TRUE(s.holds_profile());
    // The contour goes on from the held profile as if the refused call had not been.
    ASSERT_TRUE(s.spool(line_to(0, 10), tc, exec, 64, kCycle).ok());
    EXPECT_EQ(exec.fill(), before.fill + 1);  // the held line, trimmed at the inside corner
}

TEST(SpoolerBatch, AFullQueueTakesNothingAndDropsTheMovesBuilt) {
    Spooler s;
    Executor exec;
    const TcSettings tc = compensating();
    ASSERT_TRUE(s.spool(line_to(10, 0), tc, exec, 64, kCycle).ok());
    const Queue before = queue_of(exec);
    // The next call builds the held line and a transition: more than one more move fits.
    const MotionResult busy = s.spool(line_to(10, -10), tc, exec, before.fill + 1, kCycle);
    EXPECT_EQ(busy.status, Status::kBusy);
    EXPECT_EQ(exec.fill(), before.fill);
    EXPECT_EQ(exec.planned_end(), before.end);
    EXPECT_TRUE(s.holds_profile());
    ASSERT_TRUE(s.spool(line_to(10, -10), tc, exec, 64, kCycle).ok());
    EXPECT_EQ(exec.fill(), before.fill + 2);  // the held line and the outside transition
}

TEST(SpoolerTargets, AtTheLimitTakenBeyondItOrNotFiniteRefusedWithTheirStatus) {
    // The check of a profile's targets takes every coordinate within +-100000 at one test an
    // axis; one that is not gets its own status, whichever axis it is on.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    struct Case {
        double v;
        int axis;
        Status want;
    };
    const Case cases[] = {
        {kMaxCoordinate, 0, Status::kOk},
        {-kMaxCoordinate, 7, Status::kOk},
        {nan, 1, Status::kInvalidValue},
        {inf, 6, Status::kInvalidValue},
        {-inf, 2, Status::kInvalidValue},
        {1.0000000001e5, 3, Status::kValueTooHigh},
        {-1.0000000001e5, 5, Status::kValueTooLow},
    };
    for (const Case& c : cases) {
        Spooler s;
        Executor exec;
        Profile p;
        p.kind = ProfileKind::kRapid;
        p.axes = static_cast<AxisMask>(1u << c.axis);
        p.target[c.axis] = c.v;
        p.target[(c.axis + 1) % kAxisCount] = nan;  // not named: not checked
        const MotionResult r = s.spool(p, TcSettings{}, exec, 64, kCycle);
        EXPECT_EQ(r.status, c.want) << c.axis << " " << c.v;
        EXPECT_EQ(exec.fill(), c.want == Status::kOk ? 1u : 0u) << c.axis << " " << c.v;
    }
}
