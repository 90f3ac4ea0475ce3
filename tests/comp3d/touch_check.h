// SPDX-License-Identifier: MIT
// An independent check that a tool touches a surface point along its normal, for the tests of
// rwmos_comp3d. It does not use the library's corner direction: the lower end of a tool is the
// disc of radius R - R2 (centre on the axis at height R2 above the tip, perpendicular to the
// axis) grown by R2 in every direction, so
//   - a point lies on the tool's surface when its distance to that disc is R2, and
//   - the tool's lowest extent along a unit direction n is n.c - (R - R2) |n across T| - R2,
// and the tool touches S along N when S lies on its surface and the plane through S
// perpendicular to N supports it (no point of the tool lies below it).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace rwmos::comp3d::test {

struct Tool {
    double r = 0.0;
    double r2 = 0.0;
};

inline Eigen::Vector3d disc_centre(const Eigen::Vector3d& tip, const Eigen::Vector3d& t,
                                   const Tool& tool) {
    return tip + tool.r2 * t;
}

inline double distance_to_disc(const Eigen::Vector3d& p, const Eigen::Vector3d& centre,
                               const Eigen::Vector3d& t, double radius) {
    const Eigen::Vector3d q = p - centre;
    const double along = q.dot(t);
    const double across = (q - along * t).norm();
    if (across <= radius) return std::abs(along);
    return std::hypot(along, across - radius);
}

// min over the tool's lower end of n.x.
inline double lowest_extent(const Eigen::Vector3d& tip, const Eigen::Vector3d& t, const Tool& tool,
                            const Eigen::Vector3d& n) {
    const Eigen::Vector3d c = disc_centre(tip, t, tool);
    const double across = (n - n.dot(t) * t).norm();
    return n.dot(c) - (tool.r - tool.r2) * across - tool.r2;
}

struct Touch {
    double surface_gap = 0.0;  // distance of S from the tool's surface
    double support_gap = 0.0;  // n.S minus the tool's lowest extent along n
    double worst() const { return std::max(std::abs(surface_gap), std::abs(support_gap)); }
};

// How far the tool (tip, axis t) is from touching s along n.
inline Touch touch(const Eigen::Vector3d& s, const Eigen::Vector3d& n, const Eigen::Vector3d& tip,
                   const Eigen::Vector3d& t, const Tool& tool) {
    Touch out;
    out.surface_gap = distance_to_disc(s, disc_centre(tip, t, tool), t, tool.r - tool.r2) - tool.r2;
    out.support_gap = n.dot(s) - lowest_extent(tip, t, tool, n);
    return out;
}

}  // namespace rwmos::comp3d::test
