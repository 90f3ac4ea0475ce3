// SPDX-License-Identifier: MIT
// `apcictl run`'s approach and departure as the controls make them (G139, G138, G237), rapids
// under compensation, the tool length, turning tools, the board's refusals.
#include <gtest/gtest.h>

#include "apcictl_run.h"

namespace {

using namespace apcictl_run_test;

// ---- Approach and departure as the controls make them (G139, the NC programs' initial state)

// A segment's plane end point, for the points the reproductions name.
Eigen::Vector2d xy(const json& p) { return {p[0].get<double>(), p[1].get<double>()}; }

TEST_F(ApcictlRun, TheSelectionBlockIsTheApproachStraightToTheOffsetPointAtItsEnd) {
    // G0 X-10 Y-10, G41 G1 X0 Y0, G1 X20 Y0 (tool radius 0.5): LinuxCNC's entry move and the
    // ISG selection block: one line from (-10, -10) to the point at r left of (0, 0), at right
    // angles to the block, then the corner (G26: an arc about (0, 0)) onto the next element.
    const std::string prog = write("in.nc",
                                   "N10 D1 F1000 G26\nN20 G0 X-10 Y-10\nN30 G41 G1 X0 Y0\n"
                                   "N40 G1 X20 Y0\nN50 G40 G1 X30 Y-10\nN60 M30\n");
    const json doc = run_json(prog, {"--tools", tools(0.5)});
    EXPECT_EQ(roles(doc), "uncompensated/20 approach/30 transition/30 contour/40 departure/50");
    const json approach = with_role(doc, "approach").at(0);
    const double h = 0.5 / std::sqrt(2.0);
    EXPECT_LT((xy(approach.at("start")) - Eigen::Vector2d(-10, -10)).norm(), 1e-9);
    EXPECT_LT((xy(approach.at("end")) - Eigen::Vector2d(-h, h)).norm(), 1e-9);
    const json corner = with_role(doc, "transition").at(0);
    EXPECT_EQ(corner.at("kind"), "arc");
    EXPECT_LT((xy(corner.at("end")) - Eigen::Vector2d(0, 0.5)).norm(), 1e-9);
    expect_continuous(doc);
}

TEST_F(ApcictlRun, TheG40BlockIsTheDepartureFromTheLastOffsetPoint) {
    // G1 X20 Y0, then G40 G1 X30 Y-10: the G40 block itself is the departure, from (20, 0.5) to
    // (30, -10); no move back onto the programmed point first.
    const std::string prog = write("out.nc",
                                   "N10 D1 F1000\nN20 G0 X-10 Y0\nN30 G41 G1 X0 Y0\n"
                                   "N40 G1 X20 Y0\nN50 G40 G1 X30 Y-10\nN60 M30\n");
    const json doc = run_json(prog, {"--tools", tools(0.5)});
    EXPECT_EQ(with_role(doc, "departure").size(), 1u) << roles(doc);
    const json& last = doc.at("segments").back();
    EXPECT_EQ(last.at("block"), 50);
    EXPECT_EQ(last.at("role"), "departure");
    EXPECT_LT((xy(last.at("start")) - Eigen::Vector2d(20, 0.5)).norm(), 1e-9);
    EXPECT_LT((xy(last.at("end")) - Eigen::Vector2d(30, -10)).norm(), 1e-9);
    expect_continuous(doc);
}

// The selection word of a lone G40's own block decides how it leaves the contour: G237 G40
// departs at right angles at once (the board's departure), so the arc after it runs from the
// programmed point; G139 G40 leaves the departure to the next move, and an arc there is refused
// before anything runs.
TEST_F(ApcictlRun, ALoneG40DepartsByTheSelectionWordOfItsOwnBlock) {
    const json doc = run_json(write("g237.nc", "N10 D1 F1000\nN20 G0 X-10 Y0\nN30 G41 G1 X0 Y0\n"
                                               "N40 G1 X20 Y0\nN50 G237 G40\n"
                                               "N60 G2 X30 Y-10 I0 J-10\nN70 M30\n"),
                              {"--tools", tools(0.5)});
    EXPECT_EQ(roles(doc), "uncompensated/20 approach/30 contour/40 departure/40 uncompensated/60");
    ASSERT_FALSE(doc.at("segments").empty());
    const json& arc = doc.at("segments").back();
    EXPECT_EQ(arc.at("kind"), "arc");
    EXPECT_LT((xy(arc.at("start")) - Eigen::Vector2d(20, 0)).norm(), 1e-9);
    EXPECT_LT((xy(arc.at("end")) - Eigen::Vector2d(30, -10)).norm(), 1e-9);
    const std::string refused = write("g139.nc", "N10 D1 F1000 G237\nN20 G0 X-10 Y0\n"
                                                 "N30 G41 G1 X0 Y0\nN40 G1 X20 Y0\nN50 G139 G40\n"
                                                 "N60 G2 X30 Y-10 I0 J-10\nN70 M30\n");
    const auto r = apcictl({"run", refused, "--tools", tools(0.5)});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "G2 right after G40: under G139")) << r.err;
    EXPECT_TRUE(contains(r.err, "g139.nc:6:5: N60: ")) << r.err;
}

