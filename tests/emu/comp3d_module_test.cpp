// SPDX-License-Identifier: MIT
// The 3D tool compensation module on a Board (bus 1310; docs/object-map.md section 6): the
// tool-loading rules (oversize and M107, the correction table in the sum), the arming of the
// LN vectors (normalisation), and LN profiles through the spooler, compensated as
// rwmos_comp3d computes (docs/3d-compensation.md), with every refusal changing nothing.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "motion_fixture.h"
#include "rwmos/comp3d/compensation.h"
#include "rwmos/comp3d_state.h"

namespace {

using namespace motion_test;
using rwmos::comp3d::Refusal;
namespace c3 = rwmos::comp3d;
using V = Eigen::Vector3d;

// [TNC-3D], face milling block 13: the design surface point and vectors of the examples.
const V kS(36.0084, 6.177, -1.9209);
const V kN = V(-0.4658107, 0.0, 0.8848844).normalized();
const V kT = V(0.0, 0.6558846, 0.7548612).normalized();

class Comp3dBoard : public MotionBoard {
  protected:
    Status set(std::int32_t idx, std::int32_t v, std::int32_t sub = 0) {
        return write_int(c3::kBus, c3::kDevSettings, idx, sub, v);
    }
    Status set_d(std::int32_t idx, std::int32_t sub, double v) {
        return write_double(c3::kBus, c3::kDevSettings, idx, sub, v);
    }
    std::int32_t get(std::int32_t idx) { return read_int(c3::kBus, c3::kDevSettings, idx, 0); }
    double get_d(std::int32_t idx, std::int32_t sub) {
        return read_double(c3::kBus, c3::kDevSettings, idx, sub);
    }
    void tool(std::int32_t t, double r, double r2, double dl = 0, double dr = 0, double dr2 = 0) {
        const double v[] = {r, r2, dl, dr, dr2};
        for (std::int32_t sub = c3::kSubR; sub <= c3::kSubDr2; ++sub) {
            ASSERT_EQ(write_double(c3::kBus, c3::kDevTools, t, sub, v[sub - 1]), Status::kOk);
        }
    }
    void correction(std::int32_t row, double dl, double dr, double dr2) {
        const double v[] = {dl, dr, dr2};
        for (std::int32_t sub = c3::kSubCorrDl; sub <= c3::kSubCorrDr2; ++sub) {
            ASSERT_EQ(write_double(c3::kBus, c3::kDevCorrections, row, sub, v[sub - 1]),
                      Status::kOk);
        }
    }
    void call(double dl, double dr, double dr2) {
        ASSERT_EQ(set_d(c3::kIdxCallDeltas, 0, dl), Status::kOk);
        ASSERT_EQ(set_d(c3::kIdxCallDeltas, 1, dr), Status::kOk);
        ASSERT_EQ(set_d(c3::kIdxCallDeltas, 2, dr2), Status::kOk);
    }
    Status arm(const V* n, const V* t) {
        std::int32_t bits = 0;
        if (n != nullptr) {
            for (int k = 0; k < 3; ++k)
                EXPECT_EQ(set_d(c3::kIdxSurfaceNormal, k, (*n)[k]), Status::kOk);
            bits |= c3::kArmNormal;
        }
        if (t != nullptr) {
            for (int k = 0; k < 3; ++k)
                EXPECT_EQ(set_d(c3::kIdxToolVector, k, (*t)[k]), Status::kOk);
            bits |= c3::kArmToolVector;
        }
        return set(c3::kIdxArm, bits);
    }
    static Profile to(const V& p, std::uint32_t tag = 1) { return line3(tag, p.x(), p.y(), p.z()); }
    V end_of_last_segment() {
        const std::vector<Segment> segs = segments();
        EXPECT_FALSE(segs.empty());
        if (segs.empty()) return V::Zero();
        const AxisVector& e = segs.back().end;
        return V(e[0], e[1], e[2]);
    }
    // The compensated tip rwmos_comp3d gives for these settings.
    static V expected(const V& p, const V& n, const V& t, c3::ToolDimensions d, const c3::Deltas& sum,
                      c3::ProgPath path = c3::ProgPath::kOff,
                      c3::ReferencePoint ref = c3::ReferencePoint::kTip) {
        c3::Settings s;
        s.tool = d;
        s.deltas = sum;
        s.prog_path = path;
        s.reference = ref;
        const c3::Compensated c = c3::compensate(p, n, t, s);
        EXPECT_EQ(c.refusal, Refusal::kNone);
        return c.tip;
    }
};

void expect_near(const V& got, const V& want, double tol = 1e-9) {
    EXPECT_NEAR((got - want).norm(), 0.0, tol)
        << "got " << got.transpose() << ", want " << want.transpose();
}

// ---- Tool loading ([TNC-3D]: oversize, M107) ----

TEST_F(Comp3dBoard, ToolWriteLoadsTheToolWithThePendingCallDeltas) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    call(0.0, 0.05, 0.05);
    EXPECT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    EXPECT_EQ(get(c3::kIdxTool), 1);
    EXPECT_NEAR(get_d(c3::kIdxDeltas, 1), -0.05, 1e-15);
    EXPECT_NEAR(get_d(c3::kIdxDeltas, 2), -0.05, 1e-15);
    // New pending deltas do not act before the next Tool write.
    call(0.0, -0.2, -0.2);
    EXPECT_NEAR(get_d(c3::kIdxDeltas, 1), -0.05, 1e-15);
    EXPECT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    EXPECT_NEAR(get_d(c3::kIdxDeltas, 1), -0.3, 1e-15);
}

