// SPDX-License-Identifier: MIT
// The output pipeline of `apcictl run` (pipeline.h) and its ring (spsc_ring.h): order, the
// bound, either end ending the stream, a writer's failure reaching the caller, no thread left
// behind, and a run through the pipeline writing the same bytes as one without it.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "apci/apci.hpp"
#include "apci/nc/move_time.h"
#include "apci/nc/program.h"
#include "apci/run/executor.h"
#include "apci/run/json_writer.h"
#include "apci/run/pipeline.h"
#include "apci/run/program_run.h"
#include "apci/run/run_files.h"
#include "apci/run/self_approach_sink.h"
#include "apci/run/spsc_ring.h"
#include "apci/run/summary.h"
#include "apci/run/svg_writer.h"
#include "apci/run/text_sink.h"
#include "memory_file.h"
#include "plate_program.h"
#include "thread_count.h"

namespace apci::run {
namespace {

using namespace std::chrono_literals;

// ---- the ring

TEST(SpscRing, EverySlotArrivesOnceInOrderAcrossThreads) {
    SpscRing<std::uint64_t> ring(4);
    constexpr std::uint64_t kCount = 200000;
    std::thread producer([&] {
        for (std::uint64_t i = 0; i < kCount; ++i) {
            std::uint64_t* slot = ring.acquire();
            ASSERT_NE(slot, nullptr);
            *slot = i;
            ring.commit();
        }
        ring.close();
    });
    std::uint64_t expected = 0;
    while (const std::uint64_t* v = ring.front()) {
        ASSERT_EQ(*v, expected);
        ++expected;
        ring.pop();
    }
    producer.join();
    EXPECT_EQ(expected, kCount);
}

// The producer fills every slot and then waits: it never gets a slot the consumer holds.
TEST(SpscRing, AFullRingHoldsTheProducerUntilASlotIsPopped) {
    SpscRing<int> ring(3);
    std::atomic<int> committed{0};
    std::thread producer([&] {
        for (int i = 0; i < 5; ++i) {
            int* slot = ring.acquire();
            ASSERT_NE(slot, nullptr);
            *slot = i;
            ring.commit();
            committed.fetch_add(1);
        }
        ring.close();
    });
    while (committed.load() < 3) std::this_thread::sleep_for(1ms);
    std::this_thread::sleep_for(50ms);
    EXPECT_EQ(committed.load(), 3);  // bounded: the fourth waits for a free slot
    ASSERT_NE(ring.front(), nullptr);
    EXPECT_EQ(*ring.front(), 0);
    ring.pop();
    std::vector<int> rest;
    while (const int* v = ring.front()) {
        rest.push_back(*v);
        ring.pop();
    }
    producer.join();
    EXPECT_EQ(rest, (std::vector<int>{1, 2, 3, 4}));
    EXPECT_GE(ring.sleeps(), 1u);  // the producer slept on the full ring
}

TEST(SpscRing, CloseLetsTheConsumerDrainThenEnds) {
    SpscRing<int> ring(4);
    for (int i = 0; i < 2; ++i) {
        *ring.acquire() = i;
        ring.commit();
    }
    ring.close();
    ASSERT_NE(ring.front(), nullptr);
    EXPECT_EQ(*ring.front(), 0);
    ring.pop();
    ASSERT_NE(ring.front(), nullptr);
    EXPECT_EQ(*ring.front(), 1);
    ring.pop();
    EXPECT_EQ(ring.front(), nullptr);
    EXPECT_EQ(ring.front(), nullptr);  // and stays ended
}

// A consumer waiting on an empty ring wakes when the producer closes it.
TEST(SpscRing, CloseWakesAWaitingConsumer) {
    SpscRing<int> ring(2);
    std::thread consumer([&] { EXPECT_EQ(ring.front(), nullptr); });
    std::this_thread::sleep_for(20ms);
    ring.close();
    consumer.join();
}

// The consumer gives up (it failed): a producer waiting on the full ring is released, and every
// later acquire() says so at once.
TEST(SpscRing, CancelReleasesAWaitingProducer) {
    SpscRing<int> ring(2);
    std::atomic<bool> released{false};
    std::thread producer([&] {
        for (;;) {
            int* slot = ring.acquire();
            if (slot == nullptr) break;
            ring.commit();
        }
        released = true;
    });
    std::this_thread::sleep_for(30ms);
    EXPECT_FALSE(released.load());  // waiting on the full ring
    ring.cancel();
    producer.join();
    EXPECT_TRUE(released.load());
    EXPECT_TRUE(ring.cancelled());
    EXPECT_EQ(ring.acquire(), nullptr);
}

// A consumer thread that takes every slot of `ring` until its end, counting each in `taken`.
std::thread counting_consumer(SpscRing<int>& ring, std::atomic<int>& taken) {
    return std::thread([&ring, &taken] {
        while (ring.front() != nullptr) {
            ring.pop();
            taken.fetch_add(1);
        }
    });
}

// A producer thread that commits 0..n-1 to `ring`, counting each in `given`, and closes the
// ring after the last (it stops where the consumer cancelled).
std::thread counting_producer(SpscRing<int>& ring, int n, std::atomic<int>& given) {
    return std::thread([&ring, n, &given] {
        for (int i = 0; i < n; ++i) {
            int* slot = ring.acquire();
            if (slot == nullptr) return;
            *slot = i;
            ring.commit();
            given.fetch_add(1);
        }
        ring.close();
    });
}

// A sleeping consumer is woken once `wake_after` slots are ready, not for each one; closing
// wakes it whatever is ready.
TEST(SpscRing, ASleepingSideWakesForSeveralSlots) {
    SpscRing<int> ring(8, 4);
    std::atomic<int> taken{0};
    std::thread consumer = counting_consumer(ring, taken);
    std::this_thread::sleep_for(30ms);  // the consumer is asleep on the empty ring
    for (int i = 0; i < 3; ++i) {
        *ring.acquire() = i;
        ring.commit();
    }
    std::this_thread::sleep_for(50ms);
    EXPECT_EQ(taken.load(), 0);  // three ready: not yet woken
    *ring.acquire() = 3;
    ring.commit();
    for (int i = 0; i < 1000 && taken.load() < 4; ++i) std::this_thread::sleep_for(1ms);
    EXPECT_EQ(taken.load(), 4);
    std::this_thread::sleep_for(30ms);  // asleep again
    *ring.acquire() = 4;
    ring.commit();
    ring.close();  // one ready, and the end: woken
    consumer.join();
    EXPECT_EQ(taken.load(), 5);
}

// Each side has a count of its own (the read-ahead's ring: its reader woken for many free
// slots, its executor for the first committed). A consumer asleep on the empty ring wakes for
// one slot; a producer asleep on the full ring only once four are free; each side's sleeps are
// counted apart.
TEST(SpscRing, EachSideWakesForItsOwnCount) {
    SpscRing<int> ring(8, 4, 1);
    std::atomic<int> taken{0};
    std::thread consumer = counting_consumer(ring, taken);
    for (int i = 0; i < 2000 && ring.consumer_sleeps() == 0; ++i) std::this_thread::sleep_for(1ms);
    ASSERT_EQ(ring.consumer_sleeps(), 1u);  // asleep on the empty ring
    *ring.acquire() = 0;
    ring.commit();
    for (int i = 0; i < 2000 && taken.load() < 1; ++i) std::this_thread::sleep_for(1ms);
    EXPECT_EQ(taken.load(), 1);  // one ready: woken
    ring.close();
    consumer.join();
    EXPECT_EQ(ring.producer_sleeps(), 0u);

    SpscRing<int> full(8, 4, 1);
    std::atomic<int> given{0};
    std::thread producer = counting_producer(full, 12, given);
    for (int i = 0; i < 2000 && full.producer_sleeps() == 0; ++i) std::this_thread::sleep_for(1ms);
    ASSERT_EQ(full.producer_sleeps(), 1u);  // asleep on the full ring
    EXPECT_EQ(given.load(), 8);
    for (int i = 0; i < 3; ++i) {
        ASSERT_NE(full.front(), nullptr);
        full.pop();
    }
    std::this_thread::sleep_for(50ms);
    EXPECT_EQ(given.load(), 8);  // three free: not yet woken
    ASSERT_NE(full.front(), nullptr);
    full.pop();
    for (int i = 0; i < 2000 && given.load() < 12; ++i) std::this_thread::sleep_for(1ms);
    EXPECT_EQ(given.load(), 12);  // four free: woken, and the last four fit
    producer.join();              // and closed
    int rest = 0;
    while (full.front() != nullptr) {
        full.pop();
        ++rest;
    }
    EXPECT_EQ(rest, 8);
    EXPECT_EQ(full.consumer_sleeps(), 0u);  // something was always there, or the end
    EXPECT_EQ(ring.sleeps(), ring.producer_sleeps() + ring.consumer_sleeps());
    EXPECT_EQ(full.sleeps(), full.producer_sleeps() + full.consumer_sleeps());
}

// The other way round: a producer woken for one free slot while the consumer's count is four,
// and a count above half the ring taken as half (a sleeper would otherwise wait for more than
// the other side may ever leave it).
TEST(SpscRing, AProducerWakesForItsCountEvenBelowTheConsumersAndNoCountExceedsHalf) {
    // The producer asleep on a full ring; `pops` slots freed one by one; how many it had given
    // `wait_ms` later at most (9 once woken, 8 while still asleep).
    const auto given_after = [](SpscRing<int>& ring, int pops, int wait_ms) {
        std::atomic<int> given{0};
        std::thread producer = counting_producer(ring, 9, given);
        for (int i = 0; i < 2000 && ring.producer_sleeps() == 0; ++i)
            std::this_thread::sleep_for(1ms);
        EXPECT_EQ(ring.producer_sleeps(), 1u);
        for (int i = 0; i < pops; ++i) {
            EXPECT_NE(ring.front(), nullptr);
            ring.pop();
        }
        for (int i = 0; i < wait_ms && given.load() < 9; ++i) std::this_thread::sleep_for(1ms);
        const int seen = given.load();
        ring.cancel();  // a producer still asleep takes no more
        producer.join();
        return seen;
    };
    SpscRing<int> one(8, 1, 4);
    EXPECT_EQ(given_after(one, 1, 2000), 9);  // one free: woken
    SpscRing<int> half(8, 100, 100);
    EXPECT_EQ(given_after(half, 3, 50), 8);  // three free: asleep
    SpscRing<int> half_again(8, 100, 100);
    EXPECT_EQ(given_after(half_again, 4, 2000), 9);  // four free (half of 8): woken
}

// flush() wakes a consumer asleep for several slots for the one committed (a producer that
// waits on the consumer's answer to it).
TEST(SpscRing, FlushWakesASleepingConsumerForWhatIsThere) {
    SpscRing<int> ring(8, 4);
    std::atomic<int> taken{0};
    std::thread consumer = counting_consumer(ring, taken);
    std::this_thread::sleep_for(30ms);  // the consumer is asleep on the empty ring
    *ring.acquire() = 1;
    ring.commit();
    std::this_thread::sleep_for(50ms);
    EXPECT_EQ(taken.load(), 0);  // one ready: not yet woken
    ring.flush();
    for (int i = 0; i < 5000 && taken.load() < 1; ++i) std::this_thread::sleep_for(1ms);
    EXPECT_EQ(taken.load(), 1);
    ring.close();
    consumer.join();
}

// ---- the pipeline

using apci::test::baseline_thread_count;
using apci::test::thread_count;

PathSegment segment(std::int64_t n) {
    PathSegment s;
    s.block.number = n;
    s.start = Point(static_cast<double>(n), 0.0, 0.0);
    s.end = Point(static_cast<double>(n) + 1.0, 0.5, -0.25);
    return s;
}

// Writes down every call it gets, and on which thread; throws at the `fail_at`-th executed
// segment when asked to.
class Recorder final : public RunSink {
  public:
    std::vector<std::string> calls;
    std::thread::id thread;
    std::uint64_t fail_at = 0;
    std::uint64_t executed_count = 0;
    bool want_programmed = true;
    bool want_samples = true;

