// SPDX-License-Identifier: MIT
#include "cam_programs.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "rng.h"

namespace apci::test {
namespace {

using V = Eigen::Vector2d;
constexpr double kPi = std::numbers::pi;
constexpr double kTop = 0.0;   // the part's top (Z)
constexpr double kSafe = 5.0;  // rapids run at this height

// Every tool-centre point the generator plans keeps at least this much more than r from the
// walls it must not touch (far beyond rounding to 3 decimals, 7.1e-4 mm).
constexpr double kMargin = 0.02;
// A designed gouge is at least this deep (the path tolerance 1e-4 plus 2e-3, plus what
// rounding to 3 decimals can move a depth by); a pair whose depth the draw decides (a fillet
// beside a gap) is at least this far from 0 either way.
constexpr double kGougeDepthMin = 0.006;
// Where a planned path touches a wall by design (a lead's tool at r from the contour where it
// joins it): the checks measure densified walls, whose chords lie up to twice the oracle's chord
// error from the curves.
constexpr double kTouch = 2 * StockOracle::kChordError;

V left(const V& v) {
    return {-v.y(), v.x()};
}
V right(const V& v) {
    return {v.y(), -v.x()};
}
V unit_at(double a) {
    return {std::cos(a), std::sin(a)};
}
V rotated(const V& v, double a) {
    return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()};
}

// A length as the descriptions write it.
std::string mm(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3f", v);
    return buf;
}

// ---- Exact design elements (before rounding).

struct Elem {
    bool arc = false;
    V a = V::Zero(), b = V::Zero(), c = V::Zero();
    bool ccw = false;
};
using Loop = std::vector<Elem>;

Elem seg(const V& a, const V& b) {
    return {false, a, b, V::Zero(), false};
}
Elem arc_elem(const V& a, const V& b, const V& c, bool ccw) {
    return {true, a, b, c, ccw};
}
// The direction of travel at a point of an arc.
V arc_tangent(const V& p, const V& c, bool ccw) {
    const V r = (p - c).normalized();
    return ccw ? left(r) : right(r);
}
V start_tangent(const Elem& e) {
    return e.arc ? arc_tangent(e.a, e.c, e.ccw) : V((e.b - e.a).normalized());
}
V end_tangent(const Elem& e) {
    return e.arc ? arc_tangent(e.b, e.c, e.ccw) : V((e.b - e.a).normalized());
}
Loop reversed(const Loop& l) {
    Loop out;
    out.reserve(l.size());
    for (std::size_t i = l.size(); i-- > 0;) {
        const Elem& e = l[i];
        out.push_back({e.arc, e.b, e.a, e.c, !e.ccw});
    }
    return out;
}
// Turned about the origin by `angle`, then moved by `by`.
Elem placed(const Elem& e, double angle, const V& by) {
    return {e.arc, rotated(e.a, angle) + by, rotated(e.b, angle) + by, rotated(e.c, angle) + by,
            e.ccw};
}
Loop placed(const Loop& l, double angle, const V& by) {
    Loop out;
    for (const Elem& e : l) out.push_back(placed(e, angle, by));
    return out;
}
V placed(const V& p, double angle, const V& by) {
    return rotated(p, angle) + by;
}

// The oracle's geometry for the generator's own checks.
Pt pt(const V& v) {
    return {v.x(), v.y()};
}
std::vector<Pt> points_of(const Elem& e) {
    WallElement w;
    w.arc = e.arc;
    w.start = pt(e.a);
    w.end = pt(e.b);
    w.centre = pt(e.c);
    w.ccw = e.ccw;
    return densify(w);
}
std::vector<Pt> points_of(const std::vector<V>& polyline) {
    std::vector<Pt> out;
    out.reserve(polyline.size());
    for (const V& v : polyline) out.push_back(pt(v));
    return out;
}
// The points of the arc about c from p to q in the given sense.
std::vector<V> arc_points(const V& p, const V& q, const V& c, bool ccw) {
    std::vector<V> out;
    for (const Pt& x : points_of(arc_elem(p, q, c, ccw))) out.emplace_back(x.x, x.y);
    return out;
}

// ---- Filleted polygons: closed loops of lines with an arc of radius rho[i] at vertex i (0:
// sharp), starting at the middle of edge 0 (v0 -> v1). reserve[i] is the length each edge next
// to vertex i keeps straight beyond the fillet (the compensation's trim at an inside corner,
// r tan(turn / 2)). None when an edge is too short for its corners.
struct Polygon {
    Loop loop;
    std::vector<std::size_t> edge;  // the element of edge i (edge 0: its second half, loop[0])
};
std::optional<Polygon> filleted_polygon(const std::vector<V>& v, const std::vector<double>& rho,
                                        const std::vector<double>& reserve, double min_straight) {
    const std::size_t n = v.size();
    std::vector<V> u(n);  // direction of edge i (v[i] -> v[i+1])
    for (std::size_t i = 0; i < n; ++i) u[i] = (v[(i + 1) % n] - v[i]).normalized();
    std::vector<double> tangent(n), keep(n);
    std::vector<double> turn(n);
    for (std::size_t i = 0; i < n; ++i) {
        const V& in = u[(i + n - 1) % n];
        const V& out = u[i];
        turn[i] = std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out));
        if (std::abs(turn[i]) > kPi - 0.05) return std::nullopt;  // a reversal: no fillet
        tangent[i] = rho[i] * std::tan(std::abs(turn[i]) / 2);
        keep[i] = std::max(tangent[i], reserve[i]);
    }
    for (std::size_t i = 0; i < n; ++i) {
        const double len = (v[(i + 1) % n] - v[i]).norm();
        if (len < keep[i] + keep[(i + 1) % n] + min_straight) return std::nullopt;
    }
    // Edge i's straight part runs from v[i] + tangent[i] u[i] to v[i+1] - tangent[i+1] u[i].
    auto fillet = [&](std::size_t i, Loop& out) {
        if (rho[i] <= 0) return;
        const V& in = u[(i + n - 1) % n];
        const V p = v[i] - tangent[i] * in;
        const V q = v[i] + tangent[i] * u[i];
        const V c = p + rho[i] * (turn[i] > 0 ? left(in) : right(in));
        out.push_back(arc_elem(p, q, c, turn[i] > 0));
    };
    // The start: the middle of edge 0 between what its corners keep.
    const V c0 = (v[0] + keep[0] * u[0] + v[1] - keep[1] * u[0]) / 2;
    Polygon out;
    out.edge.assign(n, 0);
    Loop& loop = out.loop;
    loop.push_back(seg(c0, v[1] - tangent[1] * u[0]));
    for (std::size_t k = 1; k <= n; ++k) {
        const std::size_t i = k % n;
        fillet(i, loop);
        const V from = v[i] + tangent[i] * u[i];
        if (i == 0) {
            loop.push_back(seg(from, c0));
        } else {
            out.edge[i] = loop.size();
            loop.push_back(seg(from, v[(i + 1) % n] - tangent[(i + 1) % n] * u[i]));
        }
    }
    return out;
}

// The turn at each vertex of a polygon (counter-clockwise positive).
std::vector<double> vertex_turns(const std::vector<V>& v) {
    const std::size_t n = v.size();
    std::vector<double> t(n);
    for (std::size_t i = 0; i < n; ++i) {
        const V in = (v[i] - v[(i + n - 1) % n]).normalized();
        const V out = (v[(i + 1) % n] - v[i]).normalized();
        t[i] = std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out));
    }
    return t;
}

// ---- The NC text, rounded as written.

class NcWriter {
  public:
    NcWriter(int decimals, bool numbered, bool modal)
        : decimals_(decimals),
          numbered_(numbered),
          modal_(modal),
          scale_(std::pow(10.0, decimals)) {}

    double round(double v) const { return std::round(v * scale_) / scale_; }
    V round(const V& p) const { return {round(p.x()), round(p.y())}; }
    std::string num(double v) const {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.*f", decimals_, round(v));
        std::string s = buf;
        if (s.find_first_not_of("-0.") == std::string::npos && s[0] == '-') s.erase(0, 1);
        return s;
    }

    // A line that is no block (a comment, the program name).
    void text_line(const std::string& s) {
        text_ += s + "\n";
        ++line_;
        radius_by_line_.push_back(radius_);
    }
    // A block; returns where it is.
    run::BlockRef block(const std::string& words) {
        run::BlockRef ref{run::kNoBlock, line_ + 1};
        std::string s;
        if (numbered_) {
            next_n_ += 10;
            ref.number = next_n_;
            s = "N" + std::to_string(next_n_) + " ";
            numbers_.emplace_back(next_n_, line_ + 1);
        }
        text_line(s + words);
        return ref;
    }
    void set_radius(double r) { radius_ = r; }

    // Moves. The current point is kept as written (rounded).
    run::BlockRef rapid(const V& p) { return motion("G0", "", p, std::nullopt, nullptr); }
    run::BlockRef rapid_z(double z) {
        motion_ = "G0";
        return block("G0 Z" + num(z));
    }
    run::BlockRef feed_z(double z) {
        std::string w = (modal_ && motion_ == "G1") ? "" : "G1 ";
        motion_ = "G1";
        return block(w + "Z" + num(z));
    }
    // A line or an arc to e.b (from where the writer stands, e.a rounded), with words before the
    // motion ("G41", "G40"). `written` (may be null) gets the element as written.
    run::BlockRef move(const Elem& e, const std::string& prefix, WallElement* written) {
        if (!e.arc) return motion("G1", prefix, e.b, std::nullopt, written);
        return motion(e.ccw ? "G3" : "G2", prefix, e.b, e.c, written);
    }
    std::string text() const { return text_; }
    std::uint64_t line() const { return line_; }
    std::vector<double> radius_by_line() const { return radius_by_line_; }
    std::vector<std::pair<std::int64_t, std::uint64_t>> numbers() const { return numbers_; }

  private:
    run::BlockRef motion(const std::string& g, const std::string& prefix, const V& to,
                         std::optional<V> centre, WallElement* written) {
        const V end = round(to);
        std::string w = prefix.empty() ? "" : prefix + " ";
        if (!modal_ || motion_ != g || !prefix.empty()) w += g + " ";
        if (!modal_ || end.x() != pos_.x() || !have_pos_) w += "X" + num(end.x()) + " ";
        if (!modal_ || end.y() != pos_.y() || !have_pos_) w += "Y" + num(end.y()) + " ";
        V c = V::Zero();
        if (centre) {
            const V ij = round(V(*centre - pos_));
            c = pos_ + ij;
            w += "I" + num(ij.x()) + " J" + num(ij.y()) + " ";
        }
        w.pop_back();
        if (written) {
            written->arc = centre.has_value();
            written->start = pt(pos_);
            written->end = pt(end);
            written->centre = pt(c);
            written->ccw = g == "G3";
        }
        const run::BlockRef ref = block(w);
        if (written) written->block = ref;
        motion_ = g;
        pos_ = end;
        have_pos_ = true;
        return ref;
    }

    int decimals_;
    bool numbered_;
    bool modal_;
    double scale_;
    std::string text_;
    std::uint64_t line_ = 0;
    std::int64_t next_n_ = 0;
    double radius_ = 0.0;
    std::vector<double> radius_by_line_{0.0};  // [0]: no line
    std::vector<std::pair<std::int64_t, std::uint64_t>> numbers_;
    std::string motion_;
    V pos_ = V::Zero();
    bool have_pos_ = false;
};

// ---- Plans: what a program will do, checked before it is written.

enum class Side { kLeft, kRight };  // G41, G42
std::string side_word(Side s) {
    return s == Side::kLeft ? "G41" : "G42";
}
MaterialSide material_of(Side s) {  // the material is on the other side of the tool
    return s == Side::kLeft ? MaterialSide::kRight : MaterialSide::kLeft;
}
enum class LeadKind { kLineArc, kLine, kArc };
const char* lead_name(LeadKind k) {
    return k == LeadKind::kLineArc ? "line+arc" : k == LeadKind::kLine ? "line" : "arc";
}

struct Lead {
    LeadKind kind = LeadKind::kLineArc;
    double rl = 0;           // arc radius
    double sweep = kPi / 2;  // arc angle
    double len = 0;          // line length
    double beta = kPi / 2;   // line only: its angle to the contour
};

