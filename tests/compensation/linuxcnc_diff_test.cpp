// SPDX-License-Identifier: MIT
// The differential test of tool radius compensation against LinuxCNC's interpreter (rs274):
// thousands of random contours written as CAM systems write them (coordinates and I/J/K
// rounded to 3 or 6 decimals, tangent and collinear joins that are tangent only up to that
// rounding, short elements, G17 and G18, both sides, several radii, some coming back near
// themselves), each run on the embedded emulator as `apcictl run` runs it and by rs274, the
// two tool-centre paths compared.
//
// Verdicts (docs/testing.md, "The LinuxCNC differential test"):
// - both give a path: the paths between the middle of the lead-in and the middle of the
//   lead-out agree within 1e-3 mm (Hausdorff distance);
// - LinuxCNC reports a gouge, or its path comes closer to the contour than r - 2.5e-4: ours
//   must refuse, or warn that its path comes near the contour away from a corner (a missed
//   gouge otherwise);
// - ours refuses while LinuxCNC's path keeps the radius: a false refusal, unless the refusal is
//   one no control holding one profile can avoid (checked from the program: the trim reaches
//   back past the held element's start, into an element already spooled);
// - our path comes near the contour away from a corner (found here independently) exactly
//   when the run warns so;
// - every G17 contour run again as G19 (Y, Z; LinuxCNC has no G19) gives the same outcome.
// The generator keeps every join out of LinuxCNC's own tolerance bands (it joins turns below
// 0.05 rad without a transition or trim, and reads inside turns within 0.05 rad of a reversal
// as outside), where the two differ by design; the count of contours left out is printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "apci/run/path.h"
#include "contours.h"
#include "diff_support.h"
#include "linuxcnc.h"
#include "rwmos/geometry/shared.h"

