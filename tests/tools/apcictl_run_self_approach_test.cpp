// SPDX-License-Identifier: MIT
// `apcictl run`'s self-approach check: programs as CAM systems write them, the check's findings
// and notices, its grid against every pair, its window, rapids.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "apcictl_run.h"

namespace {

using namespace apcictl_run_test;

// ---- Programs as CAM systems write them (the compensation issue's reproductions)

// Rounds to `decimals` places, as a program writes a coordinate.
std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

TEST_F(ApcictlRun, CollinearLinesWrittenWithSixDecimalsCompensateAtEveryHeading) {
    // Two collinear 20 mm lines, a lead-in and a lead-out, written to 6 decimals: the join's
    // turn is rounding noise (about 1e-6 degrees). It used to stop with KorrError at 15, 105,
    // 195 and 285 degrees (the same pair along X ran).
    const std::string tool_list =
        write("t05.tools",
              "wz[1].gueltig 1\nwz[1].typ 0\nwz[1].mass_einheit 0\nwz[1].laenge 0\n"
              "wz[1].radius 5000\n");
    // The program as reported, number for number.
    const json reported = run_json(
        write("reported.nc",
              "%collinear\nG17 G90\nD1\nG0 X-7.071068 Y-12.247449\nG41 G1 X0 Y0 F600\n"
              "G1 X19.318517 Y5.176381\nG1 X38.637033 Y10.352762\n"
              "G40 G1 X46.033840 Y3.623182\nM30\n"),
        {"--tools", tool_list});
    EXPECT_TRUE(reported.at("errors").empty()) << reported.at("errors").dump();
    EXPECT_TRUE(contains(last_.out, "errors: none")) << last_.out;
    for (const double heading : {0.0, 15.0, 105.0, 195.0, 285.0}) {
        const double a = heading * std::numbers::pi / 180;
        const geom::Vec2 t(std::cos(a), std::sin(a)), n(-std::sin(a), std::cos(a));
        const auto p = [](const geom::Vec2& v) {
            return "X" + fixed(v.x(), 6) + " Y" + fixed(v.y(), 6);
        };
        const geom::Vec2 start = 14.142136 * geom::Vec2(std::cos(a - std::numbers::pi * 3 / 4),
                                                        std::sin(a - std::numbers::pi * 3 / 4));
        const geom::Vec2 mid = 20 * t, end = 40 * t, exit = end + 10 * geom::Vec2(t - n).normalized();
        std::string text = "%collinear\nG17 G90\nD1\nG0 " + p(start) + "\nG41 G1 X0 Y0 F600\nG1 " +
                           p(mid) + "\nG1 " + p(end) + "\nG40 G1 " + p(exit) + "\nM30\n";
        const json doc = run_json(write("c.nc", text), {"--tools", tool_list});
        EXPECT_TRUE(doc.at("errors").empty()) << heading << " " << doc.at("errors").dump();
        expect_continuous(doc);
        // The two lines as written: their offsets keep 0.5 mm, with no transition between them.
        const auto as_written = [](const geom::Vec2& v) {
            return geom::Vec2(std::stod(fixed(v.x(), 6)), std::stod(fixed(v.y(), 6)));
        };
        const std::vector<geom::Element> lines{
            geom::make_line({0, 0}, as_written(mid)),
            geom::make_line(as_written(mid), as_written(end))};
        // The segments of the two lines (program lines 6 and 7; the blocks have no N).
        json of_lines = doc;
        of_lines["segments"] = json::array();
        for (const auto& s : doc.at("segments"))
            if (s.at("line") == 6 || s.at("line") == 7) of_lines["segments"].push_back(s);
        expect_at_radius(of_lines, lines, 0.5, {"contour"});
        // At the collinear join (after line 6) nothing but a transition of rounding size.
        for (const auto& s : of_lines.at("segments")) {
            if (s.at("role") == "transition") {
                EXPECT_LT((point(s.at("end")) - point(s.at("start"))).norm(), 1e-4) << heading;
            }
        }
    }
}

TEST_F(ApcictlRun, LineTangentArcLineWrittenWithThreeDecimalsCompensatesOnBothSides) {
    // The commonest shape of CAM output: a line, a tangent arc, a tangent line, to 0.001 mm.
    // The arc's end radius is 9.99978 (rounding); with G42 it used to stop at N50 with
    // "element is too short for the corner at its end" (then "previous element is too short").
    for (const char* side : {"G41", "G42"}) {
        const std::string prog = write(
            "tangent.nc", std::string("%tangent\nN10 G17 G90 D1 F600\nN20 G0 X-10 Y-5\nN30 ") +
                              side +
                              " G1 X-10 Y0\nN40 X10 Y0\nN50 G3 X15 Y1.34 I0 J10\n"
                              "N60 G1 X32.321 Y11.34\nN70 G40 G1 X40 Y20\nN80 M30\n");
        const json doc = run_json(prog, {"--tools", tools(5.0)});
        EXPECT_TRUE(doc.at("errors").empty()) << side << " " << doc.at("errors").dump();
        expect_continuous(doc);
        // Tangent joins (up to rounding): at most a transition of rounding size (the arc's end
        // tangent and the line differ by 2.5e-5 rad, 1.25e-4 mm at r = 5), every contour point
        // 5 mm from the contour as written (the arc runs from its start to its end point).
        for (const auto& s : with_role(doc, "transition")) {
            if (s.at("block") != 30) {
                EXPECT_LT((point(s.at("end")) - point(s.at("start"))).norm(), 2e-4) << side;
            }
        }
        const std::vector<geom::Element> contour{
            geom::make_line({-10, 0}, {10, 0}), geom::make_arc({10, 0}, {15, 1.34}, {10, 10}, true),
            geom::make_line({15, 1.34}, {32.321, 11.34})};
        expect_at_radius(doc, contour, 5.0, {"contour"});
        // G139: N30 (the G41/G42 block, along +Y) is the approach from (-10, -5) to its offset
        // end: G41 5 left of (-10, 0), (-15, 0), an outside corner with N40 (G25: transition
        // lines); G42 5 right, x = -5, an inside corner trimmed where it meets N40's offset
        // y = -5: (-5, -5). N40, N50 and N60 are the contour.
        const bool left = std::string(side) == "G41";
        const auto approach = with_role(doc, "approach");
        ASSERT_EQ(approach.size(), 1u) << roles(doc);
        EXPECT_EQ(approach[0].at("block"), 30);
        EXPECT_EQ(point(approach[0].at("start")), apci::run::Point(-10, -5, 0));
        EXPECT_LT((point(approach[0].at("end")) -
                   (left ? apci::run::Point(-15, 0, 0) : apci::run::Point(-5, -5, 0)))
                      .norm(),
                  1e-9)
            << side;
        EXPECT_EQ(with_role(doc, "contour").size(), 3u) << roles(doc);
        // The G40 move N70 runs from N60's offset end, 5 beside (32.321, 11.34) at right angles
        // to N60 (direction (17.321, 10) / 20.0000), to its programmed end (40, 20).
        const apci::run::Point dir = apci::run::Point(17.321, 10, 0).normalized();
        const apci::run::Point normal(-dir.y(), dir.x(), 0);  // left of the direction
        const apci::run::Point n60_end =
            apci::run::Point(32.321, 11.34, 0) + (left ? 5.0 : -5.0) * normal;
        const json& off = doc.at("segments").back();
        EXPECT_EQ(off.at("block"), 70);
        EXPECT_EQ(off.at("role"), "departure");
        EXPECT_LT((point(off.at("start")) - n60_end).norm(), 1e-9) << side;
        EXPECT_EQ(point(off.at("end")), apci::run::Point(40, 20, 0));
    }
}

TEST_F(ApcictlRun, SelfApproachIsAWarningNamingBothBlocksOrAnErrorWhenAsked) {
    // A spike: N60 is 1.1 mm long, its neighbours come back within the tool's 5 mm of each
    // other, and each corner alone is an outside corner. The path of N70 cuts into N50.
    const std::string prog = write(
        "spike.nc",
        "N10 G17 G90 G26 D1 F600\nN20 G0 X-74.257 Y-49.657\nN30 G42 G1 X-35.095 Y-27.491\n"
        "N50 G1 X-4.063 Y-82.318\nN60 G1 X-4.273 Y-81.223\nN70 G1 X-34.475 Y-136.512\n"
        "N80 G1 X-50 Y-150\nN90 G40 G1 X-73.967 Y-114.939\nN100 M30\n");
    json doc = run_json(prog, {"--tools", tools(5.0), "--svg", path("s.svg")});
    EXPECT_TRUE(doc.at("errors").empty());
    ASSERT_FALSE(doc.at("warnings").empty());
    bool named = false;
    for (const auto& w : doc.at("warnings")) {
        EXPECT_EQ(w.at("code"), "SelfApproach");
        named |= w.at("block") == 70 &&
                 contains(w.at("message").get<std::string>(), "the tool path of N70 comes within") &&
                 contains(w.at("message").get<std::string>(), "of the contour at N50");
    }
    EXPECT_TRUE(named) << doc.at("warnings").dump();
    EXPECT_TRUE(contains(last_.out, "\nwarning: N70: SelfApproach: the tool path of N70"))
        << last_.out;
    EXPECT_TRUE(contains(read_text(path("s.svg")), ">N70 SelfApproach</text>"));
    // As an error the run stops there and exits 1.
    doc = run_json(prog, {"--tools", tools(5.0), "--self-approach", "error"}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "SelfApproach");
    // Off: nothing checked.
    doc = run_json(prog, {"--tools", tools(5.0), "--self-approach", "off"});
    EXPECT_FALSE(doc.contains("warnings"));
    // A contour that keeps its distance gets no warning: wr_quad_disc.nc's square with its lead-in.
    doc = run_json(kExamples + "/wr_quad_disc.nc",
                   {"--tools", kExamples + "/tools/wr_quad_disc.tools"});
    EXPECT_FALSE(doc.contains("warnings")) << doc.at("warnings").dump();
}

// A lead-out is held to the part as a lead-in is: the G40 block's move (the departure) that runs
// back through the part is warned against each wall it crosses, with the G40 block's number;
// one that leaves the exit corner as every control leaves it (within r of the corner, crossing
// nothing) is not.
TEST_F(ApcictlRun, SelfApproachWarnsALeadOutThroughThePartAndNotOnePastTheExitCorner) {
    // A boss 60 x 40 with rounded corners, a line and a tangent arc on and off; the G40 line
    // from the lead-out arc's offset end (-5, 22) runs right through the part to (75, 25).
    const std::string across =
        write("leadout_across.nc",
              "N10 G17 G90 D1 F800\nN20 G0 X-15 Y15\nN30 G41 G1 X-5 Y15\nN40 G3 X0 Y20 I0 J5\n"
              "N50 G1 Y35\nN60 G2 X5 Y40 I5 J0\nN70 G1 X55\nN80 G2 X60 Y35 I0 J-5\nN90 G1 Y5\n"
              "N100 G2 X55 Y0 I-5 J0\nN110 G1 X5\nN120 G2 X0 Y5 I0 J5\nN130 G1 Y20\n"
              "N140 G3 X-5 Y25 I-5 J0\nN150 G40 G1 X75 Y25\nN160 M30\n");
    json doc = run_json(across, {"--tools", tools(3.0)});
    EXPECT_TRUE(doc.at("errors").empty()) << doc.at("errors").dump();
    std::set<int> walls;
    for (const auto& w : doc.value("warnings", json::array())) {
        EXPECT_EQ(w.at("code"), "SelfApproach");
        EXPECT_EQ(w.at("block"), 150) << w.dump();
        const std::string m = w.at("message");
        EXPECT_TRUE(contains(m,
                             "(tool radius 3.0000 mm): the lead-out runs into the part there; "
                             "the path cuts ") &&
                    contains(m, " mm into it (end the lead-out clear of the part)"))
            << m;
        if (contains(m, "comes within 0.0000 mm") && contains(m, "cuts 3.0000 mm")) {
            if (contains(m, "of the contour at N50 ")) walls.insert(50);
            if (contains(m, "of the contour at N90 ")) walls.insert(90);
        }
    }
    EXPECT_EQ(walls, (std::set<int>{50, 90})) << doc.dump();
    // The same boss left back the way it came: nothing.
    const std::string back =
        write("leadout_back.nc",
              read_text(across).replace(read_text(across).find("X75 Y25"), 7, "X-15 Y25"));
    doc = run_json(back, {"--tools", tools(3.0)});
    EXPECT_FALSE(doc.contains("warnings")) << doc.at("warnings").dump();

    // A square boss closed at its start corner (0, 0), no lead arcs: the departure starts at
    // (0, -3), r below the last element N70's end.
    const auto square = [&](const std::string& to) {
        return write("leadout_square.nc",
                     "N10 G17 G90 D1 F600\nN20 G0 X-10 Y-10\nN30 G41 G1 X0 Y0\nN40 Y40\n"
                     "N50 X60\nN60 Y0\nN70 X0\nN80 G40 G1 " +
                         to + "\nN90 M30\n");
    };
    // Away past the corner: within 3 mm of the corner (2.34 mm), crossing nothing.
    doc = run_json(square("X-10 Y5"), {"--tools", tools(3.0)});
    EXPECT_FALSE(doc.contains("warnings")) << doc.at("warnings").dump();
    doc = run_json(square("X-10 Y-10"), {"--tools", tools(3.0)});
    EXPECT_FALSE(doc.contains("warnings")) << doc.at("warnings").dump();
    // Under G237 the board's own departure steps back from (0, -3) onto the programmed end
    // (0, 0), in N70's block: not held to the part (the programmer's end point), and the G40
    // block's move from there is uncompensated.
    doc = run_json(write("leadout_g237.nc",
                         "N10 G17 G90 D1 F600\nN20 G0 X-10 Y-10\nN25 G237\nN30 G41 G1 X0 Y0\n"
                         "N40 Y40\nN50 X60\nN60 Y0\nN70 X0\nN80 G40 G1 X-10 Y-10\nN90 M30\n"),
                   {"--tools", tools(3.0)});
    EXPECT_FALSE(doc.contains("warnings")) << doc.at("warnings").dump();
    // Its programmed end within the threshold (r less twice the path tolerance, 2.9998 mm: N70
    // is the element before it) of N70: the program's own choice, not held to N70; at the
    // threshold and beyond it is, and it crosses N70 into the part.
    doc = run_json(square("X10 Y2.9997"), {"--tools", tools(3.0)});
    EXPECT_FALSE(doc.contains("warnings")) << doc.at("warnings").dump();
    doc = run_json(square("X10 Y2.9998"), {"--tools", tools(3.0)});
    EXPECT_EQ(doc.value("warnings", json::array()).size(), 1u) << doc.dump();
    // ISG's #OTC example returns along the line it ground onto its start ("G40 X50 (WRK-Abwahl
    // mit Verfahrbewegung um WZR abzubauen)"): the program's end point, nothing warned.
    doc = run_json(kExamples + "/otc_general.nc",
                   {"--tools", kExamples + "/tools/wr_quad_disc.tools"});
    EXPECT_FALSE(doc.contains("warnings")) << doc.at("warnings").dump();
    // Back up through its own last element into the part: warned against N70.
    doc = run_json(square("X10 Y5"), {"--tools", tools(3.0)});
    ASSERT_EQ(doc.value("warnings", json::array()).size(), 1u) << doc.dump();
    EXPECT_EQ(doc.at("warnings")[0].at("block"), 80);
    EXPECT_TRUE(contains(doc.at("warnings")[0].at("message").get<std::string>(),
                         "the tool path of N80 comes within 0.0000 mm of the contour at N70 "))
        << doc.at("warnings")[0].dump();
}

// The warning says what came near what, and what to change: a lead-in through the part, two
// features too close (the paths of one near the other's walls), a contour near itself (the
// spike of SelfApproachIsAWarningNamingBothBlocksOrAnErrorWhenAsked).
TEST_F(ApcictlRun, SelfApproachSaysWhetherALeadTwoFeaturesOrOneContourComeNear) {
    const auto messages = [&](const std::string& name, const std::string& text, double r) {
        const json doc = run_json(write(name, text), {"--tools", tools(r)});
        std::map<int, std::vector<std::string>> by_block;
        for (const auto& w : doc.value("warnings", json::array()))
            by_block[w.at("block").get<int>()].push_back(w.at("message"));
        return by_block;
    };
    // A boss 60 x 40 whose lead-in comes from (75, 15), right through it.
    auto m = messages("lead_in_across.nc",
                      "N10 G17 G90 D1 F800\nN20 G0 X75 Y15\nN30 G41 G1 X-5 Y15\n"
                      "N40 G3 X0 Y20 I0 J5\nN50 G1 Y35\nN60 G2 X5 Y40 I5 J0\nN70 G1 X55\n"
                      "N80 G2 X60 Y35 I0 J-5\nN90 G1 Y5\nN100 G2 X55 Y0 I-5 J0\nN110 G1 X5\n"
                      "N120 G2 X0 Y5 I0 J5\nN130 G1 Y20\nN140 G3 X-5 Y25 I-5 J0\n"
                      "N150 G40 G1 X-15 Y25\nN160 M30\n",
                      3.0);
    ASSERT_EQ(m.size(), 1u);
    ASSERT_EQ(m[30].size(), 2u);  // against N90 and N130, the walls it crosses
    for (const std::string& text : m[30])
        EXPECT_TRUE(contains(text,
                             "(tool radius 3.0000 mm): the lead-in runs into the part "
                             "there; the path cuts 3.0000 mm into it (start the lead-in "
                             "clear of the part)"))
            << text;
    // Two square bosses 5 mm apart, each with its own G41 ... G40, a tool of radius 3: the
    // first one's right side and the second's left side.
    m = messages("two_bosses.nc",
                 "N10 G17 G90 D1 F600\nN20 G0 X-10 Y-10\nN30 G41 G1 X0 Y0\nN40 Y20\nN50 X20\n"
                 "N60 Y0\nN70 X0\nN80 G40 G1 X-10 Y-10\nN90 G0 X35 Y-10\nN100 G41 G1 X25 Y-3\n"
                 "N105 Y0\nN110 Y20\nN120 X45\nN130 Y0\nN140 X25\nN150 G40 G1 X35 Y-10\n"
                 "N160 M30\n",
                 3.0);
    bool features = false;
    for (const auto& [block, texts] : m)
        for (const std::string& text : texts) {
            EXPECT_TRUE(contains(text, "two features come that close there; the path cuts ") &&
                        contains(text, "(place them farther apart, or use a smaller tool)"))
                << block << ": " << text;
            features |= block == 60 && contains(text, "of the contour at N110 ") &&
                        contains(text, "comes within 2.0000 mm");
        }
    EXPECT_TRUE(features);
}

// A stretch whose path cuts back into its contour (a spike: N70's path comes within the tool
// radius of N50), its G40 at N90: the blocks after it are numbered from N200.
constexpr const char* kSpike =
    "N10 G17 G90 G26 D1 F600\nN20 G0 X-74.257 Y-49.657\nN30 G42 G1 X-35.095 Y-27.491\n"
    "N50 G1 X-4.063 Y-82.318\nN60 G1 X-4.273 Y-81.223\nN70 G1 X-34.475 Y-136.512\n"
    "N80 G1 X-50 Y-150\nN90 G40 G1 X-73.967 Y-114.939\n";

// The segments of blocks numbered 200 or more (those after kSpike).
int later_blocks(const json& doc) {
    int n = 0;
    for (const auto& s : doc.at("segments")) n += s.at("block").get<int>() >= 200;
    return n;
}

// As an error the self-approach check stops the run where it hands its finding: the spike's
// stretch, and then a second one far from it, which runs when the check only warns and not at
// all when it stops the run (no segment of its blocks is executed or reported).
TEST_F(ApcictlRun, SelfApproachAsAnErrorStopsTheRunBeforeTheBlocksAfterIt) {
    const std::string prog =
        write("spike2.nc", std::string(kSpike) +
                               "N200 G0 X200 Y200\nN210 G41 G1 X210 Y210\nN220 G1 X260\n"
                               "N230 G1 Y260\nN240 G40 G1 X300 Y300\nN250 M30\n");
    const json warned = run_json(prog, {"--tools", tools(5.0)});
    ASSERT_FALSE(warned.at("warnings").empty());
    EXPECT_GT(later_blocks(warned), 3);
    const json stopped = run_json(prog, {"--tools", tools(5.0), "--self-approach", "error"}, 1);
    ASSERT_EQ(stopped.at("errors").size(), 1u);
    EXPECT_EQ(stopped.at("errors")[0].at("code"), "SelfApproach");
    EXPECT_EQ(later_blocks(stopped), 0) << stopped.at("segments").dump();
}

// Stopped by the check on the embedded emulator (its own dry run: the board runs on with what
// was spooled), the run's outputs end where the check stopped it: the summary's time and the
// CSV's samples end with the last segment reported, as its path does. The whole program is one
// stretch here, so the finding comes only after every block was spooled.
TEST_F(ApcictlRun, SelfApproachAsAnErrorEndsTheTimeAndSamplesWithTheLastSegmentReported) {
    const std::string prog =
        write("neck.nc",
              "N10 G17 G90 D1 F700\nN20 G0 X-6 Y0\nN30 G41 G1 X-6 Y-6\nN40 G3 X0 Y-12 I6 J0\n"
              "N50 G3 X11.314 Y-4 I0 J12\nN60 G1 X38.686 Y-4\nN70 G3 X38.686 Y4 I11.314 J4\n"
              "N80 G1 X11.314 Y4\nN90 G3 X0 Y-12 I-11.314 J-4\nN100 G3 X6 Y-6 I0 J6\n"
              "N110 G40 G1 X6 Y0\nN120 M30\n");
    // The cycle the summary's time names: "time S s (C cycles of 1 ms)".
    const auto summary_cycles = [this]() -> long {
        const std::string out = last_.out;
        const std::size_t at = out.find(" cycles of ");
        if (at == std::string::npos) return -1;
        const std::size_t open = out.rfind('(', at);
        return std::stol(out.substr(open + 1, at - open - 1));
    };
    const json warned = run_json(prog, {"--tools", tools(5.0), "--csv", path("out.csv")});
    ASSERT_FALSE(warned.at("warnings").empty());
    const long all_cycles = summary_cycles();
    const auto warned_rows = test_support::read_csv(path("out.csv"));
    ASSERT_EQ(static_cast<long>(warned_rows.size()), all_cycles);

    const json stopped = run_json(
        prog, {"--tools", tools(5.0), "--csv", path("out.csv"), "--self-approach", "error"}, 1);
    ASSERT_EQ(stopped.at("errors").size(), 1u);
    EXPECT_EQ(stopped.at("errors")[0].at("code"), "SelfApproach");
    const auto& segments = stopped.at("segments");
    ASSERT_FALSE(segments.empty());
    ASSERT_LT(segments.size(), warned.at("segments").size());
    const long cycles = summary_cycles();
    EXPECT_GT(cycles, 0) << last_.out;
    EXPECT_LT(cycles, all_cycles) << last_.out;
    // One sample a cycle up to the stop, the last where the last segment reported ends.
    const auto rows = test_support::read_csv(path("out.csv"));
    ASSERT_EQ(static_cast<long>(rows.size()), cycles) << last_.out;
    EXPECT_EQ(static_cast<long>(rows.back()[0]), cycles);
    const apci::run::Point end = point(segments.back().at("end"));
    EXPECT_NEAR(rows.back()[2], end.x(), 1e-6);
    EXPECT_NEAR(rows.back()[3], end.y(), 1e-6);
    // The same motion as far as it went: its samples are the warned run's first ones.
    for (std::size_t i = 0; i < rows.size(); ++i) ASSERT_EQ(rows[i], warned_rows[i]) << i;
}

// The same stop found among the segments of a clock call within the program (the spooler full
// of the long tail after the spike), with a CSV (the samples read in chunks) and without: the
// run stops there either way, no segment of a later block is reported, and both report the
// same segments and error.
TEST_F(ApcictlRun, SelfApproachAsAnErrorStopsWithinTheProgramWithOrWithoutSamples) {
    std::string text = kSpike;
    for (int i = 0; i < 3000; ++i)
        text += fmt::format("N{} G1 X{} Y{}\n", 200 + i, 100 + (i % 2) * 10, 100 + i * 0.01);
    text += "N9000 M30\n";
    const std::string prog = write("spike_tail.nc", text);
    const json warned = run_json(prog, {"--tools", tools(5.0)});
    ASSERT_FALSE(warned.at("warnings").empty());
    ASSERT_EQ(later_blocks(warned), 3000);
    const json plain = run_json(prog, {"--tools", tools(5.0), "--self-approach", "error"}, 1);
    const std::string plain_out = last_.out;
    const json traced = run_json(
        prog, {"--tools", tools(5.0), "--self-approach", "error", "--csv", path("out.csv")}, 1);
    for (const json* doc : {&plain, &traced}) {
        ASSERT_EQ(doc->at("errors").size(), 1u) << doc->at("errors").dump();
        EXPECT_EQ(doc->at("errors")[0].at("code"), "SelfApproach");
        EXPECT_EQ(later_blocks(*doc), 0);
    }
    EXPECT_EQ(traced.at("segments"), plain.at("segments"));
    // The summary's first two lines (blocks sent, segments, path and time) are the same.
    const auto head = [](const std::string& out) {
        const std::size_t first = out.find('\n');
        return out.substr(0, out.find('\n', first + 1));
    };
    EXPECT_EQ(head(last_.out), head(plain_out));
}

// "G1 X<x> Y<y>" and a newline, y to 3 decimals.
std::string fmt_xy(double x, double y) {
    char text[64];
    std::snprintf(text, sizeof text, "G1 X%.1f Y%.4f\n", x, y);
    return text;
}

// The run's SelfApproach message for N40's path at distance d from the contour at N<n>, r 5.
std::string fmt_message(int n, double d) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "the tool path of N40 comes within %.4f mm of the contour at N%d (tool radius "
                  "5.0000 mm): the contour comes back near itself there, which no corner rule "
                  "sees; the path cuts %.4f mm into it (use a smaller tool, or give the contour "
                  "more room there)",
                  d, n, 5.0 - d);
    return text;
}