// A contour to be milled, as it will be written: oriented for its side, starting at a smooth
// point C0 = loop[0].a.
struct Contour {
    std::string what;
    Loop loop;
    bool tool_inside = true;  // a pocket's wall (the tool inside the loop) or a boss's
    Side side = Side::kLeft;
    bool wall = true;      // its elements are walls of the design part
    bool flipped = false;  // written in the other sense than it was built
    // The element of the built (counter-clockwise) loop's element i.
    std::size_t index_of(std::size_t i) const { return flipped ? loop.size() - 1 - i : i; }
};

// Orients a counter-clockwise loop for the tool's side.
Contour make_contour(std::string what, const Loop& ccw_loop, bool tool_inside, Side side,
                     bool wall = true) {
    const bool want_ccw = tool_inside == (side == Side::kLeft);
    return {std::move(what), want_ccw ? ccw_loop : reversed(ccw_loop), tool_inside, side, wall,
            !want_ccw};
}

// A planned piece of tool-centre path and the clearance it needs: `need` from every wall but
// the exempt ones, `need_exempt` from those (the elements meeting at the contour's start, which
// a lead touches by design).
struct Check {
    std::vector<V> path;
    double need = 0;
    std::vector<std::size_t> exempt;
    double need_exempt = 0;
    std::string what;
    int owner = -1;  // the contour it belongs to: measured against the design's walls and its own
};

// A wall the checks measure against: the design part's, or a contour's that is not (an inner
// loop of a pocket cleared in stepovers, which only its own leads must clear).
struct PlanWall {
    Elem e;
    int owner = -1;
    bool design = true;
};

struct Tool {
    int number = 0;
    double r = 0;
};

// Where the writer put each element of a planned contour.
struct WrittenContour {
    std::vector<WallElement> elements;
    run::BlockRef lead_in;  // the lead-in's first block (its line, or the arc)
    bool written = false;
};

struct Emit {
    explicit Emit(NcWriter w) : nc(std::move(w)) {}
    NcWriter nc;
    std::vector<WrittenContour> contours;
    std::vector<CamFeature> features;
    int tool = -1;
    void use_tool(const Tool& t) {
        if (t.number == tool) return;
        nc.set_radius(t.r);
        nc.block("D" + std::to_string(t.number));
        tool = t.number;
    }
    void begin_feature(std::string what, const Tool& t) {
        features.push_back({std::move(what), nc.line() + 1, 0, t.number, t.r});
    }
    void end_feature() { features.back().last_line = nc.line(); }
};

// An element of a planned contour: for designed gouges.
struct ElemRef {
    int contour = -1;
    std::size_t index = 0;
};

struct Plan {
    std::vector<PlanWall> walls;  // every exact wall (and what else the leads must clear)
    std::vector<Check> checks;
    std::vector<Contour> contours;  // by id
    std::vector<std::function<void(Emit&)>> steps;
    std::vector<std::pair<ElemRef, ElemRef>> designed;  // (path element, wall element)
    std::vector<double> designed_depth;
    std::vector<ElemRef> refusals;  // elements whose line a refusal may name
    bool plate = false;             // pockets: the design part is a plate around them
    bool feasible = true;  // false: a planned element cannot hold what it must (drawn again)

    std::vector<std::size_t> first_wall;  // by contour id: its first element in `walls`
    std::vector<Tool> tools;              // every tool used, once

    int add_contour(const Contour& c) {
        contours.push_back(c);
        first_wall.push_back(walls.size());
        walls_of(c);
        return static_cast<int>(contours.size()) - 1;
    }
    void walls_of(const Contour& c) {
        const int owner = static_cast<int>(contours.size()) - 1;
        for (const Elem& e : c.loop) walls.push_back({e, owner, c.wall});
    }
    void use(const Tool& t) {
        for (const Tool& u : tools)
            if (u.number == t.number) return;
        tools.push_back(t);
    }
    // The check of a contour's lead-in line (to let it cross what it is designed to cross).
    Check* lead_in_check(int id) {
        for (Check& c : checks)
            if (c.owner == id && c.what == "lead-in line") return &c;
        return nullptr;
    }
};

// Every check against every wall it is measured against: nothing when all hold, else the first
// that does not.
std::optional<std::string> failed_check(const Plan& plan) {
    if (!plan.feasible) return "an element too short for its corners";
    std::vector<std::vector<Pt>> walls;
    for (const PlanWall& w : plan.walls) walls.push_back(points_of(w.e));
    for (const Check& c : plan.checks) {
        const std::vector<Pt> path = points_of(c.path);
        for (std::size_t i = 0; i < walls.size(); ++i) {
            if (!plan.walls[i].design && plan.walls[i].owner != c.owner) continue;
            const bool exempt = std::find(c.exempt.begin(), c.exempt.end(), i) != c.exempt.end();
            const double need = exempt ? c.need_exempt : c.need;
            const double d = least_distance(path, walls[i]).distance;
            if (d < need) return c.what + " " + mm(d) + " from a wall, needs " + mm(need);
        }
    }
    return std::nullopt;
}

// The lead's geometry about the contour's start.
struct LeadGeom {
    Lead in, out;
    V c0, t, n;        // start, its direction, the normal to the tool's side
    double sense = 1;  // +1: lead arcs counter-clockwise (G41)
    V p0, s, cl;       // lead-in: start, arc start, arc centre
    V e, p3, cl_out;   // lead-out: arc end, line end, arc centre
};

V side_normal(const V& dir, Side side) {
    return side == Side::kLeft ? left(dir) : right(dir);
}

// Plans the leads of a contour whose first element starts at a smooth point, and the checks
// that keep their tool-centre path clear of every wall (the walls at the start touched only
// where the path joins the contour).
LeadGeom plan_leads(Plan& plan, int id, const Contour& c, const Lead& in, const Lead& out, double r,
                    std::size_t first_wall, std::size_t wall_count) {
    LeadGeom g;
    g.in = in;
    g.out = out;
    g.c0 = c.loop.front().a;
    g.t = start_tangent(c.loop.front());
    if ((end_tangent(c.loop.back()) - g.t).norm() > 1e-9 || (c.loop.back().b - g.c0).norm() > 1e-9)
        throw std::logic_error("cam_programs: a contour that does not close smoothly at its start");
    g.n = side_normal(g.t, c.side);
    g.sense = c.side == Side::kLeft ? 1.0 : -1.0;
    const bool ccw = g.sense > 0;
    const std::vector<std::size_t> at_start{first_wall, first_wall + wall_count - 1};
    auto clear = [&](std::vector<V> path, double need, double need_at_start, std::string what) {
        plan.checks.push_back(
            {std::move(path), need, at_start, need_at_start, std::move(what), id});
    };
    // The arc of radius rl tangent to the contour at C0 on the tool's side: its centre, and
    // the disc of radius rl about it, which holds every tool position along the arc.
    auto lead_circle = [&](double rl) {
        V cl = g.c0 + rl * g.n;
        clear({cl}, rl + kMargin, rl - kTouch, "lead arc");
        return cl;
    };
    switch (in.kind) {
        case LeadKind::kLineArc:
        case LeadKind::kArc: {
            g.cl = lead_circle(in.rl);
            g.s = g.cl + rotated(g.c0 - g.cl, -g.sense * in.sweep);
            const V ds = arc_tangent(g.s, g.cl, ccw);
            if (in.kind == LeadKind::kLineArc) {
                g.p0 = g.s - in.len * ds;
                // The approach: from the tool's position to the lead line's compensated end.
                clear({g.p0, V(g.s + r * side_normal(ds, c.side))}, r + kMargin, r + kMargin,
                      "lead-in line");
            } else {
                g.p0 = g.s;
                // LinuxCNC's entry arc: about the point on the line from the arc's
                // compensated end to its centre as far from the tool as from that end.
                const V end = g.c0 + r * g.n;
                const V u = (g.cl - end).normalized();
                const V d = g.s - end;
                const double q = d.squaredNorm() / (2 * d.dot(u));
                clear(arc_points(g.s, end, V(end + q * u), ccw), r + kMargin, r - kTouch,
                      "entry arc");
                clear({g.s}, r + kMargin, r + kMargin, "arc lead start");
            }
            break;
        }
        case LeadKind::kLine: {
            const V d = std::cos(in.beta) * g.t - std::sin(in.beta) * g.n;  // into C0
            g.p0 = g.c0 - in.len * d;
            // The corner with the first element is an inside one: the approach ends where the
            // lead's offset meets the first element's.
            const V a = g.c0 + r * side_normal(d, c.side);
            const V b = g.c0 + r * g.n;
            // a + s d = b + u t
            const double det = d.x() * (-g.t.y()) - d.y() * (-g.t.x());
            const V rhs = b - a;
            const double u = (d.x() * rhs.y() - d.y() * rhs.x()) / det;
            const V trim = b + u * g.t;
            clear({g.p0, trim}, r + kMargin, r - kTouch, "lead-in line");
            // The first element keeps its trim and its own end's.
            const Elem& first = c.loop.front();
            if (first.arc || u < 0 || (first.b - first.a).norm() < u + r + 0.2)
                plan.feasible = false;
            break;
        }
    }
    switch (out.kind) {
        case LeadKind::kLineArc:
        case LeadKind::kArc: {
            g.cl_out = lead_circle(out.rl);
            g.e = g.cl_out + rotated(g.c0 - g.cl_out, g.sense * out.sweep);
            const V de = arc_tangent(g.e, g.cl_out, ccw);
            const V e_off = g.e + r * side_normal(de, c.side);
            if (out.kind == LeadKind::kLineArc) {
                g.p3 = g.e + out.len * de;
                clear({e_off, g.p3}, r + 1e-3, r + 1e-3, "lead-out line");
            }
            break;
        }
        case LeadKind::kLine: {
            const V d = std::cos(out.beta) * g.t + std::sin(out.beta) * g.n;  // away from C0
            g.p3 = g.c0 + out.len * d;
            clear({V(g.c0 + r * g.n), g.p3}, r + kMargin, r - kTouch, "lead-out line");
            break;
        }
    }
    return g;
}

// Writes a planned contour with its leads at one level: rapid above the start, plunge, lead in,
// the contour, lead out, retract.
void write_contour(Emit& e, int id, const Contour& c, const LeadGeom& g, double level) {
    NcWriter& nc = e.nc;
    const bool ccw = g.sense > 0;
    nc.rapid_z(kSafe);
    nc.rapid(g.p0);
    nc.feed_z(level);
    run::BlockRef lead_in;
    switch (g.in.kind) {
        case LeadKind::kLineArc:
            lead_in = nc.move(seg(g.p0, g.s), side_word(c.side), nullptr);
            nc.move(arc_elem(g.s, g.c0, g.cl, ccw), "", nullptr);
            break;
        case LeadKind::kLine:
            lead_in = nc.move(seg(g.p0, g.c0), side_word(c.side), nullptr);
            break;
        case LeadKind::kArc:
            nc.block(side_word(c.side));
            lead_in = nc.move(arc_elem(g.s, g.c0, g.cl, ccw), "", nullptr);
            break;
    }
    WrittenContour& w = e.contours[static_cast<std::size_t>(id)];
    if (!w.written) w.lead_in = lead_in;
    std::vector<WallElement> elements(c.loop.size());
    for (std::size_t k = 0; k < c.loop.size(); ++k) nc.move(c.loop[k], "", &elements[k]);
    if (!w.written) {
        w.elements = std::move(elements);
        w.written = true;
    }
    switch (g.out.kind) {
        case LeadKind::kLineArc:
            nc.move(arc_elem(g.c0, g.e, g.cl_out, ccw), "", nullptr);
            nc.move(seg(g.e, g.p3), "G40", nullptr);
            nc.rapid_z(kSafe);
            break;
        case LeadKind::kLine:
            nc.move(seg(g.c0, g.p3), "G40", nullptr);
            nc.rapid_z(kSafe);
            break;
        case LeadKind::kArc:
            nc.move(arc_elem(g.c0, g.e, g.cl_out, ccw), "", nullptr);
            nc.rapid_z(kSafe);  // lifted under G41/G42, as LinuxCNC's examples leave
            nc.block("G40");
            break;
    }
}

// Draws a lead of the given kind for a tool of radius r.
Lead draw_lead(Rng& rng, LeadKind kind, double r) {
    Lead l;
    l.kind = kind;
    l.rl = r + std::max(0.1, 0.1 * r) + rng.uniform(0.0, std::max(1.0, r));
    l.sweep = rng.chance(0.7) ? kPi / 2 : rng.uniform(kPi / 4, kPi / 2);
    l.len = rng.uniform(0.5, 2 * r + 5);
    l.beta = rng.chance(0.6) ? kPi / 2 : rng.uniform(kPi / 3, kPi / 2);
    return l;
}

