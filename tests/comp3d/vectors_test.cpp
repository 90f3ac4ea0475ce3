// SPDX-License-Identifier: MIT
// The vectors of LN lines: normalisation, the tool vector of face milling, the corner
// direction and the side of peripheral milling ([TNC-3D]).
#include "rwmos/comp3d/vectors.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>

#include "rwmos/comp3d/tolerances.h"

namespace rwmos::comp3d {
namespace {

using V = Eigen::Vector3d;

TEST(Normalised, UnitVectorIsAccepted) {
    const UnitVector u = normalised(V(-0.4658107, 0.0, 0.8848844));  // [TNC-3D], block 12
    EXPECT_EQ(u.refusal, Refusal::kNone);
    EXPECT_NEAR(u.v.norm(), 1.0, 1e-15);
}

TEST(Normalised, FourDecimalVectorsOfTheTnc3dExampleAreAcceptedAndMadeUnit) {
    // [TNC-3D], peripheral milling, block 12: written with 4 decimals.
    for (const V& v : {V(0.0, 0.9397, 0.3420), V(-0.0807, -0.3409, 0.9366)}) {
        const UnitVector u = normalised(v);
        EXPECT_EQ(u.refusal, Refusal::kNone) << v.transpose();
        EXPECT_NEAR(u.v.norm(), 1.0, 1e-15);
        EXPECT_LT((u.v - v).norm(), kUnitVectorTolerance);
    }
}

TEST(Normalised, NonNormalisedVectorIsRefused) {
    // The LN syntax example of [TNC-3D] ("Eingabe"): |N| = 0.9153, |T| = 0.9140.
    EXPECT_EQ(normalised(V(0.2637581, 0.0078922, -0.8764339)).refusal,
              Refusal::kVectorNotNormalised);
    EXPECT_EQ(normalised(V(0.0078922, -0.8764339, 0.2590319)).refusal,
              Refusal::kVectorNotNormalised);
    EXPECT_EQ(normalised(V(0.0, 0.0, 0.0)).refusal, Refusal::kVectorNotNormalised);
    EXPECT_EQ(normalised(V(0.0, 0.0, 2.0)).refusal, Refusal::kVectorNotNormalised);
}

TEST(Normalised, ToleranceIsOnTheLength) {
    EXPECT_EQ(normalised(V(0.0, 0.0, 1.0 + 0.9 * kUnitVectorTolerance)).refusal, Refusal::kNone);
    EXPECT_EQ(normalised(V(0.0, 0.0, 1.0 - 0.9 * kUnitVectorTolerance)).refusal, Refusal::kNone);
    EXPECT_EQ(normalised(V(0.0, 0.0, 1.0 + 1.1 * kUnitVectorTolerance)).refusal,
              Refusal::kVectorNotNormalised);
    EXPECT_EQ(normalised(V(0.0, 1.0 - 1.1 * kUnitVectorTolerance, 0.0)).refusal,
              Refusal::kVectorNotNormalised);
}

TEST(Normalised, NonFiniteVectorIsRefused) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(normalised(V(nan, 0.0, 1.0)).refusal, Refusal::kVectorNotNormalised);
    EXPECT_EQ(normalised(V(0.0, std::numeric_limits<double>::infinity(), 0.0)).refusal,
              Refusal::kVectorNotNormalised);
}

const V kN(-0.4658107, 0.0, 0.8848844);
const V kT(0.0, 0.6558846, 0.7548612);
const V kMachine(0.0, 0.0, 1.0);

TEST(FaceMillingToolVector, WithoutTAndWithTcpmTheToolStandsPerpendicularToTheContour) {
    EXPECT_EQ(effective_tool_vector(true, std::nullopt, kN, kMachine), kN);
}

TEST(FaceMillingToolVector, WithTAndTcpmTheToolKeepsTheProgrammedOrientation) {
    EXPECT_EQ(effective_tool_vector(true, kT, kN, kMachine), kT);
}

TEST(FaceMillingToolVector, WithoutTcpmTIsIgnoredEvenIfPresent) {
    EXPECT_EQ(effective_tool_vector(false, kT, kN, kMachine), kMachine);
    EXPECT_EQ(effective_tool_vector(false, std::nullopt, kN, kMachine), kMachine);
}

TEST(PeripheralToolVector, WithTAndWithoutNTcpmKeepsT) {
    EXPECT_EQ(effective_tool_vector(true, kT, std::nullopt, kMachine), kT);
}

TEST(CornerDirection, IsMinusNAcrossTheToolAxis) {
    const V t(0.0, 0.0, 1.0);
    const V n = V(1.0, 0.0, 1.0).normalized();
    const V u = corner_direction(n, t);
    EXPECT_NEAR((u - V(-1.0, 0.0, 0.0)).norm(), 0.0, 1e-15);
    EXPECT_NEAR(u.dot(t), 0.0, 1e-15);
}

TEST(CornerDirection, PeripheralContactIsOppositeN) {
    const V t(0.0, 0.0, 1.0);
    const V n(0.0, 1.0, 0.0);
    EXPECT_NEAR((corner_direction(n, t) - V(0.0, -1.0, 0.0)).norm(), 0.0, 1e-15);
}

TEST(CornerDirection, IsZeroWhenNIsParallelToT) {
    const V t = V(1.0, 2.0, 3.0).normalized();
    EXPECT_EQ(corner_direction(t, t), V::Zero());
    const V nearly = (t + V(1e-14, 0.0, 0.0)).normalized();
    EXPECT_EQ(corner_direction(nearly, t), V::Zero());
}

TEST(PeripheralSide, RlIsLeftOfTheMotionLookingDownTheToolVector) {
    const SideNormal left = side_normal(V(5.0, 0.0, 0.0), V(0.0, 0.0, 1.0), Side::kLeft);
    EXPECT_EQ(left.refusal, Refusal::kNone);
    EXPECT_NEAR((left.n - V(0.0, 1.0, 0.0)).norm(), 0.0, 1e-15);
    const SideNormal right = side_normal(V(5.0, 0.0, 0.0), V(0.0, 0.0, 1.0), Side::kRight);
    EXPECT_NEAR((right.n - V(0.0, -1.0, 0.0)).norm(), 0.0, 1e-15);
}

TEST(PeripheralSide, IsPerpendicularToMotionAndToolVector) {
    const V d(3.0, -1.0, 0.5);
    const V t = V(0.2, 0.1, 1.0).normalized();
    const SideNormal s = side_normal(d, t, Side::kRight);
    ASSERT_EQ(s.refusal, Refusal::kNone);
    EXPECT_NEAR(s.n.norm(), 1.0, 1e-15);
    EXPECT_NEAR(s.n.dot(d), 0.0, 1e-14);
    EXPECT_NEAR(s.n.dot(t), 0.0, 1e-15);
}

TEST(PeripheralSide, PeripheralExampleBlock11RlGivesTheNormalOfBlock12) {
    // [TNC-3D], peripheral milling: block 11 "L ... RL M128" runs to block 12, whose LN gives
    // N = (0, 0.9397, 0.3420) and T = (-0.0807, -0.3409, 0.9366): RL with that T and the
    // motion from block 11 to block 12 is the same side as N.
    const V from(48.4074, 102.4717, -7.1088);
    const V to(60.6593, 102.4690, -7.1012);
    const V t = V(-0.0807, -0.3409, 0.9366).normalized();
    const SideNormal s = side_normal(to - from, t, Side::kLeft);
    ASSERT_EQ(s.refusal, Refusal::kNone);
    EXPECT_NEAR((s.n - V(0.0, 0.9397, 0.3420).normalized()).norm(), 0.0, 5e-4);
}

TEST(PeripheralSide, NoSideWithoutMotionOrForAPlunge) {
    const V t(0.0, 0.0, 1.0);
    EXPECT_EQ(side_normal(V::Zero(), t, Side::kLeft).refusal, Refusal::kNoSideFromMotion);
    EXPECT_EQ(side_normal(V(0.0, 0.0, 0.5 * kMinMotionLength), t, Side::kLeft).refusal,
              Refusal::kNoSideFromMotion);
    EXPECT_EQ(side_normal(V(0.0, 0.0, -4.0), t, Side::kRight).refusal, Refusal::kNoSideFromMotion);
    EXPECT_EQ(side_normal(V(0.5 * kPlungeAngleTolerance, 0.0, 1.0), t, Side::kRight).refusal,
              Refusal::kNoSideFromMotion);
    EXPECT_EQ(side_normal(V(2.0 * kPlungeAngleTolerance, 0.0, 1.0), t, Side::kRight).refusal,
              Refusal::kNone);
}

TEST(PeripheralSide, PreviousNormalIsMadePerpendicularToT) {
    // [TNC-3D], peripheral example: block 13 (T only) at block 12's point keeps 12's N.
    const V n12(0.0, 0.9397, 0.3420);
    const V t = V(-0.0807, -0.3409, 0.9366).normalized();
    const SideNormal s = previous_side_normal(n12.normalized(), t);
    ASSERT_EQ(s.refusal, Refusal::kNone);
    EXPECT_NEAR(s.n.norm(), 1.0, 1e-15);
    EXPECT_NEAR(s.n.dot(t), 0.0, 1e-15);
    EXPECT_NEAR((s.n - n12.normalized()).norm(), 0.0, 1e-4);
}

TEST(PeripheralSide, PreviousNormalAlongTGivesNoSide) {
    const V t(0.0, 0.0, 1.0);
    EXPECT_EQ(previous_side_normal(t, t).refusal, Refusal::kNoSideFromMotion);
    EXPECT_EQ(previous_side_normal(V::Zero(), t).refusal, Refusal::kNoSideFromMotion);
}

}  // namespace
}  // namespace rwmos::comp3d