// G138 ([ISG-PROG]'s direct selection): the G41 block runs straight to the next element's offset
// start, with no corner; the G40 block departs from the last offset end, as under G139.
TEST_F(ApcictlRun, G138SelectsDirectlyOntoTheNextElementsOffsetStart) {
    const json doc = run_json(write("g138.nc", "N10 D1 F1000 G138\nN20 G0 X-10 Y-10\n"
                                               "N30 G41 G1 X0 Y0\nN40 G1 X20 Y0\n"
                                               "N50 G40 G1 X30 Y-10\nN60 M30\n"),
                              {"--tools", tools(0.5)});
    EXPECT_EQ(roles(doc), "uncompensated/20 approach/30 contour/40 departure/50");
    const json approach = with_role(doc, "approach").at(0);
    EXPECT_LT((xy(approach.at("start")) - Eigen::Vector2d(-10, -10)).norm(), 1e-9);
    EXPECT_LT((xy(approach.at("end")) - Eigen::Vector2d(0, 0.5)).norm(), 1e-9);
    expect_continuous(doc);
}

TEST_F(ApcictlRun, G237KeepsTheBoardsPerpendicularApproachAndDeparture) {
    // The board's own way (SelectionMode 237): a right-angle approach onto the first element's
    // offset start, the element whole, and a right-angle departure back to the programmed end.
    const std::string prog = write("g237.nc",
                                   "N10 D1 F1000 G237\nN20 G0 X-10 Y0\nN30 G41 G1 X0 Y0\n"
                                   "N40 G1 X20 Y0\nN50 G40 G1 X30 Y-10\nN60 M30\n");
    const json doc = run_json(prog, {"--tools", tools(0.5)});
    EXPECT_EQ(roles(doc),
              "uncompensated/20 approach/30 contour/30 contour/40 departure/40 uncompensated/50");
    const json approach = with_role(doc, "approach").at(0);
    EXPECT_LT((xy(approach.at("end")) - Eigen::Vector2d(-10, 0.5)).norm(), 1e-9);
    const json departure = with_role(doc, "departure").at(0);
    EXPECT_LT((xy(departure.at("start")) - Eigen::Vector2d(20, 0.5)).norm(), 1e-9);
    EXPECT_LT((xy(departure.at("end")) - Eigen::Vector2d(20, 0)).norm(), 1e-9);
    expect_continuous(doc);
}

TEST_F(ApcictlRun, AG0UnderG41IsCompensatedSoALiftStaysBesideTheContour) {
    // Lifting with G0 Z5 while G41 is on: the tool rises where it stands, at r from the contour,
    // instead of crossing onto the programmed point at depth.
    const std::string prog = write("lift.nc",
                                   "N10 D1 F1000\nN20 G0 X-10 Y0 Z-2\nN30 G41 G1 X0 Y0\n"
                                   "N40 G1 X20 Y0\nN50 G0 Z5\nN60 G40 G0 X30 Y10\nN70 M30\n");
    const json doc = run_json(prog, {"--tools", tools(0.5)});
    bool lifted = false;
    for (const auto& s : doc.at("segments")) {
        if (s.at("block") != 50 || s.at("end")[2].get<double>() != 5.0) continue;
        lifted = true;
        EXPECT_LT((xy(s.at("start")) - Eigen::Vector2d(20, 0.5)).norm(), 1e-9) << s.dump();
        EXPECT_LT((xy(s.at("end")) - Eigen::Vector2d(20, 0.5)).norm(), 1e-9) << s.dump();
    }
    EXPECT_TRUE(lifted) << roles(doc);
    expect_continuous(doc);
}

