// SPDX-License-Identifier: MIT
#include "apci/nc/tools.h"

#include <gtest/gtest.h>

#include <string>

namespace apci::nc {
namespace {

const std::string kExamples = APCI_EXAMPLES_DIR;

std::string error(std::string_view text) {
    Result<ToolTable> t = parse_tool_table(text, "t.tools");
    EXPECT_FALSE(t) << text;
    return t ? std::string() : t.error().to_string();
}

ToolTable table(std::string_view text) {
    Result<ToolTable> t = parse_tool_table(text, "t.tools");
    EXPECT_TRUE(t) << t.error().to_string();
    return t ? t.value() : ToolTable{};
}

// [ISG-OTC] section 2.6: the tool data of the grinding disc, kept raw and converted.
TEST(ToolTable, GrindingDiscToolDataRawAndConverted) {
    Result<ToolTable> t = load_tool_table(kExamples + "/tools/wr_quad_disc.tools");
    ASSERT_TRUE(t) << t.error().to_string();
    const ToolData* d1 = t.value().find(1);
    ASSERT_NE(d1, nullptr);
    EXPECT_TRUE(d1->valid());
    EXPECT_EQ(d1->type(), ToolType::kGrinding);
    EXPECT_EQ(d1->mass_einheit, 0);
    EXPECT_EQ(d1->laenge, 500000.0);
    EXPECT_EQ(d1->radius, 300000.0);
    EXPECT_DOUBLE_EQ(d1->length_mm(), 50.0);
    EXPECT_DOUBLE_EQ(d1->radius_mm(), 30.0);
    EXPECT_EQ(d1->grinding_wear_const, 100000.0);
    EXPECT_DOUBLE_EQ(d1->wear_const_mm_per_m(), 10.0);
    EXPECT_EQ(d1->grinding_max_infeed, 200000.0);
    EXPECT_DOUBLE_EQ(d1->max_infeed_mm(), 20.0);
    EXPECT_EQ(d1->grinding_disc_tilt_angle, 0.0);
    EXPECT_EQ(t.value().size(), 1U);
}

TEST(ToolTable, AToolBeyondTheBoardsSizesIsRefusedByName) {
    EXPECT_EQ(error("wz[1].mass_einheit 1\nwz[1].radius 99999999999\n"),
              "t.tools:2:7: wz[1].radius is 1e+11 mm: beyond the board's tool sizes of "
              "+-100000 mm (check mass_einheit: 0 is 0.1 um, 1 is mm)");
    // Named on the line that set the size, even when mass_einheit comes after it.
    EXPECT_EQ(error("wz[1].radius 99999999999\nwz[1].mass_einheit 1\n"),
              "t.tools:1:7: wz[1].radius is 1e+11 mm: beyond the board's tool sizes of "
              "+-100000 mm (check mass_einheit: 0 is 0.1 um, 1 is mm)");
    // 0.1 um: 1e9 units are 100000 mm, within; one more unit is not.
    EXPECT_EQ(table("wz[2].laenge -1000000000\n").find(2)->length_mm(), -100000.0);
    EXPECT_NE(error("wz[2].laenge -1000000001\n"), "");
}

TEST(ToolTable, MassEinheitOneMeansMillimetres) {
    const ToolTable t = table(
        "wz[3].mass_einheit 1\nwz[3].radius 2.5\nwz[3].laenge 80\nwz[3].ax_ersatz[1] -1.5\n"
        "wz[3].r2 0.5\nwz[3].dl 0.1\nwz[3].dr -0.02\nwz[3].dr2 0.01\n");
    const ToolData* d = t.find(3);
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->radius_mm(), 2.5);
    EXPECT_EQ(d->length_mm(), 80.0);
    EXPECT_EQ(d->axis_offset_mm(1), -1.5);
    EXPECT_EQ(d->r2_mm(), 0.5);
    EXPECT_EQ(d->dl_mm(), 0.1);
    EXPECT_EQ(d->dr_mm(), -0.02);
    EXPECT_EQ(d->dr2_mm(), 0.01);
}

TEST(ToolTable, MassEinheitZeroMeansTenthMicrometres) {
    const ToolTable t = table("wz[2].r2 5000\nwz[2].dr -200\nwz[2].ax_ersatz[7] 10000\n");
    const ToolData* d = t.find(2);
    ASSERT_NE(d, nullptr);
    EXPECT_DOUBLE_EQ(d->r2_mm(), 0.5);
    EXPECT_DOUBLE_EQ(d->dr_mm(), -0.02);
    EXPECT_DOUBLE_EQ(d->axis_offset_mm(7), 1.0);
}

TEST(ToolTable, TiltAngleInTenThousandthsOfADegree) {
    const ToolTable t = table("wz[1].grinding_disc_tilt_angle -125000\n");
    EXPECT_DOUBLE_EQ(t.find(1)->disc_tilt_angle_deg(), -12.5);
}

TEST(ToolTable, UnsetDataIsZero) {
    const ToolTable t = table("wz[4].typ 2\n");
    const ToolData* d = t.find(4);
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->gueltig, 0);
    EXPECT_FALSE(d->valid());
    EXPECT_EQ(d->radius, 0.0);
    EXPECT_EQ(d->grinding_max_infeed, 0.0);
    EXPECT_EQ(d->ax_ersatz[0], 0.0);
    EXPECT_EQ(t.find(5), nullptr);
}

