// SPDX-License-Identifier: MIT
// PathCompensator: one element of lookahead ([APCI-TC] "1 Einfuhrung"), approach and
// departure, roles and indices, errors ([APCI-TC] "Tabelle 4") without state change.
#include "rwmos/geometry/compensator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rwmos::geom {
namespace {

constexpr double kEps = 1e-12;

void expect_near(const Vec2& a, const Vec2& b, double tol = kEps) {
    EXPECT_NEAR(a.x(), b.x(), tol) << "x";
    EXPECT_NEAR(a.y(), b.y(), tol) << "y";
}

CompensatorConfig config(double r, Side side = Side::kLeft,
                         TransitionMode mode = TransitionMode::kCircular) {
    return CompensatorConfig{side, r, mode};
}

bool same(const Element& a, const Element& b) {
    return a.kind == b.kind && a.ccw == b.ccw && a.start == b.start && a.end == b.end &&
           (a.kind == ElementKind::kLine || a.centre == b.centre);
}

// A square 10 x 10 from (0,0) counter-clockwise: every corner turns left.
const std::vector<Element> kSquare = {make_line({0, 0}, {10, 0}), make_line({10, 0}, {10, 10}),
                                      make_line({10, 10}, {0, 10}), make_line({0, 10}, {0, 0})};

TEST(Compensator, RoleNamesAreThoseOfTheRunJson) {
    EXPECT_EQ(role_name(SegmentRole::kContour), "contour");
    EXPECT_EQ(role_name(SegmentRole::kTransition), "transition");
    EXPECT_EQ(role_name(SegmentRole::kApproach), "approach");
    EXPECT_EQ(role_name(SegmentRole::kDeparture), "departure");
}

TEST(Compensator, PushBeforeBeginIsInitError) {
    PathCompensator c;
    SegmentBatch out;
    const StepResult r = c.push(kSquare[0], 3, out);
    EXPECT_EQ(r.reason, Reason::kNotStarted);
    EXPECT_EQ(r.errors, bits(ErrorBit::kInitError));
    EXPECT_EQ(r.index, 3u);
    EXPECT_TRUE(out.empty());
    EXPECT_EQ(c.finish(out).reason, Reason::kNotStarted);
}

TEST(Compensator, BeginRefusesBadToolRadiusSettingsAndPositionWithoutStarting) {
    PathCompensator c;
    EXPECT_EQ(c.begin(config(-1), {0, 0}).reason, Reason::kInvalidToolRadius);
    EXPECT_EQ(c.begin(config(NAN), {0, 0}).reason, Reason::kInvalidToolRadius);
    EXPECT_EQ(c.begin(config(INFINITY), {0, 0}).reason, Reason::kInvalidToolRadius);
    EXPECT_EQ(c.begin(config(2e5), {0, 0}).reason, Reason::kInvalidToolRadius);
    EXPECT_EQ(c.begin(config(1, static_cast<Side>(7)), {0, 0}).reason, Reason::kInvalidSetting);
    EXPECT_EQ(c.begin(config(1, Side::kLeft, static_cast<TransitionMode>(9)), {0, 0}).reason,
              Reason::kInvalidSetting);
    EXPECT_EQ(c.begin(config(-1), {0, 0}).errors, bits(ErrorBit::kInitError));
    EXPECT_EQ(c.begin(config(1), {NAN, 0}).reason, Reason::kInvalidCoordinate);
    EXPECT_FALSE(c.running());
    EXPECT_TRUE(c.begin(config(1), {0, 0}).ok());
    EXPECT_TRUE(c.running());
}

TEST(Compensator, BeginWhileRunningIsInitErrorAndKeepsTheHeldElement) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, 0}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    EXPECT_EQ(c.begin(config(2), {0, 0}).reason, Reason::kAlreadyStarted);
    EXPECT_TRUE(c.holds_element());
    EXPECT_EQ(c.config().tool_radius, 1.0);
}

