// SPDX-License-Identifier: MIT
// The worked examples of [TNC-3D] ("Beispiele" under face and peripheral milling). In each,
// the tool of the stated actual size, with its tip at the compensated tip, touches the design
// surface point along N (or stands off it by the allowance) within 1e-9, checked with the
// independent touch test of touch_check.h.
//
// The design surface point, normal and tool vector are those of [TNC-3D]'s face-milling block
// 13 (N and T normalised to 7 decimals there). The tool is measured at its tip
// ("Werkzeugvermessung auf Werkzeugspitze"): the tool table's L reaches the actual tip, so the
// actual tip is where the compensated tip is.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "rwmos/comp3d/compensation.h"
#include "rwmos/comp3d/vectors.h"
#include "touch_check.h"

namespace rwmos::comp3d {
namespace {

using V = Eigen::Vector3d;

constexpr double kTouchTolerance = 1e-9;

const V kS(36.0084, 6.177, -1.9209);
const V kN = V(-0.4658107, 0.0, 0.8848844).normalized();
const V kT = V(0.0, 0.6558846, 0.7548612).normalized();

// The CAM output for the 6 mm ball mill (R 3, R2 3) of the examples.
const ToolDimensions kCamBall{3.0, 3.0};
const V kCamTip = kS + 3.0 * kN - 3.0 * kT;  // "NC-Punkte auf Werkzeugspitze ausgegeben"
const V kCamCentre = kS + 3.0 * kN;          // "NC-Punkte auf Kugelmitte ausgegeben"

Settings example_settings(Deltas tool_table, Deltas tool_call, ReferencePoint ref) {
    Settings s;
    s.tool = kCamBall;  // "R und R2 die theoretischen Werkzeugdaten wie aus dem CAM-System"
    s.deltas = sum_deltas({tool_table, tool_call, {}});
    s.reference = ref;
    return s;
}

TEST(Tnc3dExample, CamPointsAreThoseOfThe6mmBall) {
    EXPECT_LT(test::touch(kS, kN, kCamTip, kT, {3.0, 3.0}).worst(), 1e-12);
    EXPECT_LT(test::touch(kS, kN, kCamCentre - 3.0 * kT, kT, {3.0, 3.0}).worst(), 1e-12);
}

// "Nachgeschliffenen Kugelfräser korrigieren, CAM-Ausgabe Werkzeugspitze": a reground ball
// mill of 5.8 mm instead of 6 mm; tool table R 3, R2 3, DL 0, DR -0.1, DR2 -0.1.
TEST(Tnc3dExample, RegroundBallMillTipOutputTouchesTheDesignSurface) {
    const Settings s = example_settings({0.0, -0.1, -0.1}, {}, ReferencePoint::kTip);
    EXPECT_EQ(check_tool_load(s.tool, s.deltas, false), Refusal::kNone);
    const Compensated c = compensate(kCamTip, kN, kT, s);
    ASSERT_EQ(c.refusal, Refusal::kNone);
    EXPECT_LT(test::touch(kS, kN, c.tip, kT, {2.9, 2.9}).worst(), kTouchTolerance);
    // The actual ball's centre lies 2.9 from S along N.
    EXPECT_NEAR((c.tip + 2.9 * kT - (kS + 2.9 * kN)).norm(), 0.0, kTouchTolerance);
}

// "... CAM-Ausgabe Kugelmitte": same tool table, TCPM REFPNT CNT-CNT; [TNC-3D]: "Mit TCPM REFPNT
// CNT-CNT sind die Werkzeugkorrekturwerte für die Ausgaben auf Werkzeugspitze oder Kugelmitte
// identisch".
TEST(Tnc3dExample, RegroundBallMillCentreOutputTouchesTheDesignSurface) {
    const Settings s = example_settings({0.0, -0.1, -0.1}, {}, ReferencePoint::kCentre);
    const Compensated c = compensate(kCamCentre, kN, kT, s);
    ASSERT_EQ(c.refusal, Refusal::kNone);
    EXPECT_LT(test::touch(kS, kN, c.tip, kT, {2.9, 2.9}).worst(), kTouchTolerance);
    EXPECT_NEAR((centre_of(c.tip, kT, effective_tool(s.tool, s.deltas)) - (kS + 2.9 * kN)).norm(),
                0.0, kTouchTolerance);
    // Same delta values, same commanded tip as with tip output.
    const Compensated from_tip =
        compensate(kCamTip, kN, kT, example_settings({0.0, -0.1, -0.1}, {}, ReferencePoint::kTip));
    EXPECT_NEAR((c.tip - from_tip.tip).norm(), 0.0, kTouchTolerance);
}

// "Werkstückaufmaß erzeugen, CAM-Ausgabe Werkzeugspitze": the 6 mm ball mill leaves 0.2 mm
// stock; TOOL CALL DL +0.2 DR +0.2 DR2 +0.2; "Mit M107 Fehlermeldung unterdrücken".
TEST(Tnc3dExample, AllowanceViaToolCallTipOutputStandsOffByTheAllowance) {
    const Settings s = example_settings({}, {0.2, 0.2, 0.2}, ReferencePoint::kTip);
    EXPECT_EQ(check_tool_load(s.tool, s.deltas, false), Refusal::kPositiveOversize);
    EXPECT_EQ(check_tool_load(s.tool, s.deltas, true), Refusal::kNone);
    const Compensated c = compensate(kCamTip, kN, kT, s);
    ASSERT_EQ(c.refusal, Refusal::kNone);
    // The actual tool is the 6 mm ball: it stands off S by 0.2 along N ...
    EXPECT_LT(test::touch(kS + 0.2 * kN, kN, c.tip, kT, {3.0, 3.0}).worst(), kTouchTolerance);
    // ... which is the tool as dimensioned (R 3.2, tip DL = 0.2 further down) touching S.
    EXPECT_LT(test::touch(kS, kN, c.tip - 0.2 * kT, kT, {3.2, 3.2}).worst(), kTouchTolerance);
}

// "Werkstückaufmaß erzeugen, CAM-Ausgabe Kugelmitte".
TEST(Tnc3dExample, AllowanceViaToolCallCentreOutputStandsOffByTheAllowance) {
    const Settings s = example_settings({}, {0.2, 0.2, 0.2}, ReferencePoint::kCentre);
    const Compensated c = compensate(kCamCentre, kN, kT, s);
    ASSERT_EQ(c.refusal, Refusal::kNone);
    EXPECT_LT(test::touch(kS + 0.2 * kN, kN, c.tip, kT, {3.0, 3.0}).worst(), kTouchTolerance);
    EXPECT_NEAR((c.tip + 3.0 * kT - (kS + 3.2 * kN)).norm(), 0.0, kTouchTolerance);
}

// The numbers docs/3d-compensation.md section 9 shows, to its 4 decimals.
TEST(Tnc3dExample, TcpValuesShownInTheDocs) {
    constexpr double kShown = 5e-5;
    EXPECT_LT((kCamTip - V(34.6110, 4.2093, -1.5308)).cwiseAbs().maxCoeff(), kShown);
    EXPECT_LT((kCamCentre - V(34.6110, 6.1770, 0.7338)).cwiseAbs().maxCoeff(), kShown);
    const V reground(34.6575, 4.2749, -1.5438);
    const V allowance(34.5178, 4.2093, -1.3539);
    for (const ReferencePoint ref : {ReferencePoint::kTip, ReferencePoint::kCentre}) {
        const V p = ref == ReferencePoint::kTip ? kCamTip : kCamCentre;
        const Compensated a = compensate(p, kN, kT, example_settings({0.0, -0.1, -0.1}, {}, ref));
        const Compensated b = compensate(p, kN, kT, example_settings({}, {0.2, 0.2, 0.2}, ref));
        EXPECT_LT((a.tip - reground).cwiseAbs().maxCoeff(), kShown);
        EXPECT_LT((b.tip - allowance).cwiseAbs().maxCoeff(), kShown);
    }
}

// "Nachgeschliffenen Schaftfräser korrigieren, CAM-Ausgabe Werkzeugmitte": an end mill of
// 11.8 mm instead of 12 mm in peripheral milling; tool table R 6, R2 0, DL 0, DR -0.1.
// Block 12 of [TNC-3D]'s peripheral example gives N and T (T perpendicular to N).
const V kWallN = V(0.0, 0.9397, 0.3420).normalized();
const V kWallT = V(-0.0807, -0.3409, 0.9366).normalized();
const V kWallS(60.6593, 102.4690, -7.1012);

Settings end_mill_settings() {
    Settings s;
    s.tool = {6.0, 0.0};
    s.deltas = {0.0, -0.1, 0.0};
    return s;
}

TEST(Tnc3dExample, RegroundEndMillPeripheralWithNTouchesTheWall) {
    const Settings s = end_mill_settings();
    const V cam_tip = tip_touching(kWallS, kWallN, kWallT, s.tool);
    ASSERT_LT(test::touch(kWallS, kWallN, cam_tip, kWallT, {6.0, 0.0}).worst(), 1e-12);
    const Compensated c = compensate(cam_tip, kWallN, kWallT, s);
    ASSERT_EQ(c.refusal, Refusal::kNone);
    EXPECT_LT(test::touch(kWallS, kWallN, c.tip, kWallT, {5.9, 0.0}).worst(), kTouchTolerance);
    // The tool moved by 0.1 towards the wall, across the tool vector.
    EXPECT_NEAR((c.tip - cam_tip).norm(), 0.1, 1e-6);
    EXPECT_NEAR((c.tip - cam_tip).dot(kWallT), 0.0, 1e-6);
}

TEST(Tnc3dExample, RegroundEndMillPeripheralWithRlTouchesTheWall) {
    // Variant with the side from RL: the wall normal is T x D for the motion of block 11 -> 12.
    const V t(0.0, 0.0, 1.0);
    const V from(48.4074, 102.4717, -7.1088);
    const V d = kWallS - from;
    const SideNormal side = side_normal(d, t, Side::kLeft);
    ASSERT_EQ(side.refusal, Refusal::kNone);
    const Settings s = end_mill_settings();
    const V cam_tip = kWallS + 6.0 * side.n;
    const Compensated c = compensate(cam_tip, side.n, t, s);
    ASSERT_EQ(c.refusal, Refusal::kNone);
    EXPECT_LT(test::touch(kWallS, side.n, c.tip, t, {5.9, 0.0}).worst(), kTouchTolerance);
    EXPECT_NEAR(c.tip.dot(d.normalized()) - cam_tip.dot(d.normalized()), 0.0, 1e-12);
}

}  // namespace
}  // namespace rwmos::comp3d
