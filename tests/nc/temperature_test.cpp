// SPDX-License-Identifier: MIT
// The setting data of the temperature compensation in tool direction ([SIN-TEMP], SINUMERIK
// 840D FB1 W1 section 2.8: SD 42960 TOOL_TEMP_COMP[0..2], "mittels Synchronaktionen oder von
// der PLC aus vom Anwender beschrieben") written from DIN 66025 programs as
// $SC_TOOL_TEMP_COMP[i] = expr; docs/nc-programs.md ("Variables"). One test per rule.
#include <gtest/gtest.h>

#include <string>

#include "apci/nc/program.h"
#include "nc_test_util.h"

namespace apci::nc {
namespace {

using test::error_of;
using test::events_of;
using test::only;

// The write is an event of its own block, between the moves before and after it, so the
// executor can act on it at its place in the program.
TEST(TemperatureSettingData, WriteIsAnEventAtItsPlaceInTheBlockSequence) {
    const auto ev =
        events_of("N10 G1 X10 F100\nN20 $SC_TOOL_TEMP_COMP[2] = 0.02\nN30 G1 X20\nN40 M30\n");
    ASSERT_EQ(ev.size(), 4u);
    EXPECT_TRUE(std::holds_alternative<LineMove>(ev[0].data));
    const auto* w = std::get_if<VariableWrite>(&ev[1].data);
    ASSERT_NE(w, nullptr);
    EXPECT_EQ(w->variable, (VariableRef{NcVariable::kToolTempComp, 2}));
    EXPECT_EQ(w->value, 0.02);
    EXPECT_EQ(ev[1].origin.block, 20);
    EXPECT_EQ(ev[1].origin.line, 2u);
    EXPECT_TRUE(std::holds_alternative<LineMove>(ev[2].data));
    EXPECT_EQ(event_name(ev[1].data), "variable_write");
}

// Every component 0..2, without an N number, in lower case, with an expression.
TEST(TemperatureSettingData, EachComponentTakesAnExpression) {
    const auto w = only<VariableWrite>(events_of(
        "P1 = 0.01\n$SC_TOOL_TEMP_COMP[0] = P1 * 2\n$sc_tool_temp_comp[ 1 ]=-[P1 + 0.005]\n"
        "N5 $SC_TOOL_TEMP_COMP[2] = SQRT[4] / 100 ; comment\nM30\n"));
    ASSERT_EQ(w.size(), 3u);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(w[static_cast<std::size_t>(i)].variable.index, i);
    EXPECT_EQ(w[0].value, 0.02);
    EXPECT_EQ(w[1].value, -0.015);
    EXPECT_EQ(w[2].value, 0.02);
}

// Expressions read the setting datum back: the front end's view is the value last written
// (0 before), the board's while apcictl run executes the program.
TEST(TemperatureSettingData, ReadsBackWhatTheProgramWrote) {
    const auto r = only<RapidMove>(events_of(
        "P1 = $SC_TOOL_TEMP_COMP[1]\n$SC_TOOL_TEMP_COMP[1] = 0.25\n"
        "$SC_TOOL_TEMP_COMP[1] = $SC_TOOL_TEMP_COMP[1] * 2\nG0 X[P1] Y[$SC_TOOL_TEMP_COMP[1]]\n"
        "M30\n"));
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].end, Eigen::Vector3d(0, 0.5, 0));
}

TEST(TemperatureSettingData, ABoardsValueReplacesTheFrontEndsView) {
    struct Board : VariableSource {
        bool read(const VariableRef& v, double& out, std::string&) override {
            out = v.variable == NcVariable::kToolTempComp ? 0.125 * (v.index + 1) : 0.0;
            return true;
        }
    } board;
    Result<Program> p = Program::from_text("G0 X[$SC_TOOL_TEMP_COMP[2]]\nM30\n", "prog.nc");
    ASSERT_TRUE(p) << p.error().to_string();
    Result<EventStream> s = p.value().events();
    ASSERT_TRUE(s);
    s.value().set_variable_source(&board);
    Event ev;
    ASSERT_EQ(s.value().next(ev), EventStream::Next::kEvent);
    EXPECT_EQ(std::get<RapidMove>(ev.data).end.x(), 0.375);
}

// ---- refusals: file:line:column, and the program does not run (Program::from_text fails)

