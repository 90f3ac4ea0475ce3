// SPDX-License-Identifier: MIT
// Bottleneck avoidance (tools/runlib/src/bottleneck.h, docs/compensation.md "Avoidance"):
// SINUMERIK's rule, the moves between two compensated moves whose tool paths cross left out.
// The avoider on events (what it holds, leaves out and puts in), and runs on the embedded board
// (the path it gives, the warning naming the blocks, the closed contour that is no bottleneck).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "apci/apci.hpp"
#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "apci/run/executor.h"
#include "bottleneck.h"

namespace {

namespace nc = apci::nc;
using apci::run::detail::Bottleneck;
using apci::run::detail::BottleneckAvoider;

// The events of a DIN program (its text in mm, tool D1).
std::vector<nc::Event> events_of(const std::string& text) {
    auto tools = nc::parse_tool_table("wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n",
                                      "t.tools");
    EXPECT_TRUE(tools);
    nc::InterpreterOptions options;
    options.tools = &tools.value();
    auto program = nc::Program::from_text(text, "b.nc", options);
    EXPECT_TRUE(program) << (program ? "" : program.error().to_string());
    std::vector<nc::Event> out;
    auto stream = program.value().events();
    EXPECT_TRUE(stream);
    nc::Event ev;
    while (stream.value().next(ev) == nc::EventStream::Next::kEvent) out.push_back(ev);
    return out;
}

// A contour along +X with a narrow V notch, then up at x = 14: under G41 (r = 5) the paths of
// N10 (y = 5) and N40 (x = 9) cross at (9, 5); N20 and N30, the notch, lie between them.
const std::string kNotch =
    "G17 G90 G26 F1000 D1\nG0 X-10 Y20 Z0\nG41 G1 X-5 Y0\nN10 G1 X10 Y0\nN20 G1 X12 Y-8\n"
    "N30 G1 X14 Y0\nN40 G1 X14 Y10\nN50 G1 X30 Y10\nN60 G40 G1 X30 Y20\nM30\n";

struct Avoided {
    std::vector<nc::Event> out;
    std::vector<Bottleneck> found;
};

Avoided avoid(const std::string& text, int blocks) {
    BottleneckAvoider a(blocks);
    Avoided r;
    for (const nc::Event& ev : events_of(text)) a.take(ev, 5.0, 17, r.out, r.found);
    a.flush(r.out);
    return r;
}

std::vector<std::int64_t> move_blocks(const std::vector<nc::Event>& events) {
    std::vector<std::int64_t> out;
    for (const auto& e : events)
        if (std::holds_alternative<nc::LineMove>(e.data) || std::holds_alternative<nc::ArcMove>(e.data))
            out.push_back(e.origin.block);
    return out;
}

TEST(BottleneckAvoider, LeavesOutTheMovesBetweenTwoWhosePathsCrossAndBridgesThem) {
    const Avoided r = avoid(kNotch, 3);
    ASSERT_EQ(r.found.size(), 1U);
    EXPECT_EQ(r.found[0].before.block, 10);
    EXPECT_EQ(r.found[0].after.block, 40);
    EXPECT_EQ(r.found[0].first.block, 20);
    EXPECT_EQ(r.found[0].last.block, 30);
    EXPECT_NEAR(r.found[0].where.x(), 9.0, 1e-12);
    EXPECT_NEAR(r.found[0].where.y(), 5.0, 1e-12);
    // The approach, N10 ending under X, the bridge (tagged N40), N40 from beside X, N50, the
    // departure.
    EXPECT_EQ(move_blocks(r.out), (std::vector<std::int64_t>{-1, 10, 40, 40, 50, 60}));
    bool bridged = false, walls_off = false;
    for (const auto& e : r.out) {
        if (const auto* l = std::get_if<nc::LineMove>(&e.data); l && e.origin.block == 10) {
            EXPECT_NEAR(l->end.x(), 9.0, 1e-12);
            EXPECT_NEAR(l->end.y(), 0.0, 1e-12);
        }
        if (const auto* a = std::get_if<nc::ArcMove>(&e.data)) {
            bridged = true;
            EXPECT_TRUE(walls_off);  // the bridge is no wall
            EXPECT_NEAR(a->center.x(), 9.0, 1e-12);
            EXPECT_NEAR(a->center.y(), 5.0, 1e-12);
            EXPECT_NEAR((a->start - a->center).norm(), 5.0, 1e-12);
            EXPECT_NEAR((a->end - a->center).norm(), 5.0, 1e-12);
            EXPECT_TRUE(a->ccw);  // G41: the tool, on the left, at its centre
        }
        if (const auto* w = std::get_if<nc::CollisionDetectionChange>(&e.data)) walls_off = !w->on;
        if (const auto* l = std::get_if<nc::LineMove>(&e.data); l && e.origin.block == 40) {
            EXPECT_NEAR(l->start.x(), 14.0, 1e-12);
            EXPECT_NEAR(l->start.y(), 5.0, 1e-12);
        }
    }
    EXPECT_TRUE(bridged);
    EXPECT_FALSE(walls_off);
}

TEST(BottleneckAvoider, LooksNoFartherBackThanItsBlocks) {
    // N10 and N40 are three moves apart: with two blocks of look back they are not compared.
    const Avoided r = avoid(kNotch, 2);
    EXPECT_TRUE(r.found.empty());
    EXPECT_EQ(move_blocks(r.out), (std::vector<std::int64_t>{-1, 10, 20, 30, 40, 50, 60}));
}

TEST(BottleneckAvoider, AClosedContoursLastAndFirstMovesAreNoBottleneck) {
    // A triangle pocket (G41 counter-clockwise, tool inside): the paths of its first and last
    // sides meet at the inside corner where it closes, which is no bottleneck.
    const std::string triangle =
        "G17 G90 G26 F1000 D1\nG0 X20 Y10 Z0\nG41 G1 X20 Y0\nN10 G1 X60 Y0\nN20 G1 X40 Y40\n"
        "N30 G1 X20 Y0\nN40 G40 G1 X30 Y10\nM30\n";
    const Avoided r = avoid(triangle, 3);
    EXPECT_TRUE(r.found.empty());
    EXPECT_EQ(move_blocks(r.out), (std::vector<std::int64_t>{-1, 10, 20, 30, 40}));
}

TEST(BottleneckAvoider, PathsThatMeetAtAPathsStartDoNotCrossThoseJustPastItDo) {
    // N20 along +X from (0, 0) (its path y = 5 from x 0), N30 back under it, N40 up x = 5 + e
    // (its path x = e): at e = 0 the paths of N20 and N40 meet at N20's path's start (0, 5),
    // which is no crossing; at e = 1e-3 they cross 1e-3 along it, and N30 is left out.
    for (const double e : {0.0, 1e-3}) {
        const std::string x = std::to_string(5.0 + e);
        const std::string text = "G17 G90 G26 F1000 D1\nG0 X-10 Y-10 Z0\nG41 G1 X0 Y0\n"
                                 "N20 G1 X20 Y0\nN30 G1 X" + x + " Y-10\nN40 G1 X" + x +
                                 " Y20\nN50 G40 G1 X" + x + " Y30\nM30\n";
        const Avoided r = avoid(text, 3);
        if (e == 0.0) {
            EXPECT_TRUE(r.found.empty());
            EXPECT_EQ(move_blocks(r.out), (std::vector<std::int64_t>{-1, 20, 30, 40, 50}));
        } else {
            ASSERT_EQ(r.found.size(), 1U);
            EXPECT_EQ(r.found[0].before.block, 20);
            EXPECT_EQ(r.found[0].after.block, 40);
            EXPECT_NEAR(r.found[0].where.x(), e, 1e-9);
            EXPECT_NEAR(r.found[0].where.y(), 5.0, 1e-9);
        }
    }
}

TEST(BottleneckAvoider, OfTwoCrossingsTheOneNearestTheLaterMovesStartIsTaken) {
    // N20 along +X (its path y = 5), N40 a counter-clockwise half circle about (0, 12) of
    // radius 15 from its left (G41: the tool inside, its path of radius 10), whose path crosses
    // y = 5 twice: first at x = -sqrt(51), then at x = sqrt(51).
    const std::string text =
        "G17 G90 G26 F1000 D1\nG0 X-20 Y-10 Z0\nG41 G1 X-20 Y0\nN20 G1 X20 Y0\n"
        "N30 G1 X-15 Y12\nN40 G3 X15 Y12 I15 J0\nN50 G40 G1 X15 Y30\nM30\n";
    const Avoided r = avoid(text, 3);
    ASSERT_EQ(r.found.size(), 1U);
    EXPECT_EQ(r.found[0].before.block, 20);
    EXPECT_EQ(r.found[0].after.block, 40);
    EXPECT_NEAR(r.found[0].where.x(), -std::sqrt(51.0), 1e-9);
    EXPECT_NEAR(r.found[0].where.y(), 5.0, 1e-9);
}

// N40 a clockwise circle about the origin (G41 outside it: its path of radius 20 crosses N20's,
// y = 5, at x = +-sqrt(375)), its end 0 to 2e-9 left of its start. Ends at most 1e-9 apart are a
// whole circle, as the board runs it: N30 between is left out as for the closed circle. Further
// apart it is the sliver from its start to its end, whose path crosses nothing.
TEST(BottleneckAvoider, AnArcWhoseEndsLieWithinTheToleranceIsAWholeCircle) {
    for (const std::string end : {"0", "-0.0000000005", "-0.000000001", "-0.000000002"}) {
        const std::string text = "G17 G90 G26 F1000 D1\nG0 X-20 Y-10 Z0\nG41 G1 X-20 Y0\n"
                                 "N20 G1 X20 Y0\nN30 G1 X0 Y-15\nN40 G2 X" + end +
                                 " Y-15 I0 J15\nN50 G40 G1 X0 Y-30\nM30\n";
        const Avoided r = avoid(text, 3);
        if (end == "-0.000000002") {
            EXPECT_TRUE(r.found.empty()) << end;
            continue;
        }
        ASSERT_EQ(r.found.size(), 1U) << end;
        EXPECT_EQ(r.found[0].before.block, 20) << end;
        EXPECT_EQ(r.found[0].after.block, 40) << end;
        EXPECT_NEAR(std::abs(r.found[0].where.x()), std::sqrt(375.0), 1e-9) << end;
        EXPECT_NEAR(r.found[0].where.y(), 5.0, 1e-9) << end;
    }
}

TEST(BottleneckAvoider, GivesEveryEventOnInOrderWhereNothingCrosses) {
    const std::string plain =
        "G17 G90 G26 F1000 D1\nG0 X0 Y-10 Z0\nG41 G1 X0 Y0\nN10 G1 X20\nN20 G3 X30 Y10 I0 J10\n"
        "N25 G1 Z-1\nN30 G1 Y30\nN40 G1 X0\nN50 G40 G1 X-10\nM30\n";
    const auto events = events_of(plain);
    const Avoided r = avoid(plain, 8);
    EXPECT_TRUE(r.found.empty());
    ASSERT_EQ(r.out.size(), events.size());
    for (std::size_t i = 0; i < events.size(); ++i) {
        EXPECT_EQ(r.out[i].origin.line, events[i].origin.line) << i;
        EXPECT_EQ(r.out[i].data.index(), events[i].data.index()) << i;
    }
}

// ---- through the executor on the embedded board

struct BoardRun {
    std::vector<apci::run::PathSegment> executed;
    apci::run::RunOutcome outcome;
};

class Segments final : public apci::run::RunSink {
  public:
    void executed(const apci::run::PathSegment& s) override { out.push_back(s); }
    std::vector<apci::run::PathSegment> out;
};

BoardRun run_on_board(const std::string& text, int blocks) {
    auto tools = nc::parse_tool_table("wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n",
                                      "t.tools");
    apci::Board board("emu:");
    Segments sink;
    apci::run::ProgramExecutor executor(board, sink, &tools.value());
    executor.set_avoid_bottlenecks(blocks);
    nc::InterpreterOptions options;
    options.tools = &tools.value();
    auto program = nc::Program::from_text(text, "b.nc", options);
    auto stream = program.value().events();
    BoardRun r;
    r.outcome = executor.run(stream.value());
    r.executed = sink.out;
    return r;
}

TEST(BottleneckAvoidance, WithoutItTheBoardRefusesTheNotchWithItThePathTurnsAtTheCrossing) {
    const BoardRun off = run_on_board(kNotch, 0);
    ASSERT_FALSE(off.outcome.errors.empty());
    EXPECT_EQ(off.outcome.errors[0].code, "KorrError");
    const BoardRun on = run_on_board(kNotch, 3);
    for (const auto& e : on.outcome.errors) ADD_FAILURE() << e.message;
    ASSERT_TRUE(on.outcome.errors.empty());
    ASSERT_EQ(on.outcome.warnings.size(), 1U);
    EXPECT_EQ(on.outcome.warnings[0].code, "Bottleneck");
    EXPECT_EQ(on.outcome.warnings[0].block.number, 20);
    EXPECT_EQ(on.outcome.warnings[0].message,
              "N20 to N30 left out: the tool paths of N10 and N40 cross at (9.0000, 5.0000) in "
              "the X-Y plane, and the tool goes from the one to the other there "
              "(--avoid-bottlenecks 3, as SINUMERIK's CDON)");
    // The path: along y = 5 to (9, 5), then up x = 9: no point of it nearer the contour than
    // the tool's radius, and it passes through the crossing.
    bool through = false;
    for (const auto& s : on.executed) {
        if (s.role == apci::run::Role::kUncompensated || s.role == apci::run::Role::kApproach ||
            s.role == apci::run::Role::kDeparture)
            continue;
        for (const double t : {0.0, 0.5, 1.0}) {
            const apci::run::Point p = apci::run::point_along(s, t);
            through |= std::abs(p.x() - 9.0) < 1e-6 && std::abs(p.y() - 5.0) < 1e-6;
            // Distance to the contour's walls that remain: y = 0 (x <= 10), x = 14 (y >= 0).
            if (p.x() <= 10.0) {
                EXPECT_GE(p.y(), 5.0 - 1e-6) << p.transpose();
            }
            if (p.y() >= 0.0 && p.y() <= 10.0) {
                EXPECT_LE(p.x(), 9.0 + 1e-6) << p.transpose();
            }
        }
    }
    EXPECT_TRUE(through);
}

}  // namespace
