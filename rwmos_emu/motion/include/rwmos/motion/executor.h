// SPDX-License-Identifier: MIT
// The executor: the board's move queue and interpolation clock. It runs the
// queued moves one after the other, one interpolation cycle at a time when the
// cycles are observed (trace on, or a time-dependent module active), or
// analytically (one position evaluation per move) when nothing observes them;
// both ways give the same positions, bit for bit (interpolator.h).
// It knows nothing of profiles or compensation: the spooler (spooler.h) fills it.
// A cycle-offset module (cycle_offsets.h, e.g. OTC) displaces the axes from the
// nominal path; the queue and the spooler work on the nominal path.
#pragma once

#include <cstddef>
#include <cstdint>

#include "rwmos/motion/cycle_offsets.h"
#include "rwmos/motion/fifo.h"
#include "rwmos/motion/interpolator.h"
#include "rwmos/motion/ring.h"
#include "rwmos/motion/types.h"

namespace rwmos::motion {

inline constexpr std::size_t kDefaultSegmentLogCapacity = 4096;
inline constexpr std::size_t kDefaultTraceCapacity = 65536;

class Executor {
  public:
    Executor() : segments_(kDefaultSegmentLogCapacity) {}

    // ---- Queue
    // Moves not yet finished (the one under way included).
    std::size_t fill() const noexcept { return moves_.size(); }
    void push(const Move& m) { moves_.push_back(m); }
    // A new move at the back of the queue, for the caller to write (every member), and the last
    // `count` moves dropped again: the spooler builds a call's moves where they will run and
    // drops them when they do not all fit.
    Move& push_slot() { return moves_.push_back_slot(); }
    void drop_back(std::size_t count) noexcept {
        for (; count > 0; --count) moves_.pop_back();
    }
    // Where the axes are now (the nominal path plus the cycle offsets).
    const AxisVector& position() const noexcept { return position_; }
    // Where the nominal path stands now (the queued moves' geometry, without offsets).
    const AxisVector& nominal_position() const noexcept { return nominal_; }
    // Where the nominal path will be when every queued move has run.
    const AxisVector& planned_end() const noexcept {
        return moves_.empty() ? nominal_ : moves_.back().end;
    }
    // Moves the nominal path's standing point by delta on one axis while nothing is queued
    // (false and no change otherwise): an offset that the cycle offsets held passes into the
    // nominal path (the OTC wear folded into the tool length), the axes stay where they are.
    bool shift_nominal(int axis, double delta) noexcept {
        if (!moves_.empty() || axis < 0 || axis >= kAxisCount) return false;
        nominal_[static_cast<std::size_t>(axis)] += delta;
        nominal_length_[static_cast<std::size_t>(axis)] += delta;
        return true;
    }
    // The tool length compensation in the nominal path's standing point (per axis): the last
    // move's Move::length_end, with what shift_nominal() folded into it since. The next
    // executed segment starts with it (Segment::length_start).
    const AxisVector& nominal_length() const noexcept { return nominal_length_; }
    // The i-th queued move (0: the one under way or next). For the modules that annotate
    // the moves a call just queued; i < fill().
    Move& queued(std::size_t i) noexcept { return moves_[i]; }
    const Move& queued(std::size_t i) const noexcept { return moves_[i]; }
    // Drops every queued move; the one under way stops where it is and is
    // logged as interrupted. Used by direct commands.
    void discard();

    // A held spooler (TC error) starts no spooled move; the move under way
    // ends, direct moves run.
    void set_halted(bool halted) noexcept { halted_ = halted; }
    bool halted() const noexcept { return halted_; }

    // ---- Clock
    std::uint64_t now() const noexcept { return now_; }
    // Nothing can move: the queue is empty, or only spooled moves wait behind a halt.
    bool idle() const noexcept;
    // Advances the clock by exactly `cycles` cycles (idle cycles included).
    void advance(std::uint64_t cycles, double cycle_seconds);
    // Advances until idle() and the offsets rest (CycleOffsets::per_cycle at no move is false),
    // or `max_cycles` ran; returns the cycles that ran.
    std::uint64_t run_until_idle(std::uint64_t max_cycles, double cycle_seconds);

    // ---- Observation
    // Per-cycle samples: on (with a ring of `capacity` samples) or off.
    void set_trace(bool on, std::size_t capacity = kDefaultTraceCapacity);
    bool tracing() const noexcept { return tracing_; }
    // A time-dependent module (e.g. discrete OTC offsets) needs every cycle run.
    void set_time_dependent(bool on) noexcept { time_dependent_ = on; }
    bool per_cycle() const noexcept { return tracing_ || time_dependent_; }
    // The cycle-offset module (not owned; nullptr: none). It decides itself, move by move,
    // whether its offsets need every cycle run (CycleOffsets::per_cycle).
    void set_offsets(CycleOffsets* offsets) noexcept { offsets_ = offsets; }
    Ring<TraceSample>& trace() noexcept { return trace_; }
    Ring<Segment>& segments() noexcept { return segments_; }
    const Ring<TraceSample>& trace() const noexcept { return trace_; }
    const Ring<Segment>& segments() const noexcept { return segments_; }

  private:
    bool can_start_front() const noexcept;
    // inert: the offsets are inert (CycleOffsets::inert) and are not told of the move.
    void start_front(double cycle_seconds, bool inert);
    void finish_front(bool interrupted, bool inert = false);
    // Runs moves for at most `budget` cycles; returns the cycles used. Stops
    // early only when idle.
    std::uint64_t run_moves(std::uint64_t budget, double cycle_seconds);
    void idle_cycles(std::uint64_t cycles, double cycle_seconds);
    // Every cycle of move `m` (nullptr: standing still) from cycle k on must be run.
    bool per_cycle(const Move* m, std::uint64_t k, std::uint64_t n) const noexcept {
        return per_cycle() || (offsets_ != nullptr && offsets_->per_cycle(m, k, n));
    }
    // nominal_ moved to cycle k of n of `m` (nullptr: standing): position_ follows.
    void place(const Move* m, std::uint64_t k, std::uint64_t n, double cycle_seconds, bool stepped);

    Fifo<Move> moves_;
    bool started_ = false;  // the front move is under way
    std::uint64_t k_ = 0;   // cycles of the front move done
    std::uint64_t n_ = 0;   // cycles the front move takes
    std::uint64_t front_start_cycle_ = 0;
    std::uint64_t now_ = 0;
    AxisVector position_{};
    AxisVector nominal_{};
    AxisVector nominal_length_{};  // nominal_length()
    CycleOffsets* offsets_ = nullptr;
    bool halted_ = false;
    bool tracing_ = false;
    bool time_dependent_ = false;
    Ring<TraceSample> trace_;
    Ring<Segment> segments_;
};

}  // namespace rwmos::motion
