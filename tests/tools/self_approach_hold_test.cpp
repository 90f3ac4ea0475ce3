// SPDX-License-Identifier: MIT
// The self-approach check with calls held back (SelfApproachCheck::Schedule::kHoldApart, the
// default; docs/performance.md "Stretches held back") against the reference that works every
// call at once (kAtOnce): the same findings, the same warnings, given out at the same call, the
// same notices. Fed as the run feeds it: the calls the executor makes on the embedded emulator
// for programs shaped like CAM output (every family of tests/support/cam_programs.h, correct,
// gouging and refused, and the benchmark's program of profiles placed apart), recorded once and
// given to two SelfApproachSinks; and stretches fed to the check directly, with the programmed
// moves running ahead of the executed ones by a random lead, with small windows and entry
// budgets (the grid lets items go), planes, tool radii, CDOF and stretches too long to hold.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <random>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "apci/apci.hpp"
#include "apci/run/executor.h"
#include "apci/run/program_run.h"
#include "apci/run/self_approach.h"
#include "apci/run/self_approach_sink.h"
#include "cam_program.h"
#include "cam_programs.h"
#include "test_segments.h"

namespace apci::test {
namespace {

using run::PathSegment;
using run::Point;
using run::Role;
using run::SegmentKind;
using run::SelfApproachCheck;
using run::SelfApproachFinding;
using Schedule = SelfApproachCheck::Schedule;

// ---- The run's calls, recorded once, given to both schedules.

struct Programmed {
    PathSegment s;
};
struct Executed {
    PathSegment s;
};
struct Begin {
    run::CompensatedStretch s;
};
struct End {};
struct Walls {
    bool on;
};
struct Error {
    run::RunError e;
    Point where;
};
using Event = std::variant<Programmed, Executed, Begin, End, Walls, Error>;

// What the executor hands the sinks behind it (the check off: the calls the check's sink gets).
class Recorder final : public run::RunSink {
  public:
    void programmed(const PathSegment& s) override { events.emplace_back(Programmed{s}); }
    void executed(const PathSegment& s) override { events.emplace_back(Executed{s}); }
    void stretch_begin(const run::CompensatedStretch& s) override { events.emplace_back(Begin{s}); }
    void stretch_end() override { events.emplace_back(End{}); }
    void walls(bool on) override { events.emplace_back(Walls{on}); }
    void error(const run::RunError& e, const Point& where) override {
        events.emplace_back(Error{e, where});
    }
    std::vector<Event> events;
};

std::vector<Event> record(const std::string& text, const std::string& tools) {
    run::RunInputFiles files;
    files.tools = tools;
    files.tools_is_text = true;
    auto inputs = run::load_run_inputs(files);
    EXPECT_TRUE(static_cast<bool>(inputs));
    if (!inputs) return {};
    apci::Board board("emu:");
    EXPECT_TRUE(board.is_open());
    Recorder sink;
    run::RunSettings settings;
    settings.self_approach = run::SelfApproachMode::kOff;
    auto ran = run::run_program(board, sink, inputs.value(),
                                run::ProgramSource::in_memory(text, "hold.nc"), settings);
    EXPECT_TRUE(static_cast<bool>(ran));
    return std::move(sink.events);
}

// What a check's sink gives the sink behind it: each warning with the number of the call it
// came at.
class Warnings final : public run::RunSink {
  public:
    void warning(const run::RunError& w, const Point& where) override {
        given.push_back({at, w.block.number, w.block.line, w.code, w.message, where});
    }
    struct Given {
        std::size_t at;
        std::int64_t number;
        std::uint64_t line;
        std::string code, message;
        Point where;
        bool operator==(const Given&) const = default;
    };
    std::size_t at = 0;
    std::vector<Given> given;
};

struct Replayed {
    std::vector<Warnings::Given> warnings;
    run::RunOutcome outcome;
    std::size_t most_held = 0;  // of the check's sink held back at once (kHoldApart)
};

void give(run::SelfApproachSink& sink, const Event& e) {
    std::visit(
        [&](const auto& x) {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, Programmed>) sink.programmed(x.s);
            if constexpr (std::is_same_v<T, Executed>) sink.executed(x.s);
            if constexpr (std::is_same_v<T, Begin>) sink.stretch_begin(x.s);
            if constexpr (std::is_same_v<T, End>) sink.stretch_end();
            if constexpr (std::is_same_v<T, Walls>) sink.walls(x.on);
            if constexpr (std::is_same_v<T, Error>) sink.error(x.e, x.where);
        },
        e);
}

// Both schedules given the same calls, side by side: the warnings must agree after every call
// (a difference is reported at the first call it shows at).
void expect_same_run(const std::vector<Event>& events, const std::string& name,
                     std::size_t* most_held = nullptr) {
    SCOPED_TRACE(name);
    Warnings held_out, once_out;
    run::SelfApproachSink held(held_out, run::SelfApproachMode::kWarn, Schedule::kHoldApart);
    run::SelfApproachSink once(once_out, run::SelfApproachMode::kWarn, Schedule::kAtOnce);
    for (std::size_t i = 0; i < events.size(); ++i) {
        held_out.at = once_out.at = i;
        give(held, events[i]);
        give(once, events[i]);
        if (held_out.given != once_out.given) {
            ADD_FAILURE() << "call " << i << " of " << events.size() << ": held back "
                          << held_out.given.size() << " warnings, at once "
                          << once_out.given.size();
            return;
        }
    }
    run::RunOutcome a, b;
    held.results(a);
    once.results(b);
    ASSERT_EQ(a.self_approach.size(), b.self_approach.size());
    for (std::size_t i = 0; i < a.self_approach.size(); ++i) {
        EXPECT_EQ(a.self_approach[i].distance, b.self_approach[i].distance);
        EXPECT_EQ(a.self_approach[i].where, b.self_approach[i].where);
    }
    ASSERT_EQ(a.notices.size(), b.notices.size());
    for (std::size_t i = 0; i < a.notices.size(); ++i) {
        EXPECT_EQ(a.notices[i].code, b.notices[i].code);
        EXPECT_EQ(a.notices[i].message, b.notices[i].message);
    }
    if (most_held != nullptr) *most_held = held_out.given.size();
}

// Every family of CAM-shaped programs, correct ones, gouges the run warns and gouges the
// compensation refuses: the same warnings held back as at once.
TEST(SelfApproachHold, CamProgramsOfEveryFamilyWarnAsAtOnce) {
    std::size_t warned = 0, refused = 0;
    for (const CamFamilyInfo& f : cam_families()) {
        for (std::uint64_t seed = 1; seed <= 6; ++seed) {
            const CamProgram p = generate_cam_program(f.family, seed);
            const std::vector<Event> events = record(p.text, p.tool_list);
            std::size_t given = 0;
            expect_same_run(events, p.name, &given);
            warned += given > 0 ? 1 : 0;
            refused += std::any_of(events.begin(), events.end(),
                                   [](const Event& e) { return std::holds_alternative<Error>(e); })
                           ? 1
                           : 0;
        }
    }
    // Not a comparison of silent runs only.
    EXPECT_GT(warned, 30u);
    EXPECT_GT(refused, 10u);
}

// Square bosses placed apart (tool radius 1), each closed at its start corner (or its last
// element stopping short of it) and left by a G40 line: past the exit corner (within r of it,
// crossing nothing), straight away, back up through its own last element into the part, or
// to an end just inside it. The departures are held to the part as at once,
// and each that runs back into the part is warned, once, with its G40 block.
TEST(SelfApproachHold, LeadOutsHeldBackWarnAsAtOnce) {
    std::mt19937_64 rng(27);
    std::uniform_real_distribution<double> side(8.0, 30.0), jitter(-0.5, 0.5);
    for (int round = 0; round < 6; ++round) {
        std::string text = "N10 G17 G90 D1 F600\n";
        int n = 20, crossing = 0;
        const auto word = [](char axis, double v) { return fmt::format(" {}{:.4f}", axis, v); };
        for (int k = 0; k < 24; ++k) {
            const double a = side(rng), x = 50.0 * k + jitter(rng), y = 40.0 * round + jitter(rng);
            // 0 past the corner, 1 away, 2 back in; 3 back in from a last element that stops a
            // quarter of the way short of the corner (nothing but that element near the exit);
            // 4 back in to an end 0.5 inside the last element (the program's end point: not
            // held to that element).
            const int way = static_cast<int>(rng() % 5);
            const double last_x = way == 3 ? x + 0.25 * a : x;
            const double tx = way == 0   ? x - 3.0
                              : way == 1 ? x - 2.0
                              : way == 2 ? x + 0.25 * a
                                         : x + 0.5 * a;
            const double ty = way == 0   ? y + 1.6
                              : way == 1 ? y - 4.0
                              : way == 4 ? y + 0.5
                                         : y + 0.25 * a;
            crossing += way == 2 || way == 3;
            const auto block = [&](const std::string& words) {
                text += "N" + std::to_string(n) + words + "\n";
                n += 10;
            };
            block(" G0" + word('X', x - 3.0) + word('Y', y - 3.0));
            block(" G41 G1" + word('X', x) + word('Y', y));
            block(" G1" + word('Y', y + a));
            block(word('X', x + a));
            block(word('Y', y));
            block(word('X', last_x));
            block(" G40 G1" + word('X', tx) + word('Y', ty));
        }
        text += "N" + std::to_string(n) + " M30\n";
        const std::vector<Event> events = record(text, apci::bench::contour_tools());
        std::size_t given = 0;
        expect_same_run(events, "lead-outs, round " + std::to_string(round), &given);
        EXPECT_EQ(given, static_cast<std::size_t>(crossing)) << text;
        EXPECT_GT(crossing, 0);
    }
}

// The benchmark's program (profiles placed apart, nothing repeated): the check holds nearly
// every call back and gives nothing out, as at once; with a neighbour moved onto a profile the
// pair it makes is warned at the same call.
TEST(SelfApproachHold, ProfilesPlacedApartAreHeldBackAndAgree) {
    const std::string program =
        apci::bench::cam_program(120, apci::bench::Dialect::kApcictl).text;
    const std::vector<Event> events = record(program, apci::bench::contour_tools());
    ASSERT_GT(events.size(), 3000u);
    expect_same_run(events, "cam 120");
    // Held back: the sink's check, fed alone, keeps most calls (all but those before its grid
    // sized its cells).
    Warnings out;
    run::SelfApproachSink sink(out, run::SelfApproachMode::kWarn, Schedule::kHoldApart);
    SelfApproachCheck check;
    std::vector<SelfApproachFinding> found;
    std::size_t most = 0;
    for (const Event& e : events) {
        if (const auto* p = std::get_if<Programmed>(&e)) check.programmed(p->s, found);
        if (const auto* x = std::get_if<Executed>(&e)) check.executed(x->s, found);
        if (const auto* b = std::get_if<Begin>(&e)) check.begin(b->s.radius, b->s.plane, b->s.side);
        if (std::holds_alternative<End>(e)) check.end(found);
        most = std::max(most, check.held());
    }
    EXPECT_TRUE(found.empty());
    EXPECT_GT(most, events.size() / 2);
}

// ---- Stretches fed directly, the programmed moves ahead of the executed ones.

// The stretches' segments: contour elements unless named.
PathSegment line(int n, const Point& a, const Point& b, Role role = Role::kContour) {
    return test_segments::line(n, a, b, role);
}

// A stretch: its plane, radius, whether its elements are walls, the elements and each one's
// executed segments (their blocks the element's).
struct Stretch {
    int plane = 17;
    double r = 1.0;
    bool walls = true;
    std::vector<PathSegment> elements;
    std::vector<std::vector<PathSegment>> paths;
    std::vector<std::size_t> cdof;  // elements programmed under CDOF (CDON again after each)
};

// In the plane's axes: (u, v) -> the point.
Point in_plane(int plane, double u, double v, double w = 0.0) {
    if (plane == 18) return Point(v, w, u);  // Z-X: first Z, second X
    if (plane == 19) return Point(w, u, v);  // Y-Z: first Y, second Z
    return Point(u, v, w);
}

// A closed polygon of k corners round (cx, cy) with leads, its paths beside its sides outside
// at 1.0 to 1.2 r, or (one time in `near_one_in`) 0.3 to 1.0 r: a path that comes near.
Stretch polygon(int& n, int plane, double cx, double cy, double rad, int k, double r,
                int near_one_in, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Stretch s;
    s.plane = plane;
    s.r = r;
    std::vector<std::pair<double, double>> c;
    for (int i = 0; i < k; ++i) {
        const double a = 2.0 * 3.141592653589793 * (i + 0.4 * u(rng)) / k;
        const double q = rad * (0.7 + 0.6 * u(rng));
        c.emplace_back(cx + q * std::cos(a), cy + q * std::sin(a));
    }
    const auto add = [&](double u0, double v0, double u1, double v1, Role role, double off) {
        const Point a = in_plane(plane, u0, v0), b = in_plane(plane, u1, v1);
        s.elements.push_back(line(n, a, b, role));
        const double du = u1 - u0, dv = v1 - v0, len = std::hypot(du, dv);
        const double ou = len > 0 ? dv / len * off : 0.0, ov = len > 0 ? -du / len * off : 0.0;
        s.paths.push_back({line(n, in_plane(plane, u0 + ou, v0 + ov),
                                in_plane(plane, u1 + ou, v1 + ov), role)});
        ++n;
    };
    if (c.empty()) return s;
    const double lead = 2.0 * r + 1.0;
    add(c[0].first, c[0].second + lead, c[0].first, c[0].second, Role::kApproach, 0.0);
    for (int i = 0; i < k; ++i) {
        const auto& a = c[static_cast<std::size_t>(i)];
        const auto& b = c[static_cast<std::size_t>((i + 1) % k)];
        const bool near = near_one_in > 0 && static_cast<int>(u(rng) * near_one_in) == 0;
        add(a.first, a.second, b.first, b.second, Role::kContour,
            r * (near ? 0.3 + 0.7 * u(rng) : 1.0 + 0.2 * u(rng)));
    }
    const bool near_last = near_one_in > 0 && static_cast<int>(u(rng) * near_one_in) == 0;
    add(c[0].first, c[0].second, c[0].first + lead, c[0].second, Role::kContour,
        r * (near_last ? 0.5 : 1.1));
    return s;
}

// Calls given to both checks, the executed moves `lead` elements behind the programmed ones
// (a rapid between stretches): the findings given after every call must agree.
void expect_same_feed(const std::vector<Stretch>& stretches, std::size_t window,
                      std::size_t budget, int lead, std::size_t& held_most,
                      std::size_t& findings) {
    SelfApproachCheck held(window, budget, SelfApproachCheck::Candidates::kGrid,
                           Schedule::kHoldApart);
    SelfApproachCheck once(window, budget, SelfApproachCheck::Candidates::kGrid,
                           Schedule::kAtOnce);
    std::vector<SelfApproachFinding> a, b;
    std::size_t calls = 0;
    const auto same = [&] {
        ++calls;
        held_most = std::max(held_most, held.held());
        if (a.size() != b.size()) return false;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (a[i].path_block.number != b[i].path_block.number ||
                a[i].contour_block.number != b[i].contour_block.number ||
                a[i].distance != b[i].distance || a[i].where != b[i].where)
                return false;
        return true;
    };
    // The programmed side: begin, walls, elements, end; the executed side: each element's
    // paths, then a rapid away.
    struct Call {
        int kind;  // 0 begin, 1 walls, 2 programmed, 3 end, 4 executed, 6 CDOF
        const Stretch* s;
        const PathSegment* seg;
    };
    std::vector<Call> programmed, executed;
    for (const Stretch& s : stretches) {
        programmed.push_back({0, &s, nullptr});
        programmed.push_back({1, &s, nullptr});
        for (std::size_t k = 0; k < s.elements.size(); ++k) {
            const bool off = std::find(s.cdof.begin(), s.cdof.end(), k) != s.cdof.end();
            if (off) programmed.push_back({6, &s, nullptr});
            programmed.push_back({2, &s, &s.elements[k]});
            if (off) programmed.push_back({1, &s, nullptr});
            for (const PathSegment& p : s.paths[k]) executed.push_back({4, &s, &p});
            executed.push_back({5, &s, nullptr});  // this element's executed part is done
        }
        programmed.push_back({3, &s, nullptr});
    }
    std::size_t pi = 0, ei = 0;
    int ahead = 0;  // elements programmed and not yet executed
    const PathSegment rapid = line(999999, Point(-5e3, -5e3, 50), Point(-5e3, -4e3, 50),
                                   Role::kUncompensated);
    const auto call = [&](const Call& c) {
        switch (c.kind) {
            case 0:
                held.begin(c.s->r, c.s->plane, 1);
                once.begin(c.s->r, c.s->plane, 1);
                break;
            case 1:
                held.set_walls(c.s->walls);
                once.set_walls(c.s->walls);
                break;
            case 2:
                held.programmed(*c.seg, a);
                once.programmed(*c.seg, b);
                ++ahead;
                break;
            case 3:
                held.end(a);
                once.end(b);
                held.executed(rapid, a);
                once.executed(rapid, b);
                break;
            case 4:
                held.executed(*c.seg, a);
                once.executed(*c.seg, b);
                break;
            case 6:
                held.set_walls(false);
                once.set_walls(false);
                break;
            default:
                --ahead;
                return;
        }
        ASSERT_TRUE(same()) << "after call " << calls << " (kind " << c.kind << ")";
    };
    while (ei < executed.size()) {
        while (pi < programmed.size() && (ahead <= lead || executed[ei].kind == 5)) {
            if (executed[ei].kind == 5 && ahead > 0) break;
            call(programmed[pi++]);
            if (testing::Test::HasFatalFailure()) return;
        }
        call(executed[ei++]);
        if (testing::Test::HasFatalFailure()) return;
    }
    while (pi < programmed.size()) {
        call(programmed[pi++]);
        if (testing::Test::HasFatalFailure()) return;
    }
    held.executed(line(999998, Point(1e4, 1e4, 0), Point(1e4 + 1, 1e4, 0)), a);
    once.executed(line(999998, Point(1e4, 1e4, 0), Point(1e4 + 1, 1e4, 0)), b);
    ASSERT_TRUE(same());
    const auto la = held.limits(), lb = once.limits();
    EXPECT_EQ(la.truncated, lb.truncated);
    EXPECT_EQ(la.truncated_at.number, lb.truncated_at.number);
    EXPECT_EQ(la.truncated_plane, lb.truncated_plane);
    EXPECT_EQ(la.capped, lb.capped);
    findings += b.size();
}

// A stretch along the polyline `pts` in G17 (its first segment the approach), each element's
// path its offset r to the left; `path_off[k]`, where given, moves element k's path instead.
Stretch strip(int& n, const std::vector<Point>& pts, double r,
              const std::vector<std::pair<std::size_t, Point>>& moved = {}) {
    Stretch s;
    s.r = r;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
        const Point d = (pts[k + 1] - pts[k]).normalized();
        Point off = r * Point(-d.y(), d.x(), 0);
        for (const auto& [at, by] : moved)
            if (at == k) off = by;
        const Role role = k == 0 ? Role::kApproach : Role::kContour;
        s.elements.push_back(line(n, pts[k], pts[k + 1], role));
        s.paths.push_back({line(n, pts[k] + off, pts[k + 1] + off, role)});
        ++n;
    }
    return s;
}