// A programmed line of block N<n> in the X-Y plane, as the check takes it.
apci::run::PathSegment programmed_line(int n, double x0, double y0, double x1, double y1) {
    apci::run::PathSegment s;
    s.block.number = n;
    s.start = {x0, y0, 0};
    s.end = {x1, y1, 0};
    return s;
}

// An executed segment of the JSON as the run's check takes it: block, role and rapids too.
apci::run::PathSegment executed_segment(const json& s) {
    using apci::run::Role;
    using apci::run::SegmentKind;
    apci::run::PathSegment out;
    out.block.number = s.at("block").get<std::int64_t>();
    out.block.line = s.value("line", std::uint64_t{0});
    const std::string kind = s.at("kind"), role = s.at("role");
    out.kind = kind == "arc" ? SegmentKind::kArc : kind == "rapid" ? SegmentKind::kRapid : SegmentKind::kLine;
    out.role = role == "contour"      ? Role::kContour
               : role == "transition" ? Role::kTransition
               : role == "approach"   ? Role::kApproach
               : role == "departure"  ? Role::kDeparture
                                      : Role::kUncompensated;
    out.start = point(s.at("start"));
    out.end = point(s.at("end"));
    if (out.kind == SegmentKind::kArc) {
        out.center = point(s.at("center"));
        out.ccw = s.at("ccw").get<bool>();
        out.plane = s.at("plane").get<int>();
    }
    return out;
}

