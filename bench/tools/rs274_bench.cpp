// SPDX-License-Identifier: MIT
// `apcictl run --json FILE` against LinuxCNC's interpreter `rs274` writing its canonical output
// to a file, side by side on the same 100,000-block G41 program of lines and arcs, whole
// processes, ten runs of each (alternating, so a change of the machine's load falls on both;
// each after a sync, so neither pays for the other's writeback), in one benchmark run. Three
// programs, one benchmark each: BM_ApcictlVsRs274, the contour that repeats one star
// (contour_program.h), BM_ApcictlVsRs274Walk, the walk that never repeats itself
// (walk_program.h), and BM_ApcictlVsRs274Cam, 6,000 profiles as CAM writes them (cam_program.h).
// Counters: the medians of wall and user
// CPU time (wait4 rusage) of each, the ratio rs274 / apcictl of each (how many times faster
// apcictl is), and apcictl's peak RSS. Target (docs/performance.md): ratio >= 10, RSS < 50 MB.
//
// rs274 is LinuxCNC's, unpacked by scripts/fetch_linuxcnc.sh into BUILD/linuxcnc (or the
// directory in $APCI_LINUXCNC_ROOT); it runs as tests/compensation/linuxcnc.cpp runs it:
// `rs274 -t TABLE -g PROGRAM`, LD_LIBRARY_PATH to its libraries, HOME a directory of its own
// (its tool data goes to $HOME/.tool.mmap). $APCI_BENCH_APCICTL runs another apcictl binary.
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cam_program.h"
#include "contour_program.h"
#include "exec_argv.h"
#include "walk_program.h"

namespace {

constexpr std::size_t kBlocks = 100'000;
constexpr std::size_t kCamProfiles = 6'000;
constexpr int kRuns = 10;

struct ChildRun {
    int exit_code = -1;
    double wall_s = 0.0;
    double user_s = 0.0;
    long peak_rss_kb = 0;
};

// Runs argv with standard input from /dev/null, standard output to `out` and standard error to
// `err`, the given variables added to the environment; times the whole process.
ChildRun run_child(const std::vector<std::string>& argv, const std::string& out,
                   const std::string& err, const std::vector<std::string>& env = {}) {
    ChildRun r;
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int in = ::open("/dev/null", O_RDONLY);
        const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (in < 0 || o < 0 || e < 0) ::_exit(126);
        ::dup2(in, 0);
        ::dup2(o, 1);
        ::dup2(e, 2);
        for (const auto& kv : env) {
            const auto eq = kv.find('=');
            ::setenv(kv.substr(0, eq).c_str(), kv.substr(eq + 1).c_str(), 1);
        }
        exec_argv(argv);
    }
    int status = 0;
    rusage usage{};
    if (pid < 0 || ::wait4(pid, &status, 0, &usage) != pid) return r;
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.user_s = static_cast<double>(usage.ru_utime.tv_sec) +
               1e-6 * static_cast<double>(usage.ru_utime.tv_usec);
    r.peak_rss_kb = usage.ru_maxrss;
    return r;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 == 1 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2.0;
}

bool write_file(const std::string& path, const std::string& text) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (f == nullptr) return false;
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    return std::fclose(f) == 0 && ok;
}

std::string read_file(const std::string& path) {
    std::string text;
    std::FILE* f = std::fopen(path.c_str(), "r");
    if (f == nullptr) return text;
    char buf[4096];
    std::size_t n = 0;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
    std::fclose(f);
    return text;
}

