// SPDX-License-Identifier: MIT
// Where the threads of `apcictl run` run (cpu_placement.h): with exactly two CPUs the executor's
// thread keeps the one it runs on and the helper threads (the writer, the NC front end's
// reader) the other; with one CPU, or more than two, nothing is placed; the executor's thread
// gets its CPUs back at the end. Each test restricts its own thread to the CPUs it needs and
// skips where the machine has fewer.
#include <dirent.h>
#include <gtest/gtest.h>
#include <sched.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "apci/nc/program.h"
#include "apci/run/cpu_placement.h"
#include "apci/run/executor.h"
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

// The CPUs of the thread of this process named `name` (/proc/self/task/TID/comm); empty where
// there is none.
std::vector<int> named_thread_cpus(const std::string& name) {
    std::vector<int> cpus;
    DIR* d = ::opendir("/proc/self/task");
    if (d == nullptr) return cpus;
    while (const dirent* e = ::readdir(d)) {
        if (e->d_name[0] == '.') continue;
        std::FILE* f = std::fopen(("/proc/self/task/" + std::string(e->d_name) + "/comm").c_str(), "r");
        if (f == nullptr) continue;
        char comm[32] = {};
        const bool read = std::fgets(comm, sizeof comm, f) != nullptr;
        std::fclose(f);
        if (read && std::string(comm) == name + "\n") {
            cpus = cpus_of_thread(static_cast<pid_t>(std::atoi(e->d_name)));
            break;
        }
    }
    ::closedir(d);
    return cpus;
}

// The reader's rule (follow_backlog) at its edges: half full or more, beside the executor; an
// eighth full or less, on the other CPU; in between, where it is.
TEST(FollowBacklog, HalfFullOrMoreGoesBesideTheExecutorAndAnEighthOrLessToTheOtherCpu) {
    for (const HelperCpu now : {HelperCpu::kOther, HelperCpu::kEither, HelperCpu::kExecutor}) {
        EXPECT_EQ(follow_backlog(32, 32, now), HelperCpu::kExecutor);
        EXPECT_EQ(follow_backlog(16, 32, now), HelperCpu::kExecutor);
        EXPECT_EQ(follow_backlog(15, 32, now), now);
        EXPECT_EQ(follow_backlog(5, 32, now), now);
        EXPECT_EQ(follow_backlog(4, 32, now), HelperCpu::kOther);
        EXPECT_EQ(follow_backlog(0, 32, now), HelperCpu::kOther);
        // A capacity that neither divides: 17 of 33 is half, 16 not; 4 of 33 an eighth, 5 not.
        EXPECT_EQ(follow_backlog(17, 33, now), HelperCpu::kExecutor);
        EXPECT_EQ(follow_backlog(16, 33, now), now);
        EXPECT_EQ(follow_backlog(5, 33, now), now);
        EXPECT_EQ(follow_backlog(4, 33, now), HelperCpu::kOther);
    }
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

// The run's inputs with one tool (D1) of the radius given (mm, as the tool list writes it).
RunInputs one_tool(const std::string& radius) {
    RunInputFiles f;
    f.tools = "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius " + radius + "\n";
    f.tools_is_text = true;
    auto tools = load_run_inputs(f);
    EXPECT_TRUE(tools) << tools.error().to_string();
    return tools ? tools.value() : RunInputs{};
}

// A run through ProgramRun: with the self-approach check warning, the check has the helpers'
// CPU to itself and the caller's sink is written on a thread that may run on either; without
// the check (or with it stopping the run, on the executor's thread) the writers keep the
// helpers' CPU.
TEST(CpuPlacement, WithTheCheckWarningTheWritersRunOnEitherCpu) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    const RunInputs tools = one_tool("2");
    const std::string program =
        "N10 G17 G90 F1000 D1\nN20 G41 G1 X0 Y0\nN30 X60\nN40 Y60\nN50 X0\nN60 Y0\n"
        "N70 G40 G1 X30 Y30\nN80 M30\n";  // out to the pocket's middle, not through its wall
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
        auto out = run_program(board, sink, tools, ProgramSource::in_memory(program, "square.nc"),
                               settings);
        ASSERT_TRUE(out) << out.error().to_string();
        EXPECT_TRUE(out.value().errors.empty());
        const std::vector<int> expected = mode == SelfApproachMode::kWarn
                                              ? two.cpus()
                                              : std::vector<int>{placement.helper_cpu()};
        EXPECT_EQ(sink.cpus, expected) << static_cast<int>(mode);
    }
}

