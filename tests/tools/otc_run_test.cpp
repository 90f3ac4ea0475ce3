// SPDX-License-Identifier: MIT
// OTC through `apcictl run` (a process on the embedded emulator): the OTC programs of [ISG-OTC] in
// examples/otc/ with their documented commands, the scripted PLC (--plc), the V.G. variables in
// the JSON and in NC expressions, the wear reaching the tool list at tool change (--tools-out),
// #HSC reported as not emulated, refusals by name. docs/otc.md, docs/apcictl.md.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "apci/nc/tools.h"
#include "apci/run/plc_script.h"
#include "apcictl.h"
#include "scratch_test.h"
#include "text.h"

namespace {

using test_support::contains;
using test_support::read_csv;
using test_support::read_text;
using nlohmann::json;
using test_support::apcictl;
using test_support::ProcessResult;

const std::string kSource = APCI_SOURCE_DIR;
const std::string kExamples = kSource + "/examples";
constexpr double kEps = 1e-9;

// The CSV of --csv: cycle, time, then the 8 axes.
class OtcRun : public test_support::ScratchTest {
  protected:
    OtcRun() : ScratchTest("otc_run_") {}

    json run_json(std::vector<std::string> args, int expected_exit = 0) {
        args.insert(args.begin(), "run");
        args.emplace_back("--json");
        args.push_back(path("out.json"));
        last_ = apcictl(args);
        EXPECT_EQ(last_.exit_code, expected_exit) << last_.out << last_.err;
        return json::parse(read_text(path("out.json")));
    }
    // The grinding disc D1 of [ISG-OTC] (section 2.6) and a milling cutter D2.
    std::string grinding_tools() const { return kExamples + "/tools/wr_quad_disc.tools"; }

