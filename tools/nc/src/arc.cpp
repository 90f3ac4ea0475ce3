// SPDX-License-Identifier: MIT
#include "apci/nc/arc.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace apci::nc {

namespace {
Eigen::Vector2d in_plane(const Eigen::Vector3d& v, PlaneAxes a) {
    return {v[a.first], v[a.second]};
}
}  // namespace

ArcCenterResult arc_center_from_radius(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                                       double r, bool ccw, Plane p) {
    ArcCenterResult out;
    const PlaneAxes a = plane_axes(p);
    const Eigen::Vector2d s = in_plane(start, a);
    const Eigen::Vector2d e = in_plane(end, a);
    const Eigen::Vector2d chord = e - s;
    const double d = chord.norm();
    const double abs_r = std::fabs(r);
    if (d < kMinArcRadius) {
        out.message =
            "R arc impossible: its end point equals the start point in the plane "
            "(program a full circle with I/J/K)";
        return out;
    }
    if (d > 2.0 * abs_r + kArcRadiusTolerance) {
        out.message = fmt::format(
            "R arc impossible: the chord from start to end is {:.4f} mm long, more than the "
            "diameter {:.4f} mm of R{}",
            d, 2.0 * abs_r, r);
        return out;
    }
    const double half = d / 2.0;
    double h = 0.0;
    if (abs_r > half) {
        // r^2 overflows for |R| beyond 1e154; the factored form stays finite there.
        const double rr = abs_r * abs_r;
        h = std::isfinite(rr) ? std::sqrt(rr - half * half)
                              : std::sqrt(abs_r - half) * std::sqrt(abs_r + half);
    }
    const Eigen::Vector2d u = chord / d;
    const Eigen::Vector2d left(-u.y(), u.x());
    // The shorter counter-clockwise arc turns around a centre left of the chord; clockwise or the
    // longer arc puts it on the right.
    const double side = (ccw ? 1.0 : -1.0) * (r > 0.0 ? 1.0 : -1.0);
    const Eigen::Vector2d c = (s + e) / 2.0 + side * h * left;
    if (!c.allFinite()) {
        out.message = fmt::format("R arc impossible: R{} puts its centre beyond any coordinate", r);
        return out;
    }
    out.center = start;
    out.center[a.first] = c.x();
    out.center[a.second] = c.y();
    out.ok = true;
    return out;
}

namespace {

// What is wrong with an arc's centre, if anything, and its radii at the start and the end.
enum class CenterFault : std::uint8_t { kNone, kZeroRadius, kOffCircle };
struct CenterCheck {
    CenterFault fault = CenterFault::kNone;
    double rs = 0.0, re = 0.0;
};

[[gnu::always_inline]] inline CenterCheck check_center(const Eigen::Vector3d& start,
                                                       const Eigen::Vector3d& end,
                                                       const Eigen::Vector3d& center,
                                                       Plane p) noexcept {
    const PlaneAxes a = plane_axes(p);
    const Eigen::Vector2d c = in_plane(center, a);
    CenterCheck out;
    out.rs = (in_plane(start, a) - c).norm();
    out.re = (in_plane(end, a) - c).norm();
    if (out.rs < kMinArcRadius)
        out.fault = CenterFault::kZeroRadius;
    else if (std::fabs(out.rs - out.re) > kArcRadiusTolerance)
        out.fault = CenterFault::kOffCircle;
    return out;
}

}  // namespace

bool arc_center_ok(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                   const Eigen::Vector3d& center, Plane p) noexcept {
    return check_center(start, end, center, p).fault == CenterFault::kNone;
}

std::string check_arc_center(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                             const Eigen::Vector3d& center, Plane p) {
    const CenterCheck c = check_center(start, end, center, p);
    switch (c.fault) {
        case CenterFault::kZeroRadius:
            return "arc radius is 0: the centre (I/J/K) is the start point";
        case CenterFault::kOffCircle:
            return fmt::format(
                "arc end point is not on the circle: radius {:.4f} mm at the start, {:.4f} mm at "
                "the end (tolerance {} mm)",
                c.rs, c.re, kArcRadiusTolerance);
        case CenterFault::kNone:
            break;
    }
    return {};
}

namespace {
// A coordinate in a message: to 0.1 um, or as a power of ten where that many digits say nothing.
std::string coordinate_text(double v) {
    return std::fabs(v) < 1e9 ? fmt::format("{:.4f}", v) : fmt::format("{:g}", v);
}
}  // namespace

std::string check_arc_range(const ArcMove& arc, double limit) {
    constexpr char kLetter[3] = {'X', 'Y', 'Z'};
    const PlaneAxes a = plane_axes(arc.plane);
    const Eigen::Vector2d c = in_plane(arc.center, a);
    if (!(std::fabs(c.x()) <= limit && std::fabs(c.y()) <= limit))
        return fmt::format(
            "arc centre {} {} {} {} mm is beyond the board's coordinate range of +-{:g} mm",
            kLetter[a.first], coordinate_text(c.x()), kLetter[a.second], coordinate_text(c.y()),
            limit);
    const Eigen::Vector2d s = in_plane(arc.start, a) - c;
    const Eigen::Vector2d e = in_plane(arc.end, a) - c;
    const double r = std::sqrt(std::max(s.squaredNorm(), e.squaredNorm()));
    // Within whatever way it turns: the usual arc, told without an angle.
    if (std::fabs(c.x()) + r <= limit && std::fabs(c.y()) + r <= limit) return {};
    // The angles the arc sweeps, from its start, in its direction (a whole turn when it ends
    // where it starts), as move_length() counts them.
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    const double start_angle = std::atan2(s.y(), s.x());
    const double sweep = std::fabs(arc_sweep(s, e, arc.ccw, !((e - s).norm() > 1e-9)));
    // Direction k (0: +first, 1: +second, 2: -first, 3: -second) lies at angle k * 90 degrees.
    for (int k = 0; k < 4; ++k) {
        const double direction = k * (kTwoPi / 4.0);
        double from_start = arc.ccw ? direction - start_angle : start_angle - direction;
        from_start = std::fmod(std::fmod(from_start, kTwoPi) + kTwoPi, kTwoPi);
        if (from_start > sweep) continue;
        const bool first = k % 2 == 0;
        const double reach = (first ? c.x() : c.y()) + (k < 2 ? r : -r);
        if (std::fabs(reach) > limit)
            return fmt::format(
                "the arc reaches {} {} mm (centre {} {} {} {}, radius {} mm), beyond the board's "
                "coordinate range of +-{:g} mm",
                kLetter[first ? a.first : a.second], coordinate_text(reach), kLetter[a.first],
                coordinate_text(c.x()), kLetter[a.second], coordinate_text(c.y()),
                coordinate_text(r), limit);
    }
    return {};
}

}  // namespace apci::nc
