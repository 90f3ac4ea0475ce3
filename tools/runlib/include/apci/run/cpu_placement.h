// SPDX-License-Identifier: MIT
// Where the threads of `apcictl run` on the embedded emulator run. The executor's thread (the
// executor and the board, the run's longest chain of work) and two helper threads (the NC front
// end's reader, read_ahead.h, and the writer, pipeline.h) are three busy threads. Where the
// process may use exactly two CPUs, the scheduler, left alone, keeps moving them and preempts
// the executor for a helper for about a tenth of the run (docs/performance.md); there a
// CpuPlacement keeps the executor's thread on the CPU it runs on and the two helpers on the
// other, where they share the time between them. With one CPU, or three and more (room for
// every thread), it places nothing.
//
//   - it changes only the affinity of the threads of the run, within the CPUs the process was
//     given (taskset, cgroups): the CPUs stay shared with every other process, and the
//     executor's thread gets its CPUs back when the placement ends;
//   - where and how often a thread runs changes no output: every output is byte for byte the
//     same.
#pragma once

#include <sched.h>

namespace apci::run {

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
    // On a helper thread: keeps it to the other CPU. Nothing when not active().
    void place_helper() const noexcept;
    // The CPUs (for tests): the executor's, the helpers'; -1 when not active().
    int executor_cpu() const noexcept { return executor_cpu_; }
    int helper_cpu() const noexcept { return helper_cpu_; }

  private:
    cpu_set_t original_{};
    int executor_cpu_ = -1;
    int helper_cpu_ = -1;
};

}  // namespace apci::run
