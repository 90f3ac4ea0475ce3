// SPDX-License-Identifier: MIT
// The command line the figure generators share: `PROGRAM [--check] DIR` writes each figure as
// DIR/NAME.svg, or with --check compares each with the file there and says which are stale.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace figure_files {

struct FigureFile {
    std::string name;                   // file name without ".svg"
    std::function<std::string()> draw;  // the SVG text
};

// main() of the generator `program` (tools/figures/PROGRAM.cpp): 0 when every figure was written
// (or, with --check, is current), 1 when one was not, 2 on a usage error.
int write_figures(int argc, char** argv, std::string_view program,
                  const std::vector<FigureFile>& figures);

}  // namespace figure_files
