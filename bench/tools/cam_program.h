// SPDX-License-Identifier: MIT
// A deterministic program shaped as CAM post-processors write "compensation in control"
// (G41, tool radius 1 mm), as a program for `apcictl run` (our DIN dialect) and the same path as a
// program for LinuxCNC's `rs274` (G21, T1 M6), beside the star of contour_program.h and the walk
// of walk_program.h (the same tool list and table). Used by bench/tools/rs274_bench.cpp.
//
// Profiles (bosses, milled from outside) placed apart on a grid of 60 mm, each new in its size
// and shape, none repeated: rounded rectangles (70 %), hexagons with rounded corners (10 %),
// slots (10 %) and circles (10 %), 8 to 36 mm across, fillets 2 to 5 mm. Each as CAM writes it:
// a rapid beside the part, a plunge, G41 on a straight lead-in, a tangent quarter arc onto the
// contour at the middle of its top (a circle: its top), the closed contour clockwise (the tool
// outside), a tangent quarter arc off it, G40 on a straight lead-out, a retract; the leads
// tangent to the contour's first element where they meet it. Coordinates with 3 decimals, arc
// centres (I, J) with 4. The profile count sets the length: 6,000 make about 86,000 blocks.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "contour_program.h"

namespace apci::bench {

// The seed of the benchmark's CAM program.
inline constexpr std::uint64_t kCamSeed = 27;

// The grid's pitch (mm) and columns; the lead-in and lead-out arcs' radius and lines' length.
inline constexpr double kCamPitch = 60.0;
inline constexpr int kCamColumns = 80;
inline constexpr double kCamLeadRadius = 3.0;
inline constexpr double kCamLeadLine = 4.0;

namespace detail {

// A move of a profile's contour: a line, or an arc (G2 clockwise / G3) about (cx, cy).
struct CamMove {
    bool arc = false;
    bool ccw = false;
    double x = 0.0, y = 0.0;    // end
    double cx = 0.0, cy = 0.0;  // centre (arcs)
};

// The contour of a profile, clockwise, from the middle of its top (sx, top) back to it: its
// moves after that start point. The shape and its size from rnd.
inline std::vector<CamMove> cam_contour(Random& rnd, double x0, double y0, double& sx,
                                        double& top) {
    std::vector<CamMove> m;
    sx = x0;
    const double pick = rnd.unit();
    const auto r3 = [](double v) { return round_to(v, 1e3); };
    if (pick < 0.1) {  // a circle: one full clockwise arc from its top
        const double radius = r3(4.0 + 14.0 * rnd.unit());
        top = r3(y0 + radius);
        m.push_back({true, false, x0, top, x0, y0});
        return m;
    }
    if (pick < 0.2) {  // a slot: two lines and two half circles
        const double half = r3(4.0 + 10.0 * rnd.unit());    // of its straight part
        const double radius = r3(3.0 + 5.0 * rnd.unit());  // its ends
        top = r3(y0 + radius);
        const double bottom = r3(y0 - radius);
        m.push_back({false, false, r3(x0 + half), top, 0, 0});
        m.push_back({true, false, r3(x0 + half), bottom, r3(x0 + half), y0});
        m.push_back({false, false, r3(x0 - half), bottom, 0, 0});
        m.push_back({true, false, r3(x0 - half), top, r3(x0 - half), y0});
        m.push_back({false, false, x0, top, 0, 0});
        return m;
    }
    // A polygon of n corners about (x0, y0), its corners rounded with radius f: each corner's
    // arc tangent to both sides. A rectangle (n = 4, half sizes a, b) or a regular hexagon.
    const bool hexagon = pick < 0.3;
    const double f = r3(2.0 + 3.0 * rnd.unit());
    std::vector<std::pair<double, double>> corners;  // clockwise from the top right
    if (hexagon) {
        const double radius = 9.0 + 9.0 * rnd.unit();
        const double turn = rnd.unit() * 0.5;  // a turned hexagon: no edge parallel to another's
        for (int k = 0; k < 6; ++k) {
            const double a = 1.5 - turn - k * (2.0 * 3.14159265358979323846 / 6.0);
            corners.emplace_back(x0 + radius * std::cos(a), y0 + radius * std::sin(a));
        }
    } else {
        const double a = 5.0 + 13.0 * rnd.unit(), b = 5.0 + 13.0 * rnd.unit();
        corners = {{x0 + a, y0 + b}, {x0 + a, y0 - b}, {x0 - a, y0 - b}, {x0 - a, y0 + b}};
    }
    const std::size_t n = corners.size();
    // Where the rounding of corner k starts and ends, and its centre: at distance f / tan(half
    // the turn) from the corner along each side.
    struct Round {
        double sx, sy, ex, ey, cx, cy;
    };
    std::vector<Round> rounds(n);
    for (std::size_t k = 0; k < n; ++k) {
        const auto [px, py] = corners[(k + n - 1) % n];
        const auto [qx, qy] = corners[k];
        const auto [nx, ny] = corners[(k + 1) % n];
        double ux = qx - px, uy = qy - py, vx = nx - qx, vy = ny - qy;
        const double lu = std::hypot(ux, uy), lv = std::hypot(vx, vy);
        ux /= lu, uy /= lu, vx /= lv, vy /= lv;
        const double turn = std::acos(std::clamp(ux * vx + uy * vy, -1.0, 1.0));
        const double d = f * std::tan(turn / 2.0);
        // Clockwise: the centre lies to the right of the direction of travel.
        const double sx = qx - d * ux, sy = qy - d * uy;
        rounds[k] = {r3(sx), r3(sy), r3(qx + d * vx), r3(qy + d * vy), sx + f * uy, sy - f * ux};
    }
    // The middle of the top side: from the last corner (top left) to the first (top right)
    // for a rectangle; a hexagon's side between its last and first corner.
    const Round& last = rounds[n - 1];
    const Round& first = rounds[0];
    const double mx = r3((last.ex + first.sx) / 2.0), my = r3((last.ey + first.sy) / 2.0);
    sx = mx;
    top = my;
    for (std::size_t k = 0; k < n; ++k) {
        const Round& r = rounds[k];
        m.push_back({false, false, r.sx, r.sy, 0, 0});
        m.push_back({true, false, r.ex, r.ey, r.cx, r.cy});
    }
    m.push_back({false, false, mx, my, 0, 0});
    return m;
}

}  // namespace detail

// The CAM-shaped program of `profiles` profiles (at most kCamColumns * kCamColumns).
inline ContourProgram cam_program(std::size_t profiles, Dialect dialect,
                                  std::uint64_t seed = kCamSeed) {
    using detail::append_number;
    using detail::round_to;
    ContourProgram p;
    detail::ProgramText w{p, dialect == Dialect::kApcictl};
    detail::Random rnd{seed};
    const bool ours = dialect == Dialect::kApcictl;
    if (ours) {
        p.text += "%cam.nc\n";
        w.begin() += "G17 G90 G26 F3000 D1\n";
    } else {
        p.text += "G21 G17 G90 G40 G49 G64\nT1 M6\nF3000\n";
        w.n += 3;
    }
    const auto xy = [](std::string& s, double x, double y) {
        s += 'X';
        append_number(s, x);
        s += " Y";
        append_number(s, y);
    };
    const auto arc = [&](std::string& s, bool ccw, double sx, double sy, double x, double y,
                         double cx, double cy) {
        s += ccw ? "G3 " : "G2 ";
        xy(s, x, y);
        s += " I";
        append_number(s, round_to(cx - sx, 1e4));
        s += " J";
        append_number(s, round_to(cy - sy, 1e4));
        s += '\n';
    };
    const double lr = kCamLeadRadius, ll = kCamLeadLine;
    for (std::size_t k = 0; k < profiles; ++k) {
        const double x0 = static_cast<double>(k % kCamColumns) * kCamPitch;
        const std::size_t row = k / kCamColumns;  // whole rows before it
        const double y0 = static_cast<double>(row) * kCamPitch;
        double sx = 0.0, top = 0.0;  // the contour's start: the middle of its top
        const std::vector<detail::CamMove> contour = detail::cam_contour(rnd, x0, y0, sx, top);
        // The direction (dx, dy) of the contour at its start and the tool's side (nx, ny): the
        // leads are tangent quarter arcs about (sx, top) + lr (nx, ny), reached and left along
        // the tool's side.
        const detail::CamMove& first = contour.front();
        double dx = 1.0, dy = 0.0;
        if (!first.arc) {
            dx = first.x - sx, dy = first.y - top;
            const double len = std::hypot(dx, dy);
            dx /= len, dy /= len;
        }
        const double nx = -dy, ny = dx;
        const double cx = sx + lr * nx, cy = top + lr * ny;
        const double inx = round_to(cx - lr * dx, 1e3), iny = round_to(cy - lr * dy, 1e3);
        const double outx = round_to(cx + lr * dx, 1e3), outy = round_to(cy + lr * dy, 1e3);
        // Rapid beside the part, plunge, G41 on the lead-in line, the quarter arc onto (sx, top).
        std::string& rapid = w.begin();
        rapid += "G0 ";
        xy(rapid, round_to(inx + ll * nx, 1e3), round_to(iny + ll * ny, 1e3));
        rapid += '\n';
        w.begin() += "G1 Z-2\n";
        std::string& in = w.begin();
        in += "G41 G1 ";
        xy(in, inx, iny);
        in += '\n';
        arc(w.begin(), true, inx, iny, sx, top, cx, cy);
        double px = sx, py = top;
        for (const detail::CamMove& m : contour) {
            std::string& s = w.begin();
            if (m.arc) {
                arc(s, m.ccw, px, py, m.x, m.y, m.cx, m.cy);
            } else {
                s += "G1 ";
                xy(s, m.x, m.y);
                s += '\n';
            }
            px = m.x, py = m.y;
        }
        // The quarter arc off it, G40 on the lead-out line, the retract.
        arc(w.begin(), true, sx, top, outx, outy, cx, cy);
        std::string& out = w.begin();
        out += "G40 G1 ";
        xy(out, round_to(outx + ll * nx, 1e3), round_to(outy + ll * ny, 1e3));
        out += '\n';
        w.begin() += "G0 Z5\n";
    }
    w.begin() += ours ? "M30\n" : "M2\n";
    p.blocks = w.n;
    return p;
}

}  // namespace apci::bench