    void programmed(const PathSegment& s) override { note("p" + std::to_string(s.block.number)); }
    bool wants_programmed() const override { return want_programmed; }
    bool take_programmed = true;
    bool takes_programmed() const override { return take_programmed; }
    void executed(const PathSegment& s) override {
        if (++executed_count == fail_at) throw std::runtime_error("writer failed");
        note("e" + std::to_string(s.block.number) + "," + std::to_string(s.end.x()) + "," +
             std::to_string(s.end.z()));
    }
    void axes(std::span<const std::string> names) override {
        std::string t = "axes";
        for (const auto& n : names) t += " " + n;
        note(t);
    }
    void axis_numbers(const std::array<int, 3>& xyz) override {
        note("xyz " + std::to_string(xyz[0]) + std::to_string(xyz[1]) + std::to_string(xyz[2]));
    }
    bool wants_samples() const override { return want_samples; }
    void sample(std::uint64_t cycle, double time_s, std::span<const double> axes) override {
        std::string t = "s" + std::to_string(cycle) + "@" + std::to_string(time_s);
        for (const double a : axes) t += " " + std::to_string(a);
        note(t);
    }
    void error(const RunError& e, const Point& where) override {
        note("error " + e.code + " " + e.message + " " + std::to_string(where.y()));
    }
    void warning(const RunError& w, const Point& where) override {
        note("warning " + w.code + " " + std::to_string(where.x()));
    }

