// SPDX-License-Identifier: MIT
#include "diff_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "apci/apci.hpp"
#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "apci/run/executor.h"
#include "apci/run/program_run.h"

namespace apci::test {
namespace {

using rwmos::geom::distance_to;
using rwmos::geom::is_arc;
using rwmos::geom::length;
using rwmos::geom::point_at;

std::string number(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    std::string s = buf;
    if (s.find_first_not_of("-0.") == std::string::npos) s = std::string(buf + (buf[0] == '-'));
    return s;
}

// "X.. Y.." (G17), "X.. Z.." (G18) or "Y.. Z.." (G19) of a plane point.
std::string axes(const DiffProgram& p, const Vec2& q) {
    if (p.plane == 18) return "X" + number(q.y(), p.decimals) + " Z" + number(q.x(), p.decimals);
    if (p.plane == 19) return "Y" + number(q.x(), p.decimals) + " Z" + number(q.y(), p.decimals);
    return "X" + number(q.x(), p.decimals) + " Y" + number(q.y(), p.decimals);
}

// I/J (G17), I/K (G18) or J/K (G19) of an arc: its centre from its start.
std::string centre_words(const DiffProgram& p, const Element& e) {
    const Vec2 d = e.centre - e.start;
    if (p.plane == 18) return "I" + number(d.y(), p.decimals) + " K" + number(d.x(), p.decimals);
    if (p.plane == 19) return "J" + number(d.x(), p.decimals) + " K" + number(d.y(), p.decimals);
    return "I" + number(d.x(), p.decimals) + " J" + number(d.y(), p.decimals);
}

std::string moves(const DiffProgram& p, const char* line_prefix) {
    std::string s;
    for (const Element& e : p.elements) {
        s += line_prefix;
        if (is_arc(e))
            s += std::string(e.ccw ? "G3 " : "G2 ") + axes(p, e.end) + " " + centre_words(p, e);
        else
            s += "G1 " + axes(p, e.end);
        s += "\n";
    }
    return s;
}

class Collector final : public apci::run::RunSink {
  public:
    explicit Collector(int plane) : plane_(plane) {}
    void executed(const apci::run::PathSegment& s) override {
        const apci::run::PlaneAxes a = apci::run::plane_axes(plane_);
        const Vec2 start(s.start[a.first], s.start[a.second]);
        const Vec2 end(s.end[a.first], s.end[a.second]);
        if (s.kind == apci::run::SegmentKind::kArc) {
            path.push_back(rwmos::geom::make_arc(start, end, {s.center[a.first], s.center[a.second]},
                                                 s.ccw));
        } else {
            path.push_back(rwmos::geom::make_line(start, end));
        }
        roles.push_back(static_cast<int>(s.role));
        lines.push_back(s.block.line);
    }
    std::vector<Element> path;
    std::vector<int> roles;
    std::vector<std::uint64_t> lines;

  private:
    int plane_;
};

// Where along an element (0..1) the point nearest p lies.
double fraction_at(const Element& e, const Vec2& p) {
    if (!is_arc(e)) {
        const Vec2 d = e.end - e.start;
        const double n2 = d.squaredNorm();
        return n2 == 0.0 ? 0.0 : std::clamp((p - e.start).dot(d) / n2, 0.0, 1.0);
    }
    const double turn = std::abs(rwmos::geom::sweep(e));
    const double along =
        rwmos::geom::angle_between(e.start - e.centre, p - e.centre, e.ccw);
    return std::clamp(along / turn, 0.0, 1.0);
}

// The piece of e from fraction t0 to t1.
Element piece(const Element& e, double t0, double t1) {
    Element out = e;
    out.start = point_at(e, t0);
    out.end = point_at(e, t1);
    if (is_arc(e) && t1 - t0 < 1.0 && (out.end - out.start).norm() < 1e-9)
        out = rwmos::geom::make_line(out.start, out.end);  // not a full circle by accident
    return out;
}

template <typename F>
void for_samples(const Element& e, double spacing, F&& f) {
    const int n = std::clamp(static_cast<int>(std::ceil(length(e) / spacing)), 1, 200000);
    for (int i = 0; i <= n; ++i) f(point_at(e, double(i) / n));
}

// A path with the bounding box of each element, to look at near elements only.
struct IndexedPath {
    explicit IndexedPath(const std::vector<Element>& path) : elements(path) {
        boxes.reserve(path.size());
        for (const Element& e : path) boxes.push_back(box_of(e, 0.0));
    }
    // The distance from p to the path, exact when it is at most `within` (else at least that).
    double distance(const Vec2& p, double within) const {
        double best = INFINITY;
        for (std::size_t i = 0; i < elements.size(); ++i) {
            const Box& b = boxes[i];
            if (p.x() < b.lo.x() - within || p.x() > b.hi.x() + within || p.y() < b.lo.y() - within ||
                p.y() > b.hi.y() + within)
                continue;
            best = std::min(best, distance_to(elements[i], p));
        }
        if (best <= within) return best;
        for (const Element& e : elements) best = std::min(best, distance_to(e, p));
        return best;
    }
    const std::vector<Element>& elements;
    std::vector<Box> boxes;
};

}  // namespace

std::string our_tool_list(double radius_mm) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "wz[1].gueltig 1\nwz[1].typ 0\nwz[1].mass_einheit 1\nwz[1].laenge 0\n"
                  "wz[1].radius %.17g\n",
                  radius_mm);
    return text;
}

