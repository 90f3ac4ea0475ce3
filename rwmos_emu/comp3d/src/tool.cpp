// SPDX-License-Identifier: MIT
#include "rwmos/comp3d/tool.h"

#include <cmath>

#include "rwmos/comp3d/tolerances.h"

namespace rwmos::comp3d {
namespace {

bool bounded(double v) noexcept {
    return std::isfinite(v) && std::abs(v) <= kMaxCoordinate;
}

}  // namespace

Refusal check_tool(const ToolDimensions& tool) noexcept {
    if (!bounded(tool.r) || !bounded(tool.r2) || tool.r < 0.0 || tool.r2 < 0.0) {
        return Refusal::kInvalidToolDimension;
    }
    if (tool.r2 > tool.r + kShapeTolerance) return Refusal::kCornerRadiusExceedsRadius;
    return Refusal::kNone;
}

ToolShape tool_shape(const ToolDimensions& tool) noexcept {
    if (tool.r2 <= kShapeTolerance) return ToolShape::kEndMill;
    if (tool.r2 >= tool.r - kShapeTolerance) return ToolShape::kBall;
    return ToolShape::kToroidal;
}

Refusal check_deltas(const Deltas& d) noexcept {
    if (!bounded(d.dl) || !bounded(d.dr) || !bounded(d.dr2)) return Refusal::kInvalidDelta;
    return Refusal::kNone;
}

Refusal check_effective_tool(const ToolDimensions& tool, const Deltas& d) noexcept {
    const ToolDimensions e = effective_tool(tool, d);
    if (e.r < -kShapeTolerance || e.r2 < -kShapeTolerance) {
        return Refusal::kEffectiveRadiusNegative;
    }
    if (e.r2 > e.r + kShapeTolerance) return Refusal::kEffectiveCornerExceedsRadius;
    return Refusal::kNone;
}

bool has_positive_oversize(const Deltas& sum) noexcept {
    return sum.dl > kOversizeTolerance || sum.dr > kOversizeTolerance ||
           sum.dr2 > kOversizeTolerance;
}

Refusal check_oversize(const Deltas& sum, bool m107_active) noexcept {
    return has_positive_oversize(sum) && !m107_active ? Refusal::kPositiveOversize : Refusal::kNone;
}

Refusal check_tool_load(const ToolDimensions& tool, const Deltas& sum, bool m107_active) noexcept {
    if (const Refusal r = check_tool(tool); r != Refusal::kNone) return r;
    if (const Refusal r = check_deltas(sum); r != Refusal::kNone) return r;
    if (const Refusal r = check_effective_tool(tool, sum); r != Refusal::kNone) return r;
    return check_oversize(sum, m107_active);
}

}  // namespace rwmos::comp3d