TEST_F(Comp3dBoard, ToolWithPositiveOversizeIsRefusedWithoutM107) {
    tool(3, 3, 3);
    call(0.2, 0.2, 0.2);
    EXPECT_EQ(set(c3::kIdxTool, 3), Status::kWrongDeviceState);
    EXPECT_EQ(get(c3::kIdxTool), 0);  // unchanged
    EXPECT_EQ(get(c3::kIdxLastError), static_cast<std::int32_t>(Refusal::kPositiveOversize));
    EXPECT_EQ(get_d(c3::kIdxDeltas, 0), 0.0);
}

TEST_F(Comp3dBoard, M107AllowsAToolWithPositiveOversize) {
    tool(3, 3, 3);
    call(0.2, 0.2, 0.2);
    ASSERT_EQ(set(c3::kIdxAllowOversize, 1), Status::kOk);
    EXPECT_EQ(set(c3::kIdxTool, 3), Status::kOk);
    EXPECT_EQ(get(c3::kIdxLastError), 0);
}

TEST_F(Comp3dBoard, M108WhileAnOversizedToolIsLoadedIsRefused) {
    tool(3, 3, 3);
    call(0.0, 0.2, 0.0);
    ASSERT_EQ(set(c3::kIdxAllowOversize, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTool, 3), Status::kOk);
    EXPECT_EQ(set(c3::kIdxAllowOversize, 0), Status::kWrongDeviceState);
    EXPECT_EQ(get(c3::kIdxAllowOversize), 1);
    call(0, 0, 0);
    ASSERT_EQ(set(c3::kIdxTool, 0), Status::kOk);
    EXPECT_EQ(set(c3::kIdxAllowOversize, 0), Status::kOk);
}

TEST_F(Comp3dBoard, CorrectionTableRowJoinsTheSum) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    correction(7, -0.01, 0.02, 0.02);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxCorrectionRow, 7), Status::kOk);
    EXPECT_NEAR(get_d(c3::kIdxDeltas, 0), -0.01, 1e-15);
    EXPECT_NEAR(get_d(c3::kIdxDeltas, 1), -0.08, 1e-15);
    EXPECT_NEAR(get_d(c3::kIdxDeltas, 2), -0.08, 1e-15);
}

