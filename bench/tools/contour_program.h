// SPDX-License-Identifier: MIT
// A deterministic radius-compensated (G41, tool radius 1 mm) contour of lines and arcs, as
// a program for `apcictl run` (our DIN dialect, with its tool list) and the same path as a
// program for LinuxCNC's `rs274` (G21, T1 M6). Used by bench/tools/rs274_bench.cpp and to
// make the contour fixture of tests/golden.
//
// A turn goes once counter-clockwise round a star of 24 vertices about (50, 50), radius
// 34..46 mm (3 decimals), starting and ending at (90, 50); the tool is on the inside (G41).
// Every turn is the same star (made once from a fixed seed), so the contour comes back only
// onto itself, never near itself (no SelfApproach warning, no tool too large for a corner).
// Between two vertices: a line (55 %), an arc tangent to the element before (25 %; a line if
// such an arc would be too tight or too flat), or an arc with its centre off the chord, bulging
// out (G3) or in (G2), joining the element before at a corner (20 %). Arc centres have 4
// decimals. The first element of a turn is a line that lowers Z by 0.01 mm (cycling over 100
// turns), so the program stays in range however long. Lines, tangent and corner joins, G2
// and G3 of the seed's turn: 10 lines, 6 G2, 8 G3.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace apci::bench {

enum class Dialect { kApcictl, kLinuxCnc };

struct ContourProgram {
    std::string text;
    std::size_t blocks = 0;  // blocks (lines with a word) of the program
};

// The tool list for `apcictl run --tools`: D1, radius 1 mm.
inline const char* contour_tools() {
    return "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 1\nwz[1].laenge 0\n";
}

// The tool table for `rs274 -t` (inches, diameter): T1 P1, radius 1 mm.
inline std::string contour_rs274_tool_table() {
    char line[96];
    std::snprintf(line, sizeof line, "T1 P1 D%.15f ;tool radius 1 mm\n", 2.0 / 25.4);
    return line;
}

namespace detail {

// splitmix64: the same sequence everywhere.
struct Random {
    std::uint64_t state;
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1).
    double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
};

inline double round_to(double v, double scale) {
    const double r = std::round(v * scale) / scale;
    return r == 0.0 ? 0.0 : r;  // no "-0"
}

// Shortest fixed text of a value with at most 4 decimals: 40, 40.5, -3.1416.
inline void append_number(std::string& out, double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4f", v);
    std::string s = text;
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
    if (s == "-0") s = "0";
    out += s;
}

// A program's text block by block: N numbers in our dialect (rs274's blocks are counted, not
// numbered), the set-up up to G41 and the end.
struct ProgramText {
    ContourProgram& program;
    bool ours;
    std::size_t n = 0;  // blocks written
    // The next block's text, its N number written.
    std::string& begin() {
        ++n;
        if (ours) {
            program.text += 'N';
            program.text += std::to_string(n);
            program.text += ' ';
        }
        return program.text;
    }
    // "%name.nc" and the set-up block (ours) or rs274's set-up lines, the rapid to the start
    // (`rapid`, a block's text) and G41.
    void header(const char* name, const std::string& rapid) {
        if (ours) {
            program.text += '%';
            program.text += name;
            program.text += ".nc\n";
            begin() += "G17 G90 G26 F3000 D1\n";
        } else {
            program.text += "G21 G17 G90 G40 G49 G64\nT1 M6\nF3000\n";
            n += 3;
        }
        begin() += rapid + '\n';
        begin() += "G41\n";
    }
    // G40 and the program's end.
    void footer() {
        begin() += "G40\n";
        begin() += ours ? "M30\n" : "M2\n";
        program.blocks = n;
    }
};

}  // namespace detail

