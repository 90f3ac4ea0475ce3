// SPDX-License-Identifier: MIT
#include "bottleneck.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <variant>

#include "geometry/element.h"

namespace apci::run::detail {
namespace {

using Vec2 = Eigen::Vector2d;
// Closer than this to a path's end, a crossing is its end (a path meeting another there).
constexpr double kEnd = 1e-6;

using geom::cross;

Vec2 in_plane(const Eigen::Vector3d& p, const PlaneAxes& ax) {
    return {p[ax.first], p[ax.second]};
}

// A crossing of two paths: the point and how far along each (0..1) it lies.
struct Crossing {
    Vec2 at;
    double on_first, on_second;
};

// Where point x, known to lie on a path's carrier, lies along the path (0..1), or nothing
// where it is beyond its ends.
template <class M>
std::optional<double> along(const M& m, const Vec2& x) {
    if (!m.arc) {
        const Vec2 d = m.b - m.a;
        const double n2 = d.squaredNorm();
        if (n2 == 0.0) return std::nullopt;
        const double t = (x - m.a).dot(d) / n2;
        if (t < 0.0 || t > 1.0) return std::nullopt;
        return t;
    }
    const Vec2 u0(std::cos(m.phi0), std::sin(m.phi0));
    const double t = geom::angle_between(u0, x - m.c, m.sweep > 0.0) / std::abs(m.sweep);
    if (t > 1.0) return std::nullopt;
    return t;
}

// The points where two circles or lines meet (the carriers), at most two.
template <class M>
std::vector<Vec2> carrier_points(const M& p, const M& q) {
    std::vector<Vec2> out;
    if (!p.arc && !q.arc) {
        const Vec2 d1 = p.b - p.a, d2 = q.b - q.a;
        const double den = cross(d1, d2);
        if (std::abs(den) < 1e-15 * d1.norm() * d2.norm()) return out;  // parallel
        out.push_back(p.a + cross(q.a - p.a, d2) / den * d1);
        return out;
    }
    if (p.arc != q.arc) {
        const M& l = p.arc ? q : p;
        const M& c = p.arc ? p : q;
        const Vec2 d = l.b - l.a;
        const double len = d.norm();
        if (len == 0.0) return out;
        const Vec2 u = d / len;
        const double along_c = (c.c - l.a).dot(u);
        const Vec2 foot = l.a + along_c * u;
        const double h2 = (c.c - foot).squaredNorm();
        const double w2 = c.rho * c.rho - h2;
        if (w2 <= 0.0) return out;  // apart, or touching: no crossing
        const double w = std::sqrt(w2);
        out.emplace_back(foot - w * u);
        out.emplace_back(foot + w * u);
        return out;
    }
    const Vec2 d = q.c - p.c;
    const double dist = d.norm();
    if (dist == 0.0 || dist >= p.rho + q.rho || dist <= std::abs(p.rho - q.rho)) return out;
    const double a = (p.rho * p.rho - q.rho * q.rho + dist * dist) / (2.0 * dist);
    const double h = std::sqrt(std::max(0.0, p.rho * p.rho - a * a));
    const Vec2 u = d / dist, n(-u.y(), u.x());
    out.push_back(p.c + a * u + h * n);
    out.push_back(p.c + a * u - h * n);
    return out;
}

}  // namespace

namespace {

// The path (offset) of a compensated move in the plane, r to the tool's side (+1 left).
template <class M>
M path_of(const nc::Event& ev, double r, int side, const PlaneAxes& ax, std::size_t index) {
    M m;
    m.event = index;
    if (const auto* l = std::get_if<nc::LineMove>(&ev.data)) {
        const Vec2 a = in_plane(l->start, ax), b = in_plane(l->end, ax);
        const Vec2 d = b - a;
        const double len = d.norm();
        const Vec2 n = len > 0.0 ? Vec2(Vec2(-d.y(), d.x()) / len) : Vec2::Zero();
        m.a = a + side * r * n;
        m.b = b + side * r * n;
        return m;
    }
    const auto& arc = std::get<nc::ArcMove>(ev.data);
    m.arc = true;
    const Vec2 c = in_plane(arc.center, ax), s = in_plane(arc.start, ax), e = in_plane(arc.end, ax);
    const double radius = (s - c).norm();
    // The tool on the left of a counter-clockwise arc is inside it.
    const bool inside = (side > 0) == arc.ccw;
    m.c = c;
    m.rho = inside ? radius - r : radius + r;
    m.usable = m.rho > 0.0 && radius > 0.0;
    m.phi0 = std::atan2(s.y() - c.y(), s.x() - c.x());
    m.sweep = geom::arc_sweep(s - c, e - c, arc.ccw, (e - s).norm() <= 1e-9);
    return m;
}

bool is_plane_move(const nc::Event& ev, const PlaneAxes& ax, int plane) {
    if (const auto* l = std::get_if<nc::LineMove>(&ev.data))
        return (in_plane(l->end, ax) - in_plane(l->start, ax)).norm() > 1e-9;
    if (const auto* a = std::get_if<nc::ArcMove>(&ev.data))
        return nc::g_number(a->plane) == plane;
    return false;
}

// The point of a move's contour whose offset (r to `side`) is x, on its path, with the
// move's coordinate on the third axis there (linear along a line, with the angle on a helix).
Eigen::Vector3d foot(const nc::Event& ev, const Vec2& x, double r, int side, const PlaneAxes& ax,
                     double t) {
    Eigen::Vector3d out = Eigen::Vector3d::Zero();
    Vec2 p = Vec2::Zero();
    double z0 = 0.0, z1 = 0.0;
    if (const auto* l = std::get_if<nc::LineMove>(&ev.data)) {
        const Vec2 a = in_plane(l->start, ax), b = in_plane(l->end, ax);
        const Vec2 d = (b - a).normalized();
        p = x - side * r * Vec2(-d.y(), d.x());
        z0 = l->start[ax.third];
        z1 = l->end[ax.third];
    } else {
        const auto& arc = std::get<nc::ArcMove>(ev.data);
        const Vec2 c = in_plane(arc.center, ax);
        const double radius = (in_plane(arc.start, ax) - c).norm();
        p = c + radius * (x - c).normalized();
        z0 = arc.start[ax.third];
        z1 = arc.end[ax.third];
    }
    out[ax.first] = p.x();
    out[ax.second] = p.y();
    out[ax.third] = z0 + t * (z1 - z0);
    return out;
}

void set_end(nc::Event& ev, const Eigen::Vector3d& p) {
    if (auto* l = std::get_if<nc::LineMove>(&ev.data)) l->end = p;
    if (auto* a = std::get_if<nc::ArcMove>(&ev.data)) a->end = p;
}
void set_start(nc::Event& ev, const Eigen::Vector3d& p) {
    if (auto* l = std::get_if<nc::LineMove>(&ev.data)) l->start = p;
    if (auto* a = std::get_if<nc::ArcMove>(&ev.data)) {
        // The arc's centre keeps the start's coordinate on the third axis.
        a->start = p;
    }
}
double feed_of(const nc::Event& ev) {
    if (const auto* l = std::get_if<nc::LineMove>(&ev.data)) return l->feed;
    if (const auto* a = std::get_if<nc::ArcMove>(&ev.data)) return a->feed;
    return 0.0;
}

}  // namespace

void BottleneckAvoider::take(const nc::Event& ev, double radius, int plane,
                             std::vector<nc::Event>& out, std::vector<Bottleneck>& found) {
    if (const auto* c = std::get_if<nc::CompensationChange>(&ev.data)) {
        flush(out);
        side_ = c->side == nc::Compensation::kLeft ? 1 : c->side == nc::Compensation::kRight ? -1 : 0;
        first_ = side_ != 0;
        out.push_back(ev);
        return;
    }
    if (const auto* w = std::get_if<nc::CollisionDetectionChange>(&ev.data)) walls_ = w->on;
    const PlaneAxes ax = plane_axes(plane);
    if (side_ == 0 || radius <= 0.0 || std::holds_alternative<nc::RapidMove>(ev.data) ||
        std::holds_alternative<nc::ProgramEnd>(ev.data)) {
        flush(out);
        if (std::holds_alternative<nc::RapidMove>(ev.data)) first_ = side_ != 0;
        out.push_back(ev);
        return;
    }
    if (!is_plane_move(ev, ax, plane)) {
        held_.push_back(ev);
        if (moves_.empty()) flush(out);
        return;
    }
    if (first_) {  // the approach: given on, not compared
        first_ = false;
        flush(out);
        out.push_back(ev);
        return;
    }
    held_.push_back(ev);
    moves_.push_back(path_of<Move>(ev, radius, side_, ax, held_.size() - 1));
    avoid(radius, plane, found);
    // Hold no more moves than are compared: the oldest go out.
    while (moves_.size() > static_cast<std::size_t>(blocks_)) release(1, out);
}

void BottleneckAvoider::flush(std::vector<nc::Event>& out) {
    for (nc::Event& e : held_) out.push_back(std::move(e));
    held_.clear();
    moves_.clear();
}

// The first `count` moves held go out, with the events before them and up to the next move.
void BottleneckAvoider::release(std::size_t count, std::vector<nc::Event>& out) {
    const std::size_t upto = count < moves_.size() ? moves_[count].event : held_.size();
    for (std::size_t i = 0; i < upto; ++i) out.push_back(std::move(held_[i]));
    held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(upto));
    moves_.erase(moves_.begin(), moves_.begin() + static_cast<std::ptrdiff_t>(count));
    for (Move& m : moves_) m.event -= upto;
}