// Plans a contour feature with leads at the given levels: its walls, its checks, its writing.
int plan_feature(Plan& plan, const Contour& c, const Lead& in, const Lead& out, const Tool& tool,
                 const std::vector<double>& levels) {
    const int id = plan.add_contour(c);
    plan.use(tool);
    const LeadGeom g =
        plan_leads(plan, id, c, in, out, tool.r, plan.first_wall.back(), c.loop.size());
    std::string what = c.what + ", " + side_word(c.side) + ", leads " + lead_name(in.kind) + "/" +
                       lead_name(out.kind);
    plan.steps.emplace_back([=](Emit& e) {
        e.use_tool(tool);
        e.begin_feature(what, tool);
        for (const double z : levels) write_contour(e, id, c, g, z);
        e.end_feature();
    });
    return id;
}

// ---- Shapes: counter-clockwise loops about the origin, starting at a smooth point.

struct Shape {
    std::string what;
    Loop loop;
    bool straight_start = true;     // loop[0] is a line (straight leads can trim into it)
    std::vector<std::size_t> edge;  // filleted polygons: the element of each edge
};

// A fillet radius for a corner where the tool is inside (the compensation trims it: sharp, or
// a radius the tool fits with a margin) or outside (any).
double inside_fillet(Rng& rng, double r, double most) {
    const double least = r + std::max(kMargin, 0.05 * r);
    if (rng.chance(0.4) || most < least + 0.01) return 0.0;
    return rng.uniform(least, most);
}
double outside_fillet(Rng& rng, double most) {
    if (rng.chance(0.4) || most < 0.3) return 0.0;
    return rng.uniform(0.2, most);
}

// A polygon's fillets and the trims its inside corners need: inside corners are those turning
// towards the tool (left turns of a counter-clockwise loop for a pocket, right turns for a boss).
// An inside corner turning less than 45 degrees stays sharp: its fillet would be a short concave
// arc, and rounding makes a short arc a spiral (its radius changing by up to 2e-3 mm over a
// small angle) whose compensated path, r less than its radius, comes nearer than r to the arc
// by about r k^2 / (2 R (R - r)) (k the change of radius per radian): beyond the path
// tolerance where the tool nearly fills the arc.
void corners_for(Rng& rng, const std::vector<V>& v, double r, bool pocket, double most,
                 std::vector<double>& rho, std::vector<double>& reserve) {
    const std::vector<double> turn = vertex_turns(v);
    rho.assign(v.size(), 0.0);
    reserve.assign(v.size(), 0.0);
    for (std::size_t i = 0; i < v.size(); ++i) {
        const bool inside = (turn[i] > 0) == pocket;
        rho[i] = !inside                        ? outside_fillet(rng, most)
                 : std::abs(turn[i]) >= kPi / 4 ? inside_fillet(rng, r, most)
                                                : 0.0;
        if (inside) reserve[i] = r * std::tan(std::abs(turn[i]) / 2);
    }
}

std::optional<Shape> from_polygon(std::string what, const std::vector<V>& v,
                                  const std::vector<double>& rho,
                                  const std::vector<double>& reserve) {
    auto p = filleted_polygon(v, rho, reserve, 0.2);
    if (!p) return std::nullopt;
    return Shape{std::move(what), std::move(p->loop), true, std::move(p->edge)};
}

// The vertices of a rectangle [x0, x1] x [y0, y1], counter-clockwise, edge 0 the given side
// (0 bottom, 1 right, 2 top, 3 left).
std::vector<V> rectangle(double x0, double y0, double x1, double y1, int first_side) {
    std::vector<V> v{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    std::rotate(v.begin(), v.begin() + first_side, v.end());
    return v;
}

std::optional<Shape> rounded_rectangle(Rng& rng, double r, bool pocket) {
    const double a = pocket ? rng.uniform(r + 1.0, r + 30) : rng.uniform(1.0, 30);
    const double b = pocket ? rng.uniform(r + 1.0, r + 20) : rng.uniform(1.0, 20);
    const std::vector<V> v = rectangle(-a, -b, a, b, 0);
    std::vector<double> rho, reserve;
    corners_for(rng, v, r, pocket, std::min(a, b) - 0.2, rho, reserve);
    return from_polygon("rounded rectangle " + mm(2 * a) + " x " + mm(2 * b), v, rho, reserve);
}

std::optional<Shape> slot(Rng& rng, double r, bool pocket) {
    const double half = rng.uniform(0.5, 25);
    const double rad = pocket ? rng.uniform(r + 0.5, r + 12) : rng.uniform(0.5, 15);
    Shape s{"slot " + mm(2 * (half + rad)) + " x " + mm(2 * rad), {}, true, {}};
    s.loop = {seg({0, -rad}, {half, -rad}), arc_elem({half, -rad}, {half, rad}, {half, 0}, true),
              seg({half, rad}, {-half, rad}),
              arc_elem({-half, rad}, {-half, -rad}, {-half, 0}, true),
              seg({-half, -rad}, {0, -rad})};
    return s;
}

std::optional<Shape> circle(Rng& rng, double r, bool pocket, double radius = 0) {
    const double R = radius > 0 ? radius
                     : pocket   ? rng.uniform(r + 1.0, r + 30)
                                : rng.uniform(0.5, 30);
    const int pieces = rng.chance(0.4) ? 1 : rng.chance(0.5) ? 2 : 4;
    const double a0 = rng.uniform(0, 2 * kPi);
    Shape s{
        "circle " + mm(2 * R) + " in " + std::to_string(pieces) + (pieces == 1 ? " arc" : " arcs"),
        {},
        false,
        {}};
    for (int k = 0; k < pieces; ++k) {
        const V p = R * unit_at(a0 + 2 * kPi * k / pieces);
        const V q = R * unit_at(a0 + 2 * kPi * (k + 1) / pieces);
        s.loop.push_back(arc_elem(p, pieces == 1 ? p : q, V::Zero(), true));
    }
    return s;
}

std::optional<Shape> polygon(Rng& rng, double r, bool pocket) {
    const int n = rng.integer(3, 7);
    const double ax = pocket ? rng.uniform(r + 3, r + 30) : rng.uniform(2, 30);
    const double ay = pocket ? rng.uniform(r + 3, r + 30) : rng.uniform(2, 30);
    std::vector<V> v;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * kPi * (i + rng.uniform(0.15, 0.85)) / n;
        v.emplace_back(ax * std::cos(a), ay * std::sin(a));
    }
    std::vector<double> rho, reserve;
    corners_for(rng, v, r, pocket, std::min(ax, ay) / 2, rho, reserve);
    return from_polygon(
        std::to_string(n) + "-gon " + mm(2 * ax) + " x " + mm(2 * ay) + " with fillets", v, rho,
        reserve);
}

// A pocket of two rooms joined by a passage of width w (along x): room 1 [0, a] x [-h1, h1],
// the passage [a, b] x [-w/2, w/2], room 2 [b, c] x [-h2, h2]. Edge 2 is the passage's
// bottom wall, edge 8 its top wall.
std::optional<Shape> rooms(Rng& rng, double r, double w, bool sharp_junctions) {
    const double a = rng.uniform(2 * r + 2, 2 * r + 25);
    const double b = a + rng.uniform(0.5, 20);
    const double c = b + rng.uniform(2 * r + 0.5, 2 * r + 25);
    const double h1 = w / 2 + rng.uniform(r + 2, r + 20);
    const double h2 = w / 2 + rng.uniform(r + 0.5, r + 20);
    const std::vector<V> v{{0, -h1}, {a, -h1}, {a, -w / 2}, {b, -w / 2}, {b, -h2}, {c, -h2},
                           {c, h2},  {b, h2},  {b, w / 2},  {a, w / 2},  {a, h1},  {0, h1}};
    std::vector<double> rho, reserve;
    corners_for(rng, v, r, true, std::min(h1, h2) / 2, rho, reserve);
    if (sharp_junctions)
        for (const int i : {2, 3, 8, 9}) rho[static_cast<std::size_t>(i)] = 0;
    return from_polygon("two rooms joined by a passage " + mm(w) + " wide, " + mm(b - a) + " long",
                        v, rho, reserve);
}

// A boss [-a, a] x [-bh, bh] with a keyhole from its top: a channel of width w down to a round
// chamber of radius rc. The channel's walls are the elements at indices `right_wall` and
// `left_wall`.
struct Keyhole {
    Shape shape;
    std::size_t right_wall = 0, left_wall = 0;
};
std::optional<Keyhole> keyhole(Rng& rng, double r, double w) {
    const double rc = std::max(r + 0.3, w / 2 + 0.5) + rng.uniform(0.0, 6.0);
    // The channel, from the top edge to the chamber: longer than r, so that the tool at its
    // entry and at its junctions with the chamber comes near only the walls across.
    const double depth = rng.uniform(r + 0.5, r + 10);
    const double a = rc + rng.uniform(1.5, 15);
    const double below = rng.uniform(1.0, 10);  // material under the chamber
    const double bh = (depth + std::sqrt(rc * rc - w * w / 4) + rc + below) / 2;
    const double yj = bh - depth;                           // where the channel meets the chamber
    const double yc = yj - std::sqrt(rc * rc - w * w / 4);  // the chamber's centre
    std::array<double, 4> rho{};  // bottom left, bottom right, top right, top left
    for (double& x : rho) x = outside_fillet(rng, std::min({bh, a - w / 2 - 0.5, a}) * 0.8);
    if (a - rho[2] - w / 2 < 0.3 || a - rho[3] - w / 2 < 0.3) return std::nullopt;
    Keyhole k;
    Loop& l = k.shape.loop;
    auto corner = [&](const V& p, const V& q, const V& c) {
        if ((p - q).norm() > 1e-12) l.push_back(arc_elem(p, q, c, true));
    };
    l.push_back(seg({0, -bh}, {a - rho[1], -bh}));
    corner({a - rho[1], -bh}, {a, -bh + rho[1]}, {a - rho[1], -bh + rho[1]});
    l.push_back(seg({a, -bh + rho[1]}, {a, bh - rho[2]}));
    corner({a, bh - rho[2]}, {a - rho[2], bh}, {a - rho[2], bh - rho[2]});
    l.push_back(seg({a - rho[2], bh}, {w / 2, bh}));
    k.right_wall = l.size();
    l.push_back(seg({w / 2, bh}, {w / 2, yj}));
    l.push_back(arc_elem({w / 2, yj}, {-w / 2, yj}, {0, yc}, false));
    k.left_wall = l.size();
    l.push_back(seg({-w / 2, yj}, {-w / 2, bh}));
    l.push_back(seg({-w / 2, bh}, {-a + rho[3], bh}));
    corner({-a + rho[3], bh}, {-a, bh - rho[3]}, {-a + rho[3], bh - rho[3]});
    l.push_back(seg({-a, bh - rho[3]}, {-a, -bh + rho[0]}));
    corner({-a, -bh + rho[0]}, {-a + rho[0], -bh}, {-a + rho[0], -bh + rho[0]});
    l.push_back(seg({-a + rho[0], -bh}, {0, -bh}));
    k.shape.what = "boss " + mm(2 * a) + " x " + mm(2 * bh) + " with a keyhole: channel " + mm(w) +
                   " wide, " + mm(depth) + " deep, chamber " + mm(2 * rc);
    return k;
}

// A pocket [-a, a] x [-bh, bh] with a tongue of material from its left wall, h thick, its tip
// a gap g from the right wall. Edge 1 is the right wall, edge 5 the tongue's tip.
std::optional<Shape> tongue(Rng& rng, double r, double g, bool sharp_tip) {
    const double h = rng.uniform(0.5, 15);
    const double bh = h / 2 + rng.uniform(2 * r + 2, 2 * r + 20);
    const double a = std::max(r + 2, (g + r + 1) / 2) + rng.uniform(0.0, 30);
    const double tip = a - g;
    if (tip + a < r + 0.5) return std::nullopt;
    const std::vector<V> v{{-a, -bh},   {a, -bh},     {a, bh},       {-a, bh},
                           {-a, h / 2}, {tip, h / 2}, {tip, -h / 2}, {-a, -h / 2}};
    std::vector<double> rho, reserve;
    corners_for(rng, v, r, true, std::min(h / 2, bh - h / 2) * 0.8, rho, reserve);
    if (sharp_tip) rho[5] = rho[6] = 0;
    return from_polygon("pocket " + mm(2 * a) + " x " + mm(2 * bh) + " with a tongue " + mm(h) +
                            " thick, its tip " + mm(g) + " from the wall",
                        v, rho, reserve);
}

