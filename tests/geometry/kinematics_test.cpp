// SPDX-License-Identifier: MIT
// The B head kinematics (DESIGN.md section 8; rwmos/geometry/kinematics.h).
#include "rwmos/geometry/kinematics.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace rwmos::geom {
namespace {

constexpr double kEps = 1e-15;

TEST(BHeadKinematics, BZeroPointsTheToolAlongPlusZ) {
    const Eigen::Vector3d t = b_head_tool_direction(0.0);
    EXPECT_EQ(t, Eigen::Vector3d(0, 0, 1));
}

TEST(BHeadKinematics, PositiveBTiltsFromPlusZTowardsPlusX) {
    const Eigen::Vector3d t = b_head_tool_direction(90.0);
    EXPECT_NEAR(t.x(), 1.0, kEps);
    EXPECT_EQ(t.y(), 0.0);
    EXPECT_NEAR(t.z(), 0.0, kEps);
    const Eigen::Vector3d t45 = b_head_tool_direction(45.0);
    EXPECT_NEAR(t45.x(), std::sqrt(0.5), kEps);
    EXPECT_NEAR(t45.z(), std::sqrt(0.5), kEps);
    const Eigen::Vector3d tm = b_head_tool_direction(-30.0);
    EXPECT_NEAR(tm.x(), -0.5, kEps);
    EXPECT_NEAR(tm.z(), std::sqrt(3.0) / 2, kEps);
}

TEST(BHeadKinematics, DirectionIsAUnitVectorInTheZXPlane) {
    for (double b = -180.0; b <= 180.0; b += 7.5) {
        const Eigen::Vector3d t = b_head_tool_direction(b);
        EXPECT_NEAR(t.norm(), 1.0, kEps) << b;
        EXPECT_EQ(t.y(), 0.0) << b;
    }
}

TEST(BHeadKinematics, TiltIsARightHandedTurnAboutY) {
    for (double b : {-60.0, -12.5, 0.0, 33.0, 90.0, 135.0}) {
        const Eigen::Vector3d rotated =
            Eigen::AngleAxisd(degrees_to_radians(b), Eigen::Vector3d::UnitY()) *
            Eigen::Vector3d::UnitZ();
        EXPECT_NEAR((b_head_tool_direction(b) - rotated).norm(), 0.0, kEps) << b;
    }
}

TEST(BHeadKinematics, PivotSitsOneToolLengthBehindTheTip) {
    const Eigen::Vector3d tip{100, 5, 50};
    const Eigen::Vector3d pivot = b_head_pivot_from_tip(tip, 45.0, 50.0);
    EXPECT_NEAR((pivot - tip).norm(), 50.0, 1e-12);
    EXPECT_NEAR(pivot.x(), 100 + 50 * std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(pivot.z(), 50 + 50 * std::sqrt(0.5), 1e-12);
    const Eigen::Vector3d back = b_head_tip_from_pivot(pivot, 45.0, 50.0);
    EXPECT_NEAR((back - tip).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace rwmos::geom
