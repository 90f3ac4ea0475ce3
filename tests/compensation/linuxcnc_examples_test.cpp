// SPDX-License-Identifier: MIT
// LinuxCNC's own example programs with cutter radius compensation (comp-g1.ngc, mmount.ngc,
// gmoccapy_2_tools_with_cutter_radius_compensation.ngc, and ngcgui's subroutines qpocket.ngc
// as qpex.ngc calls it and helix.ngc's inside cut, shipped with its package), rewritten in our
// dialect in examples/linuxcnc/, run both ways: the original by LinuxCNC's interpreter rs274
// (ngcgui's subroutines as ngcgui runs them: its preamble, the call, m2, with the subroutine
// path of its sample configurations), ours on the embedded emulator through the executor of
// `apcictl run`. The compensated tool-centre paths are compared in the plane, in mm
// (docs/linuxcnc-examples.md):
//
// - every compensated stretch (G41 .. G40) of the one has its counterpart in the other, and
//   our run has no errors and no warnings (every one is a correct program);
// - along the contour proper of each stretch (the elements after LinuxCNC's entry move, up to
//   the last compensated one: from the start of the first one's offset, or its middle where
//   the entry trims it, to the end of the last one's, or its middle) the two paths agree
//   within 1e-3 mm (Hausdorff distance), and neither comes closer to the programmed contour
//   than r - 2.5e-4 mm (where a program cuts into its own contour by design, against the
//   part that stays: see "Clearance" below);
// - the entry and exit moves (approach and departure: under G139, the NC programs' initial
//   selection method, the G41 block's move and the move after G40) agree within 1e-3 mm too,
//   and ours reaches the point where LinuxCNC's first move after G40 ends; the move that leaves
//   the contour is printed with its third axis;
// - enough was compared: every stretch, and a stated length of contour per example.
//
// rs274 prints 4 decimals in the program's unit: 0.0025 mm in inches, more than the 1e-3 mm
// the comparison needs. The inch programs are therefore also run in mm: comp-g1 and mmount
// converted (G21, every length times 25.4, made here from the original's text); qpocket and
// helix, whose subroutines read the tool's diameter from the tool table in the machine's unit
// (#5410, inches in standalone rs274), from our rewrite translated back into RS274/NGC (G21).
// The mm run must agree with the original's move for move within the printed rounding, and the
// comparison uses it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "apci/apci.hpp"
#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "apci/run/executor.h"
#include "apci/run/path.h"
#include "diff_support.h"
#include "linuxcnc.h"
#include "rwmos/geometry/shared.h"
#include "sha256.h"
#include "text.h"

namespace apci::test {
namespace {

using test_support::read_text;
using rwmos::geom::closest_point;
using rwmos::geom::distance_to;
using rwmos::geom::is_arc;
using rwmos::geom::left_normal;
using rwmos::geom::length;
using rwmos::geom::make_arc;
using rwmos::geom::make_line;
using rwmos::geom::point_at;
using rwmos::geom::sweep;
using rwmos::geom::tangent_at;

constexpr double kInch = 25.4;
// The agreement along the contour proper, and how much closer than r a path may come.
constexpr double kMaxDeviation = 1e-3;
constexpr double kClearanceTolerance = 2.5e-4;
// A window point is found on rs274's path within this (4 printed decimals), on ours within 1e-6.
constexpr double kLinuxCncWindowTolerance = 2e-4;
constexpr double kOurWindowTolerance = 1e-6;
// Samples along the paths for the Hausdorff distance and the clearance (and at every end).
constexpr double kSpacing = 0.02;
// One coordinate printed by rs274 in inches (4 decimals) and one in mm (4 decimals): how far
// the original's move and the converted one's may lie apart, per coordinate, in mm.
constexpr double kPrintedRounding = 0.5e-4 * kInch + 0.5e-4 + 1e-9;
// How far a point rs274 prints in mm (4 decimals) may lie from its own.
constexpr double kPrintedPoint = 0.5e-4 * 1.4142135623730951;

const char* kSourceDir = APCI_SOURCE_DIR;

const Rs274& rs274() {
    return test_rs274();
}

// ---- The inch programs in mm

std::string scaled(const std::string& literal) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.10f", std::strtod(literal.c_str(), nullptr) * kInch);
    std::string s = buf;
    s.erase(s.find_last_not_of('0') + 1);
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s == "-0" ? "0" : s;
}

// An RS274/NGC program in inches (G20) rewritten in mm (G21), for the two originals here
// (comp-g1.ngc, mmount.ngc): G20 becomes G21 and every number that is a length is multiplied
// by 25.4 - the values of X Y Z I J K R Q and F words, of parameter assignments (#100=10.0,
// the feeds), and inside [..] expressions every number that is neither multiplied nor divided
// by (o100's arguments, its "#5-.020"; not the "/ 2" or "/4"). Parameter numbers, G M T D S
// words and comments stay. Nothing else of RS274/NGC is needed by these programs; the test
// checks that the converted program makes the original's moves, within rs274's rounding.
std::string inch_to_mm(const std::string& ngc) {
    std::string out;
    std::istringstream lines(ngc);
    std::string line;
    const auto prev_non_space = [](const std::string& s, std::size_t i) -> char {
        while (i > 0 && std::isspace(static_cast<unsigned char>(s[i - 1]))) --i;
        return i > 0 ? s[i - 1] : '\0';
    };
    while (std::getline(lines, line)) {
        std::string code;
        int depth = 0;
        std::size_t i = 0;
        while (i < line.size()) {
            const char c = line[i];
            if (c == '(') {  // a comment to its ')'
                const std::size_t end = line.find(')', i);
                const std::size_t stop = end == std::string::npos ? line.size() : end + 1;
                code += line.substr(i, stop - i);
                i = stop;
                continue;
            }
            if (c == ';') {
                code += line.substr(i);
                break;
            }
            if (c == '[') ++depth;
            if (c == ']') --depth;
            const bool starts_number = std::isdigit(static_cast<unsigned char>(c)) ||
                                       (c == '.' && i + 1 < line.size() &&
                                        std::isdigit(static_cast<unsigned char>(line[i + 1])));
            if (!starts_number) {
                code += c;
                ++i;
                continue;
            }
            std::size_t end = i;
            while (end < line.size() &&
                   (std::isdigit(static_cast<unsigned char>(line[end])) || line[end] == '.'))
                ++end;
            const std::string literal = line.substr(i, end - i);
            // What the number belongs to: the character before it, a sign skipped (X-.5, [-1],
            // [#5-.020]: the magnitude is what is scaled).
            std::size_t at = i;
            char before = prev_non_space(line, at);
            if (before == '-' || before == '+') {
                while (at > 0 && line[at - 1] != before) --at;
                before = prev_non_space(line, at - 1);
            }
            std::size_t next = end;
            while (next < line.size() && std::isspace(static_cast<unsigned char>(line[next])))
                ++next;
            const char after = next < line.size() ? line[next] : '\0';
            const char word = static_cast<char>(std::toupper(static_cast<unsigned char>(before)));
            bool length_value = false;
            if (before == '#') {
                length_value = false;  // a parameter's number
            } else if (depth > 0) {
                length_value = before != '*' && before != '/' && after != '*' && after != '/';
            } else if (before == '=') {
                length_value = true;
            } else if (std::string("XYZIJKRQF").find(word) != std::string::npos && word != '\0') {
                length_value = true;
            }
            if (word == 'G' && literal == "20")
                code += "21";
            else
                code += length_value ? scaled(literal) : literal;
            i = end;
        }
        out += code + "\n";
    }
    return out;
}

// Our rewrite (DIN 66025, mm) as an RS274/NGC program in mm, for rs274: G21 first, the
// comments and the %name line dropped, G25/G26 dropped (LinuxCNC has no such words: its
// outside corners are arcs, as G26 makes ours), `D n` is `T n M6` (rs274's tool n), M30 is M2.
// Everything else our rewrites of ngcgui's subroutines write (G0 G1 G2 G3 G17 G40 G41 G42 G90,
// X Y Z I J F) means the same in both. The test checks the result against the original.
std::string rewrite_to_ngc(const std::string& din) {
    std::string out = "G21\n";
    std::istringstream lines(din);
    std::string line;
    bool first = true;
    while (std::getline(lines, line)) {
        std::string code;
        for (std::size_t i = 0; i < line.size();) {
            if (line[i] == ';') break;
            if (line[i] == '(') {
                const std::size_t end = line.find(')', i);
                i = end == std::string::npos ? line.size() : end + 1;
                continue;
            }
            code += line[i++];
        }
        std::istringstream words(code);
        std::string word, ngc;
        while (words >> word) {
            if (first && word[0] == '%') break;
            const char a = static_cast<char>(std::toupper(static_cast<unsigned char>(word[0])));
            if (a == 'G' && (word.substr(1) == "25" || word.substr(1) == "26")) continue;
            if (a == 'D')
                word = "T" + word.substr(1) + " M6";
            else if (a == 'M' && word.substr(1) == "30")
                word = "M2";
            ngc += (ngc.empty() ? "" : " ") + word;
        }
        if (!code.empty() && code.find_first_not_of(" \t") != std::string::npos) first = false;
        if (!ngc.empty()) out += ngc + "\n";
    }
    return out;
}

// A subroutine file as standalone rs274 can run it: its user M code M110 (a program of the
// configuration's that clears AXIS' notifications: no motion; standalone rs274 has no user M
// codes and refuses them) made a comment. Counts the lines it changed.
std::string without_m110(const std::string& ngc, int& changed) {
    std::string out;
    std::istringstream lines(ngc);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.rfind("M110", 0) == 0) {
            line = "(M110)" + line.substr(4);
            ++changed;
        }
        out += line + "\n";
    }
    return out;
}

