// SPDX-License-Identifier: MIT
// Temperature compensation in tool direction through `apcictl run` (a process on the embedded
// emulator): SD 42960 written by the NC program ($SC_TOOL_TEMP_COMP[i]) and by the scripted PLC
// (--plc tool_temp_comp[i], with the machine data tool_temp_comp_on and temp_comp_type[i]), the
// example in examples/temperature/, refusals before anything runs. [SIN-TEMP] (SINUMERIK 840D
// FB1 W1 section 2.8); docs/temperature-compensation.md, docs/apcictl.md ("run --plc").
//
// A run with the machine data and one without (which writes the same setting data and moves
// the same way, but displaces nothing) give the displacement per interpolation cycle as the
// difference of their CSV traces.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "apci/run/plc_script.h"
#include "apcictl.h"
#include "scratch_test.h"
#include "text.h"

namespace {

using test_support::read_csv;
using test_support::read_text;
using nlohmann::json;
using test_support::apcictl;
using test_support::ProcessResult;

const std::string kSource = APCI_SOURCE_DIR;
const std::string kExamples = kSource + "/examples";
const std::string kMachineData = kExamples + "/temperature/plc/machine_data.plc";
constexpr double kEps = 1e-9;
// CSV columns: cycle, time, then board axes 0..7 (X, Y, Z on 0, 1, 2 by default).
constexpr std::size_t kCycle = 0, kX = 2, kY = 3, kZ = 4;

class TempCompRun : public test_support::ScratchTest {
  protected:
    TempCompRun() : ScratchTest("tempcomp_run_") {}

