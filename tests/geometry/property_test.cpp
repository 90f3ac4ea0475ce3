// SPDX-License-Identifier: MIT
// Property tests of PathCompensator over generated contours: random open chains and
// closed loops of lines and arcs, tool radii 0.01 .. 50, both sides, both transition
// modes, mapped through the planes 17/18/19 as the spooler maps them.
//
// Properties: no point of the compensated path (approach and departure aside) is closer
// to the programmed contour than r - 1e-6; every point is at r within 1e-6 except on
// linear transitions; every programmed element that survives compensation is covered by
// its offset; a contour that cannot be compensated gets the right error bit instead of a
// path, where the condition (concave arc radius <= r: CalcError; an element the corners
// would reverse or a corner without solution: KorrError) is computed here independently
// of the library's offset, intersection and trimming code (by marching along the offset
// and measuring distances).
//
// The generator keeps non-adjacent elements more than 2r apart, and adjacent ones apart
// except at their common corner (walking away from the corner along either, the distance
// to the other grows until it exceeds 2r): with one element of lookahead, any control can
// gouge where the contour comes back near itself, so global self-approach is excluded from
// the input rather than from the properties. Closed loops
// start and end in the middle of an element (a tangent closure), as NC programmers start
// compensated closed contours. Contours within 1e-6 of an error threshold are regenerated
// (the decision there is rounding). Fixed seeds: every run is the same.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "contours.h"
#include "rwmos/geometry/compensator.h"
#include "rwmos/geometry/shared.h"

