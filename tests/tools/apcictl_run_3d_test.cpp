// SPDX-License-Identifier: MIT
// `apcictl run` on Klartext programs with the 3D tool compensation: [TNC-3D]'s examples, tool
// and correction table deltas, the board's refusals.
#include <gtest/gtest.h>

#include "apcictl_run.h"

namespace {

using namespace apcictl_run_test;

// ---- Klartext programs: the 3D tool compensation (docs/3d-compensation.md; the board's module
// on bus 1310, docs/object-map.md section 6). The segment end points are the commanded tool
// tips (TCP); the expected ones come from rwmos_comp3d, and where [TNC-3D] says what the tool
// must do, that is checked directly.

using V3 = Eigen::Vector3d;

// The executed segment of block `block` (exactly one).
json segment_of_block(const json& doc, int block) {
    json found;
    int count = 0;
    for (const auto& s : doc.at("segments")) {
        if (s.at("block") != block) continue;
        found = s;
        ++count;
    }
    EXPECT_EQ(count, 1) << "block " << block << ": " << roles(doc);
    return found;
}

V3 end_of_block(const json& doc, int block) {
    const json s = segment_of_block(doc, block);
    if (s.is_null()) return V3::Zero();
    return point(s.at("end"));
}

V3 tcp(const V3& p, const V3& n, const V3& t, const c3::ToolDimensions& tool, const c3::Deltas& d,
       c3::ReferencePoint ref = c3::ReferencePoint::kTip) {
    c3::Settings s;
    s.tool = tool;
    s.deltas = d;
    s.reference = ref;
    const c3::Compensated c = c3::compensate(p, n, t, s);
    EXPECT_EQ(c.refusal, c3::Refusal::kNone);
    return c.tip;
}

void expect_point(const V3& got, const V3& want, double tol = 1e-9) {
    EXPECT_NEAR((got - want).norm(), 0.0, tol)
        << "got " << got.transpose() << ", want " << want.transpose();
}

// [TNC-3D], face milling, blocks 12 to 14, with the reground ball mill of the tool list.
TEST_F(ApcictlRun, Tnc3dFaceMillingExampleRunsToTheCompensatedTips) {
    const json doc = run_json(kExamples + "/3d_face_milling.h",
                              {"--tools", kExamples + "/tools/3d_tools.tools"});
    EXPECT_EQ(doc.at("errors"), json::array());
    const V3 p(36.0084, 6.177, -1.9209);
    const V3 n = V3(-0.4658107, 0, 0.8848844).normalized();
    const V3 t = V3(0, 0.6558846, 0.7548612).normalized();
    const c3::Deltas reground{0.0, -0.1, -0.1};
    // 12: no TCPM, the machine's tool axis (the head at B = 0: +Z).
    expect_point(end_of_block(doc, 12), tcp(p, n, V3(0, 0, 1), {3, 3}, reground));
    // 13: T and M128: the programmed orientation.
    expect_point(end_of_block(doc, 13), tcp(p, n, t, {3, 3}, reground));
    // 14: M128 without T: perpendicular to the contour.
    expect_point(end_of_block(doc, 14), tcp(p, n, n, {3, 3}, reground));
    EXPECT_EQ(roles(doc),
              "uncompensated/2 uncompensated/3 uncompensated/11 contour/12 contour/13 contour/14 "
              "uncompensated/15");
    // The reground ball (R 2.9) at block 13's tip has its centre 2.9 off the surface point
    // that the 6 mm ball at the programmed tip touched.
    const V3 s = p + 3.0 * t - 3.0 * n;
    expect_point(end_of_block(doc, 13) + 2.9 * t, s + 2.9 * n);
}

// [TNC-3D], peripheral milling: 11 L with the head's C and B, M128 and RL; 12 LN with N and T;
// 13 LN with T only at 12's point (R0): the reground end mill (R 6, DR -0.1).
TEST_F(ApcictlRun, Tnc3dPeripheralExampleRunsWithTheSideFromRlNAndTheLineBefore) {
    const json doc =
        run_json(kExamples + "/3d_peripheral.h", {"--tools", kExamples + "/tools/3d_tools.tools"});
    EXPECT_EQ(doc.at("errors"), json::array());
    const c3::Deltas reground{0.0, -0.1, 0.0};
    const V3 p11(48.4074, 102.4717, -7.1088);
    const V3 t11 = rwmos::geom::bc_head_tool_direction(-20.0115, -267.9784);
    const V3 n11 = t11.cross(V3(1, 0, 0)).normalized();  // RL: T x D, D along +X
    expect_point(end_of_block(doc, 11), tcp(p11, n11, t11, {6, 0}, reground));
    const V3 p12(60.6593, 102.4690, -7.1012);
    const V3 n12 = V3(0, 0.9397, 0.3420).normalized();
    const V3 t12 = V3(-0.0807, -0.3409, 0.9366).normalized();
    expect_point(end_of_block(doc, 12), tcp(p12, n12, t12, {6, 0}, reground));
    const V3 kept = (n12 - n12.dot(t12) * t12).normalized();
    expect_point(end_of_block(doc, 13), tcp(p12, kept, t12, {6, 0}, reground));
    // RL at block 11 and N at block 12 name the same side of the wall.
    EXPECT_GT(n11.dot(n12), 0.999);
}

// [TNC-3D], "Werkstückaufmaß erzeugen, CAM-Ausgabe Kugelmitte": the 6 mm ball with TOOL CALL
// DL DR DR2 +0.2, M107, REFPNT CNT-CNT stands 0.2 off the design surface along N.
TEST_F(ApcictlRun, Tnc3dAllowanceExampleStandsOffTheSurfaceByTheAllowance) {
    const json doc =
        run_json(kExamples + "/3d_allowance.h", {"--tools", kExamples + "/tools/3d_tools.tools"});
    EXPECT_EQ(doc.at("errors"), json::array());
    const V3 n = V3(0.5, 0, 0.8660254).normalized();
    for (const int block : {5, 6, 7, 8}) {
        const json s = segment_of_block(doc, block);
        const V3 ball_centre_programmed(1.5,
                                        block == 5   ? 0.0
                                        : block == 8 ? 40.0
                                                     : 20.0,
                                        2.5980762);
        const V3 t = block <= 6 ? n : V3(0, 0, 1);
        const V3 got = point(s.at("end"));
        expect_point(got, tcp(ball_centre_programmed, n, t, {3, 3}, {0.2, 0.2, 0.2},
                              c3::ReferencePoint::kCentre));
        // The physical 3 mm ball, its tip at the TCP: centre 3.2 from the surface point.
        const V3 surface = ball_centre_programmed - 3.0 * n;
        expect_point(got + 3.0 * t, surface + 3.2 * n);
    }
}

// [TNC-3D]: the deltas are summed "aus der Werkzeugverwaltung, dem Werkzeugaufruf und den
// Korrekturtabellen". The face milling example with the tool as designed (tool 3) and the
// regrinding in correction table row 1 (FUNCTION CORRDATA TCS #1) reaches the tips of the
// reground tool 1 of the tool table; the example runs with the command its header documents.
TEST_F(ApcictlRun, CorrectionTableRowActsAsTheToolTablesDeltas) {
    const std::string program = kExamples + "/3d_correction_table.h";
    const json doc = run_json(program, {"--tools", kExamples + "/tools/3d_tools.tools", "--corr",
                                        kExamples + "/tools/3d_corrections.corr"});
    EXPECT_EQ(doc.at("errors"), json::array());
    const V3 p(36.0084, 6.177, -1.9209);
    const V3 n = V3(-0.4658107, 0, 0.8848844).normalized();
    const V3 t = V3(0, 0.6558846, 0.7548612).normalized();
    const c3::Deltas reground{0.0, -0.1, -0.1};
    expect_point(end_of_block(doc, 12), tcp(p, n, V3(0, 0, 1), {3, 3}, reground));
    expect_point(end_of_block(doc, 13), tcp(p, n, t, {3, 3}, reground));
    expect_point(end_of_block(doc, 14), tcp(p, n, n, {3, 3}, reground));
    const json table = run_json(kExamples + "/3d_face_milling.h",
                                {"--tools", kExamples + "/tools/3d_tools.tools"});
    for (const int block : {12, 13, 14})
        EXPECT_EQ(end_of_block(doc, block), end_of_block(table, block)) << block;
    // The header's command.
    std::vector<std::string> args = test_support::documented_command(program, kSource);
    ASSERT_FALSE(args.empty());
    EXPECT_EQ(apcictl(args).exit_code, 0);
}

// A row selected in the middle of the program acts from its block on; RESET TCS leaves it.
TEST_F(ApcictlRun, CorrectionRowActsFromItsBlockUntilReset) {
    const std::string prog = write(
        "corr.h",
        "0 BEGIN PGM C MM\n1 TOOL CALL 3 Z\n2 L X+0 Y+0 Z+50 R0 F1000\n"
        "3 LN X+10 Y+0 Z+0 NX+0.6 NY+0 NZ+0.8 TX+0 TY+0 TZ+1 R0 M128\n"
        "4 FUNCTION CORRDATA TCS #1\n"
        "5 LN X+20 Y+0 Z+0 NX+0.6 NY+0 NZ+0.8 TX+0 TY+0 TZ+1\n"
        "6 FUNCTION CORRDATA RESET TCS\n"
        "7 LN X+30 Y+0 Z+0 NX+0.6 NY+0 NZ+0.8 TX+0 TY+0 TZ+1\n"
        "8 L Z+50 FMAX M129\n9 END PGM C MM\n");
    const json doc = run_json(prog, {"--tools", kExamples + "/tools/3d_tools.tools", "--corr",
                                     kExamples + "/tools/3d_corrections.corr"});
    EXPECT_EQ(doc.at("errors"), json::array());
    const V3 n(0.6, 0, 0.8);
    const V3 t(0, 0, 1);
    const c3::Deltas none{0.0, 0.0, 0.0};
    const c3::Deltas row1{0.0, -0.1, -0.1};
    expect_point(end_of_block(doc, 3), tcp(V3(10, 0, 0), n, t, {3, 3}, none));
    expect_point(end_of_block(doc, 5), tcp(V3(20, 0, 0), n, t, {3, 3}, row1));
    expect_point(end_of_block(doc, 7), tcp(V3(30, 0, 0), n, t, {3, 3}, none));
    // Row 1 moves the tip (the reground ball is 0.1 smaller), so the comparison means something.
    EXPECT_GT((tcp(V3(20, 0, 0), n, t, {3, 3}, row1) - V3(20, 0, 0)).norm(), 0.01);
}

TEST_F(ApcictlRun, CorrectionRowWithoutATableSaysThatNoneWasGiven) {
    const std::string prog =
        write("c.h", "0 BEGIN PGM C MM\n1 FUNCTION CORRDATA TCS #1\n2 END PGM C MM\n");
    const auto r = apcictl({"run", prog, "--json", path("c.json")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err,
                         ":2:26: FUNCTION CORRDATA TCS #1: the correction table does not define "
                         "row 1 (no --corr file given)"))
        << r.err;
    EXPECT_FALSE(exists(path("c.json")));
}

TEST_F(ApcictlRun, CorrectionRowWithAPositiveOversizeNeedsM107BeforeAnythingRuns) {
    const std::string prog = write(
        "c.h", "0 BEGIN PGM C MM\n1 TOOL CALL 3 Z\n2 FUNCTION CORRDATA TCS #2\n3 END PGM C MM\n");
    const auto r = apcictl({"run", prog, "--tools", kExamples + "/tools/3d_tools.tools", "--corr",
                            kExamples + "/tools/3d_corrections.corr", "--json", path("c.json")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, ":3:3: FUNCTION CORRDATA TCS #2 (tool 3) with a positive oversize"))
        << r.err;
    EXPECT_FALSE(exists(path("c.json")));
}

TEST_F(ApcictlRun, BadCorrectionTableNamesFileAndLine) {
    const std::string t = write("bad.corr", "corr[1].dr -0.1\ncorr[1].dx 1\n");
    const auto r = apcictl({"run", kExamples + "/3d_face_milling.h", "--corr", t});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, t + ":2:9: unknown correction field 'dx' (known: dl, dr, dr2)"))
        << r.err;
}

TEST_F(ApcictlRun, LnWhileTheRadiusCompensationRunsIsRefusedByTheBoardByName) {
    const std::string prog = write("mixed.h",
                                   "0 BEGIN PGM MIXED MM\n1 L X+0 Y+0 Z+0 R0 F500\n2 L X+10 RL\n"
                                   "3 LN X+20 Y+0 Z+0 NX+0 NY+1 NZ+0\n4 END PGM MIXED MM\n");
    const json doc = run_json(prog, {}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("block"), 3);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "RadiusCompensationRunning");
}

TEST_F(ApcictlRun, KlartextOversizeWithoutM107IsRefusedBeforeAnythingRuns) {
    const std::string prog = write(
        "over.h", "0 BEGIN PGM O MM\n1 TOOL CALL 3 Z DL+0.2 DR+0.2 DR2+0.2\n2 END PGM O MM\n");
    const auto r = apcictl(
        {"run", prog, "--tools", kExamples + "/tools/3d_tools.tools", "--json", path("o.json")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, ":2:3: TOOL CALL 3 with a positive oversize")) << r.err;
    EXPECT_TRUE(contains(r.err, "program M107 before the TOOL CALL")) << r.err;
    EXPECT_FALSE(exists(path("o.json")));
}

}  // namespace
