// SPDX-License-Identifier: MIT
// The ISG commands of the DIN 66025 dialect: #OTC ([ISG-OTC], FCT-C20, section 2.1), $FOR ..
// $ENDFOR, #KIN, #TRAFO, #HSC, the B word, assignments and the OTC variables ([ISG-OTC] section
// 2.8); docs/nc-programs.md. One test per rule, named after it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "nc_test_util.h"

namespace apci::nc {
namespace {

using test::error_of;
using test::events_of;
using test::only;

// [ISG-OTC] section 2.6: D1 the grinding disc, D2 a milling cutter.
ToolTable grinding_tools() {
    Result<ToolTable> t = parse_tool_table(
        "wz[1].gueltig 1\nwz[1].typ 2\nwz[1].radius 300000\nwz[1].laenge 500000\n"
        "wz[1].grinding_wear_const 100000\nwz[1].grinding_max_infeed 200000\n"
        "wz[2].gueltig 1\nwz[2].typ 0\nwz[2].radius 50000\n",
        "grinding.tools");
    EXPECT_TRUE(t) << t.error().to_string();
    return std::move(t).value();
}

OtcCommand otc_of(std::string_view line) {
    ParsedLine p;
    Diagnostic err;
    EXPECT_TRUE(parse_din_line(line, 1, "prog.nc", p, err)) << err.to_string();
    EXPECT_EQ(p.kind, LineKind::kIsg) << line;
    EXPECT_EQ(p.isg.kind, IsgKind::kOtc) << line;
    return p.isg.otc;
}

std::string parse_error(std::string_view line) {
    ParsedLine p;
    Diagnostic err;
    if (parse_din_line(line, 1, "prog.nc", p, err)) return "";
    return err.to_string();
}

// ---- #OTC syntax: every form [ISG-OTC] writes

TEST(Otc, EveryIsgOtcFormParses) {
    const OtcCommand on = otc_of("N50 #OTC ON (OTC-Anwahl)");
    EXPECT_EQ(on.on, true);
    EXPECT_FALSE(on.type.has_value());
    EXPECT_EQ(otc_of("N90 #OTC OFF").on, false);
    const OtcCommand length = otc_of("N50 #OTC ON [LENGTH] (OTC-Anwahl)");
    EXPECT_EQ(length.type, OtcType::kLength);
    const OtcCommand disc = otc_of("N50 #OTC ON[RADIUS DISC]");
    EXPECT_EQ(disc.type, OtcType::kRadius);
    EXPECT_EQ(disc.mode, OtcMode::kDisc);
    const OtcCommand params = otc_of("N40 #OTC[RADIUS, AUTO] (OTC-Betriebsart + Mode festlegen)");
    EXPECT_FALSE(params.on.has_value());
    EXPECT_EQ(params.type, OtcType::kRadius);
    EXPECT_EQ(params.mode, OtcMode::kAuto);
    EXPECT_EQ(otc_of("N80 #OTC ON [TOOL_DIR, DISC]").type, OtcType::kToolDir);
    EXPECT_EQ(otc_of("N80 #OTC ON [SURF_NORM_DIR, DISC]").type, OtcType::kSurfNormDir);
}

TEST(Otc, WearConstAccWeightAndWearConstTool) {
    const OtcCommand c = otc_of("#OTC ON [LENGTH CONT WEAR_CONST=2500 ACC_WEIGHT=40]");
    EXPECT_EQ(c.mode, OtcMode::kCont);
    EXPECT_EQ(c.wear_const, WearConstChoice::kProgrammed);
    EXPECT_EQ(c.wear_const_value, 2500.0);
    EXPECT_EQ(c.acc_weight, 40);
    EXPECT_EQ(otc_of("#OTC [WEAR_CONST_TOOL]").wear_const, WearConstChoice::kTool);
    EXPECT_EQ(otc_of("#otc on [length, wear_const = [2*1000]]").wear_const_value, 2000.0);
}

// [ISG-OTC] section 2.1: ACC_WEIGHT "in Prozent [1;100]".
TEST(Otc, AccWeightMustBeOneToHundredPercent) {
    EXPECT_EQ(parse_error("#OTC [ACC_WEIGHT=0]"),
              "prog.nc:1:7: ACC_WEIGHT=0 out of range: a whole percentage 1..100");
    EXPECT_NE(parse_error("#OTC [ACC_WEIGHT=101]"), "");
    EXPECT_NE(parse_error("#OTC [ACC_WEIGHT=50.5]"), "");
    EXPECT_EQ(otc_of("#OTC [ACC_WEIGHT=1]").acc_weight, 1);
    EXPECT_EQ(otc_of("#OTC [ACC_WEIGHT=100]").acc_weight, 100);
}

// [ISG-OTC] section 3.2, P-TOOL-00030: 0 <= wear constant.
TEST(Otc, WearConstMustNotBeNegative) {
    EXPECT_EQ(parse_error("#OTC [WEAR_CONST=-1]"),
              "prog.nc:1:7: WEAR_CONST=-1 must not be negative (0.1 um/m)");
}

TEST(Otc, ConflictingOrUnknownParametersAreNamed) {
    EXPECT_EQ(parse_error("#OTC ON [RADIUS LENGTH]"),
              "prog.nc:1:17: RADIUS and LENGTH in one #OTC: both set the processing type");
    EXPECT_EQ(parse_error("#OTC ON [DISC AUTO]"),
              "prog.nc:1:15: DISC and AUTO in one #OTC: both set the mode");
    EXPECT_EQ(
        parse_error("#OTC [WEAR_CONST=1 WEAR_CONST_TOOL]"),
        "prog.nc:1:20: WEAR_CONST and WEAR_CONST_TOOL in one #OTC: both set the wear constant");
    EXPECT_NE(parse_error("#OTC [ACC_WEIGHT=5 ACC_WEIGHT=6]"), "");
    EXPECT_EQ(parse_error("#OTC ON [RADIUSS]").find("unknown #OTC parameter 'RADIUSS'"),
              std::string("prog.nc:1:10: ").size());
    EXPECT_EQ(parse_error("#OTC ON [LENGTH"),
              "prog.nc:1:16: expected ']' to close the '[' in column 9");
    EXPECT_EQ(parse_error("#OTC MAYBE").find("expected ON, OFF or '[' after #OTC"),
              std::string("prog.nc:1:6: ").size());
    EXPECT_EQ(parse_error("#OTC ON X1"), "prog.nc:1:9: unexpected 'X' after #OTC");
}

TEST(Otc, IsgCommandsStandInABlockOfTheirOwn) {
    EXPECT_EQ(parse_error("G1 X5 #OTC ON"),
              "prog.nc:1:7: ISG commands and assignments stand in a block of their own (after an "
              "optional N number)");
    EXPECT_EQ(otc_of("N10 #OTC ON").on, true);
}

// ---- #OTC rules in the interpreter

// [ISG-OTC] section 1: "Wird ein anderer Werkzeugtyp verwendet, so wird die Fehlermeldung
// P-ERR-21391 ausgegeben."
TEST(OtcRules, OtcOnNeedsAGrindingToolPErr21391) {
    const ToolTable tools = grinding_tools();
    InterpreterOptions o;
    o.tools = &tools;
    EXPECT_EQ(
        error_of("N10 D2\nN20 #OTC ON\nM30\n", o),
        "prog.nc:2:5: N20: P-ERR-21391: #OTC ON needs a grinding tool (tool type 2, P-TOOL-00001); "
        "D2 is type 0");
    EXPECT_EQ(
        error_of("N20 #OTC ON\nM30\n", o),
        "prog.nc:1:5: N20: P-ERR-21391: #OTC ON needs a grinding tool (tool type 2, P-TOOL-00001); "
        "D0 is type 0");
    EXPECT_EQ(error_of("N10 D1\nN20 #OTC ON\nN30 #OTC OFF\nM30\n", o), "");
}

// [ISG-OTC] section 2.2 "Hinweis": "Bei der Abwahl muss zwingend die Sequenz G40 vor #OTC OFF
// eingehalten werden."
TEST(OtcRules, G40MustComeBeforeOtcOff) {
    const std::string bad = "F600\nD1\n#OTC ON [RADIUS]\nG41 G1 X10\nX20\n#OTC OFF\nG40 X30\nM30\n";
    EXPECT_EQ(error_of(bad),
              "prog.nc:6:1: OTC_OFF_BEFORE_G40: #OTC OFF while radius compensation G41 is on: "
              "program G40 before #OTC OFF");
    EXPECT_EQ(error_of("F600\nD1\n#OTC ON [RADIUS]\nG41 G1 X10\nX20\nG40 X30\n#OTC OFF\nM30\n"),
              "");
    // [ISG-OTC]: "Bei der Anwahl ist ein Vertauschen der Befehle G41/G42 und #OTC ON möglich."
    EXPECT_EQ(error_of("F600\nD1\nG41 G1 X10\n#OTC ON [RADIUS]\nX20\nG40 X30\n#OTC OFF\nM30\n"),
              "");
}

// [ISG-OTC] section 2.2 "Hinweis": "Mit den WRK Modi G138/G139 ist eine Verfahrbewegung zwischen
// den beiden Befehlen zwingend erforderlich. Wenn der Fehler 90050 ausgegeben wird, dann ist bei
// der Abwahl mit G138/G139 die Verfahrbewegung nicht vorhanden."
TEST(OtcRules, UnderG139AMoveMustComeBetweenG40AndOtcOff) {
    EXPECT_EQ(error_of("F600\nD1\n#OTC ON [RADIUS]\nG41 G1 X10\nX20\nG40\n#OTC OFF\nM30\n"),
              "prog.nc:7:1: 90050: #OTC OFF right after G40 without a move: under G139 the block "
              "after G40 departs from the contour, so program a move (with the G40 or after it) "
              "before #OTC OFF");
    // The move with G40 or after it; G237 departs at G40 itself.
    EXPECT_EQ(error_of("F600\nD1\n#OTC ON [RADIUS]\nG41 G1 X10\nX20\nG40\nX30\n#OTC OFF\nM30\n"),
              "");
    EXPECT_EQ(error_of("F600\nD1\n#OTC ON [RADIUS]\nG41 G1 X10\nX20\nG40 X30\n#OTC OFF\nM30\n"),
              "");
    EXPECT_EQ(
        error_of("F600\nD1\nG237\n#OTC ON [RADIUS]\nG41 G1 X10\nX20\nG40\n#OTC OFF\nM30\n"), "");
    // G138 as G139 ("Mit den WRK Modi G138/G139"); the G40 block's own word decides.
    EXPECT_EQ(error_of("F600\nD1\nG138\n#OTC ON [RADIUS]\nG41 G1 X10\nX20\nG40\n#OTC OFF\nM30\n"),
              "prog.nc:8:1: 90050: #OTC OFF right after G40 without a move: under G138 the block "
              "after G40 departs from the contour, so program a move (with the G40 or after it) "
              "before #OTC OFF");
    EXPECT_EQ(error_of("F600\nD1\n#OTC ON [RADIUS]\nG41 G1 X10\nX20\nG237 G40\n#OTC OFF\nM30\n"),
              "");
    EXPECT_NE(error_of("F600\nD1\nG237\n#OTC ON [RADIUS]\nG41 G1 X10\nX20\nG139 G40\n#OTC OFF\n"
                       "M30\n"),
              "");
}

TEST(OtcRules, ParametersAreNotChangedWhileOtcIsOn) {
    EXPECT_EQ(error_of("#OTC ON\n#OTC [RADIUS]\nM30\n"),
              "prog.nc:2:1: OTC_CHANGE_WHILE_ACTIVE: processing type, mode and ACC_WEIGHT are set "
              "before or with #OTC ON, not while OTC is on");
    EXPECT_EQ(error_of("#OTC ON\n#OTC [LENGTH AUTO ACC_WEIGHT=100]\nM30\n"), "");  // in force
    EXPECT_EQ(error_of("#OTC ON\n#OTC [WEAR_CONST=5]\n#OTC [WEAR_CONST_TOOL]\nM30\n"),
              "");  // modal
}

TEST(OtcRules, NoToolChangeWhileOtcIsOn) {
    EXPECT_EQ(error_of("D1\n#OTC ON\nD2\nM30\n"),
              "prog.nc:3:1: OTC_TOOL_CHANGE_WHILE_ACTIVE: D2 while OTC is on: program #OTC OFF "
              "before a tool change");
}

TEST(OtcRules, OtcEventsCarryTheCommandInProgramOrder) {
    const auto ev = events_of("N10 D1\nN40 #OTC[RADIUS, AUTO]\nN50 #OTC ON\nN90 #OTC OFF\nM30\n");
    const auto otc = only<OtcChange>(ev);
    ASSERT_EQ(otc.size(), 3u);
    EXPECT_FALSE(otc[0].command.on.has_value());
    EXPECT_EQ(otc[1].command.on, true);
    EXPECT_EQ(otc[2].command.on, false);
}

// ---- #KIN, #TRAFO, #HSC, B

TEST(Kinematics, OnlyTheBHeadIsEmulated) {
    EXPECT_EQ(only<KinematicsSelect>(events_of("#KIN ID[4]\nM30\n")).at(0).id, 4);
    EXPECT_EQ(error_of("#KIN ID[3]\nM30\n"),
              "prog.nc:1:1: #KIN ID[3]: kinematics 3 is not emulated (ID[4]: the B head, docs/design.md "
              "section 8; ID[0]: none)");
    EXPECT_EQ(parse_error("#KIN 4"), "prog.nc:1:6: expected ID[n] after #KIN");
}

TEST(Kinematics, TrafoOnNeedsAKinematics) {
    EXPECT_EQ(error_of("#TRAFO ON\nM30\n"),
              "prog.nc:1:1: #TRAFO ON needs a kinematics: program #KIN ID[4] first");
    const auto ev = events_of("N50 #KIN ID[4]\nN50 #TRAFO ON\nN130 #TRAFO OFF\nM30\n");
    const auto t = only<TrafoChange>(ev);
    ASSERT_EQ(t.size(), 2u);
    EXPECT_TRUE(t[0].on);
    EXPECT_FALSE(t[1].on);
    EXPECT_EQ(parse_error("#TRAFO MAYBE"),
              "prog.nc:1:8: expected ON or OFF after #TRAFO, found 'MAYBE'");
}

// docs/design.md section 8: with the transformation the program gives the tool tip; at the switch
// the position in force is re-expressed, the pivot staying where it is: outside the
// transformation the length acts on the plane's tool axis (pivot = point + length e_z), under it
// along the tool (pivot = tip + length t(B)).
TEST(Kinematics, TrafoReExpressesThePositionAsTheToolTip) {
    const ToolTable tools = grinding_tools();  // D1: laenge 50 mm
    InterpreterOptions o;
    o.tools = &tools;
    const auto ev = events_of(
        "D1\nG0 X0 Y0 Z300 B0\n#KIN ID[4]\n#TRAFO ON\nG0 B45\nG1 X100 Z50 F1000\n#TRAFO OFF\nG0 X0\n"
        "M30\n",
        o);
    const auto t = only<TrafoChange>(ev);
    ASSERT_EQ(t.size(), 2u);
    EXPECT_EQ(t[0].tool_length, 50.0);
    const auto rapids = only<RapidMove>(ev);
    ASSERT_EQ(rapids.size(), 3u);
    EXPECT_EQ(rapids[1].start, Eigen::Vector3d(0, 0, 300));  // B0: the tip where it was
    EXPECT_EQ(rapids[1].end, Eigen::Vector3d(0, 0, 300));    // B45: the tip stays
    // After #TRAFO OFF the pivot, tip (100, 0, 50) + 50 (sin 45, 0, cos 45), less the length on Z.
    EXPECT_NEAR(rapids[2].start.x(), 100 + 50 * std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(rapids[2].start.z(), 50 + 50 * std::sqrt(0.5) - 50, 1e-12);
}

// In the Z-X plane the length acts on Y outside the transformation: at B0 the tip is the pivot
// one length below it along Z, the programmed point one length beside it along Y.
TEST(Kinematics, TrafoTakesTheLengthOffThePlanesToolAxis) {
    const ToolTable tools = grinding_tools();
    InterpreterOptions o;
    o.tools = &tools;
    const auto ev = events_of("D1\nG18\nG0 X0 Y0 Z300\n#KIN ID[4]\n#TRAFO ON\nG0 X1\nM30\n", o);
    const auto rapids = only<RapidMove>(ev);
    ASSERT_EQ(rapids.size(), 2u);
    EXPECT_EQ(rapids[1].start, Eigen::Vector3d(0, 50, 250));
}

TEST(Kinematics, NoToolChangeOrRadiusCompensationUnderTrafo) {
    EXPECT_EQ(error_of("D1\n#KIN ID[4]\n#TRAFO ON\nD2\nM30\n"),
              "prog.nc:4:1: D2 while #TRAFO is on: the transformation holds the tool's length; "
              "program #TRAFO OFF before a tool change");
    EXPECT_EQ(error_of("#KIN ID[4]\n#TRAFO ON\nG41\nM30\n"),
              "prog.nc:3:1: G41 while #TRAFO is on: radius compensation and the transformation do "
              "not combine here; program #TRAFO OFF first");
    EXPECT_NE(error_of("#KIN ID[4]\nG42\n#TRAFO ON\nM30\n").find("#TRAFO ON while radius compensation G42"),
              std::string::npos);
}

TEST(Kinematics, TrafoIsNotSwitchedWhileOtcIsOn) {
    EXPECT_NE(error_of("#KIN ID[4]\n#OTC ON\n#TRAFO ON\nM30\n").find("OTC_CHANGE_WHILE_ACTIVE"),
              std::string::npos);
}

// docs/design.md section 8: #HSC is parsed and reported as not emulated.
TEST(Hsc, AcceptedAndReportedAsNotEmulated) {
    const auto ev = events_of("N85 #HSC ON[BSPLINE PATH_DEV 5 MERGE = 0]\nN290 #HSC OFF\nM30\n");
    const auto n = only<NotEmulated>(ev);
    ASSERT_EQ(n.size(), 2u);
    EXPECT_EQ(n[0].command, "#HSC");
    EXPECT_EQ(parse_error("#HSC ON[BSPLINE"),
              "prog.nc:1:8: the '[' of #HSC is not closed before the end of the line");
}

TEST(BAxis, TiltsTheHeadBeforeTheBlocksMove) {
    const auto ev = events_of("N40 G00 X0 Y0 Z300 B0\nN60 G00 B45\nN70 G01 X100 Z50 F1000\nM30\n");
    const auto heads = only<HeadOrientation>(ev);
    ASSERT_EQ(heads.size(), 2u);
    EXPECT_EQ(heads[1].b, 45.0);
    // The B-only block is a rapid that stands still in X Y Z.
    const auto rapids = only<RapidMove>(ev);
    ASSERT_EQ(rapids.size(), 2u);
    EXPECT_EQ(rapids[1].start, rapids[1].end);
    EXPECT_EQ(error_of("F10\nG2 X1 I1 B5\nM30\n"),
              "prog.nc:2:10: B in an arc block: tilt the head in a G0 or G1 block");
}

// ---- $FOR .. $ENDFOR

TEST(ForLoop, ToolDirExampleLoopRunsTwentyOneTimes) {
    // [ISG-OTC] section 2.4: $FOR P1=0, 20, 1 with two moves.
    const auto ev = events_of(
        "F1000\nN90 $FOR P1=0, 20, 1\nN100 G91 G01 X10 Z-10 F2000\nN110 X-10 Z10\nN120 "
        "$ENDFOR\nM30\n");
    const auto lines = only<LineMove>(ev);
    EXPECT_EQ(lines.size(), 42u);
    EXPECT_EQ(lines.back().end, Eigen::Vector3d(0, 0, 0));
    EXPECT_EQ(ev.front().origin.block, 100);
    EXPECT_EQ(ev.front().origin.line, 3u);
    EXPECT_EQ(ev.back().origin.block, -1);  // M30
}

TEST(ForLoop, TheParameterCountsAndIsReadable) {
    const auto lines = only<RapidMove>(
        events_of("$FOR P1 = 1, 3, 1\nG0 X[P1*10] Y[P1]\n$ENDFOR\nG0 X[P1]\nM30\n"));
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[0].end, Eigen::Vector3d(10, 1, 0));
    EXPECT_EQ(lines[2].end, Eigen::Vector3d(30, 3, 0));
    EXPECT_EQ(lines[3].end.x(), 4.0);  // after the loop: passed the end
}

TEST(ForLoop, NegativeStepsCountDown) {
    const auto lines = only<RapidMove>(events_of("$FOR P2=5, 1, -2\nG0 X[P2]\n$ENDFOR\nM30\n"));
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[2].end.x(), 1.0);
}

TEST(ForLoop, LoopsNest) {
    const auto lines = only<RapidMove>(
        events_of("$FOR P1=1,3,1\n$FOR P2=1,2,1\nG0 X[P1] Y[P2]\n$ENDFOR\n$ENDFOR\nM30\n"));
    ASSERT_EQ(lines.size(), 6u);
    EXPECT_EQ(lines[5].end, Eigen::Vector3d(3, 2, 0));
}

TEST(ForLoop, ALoopWhoseConditionFailsAtOnceIsSkipped) {
    const auto lines = only<RapidMove>(
        events_of("$FOR P1=5,1,1\nG0 X[P1]\n$FOR P2=1,2,1\nG0 Y1\n$ENDFOR\n$ENDFOR\nG0 Z7\nM30\n"));
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lines[0].end.z(), 7.0);
}