// A boss [-a, a] x [-bh, bh] with a slot of width w from its top down to yb, between two
// prongs; edge 0 is the side `first_side` of: 0 the bottom, 3 the slot's right wall. Vertices
// (counter-clockwise from the bottom left): 0 (-a,-bh), 1 (a,-bh), 2 (a,bh), 3 (w/2,bh),
// 4 (w/2,yb), 5 (-w/2,yb), 6 (-w/2,bh), 7 (-a,bh).
struct UShape {
    Shape shape;
    std::vector<V> v;  // the vertices in the order built
    double a = 0, bh = 0, w = 0, yb = 0;
};
std::optional<UShape> u_shape(Rng& rng, double r, double w, int first_vertex) {
    UShape u;
    u.w = w;
    u.a = w / 2 + rng.uniform(1.0, 15);
    u.bh = rng.uniform(std::max(2.0, r + 1), 25);
    u.yb = rng.uniform(-u.bh + 1.0, u.bh - r - 1.0);
    if (u.yb < -u.bh + 0.5) return std::nullopt;
    std::vector<V> v{{-u.a, -u.bh}, {u.a, -u.bh},   {u.a, u.bh},    {w / 2, u.bh},
                     {w / 2, u.yb}, {-w / 2, u.yb}, {-w / 2, u.bh}, {-u.a, u.bh}};
    std::vector<double> rho, reserve;
    corners_for(rng, v, r, false, std::min(u.a - w / 2, u.bh) * 0.4, rho, reserve);
    std::rotate(v.begin(), v.begin() + first_vertex, v.end());
    std::rotate(rho.begin(), rho.begin() + first_vertex, rho.end());
    std::rotate(reserve.begin(), reserve.begin() + first_vertex, reserve.end());
    u.v = v;
    auto s = from_polygon(
        "boss " + mm(2 * u.a) + " x " + mm(2 * u.bh) + " with a slot " + mm(w) + " wide", v, rho,
        reserve);
    if (!s) return std::nullopt;
    u.shape = std::move(*s);
    return u;
}

// ---- Programs.

struct Options {
    int decimals = 3;
    bool numbered = false;
    bool modal = false;
    bool linear = false;  // G25
    int feed = 3000;
};

double draw_radius(Rng& rng) {
    return std::round(rng.log_uniform(0.5, 10.0) * 1000) / 1000;
}
Side draw_side(Rng& rng) {
    return rng.chance(0.5) ? Side::kLeft : Side::kRight;
}
double draw_level(Rng& rng) {
    return -std::round(rng.uniform(0.5, 3.0) * 1000) / 1000;
}
double draw_turn(Rng& rng) {
    return rng.chance(0.3) ? 0.0 : rng.uniform(0, 2 * kPi);
}
V draw_place(Rng& rng) {
    return {rng.uniform(-60, 60), rng.uniform(-60, 60)};
}
LeadKind draw_lead_kind(Rng& rng, bool straight_start) {
    const int k = rng.integer(0, straight_start ? 2 : 1);
    return k == 0 ? LeadKind::kLineArc : k == 1 ? LeadKind::kArc : LeadKind::kLine;
}

// Every draw from the generator's random numbers is a statement of its own (or one argument of
// a call that draws nothing else), so that a seed draws the same program whatever order a
// compiler evaluates a call's arguments in.

// A lead-in, then a lead-out, of drawn kinds.
std::pair<Lead, Lead> draw_leads(Rng& rng, double r, bool straight_start) {
    const Lead in = draw_lead(rng, draw_lead_kind(rng, straight_start), r);
    const Lead out = draw_lead(rng, draw_lead_kind(rng, straight_start), r);
    return {in, out};
}
// A contour with drawn leads at one level.
int plan_with_leads(Rng& rng, Plan& plan, const Contour& c, bool straight_start, const Tool& tool,
                    double level) {
    const auto [in, out] = draw_leads(rng, tool.r, straight_start);
    return plan_feature(plan, c, in, out, tool, {level});
}

Shape placed(Shape s, double turn, const V& by) {
    s.loop = placed(s.loop, turn, by);
    return s;
}

// A shape turned and moved to a drawn place.
Shape placed_at_random(Rng& rng, const Shape& shape) {
    const double turn = draw_turn(rng);
    const V at = draw_place(rng);
    return placed(shape, turn, at);
}

// A closed shape of the contour families, drawn for a tool of radius r.
std::optional<Shape> draw_shape(Rng& rng, double r, bool pocket, int kind) {
    switch (kind) {
        case 0:
            return rounded_rectangle(rng, r, pocket);
        case 1:
            return slot(rng, r, pocket);
        case 2:
            return circle(rng, r, pocket);
        default:
            return polygon(rng, r, pocket);
    }
}

// One contour with leads of the given kinds (or drawn) at one level.
bool single_contour(Rng& rng, Plan& plan, int shape_kind, bool pocket, std::optional<LeadKind> kind,
                    const std::vector<double>& levels) {
    const double r = draw_radius(rng);
    const auto shape = draw_shape(rng, r, pocket, shape_kind);
    if (!shape) return false;
    if (kind == LeadKind::kLine && !shape->straight_start) return false;
    const Shape s = placed_at_random(rng, *shape);
    const Side side = draw_side(rng);
    const Contour c = make_contour((pocket ? "pocket: " : "boss: ") + s.what, s.loop, pocket, side);
    const LeadKind in = kind ? *kind : draw_lead_kind(rng, s.straight_start);
    const LeadKind out = kind ? *kind : draw_lead_kind(rng, s.straight_start);
    plan.plate = pocket;
    const Lead lead_in = draw_lead(rng, in, r);
    const Lead lead_out = draw_lead(rng, out, r);
    plan_feature(plan, c, lead_in, lead_out, {1, r}, levels);
    return true;
}

// The least distance between two loops (exact geometry).
double loop_distance(const Loop& a, const Loop& b) {
    double d = INFINITY;
    for (const Elem& x : a)
        for (const Elem& y : b)
            d = std::min(d, least_distance(points_of(x), points_of(y)).distance);
    return d;
}

// A designed gouge between elements of planned contours (index: of the built loop).
void design_gouge(Plan& plan, int path_contour, std::size_t path_elem, int wall_contour,
                  std::size_t wall_elem, double depth) {
    const Contour& pc = plan.contours[static_cast<std::size_t>(path_contour)];
    const Contour& wc = plan.contours[static_cast<std::size_t>(wall_contour)];
    plan.designed.push_back(
        {{path_contour, pc.index_of(path_elem)}, {wall_contour, wc.index_of(wall_elem)}});
    plan.designed_depth.push_back(depth);
}
// Its path is the contour's lead-in.
constexpr std::size_t kLeadIn = static_cast<std::size_t>(-1);
void design_lead_gouge(Plan& plan, int path_contour, int wall_contour, std::size_t wall_elem,
                       double depth) {
    const Contour& wc = plan.contours[static_cast<std::size_t>(wall_contour)];
    plan.designed.push_back({{path_contour, kLeadIn}, {wall_contour, wc.index_of(wall_elem)}});
    plan.designed_depth.push_back(depth);
}

// The width of a passage, a channel or a gap: wide enough for the tool (correct programs) or
// narrower than its diameter by at least kGougeDepthMin (and wider than r, so that the tool's
// centre stays on its own side).
double draw_gap(Rng& rng, double r, bool gouge) {
    if (!gouge) return 2 * r + rng.uniform(0.05, 0.05 + 2 * r);
    return rng.uniform(std::max(1.05 * r, r + 0.02), 2 * r - kGougeDepthMin);
}

// The wall index (in plan.walls) of a built loop's element of contour `id`.
std::size_t wall_index(const Plan& plan, int id, std::size_t built_index) {
    const Contour& c = plan.contours[static_cast<std::size_t>(id)];
    return plan.first_wall[static_cast<std::size_t>(id)] + c.index_of(built_index);
}

// A fillet radius at a corner facing a gap g that leaves every pair clearly a gouge or clearly
// not: the corner's straight neighbour ends g + rho from the wall across, 2r - g - rho deep.
double facing_fillet(Rng& rng, double r, double g, double most) {
    for (int i = 0; i < 20; ++i) {
        const double rho = outside_fillet(rng, most);
        if (rho == 0 || std::abs(2 * r - g - rho) >= kGougeDepthMin) return rho;
    }
    return 0;
}

// A pocket with an island: apart by more than the tool's diameter, or (gouge) closer, the
// island's right edge facing the pocket's right wall across a gap g.
bool island(Rng& rng, Plan& plan, bool gouge) {
    const double r = draw_radius(rng);
    const double turn = draw_turn(rng);
    const V at = draw_place(rng);
    Shape pocket, isle;
    std::size_t pocket_right = 0, isle_right = 0;
    double g = 0;
    if (gouge) {
        g = draw_gap(rng, r, true);
        const double ai = rng.uniform(1.0, 12), bi = rng.uniform(1.0, 12);
        std::vector<double> rho_i(4), reserve(4, 0.0);
        for (double& x : rho_i) x = facing_fillet(rng, r, g, std::min(ai, bi) * 0.8);
        const double room = rng.uniform(4 * r + 8, 4 * r + 30);
        const double a = (room + g + 2 * ai) / 2;
        std::vector<double> rho_p(4), reserve_p(4, r);
        for (double& x : rho_p) x = inside_fillet(rng, r, 8);
        const double b = bi + 2 * r + 1 + std::max(rho_p[1], rho_p[2]) + rng.uniform(0, 15);
        // Both start on their left side (edge 0), the right side is edge 2.
        auto p = filleted_polygon(rectangle(-a, -b, a, b, 3), rho_p, reserve_p, 0.2);
        auto i =
            filleted_polygon(rectangle(a - g - 2 * ai, -bi, a - g, bi, 3), rho_i, reserve, 0.2);
        if (!p || !i) return false;
        pocket = {"pocket " + mm(2 * a) + " x " + mm(2 * b), p->loop, true, p->edge};
        isle = {"island " + mm(2 * ai) + " x " + mm(2 * bi) + " " + mm(g) + " from the wall",
                i->loop, true, i->edge};
        pocket_right = p->edge[2];
        isle_right = i->edge[2];
    } else {
        const double a = rng.uniform(2 * r + 8, 2 * r + 40), b = rng.uniform(2 * r + 8, 2 * r + 40);
        std::vector<double> rho_p(4), reserve_p(4, r);
        for (double& x : rho_p) x = inside_fillet(rng, r, 10);
        auto p = filleted_polygon(rectangle(-a, -b, a, b, 0), rho_p, reserve_p, 0.2);
        if (!p) return false;
        pocket = {"pocket " + mm(2 * a) + " x " + mm(2 * b), p->loop, true, p->edge};
        const int kind = rng.integer(0, 2);
        auto inner = draw_shape(rng, r, false, kind);
        if (!inner) return false;
        const double turn_inner = draw_turn(rng);
        const V at_inner{rng.uniform(-a, a) * 0.5, rng.uniform(-b, b) * 0.5};
        isle = placed(*inner, turn_inner, at_inner);
        isle.what = "island: " + isle.what;
        // Inside the pocket's box less the tool's diameter, and clear of its (rounded) walls.
        for (const Elem& e : isle.loop)
            for (const Pt& q : points_of(e))
                if (std::abs(q.x) > a - 2 * r - 0.1 || std::abs(q.y) > b - 2 * r - 0.1)
                    return false;
        if (loop_distance(pocket.loop, isle.loop) < 2 * r + 0.1) return false;
    }
    pocket = placed(pocket, turn, at);
    isle = placed(isle, turn, at);
    plan.plate = true;
    const Tool tool{1, r};
    const double level = draw_level(rng);
    const Side pocket_side = draw_side(rng);
    const int pid =
        plan_with_leads(rng, plan, make_contour(pocket.what, pocket.loop, true, pocket_side),
                        pocket.straight_start, tool, level);
    const Side isle_side = draw_side(rng);
    const int iid = plan_with_leads(rng, plan, make_contour(isle.what, isle.loop, false, isle_side),
                                    isle.straight_start, tool, level);
    if (gouge) {
        design_gouge(plan, pid, pocket_right, iid, isle_right, 2 * r - g);
        design_gouge(plan, iid, isle_right, pid, pocket_right, 2 * r - g);
    }
    return true;
}