std::string our_program(const DiffProgram& p) {
    std::string s = "%diff\n";
    s += "G" + std::to_string(p.plane) + " G90 " + (p.linear ? "G25" : "G26") + " D1 F600\n";
    s += "G0 " + axes(p, p.start) + "\n";
    s += std::string(p.left ? "G41" : "G42") + " G1 " + axes(p, p.entry_end) + "\n";
    s += moves(p, "");
    s += "G40 G1 " + axes(p, p.exit_end) + "\nM30\n";
    return s;
}

std::string linuxcnc_program(const DiffProgram& p) {
    std::string s = "G21 G" + std::to_string(p.plane) + " G90 G40 G49 G64\nT1 M6\nF600\n";
    s += "G0 " + axes(p, p.start) + "\n";
    s += std::string(p.left ? "G41" : "G42") + " G1 " + axes(p, p.entry_end) + "\n";
    s += moves(p, "");
    s += "G40 G1 " + axes(p, p.exit_end) + "\nM2\n";
    return s;
}

EmulatorRun run_on_emulator(std::string_view text, const std::string& name,
                            const apci::nc::ToolTable& tools, apci::run::RunSink& sink) {
    EmulatorRun out;
    apci::Board board("emu:");
    if (!board.is_open()) {
        out.error = "cannot open the embedded emulator";
        return out;
    }
    // As apcictl runs it (program_run.h), the check warning.
    apci::run::RunInputs inputs;
    inputs.tools = tools;
    inputs.tools_given = true;
    auto ran =
        apci::run::run_program(board, sink, inputs, apci::run::ProgramSource::in_memory(text, name),
                               apci::run::RunSettings{});
    if (!ran) {
        out.error = "program: " + ran.error().to_string();
        return out;
    }
    out.outcome = std::move(ran.value());
    return out;
}

OurRun run_ours(const DiffProgram& p) {
    OurRun out;
    const std::string tool_text = our_tool_list(p.r);
    auto tools = apci::nc::parse_tool_table(tool_text, "diff.tools");
    if (!tools) {
        out.error = "tool list: " + tools.error().to_string();
        return out;
    }
    Collector sink(p.plane);
    const EmulatorRun run = run_on_emulator(our_program(p), "diff.nc", tools.value(), sink);
    if (!run.error.empty()) {
        out.error = run.error;
        return out;
    }
    const apci::run::RunOutcome& result = run.outcome;
    out.path = std::move(sink.path);
    out.roles = std::move(sink.roles);
    out.lines = std::move(sink.lines);
    for (const apci::run::RunError& w : result.warnings) out.self_approach |= w.code == "SelfApproach";
    if (!result.errors.empty()) {
        out.error = result.errors.front().code + ": " + result.errors.front().message;
        out.error_line = result.errors.front().block.line;
        return out;
    }
    out.ok = true;
    return out;
}

std::vector<Element> window(const std::vector<Element>& path, const Vec2& from, const Vec2& to,
                            double tol) {
    std::size_t first = path.size(), last = path.size();
    for (std::size_t i = 0; i < path.size() && first == path.size(); ++i)
        if (length(path[i]) > 0 && distance_to(path[i], from) <= tol) first = i;
    for (std::size_t i = path.size(); i-- > 0 && last == path.size();)
        if (length(path[i]) > 0 && distance_to(path[i], to) <= tol) last = i;
    if (first == path.size() || last == path.size() || last < first) return {};
    const double t0 = fraction_at(path[first], from);
    const double t1 = fraction_at(path[last], to);
    std::vector<Element> out;
    if (first == last) {
        if (t1 >= t0) out.push_back(piece(path[first], t0, t1));
        return out;
    }
    out.push_back(piece(path[first], t0, 1.0));
    for (std::size_t i = first + 1; i < last; ++i) out.push_back(path[i]);
    out.push_back(piece(path[last], 0.0, t1));
    return out;
}

double hausdorff(const std::vector<Element>& a, const std::vector<Element>& b, double spacing) {
    double worst = 0.0;
    const IndexedPath ia(a), ib(b);
    for (const auto* pair : {&a, &b}) {
        const std::vector<Element>& from = *pair;
        const IndexedPath& other = pair == &a ? ib : ia;
        for (const Element& e : from)
            for_samples(e, spacing,
                        [&](const Vec2& q) { worst = std::max(worst, other.distance(q, 0.05)); });
    }
    return worst;
}

double clearance(const std::vector<Element>& path, const std::vector<Element>& contour, double r,
                 double spacing) {
    double least = INFINITY;
    const IndexedPath ic(contour);
    for (const Element& e : path)
        for_samples(e, spacing,
                    [&](const Vec2& q) { least = std::min(least, ic.distance(q, r + 0.01)); });
    return least;
}

}  // namespace apci::test