// [ISG-OTC] section 2: "Eilgangssätze sind verschleißfrei!" A G0 under G41 runs on the
// compensated path and is still a rapid: kind rapid (role contour) in the JSON, counted as rapid
// in the summary, and wear-free: only N50's 100 mm of contour wear (1 mm). The same through the
// daemon's socket, where the segments travel as frames.
TEST_F(ApcictlRun, AG0UnderG41IsARapidOnTheCompensatedPathAndWearsNothing) {
    const std::string prog =
        write("g0.nc", "N10 D1\nN20 #OTC ON [RADIUS CONT]\nN30 G41 G1 X50 F1000\nN40 G0 X500\n"
                       "N50 G1 X600\nN60 G40 X650\nN70 #OTC OFF\nN80 M30\n");
    const std::string socket = path("emu.sock");
    const pid_t daemon = start_daemon(socket);
    ASSERT_GT(daemon, 0);
    const json via_socket = run_json(prog, {"--tools", kExamples + "/tools/wr_quad_disc.tools",
                                            "--device", "unix:" + socket});
    ::kill(daemon, SIGTERM);
    ::waitpid(daemon, nullptr, 0);
    const json doc = run_json(prog, {"--tools", kExamples + "/tools/wr_quad_disc.tools"});
    EXPECT_EQ(via_socket, doc);
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR_RADIUS").get<double>(), 1.0, 1e-9);
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR_RADIUS_CONT").get<double>(), 1.0, 1e-9);
    bool seen = false;
    for (const auto& s : doc.at("segments")) {
        if (s.at("block") != 40) {
            EXPECT_NE(s.at("kind"), "rapid") << s.dump();
            continue;
        }
        seen = true;
        EXPECT_EQ(s.at("kind"), "rapid") << s.dump();
        EXPECT_EQ(s.at("role"), "contour") << s.dump();
        EXPECT_EQ(point(s.at("start")), apci::run::Point(50, 30, 0));
        EXPECT_EQ(point(s.at("end")), apci::run::Point(500, 30, 0));
    }
    EXPECT_TRUE(seen) << roles(doc);
    EXPECT_TRUE(contains(last_.out, "(rapid 450.000 mm)")) << last_.out;
}

TEST_F(ApcictlRun, TheToolLengthHoldsFromTheToolsSelectionNotOnlyUnderG42) {
    // wr_quad_disc.nc: D1 (length 50 mm) at N22, G42 at N55, G40 at N100. The Z axis takes the
    // length with N40, the first move after D1, and keeps it through the approach, the contour
    // and the departure: no lift at G42, no drop at G40 (as an NC control applies a tool length).
    const auto r = apcictl({"run", kExamples + "/wr_quad_disc.nc", "--tools",
                            kExamples + "/tools/wr_quad_disc.tools", "--csv", path("z.csv")});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    std::istringstream csv(read_text(path("z.csv")));
    std::string line;
    std::getline(csv, line);  // header: cycle,time_s,X,Y,Z,...
    std::size_t rows = 0, at_length = 0;
    double last_z = 0.0;
    while (std::getline(csv, line)) {
        std::vector<double> v;
        std::stringstream fields(line);
        for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
        ASSERT_GE(v.size(), 5u);
        ++rows;
        last_z = v[4];
        if (v[4] == 50.0) ++at_length;
    }
    ASSERT_GT(rows, 1000u);
    // N40 rises from 0 to 50 at its feed (F600: 10 mm/s, 5000 cycles); from then on Z is 50.
    EXPECT_EQ(at_length, rows - 4999) << "Z left the tool length somewhere";
    EXPECT_EQ(last_z, 50.0);
}

