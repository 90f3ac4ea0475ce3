// SPDX-License-Identifier: MIT
// Property tests of PathCompensator over contours shaped like real NC files: coordinates and
// arc centres rounded to 3 or 6 decimals (so tangent and collinear joins are tangent only up to
// the rounding, and arc radii differ by it), nearly tangent turns from 1e-9 rad to 3 degrees
// both ways, reversals from 170 to 180 degrees, arcs up to a full circle, inside corners whose
// offsets meet twice, tiny elements down to 1 um, several tool radii, both sides, both
// transition modes, through the plane mappings of 17, 18 and 19.
//
// The expectation follows the tolerance model of docs/compensation.md and is computed here
// independently of the library's offset, intersection and trim code: by marching along the
// held element's offset (on the spiral an arc with rounded radii is) to the next element's
// offset. Contours that come within a band of one of the model's thresholds are regenerated
// (there the decision is the rounding's). Properties: a contour is refused exactly where the
// model refuses it, with the bit it names; otherwise no point of the path comes closer to its
// own element or a neighbour than r less the path tolerance (kPathTolerance; a reversal read
// from a wedge narrower than rounding may come closer by that wedge, kReversalWedgeWidth), every
// point of a contour segment and of a circular transition is r from the contour within it, and
// the path is continuous. (G19 against G17, end to end: tests/compensation.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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
using apci::test::Rng;
using apci::test::round_to;

constexpr double kPi = std::numbers::pi;
// How close a contour may come to a threshold of the model before it is regenerated.
constexpr double kBand = 2e-6;

struct Contour {
    std::vector<Element> elements;  // as written: rounded
    double r = 1.0;
    int decimals = 3;
    std::uint64_t seed = 0;
    double wedge = 0.0;  // the widest wedge read as a reversal (its allowed approach)
    std::string label() const {
        std::ostringstream s;
        s << "seed " << seed << " r " << r << " decimals " << decimals << " elements "
          << elements.size();
        return s.str();
    }
};

std::string describe(const Contour& c) {
    std::ostringstream s;
    s.precision(17);
    for (const Element& e : c.elements) {
        s << "\n  " << (is_arc(e) ? (e.ccw ? "G03 " : "G02 ") : "G01 ") << "(" << e.start.x()
          << ", " << e.start.y() << ") -> (" << e.end.x() << ", " << e.end.y() << ")";
        if (is_arc(e)) s << " centre (" << e.centre.x() << ", " << e.centre.y() << ")";
    }
    return s.str();
}

// ---- Generation: what real files contain

// The turn at a join: mostly nearly tangent (rounding noise to 3 degrees, either way), then
// corners, reversals within 10 degrees of 180, exact tangents.
double pick_turn(Rng& rng) {
    const double u = rng.uniform();
    if (u < 0.3) return rng.sign() * rng.log_uniform(1e-9, 3 * kPi / 180);
    if (u < 0.45) return 0.0;
    if (u < 0.55) return rng.sign() * rng.uniform(170, 180) * kPi / 180;
    return rng.sign() * rng.uniform(3, 170) * kPi / 180;
}

Element pick_element(Rng& rng, const Vec2& at, double heading, double r) {
    const double u = rng.uniform();
    if (u < 0.45) {
        const double len = rng.chance(0.25) ? rng.log_uniform(1e-3, 0.05) : rng.log_uniform(0.1, 30);
        return make_line(at, at + len * dir(heading));
    }
    // Arcs from a sliver to a full circle; now and then concave and just fitting the tool.
    double radius = rng.log_uniform(0.05, 40);
    if (rng.chance(0.1)) radius = r * rng.uniform(1.0005, 1.3);
    const double sweep = rng.chance(0.1)    ? 2 * kPi
                         : rng.chance(0.15) ? rng.log_uniform(1e-4, 0.05)
                                            : rng.uniform(0.05, 2 * kPi - 1e-3);
    return arc_from(at, heading, radius, rng.sign() * sweep);
}

