// SPDX-License-Identifier: MIT
// The rules of the OTC module (bus 1330), one test per rule, named after it ([ISG-OTC], ISG
// FCT-C20; docs/otc.md and docs/object-map.md section 5). Every refusal names its error in
// LastError and changes nothing else.
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "emu_test_util.h"
#include "otc_fixture.h"

namespace otc_test {
namespace {

constexpr double kEps = 1e-9;

// ---- Selection

// [ISG-OTC] section 1: "Wird ein anderer Werkzeugtyp verwendet, so wird die Fehlermeldung
// P-ERR-21391 ausgegeben."
TEST_F(OtcBoard, ToolTypeMustBeGrindingElsePErr21391AndOtcStaysOff) {
    for (std::int32_t type : {0, 1, 3}) {
        grinding_tool(type);
        const auto before = emu_test::snapshot(board);
        EXPECT_EQ(otc_on(), Status::kWrongDeviceState) << type;
        EXPECT_EQ(last_error(), static_cast<std::int32_t>(otc::Error::kToolNotGrinding));
        EXPECT_FALSE(otc_active());
        EXPECT_TRUE(emu_test::unchanged(before, board));
    }
    grinding_tool(2);
    EXPECT_EQ(otc_on(), Status::kOk);
    EXPECT_TRUE(otc_active());
}

// [ISG-OTC] section 2.6 "Hinweis": data not set is 0, so a tool without typ is not a grinding tool.
TEST_F(OtcBoard, AToolWithoutDataIsNoGrindingTool) {
    EXPECT_EQ(otc_on(), Status::kWrongDeviceState);
    EXPECT_EQ(last_error(), 21391);
}

TEST_F(OtcBoard, LastErrorIsClearedByWritingIt) {
    EXPECT_EQ(otc_on(), Status::kWrongDeviceState);
    ASSERT_EQ(otc_int(otc::kDevChannel, otc::kIdxLastError, 0, 0), Status::kOk);
    EXPECT_EQ(last_error(), 0);
}

TEST_F(OtcBoard, OnAndOffWaitForTheQueueToEmpty) {
    grinding_tool();
    spool_ok(line(1, 10.0, 0.0));
    EXPECT_EQ(otc_on(), Status::kBusy);
    EXPECT_FALSE(otc_active());
    run();
    EXPECT_EQ(otc_on(), Status::kOk);
    spool_ok(line(2, 20.0, 0.0));
    EXPECT_EQ(otc_off(), Status::kBusy);
    EXPECT_TRUE(otc_active());
    run();
    EXPECT_EQ(otc_off(), Status::kOk);
}

TEST_F(OtcBoard, SwitchingToTheStateInForceIsANoOp) {
    grinding_tool();
    EXPECT_EQ(otc_off(), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    EXPECT_EQ(otc_on(), Status::kOk);
    EXPECT_TRUE(otc_active());
}

// [ISG-OTC] section 2.1: "Die Parametrierung kann vorab oder zusammen mit #OTC ON erfolgen."
TEST_F(OtcBoard, TypeModeAccWeightAndKinematicsAreNotChangedWhileOn) {
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);
    const auto before = emu_test::snapshot(board);
    EXPECT_EQ(set_type(otc::ProcessingType::kRadius), Status::kWrongDeviceState);
    EXPECT_EQ(last_error(), static_cast<std::int32_t>(otc::Error::kChangeWhileActive));
    EXPECT_EQ(set_mode(otc::Mode::kCont), Status::kWrongDeviceState);
    EXPECT_EQ(otc_int(otc::kDevChannel, otc::kIdxAccWeight, 0, 50), Status::kWrongDeviceState);
    EXPECT_EQ(otc_int(otc::kDevChannel, otc::kIdxKinematics, 0, 4), Status::kWrongDeviceState);
    EXPECT_EQ(otc_int(otc::kDevChannel, otc::kIdxToolAxisB, 0, 5), Status::kWrongDeviceState);
    EXPECT_TRUE(emu_test::unchanged(before, board));
    // Writing the value in force is fine.
    EXPECT_EQ(set_type(otc::ProcessingType::kLength), Status::kOk);
}

TEST_F(OtcBoard, TheToolIsNotChangedWhileOn) {
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);
    const auto before = emu_test::snapshot(board);
    EXPECT_EQ(otc_int(otc::kDevTool, otc::kIdxToolNumber, 0, 2), Status::kWrongDeviceState);
    EXPECT_EQ(last_error(), static_cast<std::int32_t>(otc::Error::kToolChangeWhileActive));
    EXPECT_EQ(otc_int(otc::kDevTool, otc::kIdxToolType, 0, 0), Status::kWrongDeviceState);
    EXPECT_EQ(otc_double(otc::kDevTool, otc::kIdxToolMaxInfeed, 0, 5.0), Status::kWrongDeviceState);
    EXPECT_EQ(otc_double(otc::kDevTool, otc::kIdxToolTiltAngle, 0, 5.0), Status::kWrongDeviceState);
    EXPECT_TRUE(emu_test::unchanged(before, board));
}

TEST_F(OtcBoard, TrafoNeedsAKinematics) {
    EXPECT_EQ(otc_int(otc::kDevChannel, otc::kIdxTrafo, 0, 1), Status::kWrongDeviceState);
    ASSERT_EQ(otc_int(otc::kDevChannel, otc::kIdxKinematics, 0, 4), Status::kOk);
    EXPECT_EQ(otc_int(otc::kDevChannel, otc::kIdxTrafo, 0, 1), Status::kOk);
}

// ---- Deselection

// [ISG-OTC] section 2.2 "Hinweis": "Bei der Abwahl muss zwingend die Sequenz G40 vor #OTC OFF
// eingehalten werden."
TEST_F(OtcBoard, G40MustComeBeforeOtcOff) {
    setup_group(kGrindingDiscRadius, /*left=*/true);
    grinding_tool();
    ASSERT_EQ(set_type(otc::ProcessingType::kRadius), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    activate(1);  // G41
    spool_ok(line(60, 50.0, 0.0));
    spool_ok(line(70, 100.0, 0.0));
    run();
    const auto before = emu_test::snapshot(board);
    EXPECT_EQ(otc_off(), Status::kWrongDeviceState);
    EXPECT_EQ(last_error(), static_cast<std::int32_t>(otc::Error::kOffBeforeG40));
    EXPECT_TRUE(otc_active());
    EXPECT_TRUE(emu_test::unchanged(before, board));
    ASSERT_EQ(deactivate(1), Status::kOk);  // G40
    run();
    EXPECT_EQ(otc_off(), Status::kOk);
}

// The rule belongs to RADIUS ([ISG-OTC] section 2.2); other types may end with TRC on.
TEST_F(OtcBoard, G40RuleBindsOnlyRadius) {
    setup_group(kGrindingDiscRadius);
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);  // LENGTH
    activate(1);
    EXPECT_EQ(otc_off(), Status::kOk);
}

// ---- Wear accrual

// [ISG-OTC] section 2: "Eilgangssätze sind verschleißfrei!"
TEST_F(OtcBoard, RapidMovesAreWearFree) {
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(rapid(1, 1000.0, 0.0));
    run();
    EXPECT_EQ(offset()[2], 0.0);
    run_and_off();
    EXPECT_EQ(wear(2), 0.0);
}

// [ISG-OTC] section 2: "Eilgangssätze sind verschleißfrei!", also a G00 on the compensated path
// (a traverse): under G41, RADIUS CONT, the G01 contour N50 (100 mm) wears 1 mm, the traverse
// N40 (450 mm) and its transition nothing.
TEST_F(OtcBoard, ATraverseUnderRadiusCompensationIsWearFree) {
    setup_group(kGrindingDiscRadius, /*left=*/true);
    ASSERT_EQ(write_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, 1, rwmos::tc::kSubSelectionMode,
                        139),
              Status::kOk);  // G139, as NC programs run: the first profile is the approach
    grinding_tool();
    ASSERT_EQ(set_type(otc::ProcessingType::kRadius), Status::kOk);
    ASSERT_EQ(set_mode(otc::Mode::kCont), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    activate(1);
    spool_ok(line(30, 50.0, 0.0, 10000.0));  // the approach
    Profile g0 = line(40, 500.0, 0.0, 0.0);
    g0.kind = ProfileKind::kTraverse;
    spool_ok(g0);
    spool_ok(line(50, 600.0, 0.0, 10000.0));
    ASSERT_EQ(deactivate(1), Status::kOk);
    spool_ok(line(60, 650.0, 0.0, 10000.0));  // the departure
    run_and_off();
    EXPECT_NEAR(wear_radius(), 100.0 * kGrindingWearConst * 1e-7, kEps);
    EXPECT_NEAR(wear_radius_cont(), 1.0, kEps);
}

// The same for every processing type (the board's G237: the first G01 is a contour element):
// only the two G01, 50 and 100 mm, wear.
TEST(OtcWearByRole, ATraverseIsWearFreeForEveryType) {
    for (auto type : {otc::ProcessingType::kRadius, otc::ProcessingType::kLength,
                      otc::ProcessingType::kToolDir, otc::ProcessingType::kSurfNormDir}) {
        OtcRig r;
        r.setup_group(5.0, /*left=*/true);
        r.grinding_tool();
        ASSERT_EQ(r.set_type(type), Status::kOk);
        ASSERT_EQ(r.set_mode(otc::Mode::kCont), Status::kOk);
        ASSERT_EQ(r.otc_on(), Status::kOk);
        r.activate(1);
        r.spool_ok(line(1, 50.0, 0.0, 10000.0));
        Profile g0 = line(2, 500.0, 0.0, 0.0);
        g0.kind = ProfileKind::kTraverse;
        r.spool_ok(g0);
        r.spool_ok(line(3, 600.0, 0.0, 10000.0));
        ASSERT_EQ(r.deactivate(1), Status::kOk);
        r.run();
        EXPECT_NEAR(r.board.state().otc_engine.continuous_wear(), 150.0 * kGrindingWearConst * 1e-7,
                    kEps)
            << otc::processing_type_name(type);
    }
}

// [ISG-OTC] section 2.2 "Hinweis": the approach after G41/G42 and the move after G40 are
// wear-free; only the compensated contour (with its transitions) wears the radius.
TEST_F(OtcBoard, TrcApproachAndDepartureAreWearFree) {
    setup_group(kGrindingDiscRadius, /*left=*/true);
    grinding_tool();
    ASSERT_EQ(board.state().tc.group(1).tool().radius, kGrindingDiscRadius);  // tool 0, by setup_group
    ASSERT_EQ(set_type(otc::ProcessingType::kRadius), Status::kOk);
    ASSERT_EQ(set_mode(otc::Mode::kCont), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    activate(1);  // N60 G41 G01 X50 (approach)
    spool_ok(line(60, 50.0, 0.0, 10000.0));
    spool_ok(line(70, 1000.0, 0.0, 10000.0));  // N70 X1000
    ASSERT_EQ(deactivate(1), Status::kOk);     // N80 G40 X50 (departure)
    spool_ok(line(80, 50.0, 0.0, 10000.0));
    run();
    double contour = 0.0, other = 0.0;
    for (const Segment& s : segments()) {
        const double len = std::hypot(s.end[0] - s.start[0], s.end[1] - s.start[1]);
        if (s.role == SegmentRole::kContour || s.role == SegmentRole::kTransition)
            contour += len;
        else
            other += len;
    }
    EXPECT_GT(other, 900.0);  // the return run N80 and the approach/departure
    run_and_off();
    EXPECT_NEAR(wear_radius_cont(), contour * kGrindingWearConst * 1e-7, kEps);
    EXPECT_NEAR(wear_radius(), wear_radius_cont(), kEps);
}

// [ISG-OTC] section 2.2: "In der Betriebsart Radiuskompensation wird der Verschleiß nur bei
// aktiver Werkzeugradiuskompensation (WRK) berücksichtigt."
TEST_F(OtcBoard, RadiusWearOnlyWithRadiusCompensation) {
    grinding_tool();
    ASSERT_EQ(set_type(otc::ProcessingType::kRadius), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 1000.0, 0.0, 10000.0));
    run();
    EXPECT_EQ(norm(offset()), 0.0);
    run_and_off();
    EXPECT_EQ(wear_radius(), 0.0);
}

// [ISG-OTC] section 2.2 "Hinweis" under G139, the NC programs' selection method: the approach
// (the G41 block's move) and the departure (the G40 block's move, the profile after STATUS = 0)
// are wear-free in every processing type; the contour and, where the type wears without radius
// compensation, the move after the departure wear. G41 G1 X100 (104.4 mm), G1 X200 (100 mm),
// G40 G1 X300 (104.4 mm), G1 X400 (100 mm).
TEST(OtcWearByRole, UnderG139TheG41AndG40BlocksMovesAreWearFree) {
    constexpr double kRatio = kGrindingWearConst * 1e-7;
    for (auto type : {otc::ProcessingType::kRadius, otc::ProcessingType::kLength,
                      otc::ProcessingType::kToolDir, otc::ProcessingType::kSurfNormDir}) {
        OtcRig r;
        r.setup_group(kGrindingDiscRadius, /*left=*/true);
        ASSERT_EQ(r.write_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, 1,
                              rwmos::tc::kSubSelectionMode, 139),
                  Status::kOk);
        r.grinding_tool();
        ASSERT_EQ(r.set_type(type), Status::kOk);
        ASSERT_EQ(r.set_mode(otc::Mode::kCont), Status::kOk);
        ASSERT_EQ(r.otc_on(), Status::kOk);
        r.activate(1);
        r.spool_ok(line(30, 100.0, 0.0, 10000.0));
        r.spool_ok(line(40, 200.0, 0.0, 10000.0));
        ASSERT_EQ(r.deactivate(1), Status::kOk);
        r.spool_ok(line(50, 300.0, 0.0, 10000.0));
        r.spool_ok(line(60, 400.0, 0.0, 10000.0));
        r.run();
        const double expected = type == otc::ProcessingType::kRadius ? 100.0 : 200.0;
        EXPECT_NEAR(r.board.state().otc_engine.continuous_wear(), expected * kRatio, kEps)
            << otc::processing_type_name(type);
    }
}