  private:
    void note(std::string text) {
        thread = std::this_thread::get_id();
        calls.push_back(std::move(text));
    }
};

// Many batches of every kind of event: what the inner sink gets, in order.
void feed(RunSink& sink, int moves) {
    const std::vector<std::string> names{"X", "Y", "Z", "A", "B", "C", "U", "V"};
    sink.axes(names);
    sink.axis_numbers({1, 0, 2});
    for (int i = 0; i < moves; ++i) {
        sink.programmed(segment(i));
        sink.executed(segment(i));
        const double axes[APCI_AXIS_COUNT] = {1.0 * i, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.5};
        sink.sample(static_cast<std::uint64_t>(i), 0.001 * i, axes);
        if (i % 997 == 0)
            sink.warning(RunError{BlockRef{i, 0}, "SelfApproach", "close"},
                         Point(static_cast<double>(i), 1.0, 2.0));
    }
    sink.error(RunError{BlockRef{moves, 3}, "KorrError", "the board's words"}, Point(0, 7.5, 0));
}

// 36,000 events: the ring's 28 batches of 512 each filled twice and more.
TEST(RunPipeline, TheInnerSinkGetsEveryCallInOrderOnTheWriterThread) {
    Recorder direct;
    feed(direct, 12000);
    Recorder inner;
    {
        PipelinedSink pipeline(inner);
        feed(pipeline, 12000);
        pipeline.finish();
    }
    EXPECT_EQ(inner.calls, direct.calls);
    EXPECT_EQ(inner.calls.size(), 3u * 12000 + 2 + 13 + 1);
    EXPECT_NE(inner.thread, std::this_thread::get_id());
}

// An inner sink that takes no programmed moves (apcictl without a plot) gets every other call,
// in order, and the moves are not handed over at all.
TEST(RunPipeline, ProgrammedMovesAreNotHandedToASinkThatTakesNone) {
    Recorder direct;
    feed(direct, 3000);
    std::vector<std::string> expected;
    for (const std::string& c : direct.calls)
        if (!c.starts_with("p")) expected.push_back(c);
    ASSERT_LT(expected.size(), direct.calls.size());  // the feed has programmed moves
    Recorder inner;
    inner.take_programmed = false;
    {
        PipelinedSink pipeline(inner);
        EXPECT_FALSE(pipeline.takes_programmed());
        feed(pipeline, 3000);
        pipeline.finish();
    }
    EXPECT_EQ(inner.calls, expected);
    Recorder taking;
    PipelinedSink pipeline(taking);
    EXPECT_TRUE(pipeline.takes_programmed());
}

TEST(RunPipeline, WantsAndProgressAreAskedOfTheInnerSinkAtOnce) {
    Recorder inner;
    PipelinedSink pipeline(inner);
    EXPECT_TRUE(pipeline.wants_programmed());
    EXPECT_TRUE(pipeline.wants_samples());
    inner.want_programmed = false;
    inner.want_samples = false;
    EXPECT_FALSE(pipeline.wants_programmed());
    EXPECT_FALSE(pipeline.wants_samples());
    pipeline.finish();
    EXPECT_TRUE(inner.calls.empty());
}

// The writer throws mid-run: the producer is not held (it would wait on the full ring for
// ever), the rest is dropped, finish() rethrows, and the thread is gone.
TEST(RunPipeline, AWriterFailureReachesTheCallerAndHoldsNothing) {
    const int threads = baseline_thread_count();
    Recorder inner;
    inner.fail_at = 1000;
    PipelinedSink pipeline(inner);
    for (int i = 0; i < 200000; ++i) pipeline.executed(segment(i));
    try {
        pipeline.finish();
        ADD_FAILURE() << "finish() did not rethrow the writer's failure";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "writer failed");
    }
    EXPECT_EQ(inner.calls.size(), 999u);
    EXPECT_EQ(thread_count(), threads);
    pipeline.finish();  // once is enough: nothing more to rethrow or join
}

TEST(RunPipeline, NoThreadOutlivesItOnAnyPath) {
    const int threads = baseline_thread_count();
    ASSERT_GT(threads, 0);
    {
        Recorder inner;
        PipelinedSink pipeline(inner);
        pipeline.finish();  // no event: no thread was started
        EXPECT_EQ(thread_count(), threads);
    }
    {
        Recorder inner;
        PipelinedSink pipeline(inner);
        feed(pipeline, 3000);
        EXPECT_EQ(thread_count(), threads + 1);
        pipeline.finish();
        EXPECT_EQ(thread_count(), threads);
    }
    {
        // Left without finish() (an exception on the caller's side): the destructor ends it.
        Recorder inner;
        try {
            PipelinedSink pipeline(inner);
            feed(pipeline, 3000);
            throw std::runtime_error("caller failed");
        } catch (const std::runtime_error&) {
        }
        EXPECT_EQ(thread_count(), threads);
    }
}

// The executor hands the pipeline its executed segments unmeasured: the writer thread measures
// each before the inner sink has it and sums the lengths in their order, the same bits as
// count_segment() on the caller's thread.
TEST(RunPipeline, TheWriterMeasuresTheExecutedSegmentsAndSumsTheirLengthsInOrder) {
    class Lengths final : public RunSink {
      public:
        std::vector<double> lengths, sweeps;
        void executed(const PathSegment& s) override {
            lengths.push_back(s.length);
            sweeps.push_back(s.sweep);
        }
    } inner;
    std::vector<PathSegment> segments;
    for (int i = 0; i < 3000; ++i) {
        PathSegment s = segment(i);
        if (i % 3 == 1) {
            s.kind = SegmentKind::kArc;
            s.start = Point(10.0 + 0.001 * i, 0.0, 0.0);
            s.end = Point(0.0, 10.0, 0.01 * i);
            s.center = Point(0.0, 0.0, 0.0);
            s.ccw = (i % 2) == 0;
        } else if (i % 7 == 0) {
            s.kind = SegmentKind::kRapid;
        }
        segments.push_back(s);
    }
    RunTotals expected;
    for (PathSegment s : segments) {
        measure(s);
        count_segment(expected, s);
    }
    PipelinedSink pipeline(inner);
    EXPECT_TRUE(pipeline.measures_executed());
    double path = -1.0, rapid = -1.0;
    pipeline.measured_lengths(path, rapid);  // nothing handed over yet
    EXPECT_EQ(path, 0.0);
    EXPECT_EQ(rapid, 0.0);
    for (const PathSegment& s : segments) pipeline.executed(s);
    pipeline.measured_lengths(path, rapid);  // waits for the writer
    EXPECT_EQ(path, expected.path_length);   // bit for bit
    EXPECT_EQ(rapid, expected.rapid_length);
    EXPECT_GT(rapid, 0.0);
    ASSERT_EQ(inner.lengths.size(), segments.size());  // every one had before the answer
    for (std::size_t i = 0; i < segments.size(); ++i) {
        EXPECT_EQ(inner.lengths[i], segment_length(segments[i])) << i;
        if (segments[i].kind == SegmentKind::kArc) {
            EXPECT_EQ(inner.sweeps[i], arc_sweep(segments[i])) << i;
        }
    }
    pipeline.finish();
    pipeline.measured_lengths(path, rapid);  // after the end: the same sums
    EXPECT_EQ(path, expected.path_length);
}

// A pipeline fed by another (the check's, ProgramRun) has its segments measured already: it
// takes their lengths as they come and measures only those that come unmeasured.
TEST(RunPipeline, ASegmentThatComesMeasuredIsNotMeasuredAgain) {
    class Lengths final : public RunSink {
      public:
        std::vector<double> lengths;
        void executed(const PathSegment& s) override { lengths.push_back(s.length); }
    } inner;
    PathSegment measured = segment(1), unmeasured = segment(2);
    measure(measured);
    measured.length += 0.5;  // not what measure() gives: seen as it came
    PipelinedSink pipeline(inner);
    pipeline.executed(measured);
    pipeline.executed(unmeasured);
    double path = 0.0, rapid = 0.0;
    pipeline.measured_lengths(path, rapid);
    pipeline.finish();
    ASSERT_EQ(inner.lengths.size(), 2u);
    EXPECT_EQ(inner.lengths[0], measured.length);
    EXPECT_EQ(inner.lengths[1], segment_length(unmeasured));
    EXPECT_EQ(path, measured.length + segment_length(unmeasured));
}

// A pipeline whose inner sink measures the segments itself (a second pipeline, as ProgramRun
// puts one behind the check) hands them on as they came and gives the inner sink's sums, asked
// once the inner sink has had every segment.
TEST(RunPipeline, WhereTheInnerSinkMeasuresTheSegmentsGoOnUnmeasured) {
    class Measuring final : public RunSink {
      public:
        std::vector<double> lengths;
        bool measures_executed() const override { return true; }
        void executed(const PathSegment& s) override { lengths.push_back(s.length); }
        void measured_lengths(double& path, double& rapid) override {
            path = 42.0 + static_cast<double>(lengths.size());
            rapid = 7.0;
        }
    } inner;
    PathSegment measured = segment(1);
    measure(measured);
    PipelinedSink pipeline(inner);
    EXPECT_TRUE(pipeline.measures_executed());
    pipeline.executed(segment(2));
    pipeline.executed(measured);
    double path = 0.0, rapid = 0.0;
    pipeline.measured_lengths(path, rapid);
    EXPECT_EQ(path, 44.0);  // the inner sink's, after both segments
    EXPECT_EQ(rapid, 7.0);
    pipeline.finish();
    ASSERT_EQ(inner.lengths.size(), 2u);
    EXPECT_TRUE(std::isnan(inner.lengths[0]));
    EXPECT_EQ(inner.lengths[1], measured.length);
}

// A writer that failed does not hold measured_lengths().
TEST(RunPipeline, MeasuredLengthsDoesNotWaitForAWriterThatFailed) {
    Recorder inner;
    inner.fail_at = 10;
    PipelinedSink pipeline(inner);
    for (int i = 0; i < 100000; ++i) pipeline.executed(segment(i));
    double path = 0.0, rapid = 0.0;
    pipeline.measured_lengths(path, rapid);
    EXPECT_GT(path, 0.0);  // what the writer summed before it failed
    EXPECT_THROW(pipeline.finish(), std::runtime_error);
}

// The writer thread leaves the process's signals to the caller's thread (whose DeferSignals
// holds them while a temporary file is made or published) and keeps those a write raises in
// its own thread (SIGPIPE, SIGXFSZ), which end the process as before.
TEST(RunPipeline, TheWriterThreadLeavesProcessSignalsToTheCaller) {
    class MaskProbe final : public RunSink {
      public:
        sigset_t mask{};
        void executed(const PathSegment&) override { ::pthread_sigmask(SIG_BLOCK, nullptr, &mask); }
    } probe;
    {
        PipelinedSink pipeline(probe);
        pipeline.executed(segment(1));
        pipeline.finish();
    }
    for (const int sig : {SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGUSR1, SIGALRM})
        EXPECT_EQ(sigismember(&probe.mask, sig), 1) << sig;
    for (const int sig : {SIGPIPE, SIGXFSZ, SIGSEGV})
        EXPECT_EQ(sigismember(&probe.mask, sig), 0) << sig;
    sigset_t mine;
    ::pthread_sigmask(SIG_BLOCK, nullptr, &mine);
    EXPECT_EQ(sigismember(&mine, SIGTERM), 0);  // the caller's mask is as it was
}

// ---- a run through the pipeline: the same bytes

std::string program_text(int turns) {
    return apci::test::plate_program(turns);
}

class JsonAndSvg final : public RunSink {
  public:
    JsonAndSvg(std::FILE* json, std::FILE* svg) : json_(json), svg_file_(svg) {}
    void programmed(const PathSegment& s) override { svg_.programmed(s); }
    bool wants_programmed() const override { return true; }
    void executed(const PathSegment& s) override {
        json_.segment(s);
        svg_.executed(s);
    }
    void error(const RunError& e, const Point& where) override {
        svg_.error_marker(e.block, where, e.code);
    }
    bool finish(const RunOutcome& out) {
        return json_.finish(out.errors, out.registers, out.variables, out.notices, out.warnings) &&
               svg_.finish(svg_file_, out.plot_plane, "p.nc");
    }