TEST_F(ApcictlRun, SelfApproachReportsTheLeastDistanceToEveryElementTheOffsetCircleCrosses) {
    // A user's report: a line along y = 0 to (20, 0), a full circle G2 about (20, -10) back to
    // (20, 0), a line on along y = 0 to (40, 0), r = 5 (G41: the circle's path is its offset
    // outside, radius 15 about (20, -10)). That path crosses y = 0 at x = 20 -+ sqrt(15^2 - 10^2),
    // at (8.8197, 0) and at (31.1803, 0): the least distance to the line there is 0. The check
    // used to stop at the first point it found closer than r (0.6066 mm, t = 7/8 of the circle)
    // and took the stretch's last element for its departure although the G40 block departs.
    // The circle is a loop; the two elements before it and the two after it are its lead-in
    // and lead-out, no walls (wall_model.h): here the line is cut at x = 5, 10, 15 before the
    // circle and 25, 30 after it, so that the circle's path crosses N27 (5..10) and N47
    // (30..40), which are walls, and comes within 3.0278 mm of N26 (0..5), and passes over the
    // leads N28, N30, N45, N46 unreported.
    // N60 (the variant below) comes back under the circle: the least distance is
    // 27 - 10 - 15 = 2 mm at (20, -25).
    const double root = std::sqrt(125.0);
    const std::string head =
        "N10 D1 F1000\nN20 G0 X-10 Y0\nN25 G41 G1 X0 Y0\nN26 G1 X5\nN27 G1 X10\nN28 G1 X15\n"
        "N30 G1 X20 Y0\nN40 G2 X20 Y0 I0 J-10\nN45 G1 X25 Y0\nN46 G1 X30\nN47 G1 X40\n";
    struct Case {
        std::string tail;
        std::vector<apci::run::PathSegment> programmed;  // N25 .. (the check's elements)
        std::vector<std::tuple<int, double, Eigen::Vector2d>> expected;  // N, distance, where
    };
    const auto line = programmed_line;
    apci::run::PathSegment circle = line(40, 20, 0, 20, 0);
    circle.kind = apci::run::SegmentKind::kArc;
    circle.center = {20, -10, 0};
    const std::vector<apci::run::PathSegment> common{
        line(25, -10, 0, 0, 0), line(26, 0, 0, 5, 0),   line(27, 5, 0, 10, 0),
        line(28, 10, 0, 15, 0), line(30, 15, 0, 20, 0), circle,
        line(45, 20, 0, 25, 0), line(46, 25, 0, 30, 0), line(47, 30, 0, 40, 0)};
    std::vector<Case> cases(2);
    cases[0].tail = "N50 G40 G1 X50 Y0\nN60 M30\n";
    cases[0].programmed = common;
    // N26 (0..5) is a wall too: its end (5, 0) is sqrt(15^2 + 10^2) from the centre.
    const double far = std::sqrt(325.0);
    const Eigen::Vector2d near26 = Eigen::Vector2d(20, -10) + 15.0 / far * Eigen::Vector2d(-15, 10);
    cases[0].expected = {{26, far - 15.0, near26}, {27, 0.0, {20 - root, 0}}, {47, 0.0, {20 + root, 0}}};
    cases[1].tail = "N50 G1 X40 Y-27\nN60 G1 X0 Y-27\nN70 G1 X0 Y-40\nN80 G40 G1 X-10 Y-50\nN90 M30\n";
    cases[1].programmed = common;
    for (const auto& s : {line(50, 40, 0, 40, -27), line(60, 40, -27, 0, -27), line(70, 0, -27, 0, -40)})
        cases[1].programmed.push_back(s);
    cases[1].expected = cases[0].expected;
    cases[1].expected.emplace_back(60, 2.0, Eigen::Vector2d(20, -25));

    for (const Case& c : cases) {
        SCOPED_TRACE(c.tail);
        const json doc = run_json(write("q4.nc", head + c.tail), {"--tools", tools(5.0)});
        EXPECT_TRUE(doc.at("errors").empty()) << doc.at("errors").dump();
        // The run: one warning per wall the circle's path comes near, with its distance.
        ASSERT_EQ(doc.at("warnings").size(), c.expected.size()) << doc.at("warnings").dump();
        for (std::size_t i = 0; i < c.expected.size(); ++i) {
            const auto& [n, d, where] = c.expected[i];
            const json& w = doc.at("warnings")[i];
            EXPECT_EQ(w.at("block"), 40);
            EXPECT_EQ(w.at("message").get<std::string>(),
                      fmt_message(n, d)) << w.dump();
        }
        // The check itself on the run's segments: the least distances exactly.
        apci::run::SelfApproachCheck check;
        std::vector<apci::run::SelfApproachFinding> found;
        check.begin(5.0, 17);
        for (const auto& s : c.programmed) check.programmed(s, found);
        check.end(found);
        for (const auto& s : doc.at("segments")) check.executed(executed_segment(s), found);
        ASSERT_EQ(found.size(), c.expected.size());
        for (std::size_t i = 0; i < c.expected.size(); ++i) {
            const auto& [n, d, where] = c.expected[i];
            EXPECT_EQ(found[i].path_block.number, 40);
            EXPECT_EQ(found[i].contour_block.number, n);
            EXPECT_NEAR(found[i].distance, d, 1e-6) << "N" << n;
            EXPECT_EQ(found[i].radius, 5.0);
            EXPECT_LT((Eigen::Vector2d(found[i].where.x(), found[i].where.y()) - where).norm(), 1e-6)
                << "N" << n << ": " << found[i].where.transpose();
        }
    }
}