// [ISG-OTC] section 2: "Eilgangssätze sind verschleißfrei!"; section 2.2 "Hinweis": the approach
// after G41/G42 and the move after G40 are wear-free, and RADIUS wears only with radius
// compensation (docs/otc.md, "Wear-free moves"). One move of every role, in every processing
// type and in both modes with continuous wear; the wear each move adds, taken as it ends,
// against its path length worked out by hand.
TEST(OtcWearByRole, RapidApproachAndDepartureAreWearFreeAndRadiusWearsOnlyTheContour) {
    constexpr double kRatio = kGrindingWearConst * 1e-7;  // wear per unit of path
    // G00 X0 Y-20 / G01 Y0 / G41 (tool radius 5, G26) G01 X50 / X50 Y-50 / G40.
    struct Expected {
        SegmentRole role;
        double length;
    };
    const Expected moves[] = {
        {SegmentRole::kRapid, 20.0},                             // (0,0) to (0,-20)
        {SegmentRole::kUncompensated, 20.0},                     // back to (0,0)
        {SegmentRole::kApproach, 5.0},                           // to (0,5), left of +X
        {SegmentRole::kContour, 50.0},                           // (0,5) to (50,5)
        {SegmentRole::kTransition, 5.0 * std::numbers::pi / 2},  // quarter arc about (50,0)
        {SegmentRole::kContour, 50.0},                           // (55,0) to (55,-50)
        {SegmentRole::kDeparture, 5.0},                          // to the programmed end (50,-50)
    };
    for (auto type : {otc::ProcessingType::kRadius, otc::ProcessingType::kLength,
                      otc::ProcessingType::kToolDir, otc::ProcessingType::kSurfNormDir}) {
        for (auto mode : {otc::Mode::kCont, otc::Mode::kAuto}) {
            const std::string label = std::string(otc::processing_type_name(type)) + " " +
                                      std::string(otc::mode_name(mode));
            OtcRig r;
            r.setup_group(5.0, /*left=*/true);
            r.grinding_tool();
            ASSERT_EQ(r.set_type(type), Status::kOk);
            ASSERT_EQ(r.set_mode(mode), Status::kOk);
            ASSERT_EQ(r.otc_on(), Status::kOk);
            r.spool_ok(rapid(1, 0.0, -20.0));
            r.spool_ok(line(2, 0.0, 0.0, 10000.0));
            r.activate(1);
            r.spool_ok(line(3, 50.0, 0.0, 10000.0));
            r.spool_ok(line(4, 50.0, -50.0, 10000.0));
            ASSERT_EQ(r.deactivate(1), Status::kOk);
            const auto& engine = r.board.state().otc_engine;
            std::vector<Segment> done;
            std::vector<double> wear;  // the wear each move added
            double before = engine.continuous_wear();
            while (r.board.state().motion.executor().fill() > 0) {
                r.board.step(1);
                const auto ended = r.segments();
                ASSERT_LE(ended.size(), 1u) << label << ": one move ends per cycle";
                if (ended.empty()) continue;
                done.push_back(ended[0]);
                wear.push_back(engine.continuous_wear() - before);
                before = engine.continuous_wear();
            }
            ASSERT_EQ(done.size(), std::size(moves)) << label;
            for (std::size_t i = 0; i < done.size(); ++i) {
                ASSERT_EQ(done[i].role, moves[i].role) << label << " move " << i;
                const bool contour = moves[i].role == SegmentRole::kContour ||
                                     moves[i].role == SegmentRole::kTransition;
                const bool wears = contour || (moves[i].role == SegmentRole::kUncompensated &&
                                               type != otc::ProcessingType::kRadius);
                EXPECT_NEAR(wear[i], wears ? kRatio * moves[i].length : 0.0, kEps)
                    << label << " move " << i << " ("
                    << rwmos::motion::segment_role_name(moves[i].role) << ")";
            }
        }
    }
}