TEST(ToolTable, CommentsBlankLinesAndTrailingText) {
    const ToolTable t = table(
        "\n# a comment\n   # indented comment\n\t\nwz[1].typ                  2      "
        "Schleifwerkzeug\nwz[1].radius 300000 # trailing\n");
    EXPECT_EQ(t.find(1)->typ, 2);
    EXPECT_EQ(t.find(1)->radius, 300000.0);
}

TEST(ToolTable, ToolsAreSortedByIndex) {
    const ToolTable t = table("wz[9].typ 1\nwz[2].typ 2\nwz[5].typ 0\n");
    ASSERT_EQ(t.size(), 3U);
    EXPECT_EQ(t.tools()[0].index, 2);
    EXPECT_EQ(t.tools()[1].index, 5);
    EXPECT_EQ(t.tools()[2].index, 9);
}

TEST(ToolTable, EveryFieldIsKnown) {
    const ToolTable t = table(
        "wz[1].gueltig 1\nwz[1].typ 3\nwz[1].mass_einheit 1\nwz[1].laenge 1\nwz[1].radius 2\n"
        "wz[1].ax_ersatz[0] 3\nwz[1].grinding_wear_const 4\nwz[1].grinding_max_infeed 5\n"
        "wz[1].grinding_disc_tilt_angle 6\nwz[1].r2 7\nwz[1].dl 8\nwz[1].dr 9\nwz[1].dr2 10\n");
    const ToolData* d = t.find(1);
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->gueltig, 1);
    EXPECT_EQ(d->typ, 3);
    EXPECT_EQ(d->mass_einheit, 1);
    EXPECT_EQ(d->laenge, 1.0);
    EXPECT_EQ(d->radius, 2.0);
    EXPECT_EQ(d->ax_ersatz[0], 3.0);
    EXPECT_EQ(d->grinding_wear_const, 4.0);
    EXPECT_EQ(d->grinding_max_infeed, 5.0);
    EXPECT_EQ(d->grinding_disc_tilt_angle, 6.0);
    EXPECT_EQ(d->r2, 7.0);
    EXPECT_EQ(d->dl, 8.0);
    EXPECT_EQ(d->dr, 9.0);
    EXPECT_EQ(d->dr2, 10.0);
}