    ProcessResult last_;
};

// Every OTC example runs with the command its header documents (paths from the source tree).
TEST_F(OtcRun, EveryOtcExampleRunsWithItsDocumentedCommand) {
    const char* programs[] = {"general",  "length",        "length_tilt",
                              "tool_dir", "surf_norm_dir", "wr_quad_disc"};
    for (const char* name : programs) {
        const std::string file = kExamples + "/otc/" + name + ".nc";
        std::vector<std::string> args = test_support::documented_command(file, kSource);
        ASSERT_FALSE(args.empty()) << file;
        args.emplace_back("--json");
        args.push_back(path("out.json"));
        const ProcessResult r = apcictl(args);
        EXPECT_EQ(r.exit_code, 0) << name << ": " << r.out << r.err;
        const json doc = json::parse(read_text(path("out.json")));
        EXPECT_EQ(doc.at("errors"), json::array()) << name;
        EXPECT_EQ(doc.at("variables").at("V.G.OTC_ACTIVE"), 0) << name;
    }
}

// The OTC example programs of examples/otc/ give the numbers the documents give (docs/otc.md section 10),
// each with its documented command: [ISG-OTC] section 2.2's general example with the tool data of
// section 2.6 (100000 x 0.1 um/m over N70's 950 mm: 9.5 mm of radius wear), section 2.3's G1
// X1000 (10 mm on the third axis), section 2.3.1's split by the disc's tilt (30 degrees in
// otc_tilt.tools: sin 30 x 10 on X, cos 30 x 10 on Z), and [ISG-OTC-EN]'s wr_quad_disc.nc with
// the discrete offset of its figure ("der diskret beauftragte Versatz beträgt 2mm", ±2 mm).
TEST_F(OtcRun, OtcExamplesGiveTheNumbersTheDocumentsGive) {
    struct Example {
        const char* program;
        const char* tools;
        const char* plc;  // nullptr: none
        const char* variable;
        double value;
    };
    const Example examples[] = {
        {"general", "wr_quad_disc", nullptr, "V.G.WZ_AKT.WEAR_RADIUS", 9.5},
        {"general", "wr_quad_disc", nullptr, "V.G.WZ_AKT.WEAR_RADIUS_CONT", 9.5},
        {"length", "wr_quad_disc", nullptr, "V.G.WZ_AKT.WEAR[2]", 10.0},
        {"length", "wr_quad_disc", nullptr, "V.G.WZ_AKT.WEAR[0]", 0.0},
        {"length_tilt", "otc_tilt", nullptr, "V.G.WZ_AKT.WEAR[0]", 5.0},
        {"length_tilt", "otc_tilt", nullptr, "V.G.WZ_AKT.WEAR[2]", 10.0 * std::sqrt(3.0) / 2.0},
        {"wr_quad_disc", "wr_quad_disc", "wr_quad_disc", "V.G.WZ_AKT.WEAR_RADIUS", 2.0},
        {"wr_quad_disc", "wr_quad_disc", "wr_quad_disc_negative", "V.G.WZ_AKT.WEAR_RADIUS", -2.0},
    };
    for (const Example& example : examples) {
        std::vector<std::string> args{kExamples + "/otc/" + example.program + ".nc", "--tools",
                                      kExamples + "/tools/" + example.tools + ".tools"};
        if (example.plc != nullptr) {
            args.emplace_back("--plc");
            args.push_back(kExamples + "/otc/plc/" + example.plc + ".plc");
        }
        const json doc = run_json(args);
        EXPECT_EQ(doc.at("errors"), json::array()) << example.program;
        EXPECT_NEAR(doc.at("variables").at(example.variable).get<double>(), example.value, kEps)
            << example.program << " " << (example.plc ? example.plc : "") << " " << example.variable;
    }
}

// [ISG-OTC] section 2.3 with the tool data of 2.6: 10.000 mm on Z within 1e-9, linear along the
// path (5.000 mm at X500), folded into the tool's length (500000 - 100000 x 0.1 um).
TEST_F(OtcRun, LengthExampleWearsTenMillimetresAndTheToolListGetsIt) {
    const json doc = run_json({kExamples + "/otc/length.nc", "--tools", grinding_tools(), "--csv",
                               path("out.csv"), "--tools-out", path("out.tools")});
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR[2]").get<double>(), 10.0, kEps);
    EXPECT_EQ(doc.at("variables").at("V.G.WZ_AKT.WEAR[0]").get<double>(), 0.0);
    // N40 G00 X0 Y0 Z0 puts D1's 50 mm on Z (50 cycles at 1000 mm/s); N60 then grinds it down
    // by 0.01 mm a mm of X. At #OTC OFF the 10 mm pass into the tool length (LengthMode 1: the
    // length acts on every move), so Z stays at 40 and nothing ramps back: the program ends there.
    const auto rows = read_csv(path("out.csv"));
    ASSERT_EQ(rows.size(), 6050u);
    bool half = false;
    for (const auto& r : rows) {
        if (r[0] <= 50) continue;
        EXPECT_NEAR(r[4], 50.0 - 0.01 * r[2], kEps) << "cycle " << r[0];
        if (r[2] == 500.0) {
            half = true;
            EXPECT_NEAR(r[4], 45.0, kEps);
        }
    }
    EXPECT_TRUE(half);
    EXPECT_NEAR(rows.back()[4], 40.0, kEps);
    auto tools = apci::nc::load_tool_table(path("out.tools"));
    ASSERT_TRUE(tools) << tools.error().to_string();
    EXPECT_NEAR(tools.value().find(1)->length_mm(), 40.0, 1e-6);
}

// Two LENGTH passes over X0..X1000, each ended by #OTC OFF, with D1 (length 50 mm).
const char* const kTwoLengthPasses =
    "N10 D1\nN20 G0 X0 Y0 Z0\nN30 #OTC ON [LENGTH]\nN40 G1 X1000 F10000\nN50 #OTC OFF\n"
    "N60 G0 X0\nN70 #OTC ON [LENGTH]\nN80 G1 X1000 F10000\nN90 #OTC OFF\nN100 G0 X0\n"
    "N110 M30\n";

// After N20 puts D1's 50 mm on Z (cycles 1..50), Z only ever goes down: the folds move nothing.
void expect_z_never_rises_after_the_length(const std::vector<std::vector<double>>& rows) {
    double previous = 50.0;
    for (const auto& r : rows) {
        if (r[0] <= 50) continue;
        EXPECT_LE(r[4], previous + kEps) << "cycle " << r[0];
        previous = r[4];
    }
}

// Two LENGTH passes of 10 mm wear each: at each #OTC OFF the wear passes into the tool length,
// which acts on every move (LengthMode 1), so the passes add up: Z ends 20 mm below the
// unworn tool, and never moves back up between the passes.
TEST_F(OtcRun, TwoLengthPassesAddUp) {
    const std::string prog = write("two.nc", kTwoLengthPasses);
    const json doc = run_json({prog, "--tools", grinding_tools(), "--csv", path("two.csv"),
                               "--tools-out", path("two.tools")});
    const auto rows = read_csv(path("two.csv"));
    ASSERT_GT(rows.size(), 50u);
    expect_z_never_rises_after_the_length(rows);
    EXPECT_NEAR(rows.back()[4], 50.0 - 20.0, kEps);
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR[2]").get<double>(), 20.0, kEps);
    // The reported path (the tool tip) stays at Z 0 and continuous across both folds.
    const json* before = nullptr;
    for (const auto& s : doc.at("segments")) {
        EXPECT_NEAR(s.at("start")[2].get<double>(), 0.0, kEps) << s.dump();
        EXPECT_NEAR(s.at("end")[2].get<double>(), 0.0, kEps) << s.dump();
        if (before != nullptr) {
            EXPECT_EQ(s.at("start"), before->at("end")) << s.dump();
        }
        before = &s;
    }
    auto tools = apci::nc::load_tool_table(path("two.tools"));
    ASSERT_TRUE(tools) << tools.error().to_string();
    EXPECT_NEAR(tools.value().find(1)->length_mm(), 30.0, 1e-6);
}

// A program ends when the OTC offsets have settled, not with a ramp under way: in wr_quad_disc.nc
// with the PLC's 2 mm the radius offset ramps off after G40 and #OTC OFF (the radius takes the
// wear, and no compensation is left to apply it); the run goes on until it rests at N100's end.
TEST_F(OtcRun, AProgramEndsWhenTheOtcRampsHaveSettled) {
    run_json({kExamples + "/otc/wr_quad_disc.nc", "--tools", grinding_tools(), "--plc",
              kExamples + "/otc/plc/wr_quad_disc.plc", "--csv", path("q.csv")});
    const auto rows = read_csv(path("q.csv"));
    ASSERT_GT(rows.size(), 200u);
    EXPECT_NE(rows[rows.size() - 200][2], 0.0);  // still ramping 200 cycles before the end
    EXPECT_EQ(rows.back()[2], 0.0);
    EXPECT_EQ(rows.back()[3], 0.0);
    EXPECT_EQ(rows.back()[4], 50.0);
}

// A tilted disc (30 degrees): each pass's 10 mm of wear lies on X and Z (5 and 8.66 mm). Z's part
// passes into the tool length, which acts on Z; X's stays on the axis as a standing offset while
// the tool is in. Two passes add up on both axes, and nothing ramps back in between.
TEST_F(OtcRun, TwoTiltedLengthPassesAddUpOnBothAxes) {
    const std::string prog = write("tilt2.nc", kTwoLengthPasses);
    run_json({prog, "--tools", kExamples + "/tools/otc_tilt.tools", "--csv", path("t.csv"),
              "--tools-out", path("t.tools")});
    const auto rows = read_csv(path("t.csv"));
    ASSERT_GT(rows.size(), 50u);
    expect_z_never_rises_after_the_length(rows);
    const double cos30 = std::sqrt(3.0) / 2.0;
    EXPECT_NEAR(rows.back()[2], 0.0 - 2 * 5.0, kEps);           // X: N100's 0, 10 mm standing
    EXPECT_NEAR(rows.back()[4], 50.0 - 2 * 10.0 * cos30, kEps);  // Z: in the length
    auto tools = apci::nc::load_tool_table(path("t.tools"));
    ASSERT_TRUE(tools) << tools.error().to_string();
    EXPECT_NEAR(tools.value().find(1)->length_mm(), 50.0 - 2 * 10.0 * cos30, 1e-6);
}

// [ISG-OTC] section 2.3.1: with the disc tilted by 30 degrees the same wear splits into sin/cos.
TEST_F(OtcRun, TiltedDiscSplitsTheWearOverXAndZ) {
    const json doc = run_json(
        {kExamples + "/otc/length_tilt.nc", "--tools", kExamples + "/tools/otc_tilt.tools"});
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR[0]").get<double>(), 10.0 * 0.5, kEps);
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR[2]").get<double>(),
                10.0 * std::sqrt(3.0) / 2.0, kEps);
}

