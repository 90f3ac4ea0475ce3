// SPDX-License-Identifier: MIT
// The Klartext subset for the 3D tool compensation ([TNC-3D]): parsing, the program rules
// and the events, with [TNC-3D]'s examples (examples/3d_*.h) and every refusal.
#include "apci/nc/klartext.h"

#include <gtest/gtest.h>

#include <string>

#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "nc_test_util.h"
#include "rwmos/comp3d/tolerances.h"

namespace apci::nc {
namespace {

using test::error_of;
using test::undefined_of;
using test::events_of;
using test::only;
using V = Eigen::Vector3d;

const std::string kExamples = APCI_EXAMPLES_DIR;

void expect_near(const V& got, const V& want, double tol = 1e-12) {
    EXPECT_NEAR((got - want).norm(), 0.0, tol)
        << "got " << got.transpose() << ", want " << want.transpose();
}

// A program around the given blocks: BEGIN PGM, a feed, the blocks, END PGM.
std::string pgm(std::string_view blocks) {
    return "0 BEGIN PGM T MM\n1 L X+0 Y+0 Z+0 R0 F1000\n" + std::string(blocks) +
           "99 END PGM T MM\n";
}

ToolTable tools(std::string_view text) {
    Result<ToolTable> t = parse_tool_table(text, "t.tools");
    EXPECT_TRUE(t) << t.error().to_string();
    return t ? t.value() : ToolTable{};
}

std::vector<Event> run_file(const std::string& path, const ToolTable* table) {
    InterpreterOptions opt;
    opt.tools = table;
    Result<Program> p = Program::load(path, opt);
    EXPECT_TRUE(p) << p.error().to_string();
    if (!p) return {};
    Result<EventStream> s = p.value().events();
    std::vector<Event> out;
    Event ev;
    while (s.value().next(ev) == EventStream::Next::kEvent) out.push_back(ev);
    return out;
}

ToolTable example_tools() {
    Result<ToolTable> t = load_tool_table(kExamples + "/tools/3d_tools.tools");
    EXPECT_TRUE(t) << t.error().to_string();
    return t ? t.value() : ToolTable{};
}

// ---- Program structure ----

TEST(Klartext, DialectIsToldByBeginPgm) {
    Result<Program> p =
        Program::from_text("; header\n0  BEGIN PGM 3DTEST MM\n1 END PGM 3DTEST MM\n", "prog.h");
    ASSERT_TRUE(p) << p.error().to_string();
    EXPECT_EQ(p.value().summary().name, "3DTEST");
    const auto ev = events_of("BEGIN PGM A MM\nEND PGM A MM\n");
    ASSERT_EQ(ev.size(), 1U);
    EXPECT_TRUE(std::holds_alternative<ProgramEnd>(ev[0].data));
}

TEST(Klartext, ProgramEndsWithEndPgm) {
    EXPECT_EQ(error_of("0 BEGIN PGM A MM\n1 L X+1 F100\n"),
              "prog.nc:2:1: the program ends without END PGM");
}

TEST(Klartext, EndPgmMustNameTheProgram) {
    EXPECT_EQ(error_of("0 BEGIN PGM A MM\n1 END PGM B MM\n"),
              "prog.nc:2:11: END PGM B does not match BEGIN PGM A");
    EXPECT_EQ(error_of("0 BEGIN PGM A MM\n1 END PGM A\n"),
              "prog.nc:2:12: expected the unit MM or INCH after the program name");
}

TEST(Klartext, NothingAfterEndPgm) {
    EXPECT_EQ(error_of("0 BEGIN PGM A MM\n1 END PGM A MM\n2 L X+1 F100\n"),
              "prog.nc:3:3: block after END PGM: the program has already ended");
    EXPECT_TRUE(error_of("0 BEGIN PGM A MM\n1 END PGM A MM\n\n; trailing comment\n").empty());
}

TEST(Klartext, OnlyEndPgmAfterM30) {
    EXPECT_EQ(error_of(pgm("2 M30\n3 L X+1\n")),
              "prog.nc:4:3: block after M2/M30: only END PGM may follow");
    const auto ev = events_of(pgm("2 M30\n"));
    EXPECT_EQ(only<ProgramEnd>(ev).size(), 1U);  // at M30, not again at END PGM
    EXPECT_EQ(ev.back().origin.line, 3U);
}

TEST(Klartext, InchProgramsAreRefused) {
    EXPECT_EQ(error_of("0 BEGIN PGM A INCH\n1 END PGM A INCH\n"),
              "prog.nc:1:15: INCH programs are not supported: the emulator works in mm (write the "
              "program in MM)");
}

TEST(Klartext, BeginPgmOnlyOnce) {
    EXPECT_EQ(error_of("0 BEGIN PGM A MM\n1 BEGIN PGM A MM\n2 END PGM A MM\n"),
              "prog.nc:2:3: BEGIN PGM appears twice: one program per file");
}

TEST(Klartext, CommentsStructureLinesAndBlankLines) {
    const auto ev = events_of(
        "0 BEGIN PGM A MM ; the program\n\n* - roughing\n1 * - structure\n; comment\n"
        "2 L X+1 F100 ; move\n3 END PGM A MM\n");
    const auto lines = only<LineMove>(ev);
    ASSERT_EQ(lines.size(), 1U);
    expect_near(lines[0].end, V(1, 0, 0));
    EXPECT_EQ(ev[0].origin.block, 2);
    EXPECT_EQ(ev[0].origin.line, 6U);
}

TEST(Klartext, UnsupportedBlocksAreNamed) {
    EXPECT_EQ(error_of(pgm("2 CC X+0 Y+0\n")),
              "prog.nc:3:3: Klartext block 'CC' is not in the supported subset (known: BEGIN PGM, "
              "END PGM, TOOL CALL, L, LN, FUNCTION PROG PATH, FUNCTION TCPM, FUNCTION RESET TCPM, "
              "FUNCTION CORRDATA, M functions)");
    EXPECT_EQ(error_of(pgm("2 FUNCTION MODE MILL\n")),
              "prog.nc:3:12: FUNCTION MODE is not in the supported subset (known: FUNCTION PROG "
              "PATH, FUNCTION TCPM, FUNCTION RESET TCPM, FUNCTION CORRDATA)");
}

// ---- L ----

TEST(KlartextL, AbsoluteAndIncrementalCoordinates) {
    const auto lines = only<LineMove>(events_of(pgm("2 L X+10 Y-5 F500\n3 L IX+2.5 Z-1\n")));
    ASSERT_EQ(lines.size(), 3U);
    expect_near(lines[1].end, V(10, -5, 0));
    EXPECT_EQ(lines[1].feed, 500.0);
    expect_near(lines[2].start, V(10, -5, 0));
    expect_near(lines[2].end, V(12.5, -5, -1));
    EXPECT_EQ(lines[2].feed, 500.0);  // modal
}

TEST(KlartextL, FmaxIsARapidMoveForThisBlockOnly) {
    const auto ev = events_of(pgm("2 L Z+50 FMAX\n3 L X+5\n"));
    ASSERT_EQ(only<RapidMove>(ev).size(), 1U);
    const auto lines = only<LineMove>(ev);
    ASSERT_EQ(lines.size(), 2U);
    EXPECT_EQ(lines[1].feed, 1000.0);
}

TEST(KlartextL, NeedsAFeed) {
    EXPECT_EQ(error_of("0 BEGIN PGM A MM\n1 L X+1\n2 END PGM A MM\n"),
              "prog.nc:2:5: no feed rate: program F (or FMAX) before the first L move");
}

TEST(KlartextL, RadiusCompensationIsModalAndSentOnChange) {
    const auto ev = events_of(pgm("2 L X+5 RL\n3 L Y+5\n4 L X+0 RR\n5 L Y+0 R0\n"));
    const auto comp = only<CompensationChange>(ev);
    ASSERT_EQ(comp.size(), 3U);
    EXPECT_EQ(comp[0].side, Compensation::kLeft);
    EXPECT_EQ(comp[1].side, Compensation::kRight);
    EXPECT_EQ(comp[2].side, Compensation::kOff);
}

TEST(KlartextL, RotaryAxesOfTheHeadAreSentBeforeTheMove) {
    const auto ev = events_of(pgm("2 L X+5 B-20 C+90\n3 L B+10\n"));
    const auto heads = only<HeadOrientation>(ev);
    ASSERT_EQ(heads.size(), 2U);
    EXPECT_EQ(heads[0].b, -20.0);
    EXPECT_EQ(heads[0].c, 90.0);
    EXPECT_EQ(heads[1].b, 10.0);
    EXPECT_EQ(heads[1].c, 90.0);               // C keeps its position
    EXPECT_EQ(only<LineMove>(ev).size(), 2U);  // block 3 turns the head only
    EXPECT_EQ(error_of(pgm("2 L A+5\n")),
              "prog.nc:3:5: the emulated head has no A axis (B tilts the tool in the Z-X plane, C "
              "turns the head about Z)");
}

TEST(KlartextL, WordErrors) {
    EXPECT_EQ(error_of(pgm("2 L X+1 X+2\n")), "prog.nc:3:9: 'X' appears twice in one block");
    EXPECT_EQ(error_of(pgm("2 L X+1 IX+2\n")),
              "prog.nc:3:9: X and IX in one block: give the axis once");
    EXPECT_EQ(error_of(pgm("2 L X+1 NX+0\n")),
              "prog.nc:3:9: 'NX' is not a word of an L block (known: X Y Z IX IY IZ B C R0 RL RR F "
              "FMAX FZ FU F AUTO M)");
    EXPECT_EQ(error_of(pgm("2 L X+1Y+2\n")),
              "prog.nc:3:8: expected a blank after the value of 'X', found 'Y' (Klartext words are "
              "separated by blanks)");
    EXPECT_EQ(error_of(pgm("2 L X+1 RL RR\n")),
              "prog.nc:3:12: R0, RL and RR in one block: give the radius compensation once");
    EXPECT_EQ(error_of(pgm("2 L X+1 R5\n")),
              "prog.nc:3:9: expected R0, RL or RR (radius compensation); 'R' takes no value here");
    EXPECT_EQ(error_of(pgm("2 L X+1 F100 FMAX\n")),
              "prog.nc:3:14: two feeds in one block (F, FMAX, FZ, FU, F AUTO): give one");
    EXPECT_EQ(error_of(pgm("2 L X+1 F0\n")), "prog.nc:3:10: feed rate F must be greater than 0");
    EXPECT_EQ(error_of(pgm("2 L X+1 M3\n")),
              "prog.nc:3:9: unknown M function M3 (known: M2, M30, M107, M108, M128, M129)");
    EXPECT_EQ(error_of(pgm("2 L X+\n")), "prog.nc:3:6: expected a number after 'X'");
    EXPECT_EQ(error_of(pgm("2 l X+1\n")),
              "prog.nc:3:3: unexpected character 'l': expected a Klartext block (BEGIN PGM, END "
              "PGM, TOOL CALL, L, LN, FUNCTION PROG PATH, FUNCTION TCPM, FUNCTION RESET TCPM, "
              "FUNCTION CORRDATA, M functions)");
}

// ---- LN ([TNC-3D], "Gerade LN") ----

// [TNC-3D]'s face-milling example (examples/3d_face_milling.h): the three variants.
TEST(KlartextLn, Tnc3dFaceMillingExample) {
    const ToolTable table = example_tools();
    const auto ev = run_file(kExamples + "/3d_face_milling.h", &table);
    const auto ln = only<VectorLineMove>(ev);
    ASSERT_EQ(ln.size(), 3U);
    const V p(36.0084, 6.177, -1.9209);
    const V n = V(-0.4658107, 0, 0.8848844).normalized();
    const V t = V(0, 0.6558846, 0.7548612).normalized();
    for (const auto& l : ln) {
        expect_near(l.start, p);
        expect_near(l.end, p);
        ASSERT_TRUE(l.has_normal);
        expect_near(l.normal, n, 1e-15);
        EXPECT_EQ(l.side, Compensation::kOff);
        EXPECT_EQ(l.feed, 1000.0);
    }
    // 12: no TCPM - the machine's tool axis.
    EXPECT_FALSE(ln[0].has_tool_vector);
    // 13: T and M128 - the programmed orientation.
    EXPECT_TRUE(ln[1].has_tool_vector);
    EXPECT_TRUE(ln[1].tool_vector_programmed);
    expect_near(ln[1].tool_vector, t, 1e-15);
    // 14: no T, M128 - perpendicular to the contour.
    EXPECT_TRUE(ln[2].has_tool_vector);
    EXPECT_FALSE(ln[2].tool_vector_programmed);
    expect_near(ln[2].tool_vector, n, 1e-15);
    const auto tcpm = only<TcpmChange>(ev);
    ASSERT_EQ(tcpm.size(), 2U);  // M128 in block 13 (14 repeats it), M129 in block 15
    EXPECT_TRUE(tcpm[0].on);
    EXPECT_FALSE(tcpm[1].on);
}

TEST(KlartextLn, WithoutTcpmAProgrammedTIsIgnored) {
    const auto ln = only<VectorLineMove>(
        events_of(pgm("2 LN X+1 Y+0 Z+0 NX+0 NY+0 NZ+1 TX+0 TY+0.6 TZ+0.8\n")));
    ASSERT_EQ(ln.size(), 1U);
    EXPECT_FALSE(ln[0].has_tool_vector);
    EXPECT_TRUE(ln[0].tool_vector_programmed);
}

// [TNC-3D]'s peripheral-milling example (examples/3d_peripheral.h): the three variants.
TEST(KlartextLn, Tnc3dPeripheralMillingExample) {
    const ToolTable table = example_tools();
    const auto ev = run_file(kExamples + "/3d_peripheral.h", &table);
    // 11: L with rotary axes, M128, RL.
    const auto heads = only<HeadOrientation>(ev);
    ASSERT_EQ(heads.size(), 1U);
    EXPECT_EQ(heads[0].b, -20.0115);
    EXPECT_EQ(heads[0].c, -267.9784);
    const auto comp = only<CompensationChange>(ev);
    ASSERT_EQ(comp.size(), 2U);
    EXPECT_EQ(comp[0].side, Compensation::kLeft);
    EXPECT_EQ(comp[1].side, Compensation::kOff);
    const auto ln = only<VectorLineMove>(ev);
    ASSERT_EQ(ln.size(), 2U);
    // 12: T perpendicular to N.
    EXPECT_TRUE(ln[0].has_normal);
    EXPECT_TRUE(ln[0].has_tool_vector);
    EXPECT_NEAR(ln[0].normal.dot(ln[0].tool_vector), 0.0, 1e-4);
    EXPECT_NEAR(ln[0].normal.norm(), 1.0, 1e-15);
    // 13: T without N.
    EXPECT_FALSE(ln[1].has_normal);
    EXPECT_TRUE(ln[1].has_tool_vector);
    expect_near(ln[1].tool_vector, V(-0.0807, -0.3409, 0.9366).normalized(), 1e-15);
    EXPECT_EQ(ln[1].feed, 500.0);
}

TEST(KlartextLn, Tnc3dSyntaxExampleIsRefusedBecauseItsVectorsAreNotNormalised) {
    // [TNC-3D], "Gerade LN", Eingabe (decimal commas and the typeset dash written as in a
    // file): |N| = 0.9152961, |T| = 0.9139454.
    EXPECT_EQ(error_of(pgm("2 LN X+31.737 Y+21.954 Z+33.165 NX+0.2637581 NY+0.0078922 "
                           "NZ-0.8764339 TX+0.0078922 TY-0.8764339 TZ+0.2590319 F1000 M128\n")),
              "prog.nc:3:33: the surface normal N (NX NY NZ) is not normalised: its length is "
              "0.9152961, not 1 (tolerance 0.0001)");
}

TEST(KlartextLn, NonNormalisedToolVectorIsRefused) {
    EXPECT_EQ(error_of(pgm("2 LN X+0 Y+0 Z+0 NX+0 NY+0 NZ+1 TX+0 TY+0 TZ+1.0002 M128\n")),
              "prog.nc:3:33: the tool vector T (TX TY TZ) is not normalised: its length is "
              "1.0002000, not 1 (tolerance 0.0001)");
    // Within the tolerance: accepted and made unit.
    const auto ln = only<VectorLineMove>(
        events_of(pgm("2 LN X+0 Y+0 Z+0 NX+0 NY+0 NZ+1 TX+0 TY+0 TZ+1.00009 M128\n")));
    ASSERT_EQ(ln.size(), 1U);
    EXPECT_EQ(ln[0].tool_vector, V(0, 0, 1));
}

TEST(KlartextLn, EveryCoordinateMustBePresent) {
    EXPECT_EQ(error_of(pgm("2 LN X+1 Y+2 NX+0 NY+0 NZ+1\n")),
              "prog.nc:3:3: LN needs all coordinates X Y Z, even when unchanged: Z is missing");
    EXPECT_EQ(error_of(pgm("2 LN Z+1 NX+0 NY+0 NZ+1\n")),
              "prog.nc:3:3: LN needs all coordinates X Y Z, even when unchanged: X Y are missing");
}

TEST(KlartextLn, EveryNormalComponentMustBePresent) {
    EXPECT_EQ(error_of(pgm("2 LN X+1 Y+2 Z+0 NX+0 NY+1\n")),
              "prog.nc:3:3: LN needs all three components of the surface normal N NX NY NZ: NZ is "
              "missing");
    EXPECT_EQ(error_of(pgm("2 LN X+1 Y+2 Z+0 NY+1\n")),
              "prog.nc:3:3: LN needs all three components of the surface normal N NX NY NZ: NX NZ "
              "are missing");
}

TEST(KlartextLn, EveryToolVectorComponentMustBePresent) {
    EXPECT_EQ(error_of(pgm("2 LN X+1 Y+2 Z+0 NX+0 NY+0 NZ+1 TX+0 TZ+1 M128\n")),
              "prog.nc:3:3: LN needs all three components of the tool vector T TX TY TZ: TY is "
              "missing");
}

TEST(KlartextLn, WordsComeInTheOrderOfTnc3d) {
    EXPECT_EQ(error_of(pgm("2 LN Y+2 X+1 Z+0 NX+0 NY+0 NZ+1\n")),
              "prog.nc:3:10: 'X' after 'Y': LN words must come in the order X Y Z NX NY NZ TX TY "
              "TZ");
    EXPECT_EQ(error_of(pgm("2 LN X+1 Y+2 Z+0 TX+0 TY+0 TZ+1 NX+0 NY+0 NZ+1 M128\n")),
              "prog.nc:3:33: 'NX' after 'TZ': LN words must come in the order X Y Z NX NY NZ TX "
              "TY TZ");
}

TEST(KlartextLn, WithoutNormalOnlyPeripheralMillingWithTAndTcpm) {
    EXPECT_EQ(error_of(pgm("2 LN X+1 Y+2 Z+0\n")),
              "prog.nc:3:3: LN needs the surface normal NX NY NZ (only peripheral milling with TX "
              "TY TZ under M128 or FUNCTION TCPM may leave it out)");
    EXPECT_EQ(error_of(pgm("2 LN X+1 Y+2 Z+0 TX+0 TY+0 TZ+1\n")),
              "prog.nc:3:3: LN without NX NY NZ needs M128 or FUNCTION TCPM (peripheral milling "
              "with the tool vector T)");
}

TEST(KlartextLn, NormalAgainstToolVectorIsRefusedUnderTcpm) {
    EXPECT_EQ(error_of(pgm("2 LN X+1 Y+2 Z+0 NX+0 NY+0 NZ-1 TX+0 TY+0 TZ+1 M128\n")),
              "prog.nc:3:18: the surface normal N points against the tool vector T (N.T = "
              "-1.0000): the tool cannot touch the surface from this side");
}

TEST(KlartextLn, AbsoluteCoordinatesOnly) {
    EXPECT_EQ(error_of(pgm("2 LN IX+1 Y+2 Z+0 NX+0 NY+0 NZ+1\n")),
              "prog.nc:3:6: 'IX': LN takes absolute coordinates only");
}

TEST(KlartextLn, FeedFmaxAndRadiusCompensation) {
    const auto ln = only<VectorLineMove>(events_of(
        pgm("2 LN X+1 Y+0 Z+0 NX+0 NY+0 NZ+1 RL F250\n3 LN X+2 Y+0 Z+0 NX+0 NY+0 NZ+1 FMAX\n")));
    ASSERT_EQ(ln.size(), 2U);
    EXPECT_EQ(ln[0].feed, 250.0);
    EXPECT_FALSE(ln[0].rapid);
    EXPECT_EQ(ln[0].side, Compensation::kLeft);
    EXPECT_TRUE(ln[1].rapid);
    EXPECT_EQ(ln[1].feed, 0.0);
    EXPECT_EQ(ln[1].side, Compensation::kLeft);
    expect_near(ln[1].start, V(1, 0, 0));
}

// ---- TCPM, PROG PATH, M107 ----

TEST(KlartextTcpm, FunctionTcpmWithReferencePoint) {
    const auto tcpm = only<TcpmChange>(events_of(
        pgm("2 FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS REFPNT CNT-CNT\n"
            "3 FUNCTION TCPM REFPNT TIP-CENTER\n4 FUNCTION RESET TCPM\n5 M128\n6 M129\n")));
    ASSERT_EQ(tcpm.size(), 5U);
    EXPECT_TRUE(tcpm[0].on);
    EXPECT_EQ(tcpm[0].reference, ToolReference::kCentre);
    EXPECT_EQ(tcpm[1].reference, ToolReference::kTip);
    EXPECT_FALSE(tcpm[2].on);
    EXPECT_TRUE(tcpm[3].on);
    EXPECT_EQ(tcpm[3].reference, ToolReference::kTip);
    EXPECT_FALSE(tcpm[4].on);
}

TEST(KlartextTcpm, OptionErrors) {
    EXPECT_EQ(error_of(pgm("2 FUNCTION TCPM REFPNT CNT-TIP\n")),
              "prog.nc:3:24: unknown REFPNT 'CNT-TIP' (known: TIP-TIP, TIP-CENTER, CENTER-CENTER; "
              "CNT for CENTER)");
    EXPECT_EQ(error_of(pgm("2 FUNCTION TCPM F FAST\n")),
              "prog.nc:3:17: unknown FUNCTION TCPM option 'F FAST' (known: F TCP|CONT, AXIS "
              "POS|SPAT, PATHCTRL AXIS|VECTOR, REFPNT TIP-TIP|TIP-CENTER|CENTER-CENTER)");
    EXPECT_EQ(error_of(pgm("2 L X+1 M128 M129\n")),
              "prog.nc:3:14: M128 and M129 in one block: they exclude each other");
}

TEST(KlartextProgPath, IsContourOrOffAndModal) {
    const auto ev =
        events_of(pgm("2 FUNCTION PROG PATH IS CONTOUR\n3 FUNCTION PROG PATH IS CONTOUR\n"
                      "4 FUNCTION PROG PATH OFF\n5 FUNCTION PROG PATH IS CONTOUR\n"
                      "6 FUNCTION PROG PATH IS OFF\n"));
    const auto pp = only<ProgPathChange>(ev);
    ASSERT_EQ(pp.size(), 4U);  // block 3 changes nothing
    EXPECT_TRUE(pp[0].contour);
    EXPECT_FALSE(pp[1].contour);
    EXPECT_TRUE(pp[2].contour);
    EXPECT_FALSE(pp[3].contour);
    EXPECT_EQ(error_of(pgm("2 FUNCTION PROG PATH IS\n")),
              "prog.nc:3:22: expected 'IS CONTOUR' or 'OFF' after 'FUNCTION PROG PATH'");
}

// ---- TOOL CALL and the oversize rule ----

TEST(KlartextToolCall, SelectsTheToolAndSendsTheCallDeltas) {
    const auto ev = events_of(pgm("2 TOOL CALL 5 Z S8000 DL-0.5 DR+0 DR2-0.05\n3 TOOL CALL 6\n"));
    const auto sel = only<ToolSelect>(ev);
    const auto calls = only<ToolCallDeltas>(ev);
    ASSERT_EQ(sel.size(), 2U);
    ASSERT_EQ(calls.size(), 2U);
    EXPECT_EQ(sel[0].tool, 5);
    EXPECT_EQ(calls[0].tool, 5);
    EXPECT_EQ(calls[0].dl, -0.5);
    EXPECT_EQ(calls[0].dr, 0.0);
    EXPECT_EQ(calls[0].dr2, -0.05);
    EXPECT_EQ(calls[0].spindle_speed, 8000.0);
    // A call without deltas resets them.
    EXPECT_EQ(calls[1].tool, 6);
    EXPECT_EQ(calls[1].dl, 0.0);
    EXPECT_EQ(calls[1].dr2, 0.0);
}

TEST(KlartextToolCall, PositiveOversizeIsAnErrorWithoutM107) {
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 3 Z DL+0.2 DR+0.2 DR2+0.2\n")),
              "prog.nc:3:3: TOOL CALL 3 with a positive oversize (summed DL +0.2000, DR +0.2000, "
              "DR2 +0.2000 mm): program M107 before the TOOL CALL to allow it");
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 3 Z DR2+0.01\n")),
              "prog.nc:3:3: TOOL CALL 3 with a positive oversize (summed DL +0.0000, DR +0.0000, "
              "DR2 +0.0100 mm): program M107 before the TOOL CALL to allow it");
}

