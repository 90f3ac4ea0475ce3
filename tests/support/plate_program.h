// SPDX-License-Identifier: MIT
// The plate contour of the run tests: `turns` turns of 12 blocks (8 lines, 4 arcs, inside and
// outside corners) under G41 with tool D1, as NC text.
#pragma once

#include <string>

namespace apci::test {

inline std::string plate_program(int turns) {
    static const char* kTurn[] = {"G1 X40 Y0", "G3 X50 Y10 I0 J10",
                                  "G1 Y30",    "G3 X40 Y40 I-10 J0",
                                  "G1 X30",    "G1 Y30",
                                  "G1 X20",    "G1 Y40",
                                  "G1 X10",    "G3 X0 Y30 I0 J-10",
                                  "G1 Y10",    "G3 X10 Y0 I10 J0"};
    std::string text = "N1 G17 G90 G26 F3000 D1\nN2 G0 X10 Y0 Z0\nN3 G41\n";
    int n = 4;
    for (int k = 0; k < turns; ++k)
        for (const char* b : kTurn) text += "N" + std::to_string(n++) + " " + b + "\n";
    return text + "N" + std::to_string(n) + " G40\nM30\n";
}

}  // namespace apci::test
