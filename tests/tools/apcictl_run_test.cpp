// SPDX-License-Identifier: MIT
// `apcictl run` as a process on the embedded emulator: [ISG-OTC-EN]'s wr_quad_disc.nc, one program per corner
// type (docs/figures/), errors with block and name, parse errors, exit codes, the outputs.
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <pty.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "apci/run/path.h"
#include "apci/run/self_approach.h"
#include "plate_program.h"
#include "process.h"
#include "rwmos/comp3d/compensation.h"
#include "rwmos/geometry/shared.h"
#include "rwmos/geometry/kinematics.h"

namespace {

using nlohmann::json;
using test_support::ProcessResult;
namespace geom = rwmos::geom;
namespace c3 = rwmos::comp3d;

const std::string kSource = APCI_SOURCE_DIR;
const std::string kExamples = kSource + "/examples";
const std::string kFigures = APCI_SOURCE_DIR "/docs/figures";
constexpr double kTol = 1e-6;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

bool exists(const std::string& path) {
    struct stat st;
    return ::stat(path.c_str(), &st) == 0;
}

// Starts the emulator daemon serving a socket at `socket` (its standard error to /dev/null) and
// waits up to 5 s for the socket; the child's pid, or -1.
pid_t start_daemon(const std::string& socket) {
    const pid_t daemon = ::fork();
    if (daemon == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 2);
        ::execl(RWMOS_EMU_PATH, RWMOS_EMU_PATH, "--socket", socket.c_str(), nullptr);
        ::_exit(127);
    }
    for (int i = 0; daemon > 0 && i < 500 && !exists(socket); ++i) ::usleep(10'000);
    return daemon;
}

class ApcictlRun : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string templ = ::testing::TempDir() + "apcictl_run_XXXXXX";
        ASSERT_NE(::mkdtemp(templ.data()), nullptr);
        dir_ = templ;
    }
    void TearDown() override { std::system(("rm -rf '" + dir_ + "'").c_str()); }

    std::string path(const std::string& name) const { return dir_ + "/" + name; }
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(path(name)) << text;
        return path(name);
    }
    // A tool list with D1 of radius r and length len, in mm.
    std::string tools(double r, double len = 0.0) const {
        return write("t.tools", "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius " +
                                    std::to_string(r) + "\nwz[1].laenge " + std::to_string(len) +
                                    "\n");
    }

    static ProcessResult apcictl(std::vector<std::string> args, const std::string& input = {}) {
        args.insert(args.begin(), APCICTL_PATH);
        return test_support::run_process(args, input);
    }
    // Runs a program with --json (and the given extra arguments); returns the JSON document.
    json run_json(const std::string& program, std::vector<std::string> extra = {},
                  int expected_exit = 0) {
        std::vector<std::string> args{"run", program, "--json", path("out.json")};
        args.insert(args.end(), extra.begin(), extra.end());
        last_ = apcictl(args);
        EXPECT_EQ(last_.exit_code, expected_exit) << last_.out << last_.err;
        return json::parse(read_text(path("out.json")));
    }

    std::string dir_;
    ProcessResult last_;
};

// ---- JSON helpers

apci::run::Point point(const json& a) {
    return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()};
}

apci::run::PathSegment segment_of(const json& s) {
    apci::run::PathSegment p;
    p.start = point(s.at("start"));
    p.end = point(s.at("end"));
    p.kind = s.at("kind") == "arc" ? apci::run::SegmentKind::kArc : apci::run::SegmentKind::kLine;
    if (p.kind == apci::run::SegmentKind::kArc) {
        p.center = point(s.at("center"));
        p.ccw = s.at("ccw").get<bool>();
        p.plane = s.at("plane").get<int>();
    }
    return p;
}

std::vector<json> with_role(const json& doc, const std::string& role) {
    std::vector<json> out;
    for (const auto& s : doc.at("segments"))
        if (s.at("role") == role) out.push_back(s);
    return out;
}

std::string roles(const json& doc) {
    std::string out;
    for (const auto& s : doc.at("segments")) {
        if (!out.empty()) out += ' ';
        out += s.at("role").get<std::string>() + "/" + std::to_string(s.at("block").get<int>());
    }
    return out;
}

// The distance from p (in the plane's coordinates) to the nearest programmed element.
double distance_to_contour(const std::vector<geom::Element>& contour, const geom::Vec2& p) {
    double d = INFINITY;
    for (const auto& e : contour) d = std::min(d, geom::distance_to(e, p));
    return d;
}

// Every point of every segment with one of `roles` (21 samples each), in the plane `plane`,
// lies `r` from the programmed contour (exactly, or at least when `at_least`).
// Segments of the blocks in `skip` are left out.
void expect_at_radius(const json& doc, const std::vector<geom::Element>& contour, double r,
                      const std::vector<std::string>& which, bool at_least = false, int plane = 17,
                      const std::vector<int>& skip = {}) {
    const apci::run::PlaneAxes a = apci::run::plane_axes(plane);
    int checked = 0;
    for (const auto& s : doc.at("segments")) {
        if (std::find(which.begin(), which.end(), s.at("role").get<std::string>()) == which.end())
            continue;
        if (std::find(skip.begin(), skip.end(), s.at("block").get<int>()) != skip.end()) continue;
        const apci::run::PathSegment seg = segment_of(s);
        for (int i = 0; i <= 20; ++i) {
            const apci::run::Point q = apci::run::point_along(seg, i / 20.0);
            const double d = distance_to_contour(contour, {q[a.first], q[a.second]});
            if (at_least) {
                EXPECT_GE(d, r - kTol) << s.dump() << " at t=" << i / 20.0;
            } else {
                EXPECT_NEAR(d, r, kTol) << s.dump() << " at t=" << i / 20.0;
            }
            ++checked;
        }
    }
    EXPECT_GT(checked, 0);
}