TEST(Compensator, FirstElementEmitsTheApproachToItsOffsetStartAndIsHeld) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 7, out).ok());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kApproach);
    EXPECT_EQ(out[0].index, 7u);
    expect_near(out[0].path.start, {-5, -5});
    expect_near(out[0].path.end, {0, 1});
    EXPECT_TRUE(c.holds_element());
    EXPECT_EQ(c.held_index(), 7u);
}

TEST(Compensator, ApproachOfZeroLengthIsNotEmitted) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {0, 1}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    EXPECT_TRUE(out.empty());
}

TEST(Compensator, NextElementReleasesTheHeldOneTrimmedAtTheInsideCorner) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    ASSERT_TRUE(c.push(kSquare[1], 1, out).ok());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kContour);
    EXPECT_EQ(out[0].index, 0u);
    expect_near(out[0].path.start, {0, 1});
    expect_near(out[0].path.end, {9, 1});
    EXPECT_EQ(c.held_index(), 1u);
}

TEST(Compensator, OutsideCornerTransitionBelongsToTheElementBeforeIt) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1, Side::kRight), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 4, out).ok());
    ASSERT_TRUE(c.push(kSquare[1], 5, out).ok());
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].role, SegmentRole::kContour);
    expect_near(out[0].path.end, {10, -1});
    EXPECT_EQ(out[1].role, SegmentRole::kTransition);
    EXPECT_EQ(out[1].index, 4u);
    EXPECT_EQ(out[1].path.kind, ElementKind::kArc);
    expect_near(out[1].path.centre, {10, 0});
    expect_near(out[1].path.end, {11, 0});
}

TEST(Compensator, LinearModeEmitsTheExtendedOffsetsAsTransition) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1, Side::kRight, TransitionMode::kLinear), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    ASSERT_TRUE(c.push(kSquare[1], 1, out).ok());
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out[1].role, SegmentRole::kTransition);
    EXPECT_EQ(out[2].role, SegmentRole::kTransition);
    expect_near(out[1].path.end, {11, -1});
    expect_near(out[2].path.end, {11, 0});
}

TEST(Compensator, TransitionModeSetDuringAContourAppliesFromTheNextCorner) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1, Side::kRight), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    ASSERT_EQ(c.set_transition(TransitionMode::kLinear), Reason::kNone);
    EXPECT_EQ(c.config().transition, TransitionMode::kLinear);
    EXPECT_TRUE(c.holds_element()) << "the contour goes on";
    ASSERT_TRUE(c.push(kSquare[1], 1, out).ok());
    ASSERT_EQ(out.size(), 3u) << "contour and the two lines of a linear transition";
    EXPECT_EQ(out[1].role, SegmentRole::kTransition);
    EXPECT_EQ(out[1].path.kind, ElementKind::kLine);
    expect_near(out[1].path.end, {11, -1});
    ASSERT_EQ(c.set_transition(TransitionMode::kCircular), Reason::kNone);
    ASSERT_TRUE(c.push(kSquare[2], 2, out).ok());
    ASSERT_EQ(out.size(), 2u) << "contour and one transition arc";
    EXPECT_EQ(out[1].path.kind, ElementKind::kArc);
}

TEST(Compensator, UndefinedTransitionModeIsRefusedAndChangesNothing) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    EXPECT_EQ(c.set_transition(static_cast<TransitionMode>(7)), Reason::kInvalidSetting);
    EXPECT_EQ(c.config().transition, TransitionMode::kCircular);
}

TEST(Compensator, FinishEmitsTheHeldElementUntrimmedAndTheDepartureToTheProgrammedEnd) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    ASSERT_TRUE(c.push(kSquare[1], 1, out).ok());
    ASSERT_TRUE(c.finish(out).ok());
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].role, SegmentRole::kContour);
    EXPECT_EQ(out[0].index, 1u);
    expect_near(out[0].path.start, {9, 1});
    expect_near(out[0].path.end, {9, 10});
    EXPECT_EQ(out[1].role, SegmentRole::kDeparture);
    EXPECT_EQ(out[1].index, 1u);
    expect_near(out[1].path.start, {9, 10});
    expect_near(out[1].path.end, {10, 10});
    EXPECT_FALSE(c.running());
    EXPECT_FALSE(c.holds_element());
}