// A stretch along the polyline `pts` in G17 (its first segment the approach), its paths as the
// compensation makes them with the tool r to the left: where the offset lines meet at an inside
// corner, each ends there; at an outside corner an arc of radius r round the corner (a
// transition, of the element before's block) joins them.
Stretch compensated(int& n, const std::vector<Point>& pts, double r) {
    Stretch s;
    s.r = r;
    const auto dir = [&](std::size_t k) {
        const Point d = pts[k + 1] - pts[k];
        return Point(d.x(), d.y(), 0).normalized();
    };
    const auto left = [&](std::size_t k) {
        const Point d = dir(k);
        return Point(-d.y(), d.x(), 0);
    };
    const auto cross = [](const Point& a, const Point& b) { return a.x() * b.y() - a.y() * b.x(); };
    Point from = pts[0] + r * left(0);
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
        const Role role = k == 0 ? Role::kApproach : Role::kContour;
        s.elements.push_back(line(n, pts[k], pts[k + 1], role));
        const Point corner = pts[k + 1];
        Point to = corner + r * left(k), next = to;
        PathSegment transition;
        bool outside = false;
        if (k + 2 < pts.size()) {
            const double turn = cross(dir(k), dir(k + 1));
            if (turn > 1e-12) {  // inside: where the offset lines meet
                const Point shift = r * (left(k + 1) - left(k));
                to = next = corner + r * left(k) + cross(shift, dir(k + 1)) / turn * dir(k);
            } else if (turn < -1e-12) {  // outside: round the corner
                outside = true;
                next = corner + r * left(k + 1);
                transition = line(n, to, next, Role::kTransition);
                transition.kind = SegmentKind::kArc;
                transition.center = corner;
                transition.ccw = false;
            }
        }
        s.paths.push_back({line(n, from, to, role)});
        if (outside) s.paths.back().push_back(transition);
        from = next;
        ++n;
    }
    return s;
}