  private:
    JsonRunWriter json_;
    SvgPlotWriter svg_;
    std::FILE* svg_file_;
};

struct Written {
    std::string json, svg, summary;
    RunTotals totals;
};

Written run_written(const std::string& text, bool pipelined) {
    auto tools =
        nc::parse_tool_table("wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 1\n", "t.tools");
    EXPECT_TRUE(tools);
    apci::Board board("emu:");
    nc::InterpreterOptions options;
    options.tools = &tools.value();
    auto program = nc::Program::from_text(text, "p.nc", options);
    EXPECT_TRUE(program);
    auto stream = program.value().events();
    apci_test::MemoryFile json, svg;
    JsonAndSvg writers(json.get(), svg.get());
    PipelinedSink pipeline(writers);
    RunSink* sink = &writers;
    if (pipelined) sink = &pipeline;
    ProgramExecutor executor(board, *sink, &tools.value());
    RunOutcome out = executor.run(stream.value());
    pipeline.finish();
    EXPECT_TRUE(writers.finish(out));
    Written w{json.text(), svg.text(), {}, {}};
    w.summary = std::to_string(out.totals.segments) + " " + std::to_string(out.totals.path_length);
    w.totals = out.totals;
    return w;
}

TEST(RunPipeline, ARunWritesTheSameBytesThroughThePipeline) {
    const std::string text = program_text(400);  // about 5,600 segments: many batches
    const Written direct = run_written(text, false);
    const Written piped = run_written(text, true);
    EXPECT_GT(direct.json.size(), 500000u);
    EXPECT_EQ(piped.json, direct.json);
    EXPECT_EQ(piped.svg, direct.svg);
    EXPECT_EQ(piped.summary, direct.summary);
}

// The lengths measured and summed on the writer thread are those the executor sums itself.
TEST(RunPipeline, ARunThroughThePipelineHasTheSameTotalsBitForBit) {
    const std::string text = program_text(200);
    const Written direct = run_written(text, false);
    const Written piped = run_written(text, true);
    EXPECT_GT(direct.totals.path_length, 10000.0);
    EXPECT_EQ(piped.totals.path_length, direct.totals.path_length);
    EXPECT_EQ(piped.totals.rapid_length, direct.totals.rapid_length);
    EXPECT_EQ(piped.totals.segments, direct.totals.segments);
    EXPECT_EQ(piped.json, direct.json);
}

// ---- the self-approach check on the writer thread

// A spike: N60 is 1.1 mm long and its neighbours come back within the tool's 5 mm of each
// other (three SelfApproach warnings with tool radius 5).
const char* const kSpike =
    "N10 G17 G90 G26 D1 F600\nN20 G0 X-74.257 Y-49.657\nN30 G42 G1 X-35.095 Y-27.491\n"
    "N50 G1 X-4.063 Y-82.318\nN60 G1 X-4.273 Y-81.223\nN70 G1 X-34.475 Y-136.512\n"
    "N80 G1 X-50 Y-150\nN90 G40 G1 X-73.967 Y-114.939\nN100 M30\n";

struct CheckedRun {
    std::vector<std::string> calls;  // what the sink got, in order
    std::vector<std::string> warnings, errors;
};

// The spike run as a program is run (program_run.h): with threads (the check, where it only
// warns, behind the pipeline on the writer thread; where it stops the run, before it) or all on
// the caller's thread.
CheckedRun run_spike(bool threads, SelfApproachMode mode) {
    RunInputFiles files;
    files.tools = "wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n";
    files.tools_is_text = true;
    auto inputs = load_run_inputs(files);
    EXPECT_TRUE(inputs);
    apci::Board board("emu:");
    Recorder recorder;
    recorder.want_samples = false;
    RunSettings settings;
    settings.threads = threads;
    settings.self_approach = mode;
    auto out = apci::run::run_program(board, recorder, inputs.value(),
                                      ProgramSource::in_memory(kSpike, "spike.nc"), settings);
    EXPECT_TRUE(out);
    CheckedRun r;
    r.calls = recorder.calls;
    for (const RunError& w : out.value().warnings)
        r.warnings.push_back(block_text(w.block) + " " + w.code + " " + w.message);
    for (const RunError& e : out.value().errors)
        r.errors.push_back(block_text(e.block) + " " + e.code + " " + e.message);
    return r;
}

// Where the check only warns, the writer thread runs it: the same warnings, given to the writers
// at the same places among the moves and segments, and the same in the run's outcome.
TEST(RunPipeline, TheWriterThreadRunsTheSelfApproachCheckWithTheSameWarnings) {
    const CheckedRun direct = run_spike(false, SelfApproachMode::kWarn);
    const CheckedRun piped = run_spike(true, SelfApproachMode::kWarn);
    EXPECT_EQ(direct.warnings.size(), 3u);
    EXPECT_TRUE(direct.errors.empty());
    EXPECT_EQ(piped.warnings, direct.warnings);
    EXPECT_EQ(piped.calls, direct.calls);
    EXPECT_EQ(piped.errors, direct.errors);
}

// Where a finding stops the run (--self-approach=error), the check runs on the executor's
// thread: the same error, at the same place.
TEST(RunPipeline, ASelfApproachErrorStopsTheRunAsWithoutThePipeline) {
    const CheckedRun direct = run_spike(false, SelfApproachMode::kError);
    const CheckedRun piped = run_spike(true, SelfApproachMode::kError);
    ASSERT_EQ(direct.errors.size(), 1u);
    EXPECT_NE(direct.errors[0].find("SelfApproach"), std::string::npos) << direct.errors[0];
    EXPECT_EQ(piped.errors, direct.errors);
    EXPECT_EQ(piped.calls, direct.calls);
    EXPECT_TRUE(piped.warnings.empty());
}

// A sink of the executor's own: the compensated stretches in their place among the moves, and
// nothing checked by the executor itself (the check is a sink, self_approach_sink.h): no
// warning, though the program comes near itself. Through the pipeline, the same calls.
class Stretches final : public RunSink {
  public:
    std::vector<std::string> calls;
    std::int64_t stop_at = -1;  // take_stop() hands an error after this block's move
    bool stop_at_end = false;   // take_stop() hands an error after the first stretch's end
    std::vector<std::int64_t> executed_blocks;  // the blocks of the executed segments, in order
    void programmed(const PathSegment& s) override {
        calls.push_back("p" + std::to_string(s.block.number));
        last_ = s.block.number;
    }
    void executed(const PathSegment& s) override {
        if (executed_blocks.empty() || executed_blocks.back() != s.block.number)
            executed_blocks.push_back(s.block.number);
    }
    void stretch_begin(const CompensatedStretch& s) override {
        calls.push_back("begin " + std::to_string(s.radius) + " " + std::to_string(s.plane) + " " +
                        std::to_string(s.side) + (s.edge.isZero(0.0) ? "" : " edge"));
    }
    void stretch_end() override {
        calls.emplace_back("end");
        ended_ = true;
    }
    void walls(bool on) override { calls.emplace_back(on ? "CDON" : "CDOF"); }
    void error(const RunError& e, const Point&) override { calls.push_back("error " + e.code); }
    std::optional<RunError> take_stop() override {
        if (stop_at_end && ended_) {
            stop_at_end = false;
            return RunError{BlockRef{last_, 0}, "Stopped", "at the end of the stretch"};
        }
        if (last_ != stop_at) return std::nullopt;
        last_ = -1;
        return RunError{BlockRef{stop_at, 0}, "Stopped", "by the sink"};
    }