TEST_F(Comp3dBoard, CorrectionRowThatMakesAnOversizeIsRefusedWithoutM107) {
    tool(1, 3, 3);
    correction(2, 0.0, 0.1, 0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    EXPECT_EQ(set(c3::kIdxCorrectionRow, 2), Status::kWrongDeviceState);
    EXPECT_EQ(get(c3::kIdxCorrectionRow), 0);
    EXPECT_EQ(get(c3::kIdxLastError), static_cast<std::int32_t>(Refusal::kPositiveOversize));
}

TEST_F(Comp3dBoard, ToolThatCannotExistIsRefused) {
    tool(4, 3, 3.5);
    EXPECT_EQ(set(c3::kIdxTool, 4), Status::kWrongDeviceState);
    EXPECT_EQ(get(c3::kIdxLastError),
              static_cast<std::int32_t>(Refusal::kCornerRadiusExceedsRadius));
    tool(5, 3, 3, 0, -0.1, 0.0);  // reground on R alone: R2' > R'
    EXPECT_EQ(set(c3::kIdxTool, 5), Status::kWrongDeviceState);
    EXPECT_EQ(get(c3::kIdxLastError),
              static_cast<std::int32_t>(Refusal::kEffectiveCornerExceedsRadius));
    EXPECT_EQ(set(c3::kIdxLastError, 99), Status::kOk);
    EXPECT_EQ(get(c3::kIdxLastError), 0);  // a write clears
}

// ---- Arming the LN vectors ([TNC-3D]: normalised vectors) ----

TEST_F(Comp3dBoard, NonNormalisedVectorIsRefusedAtArming) {
    const V bad(0.2637581, 0.0078922, -0.8764339);  // [TNC-3D]'s syntax example, |N| = 0.9153
    EXPECT_EQ(arm(&bad, nullptr), Status::kInvalidValue);
    EXPECT_EQ(get(c3::kIdxArm), 0);
    EXPECT_EQ(get(c3::kIdxLastError), static_cast<std::int32_t>(Refusal::kVectorNotNormalised));
    const V t_bad(0, 0, 1.001);
    EXPECT_EQ(arm(&kN, &t_bad), Status::kInvalidValue);
    EXPECT_EQ(get(c3::kIdxArm), 0);
    EXPECT_EQ(arm(&kN, &kT), Status::kOk);
    EXPECT_EQ(get(c3::kIdxArm), 3);
}

// ---- LN profiles ----

// [TNC-3D] "Nachgeschliffenen Kugelfräser korrigieren, CAM-Ausgabe Werkzeugspitze".
TEST_F(Comp3dBoard, RegroundBallMillLnProfileRunsToTheCompensatedTip) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    const V cam_tip = kS + 3.0 * kN - 3.0 * kT;
    ASSERT_EQ(arm(&kN, &kT), Status::kOk);
    spool_ok(to(cam_tip));
    run();
    const V want = cam_tip - 0.1 * kN + 0.1 * kT;
    expect_near(end_of_last_segment(), want);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(get_d(c3::kIdxLastTip, k), want[k], 1e-12);
    EXPECT_EQ(get(c3::kIdxArm), 0);  // used up
}

// "... CAM-Ausgabe Kugelmitte" with REFPNT CNT-CNT: the same tip.
TEST_F(Comp3dBoard, RegroundBallMillCentreOutputRunsToTheSameTip) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxReference, 1), Status::kOk);
    ASSERT_EQ(arm(&kN, &kT), Status::kOk);
    spool_ok(to(kS + 3.0 * kN));
    run();
    expect_near(end_of_last_segment(), kS + 2.9 * kN - 2.9 * kT);
}

// "Werkstückaufmaß erzeugen": TOOL CALL DL DR DR2 +0.2 with M107.
TEST_F(Comp3dBoard, AllowanceLnProfileStandsOffByTheAllowance) {
    tool(3, 3, 3);
    call(0.2, 0.2, 0.2);
    ASSERT_EQ(set(c3::kIdxAllowOversize, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTool, 3), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    const V cam_tip = kS + 3.0 * kN - 3.0 * kT;
    ASSERT_EQ(arm(&kN, &kT), Status::kOk);
    spool_ok(to(cam_tip));
    run();
    expect_near(end_of_last_segment(), cam_tip + 0.2 * kN);
}

TEST_F(Comp3dBoard, ArmedVectorsAreUsedByOneProfileOnly) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    ASSERT_EQ(arm(&kN, nullptr), Status::kOk);
    spool_ok(to(V(1, 2, 3), 1));
    spool_ok(to(V(4, 5, 6), 2));
    run();
    const std::vector<Segment> segs = segments();
    ASSERT_EQ(segs.size(), 2U);
    EXPECT_NE(segs[0].end[0], 1.0);                                            // compensated
    EXPECT_EQ(V(segs[1].end[0], segs[1].end[1], segs[1].end[2]), V(4, 5, 6));  // plain line
}

