// SPDX-License-Identifier: MIT
// `apcictl run --csv`: the axis positions of every interpolation cycle, one line a cycle,
// streamed. Header: "cycle,time_s," then one column per board axis, board axes 0..7 in order,
// named by the letters the command line names them by (`spool`, `direct`, `ssf`, `step`):
//
//   cycle,time_s,X,Y,Z,A,B,C,U,V
//   1,0.001,0.01,0,0,0,0,0,0,0
//
// `cycle` is the board's clock at the end of the cycle (1 for the first), time_s = cycle times
// the interpolation cycle. Positions are machine coordinates in program units.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>

#include "apci/run/text_sink.h"

namespace apci::run {

class TraceCsvWriter {
  public:
    // Writes the header at once. `out` is not owned.
    TraceCsvWriter(std::FILE* out, std::span<const std::string> axis_names);

    void sample(std::uint64_t cycle, double time_s, std::span<const double> positions);
    // True when every byte was written.
    bool finish() { return sink_.flush(); }
    std::uint64_t samples_written() const noexcept { return count_; }

  private:
    TextSink sink_;
    std::uint64_t count_ = 0;
};

// The letters of board axes 0..7, as apcictl's command line and the CSV name them: DIN 66025's
// order, the linear X, Y, Z, the rotary A, B, C, then U, V; as NC programs name them (their B
// word drives board axis 4, the head's B, and V.G.WZ_AKT.WEAR.<axis> counts 3 A, 4 B, 5 C).
inline constexpr std::array<char, 8> kBoardAxisLetters{'X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V'};

// The column name of board axis `axis`: its letter ("U" for axis 3); "a<i>" beyond the eighth.
std::string axis_column_name(int axis);

}  // namespace apci::run