TEST(Compensator, FinishWithoutAnyElementEmitsNothing) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {0, 0}).ok());
    ASSERT_TRUE(c.finish(out).ok());
    EXPECT_TRUE(out.empty());
    EXPECT_FALSE(c.running());
}

TEST(Compensator, HoldsExactlyOneElement) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    for (std::uint32_t i = 0; i < 4; ++i) {
        ASSERT_TRUE(c.push(kSquare[i], i, out).ok());
        EXPECT_EQ(c.held_index(), i);
        for (const Segment& s : out)
            if (s.role == SegmentRole::kContour) {
                EXPECT_EQ(s.index + 1, i);
            }
    }
}

TEST(Compensator, ErrorEmitsNothingAndLeavesTheStateAsBefore) {
    // Two compensators see the same elements; one also gets a failing arc in between.
    PathCompensator clean, failing;
    SegmentBatch a, b;
    ASSERT_TRUE(clean.begin(config(2), {-5, -5}).ok());
    ASSERT_TRUE(failing.begin(config(2), {-5, -5}).ok());
    ASSERT_TRUE(clean.push(kSquare[0], 0, a).ok());
    ASSERT_TRUE(failing.push(kSquare[0], 0, b).ok());
    // Concave arc of radius 1 < tool radius 2: CalcError.
    const Element small_arc = make_arc({10, 0}, {11, 1}, {10, 1}, true);
    const StepResult r = failing.push(small_arc, 1, b);
    EXPECT_EQ(r.reason, Reason::kOffsetRadiusNotPositive);
    EXPECT_EQ(r.errors, bits(ErrorBit::kCalcError));
    EXPECT_EQ(r.index, 1u);
    EXPECT_TRUE(b.empty());
    EXPECT_TRUE(failing.holds_element());
    EXPECT_EQ(failing.held_index(), 0u);
    for (std::uint32_t i = 1; i < 4; ++i) {
        ASSERT_TRUE(clean.push(kSquare[i], i, a).ok());
        ASSERT_TRUE(failing.push(kSquare[i], i, b).ok());
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(same(a[k].path, b[k].path));
    }
}

TEST(Compensator, CenterErrorForAnArcWhoseRadiiDiffer) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    const StepResult r = c.push(make_arc({10, 0}, {15, 6}, {15, 0}, true), 1, out);
    EXPECT_EQ(r.reason, Reason::kArcRadiiDiffer);
    EXPECT_EQ(r.errors, bits(ErrorBit::kCenterError));
    EXPECT_TRUE(out.empty());
}

TEST(Compensator, KorrErrorNamesTheHeldElementWhenItIsTooShortForTheCorner) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(make_line({0, 0}, {0.5, 0}), 10, out).ok());
    const StepResult r = c.push(make_line({0.5, 0}, {0.5, 5}), 11, out);
    EXPECT_EQ(r.reason, Reason::kHeldElementTooShort);
    EXPECT_EQ(r.errors, bits(ErrorBit::kKorrError));
    EXPECT_EQ(r.index, 10u);
    EXPECT_TRUE(out.empty());
    EXPECT_EQ(c.held_index(), 10u);
}

TEST(Compensator, KorrErrorNamesThePushedElementWhenItIsTooShortForTheCorner) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    const StepResult r = c.push(make_line({10, 0}, {10, 0.5}), 1, out);
    EXPECT_EQ(r.reason, Reason::kNextElementTooShort);
    EXPECT_EQ(r.errors, bits(ErrorBit::kKorrError));
    EXPECT_EQ(r.index, 1u);
}

TEST(Compensator, KorrErrorWhenTheElementDoesNotStartWhereTheHeldOneEnds) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    const StepResult r = c.push(make_line({10, 0.001}, {10, 10}), 1, out);
    EXPECT_EQ(r.reason, Reason::kDiscontinuous);
    EXPECT_EQ(r.errors, bits(ErrorBit::kKorrError));
}