TEST(TemperatureSettingData, IndexOutsideZeroToTwoIsRefused) {
    const std::string why =
        "$SC_TOOL_TEMP_COMP[i] takes a component index 0..2 (X, Y, Z of the geometry axes)";
    EXPECT_EQ(error_of("G0 X1\nN20 $SC_TOOL_TEMP_COMP[3] = 0.1\nM30\n"), "prog.nc:2:5: N20: " + why);
    EXPECT_EQ(error_of("$SC_TOOL_TEMP_COMP = 0.1\nM30\n"), "prog.nc:1:1: " + why);
    EXPECT_EQ(error_of("$SC_TOOL_TEMP_COMP[] = 0.1\nM30\n"), "prog.nc:1:1: " + why);
    EXPECT_EQ(error_of("$SC_TOOL_TEMP_COMP[-1] = 0.1\nM30\n"), "prog.nc:1:1: " + why);
    EXPECT_EQ(error_of("P1 = $SC_TOOL_TEMP_COMP[7]\nM30\n"), "prog.nc:1:6: " + why);
}

// The object on the board takes -1e5..1e5 (docs/object-map.md section 7).
TEST(TemperatureSettingData, ValueBeyondTheObjectsRangeIsRefused) {
    EXPECT_EQ(error_of("N7 $SC_TOOL_TEMP_COMP[2] = 100000.5\nM30\n"),
              "prog.nc:1:4: N7: $SC_TOOL_TEMP_COMP[2] = 100000.5 out of range: SD 42960 takes "
              "-100000..100000 mm");
    EXPECT_EQ(error_of("$SC_TOOL_TEMP_COMP[0] = -1000000\nM30\n"),
              "prog.nc:1:1: $SC_TOOL_TEMP_COMP[0] = -1000000 out of range: SD 42960 takes "
              "-100000..100000 mm");
    EXPECT_EQ(error_of("$SC_TOOL_TEMP_COMP[0] = 100000\n$SC_TOOL_TEMP_COMP[1] = -100000\nM30\n"),
              "");
}

TEST(TemperatureSettingData, NonFiniteValueIsRefused) {
    // 1e20 to the 16th overflows the double.
    const std::string e = error_of(
        "P1 = 100000000000000000000\n"
        "$SC_TOOL_TEMP_COMP[1] = P1*P1*P1*P1*P1*P1*P1*P1*P1*P1*P1*P1*P1*P1*P1*P1\nM30\n");
    EXPECT_EQ(e, "prog.nc:2:72: the product is not a finite number");
}

TEST(TemperatureSettingData, OtherPrefixesAndMachineDataAreNamed) {
    EXPECT_EQ(error_of("$SN_TOOL_TEMP_COMP[0] = 1\nM30\n"),
              "prog.nc:1:1: $SN_TOOL_TEMP_COMP: SD 42960 TOOL_TEMP_COMP is a channel setting "
              "datum, $SC_TOOL_TEMP_COMP[i]");
    EXPECT_EQ(error_of("$MC_TOOL_TEMP_COMP_ON = 1\nM30\n"),
              "prog.nc:1:1: $MC_TOOL_TEMP_COMP_ON is machine data (MD 20390 / MD 32750), which "
              "programs do not write: it is set on the board (bus 1320), e.g. by the apcictl run "
              "--plc script");
    EXPECT_EQ(error_of("$SC_TOOL_TEMP = 1\nM30\n"),
              "prog.nc:1:1: unknown setting datum $SC_TOOL_TEMP (known: $SC_TOOL_TEMP_COMP[i])");
    // $FOR / $ENDFOR and unknown ISG commands keep their own errors.
    EXPECT_NE(error_of("$IF P1\nM30\n").find("ISG command '$IF' is not supported"),
              std::string::npos);
}

TEST(TemperatureSettingData, WriteStandsInABlockOfItsOwn) {
    EXPECT_EQ(error_of("G1 X10 F100 $SC_TOOL_TEMP_COMP[0] = 1\nM30\n"),
              "prog.nc:1:13: ISG commands and assignments stand in a block of their own (after "
              "an optional N number)");
    EXPECT_EQ(error_of("$SC_TOOL_TEMP_COMP[0] = 1 G1 X10\nM30\n"),
              "prog.nc:1:27: unexpected 'G' after the assignment");
    EXPECT_EQ(error_of("$SC_TOOL_TEMP_COMP[0] 1\nM30\n"),
              "prog.nc:1:23: expected '=' in the assignment");
}

TEST(TemperatureSettingData, NotAfterM30) {
    EXPECT_EQ(error_of("M30\n$SC_TOOL_TEMP_COMP[0] = 1\n"),
              "prog.nc:2:1: block after M30: the program has already ended");
}

}  // namespace
}  // namespace apci::nc
