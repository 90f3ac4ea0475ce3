// SPDX-License-Identifier: MIT
// Where the threads of `apcictl run` run (cpu_placement.h): with exactly two CPUs the executor's
// thread keeps the one it runs on and the helper threads (the writer, the NC front end's
// reader) the other; with one CPU, or more than two, nothing is placed; the executor's thread
// gets its CPUs back at the end. Each test restricts its own thread to the CPUs it needs and
// skips where the machine has fewer.
#include <dirent.h>
#include <gtest/gtest.h>
#include <sched.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "apci/nc/program.h"
#include "apci/run/cpu_placement.h"
#include "apci/run/pipeline.h"
#include "apci/run/program_run.h"
#include "apci/run/read_ahead.h"

namespace apci::run {
namespace {

using namespace std::chrono_literals;

std::vector<int> cpus_of(const cpu_set_t& set) {
    std::vector<int> cpus;
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
        if (CPU_ISSET(cpu, &set)) cpus.push_back(cpu);
    return cpus;
}

// The CPUs a thread (0: the calling one) may run on.
std::vector<int> cpus_of_thread(pid_t tid = 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (::sched_getaffinity(tid, sizeof set, &set) != 0) return {};
    return cpus_of(set);
}

// The calling thread on the first `n` CPUs it may use, for the scope; its CPUs as they were
// after. ok() is false where it has fewer.
class Restricted {
  public:
    explicit Restricted(std::size_t n) {
        ::sched_getaffinity(0, sizeof original_, &original_);
        const std::vector<int> cpus = cpus_of(original_);
        if (cpus.size() < n) return;
        cpu_set_t some;
        CPU_ZERO(&some);
        for (std::size_t i = 0; i < n; ++i) CPU_SET(cpus[i], &some);
        ok_ = ::sched_setaffinity(0, sizeof some, &some) == 0;
        chosen_.assign(cpus.begin(), cpus.begin() + static_cast<std::ptrdiff_t>(n));
    }
    ~Restricted() { ::sched_setaffinity(0, sizeof original_, &original_); }
    Restricted(const Restricted&) = delete;
    Restricted& operator=(const Restricted&) = delete;
    bool ok() const { return ok_; }
    const std::vector<int>& cpus() const { return chosen_; }

  private:
    cpu_set_t original_{};
    std::vector<int> chosen_;
    bool ok_ = false;
};

// The CPUs of every other thread of this process (/proc/self/task), one list a thread.
std::vector<std::vector<int>> other_threads_cpus() {
    std::vector<std::vector<int>> all;
    DIR* d = ::opendir("/proc/self/task");
    if (d == nullptr) return all;
    const pid_t self = static_cast<pid_t>(::gettid());
    while (const dirent* e = ::readdir(d)) {
        if (e->d_name[0] == '.') continue;
        const auto tid = static_cast<pid_t>(std::atoi(e->d_name));
        if (tid != self) all.push_back(cpus_of_thread(tid));
    }
    ::closedir(d);
    return all;
}

TEST(CpuPlacement, OnTwoCpusTheExecutorKeepsOneAndTheHelpersTheOther) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    {
        const CpuPlacement placement;
        ASSERT_TRUE(placement.active());
        EXPECT_NE(placement.executor_cpu(), placement.helper_cpu());
        EXPECT_EQ(cpus_of_thread(), std::vector<int>{placement.executor_cpu()});
        // The executor keeps the CPU it ran on when the placement began.
        EXPECT_TRUE(placement.executor_cpu() == two.cpus()[0] ||
                    placement.executor_cpu() == two.cpus()[1]);
        std::vector<int> helper;
        std::thread([&] {
            placement.place_helper();
            helper = cpus_of_thread();
        }).join();
        EXPECT_EQ(helper, std::vector<int>{placement.helper_cpu()});
    }
    EXPECT_EQ(cpus_of_thread(), two.cpus());  // both again, once it ended
}

TEST(CpuPlacement, AHelperPlacedOnEitherCpuMayRunOnBoth) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    std::vector<int> started, placed;
    std::thread([&] {
        started = cpus_of_thread();  // a thread the executor's started: its CPU only
        placement.place_helper(HelperCpu::kEither);
        placed = cpus_of_thread();
    }).join();
    EXPECT_EQ(started, std::vector<int>{placement.executor_cpu()});
    EXPECT_EQ(placed, two.cpus());
}