  private:
    std::int64_t last_ = -1;
    bool ended_ = false;
};

RunOutcome run_spike_into(RunSink& sink, const char* text = kSpike) {
    auto tools =
        nc::parse_tool_table("wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 5\n", "t.tools");
    EXPECT_TRUE(tools);
    apci::Board board("emu:");
    nc::InterpreterOptions options;
    options.tools = &tools.value();
    auto program = nc::Program::from_text(text, "spike.nc", options);
    EXPECT_TRUE(program) << program.error().to_string();
    auto stream = program.value().events();
    ProgramExecutor executor(board, sink, &tools.value());
    return executor.run(stream.value());
}

TEST(RunPipeline, TheExecutorGivesTheStretchesInTheirPlaceAndChecksNothingItself) {
    Stretches direct;
    const RunOutcome out = run_spike_into(direct);
    EXPECT_TRUE(out.warnings.empty());
    EXPECT_TRUE(out.self_approach.empty());
    EXPECT_TRUE(out.errors.empty());
    // G42 begins the stretch before its block's move (N30); G40 ends it before N90 departs.
    const std::vector<std::string> expected{
        "p20", "begin 5.000000 17 -1", "p30", "p50", "p60", "p70", "p80", "end", "p90"};
    EXPECT_EQ(direct.calls, expected);
    Stretches inner;
    {
        PipelinedSink pipeline(inner);
        (void)run_spike_into(pipeline);
        pipeline.finish();
    }
    EXPECT_EQ(inner.calls, expected);
}

// The stretch runs from G41 to G40: a G0 between is compensated as a traverse and leaves it
// open; CDOF and CDON go to the sink in their place.
TEST(RunPipeline, TheStretchRunsFromG41ToG40AndCdofCdonGoInTheirPlace) {
    Stretches sink;
    const RunOutcome out = run_spike_into(
        sink,
        "N10 G17 G90 D1 F600\nN20 G41 G1 X0 Y0\nN30 X20\nN40 G0 X30\nN50 CDOF\nN60 G1 X40\n"
        "N70 CDON\nN80 G0 X50\nN90 G0 X60\nN100 G40 G1 X70\nN110 M30\n");
    for (const RunError& e : out.errors) ADD_FAILURE() << e.message;
    const std::vector<std::string> expected{"begin 5.000000 17 1",
                                            "p20",
                                            "p30",
                                            "p40",
                                            "CDOF",
                                            "p60",
                                            "CDON",
                                            "p80",
                                            "p90",
                                            "end",
                                            "p100"};
    EXPECT_EQ(sink.calls, expected);
}

// The first n calls a sink got (all of them where it got fewer).
std::vector<std::string> first_calls(const Stretches& sink, std::size_t n) {
    return std::vector<std::string>(
        sink.calls.begin(),
        sink.calls.begin() + static_cast<std::ptrdiff_t>(std::min(sink.calls.size(), n)));
}

// A sink's take_stop() stops the run where it was asked: the error recorded with its block, the
// sink told, nothing programmed after it.
TEST(RunPipeline, ASinkThatHandsAStopEndsTheRunThere) {
    Stretches sink;
    sink.stop_at = 60;
    const RunOutcome out = run_spike_into(sink);
    ASSERT_EQ(out.errors.size(), 1u);
    EXPECT_EQ(out.errors[0].code, "Stopped");
    EXPECT_EQ(out.errors[0].block.number, 60);
    EXPECT_EQ(out.errors[0].block.line, 5u);  // the line from the move programmed
    const std::vector<std::string> expected{"p20", "begin 5.000000 17 -1", "p30", "p50",
                                            "p60", "error Stopped"};
    EXPECT_EQ(first_calls(sink, expected.size()), expected);
    for (const std::string& c : sink.calls) EXPECT_NE(c, "p70");
    // N60's move is not spooled: what runs out after the stop is the moves before the one the
    // board holds (N50, the corner to N60 not known).
    EXPECT_EQ(sink.executed_blocks, (std::vector<std::int64_t>{20, 30}));
}

// A stop handed at the end of a stretch (G40 ends it) ends the run there: the G40 block's move
// is neither programmed nor run.
TEST(RunPipeline, ASinkThatHandsAStopAtAStretchsEndEndsTheRunThere) {
    Stretches sink;
    sink.stop_at_end = true;
    const RunOutcome out = run_spike_into(sink);
    ASSERT_EQ(out.errors.size(), 1u);
    EXPECT_EQ(out.errors[0].code, "Stopped");
    EXPECT_EQ(out.errors[0].block.number, 80);
    const std::vector<std::string> expected{
        "p20", "begin 5.000000 17 -1", "p30", "p50", "p60", "p70", "p80", "end", "error Stopped"};
    EXPECT_EQ(first_calls(sink, expected.size()), expected);
    for (const std::string& c : sink.calls) EXPECT_NE(c, "p90");
    EXPECT_EQ(sink.executed_blocks, (std::vector<std::int64_t>{20, 30, 50, 60, 70, 80}));
}

// ---- segments read back once, measured once

// More segments than the in-process transport takes from the log per step (256), read in one
// call: every one, in order, as the board logged them.
TEST(SegmentReadBack, OneReadTakesEverySegmentInOrder) {
    apci::Board board("emu:");
    ASSERT_TRUE(board.is_open());
    constexpr std::uint32_t kMoves = 600;
    for (std::uint32_t i = 1; i <= kMoves; ++i) {
        apci_profile p{};
        p.kind = APCI_PROFILE_LINE;
        p.tag = i;
        p.feed = 6000.0;
        p.axes = 1u;
        p.target[0] = 0.1 * i;
        for (;;) {
            const auto r = board.spool(p);
            if (r.status != APCI_BUSY) {
                ASSERT_TRUE(r.ok()) << apci::status_name(r.status);
                break;
            }
            ASSERT_TRUE(board.run_until_idle(std::uint64_t{1} << 40));
        }
    }
    ASSERT_TRUE(board.run_until_idle(std::uint64_t{1} << 40));
    std::vector<apci_segment> out(1000);
    const auto r = board.read_segments(out.data(), out.size());
    ASSERT_TRUE(r);
    ASSERT_EQ(r.value, kMoves);
    for (std::uint32_t i = 0; i < kMoves; ++i) {
        EXPECT_EQ(out[i].tag, i + 1);
        EXPECT_EQ(out[i].end[0], 0.1 * (i + 1));
        EXPECT_EQ(out[i].start[0], i == 0 ? 0.0 : 0.1 * i);
    }
    const auto again = board.read_segments(out.data(), out.size());
    ASSERT_TRUE(again);
    EXPECT_EQ(again.value, 0u);  // taken: read once
}

TEST(SegmentReadBack, MeasureGivesTheSweepAndLengthOfThePathFunctions) {
    PathSegment arc;
    arc.kind = SegmentKind::kArc;
    arc.start = Point(10, 0, 0);
    arc.end = Point(0, 10, 2);
    arc.center = Point(0, 0, 0);
    arc.ccw = true;
    PathSegment programmed = arc;
    EXPECT_TRUE(std::isnan(programmed.length));  // not measured: computed where needed
    measure(arc);
    EXPECT_EQ(arc.sweep, arc_sweep(arc));
    EXPECT_EQ(arc.length, segment_length(arc));
    EXPECT_EQ(measured_length(programmed), segment_length(programmed));
    PathSegment line = segment(3);
    measure(line);
    EXPECT_EQ(line.sweep, 0.0);
    EXPECT_EQ(line.length, segment_length(line));
}

// The totals take the length the segment carries: it is not computed again.
TEST(SegmentReadBack, CountSegmentUsesTheMeasuredLength) {
    PathSegment s = segment(1);
    s.length = 42.0;  // not this line's length: only a carried value gives it
    RunTotals t;
    count_segment(t, s);
    EXPECT_EQ(t.path_length, 42.0);
    PathSegment unmeasured = segment(1);
    count_segment(t, unmeasured);
    EXPECT_EQ(t.path_length, 42.0 + segment_length(unmeasured));
}

// Every executed segment the executor hands on is measured, with the path functions' values.
TEST(SegmentReadBack, TheExecutorMeasuresEveryExecutedSegment) {
    class Check final : public RunSink {
      public:
        std::uint64_t executed_count = 0, wrong = 0;
        void executed(const PathSegment& s) override {
            ++executed_count;
            if (s.length != segment_length(s) ||
                (s.kind == SegmentKind::kArc && s.sweep != arc_sweep(s)))
                ++wrong;
        }
    } check;
    auto tools =
        nc::parse_tool_table("wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 1\n", "t.tools");
    ASSERT_TRUE(tools);
    apci::Board board("emu:");
    nc::InterpreterOptions options;
    options.tools = &tools.value();
    const std::string text = program_text(5);  // the program reads it as it goes
    auto program = nc::Program::from_text(text, "p.nc", options);
    ASSERT_TRUE(program);
    auto stream = program.value().events();
    ProgramExecutor executor(board, check, &tools.value());
    const RunOutcome out = executor.run(stream.value());
    EXPECT_TRUE(out.errors.empty()) << (out.errors.empty() ? "" : out.errors.front().message);
    EXPECT_GT(check.executed_count, 60u);
    EXPECT_EQ(check.wrong, 0u);
}

// A sink that measures the executed segments itself gets them unmeasured (the executor's
// thread does not compute their sweep and length), and the run's lengths are its sums.
TEST(SegmentReadBack, ASinkThatMeasuresGetsTheSegmentsUnmeasuredAndGivesTheLengths) {
    class Measures final : public RunSink {
      public:
        std::uint64_t executed_count = 0, measured = 0, asked = 0;
        RunTotals sums;
        void executed(const PathSegment& s) override {
            ++executed_count;
            if (!std::isnan(s.length) || !std::isnan(s.sweep)) ++measured;
            count_segment(sums, s);
        }
        bool measures_executed() const override { return true; }
        void measured_lengths(double& path, double& rapid) override {
            ++asked;
            path = sums.path_length;
            rapid = sums.rapid_length;
        }
    } sink;
    auto tools =
        nc::parse_tool_table("wz[1].gueltig 1\nwz[1].mass_einheit 1\nwz[1].radius 1\n", "t.tools");
    ASSERT_TRUE(tools);
    const std::string text = program_text(5);
    auto program = nc::Program::from_text(text, "p.nc");
    ASSERT_TRUE(program);
    auto stream = program.value().events();
    apci::Board board("emu:");
    ProgramExecutor executor(board, sink, &tools.value());
    const RunOutcome out = executor.run(stream.value());
    EXPECT_TRUE(out.errors.empty()) << (out.errors.empty() ? "" : out.errors.front().message);
    EXPECT_GT(sink.executed_count, 60u);
    EXPECT_EQ(sink.measured, 0u);
    EXPECT_EQ(sink.asked, 1u);
    EXPECT_EQ(out.totals.segments, sink.executed_count);
    EXPECT_EQ(out.totals.path_length, sink.sums.path_length);
    EXPECT_EQ(out.totals.rapid_length, sink.sums.rapid_length);
    EXPECT_GT(out.totals.path_length, 100.0);
}

// The executor's cycle check tells most moves from a bound without roots or angles; wherever the
// bound says "surely within", the exact check agrees, and a move beyond the limit is never
// passed by the bound.
TEST(SegmentReadBack, TheCycleBoundNeverPassesAMoveTheExactCheckRefuses) {
    std::uint64_t passed = 0, undecided = 0;
    std::uint32_t lcg = 12345;  // a fixed sequence of pseudo-random numbers in [0, 1)
    const auto next = [&] {
        lcg = lcg * 1664525u + 1013904223u;
        return static_cast<double>(lcg >> 8) / static_cast<double>(1u << 24);
    };
    for (int i = 0; i < 20000; ++i) {
        PathSegment s;
        s.kind = (i % 2) == 0 ? SegmentKind::kArc : SegmentKind::kLine;
        s.plane = 17 + (i % 3);
        const double scale = std::pow(10.0, 8.0 * next() - 2.0);  // 0.01 mm .. 1e6 mm
        s.start = Point(next(), next(), next()) * scale;
        s.end = Point(next(), next(), next()) * scale;
        s.center = Point(next(), next(), next()) * scale;
        s.ccw = next() < 0.5;
        const double feed = std::pow(10.0, 6.0 * next() - 5.0);  // 1e-5 .. 10 mm/min
        const double cycle = (i % 5) == 0 ? 0.00025 : 0.001;
        const bool exact_ok = nc::check_move_cycles(segment_length(s), feed, cycle).empty();
        if (surely_within_move_cycles(s, feed, cycle)) {
            ++passed;
            EXPECT_TRUE(exact_ok) << i;
        } else {
            ++undecided;
        }
    }
    EXPECT_GT(passed, 1000u);
    EXPECT_GT(undecided, 1000u);
    // A plain move: decided by the bound.
    PathSegment line = segment(1);
    EXPECT_TRUE(surely_within_move_cycles(line, 1000.0, 0.001));
    // Zero feed or cycle: never "surely".
    EXPECT_FALSE(surely_within_move_cycles(line, 0.0, 0.001));
    EXPECT_FALSE(surely_within_move_cycles(line, 1000.0, 0.0));
}

// ---- output files: large writes, write-back started while the run goes

// A file's bytes (empty if it cannot be read).
std::string read_whole(const std::string& path) {
    std::string text;
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (f == nullptr) return text;
    char buf[65536];
    std::size_t n = 0;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
    std::fclose(f);
    return text;
}

// 12 MiB through an OutputFile (three steps of early write-back and a tail): published whole,
// byte for byte, after the fsync at close().
TEST(OutputWriteBack, ALargeOutputIsPublishedWhole) {
    char dir_template[] = "/tmp/apci-writeback-XXXXXX";
    ASSERT_NE(::mkdtemp(dir_template), nullptr);
    const std::string dir = dir_template;
    const std::string target = dir + "/big.json";
    std::string expected;
    {
        OutputFile out;
        ASSERT_EQ(out.open(target), "");
        TextSink sink(out.file());
        std::string line;
        for (std::uint64_t i = 0; expected.size() < (std::size_t{12} << 20) + 12345; ++i) {
            line = "{\"n\":" + std::to_string(i * 7919) + "}\n";
            sink.append(line);
            expected += line;
        }
        ASSERT_TRUE(sink.flush());
        ASSERT_EQ(out.close(), "");
        ASSERT_EQ(out.publish(), "");
    }
    const std::string got = read_whole(target);
    EXPECT_TRUE(got == expected) << got.size() << " bytes, expected " << expected.size();
    std::remove(target.c_str());
    ::rmdir(dir.c_str());
}

// ---- the sync behind the writer: every 2 MiB, a thread of its own makes what was written
// durable, so that the fsync at close() has only the last step left

// The syncs a test's SyncCall was asked for, the file it was given (its inode), and how they
// answer: each sync whose number (from 0) is in `failing` fails with EIO, the others succeed.
std::atomic<int> g_syncs{0};
std::atomic<unsigned> g_failing{0};  // bit i: the sync numbered i fails
std::atomic<ino_t> g_synced_inode{0};
std::atomic<int> g_sync_ms{0};  // how long each sync takes (after it is counted)
int counted_sync(int fd) {
    struct stat st {};
    g_synced_inode = ::fstat(fd, &st) == 0 ? st.st_ino : 0;
    const int n = g_syncs.fetch_add(1);
    std::this_thread::sleep_for(std::chrono::milliseconds(g_sync_ms.load()));
    if (n < 32 && (g_failing.load() >> n & 1U) != 0) {
        errno = EIO;
        return -1;
    }
    return 0;
}
// Waits (at most 10 s) until the test's SyncCall was called `n` times.
bool syncs_reach(int n) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (g_syncs.load() < n && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(1ms);
    return g_syncs.load() >= n;
}

// A new directory made from `name_template` (mkdtemp: its last six characters XXXXXX); empty,
// with the test failed, where none can be made.
std::string made_dir(std::string name_template) {
    if (::mkdtemp(name_template.data()) == nullptr) {
        ADD_FAILURE() << "mkdtemp: " << std::strerror(errno);
        return {};
    }
    return name_template;
}

// An output in a directory of its own, syncing with counted_sync (counts reset), written in
// pieces of the sizes asked (each piece one write(2): the output's FILE is unbuffered).
struct SyncedOutput {
    std::string dir, target;
    OutputFile out;
    explicit SyncedOutput(unsigned failing = 0, int sync_ms = 0)
        : dir(made_dir("/tmp/apci-syncbehind-XXXXXX")) {
        g_syncs = 0;
        g_failing = failing;
        g_sync_ms = sync_ms;
        if (dir.empty()) return;
        target = dir + "/out.json";
        EXPECT_EQ(out.open(target), "");
        out.sync_with(&counted_sync);
    }
    ~SyncedOutput() {
        out.discard();
        std::remove(target.c_str());
        ::rmdir(dir.c_str());
    }
    SyncedOutput(const SyncedOutput&) = delete;
    SyncedOutput& operator=(const SyncedOutput&) = delete;
    void write(std::size_t bytes) {
        const std::string piece(bytes, 'x');
        ASSERT_EQ(std::fwrite(piece.data(), 1, piece.size(), out.file()), bytes);
    }
};
constexpr std::size_t kMiB = std::size_t{1} << 20;

// The step is checked where the write-back starts (every 1 MiB): 2 MiB less a byte made no
// thread and no sync; 2 MiB make the thread, which syncs once; the output is published whole.
TEST(SyncBehindTheWriter, TheFirstSyncComesAtTwoMiB) {
    {
        SyncedOutput o;
        ASSERT_FALSE(o.target.empty());
        o.write(kMiB);
        o.write(kMiB - 1);
        EXPECT_FALSE(o.out.syncs_behind());
        ASSERT_EQ(o.out.close(), "");
        EXPECT_EQ(g_syncs.load(), 0);
    }
    SyncedOutput o;
    ASSERT_FALSE(o.target.empty());
    o.write(kMiB);
    EXPECT_FALSE(o.out.syncs_behind());
    o.write(kMiB);
    EXPECT_TRUE(o.out.syncs_behind());
    EXPECT_TRUE(syncs_reach(1));
    struct stat st {};
    ASSERT_EQ(::stat(o.out.temporary().c_str(), &st), 0);
    EXPECT_EQ(g_synced_inode.load(), st.st_ino);  // the temporary file's data was synced
    ASSERT_EQ(o.out.close(), "");
    EXPECT_FALSE(o.out.syncs_behind());  // close() ended it
    EXPECT_EQ(g_syncs.load(), 1);        // nothing asked since: no sync more
    ASSERT_EQ(o.out.publish(), "");
    EXPECT_TRUE(read_whole(o.target) == std::string(2 * kMiB, 'x'));
}

// Each further 2 MiB asks again; between two steps nothing is asked: 5 MiB in pieces of 1 MiB
// make two syncs (at 2 and 4 MiB), 6 MiB three.
TEST(SyncBehindTheWriter, EachStepOfTwoMiBAsksOnce) {
    for (const int mib : {5, 6}) {
        SyncedOutput o;
        ASSERT_FALSE(o.target.empty());
        for (int i = 0; i < mib; ++i) {
            o.write(kMiB);
            // Each sync done before the next step: none is left out for one under way.
            if (i % 2 == 1) {
                EXPECT_TRUE(syncs_reach((i + 1) / 2)) << i;
            }
        }
        ASSERT_EQ(o.out.close(), "");
        EXPECT_EQ(g_syncs.load(), mib / 2) << mib;
    }
}

// A sync behind the writer that failed fails close(), with its cause, though every sync after
// it succeeded (the fsync at close() would not report it again); the output is not published.
TEST(SyncBehindTheWriter, AFailedSyncFailsTheClose) {
    std::string target;
    {
        SyncedOutput o(/*failing=*/1U);  // the first sync fails, the second succeeds
        ASSERT_FALSE(o.target.empty());
        target = o.target;
        o.write(2 * kMiB);
        ASSERT_TRUE(syncs_reach(1));
        o.write(2 * kMiB);
        ASSERT_TRUE(syncs_reach(2));
        EXPECT_EQ(o.out.close(), std::strerror(EIO));
    }
    EXPECT_NE(::access(target.c_str(), F_OK), 0);  // nothing published, no temporary left
    // Failing later instead: the same.
    SyncedOutput o(/*failing=*/2U);
    ASSERT_FALSE(o.target.empty());
    o.write(2 * kMiB);
    ASSERT_TRUE(syncs_reach(1));
    o.write(2 * kMiB);
    ASSERT_TRUE(syncs_reach(2));
    EXPECT_EQ(o.out.close(), std::strerror(EIO));
}

// close() waits for the sync under way: one that fails after close() was called fails it too.
TEST(SyncBehindTheWriter, CloseWaitsForTheSyncUnderWay) {
    SyncedOutput o(/*failing=*/1U, /*sync_ms=*/300);
    ASSERT_FALSE(o.target.empty());
    o.write(2 * kMiB);
    ASSERT_TRUE(syncs_reach(1));  // begun: it fails 300 ms from now
    EXPECT_EQ(o.out.close(), std::strerror(EIO));
    EXPECT_FALSE(o.out.syncs_behind());
}

// The threads of this process named `name` (/proc/self/task/*/comm).
int threads_named(const std::string& name) {
    int n = 0;
    std::error_code ec;
    for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec))
        if (read_whole(task.path().string() + "/comm") == name + "\n") ++n;
    return n;
}

