// SPDX-License-Identifier: MIT
// The output side of `apcictl run`: path geometry helpers, the streamed JSON of docs/design.md
// section 7, the per-cycle CSV, the SVG plot and the summary.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

#include "apci/run/csv_writer.h"
#include "apci/run/json_writer.h"
#include "apci/run/path.h"
#include "apci/run/summary.h"
#include "apci/run/svg_writer.h"
#include "memory_file.h"
#include "test_segments.h"
#include "text.h"

namespace apci::run {
namespace {

using test_support::contains;
using nlohmann::json;

using apci_test::MemoryFile;

// The writers' segments: contour elements of blocks 10 (lines) and 20 (arcs) unless named.
PathSegment line(const Point& a, const Point& b, Role role = Role::kContour, std::int64_t n = 10) {
    return test_segments::line(n, a, b, role);
}

PathSegment arc(const Point& a, const Point& b, const Point& c, bool ccw, int plane = 17,
                Role role = Role::kContour, std::int64_t n = 20) {
    return test_segments::arc(n, a, b, c, ccw, role, plane);
}

// ---- path geometry

TEST(RunPath, ArcSweepIsSignedBySense) {
    const auto q = arc({1, 0, 0}, {0, 1, 0}, {0, 0, 0}, true);
    EXPECT_NEAR(arc_sweep(q), std::numbers::pi / 2, 1e-12);
    auto cw = q;
    cw.ccw = false;
    EXPECT_NEAR(arc_sweep(cw), -1.5 * std::numbers::pi, 1e-12);
}

TEST(RunPath, ArcWithStartOnEndIsAFullCircle) {
    const auto full = arc({1, 0, 0}, {1, 0, 0}, {0, 0, 0}, false);
    EXPECT_NEAR(arc_sweep(full), -2 * std::numbers::pi, 1e-12);
    EXPECT_NEAR(segment_length(full), 2 * std::numbers::pi, 1e-12);
}

TEST(RunPath, HelixLengthCountsTheThirdAxis) {
    // G18: plane Z-X, third axis Y.
    const auto helix = arc({0, 0, 1}, {0, 3, 1}, {0, 0, 0}, true, 18);
    EXPECT_NEAR(segment_length(helix), std::hypot(2 * std::numbers::pi, 3.0), 1e-12);
}

TEST(RunPath, PointAlongAnArcIsOnTheCircle) {
    const auto q = arc({2, 0, 0}, {0, 2, 0}, {0, 0, 0}, true, 17);
    const Point mid = point_along(q, 0.5);
    EXPECT_NEAR(mid.x(), std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(mid.y(), std::sqrt(2.0), 1e-12);
}

TEST(RunPath, PlaneAxesAreRightHanded) {
    for (int plane : {17, 18, 19}) {
        const PlaneAxes a = plane_axes(plane);
        Eigen::Vector3d e1 = Eigen::Vector3d::Zero(), e2 = e1, e3 = e1;
        e1[a.first] = 1;
        e2[a.second] = 1;
        e3[a.third] = 1;
        EXPECT_EQ(e1.cross(e2), e3) << plane;
    }
}

// ---- JSON

json write_json(const std::vector<PathSegment>& segs, const std::vector<RunError>& errors,
                const std::vector<GroupRegisters>& regs, std::string* text = nullptr) {
    MemoryFile f;
    JsonRunWriter w(f.get());
    for (const auto& s : segs) w.segment(s);
    EXPECT_TRUE(w.finish(errors, regs));
    const std::string t = f.text();
    if (text != nullptr) *text = t;
    return json::parse(t);
}

TEST(RunJson, SchemaOfDesignSection7) {
    PathSegment rapid = line({0, 0, 5}, {1, 2, 5}, Role::kUncompensated, kNoBlock);
    rapid.kind = SegmentKind::kRapid;
    rapid.block.line = 7;
    const auto doc =
        write_json({rapid, line({1, 2, 5}, {3, 2, 5}, Role::kApproach, 60),
                    arc({3, 2, 5}, {5, 4, 5}, {3, 4, 5}, true, 17, Role::kTransition, 70)},
                   {RunError{{80, 12}, "KorrError", "compensation impossible"}},
                   {GroupRegisters{1, true, 0x02, 0x00}, GroupRegisters{2, true, 0, 1},
                    GroupRegisters{3, false, 0, 0}});
    ASSERT_TRUE(doc.is_object());
    EXPECT_EQ(doc.size(), 4u);
    const auto& segs = doc.at("segments");
    ASSERT_EQ(segs.size(), 3u);
    EXPECT_EQ(segs[0].at("block"), -1);
    EXPECT_EQ(segs[0].at("line"), 7);
    EXPECT_EQ(segs[0].at("kind"), "rapid");
    EXPECT_EQ(segs[0].at("role"), "uncompensated");
    EXPECT_EQ(segs[0].at("start"), json::array({0, 0, 5}));
    EXPECT_EQ(segs[0].at("end"), json::array({1, 2, 5}));
    EXPECT_FALSE(segs[0].contains("center"));
    EXPECT_EQ(segs[1].at("block"), 60);
    EXPECT_FALSE(segs[1].contains("line"));
    EXPECT_EQ(segs[1].at("kind"), "line");
    EXPECT_EQ(segs[1].at("role"), "approach");
    EXPECT_FALSE(segs[1].contains("ccw"));
    EXPECT_EQ(segs[2].at("kind"), "arc");
    EXPECT_EQ(segs[2].at("role"), "transition");
    EXPECT_EQ(segs[2].at("center"), json::array({3, 4, 5}));
    EXPECT_EQ(segs[2].at("ccw"), true);
    EXPECT_EQ(segs[2].at("plane"), 17);
    const auto& errors = doc.at("errors");
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].at("block"), 80);
    EXPECT_EQ(errors[0].at("code"), "KorrError");
    EXPECT_EQ(errors[0].at("message"), "compensation impossible");
    const auto& regs = doc.at("registers");
    EXPECT_EQ(regs.at("1").at("ERROR"), 2);
    EXPECT_EQ(regs.at("1").at("ERROR_bits"), json::array({"KorrError"}));
    EXPECT_EQ(regs.at("1").at("STATUS_bits"), json::array());
    EXPECT_EQ(regs.at("2").at("STATUS_bits"), json::array({"Run"}));
    EXPECT_TRUE(regs.at("3").is_null());
    EXPECT_EQ(doc.at("variables"), json::object());
}

TEST(RunJson, EmptyRunIsStillOneObject) {
    const auto doc = write_json({}, {}, {});
    EXPECT_EQ(doc.at("segments"), json::array());
    EXPECT_EQ(doc.at("errors"), json::array());
    EXPECT_EQ(doc.at("registers"), json::object());
}

TEST(RunJson, CoordinatesReadBackExactly) {
    const Point a(0.1, -1.0 / 3.0, 1e-17), b(123456.789012345, 2.0 / 7.0, -0.0);
    const auto doc = write_json({line(a, b)}, {}, {});
    const auto& s = doc.at("segments")[0];
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(s.at("start")[i].get<double>(), a[i]);
        EXPECT_EQ(s.at("end")[i].get<double>(), b[i]);
    }
}

