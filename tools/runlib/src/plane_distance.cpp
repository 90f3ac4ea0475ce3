// SPDX-License-Identifier: MIT
// The least distance of two compact curves is reached either where one of them ends (the
// distance of that end point to the other curve) or at a pair of inner points where the segment
// joining them is normal to both curves, or where they cross (distance 0). For lines and
// circular arcs the normal pairs are few and known in closed form: a line and a circle, on the
// line through the centre normal to the line; two circles, on the line through both centres.
#include "apci/run/plane_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "geometry/element.h"

namespace apci::run::plane {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Radii of an arc that differ by no more than this (mm; a rounding's worth where the ends and the
// centre were written with a few decimals) make the bounds below take the arc as lying within
// the annulus of its two radii, without the angle of a direction along it: looser by at most
// this, far below every limit a proof is asked for.
constexpr double kRoundedRadii = 1e-9;
bool rounded_radii(const Parametric& e) { return std::abs(e.r1 - e.r0) <= kRoundedRadii; }

// The distance of a point `dist` from a centre to the annulus about it between rmin <= rmax.
double from_annulus(double dist, double rmin, double rmax) {
    return dist > rmax ? dist - rmax : (dist < rmin ? rmin - dist : 0.0);
}

using geom::cross;

bool on_segment(double t) {
    return t >= 0.0 && t <= 1.0;
}

// An arc with what the distances ask of it computed once: its ends and the unit directions of
// its ends from the centre.
struct Circle {
    Vec2 centre, start, end;
    Vec2 from, to;  // unit directions of start and end from the centre
    double radius = 0.0;
    double sweep = 0.0;
};

Circle circle_of(const Arc& a, const Vec2& from, const Vec2& to) {
    Circle c;
    c.centre = a.centre;
    c.radius = a.radius;
    c.from = from;
    c.to = to;
    c.start = a.centre + a.radius * from;
    c.end = a.centre + a.radius * to;
    c.sweep = a.sweep;
    return c;
}

Circle circle_of(const Arc& a) {
    const double phi1 = a.phi0 + a.sweep;
    return circle_of(a, Vec2(std::cos(a.phi0), std::sin(a.phi0)),
                     Vec2(std::cos(phi1), std::sin(phi1)));
}

bool within(const Circle& c, const Vec2& v) {
    return within_turn(c.from, c.to, c.sweep, v);
}

double point_circle(const Vec2& p, const Circle& c) {
    const Vec2 v = p - c.centre;
    const double n = v.norm();
    if (n == 0.0) return c.radius;
    if (within(c, v)) return std::abs(n - c.radius);
    return std::min((p - c.start).norm(), (p - c.end).norm());
}

double segment_circle(const Vec2& a0, const Vec2& a1, const Circle& b) {
    double best = std::min({point_circle(a0, b), point_circle(a1, b),
                            point_segment(b.start, a0, a1), point_segment(b.end, a0, a1)});
    const Vec2 d = a1 - a0;
    const double len = d.norm();
    if (len == 0.0) return best;
    const Vec2 u = d / len;
    const Vec2 n(-u.y(), u.x());
    // The foot of the centre on the line, and the centre's signed distance from it.
    const double along = (b.centre - a0).dot(u);
    const double h = (b.centre - a0).dot(n);
    // Where the line crosses the circle.
    if (std::abs(h) <= b.radius) {
        const double w = std::sqrt(b.radius * b.radius - h * h);
        for (const double s : {along - w, along + w})
            if (on_segment(s / len) && within(b, a0 + s * u - b.centre)) return 0.0;
    }
    // The normal pairs: the points of the circle on the normal through the centre.
    if (on_segment(along / len)) {
        for (const double side : {1.0, -1.0})
            if (within(b, side * n)) best = std::min(best, std::abs(h + side * b.radius));
    }
    return best;
}

double circle_circle(const Circle& a, const Circle& b) {
    double best = std::min({point_circle(a.start, b), point_circle(a.end, b),
                            point_circle(b.start, a), point_circle(b.end, a)});
    const Vec2 d = b.centre - a.centre;
    const double dist = d.norm();
    if (dist == 0.0) {
        // Concentric: |ra - rb| wherever the turns share a direction.
        if (within(a, b.from) || within(b, a.from))
            best = std::min(best, std::abs(a.radius - b.radius));
        return best;
    }
    const Vec2 u = d / dist;
    const Vec2 n(-u.y(), u.x());
    // Where the circles cross.
    if (dist <= a.radius + b.radius && dist >= std::abs(a.radius - b.radius)) {
        const double along =
            (a.radius * a.radius - b.radius * b.radius + dist * dist) / (2.0 * dist);
        const double w = std::sqrt(std::max(0.0, a.radius * a.radius - along * along));
        for (const double side : {1.0, -1.0}) {
            const Vec2 x = a.centre + along * u + side * w * n;
            if (within(a, x - a.centre) && within(b, x - b.centre)) return 0.0;
        }
    }
    // The normal pairs: the points of both circles on the line through the centres.
    for (const double sa : {1.0, -1.0}) {
        if (!within(a, sa * u)) continue;
        const Vec2 p = a.centre + sa * a.radius * u;
        for (const double sb : {1.0, -1.0})
            if (within(b, sb * u))
                best = std::min(best, (p - (b.centre + sb * b.radius * u)).norm());
    }
    return best;
}

}  // namespace

Parametric line_element(const Vec2& start, const Vec2& end) noexcept {
    Parametric e;
    e.start = start;
    e.end = end;
    return e;
}

namespace {

// The arc with its sweep and start angle given: both arc_element()s, inline in each.
[[gnu::always_inline]] inline Parametric arc_with(const Vec2& start, const Vec2& end,
                                                  const Vec2& centre, bool ccw, double sweep,
                                                  double phi0) {
    Parametric e;
    e.kind = geom::ElementKind::kArc;
    e.ccw = ccw;
    e.start = start;
    e.end = end;
    e.centre = centre;
    const Vec2 u0 = start - centre, u1 = end - centre;
    e.sweep = sweep;
    e.r0 = u0.norm();
    e.r1 = u1.norm();
    e.phi0 = phi0;
    return e;
}

}  // namespace

Parametric arc_element(const Vec2& start, const Vec2& end, const Vec2& centre, bool ccw) noexcept {
    const Vec2 u0 = start - centre, u1 = end - centre;
    return arc_with(start, end, centre, ccw,
                    geom::arc_sweep(u0, u1, ccw, (end - start).norm() <= 1e-9),
                    std::atan2(u0.y(), u0.x()));
}

Parametric arc_element(const Vec2& start, const Vec2& end, const Vec2& centre, bool ccw,
                       double sweep, double phi0) noexcept {
    return arc_with(start, end, centre, ccw, sweep, phi0);
}

Vec2 point_at(const Parametric& e, double t) noexcept {
    if (!is_arc(e)) return e.start + t * (e.end - e.start);
    if (t >= 1.0) return e.end;
    const double phi = e.phi0 + t * e.sweep;
    const double r = e.r0 + t * (e.r1 - e.r0);
    return e.centre + r * Vec2(std::cos(phi), std::sin(phi));
}

double distance_to(const Parametric& e, const Vec2& p) noexcept {
    if (!is_arc(e)) return point_segment(p, e.start, e.end);
    const Vec2 v = p - e.centre;
    const Vec2 u0 = e.start - e.centre;
    const double turn = std::abs(e.sweep);
    const double along = e.sweep > 0.0 ? geom::angle_between(u0, v, true)
                                        : geom::angle_between(v, u0, true);
    if (v.norm() > 0.0 && along <= turn)
        return std::abs(v.norm() - (e.r0 + (along / turn) * (e.r1 - e.r0)));
    return std::min((p - e.start).norm(), (p - e.end).norm());
}

bool within_turn(const Vec2& from, const Vec2& to, double sweep, const Vec2& v) noexcept {
    if (std::abs(sweep) >= kTwoPi) return true;
    const double sense = sweep < 0.0 ? -1.0 : 1.0;
    const double a = sense * cross(from, v), b = sense * cross(v, to);
    if (std::abs(sweep) > std::numbers::pi) return a >= 0.0 || b >= 0.0;
    return a >= 0.0 && b >= 0.0;
}

double point_segment(const Vec2& p, const Vec2& a, const Vec2& b) noexcept {
    const Vec2 d = b - a;
    const double n2 = d.squaredNorm();
    const double t = n2 == 0.0 ? 0.0 : std::clamp((p - a).dot(d) / n2, 0.0, 1.0);
    return (p - (a + t * d)).norm();
}

double point_arc(const Vec2& p, const Arc& a) noexcept {
    return point_circle(p, circle_of(a));
}

double segment_segment(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) noexcept {
    // Crossing: each segment's ends strictly on opposite sides of the other's line (touching
    // is an end point's distance, 0, below).
    const Vec2 da = a1 - a0, db = b1 - b0;
    const double s0 = cross(da, b0 - a0), s1 = cross(da, b1 - a0);
    const double s2 = cross(db, a0 - b0), s3 = cross(db, a1 - b0);
    if (((s0 < 0.0 && s1 > 0.0) || (s0 > 0.0 && s1 < 0.0)) &&
        ((s2 < 0.0 && s3 > 0.0) || (s2 > 0.0 && s3 < 0.0)))
        return 0.0;
    return std::min({point_segment(a0, b0, b1), point_segment(a1, b0, b1),
                     point_segment(b0, a0, a1), point_segment(b1, a0, a1)});
}

double segment_arc(const Vec2& a0, const Vec2& a1, const Arc& b) noexcept {
    return segment_circle(a0, a1, circle_of(b));
}

double arc_arc(const Arc& a, const Arc& b) noexcept {
    return circle_circle(circle_of(a), circle_of(b));
}

namespace {

// The part [t0, t1] of an element: a segment, or a circular arc of the radius at its middle and
// how far the element's own points may lie from it (`off`).
struct Piece {
    bool arc = false;
    double t0 = 0.0, t1 = 1.0;
    Vec2 a = Vec2::Zero(), b = Vec2::Zero();  // a line's ends
    Circle circle;
    double off = 0.0;
};

// The part [t0, t1] of e; for an arc with the unit directions of its angle at t0 and t1.
Piece piece_of(const Parametric& e, double t0, double t1, const Vec2& from, const Vec2& to) {
    Piece p;
    p.t0 = t0;
    p.t1 = t1;
    if (!is_arc(e)) {
        const Vec2 d = e.end - e.start;
        p.a = t0 == 0.0 ? e.start : e.start + t0 * d;
        p.b = t1 == 1.0 ? e.end : e.start + t1 * d;
        return p;
    }
    p.arc = true;
    const double dr = e.r1 - e.r0;
    const Arc arc{e.centre, e.r0 + 0.5 * (t0 + t1) * dr, e.phi0 + t0 * e.sweep,
                  (t1 - t0) * e.sweep};
    p.circle = circle_of(arc, from, to);
    p.off = 0.5 * (t1 - t0) * std::abs(dr);
    return p;
}

// All of e: an arc's end directions from its end points (as its angles were computed from them).
Piece whole(const Parametric& e) {
    if (!is_arc(e) || e.r0 <= 0.0 || e.r1 <= 0.0) {
        const double phi1 = e.phi0 + e.sweep;
        return piece_of(e, 0.0, 1.0, Vec2(std::cos(e.phi0), std::sin(e.phi0)),
                        Vec2(std::cos(phi1), std::sin(phi1)));
    }
    return piece_of(e, 0.0, 1.0, (e.start - e.centre) / e.r0, (e.end - e.centre) / e.r1);
}

// The two halves of a part of e.
std::array<Piece, 2> halves(const Parametric& e, const Piece& p) {
    const double m = 0.5 * (p.t0 + p.t1);
    Vec2 at = Vec2::Zero();
    if (is_arc(e)) {
        const double phi = e.phi0 + m * e.sweep;
        at = {std::cos(phi), std::sin(phi)};
    }
    return {piece_of(e, p.t0, m, p.circle.from, at), piece_of(e, m, p.t1, at, p.circle.to)};
}

double between(const Piece& p, const Piece& q) {
    if (!p.arc && !q.arc) return segment_segment(p.a, p.b, q.a, q.b);
    if (!p.arc) return segment_circle(p.a, p.b, q.circle);
    if (!q.arc) return segment_circle(q.a, q.b, p.circle);
    return circle_circle(p.circle, q.circle);
}

}  // namespace

bool apart(const Parametric& a, const Parametric& b, double limit) noexcept {
    struct Job {
        Piece p, q;
    };
    // Apart, near, or to be halved: the part p of a against the part q of b.
    enum class Verdict { kApart, kNear, kHalve };
    const auto judge = [limit](const Piece& p, const Piece& q) {
        const double d = between(p, q);
        const double off = p.off + q.off;
        if (d - off >= limit) return Verdict::kApart;
        // A pair of points of the elements within the limit, or no room left to prove it.
        if (d + off < limit || off < 1e-12) return Verdict::kNear;
        return Verdict::kHalve;
    };
    // The whole elements first: most pairs are decided there, with no stack.
    const Job whole_pair{whole(a), whole(b)};
    const Verdict v = judge(whole_pair.p, whole_pair.q);
    if (v != Verdict::kHalve) return v == Verdict::kApart;
    // Each step takes one job and leaves at most two: the stack never holds more than the
    // steps allowed, plus one. Its memory is kept by the thread from one call to the next.
    thread_local std::vector<Job> stack;
    stack.clear();
    const auto halve = [&](const Job& j) {  // the part with more room, in two
        if (j.p.off >= j.q.off) {
            const auto [lower, upper] = halves(a, j.p);
            stack.push_back(Job{lower, j.q});
            stack.push_back(Job{upper, j.q});
        } else {
            const auto [lower, upper] = halves(b, j.q);
            stack.push_back(Job{j.p, lower});
            stack.push_back(Job{j.p, upper});
        }
    };
    halve(whole_pair);
    for (int step = 1; !stack.empty(); ++step) {
        if (step >= kMaxApartSteps) return false;
        const Job j = stack.back();
        stack.pop_back();
        const Verdict w = judge(j.p, j.q);
        if (w == Verdict::kNear) return false;
        if (w == Verdict::kHalve) halve(j);
    }
    return true;
}

namespace {

// An upper bound on f(q) = q . n over the points of e (n a unit direction): exact for a line
// and a circular arc. An arc's point is centre + rho u with rho within [rmin, rmax] and u a
// direction within its turn, so u . n is 1 where n lies within the turn, else at most the ends'
// larger value, and rho u . n within the products of those. The lower bound is -most_along(e,
// -n).
double most_along(const Parametric& e, const Vec2& n) {
    const double ends = std::max(e.start.dot(n), e.end.dot(n));
    if (!is_arc(e)) return ends;
    const double rmin = std::min(e.r0, e.r1), rmax = std::max(e.r0, e.r1);
    if (e.r0 <= 0.0 || e.r1 <= 0.0) return std::max(ends, e.centre.dot(n) + rmax);
    const Vec2 from = (e.start - e.centre) / e.r0, to = (e.end - e.centre) / e.r1;
    const double turn = std::abs(e.sweep);
    const double k = (e.r1 - e.r0) / turn;
    const bool half = turn <= std::numbers::pi;
    if (within_turn(from, to, e.sweep, n)) {
        if (!half || rounded_radii(e))
            return std::max(ends, e.centre.dot(n) + rmax);
        // At the angle delta from n the point is rho cos(delta) along it, rho = rho_n + k delta
        // the radius there: with cos(delta) <= 1 - 2 delta^2 / pi^2 that is at most rho_n +
        // k delta - 2 rmin delta^2 / pi^2, at most rho_n + pi^2 k^2 / (8 rmin): the radius at
        // that direction, a hair more.
        double along = std::atan2(e.sweep > 0.0 ? cross(from, n) : cross(n, from), from.dot(n));
        if (along < 0.0) along += kTwoPi;
        return std::max(ends, e.centre.dot(n) + e.r0 + k * along +
                                  std::numbers::pi * std::numbers::pi * k * k / (8.0 * rmin));
    }
    // n beyond the turn, delta0 from its nearer end (radius rho there, the end's value rho
    // cos(delta0) exact): going along by x, cos(delta0 + x) <= cos(delta0) (1 - 2 x^2 / pi^2)
    // while delta0 + turn <= pi and cos(delta0) > 0, so the value is at most rho cos(delta0) +
    // |k| x - 2 rho cos(delta0) x^2 / pi^2 <= the end's value + pi^2 k^2 / (8 rho cos(delta0)).
    // delta0 + turn <= pi is cos(delta0) >= cos(pi - turn) = -cos(turn), both angles in
    // [0, pi]. Else the whole radius's range.
    const double cs = from.dot(n), ce = to.dot(n);
    const bool start_nearer = cs >= ce;
    const double cos0 = start_nearer ? cs : ce;
    const double rho = start_nearer ? e.r0 : e.r1;
    if (half && cos0 > 0.1 && cos0 >= -from.dot(to))
        return std::max(ends, e.centre.dot(n) + rho * cos0 +
                                  std::numbers::pi * std::numbers::pi * k * k / (8.0 * rho * cos0));
    const double most = std::max(cs, ce);
    return std::max(ends, e.centre.dot(n) + most * (most >= 0.0 ? rmax : rmin));
}

// A lower bound on the distance from p to e. For an arc of at most half a turn whose turn holds
// p's direction: with R the distance of p from the centre, d the radial distance at that
// direction and k the radius's change per radian, the point delta from it is at
// (rho - R)^2 + 2 rho R (1 - cos delta) >= max(0, d - |k| delta)^2 + c delta^2, c = 4 rmin R /
// pi^2, which is at least d^2 c / (k^2 + c): d a hair less. Elsewhere the radial distance less
// the radius's whole change.
double distance_at_least(const Parametric& e, const Vec2& p) {
    if (!is_arc(e)) return point_segment(p, e.start, e.end);
    // The radial distance less the radius's whole change.
    const auto loose = [&] { return distance_to(e, p) - std::abs(e.r1 - e.r0); };
    const double turn = std::abs(e.sweep);
    if (turn > std::numbers::pi || e.r0 <= 0.0 || e.r1 <= 0.0) return loose();
    const Vec2 v = p - e.centre;
    const double big_r = v.norm();
    if (big_r == 0.0) return loose();
    const Vec2 from = (e.start - e.centre) / e.r0, to = (e.end - e.centre) / e.r1;
    const double k = (e.r1 - e.r0) / turn;
    const double c = 4.0 * std::min(e.r0, e.r1) * big_r / (std::numbers::pi * std::numbers::pi);
    if (within_turn(from, to, e.sweep, v)) {
        // Radii a rounding apart: the distance from the annulus they span (every point of the
        // arc lies in it), at most kRoundedRadii below the radial distance at p's direction.
        const double radial = rounded_radii(e)
                                  ? from_annulus(big_r, std::min(e.r0, e.r1), std::max(e.r0, e.r1))
                                  : distance_to(e, p);
        return radial * std::sqrt(c / (k * k + c));
    }
    // p's direction beyond the turn, delta0 from its nearer end (radius rho0 there): going
    // along the arc by x from that end, delta = delta0 + x while delta0 + turn <= pi, and
    // (rho - R)^2 + c delta^2 >= max(0, A - |k| x)^2 + c x^2 + c delta0^2, A = |rho0 - R|.
    // delta0 + turn <= pi is cos(delta0) >= -cos(turn) (both angles in [0, pi]); delta0 is at
    // least the chord |u - w| of the unit directions u and w (= 2 sin(delta0 / 2)).
    const Vec2 u = v / big_r;
    const double cs = u.dot(from), ce = u.dot(to);
    const bool start_nearer = cs >= ce;
    if (std::max(cs, ce) < -from.dot(to)) return loose();
    const double chord = (u - (start_nearer ? from : to)).norm();
    const double a = std::abs((start_nearer ? e.r0 : e.r1) - big_r);
    return std::sqrt(a * a * c / (k * k + c) + c * chord * chord);
}

// The least and largest distance of the points of e from c.
void distances_from(const Parametric& e, const Vec2& c, double& lo, double& hi) {
    if (!is_arc(e)) {
        lo = point_segment(c, e.start, e.end);
        hi = std::max((e.start - c).norm(), (e.end - c).norm());
        return;
    }
    lo = std::min((e.start - c).norm(), (e.end - c).norm());
    hi = std::max((e.start - c).norm(), (e.end - c).norm());
    const Vec2 d = c - e.centre;
    const double dist = d.norm();
    const double rmin = std::min(e.r0, e.r1), rmax = std::max(e.r0, e.r1);
    if (dist == 0.0 || e.r0 <= 0.0 || e.r1 <= 0.0) {  // every point rmin..rmax away
        lo = std::min(lo, from_annulus(dist, rmin, rmax));
        hi = std::max(hi, dist + rmax);
        return;
    }
    const Vec2 u = d / dist;
    const Vec2 from = (e.start - e.centre) / e.r0, to = (e.end - e.centre) / e.r1;
    // Nearest: towards c; farthest: away from it (the radius anywhere between rmin and rmax).
    if (within_turn(from, to, e.sweep, u))
        lo = std::min(lo, from_annulus(dist, rmin, rmax));
    if (within_turn(from, to, e.sweep, -u)) hi = std::max(hi, dist + rmax);
}

}  // namespace

bool apart_by_side(const Parametric& a, const Parametric& b, double limit) noexcept {
    // b a line and a wholly behind one of its ends E (against the direction t from E into b,
    // to within eps): for p of a and q = E + s t of b, |p - q|^2 = |p - E|^2 - 2 s (p - E) . t
    // + s^2 >= |p - E|^2 - eps^2. The distance of E from a (a lower bound: for an arc whose
    // radii differ, its radial distance less that difference) then decides.
    if (!is_arc(b)) {
        const Vec2 d = b.end - b.start;
        const double len = d.norm();
        if (len > 0.0) {
            for (const bool at_start : {true, false}) {
                const Vec2 e = at_start ? b.start : b.end;
                const Vec2 t = (at_start ? d : Vec2(-d)) / len;
                const double eps = std::max(0.0, most_along(a, t) - e.dot(t));
                if (eps > 0.5 * limit) continue;
                const double de = distance_at_least(a, e);
                if (de > 0.0 && de * de - eps * eps >= limit * limit) return true;
            }
        }
    }
    if (!is_arc(a)) {
        const Vec2 d = a.end - a.start;
        const double len = d.norm();
        if (len == 0.0) return false;
        const Vec2 n(-d.y() / len, d.x() / len);
        const double base = a.start.dot(n);
        // The side b's start lies on first: the other is seldom the one that proves it.
        if (b.start.dot(n) < base) return most_along(b, n) - base <= -limit;
        return -most_along(b, -n) - base >= limit;
    }
    double lo = 0.0, hi = 0.0;
    distances_from(b, a.centre, lo, hi);
    const double rmin = std::min(a.r0, a.r1), rmax = std::max(a.r0, a.r1);
    return lo >= rmax + limit || hi <= rmin - limit;
}

Nearest lines_nearest(const Parametric& path, const Parametric& contour) noexcept {
    const Vec2 d = path.end - path.start;
    const Vec2 e = contour.end - contour.start;
    const double den = cross(d, e);
    if (den != 0.0) {
        const Vec2 w = contour.start - path.start;
        const double t = cross(w, e) / den;
        const double u = cross(w, d) / den;
        if (t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0) return Nearest{0.0, t};
    }
    Nearest best{distance_to(contour, path.start), 0.0};
    const auto take = [&](double t) {
        const double dist = distance_to(contour, point_at(path, t));
        if (dist < best.distance) best = Nearest{dist, t};
    };
    take(1.0);
    const double dd = d.squaredNorm();
    for (const Vec2& q : {contour.start, contour.end})
        take(dd > 0.0 ? std::clamp((q - path.start).dot(d) / dd, 0.0, 1.0) : 0.0);
    return best;
}

}  // namespace apci::run::plane