TEST(ForLoop, StepZeroIsRefused) {
    EXPECT_EQ(error_of("$FOR P1=0,5,0\n$ENDFOR\nM30\n"),
              "prog.nc:1:6: the $FOR step must not be 0 (the loop would never end)");
}

TEST(ForLoop, UnmatchedForAndEndForAreNamed) {
    EXPECT_EQ(error_of("$ENDFOR\nM30\n"), "prog.nc:1:1: $ENDFOR without $FOR");
    EXPECT_EQ(error_of("N5 $FOR P1=0,1,1\nG0 X1\nM30\n"),
              "prog.nc:1:4: $FOR without $ENDFOR: the program ends inside the loop");
    EXPECT_EQ(error_of("$FOR P1=2,1,1\nG0 X1\nM30\n"),
              "prog.nc:1:1: $FOR without $ENDFOR: the program ends inside the loop");
    EXPECT_EQ(parse_error("$FOR X1=0,1,1"),
              "prog.nc:1:6: expected a P parameter after $FOR ($FOR P1 = 0, 10, 1)");
    EXPECT_EQ(parse_error("$FOR P1=0,1"),
              "prog.nc:1:12: expected ',' in $FOR Pn = start, end, step");
}

TEST(ForLoop, NestingIsBounded) {
    std::string text;
    for (std::size_t i = 0; i <= kMaxLoopDepth; ++i)
        text += "$FOR P" + std::to_string(i) + "=1,1,1\n";
    text += "M30\n";
    EXPECT_NE(error_of(text).find("$FOR nested deeper than 16 loops"), std::string::npos);
}