// [ISG-OTC] section 2.1 WEAR_CONST=..: "wirkt modal" instead of the tool's; WEAR_CONST_TOOL
// switches back.
TEST_F(OtcBoard, WearConstOverridesTheToolsModallyAndWearConstToolSwitchesBack) {
    grinding_tool();
    ASSERT_EQ(otc_double(otc::kDevChannel, otc::kIdxWearConst, 0, 50000.0), Status::kOk);
    EXPECT_EQ(otc_read_double(otc::kDevChannel, otc::kIdxEffectiveWearConst), 50000.0);
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 1000.0, 0.0, 10000.0));
    spool_ok(line(2, 0.0, 0.0, 10000.0));  // still the programmed constant: modal
    run();
    EXPECT_NEAR(offset()[2], -10.0, kEps);
    ASSERT_EQ(otc_int(otc::kDevChannel, otc::kIdxWearConstSource, 0, 0),
              Status::kOk);  // WEAR_CONST_TOOL
    EXPECT_EQ(otc_read_double(otc::kDevChannel, otc::kIdxEffectiveWearConst), kGrindingWearConst);
    spool_ok(line(3, 1000.0, 0.0, 10000.0));
    run_and_off();
    EXPECT_NEAR(wear(2), 20.0, kEps);
}

// [ISG-OTC] section 2.8: V.G.WZ_AKT.WEAR_CONST can be written in the program.
TEST_F(OtcBoard, ToolWearConstIsWritableWhileOnAndActsFromTheNextMove) {
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 500.0, 0.0, 10000.0));
    run();
    ASSERT_EQ(otc_double(otc::kDevTool, otc::kIdxToolWearConst, 0, 0.0), Status::kOk);
    spool_ok(line(2, 1000.0, 0.0, 10000.0));
    run_and_off();
    EXPECT_NEAR(wear(2), 5.0, kEps);
}

