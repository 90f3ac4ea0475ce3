// SPDX-License-Identifier: MIT
// The two sides of the differential test: a contour written as an NC program in our dialect
// and as LinuxCNC G-code, run on the embedded emulator (as `apcictl run` does) and by rs274,
// and the comparison of the two tool-centre paths. docs/testing.md ("The LinuxCNC
// differential test") states the rules.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "apci/nc/tools.h"
#include "apci/run/executor.h"
#include "contours.h"
#include "rwmos/geometry/shared.h"

namespace apci::test {

// A compensated contour with its lead-in and lead-out, in the plane's coordinates (first,
// second): G17 (X, Y), G18 (Z, X), G19 (Y, Z; our dialect only, LinuxCNC has no G19). The
// program: rapid to `start`, G41/G42 with a line to
// `entry_end` (the selection block), then `elements` (the lead-in line, the contour, the
// lead-out line), then G40 with a line to `exit_end` (the deselection block).
struct DiffProgram {
    std::uint64_t seed = 0;
    int plane = 17;
    bool left = true;     // G41, else G42
    double r = 1.0;       // tool radius, mm
    int decimals = 3;     // coordinates and I/J/K are written with this many decimals
    bool linear = false;  // G25 (our dialect only; LinuxCNC has no linear transition)
    Vec2 start = Vec2::Zero();
    Vec2 entry_end = Vec2::Zero();
    std::vector<Element> elements;  // as written: coordinates already rounded
    Vec2 exit_end = Vec2::Zero();
};

std::string our_program(const DiffProgram& p);      // DIN 66025 for apcictl run
std::string our_tool_list(double radius_mm);        // wz[1] with that radius
std::string linuxcnc_program(const DiffProgram& p);  // RS274/NGC for rs274, G21

// An NC program's text (named `name` in messages) run with `tools` through the executor of
// `apcictl run` on a fresh embedded board, the executed segments to `sink`. `error` says what
// stopped it before it ran (no board, a program the front end refuses); else `outcome`.
struct EmulatorRun {
    std::string error;
    apci::run::RunOutcome outcome;
};
EmulatorRun run_on_emulator(std::string_view text, const std::string& name,
                            const apci::nc::ToolTable& tools, apci::run::RunSink& sink);

// Our side: the program run on the embedded emulator through the executor of `apcictl run`.
struct OurRun {
    bool ok = false;
    std::string error;  // the first error's code and message
    std::uint64_t error_line = 0;  // the program line of the block at fault
    std::vector<Element> path;  // every executed segment, plane coordinates, in order
    std::vector<int> roles;     // apci::run::Role of each
    std::vector<std::uint64_t> lines;  // the program line of each (its block)
    bool self_approach = false;  // the run warned that the path comes near the contour
};
OurRun run_ours(const DiffProgram& p);

// The part of a path between the first point within `tol` of `from` and the last point within
// `tol` of `to` (split elements where those points lie). Empty when either is not on it.
std::vector<Element> window(const std::vector<Element>& path, const Vec2& from, const Vec2& to,
                            double tol);

// The Hausdorff distance between two paths, sampled at most `spacing` apart and at every
// element's ends (each sample's distance to the other path is exact). Where two such paths
// differ, they differ at a corner (an element's end) or smoothly between: the samples see it.
double hausdorff(const std::vector<Element>& a, const std::vector<Element>& b, double spacing);

// The least distance from any sample of `path` (as above) to the contour; exact up to r + 0.01
// (farther samples count as at least that).
double clearance(const std::vector<Element>& path, const std::vector<Element>& contour, double r,
                 double spacing);

}  // namespace apci::test