TEST(KlartextToolCall, M107AllowsAPositiveOversize) {
    const auto ev = events_of(pgm("2 M107\n3 TOOL CALL 3 Z DL+0.2 DR+0.2 DR2+0.2\n"));
    const auto ov = only<OversizeChange>(ev);
    ASSERT_EQ(ov.size(), 1U);
    EXPECT_TRUE(ov[0].allowed);
    EXPECT_EQ(only<ToolCallDeltas>(ev).size(), 1U);
}

TEST(KlartextToolCall, M108WhileAnOversizeToolIsLoadedIsAnError) {
    EXPECT_EQ(error_of(pgm("2 M107\n3 TOOL CALL 3 Z DR+0.2\n4 M108\n")),
              "prog.nc:5:3: M108 while tool 3 with a positive oversize is loaded: call a tool "
              "without oversize first");
    const auto ov = only<OversizeChange>(
        events_of(pgm("2 M107\n3 TOOL CALL 3 Z DR+0.2\n4 TOOL CALL 4 Z\n5 M108\n")));
    ASSERT_EQ(ov.size(), 2U);
    EXPECT_FALSE(ov[1].allowed);
}

TEST(KlartextToolCall, ToolListAndCallDeltasAreSummed) {
    const ToolTable t = tools(
        "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 3\nwz[1].r2 3\nwz[1].dr -0.1\n"
        "wz[1].dr2 -0.1\n");
    InterpreterOptions opt;
    opt.tools = &t;
    // Reground by 0.1, called with +0.05: smaller than the table tool, no oversize.
    EXPECT_TRUE(error_of(pgm("2 TOOL CALL 1 Z DR+0.05 DR2+0.05\n"), opt).empty());
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 1 Z DR+0.15 DR2+0.15\n"), opt),
              "prog.nc:3:3: TOOL CALL 1 with a positive oversize (summed DL +0.0000, DR +0.0500, "
              "DR2 +0.0500 mm): program M107 before the TOOL CALL to allow it");
}