// ---- Our side

struct Seg {
    Element path;
    double z0 = 0.0, z1 = 0.0;  // the third axis (Z) at its start and end
    bool rapid = false;
    int role = static_cast<int>(apci::run::Role::kUncompensated);
    std::uint64_t line = 0;
};

Seg to_seg(const apci::run::PathSegment& s) {
    Seg g;
    const Vec2 a(s.start.x(), s.start.y()), b(s.end.x(), s.end.y());
    g.path = s.kind == apci::run::SegmentKind::kArc
                 ? make_arc(a, b, {s.center.x(), s.center.y()}, s.ccw)
                 : make_line(a, b);
    g.z0 = s.start.z();
    g.z1 = s.end.z();
    g.rapid = s.kind == apci::run::SegmentKind::kRapid;
    g.role = static_cast<int>(s.role);
    g.line = s.block.line;
    return g;
}

class Sink final : public apci::run::RunSink {
  public:
    void programmed(const apci::run::PathSegment& s) override {
        programmed_.push_back(to_seg(s));
        planes_ok_ &= s.kind != apci::run::SegmentKind::kArc || s.plane == 17;
    }
    void executed(const apci::run::PathSegment& s) override { executed_.push_back(to_seg(s)); }
    std::vector<Seg> programmed_, executed_;
    bool planes_ok_ = true;
};

struct OurExampleRun {
    std::string error;  // the tool list, program or board could not be had
    std::vector<apci::run::RunError> errors, warnings;
    std::vector<Seg> programmed, executed;
    bool planes_ok = true;
};

// The example as `apcictl run FILE --tools TOOLS` runs it (the embedded emulator).
OurExampleRun run_example(const std::string& program_path, const std::string& tools_path) {
    OurExampleRun out;
    auto tools = apci::nc::load_tool_table(tools_path);
    if (!tools) {
        out.error = "tool list: " + tools.error().to_string();
        return out;
    }
    const std::string text = read_text(program_path);
    if (text.empty()) {
        out.error = "cannot read " + program_path;
        return out;
    }
    Sink sink;
    const EmulatorRun run = run_on_emulator(text, program_path, tools.value(), sink);
    if (!run.error.empty()) {
        out.error = run.error;
        return out;
    }
    out.errors = run.outcome.errors;
    out.warnings = run.outcome.warnings;
    out.programmed = std::move(sink.programmed_);
    out.executed = std::move(sink.executed_);
    out.planes_ok = sink.planes_ok_;
    return out;
}

// ---- Paths

std::string point_text(const Vec2& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6f, %.6f)", p.x(), p.y());
    return buf;
}

std::string element_text(const Element& e) {
    if (!is_arc(e)) return "line " + point_text(e.start) + " -> " + point_text(e.end);
    return std::string(e.ccw ? "G3 " : "G2 ") + point_text(e.start) + " -> " + point_text(e.end) +
           " centre " + point_text(e.centre);
}

double path_length(const std::vector<Element>& path) {
    double s = 0.0;
    for (const Element& e : path) s += length(e);
    return s;
}

// The point r to the left (G41) or right (G42) of e at fraction t: where the compensated
// path of e lies.
Vec2 offset_at(const Element& e, double t, double r, bool left) {
    const Vec2 n = left_normal(tangent_at(e, t));
    return point_at(e, t) + (left ? r : -r) * n;
}

// e from its start to the point q on it, and from q to its end (q found by closest_point).
std::vector<Element> head_of(const Element& e, const Vec2& q) {
    if ((q - e.start).norm() <= 1e-9) return {};
    return {is_arc(e) ? make_arc(e.start, q, e.centre, e.ccw) : make_line(e.start, q)};
}
std::vector<Element> tail_of(const Element& e, const Vec2& q) {
    if ((e.end - q).norm() <= 1e-9) return {};
    return {is_arc(e) ? make_arc(q, e.end, e.centre, e.ccw) : make_line(q, e.end)};
}

// The first and the last element of the path within tol of p; npos when none is.
constexpr std::size_t kNone = static_cast<std::size_t>(-1);
std::size_t first_near(const std::vector<Element>& path, const Vec2& p, double tol) {
    for (std::size_t i = 0; i < path.size(); ++i)
        if (length(path[i]) > 0 && distance_to(path[i], p) <= tol) return i;
    return kNone;
}
std::size_t last_near(const std::vector<Element>& path, const Vec2& p, double tol) {
    for (std::size_t i = path.size(); i-- > 0;)
        if (length(path[i]) > 0 && distance_to(path[i], p) <= tol) return i;
    return kNone;
}

// The path up to the first point within tol of p; empty when p is not on it.
std::vector<Element> up_to_first(const std::vector<Element>& path, const Vec2& p, double tol) {
    std::vector<Element> out;
    for (const Element& e : path) {
        if (length(e) > 0 && distance_to(e, p) <= tol) {
            for (const Element& h : head_of(e, closest_point(e, p))) out.push_back(h);
            return out;
        }
        out.push_back(e);
    }
    return {};
}
// The path from the last point within tol of p; empty when p is not on it.
std::vector<Element> from_last(const std::vector<Element>& path, const Vec2& p, double tol) {
    for (std::size_t i = path.size(); i-- > 0;) {
        if (length(path[i]) > 0 && distance_to(path[i], p) <= tol) {
            std::vector<Element> out = tail_of(path[i], closest_point(path[i], p));
            out.insert(out.end(), path.begin() + static_cast<std::ptrdiff_t>(i) + 1, path.end());
            return out;
        }
    }
    return {};
}

// Where path a lies farthest from path b: the distance, the element of a and the point.
struct Worst {
    double distance = 0.0;
    std::size_t element = 0;
    Vec2 at = Vec2::Zero();
};
Worst farthest(const std::vector<Element>& a, const std::vector<Element>& b) {
    Worst w;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const int n = std::max(1, static_cast<int>(std::ceil(length(a[i]) / kSpacing)));
        for (int k = 0; k <= n; ++k) {
            const Vec2 q = point_at(a[i], double(k) / n);
            double d = INFINITY;
            for (const Element& e : b) d = std::min(d, distance_to(e, q));
            if (d > w.distance) w = {d, i, q};
        }
    }
    return w;
}

// Where path comes nearest the walls: the distance, the element of the path, the point, and
// the wall.
struct Nearest {
    double distance = INFINITY;
    std::size_t element = 0, wall = 0;
    Vec2 at = Vec2::Zero();
};
Nearest nearest(const std::vector<Element>& path, const std::vector<Element>& walls) {
    Nearest n;
    for (std::size_t i = 0; i < path.size(); ++i) {
        const int m = std::max(1, static_cast<int>(std::ceil(length(path[i]) / kSpacing)));
        for (int k = 0; k <= m; ++k) {
            const Vec2 q = point_at(path[i], double(k) / m);
            for (std::size_t j = 0; j < walls.size(); ++j) {
                const double d = distance_to(walls[j], q);
                if (d < n.distance) n = {d, i, j, q};
            }
        }
    }
    return n;
}