// A tool of radius 0.1 (D1), and a zigzag of `moves` compensated lines 10 long, 1 apart.
RunInputs thin_tool() {
    return one_tool("0.1");
}
std::string zigzag(int moves) {
    std::string program = "N1 G17 G90 F60000 D1\nN2 G41 G1 X0 Y0\n";
    for (int i = 0; i < moves; ++i)
        program += "G1 X" + std::to_string(i % 2 == 0 ? 10 : 0) + " Y" + std::to_string(i) + "\n";
    return program + "G40 G1 X-5\nM30\n";
}
// `program` run as apcictl runs it (the check warning on its own thread), placed by `placement`.
void run_warned(const CpuPlacement& placement, RunSink& sink, const std::string& program) {
    apci::Board board("emu:");
    RunSettings settings;
    settings.self_approach = SelfApproachMode::kWarn;
    settings.threads = true;
    settings.cpus = &placement;
    auto out = run_program(board, sink, thin_tool(), ProgramSource::in_memory(program, "zigzag.nc"),
                           settings);
    ASSERT_TRUE(out) << out.error().to_string();
}

// The same run seen from /proc while it goes: the executor (the caller's thread) keeps its CPU,
// the check's thread alone the helpers', the writers may run on either, and the reader goes
// where the check's ring says.
TEST(CpuPlacement, WithTheCheckWarningTheCheckAloneKeepsTheHelpersCpu) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    struct Census final : RunSink {
        bool taken = false;
        std::vector<int> own;                     // the writers' thread
        std::vector<std::vector<int>> others;     // every other thread's, at that moment
        std::vector<int> reader;                  // the reader's, among them
        void executed(const PathSegment&) override {
            if (taken) return;
            taken = true;
            own = cpus_of_thread();
            others = other_threads_cpus();
            reader = named_thread_cpus("apci-reader");
        }
    };
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    Census sink;
    // Long enough that the reader still reads when the first segment is written.
    run_warned(placement, sink, zigzag(40000));
    ASSERT_TRUE(sink.taken);
    EXPECT_EQ(sink.own, two.cpus());
    int on_executor = 0, on_helper = 0, on_both = 0;
    for (const auto& cpus : sink.others) {
        if (cpus == std::vector<int>{placement.executor_cpu()}) ++on_executor;
        if (cpus == std::vector<int>{placement.helper_cpu()}) ++on_helper;
        if (cpus == two.cpus()) ++on_both;
    }
    // The reader follows the check's ring (the tests with a ring of a set fill below): where
    // it is at this moment depends on how far the check has fallen behind, so it is counted
    // apart.
    const std::vector<int> reader = sink.reader;
    ASSERT_FALSE(reader.empty());
    EXPECT_TRUE(reader == two.cpus() || reader == std::vector<int>{placement.executor_cpu()} ||
                reader == std::vector<int>{placement.helper_cpu()});
    if (reader == std::vector<int>{placement.executor_cpu()}) --on_executor;
    if (reader == std::vector<int>{placement.helper_cpu()}) --on_helper;
    // The caller's (and a sanitizer's own thread, which ThreadSanitizer starts with the first
    // thread the caller starts, on the caller's CPU).
    EXPECT_GE(on_executor, 1);
    EXPECT_EQ(on_helper, 1);  // the check's
}

// The reader's CPUs (by its name) at the first executed segment, after holding that segment
// `stall` long.
struct ReaderAtFirstSegment final : RunSink {
    explicit ReaderAtFirstSegment(std::chrono::milliseconds stall = 0ms) : stall_(stall) {}
    bool taken = false;
    std::vector<int> reader;
    void executed(const PathSegment&) override {
        if (taken) return;
        taken = true;
        std::this_thread::sleep_for(stall_);
        reader = named_thread_cpus("apci-reader");
    }

  private:
    std::chrono::milliseconds stall_;
};

// ProgramExecutor::set_read_ahead's placement reaches the reader: a reader placed on either
// CPU, following no ring, runs on both; placed beside the executor, on the executor's alone.
TEST(CpuPlacement, TheExecutorsReadAheadPlacesItsReaderWhereItIsAsked) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    const RunInputs tools = thin_tool();
    const std::string program = zigzag(40000);  // the pass reads it where it is
    for (const HelperCpu where : {HelperCpu::kEither, HelperCpu::kExecutor}) {
        apci::Board board("emu:");
        ReaderAtFirstSegment sink;
        ProgramExecutor executor(board, sink, &tools.tools);
        executor.set_read_ahead(true, &placement, where);
        nc::InterpreterOptions options;
        options.tools = &tools.tools;
        options.start_position = executor.position();
        options.cycle_seconds = executor.cycle_seconds();
        nc::SinglePass pass = nc::SinglePass::from_text(program, "zigzag.nc", options);
        const RunOutcome out = executor.run(pass.events());
        std::string errors;
        for (const RunError& e : out.errors) errors += e.code + ": " + e.message + "\n";
        ASSERT_EQ(errors, "");
        ASSERT_TRUE(sink.taken);
        EXPECT_EQ(sink.reader, where == HelperCpu::kEither
                                   ? two.cpus()
                                   : std::vector<int>{placement.executor_cpu()})
            << static_cast<int>(where);
    }
}