// wr_quad_disc.nc with the PLC's 2 mm: the wear reaches WEAR_RADIUS and, at the end, the tool
// list: radius 30 - 2 mm, wear_radius 2 mm.
TEST_F(OtcRun, WrQuadDiscWithThePlcsTwoMillimetres) {
    // [ISG-OTC]'s tool with length 0, so that the approach is only the 30 mm to the offset path
    // (with 50 mm the TC's length compensation lowers Z on it, and the offset builds up there).
    std::string tool_text = read_text(grinding_tools());
    const std::size_t length_line = tool_text.find("wz[1].laenge");
    const std::size_t value = tool_text.find("500000", length_line);
    ASSERT_NE(value, std::string::npos);
    tool_text.replace(value, 6, "0");
    const std::string zero_length = write("t.tools", tool_text);
    const json doc = run_json({kExamples + "/otc/wr_quad_disc.nc", "--tools", zero_length, "--plc",
                               kExamples + "/otc/plc/wr_quad_disc.plc", "--csv", path("out.csv"),
                               "--tools-out", path("out.tools")});
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR_RADIUS").get<double>(), 2.0, kEps);
    EXPECT_EQ(doc.at("variables").at("V.G.WZ_AKT.WEAR_RADIUS_CONT").get<double>(), 0.0);
    auto tools = apci::nc::load_tool_table(path("out.tools"));
    ASSERT_TRUE(tools) << tools.error().to_string();
    EXPECT_NEAR(tools.value().find(1)->radius_mm(), 28.0, 1e-6);
    EXPECT_NEAR(tools.value().find(1)->wear_radius_mm(), 2.0, 1e-6);
    // Along the bottom edge, once built up, the tool runs 2 mm closer to the contour: y = -28.
    const auto rows = read_csv(path("out.csv"));
    bool seen = false;
    for (const auto& r : rows) {
        if (r[2] > 90.0 && r[2] < 100.0 && r[3] < -20.0) {
            seen = true;
            EXPECT_NEAR(r[3], -28.0, kEps) << "cycle " << r[0];
        }
    }
    EXPECT_TRUE(seen);
    // On the bottom edge the nominal y is -30: the offset is y + 30, built up over many cycles,
    // no step larger than the ramp allows (0.5 mm/s x 1 ms).
    std::size_t building = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const auto& a = rows[i - 1];
        const auto& b = rows[i];
        if (a[2] < 2.0 || b[2] > 102.0 || a[3] > -27.9 || b[3] > -27.9) continue;
        EXPECT_LE(std::abs(b[3] - a[3]), 0.5e-3 + 1e-12) << "cycle " << b[0];
        if (b[3] > a[3]) ++building;
    }
    EXPECT_GT(building, 500u);
    // Around the G26 corner at (102, 0) the tool centre runs on the 30 mm arc; 2 mm of wear
    // would put the axes 28 mm from the corner, but the offset lags behind the turning normal
    // ([ISG-OTC-EN], explanations 2 and 3), so they leave that circle by far more than rounding.
    double worst = 0.0;
    for (const auto& r : rows) {
        if (r[2] <= 102.0 || r[3] >= 0.0) continue;  // the quadrant of the transition arc
        worst = std::max(worst, std::abs(std::hypot(r[2] - 102.0, r[3]) - 28.0));
    }
    EXPECT_GT(worst, 0.1);
}