TEST_F(Comp3dBoard, ArmingWrittenBetweenProfilesActsOnTheNextOne) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    spool_ok(to(V(1, 2, 3), 1));  // nothing armed: as programmed
    ASSERT_EQ(arm(&kN, nullptr), Status::kOk);
    spool_ok(to(V(4, 5, 6), 2));
    spool_ok(to(V(7, 8, 9), 3));
    run();
    const std::vector<Segment> segs = segments();
    ASSERT_EQ(segs.size(), 3U);
    EXPECT_EQ(V(segs[0].end[0], segs[0].end[1], segs[0].end[2]), V(1, 2, 3));
    EXPECT_NE(V(segs[1].end[0], segs[1].end[1], segs[1].end[2]), V(4, 5, 6));  // compensated
    EXPECT_EQ(V(segs[2].end[0], segs[2].end[1], segs[2].end[2]), V(7, 8, 9));
    EXPECT_EQ(get(c3::kIdxArm), 0);
    // The segment says what the board did: the compensated line is a contour element, the
    // lines as programmed are not.
    EXPECT_EQ(segs[0].role, SegmentRole::kUncompensated);
    EXPECT_EQ(segs[1].role, SegmentRole::kContour);
    EXPECT_EQ(segs[2].role, SegmentRole::kUncompensated);
}

TEST_F(Comp3dBoard, RapidWithArmedVectorsIsNotCompensatedAndUsesThemUp) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    ASSERT_EQ(arm(&kN, nullptr), Status::kOk);
    spool_ok(rapid(1, 5, 5));
    run();
    const std::vector<Segment> segs = segments();
    ASSERT_EQ(segs.size(), 1U);
    EXPECT_EQ(V(segs[0].end[0], segs[0].end[1], segs[0].end[2]), V(5, 5, 0));
    EXPECT_EQ(segs[0].role, SegmentRole::kRapid) << "not compensated: not marked";
    EXPECT_EQ(get(c3::kIdxArm), 0);
}

// An arc with armed vectors runs as programmed (only a G01 is compensated): its segment stays
// uncompensated, as the role the spooler gave it says.
TEST_F(Comp3dBoard, ArcWithArmedVectorsIsNotCompensatedAndStaysUncompensated) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    ASSERT_EQ(arm(&kN, nullptr), Status::kOk);
    spool_ok(arc(1, true, 0, 10, 0, 5));  // a half circle from the origin
    run();
    const std::vector<Segment> segs = segments();
    ASSERT_EQ(segs.size(), 1U);
    EXPECT_EQ(segs[0].kind, SegmentKind::kArc);
    EXPECT_EQ(V(segs[0].end[0], segs[0].end[1], segs[0].end[2]), V(0, 10, 0));
    EXPECT_EQ(segs[0].role, SegmentRole::kUncompensated) << "not compensated: not marked";
    EXPECT_EQ(get(c3::kIdxArm), 0);
}

// A compensated line spooled into an empty queue is its only move (the one under way next):
// it is marked too, and its segment is a contour element.
TEST_F(Comp3dBoard, ACompensatedLineAloneInTheQueueIsAContourElement) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    ASSERT_EQ(arm(&kN, nullptr), Status::kOk);
    spool_ok(to(V(1, 2, 3), 1));
    run();
    const std::vector<Segment> segs = segments();
    ASSERT_EQ(segs.size(), 1U);
    EXPECT_NE(V(segs[0].end[0], segs[0].end[1], segs[0].end[2]), V(1, 2, 3));  // compensated
    EXPECT_EQ(segs[0].role, SegmentRole::kContour);
}

// [TNC-3D], face milling: without M128 / FUNCTION TCPM the T vector is ignored, the machine's
// tool axis (the head's B, here tilted by a G00 of axis 4) applies.
TEST_F(Comp3dBoard, WithoutTcpmTheHeadsToolAxisAppliesAndTIsIgnored) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    Profile tilt;
    tilt.kind = ProfileKind::kRapid;
    tilt.axes = 0x10;
    tilt.target[4] = 30.0;
    spool_ok(tilt);
    const V head(std::sin(M_PI / 6), 0.0, std::cos(M_PI / 6));
    const V n = V(0.3, 0.1, 1.0).normalized();
    const V p(10, 20, -5);
    ASSERT_EQ(arm(&n, &kT), Status::kOk);
    spool_ok(to(p));
    run();
    expect_near(end_of_last_segment(), expected(p, n, head, {3, 3}, {0, -0.1, -0.1}));
}

// With TCPM and no T, the tool stands perpendicular to the contour (T = N).
TEST_F(Comp3dBoard, WithTcpmAndNoTTheToolStandsAlongN) {
    tool(2, 5, 1.5, 0.0, -0.2, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 2), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    const V p(1, 2, 3);
    ASSERT_EQ(arm(&kN, nullptr), Status::kOk);
    spool_ok(to(p));
    run();
    expect_near(end_of_last_segment(), expected(p, kN, kN, {5, 1.5}, {0, -0.2, -0.1}));
}

