// SPDX-License-Identifier: MIT
// `apcictl run` end to end on a generated radius-compensated program of lines and arcs (G41),
// 100,000 and 1,000,000 blocks: blocks per second and the peak resident set size of the
// apcictl process (getrusage of the child). Targets (docs/performance.md): at least 500,000
// blocks/s writing the JSON, and under 50 MB peak RSS at 1,000,000 blocks, flat in the length.
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "exec_argv.h"

namespace {

// One turn of a plate contour (the tool on its inside, G41, r = 1): 8 lines and 4 arcs, tangent
// joins at the arcs, and a notch with two inside and two outside corners. It starts and ends
// at (10, 0); each turn lowers Z a little (cycling), so the program never leaves the board's
// coordinate range however long.
constexpr const char* kTurn[] = {"G1 X40 Y0 Z%s", "G3 X50 Y10 I0 J10",
                                 "G1 Y30",        "G3 X40 Y40 I-10 J0",
                                 "G1 X30",        "G1 Y30",
                                 "G1 X20",        "G1 Y40",
                                 "G1 X10",        "G3 X0 Y30 I0 J-10",
                                 "G1 Y10",        "G3 X10 Y0 I10 J0"};
constexpr std::size_t kTurnBlocks = sizeof kTurn / sizeof kTurn[0];

struct Program {
    std::string path;
    std::string tools;
    std::size_t blocks = 0;
};

std::string temp_path(const std::string& name) {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir != nullptr && *dir ? dir : "/tmp") + "/apci_run_bench_" +
           std::to_string(::getpid()) + "_" + name;
}

// Writes the program (about `blocks` blocks) and its tool list once per size.
const Program& program(std::size_t blocks) {
    static std::map<std::size_t, Program> made;
    auto it = made.find(blocks);
    if (it != made.end()) return it->second;
    Program p;
    p.path = temp_path(std::to_string(blocks) + ".nc");
    p.tools = temp_path("bench.tools");
    std::FILE* t = std::fopen(p.tools.c_str(), "w");
    std::fputs("wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 1\nwz[1].laenge 0\n", t);
    std::fclose(t);
    std::FILE* f = std::fopen(p.path.c_str(), "w");
    std::fputs("%bench.nc\nN1 G17 G90 G26 F3000 D1\nN2 G0 X10 Y0 Z0\nN3 G41\n", f);
    std::size_t n = 4;
    char z[16], block[64];
    for (std::size_t turn = 0; n + kTurnBlocks <= blocks; ++turn) {
        std::snprintf(z, sizeof z, "%.2f", -static_cast<double>(turn % 100) * 0.01);
        for (const char* b : kTurn) {
            std::snprintf(block, sizeof block, b, z);
            std::fprintf(f, "N%zu %s\n", n++, block);
        }
    }
    std::fprintf(f, "N%zu G40\nN%zu M30\n", n, n + 1);
    p.blocks = n + 1;
    std::fclose(f);
    return made.emplace(blocks, p).first->second;
}

struct ChildRun {
    int exit_code = -1;
    double wall_s = 0.0;
    double cpu_s = 0.0;    // user + system
    long peak_rss_kb = 0;  // ru_maxrss of the child
};

// Runs argv with standard output to /dev/null; standard error stays (failures show).
ChildRun run_child(const std::vector<std::string>& argv) {
    ChildRun r;
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 1);
        exec_argv(argv);
    }
    int status = 0;
    rusage usage{};
    ::wait4(pid, &status, 0, &usage);
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.cpu_s = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
              1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    r.peak_rss_kb = usage.ru_maxrss;
    return r;
}

// One run per iteration; time = wall clock of the whole process (start-up, validation pass,
// execution, output). Counters: blocks/s by wall and by CPU time, peak RSS in MB, output size.
void run_program(benchmark::State& state, const std::vector<std::string>& outputs) {
    const Program& p = program(static_cast<std::size_t>(state.range(0)));
    std::vector<std::string> argv{APCICTL_PATH, "run", p.path, "--tools", p.tools};
    argv.insert(argv.end(), outputs.begin(), outputs.end());
    double wall = 0.0, cpu = 0.0;
    long rss = 0;
    for ([[maybe_unused]] auto _ : state) {
        const ChildRun r = run_child(argv);
        if (r.exit_code != 0) {
            state.SkipWithError("apcictl run failed");
            break;
        }
        state.SetIterationTime(r.wall_s);
        wall += r.wall_s;
        cpu += r.cpu_s;
        rss = std::max(rss, r.peak_rss_kb);
    }
    const double blocks = static_cast<double>(p.blocks) * static_cast<double>(state.iterations());
    state.counters["blocks"] = static_cast<double>(p.blocks);
    state.counters["blocks_per_s_wall"] = blocks / wall;
    state.counters["blocks_per_s_cpu"] = blocks / cpu;
    state.counters["peak_rss_MB"] = static_cast<double>(rss) / 1024.0;
    for (std::size_t i = 0; i + 1 < outputs.size(); i += 2) std::remove(outputs[i + 1].c_str());
}

// The target: the JSON written to a file.
void BM_RunJson(benchmark::State& state) {
    run_program(state, {"--json", temp_path("out.json")});
}
// The JSON to /dev/null: the same work without the file system.
void BM_RunJsonToDevNull(benchmark::State& state) {
    run_program(state, {"--json", "/dev/null"});
}
// Only the summary: driving the board and reading the segments back.
void BM_RunSummaryOnly(benchmark::State& state) {
    run_program(state, {});
}
// The plot as well (segments through a temporary file, then the document).
void BM_RunJsonAndSvg(benchmark::State& state) {
    run_program(state, {"--json", temp_path("out.json"), "--svg", temp_path("out.svg")});
}

// Each iteration one whole run of the child, timed by the wall clock (run_program), in ms.
void whole_runs(benchmark::internal::Benchmark* b) {
    b->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
}

BENCHMARK(BM_RunJson)->Arg(100'000)->Arg(1'000'000)->Apply(whole_runs);
BENCHMARK(BM_RunJsonToDevNull)->Arg(1'000'000)->Apply(whole_runs);
BENCHMARK(BM_RunSummaryOnly)->Arg(1'000'000)->Apply(whole_runs);
BENCHMARK(BM_RunJsonAndSvg)->Arg(1'000'000)->Apply(whole_runs)->Iterations(1);

// Removes the generated programs at exit.
struct Cleanup {
    ~Cleanup() {
        for (const char* size : {"100000", "1000000"})
            std::remove(temp_path(std::string(size) + ".nc").c_str());
        std::remove(temp_path("bench.tools").c_str());
    }
} cleanup;

}  // namespace

BENCHMARK_MAIN();