// The CSV's axes carry the tool length in Klartext programs too, from the TOOL CALL on, as a
// TNC applies it (docs/compensation.md "Tool length"), with and without RL: Z = 10 + 25 along
// N3 (R0) and N4 (RL). The JSON gives the tip, Z 10.
TEST_F(ApcictlRun, KlartextAxesCarryTheToolLengthFromTheToolCall) {
    const std::string prog =
        write("len.h", "0 BEGIN PGM LEN MM\n1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+10 R0 F6000\n"
                       "3 L X+10 R0\n4 L X+20 RL\n5 L X+30 R0\n6 M30\n7 END PGM LEN MM\n");
    const json doc = run_json(prog, {"--tools", tools(1.0, 25.0), "--csv", path("k.csv")});
    for (const auto& seg : doc.at("segments"))
        EXPECT_NEAR(point(seg.at("end")).z(), 10.0, kTol) << seg.dump();
    std::istringstream lines(read_text(path("k.csv")));
    std::string line;
    std::getline(lines, line);  // header
    int rows = 0, at_length = 0;
    double last_z = 0.0;
    while (std::getline(lines, line)) {
        std::vector<double> v;
        std::stringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');) v.push_back(std::stod(cell));
        ++rows;
        last_z = v[4];
        if (v[2] > 0.0) {  // from N3 on: X moves, Z stays at the tip plus the length
            EXPECT_NEAR(v[4], 35.0, kTol) << line;
            ++at_length;
        }
    }
    EXPECT_GT(at_length, 100);
    EXPECT_NEAR(last_z, 35.0, kTol);
}

// A turning tool (docs/compensation.md "Turning tools"): with its cutting edge position the
// reported path is the imaginary tip, the nose centre's path carried over by the position's
// offset, approach and departure included: cutting edge 3 with a 2 mm nose radius in G18 moves
// the compensated path by +2 on X and -2 on Z against the same run with the nose centre
// (srk_lage 9); the uncompensated moves before and after stay.
TEST_F(ApcictlRun, ATurningToolsPathIsItsImaginaryTip) {
    const std::string prog = write("turn.nc", "N10 D5 G18 F500\nN20 G0 X10 Z5\nN30 G42 G1 X8\n"
                                              "N40 G1 Z-20\nN50 G1 X12 Z-25\nN60 G40 G1 X15\n"
                                              "N70 G0 Z5\nN80 M30\n");
    const auto list = [&](int edge) {
        return write("t" + std::to_string(edge) + ".tools",
                     "wz[5].gueltig 1\nwz[5].typ 1\nwz[5].mass_einheit 1\nwz[5].radius 2\n"
                     "wz[5].srk_lage " + std::to_string(edge) + "\n");
    };
    const json centre = run_json(prog, {"--tools", list(9)});
    const json tip = run_json(prog, {"--tools", list(3)});
    ASSERT_EQ(roles(tip), roles(centre));
    const apci::run::Point carried(2, 0, -2);  // position 3: X +r, Z -r
    const auto& a = centre.at("segments");
    const auto& b = tip.at("segments");
    ASSERT_EQ(a.size(), b.size());
    int approach = 0, departure = 0, contour = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const std::string role = a[i].at("role");
        const apci::run::Point ds = point(b[i].at("start")) - point(a[i].at("start"));
        const apci::run::Point de = point(b[i].at("end")) - point(a[i].at("end"));
        const bool start_carried = role == "contour" || role == "transition" || role == "departure";
        const bool end_carried = role == "contour" || role == "transition" || role == "approach";
        EXPECT_LT((ds - (start_carried ? carried : apci::run::Point::Zero())).norm(), 1e-9)
            << role << " " << b[i].dump();
        EXPECT_LT((de - (end_carried ? carried : apci::run::Point::Zero())).norm(), 1e-9)
            << role << " " << b[i].dump();
        approach += role == "approach";
        departure += role == "departure";
        contour += role == "contour";
    }
    EXPECT_EQ(approach, 1);
    EXPECT_EQ(departure, 1);
    EXPECT_GE(contour, 2);
    expect_continuous(tip);
}

