// SPDX-License-Identifier: MIT
// The OTC offsets inside the interpolation, cycle by cycle, on the examples of [ISG-OTC] (ISG
// FCT-C20, sections 2.2 to 2.5; [ISG-OTC-EN] for wr_quad_disc.nc). docs/otc.md states the model.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "otc_fixture.h"
#include "rwmos/geometry/kinematics.h"
#include "rwmos/otc/direction.h"

namespace otc_test {
namespace {

constexpr double kEps = 1e-9;
constexpr std::int32_t kB = 4;  // board axis of B (OTC ToolAxisB default)

Profile rapid_to(std::uint32_t tag, const AxisVector& target, rwmos::motion::AxisMask axes) {
    Profile p;
    p.kind = ProfileKind::kRapid;
    p.tag = tag;
    p.axes = axes;
    p.target = target;
    return p;
}

Profile line_to(std::uint32_t tag, const AxisVector& target, double feed,
                rwmos::motion::AxisMask axes = 0x07) {
    Profile p;
    p.kind = ProfileKind::kLine;
    p.tag = tag;
    p.feed = feed;
    p.axes = axes;
    p.target = target;
    return p;
}

// ---- LENGTH ([ISG-OTC] section 2.3, "Verschleiß in Werkzeuglänge")

// N40 G00 X0 Y0 Z0 / N50 #OTC ON [LENGTH] / N60 G1 X1000 F10000 / N70 #OTC OFF, with the tool
// data of section 2.6 (grinding_wear_const 100000 x 0.1 um/m).
TEST_F(OtcBoard, IsgOtcLengthExampleWearsTenMillimetresLinearlyOnTheThirdAxis) {
    grinding_tool();
    ASSERT_EQ(otc_on(), Status::kOk);
    ASSERT_EQ(board.set_trace(true, 1 << 14), Status::kOk);
    spool_ok(line(60, 1000.0, 0.0, 10000.0));
    run();
    std::vector<rwmos::motion::TraceSample> samples(board.motion_status().trace_pending);
    samples.resize(board.read_trace(samples));
    ASSERT_EQ(samples.size(), 6000u);  // 1000 mm at 10000 mm/min, 1 ms cycles
    bool saw_half = false;
    for (const auto& s : samples) {
        EXPECT_NEAR(s.position[2], -0.01 * s.position[0], kEps) << "cycle " << s.cycle;
        EXPECT_EQ(s.position[1], 0.0);
        if (s.position[0] == 500.0) {
            saw_half = true;
            EXPECT_NEAR(s.position[2], -5.0, kEps);
        }
    }
    EXPECT_TRUE(saw_half);
    EXPECT_EQ(position()[0], 1000.0);
    EXPECT_NEAR(position()[2], -10.0, kEps);
    run_and_off();
    EXPECT_NEAR(wear(2), 10.0, kEps);
    EXPECT_EQ(wear(0), 0.0);
    EXPECT_EQ(wear(1), 0.0);
    // Folded into the tool's length ([ISG-OTC] section 2.1 "Hinweis").
    for (const auto& g : board.state().tc.groups) EXPECT_NEAR(g.tools[kTool].length, 40.0, kEps);
}

// PU (bus 1000 index 5) is the unit of the TC tool values only (docs/object-map.md section 2):
// under PU 1 (um) the axes and the wear variables are mm as before, and the 10 mm fold into the
// TC tool's length, which is kept in um, is 10000 um.
TEST_F(OtcBoard, UnderPuMicrometreTheWearIsMmAndFoldsIntoTheToolInMicrometres) {
    ASSERT_EQ(write_int(rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxPu, 0,
                        rwmos::board::kPuMicrometre),
              Status::kOk);
    grinding_tool();
    const double before = board.state().tc.group(1).tools[kTool].length;
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(60, 1000.0, 0.0, 10000.0));
    run();
    EXPECT_NEAR(position()[2], -10.0, kEps);
    run_and_off();
    EXPECT_NEAR(wear(2), 10.0, kEps);
    EXPECT_NEAR(board.state().tc.group(1).tools[kTool].length, before - 10000.0, 1e-6);
}

// [ISG-OTC] section 2.3.1: a tilted disc splits the wear over two main axes (G17: X and Z).
TEST_F(OtcBoard, TiltedDiscSplitsTheWearIntoSinAndCosParts) {
    grinding_tool(otc::kGrindingToolType, kGrindingWearConst, kGrindingMaxInfeed, 300000.0);  // 30 degrees
    ASSERT_EQ(otc_on(), Status::kOk);
    spool_ok(line(60, 1000.0, 0.0, 10000.0));
    board.step(3000);  // half way
    EXPECT_EQ(nominal()[0], 500.0);
    EXPECT_NEAR(offset()[0], -5.0 * 0.5, kEps);
    EXPECT_NEAR(offset()[2], -5.0 * std::sqrt(3.0) / 2.0, kEps);
    run();
    EXPECT_NEAR(offset()[0], -10.0 * 0.5, kEps);
    EXPECT_NEAR(offset()[2], -10.0 * std::sqrt(3.0) / 2.0, kEps);
    EXPECT_EQ(offset()[1], 0.0);
    run_and_off();
    EXPECT_NEAR(wear(0), 5.0, kEps);
    EXPECT_NEAR(wear(2), 10.0 * std::sqrt(3.0) / 2.0, kEps);
    // The length wear is the whole 10 mm along the tilted disc axis.
    EXPECT_NEAR(board.state().tc.group(1).tools[kTool].length, 40.0, kEps);
}

// ---- The continuous wear along arcs and helices ([ISG-OTC] section 2.1, docs/otc.md section 1)

// W = wear constant x the path length on the main axes, with the length worked out by hand: an
// arc R |sweep|, a helix sqrt((R sweep)^2 + dz^2). In every processing type and both modes with
// continuous wear, W after the move and the wear #OTC OFF folds into the variables and the tool.
// RADIUS wears only on the compensated contour, the tool-centre path: G41 on a CCW arc of
// radius 20 with a tool of radius 5 runs on radius 15 (the approach and departure wear nothing).
TEST(OtcWear, ArcsAndHelicesWearTheWearConstantTimesTheirLengthOnTheMainAxes) {
    constexpr double kRatio = kGrindingWearConst * 1e-7;  // wear per unit of path
    constexpr double kArcRadius = 20.0;
    constexpr double kToolRadius = 5.0;
    constexpr double kPi = std::numbers::pi;
    struct Shape {
        const char* name;
        double sweep;  // CCW, from (20, 0) about (0, 0)
        double dz;     // third-axis travel
    };
    const Shape shapes[] = {
        {"quarter arc", kPi / 2, 0.0}, {"full circle", 2 * kPi, 0.0}, {"helix", kPi / 2, 10.0}};
    for (auto type : {otc::ProcessingType::kRadius, otc::ProcessingType::kLength,
                      otc::ProcessingType::kToolDir, otc::ProcessingType::kSurfNormDir}) {
        for (auto mode : {otc::Mode::kCont, otc::Mode::kAuto}) {
            for (const Shape& shape : shapes) {
                const std::string label = std::string(otc::processing_type_name(type)) + " " +
                                          std::string(otc::mode_name(mode)) + " " + shape.name;
                const bool radius = type == otc::ProcessingType::kRadius;
                const double rho = radius ? kArcRadius - kToolRadius : kArcRadius;
                const double expected = kRatio * std::hypot(rho * shape.sweep, shape.dz);
                OtcRig r;
                if (radius) r.setup_group(kToolRadius, /*left=*/true);
                r.grinding_tool();
                ASSERT_EQ(r.set_type(type), Status::kOk);
                ASSERT_EQ(r.set_mode(mode), Status::kOk);
                ASSERT_EQ(r.otc_on(), Status::kOk);
                r.spool_ok(rapid(1, kArcRadius, 0.0));  // wear-free
                if (radius) r.activate(1);              // G41
                const bool full = shape.sweep == 2 * kPi;
                Profile p =
                    arc(2, /*ccw=*/true, full ? kArcRadius : kArcRadius * std::cos(shape.sweep),
                        full ? 0.0 : kArcRadius * std::sin(shape.sweep), 0.0, 0.0, 10000.0);
                if (shape.dz != 0.0) {
                    p.axes = 0x07;
                    p.target[2] = shape.dz;
                }
                r.spool_ok(p);
                if (radius) {
                    ASSERT_EQ(r.deactivate(1), Status::kOk);  // G40
                }
                r.run();
                EXPECT_NEAR(r.board.state().otc_engine.continuous_wear(), expected, kEps) << label;
                ASSERT_EQ(r.otc_off(), Status::kOk);
                const auto& tool = r.board.state().tc.group(1).tools[kTool];
                if (radius) {
                    EXPECT_NEAR(r.wear_radius_cont(), expected, kEps) << label;
                    EXPECT_NEAR(r.wear_radius(), expected, kEps) << label;
                } else {
                    // Along d, a unit vector: the wear vector over the axes is W long.
                    double sum = 0.0;
                    for (int a = 0; a < 8; ++a) sum += r.wear(a) * r.wear(a);
                    EXPECT_NEAR(std::sqrt(sum), expected, kEps) << label;
                }
                // The fold: RADIUS and SURF_NORM_DIR shorten the radius, LENGTH and TOOL_DIR
                // the length (docs/otc.md section 6).
                const bool into_radius = radius || type == otc::ProcessingType::kSurfNormDir;
                EXPECT_NEAR(tool.radius, kGrindingDiscRadius - (into_radius ? expected : 0.0), kEps)
                    << label;
                EXPECT_NEAR(tool.length, kGrindingDiscLength - (into_radius ? 0.0 : expected), kEps)
                    << label;
            }
        }
    }
}

// The analytic fast path gives the same bits as stepping every cycle (docs/motion.md).
TEST(OtcClock, UnobservedRunsGiveTheSameBitsAsTracedOnes) {
    auto run_rig = [](bool trace, std::uint64_t first_step) {
        OtcRig r;
        r.grinding_tool(otc::kGrindingToolType, kGrindingWearConst, kGrindingMaxInfeed, 123456.0);
        EXPECT_EQ(r.otc_on(), Status::kOk);
        if (trace) {
            EXPECT_EQ(r.board.set_trace(true, 1 << 16), Status::kOk);
        }
        r.spool_ok(line(1, 100.0, 37.0, 3000.0));
        r.spool_ok(arc(2, true, 100.0, 77.0, 100.0, 57.0, 3000.0));
        r.spool_ok(rapid(3, 0.0, 0.0));
        r.spool_ok(line(4, -20.0, 5.0, 700.0));
        r.board.step(first_step);
        const AxisVector mid = r.position();
        r.run();
        return std::make_pair(mid, r.position());
    };
    for (std::uint64_t first : {1u, 977u, 2500u, 5000u}) {
        const auto fast = run_rig(false, first);
        const auto slow = run_rig(true, first);
        for (int a = 0; a < 8; ++a) {
            EXPECT_EQ(fast.first[a], slow.first[a]) << "axis " << a << " after " << first;
            EXPECT_EQ(fast.second[a], slow.second[a]) << "axis " << a;
        }
    }
}

TEST_F(OtcBoard, RampingOffsetsStepEveryCycleAndSettledOnesDoNot) {
    grinding_tool();
    ASSERT_EQ(set_mode(otc::Mode::kDisc), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    EXPECT_FALSE(board.state().motion.executor().per_cycle());
    auto& engine = board.state().otc_engine;
    EXPECT_FALSE(engine.per_cycle(nullptr, 0, 0));
    ASSERT_EQ(plc(2, 1000), Status::kOk);  // 0.1 mm on Z
    EXPECT_TRUE(engine.per_cycle(nullptr, 0, 0));
    board.step(5000);
    EXPECT_FALSE(engine.per_cycle(nullptr, 0, 0));
    EXPECT_NEAR(offset()[2], -0.1, 1e-12);
}

// ---- RADIUS with a discrete offset: wr_quad_disc.nc ([ISG-OTC-EN], "OTC with discrete
// compensation"; [ISG-OTC] section 2.2, Abb. 3) with the PLC commanding 2 mm.

struct Cycle {
    AxisVector offset;
    AxisVector nominal;
    SegmentRole role;
    std::uint32_t tag;
};

class WrQuadDisc : public OtcBoard {
  protected:
    void SetUp() override {
        using namespace rwmos::tc;
        setup_group(kGrindingDiscRadius, /*left=*/false);  // N55 G42
        grinding_tool();
        ASSERT_EQ(write_int(kBus, kDevGroups, 1, kSubWkzIndex, kTool), Status::kOk);  // N22 D1
        ASSERT_EQ(write_int(kBus, kDevGroups, 1, kSubCornerMode, kCornerLinear),
                  Status::kOk);                                          // G25
        ASSERT_EQ(set_type(otc::ProcessingType::kRadius), Status::kOk);  // N50 #OTC ON[RADIUS DISC]
        ASSERT_EQ(set_mode(otc::Mode::kDisc), Status::kOk);
        ASSERT_EQ(otc_on(), Status::kOk);
        ASSERT_EQ(plc(-1, 20000), Status::kOk);  // the PLC: 2 mm
        activate(1);
        spool_ok(line(60, 2.0, 0.0));
        spool_ok(line(70, 102.0, 0.0));
        ASSERT_EQ(write_int(kBus, kDevGroups, 1, kSubCornerMode, kCornerCircular),
                  Status::kOk);  // G26
        spool_ok(line(80, 102.0, 100.0));
        spool_ok(line(90, 2.0, 100.0));
        spool_ok(line(95, 2.0, 0.0));
        ASSERT_EQ(deactivate(1), Status::kOk);  // N100 G40
        spool_ok(line(100, 0.0, 0.0));
        while (board.state().motion.executor().fill() > 0) {
            board.step(1);
            const auto& e = board.state().motion.executor();
            Cycle c{offset(), nominal(), SegmentRole::kRapid, 0};
            if (e.fill() > 0) {
                c.role = board.state().motion.executor().queued(0).role;
                c.tag = board.state().motion.executor().queued(0).tag;
            }
            cycles.push_back(c);
        }
        ASSERT_EQ(otc_off(), Status::kOk);  // N110
    }
    std::vector<Cycle> cycles;
};

TEST_F(WrQuadDisc, OffsetBuildsUpOverManyCyclesNeverFasterThanTheRamp) {
    const double vmax = board.state().otc.ramp_velocity;
    const double dt = 1e-3;
    std::size_t first_nonzero = cycles.size(), reached = cycles.size();
    AxisVector prev{};
    for (std::size_t i = 0; i < cycles.size(); ++i) {
        for (int a = 0; a < 8; ++a)
            EXPECT_LE(std::abs(cycles[i].offset[a] - prev[a]), vmax * dt * (1 + 1e-9))
                << "cycle " << i << " axis " << a;
        prev = cycles[i].offset;
        const double n = norm(cycles[i].offset);
        if (n > 0.0 && first_nonzero == cycles.size()) first_nonzero = i;
        if (std::abs(n - 2.0) < kEps && reached == cycles.size()) reached = i;
    }
    ASSERT_LT(reached, cycles.size());
    EXPECT_GT(reached - first_nonzero, 1000u) << "2 mm at 0.5 mm/s take seconds, not a jump";
}

TEST_F(WrQuadDisc, OffsetActsPerpendicularToTheContourTowardsIt) {
    // On N70 (tool right of +X, centre at y = -30), once built up: 2 mm towards the contour.
    bool seen = false;
    for (const Cycle& c : cycles) {
        if (c.tag != 70 || c.role != SegmentRole::kContour || c.nominal[0] < 90.0) continue;
        seen = true;
        EXPECT_NEAR(c.offset[0], 0.0, kEps);
        EXPECT_NEAR(c.offset[1], 2.0, kEps);
    }
    EXPECT_TRUE(seen);
}

// [ISG-OTC-EN], explanations 2 and 3: "The TRC inserts a circular transition because of G26. But
// the OTC offset is so large that the increase in offset is unable to keep up with the
// continuous change in the contour." / "The OTC offset lags behind considerably."
TEST_F(WrQuadDisc, OffsetLagsAtTheG26CornerAndCatchesUpAfter) {
    const Eigen::Vector2d corner{102.0, 0.0};
    double worst = 0.0;
    for (const Cycle& c : cycles) {
        if (c.tag != 80 || c.role != SegmentRole::kTransition) continue;
        const Eigen::Vector2d n =
            (Eigen::Vector2d(c.nominal[0], c.nominal[1]) - corner).normalized();
        const Eigen::Vector2d target = -2.0 * n;
        worst = std::max(worst, (Eigen::Vector2d(c.offset[0], c.offset[1]) - target).norm());
    }
    EXPECT_GT(worst, 0.1) << "the offset should lag behind the turning normal";
    RecordProperty("worst_lag_um", static_cast<int>(worst * 1000));
    // By the end of N80's edge (x = 132) it sits 2 mm towards the contour again.
    const Cycle* last80 = nullptr;
    for (const Cycle& c : cycles)
        if (c.tag == 80 && c.role == SegmentRole::kContour) last80 = &c;
    ASSERT_NE(last80, nullptr);
    EXPECT_NEAR(last80->offset[0], -2.0, kEps);
    EXPECT_NEAR(last80->offset[1], 0.0, kEps);
}

TEST_F(WrQuadDisc, OffsetRampsOutAfterTheDepartureAndTheWearFoldsIntoTheRadius) {
    // After G40 the radius compensation is gone and so is the radius wear offset.
    run();
    board.step(20000);
    EXPECT_NEAR(norm(offset()), 0.0, kEps);
    EXPECT_NEAR(wear_radius(), 2.0, kEps);
    EXPECT_EQ(wear_radius_cont(), 0.0);  // DISC: nothing continuous
    EXPECT_NEAR(board.state().tc.group(1).tools[kTool].radius, 28.0, kEps);
}

// Design (docs/otc.md section 2, RADIUS in detail): along the approach after G41/G42 the first
// contour move's normal is weighed in from 0 to 1. A fast ramp makes the offset follow its
// target, so the channel unit's 1 mm shows the weight cycle by cycle.
TEST_F(OtcBoard, RadiusNormalIsWeighedInAlongTheApproach) {
    setup_group(kGrindingDiscRadius, /*left=*/true);  // the approach runs 30 mm
    grinding_tool();
    ASSERT_EQ(otc_double(otc::kDevChannel, otc::kIdxRampVelocity, 0, 1000.0), Status::kOk);
    ASSERT_EQ(otc_double(otc::kDevChannel, otc::kIdxRampAcceleration, 0, 1.0e6), Status::kOk);
    ASSERT_EQ(set_type(otc::ProcessingType::kRadius), Status::kOk);
    ASSERT_EQ(set_mode(otc::Mode::kDisc), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    ASSERT_EQ(plc(-1, 10000), Status::kOk);  // 1 mm
    activate(1);                             // G41
    spool_ok(line(1, 100.0, 0.0));
    spool_ok(line(2, 200.0, 0.0));
    auto& e = board.state().motion.executor();
    std::vector<double> sizes;  // |offset| at every cycle of the approach
    while (e.fill() > 0 && e.queued(0).role == SegmentRole::kApproach) {
        board.step(1);
        sizes.push_back(norm(offset()));
    }
    ASSERT_GT(sizes.size(), 1000u);
    EXPECT_LT(sizes.front(), 0.01);
    for (std::size_t i = 1; i < sizes.size(); ++i)
        EXPECT_GE(sizes[i], sizes[i - 1] - 1e-12) << "cycle " << i;
    EXPECT_NEAR(sizes.back(), 1.0, 1e-3);
    // On the contour it stays at 1 mm, towards the contour (left of +X, -Y).
    board.step(1000);
    EXPECT_NEAR(offset()[0], 0.0, kEps);
    EXPECT_NEAR(offset()[1], -1.0, kEps);
}

// ---- TOOL_DIR ([ISG-OTC] section 2.4, "OTC-Schleifen mit Kinematiktyp 4")

TEST_F(OtcBoard, ToolDirOffsetFollowsTheBHeadToolDirection) {
    grinding_tool();
    ASSERT_EQ(otc_int(otc::kDevChannel, otc::kIdxKinematics, 0, 4), Status::kOk);  // #KIN ID[4]
    ASSERT_EQ(otc_int(otc::kDevChannel, otc::kIdxTrafo, 0, 1), Status::kOk);       // #TRAFO ON
    AxisVector t{};
    t[2] = 300.0;
    spool_ok(rapid_to(40, t, 0x1F));  // N40 G00 X0 Y0 Z300 B0
    t[kB] = 45.0;
    spool_ok(rapid_to(60, t, 0x10));  // N60 G00 B45
    t[0] = 100.0;
    t[2] = 50.0;
    spool_ok(line_to(70, t, 1000.0, 0x05));  // N70 G01 X100 Z50 F1000
    run();
    ASSERT_EQ(set_type(otc::ProcessingType::kToolDir),
              Status::kOk);  // N80 #OTC ON [TOOL_DIR, DISC]
    ASSERT_EQ(set_mode(otc::Mode::kDisc), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    ASSERT_EQ(plc(-1, 10000), Status::kOk);  // 1 mm along the tool
    for (int i = 0; i <= 20; ++i) {          // N90 $FOR P1=0, 20, 1
        t[0] += 10.0;
        t[2] -= 10.0;
        spool_ok(line_to(100, t, 2000.0, 0x05));  // N100 G91 G01 X10 Z-10 F2000
        t[0] -= 10.0;
        t[2] += 10.0;
        spool_ok(line_to(110, t, 2000.0, 0x05));  // N110 X-10 Z10
    }
    const Eigen::Vector3d tool = rwmos::geom::b_head_tool_direction(45.0);
    std::uint64_t checked = 0;
    while (board.state().motion.executor().fill() > 0) {
        board.step(1);
        if (board.motion_status().now < 20000) continue;  // the ramp has settled by then
        ++checked;
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(offset()[a], -1.0 * tool[a], kEps);
    }
    EXPECT_GT(checked, 1000u);
    EXPECT_EQ(unit_state(-1), 10000);
    EXPECT_EQ(unit_request(-1), 10000);
    ASSERT_EQ(otc_off(), Status::kOk);  // N120 #OTC OFF
    EXPECT_NEAR(wear(0), std::sqrt(0.5), kEps);
    EXPECT_NEAR(wear(2), std::sqrt(0.5), kEps);
    EXPECT_NEAR(board.state().tc.group(1).tools[kTool].length, kGrindingDiscLength - 1.0, kEps);
}

// ---- SURF_NORM_DIR ([ISG-OTC] section 2.5)

TEST_F(OtcBoard, SurfNormDirOffsetIsAlongTheSurfaceNormal) {
    grinding_tool();
    ASSERT_EQ(otc_int(otc::kDevChannel, otc::kIdxKinematics, 0, 4), Status::kOk);
    ASSERT_EQ(otc_int(otc::kDevChannel, otc::kIdxTrafo, 0, 1), Status::kOk);
    // A fast ramp, so each short block of the example settles on its own normal.
    ASSERT_EQ(otc_double(otc::kDevChannel, otc::kIdxRampVelocity, 0, 1000.0), Status::kOk);
    ASSERT_EQ(otc_double(otc::kDevChannel, otc::kIdxRampAcceleration, 0, 1.0e6), Status::kOk);
    AxisVector t{};
    t[0] = 100.0;
    t[2] = 50.0;
    spool_ok(line_to(70, t, 1000.0));  // N70 G01 X100 Z50 F1000 (B0)
    run();
    ASSERT_EQ(set_type(otc::ProcessingType::kSurfNormDir), Status::kOk);  // N80
    ASSERT_EQ(set_mode(otc::Mode::kDisc), Status::kOk);
    ASSERT_EQ(otc_on(), Status::kOk);
    ASSERT_EQ(plc(2, 5000), Status::kOk);  // the third axis carries the offset: 0.5 mm
    // N100..N270: [ISG-OTC]'s loop body, incremental X Z.
    const double steps[][2] = {{3, -3}, {2, -2}, {5, -2}, {5, -1}, {5, 0},  {5, -1},
                               {5, -2}, {2, -2}, {3, -3}, {-3, 3}, {-2, 2}, {-5, 2},
                               {-5, 1}, {-5, 0}, {-5, 1}, {-5, 2}, {-2, 2}, {-3, 3}};
    const Eigen::Vector3d tool{0, 0, 1};
    int distinct = 0;
    Eigen::Vector3d previous = Eigen::Vector3d::Zero();
    for (const auto& s : steps) {
        t[0] += s[0];
        t[2] += s[1];
        spool_ok(line_to(100, t, 2000.0));
        run();
        const Eigen::Vector3d fn = otc::surface_normal(tool, Eigen::Vector3d(s[0], 0, s[1]), tool);
        EXPECT_NEAR(fn.dot(Eigen::Vector3d(s[0], 0, s[1])), 0.0, 1e-12);
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(offset()[a], -0.5 * fn[a], kEps) << s[0] << " " << s[1];
        if ((fn - previous).norm() > 1e-6) ++distinct;
        previous = fn;
    }
    EXPECT_GT(distinct, 6);
    ASSERT_EQ(otc_off(), Status::kOk);
    EXPECT_NEAR(board.state().tc.group(1).tools[kTool].radius, kGrindingDiscRadius - 0.5, kEps);
}

}  // namespace
}  // namespace otc_test