TEST(ToolTable, UnknownFieldIsError) {
    EXPECT_EQ(error("wz[1].radiu 5"),
              "t.tools:1:7: unknown tool field 'radiu' (known: gueltig, typ, mass_einheit, laenge, "
              "radius, ax_ersatz[k], grinding_wear_const, grinding_max_infeed, "
              "grinding_disc_tilt_angle, r2, dl, dr, dr2, wear_radius, wear_radius_cont, cut, "
              "srk_lage)");
}

// cut (the TNC tool table's CUT: the number of teeth, for FZ) and srk_lage (P-TOOL-00002: the
// cutting edge position of a turning tool) are whole numbers in their ranges, written back by
// format_tool_table when set.
TEST(ToolTable, CutAndCuttingEdgePositionAreWholeNumbersInTheirRanges) {
    Result<ToolTable> t = parse_tool_table(
        "wz[1].gueltig 1\nwz[1].cut 4\nwz[2].gueltig 1\nwz[2].typ 1\nwz[2].srk_lage 9\n",
        "t.tools");
    ASSERT_TRUE(t) << t.error().to_string();
    EXPECT_EQ(t.value().find(1)->cut, 4);
    EXPECT_EQ(t.value().find(2)->srk_lage, 9);
    const std::string text = format_tool_table(t.value());
    EXPECT_NE(text.find("wz[1].cut"), std::string::npos) << text;
    EXPECT_NE(text.find("wz[2].srk_lage"), std::string::npos) << text;
    Result<ToolTable> again = parse_tool_table(text, "again.tools");
    ASSERT_TRUE(again) << again.error().to_string();
    EXPECT_EQ(again.value().find(1)->cut, 4);
    EXPECT_EQ(again.value().find(2)->srk_lage, 9);
    EXPECT_EQ(error("wz[1].cut 100"), "t.tools:1:11: wz[1].cut 100 out of range 0..99");
    EXPECT_EQ(error("wz[1].cut 2.5"), "t.tools:1:11: wz[1].cut must be a whole number");
    EXPECT_EQ(error("wz[1].srk_lage 10"), "t.tools:1:16: wz[1].srk_lage 10 out of range 0..9");
    EXPECT_EQ(error("wz[1].srk_lage -1"), "t.tools:1:16: wz[1].srk_lage -1 out of range 0..9");
}

TEST(ToolTable, LineMustStartWithWz) {
    EXPECT_EQ(error("\ntool[1].radius 5"),
              "t.tools:2:1: expected 'wz[i].field value' or a '#' comment");
    EXPECT_EQ(error("..."), "t.tools:1:1: expected 'wz[i].field value' or a '#' comment");
}

TEST(ToolTable, MalformedIndexIsError) {
    EXPECT_EQ(error("wz.radius 5"), "t.tools:1:3: expected '[' after 'wz'");
    EXPECT_EQ(error("wz[].radius 5"), "t.tools:1:4: expected a tool number after '['");
    EXPECT_EQ(error("wz[1.radius 5"), "t.tools:1:5: expected ']'");
    EXPECT_EQ(error("wz[1]radius 5"), "t.tools:1:6: expected '.' and a field name after 'wz[1]'");
    EXPECT_EQ(error("wz[1]. 5"), "t.tools:1:7: expected a field name after 'wz[1].'");
}

TEST(ToolTable, ToolNumberRange) {
    EXPECT_EQ(error("wz[0].typ 1"), "t.tools:1:4: tool number 0 out of range 1..1023");
    EXPECT_EQ(error("wz[1024].typ 1"), "t.tools:1:4: tool number 1024 out of range 1..1023");
    EXPECT_NE(table("wz[1023].typ 1").find(1023), nullptr);
}

TEST(ToolTable, AxisIndexRules) {
    EXPECT_EQ(error("wz[1].ax_ersatz 0"), "t.tools:1:16: expected '[' after 'wz[1].ax_ersatz'");
    EXPECT_EQ(error("wz[1].ax_ersatz[8] 0"), "t.tools:1:17: axis index 8 out of range 0..7");
    EXPECT_EQ(error("wz[1].radius[0] 5"), "t.tools:1:13: 'radius' takes no index");
}