TEST(Compensator, ContinuityAllowsRoundingUpToItsToleranceAndNoMore) {
    // kContinuityTolerance (1e-6): the spooler composes each start from the previous end, so
    // only rounding may part them; twice that is a gap.
    for (const double off : {0.5 * kContinuityTolerance, 2 * kContinuityTolerance}) {
        PathCompensator c;
        SegmentBatch out;
        ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
        ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
        const StepResult r = c.push(make_line({10, off}, {10, 10}), 1, out);
        if (off < kContinuityTolerance) {
            EXPECT_TRUE(r.ok()) << off;
        } else {
            EXPECT_EQ(r.reason, Reason::kDiscontinuous) << off;
            EXPECT_TRUE(out.empty());
        }
    }
}

TEST(Compensator, CalcErrorForAnUnknownElementKindChangesNothing) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    Element bad = kSquare[1];
    bad.kind = static_cast<ElementKind>(3);
    const StepResult r = c.push(bad, 1, out);
    EXPECT_EQ(r.reason, Reason::kInvalidElementKind);
    EXPECT_EQ(r.errors, bits(ErrorBit::kCalcError));
    EXPECT_TRUE(out.empty());
    EXPECT_EQ(c.held_index(), 0u);
}

TEST(Compensator, CalcErrorForCoordinatesNotFinite) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    const StepResult r = c.push(make_line({0, 0}, {NAN, 0}), 0, out);
    EXPECT_EQ(r.errors, bits(ErrorBit::kCalcError));
    EXPECT_FALSE(c.holds_element());
}

TEST(Compensator, PlaneFreeElementsWaitWithTheHeldOneAndComeOutAtItsTrimmedEnd) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1, Side::kRight), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    ASSERT_TRUE(c.push(make_line({10, 0}, {10, 0}), 1, out).ok());  // a pure Z move
    EXPECT_TRUE(out.empty());
    ASSERT_TRUE(c.push(make_line({10, 0}, {10, 0}), 2, out).ok());
    EXPECT_EQ(c.held_index(), 0u);
    ASSERT_TRUE(c.push(kSquare[1], 3, out).ok());
    ASSERT_EQ(out.size(), 4u);  // contour 0, the two waiting moves, the transition
    EXPECT_EQ(out[0].index, 0u);
    for (std::size_t k : {1u, 2u}) {
        EXPECT_EQ(out[k].role, SegmentRole::kContour);
        EXPECT_EQ(out[k].index, k);
        EXPECT_EQ(out[k].path.kind, ElementKind::kLine);
        expect_near(out[k].path.start, {10, -1});
        expect_near(out[k].path.end, {10, -1});
    }
    EXPECT_EQ(out[3].role, SegmentRole::kTransition);
}

TEST(Compensator, PlaneFreeElementsWaitAtTheInsideCornerPointWhenFinished) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    ASSERT_TRUE(c.push(make_line({10, 0}, {10, 0}), 1, out).ok());
    ASSERT_TRUE(c.push(kSquare[1], 2, out).ok());
    ASSERT_EQ(out.size(), 2u);
    expect_near(out[1].path.start, {9, 1});
    ASSERT_TRUE(c.push(make_line({10, 10}, {10, 10}), 3, out).ok());
    ASSERT_TRUE(c.finish(out).ok());
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out[1].index, 3u);
    expect_near(out[1].path.start, {9, 10});
    EXPECT_EQ(out[2].role, SegmentRole::kDeparture);
}

TEST(Compensator, PlaneFreeElementBeforeTheFirstPlaneMoveIsEmittedAtTheStartPosition) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(make_line({-5, -5}, {-5, -5}), 0, out).ok());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kApproach);
    expect_near(out[0].path.start, {-5, -5});
    expect_near(out[0].path.end, {-5, -5});
    EXPECT_FALSE(c.holds_element());
}