void expect_continuous(const json& doc) {
    const auto& segs = doc.at("segments");
    for (std::size_t i = 1; i < segs.size(); ++i)
        EXPECT_LT((point(segs[i].at("start")) - point(segs[i - 1].at("end"))).norm(), 1e-9)
            << segs[i - 1].dump() << "\n"
            << segs[i].dump();
}

void expect_registers_clear(const json& doc) {
    for (const char* g : {"1", "2", "3"}) {
        EXPECT_EQ(doc.at("registers").at(g).at("ERROR"), 0) << g;
        EXPECT_EQ(doc.at("registers").at(g).at("STATUS"), 0) << g;
    }
}

// ---- wr_quad_disc.nc of [ISG-OTC-EN]

TEST_F(ApcictlRun, MustShowSeedProgramSummaryJsonAndSvg) {
    const auto r = apcictl({"run", kExamples + "/wr_quad_disc.nc", "--tools",
                            kExamples + "/tools/wr_quad_disc.tools", "--svg", path("p.svg"),
                            "--json", path("p.json")});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    // 11 segments: N40, the approach N60, 4 contour elements, 4 transitions, N100.
    EXPECT_TRUE(contains(r.out, "wr_quad_disc.nc: 11 blocks, 11 executed, 11 segments\n")) << r.out;
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
    EXPECT_TRUE(contains(last_.out, ": 1205 blocks, 1205 executed, ")) << last_.out;
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

// ---- Errors from the board: block and Table 4 name

TEST_F(ApcictlRun, KorrErrorIsReportedWithBlockAndNameAndTheRunStops) {
    const std::string prog = write("korr.nc",
                                   "N10 F1000 D1\nN40 G41 G1 X0 Y0\nN50 X60\nN60 Y2\nN70 X0\n"
                                   "N100 G40 G1 X0 Y-20\nN110 M30\n");
    const json doc = run_json(prog, {"--tools", tools(5.0), "--svg", path("k.svg")}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("block"), 60);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "KorrError");
    // The board's own words and what to change; not the driver's call, status or tag.
    EXPECT_EQ(doc.at("errors")[0].at("message"),
              "element is too short for the corner: its offset would reverse (lengthen it, join it "
              "into its neighbour, or use a smaller tool)");
    EXPECT_EQ(doc.at("registers").at("1").at("ERROR_bits"), json::array({"KorrError"}));
    EXPECT_TRUE(contains(last_.out, "errors: 1 (KorrError 1)\n  line 4 (N60): KorrError: ")) << last_.out;
    EXPECT_TRUE(contains(last_.err, "apcictl: run " + prog + ": stopped at line 4 (N60): KorrError\n"))
        << last_.err;
    // The board holds: nothing spooled after the error ran.
    for (const auto& s : doc.at("segments")) EXPECT_LT(s.at("block").get<int>(), 70);
    const std::string svg = read_text(path("k.svg"));
    EXPECT_TRUE(contains(svg, ">N60 KorrError</text>"));
    // The rest of the program is still drawn, so the place of the error is seen.
    EXPECT_TRUE(contains(svg, "L0 20") || contains(svg, "L0 2"));
}

TEST_F(ApcictlRun, AnErrorInABlockWithoutNumberNamesItsLineNeverAnInternalTag) {
    // Blocks without N carry their line through the board's tag (2^31 + line): the message
    // names the line, and neither the tag nor the spool call's status.
    const std::string prog = write("korr_lines.nc",
                                   "F1000 D1\nG41 G1 X0 Y0\nX60\nY2\nX0\nG40 G1 X0 Y-20\nM30\n");
    const json doc = run_json(prog, {"--tools", tools(5.0)}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("line"), 4);
    EXPECT_TRUE(contains(last_.out, "\n  line 4: KorrError: element is too short for the corner"))
        << last_.out;
    EXPECT_TRUE(contains(last_.err, "stopped at line 4: KorrError")) << last_.err;
    for (const std::string& text : {last_.out, last_.err, doc.dump()}) {
        EXPECT_FALSE(contains(text, "2147483")) << text;
        EXPECT_FALSE(contains(text, "WrongDeviceState")) << text;
    }
}

TEST_F(ApcictlRun, CalcErrorForAConcaveArcSmallerThanTheTool) {
    const std::string prog = write("calc.nc",
                                   "N10 F1000 D1\nN40 G41 G1 X0 Y0\nN50 X20\nN60 G3 X24 Y4 I0 J4\n"
                                   "N70 G1 Y20\nN100 G40 G1 X40\nN110 M30\n");
    const json doc = run_json(prog, {"--tools", tools(5.0)}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("block"), 60);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "CalcError");
}

