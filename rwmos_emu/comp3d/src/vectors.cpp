// SPDX-License-Identifier: MIT
#include "rwmos/comp3d/vectors.h"

#include <Eigen/Geometry>
#include <cmath>

#include "rwmos/comp3d/tolerances.h"

namespace rwmos::comp3d {

UnitVector normalised(const Eigen::Vector3d& programmed) noexcept {
    if (!programmed.allFinite()) return {Refusal::kVectorNotNormalised, Eigen::Vector3d::Zero()};
    const double length = programmed.norm();
    if (std::abs(length - 1.0) > kUnitVectorTolerance) {
        return {Refusal::kVectorNotNormalised, Eigen::Vector3d::Zero()};
    }
    return {Refusal::kNone, programmed / length};
}

Eigen::Vector3d effective_tool_vector(bool tcpm, const std::optional<Eigen::Vector3d>& programmed_t,
                                      const std::optional<Eigen::Vector3d>& normal,
                                      const Eigen::Vector3d& machine_axis) noexcept {
    if (!tcpm) return machine_axis;
    if (programmed_t) return *programmed_t;
    if (normal) return *normal;
    return machine_axis;
}

Eigen::Vector3d corner_direction(const Eigen::Vector3d& n, const Eigen::Vector3d& t) noexcept {
    const Eigen::Vector3d across = -(n - n.dot(t) * t);
    const double length = across.norm();
    if (length <= kParallelTolerance) return Eigen::Vector3d::Zero();
    return across / length;
}

SideNormal side_normal(const Eigen::Vector3d& motion, const Eigen::Vector3d& t,
                       Side side) noexcept {
    const double length = motion.norm();
    if (!(length > kMinMotionLength)) return {Refusal::kNoSideFromMotion, Eigen::Vector3d::Zero()};
    const Eigen::Vector3d left = t.cross(motion / length);
    const double across = left.norm();
    if (across <= kPlungeAngleTolerance)
        return {Refusal::kNoSideFromMotion, Eigen::Vector3d::Zero()};
    const Eigen::Vector3d n = left / across;
    return {Refusal::kNone, side == Side::kLeft ? n : Eigen::Vector3d(-n)};
}

SideNormal previous_side_normal(const Eigen::Vector3d& previous,
                                const Eigen::Vector3d& t) noexcept {
    const Eigen::Vector3d across = previous - previous.dot(t) * t;
    const double length = across.norm();
    if (!(length > kPlungeAngleTolerance)) {
        return {Refusal::kNoSideFromMotion, Eigen::Vector3d::Zero()};
    }
    return {Refusal::kNone, across / length};
}

}  // namespace rwmos::comp3d