TEST(RunJson, WholeNumbersAreWrittenAsIntegersAndReadBackExactly) {
    std::string text;
    const auto doc =
        write_json({line({1e5, -0.0, 123456789012345.0}, {-7, 0.5, 1e15})}, {}, {}, &text);
    EXPECT_TRUE(contains(text, "\"start\":[100000,-0,123456789012345],\"end\":[-7,0.5,1e+15]"))
        << text;
    const auto& s = doc.at("segments")[0];
    EXPECT_EQ(s.at("start")[0].get<double>(), 1e5);
    EXPECT_EQ(s.at("start")[1].get<double>(), 0.0);  // "-0": JSON readers may drop the sign
    EXPECT_EQ(s.at("start")[2].get<double>(), 123456789012345.0);
    EXPECT_EQ(s.at("end")[2].get<double>(), 1e15);
}

TEST(RunJson, NonFiniteCoordinateIsNull) {
    const auto doc = write_json({line({0, 0, 0}, {std::nan(""), 0, 0})}, {}, {});
    EXPECT_TRUE(doc.at("segments")[0].at("end")[0].is_null());
}

TEST(RunJson, MessagesAreEscaped) {
    const std::string nasty = "quote \" backslash \\ newline \n tab \t bell \x07 umlaut \xc3\xa4";
    const auto doc = write_json({}, {RunError{{kNoBlock, 3}, "Syntax", nasty}}, {});
    EXPECT_EQ(doc.at("errors")[0].at("message"), nasty);
    EXPECT_EQ(doc.at("errors")[0].at("line"), 3);
}