// The scripted PLC's cycle entries act at their cycle: nothing moves Z before cycle 2000 (but
// N15's rapid that puts the 50 mm tool length on Z, cycles 1..50 at 1000 mm/s).
TEST_F(OtcRun, PlcCycleWritesActAtTheirCycle) {
    const std::string prog = write("p.nc",
                                   "N10 D1\nN15 G0 Z0\nN20 #OTC ON [LENGTH DISC]\n"
                                   "N30 G1 X100 F1000\nN40 #OTC OFF\nM30\n");
    const std::string plc = write("p.plc",
                                  "cycle 0 otc_offset[2].enable 1\n"
                                  "cycle 2000 otc_offset[2].command 1000\n");
    const json doc =
        run_json({prog, "--tools", grinding_tools(), "--plc", plc, "--csv", path("c.csv")});
    const auto rows = read_csv(path("c.csv"));
    ASSERT_GT(rows.size(), 5000u);
    for (const auto& r : rows) {
        if (r[0] > 50 && r[0] <= 2000) {
            EXPECT_EQ(r[4], 50.0) << r[0];
        }
    }
    EXPECT_LT(rows[2200][4], 50.0);  // the infeed has begun to act
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR[2]").get<double>(), 0.1, kEps);
}

TEST_F(OtcRun, PlcCommandBeyondMaxInfeedIsNamed) {
    const std::string prog = write("p.nc",
                                   "N10 D1\nN20 #OTC ON [LENGTH DISC]\nN30 G1 X10 F1000\n"
                                   "N40 #OTC OFF\nM30\n");
    const std::string plc = write("p.plc", "block 30 otc_offset[2].command 200001\n");
    const json doc = run_json({prog, "--tools", grinding_tools(), "--plc", plc}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "OTC_INFEED_BEYOND_LIMIT");
    EXPECT_EQ(doc.at("errors")[0].at("block"), 30);
}

TEST_F(OtcRun, PlcScriptErrorsNameFileLineAndColumn) {
    const std::string plc =
        write("bad.plc", "cycle 0 otc_radius_offset.enable 1\nblock x1 foo 3\n");
    const ProcessResult r =
        apcictl({"run", kExamples + "/otc/length.nc", "--tools", grinding_tools(), "--plc", plc});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, plc + ":2:7: expected a whole number after 'block'")) << r.err;
}

// [ISG-OTC] section 1: P-ERR-21391, found by the validation pass from the tool list.
TEST_F(OtcRun, OtcOnWithAMillingToolIsPErr21391) {
    const std::string tools = write("t.tools", "wz[1].gueltig 1\nwz[1].typ 0\n");
    const ProcessResult r = apcictl({"run", kExamples + "/otc/length.nc", "--tools", tools});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "P-ERR-21391")) << r.err;
}

// [ISG-OTC] section 2.8: the program reads the board's wear after #OTC OFF.
TEST_F(OtcRun, ProgramsReadTheBoardsWearVariables) {
    const std::string prog = write(
        "v.nc",
        // N15 puts the tool length on Z first (a rapid, wear-free): N30 then wears X's 500 mm.
        "N10 D1\nN15 G0 Z0\nN20 #OTC ON\nN30 G1 X500 F10000\nN40 #OTC OFF\n"
        "N50 P1 = V.G.WZ_AKT.WEAR.Z\nN60 P2 = V.G.OTC_ACTIVE\nN70 G0 X[P1 * 10] Y[P2]\nM30\n");
    const json doc = run_json({prog, "--tools", grinding_tools()});
    const json& last = doc.at("segments").back();
    EXPECT_EQ(last.at("block"), 70);
    EXPECT_NEAR(last.at("end")[0].get<double>(), 50.0, 1e-9);
    EXPECT_EQ(last.at("end")[1].get<double>(), 0.0);
}

// [ISG-OTC] section 2.9: at a tool change the wear of the tool going out reaches the tool list;
// the tool comes back folded (its second contour runs at the worn radius).
TEST_F(OtcRun, WearReachesTheToolListAtToolChangeAndTheToolComesBackWorn) {
    const std::string tools = write(
        "t.tools", read_text(grinding_tools()) + "wz[2].gueltig 1\nwz[2].typ 2\nwz[2].radius 100000\n");
    const std::string prog =
        write("c.nc",
              "N10 F10000\nN20 D1\nN30 #OTC ON [RADIUS CONT]\nN40 G41 G1 X10\nN50 X510\n"
              "N60 G40 G1 X600\nN70 #OTC OFF\nN80 D2\nN90 D1\nN100 G0 X0 Y0\nN110 G41 G1 X10\n"
              "N120 X100\nN130 G40 X200\nM30\n");
    const json doc = run_json({prog, "--tools", tools, "--tools-out", path("out.tools")});
    auto out = apci::nc::load_tool_table(path("out.tools"));
    ASSERT_TRUE(out) << out.error().to_string();
    // Only N50 wears: the G41 block N40 is the approach (G139: straight from (0, 0) to its
    // offset end (10, 30)), wear-free as [ISG-OTC]'s "N60 G41 G01 X50 (select TRC, wear-free
    // movement)"; N50 is 500 mm of contour ((10, 30) to (510, 30)); there is no transition, and
    // the G40 move N60 is wear-free. 500 mm at 100000 x 0.1 um/m = 10 um/mm: 5.0 mm.
    EXPECT_NEAR(out.value().find(1)->radius_mm(), 30.0 - 5.0, 1e-6);
    EXPECT_NEAR(out.value().find(1)->wear_radius_mm(), 5.0, 1e-6);
    EXPECT_NEAR(out.value().find(1)->wear_radius_cont_mm(), 5.0, 1e-6);
    EXPECT_EQ(out.value().find(2)->wear_radius, 0.0);
    int worn_contours = 0;
    for (const auto& s : doc.at("segments")) {
        if (s.at("block") == 120 && s.at("role") == "contour") {
            ++worn_contours;
            EXPECT_NEAR(s.at("start")[1].get<double>(), 30.0 - 5.0, 1e-6);
        }
    }
    EXPECT_EQ(worn_contours, 1);
}