// Appends to s (tool radius 3, G17) a clockwise arc of 210 degrees about the origin from (0, 1)
// (more than half a turn), its path 3 mm outside it and the transition round the outside corner
// at its end, then a line leaving it whose path is moved away (clear of everything: the first
// segment of another block, where the transition's finding is given out). The transition comes
// within r of the arc's first part, more than half a turn from the corner.
void long_arc_with_transition(Stretch& s, int& n) {
    const double c150 = std::cos(2.6179938779914944), s150 = std::sin(2.6179938779914944);
    const Point e(c150, s150, 0);        // the arc's end
    const Point d2(-c150, -s150, 0);     // leaving direction: (0.866, -0.5)
    const Point n2(-d2.y(), d2.x(), 0);  // its left normal
    PathSegment a = line(n, Point(0, 1, 0), e);
    a.kind = SegmentKind::kArc;
    a.center = Point(0, 0, 0);
    a.ccw = false;
    s.elements.push_back(a);
    PathSegment offset = a;
    offset.start = Point(0, 4, 0);
    offset.end = 4.0 * e;
    PathSegment transition = offset;
    transition.role = Role::kTransition;
    transition.start = 4.0 * e;
    transition.end = e + 3.0 * n2;
    transition.center = e;
    s.paths.push_back({offset, transition});
    ++n;
    s.elements.push_back(line(n, e, e + 1.5 * d2));
    s.paths.push_back({line(n, e + Point(20, 0, 0), e + Point(20, 0, 0) + 1.5 * d2)});
    ++n;
}

