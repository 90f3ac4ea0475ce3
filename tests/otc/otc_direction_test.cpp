// SPDX-License-Identifier: MIT
// Wear directions of the four processing types ([ISG-OTC], FCT-C20, sections 2.2 to 2.5;
// rwmos/otc/direction.h).
#include <gtest/gtest.h>

#include <cmath>

#include "rwmos/geometry/kinematics.h"
#include "rwmos/otc/direction.h"

namespace rwmos::otc {
namespace {

constexpr double kEps = 1e-15;

TEST(OtcDirection, LengthWithoutTiltIsTheThirdMainAxis) {
    EXPECT_EQ(length_direction(0.0, geom::Plane::kXY), Vec3(0, 0, 1));
    EXPECT_EQ(length_direction(0.0, geom::Plane::kZX), Vec3(0, 1, 0));
    EXPECT_EQ(length_direction(0.0, geom::Plane::kYZ), Vec3(1, 0, 0));
}

// [ISG-OTC] section 2.3.1: the tilt splits the wear over two main axes, for G17 X and Z.
TEST(OtcDirection, LengthTiltSplitsIntoSinAndCosOnTwoAxes) {
    const Vec3 d = length_direction(30.0, geom::Plane::kXY);
    EXPECT_NEAR(d.x(), 0.5, kEps);
    EXPECT_EQ(d.y(), 0.0);
    EXPECT_NEAR(d.z(), std::sqrt(3.0) / 2.0, kEps);
    const Vec3 m = length_direction(-45.0, geom::Plane::kXY);
    EXPECT_NEAR(m.x(), -std::sqrt(0.5), kEps);
    EXPECT_NEAR(m.z(), std::sqrt(0.5), kEps);
}

TEST(OtcDirection, LengthTiltUsesTheFirstAxisOfEveryPlane) {
    // G18: first Z, third Y. G19: first Y, third X.
    const Vec3 zx = length_direction(30.0, geom::Plane::kZX);
    EXPECT_NEAR(zx.z(), 0.5, kEps);
    EXPECT_NEAR(zx.y(), std::sqrt(3.0) / 2.0, kEps);
    EXPECT_EQ(zx.x(), 0.0);
    const Vec3 yz = length_direction(30.0, geom::Plane::kYZ);
    EXPECT_NEAR(yz.y(), 0.5, kEps);
    EXPECT_NEAR(yz.x(), std::sqrt(3.0) / 2.0, kEps);
    EXPECT_EQ(yz.z(), 0.0);
}

TEST(OtcDirection, LengthTiltInG17TurnsLikeTheBHead) {
    for (double a : {-45.0, -10.0, 0.0, 22.5, 45.0})
        EXPECT_NEAR((length_direction(a, geom::Plane::kXY) - geom::b_head_tool_direction(a)).norm(),
                    0.0, kEps)
            << a;
}

// [ISG-OTC] section 2.2: the radius wear acts "senkrecht zur programmierten Kontur", towards the
// tool centre: left of the path for G41, right for G42.
TEST(OtcDirection, RadiusNormalPointsToTheToolSide) {
    EXPECT_EQ(contour_normal(Vec2(1, 0), Side::kLeft), Vec2(0, 1));
    EXPECT_EQ(contour_normal(Vec2(1, 0), Side::kRight), Vec2(0, -1));
    EXPECT_EQ(contour_normal(Vec2(0, 5), Side::kRight), Vec2(1, 0));
    const Vec2 n = contour_normal(Vec2(3, 4), Side::kLeft);
    EXPECT_NEAR(n.norm(), 1.0, kEps);
    EXPECT_NEAR(n.dot(Vec2(3, 4)), 0.0, kEps);
}

TEST(OtcDirection, RadiusNormalOfAStandingPathIsZero) {
    EXPECT_EQ(contour_normal(Vec2(0, 0), Side::kLeft), Vec2(0, 0));
}

// [ISG-OTC] section 2.5 example: the tool stands along Z (B0) and the path runs in X and Z.
TEST(OtcDirection, SurfaceNormalIsToolDirectionPerpendicularToThePath) {
    const Vec3 tool{0, 0, 1};
    const Vec3 fallback{0, 0, 1};
    // X5: a flat stretch, the normal is the tool direction.
    EXPECT_EQ(surface_normal(tool, Vec3(5, 0, 0), fallback), Vec3(0, 0, 1));
    // X3 Z-3: 45 degrees down, the normal points up and forward.
    const Vec3 n = surface_normal(tool, Vec3(3, 0, -3), fallback);
    EXPECT_NEAR(n.x(), std::sqrt(0.5), kEps);
    EXPECT_NEAR(n.z(), std::sqrt(0.5), kEps);
    EXPECT_NEAR(n.dot(Vec3(3, 0, -3)), 0.0, 1e-14);
    // X-5 Z1: up and back.
    const Vec3 b = surface_normal(tool, Vec3(-5, 0, 1), fallback);
    EXPECT_NEAR(b.dot(Vec3(-5, 0, 1)), 0.0, 1e-14);
    EXPECT_GT(b.z(), 0.0);
    EXPECT_GT(b.x(), 0.0);
}

TEST(OtcDirection, SurfaceNormalPointsToTheToolSide) {
    const Vec3 tool = geom::b_head_tool_direction(30.0);
    for (const Vec3& t : {Vec3(1, 0, 0), Vec3(1, 2, -3), Vec3(-4, 1, 1)}) {
        const Vec3 n = surface_normal(tool, t, Vec3::UnitZ());
        EXPECT_NEAR(n.norm(), 1.0, 1e-14);
        EXPECT_GE(n.dot(tool), 0.0);
    }
}

TEST(OtcDirection, SurfaceNormalAlongTheToolAxisKeepsTheLastNormal) {
    const Vec3 last{1, 0, 0};
    EXPECT_EQ(surface_normal(Vec3(0, 0, 1), Vec3(0, 0, -7), last), last);
    EXPECT_EQ(surface_normal(Vec3(0, 0, 1), Vec3(0, 0, 0), last), last);
}

}  // namespace
}  // namespace rwmos::otc