// A loop body larger than the line reader's buffer is replayed from the file.
TEST(ForLoop, LongBodiesAreReplayedFromTheFile) {
    const std::string path = ::testing::TempDir() + "/long_loop.nc";
    {
        std::ofstream f(path);
        f << "$FOR P1=1,3,1\n";
        for (int i = 0; i < 20000; ++i)
            f << "G0 X" << i << " Y[P1] (a comment to make the line longer)\n";
        f << "$ENDFOR\nM30\n";
    }
    Result<Program> p = Program::load(path);
    ASSERT_TRUE(p) << p.error().to_string();
    Result<EventStream> s = p.value().events();
    ASSERT_TRUE(s);
    Event ev;
    std::size_t n = 0;
    double last_y = 0.0;
    while (s.value().next(ev) == EventStream::Next::kEvent) {
        if (const auto* r = std::get_if<RapidMove>(&ev.data)) {
            ++n;
            last_y = r->end.y();
            if (n == 20001) {
                EXPECT_EQ(ev.origin.line, 2u);  // the second pass starts over
            }
        }
    }
    EXPECT_EQ(n, 60000u);
    EXPECT_EQ(last_y, 3.0);
    std::remove(path.c_str());
}

// ---- Assignments and variables

TEST(Variables, ParametersAreAssignedAndRead) {
    const auto r = only<RapidMove>(events_of("P1 = 2\nN5 P2 = P1 * 3 + 1\nG0 X[P2]\nM30\n"));
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].end.x(), 7.0);
    EXPECT_EQ(error_of("G0 X[P9]\nM30\n"), "prog.nc:1:6: P9 is used before it is set");
}