// The contour as written with `decimals`: every point and every centre (relative to its
// start) rounded, starts taken from the previous end. Empty when rounding would make an element
// nothing (a line of no length, an arc whose end falls on its start): no file holds those.
std::vector<Element> written(const std::vector<Element>& exact, int decimals) {
    std::vector<Element> out;
    const double step = std::pow(10.0, -decimals);
    Vec2 from = round_to(exact.front().start, decimals);
    for (const Element& e : exact) {
        Element w = e;
        w.start = from;
        w.end = apci::test::round_to(e.end, decimals);
        if (is_arc(e)) {
            w.centre = from + round_to(e.centre - e.start, decimals);
            if (is_full_circle(e)) w.end = from;  // a full circle stays one
            else if ((w.end - w.start).norm() < step) return {};
            if (check_element(w) != Reason::kNone) return {};
            // A sliver so short that rounding tilts its radius by more than a thousandth of a
            // radian per radian has no direction of its own (docs/compensation.md): no CAM
            // system writes one.
            if (std::abs(end_radius(w) - radius(w)) > 1e-3 * radius(w) * std::abs(sweep(w)))
                return {};
        } else if ((w.end - w.start).norm() < 0.5 * step) {
            return {};
        }
        out.push_back(w);
        from = w.end;
    }
    return out;
}

Contour generate(std::uint64_t seed) {
    Rng rng(seed);
    Contour c;
    c.seed = seed;
    const double radii[] = {0.01, 0.5, 2.0, 5.0, 20.0};
    c.r = rng.pick(radii);
    c.decimals = rng.chance(0.5) ? 3 : 6;
    std::vector<Element> chain;
    Vec2 at(rng.uniform(-50, 50), rng.uniform(-50, 50));
    double h = rng.uniform(0, 2 * kPi);
    const int n = rng.integer(2, 7);
    bool after_full_circle = false;
    for (int i = 0; i < n; ++i) {
        bool placed = false;
        for (int attempt = 0; attempt < 12 && !placed; ++attempt) {
            // A full circle starts and ends at one point: an element before or after it meets
            // both of its ends there, which no corner rule sees. Programs enter it tangentially
            // (a circular pocket's finishing pass); so do these, and it ends the contour.
            double turn = i == 0 || after_full_circle ? 0.0 : pick_turn(rng);
            Element e = pick_element(rng, at, h + turn, c.r);
            if (is_full_circle(e)) {
                // After a line only, tangentially, and so large that its far side stays clear of
                // the line (radius at least 2r).
                if (i == 0 || turn != 0.0 || is_arc(chain.back())) continue;
                if (radius(e) < 2 * c.r) continue;
                chain.push_back(e);
                placed = true;
                continue;
            }
            placed = apci::test::fits_chain(chain, e, c.r, 0.01);
            if (placed) chain.push_back(e);
        }
        if (!placed) break;
        // After a full circle, anything would meet the circle's start again: it ends the contour.
        after_full_circle = is_full_circle(chain.back());
        if (after_full_circle) break;
        at = chain.back().end;
        h = std::atan2(end_tangent(chain.back()).y(), end_tangent(chain.back()).x());
    }
    if (chain.size() >= 2) c.elements = written(chain, c.decimals);
    return c;
}

// ---- The independent expectation

bool left_of(Side side) {
    return side == Side::kLeft;
}
bool concave_for(const Element& arc, Side side) {
    return apci::test::concave_for(arc, left_of(side));
}
Vec2 offset_at(const Element& e, double t, double r, Side side) {
    return apci::test::offset_point(e, t, r, left_of(side));
}
apci::test::OffsetReading read_offset(const Element& e, const Vec2& p, double r, Side side) {
    return apci::test::read_offset(e, p, r, left_of(side));
}

struct Expectation {
    bool ambiguous = false;
    int failing_push = -1;  // -1: compensable
    ErrorBits bits = 0;
    double wedge = 0.0;     // the widest wedge read as a reversal
};