TEST_F(ApcictlRun, CompensationWithoutTheTcOptionIsAnErrorNamingIt) {
    const std::string prog = write("g41.nc", "N10 F1000\nN20 G1 X5\nN30 G41 X10\nM30\n");
    const json doc = run_json(prog, {"--device", "emu:?no-option-tc"}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("block"), 30);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "NoSuchDevice");
    EXPECT_TRUE(contains(doc.at("errors")[0].at("message").get<std::string>(), "optionTC"));
    EXPECT_EQ(doc.at("registers"), json::object());
}

TEST_F(ApcictlRun, ProgramWithoutCompensationRunsWithoutTheTcOption) {
    const std::string prog = write("plain.nc", "N10 G1 X5 F600\nN20 G2 X10 Y0 I2.5 J0\nM30\n");
    const json doc = run_json(prog, {"--device", "emu:?no-option-tc"});
    EXPECT_EQ(roles(doc), "uncompensated/10 uncompensated/20");
    EXPECT_EQ(doc.at("segments")[1].at("kind"), "arc");
    EXPECT_EQ(doc.at("segments")[1].at("ccw"), false);
}

// ---- Klartext programs: the 3D tool compensation (docs/3d-compensation.md; the board's module
// on bus 1310, docs/object-map.md section 6). The segment end points are the commanded tool
// tips (TCP); the expected ones come from rwmos_comp3d, and where [TNC-3D] says what the tool
// must do, that is checked directly.

using V3 = Eigen::Vector3d;

// The executed segment of block `block` (exactly one).
json segment_of_block(const json& doc, int block) {
    json found;
    int count = 0;
    for (const auto& s : doc.at("segments")) {
        if (s.at("block") != block) continue;
        found = s;
        ++count;
    }
    EXPECT_EQ(count, 1) << "block " << block << ": " << roles(doc);
    return found;
}

V3 end_of_block(const json& doc, int block) {
    const json s = segment_of_block(doc, block);
    if (s.is_null()) return V3::Zero();
    return point(s.at("end"));
}

V3 tcp(const V3& p, const V3& n, const V3& t, const c3::ToolDimensions& tool, const c3::Deltas& d,
       c3::ReferencePoint ref = c3::ReferencePoint::kTip) {
    c3::Settings s;
    s.tool = tool;
    s.deltas = d;
    s.reference = ref;
    const c3::Compensated c = c3::compensate(p, n, t, s);
    EXPECT_EQ(c.refusal, c3::Refusal::kNone);
    return c.tip;
}

void expect_point(const V3& got, const V3& want, double tol = 1e-9) {
    EXPECT_NEAR((got - want).norm(), 0.0, tol)
        << "got " << got.transpose() << ", want " << want.transpose();
}

// [TNC-3D], face milling, blocks 12 to 14, with the reground ball mill of the tool list.
TEST_F(ApcictlRun, SeedFaceMillingExampleRunsToTheCompensatedTips) {
    const json doc = run_json(kExamples + "/3d_face_milling.h",
                              {"--tools", kExamples + "/tools/3d_tools.tools"});
    EXPECT_EQ(doc.at("errors"), json::array());
    const V3 p(36.0084, 6.177, -1.9209);
    const V3 n = V3(-0.4658107, 0, 0.8848844).normalized();
    const V3 t = V3(0, 0.6558846, 0.7548612).normalized();
    const c3::Deltas reground{0.0, -0.1, -0.1};
    // 12: no TCPM, the machine's tool axis (the head at B = 0: +Z).
    expect_point(end_of_block(doc, 12), tcp(p, n, V3(0, 0, 1), {3, 3}, reground));
    // 13: T and M128: the programmed orientation.
    expect_point(end_of_block(doc, 13), tcp(p, n, t, {3, 3}, reground));
    // 14: M128 without T: perpendicular to the contour.
    expect_point(end_of_block(doc, 14), tcp(p, n, n, {3, 3}, reground));
    EXPECT_EQ(roles(doc),
              "uncompensated/2 uncompensated/3 uncompensated/11 contour/12 contour/13 contour/14 "
              "uncompensated/15");
    // The reground ball (R 2.9) at block 13's tip has its centre 2.9 off the surface point
    // that the 6 mm ball at the programmed tip touched.
    const V3 s = p + 3.0 * t - 3.0 * n;
    expect_point(end_of_block(doc, 13) + 2.9 * t, s + 2.9 * n);
}

