// SPDX-License-Identifier: MIT
// Units and wear accrual of the online tool compensation ([ISG-OTC], FCT-C20, sections 2.1, 2.6,
// 3.2; rwmos/otc/units.h).
#include <gtest/gtest.h>

#include "rwmos/otc/units.h"

namespace rwmos::otc {
namespace {

// [ISG-OTC] section 2.6 tool data: grinding_wear_const 100000 (0.1 um/m); section 2.3 example
// G1 X1000: 1000 mm of path.
TEST(OtcUnits, IsgOtcLengthExampleWearsTenMillimetresOverOneMetre) {
    EXPECT_NEAR(continuous_wear(1000.0, 100000.0), 10.0, 1e-12);
    EXPECT_NEAR(continuous_wear(500.0, 100000.0), 5.0, 1e-12);
}

TEST(OtcUnits, WearIsLinearInPathLength) {
    for (double len : {0.0, 0.25, 1.0, 17.5, 1234.5})
        EXPECT_NEAR(continuous_wear(len, 2500.0), len * 2500.0 * 1e-7, 1e-15) << len;
    EXPECT_EQ(continuous_wear(0.0, 100000.0), 0.0);
}

// [ISG-OTC] section 2.6: "wird grinding_wear_const nicht gesetzt, kann der kontinuierliche
// Versatz abhängig vom Weg nicht ermittelt werden": the default 0 accrues nothing.
TEST(OtcUnits, WithoutWearConstNoContinuousWearAccrues) {
    EXPECT_EQ(continuous_wear(1000.0, 0.0), 0.0);
}

TEST(OtcUnits, WearConstIsTenthMicrometrePerMetre) {
    // 1 unit = 0.1 um per 1 m = 1e-7.
    EXPECT_DOUBLE_EQ(wear_ratio(1.0), 1e-7);
    // 10 um per m: 100 units; over 1 m (1000 mm) that is 0.01 mm.
    EXPECT_NEAR(continuous_wear(1000.0, 100.0), 0.01, 1e-15);
}

TEST(OtcUnits, ControlUnitValuesAreTenthMicrometre) {
    EXPECT_DOUBLE_EQ(tenth_um_to_length(20000.0, LengthUnit::kMillimetre), 2.0);
    EXPECT_DOUBLE_EQ(tenth_um_to_length(20000.0, LengthUnit::kMicrometre), 2000.0);
    EXPECT_NEAR(tenth_um_to_length(254000.0, LengthUnit::kInch), 1.0, 1e-15);
    EXPECT_NEAR(length_to_tenth_um(2.0, LengthUnit::kMillimetre), 20000.0, 1e-9);
    EXPECT_NEAR(
        length_to_tenth_um(tenth_um_to_length(-12345.0, LengthUnit::kInch), LengthUnit::kInch),
        -12345.0, 1e-9);
}

TEST(OtcUnits, TiltAngleIsTenThousandthDegreeWithinFortyFiveDegrees) {
    EXPECT_DOUBLE_EQ(tilt_to_degrees(300000.0), 30.0);
    EXPECT_TRUE(tilt_in_range(450000.0));
    EXPECT_TRUE(tilt_in_range(-450000.0));
    EXPECT_TRUE(tilt_in_range(0.0));
    EXPECT_FALSE(tilt_in_range(450001.0));
    EXPECT_FALSE(tilt_in_range(-450001.0));
}

}  // namespace
}  // namespace rwmos::otc