namespace apci::test {
namespace {

using rwmos::geom::end_tangent;
using rwmos::geom::is_arc;
using rwmos::geom::left_normal;
using rwmos::geom::length;
using rwmos::geom::make_arc;
using rwmos::geom::make_line;
using rwmos::geom::point_at;
using rwmos::geom::start_tangent;

// LinuxCNC joins corners turning less than this without trim or transition
// (TOLERANCE_CONCAVE_CORNER in its interpreter), and reads inside turns within it of a reversal
// as outside corners.
constexpr double kLinuxCncCornerBand = 0.05;
// The agreement required of the two paths, and the gouge threshold on both.
constexpr double kMaxDeviation = 1e-3;
// LinuxCNC's path keeps the radius when it comes no closer to the contour than r less this:
// our path tolerance (1e-4), its printed rounding (4 decimals, up to 7e-5) and the largest
// deviation of its joins that the generator lets through (5e-5, below).
constexpr double kGougeTolerance = 2.5e-4;
// Our own path: the path tolerance and floating point.
constexpr double kOurGougeTolerance = 1.5e-4;
// A turn whose join LinuxCNC leaves without trim or transition deviates by r (1 - cos turn)
// from the exact path; up to this it is rounding noise for the comparison.
constexpr double kNoiseJoinDeviation = 5e-5;
// rs274 prints 4 decimals: a window point is found on its path within this.
constexpr double kWindowTolerance = 2e-4;
// LinuxCNC measures an inside corner into an arc on the arc's end radius (its interpreter's
// line-to-arc and arc-to-arc corners): where rounding made an arc's start and end radius
// differ, its trim point, and its path near it, move by up to that difference. Contours whose
// arcs' radii agree within this are compared strictly; the others with twice the difference
// as slack on LinuxCNC's side.
constexpr double kStrictMismatch = 5e-5;

const Rs274& rs274() {
    return test_rs274();
}

double turn_between(const Element& a, const Element& b) {
    const Vec2 t1 = end_tangent(a), t2 = start_tangent(b);
    return std::atan2(rwmos::geom::cross(t1, t2), t1.dot(t2));
}

Vec2 tool_side(const Vec2& tangent, bool left) {
    return left ? left_normal(tangent) : Vec2(-left_normal(tangent));
}

struct Case {
    DiffProgram program;
    double arc_mismatch = 0.0;  // the largest difference of an arc's start and end radius
    std::vector<Element> contour;  // as written: every element the tool must keep r from
    Vec2 window_from = Vec2::Zero(), window_to = Vec2::Zero();
};

enum class Made { kOk, kNoRoom, kInLinuxCncBand };

// The room the random walk keeps between elements that must stay clear of each other, beyond
// the tool's width (fits_chain, clear_of).
constexpr double kRoomMargin = 0.05;

// The lead-in line, the contour proper (a random walk of lines and arcs, tangent joins and
// corners), the lead-out line (`chain`), for the tool radius, side and decimals drawn in p; the
// leads long enough that their middles are never trimmed. False when the walk found no room.
bool random_walk(Rng& rng, const DiffProgram& p, bool lines_only, bool may_return,
                 std::vector<Element>& chain) {
    const double r = p.r;
    const double lead = 12 * r + 3;
    const Vec2 origin(rng.uniform(-40, 40), rng.uniform(-40, 40));
    double h = rng.uniform(0, 2 * kPi);
    chain.push_back(make_line(origin, origin + lead * dir(h)));
    const int n = rng.integer(1, 6);
    for (int i = 0; i <= n; ++i) {
        const bool lead_out = i == n;
        const Vec2 at = chain.back().end;
        bool placed = false;
        for (int attempt = 0; attempt < 16 && !placed; ++attempt) {
            // A corner (at the leads at most 120 degrees, so that no trim reaches their
            // middles), else a tangent join.
            const double sharpest = i == 0 || lead_out ? 120 : 165;
            double turn = 0.0;
            if (rng.chance(0.6)) turn = rng.sign() * rng.uniform(4, sharpest) * kPi / 180;
            const double start_heading = h + turn;
            Element e;
            if (lead_out || lines_only || rng.chance(0.5)) {
                const double len = lead_out ? lead
                                   : rng.chance(0.2) ? rng.log_uniform(0.02, 0.4)
                                                     : rng.log_uniform(0.5, 25);
                e = make_line(at, at + len * dir(start_heading));
            } else {
                double radius = rng.log_uniform(0.3, 25);
                const double sweep = rng.sign() * rng.uniform(3, 270) * kPi / 180;
                const bool concave = (sweep > 0) == p.left;
                if (concave) {
                    // Mostly a tool that fits; now and then one that does not (CalcError).
                    radius = rng.chance(0.05) ? r * rng.uniform(0.3, 0.85)
                                              : std::max(radius, 1.25 * r + 0.2);
                }
                e = arc_from(at, start_heading, radius, sweep);
            }
            // The leads stay clear: the comparison window lies on them.
            placed = fits_chain(chain, e, r, kRoomMargin, may_return && i != 0 && !lead_out);
            if (placed) chain.push_back(e);
        }
        if (!placed) return false;
        h = heading(end_tangent(chain.back()));
    }
    return true;
}

// Selection and deselection blocks: straight from the tool's side to the chain (from `start`),
// and back to it (to `exit`). False when they do not stay clear of the chain and each other.
bool selection_and_deselection(const std::vector<Element>& chain, const DiffProgram& p, Vec2& start,
                               Vec2& exit) {
    const double r = p.r;
    const Element& lead_in = chain.front();
    const Element& lead_out = chain.back();
    const double away = 8 * r + 5;
    start = lead_in.start + away * tool_side(start_tangent(lead_in), p.left);
    exit = lead_out.end + away * tool_side(start_tangent(lead_out), p.left);
    const Element entry = make_line(start, lead_in.start);
    const Element leave = make_line(lead_out.end, exit);
    for (std::size_t j = 0; j < chain.size(); ++j) {
        if (j != 0 && !clear_of(entry, chain[j], r, kRoomMargin)) return false;
        if (j + 1 != chain.size() && !clear_of(leave, chain[j], r, kRoomMargin)) return false;
    }
    return clear_of(entry, leave, r, kRoomMargin);
}

// Written as a program writes it: every point and I/J/K rounded to p.decimals.
void write_rounded(const std::vector<Element>& chain, const Vec2& start, const Vec2& exit,
                   DiffProgram& p) {
    const int d = p.decimals;
    p.start = round_to(start, d);
    p.entry_end = round_to(chain.front().start, d);
    Vec2 from = p.entry_end;
    for (const Element& e : chain) {
        Element w = e;
        w.start = from;
        w.end = round_to(e.end, d);
        if (is_arc(e)) w.centre = from + round_to(e.centre - from, d);
        p.elements.push_back(w);
        from = w.end;
    }
    p.exit_end = round_to(exit, d);
}

// Whether a join of the written program lies in LinuxCNC's bands: a turn that is neither
// rounding noise (its offset gap under 2e-4 even for LinuxCNC's join) nor clear of
// kLinuxCncCornerBand.
bool in_linuxcnc_band(const DiffProgram& p) {
    for (std::size_t i = 1; i < p.elements.size(); ++i) {
        const double turn = std::abs(turn_between(p.elements[i - 1], p.elements[i]));
        const bool noise = p.r * (1 - std::cos(turn)) <= kNoiseJoinDeviation;
        if ((!noise && turn < kLinuxCncCornerBand + 0.01) || turn > kPi - kLinuxCncCornerBand - 0.01)
            return true;
    }
    return false;
}

// One random contour; kNoRoom when the walk found no room, kInLinuxCncBand when rounding put a
// join into LinuxCNC's tolerance bands.
Made make_case(std::uint64_t seed, Case& out) {
    Rng rng(seed);
    DiffProgram& p = out.program;
    p.seed = seed;
    const double radii[] = {0.5, 2.0, 5.0};
    p.r = rng.pick(radii);
    p.plane = rng.chance(0.5) ? 17 : 18;
    p.left = rng.chance(0.5);
    p.decimals = rng.chance(0.45) ? 3 : 6;
    const bool lines_only = p.decimals == 3 && rng.chance(0.5);
    // Now and then a contour that comes back near itself (self-approach).
    const bool may_return = rng.chance(0.4);
    const double r = p.r;

    std::vector<Element> chain;
    if (!random_walk(rng, p, lines_only, may_return, chain)) return Made::kNoRoom;
    Vec2 start, exit;
    if (!selection_and_deselection(chain, p, start, exit)) return Made::kNoRoom;
    write_rounded(chain, start, exit, p);
    // Keep out of LinuxCNC's bands.
    if (in_linuxcnc_band(p)) return Made::kInLinuxCncBand;
    out.contour = p.elements;
    for (const Element& e : p.elements)
        if (is_arc(e))
            out.arc_mismatch =
                std::max(out.arc_mismatch, std::abs(rwmos::geom::radius(e) - rwmos::geom::end_radius(e)));
    const Element& in = p.elements.front();
    const Element& last = p.elements.back();
    out.window_from = point_at(in, 0.5) + r * tool_side(start_tangent(in), p.left);
    out.window_to = point_at(last, 0.5) + r * tool_side(start_tangent(last), p.left);
    return Made::kOk;
}

// Where our path comes near the contour away from its corners, found here independently of the
// run's own check (tools/runlib self_approach.h states the rule): a path segment against every
// element of the stretch but the first (the approach) and its own (the last one too: the
// programs' G40 G1 departs from it in the plane); a
// transition against its corner's elements only where an arc of more than half a turn comes
// back round (its part more than half a turn from the corner); the neighbours before and after
// with twice the tolerance. kNear: closer than the run's threshold less 5e-5; kBorderline:
// within 5e-5 of it (either answer is right); kClear otherwise.
enum class Approach { kClear, kNear, kBorderline };

// The part of e more than half a turn from its corner at the end (at_end) or the start; false
// when there is none (a line, an arc of at most half a turn).
bool turned_back_part(const Element& e, bool at_end, Element& out) {
    if (!is_arc(e)) return false;
    const double turn = std::abs(rwmos::geom::sweep(e));
    if (turn <= kPi) return false;
    out = e;
    if (at_end) out.end = point_at(e, (turn - kPi) / turn);
    else out.start = point_at(e, kPi / turn);
    return true;
}

Approach our_path_approaches(const OurRun& ours, const Case& c) {
    const double r = c.program.r;
    constexpr double kTolerance = 1e-4;  // the run's path tolerance
    constexpr double kBand = 5e-5;
    // The compensated elements: the selection block's line (program line 4), then the
    // program's elements (lines 5, 6, ...).
    std::vector<Element> elements{make_line(c.program.start, c.program.entry_end)};
    elements.insert(elements.end(), c.contour.begin(), c.contour.end());
    Approach worst = Approach::kClear;
    for (std::size_t i = 0; i < ours.path.size(); ++i) {
        const int role = ours.roles[i];
        const bool transition = role == static_cast<int>(apci::run::Role::kTransition);
        if (role != static_cast<int>(apci::run::Role::kContour) && !transition) continue;
        if (ours.lines[i] < 4 || ours.lines[i] >= 4 + elements.size()) continue;
        const std::size_t k = ours.lines[i] - 4;
        const Element& seg = ours.path[i];
        for (std::size_t j = 1; j < elements.size(); ++j) {
            Element part = elements[j];
            double threshold = r - kTolerance;
            if (transition && (j == k || j == k + 1)) {
                if (!turned_back_part(elements[j], j == k, part)) continue;
            } else if (!transition && j == k) {
                continue;  // its own offset
            } else if (j + 1 == k || j == k + 1) {
                threshold = r - 2 * kTolerance;
            }
            if (!box_of(seg, r).overlaps(box_of(part, 0.0))) continue;
            if (!farther_than(seg, part, threshold - kBand)) return Approach::kNear;
            if (!farther_than(seg, part, threshold + kBand)) worst = Approach::kBorderline;
        }
    }
    return worst;
}

// Where the offset of h, followed back from its end (on past its start along its carrier, at
// most one length of h or half a turn), first meets the offset of n with its foot on n (within
// the path tolerance of its ends): the fraction of h there. NaN when they do not meet.
double first_meeting(const Element& h, const Element& n, double r, bool left) {
    const auto at = [&](double t) { return read_offset(n, offset_point(h, t, r, left), r, left); };
    const double lowest = is_arc(h) ? std::max(-1.0, -kPi / std::abs(rwmos::geom::sweep(h))) : -1.0;
    const double len_n = length(n);
    constexpr int kSteps = 4000;
    double prev_t = 1.0;
    OffsetReading prev = at(1.0);
    for (int i = 1; i <= kSteps; ++i) {
        // Dense near the corner, where nearly tangent offsets meet.
        const double u = static_cast<double>(i) / kSteps;
        const double t = 1.0 - (1.0 - lowest) * u * u * u;
        const OffsetReading now = at(t);
        if ((now.residual <= 0) != (prev.residual <= 0)) {
            const double root =
                bisect_sign_change([&](double x) { return at(x).residual; }, t, prev_t);
            double f = at(root).fraction;
            // An arc's foot just before its start reads as almost a whole turn.
            if (is_arc(n)) {
                const double whole = 2 * kPi / std::abs(rwmos::geom::sweep(n));
                if (f > 1.0 && (f - whole) * len_n > -1.0) f -= whole;
            }
            if (f * len_n >= -1e-4 && (f - 1) * len_n <= 1e-4) return root;
        }
        prev_t = t;
        prev = now;
    }
    return std::nan("");
}

// Our refusal "element is too short for the corner at its end" (of the held element h, reported
// on its own block) comes from the board's lookahead, not from the tolerance model, when the held
// element h joins the element before it
// tangentially or turning away from the tool (no trim there) and the offsets of h and of the
// next element first meet before h's start: the trim would have to reach back into the element
// before or its transition, which the board, holding one profile, has spooled already.
// LinuxCNC keeps every move since its last corner in its queue (a join under 0.05 rad is none
// to it) and trims there; where it had flushed the element before, it refuses as we do ("...
// cannot be reached by the tool without gouging"). Checked here from the program alone.
bool beyond_one_profile(const Case& c, const OurRun& ours) {
    if (ours.error.find("too short for the corner at its end") == std::string::npos) return false;
    // The compensated elements: the selection block's line (program line 4), then the program's.
    std::vector<Element> elements{make_line(c.program.start, c.program.entry_end)};
    elements.insert(elements.end(), c.contour.begin(), c.contour.end());
    if (ours.error_line < 5 || ours.error_line + 1 >= 4 + elements.size()) return false;
    const std::size_t k = ours.error_line - 4;
    const Element &before = elements[k - 1], &held = elements[k], &next = elements[k + 1];
    const double r = c.program.r;
    const double turn = turn_between(before, held);
    const bool towards_tool = (turn > 0) == c.program.left;
    if (towards_tool && 2 * r * std::abs(std::sin(turn / 2)) > 1e-4) return false;  // trimmed
    const double t = first_meeting(held, next, r, c.program.left);
    return std::isfinite(t) && t * length(held) < -1e-4;
}

// The same outcome: both refuse at the same line with the same error bits, or both give the
// same path (segment by segment, roles and lines alike, points within 1e-9 mm).
std::string differs(const OurRun& a, const OurRun& b) {
    const auto bits = [](const std::string& e) { return e.substr(0, e.find(':')); };
    if (a.ok != b.ok) return a.ok ? "refused: " + b.error : "refused: " + a.error;
    if (!a.ok)
        return bits(a.error) == bits(b.error) && a.error_line == b.error_line
                   ? std::string()
                   : a.error + " | " + b.error;
    if (a.path.size() != b.path.size()) return "segment counts differ";
    for (std::size_t i = 0; i < a.path.size(); ++i) {
        const Element &x = a.path[i], &y = b.path[i];
        const double off = std::max({(x.start - y.start).norm(), (x.end - y.end).norm(),
                                     is_arc(x) ? (x.centre - y.centre).norm() : 0.0});
        if (x.kind != y.kind || x.ccw != y.ccw || a.roles[i] != b.roles[i] ||
            a.lines[i] != b.lines[i] || off > 1e-9)
            return "segment " + std::to_string(i) + " differs by " + std::to_string(off);
    }
    return a.self_approach == b.self_approach ? std::string() : "the self-approach warning differs";
}

bool gouge_message(const std::string& m) {
    for (const char* s : {"gouging", "can't fit", "cannot be reached", "concave corner",
                          "not less than arc radius"})
        if (m.find(s) != std::string::npos) return true;
    return false;
}

// The feed moves of rs274's path (a rapid move may pass the window's points by chance).
std::vector<Element> feed_path(const std::vector<CanonMove>& moves) {
    std::vector<Element> out;
    for (const CanonMove& m : moves)
        if (!m.rapid) out.push_back(m.path);
    return out;
}

// Our whole path from the G41/G42 block on: the approach, the contour and the move after G40
// (the G0 to the start before it left out, as feed_path leaves out rs274's).
std::vector<Element> whole_path(const OurRun& ours) {
    std::vector<Element> out;
    bool started = false;
    for (std::size_t i = 0; i < ours.path.size(); ++i) {
        started = started || ours.roles[i] != static_cast<int>(apci::run::Role::kUncompensated);
        if (started) out.push_back(ours.path[i]);
    }
    return out;
}

// Our compensated path: the segments of G41/G42 (not the rapid move before, nor the move
// after G40).
std::vector<Element> compensated_path(const OurRun& ours) {
    std::vector<Element> out;
    for (std::size_t i = 0; i < ours.path.size(); ++i)
        if (ours.roles[i] != static_cast<int>(apci::run::Role::kUncompensated))
            out.push_back(ours.path[i]);
    return out;
}

struct Figures {
    int contours = 0, both_paths = 0, both_refuse = 0, linuxcnc_gouges_ours_refuses = 0;
    int false_refusals = 0, missed_gouges = 0, our_gouges = 0, unexpected = 0;
    int near_self = 0, both_run_near_itself = 0, ours_warns = 0;
    int skipped_band = 0, skipped_room = 0;
    int beyond_one_profile = 0;  // ours refuses where the trim reaches past a tangent short element
    int g19 = 0;                 // G17 contours run again as G19
    int strict = 0;                   // contours whose arcs' radii agree within kStrictMismatch
    double max_deviation_strict = 0.0, max_mismatch = 0.0;
    int by_plane[2] = {0, 0}, by_decimals[2] = {0, 0}, arcs = 0, short_elements = 0;
    double max_deviation = 0.0;
    double max_whole = 0.0;  // the whole paths, approach and departure included
    std::vector<double> deviations;
};

std::string describe(const Case& c) {
    return "seed " + std::to_string(c.program.seed) + " r " + std::to_string(c.program.r) +
           (c.program.left ? " G41" : " G42") + " G" + std::to_string(c.program.plane) + " " +
           std::to_string(c.program.decimals) + " decimals\n" + our_program(c.program);
}

// `count` random contours (`cases`), with the count of those left out in `f`.
void generate_cases(int count, std::vector<Case>& cases, Figures& f) {
    Rng master(0x1CEC0DE5ULL);
    while (static_cast<int>(cases.size()) < count) {
        Case c;
        const Made m = make_case(master.next(), c);
        if (m == Made::kNoRoom) ++f.skipped_room;
        if (m == Made::kInLinuxCncBand) ++f.skipped_band;
        if (m == Made::kOk) cases.push_back(std::move(c));
    }
}

// rs274's run of every case, in the order of `cases`. rs274 reads the tool table once per run:
// the programs are grouped by radius and plane.
std::vector<Rs274Result> run_linuxcnc(const std::vector<Case>& cases) {
    std::map<std::pair<double, int>, std::vector<std::size_t>> groups;
    for (std::size_t i = 0; i < cases.size(); ++i)
        groups[{cases[i].program.r, cases[i].program.plane}].push_back(i);
    std::vector<Rs274Result> theirs(cases.size());
    const int parallel = static_cast<int>(std::max(2u, 2 * std::thread::hardware_concurrency()));
    for (const auto& [key, indices] : groups) {
        std::vector<std::string> programs;
        for (std::size_t i : indices) programs.push_back(linuxcnc_program(cases[i].program));
        auto results = run_rs274(rs274(), programs, rs274_tool_table(key.first), key.second, parallel);
        for (std::size_t k = 0; k < indices.size(); ++k) theirs[indices[k]] = std::move(results[k]);
    }
    return theirs;
}

// The failures of the test: at most three of each kind (the text before the first ':'), with
// their programs.
class FailureReport {
  public:
    void operator()(const std::string& what, const Case& c) {
        const std::string kind = what.substr(0, what.find(':'));
        if (++reported_[kind] <= 3) ADD_FAILURE() << what << "\n" << describe(c);
    }