// One turn: the 24 elements from (90, 50) round to (90, 50), the first a line (its Z added by
// the caller). The same for every turn, so the contour only ever comes back onto itself.
inline std::vector<std::string> contour_turn(std::uint64_t seed) {
    using detail::append_number;
    using detail::round_to;
    constexpr int kVertices = 24;
    constexpr double kPi = 3.14159265358979323846;
    constexpr double kCx = 50.0, kCy = 50.0;
    detail::Random rnd{seed};
    std::vector<std::string> turn;
    double px = 90.0, py = 50.0;  // where the path is
    double tx = 0.0, ty = 1.0;    // its direction there (unit)
    for (int k = 1; k <= kVertices; ++k) {
        double qx = 90.0, qy = 50.0;
        if (k < kVertices) {
            const double a = (k + (rnd.unit() - 0.5) * 0.4) * 2.0 * kPi / kVertices;
            const double r = 34.0 + 12.0 * rnd.unit();
            qx = round_to(kCx + r * std::cos(a), 1e3);
            qy = round_to(kCy + r * std::sin(a), 1e3);
        }
        const double dx = qx - px, dy = qy - py;
        const double chord = std::hypot(dx, dy);
        const double pick = rnd.unit();
        double cx = 0.0, cy = 0.0;
        bool arc = false;
        if (k > 1 && pick >= 0.45 && pick < 0.7) {
            // Tangent: the circle touching the direction (tx, ty) at P through Q.
            const double nx = -ty, ny = tx;
            const double along = nx * dx + ny * dy;
            if (std::fabs(along) > 1e-9) {
                const double rho = (dx * dx + dy * dy) / (2.0 * along);
                if (std::fabs(rho) >= 6.0 && std::fabs(rho) <= 150.0) {
                    cx = round_to(px + rho * nx, 1e4);
                    cy = round_to(py + rho * ny, 1e4);
                    arc = true;
                }
            }
        } else if (k > 1 && pick >= 0.7) {
            // Off the chord by 0.3..1.2 chords, left (G3, bulging out) or right (G2, in).
            const double side = rnd.unit() < 0.5 ? 1.0 : -1.0;
            const double h = side * (0.3 + 0.9 * rnd.unit());
            cx = round_to(px + dx / 2.0 - dy * h, 1e4);
            cy = round_to(py + dy / 2.0 + dx * h, 1e4);
            arc = true;
        }
        std::string s;
        if (arc) {
            const bool ccw = (dx * (cy - py) - dy * (cx - px)) > 0.0;  // centre on the left
            s += ccw ? "G3 X" : "G2 X";
            append_number(s, qx);
            s += " Y";
            append_number(s, qy);
            s += " I";
            append_number(s, round_to(cx - px, 1e4));
            s += " J";
            append_number(s, round_to(cy - py, 1e4));
            // The direction at Q: perpendicular to the radius, in the sense of travel.
            const double rx = qx - cx, ry = qy - cy, rl = std::hypot(rx, ry);
            tx = ccw ? -ry / rl : ry / rl;
            ty = ccw ? rx / rl : -rx / rl;
        } else {
            s += "G1 X";
            append_number(s, qx);
            s += " Y";
            append_number(s, qy);
            tx = dx / chord;
            ty = dy / chord;
        }
        turn.push_back(s);
        px = qx;
        py = qy;
    }
    return turn;
}

// The seed of the turn: one whose compensated path `apcictl run` and `rs274` both accept
// without an error or a warning (no inside corner too tight for the tool, no self-approach).
inline constexpr std::uint64_t kContourSeed = 4;

// The program of about `blocks` blocks (whole turns; at least the header and the footer).
inline ContourProgram contour_program(std::size_t blocks, Dialect dialect,
                                      std::uint64_t seed = kContourSeed) {
    const std::vector<std::string> turn = contour_turn(seed);
    ContourProgram p;
    p.text.reserve(blocks * 32);
    detail::ProgramText w{p, dialect == Dialect::kApcictl};
    w.header("contour", "G0 X90 Y50 Z0");
    constexpr std::size_t kFooter = 2;
    for (std::size_t t = 0; w.n + turn.size() + kFooter <= blocks; ++t) {
        for (std::size_t k = 0; k < turn.size(); ++k) {
            std::string& s = w.begin();
            s += turn[k];
            if (k == 0) {
                s += " Z";
                detail::append_number(s, -static_cast<double>(t % 100) * 0.01);
            }
            s += '\n';
        }
    }
    w.footer();
    return p;
}

}  // namespace apci::bench