// Two bosses milled one after the other, closer than the tool's diameter: A's right edge faces
// B's left edge (longer) across a gap g. Each starts on its far side.
bool bosses_close(Rng& rng, Plan& plan) {
    const double r = draw_radius(rng);
    const double g = draw_gap(rng, r, true);
    const double a1 = rng.uniform(1.0, 15), b1 = rng.uniform(1.0, 15);
    std::vector<double> rho_a(4), none(4, 0.0);
    for (double& x : rho_a) x = facing_fillet(rng, r, g, std::min(a1, b1) * 0.8);
    const double a2 = rng.uniform(1.0, 15);
    std::vector<double> rho_b(4);
    for (double& x : rho_b) x = outside_fillet(rng, 3);
    const double b2 = b1 + 2 * r + 0.5 + std::max(rho_b[2], rho_b[3]) + rng.uniform(0, 10);
    const double shift =
        rng.uniform(-1, 1) * (b2 - b1 - 2 * r - 0.5 - std::max(rho_b[2], rho_b[3]));
    auto pa = filleted_polygon(rectangle(-a1, -b1, a1, b1, 3), rho_a, none, 0.2);  // edge 2: right
    auto pb =
        filleted_polygon(rectangle(a1 + g, shift - b2, a1 + g + 2 * a2, shift + b2, 1), rho_b, none,
                         0.2);  // edge 2: left
    if (!pa || !pb) return false;
    const double turn = draw_turn(rng);
    const V at = draw_place(rng);
    const Tool tool{1, r};
    const double level = draw_level(rng);
    const Side side_a = draw_side(rng);
    const int ia = plan_with_leads(rng, plan,
                                   make_contour("boss A " + mm(2 * a1) + " x " + mm(2 * b1),
                                                placed(pa->loop, turn, at), false, side_a),
                                   true, tool, level);
    const Side side_b = draw_side(rng);
    const int ib = plan_with_leads(
        rng, plan,
        make_contour("boss B " + mm(2 * a2) + " x " + mm(2 * b2) + ", " + mm(g) + " from A",
                     placed(pb->loop, turn, at), false, side_b),
        true, tool, level);
    design_gouge(plan, ia, pa->edge[2], ib, pb->edge[2], 2 * r - g);
    design_gouge(plan, ib, pb->edge[2], ia, pa->edge[2], 2 * r - g);
    return true;
}

// The line+arc lead of a lead-in across a part: a quarter arc, so that its line runs straight at
// the wall the contour starts on (its length is the caller's: from beyond what it crosses).
Lead crossing_lead(Rng& rng, double r) {
    Lead l = draw_lead(rng, LeadKind::kLineArc, r);
    l.sweep = kPi / 2;
    return l;
}

// A U-shaped boss whose lead-in comes from beyond its left prong, across it, into the slot.
bool lead_across_own_part(Rng& rng, Plan& plan) {
    const double r = draw_radius(rng);
    Lead in = crossing_lead(rng, r);
    const double w = std::max(2 * r + 0.1, 2 * in.rl + 0.2) + rng.uniform(0, 6);
    const auto u =
        u_shape(rng, r, w, 3);  // edge 0: the slot's right wall; 2: its left; 4: outer left
    if (!u) return false;
    const Side side = draw_side(rng);
    // In the shape's own frame: the lead arc's start S and the length that takes the line from
    // beyond the outer left edge.
    const Contour local = make_contour("", u->shape.loop, false, side);
    const V c0 = local.loop.front().a;
    const V t = start_tangent(local.loop.front());
    const V n = side_normal(t, side);
    const double sense = side == Side::kLeft ? 1.0 : -1.0;
    const V cl = c0 + in.rl * n;
    const V s = cl + rotated(c0 - cl, -sense * in.sweep);
    in.len = (s.x() + u->a) + r + rng.uniform(1.0, 5.0);
    const double turn = draw_turn(rng);
    const V at = draw_place(rng);
    const Shape placed_shape = placed(u->shape, turn, at);
    const Contour c = make_contour(placed_shape.what, placed_shape.loop, false, side);
    Lead out = draw_lead(rng, LeadKind::kArc, r);  // lifted in the slot: nothing more to cross
    const int id = plan_feature(plan, c, in, out, {1, r}, {draw_level(rng)});
    Check* check = plan.lead_in_check(id);
    if (!check) return false;
    check->exempt = {wall_index(plan, id, u->shape.edge[2]),
                     wall_index(plan, id, u->shape.edge[4])};
    check->need_exempt = 0;
    design_lead_gouge(plan, id, id, u->shape.edge[2], r);
    design_lead_gouge(plan, id, id, u->shape.edge[4], r);
    return true;
}

// Boss A, then boss B to its right, whose lead-in comes from beyond A, across it.
bool lead_across_feature(Rng& rng, Plan& plan) {
    const double r = draw_radius(rng);
    const double a1 = rng.uniform(1.0, 12), b1 = rng.uniform(2 * r + 1.5, 2 * r + 15);
    std::vector<double> rho_a(4), none(4, 0.0);
    for (double& x : rho_a) x = outside_fillet(rng, std::min(a1, b1) * 0.5);
    auto pa =
        filleted_polygon(rectangle(-a1, -b1, a1, b1, 0), rho_a, none, 0.2);  // 1 right, 3 left
    if (!pa) return false;
    Lead in = crossing_lead(rng, r);
    const double gap = 2 * r + in.rl + rng.uniform(2.0, 15);
    const double a2 = rng.uniform(1.0, 12), b2 = rng.uniform(in.rl + 1, in.rl + 15);
    std::vector<double> rho_b(4);
    for (double& x : rho_b) x = outside_fillet(rng, 0.5 * std::min(a2, b2));
    auto built_b = [&](double shift) {
        return filleted_polygon(rectangle(a1 + gap, shift - b2, a1 + gap + 2 * a2, shift + b2, 3),
                                rho_b, none, 0.2);
    };
    auto pb = built_b(0);  // edge 0: the left edge, facing A
    if (!pb) return false;
    const Side side_b = draw_side(rng);
    // Where the lead line runs (S's height) for B at shift 0; B is moved so that it runs at
    // y_lead, across the middle part of A.
    const Contour local = make_contour("", pb->loop, false, side_b);
    const V c0 = local.loop.front().a;
    const V t = start_tangent(local.loop.front());
    const V n = side_normal(t, side_b);
    const double sense = side_b == Side::kLeft ? 1.0 : -1.0;
    const V cl = c0 + in.rl * n;
    const V s = cl + rotated(c0 - cl, -sense * in.sweep);
    const double y_lead = rng.uniform(-b1 + 2 * r + 1, b1 - 2 * r - 1);
    pb = built_b(y_lead - s.y());
    if (!pb) return false;
    in.len = (s.x() + a1) + r + rng.uniform(1.0, 5.0);
    const double turn = draw_turn(rng);
    const V at = draw_place(rng);
    const Tool tool{1, r};
    const double level = draw_level(rng);
    const Side side_a = draw_side(rng);
    const int ia = plan_with_leads(rng, plan,
                                   make_contour("boss A " + mm(2 * a1) + " x " + mm(2 * b1),
                                                placed(pa->loop, turn, at), false, side_a),
                                   true, tool, level);
    const LeadKind out_kind = rng.chance(0.5) ? LeadKind::kArc : LeadKind::kLineArc;
    const Lead out = draw_lead(rng, out_kind, r);
    const int ib = plan_feature(
        plan,
        make_contour("boss B " + mm(2 * a2) + " x " + mm(2 * b2) + ", its lead-in across A",
                     placed(pb->loop, turn, at), false, side_b),
        in, out, tool, {level});
    Check* check = plan.lead_in_check(ib);
    if (!check) return false;
    check->exempt = {wall_index(plan, ia, pa->edge[1]), wall_index(plan, ia, pa->edge[3])};
    check->need_exempt = 0;
    design_lead_gouge(plan, ib, ia, pa->edge[1], r);
    design_lead_gouge(plan, ib, ia, pa->edge[3], r);
    return true;
}

// Concentric rectangles of a pocket cleared in stepovers, innermost first, each its own
// (counter-clockwise) loop starting at the middle of its bottom edge; the last is the wall.
std::vector<Loop> stepover_loops(Rng& rng, double r, int n, double step, double a1, double b1) {
    const double an = a1 + (n - 1) * step, bn = b1 + (n - 1) * step;
    const double rho_n = inside_fillet(rng, r, std::min(an, bn) - 0.3);
    std::vector<Loop> loops;
    for (int k = 0; k < n; ++k) {
        const double grow = (n - 1 - k) * step;
        double rho = rho_n - grow;
        if (rho < r + std::max(kMargin, 0.05 * r)) rho = 0;
        auto p = filleted_polygon(rectangle(-(an - grow), -(bn - grow), an - grow, bn - grow, 0),
                                  std::vector<double>(4, rho), std::vector<double>(4, r), 0.2);
        if (!p) return {};
        loops.push_back(p->loop);
    }
    return loops;
}

// One compensated stretch from the centre through growing loops, as LinuxCNC's qpocket writes
// it: a line out to the first loop's start (the approach), each loop, a line out to the next
// loop's start, and G40 with the line back to the centre (the departure). The loops are the
// pocket's (the last its wall).
void plan_one_stretch(Plan& plan, const std::vector<Contour>& loops, const V& centre, Side side,
                      const Tool& tool, double level, const std::string& what) {
    std::vector<int> ids;
    ids.reserve(loops.size());
    for (const Contour& c : loops) ids.push_back(plan.add_contour(c));
    plan.use(tool);
    plan.plate = true;
    // The approach runs from the centre to where the line's offset meets the first loop's
    // first element's (an inside corner: the offset line, or the offset circle of a pocket's
    // arc); the departure from r beside the last loop's start back to the centre.
    const double r = tool.r;
    const Elem& first = loops.front().loop.front();
    const V d = (first.a - centre).normalized();
    const V on_lead = first.a + r * side_normal(d, side);  // the lead's offset line: + s d
    V trim;
    if (!first.arc) {
        const V t = start_tangent(first);
        const V on_first = first.a + r * side_normal(t, side);  // + u t
        const V rhs = on_first - on_lead;
        const double det = d.x() * (-t.y()) + d.y() * t.x();
        trim = on_lead + ((rhs.x() * (-t.y()) + rhs.y() * t.x()) / det) * d;
    } else {
        const double q = (first.a - first.c).norm() - r;  // the tool inside the arc
        const V f = on_lead - first.c;
        const double b = f.dot(d), disc = b * b - (f.squaredNorm() - q * q);
        if (q <= 0 || disc < 0) plan.feasible = false;
        trim = on_lead + (-b + std::sqrt(std::max(disc, 0.0))) * d;  // the root nearer C0
    }
    plan.checks.push_back({{centre, trim}, r - kTouch, {}, 0, "approach", ids.front()});
    const Contour& last = loops.back();
    const V beside = last.loop.front().a + r * side_normal(start_tangent(last.loop.front()), side);
    plan.checks.push_back({{beside, centre}, r - kTouch, {}, 0, "departure", ids.back()});
    plan.steps.emplace_back([=](Emit& e) {
        e.use_tool(tool);
        e.begin_feature(what, tool);
        NcWriter& nc = e.nc;
        nc.rapid_z(kSafe);
        nc.rapid(centre);
        nc.feed_z(level);
        nc.move(seg(centre, loops.front().loop.front().a), side_word(side), nullptr);
        for (std::size_t k = 0; k < loops.size(); ++k) {
            const Contour& c = loops[k];
            WrittenContour& w = e.contours[static_cast<std::size_t>(ids[k])];
            w.elements.resize(c.loop.size());
            for (std::size_t i = 0; i < c.loop.size(); ++i) nc.move(c.loop[i], "", &w.elements[i]);
            w.written = true;
            if (k + 1 < loops.size())
                nc.move(seg(c.loop.front().a, loops[k + 1].loop.front().a), "", nullptr);
        }
        nc.move(seg(loops.back().loop.front().a, centre), "G40", nullptr);
        nc.rapid_z(kSafe);
        e.end_feature();
    });
}