// [TNC-3D], peripheral milling: 11 L with the head's C and B, M128 and RL; 12 LN with N and T;
// 13 LN with T only at 12's point (R0): the reground end mill (R 6, DR -0.1).
TEST_F(ApcictlRun, SeedPeripheralExampleRunsWithTheSideFromRlNAndTheLineBefore) {
    const json doc =
        run_json(kExamples + "/3d_peripheral.h", {"--tools", kExamples + "/tools/3d_tools.tools"});
    EXPECT_EQ(doc.at("errors"), json::array());
    const c3::Deltas reground{0.0, -0.1, 0.0};
    const V3 p11(48.4074, 102.4717, -7.1088);
    const V3 t11 = rwmos::geom::bc_head_tool_direction(-20.0115, -267.9784);
    const V3 n11 = t11.cross(V3(1, 0, 0)).normalized();  // RL: T x D, D along +X
    expect_point(end_of_block(doc, 11), tcp(p11, n11, t11, {6, 0}, reground));
    const V3 p12(60.6593, 102.4690, -7.1012);
    const V3 n12 = V3(0, 0.9397, 0.3420).normalized();
    const V3 t12 = V3(-0.0807, -0.3409, 0.9366).normalized();
    expect_point(end_of_block(doc, 12), tcp(p12, n12, t12, {6, 0}, reground));
    const V3 kept = (n12 - n12.dot(t12) * t12).normalized();
    expect_point(end_of_block(doc, 13), tcp(p12, kept, t12, {6, 0}, reground));
    // RL at block 11 and N at block 12 name the same side of the wall.
    EXPECT_GT(n11.dot(n12), 0.999);
}

// [TNC-3D], "Werkstückaufmaß erzeugen, CAM-Ausgabe Kugelmitte": the 6 mm ball with TOOL CALL
// DL DR DR2 +0.2, M107, REFPNT CNT-CNT stands 0.2 off the design surface along N.
TEST_F(ApcictlRun, SeedAllowanceExampleStandsOffTheSurfaceByTheAllowance) {
    const json doc =
        run_json(kExamples + "/3d_allowance.h", {"--tools", kExamples + "/tools/3d_tools.tools"});
    EXPECT_EQ(doc.at("errors"), json::array());
    const V3 n = V3(0.5, 0, 0.8660254).normalized();
    for (const int block : {5, 6, 7, 8}) {
        const json s = segment_of_block(doc, block);
        const V3 ball_centre_programmed(1.5,
                                        block == 5   ? 0.0
                                        : block == 8 ? 40.0
                                                     : 20.0,
                                        2.5980762);
        const V3 t = block <= 6 ? n : V3(0, 0, 1);
        const V3 got = point(s.at("end"));
        expect_point(got, tcp(ball_centre_programmed, n, t, {3, 3}, {0.2, 0.2, 0.2},
                              c3::ReferencePoint::kCentre));
        // The physical 3 mm ball, its tip at the TCP: centre 3.2 from the surface point.
        const V3 surface = ball_centre_programmed - 3.0 * n;
        expect_point(got + 3.0 * t, surface + 3.2 * n);
    }
}

// [TNC-3D]: the deltas are summed "aus der Werkzeugverwaltung, dem Werkzeugaufruf und den
// Korrekturtabellen". The face milling example with the tool as designed (tool 3) and the
// regrinding in correction table row 1 (FUNCTION CORRDATA TCS #1) reaches the tips of the
// reground tool 1 of the tool table; the example runs with the command its header documents.
TEST_F(ApcictlRun, CorrectionTableRowActsAsTheToolTablesDeltas) {
    const std::string program = kExamples + "/3d_correction_table.h";
    const json doc = run_json(program, {"--tools", kExamples + "/tools/3d_tools.tools", "--corr",
                                        kExamples + "/tools/3d_corrections.corr"});
    EXPECT_EQ(doc.at("errors"), json::array());
    const V3 p(36.0084, 6.177, -1.9209);
    const V3 n = V3(-0.4658107, 0, 0.8848844).normalized();
    const V3 t = V3(0, 0.6558846, 0.7548612).normalized();
    const c3::Deltas reground{0.0, -0.1, -0.1};
    expect_point(end_of_block(doc, 12), tcp(p, n, V3(0, 0, 1), {3, 3}, reground));
    expect_point(end_of_block(doc, 13), tcp(p, n, t, {3, 3}, reground));
    expect_point(end_of_block(doc, 14), tcp(p, n, n, {3, 3}, reground));
    const json table = run_json(kExamples + "/3d_face_milling.h",
                                {"--tools", kExamples + "/tools/3d_tools.tools"});
    for (const int block : {12, 13, 14})
        EXPECT_EQ(end_of_block(doc, block), end_of_block(table, block)) << block;
    // The header's command.
    const std::string text = read_text(program);
    const std::string marker = "; ./build/bin/apcictl ";
    const std::size_t at = text.find(marker);
    ASSERT_NE(at, std::string::npos);
    std::stringstream cmd(
        text.substr(at + marker.size(), text.find('\n', at) - at - marker.size()));
    std::vector<std::string> args;
    for (std::string word; cmd >> word;)
        args.push_back(word.rfind("examples/", 0) == 0 ? kSource + "/" + word : word);
    EXPECT_EQ(apcictl(args).exit_code, 0);
}