// [ISG-OTC] section 2.8: V.G.OTC_ACTIVE reads the state of OTC.
TEST(Variables, OtcActiveReadsTheOtcState) {
    const auto r = only<RapidMove>(
        events_of("P1 = V.G.OTC_ACTIVE\n#OTC ON\nP2 = V.G.OTC_ACTIVE\nG0 X[P1] Y[P2]\nM30\n"));
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].end, Eigen::Vector3d(0, 1, 0));
}

// [ISG-OTC] section 2.8: "Sie kann auch im NC-Programm über die Variable V.G.WZ_AKT.WEAR_CONST
// ... geschrieben bzw. gelesen werden."
TEST(Variables, WearConstIsReadFromTheToolAndWritable) {
    const ToolTable tools = grinding_tools();
    InterpreterOptions o;
    o.tools = &tools;
    const auto ev = events_of(
        "D1\nP1 = V.G.WZ_AKT.WEAR_CONST\nV.G.WZ_AKT.WEAR_CONST = P1 / 2\nP2 = "
        "V.G.WZ_AKT.WEAR_CONST\n"
        "G0 X[P1] Y[P2]\nM30\n",
        o);
    const auto w = only<VariableWrite>(ev);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].variable.variable, NcVariable::kWearConst);
    EXPECT_EQ(w[0].value, 50000.0);
    const auto r = only<RapidMove>(ev);
    EXPECT_EQ(r.at(0).end, Eigen::Vector3d(100000, 50000, 0));
}