// Each a shape the hold must take as the check does, with findings (not a silent comparison).
TEST(SelfApproachHold, ChosenShapesAgreeCallByCall) {
    std::vector<std::pair<std::string, std::vector<Stretch>>> cases;
    int n = 10;
    {  // a zone over more than 256 zone cells (an L a metre and a half each way), then a wall
       // beside its far leg whose path crosses within r of it
        std::vector<Stretch> v;
        v.push_back(strip(n, {Point(-5, -5, 0), Point(0, 0, 0), Point(1500, 0, 0),
                              Point(1500, 1500, 0), Point(1505, 1505, 0)},
                          1.0));
        n += 10;
        v.push_back(strip(n, {Point(1500.5, 690, 0), Point(1500.5, 700, 0),
                              Point(1500.5, 800, 0), Point(1500.5, 810, 0)},
                          1.0));
        cases.emplace_back("wide zone", std::move(v));
    }
    // A wall in G17 (tool radius r), a second one `gap` below it, then a stretch in G18 with
    // r = 1 (its plane's reach is not theirs).
    const auto walls_then_g18 = [&n](double r, double gap) {
        std::vector<Stretch> v;
        v.push_back(strip(n, {Point(-5, 0, 0), Point(0, 0, 0), Point(50, 0, 0),
                              Point(55, 0, 0)},
                          r));
        n += 10;
        v.push_back(strip(n, {Point(-5, -gap, 0), Point(0, -gap, 0), Point(50, -gap, 0),
                              Point(55, -gap, 0)},
                          r));
        n += 10;
        Stretch g18 = strip(n, {Point(500, 0, 0), Point(510, 0, 0), Point(520, 5, 0),
                                Point(530, 5, 0)},
                            1.0);
        g18.plane = 18;
        v.push_back(std::move(g18));
        return v;
    };
    // r = 4: the second wall 6 mm from the first, its path passing 2 mm from it.
    cases.emplace_back("another plane's reach", walls_then_g18(4.0, 6.0));
    // r = 8, the walls 14 mm apart: the first one's zone, proved with 4 mm of room, lies 2 mm
    // from the second one's path, which passes 6 mm from the wall: within G17's reach (8 mm),
    // not within G18's (1 mm).
    cases.emplace_back("another plane's reach beyond the room", walls_then_g18(8.0, 14.0));
    {  // a wall, one far away, then one laid over the first whose path runs 0.5 mm from it
        std::vector<Stretch> v;
        v.push_back(strip(n, {Point(-5, 0, 0), Point(0, 0, 0), Point(50, 0, 0),
                              Point(55, 0, 0)},
                          1.0));
        n += 10;
        v.push_back(strip(n, {Point(495, 0, 0), Point(500, 0, 0), Point(550, 0, 0),
                              Point(555, 0, 0)},
                          1.0));
        n += 10;
        v.push_back(strip(n, {Point(45, 1.5, 0), Point(40, 1.5, 0), Point(10, 1.5, 0),
                              Point(5, 1.5, 0)},
                          1.0));
        cases.emplace_back("laid over a stretch let go", std::move(v));
    }
    {  // a path near its stretch's last element (a reversal: given when the run leaves it),
       // then a stretch far away
        std::vector<Stretch> v;
        v.push_back(strip(n, {Point(-5, 0, 0), Point(0, 0, 0), Point(20, 0, 0),
                              Point(20, 2.5, 0), Point(0, 1.5, 0)},
                          1.0));
        n += 10;
        v.push_back(strip(n, {Point(495, 0, 0), Point(500, 0, 0), Point(550, 0, 0),
                              Point(555, 0, 0)},
                          1.0));
        cases.emplace_back("finding at a stretch's end", std::move(v));
    }
    {  // an arc of 300 degrees (radius 1, clockwise from (0, 1), the tool outside at r = 3),
       // after a short approach along it and before a short line leaving at a right angle:
       // the transition round that corner (a segment of the arc's block) is the first thing to
       // come within r of anything, of the arc's first part (more than half a turn from it)
        Stretch s;
        s.r = 3.0;
        s.elements.push_back(line(n, Point(-0.5, 1, 0), Point(0, 1, 0), Role::kApproach));
        s.paths.push_back({line(n, Point(-0.5, 4, 0), Point(0, 4, 0), Role::kApproach)});
        ++n;
        long_arc_with_transition(s, n);
        std::vector<Stretch> v;
        v.push_back(std::move(s));
        cases.emplace_back("transition near a long arc", std::move(v));
    }
    {  // a path whose start comes within r of an element programmed after it ran (no approach)
        std::vector<Stretch> v;
        v.push_back(strip(n, {Point(-5, -3, 0), Point(0, 0, 0), Point(20, 0, 0),
                              Point(20, 5, 0), Point(0, 1.3, 0), Point(-5, 1.3, 0)},
                          1.0));
        cases.emplace_back("a path's start near a later element", std::move(v));
    }
    {  // the depth rule near Z = -100: the first three elements at Z -100.000007, the path that
       // comes back along them (0.5 mm beside them, after going round) at -99.999901, so that
       // their top lies kTolerance and 1e-6 mm below its tip; the grid keeps that top as a
       // float rounded up (-100), and the check measures the pair and finds it
        const double low = -100.000007, high = -99.999901;
        std::vector<Stretch> v;
        v.push_back(strip(n, {Point(-5, 0, low), Point(0, 0, low), Point(20, 0, low),
                              Point(25, 0, low), Point(25, -20, high), Point(-5, -20, high),
                              Point(-5, -1.5, high), Point(20, -1.5, high)},
                          1.0));
        cases.emplace_back("a path just over its stretch's elements far down", std::move(v));
    }
    {  // the transition near a long arc again, the element before the arc a line under CDOF
       // (no wall, and no approach: the approach is far away), so that the arc's first part is
       // the only wall the transition comes near
        Stretch s;
        s.r = 3.0;
        s.elements.push_back(line(n, Point(-10, -4, 0), Point(-10, 1, 0), Role::kApproach));
        s.paths.push_back({line(n, Point(-13, -4, 0), Point(-13, 1, 0), Role::kApproach)});
        ++n;
        s.cdof.push_back(s.elements.size());
        s.elements.push_back(line(n, Point(-10, 1, 0), Point(0, 1, 0)));
        s.paths.push_back({line(n, Point(-10, 4, 0), Point(0, 4, 0))});
        ++n;
        long_arc_with_transition(s, n);
        std::vector<Stretch> v;
        v.push_back(std::move(s));
        cases.emplace_back("transition near a long arc after a line under CDOF", std::move(v));
    }
    {  // an approach onto an inside corner of a square (a pocket), fed one element ahead: the
       // first side's path starts 0.9 mm from the closing side, not programmed when it runs
        std::vector<Stretch> v;
        v.push_back(compensated(n, {Point(-0.5, 5, 0), Point(0, 0, 0), Point(10, 0, 0),
                                    Point(10, 10, 0), Point(0, 10, 0), Point(0, 0, 0),
                                    Point(5, 5, 0)},
                                1.0));
        cases.emplace_back("an approach onto an inside corner", std::move(v));
    }
    {  // three lines in, then a pocket with a tongue that leaves a neck of 1.5 mm for a tool of
       // 1 mm: its paths come near the pocket's side (and the side near the first path) before
       // the loop closes; the loop's close places the first line (an open contour's)
        std::vector<Stretch> v;
        v.push_back(compensated(n, {Point(5, 6, 0), Point(5, 3, 0), Point(3, 3, 0),
                                    Point(0, 0, 0), Point(20, 0, 0), Point(20, 10, 0),
                                    Point(12, 10, 0), Point(12, 1.5, 0), Point(8, 1.5, 0),
                                    Point(8, 10, 0), Point(0, 10, 0), Point(0, 0, 0),
                                    Point(2, 2, 0)},
                                1.0));
        cases.emplace_back("a neck before the loop closes", std::move(v));
    }
    {  // r = 8: a wall (g) 5 mm from the first part of a stretch's last element's path, an arc
       // of 270 degrees round a circle of 10 mm (the tool outside), so that its second part
       // runs while that finding is open, after the stretch ended; then a stretch along a line
       // 14 mm above the arc (6 mm from its path's top, 10 mm from the element's box)
        std::vector<Stretch> v;
        const double a240 = 4.1887902047863905;
        const Point g(23 * std::cos(a240), 23 * std::sin(a240), 0);
        const Point t(-std::sin(a240), std::cos(a240), 0);  // along the circle, anticlockwise
        v.push_back(compensated(n, {1.6 * (g + 2 * t), g + 2 * t, g - 2 * t}, 8.0));
        n += 10;
        Stretch s = compensated(n, {Point(30, -10, 0), Point(20, -10, 0), Point(0, -10, 0)}, 8.0);
        PathSegment arc = line(n, Point(0, -10, 0), Point(10, 0, 0));
        arc.kind = SegmentKind::kArc;
        arc.center = Point(0, 0, 0);
        arc.ccw = false;
        s.elements.push_back(arc);
        const double a210 = 3.6651914291880923;
        const Point mid(18 * std::cos(a210), 18 * std::sin(a210), 0);
        PathSegment first = arc, second = arc;
        first.start = Point(0, -18, 0);
        first.end = second.start = mid;
        second.end = Point(18, 0, 0);
        s.paths.push_back({first, second});
        v.push_back(std::move(s));
        n += 10;
        v.push_back(compensated(n, {Point(-60, 24, 0), Point(-50, 24, 0), Point(-40, 24, 0),
                                    Point(-30, 24, 0), Point(30, 24, 0), Point(40, 24, 0)},
                                8.0));
        cases.emplace_back("an arc's path boxed after its stretch ended", std::move(v));
    }
    for (const auto& [name, stretches] : cases) {
        SCOPED_TRACE(name);
        std::size_t found = 0;
        for (const int lead : {0, 1, 2, 40}) {
            SCOPED_TRACE(lead);
            std::size_t held_most = 0, findings = 0;
            expect_same_feed(stretches, SelfApproachCheck::kWindow, SelfApproachCheck::kEntryBudget,
                             lead, held_most, findings);
            if (HasFatalFailure()) return;
            found += findings;
        }
        EXPECT_GT(found, 0u);  // the shape comes near
    }
}