TEST(CpuPlacement, WithOneCpuOrMoreThanTwoNothingIsPlaced) {
    for (const std::size_t n : {std::size_t{1}, std::size_t{3}}) {
        const Restricted some(n);
        if (!some.ok()) continue;  // the machine has fewer
        const CpuPlacement placement;
        EXPECT_FALSE(placement.active()) << n << " CPUs";
        EXPECT_EQ(placement.executor_cpu(), -1);
        EXPECT_EQ(cpus_of_thread(), some.cpus()) << n << " CPUs";
        std::vector<int> helper;
        for (const HelperCpu where : {HelperCpu::kOther, HelperCpu::kEither}) {
            std::thread([&] {
                placement.place_helper(where);
                helper = cpus_of_thread();
            }).join();
            EXPECT_EQ(helper, some.cpus()) << n << " CPUs";
        }
    }
}

// A sink that notes where the writer thread may run when it writes.
struct WhereWritten final : RunSink {
    std::vector<int> cpus;
    void executed(const PathSegment&) override { cpus = cpus_of_thread(); }
};

TEST(CpuPlacement, TheWriterThreadRunsOnTheHelpersCpu) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    WhereWritten inner;
    {
        PipelinedSink pipeline(inner, &placement);
        pipeline.executed(PathSegment{});
        pipeline.finish();
    }
    EXPECT_EQ(inner.cpus, std::vector<int>{placement.helper_cpu()});
}

TEST(CpuPlacement, AWriterThreadPlacedOnEitherCpuRunsOnBoth) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    WhereWritten inner;
    {
        PipelinedSink pipeline(inner, &placement, HelperCpu::kEither);
        pipeline.executed(PathSegment{});
        pipeline.finish();
    }
    EXPECT_EQ(inner.cpus, two.cpus());
}

// A run through ProgramRun: with the self-approach check warning, the check has the helpers'
// CPU to itself and the caller's sink is written on a thread that may run on either; without
// the check (or with it stopping the run, on the executor's thread) the writers keep the
// helpers' CPU.
TEST(CpuPlacement, WithTheCheckWarningTheWritersRunOnEitherCpu) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    auto tools = load_run_inputs([] {
        RunInputFiles f;
        f.tools = "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 2\n";
        f.tools_is_text = true;
        return f;
    }());
    ASSERT_TRUE(tools) << tools.error().to_string();
    const std::string program =
        "N10 G17 G90 F1000 D1\nN20 G41 G1 X0 Y0\nN30 X60\nN40 Y60\nN50 X0\nN60 Y0\n"
        "N70 G40 G1 X-20 Y0\nN80 M30\n";
    for (const SelfApproachMode mode :
         {SelfApproachMode::kWarn, SelfApproachMode::kOff, SelfApproachMode::kError}) {
        const CpuPlacement placement;
        ASSERT_TRUE(placement.active());
        apci::Board board("emu:");
        WhereWritten sink;
        RunSettings settings;
        settings.self_approach = mode;
        settings.threads = true;
        settings.cpus = &placement;
        auto out = run_program(board, sink, tools.value(),
                               ProgramSource::in_memory(program, "square.nc"), settings);
        ASSERT_TRUE(out) << out.error().to_string();
        EXPECT_TRUE(out.value().errors.empty());
        const std::vector<int> expected = mode == SelfApproachMode::kWarn
                                              ? two.cpus()
                                              : std::vector<int>{placement.helper_cpu()};
        EXPECT_EQ(sink.cpus, expected) << static_cast<int>(mode);
    }
}