TEST(Compensator, KorrErrorForTooManyPlaneFreeElementsInARow) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    const Element z_move = make_line({10, 0}, {10, 0});
    for (std::uint32_t i = 1; i <= kMaxPlaneFreeElements; ++i)
        ASSERT_TRUE(c.push(z_move, i, out).ok());
    const StepResult r = c.push(z_move, 99, out);
    EXPECT_EQ(r.reason, Reason::kTooManyPlaneFreeElements);
    EXPECT_EQ(r.errors, bits(ErrorBit::kKorrError));
    // The elements that waited are all still there.
    ASSERT_TRUE(c.push(kSquare[1], 100, out).ok());
    EXPECT_EQ(out.size(), 1 + kMaxPlaneFreeElements);
}

TEST(Compensator, DiscardDropsTheHeldElementWithoutOutput) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    c.discard();
    EXPECT_FALSE(c.running());
    EXPECT_FALSE(c.holds_element());
    EXPECT_EQ(c.push(kSquare[1], 1, out).reason, Reason::kNotStarted);
    // A new begin re-approaches from the given position.
    ASSERT_TRUE(c.begin(config(1), {10, -3}).ok());
    ASSERT_TRUE(c.push(kSquare[1], 1, out).ok());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kApproach);
    expect_near(out[0].path.end, {9, 0});
}

TEST(Compensator, ZeroToolRadiusReproducesTheProgrammedPath) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(0), {0, 0}).ok());
    std::vector<Segment> path;
    const std::vector<Element> program = {make_line({0, 0}, {10, 0}),
                                          make_arc({10, 0}, {10, 10}, {10, 5}, true),
                                          make_line({10, 10}, {0, 0})};
    for (std::uint32_t i = 0; i < program.size(); ++i) {
        ASSERT_TRUE(c.push(program[i], i, out).ok());
        for (const Segment& s : out) path.push_back(s);
    }
    ASSERT_TRUE(c.finish(out).ok());
    for (const Segment& s : out) path.push_back(s);
    ASSERT_EQ(path.size(), program.size());
    for (std::size_t i = 0; i < program.size(); ++i) {
        EXPECT_EQ(path[i].role, SegmentRole::kContour);
        EXPECT_TRUE(same(path[i].path, program[i])) << i;
    }
}

TEST(Compensator, FullCircleIsCompensatedAsFullCircle) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1, Side::kLeft), {-5, 0}).ok());
    ASSERT_TRUE(c.push(make_line({-5, 0}, {0, 0}), 0, out).ok());
    // Full circle about (0, 5) starting along +x (ccw): tangent to the line, the tool inside.
    ASSERT_TRUE(c.push(make_arc({0, 0}, {0, 0}, {0, 5}, true), 1, out).ok());
    ASSERT_TRUE(c.push(make_line({0, 0}, {5, 0}), 2, out).ok());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].path.kind, ElementKind::kArc);
    EXPECT_TRUE(is_full_circle(out[0].path));
    EXPECT_NEAR(length(out[0].path), 2 * M_PI * 4, 1e-9);
}

TEST(Compensator, BatchCapacityCoversTheLargestStep) {
    // Approach, contour, every waiting plane-free element and a three-line transition.
    EXPECT_EQ(SegmentBatch::kCapacity, 2 + kMaxPlaneFreeElements + 3);
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(config(1, Side::kRight, TransitionMode::kLinear), {-5, -5}).ok());
    ASSERT_TRUE(c.push(kSquare[0], 0, out).ok());
    for (std::uint32_t i = 1; i <= kMaxPlaneFreeElements; ++i)
        ASSERT_TRUE(c.push(make_line({10, 0}, {10, 0}), i, out).ok());
    // Turning left by 150 degrees with the tool right: an outside corner with a bounded
    // linear transition of three lines.
    ASSERT_TRUE(c.push(make_line({10, 0}, {10 - 8.66, 5}), 50, out).ok());
    EXPECT_EQ(out.size(), 1 + kMaxPlaneFreeElements + 3);
}


// ---- Indirect approach (ApproachMode::kIndirect, G139)

CompensatorConfig indirect(double r, Side side = Side::kLeft) {
    CompensatorConfig c = config(r, side);
    c.approach = ApproachMode::kIndirect;
    return c;
}