// docs/otc.md section 6: where the folded length acts on its axis now, the fold passes into the
// tool length without a motion. Under LengthMode 0 (the board's own) that is while the group
// compensates: #OTC OFF with a contour element held back folds N1's 1 mm into WkzLen and the
// nominal path at once, and Z never rises again (the held N2 and N3 run with the shorter tool;
// the offset does not ramp back up). Only the departure then takes the length out.
TEST_F(OtcBoard, LengthFoldWhileTheGroupCompensatesUnderLengthModeZeroNeverLiftsZ) {
    setup_group(5.0, /*left=*/true);
    ASSERT_EQ(write_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, 1, rwmos::tc::kSubWkzIndex, kTool),
              Status::kOk);
    ASSERT_EQ(read_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, 1, rwmos::tc::kSubLengthMode),
              rwmos::tc::kLengthWhileCompensating);
    grinding_tool();
    ASSERT_EQ(set_mode(otc::Mode::kCont), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    activate(1);
    spool_ok(line(1, 100.0, 0.0, 10000.0));
    spool_ok(line(2, 200.0, 0.0, 10000.0));
    run();
    ASSERT_TRUE(prof_marked(1));                       // N2 held: the group compensates
    ASSERT_NEAR(position()[2], kGrindingDiscLength - 1.0, kEps);  // N1's 100 mm: 1 mm
    ASSERT_EQ(otc_off(), Status::kOk);
    EXPECT_NEAR(wear(2), 1.0, kEps);
    for (const auto& g : board.state().tc.groups)
        EXPECT_NEAR(g.tools[kTool].length, kGrindingDiscLength - 1.0, kEps);
    spool_ok(line(3, 400.0, 0.0, 10000.0));
    ASSERT_EQ(deactivate(1), Status::kOk);
    double previous = position()[2];
    int cycles = 0;
    bool departing = false;
    while (board.state().motion.executor().fill() > 0 ||
           !board.state().otc_engine.ramps_settled()) {
        board.step(1);
        ++cycles;
        const double z = position()[2];
        if (position()[0] >= 400.0) departing = true;  // the departure: the length goes out
        if (!departing) {
            EXPECT_LE(z, previous + 1e-12) << "cycle " << cycles;
            EXPECT_NEAR(z, kGrindingDiscLength - 1.0, kEps) << "cycle " << cycles;
        }
        previous = z;
        ASSERT_LT(cycles, 1000000);
    }
    EXPECT_TRUE(departing);
}

// Group 1 with the grinding tool, its length on every profile (LengthMode 1, as NC programs
// run), OTC on in LENGTH CONT.
struct LengthAlwaysBoard : OtcBoard {
    void length_always_on() {
        setup_group(kGrindingDiscRadius, /*left=*/true);
        ASSERT_EQ(write_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, 1, rwmos::tc::kSubWkzIndex,
                            kTool),
                  Status::kOk);
        ASSERT_EQ(write_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, 1, rwmos::tc::kSubLengthMode,
                            rwmos::tc::kLengthAlways),
                  Status::kOk);
        grinding_tool();
        ASSERT_EQ(set_mode(otc::Mode::kCont), Status::kOk);
        ASSERT_EQ(otc_on(), Status::kOk);
    }
};

// [ISG-OTC] section 2.1: the continuous wear is the wear constant times the path travelled; the
// tool length coming onto the axis (the first move with LengthMode 1 carries WkzLen's 50 mm on
// Z) is no path: G1 X200 wears 2 mm, not 2 x sqrt(200^2 + 50^2) / 200. After a LENGTH fold (the
// nominal path takes the shorter tool without a motion) the next G1 X400 wears its 200 mm too.
TEST_F(LengthAlwaysBoard, TheToolLengthComingOnIsNoGroundPath) {
    length_always_on();
    spool_ok(line(1, 200.0, 0.0, 10000.0));
    run();
    EXPECT_EQ(position()[2], kGrindingDiscLength - 2.0);  // the length on Z, worn by 2 mm
    ASSERT_EQ(otc_off(), Status::kOk);
    EXPECT_NEAR(wear(2), 2.0, kEps);
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(2, 400.0, 0.0, 10000.0));
    run_and_off();
    EXPECT_NEAR(wear(2), 4.0, kEps);
    EXPECT_NEAR(position()[2], kGrindingDiscLength - 4.0, kEps);
}

// The same on an arc: a quarter circle of radius 100 (counter-clockwise from (0, 0) about
// (0, 100)) that takes the length onto Z as it runs wears its arc length, 100 pi / 2 mm, not that
// of the helix.
TEST_F(LengthAlwaysBoard, AnArcThatTakesTheToolLengthWearsItsArcLength) {
    length_always_on();
    spool_ok(arc(1, true, 100.0, 100.0, 0.0, 100.0, 10000.0));
    run_and_off();
    EXPECT_NEAR(wear(2), 100.0 * std::numbers::pi / 2.0 * kGrindingWearConst * 1e-7, kEps);
    EXPECT_NEAR(position()[2], kGrindingDiscLength - 100.0 * std::numbers::pi / 2.0 * 1e-2, kEps);
}

