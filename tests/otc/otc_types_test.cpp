// SPDX-License-Identifier: MIT
// Processing types, modes, which control unit acts where ([ISG-OTC], FCT-C20, sections 2.1 and
// 2.7), and the error table.
#include <gtest/gtest.h>

#include "rwmos/otc/errors.h"
#include "rwmos/otc/types.h"

namespace rwmos::otc {
namespace {

TEST(OtcTypes, KeywordsAreTheIsgOtcNames) {
    EXPECT_EQ(processing_type_name(ProcessingType::kRadius), "RADIUS");
    EXPECT_EQ(processing_type_name(ProcessingType::kLength), "LENGTH");
    EXPECT_EQ(processing_type_name(ProcessingType::kToolDir), "TOOL_DIR");
    EXPECT_EQ(processing_type_name(ProcessingType::kSurfNormDir), "SURF_NORM_DIR");
    EXPECT_EQ(mode_name(Mode::kCont), "CONT");
    EXPECT_EQ(mode_name(Mode::kDisc), "DISC");
    EXPECT_EQ(mode_name(Mode::kAuto), "AUTO");
}

// [ISG-OTC] section 2.1: LENGTH "(Standard)", AUTO "(Standard)".
TEST(OtcTypes, DefaultsAreLengthAndAuto) {
    EXPECT_EQ(kDefaultProcessingType, ProcessingType::kLength);
    EXPECT_EQ(kDefaultMode, Mode::kAuto);
}

TEST(OtcTypes, IntegersOutsideTheEnumsAreRefused) {
    EXPECT_FALSE(processing_type_from_int(-1).has_value());
    EXPECT_FALSE(processing_type_from_int(4).has_value());
    EXPECT_EQ(processing_type_from_int(3), ProcessingType::kSurfNormDir);
    EXPECT_FALSE(mode_from_int(3).has_value());
    EXPECT_EQ(mode_from_int(1), Mode::kDisc);
}

TEST(OtcTypes, AutoIsTheSumOfContAndDisc) {
    EXPECT_TRUE(mode_has_continuous(Mode::kCont));
    EXPECT_FALSE(mode_has_discrete(Mode::kCont));
    EXPECT_FALSE(mode_has_continuous(Mode::kDisc));
    EXPECT_TRUE(mode_has_discrete(Mode::kDisc));
    EXPECT_TRUE(mode_has_continuous(Mode::kAuto));
    EXPECT_TRUE(mode_has_discrete(Mode::kAuto));
}

// [ISG-OTC] section 2.7.1: only RADIUS or TOOL_DIR, only DISC or AUTO.
TEST(OtcTypes, ChannelUnitActsOnlyInRadiusOrToolDirWithDiscOrAuto) {
    for (auto t : {ProcessingType::kRadius, ProcessingType::kLength, ProcessingType::kToolDir,
                   ProcessingType::kSurfNormDir})
        for (auto m : {Mode::kCont, Mode::kDisc, Mode::kAuto}) {
            const bool expected =
                (t == ProcessingType::kRadius || t == ProcessingType::kToolDir) && m != Mode::kCont;
            EXPECT_EQ(channel_unit_acts(t, m), expected)
                << processing_type_name(t) << " " << mode_name(m);
        }
}

// [ISG-OTC] section 2.7.2: RADIUS and LENGTH use every axis; in SURF_NORM_DIR (and TOOL_DIR,
// section 2.7.1) the third axis carries the offset along the direction, the first two are ignored;
// later axes act as usual; CONT uses no unit.
TEST(OtcTypes, AxisUnitRolesFollowIsgOtcSection272) {
    for (int ax = 0; ax < 4; ++ax) {
        EXPECT_EQ(axis_unit_role(ProcessingType::kRadius, Mode::kDisc, ax), AxisUnitRole::kAxis);
        EXPECT_EQ(axis_unit_role(ProcessingType::kLength, Mode::kAuto, ax), AxisUnitRole::kAxis);
        EXPECT_EQ(axis_unit_role(ProcessingType::kLength, Mode::kCont, ax), AxisUnitRole::kIgnored);
    }
    for (auto t : {ProcessingType::kToolDir, ProcessingType::kSurfNormDir}) {
        EXPECT_EQ(axis_unit_role(t, Mode::kDisc, 0), AxisUnitRole::kIgnored);
        EXPECT_EQ(axis_unit_role(t, Mode::kDisc, 1), AxisUnitRole::kIgnored);
        EXPECT_EQ(axis_unit_role(t, Mode::kDisc, 2), AxisUnitRole::kDirection);
        EXPECT_EQ(axis_unit_role(t, Mode::kAuto, 3), AxisUnitRole::kAxis);
        EXPECT_EQ(axis_unit_role(t, Mode::kCont, 2), AxisUnitRole::kIgnored);
    }
}

TEST(OtcErrors, IsgOtcErrorKeepsItsNumberAndName) {
    EXPECT_EQ(static_cast<int>(Error::kToolNotGrinding), 21391);
    EXPECT_EQ(error_name(Error::kToolNotGrinding), "P-ERR-21391");
    EXPECT_EQ(error_name(Error::kOffBeforeG40), "OTC_OFF_BEFORE_G40");
}

TEST(OtcErrors, EveryErrorHasADistinctNameAndAMessage) {
    const Error all[] = {Error::kToolNotGrinding, Error::kOffBeforeG40, Error::kChangeWhileActive,
                         Error::kToolChangeWhileActive, Error::kInfeedBeyondLimit};
    for (Error a : all) {
        EXPECT_EQ(error_info(a).error, a);
        EXPECT_FALSE(error_message(a).empty());
        for (Error b : all)
            if (a != b) {
                EXPECT_NE(error_name(a), error_name(b));
            }
    }
    EXPECT_EQ(error_info(static_cast<Error>(12345)).error, Error::kNone);
}

}  // namespace
}  // namespace rwmos::otc