TEST(RunJson, OneSegmentALine) {
    std::string text;
    write_json({line({0, 0, 0}, {1, 0, 0}), line({1, 0, 0}, {2, 0, 0})}, {}, {}, &text);
    EXPECT_TRUE(contains(text,
                         "{\"segments\":[\n{\"block\":10,\"kind\":\"line\",\"role\":\"contour\","
                         "\"start\":[0,0,0],\"end\":[1,0,0]},\n{"))
        << text;
}

TEST(RunJson, WriteFailureIsReported) {
    std::FILE* full = std::fopen("/dev/full", "w");
    ASSERT_NE(full, nullptr);
    JsonRunWriter w(full);
    for (int i = 0; i < 10; ++i) w.segment(line({0, 0, 0}, {1, 1, 1}));
    EXPECT_FALSE(w.finish({}, {}));
    std::fclose(full);
}

TEST(RunTextSink, TextLongerThanTheBufferIsWrittenWhole) {
    MemoryFile f;
    const std::string big(TextSink::kCapacity * 2 + 17, 'x');
    {
        TextSink sink(f.get());
        sink.append("<");
        sink.append(big);
        sink.put('>');
        EXPECT_TRUE(sink.flush());
    }
    EXPECT_EQ(f.text(), "<" + big + ">");
}

TEST(RunTextSink, ManySmallPiecesKeepTheirOrder) {
    MemoryFile f;
    std::string expected;
    {
        TextSink sink(f.get());
        for (int i = 0; i < 50000; ++i) {
            append_integer(sink, i);
            sink.put(',');
            expected += std::to_string(i) + ",";
        }
    }
    EXPECT_EQ(f.text(), expected);
}

// ---- CSV

TEST(RunCsv, HeaderNamesTheAxesAndOneLineACycle) {
    MemoryFile f;
    std::vector<std::string> names;
    names.reserve(8);
    for (int i = 0; i < 8; ++i) names.push_back(axis_column_name(i));
    TraceCsvWriter w(f.get(), names);
    const double p1[8] = {0.01, 0, 0, 0, 0, 0, 0, 0};
    const double p2[8] = {0.02, -1.5, 3, 0, 0, 0, 0, 7};
    w.sample(1, 0.001, p1);
    w.sample(2, 0.002, p2);
    ASSERT_TRUE(w.finish());
    EXPECT_EQ(f.text(),
              "cycle,time_s,X,Y,Z,A,B,C,U,V\n"
              "1,0.001,0.01,0,0,0,0,0,0,0\n"
              "2,0.002,0.02,-1.5,3,0,0,0,0,7\n");
    EXPECT_EQ(w.samples_written(), 2u);
}

// A column is a board axis, named as the command line names it (docs/apcictl.md, "spool,
// direct, ssf, step"): X Y Z A B C U V are board axes 0..7, DIN 66025's order, so the column B
// is the axis a program's B word drives (board axis 4, the head's).
TEST(RunCsv, AxisNamesAreTheBoardAxisLetters) {
    const std::string letters = "XYZABCUV";
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(axis_column_name(i), std::string(1, letters[static_cast<std::size_t>(i)])) << i;
    EXPECT_EQ(axis_column_name(8), "a8");  // no such board axis: still a distinct name
}

// ---- SVG

std::string write_svg(SvgPlotWriter& w, int plane = 17, std::string_view title = "t.nc") {
    MemoryFile f;
    EXPECT_TRUE(w.finish(f.get(), plane, title));
    return f.text();
}

// The four numbers of the viewBox.
std::vector<double> view_box(const std::string& svg) {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(svg, m, std::regex("viewBox=\"([^\"]*)\"")));
    std::vector<double> v;
    std::istringstream in(m[1].str());
    for (double x; in >> x;) v.push_back(x);
    return v;
}

TEST(RunSvg, ViewBoxFitsTheDrawingWithSecondAxisUp) {
    SvgPlotWriter w;
    ASSERT_TRUE(w.ok());
    w.programmed(line({0, 0, 0}, {100, 0, 0}));
    w.executed(line({0, -5, 0}, {100, -5, 0}));
    w.executed(arc({100, -5, 0}, {105, 0, 0}, {100, 0, 0}, true, 17, Role::kTransition));
    w.programmed(line({100, 0, 0}, {100, 50, 0}));
    const std::string svg = write_svg(w);
    const auto vb = view_box(svg);
    ASSERT_EQ(vb.size(), 4u);
    // SVG y = -Y: the drawing spans x 0..105, y -50..5.
    EXPECT_LT(vb[0], 0.0);
    EXPECT_GT(vb[0] + vb[2], 105.0);
    EXPECT_LT(vb[1], -50.0);
    EXPECT_GT(vb[1] + vb[3], 5.0);
    EXPECT_TRUE(contains(svg, "<path class=\"programmed\" d=\"M0 0 L100 0 L100 -50\"/>")) << svg;
    // Tool path continues from the line into the transition arc: one path per layer.
    EXPECT_TRUE(contains(svg, "<path class=\"contour\" d=\"M0 5 L100 5\"/>")) << svg;
    EXPECT_TRUE(contains(svg, "<path class=\"transition\" d=\"M100 5 A5 5 0 0 0 105 0\"/>")) << svg;
}