// A row selected in the middle of the program acts from its block on; RESET TCS leaves it.
TEST_F(ApcictlRun, CorrectionRowActsFromItsBlockUntilReset) {
    const std::string prog = write(
        "corr.h",
        "0 BEGIN PGM C MM\n1 TOOL CALL 3 Z\n2 L X+0 Y+0 Z+50 R0 F1000\n"
        "3 LN X+10 Y+0 Z+0 NX+0.6 NY+0 NZ+0.8 TX+0 TY+0 TZ+1 R0 M128\n"
        "4 FUNCTION CORRDATA TCS #1\n"
        "5 LN X+20 Y+0 Z+0 NX+0.6 NY+0 NZ+0.8 TX+0 TY+0 TZ+1\n"
        "6 FUNCTION CORRDATA RESET TCS\n"
        "7 LN X+30 Y+0 Z+0 NX+0.6 NY+0 NZ+0.8 TX+0 TY+0 TZ+1\n"
        "8 L Z+50 FMAX M129\n9 END PGM C MM\n");
    const json doc = run_json(prog, {"--tools", kExamples + "/tools/3d_tools.tools", "--corr",
                                     kExamples + "/tools/3d_corrections.corr"});
    EXPECT_EQ(doc.at("errors"), json::array());
    const V3 n(0.6, 0, 0.8);
    const V3 t(0, 0, 1);
    const c3::Deltas none{0.0, 0.0, 0.0};
    const c3::Deltas row1{0.0, -0.1, -0.1};
    expect_point(end_of_block(doc, 3), tcp(V3(10, 0, 0), n, t, {3, 3}, none));
    expect_point(end_of_block(doc, 5), tcp(V3(20, 0, 0), n, t, {3, 3}, row1));
    expect_point(end_of_block(doc, 7), tcp(V3(30, 0, 0), n, t, {3, 3}, none));
    // Row 1 moves the tip (the reground ball is 0.1 smaller), so the comparison means something.
    EXPECT_GT((tcp(V3(20, 0, 0), n, t, {3, 3}, row1) - V3(20, 0, 0)).norm(), 0.01);
}

TEST_F(ApcictlRun, CorrectionRowWithoutATableSaysThatNoneWasGiven) {
    const std::string prog =
        write("c.h", "0 BEGIN PGM C MM\n1 FUNCTION CORRDATA TCS #1\n2 END PGM C MM\n");
    const auto r = apcictl({"run", prog, "--json", path("c.json")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err,
                         ":2:26: FUNCTION CORRDATA TCS #1: the correction table does not define "
                         "row 1 (no --corr file given)"))
        << r.err;
    EXPECT_FALSE(exists(path("c.json")));
}

TEST_F(ApcictlRun, CorrectionRowWithAPositiveOversizeNeedsM107BeforeAnythingRuns) {
    const std::string prog = write(
        "c.h", "0 BEGIN PGM C MM\n1 TOOL CALL 3 Z\n2 FUNCTION CORRDATA TCS #2\n3 END PGM C MM\n");
    const auto r = apcictl({"run", prog, "--tools", kExamples + "/tools/3d_tools.tools", "--corr",
                            kExamples + "/tools/3d_corrections.corr", "--json", path("c.json")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, ":3:3: FUNCTION CORRDATA TCS #2 (tool 3) with a positive oversize"))
        << r.err;
    EXPECT_FALSE(exists(path("c.json")));
}

TEST_F(ApcictlRun, BadCorrectionTableNamesFileAndLine) {
    const std::string t = write("bad.corr", "corr[1].dr -0.1\ncorr[1].dx 1\n");
    const auto r = apcictl({"run", kExamples + "/3d_face_milling.h", "--corr", t});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, t + ":2:9: unknown correction field 'dx' (known: dl, dr, dr2)"))
        << r.err;
}

TEST_F(ApcictlRun, LnWhileTheRadiusCompensationRunsIsRefusedByTheBoardByName) {
    const std::string prog = write("mixed.h",
                                   "0 BEGIN PGM MIXED MM\n1 L X+0 Y+0 Z+0 R0 F500\n2 L X+10 RL\n"
                                   "3 LN X+20 Y+0 Z+0 NX+0 NY+1 NZ+0\n4 END PGM MIXED MM\n");
    const json doc = run_json(prog, {}, 1);
    ASSERT_EQ(doc.at("errors").size(), 1u);
    EXPECT_EQ(doc.at("errors")[0].at("block"), 3);
    EXPECT_EQ(doc.at("errors")[0].at("code"), "RadiusCompensationRunning");
}

TEST_F(ApcictlRun, KlartextOversizeWithoutM107IsRefusedBeforeAnythingRuns) {
    const std::string prog = write(
        "over.h", "0 BEGIN PGM O MM\n1 TOOL CALL 3 Z DL+0.2 DR+0.2 DR2+0.2\n2 END PGM O MM\n");
    const auto r = apcictl(
        {"run", prog, "--tools", kExamples + "/tools/3d_tools.tools", "--json", path("o.json")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, ":2:3: TOOL CALL 3 with a positive oversize")) << r.err;
    EXPECT_TRUE(contains(r.err, "program M107 before the TOOL CALL")) << r.err;
    EXPECT_FALSE(exists(path("o.json")));
}

// ---- Program errors: nothing runs

