// SPDX-License-Identifier: MIT
#include "apci/run/summary.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace apci::run {

void count_segment(RunTotals& totals, const PathSegment& s) noexcept {
    const double length = measured_length(s);  // measured once where the segment was made
    totals.path_length += length;
    if (s.kind == SegmentKind::kRapid) totals.rapid_length += length;
    ++totals.segments;
}

std::vector<std::pair<std::string, std::size_t>> count_by_code(std::span<const RunError> errors) {
    std::vector<std::pair<std::string, std::size_t>> counts;
    for (const RunError& e : errors) {
        auto it = std::find_if(counts.begin(), counts.end(),
                               [&](const auto& c) { return c.first == e.code; });
        if (it == counts.end()) {
            counts.emplace_back(e.code, 1);
        } else {
            ++it->second;
        }
    }
    return counts;
}

std::string block_text(const BlockRef& b) {
    if (b.number != kNoBlock && b.line != 0) return fmt::format("line {} (N{})", b.line, b.number);
    if (b.number != kNoBlock) return fmt::format("N{}", b.number);
    if (b.line != 0) return fmt::format("line {}", b.line);
    return "-";
}

namespace {

// "1 ms", "250 us".
std::string cycle_text(double seconds) {
    const double us = seconds * 1e6;
    if (us >= 1000.0 && std::fmod(us, 1000.0) == 0.0) return fmt::format("{:g} ms", us / 1000.0);
    return fmt::format("{:g} us", us);
}

// "1 segment", "0 segments", "2 segments".
std::string counted(std::uint64_t n, std::string_view noun) {
    return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s");
}

}  // namespace

void print_summary(std::FILE* out, const RunTotals& t, std::span<const RunError> errors) {
    // What reached the board (a run stopped at a refusal sent the refused block) and what the
    // board executed: a block sent is not yet a block executed.
    fmt::print(out, "{}: {}, {} sent to the board, {} executed\n", t.file,
               counted(t.blocks, "block"), t.blocks_executed, counted(t.segments, "segment"));
    fmt::print(out, "path {:.3f} mm (rapid {:.3f} mm), time {:.3f} s ({} of {})\n",
               t.path_length, t.rapid_length, static_cast<double>(t.cycles) * t.cycle_seconds,
               counted(t.cycles, "cycle"), cycle_text(t.cycle_seconds));
    if (errors.empty()) {
        fmt::print(out, "errors: none\n");
        return;
    }
    std::string counts;
    for (const auto& [code, n] : count_by_code(errors)) {
        if (!counts.empty()) counts += ", ";
        counts += fmt::format("{} {}", code, n);
    }
    fmt::print(out, "errors: {} ({})\n", errors.size(), counts);
    for (std::size_t i = 0; i < errors.size() && i < kSummaryErrorLines; ++i)
        fmt::print(out, "  {}: {}: {}\n", block_text(errors[i].block), errors[i].code,
                   errors[i].message);
    if (errors.size() > kSummaryErrorLines)
        fmt::print(out, "  ... and {} more\n", errors.size() - kSummaryErrorLines);
}

}  // namespace apci::run