// LinuxCNC's qpocket: one compensated stretch from the centre through loops of growing size,
// each joined to the next by a line straight out to its start.
bool stepover_one_stretch(Rng& rng, Plan& plan) {
    const double r = draw_radius(rng);
    const double step = rng.uniform(1.15 * r + 0.05, 1.8 * r + 0.1);
    const int n = rng.integer(2, 5);
    const double a1 = rng.uniform(2 * r + 0.3, 2 * r + 6);
    const double b1 = rng.uniform(r + 0.3, r + 6);
    const std::vector<Loop> built = stepover_loops(rng, r, n, step, a1, b1);
    if (built.empty()) return false;
    const double turn = draw_turn(rng);
    const V at = draw_place(rng);
    const Side side = draw_side(rng);
    std::vector<Contour> loops;
    loops.reserve(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k)
        loops.push_back(make_contour("loop", placed(built[static_cast<std::size_t>(k)], turn, at),
                                     true, side, k == n - 1));
    const double level = draw_level(rng);
    plan_one_stretch(plan, loops, at, side, {1, r}, level,
                     "pocket cleared in " + std::to_string(n) + " loops " + mm(step) +
                         " apart, one " + side_word(side) + " stretch (qpocket)");
    return true;
}

// The same loops, each its own stretch with leads, innermost first.
bool stepover_per_loop(Rng& rng, Plan& plan) {
    const double r = draw_radius(rng);
    const double step = rng.uniform(0.4 * r, 1.8 * r);
    const int n = rng.integer(2, 5);
    const double a1 = rng.uniform(r + 2, r + 8);
    const double b1 = rng.uniform(r + 2, r + 8);
    const std::vector<Loop> built = stepover_loops(rng, r, n, step, a1, b1);
    if (built.empty()) return false;
    const double turn = draw_turn(rng);
    const V at = draw_place(rng);
    const Side side = draw_side(rng);
    const Tool tool{1, r};
    const double level = draw_level(rng);
    const LeadKind in = draw_lead_kind(rng, true), out = draw_lead_kind(rng, true);
    plan.plate = true;
    for (int k = 0; k < n; ++k) {
        const Contour c = make_contour(
            "stepover loop " + std::to_string(k + 1) + " of " + std::to_string(n),
            placed(built[static_cast<std::size_t>(k)], turn, at), true, side, k == n - 1);
        const Lead lead_in = draw_lead(rng, in, r);
        const Lead lead_out = draw_lead(rng, out, r);
        plan_feature(plan, c, lead_in, lead_out, tool, {level});
    }
    return true;
}

// Uncompensated zig-zag rows through a pocket, r plus an allowance from its walls, then the
// finishing contour with leads.
bool zigzag(Rng& rng, Plan& plan) {
    const double r = draw_radius(rng);
    const double allowance = rng.uniform(0.05, 0.5);
    const double d = r + allowance;
    const double step = rng.uniform(0.8 * r, 1.6 * r);
    const bool round = rng.chance(0.3);
    std::optional<Shape> shape;
    std::function<double(double)> half_width;  // of the region d inside the walls, at height y
    double top = 0;
    if (round) {
        shape = circle(rng, r, true);
        const double R = shape->loop.front().a.norm() - d;
        top = R;
        half_width = [R](double y) { return std::sqrt(std::max(0.0, R * R - y * y)); };
    } else {
        const double a = rng.uniform(r + 2, r + 30), b = rng.uniform(r + 2, r + 20);
        const double rho = inside_fillet(rng, r, std::min(a, b) - 0.3);
        auto p = filleted_polygon(rectangle(-a, -b, a, b, 0), std::vector<double>(4, rho),
                                  std::vector<double>(4, r), 0.2);
        if (!p) return false;
        shape = Shape{"rounded rectangle " + mm(2 * a) + " x " + mm(2 * b), p->loop, true, p->edge};
        const double ai = a - d, bi = b - d, ri = std::max(rho - d, 0.0);
        top = bi;
        half_width = [ai, bi, ri](double y) {
            const double above = std::abs(y) - (bi - ri);
            return above <= 0 ? ai : ai - ri + std::sqrt(std::max(0.0, ri * ri - above * above));
        };
    }
    if (top < 0.05) return false;
    std::vector<V> rows;
    // The rows step by `step` as accumulated (the files written stay what they were); the
    // count is bounded by the height over the step.
    const int row_count = static_cast<int>(std::ceil((2.0 * top - 0.01) / step)) + 1;
    double next = -top + 0.01;
    for (int row = 0; row < row_count; ++row) {
        const double y = next;
        next += step;
        if (!(y < top)) break;
        const double x = half_width(y);
        if (x < 0.01) continue;
        const V a(-x, y), b(x, y);
        rows.push_back(row % 2 == 0 ? a : b);
        rows.push_back(row % 2 == 0 ? b : a);
    }
    if (rows.size() < 2) return false;
    const double turn = draw_turn(rng);
    const V at = draw_place(rng);
    for (V& p : rows) p = placed(p, turn, at);
    const Shape s = placed(*shape, turn, at);
    const Tool tool{1, r};
    plan.use(tool);
    plan.plate = true;
    plan.checks.push_back({rows, r + allowance / 2, {}, 0, "zig-zag", -1});
    const double level = draw_level(rng);
    const std::string what =
        "zig-zag rows " + mm(step) + " apart, " + mm(allowance) + " left for the finish";
    plan.steps.emplace_back([=](Emit& e) {
        e.use_tool(tool);
        e.begin_feature(what, tool);
        e.nc.rapid_z(kSafe);
        e.nc.rapid(rows.front());
        e.nc.feed_z(level);
        for (std::size_t i = 1; i < rows.size(); ++i)
            e.nc.move(seg(rows[i - 1], rows[i]), "", nullptr);
        e.nc.rapid_z(kSafe);
        e.end_feature();
    });
    const LeadKind in =
        round ? (rng.chance(0.5) ? LeadKind::kArc : LeadKind::kLineArc) : draw_lead_kind(rng, true);
    const LeadKind out =
        round ? (rng.chance(0.5) ? LeadKind::kArc : LeadKind::kLineArc) : draw_lead_kind(rng, true);
    const Side side = draw_side(rng);
    const Lead lead_in = draw_lead(rng, in, r);
    const Lead lead_out = draw_lead(rng, out, r);
    plan_feature(plan, make_contour("pocket: " + s.what + " (finish)", s.loop, true, side), lead_in,
                 lead_out, tool, {level});
    return true;
}

// A circular pocket widened in passes: from the inside out (each pass its own stretch with
// leads, or one stretch joined by radial lines) or from its wall inwards.
bool circular(Rng& rng, Plan& plan, bool inside_out) {
    const double r = draw_radius(rng);
    const bool one_stretch = inside_out && rng.chance(0.4);
    const int n = rng.integer(2, 5);
    const double step =
        one_stretch ? rng.uniform(1.2 * r + 0.1, 1.8 * r + 0.1) : rng.uniform(0.4 * r, 1.8 * r);
    const double rn = rng.uniform(r + 3, r + 30);
    const double r1 = rn - (n - 1) * step;
    if (r1 < (one_stretch ? 2 * r + 0.5 : r + 1)) return false;
    const int pieces = rng.chance(0.4) ? 1 : rng.chance(0.5) ? 2 : 4;
    const double a0 = rng.uniform(0, 2 * kPi);
    const V at = draw_place(rng);
    const Side side = draw_side(rng);
    const Tool tool{1, r};
    const double level = draw_level(rng);
    plan.plate = true;
    std::vector<Contour> passes;
    for (int k = 0; k < n; ++k) {
        const double R = r1 + k * step;
        Loop l;
        for (int i = 0; i < pieces; ++i) {
            const V p = R * unit_at(a0 + 2 * kPi * i / pieces),
                    q = R * unit_at(a0 + 2 * kPi * (i + 1) / pieces);
            l.push_back(arc_elem(p, pieces == 1 ? p : q, V::Zero(), true));
        }
        passes.push_back(
            make_contour("circular pass " + mm(2 * R), placed(l, 0, at), true, side, k == n - 1));
    }
    if (!one_stretch) {
        for (int j = 0; j < n; ++j) {
            const int k = inside_out ? j : n - 1 - j;
            const auto kind = [&] { return rng.chance(0.5) ? LeadKind::kArc : LeadKind::kLineArc; };
            const Lead lead_in = draw_lead(rng, kind(), r);
            const Lead lead_out = draw_lead(rng, kind(), r);
            plan_feature(plan, passes[static_cast<std::size_t>(k)], lead_in, lead_out, tool,
                         {level});
        }
        return true;
    }
    for (int k = 0; k + 1 < n; ++k) {  // the radial line's offset must meet the next circle's
        const double rk = r1 + k * step, rnext = rk + step;
        if (std::sqrt((rnext - r) * (rnext - r) - r * r) < rk + 0.05) return false;
    }
    plan_one_stretch(plan, passes, at, side, tool, level,
                     "circular pocket in " + std::to_string(n) + " passes " + mm(step) +
                         " apart, one " + side_word(side) + " stretch");
    return true;
}

// 2 to 4 pockets in a plate, or bosses, each its own stretch and tool, G40 between them.
bool several_features(Rng& rng, Plan& plan) {
    const bool pockets = rng.chance(0.5);
    const int k = rng.integer(2, 4);
    double x = 0, reach_before = 0;
    Tool tool{0, 0};
    for (int i = 0; i < k; ++i) {
        if (i == 0 || rng.chance(0.7)) tool = {i + 1, draw_radius(rng)};
        const double r = tool.r;
        auto shape = draw_shape(rng, r, pockets, rng.integer(0, 3));
        if (!shape) return false;
        double extent = 0;
        for (const Elem& e : shape->loop)
            for (const Pt& p : points_of(e)) extent = std::max(extent, std::hypot(p.x, p.y));
        // Leads of bosses reach out; pockets keep theirs inside.
        const double reach = pockets ? 1.0 : 4 * r + 12;
        x += reach_before + extent + reach + rng.uniform(0.5, 10);
        const double turn = draw_turn(rng);
        const V at{x, rng.uniform(-10, 10)};
        const Shape s = placed(*shape, turn, at);
        x += extent;
        reach_before = reach;
        const Side side = draw_side(rng);
        const Contour c =
            make_contour((pockets ? "pocket: " : "boss: ") + s.what, s.loop, pockets, side);
        const auto [in, out] = draw_leads(rng, r, s.straight_start);
        plan_feature(plan, c, in, out, tool, {draw_level(rng)});
    }
    plan.plate = pockets;
    return true;
}

// A pocket whose first corner after the start is rounded smaller than the tool.
bool refused_pocket_fillet(Rng& rng, Plan& plan) {
    const double r = draw_radius(rng);
    const double a = rng.uniform(2 * r + 2, 2 * r + 25), b = rng.uniform(r + 2, r + 20);
    const Side side = draw_side(rng);
    const bool ccw = side == Side::kLeft;   // a pocket: G41 runs counter-clockwise
    const std::size_t small = ccw ? 1 : 0;  // the corner reached first from the bottom's middle
    std::vector<double> rho(4), reserve(4, r);
    for (double& x : rho) x = inside_fillet(rng, r, std::min(a, b) - 0.3);
    const double rs = rng.uniform(std::max(0.05, 0.3 * r), r - 0.01);
    rho[small] = rs;
    auto p = filleted_polygon(rectangle(-a, -b, a, b, 0), rho, reserve, 0.2);
    if (!p) return false;
    const Shape s =
        placed_at_random(rng, Shape{"pocket " + mm(2 * a) + " x " + mm(2 * b) +
                                        ", a corner rounded " + mm(rs) + " (tool " + mm(r) + ")",
                                    p->loop, true, p->edge});
    plan.plate = true;
    const double level = draw_level(rng);
    const int id =
        plan_with_leads(rng, plan, make_contour(s.what, s.loop, true, side), true, {1, r}, level);
    const std::size_t last = s.loop.size() - 1;
    design_gouge(plan, id, ccw ? 0 : last, id, ccw ? 1 : last - 1, r - rs);
    plan.refusals.push_back(plan.designed.back().second);
    return true;
}