// [ISG-OTC] section 2.1, WEAR_CONST "wirkt modal": a change acts from the next profile spooled,
// not on the moves spooled before it that have not run yet. X0..X100 at the tool's 100000 and
// X100..X200 at 200000 (0.1 um/m): 1 + 2 mm, whichever object changes the constant; Z stands 1
// mm down at X100.
TEST(OtcWearConst, AChangeActsFromTheNextProfileNotOnTheQueuedOnes) {
    struct Change {
        const char* what;
        std::int32_t dev, index;
        bool programmed;  // WearConst (WEAR_CONST=..) rather than the tool's constant
    };
    const Change changes[] = {{"WEAR_CONST=", otc::kDevChannel, otc::kIdxWearConst, true},
                              {"V.G.WZ_AKT.WEAR_CONST", otc::kDevTool, otc::kIdxToolWearConst,
                               false}};
    for (const Change& c : changes) {
        OtcRig r;
        r.grinding_tool();
        ASSERT_EQ(r.otc_on(), Status::kOk);
        r.spool_ok(line(1, 100.0, 0.0, 10000.0));
        ASSERT_EQ(r.otc_double(c.dev, c.index, 0, 200000.0), Status::kOk);  // N1 not run yet
        r.spool_ok(line(2, 200.0, 0.0, 10000.0));
        bool at_100 = false;
        while (r.board.state().motion.executor().fill() > 0) {
            r.board.step(1);
            if (r.nominal()[0] == 100.0 && !at_100) {
                at_100 = true;
                EXPECT_NEAR(r.offset()[2], -1.0, kEps) << c.what;
            }
        }
        EXPECT_TRUE(at_100) << c.what;
        ASSERT_EQ(r.otc_off(), Status::kOk);
        EXPECT_NEAR(r.wear(2), 3.0, kEps) << c.what;
    }
}

// WEAR_CONST_TOOL (WearConstSource 0) waits for its place as well: N1 at the programmed 300000,
// N2 at the tool's 100000.
TEST_F(OtcBoard, WearConstToolActsFromTheNextProfile) {
    grinding_tool();
    ASSERT_EQ(otc_double(otc::kDevChannel, otc::kIdxWearConst, 0, 300000.0), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 100.0, 0.0, 10000.0));
    ASSERT_EQ(otc_int(otc::kDevChannel, otc::kIdxWearConstSource, 0, 0), Status::kOk);
    spool_ok(line(2, 200.0, 0.0, 10000.0));
    run_and_off();
    EXPECT_NEAR(wear(2), 3.0 + 1.0, kEps);
}

// Under G41 the spooler holds the contour element back: a change written while N2 (50 mm) is
// held acts from N3 (100 mm) on. RADIUS CONT, G139: 0.5 + 2 mm.
TEST_F(OtcBoard, AWearConstChangeSparesTheHeldProfile) {
    setup_group(kGrindingDiscRadius, /*left=*/true);
    ASSERT_EQ(write_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, 1, rwmos::tc::kSubSelectionMode,
                        139),
              Status::kOk);
    grinding_tool();
    ASSERT_EQ(set_type(otc::ProcessingType::kRadius), Status::kOk);
    ASSERT_EQ(set_mode(otc::Mode::kCont), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    activate(1);
    spool_ok(line(1, 50.0, 0.0, 10000.0));  // the approach
    spool_ok(line(2, 100.0, 0.0, 10000.0));
    run();
    ASSERT_TRUE(prof_marked(1));  // N2 held
    ASSERT_EQ(otc_double(otc::kDevTool, otc::kIdxToolWearConst, 0, 200000.0), Status::kOk);
    spool_ok(line(3, 200.0, 0.0, 10000.0));
    ASSERT_EQ(deactivate(1), Status::kOk);
    spool_ok(line(4, 250.0, 0.0, 10000.0));  // the departure
    run_and_off();
    EXPECT_NEAR(wear_radius(), 0.5 + 2.0, kEps);
}

// With nothing queued or held the change acts at once, and many changes between two profiles
// keep one entry: the last one counts.
TEST_F(OtcBoard, WearConstChangesBetweenTwoProfilesTheLastCounts) {
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 100.0, 0.0, 10000.0));
    for (int i = 1; i <= 1000; ++i)
        ASSERT_EQ(otc_double(otc::kDevChannel, otc::kIdxWearConst, 0, 1000.0 * i), Status::kOk);
    ASSERT_EQ(otc_double(otc::kDevChannel, otc::kIdxWearConst, 0, 400000.0), Status::kOk);
    spool_ok(line(2, 200.0, 0.0, 10000.0));
    run();
    ASSERT_EQ(otc_double(otc::kDevChannel, otc::kIdxWearConst, 0, 0.0), Status::kOk);
    spool_ok(line(3, 300.0, 0.0, 10000.0));  // nothing in flight: 0 from here
    run_and_off();
    EXPECT_NEAR(wear(2), 1.0 + 4.0, kEps);
}

// [ISG-OTC] section 2.6: "wird grinding_wear_const nicht gesetzt, kann der kontinuierliche
// Versatz abhängig vom Weg nicht ermittelt werden."
TEST_F(OtcBoard, WithoutWearConstNoContinuousWearAccrues) {
    grinding_tool(otc::kGrindingToolType, 0.0);
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 1000.0, 0.0, 10000.0));
    run_and_off();
    EXPECT_EQ(wear(2), 0.0);
}

TEST_F(OtcBoard, DiscModeAccruesNoContinuousWear) {
    grinding_tool();
    ASSERT_EQ(set_mode(otc::Mode::kDisc), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 1000.0, 0.0, 10000.0));
    run_and_off();
    EXPECT_EQ(wear(2), 0.0);
}

// ---- Discrete offsets ([ISG-OTC] section 2.7)

// [ISG-OTC] section 2.6: "Wenn grinding_max_infeed nicht gesetzt wird, kann kein diskreter
// Versatz beauftragt werden."
TEST_F(OtcBoard, WithoutMaxInfeedNoDiscreteOffsetCanBeCommanded) {
    grinding_tool(otc::kGrindingToolType, kGrindingWearConst, 0.0);
    const auto before = emu_test::snapshot(board);
    EXPECT_EQ(otc_int(otc::kDevAxisUnits, 2, otc::kSubCommand, 1), Status::kValueTooHigh);
    EXPECT_EQ(otc_int(otc::kDevChannel, otc::kIdxRadiusOffsetUnit, otc::kSubCommand, -1),
              Status::kValueTooLow);
    EXPECT_EQ(last_error(), static_cast<std::int32_t>(otc::Error::kInfeedBeyondLimit));
    EXPECT_TRUE(emu_test::unchanged(before, board));
}

