// SPDX-License-Identifier: MIT
// A deterministic radius-compensated (G41, tool radius 1 mm) walk of lines and arcs that never
// repeats itself, as a program for `apcictl run` (our DIN dialect) and the same path as a
// program for LinuxCNC's `rs274` (G21, T1 M6), beside the repeating star of contour_program.h
// (the same tool list and table). Used by bench/tools/rs274_bench.cpp.
//
// The walk starts at (-80000, 0) and goes along +X, each element 1.0 .. 1.8 mm long, drawn as a
// line at a corner (30 % of the draws), a line tangent to the element before (10 %), an arc
// tangent to the element before (25 %, radius 4 .. 40 mm), or an arc at a corner (35 %, radius
// 2 .. 5 chords and at least 3 mm, G2 or G3). Coordinates have 3 decimals, arc centres (I, J) 4.
// Every element's direction stays within 0.75 rad of +X, so the path only ever moves on along X and
// never comes back near itself (no SelfApproach warning); its heading is pulled toward Y = 0, and Y
// stays within +-40 mm. Lines carry Z, lowered by 0.001 mm every 50 elements (cycling over 1,000
// steps), so the program stays in range however long. An element whose join or heading would
// break one of these rules is drawn again (after 32 draws: a line tangent to the one
// before, which breaks none).
//
// Joins: a corner turns by 0.06 .. 0.75 rad. Never less: LinuxCNC's interpreter reads a turn
// under 0.05 rad as tangent and joins it without a transition, so an inside arc after a slight
// outside corner starts before its programmed start on the offset circle; when that reaches
// back more than 0.0254 rad it refuses the arc with "Arc move in concave corner cannot be
// reached by the tool without gouging", though the corner is an outside one and the TC
// ([APCI-TC]) runs it without gouging (docs/compensation.md, "Agreement with LinuxCNC").
// Tangent joins are tangent up to the rounding of the numbers (about 1e-3 rad at most).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "contour_program.h"