TEST(RunSvg, ClockwiseArcHasSweepFlagOne) {
    SvgPlotWriter w;
    w.executed(arc({0, 1, 0}, {1, 0, 0}, {0, 0, 0}, false));
    const std::string svg = write_svg(w);
    EXPECT_TRUE(contains(svg, "A1 1 0 0 1 1 0\"")) << svg;
}

TEST(RunSvg, FullCircleIsDrawnInTwoHalves) {
    SvgPlotWriter w;
    w.executed(arc({2, 0, 0}, {2, 0, 0}, {0, 0, 0}, true));
    const std::string svg = write_svg(w);
    EXPECT_TRUE(contains(svg, "M2 0 A2 2 0 0 0 -2 0 A2 2 0 0 0 2 0\"")) << svg;
    const auto vb = view_box(svg);
    EXPECT_LT(vb[0], -2.0);
    EXPECT_GT(vb[0] + vb[2], 2.0);
}

TEST(RunSvg, ArcBoundsIncludeTheCircleExtremesItPasses) {
    Bounds b;
    b.add(arc({1, 0, 0}, {-1, 0, 0}, {0, 0, 0}, true));  // upper half: passes (0, 1)
    EXPECT_NEAR(b.hi.y(), 1.0, 1e-12);
    EXPECT_NEAR(b.lo.y(), 0.0, 1e-12);
    Bounds c;
    c.add(arc({1, 0, 0}, {-1, 0, 0}, {0, 0, 0}, false));  // lower half: passes (0, -1)
    EXPECT_NEAR(c.lo.y(), -1.0, 1e-12);
    EXPECT_NEAR(c.hi.y(), 0.0, 1e-12);
}

TEST(RunSvg, GapStartsANewSubpath) {
    SvgPlotWriter w;
    w.executed(line({0, 0, 0}, {1, 0, 0}));
    w.executed(line({2, 0, 0}, {3, 0, 0}));
    const std::string svg = write_svg(w);
    EXPECT_TRUE(contains(svg, "d=\"M0 0 L1 0 M2 0 L3 0\"")) << svg;
}

TEST(RunSvg, EachRoleHasItsOwnStyleAndLegendEntry) {
    SvgPlotWriter w;
    PathSegment rapid = line({0, 0, 0}, {1, 0, 0}, Role::kUncompensated);
    rapid.kind = SegmentKind::kRapid;
    w.executed(rapid);
    w.executed(line({1, 0, 0}, {2, 0, 0}, Role::kUncompensated));
    w.executed(line({2, 0, 0}, {3, 0, 0}, Role::kApproach));
    w.executed(line({3, 0, 0}, {4, 0, 0}, Role::kContour));
    w.executed(line({4, 0, 0}, {5, 0, 0}, Role::kTransition));
    w.executed(line({5, 0, 0}, {6, 0, 0}, Role::kDeparture));
    w.programmed(line({0, 1, 0}, {6, 1, 0}));
    w.cycle({0, 2, 0});
    w.cycle({6, 2, 0});
    const std::string svg = write_svg(w);
    for (std::size_t l = 0; l < kPlotLayerCount; ++l) {
        const auto layer = static_cast<PlotLayer>(l);
        const std::string cls(layer_class(layer));
        EXPECT_TRUE(contains(svg, "." + cls + " {")) << cls;
        EXPECT_TRUE(contains(svg, "<path class=\"" + cls + "\"")) << cls;
        EXPECT_TRUE(contains(svg, ">" + std::string(layer_label(layer)) + "</text>")) << cls;
        EXPECT_EQ(w.count(layer), 1u) << cls;
    }
}