// A boss with a concave scallop smaller than the tool in its bottom edge, the first thing the
// contour reaches from its start.
bool refused_boss_scallop(Rng& rng, Plan& plan) {
    const double r = draw_radius(rng);
    const double rs = rng.uniform(std::max(0.05, 0.3 * r), r - 0.01);
    const double away = rs + rng.uniform(2 * r + 1, 2 * r + 10);  // from the start to its centre
    // The scallop bites rs into a boss 2b high.
    const double a = away + rs + rng.uniform(1.0, 10), b = rng.uniform(std::max(1.0, rs), 20);
    const Side side = draw_side(rng);
    const bool ccw = side == Side::kRight;  // a boss: G42 runs counter-clockwise
    const double xs = ccw ? away : -away;
    std::array<double, 4> rho{};
    for (double& x : rho) x = outside_fillet(rng, std::min({b, a - away - rs}) * 0.8);
    Loop l;
    auto corner = [&](const V& p, const V& q, const V& c) {
        if ((p - q).norm() > 1e-12) l.push_back(arc_elem(p, q, c, true));
    };
    const V s0(xs - rs, -b), s1(xs + rs, -b);
    const Elem scallop = arc_elem(s0, s1, V(xs, -b), false);  // bites up into the boss
    if (ccw) {
        l.push_back(seg({0, -b}, s0));
        l.push_back(scallop);
        l.push_back(seg(s1, {a - rho[1], -b}));
    } else {
        l.push_back(seg({0, -b}, {a - rho[1], -b}));
    }
    corner({a - rho[1], -b}, {a, -b + rho[1]}, {a - rho[1], -b + rho[1]});
    l.push_back(seg({a, -b + rho[1]}, {a, b - rho[2]}));
    corner({a, b - rho[2]}, {a - rho[2], b}, {a - rho[2], b - rho[2]});
    l.push_back(seg({a - rho[2], b}, {-a + rho[3], b}));
    corner({-a + rho[3], b}, {-a, b - rho[3]}, {-a + rho[3], b - rho[3]});
    l.push_back(seg({-a, b - rho[3]}, {-a, -b + rho[0]}));
    corner({-a, -b + rho[0]}, {-a + rho[0], -b}, {-a + rho[0], -b + rho[0]});
    if (ccw) {
        l.push_back(seg({-a + rho[0], -b}, {0, -b}));
    } else {
        l.push_back(seg({-a + rho[0], -b}, s0));
        l.push_back(scallop);
        l.push_back(seg(s1, {0, -b}));
    }
    const Shape s = placed_at_random(
        rng, Shape{"boss " + mm(2 * a) + " x " + mm(2 * b) + " with a scallop of radius " + mm(rs) +
                       " (tool " + mm(r) + ")",
                   l,
                   true,
                   {}});
    const double level = draw_level(rng);
    const int id =
        plan_with_leads(rng, plan, make_contour(s.what, s.loop, false, side), true, {1, r}, level);
    const std::size_t last = l.size() - 1;
    design_gouge(plan, id, ccw ? 0 : last, id, ccw ? 1 : last - 1, r - rs);
    plan.refusals.push_back(plan.designed.back().second);
    return true;
}

// A boss with a notch from its top edge narrower than the tool, its bottom a half circle
// (smaller than the tool) or flat (too short for its two inside corners). The tool reaches it
// from the contour's start on the bottom edge.
bool refused_notch(Rng& rng, Plan& plan) {
    const double r = draw_radius(rng);
    const double w = rng.uniform(std::max(0.1, 0.6 * r), 2 * r - kGougeDepthMin);
    const double a = w / 2 + rng.uniform(1.0, 15), bh = rng.uniform(std::max(2.0, r + 1), 20);
    const double depth = rng.uniform(0.5, bh);
    const double yb = bh - depth;  // the bottom of the notch (its straight walls' lower end)
    const bool round = rng.chance(0.5);
    std::array<double, 4> rho{};
    for (double& x : rho) x = outside_fillet(rng, std::min(a - w / 2, bh) * 0.5);
    Loop l;
    auto corner = [&](const V& p, const V& q, const V& c) {
        if ((p - q).norm() > 1e-12) l.push_back(arc_elem(p, q, c, true));
    };
    l.push_back(seg({0, -bh}, {a - rho[1], -bh}));
    corner({a - rho[1], -bh}, {a, -bh + rho[1]}, {a - rho[1], -bh + rho[1]});
    l.push_back(seg({a, -bh + rho[1]}, {a, bh - rho[2]}));
    corner({a, bh - rho[2]}, {a - rho[2], bh}, {a - rho[2], bh - rho[2]});
    l.push_back(seg({a - rho[2], bh}, {w / 2, bh}));
    const std::size_t right_wall = l.size();
    l.push_back(seg({w / 2, bh}, {w / 2, yb}));
    const std::size_t bottom = l.size();
    if (round)
        l.push_back(arc_elem({w / 2, yb}, {-w / 2, yb}, {0, yb}, false));  // concave for the tool
    else
        l.push_back(seg({w / 2, yb}, {-w / 2, yb}));
    const std::size_t left_wall = l.size();
    l.push_back(seg({-w / 2, yb}, {-w / 2, bh}));
    l.push_back(seg({-w / 2, bh}, {-a + rho[3], bh}));
    corner({-a + rho[3], bh}, {-a, bh - rho[3]}, {-a + rho[3], bh - rho[3]});
    l.push_back(seg({-a, bh - rho[3]}, {-a, -bh + rho[0]}));
    corner({-a, -bh + rho[0]}, {-a + rho[0], -bh}, {-a + rho[0], -bh + rho[0]});
    l.push_back(seg({-a + rho[0], -bh}, {0, -bh}));
    const Shape s = placed_at_random(
        rng, Shape{"boss " + mm(2 * a) + " x " + mm(2 * bh) + " with a notch " + mm(w) + " wide, " +
                       (round ? "round" : "flat") + " bottom (tool " + mm(r) + ")",
                   l,
                   true,
                   {}});
    const Side side = draw_side(rng);
    const Contour c = make_contour(s.what, s.loop, false, side);
    const double level = draw_level(rng);
    const int id = plan_with_leads(rng, plan, c, true, {1, r}, level);
    // The wall reached first gouges the other one (a boss runs counter-clockwise under G42).
    const bool ccw = side == Side::kRight;
    const std::size_t first = ccw ? right_wall : left_wall, other = ccw ? left_wall : right_wall;
    design_gouge(plan, id, first, id, other, 2 * r - w);
    for (const std::size_t i : {first, bottom, other}) plan.refusals.push_back({id, c.index_of(i)});
    return true;
}

// A slot pocket narrower than the tool: plunged into at its centre, a straight lead onto its
// side, its round ends smaller than the tool.
bool refused_slot(Rng& rng, Plan& plan) {
    const double r = draw_radius(rng);
    const double rad = rng.uniform(std::max(0.05, 0.3 * r), r - kGougeDepthMin);
    const double half = rng.uniform(rad + 0.5, 25);
    const Loop built{
        seg({0, -rad}, {half, -rad}), arc_elem({half, -rad}, {half, rad}, {half, 0}, true),
        seg({half, rad}, {-half, rad}), arc_elem({-half, rad}, {-half, -rad}, {-half, 0}, true),
        seg({-half, -rad}, {0, -rad})};
    const double turn = draw_turn(rng);
    const V at = draw_place(rng);
    const Side side = draw_side(rng);
    const Contour c =
        make_contour("slot " + mm(2 * (half + rad)) + " x " + mm(2 * rad) + " (tool " + mm(r) + ")",
                     placed(built, turn, at), true, side);
    const int id = plan.add_contour(c);
    const Tool tool{1, r};
    plan.use(tool);
    plan.plate = true;
    const double level = draw_level(rng);
    const std::string what =
        "pocket: " + c.what + ", plunged at its centre, " + side_word(side) + ", a straight lead";
    plan.steps.emplace_back([=](Emit& e) {
        e.use_tool(tool);
        e.begin_feature(what, tool);
        NcWriter& nc = e.nc;
        nc.rapid_z(kSafe);
        nc.rapid(at);
        nc.feed_z(level);
        WrittenContour& w = e.contours[static_cast<std::size_t>(id)];
        w.lead_in = nc.move(seg(at, c.loop.front().a), side_word(side), nullptr);
        w.elements.resize(c.loop.size());
        for (std::size_t i = 0; i < c.loop.size(); ++i) nc.move(c.loop[i], "", &w.elements[i]);
        w.written = true;
        nc.move(seg(c.loop.front().a, at), "G40", nullptr);
        nc.rapid_z(kSafe);
        e.end_feature();
    });
    design_lead_gouge(plan, id, id, 0, r - rad);
    // Its round ends are smaller than the tool, its sides too short for the corners a tool that
    // large makes: any of its elements may be the one refused.
    for (std::size_t i = 0; i < c.loop.size(); ++i) plan.refusals.push_back({id, i});
    return true;
}

// A contour of a drawn shape with leads of `kind`, drawn straight (G25) now and then.
bool plan_lead(Rng& rng, Plan& plan, Options& opt, LeadKind kind, bool pocket) {
    const int kinds[] = {0, 1, 3, 2};  // a line lead needs a straight start: no circle
    const int kind_index = rng.integer(0, kind == LeadKind::kLine ? 2 : 3);
    opt.linear = rng.chance(0.25);
    return single_contour(rng, plan, kinds[kind_index], pocket, kind, {draw_level(rng)});
}

// A contour of one shape (rounded rectangle, slot, circle, filleted polygon), pocket or boss,
// with drawn leads, drawn straight (G25) now and then.
bool plan_single_shape(Rng& rng, Plan& plan, Options& opt, CamFamily family) {
    const int kind = family == CamFamily::kRoundedRectangle ? 0
                     : family == CamFamily::kSlot           ? 1
                     : family == CamFamily::kCircle         ? 2
                                                            : 3;
    opt.linear = rng.chance(0.25);
    const bool pocket = rng.chance(0.5);
    const double level = draw_level(rng);
    return single_contour(rng, plan, kind, pocket, std::nullopt, {level});
}

// A pocket whose two walls at edges `a` and `b` of its shape (drawn by `shape` with the tool
// radius, the gap and `gouge`) stand the gap apart; with `gouge`, nearer than the tool is wide,
// each of them gouged by the path along the other.
bool plan_two_wall_pocket(Rng& rng, Plan& plan, bool gouge,
                          std::optional<Shape> (*shape)(Rng&, double, double, bool), std::size_t a,
                          std::size_t b) {
    const double r = draw_radius(rng);
    const double gap = draw_gap(rng, r, gouge);
    const auto sh = shape(rng, r, gap, gouge);
    if (!sh) return false;
    const Shape s = placed_at_random(rng, *sh);
    const Contour c = make_contour("pocket: " + s.what, s.loop, true, draw_side(rng));
    plan.plate = true;
    const double level = draw_level(rng);
    const int id = plan_with_leads(rng, plan, c, true, {1, r}, level);
    if (gouge) {
        design_gouge(plan, id, s.edge[a], id, s.edge[b], 2 * r - gap);
        design_gouge(plan, id, s.edge[b], id, s.edge[a], 2 * r - gap);
    }
    return true;
}

// A pocket of two rooms joined by a passage (rooms()); with `gouge`, narrower than the tool.
bool plan_rooms(Rng& rng, Plan& plan, bool gouge) {
    return plan_two_wall_pocket(rng, plan, gouge, rooms, 2, 8);
}

// A boss with a keyhole (keyhole()); with `gouge`, a channel narrower than the tool, each of
// its walls gouged by the path along the other.
bool plan_keyhole(Rng& rng, Plan& plan, bool gouge) {
    const double r = draw_radius(rng);
    const double w = draw_gap(rng, r, gouge);
    const auto k = keyhole(rng, r, w);
    if (!k) return false;
    const Shape s = placed_at_random(rng, k->shape);
    const Contour c = make_contour(s.what, s.loop, false, draw_side(rng));
    const double level = draw_level(rng);
    const int id = plan_with_leads(rng, plan, c, true, {1, r}, level);
    if (gouge) {
        design_gouge(plan, id, k->right_wall, id, k->left_wall, 2 * r - w);
        design_gouge(plan, id, k->left_wall, id, k->right_wall, 2 * r - w);
    }
    return true;
}

// A pocket with a tongue of material (tongue()); with `gouge`, its tip nearer the wall than the
// tool is wide.
bool plan_tongue(Rng& rng, Plan& plan, bool gouge) {
    return plan_two_wall_pocket(rng, plan, gouge, tongue, 1, 5);
}

// A boss with a slot between two prongs (u_shape()), wide enough for the tool, drawn straight
// (G25) now and then.
bool plan_u_shape(Rng& rng, Plan& plan, Options& opt) {
    const double r = draw_radius(rng);
    const auto u = u_shape(rng, r, draw_gap(rng, r, false), 0);
    if (!u) return false;
    const Shape s = placed_at_random(rng, u->shape);
    const Contour c = make_contour(s.what, s.loop, false, draw_side(rng));
    opt.linear = rng.chance(0.25);
    const double level = draw_level(rng);
    plan_with_leads(rng, plan, c, true, {1, r}, level);
    return true;
}