TEST(KlartextToolCall, ToolShapeMustExist) {
    const ToolTable t = tools(
        "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 3\nwz[1].r2 3.5\n"
        "wz[2].gueltig 1\nwz[2].mass_einheit 1\nwz[2].radius 3\nwz[2].r2 3\n"
        "wz[3].gueltig 0\n");
    InterpreterOptions opt;
    opt.tools = &t;
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 1 Z\n"), opt),
              "prog.nc:3:13: TOOL CALL 1: corner radius R2 3.5000 mm is larger than the radius R "
              "3.0000 mm in the tool list");
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 2 Z DR-0.1\n"), opt),
              "prog.nc:3:3: TOOL CALL 2: R2 + DR2 = 3.0000 mm is larger than R + DR = 2.9000 mm: "
              "no such tool");
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 2 Z DR-3.5 DR2-3.5\n"), opt),
              "prog.nc:3:3: TOOL CALL 2: R + DR = -0.5000 mm, R2 + DR2 = -0.5000 mm: the deltas "
              "take away more than the tool has");
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 3 Z\n"), opt),
              "prog.nc:3:13: TOOL CALL 3: tool 3 is not valid (wz[3].gueltig is 0, not 1; unset "
              "data is 0)");
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 9 Z\n"), opt),
              "prog.nc:3:13: TOOL CALL 9: the tool list does not define tool 9");
    EXPECT_EQ(undefined_of(pgm("2 TOOL CALL 9 Z\n"), opt), Undefined::kTool);
    EXPECT_EQ(undefined_of(pgm("2 TOOL CALL 3 Z\n"), opt), Undefined::kNothing);
}

