// SPDX-License-Identifier: MIT
#include "apci/run/cpu_placement.h"

namespace apci::run {

namespace {

bool set_cpu(int cpu) noexcept {
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    return ::sched_setaffinity(0, sizeof one, &one) == 0;
}

}  // namespace

HelperCpu follow_backlog(std::size_t backlog, std::size_t capacity, HelperCpu now) noexcept {
    if (2 * backlog >= capacity) return HelperCpu::kExecutor;
    if (8 * backlog <= capacity) return HelperCpu::kOther;
    return now;
}

CpuPlacement::CpuPlacement() noexcept {
    if (::sched_getaffinity(0, sizeof original_, &original_) != 0 || CPU_COUNT(&original_) != 2)
        return;
    int here = ::sched_getcpu();
    int cpus[2] = {-1, -1};
    for (int cpu = 0, n = 0; cpu < CPU_SETSIZE && n < 2; ++cpu)
        if (CPU_ISSET(cpu, &original_)) cpus[n++] = cpu;
    if (here != cpus[0] && here != cpus[1]) here = cpus[0];  // not known: the first
    if (!set_cpu(here)) return;
    executor_cpu_ = here;
    helper_cpu_ = here == cpus[0] ? cpus[1] : cpus[0];
}

CpuPlacement::~CpuPlacement() {
    if (active()) ::sched_setaffinity(0, sizeof original_, &original_);
}

void CpuPlacement::place_helper(HelperCpu where) const noexcept {
    if (!active()) return;
    if (where == HelperCpu::kOther) {
        set_cpu(helper_cpu_);
    } else if (where == HelperCpu::kExecutor) {
        set_cpu(executor_cpu_);
    } else {
        ::sched_setaffinity(0, sizeof original_, &original_);
    }
}

}  // namespace apci::run