TEST(Variables, WearVariablesAreReadOnly) {
    EXPECT_EQ(error_of("V.G.WZ_AKT.WEAR_RADIUS = 1\nM30\n"),
              "prog.nc:1:1: V.G.WZ_AKT.WEAR_RADIUS is read-only (only V.G.WZ_AKT.WEAR_CONST and "
              "$SC_TOOL_TEMP_COMP[i] are written by programs)");
    EXPECT_NE(error_of("V.G.WZ_AKT.WEAR_CONST = -1\nM30\n"), "");
}

TEST(Variables, AllIsgOtcNamesAreKnown) {
    for (const char* name : {"V.G.WZ_AKT.WEAR_RADIUS", "V.G.WZ_AKT.WEAR_RADIUS_CONT",
                             "V.G.WZ_AKT.WEAR[0]", "V.G.WZ_AKT.WEAR[2]", "V.G.WZ_AKT.WEAR.X",
                             "V.G.WZ_AKT.WEAR.Z", "V.G.WZ_AKT.WEAR_CONST", "V.G.OTC_ACTIVE"}) {
        EXPECT_EQ(error_of(std::string("P1 = ") + name + "\nM30\n"), "") << name;
    }
    EXPECT_NE(error_of("P1 = V.G.WZ_AKT.WEAR[8]\nM30\n").find("axis index 0..7"),
              std::string::npos);
    EXPECT_NE(error_of("P1 = V.G.WZ_AKT.WEAR.Q\nM30\n").find("unknown axis"), std::string::npos);
    EXPECT_NE(error_of("P1 = V.G.NOPE\nM30\n").find("unknown variable V.G.NOPE"),
              std::string::npos);
}