    // Runs the program with the PLC script (none: "") and returns the CSV trace; the JSON goes
    // to `json_name`.
    std::vector<std::vector<double>> trace(const std::string& program, const std::string& plc,
                                           const std::string& json_name = "out.json") {
        std::vector<std::string> args{"run",           program,  "--csv",
                                      path("out.csv"), "--json", path(json_name)};
        if (!plc.empty()) {
            args.emplace_back("--plc");
            args.push_back(plc);
        }
        const ProcessResult r = apcictl(args);
        EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
        return read_csv(path("out.csv"));
    }
    json doc(const std::string& json_name = "out.json") const {
        return json::parse(read_text(path(json_name)));
    }

};

// The example runs with the command its header documents (paths from the source tree).
TEST_F(TempCompRun, ExampleRunsWithItsDocumentedCommand) {
    const std::string file = kExamples + "/temperature/spindle_growth.nc";
    std::vector<std::string> args = test_support::documented_command(file, kSource);
    ASSERT_FALSE(args.empty());
    args.emplace_back("--json");
    args.push_back(path("out.json"));
    const ProcessResult r = apcictl(args);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    const json d = doc();
    EXPECT_EQ(d.at("errors"), json::array());
    EXPECT_EQ(d.at("variables").at("$SC_TOOL_TEMP_COMP[2]"), 0.0);  // N80 took it off
}

// [SIN-TEMP]: the setting data act at once; a program's write acts from its block on, also in
// the middle of the program: N40 0.015, N60 and N70 0.025, N90 0 (the example's comments).
// The positions the moves pass are the same with and without the compensation; Z differs by
// the value in force, X and Y not at all.
TEST_F(TempCompRun, ProgramWriteActsFromItsBlockOn) {
    const std::string program = kExamples + "/temperature/spindle_growth.nc";
    const auto on = trace(program, kMachineData);
    const auto off = trace(program, "");
    ASSERT_EQ(on.size(), off.size());
    ASSERT_GT(on.size(), 1000u);
    std::array<int, 4> seen{};
    for (std::size_t i = 0; i < on.size(); ++i) {
        const auto& n = off[i];  // the nominal path
        double expected = 0.0;
        if (n[kZ] > 10.0) {
            expected = 0.0;  // N90, after N80 took it off
            ++seen[3];
        } else if (n[kY] == 0.0 && n[kX] <= 50.0) {
            expected = 0.0;  // N10, N20: before N30
            ++seen[0];
        } else if (n[kY] == 0.0) {
            expected = 0.015;  // N40
            ++seen[1];
        } else {
            expected = 0.025;  // N60, N70
            ++seen[2];
        }
        ASSERT_EQ(on[i][kCycle], n[kCycle]);
        EXPECT_EQ(on[i][kX], n[kX]) << "cycle " << n[kCycle];
        EXPECT_EQ(on[i][kY], n[kY]) << "cycle " << n[kCycle];
        EXPECT_NEAR(on[i][kZ] - n[kZ], expected, kEps) << "cycle " << n[kCycle];
    }
    for (int k = 0; k < 4; ++k) EXPECT_GT(seen[static_cast<std::size_t>(k)], 20) << k;
    // Without the machine data the program's writes still reach the board.
    EXPECT_EQ(doc().at("variables").at("$SC_TOOL_TEMP_COMP[2]"), 0.0);
}

// Under radius compensation the TC module holds the last contour element back until the next
// one arrives ([APCI-TC] section 1, docs/compensation.md): the write comes after every move that
// could run, so the held element of the block before it (N40) runs with the new value, and the
// elements before it (N30) without.
TEST_F(TempCompRun, UnderRadiusCompensationTheHeldElementTakesTheWrite) {
    const std::string tools = write("m.tools", "wz[2].gueltig 1\nwz[2].mass_einheit 1\n"
                                               "wz[2].radius 5\n");
    const std::string program = write(
        "g41.nc", "N10 D2\nN20 G0 X0 Y0 Z0\nN30 G41 G1 X10 Y0 F3000\nN40 G1 X50\n"
                  "N50 $SC_TOOL_TEMP_COMP[2] = 0.1\nN60 G1 Y40\nN70 G40 G1 X0 Y0\nN80 M30\n");
    auto run = [&](const std::string& plc) {
        std::vector<std::string> args{"run", program, "--tools", tools, "--csv", path("g.csv")};
        if (!plc.empty()) args.insert(args.end(), {"--plc", plc});
        const ProcessResult r = apcictl(args);
        EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
        return read_csv(path("g.csv"));
    };
    const auto on = run(kMachineData);
    const auto off = run("");
    ASSERT_EQ(on.size(), off.size());
    // The compensated path: N30 ends at (10, 5), N40 runs along Y = 5 to X = 45; from N40's
    // first cycle on (to the end) Z carries the value, before it not.
    std::size_t first_n40 = on.size();
    for (std::size_t i = 0; i < off.size() && first_n40 == on.size(); ++i)
        if (off[i][kY] == 5.0 && off[i][kX] > 10.0) first_n40 = i;
    ASSERT_GT(first_n40, 100u);
    ASSERT_LT(first_n40 + 100, on.size());
    for (std::size_t i = 0; i < on.size(); ++i) {
        const auto& n = off[i];
        EXPECT_NEAR(on[i][kZ] - n[kZ], i < first_n40 ? 0.0 : 0.1, kEps) << "cycle " << n[kCycle];
    }
    int n40 = 0;
    for (const auto& n : off)
        if (n[kY] == 5.0 && n[kX] > 10.0) ++n40;
    EXPECT_GT(n40, 100);
}

// The value a program reads is the board's when the line is read, after the blocks before it
// were sent: the PLC's write at block 10 is seen by N20.
TEST_F(TempCompRun, ProgramReadsTheBoardsSettingData) {
    const std::string program =
        write("p.nc",
              "N10 G1 X10 F6000\nN20 $SC_TOOL_TEMP_COMP[0] = $SC_TOOL_TEMP_COMP[1] * 2\n"
              "N30 M30\n");
    const std::string plc = write("p.plc", "block 10 tool_temp_comp[1] 0.125\n");
    (void)trace(program, plc);
    const json v = doc().at("variables");
    EXPECT_EQ(v.at("$SC_TOOL_TEMP_COMP[0]"), 0.25);
    EXPECT_EQ(v.at("$SC_TOOL_TEMP_COMP[1]"), 0.125);
    EXPECT_EQ(v.at("$SC_TOOL_TEMP_COMP[2]"), 0.0);
}

// A PLC cycle write acts at its cycle, in the middle of a move ("Werteveränderungen in den
// Settingdaten werden sofort wirksam"); a block write from its block on. Each axis needs bit 2
// of its MD 32750: Z without it gets nothing, silently, while X and Y take theirs.
TEST_F(TempCompRun, PlcWritesActAtTheirCycleAndBlock) {
    const std::string program =
        write("p.nc", "N10 G1 X100 F6000\nN20 G1 Y50\nN30 G1 X0\nN40 M30\n");
    const std::string md =
        "cycle 0 tool_temp_comp_on TRUE\ncycle 0 temp_comp_type[0] 4\n"
        "cycle 0 temp_comp_type[1] 7\n";
    const std::string plc = write("on.plc", md + "cycle 400 tool_temp_comp[0] 0.05\n"
                                                 "block 30 tool_temp_comp[1] -0.02\n"
                                                 "block 20 tool_temp_comp[2] 0.5\n");
    const auto on = trace(program, plc, "on.json");
    const auto off = trace(program, write("off.plc", md));
    ASSERT_EQ(on.size(), off.size());
    int mid_move = 0;
    int after_block = 0;
    for (std::size_t i = 0; i < on.size(); ++i) {
        const auto& n = off[i];
        const double cycle = n[kCycle];
        const bool n30 = n[kY] == 50.0 && n[kX] < 100.0;
        EXPECT_NEAR(on[i][kX] - n[kX], cycle > 400 ? 0.05 : 0.0, kEps) << "cycle " << cycle;
        EXPECT_NEAR(on[i][kY] - n[kY], n30 ? -0.02 : 0.0, kEps) << "cycle " << cycle;
        EXPECT_EQ(on[i][kZ], n[kZ]) << "cycle " << cycle;
        if (cycle > 400 && n[kY] == 0.0 && n[kX] < 100.0) ++mid_move;
        if (n30) ++after_block;
    }
    EXPECT_GT(mid_move, 100);  // the cycle write landed while N10 was under way
    EXPECT_GT(after_block, 100);
    const json v = doc("on.json").at("variables");
    EXPECT_EQ(v.at("$SC_TOOL_TEMP_COMP[2]"), 0.5);
}

// A PLC write past the program's end is written after it (the clock runs on to it).
TEST_F(TempCompRun, PlcWriteAfterTheProgramsEndIsWritten) {
    const std::string program = write("p.nc", "N10 G1 X10 F6000\nN20 M30\n");
    const std::string plc = write("p.plc", "cycle 5000 tool_temp_comp[0] 0.5\n");
    const auto rows = trace(program, plc);
    ASSERT_FALSE(rows.empty());
    EXPECT_EQ(rows.back()[kCycle], 5000.0);
    EXPECT_EQ(doc().at("variables").at("$SC_TOOL_TEMP_COMP[0]"), 0.5);
}

// [SIN-TEMP]: with an orientable tool holder the vector turns with the tool orientation, at once.
// The PLC switches the holder on (tool_holder); the program turns the head's B (board axis 4)
// from 0 to 90 degrees during N30: at every cycle the displacement is Ry(B) (0, 0, 0.1), so Z's
// 0.1 goes over to X. With the holder's B on another axis (tool_holder_axis_b 5, which stays at
// 0) nothing turns; without the holder nothing turns either.
TEST_F(TempCompRun, PlcToolHolderTurnsTheVectorWithTheHead) {
    constexpr std::size_t kB = 6;  // board axis 4
    const std::string program = write("h.nc",
                                      "N10 G0 X0 Y0 Z10 B0\nN20 $SC_TOOL_TEMP_COMP[2] = 0.1\n"
                                      "N30 G1 X10 B90 F3000\nN40 G1 X20\nN50 M30\n");
    const std::string md =
        "cycle 0 tool_temp_comp_on 1\ncycle 0 temp_comp_type[0] 4\n"
        "cycle 0 temp_comp_type[2] 4\ncycle 0 temp_ramp_velocity 0.5\n";
    const auto off = trace(program, "");
    const auto still = trace(program, write("still.plc", md), "still.json");
    const auto turned = trace(program, write("on.plc", md + "cycle 0 tool_holder TRUE\n"));
    const auto other_axis =
        trace(program, write("b5.plc", md + "cycle 0 tool_holder 1\ncycle 0 tool_holder_axis_b 5\n"
                                            "cycle 0 tool_holder_axis_c -1\n"));
    ASSERT_EQ(turned.size(), off.size());
    ASSERT_EQ(still.size(), off.size());
    ASSERT_EQ(other_axis.size(), off.size());
    int turning = 0;
    for (std::size_t i = 0; i < off.size(); ++i) {
        const auto& n = off[i];
        const double b = n[kB] * std::numbers::pi / 180.0;
        // N10 runs before the write; from N20 on (the axes standing at X0 Z10) the vector acts,
        // and N30 moves X and B from its first cycle.
        const double v = n[kX] > 0.0 || n[kB] > 0.0 ? 0.1 : 0.0;
        EXPECT_NEAR(turned[i][kX] - n[kX], v * std::sin(b), kEps) << "cycle " << n[kCycle];
        EXPECT_NEAR(turned[i][kZ] - n[kZ], v * std::cos(b), kEps) << "cycle " << n[kCycle];
        EXPECT_EQ(turned[i][kB], n[kB]);  // the head itself is not displaced
        EXPECT_NEAR(still[i][kX] - n[kX], 0.0, kEps) << "cycle " << n[kCycle];
        EXPECT_NEAR(still[i][kZ] - n[kZ], v, kEps) << "cycle " << n[kCycle];
        EXPECT_NEAR(other_axis[i][kX] - n[kX], 0.0, kEps) << "cycle " << n[kCycle];
        EXPECT_NEAR(other_axis[i][kZ] - n[kZ], v, kEps) << "cycle " << n[kCycle];
        if (n[kB] > 1.0 && n[kB] < 89.0) ++turning;
    }
    EXPECT_GT(turning, 50);  // N30 turns the head over many cycles
    EXPECT_EQ(off.back()[kB], 90.0);
}

// [SIN-TEMP]: with the orientation transformation on (#KIN ID[4], #TRAFO ON) the vector turns
// with the tool, without the tool holder: at B90 the 0.1 mm on Z of N60 acts on X along N70, and
// on Z again after #TRAFO OFF (N90). No tool: the pivot is the tip.
TEST_F(TempCompRun, TheVectorTurnsWithTheOrientationTransformation) {
    const std::string program =
        write("t.nc",
              "N10 G0 X0 Y0 Z10 B0\nN30 #KIN ID[4]\nN40 #TRAFO ON\nN50 G0 B90\n"
              "N60 $SC_TOOL_TEMP_COMP[2] = 0.1\nN70 G1 X10 F3000\nN80 #TRAFO OFF\n"
              "N90 G1 X20\nN100 M30\n");
    const std::string md =
        "cycle 0 tool_temp_comp_on 1\ncycle 0 temp_comp_type[0] 4\n"
        "cycle 0 temp_comp_type[2] 4\n";
    const auto off = trace(program, "");
    const auto on = trace(program, write("md.plc", md));
    ASSERT_EQ(on.size(), off.size());
    int along_x = 0, along_z = 0;
    for (std::size_t i = 0; i < off.size(); ++i) {
        const auto& n = off[i];
        const double dx = on[i][kX] - n[kX], dz = on[i][kZ] - n[kZ];
        if (n[kX] > 0.0 && n[kX] < 10.0) {  // N70, under the transformation at B90
            EXPECT_NEAR(dx, 0.1, kEps) << "cycle " << n[kCycle];
            EXPECT_NEAR(dz, 0.0, kEps) << "cycle " << n[kCycle];
            ++along_x;
        } else if (n[kX] > 10.0) {  // N90, after #TRAFO OFF
            EXPECT_NEAR(dx, 0.0, kEps) << "cycle " << n[kCycle];
            EXPECT_NEAR(dz, 0.1, kEps) << "cycle " << n[kCycle];
            ++along_z;
        }
    }
    EXPECT_GT(along_x, 100);
    EXPECT_GT(along_z, 100);
}

// ---- refusals: named by file and line, and nothing runs (no output file is written)

TEST_F(TempCompRun, BadProgramWriteIsRefusedBeforeAnythingRuns) {
    struct Case {
        const char* line;
        const char* error;
    };
    const Case cases[] = {
        {"N20 $SC_TOOL_TEMP_COMP[3] = 0.1",
         ":2:5: N20: $SC_TOOL_TEMP_COMP[i] takes a component index 0..2"},
        {"N20 $SC_TOOL_TEMP_COMP[1] = 200000",
         ":2:5: N20: $SC_TOOL_TEMP_COMP[1] = 200000 out of range: SD 42960 takes -100000..100000 mm"},
        {"N20 $SC_TOOL_TEMP_COMP[1] = 1 / 0", ":2:"},
        {"N20 $SN_TOOL_TEMP_COMP[1] = 1", ":2:5: N20: $SN_TOOL_TEMP_COMP: SD 42960 TOOL_TEMP_COMP is"},
    };
    for (const Case& c : cases) {
        const std::string program =
            write("bad.nc", std::string("N10 G1 X10 F6000\n") + c.line + "\nN30 M30\n");
        std::filesystem::remove(path("out.json"));
        const ProcessResult r = apcictl({"run", program, "--json", path("out.json")});
        EXPECT_EQ(r.exit_code, 1) << c.line;
        EXPECT_NE(r.err.find(program + c.error), std::string::npos) << c.line << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(path("out.json"))) << c.line;
    }
}