// `count` straight strips (tool radius r) of `per` elements of 5 mm along X from x0, 20 mm
// apart, appended to `to`: every path keeps its radius, nothing comes near.
void straight_strips(std::vector<Stretch>& to, int count, int per, double x0, double r, int& n) {
    for (int k = 0; k < count; ++k) {
        std::vector<Point> pts;
        for (int i = 0; i <= per; ++i) pts.emplace_back(x0 + 5.0 * i, 20.0 * k, 0.0);
        to.push_back(strip(n, pts, r));
        n += 100;
    }
}

// Stretches where nothing comes near, fed to both schedules with these leads: the same, and no
// finding.
void expect_same_and_silent(const std::vector<Stretch>& stretches, std::size_t window,
                            std::initializer_list<int> leads) {
    for (const int lead : leads) {
        SCOPED_TRACE(lead);
        std::size_t held_most = 0, findings = 0;
        expect_same_feed(stretches, window, SelfApproachCheck::kEntryBudget, lead, held_most,
                         findings);
        EXPECT_EQ(findings, 0u);
    }
}

// The queue of elements waiting to be executed is compacted when its head passes the 1,024th:
// the segment executed then belongs to the element at the head, not the one before it. Straight
// strips, 1,025 elements with a tool of 4 mm, then strips with 1 mm (the first of them at the
// head at that moment): every path keeps its radius, so nothing is found, by either schedule
// (a path taken as the element's before it would be held to the tool of 4 mm, and to its own
// element as another stretch's).
TEST(SelfApproachHold, ThePathAtTheQueuesCompactionIsItsOwnElements) {
    std::vector<Stretch> stretches;
    int n = 10;
    straight_strips(stretches, 205, 5, 0.0, 4.0, n);
    straight_strips(stretches, 10, 3, 1000.0, 1.0, n);
    expect_same_and_silent(stretches, SelfApproachCheck::kWindow, {0, 1, 3});
}

