// SPDX-License-Identifier: MIT
// Where the threads of `apcictl run` on the embedded emulator run. The executor's thread (the
// executor and the board) and the helper threads (the NC front end's reader, read_ahead.h, and
// the writer, pipeline.h; with the self-approach check warning, the check on a thread of its
// own and the writers on another) are three or four busy threads. Where the process may use
// exactly two CPUs, the scheduler, left alone, keeps moving them and preempts the executor for
// a helper for about a tenth of the run (docs/performance.md); there a CpuPlacement keeps the
// executor's thread on the CPU it runs on and the helpers on the other, where they share the
// time between them (HelperCpu::kOther) -- but for the reader and the writers beside the
// check, which may run on either CPU (HelperCpu::kEither): the check keeps the other CPU busy
// on a program of many contours, the executor its own on one long contour, and the two lighter
// threads go where there is time. With one CPU, or three and more (room for every thread), it
// places nothing.
//
//   - it changes only the affinity of the threads of the run, within the CPUs the process was
//     given (taskset, cgroups): the CPUs stay shared with every other process, and the
//     executor's thread gets its CPUs back when the placement ends;
//   - where and how often a thread runs changes no output: every output is byte for byte the
//     same.
#pragma once

#include <sched.h>

#include <cstddef>
#include <cstdint>

namespace apci::run {

// Where a helper thread runs: on the CPU the executor leaves to the helpers, on either (where
// the scheduler finds time: beside a helper that keeps the other CPU busy), or on the
// executor's (beside it, where the helper on the other CPU is the longer chain of work).
enum class HelperCpu : std::uint8_t { kOther, kEither, kExecutor };

// How full a ring is whose fill a helper's placement follows (the self-approach check's
// pipeline, pipeline.h): batches committed and not yet taken, of how many. Read from another
// thread than the ring's two: a value as recent as the reading thread can see.
class RingFill {
  public:
    virtual std::size_t backlog() const noexcept = 0;
    virtual std::size_t capacity() const noexcept = 0;

  protected:
    RingFill() = default;
    RingFill(const RingFill&) = default;
    RingFill& operator=(const RingFill&) = default;
    ~RingFill() = default;
};

// Where the NC front end's reader goes while a run goes, following the ring that feeds the
// thread on the other CPU (the check): beside the executor once that thread has fallen behind
// (its ring half full or more: the other CPU is the busier), on the other CPU once it has
// caught up (an eighth full or less: the executor's is), else where it is (`now`). On a
// program of many contours the check is the longer chain and the reader goes beside the
// executor; on one long contour the executor is, and it goes beside the check (docs/
// performance.md, "The run's ends").
HelperCpu follow_backlog(std::size_t backlog, std::size_t capacity, HelperCpu now) noexcept;

class CpuPlacement {
  public:
    // Keeps the calling thread (the executor's) to the CPU it runs on, where the process may use
    // exactly two; otherwise places nothing.
    CpuPlacement() noexcept;
    // The calling thread's CPUs as they were. On the thread that made it.
    ~CpuPlacement();
    CpuPlacement(const CpuPlacement&) = delete;
    CpuPlacement& operator=(const CpuPlacement&) = delete;

    // Whether it placed the executor (and places helpers).
    bool active() const noexcept { return helper_cpu_ >= 0; }
    // On a helper thread: keeps it to the other CPU (kOther) or to the executor's (kExecutor),
    // or lets it run on either of the two (kEither: a thread started by the executor's has
    // only the executor's CPU). Nothing when not active().
    void place_helper(HelperCpu where = HelperCpu::kOther) const noexcept;
    // The CPUs (for tests): the executor's, the helpers'; -1 when not active().
    int executor_cpu() const noexcept { return executor_cpu_; }
    int helper_cpu() const noexcept { return helper_cpu_; }

  private:
    cpu_set_t original_{};
    int executor_cpu_ = -1;
    int helper_cpu_ = -1;
};

}  // namespace apci::run