// [ISG-OTC] section 2.7: "Wertebereich [-P-TOOL-00031, P-TOOL-00031]".
TEST_F(OtcBoard, CommandBeyondMaxInfeedIsRefused) {
    grinding_tool();
    EXPECT_EQ(otc_int(otc::kDevAxisUnits, 2, otc::kSubCommand, 200001), Status::kValueTooHigh);
    EXPECT_EQ(otc_int(otc::kDevAxisUnits, 2, otc::kSubCommand, -200001), Status::kValueTooLow);
    EXPECT_EQ(otc_int(otc::kDevAxisUnits, 2, otc::kSubCommand, 200000), Status::kOk);
    EXPECT_EQ(otc_int(otc::kDevAxisUnits, 2, otc::kSubCommand, -200000), Status::kOk);
}

// [ISG-OTC] section 2.7.1: "Ändert sich der Verschleißwert, wird diese Änderung auf mehrere
// Interpolationszyklen verteilt, so dass sprunghafte Änderungen vermieden werden."
TEST_F(OtcBoard, DiscreteOffsetIsRampedNeverAJump) {
    grinding_tool();
    ASSERT_EQ(set_mode(otc::Mode::kDisc), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    ASSERT_EQ(plc(2, 20000), Status::kOk);
    EXPECT_EQ(unit_request(2), 20000);
    EXPECT_EQ(unit_state(2), 0);
    double prev = 0.0;
    int cycles = 0;
    while (std::abs(offset()[2] + 2.0) > 0.0 && cycles < 100000) {
        board.step(1);
        ++cycles;
        EXPECT_LE(std::abs(offset()[2] - prev), 0.5e-3 * (1 + 1e-12));
        prev = offset()[2];
    }
    EXPECT_EQ(offset()[2], -2.0);
    EXPECT_GT(cycles, 4000);
    EXPECT_EQ(unit_state(2), 20000);
}

// [ISG-OTC] section 2.1: ACC_WEIGHT "Beschleunigungsgewichtung in Prozent [1;100]".
TEST_F(OtcBoard, AccWeightWeightsTheAccelerationOfTheRamp) {
    auto cycles_to_reach = [](std::int32_t weight) {
        OtcRig r;
        r.grinding_tool();
        EXPECT_EQ(r.otc_int(otc::kDevChannel, otc::kIdxAccWeight, 0, weight), Status::kOk);
        EXPECT_EQ(r.set_mode(otc::Mode::kDisc), Status::kOk);
        EXPECT_EQ(r.otc_on(), Status::kOk);
        EXPECT_EQ(r.plc(2, 1000), Status::kOk);
        int n = 0;
        while (r.offset()[2] != -0.1 && n < 1000000) {
            r.board.step(1);
            ++n;
        }
        return n;
    };
    const int full = cycles_to_reach(100);
    const int tenth = cycles_to_reach(10);
    EXPECT_GT(tenth, full + 100);
    EXPECT_EQ(otc_int(otc::kDevChannel, otc::kIdxAccWeight, 0, 0), Status::kValueTooLow);
    EXPECT_EQ(otc_int(otc::kDevChannel, otc::kIdxAccWeight, 0, 101), Status::kValueTooHigh);
}

// [ISG-OTC] section 2.1 CONT: "Vorgabe der Werte nur aus Berechnung des zurückgelegten Weges".
TEST_F(OtcBoard, ContModeIgnoresTheControlUnits) {
    grinding_tool();
    ASSERT_EQ(set_mode(otc::Mode::kCont), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    ASSERT_EQ(plc(2, 20000), Status::kOk);
    board.step(10000);
    EXPECT_EQ(offset()[2], 0.0);
    EXPECT_EQ(unit_request(2), 0);
}

// [ISG-OTC] section 2.7.1: the channel unit acts only in RADIUS or TOOL_DIR.
TEST_F(OtcBoard, ChannelUnitActsOnlyInRadiusOrToolDir) {
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);  // LENGTH
    ASSERT_EQ(plc(-1, 20000), Status::kOk);
    board.step(10000);
    EXPECT_EQ(norm(offset()), 0.0);
    EXPECT_EQ(unit_request(-1), 0);
}

// [ISG-OTC] section 2.7.2: in LENGTH every axis takes its own wear offset.
TEST_F(OtcBoard, AxisUnitsActOnTheirAxisInLength) {
    grinding_tool();
    ASSERT_EQ(set_mode(otc::Mode::kDisc), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    ASSERT_EQ(plc(0, 1000), Status::kOk);
    ASSERT_EQ(plc(5, -2000), Status::kOk);
    board.step(20000);
    EXPECT_NEAR(offset()[0], -0.1, kEps);
    EXPECT_NEAR(offset()[5], 0.2, kEps);
    EXPECT_EQ(offset()[2], 0.0);
    ASSERT_EQ(otc_off(), Status::kOk);
    EXPECT_NEAR(wear(0), 0.1, kEps);
    EXPECT_NEAR(wear(5), -0.2, kEps);
}

// [ISG-OTC] sections 2.7.1/2.7.2: in TOOL_DIR and SURF_NORM_DIR the first two axes' units are
// ignored.
TEST_F(OtcBoard, FirstTwoAxisUnitsAreIgnoredInToolDirAndSurfNormDir) {
    for (auto type : {otc::ProcessingType::kToolDir, otc::ProcessingType::kSurfNormDir}) {
        OtcRig r;
        r.grinding_tool();
        ASSERT_EQ(r.set_type(type), Status::kOk);
        ASSERT_EQ(r.otc_on(), Status::kOk);
        ASSERT_EQ(r.plc(0, 1000), Status::kOk);
        ASSERT_EQ(r.plc(1, 1000), Status::kOk);
        r.board.step(20000);
        EXPECT_EQ(norm(r.offset()), 0.0) << otc::processing_type_name(type);
        // The third axis carries the offset along the direction (here the tool along Z).
        ASSERT_EQ(r.plc(2, 1000), Status::kOk);
        r.board.step(20000);
        EXPECT_NEAR(r.offset()[2], -0.1, kEps) << otc::processing_type_name(type);
    }
}

// ---- The variables ([ISG-OTC] section 2.8) and the fold into the tool

// "Während aktiver OTC sind die V.G.WZ_AKT-Verschleißwerte nicht aktuell, sie werden erst nach
// Abwahl der OTC (#OTC OFF) aktualisiert!"
TEST_F(OtcBoard, WearVariablesAreUpdatedOnlyAtOtcOff) {
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 1000.0, 0.0, 10000.0));
    run();
    EXPECT_NEAR(offset()[2], -10.0, kEps);
    EXPECT_EQ(wear(2), 0.0);
    ASSERT_EQ(otc_off(), Status::kOk);
    EXPECT_NEAR(wear(2), 10.0, kEps);
}