TEST_F(ApcictlRun, CdofMakesTheElementsAfterItNoWallsWhileTheirPathsAreStillChecked) {
    // The circle's path of the test above crosses N27 and N47 and comes within 3.0278 mm of
    // N26. Under CDOF, N26 and N27 are no walls (the program says they are not what it leaves
    // standing): only N47 is warned. A circle programmed under CDOF is no wall, but its path
    // is still held to the walls programmed under CDON: the three warnings stay.
    const std::string head = "N10 D1 F1000\nN20 G0 X-10 Y0\nN25 G41 G1 X0 Y0\n";
    const std::string tail = "N45 G1 X25 Y0\nN46 G1 X30\nN47 G1 X40\nN50 G40 G1 X50\nN60 M30\n";
    const auto warned = [&](const std::string& middle) {
        const json doc =
            run_json(write("cdof.nc", head + middle + tail), {"--tools", tools(5.0)});
        EXPECT_TRUE(doc.at("errors").empty()) << doc.at("errors").dump();
        std::vector<int> blocks;
        if (doc.contains("warnings"))
            for (const auto& w : doc.at("warnings")) {
                EXPECT_EQ(w.at("block"), 40) << w.dump();
                const std::string m = w.at("message");
                const auto at = m.find("contour at N");
                if (at != std::string::npos) blocks.push_back(std::stoi(m.substr(at + 12)));
            }
        return blocks;
    };
    EXPECT_EQ(warned("N26 CDOF G1 X5\nN27 G1 X10\nN28 CDON G1 X15\nN30 G1 X20\n"
                     "N40 G2 X20 Y0 I0 J-10\n"),
              (std::vector<int>{47}));
    EXPECT_EQ(warned("N26 G1 X5\nN27 G1 X10\nN28 G1 X15\nN30 G1 X20\n"
                     "N40 CDOF G2 X20 Y0 I0 J-10\nN42 CDON\n"),
              (std::vector<int>{26, 27, 47}));
}