namespace rwmos::geom {
namespace {

using apci::test::arc_from;
using apci::test::dir;
using apci::test::diverge;
using apci::test::heading;
using apci::test::Rng;
using apci::test::turned;

constexpr double kPi = std::numbers::pi;
constexpr double kPropertyTolerance = 1e-6;

// ---- Contour generation ----

struct Contour {
    std::vector<Element> elements;
    double r = 1.0;
    bool closed = false;
    std::uint64_t seed = 0;
};

// Non-adjacent elements stay more than 2r apart, with a margin of r / 4.
bool clear_of(const Element& e, const Element& other, double r) {
    return apci::test::clear_of(e, other, r, r / 4);
}

// A random walk of lines and arcs; each new element stays more than 2r from all but its
// predecessor.
Contour open_chain(Rng& rng, double r) {
    Contour c;
    c.r = r;
    const int n = rng.integer(2, 10);
    const bool short_prone = rng.chance(0.4);
    Vec2 p = Vec2::Zero();
    double h = rng.uniform(0, 2 * kPi);
    for (int i = 0; i < n; ++i) {
        bool placed = false;
        for (int attempt = 0; attempt < 30 && !placed; ++attempt) {
            double turn = 0;
            if (i > 0 && !rng.chance(0.2))
                turn = (rng.chance(0.5) ? 1 : -1) * rng.uniform(3, 170) * kPi / 180;
            const double start_heading = h + turn;
            Element e;
            if (rng.chance(0.5)) {
                const double len =
                    r * (short_prone ? rng.log_uniform(0.2, 8) : rng.log_uniform(2, 20));
                e = make_line(p, p + len * dir(start_heading));
            } else {
                const double radius = r * rng.log_uniform(0.6, 30);
                const double sweep = rng.uniform(10, short_prone ? 60 : 120) * kPi / 180;
                e = arc_from(p, start_heading, radius, rng.chance(0.5) ? sweep : -sweep);
            }
            placed = c.elements.empty() || diverge(c.elements.back(), e, r);
            for (std::size_t j = 0; j + 1 < c.elements.size() && placed; ++j)
                placed = clear_of(e, c.elements[j], r);
            if (placed) c.elements.push_back(e);
        }
        if (!placed) break;
        p = c.elements.back().end;
        h = heading(end_tangent(c.elements.back()));
    }
    return c;
}

// A star-shaped loop of lines and arcs, started in the middle of its first element.
Contour closed_loop(Rng& rng, double r) {
    Contour c;
    c.r = r;
    c.closed = true;
    const int n = rng.integer(3, 9);
    const double size = r * rng.log_uniform(4, 40);
    std::vector<double> angles;
    angles.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) angles.push_back(rng.uniform(0, 2 * kPi));
    std::sort(angles.begin(), angles.end());
    const bool reverse = rng.chance(0.5);
    if (reverse) std::reverse(angles.begin(), angles.end());
    std::vector<Vec2> corners;
    corners.reserve(angles.size());
    for (double a : angles) corners.emplace_back(size * rng.uniform(0.6, 1.4) * dir(a));
    std::vector<Element> loop;
    for (int i = 0; i < n; ++i) {
        const Vec2 a = corners[i];
        const Vec2 b = corners[(i + 1) % n];
        if ((b - a).norm() < 1e-3 * size) return c;
        if (rng.chance(0.5)) {
            loop.push_back(make_line(a, b));
        } else {
            // An arc through a and b turning by sweep, bulging to either side.
            const double sweep = rng.uniform(10, 120) * kPi / 180 * (rng.chance(0.5) ? 1 : -1);
            const double chord = (b - a).norm();
            const double radius = chord / (2 * std::sin(std::abs(sweep) / 2));
            const double start_heading = heading(b - a) - sweep / 2;
            Element e = arc_from(a, start_heading, radius, sweep);
            e.end = b;  // exact closure; the rounding difference is far below tolerance
            loop.push_back(e);
        }
    }
    // Adjacent elements diverge from their corner; non-adjacent ones (cyclically) stay more
    // than 2r apart.
    for (int i = 0; i < n; ++i)
        if (!diverge(loop[i], loop[(i + 1) % n], r)) return c;
    for (int i = 0; i < n; ++i)
        for (int j = i + 2; j < n; ++j)
            if (!(i == 0 && j == n - 1) && !clear_of(loop[i], loop[j], r)) return c;
    // Split the first element at its middle: the loop starts and ends there.
    const Element& first = loop[0];
    const Vec2 mid = point_at(first, 0.5);
    Element head = first, tail = first;
    head.start = mid;
    tail.end = mid;
    c.elements.push_back(head);
    for (int i = 1; i < n; ++i) c.elements.push_back(loop[i]);
    c.elements.push_back(tail);
    return c;
}

// ---- The independent expectation ----

bool concave_for(const Element& arc, Side side) {
    return arc.ccw == (side == Side::kLeft);
}

// Offset point at fraction t of the element: beside point_at(t), r to the tool side.
Vec2 offset_at(const Element& e, double t, double r, Side side) {
    return point_at(e, t) + (side == Side::kLeft ? r : -r) * left_normal(tangent_at(e, t));
}

// Fraction of the element at which its point nearest x lies.
double fraction_of_nearest(const Element& e, const Vec2& x) {
    const Vec2 q = closest_point(e, x);
    if (!is_arc(e)) return (q - e.start).dot(e.end - e.start) / (e.end - e.start).squaredNorm();
    return angle_between(e.start - e.centre, q - e.centre, e.ccw) / std::abs(sweep(e));
}

double offset_length_of(const Element& e, double r, Side side) {
    if (!is_arc(e)) return length(e);
    return length(e) * (radius(e) + (concave_for(e, side) ? -r : r)) / radius(e);
}

// How far p is from the offset carrier of e (the offset line, or the offset circle),
// signed, and where p's foot lies on e as a fraction of e (unbounded for lines, an angle
// fraction in [0, 2 pi / sweep) for arcs).
struct CarrierReading {
    double residual;
    double fraction;
};
CarrierReading read_carrier(const Element& e, const Vec2& p, double r, Side side) {
    const double s = side == Side::kLeft ? 1.0 : -1.0;
    if (!is_arc(e)) {
        const Vec2 t = (e.end - e.start).normalized();
        const Vec2 v = p - e.start;
        return {s * cross(t, v) - r, v.dot(t) / length(e)};
    }
    const double rho = radius(e) + (concave_for(e, side) ? -r : r);
    return {(p - e.centre).norm() - rho,
            angle_between(e.start - e.centre, p - e.centre, e.ccw) / std::abs(sweep(e))};
}

struct Expectation {
    bool ambiguous = false;
    int failing_push = -1;  // -1: compensable
    ErrorBits bits = 0;
    std::vector<double> t_start, t_end;  // surviving fraction of every element
};

// Walks the contour as the compensator must: CalcError where the tool does not fit into
// a concave arc; at inside corners, the trim point is found by marching back along the
// held element's offset from the corner to the first point that lies on the next
// element's offset carrier with its foot on the next element; KorrError where there is
// none within what is left of the held element, or where it leaves nothing of the next.
Expectation expect(const Contour& c, Side side) {
    const std::vector<Element>& E = c.elements;
    const double r = c.r;
    const double band = kPropertyTolerance * std::max(1.0, r);
    Expectation x;
    x.t_start.assign(E.size(), 0.0);
    x.t_end.assign(E.size(), 1.0);
    auto fail = [&](std::size_t k, ErrorBit bit) {
        x.failing_push = static_cast<int>(k);
        x.bits = bits(bit);
        return x;
    };
    auto ambiguous = [&] {
        x.ambiguous = true;
        return x;
    };
    for (std::size_t k = 0; k < E.size(); ++k) {
        const Element& b = E[k];
        if (is_arc(b) && concave_for(b, side)) {
            if (std::abs(radius(b) - r) < band) return ambiguous();
            if (radius(b) < r) return fail(k, ErrorBit::kCalcError);
        }
        if (k == 0) continue;
        const Element& a = E[k - 1];
        const double turn = std::atan2(cross(end_tangent(a), start_tangent(b)),
                                       end_tangent(a).dot(start_tangent(b)));
        if (std::abs(turn) < 1e-7) continue;                // generated tangent join
        if ((turn > 0) != (side == Side::kLeft)) continue;  // outside corner: no trim
        const double len_a = offset_length_of(a, r, side);
        const double len_b = offset_length_of(b, r, side);
        auto h = [&](double t) { return read_carrier(b, offset_at(a, t, r, side), r, side); };
        const double lowest = x.t_start[k - 1];
        const int steps = 4000;
        double found = -1;
        double prev_t = 1.0;
        CarrierReading prev = h(1.0);
        for (int i = steps - 1; i >= 0 && found < 0; --i) {
            const double t = lowest + (1.0 - lowest) * i / steps;
            const CarrierReading now = h(t);
            if ((now.residual <= 0) != (prev.residual <= 0)) {
                double lo = t, hi = prev_t;  // root between; h(lo) and h(hi) differ in sign
                const bool lo_negative = now.residual <= 0;
                for (int n = 0; n < 200 && hi - lo > 1e-16; ++n) {
                    const double mid = 0.5 * (lo + hi);
                    ((h(mid).residual <= 0) == lo_negative ? lo : hi) = mid;
                }
                const double root = 0.5 * (lo + hi);
                const double foot = h(root).fraction;
                if (std::abs(foot - 1.0) * len_b < band || std::abs(foot) * len_b < band)
                    return ambiguous();
                if (foot > 0 && foot < 1) found = root;
            }
            prev_t = t;
            prev = now;
        }
        if (found < 0) return fail(k, ErrorBit::kKorrError);
        if ((found - lowest) * len_a < band) return ambiguous();
        x.t_end[k - 1] = found;
        x.t_start[k] = h(found).fraction;
    }
    return x;
}

// ---- Running a contour through the plane mapping, as the spooler does ----

struct Element3 {
    ElementKind kind;
    bool ccw;
    Vec3 start, end, centre;
};

Element3 lift(const Element& e, double z_start, double z_end, Plane p) {
    return {e.kind, e.ccw, from_plane(e.start, z_start, p), from_plane(e.end, z_end, p),
            from_plane(e.centre, z_start, p)};
}

Element project(const Element3& e, Plane p) {
    Element out;
    out.kind = e.kind;
    out.ccw = e.ccw;
    out.start = to_plane(e.start, p);
    out.end = to_plane(e.end, p);
    out.centre = to_plane(e.centre, p);
    return out;
}

struct Segment3 {
    Segment plane;  // as emitted
    Vec3 start, end;
};

struct CompensationRun {
    const Contour* contour = nullptr;
    Side side = Side::kLeft;
    TransitionMode mode = TransitionMode::kCircular;
    Plane plane = Plane::kXY;
    Expectation expected;
    std::vector<Segment3> path;
    bool failed = false;
    std::size_t emitted_on_failure = 0;
    StepResult error;
    int failing_push = -1;
    std::string label() const {
        std::ostringstream s;
        s << "seed " << contour->seed << (contour->closed ? " closed" : " open") << " r "
          << contour->r << (side == Side::kLeft ? " G41" : " G42")
          << (mode == TransitionMode::kCircular ? " G26" : " G25") << " plane " << plane_code(plane)
          << " elements " << contour->elements.size();
        return s.str();
    }
};

CompensationRun compensate(const Contour& c, Side side, TransitionMode mode, Plane plane) {
    CompensationRun out;
    out.contour = &c;
    out.side = side;
    out.mode = mode;
    out.plane = plane;
    out.expected = expect(c, side);
    // The spooler's view: 3D profiles with a third coordinate rising along the contour.
    std::vector<Element3> program;
    for (std::size_t k = 0; k < c.elements.size(); ++k)
        program.push_back(lift(c.elements[k], 0.1 * k, 0.1 * (k + 1), plane));
    const Vec2 first_start = project(program[0], plane).start;
    const Vec2 position = first_start + 3 * c.r * Vec2(1, 1);
    PathCompensator comp;
    SegmentBatch batch;
    EXPECT_TRUE(comp.begin({side, c.r, mode}, position).ok());
    auto take = [&](double third) {
        for (const Segment& s : batch)
            out.path.push_back(
                {s, from_plane(s.path.start, third, plane), from_plane(s.path.end, third, plane)});
    };
    for (std::size_t k = 0; k < program.size(); ++k) {
        const StepResult r =
            comp.push(project(program[k], plane), static_cast<std::uint32_t>(k), batch);
        if (!r.ok()) {
            out.failed = true;
            out.emitted_on_failure = batch.size();
            out.error = r;
            out.failing_push = static_cast<int>(k);
            return out;
        }
        take(0.1 * k);
    }
    comp.finish(batch);
    take(0.1 * program.size());
    return out;
}

std::string describe(const Contour& c) {
    std::ostringstream s;
    s.precision(17);
    for (const Element& e : c.elements) {
        s << "\n  " << (is_arc(e) ? (e.ccw ? "G03 " : "G02 ") : "G01 ") << "(" << e.start.x()
          << ", " << e.start.y() << ") -> (" << e.end.x() << ", " << e.end.y() << ")";
        if (is_arc(e))
            s << " centre (" << e.centre.x() << ", " << e.centre.y() << ") R " << radius(e)
              << " sweep " << sweep(e) * 180 / kPi;
    }
    return s.str();
}

// ---- All runs, generated once ----

int ambiguous_skipped = 0;

struct Stats {
    int contours = 0, closed = 0;
    int runs = 0, compensated = 0, calc_errors = 0, korr_errors = 0;
};

const std::vector<Contour>& contours() {
    static const std::vector<Contour> all = [] {
        std::vector<Contour> out;
        Rng rng(0x7C0DE5EEDULL);
        while (out.size() < 600) {
            const std::uint64_t seed = rng.next();
            Rng local(seed);
            const double r = local.log_uniform(0.01, 50);
            Contour c = local.chance(0.35) ? closed_loop(local, r) : open_chain(local, r);
            c.seed = seed;
            if (c.elements.size() < 2) continue;
            bool ambiguous = false;
            for (Side side : {Side::kLeft, Side::kRight}) ambiguous |= expect(c, side).ambiguous;
            if (ambiguous) {
                ++ambiguous_skipped;
                continue;
            }
            out.push_back(std::move(c));
        }
        return out;
    }();
    return all;
}

const std::vector<CompensationRun>& runs() {
    static const std::vector<CompensationRun> all = [] {
        std::vector<CompensationRun> out;
        const Plane planes[3] = {Plane::kXY, Plane::kZX, Plane::kYZ};
        const auto& cs = contours();
        for (std::size_t i = 0; i < cs.size(); ++i)
            for (Side side : {Side::kLeft, Side::kRight})
                for (TransitionMode mode : {TransitionMode::kCircular, TransitionMode::kLinear})
                    out.push_back(compensate(cs[i], side, mode, planes[i % 3]));
        return out;
    }();
    return all;
}

double clearance(const Contour& c, const Vec2& p) {
    double best = INFINITY;
    for (const Element& e : c.elements) best = std::min(best, distance_to(e, p));
    return best;
}

bool checked_role(SegmentRole role) {
    return role == SegmentRole::kContour || role == SegmentRole::kTransition;
}

// Samples along a segment: both ends and at most r / 8 apart.
template <typename F>
void for_samples(const Element& e, double r, F&& f) {
    const int n = std::clamp(static_cast<int>(std::ceil(length(e) / (r / 8))), 16, 4000);
    for (int i = 0; i <= n; ++i) f(point_at(e, double(i) / n));
}

TEST(CompensationProperty, GeneratorCoversEnoughContoursOfEveryOutcome) {
    Stats s;
    for (const CompensationRun& r : runs()) {
        ++s.runs;
        if (!r.failed) ++s.compensated;
        if (r.failed && has(r.error.errors, ErrorBit::kCalcError)) ++s.calc_errors;
        if (r.failed && has(r.error.errors, ErrorBit::kKorrError)) ++s.korr_errors;
    }
    for (const Contour& c : contours()) s.closed += c.closed;
    s.contours = static_cast<int>(contours().size());
    std::printf(
        "contours %d (closed %d; %d regenerated near an error threshold), runs %d: "
        "compensated %d, CalcError %d, KorrError %d\n",
        s.contours, s.closed, ambiguous_skipped, s.runs, s.compensated, s.calc_errors,
        s.korr_errors);
    EXPECT_GE(s.contours, 500);
    EXPECT_GE(s.closed, 100);
    EXPECT_GE(s.compensated, 1000);
    EXPECT_GE(s.calc_errors, 50);
    EXPECT_GE(s.korr_errors, 50);
}

TEST(CompensationProperty, UncompensableContourGetsTheRightErrorBitInsteadOfAPath) {
    int mismatches = 0;
    for (const CompensationRun& r : runs()) {
        const Expectation& x = r.expected;
        const bool ok = r.failed ? (x.failing_push == r.failing_push && r.error.errors == x.bits)
                                 : x.failing_push < 0;
        if (!ok && ++mismatches <= 10)
            ADD_FAILURE() << r.label() << ": expected "
                          << (x.failing_push < 0 ? std::string("a path")
                                                 : "bits " + std::to_string(x.bits) + " at push " +
                                                       std::to_string(x.failing_push))
                          << ", got "
                          << (r.failed ? "bits " + std::to_string(r.error.errors) + " (" +
                                             std::string(reason_name(r.error.reason)) +
                                             ") at push " + std::to_string(r.failing_push)
                                       : std::string("a path"))
                          << (mismatches <= 3 ? describe(*r.contour) : std::string());
        if (r.failed) {
            EXPECT_EQ(r.emitted_on_failure, 0u) << r.label();
            EXPECT_TRUE(r.error.errors == bits(ErrorBit::kCalcError) ||
                        r.error.errors == bits(ErrorBit::kKorrError))
                << r.label();
        }
    }
    EXPECT_EQ(mismatches, 0);
}

TEST(CompensationProperty, NoPointOfTheCompensatedPathGouges) {
    int gouges = 0;
    for (const CompensationRun& r : runs()) {
        if (r.failed) continue;
        const double tool = r.contour->r;
        for (const Segment3& s : r.path) {
            if (!checked_role(s.plane.role)) continue;
            for_samples(s.plane.path, tool, [&](const Vec2& p) {
                const double d = clearance(*r.contour, p);
                if (d < tool - kPropertyTolerance && ++gouges <= 10)
                    ADD_FAILURE() << r.label() << ": point (" << p.x() << ", " << p.y()
                                  << ") of element " << s.plane.index << " (role "
                                  << int(s.plane.role) << ") is " << d << " from the contour"
                                  << (gouges <= 2 ? describe(*r.contour) : std::string());
            });
        }
    }
    EXPECT_EQ(gouges, 0);
}

TEST(CompensationProperty, EveryPointIsAtToolRadiusExceptOnLinearTransitions) {
    int off = 0;
    for (const CompensationRun& r : runs()) {
        if (r.failed) continue;
        const double tool = r.contour->r;
        for (const Segment3& s : r.path) {
            if (!checked_role(s.plane.role)) continue;
            if (s.plane.role == SegmentRole::kTransition && r.mode == TransitionMode::kLinear)
                continue;
            for_samples(s.plane.path, tool, [&](const Vec2& p) {
                const double d = clearance(*r.contour, p);
                if (std::abs(d - tool) > kPropertyTolerance && ++off <= 10)
                    ADD_FAILURE() << r.label() << ": point of element " << s.plane.index << " is "
                                  << d << " from the contour, r = " << tool;
            });
        }
    }
    EXPECT_EQ(off, 0);
}

TEST(CompensationProperty, EverySurvivingProgrammedElementIsCoveredByItsOffset) {
    int missing = 0;
    for (const CompensationRun& r : runs()) {
        if (r.failed) continue;
        const Contour& c = *r.contour;
        for (std::size_t k = 0; k < c.elements.size(); ++k) {
            bool any = false;
            for (const Segment3& s : r.path)
                any |= s.plane.role == SegmentRole::kContour && s.plane.index == k;
            if (!any && ++missing <= 10)
                ADD_FAILURE() << r.label() << ": element " << k << " not emitted";
            const double t0 = r.expected.t_start[k], t1 = r.expected.t_end[k];
            if ((t1 - t0) * length(c.elements[k]) < 1e-6 * std::max(1.0, c.r))
                continue;  // consumed
            for (double f : {0.25, 0.5, 0.75}) {
                const Vec2 p = offset_at(c.elements[k], t0 + f * (t1 - t0), c.r, r.side);
                double best = INFINITY;
                for (const Segment3& s : r.path)
                    if (s.plane.role == SegmentRole::kContour && s.plane.index == k)
                        best = std::min(best, distance_to(s.plane.path, p));
                if (best > kPropertyTolerance * std::max(1.0, c.r) && ++missing <= 10)
                    ADD_FAILURE() << r.label() << ": offset of element " << k << " at " << f
                                  << " of its surviving part is " << best << " from the path";
            }
        }
    }
    EXPECT_EQ(missing, 0);
}

TEST(CompensationProperty, PathIsContinuousFromApproachToDeparture) {
    int gaps = 0;
    for (const CompensationRun& r : runs()) {
        if (r.failed) continue;
        for (std::size_t i = 1; i < r.path.size(); ++i) {
            const double gap = (r.path[i].plane.path.start - r.path[i - 1].plane.path.end).norm();
            if (gap > 1e-9 * std::max(1.0, r.contour->r) && ++gaps <= 10)
                ADD_FAILURE() << r.label() << ": gap " << gap << " before segment " << i;
        }
        ASSERT_FALSE(r.path.empty());
        EXPECT_EQ(r.path.back().plane.role, SegmentRole::kDeparture) << r.label();
        EXPECT_NEAR((r.path.back().plane.path.end - r.contour->elements.back().end).norm(), 0,
                    1e-12);
        if (r.contour->closed) {
            // Closed loops start and end in the middle of an element: the path closes.
            const Segment3* first = nullptr;
            const Segment3* last = nullptr;
            for (const Segment3& s : r.path)
                if (s.plane.role == SegmentRole::kContour) {
                    if (!first) first = &s;
                    last = &s;
                }
            EXPECT_LT((first->plane.path.start - last->plane.path.end).norm(),
                      1e-9 * std::max(1.0, r.contour->r))
                << r.label();
        }
    }
    EXPECT_EQ(gaps, 0);
}

TEST(CompensationProperty, ToolSideIsLeftOrRightSeenFromThePositiveThirdAxisInEveryPlane) {
    int wrong = 0;
    for (const CompensationRun& r : runs()) {
        if (r.failed) continue;
        const PlaneAxes axes = plane_axes(r.plane);
        Vec3 third = Vec3::Zero();
        third[axes.third] = 1;
        for (const Segment3& s : r.path) {
            if (s.plane.role != SegmentRole::kContour || length(s.plane.path) < 1e-6) continue;
            // Work in 3D: midpoint of the emitted segment, nearest programmed point, tangent.
            const Element& e = r.contour->elements[s.plane.index];
            const Vec2 mid2 = point_at(s.plane.path, 0.5);
            const Vec3 mid = from_plane(mid2, 0, r.plane);
            const Vec3 on_contour = from_plane(closest_point(e, mid2), 0, r.plane);
            const double t = fraction_of_nearest(e, mid2);
            const Vec3 tangent = from_plane(tangent_at(e, t), 0, r.plane);
            const double side = tangent.cross(mid - on_contour).dot(third);
            const bool left = side > 0;
            if (left != (r.side == Side::kLeft) && ++wrong <= 10)
                ADD_FAILURE() << r.label() << ": element " << s.plane.index << " on the wrong side";
        }
    }
    EXPECT_EQ(wrong, 0);
}

}  // namespace
}  // namespace rwmos::geom
