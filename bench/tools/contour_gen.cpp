// SPDX-License-Identifier: MIT
// Writes the benchmark's contour (bench/tools/contour_program.h) to standard output:
//   bench_contour_gen BLOCKS apcictl|linuxcnc|tools|rs274-tools [SEED]
// SEED: another turn than the benchmark's (to look for a seed both sides accept).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "contour_program.h"

int main(int argc, char** argv) {
    using apci::bench::Dialect;
    char* end = nullptr;
    const unsigned long long blocks = argc == 3 || argc == 4 ? std::strtoull(argv[1], &end, 10) : 0;
    if ((argc != 3 && argc != 4) || end == argv[1] || *end != '\0' || blocks < 8 ||
        blocks > 100'000'000) {
        std::fputs(
            "usage: bench_contour_gen BLOCKS apcictl|linuxcnc|tools|rs274-tools [SEED]\n"
            "  BLOCKS: 8..100000000\n",
            stderr);
        return 2;
    }
    std::uint64_t seed = apci::bench::kContourSeed;
    if (argc == 4) {
        char* seed_end = nullptr;
        seed = std::strtoull(argv[3], &seed_end, 10);
        if (seed_end == argv[3] || *seed_end != '\0') {
            std::fprintf(stderr, "bench_contour_gen: SEED must be a whole number, not '%s'\n",
                         argv[3]);
            return 2;
        }
    }
    const std::string what = argv[2];
    std::string text;
    if (what == "apcictl") {
        text = apci::bench::contour_program(blocks, Dialect::kApcictl, seed).text;
    } else if (what == "linuxcnc") {
        text = apci::bench::contour_program(blocks, Dialect::kLinuxCnc, seed).text;
    } else if (what == "tools") {
        text = apci::bench::contour_tools();
    } else if (what == "rs274-tools") {
        text = apci::bench::contour_rs274_tool_table();
    } else {
        std::fprintf(stderr,
                     "bench_contour_gen: unknown output '%s' (apcictl, linuxcnc, tools, "
                     "rs274-tools)\n",
                     argv[2]);
        return 2;
    }
    return std::fwrite(text.data(), 1, text.size(), stdout) == text.size() ? 0 : 1;
}