// "Bei mehrfacher An- und Abwahl der OTC im NC-Programm enthalten die obigen Variablen den
// kumulierten Verschleiß!"
TEST_F(OtcBoard, RepeatedOnOffAccumulatesTheWear) {
    grinding_tool();
    for (int i = 0; i < 3; ++i) {
        ASSERT_EQ(otc_on(), Status::kOk);
        spool_ok(line(1, i % 2 == 0 ? 500.0 : 0.0, 0.0, 10000.0));
        run_and_off();
        EXPECT_NEAR(wear(2), 5.0 * (i + 1), kEps) << i;
        EXPECT_NEAR(board.state().tc.group(1).tools[kTool].length, kGrindingDiscLength - 5.0 * (i + 1),
                    kEps);
    }
}

TEST_F(OtcBoard, RadiusWearVariablesAfterOneAndSeveralCycles) {
    setup_group(kGrindingDiscRadius, /*left=*/true);
    grinding_tool();
    ASSERT_EQ(write_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, 1, rwmos::tc::kSubWkzIndex, kTool),
              Status::kOk);
    ASSERT_EQ(set_type(otc::ProcessingType::kRadius), Status::kOk);
    for (int i = 1; i <= 2; ++i) {
        ASSERT_EQ(otc_on(), Status::kOk);
        ASSERT_EQ(plc(-1, 1000), Status::kOk);  // AUTO: 0.1 mm discrete on top
        activate(1);
        spool_ok(line(60, 10.0, 0.0, 10000.0));
        spool_ok(line(70, 510.0, 0.0, 10000.0));  // 510 mm of contour: 5.1 mm of wear
        ASSERT_EQ(deactivate(1), Status::kOk);
        spool_ok(line(80, 0.0, 0.0, 10000.0));
        run_and_off();
        EXPECT_NEAR(wear_radius_cont(), 5.1 * i, kEps) << i;
        EXPECT_NEAR(wear_radius(), 5.2 * i, kEps) << i;
        EXPECT_NEAR(board.state().tc.group(1).tools[kTool].radius, kGrindingDiscRadius - 5.2 * i, kEps);
        board.step(50000);  // let the discrete offset ramp out
    }
}

// [ISG-OTC] section 2.9: the wear belongs to the tool since it was changed in.
TEST_F(OtcBoard, ToolChangeStartsTheWearFromZero) {
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 500.0, 0.0, 10000.0));
    run_and_off();
    ASSERT_NEAR(wear(2), 5.0, kEps);
    ASSERT_EQ(otc_int(otc::kDevTool, otc::kIdxToolNumber, 0, kTool), Status::kOk);  // same tool
    EXPECT_NEAR(wear(2), 5.0, kEps);
    ASSERT_EQ(otc_int(otc::kDevTool, otc::kIdxToolNumber, 0, 2), Status::kOk);
    EXPECT_EQ(wear(2), 0.0);
}

// Design (docs/otc.md): after #OTC OFF the wear is tool data; the offset leaves the axes over
// several cycles, never in a jump.
TEST_F(OtcBoard, OffsetRampsOutAfterOtcOffWithoutAJump) {
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 100.0, 0.0, 10000.0));
    run_and_off();
    double prev = offset()[2];
    EXPECT_NEAR(prev, -1.0, kEps);
    int cycles = 0;
    while (offset()[2] != 0.0 && cycles < 100000) {
        board.step(1);
        ++cycles;
        EXPECT_LE(std::abs(offset()[2] - prev), 0.5e-3 * (1 + 1e-12));
        prev = offset()[2];
    }
    EXPECT_EQ(offset()[2], 0.0);
    EXPECT_GT(cycles, 1000);
}

