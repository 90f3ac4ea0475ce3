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

void Executor::start_front(double cycle_seconds, bool inert) {
    const Move& m = moves_.front();
    n_ = cycles_for(path_length(m), m.feed, cycle_seconds);
    k_ = 0;
    started_ = true;
    front_start_cycle_ = now_;
    if (offsets_ != nullptr && !inert)
        offsets_->move_started(m, moves_.size() > 1 ? &moves_[1] : nullptr);
}

void Executor::finish_front(bool interrupted, bool inert) {
    // The length where the move began and where it ended (stopped): the segment's, and from
    // here on the nominal path's. Kept even when the log has no room for the segment.
    const AxisVector at_start = nominal_length_;
    length_at(moves_.front(), at_start, k_, n_, nominal_length_);
    segments_.push_with([&](Segment& s) {
        segment_into(moves_.front(), s);
        s.end = nominal_;
        s.length_start = at_start;
        s.length_end = nominal_length_;
        s.start_cycle = front_start_cycle_;
        s.end_cycle = now_;
        s.interrupted = interrupted;
    });
    if (offsets_ != nullptr && !inert) offsets_->move_finished(moves_.front(), k_, n_);
    moves_.pop_front();
    started_ = false;
    k_ = n_ = 0;
}

void Executor::discard() {
    if (started_) finish_front(/*interrupted=*/true);
    moves_.clear();
}

void Executor::place(const Move* m, std::uint64_t k, std::uint64_t n, double cycle_seconds,
                     bool stepped) {
    position_ = nominal_;
    if (offsets_ == nullptr) return;
    if (stepped)
        offsets_->step(m, k, n, cycle_seconds, position_);
    else
        offsets_->at(m, k, n, position_);
}

void Executor::idle_cycles(std::uint64_t cycles, double cycle_seconds) {
    std::uint64_t left = cycles;
    while (left > 0 && per_cycle(nullptr, 0, 0)) {
        ++now_;
        --left;
        place(nullptr, 0, 0, cycle_seconds, /*stepped=*/true);
        if (tracing_) trace_.push(TraceSample{now_, position_});
    }
    if (left > 0) {
        now_ += left;
        place(nullptr, 0, 0, cycle_seconds, /*stepped=*/false);
    }
}

std::uint64_t Executor::run_moves(std::uint64_t budget, double cycle_seconds) {
    std::uint64_t used = 0;
    // Inert offsets (CycleOffsets::inert) act the same after every move: evaluated once, after
    // the last one of this stretch. Nothing else acts on the modules meanwhile.
    const bool inert = offsets_ != nullptr && !per_cycle() && offsets_->inert();
    bool placed_late = false;
    while (can_start_front()) {
        if (!started_) {
            if (used == budget) break;  // the next move starts with the next cycle
            start_front(cycle_seconds, inert);
        }
        const Move& m = moves_.front();
        if (n_ == 0) {  // a zero-length move takes no cycle
            nominal_ = m.end;
            if (inert)
                placed_late = true;
            else
                place(&m, 1, 1, cycle_seconds, /*stepped=*/false);
            finish_front(/*interrupted=*/false, inert);
            continue;
        }
        while (k_ < n_ && used < budget) {
            if (!inert && per_cycle(&m, k_, n_)) {
                ++k_;
                ++now_;
                ++used;
                position_at(m, k_, n_, nominal_);
                place(&m, k_, n_, cycle_seconds, /*stepped=*/true);
                if (tracing_) trace_.push(TraceSample{now_, position_});
            } else {
                const std::uint64_t take = std::min(n_ - k_, budget - used);
                k_ += take;
                now_ += take;
                used += take;
                position_at(m, k_, n_, nominal_);
                if (inert)
                    placed_late = true;
                else
                    place(&m, k_, n_, cycle_seconds, /*stepped=*/false);
            }
        }
        if (k_ < n_) break;  // budget spent inside this move
        finish_front(/*interrupted=*/false, inert);
    }
    // The inert offsets' at() does not depend on the move or the cycle.
    if (placed_late) place(nullptr, 0, 0, cycle_seconds, /*stepped=*/false);
    return used;
}

void Executor::advance(std::uint64_t cycles, double cycle_seconds) {
    const std::uint64_t used = run_moves(cycles, cycle_seconds);
    idle_cycles(cycles - used, cycle_seconds);
}

std::uint64_t Executor::run_until_idle(std::uint64_t max_cycles, double cycle_seconds) {
    std::uint64_t used = run_moves(max_cycles, cycle_seconds);
    // Idle means nothing moves, the offsets included: offsets still settling (the OTC ramps
    // after #OTC OFF) run on until they rest, within the same bound.
    while (used < max_cycles && idle() && offsets_ != nullptr &&
           offsets_->per_cycle(nullptr, 0, 0)) {
        ++now_;
        ++used;
        place(nullptr, 0, 0, cycle_seconds, /*stepped=*/true);
        if (tracing_) trace_.push(TraceSample{now_, position_});
    }
    return used;
}

void Executor::set_trace(bool on, std::size_t capacity) {
    tracing_ = on;
    trace_.set_capacity(on ? capacity : 0);
}

}  // namespace rwmos::motion
