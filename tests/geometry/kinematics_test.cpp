// SPDX-License-Identifier: MIT
// The B head kinematics (docs/design.md section 8; rwmos/geometry/kinematics.h).
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
    for (int step = -24; step <= 24; ++step) {
        const double b = 7.5 * step;
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

TEST(BcHeadKinematics, CZeroIsTheBHeadAlone) {
    for (double b : {-75.0, -20.0115, 0.0, 10.0, 90.0}) {
        EXPECT_NEAR((bc_head_tool_direction(b, 0.0) - b_head_tool_direction(b)).norm(), 0.0, kEps);
    }
}

TEST(BcHeadKinematics, CTurnsTheTiltedToolAboutZ) {
    const Eigen::Vector3d t = bc_head_tool_direction(90.0, 90.0);
    EXPECT_NEAR((t - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, kEps);
    for (int step = -12; step <= 12; ++step) {
        const double c = 22.5 * step;
        const Eigen::Vector3d tc = bc_head_tool_direction(30.0, c);
        EXPECT_NEAR(tc.norm(), 1.0, kEps);
        EXPECT_NEAR(tc.z(), std::cos(degrees_to_radians(30.0)), kEps);
        const Eigen::Vector3d turned =
            Eigen::AngleAxisd(degrees_to_radians(c), Eigen::Vector3d::UnitZ()) *
            b_head_tool_direction(30.0);
        EXPECT_NEAR((tc - turned).norm(), 0.0, kEps) << c;
    }
}

TEST(BcHeadKinematics, RotationTurnsPlusZIntoTheToolDirectionAndIsOrthonormal) {
    for (double b : {-60.0, 0.0, 25.0}) {
        for (double c : {-267.9784, 0.0, 45.0, 180.0}) {
            const Eigen::Matrix3d r = bc_head_rotation(b, c);
            EXPECT_NEAR((r * Eigen::Vector3d::UnitZ() - bc_head_tool_direction(b, c)).norm(), 0.0,
                        1e-15);
            EXPECT_NEAR((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-15);
            EXPECT_NEAR(r.determinant(), 1.0, 1e-15);
        }
    }
}

TEST(BcHeadKinematics, Tnc3dPeripheralBlock11PointsNearBlock12sToolVector) {
    // [TNC-3D], peripheral milling: block 11 turns the head to C-267.9784 B-20.0115; block 12
    // (a little further along the wall) gives T = (-0.0807, -0.3409, 0.9366).
    const Eigen::Vector3d t = bc_head_tool_direction(-20.0115, -267.9784);
    EXPECT_NEAR(t.z(), 0.9396, 1e-4);
    EXPECT_NEAR(t.y(), -0.3419, 1e-4);
    EXPECT_LT((t - Eigen::Vector3d(-0.0807, -0.3409, 0.9366)).norm(), 0.1);
}

}  // namespace
}  // namespace rwmos::geom
