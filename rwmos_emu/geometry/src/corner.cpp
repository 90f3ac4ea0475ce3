// SPDX-License-Identifier: MIT
#include "rwmos/geometry/corner.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "rwmos/geometry/intersect.h"
#include "rwmos/geometry/shared.h"

namespace rwmos::geom {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
// Radius differences of a spiral below this are not corrected at a corner: the path is then at
// most this far from the exact one, far below kPathTolerance.
constexpr double kSpiralCorrection = 1e-7;

// The roots of s^2 + 2 b s + c = 0, computed without cancellation (the smaller one from
// the larger by Vieta). Near-tangent meetings (a discriminant within rounding of zero)
// count as touching.
struct Roots {
    double s[2] = {0.0, 0.0};
    int count = 0;
};
Roots half_b_quadratic(double b, double c) noexcept {
    Roots out;
    double disc = b * b - c;
    const double scale = std::max(b * b, std::abs(c));
    if (disc < 0.0) {
        if (disc < -1e-12 * scale) return out;
        disc = 0.0;
    }
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    if (q == 0.0) {  // b == 0 and c == 0: a double root at 0
        out.count = 1;
        return out;
    }
    out.s[0] = q;
    out.s[1] = c / q;
    out.count = 2;
    return out;
}

// One intersection of the two carriers, as a displacement y from the held element's end
// P1 (X = P1 + y). Displacements stay small near the corner, so they keep their
// precision where absolute coordinates would cancel.
struct Meeting {
    Vec2 y = Vec2::Zero();
};

// The carrier of an offset element at the corner: the held element at its end, the
// next at its start. Arcs: the circle about the centre through that end.
struct Carrier {
    bool arc = false;
    Vec2 direction = Vec2::Zero();  // lines
    Vec2 centre = Vec2::Zero();     // arcs
};

Carrier carrier_of(const OffsetElement& o) noexcept {
    Carrier c;
    c.arc = is_arc(o.path);
    c.direction = o.direction;
    c.centre = o.path.centre;
    return c;
}

// Intersections of the held carrier (through P1) and the next carrier (through P1 + gap),
// with u = P1 - centre of the held arc and v = P2 - centre of the next arc. An arc's carrier
// is the circle through its corner end, its radius changed by dh (held) or dn (next): an arc
// whose radius changes along it (a spiral) meets the other carrier where its radius is that.
int meet(const Carrier& h, const Carrier& n, const Vec2& p1, const Vec2& p2, const Vec2& gap,
         double dh, double dn, Meeting out[2]) noexcept {
    if (!h.arc && !n.arc) {
        // P1 + y with y = -a t1 = gap + b t2: a = -cross(gap, t2) / cross(t1, t2).
        const double den = cross(h.direction, n.direction);
        if (den == 0.0) return 0;
        const double a = -cross(gap, n.direction) / den;
        out[0].y = -a * h.direction;
        return 1;
    }
    if (!h.arc) {
        // y = -a t1 on the circle about cB of radius |v| + dn: with w = P1 - cB = v - gap,
        // |w - a t1|^2 = (|v| + dn)^2, i.e.
        // a^2 - 2 (t1.w) a + (|gap|^2 - 2 v.gap - 2 |v| dn - dn^2) = 0.
        const Vec2 v = p2 - n.centre;
        const Vec2 w = v - gap;
        const Roots r = half_b_quadratic(
            -h.direction.dot(w), gap.squaredNorm() - 2 * v.dot(gap) - dn * (2 * v.norm() + dn));
        for (int i = 0; i < r.count; ++i) out[i].y = -r.s[i] * h.direction;
        return r.count;
    }
    if (!n.arc) {
        // y = gap + b t2 on the circle about cA of radius |u| + dh (u = P1 - cA):
        // b^2 + 2 t2.(u + gap) b + (2 u.gap + |gap|^2 - 2 |u| dh - dh^2) = 0.
        const Vec2 u = p1 - h.centre;
        const Roots r = half_b_quadratic(n.direction.dot(u + gap),
                                         2 * u.dot(gap) + gap.squaredNorm() - dh * (2 * u.norm() + dh));
        for (int i = 0; i < r.count; ++i) out[i].y = gap + r.s[i] * n.direction;
        return r.count;
    }
    // Two circles: |u + y| = |u| + dh and |v - gap + y| = |v| + dn. Their difference is the
    // radical line e.y = k with e = cA - cB; y = y0 + s e_perp on it, then on the first circle.
    const Vec2 u = p1 - h.centre;
    const Vec2 v = p2 - n.centre;
    const Vec2 e = h.centre - n.centre;
    const double e2 = e.squaredNorm();
    if (e2 == 0.0) return 0;  // concentric
    const double kh = dh * (2 * u.norm() + dh);
    const double kn = dn * (2 * v.norm() + dn);
    const double k = v.dot(gap) - 0.5 * gap.squaredNorm() + 0.5 * (kn - kh);
    const Vec2 y0 = (k / e2) * e;
    const Vec2 e_perp = left_normal(e) / std::sqrt(e2);
    const Roots r = half_b_quadratic(u.dot(e_perp), 2 * u.dot(y0) + y0.squaredNorm() - kh);
    for (int i = 0; i < r.count; ++i) out[i].y = y0 + r.s[i] * e_perp;
    return r.count;
}

// What the trim reads of an offset arc again and again, measured once: its radius at its start
// and its end, and their mean (lengths along it are angles times the mean). Zero for lines.
struct Radii {
    double start = 0.0;
    double end = 0.0;
    double mean = 0.0;
};

Radii radii_of(const OffsetElement& o) noexcept {
    Radii r;
    if (!is_arc(o.path)) return r;
    r.start = radius(o.path);
    r.end = end_radius(o.path);
    r.mean = 0.5 * (r.start + r.end);
    return r;
}

// offset_length(o) with the mean radius of its radii (the same value, the radii measured once).
double length_of(const OffsetElement& o, const Radii& radii) noexcept {
    if (!is_arc(o.path)) return (o.path.end - o.path.start).norm();
    return std::abs(o.sweep) * radii.mean;
}

bool same_bits(const Vec2& a, const Vec2& b) noexcept {
    return std::bit_cast<std::uint64_t>(a.x()) == std::bit_cast<std::uint64_t>(b.x()) &&
           std::bit_cast<std::uint64_t>(a.y()) == std::bit_cast<std::uint64_t>(b.y());
}

// The angle along the held arc back from its end P1 to P1 + y: angle_between(u + y, u) with
// u = P1 - centre. The meeting's readings (back_from_end) and its spiral correction
// (on_spirals) read it at the same meetings: the one of the last y is kept.
class BackAngle {
  public:
    BackAngle(const OffsetElement& held, const Vec2& p1) noexcept
        : u_(p1 - held.path.centre), ccw_(held.path.ccw) {}
    double at(const Vec2& y) noexcept {
        if (!valid_ || !same_bits(y, y_)) {
            angle_ = angle_between(u_ + y, u_, ccw_);
            y_ = y;
            valid_ = true;
        }
        return angle_;
    }