// ---- The examples

// A stretch of compensation: what the spec says of it.
struct StretchSpec {
    double r = 0.0;     // mm
    bool o100 = false;  // mmount's helical hole milling (below)
    // The last compensated element leads the tool away past the part ("continue past edge",
    // "out of the workpiece"): compared, but no wall the paths must keep r from.
    bool lead_out = false;
    // qpocket's pocket: the outlines inside the full one are cut away by the next (below).
    bool pocket = false;
};

struct Example {
    std::string name;
    std::string original;  // in LinuxCNC's ncfiles
    bool inches = false;   // G20: run in mm as well
    // The mm run is our rewrite translated into RS274/NGC (rewrite_to_ngc) rather than the
    // original converted (inch_to_mm).
    bool mm_from_rewrite = false;
    // An ngcgui subroutine (`original`) runs as ngcgui runs it: the preamble (under ncfiles),
    // `call`, m2; the subroutines are found in `subroutine_dirs` (under ncfiles), those of
    // `m110_files` (under ncfiles) with their M110 lines made comments (without_m110).
    std::string preamble, call;
    std::vector<std::string> subroutine_dirs, m110_files;
    std::string tool_table;  // for rs274 (inches, D = diameter)
    std::string program;     // ours, under the source tree
    std::string tools;       // our tool list
    std::vector<StretchSpec> stretches;
    double min_compared_mm;  // the contour proper compared, at least (both paths)
};

// gtest names the parameter by this.
void PrintTo(const Example& e, std::ostream* os) {
    *os << e.name;
}

// Tool radius in mm of a diameter in inches.
double radius_of(double diameter_inches) {
    return diameter_inches / 2 * kInch;
}

// LinuxCNC's example programs with cutter compensation (its ncfiles), run as they stand.
std::vector<Example> ncfiles_examples() {
    std::vector<Example> out;
    {
        Example e;
        e.name = "comp-g1";
        e.original = "comp-g1.ngc";
        e.inches = true;
        e.tool_table = "T4 P4 D1.0 ;1 inch end mill, as the program's header asks\n";
        e.program = "examples/linuxcnc/comp_g1.nc";
        e.tools = "examples/linuxcnc/comp_g1.tools";
        e.stretches = {{radius_of(1.0), false}};
        e.min_compared_mm = 480;
        out.push_back(e);
    }
    {
        Example e;
        e.name = "mmount";
        e.original = "mmount.ngc";
        e.inches = true;
        // The tools of its header comment: tool, pocket, Z offset, diameter (inches).
        e.tool_table =
            "T1 P1 Z-1.1901 D0.250 ;3/4 center drill\n"
            "T2 P2 Z-0.2875 D0.209 ;#4 tap drill\n"
            "T3 P3 Z0.0 D0.1406 ;9/64 clearance drill\n"
            "T4 P4 Z-1.6630 D0.25 ;1/4 end mill\n"
            "T5 P5 Z-1.5042 D0.5 ;1/2 end mill\n"
            "T15 P15 Z-1.5042 D0.55 ;same 1/2 end mill oversize roughing\n"
            "T6 P6 Z-0.1833 D0.25 ;1/4-20 pulley tap\n";
        e.program = "examples/linuxcnc/mmount_milling.nc";
        e.tools = "examples/linuxcnc/mmount.tools";
        // Two curved slots, four holes and four counterbores (o100) with T4, four large holes
        // (o100) with T5, the perimeter with D15 and with D5.
        for (int i = 0; i < 2; ++i) e.stretches.push_back({radius_of(0.25), false});
        for (int i = 0; i < 8; ++i) e.stretches.push_back({radius_of(0.25), true});
        for (int i = 0; i < 4; ++i) e.stretches.push_back({radius_of(0.5), true});
        e.stretches.push_back({radius_of(0.55), false});
        e.stretches.push_back({radius_of(0.5), false, true});  // "continue past edge"
        e.min_compared_mm = 5500;
        out.push_back(e);
    }
    {
        Example e;
        e.name = "gmoccapy";
        e.original = "gmoccapy_2_tools_with_cutter_radius_compensation.ngc";
        e.inches = false;
        // The diameters of T1 (1 mm) and T3 (3 mm) in the tool table of LinuxCNC's gmoccapy
        // sample configuration (metric), written in inches for standalone rs274.
        char table[160];
        std::snprintf(table, sizeof table, "T1 P1 D%.15f ;1 mm\nT3 P3 D%.15f ;3 mm\n", 1.0 / kInch,
                      3.0 / kInch);
        e.tool_table = table;
        e.program = "examples/linuxcnc/gmoccapy_two_circles.nc";
        e.tools = "examples/linuxcnc/gmoccapy.tools";
        e.stretches = {{1.5, false, true}, {0.5, false, true}};  // "out of the workpiece"
        e.min_compared_mm = 240;
        out.push_back(e);
    }
    return out;
}

// ngcgui's subroutines, as ngcgui calls them.
std::vector<Example> ngcgui_examples() {
    std::vector<Example> out;
    {
        // ngcgui's qpocket.ngc as its example caller qpex.ngc calls it, with qpex's defaults,
        // in the ngcgui sample configuration that offers it (sim/axis/ngcgui: inches, preamble
        // in_std.ngc, tool table sim.tbl with T1 0.1 in). Seven pockets, one stretch each.
        Example e;
        e.name = "qpocket";
        e.original = "ngcgui_lib/qpex.ngc";
        e.inches = true;
        e.mm_from_rewrite = true;
        e.preamble = "ngcgui_lib/utilitysubs/in_std.ngc";
        // toolno rpm dir feedrate cutdepth zincr zsafe zstart stepover g64tol spin_notify
        // use_g43 h_for_g43 verbose: qpex.ngc's defaults.
        e.call = "o<qpex> call [1][1000][2][10][1][.4][0.2][0][0.9][0.002][0][1][0][0]";
        e.subroutine_dirs = {"ngcgui_lib", "ngcgui_lib/utilitysubs"};
        e.m110_files = {"ngcgui_lib/qpex.ngc"};
        e.tool_table = "T1 P1 D0.1 ;sim.tbl of LinuxCNC's ngcgui sample configuration\n";
        e.program = "examples/linuxcnc/qpocket_qpex.nc";
        e.tools = "examples/linuxcnc/qpocket.tools";
        for (int i = 0; i < 7; ++i) e.stretches.push_back({radius_of(0.1), false, false, true});
        e.min_compared_mm = 10000;
        out.push_back(e);
    }
    {
        // ngcgui's helix.ngc, its inside cut without the D flat, with the hole of LinuxCNC's
        // helical hole example (useful-subroutines.ngc, o100's second call) and a 1/16 in end
        // mill; an inch configuration with preamble in_std.ngc.
        Example e;
        e.name = "helix";
        e.original = "ngcgui_lib/helix.ngc";
        e.inches = true;
        e.mm_from_rewrite = true;
        e.preamble = "ngcgui_lib/utilitysubs/in_std.ngc";
        // toolno rpm feedrate dir inside cutdepth zincr zsafe x y hdiam faceangle d_angle
        // zstart spin_notify use_g43 h_for_g43 verbose.
        e.call =
            "o<helix> call [1][2000][10][3][1][0.0625][0.03125][0.5][0.25][0][0.25][0][0][0][0]"
            "[1][0][0]";
        e.subroutine_dirs = {"ngcgui_lib", "ngcgui_lib/utilitysubs"};
        e.tool_table = "T1 P1 D0.0625 ;1/16 end mill\n";
        e.program = "examples/linuxcnc/helix_inside.nc";
        e.tools = "examples/linuxcnc/helix.tools";
        e.stretches = {{radius_of(0.0625)}};
        e.min_compared_mm = 40;
        out.push_back(e);
    }
    return out;
}

