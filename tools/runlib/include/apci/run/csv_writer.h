// SPDX-License-Identifier: MIT
// `apcictl run --csv`: the axis positions of every interpolation cycle, one line a cycle,
// streamed. Header: "cycle,time_s," then one column per board axis, named by the axis it
// serves (X, Y, Z through the TC Axis-Nr objects, a<i> for the others):
//
//   cycle,time_s,X,Y,Z,a3,a4,a5,a6,a7
//   1,0.001,0.01,0,0,0,0,0,0,0
//
// `cycle` is the board's clock at the end of the cycle (1 for the first), time_s = cycle times
// the interpolation cycle. Positions are machine coordinates in program units.
#pragma once

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

// The column name of board axis `axis` when X, Y and Z are board axes x, y and z.
std::string axis_column_name(int axis, int x, int y, int z);

}  // namespace apci::run