// The per-cycle axes (apcictl run --svg-cycles): straight stretches become one line, a turn
// keeps its vertex, the last point is always drawn, and a plot without them has no style for
// them.
TEST(RunSvg, CyclesAreSimplifiedAndEndOnTheLastPoint) {
    SvgPlotWriter w;
    for (int i = 0; i <= 128; ++i) w.cycle({i / 128.0, 0, 0});  // 1 mm along X
    for (int i = 1; i <= 128; ++i) w.cycle({1.0, i / 128.0, 0});  // then 1 mm along Y
    w.cycle({1.0, 1.0, 0.005});
    const std::string svg = write_svg(w);
    // (0,0) -> (1,0) -> (1,1) -> (1,1,0.005): three lines.
    EXPECT_EQ(w.count(PlotLayer::kCycles), 3u);
    EXPECT_TRUE(contains(svg, "M0 0 L1 0 L1 -1")) << svg;
    SvgPlotWriter plain;
    plain.executed(line({0, 0, 0}, {1, 0, 0}, Role::kContour));
    EXPECT_FALSE(contains(write_svg(plain), ".cycles {"));
}

TEST(RunSvg, ProgrammedRapidIsNotDrawnTwice) {
    SvgPlotWriter w;
    PathSegment rapid = line({0, 0, 0}, {1, 0, 0}, Role::kUncompensated);
    rapid.kind = SegmentKind::kRapid;
    w.programmed(rapid);
    EXPECT_EQ(w.count(PlotLayer::kProgrammed), 0u);
}

TEST(RunSvg, ErrorMarkerNamesBlockAndError) {
    SvgPlotWriter w;
    w.programmed(line({0, 0, 0}, {10, 0, 0}));
    w.error_marker({80, 9}, {5, 0, 0}, "KorrError");
    w.error_marker({kNoBlock, 12}, {10, 0, 0}, "CalcError");
    const std::string svg = write_svg(w);
    EXPECT_TRUE(contains(svg, "<circle class=\"error\" cx=\"5\" cy=\"0\"")) << svg;
    EXPECT_TRUE(contains(svg, ">N80 KorrError</text>")) << svg;
    EXPECT_TRUE(contains(svg, ">line 12 CalcError</text>")) << svg;
}

TEST(RunSvg, WarningMarkersAreOrangeWithAnEntryOfTheirOwnInTheLegend) {
    // A warning alone: an orange marker and "warning" in the legend, no "error".
    SvgPlotWriter w;
    w.programmed(line({0, 0, 0}, {10, 0, 0}));
    w.warning_marker({70, 0}, {5, 0, 0}, "SelfApproach");
    std::string svg = write_svg(w);
    EXPECT_TRUE(contains(svg, "<circle class=\"warning\" cx=\"5\" cy=\"0\"")) << svg;
    EXPECT_TRUE(contains(svg, "<text class=\"warning\"")) << svg;
    EXPECT_TRUE(contains(svg, ">N70 SelfApproach</text>")) << svg;
    EXPECT_TRUE(contains(svg, ">warning</text>")) << svg;
    EXPECT_FALSE(contains(svg, ">error</text>")) << svg;
    EXPECT_FALSE(contains(svg, "class=\"error\" cx")) << svg;
    // With an error too: both entries, each with its sample.
    SvgPlotWriter both;
    both.programmed(line({0, 0, 0}, {10, 0, 0}));
    both.warning_marker({70, 0}, {5, 0, 0}, "SelfApproach");
    both.error_marker({80, 0}, {10, 0, 0}, "KorrError");
    svg = write_svg(both);
    EXPECT_TRUE(contains(svg, ">warning</text>")) << svg;
    EXPECT_TRUE(contains(svg, ">error</text>")) << svg;
    EXPECT_TRUE(contains(svg, "<circle class=\"error\" cx=\"10\" cy=\"0\"")) << svg;
}

TEST(RunSvg, ScaleBarAxesAndTitleOfThePlane) {
    SvgPlotWriter w;
    // G18: Z right, X up.
    w.programmed(line({0, 0, 0}, {0, 0, 100}));
    w.programmed(line({0, 0, 100}, {40, 0, 100}));
    const std::string svg = write_svg(w, 18, "prog.nc");
    EXPECT_TRUE(contains(svg, "<path class=\"programmed\" d=\"M0 0 L100 0 L100 -40\"/>")) << svg;
    EXPECT_TRUE(contains(svg, ">20 mm</text>")) << svg;  // a quarter of 100, rounded to 1-2-5
    EXPECT_TRUE(contains(svg, ">Z 0 .. 100, X 0 .. 40 mm</text>")) << svg;
    EXPECT_TRUE(contains(svg, ">Z</text>")) << svg;
    EXPECT_TRUE(contains(svg, ">X</text>")) << svg;
    EXPECT_TRUE(contains(svg, "prog.nc \xe2\x80\x94 G18 plane Z-X, seen from +Y</text>")) << svg;
}