// The executor's values (the board's) replace the front end's view while it executes.
TEST(Variables, AVariableSourceSuppliesTheBoardsValues) {
    struct Board : VariableSource {
        bool read(const VariableRef& v, double& out, std::string& why) override {
            if (v.variable == NcVariable::kWear && v.index == 2) {
                out = 10.0;
                return true;
            }
            why = "not on this board";
            return false;
        }
    } board;
    Result<Program> p = Program::from_text("P1 = V.G.WZ_AKT.WEAR.Z\nG0 X[P1]\nM30\n", "prog.nc");
    ASSERT_TRUE(p) << p.error().to_string();
    Result<EventStream> s = p.value().events();
    ASSERT_TRUE(s);
    s.value().set_variable_source(&board);
    Event ev;
    ASSERT_EQ(s.value().next(ev), EventStream::Next::kEvent);
    EXPECT_EQ(std::get<RapidMove>(ev.data).end.x(), 10.0);

    Result<Program> q = Program::from_text("P1 = V.G.WZ_AKT.WEAR_RADIUS\nM30\n", "prog.nc");
    ASSERT_TRUE(q);
    Result<EventStream> t = q.value().events();
    t.value().set_variable_source(&board);
    EXPECT_EQ(t.value().next(ev), EventStream::Next::kError);
    EXPECT_EQ(t.value().error().to_string(),
              "prog.nc:1:6: V.G.WZ_AKT.WEAR_RADIUS cannot be read: not on this board");
}