Expectation expect(const Contour& c, Side side, TransitionMode /*mode: the same for both*/) {
    const std::vector<Element>& E = c.elements;
    const double r = c.r;
    Expectation x;
    std::vector<double> t_start(E.size(), 0.0);
    const auto fail = [&](std::size_t k, ErrorBit bit) {
        x.failing_push = static_cast<int>(k);
        x.bits = bits(bit);
        return x;
    };
    const auto ambiguous = [&] {
        x.ambiguous = true;
        return x;
    };
    for (std::size_t k = 0; k < E.size(); ++k) {
        const Element& b = E[k];
        // TC Table 4 CalcError: the arc's radius smaller than the tool radius (beyond the path
        // tolerance).
        if (is_arc(b) && concave_for(b, side)) {
            const double rho = std::min(radius(b), end_radius(b)) - r;
            if (std::abs(rho + kOffsetRadiusTolerance) < kBand) return ambiguous();
            if (rho < -kOffsetRadiusTolerance) return fail(k, ErrorBit::kCalcError);
            if (rho < 1e-6) return ambiguous();  // a tool that just fits: its centre stands still
        }
        if (k == 0) continue;
        const Element& a = E[k - 1];
        const Vec2 t1 = end_tangent(a), t2 = start_tangent(b);
        const double turn = std::atan2(cross(t1, t2), t1.dot(t2));
        // Tangent: the offset ends lie within the path tolerance.
        const double gap = 2 * r * std::abs(std::sin(turn / 2));
        if (std::abs(gap - kPathTolerance) < 1e-7) return ambiguous();
        if (gap <= kPathTolerance) continue;
        const bool towards_tool = (turn > 0) == (side == Side::kLeft);
        if (!towards_tool) continue;  // outside: the offsets are bridged, nothing trimmed
        // A reversal written with rounding: the tool goes round the end.
        const double wedge_angle = kPi - std::abs(turn);
        const double wedge = std::min(length(a), length(b)) * std::sin(wedge_angle);
        if (wedge_angle <= kMaxReversalWedgeAngle + 1e-9 &&
            std::abs(wedge - kReversalWedgeWidth) < kBand)
            return ambiguous();
        if (std::abs(wedge_angle - kMaxReversalWedgeAngle) < 1e-9) return ambiguous();
        if (wedge_angle <= kMaxReversalWedgeAngle && wedge <= kReversalWedgeWidth) {
            x.wedge = std::max(x.wedge, wedge);
            continue;
        }
        // An arc so short that rounding tilts its radius by more than a thousandth of a radian
        // per radian (a sliver written with 3 decimals) has no direction to read a trim on.
        for (const Element* e : {&a, &b})
            if (is_arc(*e) && std::abs(end_radius(*e) - radius(*e)) >
                                  1e-3 * radius(*e) * std::abs(sweep(*e)))
                return ambiguous();
        // Inside: march back along a's offset from its end to the first point on b's offset
        // with its foot on b; the trim may reach kTrimTolerance beyond either end.
        const double len_a = length(a), len_b = length(b);
        const auto h = [&](double t) { return read_offset(b, offset_at(a, t, r, side), r, side); };
        const double lowest = t_start[k - 1] - kTrimTolerance / len_a;
        // Steps dense near the corner (meetings of nearly tangent offsets lie close to it and
        // close to each other), coarser away from it: t = 1 - (1 - lowest) s^3.
        const int steps = 3000;
        double found = -1, foot = 0;
        double prev_t = 1.0;
        apci::test::OffsetReading prev = h(1.0);
        double closest = std::abs(prev.residual);  // how near the offsets come without meeting
        for (int i = 1; i <= steps && found < 0; ++i) {
            const double s3 = std::pow(double(i) / steps, 3);
            const double t = 1.0 - (1.0 - lowest) * s3;
            const apci::test::OffsetReading now = h(t);
            closest = std::min(closest, std::abs(now.residual));
            if ((now.residual <= 0) != (prev.residual <= 0)) {
                const double root = apci::test::bisect_sign_change(
                    [&](double x) { return h(x).residual; }, t, prev_t);
                double f = h(root).fraction;
                // An arc's foot just before its start reads as almost a whole turn.
                if (is_arc(b) && f > 1.0 && (f - 2 * kPi / std::abs(sweep(b))) * len_b > -1.0)
                    f -= 2 * kPi / std::abs(sweep(b));
                const double before = -f * len_b, after = (f - 1) * len_b;
                if (std::abs(before - kTrimTolerance) < 1e-6 || std::abs(after - kTrimTolerance) < 1e-6)
                    return ambiguous();
                if (before <= kTrimTolerance && after <= kTrimTolerance) {
                    found = root;
                    foot = std::clamp(f, 0.0, 1.0);
                }
            }
            prev_t = t;
            prev = now;
        }
        // Offsets that come within a micrometre of meeting: whether they meet is the rounding's.
        if (found < 0 && closest < 1e-6) return ambiguous();
        if (found < 0) return fail(k, ErrorBit::kKorrError);
        if (std::abs((found - t_start[k - 1]) * len_a + kTrimTolerance) < 1e-6) return ambiguous();
        t_start[k] = foot;
    }
    return x;
}