// A grid of a window of 24 lets items go at its 48th distinct element: here the program's last,
// with nothing found before, so that it may come while calls are held. The check that holds
// must work it (its grid lets items go there, and the run says so), as the check at once does.
TEST(SelfApproachHold, TheElementWhereTheGridLetsItemsGoIsWorked) {
    for (const int per : {6, 8, 12}) {  // elements per stretch: 48 in all
        SCOPED_TRACE(per);
        std::vector<Stretch> stretches;
        int n = 10;
        straight_strips(stretches, 48 / per, per, 0.0, 1.0, n);
        expect_same_and_silent(stretches, 24, {0, 1, 3, 60});
        // Not a comparison of runs that let nothing go.
        SelfApproachCheck once(24, SelfApproachCheck::kEntryBudget,
                               SelfApproachCheck::Candidates::kGrid, Schedule::kAtOnce);
        std::vector<SelfApproachFinding> found;
        for (const Stretch& s : stretches) {
            once.begin(s.r, 17, 1);
            for (const PathSegment& e : s.elements) once.programmed(e, found);
            once.end(found);
        }
        EXPECT_TRUE(once.limits().truncated);
    }
    // The paths' list (three a window element: 144 here) let go at its 144th path, the last:
    // 36 elements, each executed in four pieces.
    std::vector<Stretch> stretches;
    int n = 10;
    straight_strips(stretches, 6, 6, 0.0, 1.0, n);
    for (Stretch& s : stretches)
        for (auto& pieces : s.paths) {
            const PathSegment whole = pieces.front();
            pieces.clear();
            for (int q = 0; q < 4; ++q) {
                PathSegment piece = whole;
                piece.start = whole.start + (whole.end - whole.start) * (q / 4.0);
                piece.end = whole.start + (whole.end - whole.start) * ((q + 1) / 4.0);
                pieces.push_back(piece);
            }
        }
    expect_same_and_silent(stretches, 24, {0, 1, 3, 60});
}

