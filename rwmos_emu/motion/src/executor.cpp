// SPDX-License-Identifier: MIT
#include "rwmos/motion/executor.h"

#include <algorithm>

namespace rwmos::motion {

bool Executor::can_start_front() const noexcept {
    return !moves_.empty() && (started_ || !halted_ || moves_.front().direct);
}

bool Executor::idle() const noexcept {
    return !can_start_front();
}

void Executor::start_front(double cycle_seconds) {
    const Move& m = moves_.front();
    n_ = cycles_for(path_length(m), m.feed, cycle_seconds);
    k_ = 0;
    started_ = true;
    front_start_cycle_ = now_;
}

void Executor::finish_front(bool interrupted) {
    Segment s = segment_of(moves_.front());
    s.end = position_;
    s.start_cycle = front_start_cycle_;
    s.end_cycle = now_;
    s.interrupted = interrupted;
    segments_.push(s);
    moves_.pop_front();
    started_ = false;
    k_ = n_ = 0;
}

void Executor::discard() {
    if (started_) finish_front(/*interrupted=*/true);
    moves_.clear();
}

void Executor::idle_cycles(std::uint64_t cycles) {
    if (per_cycle()) {
        for (std::uint64_t i = 0; i < cycles; ++i) {
            ++now_;
            if (tracing_) trace_.push(TraceSample{now_, position_});
        }
    } else {
        now_ += cycles;
    }
}

std::uint64_t Executor::run_moves(std::uint64_t budget, double cycle_seconds) {
    std::uint64_t used = 0;
    while (can_start_front()) {
        if (!started_) {
            if (used == budget) break;  // the next move starts with the next cycle
            start_front(cycle_seconds);
        }
        const Move& m = moves_.front();
        if (n_ == 0) {  // a zero-length move takes no cycle
            position_ = m.end;
            finish_front(/*interrupted=*/false);
            continue;
        }
        const std::uint64_t take = std::min(n_ - k_, budget - used);
        if (per_cycle()) {
            for (std::uint64_t i = 0; i < take; ++i) {
                ++k_;
                ++now_;
                position_at(m, k_, n_, position_);
                if (tracing_) trace_.push(TraceSample{now_, position_});
            }
        } else if (take > 0) {
            k_ += take;
            now_ += take;
            position_at(m, k_, n_, position_);
        }
        used += take;
        if (k_ < n_) break;  // budget spent inside this move
        finish_front(/*interrupted=*/false);
    }
    return used;
}

void Executor::advance(std::uint64_t cycles, double cycle_seconds) {
    const std::uint64_t used = run_moves(cycles, cycle_seconds);
    idle_cycles(cycles - used);
}

std::uint64_t Executor::run_until_idle(std::uint64_t max_cycles, double cycle_seconds) {
    return run_moves(max_cycles, cycle_seconds);
}

void Executor::set_trace(bool on, std::size_t capacity) {
    tracing_ = on;
    trace_.set_capacity(on ? capacity : 0);
}

}  // namespace rwmos::motion