// ---- Running, through the plane mappings

struct CompRun {
    const Contour* contour = nullptr;
    Side side = Side::kLeft;
    TransitionMode mode = TransitionMode::kCircular;
    Plane plane = Plane::kXY;
    Expectation expected;
    bool failed = false;
    StepResult error;
    int failing_push = -1;
    std::vector<Segment> path;  // back in the G17 coordinates of the contour
    std::string label() const {
        return contour->label() + (side == Side::kLeft ? " G41" : " G42") +
               (mode == TransitionMode::kCircular ? " G26" : " G25") + " plane " +
               std::to_string(plane_code(plane));
    }
};

// The contour's (first, second) read as plane `p`'s coordinates, compensated there: the path
// comes back in the same (first, second), so every plane gives the same numbers.
CompRun compensate(const Contour& c, Side side, TransitionMode mode, Plane plane) {
    CompRun out;
    out.contour = &c;
    out.side = side;
    out.mode = mode;
    out.plane = plane;
    out.expected = expect(c, side, mode);
    const auto lift = [plane](const Vec2& q, double third) { return from_plane(q, third, plane); };
    PathCompensator comp;
    SegmentBatch batch;
    const Vec2 position = c.elements.front().start + 3 * c.r * Vec2(1, 1);
    EXPECT_TRUE(comp.begin({side, c.r, mode}, to_plane(lift(position, 0), plane)).ok());
    for (std::size_t k = 0; k < c.elements.size(); ++k) {
        const Element& e = c.elements[k];
        Element mapped = e;
        mapped.start = to_plane(lift(e.start, 0.1 * k), plane);
        mapped.end = to_plane(lift(e.end, 0.1 * (k + 1)), plane);
        mapped.centre = to_plane(lift(e.centre, 0.1 * k), plane);
        const StepResult r = comp.push(mapped, static_cast<std::uint32_t>(k), batch);
        if (!r.ok()) {
            out.failed = true;
            out.error = r;
            out.failing_push = static_cast<int>(k);
            EXPECT_EQ(batch.size(), 0u) << out.label();
            return out;
        }
        out.path.insert(out.path.end(), batch.begin(), batch.end());
    }
    comp.finish(batch);
    out.path.insert(out.path.end(), batch.begin(), batch.end());
    return out;
}

// ---- All runs, generated once

int regenerated = 0;

const std::vector<Contour>& contours() {
    static const std::vector<Contour> all = [] {
        std::vector<Contour> out;
        Rng rng(0x50DA7E5ULL);
        while (out.size() < 800) {
            Contour c = generate(rng.next());
            if (c.elements.size() < 2) continue;
            bool ambiguous = false;
            for (Side side : {Side::kLeft, Side::kRight})
                for (TransitionMode mode : {TransitionMode::kCircular, TransitionMode::kLinear})
                    ambiguous |= expect(c, side, mode).ambiguous;
            if (ambiguous) {
                ++regenerated;
                continue;
            }
            out.push_back(std::move(c));
        }
        return out;
    }();
    return all;
}

