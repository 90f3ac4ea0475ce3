// SPDX-License-Identifier: MIT
// The OTC engine: the wear offsets of the online tool compensation ([ISG-OTC], ISG FCT-C20),
// computed inside the interpolation, cycle by cycle (motion::CycleOffsets). docs/otc.md states
// the model; in short, at cycle k of a move the axes are displaced by
//
//   - W(k) * d(k)  +  o_channel + o_direction + o_axes
//
// W(k) the continuous wear (path length x wear constant, exact and analytic along the move),
// d(k) the processing type's unit direction (rwmos/otc/direction.h; for RADIUS weighted in on
// the approach and out after the contour), and the o's the ramped (rwmos/otc/ramp.h) discrete
// offsets the PLC commands through the control units. The ramps need every cycle run; when
// they rest and their targets do not turn, the executor keeps its analytic fast path.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "objif/status.h"
#include "rwmos/board.h"
#include "rwmos/geometry/shared.h"
#include "rwmos/motion/cycle_offsets.h"
#include "rwmos/otc/direction.h"
#include "rwmos/otc/ramp.h"
#include "rwmos/otc/types.h"
#include "rwmos/otc/units.h"
#include "rwmos/otc_state.h"

namespace rwmos {

class OtcEngine final : public motion::CycleOffsets {
  public:
    explicit OtcEngine(EmulatedBoard::State& state) noexcept : state_(state) {}
    OtcEngine(const OtcEngine&) = delete;
    OtcEngine& operator=(const OtcEngine&) = delete;

    // #OTC ON: the session's settings are taken from the state (type, mode, plane, axes, PU,
    // tool tilt, kinematics). The module has checked the rules.
    void start_session() noexcept;
    // #OTC OFF: the wear is folded into the state's variables and the TC tool tables; the
    // offsets on the axes ramp out (never a jump).
    void end_session() noexcept;
    // The current tool changed: its wear starts from zero ([ISG-OTC] section 2.9).
    void tool_changed() noexcept;
    // The effective wear constant changed (WearConst, WearConstSource, the tool's
    // grinding_wear_const); `before` was in force. It acts from the next profile taken on: the
    // moves of profiles taken before keep `before` ([ISG-OTC] section 2.1, WEAR_CONST "wirkt
    // modal": from its block on).
    void wear_const_changed(double before) noexcept;

    // The control units' request_r and state_r (0.1 um): the target the unit's ramp heads for
    // (0 when the unit does not act) and the offset it has reached along its direction.
    std::int32_t channel_request() const noexcept;
    std::int32_t channel_state() const noexcept;
    std::int32_t axis_request(int axis) const noexcept;
    std::int32_t axis_state(int axis) const noexcept;

    // The continuous wear of the session so far (mm), for tests and status.
    double continuous_wear() const noexcept { return wear_; }
    // Every ramp rests on its target.
    bool ramps_settled() const noexcept;

    // ---- motion::CycleOffsets
    void move_started(const motion::Move& m, const motion::Move* next) noexcept override;
    void move_finished(const motion::Move& m, std::uint64_t k, std::uint64_t n) noexcept override;
    bool per_cycle(const motion::Move* m, std::uint64_t k, std::uint64_t n) const noexcept override;
    void step(const motion::Move* m, std::uint64_t k, std::uint64_t n, double dt,
              motion::AxisVector& pos) noexcept override;
    void at(const motion::Move* m, std::uint64_t k, std::uint64_t n,
            motion::AxisVector& pos) const noexcept override;
    // Off with every ramp at rest: at() adds the ramps' resting positions, nothing else acts.
    bool inert() const noexcept override;

  private:
    using AxisVector = motion::AxisVector;
    using Vec3 = Eigen::Vector3d;