  private:
    Vec2 u_;
    bool ccw_;
    bool valid_ = false;
    Vec2 y_ = Vec2::Zero();
    double angle_ = 0.0;
};

// The radius of an offset arc (a spiral from the radius at its start to the one at its end)
// at the point c + x, less its radius at the held end (from_end) or next start. The angle from
// the corner end to x along the arc (held: back from its end; next: on from its start) is
// from_corner(), read only for an arc that turns.
template <class Angle>
double spiral_offset(const OffsetElement& o, const Radii& radii, bool from_end,
                     Angle&& from_corner_angle) noexcept {
    const double turn = std::abs(o.sweep);
    if (!is_arc(o.path) || turn == 0.0) return 0.0;
    const double r0 = radii.start, r1 = radii.end;
    // Beyond the corner end (nearer it that way round) counts as at it.
    const double from_corner = from_corner_angle();
    const double beyond = from_corner > std::numbers::pi + 0.5 * turn ? 0.0 : from_corner;
    const double t = std::clamp(from_end ? 1.0 - beyond / turn : beyond / turn, 0.0, 1.0);
    return r0 + t * (r1 - r0) - (from_end ? r1 : r0);
}

// The meetings of the carriers with the corrections dh and dn (meet()), kept for the next
// round of on_spirals.
struct MetAt {
    Meeting again[2];
    int count = 0;
    bool valid = false;
    std::uint64_t dh_bits = 0;
    std::uint64_t dn_bits = 0;
    bool holds(double dh, double dn) const noexcept {
        return valid && std::bit_cast<std::uint64_t>(dh) == dh_bits &&
               std::bit_cast<std::uint64_t>(dn) == dn_bits;
    }
    void update(int met, double dh, double dn) noexcept {
        count = met;
        dh_bits = std::bit_cast<std::uint64_t>(dh);
        dn_bits = std::bit_cast<std::uint64_t>(dn);
        valid = true;
    }
};

// Moves a meeting of the circles through the corner ends onto the spirals the arcs really
// are: a few rounds of taking each arc's radius where the meeting lies.
Vec2 on_spirals(const OffsetElement& held, const OffsetElement& next, const Radii& held_radii,
                const Radii& next_radii, BackAngle& back, const Carrier& h, const Carrier& n,
                const Vec2& p1, const Vec2& p2, const Vec2& gap, Vec2 y) noexcept {
    if (!h.arc && !n.arc) return y;
    MetAt met;
    for (int round = 0; round < 4; ++round) {
        // The held arc's angle back from its end to p1 + y: (p1 - centre) + y against
        // p1 - centre (p1 is its end), as back_from_end reads it.
        const double dh =
            h.arc ? spiral_offset(held, held_radii, true, [&] { return back.at(y); }) : 0.0;
        const double dn =
            n.arc ? spiral_offset(next, next_radii, false,
                                  [&] {
                                      const Vec2 x = p1 - n.centre + y;
                                      return angle_between(next.path.start - next.path.centre, x,
                                                           next.path.ccw);
                                  })
                  : 0.0;
        // Near the corner ends the spirals have the circles' radii: a meeting that close needs
        // no correction (and where the carriers nearly touch, a correction of a few nm would
        // slide it along them far more than it moves it across).
        if (std::abs(dh) <= kSpiralCorrection && std::abs(dn) <= kSpiralCorrection) return y;
        // The carriers' meetings depend on the corrections alone (the rest is fixed): a round
        // whose corrections have the bits of the last one's meets where that one did (the
        // round that confirms the meeting has settled).
        if (!met.holds(dh, dn)) met.update(meet(h, n, p1, p2, gap, dh, dn, met.again), dh, dn);
        const int count = met.count;
        const Meeting* again = met.again;
        if (count == 0) return y;
        Vec2 best = again[0].y;
        for (int i = 1; i < count; ++i)
            if ((again[i].y - y).norm() < (best - y).norm()) best = again[i].y;
        const bool settled = (best - y).norm() < 1e-13;
        y = best;
        if (settled) break;
    }
    return y;
}

// How far back from the held element's end the point P1 + y lies, along the element (mm;
// arcs: the angle turned from there to the end times the mean radius). Arcs give the
// readings within a turn; `wrapped` the one a circumference earlier (a point just past the
// end reads as almost a full turn back, and as slightly negative).
double back_from_end(const OffsetElement& o, const Radii& radii, BackAngle& back, const Vec2& y,
                     double& wrapped) noexcept {
    if (!is_arc(o.path)) {
        wrapped = std::numeric_limits<double>::quiet_NaN();
        return -y.dot(o.direction);
    }
    const double angle = back.at(y);
    wrapped = (angle - kTwoPi) * radii.mean;
    return angle * radii.mean;
}

// How far beyond the next element's start the point P1 + y lies, along the element.
double past_start(const OffsetElement& o, const Radii& radii, const Vec2& p2, const Vec2& gap,
                  const Vec2& y, double& wrapped) noexcept {
    if (!is_arc(o.path)) {
        wrapped = std::numeric_limits<double>::quiet_NaN();
        return (y - gap).dot(o.direction);
    }
    const Vec2 v = p2 - o.path.centre;
    const double angle = angle_between(v, v - gap + y, o.path.ccw);
    wrapped = (angle - kTwoPi) * radii.mean;
    return angle * radii.mean;
}

// Picks the reading within [-kTrimTolerance, len + kTrimTolerance] nearest 0 (the corner),
// clamped to [0, len]. False if neither reading lies there.
bool on_element(double reading, double wrapped, double len, double& along) noexcept {
    bool found = false;
    for (double v : {reading, wrapped}) {
        if (!(v >= -kTrimTolerance && v <= len + kTrimTolerance)) continue;  // NaN fails too
        const double clamped = std::clamp(v, 0.0, len);
        if (!found || clamped < along) along = clamped;
        found = true;
    }
    return found;
}

Element line(const Vec2& a, const Vec2& b) noexcept {
    return make_line(a, b);
}

// The offset element made to start at x instead of its start (x within kPathTolerance of it):
// an arc keeps its centre and turns by as much less as x lies ahead of the old start.
// (Everything read from o is read before o changes.)
void start_at(OffsetElement& o, const Vec2& x) noexcept {
    // A full circle still closes where it starts: a whole turn from x.
    if (is_arc(o.path) && std::abs(o.sweep) >= kTwoPi) {
        o.path.start = x;
        o.path.end = x;
        return;
    }
    if (is_arc(o.path)) {
        const Vec2 before = o.path.start - o.path.centre;
        const Vec2 after = x - o.path.centre;
        o.sweep = o.sweep - turn_angle(before, after);
    }
    o.path.start = x;
}

// The offset element made to end at x instead of its end (x just past it): an arc turns by as
// much more.
void end_at(OffsetElement& o, const Vec2& x) noexcept {
    if (is_arc(o.path)) {
        const Vec2 before = o.path.end - o.path.centre;
        const Vec2 after = x - o.path.centre;
        o.sweep = o.sweep + turn_angle(before, after);
    }
    o.path.end = x;
}

// A reading from the corner end (back from the held end, or on from the next start) that lies
// on the element: not just beyond the corner end (a negative or wrapped-round reading).
bool back_is_before_end(double reading, double wrapped, double len) noexcept {
    if (reading <= len) return reading >= 0.0;
    // Beyond the far end, or (an arc read round the circle) just before the corner end:
    // whichever is nearer.
    return !(wrapped <= 0.0 && -wrapped < reading - len);
}

// The sense of the turn from t1 to t2 (+1 counter-clockwise, -1 clockwise) when the corner is
// surely neither tangent nor a reversal for tool radius r, whatever the rounding of the angle
// classify_corner computes; 0 when it may be either (classify_corner then reads the angle).
// With c = cross(t1, t2) = h sin(turn), d = t1.t2 = h cos(turn), h = |t1| |t2|:
// - apart (offset_gap > kPathTolerance): 2 r |sin(turn / 2)| >= r |sin(turn)| = r |c| / h, and
//   >= sqrt(2) r for |turn| >= pi / 2 (d <= 0); a margin of 2 (of sqrt(2)) covers every rounding;
// - no reversal: d >= -0.999 h puts |turn| at most acos(-0.999) = pi - 2.56 degrees, so the wedge
//   is wider than kMaxReversalWedgeAngle;
// - the sense: atan2(c, d) has the sign of c != 0, and being apart keeps |turn| >= 2e-9 (for r up
//   to kMaxCoordinate; larger r, NaN or infinite, are left to the angle), far from an underflow.
int clear_turn(const Vec2& t1, const Vec2& t2, double r) noexcept {
    static_assert(kMaxReversalWedgeAngle <= std::numbers::pi / 180);
    const double c = cross(t1, t2);
    const double d = t1.dot(t2);
    if (!(c != 0.0) || !(r <= kMaxCoordinate)) return 0;
    const double h = std::sqrt(c * c + d * d);
    const bool apart =
        r * std::abs(c) >= 2 * kPathTolerance * h || (d <= 0.0 && r >= kPathTolerance);
    if (!apart || !(d >= -0.999 * h)) return 0;
    return c > 0.0 ? 1 : -1;
}

}  // namespace