// An output discarded (the run failed) ends the thread (`apci-sync`) before its descriptor is
// closed, and removes the temporary file; no thread outlives it.
TEST(SyncBehindTheWriter, DiscardEndsTheThread) {
    SyncedOutput o;
    ASSERT_FALSE(o.target.empty());
    o.write(2 * kMiB);
    ASSERT_TRUE(o.out.syncs_behind());
    const std::string temporary = o.out.temporary();
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (threads_named("apci-sync") == 0 && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(1ms);  // it names itself once it runs
    EXPECT_EQ(threads_named("apci-sync"), 1);
    o.out.discard();
    EXPECT_FALSE(o.out.syncs_behind());
    EXPECT_EQ(threads_named("apci-sync"), 0);
    EXPECT_NE(::access(temporary.c_str(), F_OK), 0);
}

// Standard output and a target written in place (not a regular file) are never synced behind:
// there is no temporary file to make durable before a rename.
TEST(SyncBehindTheWriter, NoneForAnOutputWrittenInPlace) {
    g_syncs = 0;
    OutputFile out;
    ASSERT_EQ(out.open("/dev/null"), "");
    out.sync_with(&counted_sync);
    const std::string piece(4 * kMiB, 'x');
    ASSERT_EQ(std::fwrite(piece.data(), 1, piece.size(), out.file()), piece.size());
    EXPECT_FALSE(out.syncs_behind());
    ASSERT_EQ(out.close(), "");
    EXPECT_EQ(g_syncs.load(), 0);
}

// How many of a file's pages are in the page cache (mincore over a fresh mapping); -1 if it
// cannot be told.
long cached_pages(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return -1;
    struct stat st {};
    long cached = -1;
    if (::fstat(fd, &st) == 0 && st.st_size > 0) {
        const auto size = static_cast<std::size_t>(st.st_size);
        void* map = ::mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0);
        if (map != MAP_FAILED) {
            const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
            std::vector<unsigned char> in((size + page - 1) / page);
            if (::mincore(map, size, in.data()) == 0) {
                cached = 0;
                for (const unsigned char c : in) cached += c & 1;
            }
            ::munmap(map, size);
        }
    }
    ::close(fd);
    return cached;
}

