// SPDX-License-Identifier: MIT
// The board's motion layer: the spooler and the executor (rwmos_motion) bound
// to the Board's state. It reads the TC module's state into a TcSettings
// snapshot for every call (the parts only object accesses change kept until the
// next one, settings_changed()), writes back what the TC module shows (ERROR bits,
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
    explicit MotionLayer(EmulatedBoard::State& state) noexcept : state_(state) {}
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

    // The objects the TC settings are read from (TC module, PU) or their tool table (OTC's fold)
    // may have changed: the next call reads them again. Every object access through the board
    // calls it (Board::read/write), and so do the modules that change them (TcModule,
    // BoardModule's PU and rs, OtcEngine's fold into the tool table). ERROR and Run are read
    // at every call.
    void settings_changed() noexcept { settings_valid_ = false; }

    // The board axis on which the active group's WkzLen of `tool` acts now (LengthMode 1, or
    // the group compensating), or -1.
    int length_axis_of(std::int32_t tool) const noexcept;

    // The number the next profile taken will carry (Move::profile), and the oldest number
    // whose moves have not all ended yet (queued, under way, or held back by the spooler; the
    // next profile's when there are none): a setting that acts from the next profile on still
    // concerns the profiles from this one up to the next's.
    std::uint64_t next_profile() const noexcept { return spooler_.profiles_taken() + 1; }

    // Manual mode (design, for [ISG-OTC] section 2.7.3's ManualMvBackToStart): from a direct
    // command (JA, JS; [APCI-TC] section 1's JOG moves) until the next profile is taken. Its
    // start is where the axes stood at the first direct command; an axis's manual offset is how
    // far it stands from there now (0 outside manual mode).
    bool manual_mode() const noexcept { return manual_; }
    double manual_offset(int axis) const noexcept;
    // Moves `axis` back to the start of manual mode (a JA at the rapid feed), when the channel
    // is in manual mode, no move is under way and the axis has an offset; false otherwise,
    // and nothing moves.
    bool move_back_to_manual_start(int axis);
    // The axis is moving back (move_back_to_manual_start) and has not arrived.
    bool moving_back(int axis) const noexcept;

    // The tool length on `axis` changed by `delta` without a motion (OTC's fold at #OTC OFF):
    // the nominal path takes it, the axes stay. False, and nothing changes, while moves are
    // queued (Executor::shift_nominal).
    bool shift_length(int axis, double delta) noexcept {
        if (!exec_.shift_nominal(axis, delta)) return false;
        spooler_.length_shifted(axis, delta);
        return true;
    }
    std::uint64_t oldest_profile_in_flight() const noexcept;
    // The profile just taken was compensated by the 3D module: its queued moves are marked
    // (Move::surface), so their executed segments are contour elements. A profile the TC module
    // holds back has none queued yet; its moves are the TC's contour elements anyway.
    void mark_surface() noexcept {
        const std::uint64_t taken = spooler_.profiles_taken();
        for (std::size_t i = exec_.fill(); i-- > 0;) {
            motion::Move& m = exec_.queued(i);
            if (m.profile != taken) break;
            m.surface = true;
        }
    }

  private:
    // The TcSettings for a call: what only object accesses change as last read (read again
    // after settings_changed()), ERROR (error_pending) and the active group's Run read now.
    const motion::TcSettings& settings() const noexcept;
    // The whole snapshot read from the objects now. The TcMotion hooks use it: they run inside
    // an object write, between its changes.
    motion::TcSettings read_settings() const noexcept;
    // Records a call's TC errors: ERROR bits set, Run cleared ([APCI-TC] Table 4/5).
    void record(const motion::MotionResult& r) noexcept;
    // Mirrors the motion state into the objects: ProfMarked, offsets, spooler
    // fill level, axis positions; and holds the executor while an error is set.
    void sync() noexcept;
    // sync() with error_pending() already known.
    void sync(bool errors) noexcept;

    EmulatedBoard::State& state_;
    mutable motion::TcSettings settings_;
    mutable bool settings_valid_ = false;
    motion::Executor exec_;
    motion::Spooler spooler_;
    bool manual_ = false;
    motion::AxisVector manual_start_{};
    motion::AxisMask moving_back_ = 0;  // axes sent back; valid while the executor has moves
};

}  // namespace rwmos