TEST(ToolTable, ValueRules) {
    EXPECT_EQ(error("wz[1].radius"), "t.tools:1:13: expected a value after 'wz[1].radius'");
    EXPECT_EQ(error("wz[1].radius   abc"), "t.tools:1:16: expected a value after 'wz[1].radius'");
    EXPECT_EQ(error("wz[1].radius 12abc"),
              "t.tools:1:16: expected a blank or the end of the line after the value of "
              "wz[1].radius");
    EXPECT_EQ(error("wz[1].radius-5"),
              "t.tools:1:13: expected a blank and the value after 'wz[1].radius'");
}

TEST(ToolTable, WholeNumberFields) {
    EXPECT_EQ(error("wz[1].typ 2.5"), "t.tools:1:11: wz[1].typ must be a whole number");
    EXPECT_EQ(error("wz[1].gueltig 0.5"), "t.tools:1:15: wz[1].gueltig must be a whole number");
    EXPECT_EQ(table("wz[1].typ 2.0").find(1)->typ, 2);
}

TEST(ToolTable, RangesOfTheToolListFields) {
    EXPECT_EQ(error("wz[1].typ 4"), "t.tools:1:11: wz[1].typ 4 out of range 0..3");
    EXPECT_EQ(error("wz[1].gueltig 2"), "t.tools:1:15: wz[1].gueltig 2 out of range 0..1");
    EXPECT_EQ(error("wz[1].mass_einheit -1"),
              "t.tools:1:20: wz[1].mass_einheit -1 out of range 0..1");
    EXPECT_EQ(error("wz[1].radius -1"), "t.tools:1:14: wz[1].radius -1 out of range >= 0");
    EXPECT_EQ(error("wz[1].r2 -0.5"), "t.tools:1:10: wz[1].r2 -0.5 out of range >= 0");
    EXPECT_EQ(error("wz[1].grinding_wear_const -3"),
              "t.tools:1:27: wz[1].grinding_wear_const -3 out of range >= 0");
    EXPECT_EQ(error("wz[1].grinding_max_infeed 2147483648"),
              "t.tools:1:27: wz[1].grinding_max_infeed 2147483648 out of range "
              "-2147483648..2147483647 (SGN32)");
    EXPECT_EQ(error("wz[1].grinding_disc_tilt_angle 450001"),
              "t.tools:1:32: wz[1].grinding_disc_tilt_angle 450001 out of range -450000..450000 "
              "(-45..45 degrees in 0.0001 degree)");
    EXPECT_EQ(table("wz[1].grinding_disc_tilt_angle -450000").find(1)->disc_tilt_angle_deg(),
              -45.0);
}

TEST(ToolTable, FieldSetTwiceIsError) {
    EXPECT_EQ(error("wz[1].radius 5\n# x\nwz[1].radius 6\n"),
              "t.tools:3:7: wz[1].radius set twice (first on line 1)");
    EXPECT_EQ(error("wz[1].ax_ersatz[2] 5\nwz[1].ax_ersatz[2] 6\n"),
              "t.tools:2:7: wz[1].ax_ersatz[2] set twice (first on line 1)");
    // The same field of another tool, or another axis, is fine.
    EXPECT_EQ(table("wz[1].radius 5\nwz[2].radius 6\nwz[1].ax_ersatz[0] 1\nwz[1].ax_ersatz[1] 1\n")
                  .size(),
              2U);
}

TEST(ToolTable, MissingFileIsIoError) {
    Result<ToolTable> t = load_tool_table("/nonexistent/x.tools");
    ASSERT_FALSE(t);
    EXPECT_EQ(t.error().kind, ErrorKind::kIo);
    EXPECT_EQ(t.error().to_string(),
              "/nonexistent/x.tools: cannot open: No such file or directory");
}

}  // namespace
}  // namespace apci::nc
