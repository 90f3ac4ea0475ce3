// SPDX-License-Identifier: MIT
// Values the compensation measures once and carries instead of measuring again must be the
// values it measured before, bit for bit: the offset arc's sweep is the programmed arc's
// sweep(), and the length from it (length_with_sweep) is length(). Random elements: coordinates
// rounded to 3 to 6 decimals (radii that differ by the rounding), tangent joins, tiny elements,
// full circles, both senses.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

#include "contours.h"
#include "rwmos/geometry/compensator.h"
#include "rwmos/geometry/offset.h"

namespace rwmos::geom {
namespace {

using apci::test::arc_from;
using apci::test::Rng;
using apci::test::round_to;

bool same_bits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// A random element from `start`: a line or an arc of any sweep up to a full circle, from 1 um
// to 100 mm, its coordinates rounded to `decimals` (3 to 6) or not at all (0).
Element random_element(Rng& rng, const Vec2& start, double heading, int decimals) {
    const double size = rng.log_uniform(1e-6, 100.0);
    Element e;
    if (rng.chance(0.3)) {
        e = make_line(start, start + size * apci::test::dir(heading));
    } else {
        const double turn = rng.sign() * (rng.chance(0.1) ? 2 * apci::test::kPi
                                                          : rng.uniform(1e-6, 2 * apci::test::kPi));
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
                                         rng.uniform(-apci::test::kPi, apci::test::kPi),
                                         decimals == 2 ? 0 : decimals);
        if (check_element(e) != Reason::kNone) continue;
        arcs += is_arc(e) ? 1 : 0;
        ASSERT_TRUE(same_bits(length_with_sweep(e, sweep(e)), length(e))) << i;
    }
    EXPECT_GT(arcs, 10000);
}

TEST(CarriedValues, AnOffsetArcCarriesTheProgrammedSweepSoItsLengthIsTheProgrammedOne) {
    // PathCompensator::push measures the programmed length from the offset element's sweep.
    Rng rng(0x5eed'0002);
    int offset_arcs = 0;
    for (int i = 0; i < 20000; ++i) {
        const int decimals = rng.integer(2, 6);
        const Element e = random_element(rng, {rng.uniform(-500, 500), rng.uniform(-500, 500)},
                                         rng.uniform(-apci::test::kPi, apci::test::kPi),
                                         decimals == 2 ? 0 : decimals);
        if (check_element(e) != Reason::kNone || is_plane_free(e)) continue;
        const double r = rng.chance(0.2) ? 0.0 : rng.log_uniform(1e-3, 50.0);
        const OffsetResult o = offset_element(e, r, rng.chance(0.5) ? Side::kLeft : Side::kRight);
        if (o.reason != Reason::kNone) continue;
        if (is_arc(e)) {
            ++offset_arcs;
            ASSERT_TRUE(same_bits(o.element.sweep, sweep(e))) << i;
        }
        ASSERT_TRUE(same_bits(length_with_sweep(e, o.element.sweep), length(e))) << i;
    }
    EXPECT_GT(offset_arcs, 5000);
}

}  // namespace
}  // namespace rwmos::geom