namespace apci::bench {

// The seed of the benchmark's walk.
inline constexpr std::uint64_t kWalkSeed = 11;

// The most blocks a walk may have: it runs along +X from -80000 mm, about 1.35 mm a block, and
// must stay inside the board's coordinate range of +-100000 mm.
inline constexpr std::size_t kWalkMaxBlocks = 120'000;

// The blocks a walk program has besides its elements: G17 .., G0, G41 before, G40 and M30 (M2)
// after (our dialect's count).
inline constexpr std::size_t kWalkFrameBlocks = 5;

namespace detail {

inline constexpr double kWalkStartX = -80'000.0;
inline constexpr double kWalkPi = 3.14159265358979323846;
inline constexpr double kWalkMaxHeading = 0.75;  // rad from +X, every element's direction
inline constexpr double kWalkMinCorner = 0.06;   // rad, the least turn at a corner
inline constexpr double kWalkMaxCorner = 0.75;   // rad, the largest turn at a corner
inline constexpr double kWalkMaxY = 40.0;        // mm

// The angle in (-pi, pi].
inline double wrap_angle(double a) {
    while (a > kWalkPi) a -= 2.0 * kWalkPi;
    while (a <= -kWalkPi) a += 2.0 * kWalkPi;
    return a;
}

// One element of the walk as written (rounded) and its directions at start and end, read from
// the rounded numbers as an interpreter reads them.
struct WalkElement {
    bool arc = false;
    bool ccw = false;
    bool tangent = false;     // made tangent to the element before
    double x = 0.0, y = 0.0;  // end
    double i = 0.0, j = 0.0;  // centre relative to the start (arcs)
    double start_heading = 0.0;
    double end_heading = 0.0;
};

// The direction of travel on a circle about (cx, cy) at (x, y).
inline double arc_heading(double cx, double cy, double x, double y, bool ccw) {
    return std::atan2(y - cy, x - cx) + (ccw ? kWalkPi / 2.0 : -kWalkPi / 2.0);
}

// An arc from (px, py) to (qx, qy) about (px + i, py + j), all rounded.
inline WalkElement make_walk_arc(double px, double py, double qx, double qy, double i, double j,
                                 bool ccw, bool tangent) {
    WalkElement e;
    e.arc = true;
    e.ccw = ccw;
    e.tangent = tangent;
    e.x = round_to(qx, 1e3);
    e.y = round_to(qy, 1e3);
    e.i = round_to(i, 1e4);
    e.j = round_to(j, 1e4);
    e.start_heading = wrap_angle(arc_heading(px + e.i, py + e.j, px, py, ccw));
    e.end_heading = wrap_angle(arc_heading(px + e.i, py + e.j, e.x, e.y, ccw));
    return e;
}

inline WalkElement make_walk_line(double px, double py, double qx, double qy, bool tangent) {
    WalkElement e;
    e.tangent = tangent;
    e.x = round_to(qx, 1e3);
    e.y = round_to(qy, 1e3);
    e.start_heading = e.end_heading = std::atan2(e.y - py, e.x - px);
    return e;
}

// Whether an element may follow a path at (px, py) heading `heading` (`first`: there is no
// element before, so no join).
inline bool walk_element_ok(const WalkElement& e, double heading, bool first) {
    if (std::fabs(e.start_heading) > kWalkMaxHeading ||
        std::fabs(e.end_heading) > kWalkMaxHeading || std::fabs(e.y) > kWalkMaxY)
        return false;
    if (first || e.tangent) return true;
    const double turn = std::fabs(wrap_angle(e.start_heading - heading));
    return turn >= kWalkMinCorner && turn <= kWalkMaxCorner;
}

// Draws one element from (px, py), the path heading `heading` there.
inline WalkElement draw_walk_element(Random& rnd, double px, double py, double heading,
                                     bool first) {
    const double length = 1.0 + 0.8 * rnd.unit();
    const double pick = rnd.unit();
    // Toward Y = 0: the farther off, the stronger the pull.
    const double steer = std::fmax(-0.3, std::fmin(0.3, -py * 0.02));
    if (first || pick < 0.30) {
        const double h = steer + (rnd.unit() - 0.5) * 1.2;
        return make_walk_line(px, py, px + length * std::cos(h), py + length * std::sin(h), false);
    }
    if (pick < 0.40) {
        return make_walk_line(px, py, px + length * std::cos(heading),
                              py + length * std::sin(heading), true);
    }
    if (pick < 0.65) {
        // Tangent: a circle touching the heading at P, on its left (G3) or right (G2).
        const bool ccw = rnd.unit() < 0.5;
        const double rho = 4.0 + 36.0 * rnd.unit();
        const double side = ccw ? 1.0 : -1.0;
        const double nx = -std::sin(heading) * side, ny = std::cos(heading) * side;
        const double cx = px + rho * nx, cy = py + rho * ny;
        const double a = std::atan2(py - cy, px - cx) + side * length / rho;
        return make_walk_arc(px, py, cx + rho * std::cos(a), cy + rho * std::sin(a), cx - px,
                             cy - py, ccw, true);
    }
    // At a corner: a chord along `h`, the centre off it on the left (G3) or right (G2).
    const double h = steer + (rnd.unit() - 0.5) * 1.0;
    const bool ccw = rnd.unit() < 0.5;
    const double radius = std::fmax(3.0, length * (2.0 + 3.0 * rnd.unit()));
    const double qx = px + length * std::cos(h), qy = py + length * std::sin(h);
    const double half = length / 2.0;
    const double off = std::sqrt(radius * radius - half * half) * (ccw ? 1.0 : -1.0);
    const double cx = (px + qx) / 2.0 - std::sin(h) * off;
    const double cy = (py + qy) / 2.0 + std::cos(h) * off;
    return make_walk_arc(px, py, qx, qy, cx - px, cy - py, ccw, false);
}

// The next element: drawn until it keeps the rules, at most 32 times, then a tangent line.
inline WalkElement next_walk_element(Random& rnd, double px, double py, double heading,
                                     bool first) {
    for (int attempt = 0; attempt < 32; ++attempt) {
        const WalkElement e = draw_walk_element(rnd, px, py, heading, first);
        if (walk_element_ok(e, heading, first)) return e;
    }
    return make_walk_line(px, py, px + 1.4 * std::cos(heading), py + 1.4 * std::sin(heading), true);
}

}  // namespace detail

// The walk's elements (G1 .. Z.., G2/G3 .. I.. J..) from (-80000, 0), `count` of them.
inline std::vector<std::string> walk_elements(std::size_t count, std::uint64_t seed = kWalkSeed) {
    using detail::append_number;
    detail::Random rnd{seed};
    std::vector<std::string> out;
    out.reserve(count);
    double px = detail::kWalkStartX, py = 0.0, heading = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
        const detail::WalkElement e = detail::next_walk_element(rnd, px, py, heading, k == 0);
        std::string s = e.arc ? (e.ccw ? "G3 X" : "G2 X") : "G1 X";
        append_number(s, e.x);
        s += " Y";
        append_number(s, e.y);
        if (e.arc) {
            s += " I";
            append_number(s, e.i);
            s += " J";
            append_number(s, e.j);
        } else {
            s += " Z";
            append_number(s, -static_cast<double>((k / 50) % 1000) * 0.001);
        }
        out.push_back(std::move(s));
        px = e.x;
        py = e.y;
        heading = e.end_heading;
    }
    return out;
}

// The walk program of `blocks` blocks in our dialect (its elements: blocks - kWalkFrameBlocks;
// the rs274 program has the same elements). `blocks`: kWalkFrameBlocks + 1 .. kWalkMaxBlocks
// (fewer or more give an empty program).
inline ContourProgram walk_program(std::size_t blocks, Dialect dialect,
                                   std::uint64_t seed = kWalkSeed) {
    ContourProgram p;
    if (blocks <= kWalkFrameBlocks || blocks > kWalkMaxBlocks) return p;
    const std::vector<std::string> elements = walk_elements(blocks - kWalkFrameBlocks, seed);
    p.text.reserve(blocks * 36);
    detail::ProgramText w{p, dialect == Dialect::kApcictl};
    std::string rapid = "G0 X";
    detail::append_number(rapid, detail::kWalkStartX);
    rapid += " Y0 Z0";
    w.header("walk", rapid);
    for (const std::string& e : elements) {
        std::string& s = w.begin();
        s += e;
        s += '\n';
    }
    w.footer();
    return p;
}

}  // namespace apci::bench