TEST_F(ApcictlRun, ParseErrorNamesFileLineAndColumnAndRunsNothing) {
    const std::string prog = write("bad.nc", "N10 G1 X1 F100\nN20 G1 X\nM30\n");
    const auto r = apcictl({"run", prog, "--json", path("bad.json"), "--svg", path("bad.svg")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "apcictl: " + prog + ":2:9: N20: expected a number after 'X'\n");
    EXPECT_FALSE(exists(path("bad.json")));
    EXPECT_FALSE(exists(path("bad.svg")));
}

TEST_F(ApcictlRun, ToolNotInTheToolListSaysThatNoneWasGiven) {
    const std::string prog = write("d1.nc", "N10 D1\nM30\n");
    const auto r = apcictl({"run", prog});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err,
                         ":1:5: N10: D1 selects tool 1, which the tool list does not define "
                         "(no --tools file given)"))
        << r.err;
}

TEST_F(ApcictlRun, BadToolListNamesFileAndLine) {
    const std::string t = write("bad.tools", "wz[1].radius 5\nwz[1].typ 9\n");
    const auto r = apcictl({"run", kExamples + "/wr_quad_disc.nc", "--tools", t});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "bad.tools:2:")) << r.err;
}

// ---- Exit codes and usage

TEST_F(ApcictlRun, UsageErrorsExitTwo) {
    EXPECT_EQ(apcictl({"run"}).exit_code, 2);
    EXPECT_EQ(apcictl({"run", "x.nc", "--bogus"}).exit_code, 2);
    // --avoid-bottlenecks: 0 (off) or 2..64 moves back.
    const std::string wr = kExamples + "/wr_quad_disc.nc", wr_tools = kExamples + "/tools/wr_quad_disc.tools";
    for (const char* bad : {"1", "65", "-1", "x"})
        EXPECT_EQ(apcictl({"run", wr, "--tools", wr_tools, "--avoid-bottlenecks", bad}).exit_code, 2)
            << bad;
    for (const char* good : {"0", "2", "64"})
        EXPECT_EQ(apcictl({"run", wr, "--tools", wr_tools, "--avoid-bottlenecks", good}).exit_code, 0)
            << good;
    const auto missing = apcictl({"run", path("missing.nc")});
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_TRUE(contains(missing.err, "missing.nc: cannot open")) << missing.err;
    const auto unwritable =
        apcictl({"run", kExamples + "/wr_quad_disc.nc", "--tools",
                 kExamples + "/tools/wr_quad_disc.tools", "--json", path("no/such/dir.json")});
    EXPECT_EQ(unwritable.exit_code, 2);
    EXPECT_EQ(unwritable.out, "");  // nothing ran
    EXPECT_TRUE(contains(unwritable.err, "cannot write " + path("no/such/dir.json")))
        << unwritable.err;
}

TEST_F(ApcictlRun, HelpNamesTheOptions) {
    const auto r = apcictl({"run", "--help"});
    EXPECT_EQ(r.exit_code, 0);
    for (const char* opt : {"--tools", "--svg", "--json", "--csv"})
        EXPECT_TRUE(contains(r.out, opt)) << opt;
}

TEST_F(ApcictlRun, ProgramFromStandardInput) {
    const auto r = apcictl({"run", "-", "--json", path("in.json")}, "N10 G1 X3 Y4 F600\nM30\n");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "<stdin>: 2 blocks, 2 executed, 1 segments\npath 5.000 mm"))
        << r.out;
    const auto bad = apcictl({"run", "-"}, "N10 G1 X\n");
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_TRUE(contains(bad.err, "<stdin>:1:9: N10: expected a number after 'X'")) << bad.err;
}

// Runs apcictl with standard error on a pseudo-terminal; returns what it wrote there.
std::string stderr_on_a_terminal(const std::vector<std::string>& args, int& exit_code) {
    int master = -1;
    const pid_t pid = ::forkpty(&master, nullptr, nullptr, nullptr);
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 1);  // only standard error stays on the terminal
        std::vector<char*> argv{const_cast<char*>(APCICTL_PATH)};
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    std::string text;
    char buf[4096];
    for (;;) {
        const ssize_t n = ::read(master, buf, sizeof buf);
        if (n <= 0) break;  // EIO once the child closed the terminal
        text.append(buf, static_cast<std::size_t>(n));
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    ::close(master);
    exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return text;
}

TEST_F(ApcictlRun, ProgressBarOnlyOnATerminalAndClearedAtTheEnd) {
    std::string text = "N1 G1 F60000\n";
    for (int i = 0; i < 10000; ++i) text += (i % 2 == 0 ? "X1\n" : "X0\n");
    text += "M30\n";
    const std::string prog = write("long.nc", text);
    int exit_code = -1;
    const std::string terminal = stderr_on_a_terminal({"run", prog}, exit_code);
    EXPECT_EQ(exit_code, 0) << terminal;
    EXPECT_TRUE(contains(terminal, "\r[")) << terminal;
    EXPECT_TRUE(contains(terminal, " of 10002 blocks")) << terminal;
    EXPECT_TRUE(terminal.size() >= 4 && terminal.substr(terminal.size() - 4) == "\r\x1b[K")
        << terminal;
    const auto piped = apcictl({"run", prog});  // standard error is a pipe here
    EXPECT_EQ(piped.exit_code, 0);
    EXPECT_EQ(piped.err, "");
}