TEST(KlartextToolCall, SyntaxAndRules) {
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 1 X\n")),
              "prog.nc:3:15: tool axis X: only Z is supported (the documented head tilts the Z "
              "tool axis)");
    EXPECT_EQ(
        error_of(pgm("2 TOOL CALL 1 Z DR20.1\n")),
        "prog.nc:3:17: ambiguous 'DR2...': write the sign, DR2+0.1 for DR2 or DR+2... for DR");
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 1024 Z\n")),
              "prog.nc:3:13: tool number 1024 out of range 0..1023");
    EXPECT_EQ(error_of(pgm("2 TOOL CALL \"MILL\" Z\n")),
              "prog.nc:3:13: tools are called by number (TOOL CALL 5 Z), not by name");
    EXPECT_EQ(error_of(pgm("2 TOOL CALL 1 Z R+3\n")),
              "prog.nc:3:17: unknown word 'R' in TOOL CALL (known: the tool axis Z, S, F, DL, DR, "
              "DR2)");
    EXPECT_EQ(error_of(pgm("2 L X+1 RL\n3 TOOL CALL 1 Z\n")),
              "prog.nc:4:3: TOOL CALL 1 while radius compensation RL is on: program R0 in an "
              "earlier block");
}

// ---- [TNC-3D]'s allowance example as a whole program ----

