// SPDX-License-Identifier: MIT
// The board's motion layer: the spooler and the executor (rwmos_motion) bound
// to the Board's state. It reads the TC module's state into a TcSettings
// snapshot for every call, writes back what the TC module shows (ERROR bits,
// Run, ProfMarked, stored offsets) and what the board module shows (spooler
// fill level, axis positions), and serves the TC hooks' seam (TcMotion).
// Lives in Board::State (all device state in one struct). docs/motion.md.
#pragma once

#include <cstdint>

#include "rwmos/board.h"
#include "rwmos/motion/executor.h"
#include "rwmos/motion/spooler.h"
#include "rwmos/motion/types.h"
#include "rwmos/tc_state.h"

namespace rwmos {

class MotionLayer final : public TcMotion {
  public:
    explicit MotionLayer(Board::State& state) noexcept : state_(state) {}
    MotionLayer(const MotionLayer&) = delete;
    MotionLayer& operator=(const MotionLayer&) = delete;

    motion::MotionResult spool(const motion::Profile& p);
    motion::MotionResult direct(const motion::DirectCommand& c);
    motion::MotionResult ssf(motion::AxisMask axes, std::int32_t command);
    void step(std::uint64_t cycles);
    std::uint64_t run_until_idle(std::uint64_t max_cycles);

    motion::Executor& executor() noexcept { return exec_; }
    const motion::Executor& executor() const noexcept { return exec_; }
    const motion::Spooler& spooler() const noexcept { return spooler_; }
    // The interpolation cycle in seconds (board object InterpolationCycle).
    double cycle_seconds() const noexcept;
    // Some TC group's ERROR is set: the spooler holds.
    bool error_pending() const noexcept;

    // TcMotion: the TC module's hooks call these.
    objif::Status release_held_profile(std::int32_t group) override;
    void discard_held_profile(std::int32_t group) override;
    void compensation_started(std::int32_t group) override;
    void clear_shift() override;

    // The board axis on which the active group's WkzLen of `tool` acts now (LengthMode 1, or
    // the group compensating), or -1.
    int length_axis_of(std::int32_t tool) const noexcept;

  private:
    motion::TcSettings settings() const noexcept;
    // Records a call's TC errors: ERROR bits set, Run cleared ([APCI-TC] Table 4/5).
    void record(const motion::MotionResult& r) noexcept;
    // Mirrors the motion state into the objects: ProfMarked, offsets, spooler
    // fill level, axis positions; and holds the executor while an error is set.
    void sync() noexcept;
    // sync() with error_pending() already known.
    void sync(bool errors) noexcept;

    Board::State& state_;
    motion::Executor exec_;
    motion::Spooler spooler_;
};

}  // namespace rwmos