TEST_F(ApcictlRun, SelfApproachComparesEachElementWithAWindowOfThoseBeforeIt) {
    // N30 runs along y = 0; the contour goes up, back along y = 50 in 14 steps, down at x = 30
    // and along y = 1.5 (N...: X20): its path (r 1, G41) is 0.5 from N30, and N30's path 0.5
    // from it. The check finds both with its window (16,384 elements); with a window of 4 it
    // has let N30 go by then, says so (truncated) and keeps no more than 2 * 4 elements and 6 * 4
    // paths.
    std::string prog =
        "N10 D1 F1000\nN20 G0 X-10 Y0\nN25 G41 G1 X0 Y0\nN30 G1 X100 Y0\nN40 G1 X100 Y50\n";
    std::vector<apci::run::PathSegment> programmed;
    const auto line = [&](int n, double x0, double y0, double x1, double y1) {
        apci::run::PathSegment s;
        s.block.number = n;
        s.start = {x0, y0, 0};
        s.end = {x1, y1, 0};
        programmed.push_back(s);
    };
    line(25, -10, 0, 0, 0);
    line(30, 0, 0, 100, 0);
    line(40, 100, 0, 100, 50);
    int n = 50;
    for (int x = 95; x >= 30; x -= 5, n += 10) {
        prog += "N" + std::to_string(n) + " G1 X" + std::to_string(x) + " Y50\n";
        line(n, x + 5, 50, x, 50);
    }
    const int down = n, back = n + 10;
    prog +=
        "N" + std::to_string(down) + " G1 X30 Y1.5\nN" + std::to_string(back) + " G1 X20 Y1.5\n";
    line(down, 30, 50, 30, 1.5);
    line(back, 30, 1.5, 20, 1.5);
    prog += "N" + std::to_string(back + 10) + " G40 G1 X20 Y20\nN" + std::to_string(back + 20) +
            " M30\n";
    const json doc = run_json(write("window.nc", prog), {"--tools", tools(1.0)});
    EXPECT_TRUE(doc.at("errors").empty()) << doc.at("errors").dump();
    const std::string near_n30 = "of the contour at N30 ";
    const std::string n30_near = "the tool path of N30 comes within 0.5000 mm of the contour at N" +
                                 std::to_string(back) + " ";
    bool found_near_n30 = false, found_n30_near = false;
    for (const auto& w : doc.value("warnings", json::array())) {
        const std::string m = w.at("message");
        found_near_n30 |=
            w.at("block") == back && contains(m, near_n30) && contains(m, "0.5000 mm");
        found_n30_near |= contains(m, n30_near);
    }
    EXPECT_TRUE(found_near_n30 && found_n30_near) << doc.dump();
    EXPECT_FALSE(doc.contains("notices")) << doc.at("notices").dump();
    // The check itself, fed as the run feeds it: each element, then the segments of the
    // element before it (one element of lookahead).
    const auto check_with = [&](std::size_t window, bool& truncated, std::size_t& most_kept) {
        apci::run::SelfApproachCheck check(window);
        std::vector<apci::run::SelfApproachFinding> found;
        check.begin(1.0, 17);
        std::size_t next = 0;
        const json& segments = doc.at("segments");
        const auto execute_to = [&](std::int64_t block) {
            for (;
                 next < segments.size() && segments[next].at("block").get<std::int64_t>() <= block;
                 ++next)
                check.executed(executed_segment(segments[next]), found);
        };
        most_kept = 0;
        for (std::size_t k = 0; k < programmed.size(); ++k) {
            check.programmed(programmed[k], found);
            if (k > 0) execute_to(programmed[k - 1].block.number);
            most_kept = std::max(most_kept, check.kept());
        }
        check.end(found);
        execute_to(back + 20);
        truncated = check.limits().truncated;
        return found;
    };
    bool truncated = true;
    std::size_t most_kept = 0;
    auto found = check_with(apci::run::SelfApproachCheck::kWindow, truncated, most_kept);
    EXPECT_FALSE(truncated);
    const auto involves_n30 = [](const apci::run::SelfApproachFinding& f) {
        return f.path_block.number == 30 || f.contour_block.number == 30;
    };
    // N30's path near the elements coming down and back, and their paths (the one coming
    // down with its transition round (30, 1.5)) near N30: 0.5 mm each.
    std::set<std::pair<std::int64_t, std::int64_t>> pairs;
    for (const auto& f : found) {
        if (!involves_n30(f)) continue;
        pairs.emplace(f.path_block.number, f.contour_block.number);
        EXPECT_NEAR(f.distance, 0.5, 1e-9);
    }
    const std::set<std::pair<std::int64_t, std::int64_t>> expected{
        {30, down}, {30, back}, {down, 30}, {back, 30}};
    EXPECT_EQ(pairs, expected);
    found = check_with(4, truncated, most_kept);
    EXPECT_TRUE(truncated);
    EXPECT_EQ(std::count_if(found.begin(), found.end(), involves_n30), 0);
    EXPECT_LE(most_kept, 8u * 4u);
}