TEST(Klartext, Tnc3dAllowanceExampleRunsWithM107AndCentreReference) {
    const ToolTable table = example_tools();
    const auto ev = run_file(kExamples + "/3d_allowance.h", &table);
    const auto calls = only<ToolCallDeltas>(ev);
    ASSERT_EQ(calls.size(), 1U);
    EXPECT_EQ(calls[0].dr, 0.2);
    const auto tcpm = only<TcpmChange>(ev);
    ASSERT_EQ(tcpm.size(), 2U);
    EXPECT_EQ(tcpm[0].reference, ToolReference::kCentre);
    const auto ln = only<VectorLineMove>(ev);
    ASSERT_EQ(ln.size(), 4U);
    expect_near(ln[0].tool_vector, ln[0].normal);  // no T: perpendicular to the contour
    expect_near(ln[2].tool_vector, V(0, 0, 1));
    // Without M107 the same program is refused at the TOOL CALL.
    InterpreterOptions opt;
    opt.tools = &table;
    Result<Program> p = Program::load(kExamples + "/3d_allowance.h", opt);
    ASSERT_TRUE(p);
    EXPECT_EQ(p.value().summary().moves, 6U);
}

TEST(Klartext, EventOrderInOneBlock) {
    const auto ev = events_of(pgm("2 L X+5 B+10 RL M107 M128 M30\n"));
    ASSERT_EQ(ev.size(), 7U);
    EXPECT_EQ(event_name(ev[1].data), "oversize");
    EXPECT_EQ(event_name(ev[2].data), "tcpm");
    EXPECT_EQ(event_name(ev[3].data), "compensation");
    EXPECT_EQ(event_name(ev[4].data), "head");
    EXPECT_EQ(event_name(ev[5].data), "line");
    EXPECT_EQ(event_name(ev[6].data), "end");
}