bool is_file(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

// A scratch directory, removed with what the runs left in it.
struct Scratch {
    std::string dir;
    Scratch() {
        const char* tmp = std::getenv("TMPDIR");
        std::string templ =
            std::string(tmp != nullptr && *tmp ? tmp : "/tmp") + "/apci-rs274-bench-XXXXXX";
        if (::mkdtemp(templ.data()) != nullptr) dir = templ;
    }
    ~Scratch() {
        if (dir.empty()) return;
        for (const char* name :
             {"contour.nc", "contour.tools", "contour.ngc", "tools.tbl", "out.json", "rs274.out",
              "apcictl.err", "rs274.err", "summary.out", "home/.tool.mmap", "home"})
            std::remove((dir + "/" + name).c_str());
        ::rmdir(dir.c_str());
    }
    std::string path(const char* name) const { return dir + "/" + name; }
};

// Times `apcictl run` on `ours` against `rs274` on `theirs` (the same path in its dialect).
void compare(benchmark::State& state, const apci::bench::ContourProgram& ours,
             const apci::bench::ContourProgram& theirs) {
    const char* env_root = std::getenv("APCI_LINUXCNC_ROOT");
    const std::string root = env_root != nullptr && *env_root ? env_root : APCI_LINUXCNC_ROOT;
    const std::string rs274 = root + "/usr/bin/rs274";
    if (!is_file(rs274)) {
        state.SkipWithError(("LinuxCNC's rs274 is not unpacked at " + rs274 +
                             " (scripts/fetch_linuxcnc.sh, or set APCI_LINUXCNC_ROOT)")
                                .c_str());
        return;
    }
    Scratch scratch;
    if (scratch.dir.empty() || ::mkdir(scratch.path("home").c_str(), 0700) != 0) {
        state.SkipWithError("cannot make a scratch directory under $TMPDIR");
        return;
    }
    if (!write_file(scratch.path("contour.nc"), ours.text) ||
        !write_file(scratch.path("contour.tools"), apci::bench::contour_tools()) ||
        !write_file(scratch.path("contour.ngc"), theirs.text) ||
        !write_file(scratch.path("tools.tbl"), apci::bench::contour_rs274_tool_table())) {
        state.SkipWithError("cannot write the programs");
        return;
    }
    // Another apcictl (say a build of the commit before) for an A/B comparison on one machine.
    const char* env_apcictl = std::getenv("APCI_BENCH_APCICTL");
    const std::string apcictl_path =
        env_apcictl != nullptr && *env_apcictl ? env_apcictl : APCICTL_PATH;
    const std::vector<std::string> apcictl{apcictl_path,
                                           "run",
                                           scratch.path("contour.nc"),
                                           "--tools",
                                           scratch.path("contour.tools"),
                                           "--json",
                                           scratch.path("out.json")};
    const std::vector<std::string> interp{rs274, "-t", scratch.path("tools.tbl"), "-g",
                                          scratch.path("contour.ngc")};
    const std::vector<std::string> interp_env{
        "LD_LIBRARY_PATH=" + root + "/usr/lib:" + root + "/usr/lib/x86_64-linux-gnu",
        "HOME=" + scratch.path("home")};
    std::vector<double> ours_wall, ours_user, theirs_wall, theirs_user;
    long rss_kb = 0;
    for ([[maybe_unused]] auto _ : state) {
        for (int i = 0; i < kRuns; ++i) {
            // Each timed run starts with nothing of the other's left to write back: rs274 leaves
            // its output dirty in the page cache, and the kernel writing it out while apcictl
            // runs would be rs274's cost paid in apcictl's time (apcictl writes its own output
            // back itself, fsync included). Outside the timed region, like hyperfine's
            // `--prepare sync`.
            ::sync();
            const ChildRun a =
                run_child(apcictl, scratch.path("summary.out"), scratch.path("apcictl.err"));
            ::sync();
            const ChildRun b =
                run_child(interp, scratch.path("rs274.out"), scratch.path("rs274.err"), interp_env);
            if (a.exit_code != 0) {
                state.SkipWithError(
                    ("apcictl run failed: " + read_file(scratch.path("apcictl.err")).substr(0, 400))
                        .c_str());
                return;
            }
            if (b.exit_code != 0) {
                state.SkipWithError(
                    ("rs274 failed: " + read_file(scratch.path("rs274.err")).substr(0, 400))
                        .c_str());
                return;
            }
            ours_wall.push_back(a.wall_s);
            ours_user.push_back(a.user_s);
            theirs_wall.push_back(b.wall_s);
            theirs_user.push_back(b.user_s);
            rss_kb = std::max(rss_kb, a.peak_rss_kb);
        }
        state.SetIterationTime(median(ours_wall));
    }
    const double aw = median(ours_wall), au = median(ours_user);
    const double bw = median(theirs_wall), bu = median(theirs_user);
    state.counters["blocks"] = static_cast<double>(ours.blocks);
    state.counters["apcictl_wall_s"] = aw;
    state.counters["apcictl_user_s"] = au;
    state.counters["rs274_wall_s"] = bw;
    state.counters["rs274_user_s"] = bu;
    state.counters["ratio_wall"] = bw / aw;
    state.counters["ratio_user"] = bu / au;
    state.counters["apcictl_peak_rss_MB"] = static_cast<double>(rss_kb) / 1024.0;
}

// The contour that repeats one star of 24 elements, turn after turn.
void BM_ApcictlVsRs274(benchmark::State& state) {
    using apci::bench::Dialect;
    compare(state, apci::bench::contour_program(kBlocks, Dialect::kApcictl),
            apci::bench::contour_program(kBlocks, Dialect::kLinuxCnc));
}

// The walk along +X that never repeats itself (every element new to the self-approach check).
void BM_ApcictlVsRs274Walk(benchmark::State& state) {
    using apci::bench::Dialect;
    compare(state, apci::bench::walk_program(kBlocks, Dialect::kApcictl),
            apci::bench::walk_program(kBlocks, Dialect::kLinuxCnc));
}

// The program shaped as CAM writes it: 6,000 profiles with leads, placed apart, nothing
// repeated (about 86,000 blocks), where the self-approach check has every element to place and
// no warning to give.
void BM_ApcictlVsRs274Cam(benchmark::State& state) {
    using apci::bench::Dialect;
    compare(state, apci::bench::cam_program(kCamProfiles, Dialect::kApcictl),
            apci::bench::cam_program(kCamProfiles, Dialect::kLinuxCnc));
}

BENCHMARK(BM_ApcictlVsRs274)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ApcictlVsRs274Cam)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ApcictlVsRs274Walk)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