TEST(Compensator, IndirectApproachIsOneLineToTheFirstElementsOffsetEnd) {
    // From (-10, -10) over (0, 0) to (20, 0), r 0.5 left: LinuxCNC's entry move ends at r left
    // of (0, 0) at right angles to the entry; then the outside corner's arc about (0, 0).
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(indirect(0.5), {-10, -10}).ok());
    ASSERT_TRUE(c.push(make_line({-10, -10}, {0, 0}), 1, out).ok());
    EXPECT_TRUE(out.empty());  // nothing before the corner is known
    ASSERT_TRUE(c.push(make_line({0, 0}, {20, 0}), 2, out).ok());
    ASSERT_EQ(out.size(), 2u);
    const double h = 0.5 / std::sqrt(2.0);
    EXPECT_EQ(out[0].role, SegmentRole::kApproach);
    EXPECT_EQ(out[0].index, 1u);
    EXPECT_TRUE(same(out[0].path, make_line({-10, -10}, {-h, h})));
    EXPECT_EQ(out[1].role, SegmentRole::kTransition);
    EXPECT_TRUE(is_arc(out[1].path));
    expect_near(out[1].path.end, {0, 0.5});
}

TEST(Compensator, IndirectApproachIntoAnInsideCornerEndsWhereTheOffsetsMeet) {
    // Entry along +x to (10, 0), then up: left compensation turns left, an inside corner; the
    // entry's offset (y = 0.5) meets the next one's (x = 9.5) at (9.5, 0.5).
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(indirect(0.5), {0, -3}).ok());
    ASSERT_TRUE(c.push(make_line({0, 0}, {10, 0}), 1, out).ok());
    ASSERT_TRUE(c.push(make_line({10, 0}, {10, 10}), 2, out).ok());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kApproach);
    EXPECT_TRUE(same(out[0].path, make_line({0, -3}, {9.5, 0.5})));
}

TEST(Compensator, IndirectApproachOfASingleElementRunsToItsOffsetEnd) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(indirect(2, Side::kRight), {0, 0}).ok());
    ASSERT_TRUE(c.push(make_line({0, 0}, {2, 0}), 7, out).ok());
    ASSERT_TRUE(c.finish(out).ok());
    // A block shorter than the tool radius still selects ([ISG-OTC-EN]'s wr_quad_disc.nc).
    ASSERT_GE(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kApproach);
    EXPECT_TRUE(same(out[0].path, make_line({0, 0}, {2, -2})));
}

TEST(Compensator, IndirectApproachShorterThanItsInsideCornerEndsBackWhereTheOffsetsMeet) {
    // A selection block of 1 mm with r 5, then up: the offsets y = 5 and x = -4 meet 4 mm behind
    // the block's offset start. The approach comes from the tool, so it runs there; nothing is
    // too short.
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(indirect(5), {0, 0}).ok());
    ASSERT_TRUE(c.push(make_line({0, 0}, {1, 0}), 1, out).ok());
    const StepResult r = c.push(make_line({1, 0}, {1, 20}), 2, out);
    ASSERT_TRUE(r.ok()) << reason_name(r.reason);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kApproach);
    EXPECT_TRUE(same(out[0].path, make_line({0, 0}, {-4, 5})));
}

TEST(Compensator, IndirectApproachByAnArcArrivesAlongTheOffsetArc) {
    // A quarter arc from (0, 0) about (0, 10) counter-clockwise to (10, 10), r 1 right (the tool
    // outside): the offset end is (11, 10); the entry arc from (0, 0) has its centre on the line
    // from (11, 10) to (0, 10), as far from (0, 0) as from (11, 10): (0.5, 10), radius 10.5...
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(indirect(1, Side::kRight), {0, 0}).ok());
    ASSERT_TRUE(c.push(make_arc({0, 0}, {10, 10}, {0, 10}, true), 1, out).ok());
    ASSERT_TRUE(c.finish(out).ok());
    ASSERT_GE(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kApproach);
    ASSERT_TRUE(is_arc(out[0].path));
    EXPECT_TRUE(out[0].path.ccw);
    expect_near(out[0].path.start, {0, 0});
    expect_near(out[0].path.end, {11, 10});
    const Vec2 centre = out[0].path.centre;
    // ... on that line, equidistant from both ends.
    EXPECT_NEAR(centre.y(), 10.0, kEps);
    EXPECT_NEAR((centre - Vec2(0, 0)).norm(), (centre - Vec2(11, 10)).norm(), 1e-9);
}

