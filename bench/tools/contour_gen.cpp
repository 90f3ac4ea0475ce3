// SPDX-License-Identifier: MIT
// Writes the benchmark's programs to standard output: the repeating contour
// (bench/tools/contour_program.h), the walk that never repeats (bench/tools/walk_program.h) or
// the CAM-shaped program (bench/tools/cam_program.h), in our dialect or rs274's, and their tool
// list and table:
//   bench_contour_gen BLOCKS apcictl|linuxcnc|walk|walk-linuxcnc|tools|rs274-tools [SEED]
//   bench_contour_gen PROFILES cam|cam-linuxcnc [SEED]
// SEED: another turn, walk or CAM program than the benchmark's (to look for a seed both sides
// accept). The CAM program's length is its profile count (BM_ApcictlVsRs274Cam: 6000).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "cam_program.h"
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
            "       bench_contour_gen PROFILES cam|cam-linuxcnc [SEED]\n"
            "  BLOCKS: 8..100000000 (the walk: 8..120000); PROFILES: 8..6400\n",
            stderr);
        return 2;
    }
    const std::string what = argv[2];
    const bool walk = what == "walk" || what == "walk-linuxcnc";
    const bool cam = what == "cam" || what == "cam-linuxcnc";
    std::uint64_t seed = walk  ? apci::bench::kWalkSeed
                         : cam ? apci::bench::kCamSeed
                               : apci::bench::kContourSeed;
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
    constexpr auto kCamMaxProfiles =
        static_cast<unsigned long long>(apci::bench::kCamColumns) * apci::bench::kCamColumns;
    if (cam && blocks > kCamMaxProfiles) {
        std::fprintf(stderr,
                     "bench_contour_gen: the CAM program places its profiles on a grid of %d x "
                     "%d: at most %llu profiles, not %llu\n",
                     apci::bench::kCamColumns, apci::bench::kCamColumns, kCamMaxProfiles, blocks);
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
    } else if (cam) {
        text = apci::bench::cam_program(
                   blocks, what == "cam" ? Dialect::kApcictl : Dialect::kLinuxCnc, seed)
                   .text;
    } else if (what == "tools") {
        text = apci::bench::contour_tools();
    } else if (what == "rs274-tools") {
        text = apci::bench::contour_rs274_tool_table();
    } else {
        std::fprintf(stderr,
                     "bench_contour_gen: unknown output '%s' (apcictl, linuxcnc, walk, "
                     "walk-linuxcnc, cam, cam-linuxcnc, tools, rs274-tools)\n",
                     argv[2]);
        return 2;
    }
    return std::fwrite(text.data(), 1, text.size(), stdout) == text.size() ? 0 : 1;
}