// A compensated stretch as the check takes it: the tool radius and its programmed elements.
using CheckStretch = std::pair<double, std::vector<apci::run::PathSegment>>;

// The findings of a check fed as the run feeds it, in G17 (each element, then the executed
// segments of the element before: one element of lookahead; a stretch's rest when it ends;
// then every segment left), its candidates from the grid or every pair.
std::vector<apci::run::SelfApproachFinding> feed_check(
    const json& segments, const std::vector<CheckStretch>& stretches,
    apci::run::SelfApproachCheck::Candidates candidates) {
    apci::run::SelfApproachCheck check(apci::run::SelfApproachCheck::kWindow,
                                       apci::run::SelfApproachCheck::kEntryBudget, candidates);
    std::vector<apci::run::SelfApproachFinding> found;
    std::size_t next = 0;
    const auto execute_to = [&](std::int64_t block) {
        for (; next < segments.size() && segments[next].at("block").get<std::int64_t>() <= block;
             ++next)
            check.executed(executed_segment(segments[next]), found);
    };
    for (const auto& [r, elements] : stretches) {
        check.begin(r, 17);
        for (std::size_t k = 0; k < elements.size(); ++k) {
            check.programmed(elements[k], found);
            if (k > 0) execute_to(elements[k - 1].block.number);
        }
        check.end(found);
        if (!elements.empty()) execute_to(elements.back().block.number + 9);
    }
    execute_to(std::numeric_limits<std::int64_t>::max());
    return found;
}

// The same findings in the same order, to the bit.
void expect_same_findings(const std::vector<apci::run::SelfApproachFinding>& a,
                          const std::vector<apci::run::SelfApproachFinding>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].path_block.number, b[i].path_block.number);
        EXPECT_EQ(a[i].contour_block.number, b[i].contour_block.number);
        EXPECT_EQ(a[i].distance, b[i].distance);
        EXPECT_EQ(a[i].where, b[i].where);
    }
}

