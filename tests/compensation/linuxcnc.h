// SPDX-License-Identifier: MIT
// LinuxCNC's standalone interpreter rs274 as an independent implementation of tool radius
// compensation: found where scripts/fetch_linuxcnc.sh unpacked Debian's linuxcnc-uspace,
// run on many programs at once (one process each, several in flight), its canonical moves
// parsed into plane elements. docs/testing.md ("The LinuxCNC differential test").
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rwmos/geometry/shared.h"

namespace apci::test {

// Where rs274 and its libraries are; empty `why` when it can be run.
struct Rs274 {
    std::string binary;        // .../usr/bin/rs274
    std::string library_path;  // LD_LIBRARY_PATH for it
    std::string ncfiles;       // .../usr/share/linuxcnc/ncfiles (its example programs)
    std::string why;           // why rs274 cannot be had (the test skips with it)
};
// Looks under `root` (the unpacked packages), and runs a trivial program once.
Rs274 find_rs274(const std::string& root);
// The tests' rs274: under $APCI_LINUXCNC_ROOT, else where the build unpacked it (the CMake
// cache's APCI_LINUXCNC_ROOT); looked for once.
const Rs274& test_rs274();

// One move of rs274's output in the plane's coordinates (first, second): G17 (X, Y), G18
// (Z, X). Arcs keep LinuxCNC's form: end point and centre (a spiral when rounding made the
// radii differ, as its motion planner runs them).
struct CanonMove {
    rwmos::geom::Element path;
    bool rapid = false;  // STRAIGHT_TRAVERSE
    // The cutter radius compensation in force when the interpreter issued the move: 40 off,
    // 41 left, 42 right (from its comments "interpreter: cutter radius compensation on
    // left/right/off", which it queues in order with the moves it holds back).
    int compensation = 40;
    double third = 0.0;  // the end point on the plane's third axis (G17 Z, G18 Y)
};

struct Rs274Result {
    bool ran = false;      // the process ran and exited
    int exit_code = -1;
    std::string error;     // its error message (standard error, last line), when exit_code != 0
    std::vector<CanonMove> moves;
};

// Where rs274 finds the subroutines a program calls (`o<name> call` opens name.ngc): none by
// default. `files` (name, NGC text) are written to a scratch directory searched first, then
// `directories` in order; rs274 gets them as [RS274NGC]SUBROUTINE_PATH of an INI file (-i).
struct Rs274Subroutines {
    std::vector<std::pair<std::string, std::string>> files;
    std::vector<std::string> directories;
    bool empty() const { return files.empty() && directories.empty(); }
};

// Runs rs274 -t tool_table -g on every program (NGC text), at most `parallel` at a time; the
// moves are read in `plane` (17 or 18). Results in the order of the programs. Block delete is
// off (rs274's default): lines beginning with "/" run.
std::vector<Rs274Result> run_rs274(const Rs274& rs, const std::vector<std::string>& programs,
                                   const std::string& tool_table, int plane, int parallel,
                                   const Rs274Subroutines& subroutines = {});

// A tool table for rs274 (standalone rs274 reads it in inches: D is the diameter) with tool
// 1 of radius r mm.
std::string rs274_tool_table(double radius_mm);

}  // namespace apci::test