TEST_F(Comp3dBoard, ProgPathContourAppliesTheFullRadii) {
    tool(1, 3, 3, 0, -0.1, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxProgPath, 1), Status::kOk);
    ASSERT_EQ(arm(&kN, &kT), Status::kOk);
    spool_ok(to(kS));
    run();
    expect_near(end_of_last_segment(), kS + 2.9 * kN - 2.9 * kT);
}

// [TNC-3D], peripheral milling, the reground end mill with RL and LN without N.
TEST_F(Comp3dBoard, PeripheralLnWithoutNTakesTheSideFromRlAndTheMotion) {
    tool(2, 6, 0, 0, -0.1, 0);
    ASSERT_EQ(set(c3::kIdxTool, 2), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxSide, rwmos::tc::kSideLeft), Status::kOk);
    const V t(0, 0, 1);
    ASSERT_EQ(arm(nullptr, &t), Status::kOk);
    spool_ok(to(V(10, 0, 0)));  // motion along +X from the origin; RL: the wall is at -Y
    run();
    expect_near(end_of_last_segment(), V(10, -0.1, 0));
}

// [TNC-3D], peripheral variant 1: an L line with the rotary axes programmed, TCPM and RL: T from
// the head (B tilted by a G00 of axis 4), the side across the motion and T.
TEST_F(Comp3dBoard, PeripheralLLineWithRlTakesTFromTheHead) {
    tool(2, 6, 0, 0, -0.1, 0);
    ASSERT_EQ(set(c3::kIdxTool, 2), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxSide, rwmos::tc::kSideLeft), Status::kOk);
    Profile tilt;
    tilt.kind = ProfileKind::kRapid;
    tilt.axes = 0x10;
    tilt.target[4] = -20.0;
    spool_ok(tilt);
    ASSERT_EQ(set(c3::kIdxArm, c3::kArmLine), Status::kOk);
    spool_ok(to(V(0, 10, 0)));  // along +Y
    run();
    const V t(std::sin(-20.0 * M_PI / 180), 0.0, std::cos(-20.0 * M_PI / 180));
    const V n = t.cross(V(0, 1, 0)).normalized();  // RL: T x D
    expect_near(end_of_last_segment(), V(0, 10, 0) - 0.1 * n);
    EXPECT_NEAR(n.dot(t), 0.0, 1e-15);
}