TEST(RunSvg, ArcOutsideThePlottedPlaneIsProjected) {
    SvgPlotWriter w;
    // A G19 (Y-Z) half circle seen in G17: a straight back-and-forth in Y only.
    w.executed(arc({0, 1, 0}, {0, -1, 0}, {0, 0, 0}, true, 19));
    const std::string svg = write_svg(w, 17);
    EXPECT_FALSE(contains(svg, " A")) << svg;
    EXPECT_TRUE(contains(svg, " L0 1\"")) << svg;  // ends at (0, -1), SVG y = 1
}

TEST(RunSvg, TitleIsEscaped) {
    SvgPlotWriter w;
    const std::string svg = write_svg(w, 17, "a<b&c.nc");
    EXPECT_TRUE(contains(svg, "a&lt;b&amp;c.nc")) << svg;
}

TEST(RunSvg, ManyErrorsAreCountedNotDrawn) {
    SvgPlotWriter w;
    for (std::size_t i = 0; i < kMaxErrorMarkers + 5; ++i)
        w.error_marker({static_cast<std::int64_t>(i), 0}, {0, 0, 0}, "KorrError");
    const std::string svg = write_svg(w);
    EXPECT_TRUE(contains(svg, "(5 more not drawn)")) << svg;
}

// ---- Summary

TEST(RunSummary, NamesBlocksPathAndErrorsByName) {
    RunTotals t;
    t.file = "p.nc";
    t.blocks = 11;
    t.blocks_executed = 9;
    PathSegment rapid = line({0, 0, 0}, {3, 4, 0}, Role::kUncompensated);
    rapid.kind = SegmentKind::kRapid;
    count_segment(t, rapid);
    count_segment(t, line({3, 4, 0}, {13, 4, 0}));
    t.cycles = 1500;
    t.cycle_seconds = 0.001;
    const std::vector<RunError> errors{{{80, 0}, "KorrError", "too short"},
                                       {{90, 0}, "CalcError", "arc"},
                                       {{95, 0}, "KorrError", "again"}};
    MemoryFile f;
    print_summary(f.get(), t, errors);
    EXPECT_EQ(f.text(),
              "p.nc: 11 blocks, 9 sent to the board, 2 segments executed\n"
              "path 15.000 mm (rapid 5.000 mm), time 1.500 s (1500 cycles of 1 ms)\n"
              "errors: 3 (KorrError 2, CalcError 1)\n"
              "  N80: KorrError: too short\n"
              "  N90: CalcError: arc\n"
              "  N95: KorrError: again\n");
}

TEST(RunSummary, NoErrorsSaysNone) {
    RunTotals t;
    t.file = "p.nc";
    t.cycle_seconds = 0.00025;
    MemoryFile f;
    print_summary(f.get(), t, {});
    EXPECT_TRUE(contains(f.text(), "(0 cycles of 250 us)\nerrors: none\n")) << f.text();
}

TEST(RunSummary, OneOfEachIsSingularAndNoneAndTwoArePlural) {
    RunTotals t;
    t.file = "p.nc";
    t.blocks = 1;
    t.blocks_executed = 1;
    t.segments = 1;
    t.cycles = 1;
    t.cycle_seconds = 0.001;
    MemoryFile one;
    print_summary(one.get(), t, {});
    EXPECT_TRUE(contains(one.text(), "p.nc: 1 block, 1 sent to the board, 1 segment executed\n")) << one.text();
    EXPECT_TRUE(contains(one.text(), "(1 cycle of 1 ms)\n")) << one.text();
    t.blocks = 2;
    t.segments = 0;
    t.cycles = 2;
    MemoryFile two;
    print_summary(two.get(), t, {});
    EXPECT_TRUE(contains(two.text(), "p.nc: 2 blocks, 1 sent to the board, 0 segments executed\n")) << two.text();
    EXPECT_TRUE(contains(two.text(), "(2 cycles of 1 ms)\n")) << two.text();
}

TEST(RunSummary, LongErrorListIsCut) {
    std::vector<RunError> errors(kSummaryErrorLines + 3, RunError{{1, 0}, "KorrError", "x"});
    MemoryFile f;
    print_summary(f.get(), RunTotals{}, errors);
    EXPECT_TRUE(contains(f.text(), "  ... and 3 more\n")) << f.text();
}

}  // namespace
}  // namespace apci::run
