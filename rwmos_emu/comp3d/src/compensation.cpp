// SPDX-License-Identifier: MIT
#include "rwmos/comp3d/compensation.h"

#include <cmath>

#include "rwmos/comp3d/tolerances.h"
#include "rwmos/comp3d/vectors.h"

namespace rwmos::comp3d {

Eigen::Vector3d tip_touching(const Eigen::Vector3d& s, const Eigen::Vector3d& n,
                             const Eigen::Vector3d& t, const ToolDimensions& d) noexcept {
    return s + d.r2 * n - d.r2 * t - (d.r - d.r2) * corner_direction(n, t);
}

Eigen::Vector3d contact_point(const Eigen::Vector3d& tip, const Eigen::Vector3d& n,
                              const Eigen::Vector3d& t, const ToolDimensions& d) noexcept {
    return corner_centre(tip, n, t, d) - d.r2 * n;
}

Eigen::Vector3d corner_centre(const Eigen::Vector3d& tip, const Eigen::Vector3d& n,
                              const Eigen::Vector3d& t, const ToolDimensions& d) noexcept {
    return tip + d.r2 * t + (d.r - d.r2) * corner_direction(n, t);
}

namespace {

bool valid_point(const Eigen::Vector3d& p) noexcept {
    return p.allFinite() && p.cwiseAbs().maxCoeff() <= kMaxCoordinate;
}

Refusal check_settings(const Settings& s) noexcept {
    if (const Refusal r = check_tool(s.tool); r != Refusal::kNone) return r;
    if (const Refusal r = check_deltas(s.deltas); r != Refusal::kNone) return r;
    return check_effective_tool(s.tool, s.deltas);
}

// Step 1: the design surface point behind the programmed point.
Eigen::Vector3d design_contact(const Eigen::Vector3d& programmed, const Eigen::Vector3d& n,
                               const Eigen::Vector3d& t, const Settings& s) noexcept {
    if (s.prog_path == ProgPath::kContour) return programmed;
    const Eigen::Vector3d tip = s.reference == ReferencePoint::kCentre
                                    ? Eigen::Vector3d(programmed - s.tool.r2 * t)
                                    : programmed;
    return contact_point(tip, n, t, s.tool);
}

}  // namespace

Compensated compensate(const Eigen::Vector3d& programmed, const Eigen::Vector3d& n,
                       const Eigen::Vector3d& t, const Settings& s) noexcept {
    Compensated out;
    if (!valid_point(programmed)) {
        out.refusal = Refusal::kInvalidCoordinate;
        return out;
    }
    const UnitVector un = normalised(n);
    const UnitVector ut = normalised(t);
    if (un.refusal != Refusal::kNone || ut.refusal != Refusal::kNone) {
        out.refusal = Refusal::kVectorNotNormalised;
        return out;
    }
    if (const Refusal r = check_settings(s); r != Refusal::kNone) {
        out.refusal = r;
        return out;
    }
    if (un.v.dot(ut.v) < -kNormalAgainstToolTolerance) {
        out.refusal = Refusal::kNormalAgainstTool;
        return out;
    }
    out.contact = design_contact(programmed, un.v, ut.v, s);
    const ToolDimensions actual = effective_tool(s.tool, s.deltas);
    out.tip = tip_touching(out.contact, un.v, ut.v, actual) + s.deltas.dl * ut.v;
    return out;
}

}  // namespace rwmos::comp3d