TEST(Compensator, IndirectApproachConfigIsCheckedLikeTheOthers) {
    PathCompensator c;
    CompensatorConfig bad = indirect(1);
    bad.approach = static_cast<ApproachMode>(5);
    EXPECT_EQ(c.begin(bad, {0, 0}).reason, Reason::kInvalidSetting);
    EXPECT_FALSE(c.running());
}

// ---- Direct approach (ApproachMode::kDirect, G138, [ISG-PROG]'s direct selection)

CompensatorConfig direct(double r, Side side = Side::kLeft) {
    CompensatorConfig c = config(r, side);
    c.approach = ApproachMode::kDirect;
    return c;
}

TEST(Compensator, DirectApproachRunsStraightToTheNextElementsOffsetStart) {
    // From (-10, -10) over (0, 0) to (20, 0), r 0.5 left: the selection block runs straight to
    // r left of (0, 0) at right angles to the next element, (0, 0.5), with no corner (a kink).
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(direct(0.5), {-10, -10}).ok());
    ASSERT_TRUE(c.push(make_line({-10, -10}, {0, 0}), 1, out).ok());
    EXPECT_TRUE(out.empty());
    ASSERT_TRUE(c.push(make_line({0, 0}, {20, 0}), 2, out).ok());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kApproach);
    EXPECT_EQ(out[0].index, 1u);
    EXPECT_TRUE(same(out[0].path, make_line({-10, -10}, {0, 0.5})));
    ASSERT_TRUE(c.finish(out).ok());
    ASSERT_GE(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kContour);
    EXPECT_TRUE(same(out[0].path, make_line({0, 0.5}, {20, 0.5})));
}

TEST(Compensator, DirectApproachOntoAnArcEndsAtTheArcsOffsetStart) {
    // Then a quarter arc about (0, 10) counter-clockwise, r 1 left (inside): its offset starts at
    // (0, 1).
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(direct(1), {-5, -5}).ok());
    ASSERT_TRUE(c.push(make_line({-5, -5}, {0, 0}), 1, out).ok());
    ASSERT_TRUE(c.push(make_arc({0, 0}, {10, 10}, {0, 10}, true), 2, out).ok());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(same(out[0].path, make_line({-5, -5}, {0, 1})));
}

TEST(Compensator, DirectApproachOfASingleElementRunsToItsOffsetEnd) {
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(direct(2, Side::kRight), {0, 0}).ok());
    ASSERT_TRUE(c.push(make_line({0, 0}, {2, 0}), 7, out).ok());
    ASSERT_TRUE(c.finish(out).ok());
    ASSERT_GE(out.size(), 1u);
    EXPECT_EQ(out[0].role, SegmentRole::kApproach);
    EXPECT_TRUE(same(out[0].path, make_line({0, 0}, {2, -2})));
}

TEST(Compensator, DirectSelectionOnAnArcIsKorrError) {
    // [ISG-PROG]: approach blocks are built on lines only.
    PathCompensator c;
    SegmentBatch out;
    ASSERT_TRUE(c.begin(direct(1), {0, 0}).ok());
    const StepResult r = c.push(make_arc({0, 0}, {10, 10}, {0, 10}, true), 3, out);
    EXPECT_EQ(r.reason, Reason::kDirectSelectionOnAnArc);
    EXPECT_EQ(r.errors, bits(ErrorBit::kKorrError));
    EXPECT_EQ(r.index, 3u);
    EXPECT_TRUE(out.empty());
    // Nothing changed: a line is taken after it.
    ASSERT_TRUE(c.push(make_line({0, 0}, {10, 0}), 4, out).ok());
}

}  // namespace
}  // namespace rwmos::geom