// [ISG-OTC] section 2.8: the wear values are "in [mm] oder [Inch]": under G70 a program reads
// them in inches (the board's 9.652 mm of radius wear is 0.38 in, and G0 X[P1] goes to 9.652
// mm); under G71 in mm. The wear on A, B, C is an angle, the wear constant 0.1 um/m: as read.
TEST(Variables, WearLengthsAreReadInTheProgramsUnit) {
    struct Board : VariableSource {
        bool read(const VariableRef& v, double& out, std::string&) override {
            out = v.variable == NcVariable::kWearConst ? 1000.0 : 9.652;
            return true;
        }
    } board;
    struct Case {
        const char* variable;
        double inch_value;  // what P1 holds under G70
    };
    const Case cases[] = {{"V.G.WZ_AKT.WEAR_RADIUS", 0.38},
                          {"V.G.WZ_AKT.WEAR_RADIUS_CONT", 0.38},
                          {"V.G.WZ_AKT.WEAR[0]", 0.38},
                          {"V.G.WZ_AKT.WEAR.Z", 0.38},
                          {"V.G.WZ_AKT.WEAR[6]", 0.38},
                          {"V.G.WZ_AKT.WEAR[4]", 9.652},  // B: degrees
                          {"V.G.WZ_AKT.WEAR.A", 9.652},
                          {"V.G.WZ_AKT.WEAR_CONST", 1000.0}};
    for (const Case& c : cases) {
        for (const char* units : {"G70", "G71"}) {
            const bool inch = std::string(units) == "G70";
            const std::string text =
                std::string(units) + "\nP1 = " + c.variable + "\nG0 X[P1]\nM30\n";
            Result<Program> p = Program::from_text(text, "prog.nc");  // keeps a view of text
            ASSERT_TRUE(p) << p.error().to_string();
            Result<EventStream> s = p.value().events();
            ASSERT_TRUE(s);
            s.value().set_variable_source(&board);
            Event ev;
            ASSERT_EQ(s.value().next(ev), EventStream::Next::kEvent)
                << c.variable << " " << units << ": " << s.value().error().to_string();
            const double p1 = inch ? c.inch_value : (c.inch_value == 0.38 ? 9.652 : c.inch_value);
            EXPECT_NEAR(std::get<RapidMove>(ev.data).end.x(), inch ? p1 * kMillimetresPerInch : p1,
                        1e-9)
                << c.variable << " " << units;
        }
    }
}

}  // namespace
}  // namespace apci::nc
