// SPDX-License-Identifier: MIT
// The offset ramp ([ISG-OTC], FCT-C20, section 2.7.1: a changed wear value is distributed over
// several interpolation cycles; rwmos/otc/ramp.h).
#include <gtest/gtest.h>

#include <cmath>

#include "rwmos/otc/ramp.h"

namespace rwmos::otc {
namespace {

constexpr double kDt = 0.001;
constexpr RampLimits kLimits{0.5, 1.0};

TEST(OtcRamp, AStepOfTwoMillimetresTakesManyCyclesAndLandsExactly) {
    RampState s;
    int cycles = 0;
    while (!settled(s, 2.0) && cycles < 100000) {
        s = ramp_step(s, 2.0, kLimits, kDt);
        ++cycles;
    }
    EXPECT_EQ(s.position, 2.0);
    EXPECT_EQ(s.velocity, 0.0);
    // 2 mm at 0.5 mm/s takes 4 s plus 0.5 s to accelerate and to brake.
    EXPECT_GT(cycles, 4000);
    EXPECT_LT(cycles, 4700);
}

TEST(OtcRamp, NoStepIsLargerThanTheRampAllows) {
    RampState s;
    double target = 2.0;
    for (int i = 0; i < 20000; ++i) {
        if (i == 1500) target = -1.0;  // reversal while moving
        if (i == 9000) target = 0.3;
        const RampState next = ramp_step(s, target, kLimits, kDt);
        EXPECT_LE(std::abs(next.position - s.position), kLimits.velocity * kDt * (1 + 1e-12)) << i;
        EXPECT_LE(std::abs(next.velocity - s.velocity), kLimits.acceleration * kDt * (1 + 1e-12))
            << i;
        s = next;
    }
    EXPECT_TRUE(settled(s, 0.3));
}

TEST(OtcRamp, NeverAJump) {
    RampState s;
    s = ramp_step(s, 2.0, kLimits, kDt);
    EXPECT_GT(s.position, 0.0);
    EXPECT_LE(s.position, kLimits.acceleration * kDt * kDt);
}

TEST(OtcRamp, BrakesWithoutOvershootOnAFixedTarget) {
    RampState s;
    double highest = 0.0;
    for (int i = 0; i < 10000; ++i) {
        s = ramp_step(s, 0.75, kLimits, kDt);
        highest = std::max(highest, s.position);
    }
    EXPECT_EQ(highest, 0.75);
}

TEST(OtcRamp, SettledStaysSettled) {
    RampState s{1.25, 0.0};
    const RampState n = ramp_step(s, 1.25, kLimits, kDt);
    EXPECT_EQ(n.position, 1.25);
    EXPECT_EQ(n.velocity, 0.0);
}

// [ISG-OTC] section 2.1: ACC_WEIGHT in percent [1;100] weights the acceleration.
TEST(OtcRamp, AccWeightScalesTheAcceleration) {
    EXPECT_DOUBLE_EQ(weighted_acceleration(2.0, 100), 2.0);
    EXPECT_DOUBLE_EQ(weighted_acceleration(2.0, 50), 1.0);
    EXPECT_DOUBLE_EQ(weighted_acceleration(2.0, 1), 0.02);
    // A lower weight takes longer to reach the same offset.
    auto cycles_to = [](double acc) {
        RampState s;
        int n = 0;
        while (!settled(s, 0.1) && n < 1000000) {
            s = ramp_step(s, 0.1, RampLimits{0.5, acc}, kDt);
            ++n;
        }
        return n;
    };
    EXPECT_GT(cycles_to(weighted_acceleration(1.0, 10)),
              cycles_to(weighted_acceleration(1.0, 100)));
}

TEST(OtcRamp, BrakingSpeedMatchesTheDiscreteBrakingDistance) {
    // From m * a * dt, braking covers a * dt^2 * m (m + 1) / 2.
    const double a = 1.0;
    for (int m : {1, 2, 10, 500}) {
        const double dist = a * kDt * kDt * m * (m + 1) / 2.0;
        EXPECT_NEAR(braking_speed(dist, a, kDt), m * a * kDt, 1e-12) << m;
    }
    EXPECT_EQ(braking_speed(0.0, a, kDt), 0.0);
}

TEST(OtcRamp, FollowsAMovingTargetWithLag) {
    // A target turning faster than the ramp's speed limit is followed with a lag.
    RampState s{1.0, 0.0};
    double worst = 0.0;
    for (int i = 1; i <= 3000; ++i) {
        const double target = std::cos(i * kDt);  // speed up to 1 unit/s > 0.5
        s = ramp_step(s, target, kLimits, kDt);
        worst = std::max(worst, std::abs(s.position - target));
    }
    EXPECT_GT(worst, 0.1);
}

}  // namespace
}  // namespace rwmos::otc