TEST_F(ApcictlRun, SelfApproachGridFindsWhatComparingEveryPairFinds) {
    // Random G41 contours as CAM writes them (3 decimals; lines and arcs from 0.6 to 26 mm, so
    // that both short elements, listed by their box, and long ones, listed by samples, come;
    // crossing themselves, and running back alongside after sharp turns) run through apcictl
    // (tool radius 0.5 mm); their programmed elements and executed segments fed to the check
    // with its grid, and to the check that compares every pair. The findings must be the same,
    // to the bit, and the run's warnings as many. (With the grid's reach halved, this fails.)
    std::mt19937_64 rng(424242);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const auto r3 = [](double v) { return std::round(v * 1000.0) / 1000.0; };
    int with_findings = 0, total_findings = 0;
    for (int program = 0; program < 40; ++program) {
        std::string text = "N10 D1 F2000\nN20 G0 X0 Y0\n";
        std::vector<apci::run::PathSegment> programmed;
        double x = 0, y = 0, heading = 0;
        bool long_line = false;  // the element before is a line of 6 mm or more
        int n = 30;
        for (int k = 0; k < 60; ++k, n += 10) {
            // Now and then a sharp turn between two long lines, after which the contour runs
            // back alongside itself.
            const bool sharp = long_line && u(rng) < 0.3;
            const double pick = u(rng);
            const double len = sharp        ? 6 + 8 * u(rng)
                               : pick < 0.3 ? 0.6 + 0.6 * u(rng)
                               : pick < 0.7 ? 1.2 + 5 * u(rng)
                                            : 6 + 20 * u(rng);
            heading +=
                sharp ? (u(rng) < 0.5 ? -1 : 1) * (2.6 + 0.3 * u(rng)) : 1.8 * (u(rng) - 0.5);
            long_line = false;
            apci::run::PathSegment s;
            s.block.number = n;
            s.start = {x, y, 0};
            const char* head = k == 0 ? "G41 " : "";
            if (k == 0 || sharp || u(rng) < 0.5) {
                const double nx = r3(x + len * std::cos(heading)),
                             ny = r3(y + len * std::sin(heading));
                if (std::hypot(nx - x, ny - y) < 0.005) continue;
                text += fmt::format("N{} {}G1 X{:.3f} Y{:.3f}\n", n, head, nx, ny);
                long_line = len >= 6;
                s.end = {nx, ny, 0};
                x = nx, y = ny;
            } else {
                // An arc of radius len / turn about a centre to the left or right.
                const double turn = std::min(0.2 + 2.5 * u(rng), len / 1.5);
                const double radius = len / turn;
                const bool ccw = u(rng) < 0.5;
                const double side = ccw ? 1.0 : -1.0;
                const double cx = r3(x - side * radius * std::sin(heading));
                const double cy = r3(y + side * radius * std::cos(heading));
                const double a0 = std::atan2(y - cy, x - cx) + side * turn;
                const double rr = std::hypot(x - cx, y - cy);
                const double nx = r3(cx + rr * std::cos(a0)), ny = r3(cy + rr * std::sin(a0));
                if (std::hypot(nx - x, ny - y) < 0.005) continue;
                text += fmt::format("N{} {} X{:.3f} Y{:.3f} I{:.3f} J{:.3f}\n", n,
                                    ccw ? "G3" : "G2", nx, ny, r3(cx - x), r3(cy - y));
                s.kind = apci::run::SegmentKind::kArc;
                s.ccw = ccw;
                s.center = {cx, cy, 0};
                s.end = {nx, ny, 0};
                heading += side * turn;
                x = nx, y = ny;
            }
            programmed.push_back(s);
        }
        text +=
            fmt::format("N{} G40 G1 X{:.3f} Y{:.3f}\nN{} M30\n", n, r3(x + 5), r3(y + 5), n + 10);
        const std::string prog = write("random.nc", text);
        std::remove(path("out.json").c_str());
        last_ = apcictl({"run", prog, "--json", path("out.json"), "--tools", tools(0.5)});
        if (!exists(path("out.json"))) continue;
        const json doc = json::parse(read_text(path("out.json")));
        const std::vector<CheckStretch> stretches{{0.5, programmed}};
        const auto grid = feed_check(doc.at("segments"), stretches,
                                     apci::run::SelfApproachCheck::Candidates::kGrid);
        EXPECT_EQ(grid.size(), doc.value("warnings", json::array()).size());
        SCOPED_TRACE(text);
        expect_same_findings(grid, feed_check(doc.at("segments"), stretches,
                                              apci::run::SelfApproachCheck::Candidates::kAll));
        with_findings += !grid.empty();
        total_findings += static_cast<int>(grid.size());
    }
    // The programs run and come near themselves: the comparison is not of empty lists only.
    EXPECT_GE(with_findings, 20);
    EXPECT_GE(total_findings, 200);
}

TEST_F(ApcictlRun, AProgramLongerThanTheSelfApproachWindowGetsANotice) {
    // 2 * kWindow + 232 distinct elements under G41: a zigzag along X. More than twice the
    // window: the check lets the oldest go (its memory stays bounded) and the run says so.
    // Teeth of 0.5 mm along X (the board's range is +-100,000 mm) with a tool of 0.5 mm.
    constexpr int kWindow = static_cast<int>(apci::run::SelfApproachCheck::kWindow);
    std::string prog = "N10 D1 F3000\nN20 G0 X0 Y0\nN30 G41 G1 X0.5 Y0\n";
    for (int k = 0; k < 2 * kWindow + 232; ++k)
        prog += fmt_xy(1.0 + 0.5 * k, ((k % 2) * 0.5 + (k % 7) * 0.001) / 2.0);
    prog += "G40 G1 X" + std::to_string(kWindow + 2000) + " Y10\nM30\n";
    const json doc = run_json(write("long.nc", prog), {"--tools", tools(0.5)});
    EXPECT_TRUE(doc.at("errors").empty()) << doc.at("errors").dump();
    EXPECT_FALSE(doc.contains("warnings")) << doc.at("warnings").dump();
    ASSERT_TRUE(doc.contains("notices"));
    ASSERT_EQ(doc.at("notices").size(), 1u) << doc.at("notices").dump();
    EXPECT_EQ(doc.at("notices")[0].at("code"), "SelfApproachTruncated");
    EXPECT_TRUE(contains(doc.at("notices")[0].at("message").get<std::string>(),
                         "from here on the self-approach check compared each compensated element "
                         "in G17 only with the " + std::to_string(kWindow) +
                             " distinct elements before it"))
        << doc.at("notices")[0].dump();
    // Where: the block that let the first go, at twice the window (the program's
    // (2 * kWindow)th element, on line 2 * kWindow + 2: the G41 block's move on line 3 is the
    // first).
    EXPECT_EQ(doc.at("notices")[0].at("line"), 2 * kWindow + 2) << doc.at("notices")[0].dump();
    EXPECT_TRUE(contains(last_.out, "notice: line " + std::to_string(2 * kWindow + 2) +
                                        ": from here on the self-approach check"))
        << last_.out;
}

TEST_F(ApcictlRun, SelfApproachTakesTheFirstMoveInThePlaneForTheApproach) {
    // A rectangle whose last side runs back over the lead-in N50 (which the check exempts, as
    // the board runs N50 as the approach). A plunge in Z after G41, or G41 G1 to the point where
    // the tool stands, does not move in the plane: N50 stays the approach, with no warning. (The
    // plunge used to be taken for the approach, and N80 warned against N50.)
    const std::string tail =
        "N50 G1 X60 Y0 F1000\nN60 G1 X60 Y40\nN70 G1 X0 Y40\nN80 G1 X0 Y0\n"
        "N90 G40 G1 X-10 Y-10\nN100 M30\n";
    for (const std::string& start :
         {std::string("N30 G41\n"), std::string("N30 G41\nN40 G1 Z-1 F300\n"),
          std::string("N30 G41 G1 X0 Y0 F1000\n")}) {
        SCOPED_TRACE(start);
        const json doc =
            run_json(write("ap.nc", "N10 G17 G90 D1\nN20 G0 X0 Y0 Z0\n" + start + tail),
                     {"--tools", tools(5.0)});
        EXPECT_TRUE(doc.at("errors").empty()) << doc.at("errors").dump();
        EXPECT_FALSE(doc.contains("warnings")) << doc.at("warnings").dump();
        bool n50_approach = false;
        for (const auto& seg : doc.at("segments"))
            n50_approach |= seg.at("block") == 50 && seg.at("role") == "approach";
        EXPECT_TRUE(n50_approach);
    }
}

