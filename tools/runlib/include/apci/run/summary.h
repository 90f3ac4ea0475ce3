// SPDX-License-Identifier: MIT
// The summary `apcictl run` prints on standard output:
//
//   examples/wr_quad_disc.nc: 11 blocks, 11 executed, 13 segments
//   path 632.743 mm (rapid 0 mm), time 63.274 s (63274 cycles of 1 ms)
//   errors: none
//
// or, after errors, "errors: 2 (KorrError 1, CalcError 1)" and one line per error
// ("  N80: KorrError: ..."), at most kSummaryErrorLines of them.
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "apci/run/path.h"

namespace apci::run {

struct RunTotals {
    std::string file;
    std::uint64_t blocks = 0;           // blocks of the program (validation pass)
    std::uint64_t blocks_executed = 0;  // blocks whose events reached the board (sent)
    std::uint64_t segments = 0;         // executed segments read back
    double path_length = 0.0;           // tool-centre path, every segment, mm
    double rapid_length = 0.0;          // of which rapid moves
    std::uint64_t cycles = 0;           // interpolation cycles the run took
    double cycle_seconds = 0.001;
};

// Accumulates one executed segment into the totals.
void count_segment(RunTotals& totals, const PathSegment& s) noexcept;

// Error codes with their counts, in the order they first occur.
std::vector<std::pair<std::string, std::size_t>> count_by_code(std::span<const RunError> errors);

inline constexpr std::size_t kSummaryErrorLines = 20;

// "line 12 (N80)" when both are known, "N80" (a segment carries only its N), "line 12" (a block
// without N), or "-" when unknown.
std::string block_text(const BlockRef& b);

void print_summary(std::FILE* out, const RunTotals& totals, std::span<const RunError> errors);

}  // namespace apci::run