TEST_F(TempCompRun, BadPlcScriptIsRefusedBeforeAnythingRuns) {
    const std::string program = write("p.nc", "N10 G1 X10 F6000\nN20 M30\n");
    const std::string plc =
        write("bad.plc", "cycle 0 tool_temp_comp_on 1\nblock 10 tool_temp_comp[2] 100000.5\n");
    const ProcessResult r = apcictl({"run", program, "--plc", plc, "--json", path("out.json")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find(plc + ":2:28: tool_temp_comp[2] (SD 42960, mm) takes -100000..100000"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("out.json")));
}

// ---- the PLC script's temperature units (apci/run/plc_script.h)

TEST(PlcScriptTemperature, ParsesTheSettingAndMachineData) {
    using apci::run::PlcWrite;
    auto s = apci::run::parse_plc_script(
        "cycle 0 tool_temp_comp_on TRUE\ncycle 0 temp_comp_type[7] 255\n"
        "block 20 tool_temp_comp[2] -0.0125  # growth\ncycle 10 TOOL_TEMP_COMP[0] 3\n",
        "p.plc");
    ASSERT_TRUE(s) << s.error().to_string();
    const auto& c = s.value().cycle_writes();
    ASSERT_EQ(c.size(), 3u);
    EXPECT_EQ(c[0].unit, PlcWrite::Unit::kToolTempCompOn);
    EXPECT_EQ(c[0].value, 1.0);
    EXPECT_EQ(c[1].unit, PlcWrite::Unit::kTempCompType);
    EXPECT_EQ(c[1].index, 7);
    EXPECT_EQ(c[1].value, 255.0);
    EXPECT_EQ(c[2].unit, PlcWrite::Unit::kToolTempComp);
    EXPECT_EQ(c[2].index, 0);
    EXPECT_EQ(c[2].value, 3.0);
    const auto& b = s.value().block_writes();
    ASSERT_EQ(b.size(), 1u);
    EXPECT_EQ(b[0].index, 2);
    EXPECT_EQ(b[0].value, -0.0125);
    EXPECT_EQ(apci::run::plc_unit_name(b[0]), "tool_temp_comp[2]");
    EXPECT_EQ(apci::run::plc_unit_name(c[0]), "tool_temp_comp_on");
    EXPECT_EQ(apci::run::plc_unit_name(c[1]), "temp_comp_type[7]");
}

// [SIN-TEMP]: MD 20390 is on for any value "ungleich Null": the script passes any int32 on.
TEST(PlcScriptTemperature, Md20390TakesAnyWholeInt32) {
    auto s = apci::run::parse_plc_script(
        "cycle 0 tool_temp_comp_on 2\ncycle 0 tool_temp_comp_on -2147483648\n"
        "cycle 0 tool_temp_comp_on 2147483647\ncycle 0 tool_temp_comp_on FALSE\n",
        "p.plc");
    ASSERT_TRUE(s) << s.error().to_string();
    const auto& c = s.value().cycle_writes();
    ASSERT_EQ(c.size(), 4u);
    EXPECT_EQ(c[0].value, 2.0);
    EXPECT_EQ(c[1].value, -2147483648.0);
    EXPECT_EQ(c[2].value, 2147483647.0);
    EXPECT_EQ(c[3].value, 0.0);
}

TEST(PlcScriptTemperature, RefusalsNameTheLineAndWhatWasWrong) {
    auto err = [](const char* text) {
        auto s = apci::run::parse_plc_script(text, "p.plc");
        return s ? std::string() : s.error().to_string();
    };
    EXPECT_EQ(err("cycle 5 tool_temp_comp[3] 1"),
              "p.plc:1:9: tool_temp_comp[i]: component index 0..2");
    EXPECT_EQ(err("cycle 5 tool_temp_comp 1"), "p.plc:1:23: expected '[i]' after tool_temp_comp");
    EXPECT_EQ(err("cycle 5 temp_comp_type[8] 4"), "p.plc:1:9: temp_comp_type[i]: axis index 0..7");
    EXPECT_EQ(err("cycle 5 tool_temp_comp[0] 100001"),
              "p.plc:1:27: tool_temp_comp[0] (SD 42960, mm) takes -100000..100000");
    EXPECT_EQ(err("cycle 5 tool_temp_comp[0] -100001"),
              "p.plc:1:27: tool_temp_comp[0] (SD 42960, mm) takes -100000..100000");
    EXPECT_EQ(err("cycle 5 tool_temp_comp[0] nan"),
              "p.plc:1:27: expected a value (a finite number)");
    EXPECT_EQ(err("cycle 5 tool_temp_comp[0] inf"),
              "p.plc:1:27: expected a value (a finite number)");
    EXPECT_EQ(err("cycle 5 tool_temp_comp_on 2.5"),
              "p.plc:1:27: tool_temp_comp_on (MD 20390) takes a whole number (int32; not 0: on), "
              "TRUE or FALSE");
    EXPECT_EQ(err("cycle 5 tool_temp_comp_on 2147483648"),
              "p.plc:1:27: tool_temp_comp_on (MD 20390) takes a whole number (int32; not 0: on), "
              "TRUE or FALSE");
    EXPECT_EQ(err("cycle 5 tool_temp_comp_on on"),
              "p.plc:1:27: tool_temp_comp_on (MD 20390) takes a whole number (int32; not 0: on), "
              "TRUE or FALSE");
    EXPECT_EQ(err("cycle 5 temp_comp_type[1] 4.5"),
              "p.plc:1:27: temp_comp_type[i] (MD 32750) takes a whole number 0..255 (bit 2, 4: "
              "the axis takes the vector)");
    EXPECT_EQ(err("cycle 5 temp_comp_type[1] 256"),
              "p.plc:1:27: temp_comp_type[i] (MD 32750) takes a whole number 0..255 (bit 2, 4: "
              "the axis takes the vector)");
    EXPECT_EQ(err("cycle 5 tool_temp_comp[0] 1 2"), "p.plc:1:29: unexpected text after the value");
    EXPECT_EQ(err("cycle 5 tool_holder 2"), "p.plc:1:21: tool_holder takes 0, 1, TRUE or FALSE");
    EXPECT_EQ(err("cycle 5 tool_holder yes"), "p.plc:1:21: tool_holder takes 0, 1, TRUE or FALSE");
    EXPECT_EQ(err("cycle 5 tool_holder_axis_b -1"),
              "p.plc:1:28: tool_holder_axis_b takes a board axis 0..7");
    EXPECT_EQ(err("cycle 5 tool_holder_axis_b 8"),
              "p.plc:1:28: tool_holder_axis_b takes a board axis 0..7");
    EXPECT_EQ(err("cycle 5 tool_holder_axis_c -2"),
              "p.plc:1:28: tool_holder_axis_c takes a board axis 0..7, or -1 (no C axis)");
    EXPECT_EQ(err("cycle 5 tool_holder_axis_c 4.5"),
              "p.plc:1:28: tool_holder_axis_c takes a board axis 0..7, or -1 (no C axis)");
    EXPECT_EQ(err("cycle 5 temp_ramp_velocity 0"),
              "p.plc:1:28: temp_ramp_velocity (mm/s) takes 1e-06..100000");
    EXPECT_EQ(err("cycle 5 temp_ramp_velocity 100001"),
              "p.plc:1:28: temp_ramp_velocity (mm/s) takes 1e-06..100000");
    EXPECT_EQ(err("cycle 5 temp_ramp_velocity nan"),
              "p.plc:1:28: expected a value (a finite number)");
    EXPECT_EQ(err("cycle 5 tool_holder.enable 1"),
              "p.plc:1:20: expected a value (a finite number)");
}

TEST(PlcScriptTemperature, ParsesTheToolHolderUnits) {
    using apci::run::PlcWrite;
    auto s = apci::run::parse_plc_script(
        "cycle 1 tool_holder TRUE\ncycle 2 TOOL_HOLDER_AXIS_B 6\ncycle 3 tool_holder_axis_c -1\n"
        "cycle 4 temp_ramp_velocity 2.5\ncycle 5 tool_holder 0\n",
        "p.plc");
    ASSERT_TRUE(s) << s.error().to_string();
    const auto& c = s.value().cycle_writes();
    ASSERT_EQ(c.size(), 5u);
    const PlcWrite::Unit units[] = {PlcWrite::Unit::kToolHolder, PlcWrite::Unit::kToolHolderAxisB,
                                    PlcWrite::Unit::kToolHolderAxisC,
                                    PlcWrite::Unit::kTempRampVelocity, PlcWrite::Unit::kToolHolder};
    const double values[] = {1.0, 6.0, -1.0, 2.5, 0.0};
    const char* names[] = {"tool_holder", "tool_holder_axis_b", "tool_holder_axis_c",
                           "temp_ramp_velocity", "tool_holder"};
    for (std::size_t i = 0; i < c.size(); ++i) {
        EXPECT_EQ(c[i].unit, units[i]) << i;
        EXPECT_EQ(c[i].value, values[i]) << i;
        EXPECT_EQ(apci::run::plc_unit_name(c[i]), names[i]) << i;
        EXPECT_FALSE(c[i].otc()) << i;
    }
    EXPECT_TRUE(c[0].flag());
    EXPECT_FALSE(c[1].flag());
}

}  // namespace