// [TNC-3D], peripheral example: block 12 (N and T) then block 13 at the same point with T only
// and R0 in force: the side of block 12 is kept ("Kompensation möglich").
TEST_F(Comp3dBoard, PeripheralLnWithoutNAtTheSamePointKeepsThePreviousSide) {
    tool(2, 6, 0, 0, -0.1, 0);
    ASSERT_EQ(set(c3::kIdxTool, 2), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    const V n12 = V(0.0, 0.9397, 0.3420).normalized();
    const V t = V(-0.0807, -0.3409, 0.9366).normalized();
    const V p(60.6593, 102.4690, -7.1012);
    ASSERT_EQ(arm(&n12, &t), Status::kOk);
    spool_ok(to(p, 12));
    ASSERT_EQ(arm(nullptr, &t), Status::kOk);
    spool_ok(to(p, 13));
    run();
    const std::vector<Segment> segs = segments();
    ASSERT_GE(segs.size(), 1U);
    const V tip12 = expected(p, n12, t, {6, 0}, {0, -0.1, 0});
    const V kept = (n12 - n12.dot(t) * t).normalized();
    const V tip13 = expected(p, kept, t, {6, 0}, {0, -0.1, 0});
    expect_near(V(position()[0], position()[1], position()[2]), tip13);
    expect_near(tip13, tip12, 1e-4);  // the same side, 4-decimal vectors
}

TEST_F(Comp3dBoard, UncompensatedProfileEndsThePathAndItsSide) {
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    const V n(0, 1, 0);
    const V t(0, 0, 1);
    ASSERT_EQ(arm(&n, &t), Status::kOk);
    spool_ok(to(V(1, 0, 0)));
    spool_ok(to(V(2, 0, 0)));  // plain line
    ASSERT_EQ(arm(nullptr, &t), Status::kOk);
    const MotionResult r = board.spool(to(V(2, 0, 0)));
    EXPECT_EQ(r.status, Status::kWrongDeviceState);
    EXPECT_EQ(get(c3::kIdxLastError), static_cast<std::int32_t>(Refusal::kNoCompensationSide));
}

TEST_F(Comp3dBoard, PeripheralLnWithoutNAndWithoutSideIsRefused) {
    const V t(0, 0, 1);
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    ASSERT_EQ(arm(nullptr, &t), Status::kOk);
    const MotionResult r = board.spool(to(V(10, 0, 0), 7));
    EXPECT_EQ(r.status, Status::kWrongDeviceState);
    EXPECT_EQ(r.tag, 7U);
    EXPECT_EQ(r.message, c3::refusal_message(Refusal::kNoCompensationSide));
    EXPECT_EQ(get(c3::kIdxLastError), static_cast<std::int32_t>(Refusal::kNoCompensationSide));
    EXPECT_EQ(get(c3::kIdxArm), 2);  // still armed: nothing changed
    EXPECT_EQ(board.motion_status().fill, 0U);
}

TEST_F(Comp3dBoard, NormalAgainstTheToolIsRefused) {
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    const V down(0, 0, -1);
    const V up(0, 0, 1);
    ASSERT_EQ(arm(&down, &up), Status::kOk);
    const MotionResult r = board.spool(to(V(1, 1, 1)));
    EXPECT_EQ(r.status, Status::kInvalidValue);
    EXPECT_EQ(get(c3::kIdxLastError), static_cast<std::int32_t>(Refusal::kNormalAgainstTool));
    EXPECT_EQ(board.motion_status().fill, 0U);
}

TEST_F(Comp3dBoard, ToolTableEditedIntoAnOversizeIsRefusedAtTheProfile) {
    tool(1, 3, 3);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    tool(1, 3, 3, 0, 0.1, 0.1);  // the loaded tool's table row grows
    ASSERT_EQ(arm(&kN, nullptr), Status::kOk);
    const MotionResult r = board.spool(to(V(1, 1, 1)));
    EXPECT_EQ(r.status, Status::kWrongDeviceState);
    EXPECT_EQ(get(c3::kIdxLastError), static_cast<std::int32_t>(Refusal::kPositiveOversize));
}

TEST_F(Comp3dBoard, LnWhileTcRadiusCompensationRunsIsRefused) {
    setup_group(2.0);
    activate();
    ASSERT_EQ(arm(&kN, nullptr), Status::kOk);
    const MotionResult r = board.spool(to(V(1, 1, 1)));
    EXPECT_EQ(r.status, Status::kWrongDeviceState);
    EXPECT_EQ(get(c3::kIdxLastError),
              static_cast<std::int32_t>(Refusal::kRadiusCompensationRunning));
}

TEST_F(Comp3dBoard, CompensationActsOnTheGeometryAxesOfTheTcModule) {
    using namespace rwmos::tc;
    ASSERT_EQ(write_int(kBus, kDevInit, kIdxAxisNr, kSubX, 3), Status::kOk);  // X on axis 3
    tool(1, 3, 3, 0, -0.1, -0.1);
    ASSERT_EQ(set(c3::kIdxTool, 1), Status::kOk);
    ASSERT_EQ(set(c3::kIdxTcpm, 1), Status::kOk);
    ASSERT_EQ(arm(&kN, &kT), Status::kOk);
    Profile p;
    p.kind = ProfileKind::kLine;
    p.feed = 600;
    p.axes = 0x0E;  // axes 1, 2, 3: Y, Z, X
    p.target[3] = 1.0;
    p.target[1] = 2.0;
    p.target[2] = 3.0;
    spool_ok(p);
    run();
    const V want = V(1, 2, 3) - 0.1 * kN + 0.1 * kT;
    const AxisVector e = position();
    EXPECT_NEAR(e[3], want.x(), 1e-9);
    EXPECT_NEAR(e[1], want.y(), 1e-9);
    EXPECT_NEAR(e[2], want.z(), 1e-9);
    EXPECT_EQ(e[0], 0.0);
}

TEST_F(Comp3dBoard, BusySpoolerLeavesTheVectorsArmed) {
    std::uint32_t tag = 1;
    while (board.spool(line(tag, tag % 2, 0)).ok()) ++tag;  // fill the spooler, clock stopped
    ASSERT_EQ(arm(&kN, nullptr), Status::kOk);
    const MotionResult r = board.spool(to(V(1, 1, 1)));
    EXPECT_EQ(r.status, Status::kBusy);
    EXPECT_EQ(get(c3::kIdxArm), 1);
}

}  // namespace