// Every example: the programs, then the subroutines.
std::vector<Example> examples() {
    std::vector<Example> out = ncfiles_examples();
    const std::vector<Example> ngcgui = ngcgui_examples();
    out.insert(out.end(), ngcgui.begin(), ngcgui.end());
    return out;
}

// The moves that move: left out, those that go nowhere (in the plane nor on the third axis).
// In LinuxCNC a block without X and Y right after G40 stays where the compensated path ended
// (qpocket's "g0 z#<zsafe>" at the start of a call, with Z already there): a move to where
// the tool is, which our rewrite leaves out (its header says why).
std::vector<CanonMove> moving(const std::vector<CanonMove>& moves) {
    std::vector<CanonMove> out;
    double third = NAN;
    for (const CanonMove& m : moves) {
        if (!(length(m.path) == 0.0 && m.third == third)) out.push_back(m);
        third = m.third;
    }
    return out;
}

// One compensated stretch on either side.
struct Stretch {
    std::size_t first = 0, last = 0;  // indices of its moves / segments
};

std::vector<Stretch> linuxcnc_stretches(const std::vector<CanonMove>& moves) {
    std::vector<Stretch> out;
    for (std::size_t i = 0; i < moves.size(); ++i) {
        if (moves[i].compensation == 40) continue;
        if (i == 0 || moves[i - 1].compensation == 40) out.push_back({i, i});
        out.back().last = i;
    }
    return out;
}

bool compensated_role(int role) {
    using apci::run::Role;
    return role == static_cast<int>(Role::kApproach) || role == static_cast<int>(Role::kContour) ||
           role == static_cast<int>(Role::kTransition) ||
           role == static_cast<int>(Role::kDeparture);
}

std::vector<Stretch> our_stretches(const std::vector<Seg>& segs) {
    const int approach = static_cast<int>(apci::run::Role::kApproach);
    std::vector<Stretch> out;
    for (std::size_t i = 0; i < segs.size(); ++i) {
        if (!compensated_role(segs[i].role)) continue;
        const bool starts = i == 0 || !compensated_role(segs[i - 1].role) ||
                            (segs[i].role == approach && segs[i - 1].role != approach);
        if (starts) out.push_back({i, i});
        out.back().last = i;
    }
    return out;
}

// A part of the contour proper and the programmed elements its path must keep r from.
struct Pass {
    const char* name;
    Vec2 from, to;
    std::vector<Element> walls;
};

struct Figures {
    int stretches = 0;
    double compared_ours = 0.0, compared_linuxcnc = 0.0;
    double max_deviation = 0.0;
    double min_clearance_margin = INFINITY;  // least (clearance - r) over both paths
    double max_approach = 0.0, max_departure = 0.0;
    double max_deviation_inch = 0.0;  // our path from rs274's output for the inch original
    double max_length_apart = 0.0;    // the lengths' difference, as a fraction of its tolerance
};

std::string dump(const std::vector<Element>& path, const std::vector<std::uint64_t>* lines) {
    std::string s;
    for (std::size_t i = 0; i < path.size(); ++i) {
        s += "    ";
        if (lines != nullptr) s += "line " + std::to_string((*lines)[i]) + ": ";
        s += element_text(path[i]) + "\n";
    }
    return s;
}

class LinuxCncExamples : public ::testing::TestWithParam<Example> {};

// ---- The comparison, step by step

// LinuxCNC's runs of the example (`runs`): the original (an ngcgui subroutine as ngcgui runs it)
// and, for an inch program, its mm version; fails where a file cannot be read or rs274 fails.
void run_linuxcnc(const Example& ex, std::vector<Rs274Result>& runs) {
    const std::string ncfiles = rs274().ncfiles + "/";
    const std::string original = read_text(ncfiles + ex.original);
    ASSERT_FALSE(original.empty()) << "cannot read " << ncfiles << ex.original;
    std::string program = original;
    Rs274Subroutines subroutines;
    if (!ex.call.empty()) {
        const std::string preamble = read_text(ncfiles + ex.preamble);
        ASSERT_FALSE(preamble.empty()) << "cannot read " << ncfiles << ex.preamble;
        program = preamble + ex.call + "\nm2\n";
        for (const std::string& d : ex.subroutine_dirs)
            subroutines.directories.push_back(ncfiles + d);
        for (const std::string& f : ex.m110_files) {
            int changed = 0;
            subroutines.files.emplace_back(f.substr(f.rfind('/') + 1),
                                           without_m110(read_text(ncfiles + f), changed));
            ASSERT_GT(changed, 0) << f << " has no M110 line";
        }
    }
    const std::string ours_text = read_text(std::string(kSourceDir) + "/" + ex.program);
    ASSERT_FALSE(ours_text.empty()) << "cannot read " << ex.program;
    std::vector<std::string> programs{program};
    if (ex.inches)
        programs.push_back(ex.mm_from_rewrite ? rewrite_to_ngc(ours_text) : inch_to_mm(original));
    runs = run_rs274(rs274(), programs, ex.tool_table, 17, 2, subroutines);
    for (std::size_t i = 0; i < runs.size(); ++i) {
        ASSERT_TRUE(runs[i].ran && runs[i].exit_code == 0 && !runs[i].moves.empty())
            << "rs274 on " << ex.original
            << (i == 0               ? ""
                : ex.mm_from_rewrite ? " (our rewrite in RS274/NGC)"
                                     : " (in mm)")
            << ": exit " << runs[i].exit_code << " " << runs[i].error;
    }
}

// The conversion of an inch program keeps LinuxCNC's moves: `in` (the original's moves that
// move) and `lc` (its mm version's) are the same moves, with the same compensation, every
// coordinate within the two printed roundings.
void expect_mm_version_moves_alike(const Example& ex, const std::vector<Rs274Result>& runs,
                                   const std::vector<CanonMove>& in,
                                   const std::vector<CanonMove>& lc) {
    ASSERT_EQ(in.size(), lc.size()) << "the original and its mm version differ in moves";
    double worst = 0.0;
    for (std::size_t i = 0; i < lc.size(); ++i) {
        const Element &a = in[i].path, &b = lc[i].path;
        ASSERT_TRUE(in[i].rapid == lc[i].rapid && in[i].compensation == lc[i].compensation &&
                    a.kind == b.kind && a.ccw == b.ccw)
            << "move " << i << ": " << element_text(a) << " (inches) vs " << element_text(b);
        for (const auto& [p, q] : {std::pair{a.end, b.end}, std::pair{a.centre, b.centre}}) {
            const Vec2 d = (kInch * p - q).cwiseAbs();
            worst = std::max({worst, d.x(), d.y()});
        }
        worst = std::max(worst, std::abs(kInch * in[i].third - lc[i].third));
    }
    EXPECT_LE(worst, kPrintedRounding)
        << "the mm version of " << ex.original << " moves differently from the original";
    std::printf(
        "%s: the original (inches) and its mm version: %zu moves alike (%zu and %zu that move "
        "nowhere left out), coordinates within %.2e mm (rs274's printed rounding %.2e)\n",
        ex.name.c_str(), lc.size(), runs[0].moves.size() - in.size(),
        runs.back().moves.size() - lc.size(), worst, kPrintedRounding);
}

// Our run of the example (`ours`), which must have no errors and no warnings: each is a correct
// program (its leads, its passes widening a pocket, its roughing circles are no walls:
// docs/compensation.md, "What is a wall").
void run_ours(const Example& ex, OurExampleRun& ours) {
    ours = run_example(std::string(kSourceDir) + "/" + ex.program,
                       std::string(kSourceDir) + "/" + ex.tools);
    ASSERT_TRUE(ours.error.empty()) << ours.error;
    ASSERT_TRUE(ours.planes_ok);
    for (const apci::run::RunError& e : ours.errors)
        ADD_FAILURE() << ex.program << ": line " << e.block.line << ": " << e.code << ": "
                      << e.message;
    ASSERT_TRUE(ours.errors.empty());
    for (const apci::run::RunError& w : ours.warnings)
        ADD_FAILURE() << ex.program << ": line " << w.block.line << ": " << w.code << ": "
                      << w.message;
    std::printf("%s: our run: %zu segments, no errors, no warnings\n", ex.name.c_str(),
                ours.executed.size());
}

