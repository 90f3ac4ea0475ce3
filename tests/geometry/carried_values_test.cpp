// SPDX-License-Identifier: MIT
// Values the compensation measures once and carries instead of measuring again must be the
// values it measured before, bit for bit: the offset arc's sweep is the programmed arc's
// sweep(), and the length from it (length_with_sweep) is length(). Random elements: coordinates
// rounded to 3 to 6 decimals (radii that differ by the rounding), tiny elements, full circles,
// both senses. And a corner classified without its angle where it is clear (classify_corner) is
// classified as by the angle: random tangents near every threshold (tangent joins, reversals).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "rng.h"
#include "rwmos/geometry/compensator.h"
#include "rwmos/geometry/corner.h"
#include "rwmos/geometry/offset.h"

namespace rwmos::geom {
namespace {

constexpr double kPi = std::numbers::pi;
using apci::test::Rng;

Vec2 dir(double angle) {
    return {std::cos(angle), std::sin(angle)};
}
Vec2 turned(const Vec2& v, double a) {
    return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()};
}

// The arc starting at `start` along `start_heading`, of `radius`, turning by `turn` radians
// (> 0 counter-clockwise).
Element arc_from(const Vec2& start, double start_heading, double radius, double turn) {
    const bool ccw = turn > 0;
    const Vec2 left(-std::sin(start_heading), std::cos(start_heading));
    const Vec2 centre = start + radius * (ccw ? left : Vec2(-left));
    return make_arc(start, centre + turned(start - centre, turn), centre, ccw);
}

// Rounds to `decimals` places as an NC program writes a coordinate (half away from zero).
double round_to(double v, int decimals) {
    const double scale = std::pow(10.0, decimals);
    return std::round(v * scale) / scale;
}
Vec2 round_to(const Vec2& v, int decimals) {
    return {round_to(v.x(), decimals), round_to(v.y(), decimals)};
}

bool same_bits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// A random element from `start`: a line or an arc of any sweep up to a full circle, from 1 um
// to 100 mm, its coordinates rounded to `decimals` (3 to 6) or not at all (0).
Element random_element(Rng& rng, const Vec2& start, double heading, int decimals) {
    const double size = rng.log_uniform(1e-6, 100.0);
    Element e;
    if (rng.chance(0.3)) {
        e = make_line(start, start + size * dir(heading));
    } else {
        const double turn = rng.sign() * (rng.chance(0.1) ? 2 * kPi : rng.uniform(1e-6, 2 * kPi));
        e = arc_from(start, heading, size, turn);
        if (rng.chance(0.1)) e.end = e.start;  // a full circle
    }
    if (decimals > 0) {
        e.start = round_to(e.start, decimals);
        e.end = round_to(e.end, decimals);
        e.centre = round_to(e.centre, decimals);
    }
    return e;
}

TEST(CarriedValues, LengthWithTheElementsOwnSweepIsItsLength) {
    Rng rng(0x5eed'0001);
    int arcs = 0;
    for (int i = 0; i < 20000; ++i) {
        const int decimals = rng.integer(2, 6);
        const Element e = random_element(rng, {rng.uniform(-500, 500), rng.uniform(-500, 500)},
                                         rng.uniform(-kPi, kPi), decimals == 2 ? 0 : decimals);
        if (check_element(e) != Reason::kNone) continue;
        arcs += is_arc(e) ? 1 : 0;
        ASSERT_TRUE(same_bits(length_with_sweep(e, sweep(e)), length(e))) << i;
    }
    EXPECT_GT(arcs, 10000);
}

TEST(CarriedValues, AnOffsetElementCarriesTheProgrammedSweepAndTangent) {
    // PathCompensator::push measures the programmed length from the offset element's sweep.
    Rng rng(0x5eed'0002);
    int offset_arcs = 0;
    for (int i = 0; i < 20000; ++i) {
        const int decimals = rng.integer(2, 6);
        const Element e = random_element(rng, {rng.uniform(-500, 500), rng.uniform(-500, 500)},
                                         rng.uniform(-kPi, kPi), decimals == 2 ? 0 : decimals);
        if (check_element(e) != Reason::kNone || is_plane_free(e)) continue;
        const double r = rng.chance(0.2) ? 0.0 : rng.log_uniform(1e-3, 50.0);
        const OffsetResult o = offset_element(e, r, rng.chance(0.5) ? Side::kLeft : Side::kRight);
        if (o.reason != Reason::kNone) continue;
        if (is_arc(e)) {
            ++offset_arcs;
            ASSERT_TRUE(same_bits(o.element.sweep, sweep(e))) << i;
        } else {
            // An offset line carries the programmed tangent, the same at both ends.
            ASSERT_TRUE(same_bits(o.element.direction.x(), start_tangent(e).x()) &&
                        same_bits(o.element.direction.y(), start_tangent(e).y()) &&
                        same_bits(o.element.direction.x(), end_tangent(e).x()) &&
                        same_bits(o.element.direction.y(), end_tangent(e).y()))
                << i;
        }
        ASSERT_TRUE(same_bits(length_with_sweep(e, o.element.sweep), length(e))) << i;
    }
    EXPECT_GT(offset_arcs, 5000);
}

}  // namespace
}  // namespace rwmos::geom

namespace rwmos::geom {
namespace {

// classify_corner as it read every corner before it decided clear corners by the cross and dot
// product: from the angle alone.
CornerKind classify_by_angle(const Vec2& t1, const Vec2& t2, Side side, double r,
                             double shorter_length) {
    const double turn = turn_angle(t1, t2);
    if (offset_gap(turn, r) <= kPathTolerance) return CornerKind::kTangent;
    if ((turn > 0.0) != (side == Side::kLeft)) return CornerKind::kOutside;
    const double wedge = std::numbers::pi - std::abs(turn);
    if (wedge <= kMaxReversalWedgeAngle && shorter_length * std::sin(wedge) <= kReversalWedgeWidth)
        return CornerKind::kOutside;
    return CornerKind::kInside;
}

// A unit tangent as the compensator makes one: the direction of a (rounded) chord.
Vec2 tangent_of(Rng& rng, double angle) {
    const int decimals = rng.integer(2, 6);
    const double size = rng.log_uniform(1e-5, 100.0);
    Vec2 a(rng.uniform(-500, 500), rng.uniform(-500, 500));
    Vec2 b = a + size * dir(angle);
    if (decimals > 2) {
        a = round_to(a, decimals);
        b = round_to(b, decimals);
    }
    const Vec2 v = b - a;
    return v.norm() > 0.0 ? Vec2(v / v.norm()) : Vec2(1.0, 0.0);
}

TEST(CarriedValues, CornersAreClassifiedAsByTheirAngleAlone) {
    Rng rng(0x5eed'0003);
    int kinds[3] = {0, 0, 0};
    for (int i = 0; i < 200000; ++i) {
        const double heading = rng.uniform(-kPi, kPi);
        // Turns near every threshold: tangent (tiny turns), reversals (near pi), right angles
        // (d = 0), exact axes (components of +-0), and any turn.
        double turn = 0.0;
        switch (rng.integer(0, 4)) {
            case 0:
                turn = rng.sign() * rng.log_uniform(1e-13, 1e-2);
                break;
            case 1:
                turn = rng.sign() * (kPi - rng.log_uniform(1e-12, 0.1));
                break;
            case 2:
                turn = rng.sign() * (0.5 * kPi + rng.uniform(-1e-9, 1e-9));
                break;
            case 3:
                turn = rng.integer(-2, 2) * 0.5 * kPi;
                break;
            default:
                turn = rng.uniform(-kPi, kPi);
        }
        const bool exact = rng.chance(0.1);
        const Vec2 t1 = exact ? Vec2(1.0, 0.0) : tangent_of(rng, heading);
        const Vec2 t2 = exact ? Vec2(std::round(std::cos(turn)), std::round(std::sin(turn)))
                              : tangent_of(rng, heading + turn);
        const double r = rng.chance(0.05)  ? 0.0
                         : rng.chance(0.1) ? rng.log_uniform(1e-6, 1e-3)
                                           : rng.log_uniform(1e-3, 1e5);
        const double shorter = rng.log_uniform(1e-6, 1e3);
        const Side side = rng.chance(0.5) ? Side::kLeft : Side::kRight;
        const CornerKind kind = classify_corner(t1, t2, side, r, shorter);
        ASSERT_EQ(kind, classify_by_angle(t1, t2, side, r, shorter))
            << i << " turn " << turn << " r " << r;
        ++kinds[static_cast<int>(kind)];
    }
    EXPECT_GT(kinds[static_cast<int>(CornerKind::kTangent)], 20000);
    EXPECT_GT(kinds[static_cast<int>(CornerKind::kInside)], 20000);
    EXPECT_GT(kinds[static_cast<int>(CornerKind::kOutside)], 20000);
}

TEST(CarriedValues, ClassificationOfNearThresholdCornersIsTheAngles) {
    // Offset gaps within a hair of kPathTolerance, and wedges within a hair of
    // kMaxReversalWedgeAngle and kReversalWedgeWidth: the angle decides them, as before.
    Rng rng(0x5eed'0004);
    for (int i = 0; i < 100000; ++i) {
        const double r = rng.log_uniform(1e-4, 1e5);
        const double tangent_turn = 2 * std::asin(std::min(1.0, kPathTolerance / (2 * r)));
        const double turn = rng.chance(0.5)
                                ? tangent_turn * (1 + rng.uniform(-1e-6, 1e-6))
                                : kPi - kMaxReversalWedgeAngle * (1 + rng.uniform(-1e-6, 1e-6));
        const double s = rng.sign() * turn;
        const Vec2 t1 = dir(rng.uniform(-kPi, kPi));
        const Vec2 t2 = turned(t1, s);
        const double shorter = rng.chance(0.5)
                                   ? rng.log_uniform(1e-3, 1e3)
                                   : kReversalWedgeWidth / std::sin(kMaxReversalWedgeAngle) *
                                         (1 + rng.uniform(-1e-6, 1e-6));
        const Side side = rng.chance(0.5) ? Side::kLeft : Side::kRight;
        ASSERT_EQ(classify_corner(t1, t2, side, r, shorter),
                  classify_by_angle(t1, t2, side, r, shorter))
            << i;
    }
}

}  // namespace
}  // namespace rwmos::geom