  private:
    std::map<std::string, int> reported_;
};

// The contour's share of the figures: its plane, decimals, arcs and short elements.
void count_contour(const Case& c, Figures& f) {
    ++f.contours;
    ++f.by_plane[c.program.plane == 18];
    ++f.by_decimals[c.program.decimals == 6];
    for (const Element& e : c.contour) {
        f.arcs += is_arc(e);
        f.short_elements += length(e) < 0.5;
    }
}

// Our run of the case; a G17 contour runs again as G19 (LinuxCNC has none): the contour's
// (first, second) as (Y, Z), I/J as J/K, is compensated exactly as in X-Y.
OurRun run_ours_in_both_planes(const Case& c, Figures& f, FailureReport& report) {
    OurRun ours = run_ours(c.program);
    if (c.program.plane == 17) {
        DiffProgram turned = c.program;
        turned.plane = 19;
        ++f.g19;
        if (const std::string d = differs(ours, run_ours(turned)); !d.empty()) {
            report("G19 differs from G17: " + d, c);
            ++f.unexpected;
        }
    }
    return ours;
}

// What rs274 made of a case: whether it gouges (refuses with a gouge message, or its path comes
// closer to the contour than r - kGougeTolerance) and its path over the window.
struct LinuxCncOutcome {
    bool gouges = false;
    std::vector<Element> window;
};

// rs274's outcome for the case; false (reported) when it refused for a reason that is no gouge
// or its path misses the window.
bool linuxcnc_outcome(const Case& c, const Rs274Result& lc, double slack, double spacing,
                      Figures& f, FailureReport& report, LinuxCncOutcome& out) {
    if (lc.exit_code != 0) {
        if (!gouge_message(lc.error)) {
            report("rs274 refused for a reason that is no gouge: " + lc.error, c);
            ++f.unexpected;
            return false;
        }
        out.gouges = true;
        return true;
    }
    out.window = window(feed_path(lc.moves), c.window_from, c.window_to, kWindowTolerance + slack);
    if (out.window.empty()) {
        report("the window is not on rs274's path", c);
        ++f.unexpected;
        return false;
    }
    out.gouges = clearance(out.window, c.contour, c.program.r, spacing) <
                 c.program.r - kGougeTolerance - slack;
    return true;
}

// Our refusal judged: a gouge refusal where rs274 gouges too, or beyond what one held profile
// can avoid; anything else a false refusal (or an unexpected error).
void judge_refusal(const Case& c, const OurRun& ours, const Rs274Result& lc, bool lc_gouges,
                   Figures& f, FailureReport& report) {
    if (ours.error.rfind("KorrError", 0) != 0 && ours.error.rfind("CalcError", 0) != 0) {
        report("ours refused for a reason that is no gouge: " + ours.error, c);
        ++f.unexpected;
    } else if (lc_gouges) {
        ++(lc.exit_code != 0 ? f.both_refuse : f.linuxcnc_gouges_ours_refuses);
    } else if (beyond_one_profile(c, ours)) {
        ++f.beyond_one_profile;
    } else {
        report("false refusal: ours says " + ours.error + "; rs274 keeps the radius", c);
        ++f.false_refusals;
    }
}

// Our path may come near the contour only where the contour comes back near itself
// (away from the corner of the path's element), and then the run warns.
Approach judge_self_approach(const Case& c, const OurRun& ours,
                             const std::vector<Element>& our_window, double spacing, Figures& f,
                             FailureReport& report) {
    const double r = c.program.r;
    const Approach approach = our_path_approaches(ours, c);
    const bool ours_gouges = clearance(our_window, c.contour, r, spacing) < r - kOurGougeTolerance;
    if (approach == Approach::kNear) ++f.near_self;
    if (approach == Approach::kNear && !ours.self_approach) {
        report("missed self-approach: our path comes near the contour, no warning", c);
        ++f.our_gouges;
    } else if (approach == Approach::kClear && ours.self_approach) {
        report("false self-approach: the run warns, our path keeps the radius", c);
        ++f.unexpected;
    } else if (ours_gouges && approach == Approach::kClear) {
        report("our path gouges: away from any self-approach", c);
        ++f.our_gouges;
    }
    if (approach == Approach::kNear && ours.self_approach) ++f.ours_warns;
    return approach;
}

// Both give a path: the windows agree within kMaxDeviation (and the slack of a contour whose
// arcs' radii differ), and so do the whole paths.
void compare_paths(const Case& c, const OurRun& ours, const Rs274Result& lc,
                   const std::vector<Element>& lc_window, const std::vector<Element>& our_window,
                   double spacing, double slack, Figures& f, FailureReport& report) {
    ++f.both_paths;
    const double dev = hausdorff(our_window, lc_window, spacing);
    f.deviations.push_back(dev);
    f.max_deviation = std::max(f.max_deviation, dev);
    if (c.arc_mismatch <= kStrictMismatch)
        f.max_deviation_strict = std::max(f.max_deviation_strict, dev);
    if (dev > kMaxDeviation + slack)
        report("paths differ: by " + std::to_string(dev) + " mm (arc radii differ by " +
                   std::to_string(c.arc_mismatch) + ")",
               c);
    // The whole tool path: the entry move (our approach under G139) and the exit move after
    // G40 as well.
    const double whole = hausdorff(whole_path(ours), feed_path(lc.moves), spacing);
    f.max_whole = std::max(f.max_whole, whole);
    if (whole > kMaxDeviation + slack)
        report("whole paths differ: by " + std::to_string(whole) +
                   " mm with approach and departure (arc radii differ by " +
                   std::to_string(c.arc_mismatch) + ")",
               c);
}

// One case judged against rs274's run (the verdicts at the top of this file); the time our runs
// took added to t_ours.
void judge_case(const Case& c, const Rs274Result& lc, Figures& f, FailureReport& report,
                double& t_ours) {
    const double r = c.program.r;
    count_contour(c, f);
    if (!lc.ran) {
        report("rs274 did not run", c);
        ++f.unexpected;
        return;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const OurRun ours = run_ours_in_both_planes(c, f, report);
    t_ours += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double spacing = std::min(0.05, r / 10);
    const bool strict = c.arc_mismatch <= kStrictMismatch;
    const double slack = strict ? 0.0 : 2 * c.arc_mismatch;
    f.strict += strict;
    f.max_mismatch = std::max(f.max_mismatch, c.arc_mismatch);
    LinuxCncOutcome theirs;
    if (!linuxcnc_outcome(c, lc, slack, spacing, f, report, theirs)) return;
    if (!ours.ok) {
        judge_refusal(c, ours, lc, theirs.gouges, f, report);
        return;
    }
    const std::vector<Element> our_window =
        window(compensated_path(ours), c.window_from, c.window_to, 1e-6);
    if (our_window.empty()) {
        report("the window is not on our path", c);
        ++f.unexpected;
        return;
    }
    const bool near_self =
        judge_self_approach(c, ours, our_window, spacing, f, report) != Approach::kClear;
    if (theirs.gouges) {
        // rs274 refuses or cuts in where ours gives a path: only where the contour comes
        // near itself (both gouge; ours warns), else it is a gouge we missed.
        if (near_self) {
            ++f.both_run_near_itself;
        } else {
            report("missed gouge: rs274 " +
                       (lc.exit_code != 0 ? "says " + lc.error
                                          : std::string("cuts into the contour")) +
                       "; ours gives a path",
                   c);
            ++f.missed_gouges;
        }
        return;
    }
    if (near_self) return;  // rs274 keeps the radius here; no comparison of paths
    compare_paths(c, ours, lc, theirs.window, our_window, spacing, slack, f, report);
}

// The figures of the whole run, printed (`deviations` sorted for the quantiles).
void print_figures(Figures& f) {
    std::sort(f.deviations.begin(), f.deviations.end());
    const auto quantile = [&](double q) {
        return f.deviations.empty() ? 0.0
                                    : f.deviations[static_cast<std::size_t>(q * (f.deviations.size() - 1))];
    };
    std::printf(
        "contours %d (G17 %d, G18 %d; 3 decimals %d, 6 decimals %d; %d arcs, %d elements under "
        "0.5 mm); the G17 ones run again as G19: %d\n"
        "  both give a path %d: deviation median %.2e, 99%% %.2e, max %.2e mm; max %.2e mm on "
        "the %d contours whose arcs' radii agree within %.0e (largest difference %.2e)\n"
        "  both refuse %d; rs274's path cuts in and ours refuses %d; ours refuses where the trim "
        "reaches back past an element joined without a trim (one profile held) %d\n"
        "  false refusals %d, missed gouges %d, our path gouges %d, unexpected %d\n"
        "  our path comes near the contour away from a corner %d (warned %d), rs274 also cuts in "
        "there %d\n"
        "  left out: %d in LinuxCNC's tolerance bands, %d without room\n"
        "  the whole paths (approach and departure included): max %.2e mm\n",
        f.contours, f.by_plane[0], f.by_plane[1], f.by_decimals[0], f.by_decimals[1], f.arcs,
        f.short_elements, f.g19, f.both_paths, quantile(0.5), quantile(0.99), f.max_deviation,
        f.max_deviation_strict, f.strict, kStrictMismatch, f.max_mismatch,
        f.both_refuse, f.linuxcnc_gouges_ours_refuses, f.beyond_one_profile, f.false_refusals, f.missed_gouges,
        f.our_gouges, f.unexpected, f.near_self, f.ours_warns, f.both_run_near_itself,
        f.skipped_band, f.skipped_room, f.max_whole);
}

TEST(LinuxCncDifferential, RandomContoursAgreeWithRs274) {
    if (!rs274().why.empty()) GTEST_SKIP() << rs274().why;
    const auto t_start = std::chrono::steady_clock::now();
    constexpr int kContours = 2600;
    std::vector<Case> cases;
    Figures f;
    generate_cases(kContours, cases, f);
    const auto t_generated = std::chrono::steady_clock::now();
    const std::vector<Rs274Result> theirs = run_linuxcnc(cases);

    const auto t_rs274 = std::chrono::steady_clock::now();
    double t_ours = 0.0;
    FailureReport report;
    for (std::size_t i = 0; i < cases.size(); ++i)
        judge_case(cases[i], theirs[i], f, report, t_ours);
    const auto t_end = std::chrono::steady_clock::now();
    const auto seconds = [](auto a, auto b) {
        return std::chrono::duration<double>(b - a).count();
    };
    std::printf("time: generating %.1f s, rs274 %.1f s, ours %.1f s, comparing %.1f s\n",
                seconds(t_start, t_generated), seconds(t_generated, t_rs274), t_ours,
                seconds(t_rs274, t_end) - t_ours);
    print_figures(f);
    EXPECT_GE(f.contours, 2000);
    EXPECT_GE(f.g19, 1000);
    EXPECT_GE(f.strict, 2000);
    EXPECT_LE(f.max_deviation_strict, kMaxDeviation);
    EXPECT_EQ(f.false_refusals, 0);
    EXPECT_EQ(f.missed_gouges, 0);
    EXPECT_EQ(f.our_gouges, 0);
    EXPECT_EQ(f.unexpected, 0);
    // Enough of every outcome that the verdicts mean something.
    EXPECT_GE(f.near_self, 10);
    EXPECT_GE(f.both_paths, 1000);
    EXPECT_GE(f.both_refuse + f.linuxcnc_gouges_ours_refuses, 50);
}

}  // namespace
}  // namespace apci::test
