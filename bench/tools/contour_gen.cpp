// SPDX-License-Identifier: MIT
// Writes the benchmark's programs to standard output: the repeating contour
// (bench/tools/contour_program.h) or the walk that never repeats (bench/tools/walk_program.h),
// in our dialect or rs274's, and their tool list and table:
//   bench_contour_gen BLOCKS apcictl|linuxcnc|walk|walk-linuxcnc|tools|rs274-tools [SEED]
// SEED: another turn or walk than the benchmark's (to look for a seed both sides accept).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "contour_program.h"
#include "walk_program.h"

int main(int argc, char** argv) {
    using apci::bench::Dialect;
    char* end = nullptr;
    const unsigned long long blocks = argc == 3 || argc == 4 ? std::strtoull(argv[1], &end, 10) : 0;
    if ((argc != 3 && argc != 4) || end == argv[1] || *end != '\0' || blocks < 8 ||
        blocks > 100'000'000) {
        std::fputs(
            "usage: bench_contour_gen BLOCKS "
            "apcictl|linuxcnc|walk|walk-linuxcnc|tools|rs274-tools [SEED]\n"
            "  BLOCKS: 8..100000000 (the walk: 8..120000)\n",
            stderr);
        return 2;
    }
    const std::string what = argv[2];
    const bool walk = what == "walk" || what == "walk-linuxcnc";
    std::uint64_t seed = walk ? apci::bench::kWalkSeed : apci::bench::kContourSeed;
    if (argc == 4) {
        char* seed_end = nullptr;
        seed = std::strtoull(argv[3], &seed_end, 10);
        if (seed_end == argv[3] || *seed_end != '\0') {
            std::fprintf(stderr, "bench_contour_gen: SEED must be a whole number, not '%s'\n",
                         argv[3]);
            return 2;
        }
    }
    if (walk && blocks > apci::bench::kWalkMaxBlocks) {
        std::fprintf(stderr,
                     "bench_contour_gen: the walk runs along +X inside the board's range of "
                     "+-100000 mm: at most %zu blocks, not %llu\n",
                     apci::bench::kWalkMaxBlocks, blocks);
        return 2;
    }
    std::string text;
    if (what == "apcictl") {
        text = apci::bench::contour_program(blocks, Dialect::kApcictl, seed).text;
    } else if (what == "linuxcnc") {
        text = apci::bench::contour_program(blocks, Dialect::kLinuxCnc, seed).text;
    } else if (what == "walk") {
        text = apci::bench::walk_program(blocks, Dialect::kApcictl, seed).text;
    } else if (what == "walk-linuxcnc") {
        text = apci::bench::walk_program(blocks, Dialect::kLinuxCnc, seed).text;
    } else if (what == "tools") {
        text = apci::bench::contour_tools();
    } else if (what == "rs274-tools") {
        text = apci::bench::contour_rs274_tool_table();
    } else {
        std::fprintf(stderr,
                     "bench_contour_gen: unknown output '%s' (apcictl, linuxcnc, walk, "
                     "walk-linuxcnc, tools, rs274-tools)\n",
                     argv[2]);
        return 2;
    }
    return std::fwrite(text.data(), 1, text.size(), stdout) == text.size() ? 0 : 1;
}
