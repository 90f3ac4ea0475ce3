// SPDX-License-Identifier: MIT
// The rules of the temperature compensation in tool direction ([SIN-TEMP], SINUMERIK FB1 W1
// section 2.8), as pure functions.
#include "rwmos/tempcomp/tempcomp.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "rwmos/geometry/kinematics.h"

namespace rwmos::tempcomp {
namespace {

using V = Eigen::Vector3d;

Settings all_on() {
    Settings s;
    s.on = true;
    s.type.fill(kToolDirectionBit);
    s.comp = V(0.01, 0.02, 0.03);
    return s;
}

TEST(TempComp, Bit2OfMd32750TakesTheToolDirection) {
    EXPECT_TRUE(takes_tool_direction(0x04));
    EXPECT_TRUE(takes_tool_direction(0x07));
    EXPECT_FALSE(takes_tool_direction(0x03));
    EXPECT_FALSE(takes_tool_direction(0));
}

TEST(TempComp, ComponentsActOnTheThreeGeometryAxesInOrder) {
    const Settings s = all_on();
    const AxisValues t = targets(s, s.comp);
    EXPECT_EQ(t[0], 0.01);
    EXPECT_EQ(t[1], 0.02);
    EXPECT_EQ(t[2], 0.03);
    for (int a = 3; a < kAxisCount; ++a) EXPECT_EQ(t[static_cast<std::size_t>(a)], 0.0);
}

TEST(TempComp, GeometryAxisAssignmentDecidesWhichBoardAxisTakesWhichComponent) {
    Settings s = all_on();
    s.geometry_axes = {5, 0, 3};
    const AxisValues t = targets(s, s.comp);
    EXPECT_EQ(t[5], 0.01);
    EXPECT_EQ(t[0], 0.02);
    EXPECT_EQ(t[3], 0.03);
    EXPECT_EQ(t[1], 0.0);
    EXPECT_EQ(t[2], 0.0);
    EXPECT_TRUE(is_geometry_axis(s, 5));
    EXPECT_FALSE(is_geometry_axis(s, 2));
}

TEST(TempComp, Md20390OffMeansNoValueAnywhere) {
    Settings s = all_on();
    s.on = false;
    for (const double v : targets(s, s.comp)) EXPECT_EQ(v, 0.0);
}

TEST(TempComp, AxisWithoutBit2GetsNoValueSilentlyOthersUnaffected) {
    Settings s = all_on();
    s.type[1] = 0x03;  // bits 0 and 1, not 2
    const AxisValues t = targets(s, s.comp);
    EXPECT_EQ(t[0], 0.01);
    EXPECT_EQ(t[1], 0.0);
    EXPECT_EQ(t[2], 0.03);
}

TEST(TempComp, VectorTurnsWithTheToolHolder) {
    const V z(0, 0, 0.05);
    const V turned = oriented(z, geom::bc_head_rotation(90.0, 0.0));
    EXPECT_NEAR((turned - V(0.05, 0, 0)).norm(), 0.0, 1e-15);
    // The vector turns as the tool does: +Z (the tool in its basic position) goes where the tool
    // points.
    const V t = geom::bc_head_tool_direction(-20.0, 35.0);
    EXPECT_NEAR((oriented(V(0, 0, 1), geom::bc_head_rotation(-20.0, 35.0)) - t).norm(), 0.0, 1e-15);
    // Lengths are kept.
    EXPECT_NEAR(oriented(V(0.01, 0.02, 0.03), geom::bc_head_rotation(33, -71)).norm(),
                V(0.01, 0.02, 0.03).norm(), 1e-17);
}

TEST(TempComp, RampGoesTowardsZeroByAtMostTheStepAndNeverPastIt) {
    EXPECT_DOUBLE_EQ(ramp_to_zero(0.03, 0.001), 0.029);
    EXPECT_DOUBLE_EQ(ramp_to_zero(-0.03, 0.001), -0.029);
    EXPECT_EQ(ramp_to_zero(0.0005, 0.001), 0.0);
    EXPECT_EQ(ramp_to_zero(-0.001, 0.001), 0.0);
    EXPECT_EQ(ramp_to_zero(0.0, 0.001), 0.0);
}

}  // namespace
}  // namespace rwmos::tempcomp
