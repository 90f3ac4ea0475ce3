// SPDX-License-Identifier: MIT
// Property tests over random LN lines: for every tool shape (end mill, toroidal, ball), both
// FUNCTION PROG PATH settings and both reference points (tip, centre), 1,000 lines each with a
// random design surface point S, a random unit normal N, a random unit tool vector T (with
// N.T >= 0, one in ten parallel to N, one in ten perpendicular: peripheral milling), a random
// tool and random delta values: the compensated tool, as dimensioned by the deltas (radii
// R + DR, R2 + DR2, its tip DL below the commanded tip along T), touches S along N within
// 1e-9. Touching is checked independently of the library (touch_check.h). For PROG PATH OFF
// the programmed point is the CAM point of the tool table's tool, itself checked to touch S.
// Peripheral milling with RL/RR is covered by 1,000 further lines per shape with the normal
// from the motion. Fixed seeds: every run is the same.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "rng.h"
#include "rwmos/comp3d/compensation.h"
#include "rwmos/comp3d/vectors.h"
#include "touch_check.h"

namespace rwmos::comp3d {
namespace {

using V = Eigen::Vector3d;

constexpr double kPropertyTolerance = 1e-9;
constexpr int kLinesPerCase = 1000;

// The shared splitmix64 numbers, and directions.
class Rng : public apci::test::Rng {
  public:
    using apci::test::Rng::Rng;
    // Uniform on the unit sphere (rejection from the cube).
    V unit() {
        for (;;) {
            const V v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
            const double n = v.norm();
            if (n > 0.1 && n <= 1.0) return v / n;
        }
    }
};

struct Line {
    ToolDimensions tool;
    Deltas deltas;
    V s, n, t;
};

ToolDimensions random_tool(Rng& rng, ToolShape shape) {
    const double r = rng.uniform(0.5, 20.0);
    switch (shape) {
        case ToolShape::kEndMill:
            return {r, 0.0};
        case ToolShape::kToroidal:
            return {r, rng.uniform(0.05, 0.95) * r};
        case ToolShape::kBall:
            break;
    }
    return {r, r};
}

// Random deltas that leave an existing tool of the same shape (DR2 on an end mill only
// grows a corner radius, so it stays >= 0 there).
Deltas random_deltas(Rng& rng, const ToolDimensions& tool, ToolShape shape) {
    for (;;) {
        Deltas d{rng.uniform(-1.0, 1.0), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)};
        if (shape == ToolShape::kBall) d.dr2 = d.dr;
        if (shape == ToolShape::kEndMill) d.dr2 = rng.chance(0.5) ? 0.0 : std::abs(d.dr2);
        if (check_effective_tool(tool, d) == Refusal::kNone && tool.r + d.dr > 0.05) return d;
    }
}

V random_tool_vector(Rng& rng, const V& n) {
    const double pick = rng.uniform();
    if (pick < 0.1) return n;  // face milling perpendicular to the contour
    V t = rng.unit();
    if (pick < 0.2) return (t - t.dot(n) * n).normalized();  // peripheral: T perpendicular to N
    return t.dot(n) < 0.0 ? V(-t) : t;
}

std::string describe(const Line& l, const Settings& s) {
    std::ostringstream o;
    o.precision(17);
    o << "R " << l.tool.r << " R2 " << l.tool.r2 << " DL " << l.deltas.dl << " DR " << l.deltas.dr
      << " DR2 " << l.deltas.dr2 << " S " << l.s.transpose() << " N " << l.n.transpose() << " T "
      << l.t.transpose() << " path " << static_cast<int>(s.prog_path) << " ref "
      << static_cast<int>(s.reference);
    return o.str();
}

// The programmed point: the contour point, or the CAM point of the tool table's tool.
V programmed_point(const Line& l, const Settings& s) {
    if (s.prog_path == ProgPath::kContour) return l.s;
    const V cam_tip = tip_touching(l.s, l.n, l.t, l.tool);
    return s.reference == ReferencePoint::kCentre ? V(cam_tip + l.tool.r2 * l.t) : cam_tip;
}

// Checks one line; returns the worst deviation found.
double check_line(const Line& l, const Settings& s) {
    const V p = programmed_point(l, s);
    double worst = 0.0;
    if (s.prog_path == ProgPath::kOff) {
        const V cam_tip = s.reference == ReferencePoint::kCentre ? V(p - l.tool.r2 * l.t) : p;
        worst = test::touch(l.s, l.n, cam_tip, l.t, {l.tool.r, l.tool.r2}).worst();
    }
    const Compensated c = compensate(p, l.n, l.t, s);
    if (c.refusal != Refusal::kNone) return INFINITY;
    const ToolDimensions actual = effective_tool(l.tool, l.deltas);
    const V actual_tip = c.tip - l.deltas.dl * l.t;
    worst = std::max(worst, test::touch(l.s, l.n, actual_tip, l.t, {actual.r, actual.r2}).worst());
    worst = std::max(worst, (c.contact - l.s).norm());
    return worst;
}

struct Case {
    ToolShape shape;
    ProgPath path;
    ReferencePoint reference;
};

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
    static constexpr const char* kShape[] = {"EndMill", "Toroidal", "Ball"};
    const Case& k = info.param;
    return std::string(kShape[static_cast<int>(k.shape)]) +
           (k.path == ProgPath::kOff ? "ProgPathOff" : "ProgPathContour") +
           (k.reference == ReferencePoint::kTip ? "Tip" : "Centre");
}