TEST_F(ApcictlRun, TheReportedPathIsTheToolTipWhicheverPlaneTheLengthActsIn) {
    // D2 (length 100) in G17, then G18 and G17 again: the length moves from Z to Y and back on
    // the axes; the JSON shows the programmed tip throughout.
    const std::string prog = write("planes.nc",
                                   "N10 D1\nN15 G18\nN20 G0 X-10 Y0 Z5\nN30 G1 X0 F1000\n"
                                   "N40 G17\nN50 G1 Z0\nN60 M30\n");
    const json doc = run_json(prog, {"--tools", tools(0.5, 100.0)});
    ASSERT_EQ(doc.at("segments").size(), 3u) << roles(doc);
    EXPECT_EQ(point(doc.at("segments")[0].at("end")), apci::run::Point(-10, 0, 5));
    EXPECT_EQ(point(doc.at("segments")[1].at("end")), apci::run::Point(0, 0, 5));
    EXPECT_EQ(point(doc.at("segments")[2].at("start")), apci::run::Point(0, 0, 5));
    EXPECT_EQ(point(doc.at("segments")[2].at("end")), apci::run::Point(0, 0, 0));
    EXPECT_TRUE(contains(last_.out, "path 26.180 mm (rapid 11.180 mm)")) << last_.out;
}

TEST_F(ApcictlRun, ABoardRefusalOfAMoveIsInTheBoardsWordsWithoutTheDriversCallOrTag) {
    const std::string prog = write("feed.nc", "F2000000000\nG1 X1\nM30\n");
    const json doc = run_json(prog, {}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "ValueTooHigh");
    EXPECT_EQ(doc.at("errors")[0].at("message"), "feed above 1e9 units per minute");
    EXPECT_TRUE(contains(last_.out, "\n  line 2: ValueTooHigh: feed above 1e9 units per minute\n"))
        << last_.out;
    for (const std::string& text : {last_.out, last_.err})
        EXPECT_FALSE(contains(text, "spool") || contains(text, "N2147")) << text;
}

TEST_F(ApcictlRun, AProgramThatEndsUnderG41IsToldSo) {
    const std::string prog =
        write("open.nc", "N10 D1 F1000\nN20 G0 X-10 Y0\nN30 G41 G1 X0 Y0\nN40 G1 X20\nN50 M30\n");
    const json doc = run_json(prog, {"--tools", tools(0.5)});
    ASSERT_EQ(doc.at("notices").size(), 1u) << doc.dump();
    EXPECT_EQ(doc.at("notices")[0].at("code"), "CompensationOnAtEnd");
    EXPECT_TRUE(contains(last_.out, "notice: line 5 (N50): the program ends with radius "
                                    "compensation still on"))
        << last_.out;
    // The tool stays at the last compensated point (G139).
    EXPECT_LT((xy(doc.at("segments").back().at("end")) - Eigen::Vector2d(20, 0.5)).norm(), 1e-9);
}

namespace {
// The notices of a run's JSON with the given code, as "line: message".
std::vector<std::string> notices_of(const json& doc, const std::string& code) {
    std::vector<std::string> out;
    if (!doc.contains("notices")) return out;
    for (const json& n : doc.at("notices"))
        if (n.at("code") == code)
            out.push_back(std::to_string(n.at("block").get<int>()) + ": " +
                          n.at("message").get<std::string>());
    return out;
}
}  // namespace

TEST_F(ApcictlRun, CompensationWithoutARadiusIsToldOncePerToolWithTheReason) {
    // No D word, then D1 (radius 0), D2 (radius 5 written as if mm, in 0.1 um: 0.0005 mm),
    // D3 (0.000999 mm, in mm: one step under the bound), D4 (0.001 mm: at the bound). Each
    // selects G41 twice; a tool is named once.
    const std::string list = write("small.tools",
                                   "wz[1].gueltig 1\n"
                                   "wz[2].gueltig 1\nwz[2].radius 5\n"
                                   "wz[3].gueltig 1\nwz[3].mass_einheit 1\nwz[3].radius 0.000999\n"
                                   "wz[4].gueltig 1\nwz[4].mass_einheit 1\nwz[4].radius 0.001\n");
    std::string text = "F1000\n";
    for (const char* d : {"", "D1 ", "D2 ", "D3 ", "D4 "})
        for (int pass = 0; pass < 2; ++pass)
            text += std::string(d) + "G0 X-10 Y0\nG41 G1 X0 Y0\nG1 X20\nG40 G1 X20 Y-10\n";
    text += "G42 G1 X0 Y0\nG1 X-5\nG40 G1 X-10\nM30\n";  // D4 in force, G42: nothing to say
    std::string numbered;  // line n is block N(10 n)
    int line = 0;
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t end = text.find('\n', at);
        numbered += "N" + std::to_string(10 * ++line) + " " + text.substr(at, end + 1 - at);
        at = end + 1;
    }
    const json doc = run_json(write("small.nc", numbered), {"--tools", list});
    const std::vector<std::string> told = notices_of(doc, "NoRadius");
    ASSERT_EQ(told.size(), 4u) << doc.dump();
    EXPECT_EQ(told[0],
              "30: G41 with no tool selected (no D word yet, or D0) compensates by radius 0: the "
              "path is the programmed contour; select the tool with D n");
    EXPECT_EQ(told[1],
              "110: G41 with tool 1, whose radius is 0, compensates by nothing: the path is the "
              "programmed contour");
    EXPECT_EQ(told[2],
              "190: G41 with tool 2 compensates by 0.0005 mm only: the tool list gives lengths in "
              "0.1 um unless wz[2].mass_einheit is 1 (radius 50000 is 5 mm)");
    EXPECT_EQ(told[3], "270: G41 with tool 3 compensates by 0.000999 mm only");
    EXPECT_TRUE(contains(last_.out, "notice: line 3 (N30): G41 with no tool selected")) << last_.out;
    EXPECT_EQ(doc.at("errors").size(), 0u);
}