double offset_gap(double turn, double r) noexcept {
    return 2 * r * std::abs(std::sin(0.5 * turn));
}

CornerKind classify_corner(const Vec2& end_tangent, const Vec2& start_tangent, Side side,
                           double r, double shorter_length) noexcept {
    // Most corners are far from every threshold: their kind is the sense of the turn alone.
    if (const int sense = clear_turn(end_tangent, start_tangent, r); sense != 0)
        return (sense > 0) != (side == Side::kLeft) ? CornerKind::kOutside : CornerKind::kInside;
    const double turn = turn_angle(end_tangent, start_tangent);
    if (offset_gap(turn, r) <= kPathTolerance) return CornerKind::kTangent;
    const bool turns_left = turn > 0.0;
    if (turns_left != (side == Side::kLeft)) return CornerKind::kOutside;
    // An inside turn of nearly 180 degrees: a wedge of angle pi - |turn|, as wide as
    // shorter_length * sin(pi - |turn|) at the far end of the shorter element.
    const double wedge = std::numbers::pi - std::abs(turn);
    if (wedge <= kMaxReversalWedgeAngle && shorter_length * std::sin(wedge) <= kReversalWedgeWidth)
        return CornerKind::kOutside;
    return CornerKind::kInside;
}

InsideTrim trim_inside_corner(const OffsetElement& held, const OffsetElement& next,
                              const Vec2& corner) noexcept {
    InsideTrim out;
    out.held = held;
    out.next = next;
    out.reason = trim_inside_corner_in_place(out.held, out.next, corner);
    if (out.reason != Reason::kNone) out.held = out.next = OffsetElement{};
    return out;
}

