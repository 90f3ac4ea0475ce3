// SPDX-License-Identifier: MIT
// `apcictl run` on the embedded emulator, the tool radius compensation: [ISG-OTC-EN]'s
// wr_quad_disc.nc, one program per corner type (docs/figures/), closed contours, switching
// sides, the same run through the daemon's socket, planes, tool length, the CSV's cycles.
#include <gtest/gtest.h>

#include <set>

#include "apcictl_run.h"
#include "plate_program.h"

namespace {

using namespace apcictl_run_test;

// ---- wr_quad_disc.nc of [ISG-OTC-EN]

TEST_F(ApcictlRun, MustShowWrQuadDiscSummaryJsonAndSvg) {
    const auto r = apcictl({"run", kExamples + "/wr_quad_disc.nc", "--tools",
                            kExamples + "/tools/wr_quad_disc.tools", "--svg", path("p.svg"),
                            "--json", path("p.json")});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    // 11 segments: N40, the approach N60, 4 contour elements, 4 transitions, N100.
    EXPECT_TRUE(contains(r.out, "wr_quad_disc.nc: 11 blocks, 11 sent to the board, 11 segments executed\n")) << r.out;
    EXPECT_TRUE(contains(r.out, "\nerrors: none\n")) << r.out;
    EXPECT_EQ(r.err, "");
    const json doc = json::parse(read_text(path("p.json")));
    // As the program's text says: N22 G25 makes the corner after N70 linear (two lines along
    // the tangents, a 90-degree turn), N80 G26 the corners after N80 and N90 circular. The
    // program runs in G139 (indirect): N60, the first move after N55 G42, is the approach (no
    // contour of its own), and G40 spools N95 to its offset end; the G40 block's move N100 is
    // the departure, from there to its programmed end.
    EXPECT_EQ(roles(doc),
              "uncompensated/40 approach/60 contour/70 transition/70 transition/70 "
              "contour/80 transition/80 contour/90 transition/90 contour/95 departure/100");
    expect_continuous(doc);
    // The approach runs straight from where the tool stands, (0, 0), to N60's compensated end:
    // 30 mm right of its programmed end (2, 0) (G42, N60 along +X), where N70's offset starts
    // (N60 and N70 are collinear: no corner).
    const auto approach = with_role(doc, "approach");
    ASSERT_EQ(approach.size(), 1u);
    EXPECT_EQ(approach[0].at("kind"), "line");
    EXPECT_EQ(point(approach[0].at("start")), apci::run::Point(0, 0, 0));
    EXPECT_EQ(point(approach[0].at("end")), apci::run::Point(2, -30, 0));
    // N100 (G40 G1 X0) starts at N95's offset end, 30 mm right of (2, 0) going -Y: (-28, 0).
    const auto off = with_role(doc, "departure");
    ASSERT_EQ(off.size(), 1u);
    EXPECT_EQ(off[0].at("block"), 100);
    EXPECT_EQ(point(off[0].at("start")), apci::run::Point(-28, 0, 0));
    EXPECT_EQ(point(off[0].at("end")), apci::run::Point(0, 0, 0));
    const auto linear = with_role(doc, "transition");
    ASSERT_EQ(linear.size(), 4u);
    EXPECT_EQ(linear[0].at("kind"), "line");
    EXPECT_EQ(point(linear[0].at("end")), apci::run::Point(132, -30, 0));
    EXPECT_EQ(point(linear[1].at("end")), apci::run::Point(132, 0, 0));
    EXPECT_EQ(linear[2].at("kind"), "arc");
    EXPECT_EQ(linear[3].at("kind"), "arc");
    // The square N70..N95 (N60 is its lead-in on the same line, run as the approach): every
    // contour element and the circular transitions at 30 mm, the linear one no closer.
    const std::vector<geom::Element> square{
        geom::make_line({2, 0}, {102, 0}), geom::make_line({102, 0}, {102, 100}),
        geom::make_line({102, 100}, {2, 100}), geom::make_line({2, 100}, {2, 0})};
    expect_at_radius(doc, square, 30.0, {"contour"});
    expect_at_radius(doc, square, 30.0, {"transition"}, false, 17, {70});
    expect_at_radius(doc, square, 30.0, {"transition"}, true, 17, {80, 90});
    // G42 on a counter-clockwise loop: the tool runs outside, right of the direction of travel;
    // the first contour element N70 starts where the approach ended.
    EXPECT_EQ(with_role(doc, "contour")[0].at("block"), 70);
    EXPECT_EQ(point(with_role(doc, "contour")[0].at("start")), apci::run::Point(2, -30, 0));
    expect_registers_clear(doc);
    // The OTC variables by their names in [ISG-OTC] (no #OTC here: no wear; D1's wear constant).
    EXPECT_EQ(doc.at("variables").at("V.G.OTC_ACTIVE"), 0);
    EXPECT_EQ(doc.at("variables").at("V.G.WZ_AKT.WEAR_RADIUS"), 0);
    EXPECT_EQ(doc.at("variables").at("V.G.WZ_AKT.WEAR[2]"), 0);
    EXPECT_EQ(doc.at("variables").at("V.G.WZ_AKT.WEAR_CONST"), 100000);
    EXPECT_EQ(doc.at("errors"), json::array());
    const std::string svg = read_text(path("p.svg"));
    for (const char* cls :
         {"programmed", "contour", "transition", "approach", "departure", "uncompensated"})
        EXPECT_TRUE(contains(svg, std::string("<path class=\"") + cls + "\"")) << cls;
}

// A figure program (docs/figures) with G237 in its first block N10: the board's own
// perpendicular approach and departure instead of the NC start state G139.
std::string figure_with_g237(const std::string& name) {
    std::string text = read_text(kFigures + "/" + name);
    const std::size_t at = text.find("\nN10 ");
    EXPECT_NE(at, std::string::npos) << name;
    if (at != std::string::npos) text.insert(at + 5, "G237 ");
    return text;
}

// ---- One program per corner type (docs/figures)

const std::vector<geom::Element> kInsideCorners{
    geom::make_line({0, 0}, {40, 0}), geom::make_line({40, 0}, {40, 30}),
    geom::make_arc({60, 0}, {100, 0}, {80, 20}, true),
    geom::make_arc({100, 0}, {75, 25}, {75, 0}, true)};

// The NC start state G139: the first element of each stretch (N40, N90) is the approach, straight
// (N40) or LinuxCNC's entry arc (N90) to its offset end, trimmed at the inside corner.
TEST_F(ApcictlRun, InsideCornerIsTrimmedAtTheIntersectionOfTheOffsetElements) {
    const json doc =
        run_json(kFigures + "/tc-inside-corners.nc", {"--tools", kFigures + "/tc-figures.tools"});
    EXPECT_TRUE(with_role(doc, "transition").empty()) << roles(doc);
    EXPECT_TRUE(with_role(doc, "departure").empty()) << roles(doc);
    expect_continuous(doc);
    const auto approach = with_role(doc, "approach");
    const auto contour = with_role(doc, "contour");
    ASSERT_EQ(approach.size(), 2u) << roles(doc);
    ASSERT_EQ(contour.size(), 2u) << roles(doc);
    // line-line: the approach N40 runs from (0, 0) straight to the intersection (35, 5) of the
    // offset lines y = 5 (N40, G41 along +X) and x = 35 (N50 along +Y), where N50 starts.
    EXPECT_EQ(approach[0].at("block"), 40);
    EXPECT_EQ(approach[0].at("kind"), "line");
    EXPECT_EQ(point(approach[0].at("start")), apci::run::Point(0, 0, 0));
    EXPECT_LT((point(approach[0].at("end")) - apci::run::Point(35, 5, 0)).norm(), 1e-9);
    EXPECT_EQ(contour[0].at("block"), 50);
    EXPECT_LT((point(contour[0].at("start")) - apci::run::Point(35, 5, 0)).norm(), 1e-9);
    expect_at_radius(doc, kInsideCorners, 5.0, {"contour"});
    // arc-arc: the approach N90 ends where both offset arcs (radii 28.28 - 5 and 25 - 5) meet,
    // and N100's offset arc starts there.
    EXPECT_EQ(approach[1].at("block"), 90);
    EXPECT_EQ(contour[1].at("block"), 100);
    EXPECT_EQ(approach[1].at("kind"), "arc");
    EXPECT_EQ(contour[1].at("kind"), "arc");
    const apci::run::Point corner = point(approach[1].at("end"));
    EXPECT_LT((corner - point(contour[1].at("start"))).norm(), 1e-9);
    EXPECT_NEAR((corner - apci::run::Point(80, 20, 0)).norm(), std::sqrt(800.0) - 5.0, kTol);
    EXPECT_NEAR((point(contour[1].at("start")) - apci::run::Point(75, 0, 0)).norm(), 20.0, kTol);
    // The entry arc: from the tool at (60, 0), counter-clockwise as N90, about a centre on the
    // line from its end to N90's centre (80, 20), on the same side: it arrives along the offset
    // arc's tangent.
    EXPECT_EQ(point(approach[1].at("start")), apci::run::Point(60, 0, 0));
    EXPECT_EQ(approach[1].at("ccw"), true);
    const apci::run::Point c = point(approach[1].at("center"));
    const apci::run::Point to_c = c - corner;
    const apci::run::Point to_programmed = apci::run::Point(80, 20, 0) - corner;
    EXPECT_NEAR(to_c.x() * to_programmed.y() - to_c.y() * to_programmed.x(), 0.0, kTol);
    EXPECT_GT(to_c.dot(to_programmed), 0.0);
    EXPECT_NEAR((c - apci::run::Point(60, 0, 0)).norm(), to_c.norm(), kTol);
    expect_registers_clear(doc);
}

// G237, the board's perpendicular approach: N40 and N90 run whole as offset elements, and both
// offset elements of each corner are cut back to their intersection.
TEST_F(ApcictlRun, InsideCornerUnderG237TrimsBothOffsetElements) {
    const json doc = run_json(write("inside.nc", figure_with_g237("tc-inside-corners.nc")),
                              {"--tools", kFigures + "/tc-figures.tools"});
    EXPECT_TRUE(with_role(doc, "transition").empty()) << roles(doc);
    expect_continuous(doc);
    // line-line: N40 ends and N50 starts at the intersection (35, 5) of the offset lines.
    const auto contour = with_role(doc, "contour");
    ASSERT_GE(contour.size(), 4u);
    EXPECT_EQ(contour[0].at("block"), 40);
    EXPECT_LT((point(contour[0].at("end")) - apci::run::Point(35, 5, 0)).norm(), 1e-9);
    EXPECT_EQ(contour[1].at("block"), 50);
    expect_at_radius(doc, kInsideCorners, 5.0, {"contour"});
    // arc-arc: both offset arcs (radii 28.28 - 5 and 25 - 5) end and start at one point.
    EXPECT_EQ(contour[2].at("kind"), "arc");
    EXPECT_EQ(contour[3].at("kind"), "arc");
    EXPECT_LT((point(contour[2].at("end")) - point(contour[3].at("start"))).norm(), 1e-9);
    EXPECT_NEAR((point(contour[2].at("end")) - apci::run::Point(80, 20, 0)).norm(),
                std::sqrt(800.0) - 5.0, kTol);
    EXPECT_NEAR((point(contour[3].at("start")) - apci::run::Point(75, 0, 0)).norm(), 20.0, kTol);
    // Perpendicular approach onto each first offset element's start, departure back to the
    // programmed end of each last element.
    EXPECT_EQ(roles(doc),
              "uncompensated/20 approach/40 contour/40 contour/50 departure/50 uncompensated/70 "
              "approach/90 contour/90 contour/100 departure/100");
    expect_registers_clear(doc);
}

TEST_F(ApcictlRun, OutsideCornerGetsACircularTransitionAboutTheCorner) {
    const json doc =
        run_json(kFigures + "/tc-outside-circular.nc", {"--tools", kFigures + "/tc-figures.tools"});
    const auto transitions = with_role(doc, "transition");
    ASSERT_EQ(transitions.size(), 2u) << roles(doc);
    EXPECT_EQ(transitions[0].at("block"), 40);  // belongs to the element before the corner
    EXPECT_EQ(transitions[0].at("kind"), "arc");
    EXPECT_EQ(point(transitions[0].at("center")), apci::run::Point(40, 0, 0));
    EXPECT_EQ(transitions[0].at("ccw"), true);  // G42: counter-clockwise round the corner
    EXPECT_EQ(transitions[1].at("block"), 50);
    EXPECT_EQ(point(transitions[1].at("center")), apci::run::Point(40, 30, 0));
    expect_continuous(doc);
    expect_at_radius(doc,
                     {geom::make_line({0, 0}, {40, 0}), geom::make_line({40, 0}, {40, 30}),
                      geom::make_arc({40, 30}, {20, 30}, {30, 20}, true)},
                     5.0, {"contour", "transition"});
}

TEST_F(ApcictlRun, LinearTransitionExtendsTheOffsetsAndIsBoundedBeyond90Degrees) {
    const json doc =
        run_json(kFigures + "/tc-outside-linear.nc", {"--tools", kFigures + "/tc-figures.tools"});
    std::vector<json> at60, at150;
    for (const auto& t : with_role(doc, "transition")) {
        EXPECT_EQ(t.at("kind"), "line");
        (t.at("block") == 40 ? at60 : at150).push_back(t);
    }
    // 60 degrees: two lines meeting at the tangent intersection, r / cos(30) from the corner.
    ASSERT_EQ(at60.size(), 2u) << roles(doc);
    EXPECT_NEAR((point(at60[0].at("end")) - apci::run::Point(40, 0, 0)).norm(),
                5.0 / std::cos(std::numbers::pi / 6), kTol);
    // 150 degrees: A extended by exactly r, a chamfer, B's start reached backwards by r.
    ASSERT_EQ(at150.size(), 3u) << roles(doc);
    EXPECT_NEAR(segment_length(segment_of(at150[0])), 5.0, kTol);
    EXPECT_NEAR(segment_length(segment_of(at150[2])), 5.0, kTol);
    expect_continuous(doc);
    const std::vector<geom::Element> contour{
        geom::make_line({0, 0}, {40, 0}), geom::make_line({40, 0}, {55, 25.980762}),
        geom::make_line({70, 0}, {110, 0}), geom::make_line({110, 0}, {75.358984, 20})};
    expect_at_radius(doc, contour, 5.0, {"contour"});
    expect_at_radius(doc, contour, 5.0, {"transition"}, /*at_least=*/true);
}

// tc-closed-contour.nc's plate with its lead-in N40 and lead-out N150.
const std::vector<geom::Element> kPlate{
    geom::make_line({30, -20}, {30, 0}), geom::make_line({30, 0}, {80, 0}),
    geom::make_line({80, 0}, {80, 30}),  geom::make_arc({80, 30}, {60, 50}, {60, 30}, true),
    geom::make_line({60, 50}, {45, 50}), geom::make_line({45, 50}, {45, 35}),
    geom::make_line({45, 35}, {35, 35}), geom::make_line({35, 35}, {35, 50}),
    geom::make_line({35, 50}, {0, 50}),  geom::make_line({0, 50}, {0, 0}),
    geom::make_line({0, 0}, {30, 0}),    geom::make_line({30, 0}, {30, -20})};

// G139 (the NC start state): the lead-in N40 is the approach, the lead-out N150 the last contour
// element, and G40 alone in N160 leaves the tool at N150's offset end (no departure).
TEST_F(ApcictlRun, ClosedContourKeepsTheRadiusFromTheApproachToTheLastOffsetEnd) {
    const json doc =
        run_json(kFigures + "/tc-closed-contour.nc", {"--tools", kFigures + "/tc-figures.tools"});
    const auto approach = with_role(doc, "approach");
    ASSERT_EQ(approach.size(), 1u);
    EXPECT_TRUE(with_role(doc, "departure").empty()) << roles(doc);
    // From the start point straight to N40's offset end, trimmed at the inside corner with N50:
    // x = 35 (5 right of N40 going +Y) meets y = -5 (5 right of N50 going +X) at (35, -5).
    EXPECT_EQ(approach[0].at("block"), 40);
    EXPECT_EQ(point(approach[0].at("start")), apci::run::Point(30, -20, 0));
    EXPECT_EQ(point(approach[0].at("end")), apci::run::Point(35, -5, 0));
    const auto contour = with_role(doc, "contour");
    ASSERT_FALSE(contour.empty());
    EXPECT_EQ(contour.front().at("block"), 50);
    EXPECT_EQ(point(contour.front().at("start")), apci::run::Point(35, -5, 0));
    // The path ends with N150's offset, 5 left of it (right of -Y): at (25, -20).
    const json& last = doc.at("segments").back();
    EXPECT_EQ(last.at("block"), 150);
    EXPECT_EQ(last.at("role"), "contour");
    EXPECT_EQ(point(last.at("end")), apci::run::Point(25, -20, 0));
    expect_continuous(doc);
    // Every contour element after the approach, N50 to N150, and every transition at r.
    expect_at_radius(doc, kPlate, 5.0, {"contour", "transition"});
    expect_registers_clear(doc);
}

// G237 (the board's own): a perpendicular approach onto N40's offset start, N40 run whole, and
// the departure at right angles from N150's offset back to its programmed end.
TEST_F(ApcictlRun, ClosedContourUnderG237KeepsTheRadiusWithPerpendicularApproachAndDeparture) {
    const json doc = run_json(write("closed.nc", figure_with_g237("tc-closed-contour.nc")),
                              {"--tools", kFigures + "/tc-figures.tools", "--svg", path("c.svg")});
    const auto approach = with_role(doc, "approach");
    const auto departure = with_role(doc, "departure");
    ASSERT_EQ(approach.size(), 1u);
    ASSERT_EQ(departure.size(), 1u);
    EXPECT_EQ(approach[0].at("block"), 40);  // the first compensated element
    EXPECT_EQ(point(approach[0].at("start")), apci::run::Point(30, -20, 0));
    EXPECT_EQ(point(approach[0].at("end")), apci::run::Point(35, -20, 0));
    EXPECT_EQ(with_role(doc, "contour").front().at("block"), 40);
    EXPECT_EQ(departure[0].at("block"), 150);  // the last
    EXPECT_EQ(point(departure[0].at("start")), apci::run::Point(25, -20, 0));
    EXPECT_EQ(point(departure[0].at("end")), apci::run::Point(30, -20, 0));
    expect_continuous(doc);
    expect_at_radius(doc, kPlate, 5.0, {"contour", "transition"});
    expect_registers_clear(doc);
    const std::string svg = read_text(path("c.svg"));
    for (const char* cls : {"approach", "departure"})
        EXPECT_TRUE(contains(svg, std::string("<path class=\"") + cls + "\"")) << cls;
}

// More profiles than the spooler holds: Busy makes the executor run the clock and spool again;
// every block runs, in order, and the path stays r from the contour throughout.
TEST_F(ApcictlRun, ProgramLongerThanTheSpoolerRunsWhole) {
    const std::string text = apci::test::plate_program(100);
    const json doc = run_json(write("long.nc", text), {"--tools", tools(1.0)});
    EXPECT_TRUE(contains(last_.out, ": 1205 blocks, 1205 sent to the board, ")) << last_.out;
    expect_continuous(doc);
    int last_block = 0;
    std::set<int> contour_blocks;
    for (const auto& s : doc.at("segments")) {
        const int b = s.at("block").get<int>();
        EXPECT_GE(b, last_block) << s.dump();  // in program order
        if (s.at("role") == "contour") contour_blocks.insert(b);
        last_block = b;
    }
    // G139: N4, the first move after N3 G41, is the approach (one line from (10, 0) to its
    // offset end (40, 1), 1 left of (40, 0); N5's arc joins it tangentially); N5..N1203 are
    // contour (1199 blocks), and N1204 G40 leaves the tool at N1203's offset end (10, 1).
    const auto approach = with_role(doc, "approach");
    ASSERT_EQ(approach.size(), 1u);
    EXPECT_EQ(approach[0].at("block"), 4);
    EXPECT_EQ(point(approach[0].at("start")), apci::run::Point(10, 0, 0));
    EXPECT_LT((point(approach[0].at("end")) - apci::run::Point(40, 1, 0)).norm(), 1e-9);
    EXPECT_EQ(contour_blocks.size(), 1199u);
    EXPECT_EQ(*contour_blocks.begin(), 5);
    EXPECT_EQ(*contour_blocks.rbegin(), 1203);
    EXPECT_LT((point(doc.at("segments").back().at("end")) - apci::run::Point(10, 1, 0)).norm(),
              1e-9);
    expect_at_radius(
        doc,
        {geom::make_line({10, 0}, {40, 0}), geom::make_arc({40, 0}, {50, 10}, {40, 10}, true),
         geom::make_line({50, 10}, {50, 30}), geom::make_arc({50, 30}, {40, 40}, {40, 30}, true),
         geom::make_line({40, 40}, {30, 40}), geom::make_line({30, 40}, {30, 30}),
         geom::make_line({30, 30}, {20, 30}), geom::make_line({20, 30}, {20, 40}),
         geom::make_line({20, 40}, {10, 40}), geom::make_arc({10, 40}, {0, 30}, {10, 30}, true),
         geom::make_line({0, 30}, {0, 10}), geom::make_arc({0, 10}, {10, 0}, {10, 10}, true)},
        1.0, {"contour", "transition"});
}

// G139: the G42 block ends the left stretch at N30's offset end (no departure) and is the
// approach of the right one, straight from there to its own offset end.
TEST_F(ApcictlRun, SwitchingSidesApproachesTheOtherSideFromTheLastOffsetEnd) {
    const std::string prog = write("sides.nc",
                                   "N10 F1000 D1\nN20 G41 G1 X10\nN30 X20\nN40 G42 X30\nN50 X40\n"
                                   "N60 G40 X50\nM30\n");
    const json doc = run_json(prog, {"--tools", tools(2.0)});
    EXPECT_EQ(roles(doc), "approach/20 contour/30 approach/40 contour/50 departure/60")
        << doc.dump();
    expect_continuous(doc);
    const auto approach = with_role(doc, "approach");
    const auto contour = with_role(doc, "contour");
    ASSERT_EQ(approach.size(), 2u);
    ASSERT_EQ(contour.size(), 2u);
    // r = 2, along +X: G41 left (y = 2), G42 right (y = -2), each approach to its element's
    // offset end, the G40 move N60 from the last offset end (40, -2) to (50, 0).
    EXPECT_EQ(point(approach[0].at("start")), apci::run::Point(0, 0, 0));
    EXPECT_EQ(point(approach[0].at("end")), apci::run::Point(10, 2, 0));
    EXPECT_EQ(point(contour[0].at("end")), apci::run::Point(20, 2, 0));   // G41: left
    EXPECT_EQ(point(approach[1].at("start")), apci::run::Point(20, 2, 0));
    EXPECT_EQ(point(approach[1].at("end")), apci::run::Point(30, -2, 0));
    EXPECT_EQ(point(contour[1].at("end")), apci::run::Point(40, -2, 0));  // G42: right
    const json& off = doc.at("segments").back();
    EXPECT_EQ(point(off.at("start")), apci::run::Point(40, -2, 0));
    EXPECT_EQ(point(off.at("end")), apci::run::Point(50, 0, 0));
}

// G237: each side's stretch departs at right angles back to its programmed end, and the next
// approaches at right angles onto its first offset element.
TEST_F(ApcictlRun, SwitchingSidesUnderG237DepartsAndApproachesAgain) {
    const std::string prog = write("sides.nc",
                                   "N10 G237 F1000 D1\nN20 G41 G1 X10\nN30 X20\nN40 G42 X30\n"
                                   "N50 X40\nN60 G40 X50\nM30\n");
    const json doc = run_json(prog, {"--tools", tools(2.0)});
    EXPECT_EQ(roles(doc),
              "approach/20 contour/20 contour/30 departure/30 approach/40 contour/40 contour/50 "
              "departure/50 uncompensated/60")
        << doc.dump();
    EXPECT_NEAR(point(with_role(doc, "contour")[1].at("end")).y(), 2.0, kTol);   // G41: left
    EXPECT_NEAR(point(with_role(doc, "contour")[3].at("end")).y(), -2.0, kTol);  // G42: right
}

// The figures of docs/compensation.md are what apcictl draws now (scripts/tc_figures.sh
// redraws them). Run from the source root, so the titles name the programs as the script does.
TEST_F(ApcictlRun, CompensationFiguresAreCurrent) {
    const std::string cwd = std::filesystem::current_path();
    std::filesystem::current_path(APCI_SOURCE_DIR);
    int figures = 0;
    for (const auto& entry : std::filesystem::directory_iterator("docs/figures")) {
        const std::string name = entry.path().filename();
        if (name.rfind("tc-", 0) != 0 || entry.path().extension() != ".nc") continue;
        const std::string program = "docs/figures/" + name;
        const std::string svg = program.substr(0, program.size() - 3) + ".svg";
        const auto r = apcictl({"run", program, "--tools", "docs/figures/tc-figures.tools", "--svg",
                                path("figure.svg")});
        const bool shows_error = name.find("-error.nc") != std::string::npos;
        EXPECT_EQ(r.exit_code, shows_error ? 1 : 0) << name << r.err;
        EXPECT_TRUE(exists(svg)) << svg;
        EXPECT_EQ(read_text(path("figure.svg")), read_text(svg))
            << svg << " is stale: run scripts/tc_figures.sh";
        ++figures;
    }
    std::filesystem::current_path(cwd);
    EXPECT_EQ(figures, 8);
}

// The executor uses libapci only, so the run is the same through the emulator daemon's socket
// as on the embedded board: the same JSON, byte for byte.
TEST_F(ApcictlRun, SamePathThroughTheDaemonSocketAsOnTheEmbeddedBoard) {
    const std::string socket = path("emu.sock");
    const pid_t daemon = start_daemon(socket);
    ASSERT_GT(daemon, 0);
    ASSERT_TRUE(exists(socket));
    const std::vector<std::string> args{"run", kExamples + "/wr_quad_disc.nc", "--tools",
                                        kExamples + "/tools/wr_quad_disc.tools", "--json"};
    auto via_socket = args;
    via_socket.push_back(path("socket.json"));
    via_socket.insert(via_socket.begin(), {"--device", "unix:" + socket});
    const auto r = apcictl(via_socket);
    ::kill(daemon, SIGTERM);
    ::waitpid(daemon, nullptr, 0);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto embedded = args;
    embedded.push_back(path("emu.json"));
    ASSERT_EQ(apcictl(embedded).exit_code, 0);
    EXPECT_EQ(read_text(path("socket.json")), read_text(path("emu.json")));
}

// ---- Planes and tool length

TEST_F(ApcictlRun, ZxPlaneCompensatesArcsInThatPlaneSeenFromPlusY) {
    // G18: first axis Z, second X. A G3 half circle in Z-X and lines, G41.
    const std::string prog = write("zx.nc",
                                   "N10 G18 G26 F1000 D1\nN20 G41 G1 Z20\nN30 G3 Z40 X0 K10 I0\n"
                                   "N40 G1 Z60\nN50 G40\nM30\n");
    const json doc = run_json(prog, {"--tools", tools(3.0)});
    bool saw_arc = false;
    for (const auto& s : doc.at("segments")) {
        if (s.at("kind") != "arc") continue;
        saw_arc = true;
        EXPECT_EQ(s.at("plane"), 18) << s.dump();
        EXPECT_NEAR(point(s.at("start")).y(), 0.0, kTol);
    }
    EXPECT_TRUE(saw_arc);
    // Plane coordinates of G18: (Z, X).
    expect_at_radius(
        doc,
        {geom::make_line({0, 0}, {20, 0}), geom::make_arc({20, 0}, {40, 0}, {30, 0}, true),
         geom::make_line({40, 0}, {60, 0})},
        3.0, {"contour", "transition"}, false, 18);
}

TEST_F(ApcictlRun, ToolLengthIsTakenOffTheToolCentrePointButMovesTheAxis) {
    const std::string prog =
        write("len.nc", "N10 F6000 D1\nN20 G41 G1 X10 Y0 Z-1\nN30 X20\nN40 G40\nM30\n");
    const json doc = run_json(prog, {"--tools", tools(1.0, 25.0), "--csv", path("len.csv")});
    for (const auto& s : doc.at("segments")) {
        if (s.at("role") == "approach") continue;  // from Z 0 down to the programmed Z -1
        EXPECT_NEAR(point(s.at("end")).z(), -1.0, kTol) << s.dump();
    }
    // The axis itself carries the length: Z = -1 + 25 while compensating.
    const std::string csv = read_text(path("len.csv"));
    std::istringstream lines(csv);
    std::string line, header;
    std::getline(lines, header);
    EXPECT_EQ(header, "cycle,time_s,X,Y,Z,A,B,C,U,V");
    int on_n30 = 0;
    while (std::getline(lines, line)) {
        std::vector<double> v;
        std::stringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');) v.push_back(std::stod(cell));
        ASSERT_EQ(v.size(), 10u) << line;
        if (v[2] > 10.5 && v[2] < 19.5) {  // on N30, programmed Z -1 throughout
            EXPECT_NEAR(v[4], 24.0, kTol) << line;
            ++on_n30;
        }
    }
    EXPECT_GT(on_n30, 50);
}

TEST_F(ApcictlRun, CsvHasOneLineForEveryCycle) {
    const std::string prog = write("csv.nc", "N10 G1 X1 F600\nM30\n");  // 1 mm at 10 mm/s: 100 ms
    const auto r = apcictl({"run", prog, "--csv", path("c.csv")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "time 0.100 s (100 cycles of 1 ms)")) << r.out;
    const std::string csv = read_text(path("c.csv"));
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);
    std::uint64_t n = 0;
    std::string last;
    while (std::getline(lines, line)) {
        ++n;
        EXPECT_EQ(line.substr(0, line.find(',')), std::to_string(n));
        last = line;
    }
    EXPECT_EQ(n, 100u);
    EXPECT_EQ(last, "100,0.1,1,0,0,0,0,0,0,0");
}

}  // namespace