// docs/design.md section 8: with #TRAFO ON the program gives the tool tip; the board's axes carry the
// pivot one tool length (50 mm) behind it along t(B); the JSON shows the tip.
TEST_F(OtcRun, TrafoMovesThePivotAndReportsTheTip) {
    const std::string prog = write("t.nc", "N30 D1\nN40 G00 X0 Y0 Z300 B0\nN50 #KIN ID[4]\n"
                                           "N55 #TRAFO ON\nN60 G00 B45\nN70 G01 X100 Z50 F1000\n"
                                           "N80 #TRAFO OFF\nM30\n");
    const json doc = run_json({prog, "--tools", grinding_tools(), "--csv", path("t.csv")});
    bool seen = false;
    for (const auto& s : doc.at("segments")) {
        if (s.at("block") != 70) continue;
        seen = true;
        EXPECT_NEAR(s.at("end")[0].get<double>(), 100.0, 1e-9);
        EXPECT_NEAR(s.at("end")[2].get<double>(), 50.0, 1e-9);
    }
    EXPECT_TRUE(seen);
    const auto rows = read_csv(path("t.csv"));
    const auto& last = rows.back();
    EXPECT_NEAR(last[2], 100.0 + 50.0 * std::sqrt(0.5), 1e-9);
    EXPECT_NEAR(last[4], 50.0 + 50.0 * std::sqrt(0.5), 1e-9);
    EXPECT_EQ(last[6], 45.0);  // B on board axis 4
}

// After #TRAFO OFF the axes carry the pivot, which the length LengthMode 1 now adds makes the
// tip: the first segment after the switch starts at the tip where the last one under the
// transformation ended (the length taken off its start, though the board carried none there),
// and the segments after it take off what the board reports, which D2 (30 mm) changes: the
// path is continuous and stands at the tip throughout.
TEST_F(OtcRun, AfterTrafoOffTheFirstSegmentStartsAtTheTipAndLaterOnesTakeTheBoardsLengthOff) {
    const std::string tools =
        write("two.tools", read_text(grinding_tools()) +
                               "\nwz[2].gueltig 1\nwz[2].typ 2\nwz[2].mass_einheit 0\n"
                               "wz[2].laenge 300000\nwz[2].radius 300000\n");
    const std::string prog = write("off.nc",
                                   "N30 D1\nN40 G00 X0 Y0 Z300 B0\nN50 #KIN ID[4]\nN55 #TRAFO ON\n"
                                   "N70 G01 X100 Z50 F1000\nN80 #TRAFO OFF\nN90 G01 X150\nN100 D2\n"
                                   "N110 G01 X160\nN120 G01 X170 Z60\nM30\n");
    const json doc = run_json({prog, "--tools", tools});
    const auto& segments = doc.at("segments");
    ASSERT_GE(segments.size(), 4u);
    const auto point = [](const json& p) {
        return std::vector<double>{p[0].get<double>(), p[1].get<double>(), p[2].get<double>()};
    };
    const auto expect_at = [](const std::vector<double>& got, double x, double y, double z) {
        ASSERT_EQ(got.size(), 3u);
        EXPECT_NEAR(got[0], x, 1e-9);
        EXPECT_NEAR(got[1], y, 1e-9);
        EXPECT_NEAR(got[2], z, 1e-9);
    };
    std::set<int> seen;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const json& s = segments[i];
        SCOPED_TRACE("segment " + std::to_string(i) + " of block " + s.at("block").dump());
        if (i > 0) {
            const std::vector<double> from = point(s.at("start")),
                                      to = point(segments[i - 1].at("end"));
            for (std::size_t a = 0; a < 3; ++a) EXPECT_NEAR(from[a], to[a], 1e-9) << "axis " << a;
        }
        const int block = s.at("block").get<int>();
        seen.insert(block);
        if (block == 90) {
            expect_at(point(s.at("start")), 100, 0, 50);
            expect_at(point(s.at("end")), 150, 0, 50);
        } else if (block == 110) {
            expect_at(point(s.at("end")), 160, 0, 50);
        } else if (block == 120) {
            expect_at(point(s.at("start")), 160, 0, 50);
            expect_at(point(s.at("end")), 170, 0, 60);
        }
    }
    for (const int block : {70, 90, 110, 120}) EXPECT_EQ(seen.count(block), 1u) << block;
}