class RandomLnLines : public ::testing::TestWithParam<Case> {};

TEST_P(RandomLnLines, CompensatedToolTouchesTheDesignSurfacePointAlongN) {
    const Case k = GetParam();
    Rng rng(0xC0FFEEULL + 97 * static_cast<std::uint64_t>(k.shape) +
            13 * static_cast<std::uint64_t>(k.path) + static_cast<std::uint64_t>(k.reference));
    int failures = 0;
    double worst = 0.0;
    for (int i = 0; i < kLinesPerCase; ++i) {
        Line l;
        l.tool = random_tool(rng, k.shape);
        l.deltas = random_deltas(rng, l.tool, k.shape);
        l.s = V(rng.uniform(-100, 100), rng.uniform(-100, 100), rng.uniform(-100, 100));
        l.n = rng.unit();
        l.t = random_tool_vector(rng, l.n);
        Settings s;
        s.tool = l.tool;
        s.deltas = l.deltas;
        s.prog_path = k.path;
        s.reference = k.reference;
        const double w = check_line(l, s);
        worst = std::max(worst, w);
        if (!(w <= kPropertyTolerance) && ++failures <= 3) {
            ADD_FAILURE() << "line " << i << " misses by " << w << ": " << describe(l, s);
        }
    }
    EXPECT_EQ(failures, 0);
    EXPECT_LE(worst, kPropertyTolerance);
}

INSTANTIATE_TEST_SUITE_P(
    EveryShapePathAndReference, RandomLnLines,
    ::testing::Values(Case{ToolShape::kEndMill, ProgPath::kOff, ReferencePoint::kTip},
                      Case{ToolShape::kEndMill, ProgPath::kOff, ReferencePoint::kCentre},
                      Case{ToolShape::kEndMill, ProgPath::kContour, ReferencePoint::kTip},
                      Case{ToolShape::kToroidal, ProgPath::kOff, ReferencePoint::kTip},
                      Case{ToolShape::kToroidal, ProgPath::kOff, ReferencePoint::kCentre},
                      Case{ToolShape::kToroidal, ProgPath::kContour, ReferencePoint::kTip},
                      Case{ToolShape::kBall, ProgPath::kOff, ReferencePoint::kTip},
                      Case{ToolShape::kBall, ProgPath::kOff, ReferencePoint::kCentre},
                      Case{ToolShape::kBall, ProgPath::kContour, ReferencePoint::kTip},
                      Case{ToolShape::kBall, ProgPath::kContour, ReferencePoint::kCentre}),
    case_name);

std::string shape_name(const ::testing::TestParamInfo<ToolShape>& info) {
    static constexpr const char* kShape[] = {"EndMill", "Toroidal", "Ball"};
    return kShape[static_cast<int>(info.param)];
}

class RandomPeripheralLines : public ::testing::TestWithParam<ToolShape> {};

TEST_P(RandomPeripheralLines, RlRrToolTouchesTheWallAcrossMotionAndToolVector) {
    const ToolShape shape = GetParam();
    Rng rng(0xBADC0DEULL + static_cast<std::uint64_t>(shape));
    int failures = 0;
    int checked = 0;
    while (checked < kLinesPerCase) {
        Line l;
        l.tool = random_tool(rng, shape);
        l.deltas = random_deltas(rng, l.tool, shape);
        l.s = V(rng.uniform(-100, 100), rng.uniform(-100, 100), rng.uniform(-100, 100));
        l.t = rng.unit();
        const V motion = rng.uniform(0.01, 50.0) * rng.unit();
        const Side side = rng.chance(0.5) ? Side::kLeft : Side::kRight;
        const SideNormal sn = side_normal(motion, l.t, side);
        if (sn.refusal != Refusal::kNone) continue;  // a plunge: no side (tested elsewhere)
        ++checked;
        l.n = sn.n;
        Settings s;
        s.tool = l.tool;
        s.deltas = l.deltas;
        s.prog_path = rng.chance(0.5) ? ProgPath::kOff : ProgPath::kContour;
        const double w = check_line(l, s);
        const bool across =
            std::abs(l.n.dot(motion)) <= 1e-12 * motion.norm() && std::abs(l.n.dot(l.t)) <= 1e-12;
        if ((!(w <= kPropertyTolerance) || !across) && ++failures <= 3) {
            ADD_FAILURE() << "line " << checked << " misses by " << w << ": " << describe(l, s);
        }
    }
    EXPECT_EQ(failures, 0);
}

INSTANTIATE_TEST_SUITE_P(EveryShape, RandomPeripheralLines,
                         ::testing::Values(ToolShape::kEndMill, ToolShape::kToroidal,
                                           ToolShape::kBall),
                         shape_name);

}  // namespace
}  // namespace rwmos::comp3d