// One compensated stretch of the example as both runs made it.
struct StretchRun {
    const Example& ex;
    std::size_t k;  // its index (number k + 1 in the messages)
    const StretchSpec& spec;
    const std::vector<CanonMove>& lc;  // LinuxCNC's moves that move, in mm
    const std::vector<CanonMove>& in;  // the same as the original makes them
    const OurExampleRun& ours;
    const Stretch& ts;  // LinuxCNC's moves of the stretch
    const Stretch& os;  // our executed segments of the stretch
    double r;           // the tool radius, mm
    bool left;          // G41
};

// The stretch's paths in the plane and the programmed contour they are compared along.
struct StretchPaths {
    std::vector<Element> contour;  // the contour proper's programmed elements
    std::vector<std::uint64_t> contour_lines;
    std::vector<Element> lc_path, our_path;  // LinuxCNC's feed moves, our segments
    std::vector<std::uint64_t> our_lines;
    std::string both;                      // both paths as text, for the failure messages
    Vec2 from, to;                         // where the contour proper begins and ends on the paths
    std::vector<Element> lc_win, our_win;  // the paths from `from` to `to`
};

// The programmed elements of the stretch: our executed segments name their blocks (a
// departure under G139 is the G40 block's move, not an element of the contour).
void programmed_contour(const StretchRun& s, StretchPaths& p) {
    std::set<std::uint64_t> stretch_lines;
    for (std::size_t i = s.os.first; i <= s.os.last; ++i)
        if (s.ours.executed[i].role != static_cast<int>(apci::run::Role::kDeparture))
            stretch_lines.insert(s.ours.executed[i].line);
    for (const Seg& g : s.ours.programmed) {
        if (g.rapid || length(g.path) <= 1e-9 || !stretch_lines.count(g.line)) continue;
        p.contour.push_back(g.path);
        p.contour_lines.push_back(g.line);
    }
    // LinuxCNC's first move after G41 is its entry move: a feed move there is our first
    // compensated element, reached by our approach. Not part of the contour proper.
    const bool entry_is_feed = !s.lc[s.ts.first].rapid;
    if (entry_is_feed && !p.contour.empty()) {
        p.contour.erase(p.contour.begin());
        p.contour_lines.erase(p.contour_lines.begin());
    }
    ASSERT_FALSE(p.contour.empty()) << "no contour proper";
}

// Both paths in the plane: LinuxCNC's feed moves of the stretch, our segments.
void both_paths(const StretchRun& s, StretchPaths& p) {
    for (std::size_t i = s.ts.first; i <= s.ts.last; ++i)
        if (!s.lc[i].rapid) p.lc_path.push_back(s.lc[i].path);
    for (std::size_t i = s.os.first; i <= s.os.last; ++i) {
        p.our_path.push_back(s.ours.executed[i].path);
        p.our_lines.push_back(s.ours.executed[i].line);
    }
    p.both = "  LinuxCNC's path (stretch " + std::to_string(s.k + 1) + "):\n";
    for (std::size_t i = s.ts.first; i <= s.ts.last; ++i)
        p.both +=
            std::string(s.lc[i].rapid ? "    rapid " : "    ") + element_text(s.lc[i].path) + "\n";
    p.both += "  our path:\n" + dump(p.our_path, &p.our_lines);
}

// The contour proper: from the start of its first element's offset when both paths
// pass there on their way to its middle (the entry meets it at an outside or tangent
// corner on both), else from its middle (an inside corner trims it, each path at its
// own point); to the end of its last element's offset when both pass there after its
// middle (or pass there and not its middle: the corner before it trims more than its
// half), else to its middle.
void contour_proper_ends(const StretchRun& s, StretchPaths& p) {
    const auto reaches_first = [&](const Vec2& at, const Vec2& mid) {
        for (const auto& [path, tol] : {std::pair{&p.lc_path, kLinuxCncWindowTolerance},
                                        std::pair{&p.our_path, kOurWindowTolerance}}) {
            const std::size_t a = first_near(*path, at, tol), b = first_near(*path, mid, tol);
            if (a == kNone || b == kNone || a > b) return false;
        }
        return true;
    };
    const auto leaves_last = [&](const Vec2& at, const Vec2& mid) {
        for (const auto& [path, tol] : {std::pair{&p.lc_path, kLinuxCncWindowTolerance},
                                        std::pair{&p.our_path, kOurWindowTolerance}}) {
            // The middle is not on the path where the corner before a short element trims
            // more than its half (qpocket's last move along a side, shorter than 2r).
            const std::size_t a = last_near(*path, at, tol), b = last_near(*path, mid, tol);
            if (a == kNone || (b != kNone && a < b)) return false;
        }
        return true;
    };
    const Vec2 first_mid = offset_at(p.contour.front(), 0.5, s.r, s.left);
    const Vec2 last_mid = offset_at(p.contour.back(), 0.5, s.r, s.left);
    p.from = offset_at(p.contour.front(), 0.0, s.r, s.left);
    if (!reaches_first(p.from, first_mid)) p.from = first_mid;
    p.to = offset_at(p.contour.back(), 1.0, s.r, s.left);
    if (!leaves_last(p.to, last_mid)) p.to = last_mid;
}

// The two paths along the contour proper (`lc_win`, `our_win`); fails where either misses it.
void contour_proper_windows(StretchPaths& p) {
    p.lc_win = window(p.lc_path, p.from, p.to, kLinuxCncWindowTolerance);
    p.our_win = window(p.our_path, p.from, p.to, kOurWindowTolerance);
    ASSERT_FALSE(p.lc_win.empty()) << "the contour proper " << point_text(p.from) << " .. "
                                   << point_text(p.to) << " is not on LinuxCNC's path\n"
                                   << p.both;
    ASSERT_FALSE(p.our_win.empty()) << "the contour proper " << point_text(p.from) << " .. "
                                    << point_text(p.to) << " is not on our path\n"
                                    << p.both;
}

// How far the two paths lie apart along the contour proper (Hausdorff distance); a failure,
// with where, beyond kMaxDeviation.
double contour_proper_deviation(const StretchPaths& p) {
    const double dev = hausdorff(p.our_win, p.lc_win, kSpacing);
    if (dev > kMaxDeviation) {
        const Worst a = farthest(p.our_win, p.lc_win), b = farthest(p.lc_win, p.our_win);
        ADD_FAILURE() << "the paths differ by " << dev << " mm on the contour proper: ours "
                      << a.distance << " mm from LinuxCNC's at " << point_text(a.at) << " ("
                      << element_text(p.our_win[a.element]) << "), LinuxCNC's " << b.distance
                      << " mm from ours at " << point_text(b.at) << " ("
                      << element_text(p.lc_win[b.element]) << ")\n"
                      << "  programmed contour:\n"
                      << dump(p.contour, &p.contour_lines) << p.both;
    }
    return dev;
}

// The same length: the Hausdorff distance does not see a pass run twice or left out
// where passes lie on each other in the plane (the depth passes of qpocket and helix,
// the laps of mmount's holes). Each of LinuxCNC's elements may be off by its two end
// points' printed rounding, an arc also by its radius's for every radian; the window's
// ends by the tolerance they are found within.
void expect_same_length(const StretchPaths& p, Figures& f) {
    double length_tolerance = 2 * kLinuxCncWindowTolerance;
    for (const Element& e : p.lc_win)
        length_tolerance += kPrintedPoint * (2 + (is_arc(e) ? std::abs(sweep(e)) : 0.0));
    const double length_apart = std::abs(path_length(p.our_win) - path_length(p.lc_win));
    f.max_length_apart = std::max(f.max_length_apart, length_apart / length_tolerance);
    EXPECT_LE(length_apart, length_tolerance)
        << "the contour proper is " << path_length(p.our_win) << " mm long on our path, "
        << path_length(p.lc_win) << " mm on LinuxCNC's\n"
        << p.both;
}

