// SPDX-License-Identifier: MIT
// loop_marker (parser.h): how a $FOR whose condition fails at once is skipped to its $ENDFOR
// without the body being parsed; and the names of #OTC's settings (block.h) that its messages
// give. One test per rule, named after it.
#include <gtest/gtest.h>

#include "apci/nc/block.h"
#include "apci/nc/parser.h"

namespace apci::nc {
namespace {

TEST(LoopMarker, ForAndEndForAreMarked) {
    EXPECT_EQ(loop_marker("$FOR P1 = 0, 10, 1"), LoopMarker::kFor);
    EXPECT_EQ(loop_marker("$ENDFOR"), LoopMarker::kEndFor);
}

TEST(LoopMarker, AfterBlanksAndABlockNumber) {
    EXPECT_EQ(loop_marker("  N20 $ENDFOR"), LoopMarker::kEndFor);
    EXPECT_EQ(loop_marker("\tN5\t$FOR P2 = 1, 2, 1"), LoopMarker::kFor);
    EXPECT_EQ(loop_marker("N7$ENDFOR"), LoopMarker::kEndFor);
}

TEST(LoopMarker, InAnyCase) {
    EXPECT_EQ(loop_marker("n5 $for P2 = 1, 2, 1"), LoopMarker::kFor);
    EXPECT_EQ(loop_marker("$EndFor"), LoopMarker::kEndFor);
}

TEST(LoopMarker, AnythingElseIsNone) {
    EXPECT_EQ(loop_marker(""), LoopMarker::kNone);
    EXPECT_EQ(loop_marker("   "), LoopMarker::kNone);
    EXPECT_EQ(loop_marker("G1 X10"), LoopMarker::kNone);
    EXPECT_EQ(loop_marker("#OTC ON"), LoopMarker::kNone);
    EXPECT_EQ(loop_marker("$FORX P1 = 0, 1, 1"), LoopMarker::kNone);  // another name
    EXPECT_EQ(loop_marker("$ENDFO"), LoopMarker::kNone);
    EXPECT_EQ(loop_marker("$"), LoopMarker::kNone);
}

TEST(LoopMarker, OnlyAtTheStartOfTheBlock) {
    EXPECT_EQ(loop_marker("G1 $FOR"), LoopMarker::kNone);
    EXPECT_EQ(loop_marker("N $FOR P1 = 0, 1, 1"), LoopMarker::kNone);  // N without a number
    EXPECT_EQ(loop_marker("N10 G1 $ENDFOR"), LoopMarker::kNone);
}

TEST(OtcSettingNames, AreTheKeywordsOfTheCommand) {
    EXPECT_EQ(otc_type_name(OtcType::kRadius), "RADIUS");
    EXPECT_EQ(otc_type_name(OtcType::kLength), "LENGTH");
    EXPECT_EQ(otc_type_name(OtcType::kToolDir), "TOOL_DIR");
    EXPECT_EQ(otc_type_name(OtcType::kSurfNormDir), "SURF_NORM_DIR");
    EXPECT_EQ(otc_mode_name(OtcMode::kCont), "CONT");
    EXPECT_EQ(otc_mode_name(OtcMode::kDisc), "DISC");
    EXPECT_EQ(otc_mode_name(OtcMode::kAuto), "AUTO");
}

TEST(OtcSettingNames, AValueOutsideTheEnumIsAQuestionMark) {
    EXPECT_EQ(otc_type_name(static_cast<OtcType>(9)), "?");
    EXPECT_EQ(otc_mode_name(static_cast<OtcMode>(9)), "?");
}

}  // namespace
}  // namespace apci::nc