TEST(Klartext, AFailedBlockChangesNoState) {
    KlartextInterpreter in;
    KlartextBlock b;
    Diagnostic err;
    EventBatch out;
    ASSERT_TRUE(parse_klartext_line("0 BEGIN PGM A MM", 1, "p", b, err));
    ASSERT_TRUE(in.apply(b, "p", out, err));
    ASSERT_TRUE(parse_klartext_line("1 L X+1 RL M128 F100", 2, "p", b, err));
    ASSERT_TRUE(in.apply(b, "p", out, err));
    const KlartextState before = in.state();
    ASSERT_TRUE(
        parse_klartext_line("2 LN X+2 Y+0 Z+0 NX+0 NY+0 NZ+0.5 M129 M107 R0 F5", 3, "p", b, err));
    EXPECT_FALSE(in.apply(b, "p", out, err));
    EXPECT_TRUE(out.empty());
    const KlartextState& after = in.state();
    EXPECT_EQ(after.position, before.position);
    EXPECT_EQ(after.tcpm, before.tcpm);
    EXPECT_EQ(after.m107, before.m107);
    EXPECT_EQ(after.radius_comp, before.radius_comp);
    EXPECT_EQ(after.feed, before.feed);
}

TEST(Klartext, TolerancesAreTheBoardsOwn) {
    EXPECT_EQ(kVectorLengthTolerance, rwmos::comp3d::kUnitVectorTolerance);
    EXPECT_EQ(kNormalAgainstToolTolerance, rwmos::comp3d::kNormalAgainstToolTolerance);
}

