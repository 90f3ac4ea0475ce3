// SPDX-License-Identifier: MIT
// Tool shapes, delta sums, the effective tool and the oversize rule ([TNC-3D], "Werkzeuge für
// die 3D-Werkzeugkorrektur" and M107).
#include "rwmos/comp3d/tool.h"

#include <gtest/gtest.h>

#include <limits>
#include <set>
#include <string>

#include "rwmos/comp3d/tolerances.h"

namespace rwmos::comp3d {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(ToolShape, EndMillHasR2Zero) {
    EXPECT_EQ(tool_shape({6.0, 0.0}), ToolShape::kEndMill);
    EXPECT_EQ(tool_shape({6.0, 0.5 * kShapeTolerance}), ToolShape::kEndMill);
}

TEST(ToolShape, ToroidalHasR2BetweenZeroAndR) {
    EXPECT_EQ(tool_shape({6.0, 1.0}), ToolShape::kToroidal);
    EXPECT_EQ(tool_shape({6.0, 1e-6}), ToolShape::kToroidal);
    EXPECT_EQ(tool_shape({6.0, 6.0 - 1e-6}), ToolShape::kToroidal);
}

TEST(ToolShape, BallHasR2EqualR) {
    EXPECT_EQ(tool_shape({3.0, 3.0}), ToolShape::kBall);
    EXPECT_EQ(tool_shape({3.0, 3.0 - 0.5 * kShapeTolerance}), ToolShape::kBall);
}

TEST(ToolShape, ZeroSizeToolIsAnEndMill) {
    EXPECT_EQ(tool_shape({0.0, 0.0}), ToolShape::kEndMill);
}

TEST(CheckTool, AcceptsEveryShape) {
    EXPECT_EQ(check_tool({6.0, 0.0}), Refusal::kNone);
    EXPECT_EQ(check_tool({6.0, 2.0}), Refusal::kNone);
    EXPECT_EQ(check_tool({3.0, 3.0}), Refusal::kNone);
    EXPECT_EQ(check_tool({0.0, 0.0}), Refusal::kNone);
}

TEST(CheckTool, RefusesNegativeOrNonFiniteDimensions) {
    EXPECT_EQ(check_tool({-1.0, 0.0}), Refusal::kInvalidToolDimension);
    EXPECT_EQ(check_tool({1.0, -0.1}), Refusal::kInvalidToolDimension);
    EXPECT_EQ(check_tool({kNaN, 0.0}), Refusal::kInvalidToolDimension);
    EXPECT_EQ(check_tool({1.0, kInf}), Refusal::kInvalidToolDimension);
    EXPECT_EQ(check_tool({2 * kMaxCoordinate, 0.0}), Refusal::kInvalidToolDimension);
}

TEST(CheckTool, RefusesCornerRadiusLargerThanRadius) {
    EXPECT_EQ(check_tool({3.0, 3.0 + 1e-6}), Refusal::kCornerRadiusExceedsRadius);
    EXPECT_EQ(check_tool({3.0, 3.0 + 0.5 * kShapeTolerance}), Refusal::kNone);
}

TEST(Deltas, SumOfToolTableToolCallAndCorrectionTable) {
    DeltaSources s;
    s.tool_table = {0.0, -0.1, -0.1};
    s.tool_call = {0.2, 0.2, 0.2};
    s.correction_table = {-0.05, 0.01, 0.0};
    const Deltas sum = sum_deltas(s);
    EXPECT_DOUBLE_EQ(sum.dl, 0.15);
    EXPECT_DOUBLE_EQ(sum.dr, 0.11);
    EXPECT_DOUBLE_EQ(sum.dr2, 0.1);
}

TEST(Deltas, CheckRefusesNonFiniteAndHugeDeltas) {
    EXPECT_EQ(check_deltas({0.0, -0.1, 0.2}), Refusal::kNone);
    EXPECT_EQ(check_deltas({kNaN, 0.0, 0.0}), Refusal::kInvalidDelta);
    EXPECT_EQ(check_deltas({0.0, -kInf, 0.0}), Refusal::kInvalidDelta);
    EXPECT_EQ(check_deltas({0.0, 0.0, 2 * kMaxCoordinate}), Refusal::kInvalidDelta);
}

TEST(EffectiveTool, IsRPlusDrAndR2PlusDr2) {
    const ToolDimensions e = effective_tool({3.0, 3.0}, {0.0, -0.1, -0.1});
    EXPECT_DOUBLE_EQ(e.r, 2.9);
    EXPECT_DOUBLE_EQ(e.r2, 2.9);
}

TEST(EffectiveTool, MustNotBeNegative) {
    EXPECT_EQ(check_effective_tool({1.0, 0.5}, {0.0, -1.5, 0.0}),
              Refusal::kEffectiveRadiusNegative);
    EXPECT_EQ(check_effective_tool({1.0, 0.5}, {0.0, 0.0, -0.6}),
              Refusal::kEffectiveRadiusNegative);
    EXPECT_EQ(check_effective_tool({1.0, 0.5}, {0.0, -1.0, -0.5}), Refusal::kNone);
}

TEST(EffectiveTool, CornerMustNotExceedRadius) {
    // A ball mill reground on its radius but not on its corner radius is no tool.
    EXPECT_EQ(check_effective_tool({3.0, 3.0}, {0.0, -0.1, 0.0}),
              Refusal::kEffectiveCornerExceedsRadius);
    EXPECT_EQ(check_effective_tool({3.0, 3.0}, {0.0, -0.1, -0.1}), Refusal::kNone);
}

TEST(Oversize, PositiveSummedDeltaIsAnErrorWithoutM107) {
    EXPECT_EQ(check_oversize({0.2, 0.0, 0.0}, false), Refusal::kPositiveOversize);
    EXPECT_EQ(check_oversize({0.0, 0.2, 0.0}, false), Refusal::kPositiveOversize);
    EXPECT_EQ(check_oversize({0.0, 0.0, 0.2}, false), Refusal::kPositiveOversize);
}

TEST(Oversize, M107AllowsPositiveDeltas) {
    EXPECT_EQ(check_oversize({0.2, 0.2, 0.2}, true), Refusal::kNone);
}

TEST(Oversize, NegativeAndZeroDeltasAreNoOversize) {
    EXPECT_EQ(check_oversize({0.0, -0.1, -0.1}, false), Refusal::kNone);
    EXPECT_EQ(check_oversize({0.0, 0.0, 0.0}, false), Refusal::kNone);
    // Rounding of summed decimal values is no oversize.
    EXPECT_EQ(check_oversize(Deltas{0.0, 0.1, 0.0} + Deltas{0.0, 0.2, 0.0} + Deltas{0.0, -0.3, 0.0},
                             false),
              Refusal::kNone);
}

TEST(Oversize, TheSumDecidesNotEachSource) {
    // Reground by 0.1, called with 0.05 allowance: still smaller than the table tool.
    DeltaSources s;
    s.tool_table = {0.0, -0.1, -0.1};
    s.tool_call = {0.0, 0.05, 0.05};
    EXPECT_EQ(check_oversize(sum_deltas(s), false), Refusal::kNone);
}

TEST(ToolLoad, ChecksTableToolThenDeltasThenEffectiveToolThenOversize) {
    EXPECT_EQ(check_tool_load({3.0, 4.0}, {kNaN, 0.0, 0.0}, false),
              Refusal::kCornerRadiusExceedsRadius);
    EXPECT_EQ(check_tool_load({3.0, 3.0}, {kNaN, 0.0, 0.0}, false), Refusal::kInvalidDelta);
    EXPECT_EQ(check_tool_load({3.0, 3.0}, {0.1, -0.1, 0.0}, false),
              Refusal::kEffectiveCornerExceedsRadius);
    EXPECT_EQ(check_tool_load({3.0, 3.0}, {0.2, 0.2, 0.2}, false), Refusal::kPositiveOversize);
    EXPECT_EQ(check_tool_load({3.0, 3.0}, {0.2, 0.2, 0.2}, true), Refusal::kNone);
}

TEST(RefusalTable, EveryRefusalHasAUniqueNameAndAMessage) {
    std::set<std::string> names;
    for (std::size_t i = 0; i < kRefusalCount; ++i) {
        const auto r = static_cast<Refusal>(i);
        EXPECT_NE(refusal_name(r), "Unknown");
        EXPECT_FALSE(refusal_message(r).empty());
        names.insert(std::string(refusal_name(r)));
    }
    EXPECT_EQ(names.size(), kRefusalCount);
    EXPECT_EQ(refusal_name(static_cast<Refusal>(kRefusalCount)), "Unknown");
    EXPECT_EQ(refusal_name(Refusal::kPositiveOversize), "PositiveOversize");
}

}  // namespace
}  // namespace rwmos::comp3d