TEST_F(ApcictlRun, D0AfterAToolIsToldAgainAndG42SaysItsOwnWord) {
    const std::string prog = write("d0.nc",
                                   "N10 D1 F1000\nN20 G0 X-10 Y0\nN30 G42 G1 X0 Y0\nN40 G1 X20\n"
                                   "N50 G40 G1 X20 Y10\nN60 D0\nN70 G42 G1 X0 Y10\nN80 G40 G1 X0 "
                                   "Y20\nN90 M30\n");
    const json doc = run_json(prog, {"--tools", tools(0.5)});
    const std::vector<std::string> told = notices_of(doc, "NoRadius");
    ASSERT_EQ(told.size(), 1u) << doc.dump();
    EXPECT_EQ(told[0],
              "70: G42 with no tool selected (no D word yet, or D0) compensates by radius 0: the "
              "path is the programmed contour; select the tool with D n");
}

TEST_F(ApcictlRun, TheIsgGeneralExampleWearsOnlyItsContour) {
    // [ISG-OTC] section 2.2's general example: N60 G41 (selection, "verschleißfreie Bewegung"),
    // N70 X1000, N80 G40 X50 (deselection): only N70's 950 mm of contour wear, at the disc's
    // 100000 x 0.1 um/m: 9.5 mm.
    const json doc = run_json(kExamples + "/otc/general.nc",
                              {"--tools", kExamples + "/tools/wr_quad_disc.tools"});
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR_RADIUS").get<double>(), 9.5, 1e-9);
    EXPECT_EQ(roles(doc), "uncompensated/30 approach/60 contour/70 departure/80 uncompensated/100");
}

// Zero-length moves take no cycle, however many: a spooler full of them empties while the clock
// stands still, and the run goes on (make_room counts moves consumed, not only cycles run).
TEST_F(ApcictlRun, ManyZeroLengthMovesRunWhole) {
    std::string text = "F1000\nG1 X1\n";
    for (int k = 0; k < 1000; ++k) text += "G1 X1\n";
    text += "M30\n";
    const json doc = run_json(write("zero.nc", text));
    EXPECT_TRUE(doc.at("errors").empty()) << doc.at("errors").dump();
    EXPECT_EQ(doc.at("segments").size(), 1001u);
    EXPECT_TRUE(contains(last_.out, ": 1003 blocks, 1003 sent to the board, 1001 segments executed")) << last_.out;
    EXPECT_TRUE(contains(last_.out, "(60 cycles of 1 ms)")) << last_.out;  // 1 mm at 1000 mm/min
    // From the start: none of the moves takes a cycle.
    std::string still = "F1000\n";
    for (int k = 0; k < 1000; ++k) still += "G1 X0\n";
    still += "M30\n";
    const json doc2 = run_json(write("still.nc", still));
    EXPECT_TRUE(doc2.at("errors").empty()) << doc2.at("errors").dump();
    EXPECT_EQ(doc2.at("segments").size(), 1000u);
    EXPECT_TRUE(contains(last_.out, "(0 cycles of 1 ms)")) << last_.out;
}

}  // namespace