TEST_F(ApcictlRun, BlocksWithoutNumberCarryTheirLine) {
    const std::string prog = write("nonum.nc", "F600\n\nG1 X1\nN7 X2\nM30\n");
    const json doc = run_json(prog);
    ASSERT_EQ(doc.at("segments").size(), 2u);
    EXPECT_EQ(doc.at("segments")[0].at("block"), -1);
    EXPECT_EQ(doc.at("segments")[0].at("line"), 3);
    EXPECT_EQ(doc.at("segments")[1].at("block"), 7);
    EXPECT_FALSE(doc.at("segments")[1].contains("line"));
}

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
    // "previous element is too short".
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
                  "sees; the path cuts %.4f mm into it",
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

// ---- Approach and departure as the controls make them (G139, the NC programs' initial state)

// A segment's plane end point, for the points the issue's reproductions name.
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
    EXPECT_TRUE(contains(last_.out, ": 1003 blocks, 1003 executed, 1001 segments")) << last_.out;
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

// An output that names an input or another output is refused before anything runs (hardening
// issue, item 6): `--json p.nc` overwrote the program, `--json X --csv X` mixed both outputs, and
// both exited 0. The same file is found through `..`, symlinks and hard links.
TEST_F(ApcictlRun, AnOutputThatIsAnInputOrAnotherOutputIsRefusedBeforeAnythingRuns) {
    const std::string program_text = "N10 G1 X3 Y4 F600\nM30\n";
    const std::string prog = write("p.nc", program_text);
    const std::string tools_file = tools(1.0);
    const std::string plc = write("s.plc", "");
    const std::string corr = write("c.corr", "");
    ASSERT_EQ(::symlink(prog.c_str(), path("link.nc").c_str()), 0);
    ASSERT_EQ(::link(tools_file.c_str(), path("hard.tools").c_str()), 0);
    const std::string dotted = dir_ + "/../" + std::filesystem::path(dir_).filename().string();
    struct Case {
        std::vector<std::string> args;
        std::string says;
    };
    const std::vector<Case> cases{
        {{"--json", prog}, "--json '" + prog + "' is the same file as PROGRAM '" + prog + "'"},
        {{"--svg", dotted + "/p.nc"}, "--svg '" + dotted + "/p.nc' is the same file as PROGRAM"},
        {{"--csv", path("link.nc")}, "--csv '" + path("link.nc") + "' is the same file as PROGRAM"},
        {{"--tools", tools_file, "--json", tools_file},
         "--json '" + tools_file + "' is the same file as --tools"},
        {{"--tools", tools_file, "--tools-out", path("hard.tools")},
         "--tools-out '" + path("hard.tools") + "' is the same file as --tools"},
        {{"--plc", plc, "--csv", plc}, "--csv '" + plc + "' is the same file as --plc"},
        {{"--corr", corr, "--svg", corr}, "--svg '" + corr + "' is the same file as --corr"},
        {{"--json", path("x"), "--csv", path("x")},
         "--csv '" + path("x") + "' is the same file as --json '" + path("x") + "'"},
        {{"--svg", path("y"), "--tools-out", path("y")},
         "--tools-out '" + path("y") + "' is the same file as --svg"},
    };
    for (const auto& c : cases) {
        std::vector<std::string> args{"run", prog};
        args.insert(args.end(), c.args.begin(), c.args.end());
        const auto r = apcictl(args);
        EXPECT_EQ(r.exit_code, 2) << c.says;
        EXPECT_EQ(r.out, "") << c.says;
        EXPECT_TRUE(contains(r.err, c.says)) << r.err;
    }
    // Nothing ran and nothing was written: the inputs are as they were, no output was made.
    EXPECT_EQ(read_text(prog), program_text);
    EXPECT_TRUE(contains(read_text(tools_file), "wz[1].radius 1.0")) << read_text(tools_file);
    EXPECT_FALSE(exists(path("x")));
    EXPECT_FALSE(exists(path("y")));
    // A program from standard input has no file to clash with; distinct outputs still run.
    const auto ok =
        apcictl({"run", "-", "--json", path("a.json"), "--csv", path("a.csv")}, program_text);
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

// ---- One pass on the embedded emulator, the validation first elsewhere

// A program of `moves` G1 blocks that are valid, then `last` (its last line or lines).
std::string moves_then(int moves, const std::string& last) {
    std::string text = "N1 G17 G90 F3000\nN2 G0 X0 Y0 Z0\n";
    for (int i = 0; i < moves; ++i)
        text += "N" + std::to_string(i + 3) + (i % 2 == 0 ? " G1 X1\n" : " G1 Y1\n");
    return text + last;
}

// The names in the test's directory (temporary files of the outputs would show here).
std::set<std::string> names_in(const std::string& dir) {
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        names.insert(e.path().filename().string());
    return names;
}

// The embedded emulator validates while it runs: the moves before the error went to its board,
// but nothing of them is published, and the error is the one the validation pass gave.
TEST_F(ApcictlRun, AnInvalidProgramOnTheEmbeddedBoardPublishesNothingAndNamesItsLine) {
    const std::string prog = write("late.nc", moves_then(6000, "N6010 G1 X\nM30\n"));
    const auto before = names_in(dir_);
    const auto r = apcictl({"run", prog, "--json", path("o.json"), "--svg", path("o.svg"), "--csv",
                            path("o.csv"), "--tools-out", path("o.tools")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "apcictl: " + prog + ":6003:11: N6010: expected a number after 'X'\n");
    EXPECT_EQ(names_in(dir_), before);  // no output, no temporary file left behind

    // A rule of the program, with what was not given, as before.
    const std::string d1 = write("d1late.nc", moves_then(5000, "N6000 G40 D1\nM30\n"));
    const auto t = apcictl({"run", d1, "--json", path("d.json")});
    EXPECT_EQ(t.exit_code, 1);
    EXPECT_EQ(t.out, "");
    EXPECT_EQ(t.err, "apcictl: " + d1 +
                         ":5003:11: N6000: D1 selects tool 1, which the tool list does not define "
                         "(no --tools file given)\n");
    EXPECT_FALSE(exists(path("d.json")));
    // From standard input too.
    const auto in =
        apcictl({"run", "-", "--json", path("i.json")}, moves_then(5000, "N6000 G1 X\nM30\n"));
    EXPECT_EQ(in.exit_code, 1);
    EXPECT_EQ(in.err, "apcictl: <stdin>:5003:11: N6000: expected a number after 'X'\n");
    EXPECT_FALSE(exists(path("i.json")));
}

// The last line is read after M30 has run on the board: an error there still publishes nothing
// and leaves every existing target as it was.
TEST_F(ApcictlRun, AnErrorAtTheLastLineLeavesTheExistingOutputsUntouched) {
    const std::string prog = write("after.nc", moves_then(5000, "N5003 M30\nN5004 G1 X2\n"));
    const std::vector<std::string> outputs{"o.json", "o.svg", "o.csv", "o.tools"};
    for (const auto& o : outputs) write(o, "old " + o + "\n");
    const auto before = names_in(dir_);
    const auto r = apcictl({"run", prog, "--json", path("o.json"), "--svg", path("o.svg"), "--csv",
                            path("o.csv"), "--tools-out", path("o.tools")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "apcictl: " + prog +
                         ":5004:1: N5004: block after M30: the program has already ended\n");
    for (const auto& o : outputs) EXPECT_EQ(read_text(path(o)), "old " + o + "\n") << o;
    EXPECT_EQ(names_in(dir_), before);
}

// A daemon stands for a board others see (and a real one): there the program is validated
// before anything moves, so its board sees no profile of an invalid program.
TEST_F(ApcictlRun, ADaemonsBoardSeesNoMoveOfAnInvalidProgram) {
    const std::string socket = path("emu.sock");
    const pid_t daemon = start_daemon(socket);
    ASSERT_GT(daemon, 0);
    ASSERT_TRUE(exists(socket));
    const std::string bad = write("bad.nc", moves_then(3000, "N3003 G1 X7\nN3004 G1 X\nM30\n"));
    const std::string good = write("good.nc", "N1 G1 Y1 F1000\nM30\n");
    const std::string device = "unix:" + socket;
    const auto r = apcictl({"--device", device, "run", bad, "--json", path("bad.json")});
    const auto after = apcictl({"--device", device, "run", good, "--json", path("socket.json")});
    ::kill(daemon, SIGTERM);
    ::waitpid(daemon, nullptr, 0);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    // The same words as on the embedded board.
    EXPECT_EQ(r.err, apcictl({"run", bad}).err);
    EXPECT_EQ(r.err, "apcictl: " + bad + ":3004:11: N3004: expected a number after 'X'\n");
    EXPECT_FALSE(exists(path("bad.json")));
    // The next program starts where a fresh board stands: nothing of the invalid one moved it.
    ASSERT_EQ(after.exit_code, 0) << after.err;
    ASSERT_EQ(apcictl({"run", good, "--json", path("emu.json")}).exit_code, 0);
    EXPECT_EQ(read_text(path("socket.json")), read_text(path("emu.json")));
}

// One pass reads the program once, so a program from a pipe (a FIFO, `<(generator)`) runs on
// the embedded board: the same run as from a file.
TEST_F(ApcictlRun, AProgramFromAPipeRunsOnTheEmbeddedBoard) {
    const std::string text = moves_then(5000, "N5003 M30\n");
    const std::string file = write("file.nc", text);
    ASSERT_EQ(apcictl({"run", file, "--json", path("file.json")}).exit_code, 0);
    const std::string fifo = path("pipe.nc");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] {
        // Waits (bounded) for apcictl to open the pipe, then writes the program once.
        int fd = -1;
        for (int i = 0; i < 3000 && fd < 0; ++i) {
            fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
            if (fd < 0) ::usleep(10'000);
        }
        if (fd < 0) return;
        ::fcntl(fd, F_SETFL, 0);
        std::size_t done = 0;
        while (done < text.size()) {
            const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
            if (n <= 0) break;
            done += static_cast<std::size_t>(n);
        }
        ::close(fd);
    });
    // Bounded: a pass that opened the pipe a second time would wait for a writer for ever.
    const auto r = test_support::run_process(
        {"/usr/bin/timeout", "60", APCICTL_PATH, "run", fifo, "--json", path("pipe.json")});
    writer.join();
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, fifo + ": 5003 blocks, 5003 executed")) << r.out;
    EXPECT_EQ(read_text(path("pipe.json")), read_text(path("file.json")));
}

}  // namespace