const std::vector<CompRun>& runs() {
    static const std::vector<CompRun> all = [] {
        std::vector<CompRun> out;
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

template <typename F>
void for_samples(const Element& e, double r, F&& f) {
    const int n = std::clamp(static_cast<int>(std::ceil(length(e) / (r / 8))), 16, 4000);
    for (int i = 0; i <= n; ++i) f(point_at(e, double(i) / n));
}

// The part of e near its corner at the end (at_end) or the start: all of a line, the last (first)
// half turn of an arc. An arc of more than half a turn comes back round towards its own
// corner; a transition there that comes near its farther part is the contour coming back near
// itself (self-approach), as in tools/runlib's check.
Element near_corner(const Element& e, bool at_end) {
    const double turn = is_arc(e) ? std::abs(sweep(e)) : 0.0;
    if (turn <= kPi) return e;
    Element part = e;
    if (at_end) part.start = point_at(e, (turn - kPi) / turn);
    else part.end = point_at(e, kPi / turn);
    return part;
}

// ---- Properties

TEST(RoundedContourProperty, GeneratorMakesEnoughOfEveryKind) {
    int near_tangent = 0, reversals = 0, full_circles = 0, tiny = 0, fits = 0, compensated = 0;
    int calc = 0, korr = 0, three = 0, six = 0;
    for (const Contour& c : contours()) {
        (c.decimals == 3 ? three : six) += 1;
        for (std::size_t k = 0; k < c.elements.size(); ++k) {
            const Element& e = c.elements[k];
            tiny += length(e) < 0.01;
            full_circles += is_full_circle(e);
            fits += is_arc(e) && std::abs(radius(e) - c.r) < 0.3 * c.r;
            if (k == 0) continue;
            const double turn = std::abs(std::atan2(cross(end_tangent(c.elements[k - 1]), start_tangent(e)),
                                                    end_tangent(c.elements[k - 1]).dot(start_tangent(e))));
            near_tangent += turn > 0 && turn < 3 * kPi / 180;
            reversals += turn > 170 * kPi / 180;
        }
    }
    for (const CompRun& r : runs()) {
        compensated += !r.failed;
        calc += r.failed && has(r.error.errors, ErrorBit::kCalcError);
        korr += r.failed && has(r.error.errors, ErrorBit::kKorrError);
    }
    std::printf(
        "contours %zu (3 decimals %d, 6 decimals %d; %d regenerated near a threshold): %d nearly "
        "tangent joins, %d reversals, %d full circles, %d elements under 10 um, %d arcs near the "
        "tool radius; runs %zu: compensated %d, CalcError %d, KorrError %d\n",
        contours().size(), three, six, regenerated, near_tangent, reversals, full_circles, tiny,
        fits, runs().size(), compensated, calc, korr);
    EXPECT_GE(near_tangent, 300);
    EXPECT_GE(reversals, 60);
    EXPECT_GE(full_circles, 8);
    EXPECT_GE(tiny, 60);
    EXPECT_GE(compensated, 1000);
    EXPECT_GE(calc, 30);
    EXPECT_GE(korr, 200);
}

TEST(RoundedContourProperty, RefusedExactlyWhereTheModelRefusesWithItsBit) {
    int mismatches = 0;
    for (const CompRun& r : runs()) {
        const Expectation& x = r.expected;
        const bool ok = r.failed ? (x.failing_push == r.failing_push && r.error.errors == x.bits)
                                 : x.failing_push < 0;
        if (!ok && ++mismatches <= 8)
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
    }
    EXPECT_EQ(mismatches, 0);
}

TEST(RoundedContourProperty, NoPointComesCloserThanThePathToleranceToTheElementsOfItsCorner) {
    // Every point of an element's offset keeps r from that element, and every point of a
    // transition from the two elements meeting at its corner (within the path tolerance; a
    // reversal read from a wedge narrower than rounding within that wedge). Where a path comes
    // closer to another element, the neighbour before or after away from their corner
    // included, the contour comes back near itself (an arc curling round a corner, a contour
    // coming back alongside after a reversal, the element before a short one reached by the
    // next corner, a near-full arc whose start a transition at its end reaches, a transition
    // at a corner whose elements come back within 2r of each other): no corner rule
    // with one element of lookahead sees it, and apcictl run reports it (tools/runlib
    // self_approach.h). Those points are counted here.
    int gouges = 0, self_approach = 0;
    for (const CompRun& r : runs()) {
        if (r.failed) continue;
        const Contour& c = *r.contour;
        const double allowed = kPathTolerance + r.expected.wedge + 1e-9;
        // Corners whose elements come back within 2r of each other away from the corner (a
        // short element after a small arc, turning back into it): the offsets do, and so may a
        // transition joining them.
        std::vector<bool> diverges(c.elements.size(), true);
        for (std::size_t k = 0; k + 1 < c.elements.size(); ++k)
            diverges[k] = apci::test::diverge(c.elements[k], c.elements[k + 1], c.r);
        for (const Segment& s : r.path) {
            if (s.role != SegmentRole::kContour && s.role != SegmentRole::kTransition) continue;
            const std::size_t k = s.index;
            const bool transition = s.role == SegmentRole::kTransition;
            for_samples(s.path, c.r, [&](const Vec2& p) {
                for (std::size_t j = 0; j < c.elements.size(); ++j) {
                    const double d = distance_to(c.elements[j], p);
                    if (d >= c.r - allowed) continue;
                    const bool own = j == k || (transition && j == k + 1);
                    const bool comes_back =
                        transition &&
                        (!diverges[k] ||
                         distance_to(near_corner(c.elements[j], j == k), p) >= c.r - allowed);
                    if (!own || comes_back) {
                        ++self_approach;
                        continue;
                    }
                    if (++gouges <= 8)
                        ADD_FAILURE() << r.label() << ": a point of element " << k << " is " << d
                                      << " from element " << j << ", r = " << c.r
                                      << (gouges <= 2 ? describe(c) : std::string());
                }
            });
        }
    }
    std::printf("samples nearer another element than r (self-approach): %d\n", self_approach);
    EXPECT_EQ(gouges, 0);
}

TEST(RoundedContourProperty, EveryPointIsAtToolRadiusWithinThePathToleranceExceptOnLinearTransitions) {
    // An element's offset is r from the element; a circular transition r from its corner.
    int off = 0;
    for (const CompRun& r : runs()) {
        if (r.failed) continue;
        const Contour& c = *r.contour;
        for (const Segment& s : r.path) {
            const bool transition = s.role == SegmentRole::kTransition;
            if ((s.role != SegmentRole::kContour && !transition) ||
                (transition && r.mode == TransitionMode::kLinear))
                continue;
            const Element& e = c.elements[s.index];
            for_samples(s.path, c.r, [&](const Vec2& p) {
                const double d = transition ? (p - e.end).norm() : distance_to(e, p);
                if (std::abs(d - c.r) > kPathTolerance + r.expected.wedge + 1e-9 && ++off <= 8)
                    ADD_FAILURE() << r.label() << ": a point of element " << s.index << " is "
                                  << d << (transition ? " from its corner" : " from it")
                                  << ", r = " << c.r << (off <= 2 ? describe(c) : std::string());
            });
        }
    }
    EXPECT_EQ(off, 0);
}

TEST(RoundedContourProperty, PathIsContinuous) {
    int gaps = 0;
    for (const CompRun& r : runs()) {
        if (r.failed) continue;
        for (std::size_t i = 1; i < r.path.size(); ++i) {
            const double gap = (r.path[i].path.start - r.path[i - 1].path.end).norm();
            if (gap > 1e-9 * std::max(1.0, r.contour->r) && ++gaps <= 8)
                ADD_FAILURE() << r.label() << ": gap " << gap << " before segment " << i;
        }
    }
    EXPECT_EQ(gaps, 0);
}

}  // namespace
}  // namespace rwmos::geom