// The sets of stretches the fed tests draw: mostly apart on a grid, now and then one placed
// onto the one before, in another plane, with a larger tool, under CDOF, or too long to hold;
// or (regime 1) a square over a metre wide (a wide zone) with small ones beside its far sides;
// or (2) stretches laid over one drawn earlier; or (3) long sides (the grid's entries fill).
std::vector<Stretch> draw(std::uint64_t seed, int regime) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Stretch> stretches;
    int n = 10;
    const int near_one_in = seed % 3 == 0 ? 6 : regime == 0 ? 0 : 4;
    if (regime == 1) {
        const double side = 1300.0 + 200.0 * u(rng);
        stretches.push_back(polygon(n, 17, side / 2, side / 2, side * 0.72, 4, 1.0, 0, rng));
        n += 10;
    }
    const int count = 20 + static_cast<int>(40 * u(rng));
    for (int k = 0; k < count; ++k) {
        const int plane = u(rng) < 0.1 ? (u(rng) < 0.5 ? 18 : 19) : 17;
        const double r = u(rng) < 0.15 ? 2.0 + 2.0 * u(rng) : 1.0;
        double cx = 60.0 * (k % 8), cy = 60.0 * (k / 8);
        double rad = 8.0 + 12.0 * u(rng);
        if (u(rng) < 0.12 && k > 0) cx -= 60.0 - 10.0 * u(rng);
        if (regime == 1) {  // beside the square's far side, about r from its path
            cx = 200.0 + 900.0 * u(rng);
            cy = stretches.front().elements[2].start.y() + rad + 1.0 + 3.0 * u(rng);
        }
        if (regime == 2 && k > 1 && u(rng) < 0.3) {  // over one drawn before
            const auto& old = stretches[static_cast<std::size_t>(u(rng) * (k - 1))];
            cx = old.elements[1].start.x() + 4.0 * u(rng);
            cy = old.elements[1].start.y() + 4.0 * u(rng);
        }
        if (regime == 3) rad = 30.0 + 50.0 * u(rng), cx *= 3.0, cy *= 3.0;
        const int sides = u(rng) < 0.05 ? 300 : 3 + static_cast<int>(9 * u(rng));
        Stretch s = polygon(n, plane, cx, cy, rad, sides, r, near_one_in, rng);
        s.walls = u(rng) > 0.08;
        stretches.push_back(std::move(s));
        n += 10;
    }
    return stretches;
}