    // What is fixed from #OTC ON to #OTC OFF.
    struct Session {
        otc::ProcessingType type = otc::kDefaultProcessingType;
        otc::Mode mode = otc::kDefaultMode;
        geom::Plane plane = geom::Plane::kXY;
        std::array<int, 3> xyz{0, 1, 2};      // board axes of X, Y, Z (TC X/Y/Z-Axis-Nr)
        std::array<int, 2> plane_axes{0, 1};  // board axes of the plane's first and second axis
        otc::LengthUnit unit = otc::LengthUnit::kMillimetre;
        Vec3 length_direction{0, 0, 1};  // LENGTH: third main axis tilted by P-TOOL-00138
        bool tool_from_b = false;        // the B head gives the tool direction (#KIN 4 + #TRAFO ON)
        int b_axis = kDefaultToolAxisB;
    };
    // RADIUS: how the contour normal weighs in during a move.
    enum class Blend : std::uint8_t {
        kNone,  // no radius compensation: no radius wear offset
        kFull,  // a contour or transition move: the normal of the move itself
        kIn,    // the approach: the first contour's start normal, weighed in from 0 to 1
        kOut,   // after the contour (departure, or whatever ends it): weighed out from 1 to 0
    };
    // The move under way (or the last one, while standing still).
    struct Context {
        double wear_start = 0.0;         // W at the move's start
        double wear_per_fraction = 0.0;  // wear the whole move adds (0: wear-free)
        Blend blend = Blend::kNone;
        Eigen::Vector2d fixed_normal{0, 0};  // kIn / kOut
        double out_weight = 0.0;             // kOut: the weight it starts from
        Eigen::Vector2d end_normal{0, 0};    // the normal and weight the move ended with
        double end_weight = 0.0;
        Vec3 last_surface_normal{0, 0, 1};  // SURF_NORM_DIR when the path gives none
    };
    // Targets of the three ramps at one cycle.
    struct Targets {
        AxisVector channel{};
        AxisVector direction{};
        AxisVector axes{};
    };

    // The unit wear direction at cycle k of n of `m` (m == nullptr: standing at the last move's
    // end), in board axes; RADIUS multiplied by its blend weight.
    AxisVector direction(const motion::Move* m, std::uint64_t k, std::uint64_t n,
                         const AxisVector& nominal) const noexcept;
    Vec3 tool_direction(const AxisVector& nominal) const noexcept;
    Vec3 surface_normal_at(const motion::Move* m, std::uint64_t k, std::uint64_t n,
                           const AxisVector& nominal) const noexcept;
    Eigen::Vector2d contour_normal_at(const motion::Move& m, std::uint64_t k,
                                      std::uint64_t n) const noexcept;
    double wear_at(const motion::Move* m, std::uint64_t k, std::uint64_t n) const noexcept;
    Targets targets(const AxisVector& dir) const noexcept;
    // The targets now: targets() while OTC is on, the standing offsets while it is off.
    Targets targets_now(const AxisVector& dir) const noexcept;
    // The direction turns during `m` while a direction-bound unit commands an offset.
    bool direction_turns(const motion::Move* m) const noexcept;
    void add_offsets(const AxisVector& dir, double wear, AxisVector& pos) const noexcept;
    otc::RampLimits limits() const noexcept;
    bool ramps_at_rest() const noexcept;
    // A unit's commanded offset in mm, 0 when it does not act.
    double channel_command() const noexcept;
    double direction_command() const noexcept;
    double axis_command(int axis) const noexcept;
    int sequence_position(int axis) const noexcept;  // 0, 1, 2 for X, Y, Z; 3 for the others
    Vec3 to_xyz(const AxisVector& v) const noexcept;
    void add_xyz(const Vec3& v, double scale, AxisVector& out) const noexcept;

    EmulatedBoard::State& state_;
    Session session_;
    Context ctx_;
    motion::Move last_move_{};
    bool have_last_ = false;
    double wear_ = 0.0;  // continuous wear of the session so far (mm), at the last move's end
    // The wear constant (0.1 um/m) of each profile: a change acts from the profile number
    // `from` on (the oldest first); before the first, `before` holds. Entries whose profiles
    // have all ended are folded into `before` at every change, so there are at most as many as
    // profiles in flight.
    struct WearConstChange {
        std::uint64_t from = 0;
        double value = 0.0;
    };
    std::vector<WearConstChange> wear_const_changes_;
    double wear_const_before_ = 0.0;
    // The wear constant of the moves of profile `profile` (and drops the changes before it).
    double wear_const_for(std::uint64_t profile) noexcept;
    std::array<otc::RampState, kOtcAxisCount> ramp_channel_{};
    std::array<otc::RampState, kOtcAxisCount> ramp_direction_{};
    std::array<otc::RampState, kOtcAxisCount> ramp_axes_{};
    // Offsets that stay on the axes while OTC is off: the part of a folded wear across the tool
    // length's axis (a tilted disc's X), until the tool changes.
    AxisVector standing_{};
    // Every ramp at rest on its off target (0, the axes' at standing_) while OTC is off (then a
    // cycle steps no ramp): updated by step() and wherever the ramps are set otherwise.
    bool ramps_quiet_ = true;
    mutable AxisVector last_dir_{};  // the direction at the last evaluated cycle
};

}  // namespace rwmos