// A file of `size` bytes of `fill`, written, synced (its pages clean) and read (cached).
void write_cached(const std::string& path, std::size_t size, char fill) {
    const std::string text(size, fill);
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(std::fwrite(text.data(), 1, text.size(), f), text.size());
    ASSERT_EQ(std::fflush(f), 0);
    ASSERT_EQ(::fsync(::fileno(f)), 0);
    std::fclose(f);
    std::string back(size, '\0');
    f = std::fopen(path.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(std::fread(back.data(), 1, back.size(), f), size);
    std::fclose(f);
}

// The first write drops the cached pages of the file the output will replace (the rename at
// the end has less to free); its contents stay: a run that fails leaves it as it was. Skipped
// where the file system keeps pages it was told it may drop (tmpfs: the pages are the file).
TEST(OutputWriteBack, TheFirstWriteDropsTheCachedPagesOfTheFileItWillReplace) {
    char dir_template[] = "/tmp/apci-replace-XXXXXX";
    ASSERT_NE(::mkdtemp(dir_template), nullptr);
    const std::string dir = dir_template;
    const std::string probe = dir + "/probe", target = dir + "/old.json";
    constexpr std::size_t kSize = std::size_t{4} << 20;
    write_cached(probe, kSize, 'p');
    {
        const int fd = ::open(probe.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd >= 0) {
            ::posix_fadvise(fd, 0, 0, POSIX_FADV_DONTNEED);
            ::close(fd);
        }
        ASSERT_GE(fd, 0);
    }
    const bool drops = cached_pages(probe) == 0;
    std::remove(probe.c_str());
    if (!drops) {
        ::rmdir(dir.c_str());
        GTEST_SKIP() << "the file system under " << dir << " keeps the pages";
    }
    write_cached(target, kSize, 'o');
    ASSERT_GT(cached_pages(target), 0);
    {
        OutputFile out;
        ASSERT_EQ(out.open(target), "");
        EXPECT_GT(cached_pages(target), 0);  // opening alone drops nothing
        TextSink sink(out.file());
        sink.append("{\"new\":1}\n");
        ASSERT_TRUE(sink.flush());
        EXPECT_EQ(cached_pages(target), 0);
        out.discard();  // the run failed: nothing published
    }
    EXPECT_TRUE(read_whole(target) == std::string(kSize, 'o'));
    std::remove(target.c_str());
    ::rmdir(dir.c_str());
}

// Counts the executed segments it is given, for a thread that waits for them.
class CountingSink final : public RunSink {
  public:
    std::atomic<std::uint64_t> executed_count{0};
    void executed(const PathSegment& s) override {
        (void)s;
        executed_count.fetch_add(1, std::memory_order_release);
    }
};

// Waits up to `limit` for `sink` to have `n` executed segments.
bool reaches(const CountingSink& sink, std::uint64_t n, std::chrono::milliseconds limit) {
    const auto until = std::chrono::steady_clock::now() + limit;
    while (sink.executed_count.load(std::memory_order_acquire) < n) {
        if (std::chrono::steady_clock::now() > until) return false;
        std::this_thread::sleep_for(1ms);
    }
    return true;
}

// A writer woken for one batch (the self-approach check's pipeline) takes the first batch as
// soon as it is full, while the producer gives nothing more and neither flushes nor finishes;
// woken for the default count it waits for more (the writers of a run: fewer wakeups).
TEST(PipelineWake, AWriterWokenForOneBatchTakesTheFirstBatchAtOnce) {
    CountingSink one;
    PipelinedSink pipeline(one, nullptr, HelperCpu::kOther, 1);
    // The writer starts with the first event; given time, it finds the ring empty and sleeps
    // (a writer that came to the ring only after the batch would take it without sleeping).
    pipeline.executed(segment(0));
    std::this_thread::sleep_for(50ms);
    for (std::size_t i = 1; i < PipelinedSink::kBatchEvents; ++i)
        pipeline.executed(segment(static_cast<std::int64_t>(i)));
    EXPECT_TRUE(reaches(one, PipelinedSink::kBatchEvents, std::chrono::seconds(10)));
    pipeline.finish();
    EXPECT_EQ(one.executed_count.load(), PipelinedSink::kBatchEvents);
}

TEST(PipelineWake, AWriterWokenForTheDefaultCountWaitsForMoreThanOneBatch) {
    static_assert(PipelinedSink::kWriterWakesAfter > 1);
    CountingSink many;
    PipelinedSink pipeline(many);
    for (std::size_t i = 0; i < PipelinedSink::kBatchEvents; ++i)
        pipeline.executed(segment(static_cast<std::int64_t>(i)));
    // The writer spins briefly before it sleeps: it may take the batch if it was still
    // spinning when the batch came; after that it sleeps until kWriterWakesAfter are ready.
    std::this_thread::sleep_for(20ms);
    for (std::size_t i = 0; i < PipelinedSink::kBatchEvents; ++i)
        pipeline.executed(segment(static_cast<std::int64_t>(i)));
    EXPECT_FALSE(reaches(many, 2 * PipelinedSink::kBatchEvents, 200ms));
    pipeline.finish();
    EXPECT_EQ(many.executed_count.load(), 2 * PipelinedSink::kBatchEvents);
}

// The pipeline's fill, as the NC front end's reader follows it (RingFill): the batches handed
// over and not yet taken back by the writer (the one it is delivering counts until it is done),
// of its 32.
TEST(PipelineFill, TheBacklogIsTheBatchesHandedOverAndNotYetTaken) {
    class Gate final : public RunSink {
      public:
        std::atomic<bool> open{false};
        std::atomic<bool> entered{false};
        void executed(const PathSegment& s) override {
            (void)s;
            entered.store(true);
            while (!open.load()) std::this_thread::sleep_for(1ms);
        }
    };
    Gate gate;
    PipelinedSink pipeline(gate, nullptr, HelperCpu::kOther, 1);
    EXPECT_EQ(pipeline.capacity(), PipelinedSink::kBatches);
    EXPECT_EQ(pipeline.backlog(), 0u);
    for (std::size_t i = 0; i < 3 * PipelinedSink::kBatchEvents; ++i)
        pipeline.executed(segment(static_cast<std::int64_t>(i)));
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!gate.entered.load() && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(1ms);
    ASSERT_TRUE(gate.entered.load());
    EXPECT_EQ(pipeline.backlog(), 3u);  // the first being delivered, two waiting
    gate.open.store(true);
    pipeline.finish();
    EXPECT_EQ(pipeline.backlog(), 0u);
}

// How many of this process's descriptors are open on the file (dev, ino): /proc/self/fd's links,
// followed (a file renamed over, or removed, is still there through them).
int descriptors_on(dev_t dev, ino_t ino) {
    int n = 0;
    for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) {
        struct stat st {};
        if (::stat(entry.path().c_str(), &st) == 0 && st.st_dev == dev && st.st_ino == ino) ++n;
    }
    return n;
}

