// SPDX-License-Identifier: MIT
// The self-approach check of `apcictl run` against the stock-removal oracle, on programs shaped
// like CAM output (docs/testing.md, "The gouge oracle"). Each generated program runs through
// the executor on the embedded emulator; the oracle simulates the material its executed path
// removes from the design part the generator built, and the check's findings must agree:
//
//   correct programs: the run has no error, the oracle finds no gouge, the check warns nothing;
//   gouge programs:   the oracle finds the designed gouge; the run warns exactly the oracle's
//                     (path block, wall block) pairs, each depth within 1e-3 mm of the
//                     oracle's, or (only for shapes the compensation refuses) stops with an
//                     error before anything of the part is cut.
//
// One test per family (ctest label `gouge`), so that they run in parallel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

#include "apci/apci.hpp"
#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "apci/run/executor.h"
#include "apci/run/program_run.h"
#include "cam_programs.h"
#include "stock_oracle.h"

namespace apci::test {
namespace {

// Programs per family: at least 1,000 correct ones, at least 500 gouges the run must warn.
constexpr int kCorrectPerFamily = 46;
constexpr int kWarnedPerFamily = 75;
constexpr int kRefusedPerFamily = 30;
// The agreement in depth between the check and the oracle.
constexpr double kDepthAgreement = 1e-3;
// A designed gouge's depth as the oracle finds it, against the design before rounding.
constexpr double kDesignAgreement = 5e-3;
// No depth of a gouge program lies this close above the path tolerance (too close to call).
constexpr double kBand = 2e-3;

int cases_of(const CamFamilyInfo& f) {
    return !f.gouge ? kCorrectPerFamily : f.may_refuse ? kRefusedPerFamily : kWarnedPerFamily;
}

class Recorder final : public run::RunSink {
  public:
    void executed(const run::PathSegment& s) override { path.push_back(s); }
    std::vector<run::PathSegment> path;
};

struct CaseRun {
    std::string setup_error;  // the front end refused the program or its tool list
    run::RunOutcome outcome;
    std::vector<run::PathSegment> path;
};

// The program run as apcictl runs it (program_run.h), the check warning.
CaseRun run_case(const CamProgram& p) {
    CaseRun out;
    run::RunInputFiles files;
    files.tools = p.tool_list;
    files.tools_is_text = true;
    auto inputs = run::load_run_inputs(files);
    if (!inputs) {
        out.setup_error = "tool list: " + inputs.error().to_string();
        return out;
    }
    apci::Board board("emu:");
    if (!board.is_open()) {
        out.setup_error = "cannot open the embedded emulator";
        return out;
    }
    Recorder sink;
    auto ran =
        run::run_program(board, sink, inputs.value(),
                         run::ProgramSource::in_memory(p.text, "cam.nc"), run::RunSettings{});
    if (!ran) {
        out.setup_error = "program: " + ran.error().to_string();
        return out;
    }
    out.outcome = std::move(ran.value());
    out.path = std::move(sink.path);
    return out;
}

// A (path block, wall block) pair by source lines, with its depth.
struct Pair {
    std::uint64_t path = 0, wall = 0;
    double depth = 0;
};

std::string describe(const std::vector<Pair>& pairs) {
    std::string s;
    char buf[160];
    for (const Pair& p : pairs) {
        std::snprintf(buf, sizeof buf, "    path line %llu, wall line %llu: depth %.6f\n",
                      static_cast<unsigned long long>(p.path),
                      static_cast<unsigned long long>(p.wall), p.depth);
        s += buf;
    }
    return s.empty() ? "    (none)\n" : s;
}

const Pair* find(const std::vector<Pair>& pairs, std::uint64_t path, std::uint64_t wall) {
    for (const Pair& p : pairs)
        if (p.path == path && p.wall == wall) return &p;
    return nullptr;
}

// What one program showed.
struct Verdict {
    std::string outcome;  // "ok", "warned", "refused", or what failed
    bool ok = false;
    std::string detail;           // for a failure: the program, the oracle's and the check's pairs
    std::size_t check_pairs = 0;  // the check's findings
    // Of those the oracle does not name: against an element of the design part's boundary, or
    // against one that is none (a lead, a connecting move, an inner stepover loop).
    std::size_t false_on_walls = 0, false_on_non_walls = 0;
    std::size_t missed = 0;        // the oracle's pairs the check does not name
    double depth_difference = 0;   // the largest between the check's and the oracle's depth
    double deepest_intact = -1e9;  // the oracle's deepest pair within the tolerance
};

// v failed: what failed (its outcome), and why added to its detail.
Verdict failed(Verdict v, std::string outcome, const std::string& why) {
    v.outcome = std::move(outcome);
    v.ok = false;
    v.detail += why + "\n";
    return v;
}

// v passed, with this outcome.
Verdict passed(Verdict v, std::string outcome) {
    v.outcome = std::move(outcome);
    v.ok = true;
    return v;
}

// The tool radius of every executed segment (`radius`); why not, where a move below the top
// has none (the oracle would be blind there), else empty.
std::string tool_radii(const CamProgram& p, const CaseRun& run, std::vector<double>& radius) {
    for (const run::PathSegment& s : run.path) {
        radius.push_back(p.radius_at(s.block));
        if (std::min(s.start.z(), s.end.z()) < p.part.top && !(radius.back() > 0))
            return "a segment of line " + std::to_string(p.line_of(s.block)) +
                   " cuts with no tool radius known";
    }
    return {};
}

// What the oracle and the check found, by source lines.
struct Findings {
    OracleReport oracle;
    std::vector<Pair> theirs;  // the oracle's gouges
    std::vector<Pair> ours;    // the check's findings
};

// The oracle's gouges and the check's findings as (path line, wall line) pairs.
void pairs_by_line(const CamProgram& p, const CaseRun& run, Findings& found) {
    for (const OracleGouge& g : found.oracle.gouges)
        found.theirs.push_back({p.line_of(g.path_block), p.line_of(g.wall_block), g.depth});
    for (const run::SelfApproachFinding& f : run.outcome.self_approach)
        found.ours.push_back(
            {p.line_of(f.path_block), p.line_of(f.contour_block), f.radius - f.distance});
}

// The check's findings the oracle does not name (on walls of the design part or not), the
// oracle's the check misses, and the largest difference in depth of those both name.
void count_disagreements(const CamProgram& p, const Findings& found, Verdict& v) {
    std::vector<std::uint64_t> wall_lines;
    for (const DesignLoop& l : p.part.loops)
        for (const WallElement& e : l.elements) wall_lines.push_back(p.line_of(e.block));
    for (const Pair& o : found.ours)
        if (!find(found.theirs, o.path, o.wall)) {
            if (std::find(wall_lines.begin(), wall_lines.end(), o.wall) != wall_lines.end())
                ++v.false_on_walls;
            else
                ++v.false_on_non_walls;
        }
    for (const Pair& t : found.theirs) {
        const Pair* o = find(found.ours, t.path, t.wall);
        if (!o)
            ++v.missed;
        else
            v.depth_difference = std::max(v.depth_difference, std::abs(o->depth - t.depth));
    }
}

// The program, the run's errors, the oracle's and the check's pairs: a failure's detail.
std::string case_detail(const CamProgram& p, const CaseRun& run, const Findings& found) {
    std::string errors;
    for (const run::RunError& e : run.outcome.errors)
        errors += "    line " + std::to_string(p.line_of(e.block)) + ": " + e.code + ": " +
                  e.message + "\n";
    return "  features:\n" + p.summary() + "  run errors:\n" +
           (errors.empty() ? "    (none)\n" : errors) +
           "  the oracle's gouges (executed path against the design part):\n" +
           describe(found.theirs) +
           (found.oracle.buried.empty()
                ? ""
                : "  the oracle's buried blocks:\n" + apci::test::describe(found.oracle)) +
           "  the check's findings:\n" + describe(found.ours) + "  program:\n" + p.text +
           "  tool list:\n" + p.tool_list;
}

// A correct program: no run error, no gouge, no warning.
Verdict judge_correct_program(const CaseRun& run, const Findings& found, const Verdict& v) {
    if (!run.outcome.errors.empty())
        return failed(v, "run error", "a correct program stopped with an error");
    if (found.oracle.gouged())
        return failed(v, "oracle gouge", "the oracle finds the part cut by a correct program");
    if (!found.ours.empty())
        return failed(v, "false alarm", "the check warns a program that leaves the part intact");
    return passed(v, "ok");
}

// Why the oracle does not find the gouges built into a program that ran to its end (not at
// all, or not at the designed depth), or empty.
std::string design_missed(const CamProgram& p, const std::vector<Pair>& theirs) {
    for (const DesignedGouge& d : p.designed) {
        const Pair* found = find(theirs, d.path_line, d.wall_line);
        if (!found)
            return "the oracle does not find the designed gouge of line " +
                   std::to_string(d.path_line) + " into line " + std::to_string(d.wall_line);
        if (std::abs(found->depth - d.depth) > kDesignAgreement)
            return "the oracle's depth " + std::to_string(found->depth) + " is not the designed " +
                   std::to_string(d.depth);
    }
    return {};
}

// Where the check's pairs and the oracle's disagree (a pair not warned, one warned and not cut,
// a depth that differs), one line each; empty when they agree.
std::string pair_disagreement(const Findings& found) {
    std::string why;
    for (const Pair& t : found.theirs) {
        const Pair* o = find(found.ours, t.path, t.wall);
        if (!o) {
            why += "not warned: path line " + std::to_string(t.path) + ", wall line " +
                   std::to_string(t.wall) + "\n";
        } else if (std::abs(o->depth - t.depth) > kDepthAgreement) {
            why += "depth differs: path line " + std::to_string(t.path) + ", wall line " +
                   std::to_string(t.wall) + "\n";
        }
    }
    for (const Pair& o : found.ours)
        if (!find(found.theirs, o.path, o.wall))
            why += "warned, not cut: path line " + std::to_string(o.path) + ", wall line " +
                   std::to_string(o.wall) + "\n";
    return why;
}

// A gouge program: refused at the element the tool does not fit (for the shapes the
// compensation refuses), or the oracle finds the designed gouge and the check warns exactly
// the oracle's pairs at their depths (also what a refused run cut before it stopped).
Verdict judge_gouge_program(const CamProgram& p, const CaseRun& run, const Findings& found,
                            const Verdict& v) {
    const bool refused = !run.outcome.errors.empty();
    if (refused) {
        if (!p.may_refuse)
            return failed(v, "run error", "the compensation refused a shape it should run");
        // Refused for the shape built in: at the element the tool does not fit.
        const std::uint64_t at = p.line_of(run.outcome.errors.front().block);
        if (std::find(p.refused_at.begin(), p.refused_at.end(), at) == p.refused_at.end())
            return failed(v, "refused elsewhere",
                          "the run stopped at line " + std::to_string(at) +
                              ", not at the element smaller than the tool");
        if (!found.oracle.gouged() && found.ours.empty()) return passed(v, "refused");
        // It cut the part before it stopped: the run must have warned what it cut.
    } else if (const std::string why = design_missed(p, found.theirs); !why.empty()) {
        // Ran to its end: the oracle finds what was built in.
        return failed(v, "oracle misses the design", why);
    }
    if (!found.oracle.buried.empty())
        return failed(v, "buried", "a gouge program buries a block (not designed)");
    for (const Pair& t : found.theirs)
        if (t.depth < StockOracle::kPathTolerance + kBand)
            return failed(v, "too close to call",
                          "an oracle depth lies within 2e-3 mm of the path tolerance");
    if (const std::string why = pair_disagreement(found); !why.empty()) {
        const bool missed = why.find("not warned") != std::string::npos;
        const bool extra = why.find("warned, not cut") != std::string::npos;
        return failed(v,
                      std::string(refused ? "cut before the refusal, " : "") +
                          (missed && extra ? "missed and false pairs"
                           : missed        ? "missed pairs"
                           : extra         ? "false pairs"
                                           : "depth"),
                      why);
    }
    return passed(v, refused ? "warned, then refused" : "warned");
}

// The program run, its path measured by the oracle, and the check's findings judged against
// the oracle's.
Verdict judge(const CamProgram& p) {
    Verdict v;
    const CaseRun run = run_case(p);
    if (!run.setup_error.empty()) return failed(v, "front end refused it", run.setup_error);
    // Every move below the top has the radius of a tool: the oracle is not blind anywhere.
    std::vector<double> radius;
    if (const std::string why = tool_radii(p, run, radius); !why.empty())
        return failed(v, "no tool radius", why);
    Findings found;
    try {
        found.oracle = StockOracle(p.part).run(run.path, radius);
    } catch (const std::exception& e) {
        return failed(v, "oracle failed", e.what());
    }
    v.check_pairs = run.outcome.self_approach.size();
    v.deepest_intact = found.oracle.deepest_intact;
    pairs_by_line(p, run, found);
    count_disagreements(p, found, v);
    v.detail = case_detail(p, run, found);
    return p.gouge ? judge_gouge_program(p, run, found, v) : judge_correct_program(run, found, v);
}

class GougeAgreement : public testing::TestWithParam<CamFamilyInfo> {};

}  // namespace

// The family by its name in test listings.
void PrintTo(const CamFamilyInfo& f, std::ostream* os) {
    *os << f.name;
}

namespace {

TEST_P(GougeAgreement, CheckAgreesWithTheOracle) {
    const CamFamilyInfo& family = GetParam();
    int n = cases_of(family);
    // GOUGE_SEEDS=FIRST:COUNT draws other programs (the suite's are seeds 1000 on).
    std::uint64_t first_seed = 1000;
    if (const char* seeds = std::getenv("GOUGE_SEEDS")) {
        unsigned long long a = 0;
        int b = 0;
        ASSERT_EQ(std::sscanf(seeds, "%llu:%d", &a, &b), 2) << "GOUGE_SEEDS=FIRST:COUNT";
        first_seed = a;
        n = b;
    }
    std::vector<std::pair<std::string, int>> outcomes;
    int failures = 0, shown = 0;
    std::size_t check_pairs = 0, false_on_walls = 0, false_on_non_walls = 0, missed = 0;
    double deepest_intact = -1e9, depth_difference = 0;
    // GOUGE_DUMP=DIR writes every program and its tool list there (to run with apcictl).
    const char* dump = std::getenv("GOUGE_DUMP");
    for (int i = 0; i < n; ++i) {
        const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
        const CamProgram program = generate_cam_program(family.family, seed);
        if (dump) {
            const std::string base =
                std::string(dump) + "/" + program.text.substr(1, program.text.find('\n') - 1);
            std::ofstream(base + ".nc") << program.text;
            std::ofstream(base + ".tools") << program.tool_list;
            std::ofstream part(base +
                               ".part");  // one wall element a line: arc x0 y0 x1 y1 cx cy ccw line
            for (const DesignLoop& l : program.part.loops)
                for (const WallElement& e : l.elements)
                    part << e.arc << ' ' << e.start.x << ' ' << e.start.y << ' ' << e.end.x << ' '
                         << e.end.y << ' ' << e.centre.x << ' ' << e.centre.y << ' ' << e.ccw << ' '
                         << program.line_of(e.block) << '\n';
        }
        const Verdict v = judge(program);
        check_pairs += v.check_pairs;
        false_on_walls += v.false_on_walls;
        false_on_non_walls += v.false_on_non_walls;
        missed += v.missed;
        depth_difference = std::max(depth_difference, v.depth_difference);
        deepest_intact = std::max(deepest_intact, v.deepest_intact);
        auto it = std::find_if(outcomes.begin(), outcomes.end(),
                               [&](const auto& o) { return o.first == v.outcome; });
        if (it == outcomes.end())
            outcomes.emplace_back(v.outcome, 1);
        else
            ++it->second;
        if (v.ok) continue;
        ++failures;
        if (shown++ < 2)
            ADD_FAILURE() << program.name << ": " << v.outcome << "\n" << v.detail;
        else
            ADD_FAILURE() << program.name << ": " << v.outcome;
    }
    std::string summary;
    for (const auto& [what, count] : outcomes)
        summary += " " + what + " " + std::to_string(count) + ",";
    summary.pop_back();
    char deepest[32] = "none";
    if (deepest_intact > -1.0) std::snprintf(deepest, sizeof deepest, "%.1e mm", deepest_intact);
    std::printf(
        "[ gouge    ] %s: %d programs:%s; the check's pairs %zu (not cut: %zu against walls, %zu "
        "against leads or passes; cut but not warned: %zu; depths differ by %.1e mm at most); "
        "deepest intact pair %s\n",
        std::string(family.name).c_str(), n, summary.c_str(), check_pairs, false_on_walls,
        false_on_non_walls, missed, depth_difference, deepest);
    EXPECT_EQ(failures, 0) << family.name;
}

std::string family_test_name(const testing::TestParamInfo<CamFamilyInfo>& info) {
    std::string s;
    for (const char c : info.param.name) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return s;
}

INSTANTIATE_TEST_SUITE_P(Families, GougeAgreement,
                         testing::ValuesIn(cam_families().begin(), cam_families().end()),
                         family_test_name);

// The generators: the same seed draws the same program; its design part is exactly the
// geometry the NC front end reads from its text (rounded as written), each wall element tagged
// with the block that wrote it; every D has a tool; gouge programs carry their designed gouges.
TEST(CamPrograms, DesignPartIsTheGeometryTheProgramWrites) {
    int walls = 0, programs = 0;
    for (const CamFamilyInfo& f : cam_families()) {
        for (std::uint64_t seed = 1; seed <= 4; ++seed) {
            const CamProgram p = generate_cam_program(f.family, seed);
            const CamProgram again = generate_cam_program(f.family, seed);
            ASSERT_EQ(p.text, again.text) << p.name;
            ASSERT_EQ(p.tool_list, again.tool_list) << p.name;
            auto tools = nc::parse_tool_table(p.tool_list, "cam.tools");
            ASSERT_TRUE(tools) << p.name << ": " << tools.error().to_string();
            nc::InterpreterOptions options;
            options.tools = &tools.value();
            auto stream = nc::EventStream::from_text(p.text, "cam.nc", options);
            std::vector<nc::Event> moves;
            std::uint64_t lines = 0;
            for (nc::Event e;;) {
                const auto next = stream.next(e);
                ASSERT_NE(next, nc::EventStream::Next::kError)
                    << p.name << ": " << stream.error().to_string();
                if (next == nc::EventStream::Next::kEnd) break;
                lines = std::max(lines, e.origin.line);
                if (std::holds_alternative<nc::LineMove>(e.data) ||
                    std::holds_alternative<nc::ArcMove>(e.data))
                    moves.push_back(e);
            }
            EXPECT_EQ(p.radius_by_line.size(), lines + 1) << p.name;
            for (const auto& [number, line] : p.line_of_number)
                EXPECT_EQ(std::count_if(p.line_of_number.begin(), p.line_of_number.end(),
                                        [n = number](const auto& x) { return x.first == n; }),
                          1)
                    << p.name << ": N" << number << " twice";
            ASSERT_NO_THROW(StockOracle{p.part}) << p.name;
            for (const DesignLoop& l : p.part.loops)
                for (const WallElement& w : l.elements) {
                    const std::uint64_t line = p.line_of(w.block);
                    if (line == 0) continue;  // the plate around pockets
                    auto it = std::find_if(moves.begin(), moves.end(), [&](const nc::Event& e) {
                        return e.origin.line == line;
                    });
                    ASSERT_NE(it, moves.end()) << p.name << ": no move at line " << line;
                    EXPECT_EQ(it->origin.block, w.block.number) << p.name;
                    if (const auto* a = std::get_if<nc::ArcMove>(&it->data)) {
                        ASSERT_TRUE(w.arc) << p.name << " line " << line;
                        EXPECT_EQ(w.centre.x, a->center.x()) << p.name << " line " << line;
                        EXPECT_EQ(w.centre.y, a->center.y()) << p.name << " line " << line;
                        EXPECT_EQ(w.ccw, a->ccw) << p.name << " line " << line;
                        EXPECT_EQ(w.start.x, a->start.x());
                        EXPECT_EQ(w.start.y, a->start.y());
                        EXPECT_EQ(w.end.x, a->end.x());
                        EXPECT_EQ(w.end.y, a->end.y());
                    } else {
                        const auto& m = std::get<nc::LineMove>(it->data);
                        ASSERT_FALSE(w.arc) << p.name << " line " << line;
                        EXPECT_EQ(w.start.x, m.start.x());
                        EXPECT_EQ(w.start.y, m.start.y());
                        EXPECT_EQ(w.end.x, m.end.x());
                        EXPECT_EQ(w.end.y, m.end.y());
                    }
                    ++walls;
                }
            EXPECT_EQ(p.gouge, !p.designed.empty()) << p.name;
            for (const DesignedGouge& d : p.designed) {
                EXPECT_GT(d.path_line, 0U) << p.name;
                EXPECT_GT(d.wall_line, 0U) << p.name;
                EXPECT_GE(d.depth, StockOracle::kPathTolerance + kBand) << p.name;
            }
            EXPECT_EQ(p.may_refuse, !p.refused_at.empty()) << p.name;
            ++programs;
        }
    }
    EXPECT_EQ(programs, static_cast<int>(cam_families().size()) * 4);
    EXPECT_GT(walls, 1000);
}

TEST(GougeAgreementCounts, AtLeastAThousandCorrectProgramsAndFiveHundredWarnedGouges) {
    int correct = 0, warned = 0, refused = 0;
    for (const CamFamilyInfo& f : cam_families()) {
        if (!f.gouge)
            correct += cases_of(f);
        else if (f.may_refuse)
            refused += cases_of(f);
        else
            warned += cases_of(f);
    }
    EXPECT_GE(correct, 1000);
    EXPECT_GE(warned, 500);
    EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace apci::test