// [ISG-OTC] section 2.1, WEAR_CONST "wirkt modal", and 2.8 (V.G.WZ_AKT.WEAR_CONST written in
// the program): the new constant acts from its block on. X0..X100 at 100000, X100..X200 at
// 200000 (0.1 um/m): 1 + 2 mm, Z 1 mm down at X100; under G41 the held element N40 keeps the
// old constant too (0.5 + 2 mm).
TEST_F(OtcRun, AWearConstantChangeActsFromItsBlock) {
    for (const char* change : {"V.G.WZ_AKT.WEAR_CONST = 200000", "#OTC [WEAR_CONST=200000]"}) {
        const std::string prog = write(
            "wc.nc", std::string("N10 D1\nN20 G0 X0 Y0 Z0\nN30 #OTC ON [LENGTH CONT]\n"
                                 "N40 G1 X100 F10000\nN50 ") +
                         change + "\nN60 G1 X200\nN70 #OTC OFF\nN80 M30\n");
        const json doc = run_json({prog, "--tools", grinding_tools(), "--csv", path("wc.csv")});
        EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR[2]").get<double>(), 3.0, kEps)
            << change;
        bool at_100 = false;
        for (const auto& r : read_csv(path("wc.csv"))) {
            if (r[2] != 100.0) continue;
            at_100 = true;
            EXPECT_NEAR(r[4], 50.0 - 1.0, kEps) << change;
            break;
        }
        EXPECT_TRUE(at_100) << change;
    }
    const json doc = run_json({write("held.nc",
                                     "N10 D1\nN20 #OTC ON [RADIUS CONT]\nN30 G41 G1 X50 F10000\n"
                                     "N40 G1 X100\nN50 V.G.WZ_AKT.WEAR_CONST = 200000\n"
                                     "N60 G1 X200\nN70 G40 G1 X250\nN80 #OTC OFF\nN90 M30\n"),
                               "--tools", grinding_tools()});
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR_RADIUS").get<double>(), 2.5, kEps);
}

// [ISG-OTC] section 2.2 "Hinweis": the approach after G41 and the move after G40 are wear-free,
// for LENGTH too. Under G139 (the start state) those are the G41 and the G40 block's moves:
// N40 and N60 wear, 1 + 1 mm. Under G237 (the board's perpendicular approach and departure,
// docs/otc.md) the G41 block's move is on the offset path and the G40 block's move runs after
// the departure: N30, N40, N50, N60 wear, 4 mm.
TEST_F(OtcRun, LengthSparesTheApproachAndTheDeparture) {
    const std::string body =
        "N20 #OTC ON [LENGTH CONT]\nN30 G41 G1 X100 F10000\nN40 G1 X200\nN50 G40 G1 X300\n"
        "N60 G1 X400\nN70 #OTC OFF\nN80 M30\n";
    const json g139 = run_json({write("a.nc", "N10 D1\n" + body), "--tools", grinding_tools()});
    EXPECT_NEAR(g139.at("variables").at("V.G.WZ_AKT.WEAR[2]").get<double>(), 2.0, kEps);
    std::string roles;
    for (const auto& s : g139.at("segments"))
        roles += s.at("role").get<std::string>() + "/" + std::to_string(s.at("block").get<int>()) +
                 " ";
    EXPECT_EQ(roles, "approach/30 contour/40 departure/50 uncompensated/60 ");
    const json g237 = run_json({write("b.nc", "N10 D1 G237\n" + body), "--tools", grinding_tools()});
    EXPECT_NEAR(g237.at("variables").at("V.G.WZ_AKT.WEAR[2]").get<double>(), 4.0, kEps);
}

// [ISG-OTC] section 2.8: the wear variables are "in [mm] oder [Inch]": under G70 a program reads
// the board's 9.652 mm of radius wear as 0.38 in, so G00 X[P1] goes to X 9.652 mm.
TEST_F(OtcRun, WearVariablesAreReadInInchesUnderG70) {
    const json doc = run_json(
        {write("inch.nc",
               "N10 D1\nN20 #OTC ON [RADIUS CONT]\nN30 G41 G1 X50 F10000\nN40 G1 X1015.2\n"
               "N50 G40 G1 X1100\nN60 #OTC OFF\nN70 G70\nN80 P1 = V.G.WZ_AKT.WEAR_RADIUS\n"
               "N90 G00 X[P1]\nN100 M30\n"),
         "--tools", grinding_tools()});
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR_RADIUS").get<double>(), 9.652, 1e-9);
    const json& last = doc.at("segments").back();
    EXPECT_EQ(last.at("block"), 90);
    EXPECT_NEAR(last.at("end")[0].get<double>(), 9.652, 1e-9);
}

// [ISG-OTC] section 2.1: the wear is that of the path travelled, and the Z motion of the tool
// length (D1's 50 mm coming onto Z along N30) is none: G1 X200 wears 2.000 mm.
TEST_F(OtcRun, TheToolLengthsMotionIsNoGroundPath) {
    const json doc =
        run_json({write("len.nc", "N10 D1\nN20 #OTC ON [LENGTH CONT]\nN30 G1 X200 F10000\n"
                                  "N40 #OTC OFF\nN50 M30\n"),
                  "--tools", grinding_tools()});
    EXPECT_NEAR(doc.at("variables").at("V.G.WZ_AKT.WEAR[2]").get<double>(), 2.0, kEps);
}