// Design: the discrete infeed is consumed by the fold; the next session starts from 0.
TEST_F(OtcBoard, OtcOffConsumesTheDiscreteCommands) {
    grinding_tool();
    ASSERT_EQ(set_mode(otc::Mode::kDisc), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    ASSERT_EQ(plc(2, 1000), Status::kOk);
    board.step(5000);
    ASSERT_EQ(otc_off(), Status::kOk);
    EXPECT_EQ(otc_read_int(otc::kDevAxisUnits, 2, otc::kSubCommand), 0);
    EXPECT_NEAR(wear(2), 0.1, kEps);
}

// docs/otc.md section 6, LENGTH: length -= W + sum of D_i d_i: of the discrete offsets, only
// their parts along the disc axis shorten the tool. A 30-degree disc: d = (sin 30, 0, cos 30).
TEST_F(OtcBoard, LengthFoldTakesTheDiscreteOffsetsAlongTheDiscAxis) {
    grinding_tool(otc::kGrindingToolType, kGrindingWearConst, kGrindingMaxInfeed, 300000.0);
    ASSERT_EQ(set_mode(otc::Mode::kDisc), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    ASSERT_EQ(plc(0, 10000), Status::kOk);  // 1 mm on X
    ASSERT_EQ(plc(1, 10000), Status::kOk);  // 1 mm on Y: across the disc axis
    ASSERT_EQ(plc(2, 20000), Status::kOk);  // 2 mm on Z
    board.step(20000);
    ASSERT_EQ(otc_off(), Status::kOk);
    EXPECT_NEAR(wear(0), 1.0, kEps);
    EXPECT_NEAR(wear(1), 1.0, kEps);
    EXPECT_NEAR(wear(2), 2.0, kEps);
    const double along = 1.0 * 0.5 + 2.0 * std::sqrt(3.0) / 2.0;
    for (const auto& g : board.state().tc.groups) {
        EXPECT_NEAR(g.tools[kTool].length, kGrindingDiscLength - along, kEps);
        EXPECT_EQ(g.tools[kTool].radius, kGrindingDiscRadius);
    }
}

// docs/otc.md section 6: the radius folds "not below 0"; the variables keep the whole wear.
TEST_F(OtcBoard, FoldedRadiusStopsAtZero) {
    grinding_tool();
    for (auto& g : board.state().tc.groups) g.tools[kTool].radius = 4.0;
    ASSERT_EQ(set_type(otc::ProcessingType::kSurfNormDir), Status::kOk);  // folds into the radius
    ASSERT_EQ(set_mode(otc::Mode::kCont), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(1, 1000.0, 0.0, 10000.0));  // 10 mm of wear, more than the radius
    run_and_off();
    EXPECT_NEAR(wear(2), 10.0, kEps);
    for (const auto& g : board.state().tc.groups) {
        EXPECT_EQ(g.tools[kTool].radius, 0.0);
        EXPECT_EQ(g.tools[kTool].length, kGrindingDiscLength);
    }
}

// [ISG-OTC] section 2.7.3, ManualMvBackToStart: "Ist der Handbetrieb im Kanal aktiv und bewegt
// sich die beauftragte Achse nicht, wird die Achse durch dieses Kommando so bewegt, dass der
// Handbetriebsoffset anschließend 0 ist. ... Eine steigende Flanke (FALSE -> TRUE) an X_Command
// löst den Vorgang aus." Manual mode: after a direct command (JA), until the next profile.
struct BackToStart : OtcRig {
    Status back(int axis, std::int32_t sub, std::int32_t v) {
        return otc_int(otc::kDevAxisUnits, axis, sub, v);
    }
    std::int32_t back_read(int axis, std::int32_t sub) {
        return otc_read_int(otc::kDevAxisUnits, axis, sub);
    }
    void jog(int axis, double to) {
        DirectCommand c;
        c.code = rwmos::motion::DirectCode::kJA;
        c.axes = static_cast<rwmos::motion::AxisMask>(1u << axis);
        c.target[static_cast<std::size_t>(axis)] = to;
        c.feed = 6000.0;
        ASSERT_EQ(board.direct(c).status, Status::kOk);
    }
};

TEST(OtcBackToStart, ARisingEdgeMovesTheAxisBackToWhereManualModeBegan) {
    BackToStart r;
    r.spool_ok(line(1, 10.0, 5.0, 6000.0));
    r.run();
    r.jog(0, 30.0);  // manual mode begins at X10
    r.run();
    r.jog(0, 40.0);
    r.run();
    ASSERT_EQ(r.position()[0], 40.0);
    ASSERT_EQ(r.back(0, otc::kSubBackEnable, 1), Status::kOk);
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 1), Status::kOk);
    EXPECT_EQ(r.back_read(0, otc::kSubBackRequest), 1);
    r.board.step(10);
    EXPECT_EQ(r.back_read(0, otc::kSubBackState), 1);  // under way
    EXPECT_GT(r.position()[0], 10.0);
    EXPECT_LT(r.position()[0], 40.0);
    r.run();
    EXPECT_EQ(r.position()[0], 10.0);
    EXPECT_EQ(r.position()[1], 5.0);  // the other axes stay
    EXPECT_EQ(r.back_read(0, otc::kSubBackState), 0);
    // The edge has passed: holding the command (1 written again while it is 1) moves nothing,
    // though X has an offset again (manual mode goes on, its start still X10).
    r.jog(0, 25.0);
    r.run();
    r.jog(1, 8.0);
    r.run();
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 1), Status::kOk);
    EXPECT_EQ(r.back_read(0, otc::kSubBackState), 0);
    r.run();
    EXPECT_EQ(r.position()[0], 25.0);
    EXPECT_EQ(r.position()[1], 8.0);
    // A new edge takes X back; one more with no offset left is ignored.
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 0), Status::kOk);
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 1), Status::kOk);
    r.run();
    EXPECT_EQ(r.position()[0], 10.0);
    EXPECT_EQ(r.position()[1], 8.0);
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 0), Status::kOk);
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 1), Status::kOk);
    EXPECT_EQ(r.back_read(0, otc::kSubBackState), 0);  // X has no offset: ignored
    ASSERT_EQ(r.back(1, otc::kSubBackEnable, 1), Status::kOk);
    ASSERT_EQ(r.back(1, otc::kSubBackCommand, 1), Status::kOk);
    r.run();
    EXPECT_EQ(r.position()[1], 5.0);
}

TEST(OtcBackToStart, TheCommandIsIgnoredWithoutManualModeEnableOrWhileAMoveRuns) {
    BackToStart r;
    r.jog(0, 20.0);
    r.run();
    // Not enabled: ignored.
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 1), Status::kOk);
    EXPECT_EQ(r.back_read(0, otc::kSubBackRequest), 0);
    r.run();
    EXPECT_EQ(r.position()[0], 20.0);
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 0), Status::kOk);
    ASSERT_EQ(r.back(0, otc::kSubBackEnable, 1), Status::kOk);
    // A jog still under way: ignored ("wenn noch eine Handbetriebsbewegung aktiv ist").
    r.jog(0, 30.0);
    r.board.step(5);
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 1), Status::kOk);
    r.run();
    EXPECT_EQ(r.position()[0], 30.0);
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 0), Status::kOk);
    // A profile ends manual mode: no offset to take back.
    r.spool_ok(line(2, 35.0, 0.0, 6000.0));
    r.run();
    ASSERT_EQ(r.back(0, otc::kSubBackCommand, 1), Status::kOk);
    r.run();
    EXPECT_EQ(r.position()[0], 35.0);
}

TEST(OtcOption, WithoutTheOptionBus1330IsMissing) {
    rwmos::BoardConfig cfg;
    cfg.option_otc = false;
    rwmos::EmulatedBoard board(cfg);
    objif::Descriptor d{{otc::kBus, otc::kDevChannel, otc::kIdxActive, 0}, 0};
    objif::Value v;
    EXPECT_EQ(board.read(d, objif::ValueType::kInt32, v), Status::kNoSuchDevice);
    objif::Descriptor o{{rwmos::board::kBus, 0, rwmos::board::kIdxOptions, 0}, 0};
    ASSERT_EQ(board.read(o, objif::ValueType::kInt32, v), Status::kOk);
    EXPECT_EQ(v.as_int() & rwmos::board::kOptionOtc, 0);
}

}  // namespace
}  // namespace otc_test