TEST_F(ApcictlRun, SelfApproachFindsTheSameAfterALargerToolMakesTheGridCoarser) {
    // A first stretch with a 0.1 mm tool sets the grid's cells to 0.5 mm; the second, with a
    // 5 mm tool, makes them 10 mm (every item listed again). Its path passes 3 mm from the first
    // stretch's contour (N14), and its contour comes back alongside itself 6 mm away: what the
    // run warns is what comparing every pair finds.
    const std::string tools2 = write("t2.tools",
                                     "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n"
                                     "wz[2].gueltig 1\nwz[2].mass_einheit 1\nwz[2].radius 0.1\n");
    const std::string prog =
        "N10 G17 G90 F1000\nN11 D2\nN12 G0 X55 Y4 Z0\nN13 G41 G1 X60 Y8\nN14 G1 X70 Y8\n"
        "N15 G1 X70 Y18\nN16 G40 G1 X75 Y20\nN17 D1\nN20 G0 X-10 Y10\nN30 G41 G1 X0 Y0\n"
        "N40 G1 X100 Y0\nN50 G1 X120\nN60 G1 Y-30\nN70 G1 X-20\nN80 G1 Y-6\nN90 G1 X50\n"
        "N100 G1 Y-50\nN110 G40 G1 X60 Y-60\nN120 M30\n";
    const json doc = run_json(write("coarser.nc", prog), {"--tools", tools2});
    EXPECT_TRUE(doc.at("errors").empty()) << doc.at("errors").dump();
    const json warnings = doc.value("warnings", json::array());
    ASSERT_FALSE(warnings.empty());
    const auto line = programmed_line;
    const std::vector<CheckStretch> stretches{
        {0.1, {line(13, 55, 4, 60, 8), line(14, 60, 8, 70, 8), line(15, 70, 8, 70, 18)}},
        {5.0,
         {line(30, -10, 10, 0, 0), line(40, 0, 0, 100, 0), line(50, 100, 0, 120, 0),
          line(60, 120, 0, 120, -30), line(70, 120, -30, -20, -30), line(80, -20, -30, -20, -6),
          line(90, -20, -6, 50, -6), line(100, 50, -6, 50, -50)}}};
    const auto grid =
        feed_check(doc.at("segments"), stretches, apci::run::SelfApproachCheck::Candidates::kGrid);
    ASSERT_EQ(grid.size(), warnings.size());
    bool n40_near_n14 = false;
    for (std::size_t i = 0; i < grid.size(); ++i) {
        n40_near_n14 |= grid[i].path_block.number == 40 && grid[i].contour_block.number == 14;
        EXPECT_EQ(grid[i].path_block.number, warnings[i].at("block").get<std::int64_t>());
    }
    EXPECT_TRUE(n40_near_n14);
    expect_same_findings(grid, feed_check(doc.at("segments"), stretches,
                                          apci::run::SelfApproachCheck::Candidates::kAll));
}

TEST_F(ApcictlRun, SelfApproachLeavesContoursBelowTheToolTipOut) {
    // Two levels of a round boss milled from the top down (tool radius 5, G41 outside a
    // clockwise circle): Z0 radius 20, then Z-1 radius 20.05 (a draft) or 19.95 (an undercut). The
    // upper level's path comes within 4.95 mm of the lower contour, but the tool's tip at Z0 never
    // reaches Z-1: no warning. The lower level's path comes within 4.95 mm of the upper contour
    // with the undercut, and its flank cuts it: warnings. (Both levels warned before, the draft
    // too.)
    for (const double lower : {20.05, 19.95}) {
        SCOPED_TRACE(lower);
        std::string prog = "N10 G17 G90 D1 F1000\nN20 G0 X40 Y0 Z0\n";
        prog += "N30 G41 G1 X20 Y0\nN40 G2 X20 Y0 I-20 J0\nN50 G40 G1 X40 Y0\n";
        prog += fmt::format(
            "N60 G1 Z-1\nN70 G41 G1 X{0:.2f} Y0\nN80 G2 X{0:.2f} Y0 I{1:.2f} J0\n"
            "N90 G40 G1 X40 Y0\nN100 M30\n",
            lower, -lower);
        const json doc = run_json(write("levels.nc", prog), {"--tools", tools(5.0)});
        EXPECT_TRUE(doc.at("errors").empty()) << doc.at("errors").dump();
        const json warnings = doc.value("warnings", json::array());
        if (lower > 20.0) {
            EXPECT_TRUE(warnings.empty()) << warnings.dump();
        } else {
            // The lower level's approach (N70, to the circle's offset start) and its circle.
            ASSERT_EQ(warnings.size(), 2u) << warnings.dump();
            EXPECT_EQ(warnings[0].at("message").get<std::string>().substr(0, 69),
                      "the tool path of N70 comes within 4.9500 mm of the contour at N40 (to");
            EXPECT_EQ(warnings[1].at("message").get<std::string>().substr(0, 69),
                      "the tool path of N80 comes within 4.9500 mm of the contour at N40 (to");
        }
    }
}

TEST_F(ApcictlRun, MoreThanAThousandPairsComingNearAreCappedWithANotice) {
    // 100 bosses of radius 10 (four quarter arcs each, its own G42 stretch, tool radius 5)
    // whose centres lie 0.01 mm apart along X: each boss's path comes within 5 - 0.01 |k - j|
    // of every other boss j, and none encloses another (wall_model.h: they overlap), so every
    // one is a wall. The first 1,000 pairs are warned; the run says there were more, and stops
    // looking (the run stays quick however many bosses follow).
    std::string prog = "N10 G17 G90 D1\nN20 G0 X30 Y-30 Z0\n";
    int n = 30;
    for (int k = 0; k < 100; ++k) {
        const double cx = 0.01 * k, r = 10.0;
        prog += fmt::format("N{} G42 G1 X{:.3f} Y0 F6000\n", n, cx + r), n += 10;
        const double pts[4][2] = {{0, r}, {-r, 0}, {0, -r}, {r, 0}};
        double sx = r, sy = 0;
        for (const auto& p : pts) {
            prog += fmt::format("N{} G3 X{:.3f} Y{:.3f} I{:.3f} J{:.3f}\n", n, cx + p[0], p[1],
                                -sx, -sy);
            n += 10, sx = p[0], sy = p[1];
        }
        prog += fmt::format("N{} G40 G1 X30 Y-30\n", n), n += 10;
    }
    prog += fmt::format("N{} M30\n", n);
    const json doc = run_json(write("circles.nc", prog), {"--tools", tools(5.0)});
    EXPECT_TRUE(doc.at("errors").empty()) << doc.at("errors").dump();
    EXPECT_EQ(doc.at("warnings").size(), apci::run::SelfApproachCheck::kMaxFindings);
    ASSERT_TRUE(doc.contains("notices"));
    bool capped = false;
    for (const auto& notice : doc.at("notices"))
        capped |= notice.at("code") == "SelfApproachCapped" &&
                  contains(notice.at("message").get<std::string>(),
                           "more than 1000 pairs of blocks come near each other: the first 1000 "
                           "are reported");
    EXPECT_TRUE(capped) << doc.at("notices").dump();
}

TEST_F(ApcictlRun, RapidMovesAreRapidAndUncompensated) {
    const std::string prog = write("g0.nc", "N10 G0 X10 Y5\nM30\n");
    const json doc = run_json(prog);
    ASSERT_EQ(doc.at("segments").size(), 1u);
    EXPECT_EQ(doc.at("segments")[0].at("kind"), "rapid");
    EXPECT_EQ(doc.at("segments")[0].at("role"), "uncompensated");
    EXPECT_TRUE(contains(last_.out, "(rapid 11.180 mm)")) << last_.out;
}

}  // namespace