Reason trim_inside_corner_in_place(OffsetElement& held, OffsetElement& next,
                                   const Vec2& corner) noexcept {
    const Vec2 p1 = held.path.end;
    const Vec2 p2 = next.path.start;
    const Vec2 gap = p2 - p1;
    Meeting meetings[2];
    const Carrier hc = carrier_of(held), nc = carrier_of(next);
    const int count = meet(hc, nc, p1, p2, gap, 0.0, 0.0, meetings);
    if (count == 0) return Reason::kNoCornerSolution;
    const Radii held_radii = radii_of(held), next_radii = radii_of(next);
    const double held_len = length_of(held, held_radii);
    const double next_len = length_of(next, next_radii);
    BackAngle back_angle(held, p1);
    bool found = false;
    double best_back = 0.0, best_past = 0.0;
    Vec2 best_y = Vec2::Zero();
    double nearest = std::numeric_limits<double>::infinity();
    Reason nearest_failure = Reason::kNoCornerSolution;
    for (int i = 0; i < count; ++i) {
        // Which meeting, and whether it lies on both, is read on the circles through the
        // corner ends: there each arc has exactly that radius, and near a tangent meeting a
        // spiral's slight change of radius would move the meeting along far more than across.
        const Vec2& y = meetings[i].y;
        double held_wrapped = 0.0, next_wrapped = 0.0;
        const double held_reading = back_from_end(held, held_radii, back_angle, y, held_wrapped);
        double back = 0.0, past = 0.0;
        const bool on_held = on_element(held_reading, held_wrapped, held_len, back);
        // Off the held element the meeting fails whatever the next one reads there.
        bool on_next = false;
        if (on_held) {
            const double next_reading = past_start(next, next_radii, p2, gap, y, next_wrapped);
            on_next = on_element(next_reading, next_wrapped, next_len, past);
        }
        if (!on_held || !on_next) {
            const double to_corner = (p1 - corner + y).norm();
            if (to_corner < nearest) {
                nearest = to_corner;
                nearest_failure =
                    on_held ? Reason::kNextElementTooShort : Reason::kHeldElementTooShort;
            }
            continue;
        }
        // The meeting latest on the held element (nearest its end); equal: earliest on next.
        if (!found || back < best_back || (back == best_back && past < best_past)) {
            best_back = back;
            best_past = past;
            best_y = y;
        }
        found = true;
    }
    if (!found) return nearest_failure;
    // Then the meeting moves onto the spirals the arcs are (a trim deep into an arc whose
    // radii differ by rounding), and both elements end and start there.
    const Vec2 y =
        on_spirals(held, next, held_radii, next_radii, back_angle, hc, nc, p1, p2, gap, best_y);
    const Vec2 x = p1 + y;
    double held_wrapped = 0.0, next_wrapped = 0.0;
    const double back = back_from_end(held, held_radii, back_angle, y, held_wrapped);
    const double past = past_start(next, next_radii, p2, gap, y, next_wrapped);
    if (back_is_before_end(back, held_wrapped, held_len))
        trim_end_in_place(held, x, held_len - std::clamp(back, 0.0, held_len));
    else
        end_at(held, x);
    if (back_is_before_end(past, next_wrapped, next_len))
        trim_start_in_place(next, x, std::clamp(past, 0.0, next_len));
    else
        start_at(next, x);
    return Reason::kNone;
}

