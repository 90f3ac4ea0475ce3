// SPDX-License-Identifier: MIT
// The temperature compensation module's state (bus 1320; docs/object-map.md section 7) and its
// engine: the displacement of the axes along the tool direction, cycle by cycle
// (motion::CycleOffsets), after the rules of [SIN-TEMP] (rwmos_tempcomp,
// docs/temperature-compensation.md).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "rwmos/board.h"
#include "rwmos/motion/cycle_offsets.h"
#include "rwmos/object_map.h"
#include "rwmos/tempcomp/tempcomp.h"

namespace rwmos {

struct TempCompState {
    Eigen::Vector3d comp = Eigen::Vector3d::Zero();         // SD 42960 TOOL_TEMP_COMP[0..2], mm
    std::int32_t on = 0;                                    // MD 20390 TOOL_TEMP_COMP_ON
    std::array<std::int32_t, tempcomp::kAxisCount> type{};  // MD 32750 TEMP_COMP_TYPE[axis]
    std::int32_t tool_holder = 0;  // 1: orientable tool holder (the B/C head)
    std::int32_t head_axis_b = 4;
    std::int32_t head_axis_c = tempcomp::kNoHeadAxis;
    double ramp_velocity = tempcomp::kDefaultRampVelocity;  // mm/s
};

class TempCompEngine final : public motion::CycleOffsets {
  public:
    explicit TempCompEngine(EmulatedBoard::State& state) noexcept : state_(state) {}
    TempCompEngine(const TempCompEngine&) = delete;
    TempCompEngine& operator=(const TempCompEngine&) = delete;

    // The displacement of each board axis at the last evaluated cycle (mm).
    const tempcomp::AxisValues& applied() const noexcept { return applied_; }
    // Some axis is still on its way to zero.
    bool ramping() const noexcept;

    // ---- motion::CycleOffsets
    void move_started(const motion::Move&, const motion::Move*) noexcept override {}
    void move_finished(const motion::Move&, std::uint64_t, std::uint64_t) noexcept override {}
    // Only a ramp needs every cycle: otherwise the displacement is a function of the settings
    // and the head's position at the cycle, which the analytic path evaluates exactly.
    bool per_cycle(const motion::Move* m, std::uint64_t k, std::uint64_t n) const noexcept override;
    void step(const motion::Move* m, std::uint64_t k, std::uint64_t n, double dt,
              motion::AxisVector& pos) noexcept override;
    void at(const motion::Move* m, std::uint64_t k, std::uint64_t n,
            motion::AxisVector& pos) const noexcept override;
    // Off with nothing applied: at() adds 0.0 to every axis, nothing ramps.
    bool inert() const noexcept override;

  private:
    tempcomp::Settings settings() const noexcept;
    // The vector as it acts at `pos` (turned with the tool holder).
    Eigen::Vector3d vector_at(const motion::AxisVector& pos) const noexcept;
    // Notices a change of the geometry-axis assignment (TC Device 0 Index 11) since the last
    // evaluation: an axis that left starts its ramp from where it was.
    void follow_assignment() const noexcept;
    void apply(const motion::AxisVector& nominal, double max_step,
               motion::AxisVector& pos) const noexcept;
    // Compensation off (no option, or switched off): apply() sets every axis to 0 at once.
    bool off() const noexcept;
    void rest(motion::AxisVector& pos) const noexcept;

    EmulatedBoard::State& state_;
    // The engine's evaluation state: the last applied values, which axes ramp, and the
    // assignment they were applied under. Changed by the const evaluations too, as a cache of
    // "where the axes are" (the analytic path evaluates with at()).
    mutable tempcomp::AxisValues applied_{};
    mutable std::array<bool, tempcomp::kAxisCount> ramping_{};
    // False while no ramping_ is set (only follow_assignment sets one): ramping() is false.
    mutable bool may_ramp_ = false;
    mutable std::array<int, 3> assignment_{0, 1, 2};
};

}  // namespace rwmos