// A run whose check falls behind (its writers stall, so the check waits for them and its own
// ring fills) moves the reader beside the executor: ProgramRun gives the reader the check's
// ring to follow.
TEST(CpuPlacement, WhereTheCheckFallsBehindTheReaderGoesBesideTheExecutor) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    // Meanwhile the writers' ring fills, then the check's, and the executor waits.
    ReaderAtFirstSegment sink(300ms);
    // More than the three rings hold (8,192 + 2 x 14,336 events): the reader still reads.
    run_warned(placement, sink, zigzag(80000));
    ASSERT_TRUE(sink.taken);
    EXPECT_EQ(sink.reader, std::vector<int>{placement.executor_cpu()});
}

// The CPUs of every other thread while a reader placed `where` (and following `follows`, where
// given) waits: its program (20,000 moves) is more than its ring holds, so it fills the ring
// and waits, alive. The reader's own, by its name, in `reader`.
std::vector<std::vector<int>> threads_beside_a_reader(const CpuPlacement& placement,
                                                      HelperCpu where,
                                                      const RingFill* follows = nullptr,
                                                      std::vector<int>* reader = nullptr) {
    std::string text = "%many\nN1 G17 G90 F3000\n";
    for (int i = 0; i < 20000; ++i)
        text += "N" + std::to_string(i + 2) + " G1 X" + std::to_string(i % 97) + "\n";
    nc::EventStream stream = nc::EventStream::from_text(text, "p.nc");
    ReadAhead ahead(stream, &placement, where, follows);
    nc::Event ev;
    EXPECT_EQ(ahead.next(ev), nc::EventStream::Next::kEvent);
    std::this_thread::sleep_for(100ms);  // the reader fills the ring and waits
    std::vector<std::vector<int>> cpus = other_threads_cpus();
    if (reader != nullptr) *reader = named_thread_cpus("apci-reader");
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

// A ring of a fill the test sets.
class SetFill final : public RingFill {
  public:
    SetFill(std::size_t backlog, std::size_t capacity) : backlog_(backlog), capacity_(capacity) {}
    std::size_t backlog() const noexcept override { return backlog_; }
    std::size_t capacity() const noexcept override { return capacity_; }

  private:
    std::size_t backlog_, capacity_;
};

// A ring that reads `first` for its first `looks` looks and `then` after, counting the looks.
class ChangingFill final : public RingFill {
  public:
    ChangingFill(std::size_t first, int looks, std::size_t then)
        : first_(first), then_(then), left_(looks) {}
    std::size_t backlog() const noexcept override {
        looked.fetch_add(1);
        return left_.fetch_sub(1) > 0 ? first_ : then_;
    }
    std::size_t capacity() const noexcept override { return 32; }
    mutable std::atomic<int> looked{0};

  private:
    std::size_t first_, then_;
    mutable std::atomic<int> left_;
};

// The reader looks at the ring once every ReadAhead::kFollowEvery batches it opens: filling its
// ring of kBatches (and waiting to open one more), kBatches / kFollowEvery times. A reader that
// started on the helpers' CPU, moved beside the executor by a ring half full, goes back once
// the ring has emptied (it knows where it is now, not only where it started).
TEST(CpuPlacement, AReaderLooksEveryFewBatchesAndGoesBackWhenTheRingEmpties) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    static_assert(ReadAhead::kBatches % ReadAhead::kFollowEvery == 0);
    const ChangingFill fill(16, 2, 0);
    std::vector<int> reader;
    threads_beside_a_reader(placement, HelperCpu::kOther, &fill, &reader);
    EXPECT_EQ(fill.looked.load(),
              static_cast<int>(ReadAhead::kBatches / ReadAhead::kFollowEvery));
    EXPECT_EQ(reader, std::vector<int>{placement.helper_cpu()});
}

// A reader that follows a ring looks at it every ReadAhead::kFollowEvery batches it opens (it
// opens all of its ring's while it fills it, here): half full, it goes beside the executor; an
// eighth full, to the helpers' CPU; in between it stays on the CPU it started on.
TEST(CpuPlacement, AReaderFollowsTheFillOfTheRingItIsGiven) {
    const Restricted two(2);
    if (!two.ok()) GTEST_SKIP() << "fewer than two CPUs";
    const CpuPlacement placement;
    ASSERT_TRUE(placement.active());
    static_assert(ReadAhead::kFollowEvery < ReadAhead::kBatches);
    const std::vector<int> executor{placement.executor_cpu()}, helper{placement.helper_cpu()};
    struct Case {
        std::size_t backlog;
        HelperCpu start;
        std::vector<int> expected;
    };
    const std::vector<Case> cases = {
        {16, HelperCpu::kEither, executor}, {16, HelperCpu::kOther, executor},
        {4, HelperCpu::kEither, helper},    {4, HelperCpu::kExecutor, helper},
        {10, HelperCpu::kEither, two.cpus()}, {10, HelperCpu::kOther, helper},
    };
    for (const Case& c : cases) {
        const SetFill fill(c.backlog, 32);
        std::vector<int> reader;
        threads_beside_a_reader(placement, c.start, &fill, &reader);
        EXPECT_EQ(reader, c.expected) << "backlog " << c.backlog << " of 32, starting on "
                                      << static_cast<int>(c.start);
    }
}

}  // namespace
}  // namespace apci::run