// The passes whose clearance is checked (`passes`). mmount's holes (o100) are roughed 0.020 in
// under size and then finished at size, by a half circle out to the hole, the full circle, and a
// half circle back: the finishing cuts 0.254 mm into the roughing contour, and the full circle's
// path into the half circles', by design. There the roughing path keeps r from the roughing
// circles (from the window's start to a quarter into the last), the finishing path (from the
// middle of the first half circle to the window's end) from the finished hole. qpocket clears
// its pocket in outlines, each from the next corner of a larger one, the last at full size, and
// ends along that one's next side: the part that stays is the full outline, and the whole
// contour proper keeps r from its four sides and the last move along the fifth. Elsewhere the
// whole contour proper keeps r from all of it but a last element that leads out past the part
// (StretchSpec::lead_out).
void clearance_passes(const StretchRun& s, const StretchPaths& p, std::vector<Pass>& passes) {
    const std::vector<Element>& contour = p.contour;
    if (s.spec.pocket) {
        ASSERT_GE(contour.size(), 5u);
        const std::vector<Element> outline(contour.end() - 5, contour.end());
        // A closed quadrilateral: the four sides end where they began, and the move that
        // ends the stretch starts at a corner and runs along the first side's line.
        EXPECT_LE((outline[3].end - outline[0].start).norm(), 1e-9) << dump(outline, nullptr);
        EXPECT_LE((outline[4].start - outline[3].end).norm(), 1e-9) << dump(outline, nullptr);
        // (the program's numbers have 6 decimals)
        const Vec2 along = outline[0].end - outline[0].start;
        EXPECT_LE(
            distance_to(make_line(outline[0].start - 1e3 * along, outline[0].end + 1e3 * along),
                        outline[4].end),
            1e-5)
            << dump(outline, nullptr);
        passes.push_back({"pocket", p.from, p.to, outline});
    } else if (s.spec.o100) {
        ASSERT_GE(contour.size(), 5u);
        const std::size_t n = contour.size();
        passes.push_back({"roughing", p.from, offset_at(contour[n - 4], 0.25, s.r, s.left),
                          std::vector<Element>(contour.begin(), contour.end() - 3)});
        passes.push_back({"finishing", offset_at(contour[n - 3], 0.5, s.r, s.left), p.to,
                          std::vector<Element>{contour[n - 2]}});
    } else {
        std::vector<Element> walls = contour;
        if (s.spec.lead_out && walls.size() > 1) walls.pop_back();
        passes.push_back({"contour", p.from, p.to, walls});
    }
}

// Clearance, pass by pass: neither path comes closer to the pass's walls than r, within
// kClearanceTolerance.
void expect_clearance(const StretchRun& s, const StretchPaths& p, const std::vector<Pass>& passes,
                      Figures& f) {
    const double r = s.r;
    for (const Pass& pass : passes) {
        for (const auto& [who, path, tol] :
             {std::tuple{"LinuxCNC's", &p.lc_path, kLinuxCncWindowTolerance},
              std::tuple{"our", &p.our_path, kOurWindowTolerance}}) {
            const std::vector<Element> w = window(*path, pass.from, pass.to, tol);
            ASSERT_FALSE(w.empty()) << pass.name << " pass not on " << who << " path\n" << p.both;
            const double c = clearance(w, pass.walls, r, kSpacing);
            f.min_clearance_margin = std::min(f.min_clearance_margin, c - r);
            if (c < r - kClearanceTolerance) {
                const Nearest n = nearest(w, pass.walls);
                ADD_FAILURE() << who << " path comes within " << c << " mm of the contour ("
                              << pass.name << " pass, r " << r << ") at " << point_text(n.at)
                              << " on " << element_text(w[n.element]) << ", near "
                              << element_text(pass.walls[n.wall]) << "\n  programmed contour:\n"
                              << dump(pass.walls, nullptr) << p.both;
            }
        }
    }
}

// rs274's output for the original itself (inches, 4 decimals): how far it lies from
// our path, its printed rounding included (not a verdict: that is the mm run's). NAN for a
// program in mm.
double inch_deviation(const StretchRun& s, const StretchPaths& p, Figures& f) {
    double dev_inch = NAN;
    if (s.ex.inches) {
        std::vector<Element> inch_path;
        for (std::size_t i = s.ts.first; i <= s.ts.last; ++i) {
            const Element& e = s.in[i].path;
            if (s.in[i].rapid) continue;
            inch_path.push_back(
                is_arc(e) ? make_arc(kInch * e.start, kInch * e.end, kInch * e.centre, e.ccw)
                          : make_line(kInch * e.start, kInch * e.end));
        }
        const std::vector<Element> w =
            window(inch_path, p.from, p.to, std::sqrt(2.0) * kPrintedRounding);
        if (!w.empty()) dev_inch = hausdorff(p.our_win, w, kSpacing);
        f.max_deviation_inch = std::max(f.max_deviation_inch, dev_inch);
    }
    return dev_inch;
}

// A stretch's approach and departure on both paths, and how far they lie apart.
struct EntryAndExit {
    std::vector<Element> lc_in, our_in, lc_out, our_out;
    Vec2 exit_point;    // where LinuxCNC's first move after G40 that moves in the plane ends
    bool ours_reaches;  // our departure reaches it
    double d_in, d_out;
};

// Approach and departure: compared as the contour proper is. The lead-in runs from
// where the tool stood before G41 (LinuxCNC's stretch begins there) to the contour
// proper; the lead-out from the contour proper to where LinuxCNC's first move after
// G40 that moves in the plane ends, and ours reaches the same point.
EntryAndExit compare_approach_and_departure(const StretchRun& s, const StretchPaths& p,
                                            Figures& f) {
    const std::vector<CanonMove>& lc = s.lc;
    const std::vector<Seg>& executed = s.ours.executed;
    EntryAndExit e;
    std::vector<Element> lc_all, our_before;
    for (std::size_t i = s.ts.first; i <= s.ts.last; ++i) lc_all.push_back(lc[i].path);
    const Vec2 start = lc[s.ts.first].path.start;
    std::size_t first = s.os.first;
    for (std::size_t back = 0; back <= 3 && back <= s.os.first; ++back) {
        if ((executed[s.os.first - back].path.start - start).norm() <= kLinuxCncWindowTolerance) {
            first = s.os.first - back;
            break;
        }
    }
    for (std::size_t i = first; i < s.os.first; ++i) our_before.push_back(executed[i].path);
    our_before.insert(our_before.end(), p.our_path.begin(), p.our_path.end());
    e.lc_in = up_to_first(lc_all, p.from, kLinuxCncWindowTolerance);
    e.our_in = up_to_first(our_before, p.from, kOurWindowTolerance);
    e.lc_out = from_last(lc_all, p.to, kLinuxCncWindowTolerance);
    e.our_out = from_last(p.our_path, p.to, kOurWindowTolerance);
    e.exit_point = lc_all.back().end;
    for (std::size_t i = s.ts.last + 1; i < lc.size(); ++i) {
        e.lc_out.push_back(lc[i].path);
        e.exit_point = lc[i].path.end;
        if (length(lc[i].path) > 1e-9) break;
    }
    // A program that ends under G41 leaves the tool where the stretch ends, on both.
    e.ours_reaches = !p.our_path.empty() &&
                     (p.our_path.back().end - e.exit_point).norm() <= kLinuxCncWindowTolerance;
    for (std::size_t i = s.os.last + 1;
         i < executed.size() && i <= s.os.last + 4 && !e.ours_reaches; ++i) {
        e.our_out.push_back(executed[i].path);
        e.ours_reaches = (executed[i].path.end - e.exit_point).norm() <= kLinuxCncWindowTolerance;
    }
    const auto apart = [](const std::vector<Element>& a, const std::vector<Element>& b) {
        return a.empty() || b.empty() ? NAN : hausdorff(a, b, kSpacing);
    };
    e.d_in = apart(e.our_in, e.lc_in);
    e.d_out = apart(e.our_out, e.lc_out);
    f.max_approach = std::max(f.max_approach, e.d_in);
    f.max_departure = std::max(f.max_departure, e.d_out);
    const std::string& name = s.ex.name;
    EXPECT_LE(e.d_in, kMaxDeviation) << name << " stretch " << s.k + 1 << ": the approaches differ";
    EXPECT_LE(e.d_out, kMaxDeviation)
        << name << " stretch " << s.k + 1 << ": the departures differ";
    EXPECT_TRUE(e.ours_reaches) << name << " stretch " << s.k + 1
                                << ": our departure does not reach " << point_text(e.exit_point);
    return e;
}

