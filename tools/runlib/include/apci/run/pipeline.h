// SPDX-License-Identifier: MIT
// The output pipeline of `apcictl run`: a RunSink that hands what the executor produces (the
// programmed moves, the executed segments, the samples, the errors and warnings with their
// places, the axis names and numbers) in batches through a bounded ring (spsc_ring.h) to one
// writer thread, which calls another RunSink with them in the order they came. The executor
// and the board run on the caller's thread, the writers (JSON, CSV, SVG) on the writer thread
// (and with ProgramExecutor::set_read_ahead the NC front end on a third, read_ahead.h).
//
//   - bounded: kBatches batches of at most kBatchEvents events; a producer that finds every
//     batch taken waits for the writer (memory stays flat however long the program);
//   - in order: the inner sink sees exactly the calls, in the order, it would have seen
//     without the pipeline (but the programmed moves where it takes none, takes_programmed()),
//     so every output is byte for byte the same;
//   - progress() goes to the inner sink at once, on the caller's thread, and wants_programmed(),
//     takes_programmed() and wants_samples() are asked of it there too: the inner sink must
//     keep what these read unchanged while the run goes;
//   - measured on the writer thread: the executed segments come unmeasured
//     (measures_executed()); the writer thread measures each (measure()) before the inner sink
//     has it (one that comes measured is taken as it comes), and sums the lengths in their
//     order as count_segment() does, which measured_lengths() hands back once the writer has
//     had every segment: the inner sink and the totals see the same values, bit for bit, as
//     when the executor measured them. Where the inner sink measures them itself (a second
//     pipeline behind a check: ProgramRun), they go on unmeasured and measured_lengths() is
//     the inner sink's, asked once the writer has had every segment;
//   - the compensated stretches (stretch_begin, stretch_end, walls) go to the inner sink in
//     their place like every other call: a SelfApproachSink there (self_approach_sink.h) checks
//     the run on the writer thread (and hands every call on to a second pipeline, whose thread
//     writes the outputs: ProgramRun). The inner sink cannot stop the run (take_stop() is not
//     passed on): a check whose finding stops the run stands before the pipeline;
//   - errors: an exception of the inner sink on the writer thread stops the writer (the
//     producer drops what follows instead of waiting) and is rethrown by finish(). Write
//     errors the writers remember (TextSink) are theirs to report after finish(), as before;
//   - no thread outlives it: finish() (or the destructor, on any path out) ends the writer
//     thread and joins it. The writer thread blocks the signals sent to the process (SIGTERM,
//     SIGINT, SIGHUP, ...), so they reach the caller's thread, whose DeferSignals (run_files.h)
//     holds them; the signals a write raises for its own thread (SIGPIPE, SIGXFSZ) stay
//     unblocked and end the process as they did.
#pragma once

#include <array>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "apci/apci.h"
#include "apci/run/cpu_placement.h"
#include "apci/run/executor.h"
#include "apci/run/slab.h"
#include "apci/run/spsc_ring.h"
#include "apci/run/summary.h"

namespace apci::run {

class PipelinedSink final : public RunSink, public RingFill {
  public:
    static constexpr std::size_t kBatchEvents = 512;
    // As many batches as one slab block holds (2 MiB: 28 full batches of 72 KiB): no second
    // block is mapped for a few batches (docs/performance.md, "What a fresh huge page costs
    // here").
    static constexpr std::size_t kBatches = 28;
    // Batches a writer asleep on an empty ring is woken for by default (a writer faster than
    // the producer sleeps often: one wakeup per 8 batches, not one per batch).
    static constexpr std::size_t kWriterWakesAfter = 8;
    // Free batches a producer asleep on a full ring is woken for.
    static constexpr std::size_t kProducerWakesAfter = 8;

    // `inner` must outlive this. The writer thread starts with the first event. With `cpus`
    // (which must outlive this too), it runs where that places helpers (cpu_placement.h). The
    // writer, asleep on an empty ring, is woken when `writer_wakes_after` batches are ready (at
    // least 1, at most half the ring), or the stream ends; the producer, asleep on a full ring,
    // when kProducerWakesAfter are free.
    explicit PipelinedSink(RunSink& inner, const CpuPlacement* cpus = nullptr,
                           HelperCpu where = HelperCpu::kOther,
                           std::size_t writer_wakes_after = kWriterWakesAfter);
    ~PipelinedSink() override;
    PipelinedSink(const PipelinedSink&) = delete;
    PipelinedSink& operator=(const PipelinedSink&) = delete;