// The same run seen from /proc while it goes: the executor (the caller's thread) keeps its CPU,
// the check's thread alone the helpers', and the reader and the writers may run on either.
TEST(CpuPlacement, WithTheCheckWarningOnlyTheCheckKeepsTheHelpersCpu) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    struct Census final : RunSink {
        bool taken = false;
        std::vector<int> own;                     // the writers' thread
        std::vector<std::vector<int>> others;     // every other thread's, at that moment
        void executed(const PathSegment&) override {
            if (taken) return;
            taken = true;
            own = cpus_of_thread();
            others = other_threads_cpus();
        }
    };
    auto tools = load_run_inputs([] {
        RunInputFiles f;
        f.tools = "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 0.1\n";
        f.tools_is_text = true;
        return f;
    }());
    ASSERT_TRUE(tools) << tools.error().to_string();
    // Long enough that the reader still reads when the first segment is written.
    std::string program = "N1 G17 G90 F60000 D1\nN2 G41 G1 X0 Y0\n";
    for (int i = 0; i < 40000; ++i)
        program += "G1 X" + std::to_string(i % 2 == 0 ? 10 : 0) + " Y" + std::to_string(i) + "\n";
    program += "G40 G1 X-5\nM30\n";
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    apci::Board board("emu:");
    Census sink;
    RunSettings settings;
    settings.self_approach = SelfApproachMode::kWarn;
    settings.threads = true;
    settings.cpus = &placement;
    auto out = run_program(board, sink, tools.value(),
                           ProgramSource::in_memory(program, "zigzag.nc"), settings);
    ASSERT_TRUE(out) << out.error().to_string();
    ASSERT_TRUE(sink.taken);
    EXPECT_EQ(sink.own, two.cpus());
    int on_executor = 0, on_helper = 0, on_both = 0;
    for (const auto& cpus : sink.others) {
        if (cpus == std::vector<int>{placement.executor_cpu()}) ++on_executor;
        if (cpus == std::vector<int>{placement.helper_cpu()}) ++on_helper;
        if (cpus == two.cpus()) ++on_both;
    }
    // The caller's (and a sanitizer's own thread, which ThreadSanitizer starts with the first
    // thread the caller starts, on the caller's CPU).
    EXPECT_GE(on_executor, 1);
    EXPECT_EQ(on_helper, 1);  // the check's
    EXPECT_GE(on_both, 1);    // the reader's (and the writers' own, above)
}

// The CPUs of every other thread while a reader placed `where` waits: its program (20,000
// moves) is more than its ring holds, so it fills the ring and waits, alive.
std::vector<std::vector<int>> threads_beside_a_reader(const CpuPlacement& placement,
                                                      HelperCpu where) {
    std::string text = "%many\nN1 G17 G90 F3000\n";
    for (int i = 0; i < 20000; ++i)
        text += "N" + std::to_string(i + 2) + " G1 X" + std::to_string(i % 97) + "\n";
    nc::EventStream stream = nc::EventStream::from_text(text, "p.nc");
    ReadAhead ahead(stream, &placement, where);
    nc::Event ev;
    EXPECT_EQ(ahead.next(ev), nc::EventStream::Next::kEvent);
    std::this_thread::sleep_for(100ms);  // the reader fills the ring and waits
    std::vector<std::vector<int>> cpus = other_threads_cpus();
    ahead.stop();
    return cpus;
}

TEST(CpuPlacement, TheReaderThreadRunsOnTheHelpersCpu) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    // The reader is the one thread on the helpers' CPU alone (a sanitizer's own thread, if
    // any, may run anywhere).
    int on_helper_cpu = 0;
    for (const auto& cpus : threads_beside_a_reader(placement, HelperCpu::kOther))
        if (cpus == std::vector<int>{placement.helper_cpu()}) ++on_helper_cpu;
    EXPECT_EQ(on_helper_cpu, 1);
}

TEST(CpuPlacement, AReaderThreadPlacedOnEitherCpuRunsOnBoth) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    int on_helper_cpu = 0, on_both = 0;
    for (const auto& cpus : threads_beside_a_reader(placement, HelperCpu::kEither)) {
        if (cpus == std::vector<int>{placement.helper_cpu()}) ++on_helper_cpu;
        if (cpus == two.cpus()) ++on_both;
    }
    EXPECT_EQ(on_helper_cpu, 0);
    EXPECT_GE(on_both, 1);
}

}  // namespace
}  // namespace apci::run