// A B word tilts the B head; it does not switch the tool length off. D1 (length 50 mm) puts
// its length on Z with N40: machine Z 350 for Z300, and it stays there through N45 (with B) and
// N46 (without), as in the same program without the B word. The reported path is the same
// with and without it.
TEST_F(OtcRun, ABWordKeepsTheToolLengthOnTheAxis) {
    const char* with_b = "N30 D1 F1000\nN40 G1 X0 Y0 Z300\nN45 G1 X10 B0\nN46 G1 X20\nM30\n";
    const char* without_b = "N30 D1 F1000\nN40 G1 X0 Y0 Z300\nN45 G1 X10\nN46 G1 X20\nM30\n";
    const json doc = run_json({write("b.nc", with_b), "--tools", grinding_tools(), "--csv",
                               path("b.csv")});
    const auto rows = read_csv(path("b.csv"));
    ASSERT_FALSE(rows.empty());
    bool reached = false;
    for (const auto& r : rows) {
        if (r[4] == 350.0) reached = true;
        if (reached) {
            EXPECT_EQ(r[4], 350.0) << "cycle " << r[0];  // never down towards the work
        }
        EXPECT_LE(r[4], 350.0) << "cycle " << r[0];
    }
    EXPECT_TRUE(reached);
    EXPECT_EQ(rows.back()[2], 20.0);
    const json plain = run_json({write("nob.nc", without_b), "--tools", grinding_tools()});
    ASSERT_EQ(doc.at("segments").size(), plain.at("segments").size());
    for (std::size_t i = 0; i < plain.at("segments").size(); ++i) {
        EXPECT_EQ(doc.at("segments")[i].at("start"), plain.at("segments")[i].at("start")) << i;
        EXPECT_EQ(doc.at("segments")[i].at("end"), plain.at("segments")[i].at("end")) << i;
    }
    EXPECT_EQ(doc.at("segments")[0].at("end"), json::array({0, 0, 300}));
}

// The tool length D1 puts on Z (50 mm) is taken off an arc's centre as off its start: the
// reported centre of a G17 arc and of a helix stands at the tool tip's Z where the arc starts
// (its centre on the other axes is its start's), not at the machine's.
TEST_F(OtcRun, AnArcsCentreHasTheToolLengthTakenOffAsItsStart) {
    const json doc = run_json({write("arc.nc",
                                     "N30 D1 F1000\nN40 G1 X0 Y0 Z300\nN50 G2 X20 Y0 I10 J0\n"
                                     "N60 G3 X40 Y0 Z310 I10 J0\nM30\n"),
                               "--tools", grinding_tools()});
    int arcs = 0;
    for (const auto& s : doc.at("segments")) {
        const int block = s.at("block").get<int>();
        if (block != 50 && block != 60) continue;
        ++arcs;
        ASSERT_TRUE(s.contains("center")) << block;
        EXPECT_NEAR(s.at("center")[0].get<double>(), block == 50 ? 10.0 : 30.0, 1e-9) << block;
        EXPECT_NEAR(s.at("center")[1].get<double>(), 0.0, 1e-9) << block;
        EXPECT_NEAR(s.at("start")[2].get<double>(), 300.0, 1e-9) << block;
        EXPECT_NEAR(s.at("center")[2].get<double>(), 300.0, 1e-9) << block;
        EXPECT_NEAR(s.at("end")[2].get<double>(), block == 50 ? 300.0 : 310.0, 1e-9) << block;
    }
    EXPECT_EQ(arcs, 2);
}

// [ISG-OTC] sections 2.4 and 2.5 program N40 G00 X0 Y0 Z300 B0 with the 50 mm disc before
// #TRAFO ON: the machine's Z stands at 350 (the tip at 300) until the transformation takes the
// length over, and the tip stays at Z300 across #TRAFO ON and N60's B (the pivot moves).
TEST_F(OtcRun, TheIsgToolDirAndSurfNormDirExamplesStandAtMachineZ350ForZ300) {
    for (const char* name : {"tool_dir", "surf_norm_dir"}) {
        const json doc =
            run_json({kExamples + "/otc/" + name + ".nc", "--tools", grinding_tools(), "--plc",
                      kExamples + "/otc/plc/" + name + ".plc", "--csv", path("e.csv")});
        const auto rows = read_csv(path("e.csv"));
        ASSERT_FALSE(rows.empty()) << name;
        // Until X or B (board axis 4, the head's) moves (N60, N70), Z rises to 350 and holds
        // there.
        double z_before = 0.0;
        for (const auto& r : rows) {
            if (r[2] != 0.0 || r[6] != 0.0) break;
            EXPECT_LE(r[4], 350.0) << name << " cycle " << r[0];
            z_before = r[4];
        }
        EXPECT_EQ(z_before, 350.0) << name;
        const auto& segments = doc.at("segments");
        ASSERT_GE(segments.size(), 3u) << name;
        EXPECT_EQ(segments[0].at("block"), 40) << name;
        EXPECT_EQ(segments[0].at("end"), json::array({0, 0, 300})) << name;
        EXPECT_EQ(segments[1].at("block"), 60) << name;
        EXPECT_EQ(segments[1].at("start"), json::array({0, 0, 300})) << name;
        EXPECT_EQ(segments[1].at("end"), json::array({0, 0, 300})) << name;
    }
}