struct FileId {
    dev_t dev = 0;
    ino_t ino = 0;
};
FileId id_of(const std::string& path) {
    struct stat st {};
    EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
    return {st.st_dev, st.st_ino};
}

// A directory of its own holding a target of 1 MiB of 'o' (written, synced, cached), which an
// output will replace; both removed at the end.
struct OldTarget {
    std::string dir, path;
    FileId id;
    OldTarget() : dir(made_dir("/tmp/apci-hold-XXXXXX")) {
        if (dir.empty()) return;
        path = dir + "/old.json";
        write_cached(path, std::size_t{1} << 20, 'o');
        id = id_of(path);
    }
    ~OldTarget() {
        std::remove(path.c_str());
        ::rmdir(dir.c_str());
    }
    OldTarget(const OldTarget&) = delete;
    OldTarget& operator=(const OldTarget&) = delete;
    int held() const { return descriptors_on(id.dev, id.ino); }
};

// The new output's text, written as the writers write it (its first write).
void write_new(OutputFile& out) {
    TextSink sink(out.file());
    sink.append("{\"new\":1}\n");
    ASSERT_TRUE(sink.flush());
}

// The file an output replaces is held open from the first write (so that the rename frees
// nothing), not before; after the rename the target is the new file, and the thread that
// closes the old one soon lets it go.
TEST(OutputWriteBack, TheReplacedFileIsHeldFromTheFirstWriteAndLetGoAfterThePublish) {
    const OldTarget old;
    ASSERT_FALSE(old.path.empty());
    {
        OutputFile out;
        ASSERT_EQ(out.open(old.path), "");
        EXPECT_EQ(old.held(), 0);  // opening alone holds nothing
        write_new(out);
        EXPECT_EQ(old.held(), 1);
        ASSERT_EQ(out.close(), "");
        EXPECT_EQ(old.held(), 1);  // held until the rename
        ASSERT_EQ(out.publish(), "");
        EXPECT_EQ(read_whole(old.path), "{\"new\":1}\n");
        const FileId now = id_of(old.path);
        EXPECT_FALSE(now.dev == old.id.dev && now.ino == old.id.ino);
    }
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (old.held() != 0 && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(1ms);
    EXPECT_EQ(old.held(), 0);
}

// An output not published lets the file it would have replaced go at once, unchanged.
TEST(OutputWriteBack, AnOutputNotPublishedLetsTheFileItWouldReplaceGoAtOnce) {
    const OldTarget old;
    ASSERT_FALSE(old.path.empty());
    OutputFile out;
    ASSERT_EQ(out.open(old.path), "");
    write_new(out);
    EXPECT_EQ(old.held(), 1);
    out.discard();  // the run failed
    EXPECT_EQ(old.held(), 0);
    EXPECT_TRUE(read_whole(old.path) == std::string(std::size_t{1} << 20, 'o'));
}

// As another user (nobody), a target it may write but not read (mode 0200, its own) is not
// held (it cannot be opened for reading) and is still replaced whole by the rename.
TEST(OutputWriteBack, ATargetTheUserMayNotReadIsReplacedWithoutBeingHeld) {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root to become another user";
    char dir_template[] = "/tmp/apci-hold-XXXXXX";
    ASSERT_NE(::mkdtemp(dir_template), nullptr);
    const std::string dir = dir_template;
    ASSERT_EQ(::chown(dir.c_str(), 65534, 65534), 0);
    const std::string target = dir + "/old.json";
    write_cached(target, 4096, 'o');
    ASSERT_EQ(::chown(target.c_str(), 65534, 65534), 0);
    ASSERT_EQ(::chmod(target.c_str(), 0200), 0);
    const FileId old = id_of(target);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        // The child: 1 where becoming nobody failed, 2 where the output failed, 3 where the
        // old file was held, 0 when it was replaced without.
        if (::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(1);
        int code = 0;
        {
            OutputFile out;
            if (!out.open(target).empty()) ::_exit(2);
            TextSink sink(out.file());
            sink.append("{\"new\":1}\n");
            if (!sink.flush()) ::_exit(2);
            if (descriptors_on(old.dev, old.ino) != 0) code = 3;
            if (!out.close().empty() || !out.publish().empty()) ::_exit(2);
        }
        ::_exit(code);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    EXPECT_EQ(read_whole(target), "{\"new\":1}\n");
    std::remove(target.c_str());
    ::rmdir(dir.c_str());
}

}  // namespace
}  // namespace apci::run
