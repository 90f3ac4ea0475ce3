// SPDX-License-Identifier: MIT
// compensate() and the touching geometry: which delta acts along which vector, FUNCTION PROG
// PATH, the reference point, and every refusal ([TNC-3D]).
#include "rwmos/comp3d/compensation.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>

#include "rwmos/comp3d/tolerances.h"
#include "rwmos/comp3d/vectors.h"
#include "touch_check.h"

namespace rwmos::comp3d {
namespace {

using V = Eigen::Vector3d;

constexpr double kTol = 1e-12;

const V kP(36.0084, 6.177, -1.9209);  // [TNC-3D], face milling, block 13
const V kN = V(-0.4658107, 0.0, 0.8848844).normalized();
const V kT = V(0.0, 0.6558846, 0.7548612).normalized();

Settings settings(ToolDimensions tool, const Deltas& d, ProgPath path = ProgPath::kOff,
                  ReferencePoint ref = ReferencePoint::kTip) {
    Settings s;
    s.tool = tool;
    s.deltas = d;
    s.prog_path = path;
    s.reference = ref;
    return s;
}

TEST(TouchGeometry, ContactPointIsTheInverseOfTipTouching) {
    for (const ToolDimensions d :
         {ToolDimensions{6.0, 0.0}, ToolDimensions{5.0, 1.5}, ToolDimensions{3.0, 3.0}}) {
        const V tip = tip_touching(kP, kN, kT, d);
        EXPECT_NEAR((contact_point(tip, kN, kT, d) - kP).norm(), 0.0, kTol);
        const test::Touch t = test::touch(kP, kN, tip, kT, {d.r, d.r2});
        EXPECT_LT(t.worst(), kTol) << d.r << " " << d.r2;
    }
}

TEST(TouchGeometry, NormalPointsToTheCornerRadiusCentre) {
    // [TNC-3D]: "Der Flächennormalenvektor zeigt immer auf das Zentrum Werkzeugradius 2 CR2".
    const ToolDimensions d{5.0, 1.5};
    const V tip = tip_touching(kP, kN, kT, d);
    EXPECT_NEAR((corner_centre(tip, kN, kT, d) - (kP + 1.5 * kN)).norm(), 0.0, kTol);
}

TEST(Compensate, WithoutDeltasTheProgrammedTipStays) {
    for (const ToolDimensions d :
         {ToolDimensions{6.0, 0.0}, ToolDimensions{5.0, 1.5}, ToolDimensions{3.0, 3.0}}) {
        const Compensated c = compensate(kP, kN, kT, settings(d, {}));
        ASSERT_EQ(c.refusal, Refusal::kNone);
        EXPECT_NEAR((c.tip - kP).norm(), 0.0, kTol);
    }
}

TEST(Compensate, DlActsAlongT) {
    const Compensated c = compensate(kP, kN, kT, settings({5.0, 1.5}, {0.3, 0.0, 0.0}));
    ASSERT_EQ(c.refusal, Refusal::kNone);
    EXPECT_NEAR((c.tip - (kP + 0.3 * kT)).norm(), 0.0, kTol);
}

TEST(Compensate, Dr2OfABallActsAlongNAtTheBallCentre) {
    // A ball with DR = DR2: its centre moves along N by DR2, the tip with it.
    const Compensated c = compensate(kP, kN, kT, settings({3.0, 3.0}, {0.0, -0.2, -0.2}));
    ASSERT_EQ(c.refusal, Refusal::kNone);
    const V centre_before = kP + 3.0 * kT;
    const V centre_after = c.tip + 2.8 * kT;
    EXPECT_NEAR((centre_after - (centre_before - 0.2 * kN)).norm(), 0.0, kTol);
}

TEST(Compensate, ClosedFormForTipOutputWithProgPathOff) {
    // tip = P + DR2 (N - T) - (DR - DR2) u + DL T.
    const Deltas d{0.05, -0.3, -0.1};
    const Compensated c = compensate(kP, kN, kT, settings({5.0, 1.5}, d));
    ASSERT_EQ(c.refusal, Refusal::kNone);
    const V u = corner_direction(kN, kT);
    const V expected = kP + d.dr2 * (kN - kT) - (d.dr - d.dr2) * u + d.dl * kT;
    EXPECT_NEAR((c.tip - expected).norm(), 0.0, kTol);
}

TEST(Compensate, DrInPeripheralMillingActsAlongTheSideNormalOnly) {
    // End mill, N perpendicular to T: only DR moves the tool, across motion and tool vector.
    const V t(0.0, 0.0, 1.0);
    const SideNormal side = side_normal(V(10.0, 0.0, 0.0), t, Side::kLeft);
    ASSERT_EQ(side.refusal, Refusal::kNone);
    const Compensated c = compensate(kP, side.n, t, settings({6.0, 0.0}, {0.0, -0.1, 0.0}));
    ASSERT_EQ(c.refusal, Refusal::kNone);
    EXPECT_NEAR((c.tip - (kP + V(0.0, -0.1, 0.0))).norm(), 0.0, kTol);
}

TEST(ProgPathContour, ProgrammedPointIsTheContourPoint) {
    for (const ToolDimensions d :
         {ToolDimensions{6.0, 0.0}, ToolDimensions{5.0, 1.5}, ToolDimensions{3.0, 3.0}}) {
        const Deltas delta{0.0, -0.1, d.r2 > 0 ? -0.1 : 0.0};
        const Compensated c = compensate(kP, kN, kT, settings(d, delta, ProgPath::kContour));
        ASSERT_EQ(c.refusal, Refusal::kNone);
        EXPECT_EQ(c.contact, kP);
        const ToolDimensions full = effective_tool(d, delta);
        EXPECT_LT(test::touch(kP, kN, c.tip, kT, {full.r, full.r2}).worst(), kTol);
    }
}

TEST(ProgPathContour, AppliesTheFullRadiiNotOnlyTheDeltas) {
    const Compensated off = compensate(kP, kN, kT, settings({3.0, 3.0}, {}, ProgPath::kOff));
    const Compensated contour =
        compensate(kP, kN, kT, settings({3.0, 3.0}, {}, ProgPath::kContour));
    EXPECT_NEAR((off.tip - kP).norm(), 0.0, kTol);
    EXPECT_NEAR((contour.tip - (kP + 3.0 * kN - 3.0 * kT)).norm(), 0.0, kTol);
}

TEST(ReferencePointCentre, ProgrammedPointIsTheCentreAtHeightR2) {
    const ToolDimensions d{5.0, 1.5};
    const Compensated tip_ref =
        compensate(kP, kN, kT, settings(d, {0.0, -0.1, -0.05}, ProgPath::kOff));
    const Compensated centre_ref =
        compensate(kP + 1.5 * kT, kN, kT,
                   settings(d, {0.0, -0.1, -0.05}, ProgPath::kOff, ReferencePoint::kCentre));
    ASSERT_EQ(centre_ref.refusal, Refusal::kNone);
    EXPECT_NEAR((tip_ref.tip - centre_ref.tip).norm(), 0.0, kTol);
    EXPECT_NEAR((tip_ref.contact - centre_ref.contact).norm(), 0.0, kTol);
}

TEST(ReferencePointCentre, IsIgnoredForContourPoints) {
    const Compensated a = compensate(kP, kN, kT, settings({3.0, 3.0}, {}, ProgPath::kContour));
    const Compensated b = compensate(
        kP, kN, kT, settings({3.0, 3.0}, {}, ProgPath::kContour, ReferencePoint::kCentre));
    EXPECT_EQ(a.tip, b.tip);
}

TEST(FlatEndFace, NormalAlongTheToolAxisTouchesWithTheTipCentre) {
    const V t(0.0, 0.0, 1.0);
    const Compensated c =
        compensate(kP, t, t, settings({5.0, 1.0}, {0.0, -0.2, -0.1}, ProgPath::kContour));
    ASSERT_EQ(c.refusal, Refusal::kNone);
    EXPECT_NEAR((c.tip - kP).norm(), 0.0, kTol);
}

TEST(CompensateRefuses, NonNormalisedVectors) {
    const Settings s = settings({3.0, 3.0}, {});
    EXPECT_EQ(compensate(kP, 0.9 * kN, kT, s).refusal, Refusal::kVectorNotNormalised);
    EXPECT_EQ(compensate(kP, kN, 1.1 * kT, s).refusal, Refusal::kVectorNotNormalised);
}

TEST(CompensateRefuses, InvalidCoordinates) {
    const Settings s = settings({3.0, 3.0}, {});
    EXPECT_EQ(compensate(V(std::numeric_limits<double>::quiet_NaN(), 0, 0), kN, kT, s).refusal,
              Refusal::kInvalidCoordinate);
    EXPECT_EQ(compensate(V(0, 2 * kMaxCoordinate, 0), kN, kT, s).refusal,
              Refusal::kInvalidCoordinate);
}

TEST(CompensateRefuses, InvalidToolsAndDeltas) {
    EXPECT_EQ(compensate(kP, kN, kT, settings({3.0, 4.0}, {})).refusal,
              Refusal::kCornerRadiusExceedsRadius);
    EXPECT_EQ(compensate(kP, kN, kT, settings({3.0, 3.0}, {0.0, -0.1, 0.0})).refusal,
              Refusal::kEffectiveCornerExceedsRadius);
    EXPECT_EQ(compensate(kP, kN, kT, settings({3.0, 0.0}, {0.0, -4.0, 0.0})).refusal,
              Refusal::kEffectiveRadiusNegative);
    EXPECT_EQ(compensate(kP, kN, kT,
                         settings({3.0, 0.0}, {std::numeric_limits<double>::infinity(), 0, 0}))
                  .refusal,
              Refusal::kInvalidDelta);
}

TEST(CompensateRefuses, NormalPointingAgainstTheTool) {
    const V t(0.0, 0.0, 1.0);
    const V down = V(0.3, 0.0, -0.9).normalized();
    EXPECT_EQ(compensate(kP, down, t, settings({3.0, 3.0}, {})).refusal,
              Refusal::kNormalAgainstTool);
    // Within the tolerance a peripheral normal that rounding tilted slightly down is accepted.
    const V slightly = V(1.0, 0.0, -0.5 * kNormalAgainstToolTolerance).normalized();
    EXPECT_EQ(compensate(kP, slightly, t, settings({3.0, 3.0}, {})).refusal, Refusal::kNone);
}

}  // namespace
}  // namespace rwmos::comp3d