    void programmed(const PathSegment& s) override;
    bool wants_programmed() const override { return inner_.wants_programmed(); }
    bool takes_programmed() const override { return inner_.takes_programmed(); }
    void executed(const PathSegment& s) override;
    void axes(std::span<const std::string> names) override;
    void axis_numbers(const std::array<int, 3>& xyz) override;
    bool wants_samples() const override { return inner_.wants_samples(); }
    void sample(std::uint64_t cycle, double time_s, std::span<const double> axes) override;
    void error(const RunError& e, const Point& where) override;
    void warning(const RunError& w, const Point& where) override;
    void progress(std::uint64_t blocks, std::uint64_t offset) override {
        inner_.progress(blocks, offset);
    }
    bool measures_executed() const override { return true; }
    // Waits until the writer thread has had every event handed over (or stopped).
    void measured_lengths(double& path, double& rapid) override;
    void stretch_begin(const CompensatedStretch& s) override;
    void stretch_end() override;
    void walls(bool on) override;

    // Hands over the last batch, waits until the inner sink has had every event, and ends the
    // writer thread. Rethrows the exception that stopped the writer, if one did. Idempotent.
    void finish();
    // Batches the producer waited for (the writer was behind) and the writer waited for (the
    // producer was behind), together: for measurements.
    std::uint64_t waits() const noexcept { return ring_.sleeps(); }
    // Batches handed over and not yet taken by the writer, of kBatches (RingFill: the NC front
    // end's reader follows the check's ring, read_ahead.h).
    std::size_t backlog() const noexcept override { return ring_.backlog(); }
    std::size_t capacity() const noexcept override { return ring_.capacity(); }

  private:
    enum class Kind : std::uint8_t {
        kProgrammed,
        kExecuted,
        kSample,
        kError,
        kWarning,
        kAxes,
        kAxisNumbers,
        kBarrier,  // measured_lengths(): the writer has had every event before it
        kStretchBegin,
        kStretchEnd,
        kWalls  // the index is 1 for CDON, 0 for CDOF
    };
    struct Sample {
        std::uint64_t cycle = 0;
        double time_s = 0.0;
        std::uint32_t count = 0;
        std::array<double, APCI_AXIS_COUNT> axes{};
    };
    struct Note {  // an error or warning, and where
        RunError what;
        Point where = Point::Zero();
    };
    // One batch: the order of its events, each an index into the array of its kind. The
    // arrays keep their capacity from batch to batch.
    struct Batch {
        // The arrays every batch fills, carved from the pipeline's slab the first time round.
        std::vector<std::pair<Kind, std::uint32_t>,
                    detail::SlabAllocator<std::pair<Kind, std::uint32_t>>>
            order;
        std::vector<PathSegment, detail::SlabAllocator<PathSegment>> segments;
        std::vector<Sample> samples;
        std::vector<Note> notes;
        std::vector<std::string> names;
        std::vector<CompensatedStretch> stretches;  // stretch_begin's
        std::array<int, 3> xyz{0, 1, 2};
        void clear() noexcept;
    };

    // The batch being filled (nullptr when the writer stopped); committed when full.
    Batch* open_batch();
    void add(Kind kind, std::uint32_t index);
    void commit();
    void start();
    void write_loop() noexcept;
    void deliver(Batch& b);
    void writer_reached(bool barrier) noexcept;
    void sync();  // waits until the writer has had every event so far (or ended)
    void add_only(Kind kind, std::uint32_t index = 0);  // an event with nothing but its kind
    void stop() noexcept;

    RunSink& inner_;
    const CpuPlacement* cpus_;
    HelperCpu where_;
    // The inner sink measures the executed segments itself (asked when the writer starts).
    bool inner_measures_ = false;
    // 28 batches (14,336 events, 2 MB, one slab block): the writer shares its core with the NC
    // front end's reader (read_ahead.h) and falls behind while that runs; with 8 batches the
    // executor found the ring full 10 to 20 times a run and slept up to a millisecond each time
    // (perf sched), 96 -> 85 ms wall for the 100k-block contour (docs/performance.md). A
    // sleeping producer wakes for 8 batches, so the executor never waits long for room; a
    // sleeping writer for the count the constructor was given.
    // The batches' orders and segments (slab.h): before the ring, which goes first.
    detail::Slab slab_;
    SpscRing<Batch> ring_;
    Batch* filling_ = nullptr;
    bool started_ = false;
    bool finished_ = false;
    std::thread writer_;
    std::exception_ptr failure_;  // written by the writer thread before it ends
    // The writer thread's sums of the executed segments' lengths (count_segment()).
    RunTotals measured_;
    // Barriers handed over, and those the writer passed; the writer ended.
    std::uint64_t barriers_sent_ = 0;
    std::mutex sync_mutex_;
    std::condition_variable synced_;
    std::uint64_t barriers_passed_ = 0;
    bool writer_ended_ = false;
};

}  // namespace apci::run
