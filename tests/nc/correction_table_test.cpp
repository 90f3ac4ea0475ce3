// SPDX-License-Identifier: MIT
// The 3D compensation's correction table ([TNC-3D]: the delta values are summed "aus der
// Werkzeugverwaltung, dem Werkzeugaufruf und den Korrekturtabellen"): the table file
// (apci/nc/correction_table.h) and its selection in Klartext programs, FUNCTION CORRDATA TCS #n
// / FUNCTION CORRDATA RESET TCS, with the tool checks over the summed deltas.
// docs/nc-programs.md ("Correction table"). One test per rule.
#include "apci/nc/correction_table.h"

#include <gtest/gtest.h>

#include <string>

#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "nc_test_util.h"

namespace apci::nc {
namespace {

using test::only;

const std::string kExamples = APCI_EXAMPLES_DIR;

std::string table_error(std::string_view text) {
    Result<CorrectionTable> t = parse_correction_table(text, "t.corr");
    return t ? std::string() : t.error().to_string();
}

CorrectionTable table(std::string_view text) {
    Result<CorrectionTable> t = parse_correction_table(text, "t.corr");
    EXPECT_TRUE(t) << t.error().to_string();
    return t ? t.value() : CorrectionTable{};
}

ToolTable tnc3d_tools() {
    Result<ToolTable> t = load_tool_table(kExamples + "/tools/3d_tools.tools");
    EXPECT_TRUE(t) << t.error().to_string();
    return t ? t.value() : ToolTable{};
}

// A program around the given blocks.
std::string pgm(std::string_view blocks) {
    return "0 BEGIN PGM T MM\n1 L X+0 Y+0 Z+0 R0 F1000\n" + std::string(blocks) +
           "99 END PGM T MM\n";
}

struct Tables {
    ToolTable tools = tnc3d_tools();
    CorrectionTable corr = table("corr[1].dr -0.1\ncorr[1].dr2 -0.1\ncorr[2].dr 0.2\n");
    InterpreterOptions options() const {
        InterpreterOptions o;
        o.tools = &tools;
        o.corrections = &corr;
        return o;
    }
};

// ---- the table file

TEST(CorrectionTableFile, RowsHoldDlDrDr2InMillimetres) {
    const CorrectionTable t =
        table("# comment\n\ncorr[7].dl 0.25   # trailing\ncorr[2].dr2 -.05\n  corr[7].dr -0.1\n");
    ASSERT_EQ(t.rows().size(), 2u);
    EXPECT_EQ(t.rows()[0].row, 2);  // ordered by row
    EXPECT_EQ(t.rows()[0].dr2, -0.05);
    EXPECT_EQ(t.rows()[0].dl, 0.0);  // unset values are 0
    const CorrectionRow* r = t.find(7);
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->dl, 0.25);
    EXPECT_EQ(r->dr, -0.1);
    EXPECT_EQ(t.find(1), nullptr);
    EXPECT_EQ(t.find(0), nullptr);
}

TEST(CorrectionTableFile, TheExampleTableLoads) {
    Result<CorrectionTable> t = load_correction_table(kExamples + "/tools/3d_corrections.corr");
    ASSERT_TRUE(t) << t.error().to_string();
    ASSERT_NE(t.value().find(1), nullptr);
    EXPECT_EQ(t.value().find(1)->dr, -0.1);
    EXPECT_EQ(t.value().find(2)->dl, 0.2);
}

TEST(CorrectionTableFile, ErrorsNameLineColumnAndWhatWasWrong) {
    EXPECT_EQ(table_error("corr[1].dr -0.1\nwz[1].dr 1\n"),
              "t.corr:2:1: expected 'corr[n].dl|dr|dr2 value' or a '#' comment");
    EXPECT_EQ(table_error("corr[0].dr 1\n"),
              "t.corr:1:6: correction row 0 out of range 1..1023 (row 0 is no correction: "
              "FUNCTION CORRDATA RESET TCS)");
    EXPECT_EQ(table_error("corr[1024].dr 1\n"),
              "t.corr:1:6: correction row 1024 out of range 1..1023 (row 0 is no correction: "
              "FUNCTION CORRDATA RESET TCS)");
    EXPECT_EQ(table_error("corr[x].dr 1\n"), "t.corr:1:6: expected a row number after '['");
    EXPECT_EQ(table_error("corr[1].r2 1\n"),
              "t.corr:1:9: unknown correction field 'r2' (known: dl, dr, dr2)");
    EXPECT_EQ(table_error("corr[1].dr\n"), "t.corr:1:11: expected a value after 'corr[1].dr'");
    EXPECT_EQ(table_error("corr[1].dr 1 2\n"),
              "t.corr:1:14: unexpected text after the value of corr[1].dr");
    EXPECT_EQ(table_error("corr[1].dr 100000.5\n"),
              "t.corr:1:12: corr[1].dr 100000.5 out of range -100000..100000 mm");
    EXPECT_EQ(table_error("corr[3].dl 1\ncorr[3].dl 2\n"),
              "t.corr:2:9: corr[3].dl set twice (first on line 1)");
}

// ---- FUNCTION CORRDATA in Klartext programs

TEST(CorrData, SelectsARowAndResetLeavesTheTable) {
    const Tables r;
    const auto ev = test::events_of(
        pgm("2 TOOL CALL 3 Z\n3 FUNCTION CORRDATA TCS #1\n4 FUNCTION CORRDATA RESET TCS\n"
            "5 M107\n6 FUNCTION  CORRDATA  TCS  #2 ; comment\n"),
        r.options());
    const auto sel = only<CorrectionSelect>(ev);
    ASSERT_EQ(sel.size(), 3u);
    EXPECT_EQ(sel[0].row, 1);
    EXPECT_EQ(sel[1].row, 0);
    EXPECT_EQ(sel[2].row, 2);
    for (const Event& e : ev) {
        if (std::holds_alternative<CorrectionSelect>(e.data)) {
            EXPECT_EQ(event_name(e.data), "correction_row");
        }
    }
}

TEST(CorrData, RowMustBeInTheTable) {
    const Tables r;
    EXPECT_EQ(test::error_of(pgm("2 FUNCTION CORRDATA TCS #5\n"), r.options()),
              "prog.nc:3:26: FUNCTION CORRDATA TCS #5: the correction table does not define "
              "row 5");
    EXPECT_EQ(test::undefined_of(pgm("2 FUNCTION CORRDATA TCS #5\n"), r.options()),
              Undefined::kCorrectionRow);
    EXPECT_EQ(test::undefined_of(pgm("2 TOOL CALL 9 Z\n"), r.options()), Undefined::kTool);
    // Without a table any row 1..1023 is taken (its deltas are the board's).
    EXPECT_EQ(test::error_of(pgm("2 FUNCTION CORRDATA TCS #5\n")), "");
}

TEST(CorrData, SyntaxErrorsSayWhatWasExpected) {
    EXPECT_EQ(test::error_of(pgm("2 FUNCTION CORRDATA TCS 5\n")),
              "prog.nc:3:25: expected '#' and the row number after 'FUNCTION CORRDATA TCS'");
    EXPECT_EQ(test::error_of(pgm("2 FUNCTION CORRDATA TCS #0\n")),
              "prog.nc:3:26: correction row 0 out of range 1..1023 (FUNCTION CORRDATA RESET TCS "
              "leaves the table)");
    EXPECT_EQ(test::error_of(pgm("2 FUNCTION CORRDATA TCS #1024\n")),
              "prog.nc:3:26: correction row 1024 out of range 1..1023 (FUNCTION CORRDATA RESET "
              "TCS leaves the table)");
    EXPECT_EQ(test::error_of(pgm("2 FUNCTION CORRDATA XYZ\n")),
              "prog.nc:3:21: expected 'TCS #n' or 'RESET TCS' after 'FUNCTION CORRDATA'");
    EXPECT_EQ(test::error_of(pgm("2 FUNCTION CORRDATA WPL #1\n")),
              "prog.nc:3:21: FUNCTION CORRDATA WPL (workpiece corrections) is not emulated: only "
              "TCS, the correction table of the tool's delta values");
    EXPECT_EQ(test::error_of(pgm("2 FUNCTION CORRDATA RESET TCS #1\n")),
              "prog.nc:3:31: unexpected '#' after FUNCTION CORRDATA RESET TCS");
}

// [TNC-3D]: a positive oversize is an error unless M107 allows it, whichever of tool table,
// tool call and correction table brings it; the board checks the same at CorrectionRow.
TEST(CorrData, RowThatGivesAPositiveOversizeNeedsM107) {
    const Tables r;
    EXPECT_EQ(test::error_of(pgm("2 TOOL CALL 3 Z\n3 FUNCTION CORRDATA TCS #2\n"), r.options()),
              "prog.nc:4:3: FUNCTION CORRDATA TCS #2 (tool 3) with a positive oversize (summed DL "
              "+0.0000, DR +0.2000, DR2 +0.0000 mm): program M107 before FUNCTION CORRDATA to "
              "allow it");
    // The row in force counts at the next TOOL CALL too.
    EXPECT_EQ(test::error_of(pgm("2 M107\n3 FUNCTION CORRDATA TCS #2\n4 M108\n5 TOOL CALL 3 Z\n"),
                             r.options()),
              "prog.nc:6:3: TOOL CALL 3 with a positive oversize (summed DL +0.0000, DR +0.2000, "
              "DR2 +0.0000 mm): program M107 before the TOOL CALL to allow it");
    // With M107 it runs, and M108 is refused while the oversize is loaded.
    EXPECT_EQ(
        test::error_of(pgm("2 M107\n3 TOOL CALL 3 Z\n4 FUNCTION CORRDATA TCS #2\n"), r.options()),
        "");
    EXPECT_EQ(test::error_of(pgm("2 M107\n3 TOOL CALL 3 Z\n4 FUNCTION CORRDATA TCS #2\n5 M108\n"),
                             r.options()),
              "prog.nc:6:3: M108 while tool 3 with a positive oversize is loaded: call a tool "
              "without oversize first");
    // Leaving the row takes the oversize away.
    EXPECT_EQ(test::error_of(pgm("2 M107\n3 TOOL CALL 3 Z\n4 FUNCTION CORRDATA TCS #2\n"
                                 "5 FUNCTION CORRDATA RESET TCS\n6 M108\n"),
                             r.options()),
              "");
}

// A row's negative deltas with the tool's make the tool checks as a TOOL CALL's do.
TEST(CorrData, RowDeltasJoinTheToolChecks) {
    Tables r;
    r.corr = table("corr[4].dr -3.5\n");
    EXPECT_EQ(test::error_of(pgm("2 TOOL CALL 3 Z\n3 FUNCTION CORRDATA TCS #4\n"), r.options()),
              "prog.nc:4:3: FUNCTION CORRDATA TCS #4 (tool 3): R + DR = -0.5000 mm, R2 + DR2 = "
              "3.0000 mm: the deltas take away more than the tool has");
}

// The example programs through the front end: the correction table example names rows of
// its table.
TEST(CorrData, TheExampleProgramValidates) {
    const ToolTable tools = tnc3d_tools();
    Result<CorrectionTable> corr = load_correction_table(kExamples + "/tools/3d_corrections.corr");
    ASSERT_TRUE(corr);
    InterpreterOptions o;
    o.tools = &tools;
    o.corrections = &corr.value();
    Result<Program> p = Program::load(kExamples + "/3d_correction_table.h", o);
    ASSERT_TRUE(p) << p.error().to_string();
    Result<EventStream> s = p.value().events();
    ASSERT_TRUE(s);
    std::vector<int> rows;
    Event ev;
    while (s.value().next(ev) == EventStream::Next::kEvent)
        if (const auto* c = std::get_if<CorrectionSelect>(&ev.data)) rows.push_back(c->row);
    EXPECT_EQ(rows, (std::vector<int>{1, 0}));
}

}  // namespace
}  // namespace apci::nc