// [TNC-3D], "Gerade LN": "F, FMAX, FZ, FU oder F AUTO". FZ is per tooth (x the tool's teeth,
// the TNC tool table's CUT, wz[n].cut, x S), FU per revolution (x S), F AUTO the TOOL CALL's F;
// each modal, turned into mm/min at every move with the S and the tool in force then.
TEST(KlartextFeeds, FzFuAndFAutoBecomeFeedsInMillimetresPerMinute) {
    const ToolTable t = tools("wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n"
                              "wz[1].cut 4\nwz[2].gueltig 1\nwz[2].cut 2\n");
    InterpreterOptions o;
    o.tools = &t;
    const auto ev = events_of(
        "0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000 F300\n2 L X+10 Y+0 Z+0 R0 FZ0.05\n"
        "3 L X+20 FU0.2\n4 L X+30 F AUTO\n5 L X+40 F600\n6 L X+50 FZ0.1\n"
        "7 TOOL CALL 2 Z S500\n8 L X+60\n10 END PGM T MM\n",
        o);
    std::vector<double> feeds;
    for (const auto& l : only<LineMove>(ev)) feeds.push_back(l.feed);
    // 0.05 x 4 x 1000; 0.2 x 1000; F300 of the call; F600; 0.1 x 4 x 1000; the new tool's two
    // teeth at S500: 0.1 x 2 x 500.
    EXPECT_EQ(feeds, (std::vector<double>{200.0, 200.0, 300.0, 600.0, 400.0, 100.0}));
}