Transition outside_transition(const Vec2& corner, const Vec2& held_end, const Vec2& end_tangent,
                              const Vec2& next_start, const Vec2& start_tangent, Side side,
                              double r, TransitionMode mode) noexcept {
    Transition out;
    if (mode == TransitionMode::kCircular) {
        // Outside corners turn away from the tool: right (clockwise) for G41.
        out.elements[0] = make_arc(held_end, next_start, corner, side == Side::kRight);
        out.count = 1;
        return out;
    }
    const double turn = std::abs(turn_angle(end_tangent, start_tangent));
    if (turn <= kLinearCornerMaxTurn) {
        const Intersections meet_at =
            intersect_lines(held_end, end_tangent, next_start, start_tangent);
        if (meet_at.count == 1) {
            out.elements[0] = line(held_end, meet_at.points[0]);
            out.elements[1] = line(meet_at.points[0], next_start);
            out.count = 2;
            return out;
        }
    }
    // The turn the tool makes round the corner: away from the tool (clockwise for G41). A
    // reversal read from a wedge turns a little over 180 degrees; there extensions of r would
    // cut the chamfer into the circle of radius r about the corner, so they are lengthened to
    // r tan(turn / 4), which lays the chamfer on that circle's tangent.
    double around = turn_angle(end_tangent, start_tangent);
    if (side == Side::kLeft) around = -around;
    if (around < 0) around += 2 * std::numbers::pi;
    const double reach = r * std::max(1.0, std::tan(0.25 * around));
    const Vec2 extended_end = held_end + reach * end_tangent;
    const Vec2 extended_start = next_start - reach * start_tangent;
    out.elements[0] = line(held_end, extended_end);
    out.elements[1] = line(extended_end, extended_start);
    out.elements[2] = line(extended_start, next_start);
    out.count = 3;
    return out;
}