// One test for each regime of draw(): they run side by side (each is a few seconds, five
// times that under AddressSanitizer).
class StretchesFedWithALead : public ::testing::TestWithParam<int> {};

TEST_P(StretchesFedWithALead, AgreeCallByCall) {
    const int regime = GetParam();
    std::size_t held_most = 0, findings = 0;
    for (std::uint64_t k = 1; k <= 12; ++k) {
        SCOPED_TRACE(::testing::Message() << "regime " << regime << " set " << k);
        const std::vector<Stretch> stretches = draw(100 * regime + k, regime);
        // No lookahead, a little, or much (every element of several stretches ahead).
        for (const int lead : {0, 1 + static_cast<int>(k % 7), 40}) {
            for (const auto& [window, budget] :
                 {std::pair<std::size_t, std::size_t>{SelfApproachCheck::kWindow,
                                                      SelfApproachCheck::kEntryBudget},
                  {256, 4096},
                  {40, 400},
                  {24, 96}}) {
                SCOPED_TRACE(::testing::Message() << "lead " << lead << " window " << window);
                expect_same_feed(stretches, window, budget, lead, held_most, findings);
                if (HasFatalFailure()) return;
            }
        }
    }
    EXPECT_GT(held_most, 50u);  // calls were held back
    EXPECT_GT(findings, 50u);   // and findings given out
}

INSTANTIATE_TEST_SUITE_P(SelfApproachHold, StretchesFedWithALead, ::testing::Range(0, 4));

// More calls held than one chunk of the hold's memory keeps (2 MiB: about 18,700 calls),
// then a stretch laid onto the first strip's wall: every call kept is worked, in order, across
// the chunks, and the findings are those of the check at once.
// A stretch's record keeps at most 256 elements and 256 paths (Hold::kOwn): a stretch of 256
// is held like any other, and the holding goes on after it; its 257th element ends the holding
// for the run (the calls kept are worked, none kept after). Fed to a held check alone, each
// element executed after it is programmed, after 80 short strips (the grid sized, holding
// begun), then four more short strips far from the others.
TEST(SelfApproachHold, TheTwoHundredAndFiftySeventhItemOfAStretchEndsTheHolding) {
    for (const int per : {256, 257}) {
        SCOPED_TRACE(per);
        std::vector<Stretch> stretches;
        int n = 10;
        straight_strips(stretches, 80, 5, 0.0, 1.0, n);
        std::vector<Point> pts;
        for (int i = 0; i <= per; ++i) pts.emplace_back(5.0 * i, -500.0, 0.0);
        stretches.push_back(strip(n, pts, 1.0));
        n += 1000;
        straight_strips(stretches, 4, 5, 3000.0, 1.0, n);
        SelfApproachCheck check(SelfApproachCheck::kWindow, SelfApproachCheck::kEntryBudget,
                                SelfApproachCheck::Candidates::kGrid, Schedule::kHoldApart);
        std::vector<SelfApproachFinding> found;
        const PathSegment rapid =
            line(999999, Point(-5e3, -5e3, 50), Point(-5e3, -4e3, 50), Role::kUncompensated);
        std::size_t held_before = 0, held_in_long = 0, held_after = 0;
        for (std::size_t i = 0; i < stretches.size(); ++i) {
            const Stretch& st = stretches[i];
            check.begin(st.r, st.plane, 1);
            check.set_walls(true);
            for (std::size_t k = 0; k < st.elements.size(); ++k) {
                check.programmed(st.elements[k], found);
                for (const PathSegment& p : st.paths[k]) check.executed(p, found);
                if (i == 80) held_in_long = std::max(held_in_long, check.held());
            }
            check.end(found);
            check.executed(rapid, found);
            std::size_t& most = i < 80 ? held_before : i == 80 ? held_in_long : held_after;
            most = std::max(most, check.held());
        }
        EXPECT_TRUE(found.empty());
        EXPECT_GT(held_before, 0u);  // holding had begun
        if (per == 256) {
            EXPECT_GT(held_in_long, 2u * 256u);   // the long stretch's calls kept
            EXPECT_GT(held_after, held_in_long);  // and the later ones
        } else {
            EXPECT_EQ(held_after, 0u) << "calls kept after a stretch of 257 elements";
        }
    }
}

TEST(SelfApproachHold, CallsHeldOverSeveralChunksAreWorkedInOrder) {
    std::vector<Stretch> stretches;
    int n = 10;
    straight_strips(stretches, 3500, 5, 0.0, 1.0, n);
    stretches.push_back(strip(n, {Point(-5, 0.5, 0), Point(2, 0.5, 0), Point(20, 0.5, 0),
                                  Point(22, 0.5, 0)},
                              1.0, {{1, Point(0, -0.5, 0)}}));
    std::size_t held_most = 0, findings = 0;
    expect_same_feed(stretches, SelfApproachCheck::kWindow, SelfApproachCheck::kEntryBudget, 1,
                     held_most, findings);
    EXPECT_GT(held_most, 40'000u);
    EXPECT_GT(findings, 0u);
}

}  // namespace
}  // namespace apci::test