// The move that leaves the contour proper (the first after it that moves in the
// plane), with the third axis (Z) at its start and end: where the tool goes sideways.
std::string leaving_the_contour(const StretchRun& s, const StretchPaths& p) {
    const std::vector<CanonMove>& lc = s.lc;
    const std::vector<Seg>& executed = s.ours.executed;
    std::size_t i = s.ts.last + 1;
    for (std::size_t k2 = s.ts.first; k2 <= s.ts.last; ++k2)
        if (length(lc[k2].path) > 0 && distance_to(lc[k2].path, p.to) <= kLinuxCncWindowTolerance)
            i = k2 + 1;
    while (i < lc.size() && length(lc[i].path) <= 1e-9) ++i;
    char buf[200];
    if (i < lc.size())
        std::snprintf(buf, sizeof buf, "LinuxCNC %s to %s, Z %.3f -> %.3f",
                      lc[i].rapid ? "rapid" : "feed", point_text(lc[i].path.end).c_str(),
                      lc[i - 1].third, lc[i].third);
    else
        std::snprintf(buf, sizeof buf, "LinuxCNC stays (the program ends under G41)");
    std::string leaves = buf;
    std::size_t o = s.os.last + 1;
    for (std::size_t k2 = s.os.first; k2 <= s.os.last; ++k2)
        if (length(p.our_path[k2 - s.os.first]) > 0 &&
            distance_to(p.our_path[k2 - s.os.first], p.to) <= kOurWindowTolerance)
            o = k2 + 1;
    while (o < executed.size() && length(executed[o].path) <= 1e-9) ++o;
    if (o < executed.size()) {
        const Seg& g = executed[o];
        std::snprintf(
            buf, sizeof buf, "; ours %s to %s, Z %.3f -> %.3f",
            std::string(apci::run::role_name(static_cast<apci::run::Role>(g.role))).c_str(),
            point_text(g.path.end).c_str(), g.z0, g.z1);
        leaves += buf;
    }
    return leaves;
}

// The stretch's figures, printed.
void print_stretch(const StretchRun& s, const StretchPaths& p, double dev, double dev_inch,
                   const EntryAndExit& e, const std::string& leaves) {
    char inch_text[64] = "";
    if (s.ex.inches)
        std::snprintf(inch_text, sizeof inch_text, " (from the inch output: %.2e mm)", dev_inch);
    std::printf(
        "%s stretch %zu (r %.4f mm, our lines %llu..%llu): contour proper %zu elements, "
        "compared %.3f mm (ours) / %.3f mm (LinuxCNC), deviation %.2e mm%s\n"
        "    approach: LinuxCNC %.3f mm, ours %.3f mm, apart by up to %.4f mm; departure to "
        "%s: LinuxCNC %.3f mm, ours %.3f mm%s, apart by up to %.4f mm\n"
        "    leaving the contour: %s\n",
        s.ex.name.c_str(), s.k + 1, s.r,
        static_cast<unsigned long long>(s.ours.executed[s.os.first].line),
        static_cast<unsigned long long>(s.ours.executed[s.os.last].line), p.contour.size(),
        path_length(p.our_win), path_length(p.lc_win), dev, inch_text, path_length(e.lc_in),
        path_length(e.our_in), e.d_in, point_text(e.exit_point).c_str(), path_length(e.lc_out),
        path_length(e.our_out), e.ours_reaches ? "" : " (not reaching it)", e.d_out,
        leaves.c_str());
}

// One stretch compared, step by step; its figures added to `f`.
void compare_stretch(const StretchRun& s, Figures& f) {
    SCOPED_TRACE(s.ex.name + " stretch " + std::to_string(s.k + 1) + " (r " + std::to_string(s.r) +
                 " mm, our lines " + std::to_string(s.ours.executed[s.os.first].line) + ".." +
                 std::to_string(s.ours.executed[s.os.last].line) + ")");
    StretchPaths p;
    ASSERT_NO_FATAL_FAILURE(programmed_contour(s, p));
    both_paths(s, p);
    contour_proper_ends(s, p);
    ASSERT_NO_FATAL_FAILURE(contour_proper_windows(p));
    const double dev = contour_proper_deviation(p);
    expect_same_length(p, f);
    std::vector<Pass> passes;
    ASSERT_NO_FATAL_FAILURE(clearance_passes(s, p, passes));
    ASSERT_NO_FATAL_FAILURE(expect_clearance(s, p, passes, f));
    const double dev_inch = inch_deviation(s, p, f);
    const EntryAndExit e = compare_approach_and_departure(s, p, f);
    print_stretch(s, p, dev, dev_inch, e, leaving_the_contour(s, p));
    ++f.stretches;
    f.compared_ours += path_length(p.our_win);
    f.compared_linuxcnc += path_length(p.lc_win);
    f.max_deviation = std::max(f.max_deviation, dev);
}

// The example's figures, printed.
void print_figures(const Example& ex, const Figures& f, double seconds) {
    std::printf(
        "%s: %d stretches; contour proper compared %.1f mm (ours) / %.1f mm (LinuxCNC); "
        "max deviation %.2e mm (limit %.0e); lengths apart by up to %.0f %% of their tolerance; "
        "least clearance r %+.2e mm (limit -%.1e); approach apart by up to %.4f mm, departure "
        "by up to %.4f mm; %.2f s\n",
        ex.name.c_str(), f.stretches, f.compared_ours, f.compared_linuxcnc, f.max_deviation,
        kMaxDeviation, 100 * f.max_length_apart, f.min_clearance_margin, kClearanceTolerance,
        f.max_approach, f.max_departure, seconds);
    if (ex.inches)
        std::printf(
            "%s: our path from rs274's output for the inch original itself: up to %.2e mm "
            "(its 4 printed decimals in inches alone allow %.2e)\n",
            ex.name.c_str(), f.max_deviation_inch, std::sqrt(2.0) * 0.5e-4 * kInch);
}