TEST(KlartextFeeds, WhatAFeedNeedsIsNamedWhereItIsMissing) {
    const ToolTable t = tools("wz[1].gueltig 1\nwz[2].gueltig 1\nwz[2].cut 3\n");
    InterpreterOptions o;
    o.tools = &t;
    const auto prog = [](std::string_view call, std::string_view move) {
        return "0 BEGIN PGM T MM\n1 " + std::string(call) + "\n2 L X+1 Y+0 Z+0 R0 " +
               std::string(move) + "\n3 END PGM T MM\n";
    };
    EXPECT_EQ(error_of(prog("TOOL CALL 2 Z", "FZ0.1"), o),
              "prog.nc:3:20: FZ0.1 needs the spindle speed: give S in the TOOL CALL (TOOL CALL 2 "
              "Z S..)");
    EXPECT_EQ(error_of(prog("TOOL CALL 2 Z", "FU0.1"), o),
              "prog.nc:3:20: FU0.1 needs the spindle speed: give S in the TOOL CALL (TOOL CALL 2 "
              "Z S..)");
    EXPECT_EQ(error_of(prog("TOOL CALL 1 Z S100", "FZ0.1"), o),
              "prog.nc:3:20: FZ0.1 needs the number of teeth of tool 1: the tool list does not "
              "give it (wz[1].cut, the TNC tool table's CUT)");
    EXPECT_EQ(error_of(prog("TOOL CALL 0 Z S100", "FZ0.1")),
              "prog.nc:3:20: FZ0.1 needs the number of teeth of the tool in force, and no tool is "
              "called: program TOOL CALL first");
    EXPECT_EQ(error_of(prog("TOOL CALL 2 Z S100", "F AUTO"), o),
              "prog.nc:3:20: F AUTO takes the feed of the TOOL CALL, and TOOL CALL 2 gives none: "
              "program F in the TOOL CALL");
    EXPECT_EQ(error_of(prog("TOOL CALL 2 Z S100", "FZ0.1"), o), "");
    EXPECT_EQ(error_of(prog("TOOL CALL 2 Z S100 F50", "F AUTO"), o), "");
    EXPECT_EQ(error_of(prog("TOOL CALL 2 Z S100 F0", "F AUTO"), o),
              "prog.nc:2:22: feed rate F must be greater than 0");
    EXPECT_EQ(error_of(prog("TOOL CALL 2 Z S100", "FZ0"), o),
              "prog.nc:3:22: feed rate FZ must be greater than 0");
    EXPECT_EQ(error_of(prog("TOOL CALL 2 Z S100", "FZ0.1 F AUTO"), o),
              "prog.nc:3:26: two feeds in one block (F, FMAX, FZ, FU, F AUTO): give one");
    EXPECT_EQ(error_of(prog("TOOL CALL 2 Z S100", "F AUTOX"), o),
              "prog.nc:3:22: expected a number or AUTO after 'F'");
}

}  // namespace
}  // namespace apci::nc