CornerJoin join_corner(const OffsetElement& held, const OffsetElement& next, const Vec2& corner,
                       const Vec2& end_tangent, const Vec2& start_tangent, Side side, double r,
                       TransitionMode mode, double shorter_length) noexcept {
    CornerJoin out;
    out.held = held;
    out.next = next;
    const JoinKind joined =
        join_corner_in_place(out.held, out.next, out.transition, corner, end_tangent, start_tangent,
                             side, r, mode, shorter_length);
    out.reason = joined.reason;
    out.kind = joined.kind;
    return out;
}

JoinKind join_corner_in_place(OffsetElement& held, OffsetElement& next, Transition& transition,
                              const Vec2& corner, const Vec2& end_tangent,
                              const Vec2& start_tangent, Side side, double r, TransitionMode mode,
                              double shorter_length) noexcept {
    JoinKind out;
    out.kind = classify_corner(end_tangent, start_tangent, side, r, shorter_length);
    switch (out.kind) {
        case CornerKind::kTangent:
            // The offset ends lie at most kPathTolerance apart: the next starts where the
            // held one ends, so the path is continuous.
            start_at(next, held.path.end);
            return out;
        case CornerKind::kInside:
            out.reason = trim_inside_corner_in_place(held, next, corner);
            return out;
        case CornerKind::kOutside:
            transition = outside_transition(corner, held.path.end, end_tangent, next.path.start,
                                            start_tangent, side, r, mode);
            return out;
    }
    return out;
}

}  // namespace rwmos::geom