TEST_P(LinuxCncExamples, CompensatedPathsAgreeWithRs274) {
    if (!rs274().why.empty()) GTEST_SKIP() << rs274().why;
    const Example& ex = GetParam();
    const auto t0 = std::chrono::steady_clock::now();

    // LinuxCNC: the original (and, for inch programs, the original in mm).
    std::vector<Rs274Result> runs;
    ASSERT_NO_FATAL_FAILURE(run_linuxcnc(ex, runs));
    // LinuxCNC's moves that move, in mm (the mm run) and as the original makes them.
    const std::vector<CanonMove> lc = moving(runs.back().moves);
    const std::vector<CanonMove> in = moving(runs[0].moves);
    if (ex.inches) {
        ASSERT_NO_FATAL_FAILURE(expect_mm_version_moves_alike(ex, runs, in, lc));
    }

    // Ours.
    OurExampleRun ours;
    ASSERT_NO_FATAL_FAILURE(run_ours(ex, ours));

    const std::vector<Stretch> theirs_s = linuxcnc_stretches(lc);
    const std::vector<Stretch> ours_s = our_stretches(ours.executed);
    ASSERT_EQ(theirs_s.size(), ex.stretches.size()) << "LinuxCNC's compensated stretches";
    ASSERT_EQ(ours_s.size(), ex.stretches.size()) << "our compensated stretches";

    Figures f;
    for (std::size_t k = 0; k < ex.stretches.size(); ++k) {
        const StretchSpec& spec = ex.stretches[k];
        const Stretch& ts = theirs_s[k];
        const StretchRun s{ex,   k,  spec,      lc,     in,
                           ours, ts, ours_s[k], spec.r, lc[ts.first].compensation == 41};
        ASSERT_NO_FATAL_FAILURE(compare_stretch(s, f));
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    print_figures(ex, f, seconds);
    // Enough was compared that an empty or shrunken window cannot pass.
    EXPECT_EQ(f.stretches, static_cast<int>(ex.stretches.size()));
    EXPECT_GE(f.compared_ours, ex.min_compared_mm);
    EXPECT_GE(f.compared_linuxcnc, ex.min_compared_mm);
}

INSTANTIATE_TEST_SUITE_P(Examples, LinuxCncExamples, ::testing::ValuesIn(examples()),
                         [](const ::testing::TestParamInfo<Example>& info) {
                             std::string n;
                             for (char c : info.param.name)
                                 n += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                             return n;
                         });

// ---- LinuxCNC's lathe programs: a turning tool's imaginary tip (docs/linuxcnc-examples.md)

// One lathe program both ways: LinuxCNC's lathecomp.ngc (nc_files), and its regression test
// tests/ccomp/lathe-comp/test.ngc, which is lathecomp.ngc with G41 and G42 swapped (not in the
// package: made here, and checked against the file's SHA-256).
struct LatheExample {
    std::string name;
    bool swap_sides = false;        // made from lathecomp.ngc by swapping G41 and G42
    std::string sha256;             // of the original's text
    std::string program;            // ours, under the source tree
    std::size_t warnings = 0;       // SelfApproach warnings of our run
};

void PrintTo(const LatheExample& e, std::ostream* os) {
    *os << e.name;
}

std::vector<LatheExample> lathe_examples() {
    return {{"lathecomp", false,
             "a30716e99d35e02e72009538bd69eb97454278ce8cbbd5abf14c227b666bde5c",
             "examples/linuxcnc/lathecomp.nc", 0},
            {"lathe-comp", true,
             "d40314817adf2b47bfa3583c88eae224658a140988a43ed15542a1788d35742f",
             "examples/linuxcnc/lathe_comp.nc", 0}};
}

// The lines "g41" and "g42" swapped.
std::string swap_sides(const std::string& ngc) {
    std::string out;
    std::istringstream lines(ngc);
    for (std::string line; std::getline(lines, line);)
        out += (line == "g41" ? "g42" : line == "g42" ? "g41" : line) + "\n";
    return out;
}

// Our executed path in the turning plane G18: (Z, X), the third axis Y.
class LatheSink final : public apci::run::RunSink {
  public:
    void executed(const apci::run::PathSegment& s) override {
        CanonMove m;
        const Vec2 a(s.start.z(), s.start.x()), b(s.end.z(), s.end.x());
        m.path = s.kind == apci::run::SegmentKind::kArc
                     ? make_arc(a, b, {s.center.z(), s.center.x()}, s.ccw)
                     : make_line(a, b);
        m.rapid = s.kind == apci::run::SegmentKind::kRapid;
        m.third = s.end.y();
        moves.push_back(m);
    }
    std::vector<CanonMove> moves;
};

class LinuxCncLathe : public ::testing::TestWithParam<LatheExample> {};

// The whole path, every move of it (rapid moves, the first pass without compensation, the
// approach to each compensated pass, its contour, the move after G40), is LinuxCNC's within
// 1e-3 mm: move for move, the same kind (rapid, line, arc and its sense), the end points and arc
// centres within 1e-3 mm, and the Hausdorff distance of the two paths within 1e-3 mm. LinuxCNC
// controls a turning tool's imaginary tip (tool orientation Q2, Q7); so does ours, with the
// cutting edge position (srk_lage 2, 7).
TEST_P(LinuxCncLathe, TheWholePathIsLinuxCncsWithinAThousandthOfAMillimetre) {
    if (!rs274().why.empty()) GTEST_SKIP() << rs274().why;
    const LatheExample& ex = GetParam();
    std::string original = read_text(rs274().ncfiles + "/lathecomp.ngc");
    ASSERT_FALSE(original.empty()) << "cannot read " << rs274().ncfiles << "/lathecomp.ngc";
    if (ex.swap_sides) original = swap_sides(original);
    ASSERT_EQ(test_support::sha256_hex(original), ex.sha256)
        << ex.name << ": not the text of LinuxCNC's file";
    // T2, T7 and T9 of the lathe tool tables (tests/ccomp/lathe-comp/test.tbl): 0.1 in nose
    // diameter, orientation Q2 and Q7, no offsets (H9 is T9's).
    const std::string table = "T2 P2 Z0.0 X0.0 D0.1 Q2 ;\nT7 P7 Z0.0 X0.0 D0.1 Q7 ;\n"
                              "T9 P9 Z0.0 X0.0 D0.1 Q9 ;\n";
    const std::vector<Rs274Result> runs =
        run_rs274(rs274(), {original, inch_to_mm(original)}, table, 18, 2);
    for (std::size_t i = 0; i < runs.size(); ++i)
        ASSERT_TRUE(runs[i].ran && runs[i].exit_code == 0 && !runs[i].moves.empty())
            << "rs274 on " << ex.name << (i == 1 ? " (in mm)" : "") << ": exit "
            << runs[i].exit_code << " " << runs[i].error;
    const std::vector<CanonMove>& lc = runs[1].moves;
    {
        // The mm version makes the original's moves (within the two printed roundings).
        const std::vector<CanonMove>& in = runs[0].moves;
        ASSERT_EQ(in.size(), lc.size());
        for (std::size_t i = 0; i < lc.size(); ++i)
            EXPECT_LE((kInch * in[i].path.end - lc[i].path.end).cwiseAbs().maxCoeff(),
                      kPrintedRounding)
                << "move " << i;
    }

    auto tools = apci::nc::load_tool_table(std::string(kSourceDir) + "/examples/linuxcnc/lathe.tools");
    ASSERT_TRUE(tools) << tools.error().to_string();
    const std::string path = std::string(kSourceDir) + "/" + ex.program;
    LatheSink sink;
    const EmulatorRun run = run_on_emulator(read_text(path), path, tools.value(), sink);
    ASSERT_TRUE(run.error.empty()) << run.error;
    for (const apci::run::RunError& e : run.outcome.errors)
        ADD_FAILURE() << ex.program << ": line " << e.block.line << ": " << e.code << ": "
                      << e.message;
    for (const apci::run::RunError& w : run.outcome.warnings)
        EXPECT_EQ(w.code, "SelfApproach") << "line " << w.block.line << ": " << w.message;
    EXPECT_EQ(run.outcome.warnings.size(), ex.warnings);

    // Move for move (zero-length moves left out on both sides).
    const auto moving = [](const std::vector<CanonMove>& all) {
        std::vector<CanonMove> out;
        for (const CanonMove& m : all)
            if (length(m.path) > 1e-9) out.push_back(m);
        return out;
    };
    const std::vector<CanonMove> theirs = moving(lc), ours = moving(sink.moves);
    ASSERT_EQ(ours.size(), theirs.size()) << ex.name << ": moves";
    double worst_point = 0.0;
    std::vector<Element> their_path, our_path;
    for (std::size_t i = 0; i < theirs.size(); ++i) {
        const Element &a = ours[i].path, &b = theirs[i].path;
        EXPECT_EQ(ours[i].rapid, theirs[i].rapid) << "move " << i << ": " << element_text(a);
        EXPECT_EQ(is_arc(a), is_arc(b)) << "move " << i << ": " << element_text(a) << " vs "
                                       << element_text(b);
        if (is_arc(a) && is_arc(b)) {
            EXPECT_EQ(a.ccw, b.ccw) << "move " << i;
            worst_point = std::max(worst_point, (a.centre - b.centre).norm());
        }
        worst_point = std::max({worst_point, (a.start - b.start).norm(), (a.end - b.end).norm(),
                                std::abs(ours[i].third - theirs[i].third)});
        their_path.push_back(b);
        our_path.push_back(a);
    }
    const double dev = hausdorff(our_path, their_path, kSpacing);
    EXPECT_LE(worst_point, kMaxDeviation) << ex.name;
    EXPECT_LE(dev, kMaxDeviation) << ex.name;
    std::printf("%s: %zu moves alike, end points and centres within %.2e mm, whole path (%.3f mm) "
                "within %.2e mm of LinuxCNC's (limit %.0e)\n",
                ex.name.c_str(), ours.size(), worst_point, path_length(our_path), dev,
                kMaxDeviation);
    EXPECT_GT(path_length(our_path), 250.0);
}

INSTANTIATE_TEST_SUITE_P(Examples, LinuxCncLathe, ::testing::ValuesIn(lathe_examples()),
                         [](const ::testing::TestParamInfo<LatheExample>& info) {
                             std::string n;
                             for (char c : info.param.name)
                                 n += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                             return n;
                         });

}  // namespace
}  // namespace apci::test