void BottleneckAvoider::avoid(double radius, int plane, std::vector<Bottleneck>& found) {
    const std::size_t j = moves_.size() - 1;
    if (j < 2 || !moves_[j].usable) return;
    const PlaneAxes ax = plane_axes(plane);
    const Move& mj = moves_[j];
    const nc::Event& ej = held_[mj.event];
    // The farthest back first (SINUMERIK: the last intersection found is valid).
    for (std::size_t i = 0; i + 2 <= j; ++i) {
        const Move& mi = moves_[i];
        if (!mi.usable) continue;
        const nc::Event& ei = held_[mi.event];
        // A move that closes a contour onto the start of move i follows it round the contour:
        // their paths meet at that corner, which is no bottleneck.
        const auto* li = std::get_if<nc::LineMove>(&ei.data);
        const auto* ai = std::get_if<nc::ArcMove>(&ei.data);
        const Eigen::Vector3d i_start = li != nullptr ? li->start : ai->start;
        const auto* lj = std::get_if<nc::LineMove>(&ej.data);
        const auto* aj = std::get_if<nc::ArcMove>(&ej.data);
        const Eigen::Vector3d j_end = lj != nullptr ? lj->end : aj->end;
        if ((in_plane(i_start, ax) - in_plane(j_end, ax)).norm() <= 1e-6) continue;
        std::optional<Crossing> best;
        for (const Vec2& x : carrier_points(mi, mj)) {
            const auto ti = along(mi, x), tj = along(mj, x);
            if (!ti || !tj || *ti <= kEnd || *ti >= 1.0 - kEnd || *tj <= kEnd ||
                *tj >= 1.0 - kEnd)
                continue;
            if (!best || *tj < best->on_second) best = Crossing{x, *ti, *tj};
        }
        if (!best) continue;
        // The moves between go in the plane; what else their blocks do stays, in order, at X.
        Bottleneck b;
        b.before = ei.origin;
        b.after = ej.origin;
        b.first = held_[moves_[i + 1].event].origin;
        b.last = held_[moves_[j - 1].event].origin;
        const Eigen::Vector3d pi = foot(ei, best->at, radius, side_, ax, best->on_first);
        const Eigen::Vector3d pj = foot(ej, best->at, radius, side_, ax, best->on_second);
        b.where = Point::Zero();
        b.where[ax.first] = best->at.x();
        b.where[ax.second] = best->at.y();
        b.where[ax.third] = pi[ax.third];
        std::deque<nc::Event> kept;
        for (std::size_t e = 0; e < held_.size(); ++e) {
            const bool between = e > mi.event && e < mj.event;
            if (between && is_plane_move(held_[e], ax, plane)) continue;
            if (e == mi.event) {
                nc::Event shortened = held_[e];
                set_end(shortened, pi);
                kept.push_back(shortened);
                continue;
            }
            if (e == mj.event) {
                // The arc about X from the one contour to the other, its offset X: no wall.
                nc::ArcMove bridge;
                bridge.start = pi;
                bridge.end = pj;
                bridge.center = pi;
                bridge.center[ax.first] = best->at.x();
                bridge.center[ax.second] = best->at.y();
                bridge.ccw = side_ > 0;
                bridge.plane = static_cast<nc::Plane>(plane);
                bridge.feed = feed_of(ej);
                kept.push_back(nc::Event{ej.origin, nc::CollisionDetectionChange{false}});
                kept.push_back(nc::Event{ej.origin, bridge});
                kept.push_back(nc::Event{ej.origin, nc::CollisionDetectionChange{walls_}});
                nc::Event started = held_[e];
                set_start(started, pj);
                kept.push_back(started);
                continue;
            }
            kept.push_back(held_[e]);
        }
        held_ = std::move(kept);
        // The paths held again, from the events as they are now.
        moves_.clear();
        for (std::size_t e = 0; e < held_.size(); ++e)
            if (is_plane_move(held_[e], ax, plane) &&
                !std::holds_alternative<nc::CollisionDetectionChange>(held_[e].data)) {
                Move m = path_of<Move>(held_[e], radius, side_, ax, e);
                // The bridge's path is a point: nothing to compare.
                if (m.arc && m.rho <= 1e-9) m.usable = false;
                moves_.push_back(m);
            }
        found.push_back(b);
        return;  // one bottleneck per new move: the next moves compare with what is left
    }
}

}  // namespace apci::run::detail
