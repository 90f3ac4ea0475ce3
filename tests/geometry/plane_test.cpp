// SPDX-License-Identifier: MIT
// Plane mapping (TcPlane 17/18/19, [APCI-TC] "Tabelle 2") and coordinate rotation
// ([APCI-TC] "2.1.1 Koordinatendrehung").
#include "geometry/plane.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace geom {
namespace {

TEST(Plane, CodesSeventeenToNineteenAreThePlanes) {
    EXPECT_EQ(plane_from_code(17), Plane::kXY);
    EXPECT_EQ(plane_from_code(18), Plane::kZX);
    EXPECT_EQ(plane_from_code(19), Plane::kYZ);
    EXPECT_FALSE(plane_from_code(16).has_value());
    EXPECT_FALSE(plane_from_code(20).has_value());
    EXPECT_FALSE(plane_from_code(0).has_value());
    EXPECT_EQ(plane_code(Plane::kZX), 18);
}

TEST(Plane, SeventeenIsXYWithThirdAxisZ) {
    const PlaneAxes a = plane_axes(Plane::kXY);
    EXPECT_EQ(a.first, 0);
    EXPECT_EQ(a.second, 1);
    EXPECT_EQ(a.third, 2);
}

TEST(Plane, EighteenIsZXWithFirstAxisZAndThirdAxisY) {
    const PlaneAxes a = plane_axes(Plane::kZX);
    EXPECT_EQ(a.first, 2);
    EXPECT_EQ(a.second, 0);
    EXPECT_EQ(a.third, 1);
    const Vec3 p{1, 2, 3};
    EXPECT_EQ(to_plane(p, Plane::kZX), Vec2(3, 1));
    EXPECT_EQ(third_coordinate(p, Plane::kZX), 2);
}

TEST(Plane, NineteenIsYZWithThirdAxisX) {
    const Vec3 p{1, 2, 3};
    EXPECT_EQ(to_plane(p, Plane::kYZ), Vec2(2, 3));
    EXPECT_EQ(third_coordinate(p, Plane::kYZ), 1);
}

TEST(Plane, AxesOfEveryPlaneAreRightHanded) {
    for (Plane p : {Plane::kXY, Plane::kZX, Plane::kYZ}) {
        const PlaneAxes a = plane_axes(p);
        Vec3 e1 = Vec3::Zero(), e2 = Vec3::Zero(), e3 = Vec3::Zero();
        e1[a.first] = 1;
        e2[a.second] = 1;
        e3[a.third] = 1;
        EXPECT_EQ(e1.cross(e2), e3) << plane_code(p);
    }
}

TEST(Plane, FromPlaneInvertsToPlane) {
    const Vec3 p{-4.5, 7.25, 0.125};
    for (Plane plane : {Plane::kXY, Plane::kZX, Plane::kYZ})
        EXPECT_EQ(from_plane(to_plane(p, plane), third_coordinate(p, plane), plane), p);
}

TEST(Plane, BoardAxesFollowTheAxisAssignment) {
    const AxisAssignment axes{4, 6, 1};  // X is board axis 4, Y 6, Z 1
    const PlaneAxes xy = board_axes(Plane::kXY, axes);
    EXPECT_EQ(xy.first, 4);
    EXPECT_EQ(xy.second, 6);
    EXPECT_EQ(xy.third, 1);
    const PlaneAxes zx = board_axes(Plane::kZX, axes);
    EXPECT_EQ(zx.first, 1);
    EXPECT_EQ(zx.second, 4);
    EXPECT_EQ(zx.third, 6);
    const PlaneAxes yz = board_axes(Plane::kYZ, axes);
    EXPECT_EQ(yz.first, 6);
    EXPECT_EQ(yz.second, 1);
    EXPECT_EQ(yz.third, 4);
}

TEST(Rotation, PositiveAngleTurnsCounterClockwiseAboutTheCentre) {
    const Vec2 r = rotate_about({3, 1}, {1, 1}, 90.0);
    EXPECT_NEAR(r.x(), 1.0, 1e-15);
    EXPECT_NEAR(r.y(), 3.0, 1e-15);
    const Vec2 back = rotate_about(r, {1, 1}, -90.0);
    EXPECT_NEAR(back.x(), 3.0, 1e-15);
    EXPECT_NEAR(back.y(), 1.0, 1e-15);
}

TEST(Rotation, ZeroAngleAndCentreStayFixed) {
    EXPECT_EQ(rotate_about({3, 1}, {1, 1}, 0.0), Vec2(3, 1));
    EXPECT_EQ(rotate_about({1, 1}, {1, 1}, 37.0), Vec2(1, 1));
}

TEST(Rotation, ThirtyDegreesKeepsTheDistanceToTheCentre) {
    const Vec2 c{-2, 5};
    const Vec2 p{4, 1};
    const Vec2 r = rotate_about(p, c, 30.0);
    EXPECT_NEAR((r - c).norm(), (p - c).norm(), 1e-12);
    EXPECT_NEAR(std::acos((r - c).normalized().dot((p - c).normalized())) * 180 / M_PI, 30.0, 1e-9);
}

}  // namespace
}  // namespace geom