// One contour cut at two to four levels, each deeper by the same step.
bool plan_depth_passes(Rng& rng, Plan& plan) {
    std::vector<double> levels;
    const int n = rng.integer(2, 4);
    const double dz = rng.uniform(0.3, 2.0);
    for (int i = 1; i <= n; ++i) levels.push_back(-std::round(i * dz * 1000) / 1000);
    const int kind = rng.integer(0, 3);
    const bool pocket = rng.chance(0.5);
    return single_contour(rng, plan, kind, pocket, std::nullopt, levels);
}

// One program of the family planned; false where the draw found no room (the caller draws
// again).
bool plan_family(Rng& rng, CamFamily family, Plan& plan, Options& opt) {
    switch (family) {
        case CamFamily::kLeadLineArcPocket:
            return plan_lead(rng, plan, opt, LeadKind::kLineArc, true);
        case CamFamily::kLeadLineArcBoss:
            return plan_lead(rng, plan, opt, LeadKind::kLineArc, false);
        case CamFamily::kLeadLinePocket:
            return plan_lead(rng, plan, opt, LeadKind::kLine, true);
        case CamFamily::kLeadLineBoss:
            return plan_lead(rng, plan, opt, LeadKind::kLine, false);
        case CamFamily::kLeadArcPocket:
            return plan_lead(rng, plan, opt, LeadKind::kArc, true);
        case CamFamily::kLeadArcBoss:
            return plan_lead(rng, plan, opt, LeadKind::kArc, false);
        case CamFamily::kRoundedRectangle:
        case CamFamily::kSlot:
        case CamFamily::kCircle:
        case CamFamily::kFilletedPolygon:
            return plan_single_shape(rng, plan, opt, family);
        case CamFamily::kIsland:
            return island(rng, plan, false);
        case CamFamily::kGougeIslandClose:
            return island(rng, plan, true);
        case CamFamily::kRooms:
            return plan_rooms(rng, plan, false);
        case CamFamily::kGougeNeck:
            return plan_rooms(rng, plan, true);
        case CamFamily::kKeyhole:
            return plan_keyhole(rng, plan, false);
        case CamFamily::kGougeKeyhole:
            return plan_keyhole(rng, plan, true);
        case CamFamily::kTongue:
            return plan_tongue(rng, plan, false);
        case CamFamily::kGougeTongue:
            return plan_tongue(rng, plan, true);
        case CamFamily::kUShape:
            return plan_u_shape(rng, plan, opt);
        case CamFamily::kGougeLeadCrossesPart:
            return lead_across_own_part(rng, plan);
        case CamFamily::kGougeLeadCrossesFeature:
            return lead_across_feature(rng, plan);
        case CamFamily::kGougeBossesClose:
            return bosses_close(rng, plan);
        case CamFamily::kStepoverOneStretch:
            return stepover_one_stretch(rng, plan);
        case CamFamily::kStepoverPerLoop:
            return stepover_per_loop(rng, plan);
        case CamFamily::kZigzag:
            return zigzag(rng, plan);
        case CamFamily::kCircularInsideOut:
            return circular(rng, plan, true);
        case CamFamily::kCircularOutsideIn:
            return circular(rng, plan, false);
        case CamFamily::kSeveralFeatures:
            return several_features(rng, plan);
        case CamFamily::kDepthPasses:
            return plan_depth_passes(rng, plan);
        case CamFamily::kRefusedPocketFillet:
            return refused_pocket_fillet(rng, plan);
        case CamFamily::kRefusedBossScallop:
            return refused_boss_scallop(rng, plan);
        case CamFamily::kRefusedNotch:
            return refused_notch(rng, plan);
        case CamFamily::kRefusedSlot:
            return refused_slot(rng, plan);
    }
    return false;
}

constexpr CamFamilyInfo kFamilies[] = {
    {CamFamily::kLeadLineArcPocket, false, false, "lead.line+arc.pocket"},
    {CamFamily::kLeadLineArcBoss, false, false, "lead.line+arc.boss"},
    {CamFamily::kLeadLinePocket, false, false, "lead.line.pocket"},
    {CamFamily::kLeadLineBoss, false, false, "lead.line.boss"},
    {CamFamily::kLeadArcPocket, false, false, "lead.arc.pocket"},
    {CamFamily::kLeadArcBoss, false, false, "lead.arc.boss"},
    {CamFamily::kRoundedRectangle, false, false, "contour.rounded_rectangle"},
    {CamFamily::kSlot, false, false, "contour.slot"},
    {CamFamily::kCircle, false, false, "contour.circle"},
    {CamFamily::kFilletedPolygon, false, false, "contour.filleted_polygon"},
    {CamFamily::kIsland, false, false, "contour.island"},
    {CamFamily::kRooms, false, false, "contour.rooms"},
    {CamFamily::kKeyhole, false, false, "contour.keyhole"},
    {CamFamily::kTongue, false, false, "contour.tongue"},
    {CamFamily::kUShape, false, false, "contour.u_shape"},
    {CamFamily::kStepoverOneStretch, false, false, "pocket.stepover_one_stretch"},
    {CamFamily::kStepoverPerLoop, false, false, "pocket.stepover_per_loop"},
    {CamFamily::kZigzag, false, false, "pocket.zigzag"},
    {CamFamily::kCircularInsideOut, false, false, "pocket.circular_inside_out"},
    {CamFamily::kCircularOutsideIn, false, false, "pocket.circular_outside_in"},
    {CamFamily::kSeveralFeatures, false, false, "program.several_features"},
    {CamFamily::kDepthPasses, false, false, "program.depth_passes"},
    {CamFamily::kGougeNeck, true, false, "gouge.neck"},
    {CamFamily::kGougeKeyhole, true, false, "gouge.keyhole"},
    {CamFamily::kGougeTongue, true, false, "gouge.tongue"},
    {CamFamily::kGougeBossesClose, true, false, "gouge.bosses_close"},
    {CamFamily::kGougeIslandClose, true, false, "gouge.island_close"},
    {CamFamily::kGougeLeadCrossesPart, true, false, "gouge.lead_across_own_part"},
    {CamFamily::kGougeLeadCrossesFeature, true, false, "gouge.lead_across_feature"},
    {CamFamily::kRefusedPocketFillet, true, true, "refused.pocket_fillet_under_tool"},
    {CamFamily::kRefusedBossScallop, true, true, "refused.boss_scallop_under_tool"},
    {CamFamily::kRefusedNotch, true, true, "refused.notch_under_tool"},
    {CamFamily::kRefusedSlot, true, true, "refused.slot_under_tool"},
};

// The plate around pockets: the box of every wall, 30 mm larger, no block.
DesignLoop plate_around(const Plan& plan) {
    double lx = INFINITY, ly = INFINITY, hx = -INFINITY, hy = -INFINITY;
    for (const PlanWall& w : plan.walls)
        for (const Pt& p : points_of(w.e)) {
            lx = std::min(lx, p.x);
            ly = std::min(ly, p.y);
            hx = std::max(hx, p.x);
            hy = std::max(hy, p.y);
        }
    lx -= 30;
    ly -= 30;
    hx += 30;
    hy += 30;
    DesignLoop l;
    const Pt c[] = {{lx, ly}, {hx, ly}, {hx, hy}, {lx, hy}};
    for (int i = 0; i < 4; ++i) {
        WallElement e;
        e.start = c[i];
        e.end = c[(i + 1) % 4];
        e.material = MaterialSide::kLeft;
        l.elements.push_back(e);
    }
    return l;
}

std::string program_name(const CamFamilyInfo& info, std::uint64_t seed) {
    std::string name;
    for (const char ch : info.name) name += ch == '+' ? 'p' : ch == '.' ? '_' : ch;
    return name + "_" + std::to_string(seed);
}

CamProgram write_program(const CamFamilyInfo& info, std::uint64_t seed, const Plan& plan,
                         const Options& opt) {
    Emit e(NcWriter(opt.decimals, opt.numbered, opt.modal));
    e.contours.resize(plan.contours.size());
    NcWriter& nc = e.nc;
    nc.text_line("%" + program_name(info, seed));
    nc.text_line("; " + std::string(info.name) + ", seed " + std::to_string(seed) +
                 " (tests/support/cam_programs.h)");
    nc.block(std::string("G17 G40 G90 ") + (opt.linear ? "G25" : "G26"));
    nc.block("F" + std::to_string(opt.feed));
    for (const auto& step : plan.steps) step(e);
    nc.block("M30");

    CamProgram out;
    out.family = info.family;
    out.seed = seed;
    out.name = std::string(info.name) + "#" + std::to_string(seed);
    out.text = nc.text();
    out.gouge = info.gouge;
    out.may_refuse = info.may_refuse;
    out.features = e.features;
    out.radius_by_line = nc.radius_by_line();
    out.line_of_number = nc.numbers();
    char buf[256];
    for (const Tool& t : plan.tools) {
        std::snprintf(buf, sizeof buf,
                      "wz[%d].gueltig 1\nwz[%d].typ 0\nwz[%d].mass_einheit 1\nwz[%d].laenge 0\n"
                      "wz[%d].radius %.3f\n",
                      t.number, t.number, t.number, t.number, t.number, t.r);
        out.tool_list += buf;
    }
    out.part.plane = 17;
    out.part.top = kTop;
    if (plan.plate) out.part.loops.push_back(plate_around(plan));
    for (std::size_t id = 0; id < plan.contours.size(); ++id) {
        const Contour& c = plan.contours[id];
        if (!c.wall) continue;
        const WrittenContour& w = e.contours[id];
        if (!w.written) throw std::logic_error("cam_programs: a wall contour was not written");
        DesignLoop l;
        l.elements = w.elements;
        for (WallElement& x : l.elements) x.material = material_of(c.side);
        out.part.loops.push_back(std::move(l));
    }
    for (std::size_t i = 0; i < plan.designed.size(); ++i) {
        const auto& [path, wall] = plan.designed[i];
        const WrittenContour& pc = e.contours[static_cast<std::size_t>(path.contour)];
        const WrittenContour& wc = e.contours[static_cast<std::size_t>(wall.contour)];
        const run::BlockRef pb = path.index == kLeadIn ? pc.lead_in : pc.elements[path.index].block;
        out.designed.push_back(
            {pb.line, wc.elements[wall.index].block.line, plan.designed_depth[i]});
    }
    for (const ElemRef& r : plan.refusals)
        out.refused_at.push_back(
            e.contours[static_cast<std::size_t>(r.contour)].elements[r.index].block.line);
    return out;
}

}  // namespace

std::span<const CamFamilyInfo> cam_families() {
    return kFamilies;
}

const CamFamilyInfo& family_info(CamFamily family) {
    for (const CamFamilyInfo& f : kFamilies)
        if (f.family == family) return f;
    throw std::invalid_argument("cam_programs: unknown family");
}

std::uint64_t CamProgram::line_of(const run::BlockRef& b) const {
    if (b.number == run::kNoBlock) return b.line;
    for (const auto& [n, line] : line_of_number)
        if (n == b.number) return line;
    return 0;
}

double CamProgram::radius_at(const run::BlockRef& b) const {
    const std::uint64_t line = line_of(b);
    return line < radius_by_line.size() ? radius_by_line[line] : 0.0;
}

std::string CamProgram::summary() const {
    std::string s;
    for (const CamFeature& f : features)
        s += "  lines " + std::to_string(f.first_line) + "-" + std::to_string(f.last_line) + ": D" +
             std::to_string(f.tool) + " r " + mm(f.radius) + ": " + f.what + "\n";
    return s;
}

CamProgram generate_cam_program(CamFamily family, std::uint64_t seed) {
    const CamFamilyInfo& info = family_info(family);
    // The family's own sequence of draws for each number.
    const std::uint64_t start = seed * 0x9E3779B97F4A7C15ULL +
                                static_cast<std::uint64_t>(family) * 0xD1B54A32D192ED03ULL + 1;
    Rng rng(start);
    std::string last = "no shape fitted";
    for (int attempt = 0; attempt < 5000; ++attempt) {
        Plan plan;
        Options opt;
        opt.decimals = rng.chance(0.7) ? 3 : 4;
        opt.numbered = rng.chance(0.5);
        opt.modal = rng.chance(0.5);
        opt.feed = 100 * rng.integer(30, 60);
        if (!plan_family(rng, family, plan, opt)) continue;
        if (info.gouge) opt.linear = false;
        if (const auto failed = failed_check(plan)) {
            last = *failed;
            continue;
        }
        return write_program(info, seed, plan, opt);
    }
    throw std::runtime_error("cam_programs: no program of " + std::string(info.name) +
                             " could be drawn from seed " + std::to_string(seed) +
                             " in 5000 draws (the last: " + last + ")");
}

}  // namespace apci::test