// docs/design.md section 8: #HSC is accepted and reported as not emulated.
TEST_F(OtcRun, HscIsReportedAsNotEmulated) {
    const std::string prog =
        write("h.nc", "N85 #HSC ON[BSPLINE PATH_DEV 5 MERGE = 0]\nG0 X1\nM30\n");
    const json doc = run_json({prog});
    ASSERT_EQ(doc.at("notices").size(), 1u);
    EXPECT_EQ(doc.at("notices")[0].at("code"), "NotEmulated");
    EXPECT_EQ(doc.at("notices")[0].at("block"), 85);
    EXPECT_TRUE(contains(last_.out, "notice: line 1 (N85): #HSC is accepted and not emulated")) << last_.out;
}

// The plots of docs/otc.md are what apcictl draws now (scripts/otc_figures.sh redraws them from
// docs/figures/otc-figures.txt). Run from the source root, as the script does.
TEST_F(OtcRun, OtcFiguresAreCurrent) {
    std::stringstream list(read_text(kSource + "/docs/figures/otc-figures.txt"));
    int figures = 0;
    for (std::string line; std::getline(list, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::stringstream f(line);
        std::string name, program, tools, plc, plane;
        f >> name >> program >> tools >> plc >> plane;
        std::vector<std::string> args{"/bin/sh", "-c", ""};
        std::string cmd = "cd '" + kSource + "' && '" + APCICTL_PATH + "' run " + program +
                          " --tools " + tools + " --plane " + plane + " --svg '" +
                          path(name + ".svg") + "' --svg-cycles";
        if (plc != "-") cmd += " --plc " + plc;
        args[2] = cmd + " > /dev/null";
        const ProcessResult r = test_support::run_process(args);
        EXPECT_EQ(r.exit_code, 0) << name << r.err;
        EXPECT_EQ(read_text(path(name + ".svg")),
                  read_text(kSource + "/docs/figures/" + name + ".svg"))
            << name << ".svg is stale: run scripts/otc_figures.sh";
        ++figures;
    }
    EXPECT_EQ(figures, 3);
}

// ---- The PLC script parser (apci/run/plc_script.h)

TEST(PlcScript, ParsesCycleAndBlockWritesInOrder) {
    auto s = apci::run::parse_plc_script(
        "# comment\ncycle 500 otc_offset[2].command -500  # trailing\n"
        "block 60 otc_radius_offset.enable TRUE\ncycle 0 otc_radius_offset.command_w 20000\n",
        "p.plc");
    ASSERT_TRUE(s) << s.error().to_string();
    const auto& c = s.value().cycle_writes();
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c[0].at, 0u);  // sorted by cycle
    EXPECT_EQ(c[0].unit, apci::run::PlcWrite::Unit::kOtcRadiusOffset);
    EXPECT_EQ(c[0].value, 20000);
    EXPECT_EQ(c[1].unit, apci::run::PlcWrite::Unit::kOtcOffset);
    EXPECT_EQ(c[1].index, 2);
    EXPECT_EQ(c[1].value, -500);
    ASSERT_EQ(s.value().block_writes().size(), 1u);
    EXPECT_EQ(s.value().block_writes()[0].field, apci::run::PlcWrite::Field::kEnable);
    EXPECT_EQ(s.value().block_writes()[0].value, 1);
    EXPECT_EQ(apci::run::plc_unit_name(c[1]), "otc_offset[2].command");
}

TEST(PlcScript, ErrorsSayWhatWasExpected) {
    auto err = [](const char* text) {
        auto s = apci::run::parse_plc_script(text, "p.plc");
        return s ? std::string() : s.error().to_string();
    };
    EXPECT_EQ(err("at 5 x 1"),
              "p.plc:1:1: expected 'cycle N' or 'block N' at the start of the line");
    EXPECT_EQ(err("cycle 5 motor.command 1"),
              "p.plc:1:9: unknown unit (known: otc_radius_offset, otc_offset[i], "
              "tool_temp_comp[i], tool_temp_comp_on, temp_comp_type[i], tool_holder, "
              "tool_holder_axis_b, tool_holder_axis_c, temp_ramp_velocity)");
    EXPECT_EQ(err("cycle 5 otc_offset[9].command 1"), "p.plc:1:9: otc_offset[i]: axis index 0..7");
    EXPECT_EQ(err("cycle 5 otc_offset[1].speed 1"),
              "p.plc:1:23: unknown field (known: command, enable)");
    EXPECT_EQ(err("cycle 5 otc_offset[1].enable 2"),
              "p.plc:1:30: enable takes 0, 1, TRUE or FALSE");
    EXPECT_EQ(err("cycle 5 otc_offset[1].command 1.5"),
              "p.plc:1:31: the value must be a whole number in the DINT range (0.1 um)");
    EXPECT_EQ(err("cycle 5 otc_offset[1].command 3000000000"),
              "p.plc:1:31: the value must be a whole number in the DINT range (0.1 um)");
    EXPECT_EQ(err("cycle 5 otc_offset[1].command 1 2"),
              "p.plc:1:33: unexpected text after the value");
}

}  // namespace
