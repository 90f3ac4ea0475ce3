// SPDX-License-Identifier: MIT
// The spooler: the state machine between the host's profiles and the move
// queue (executor.h). It resolves each profile to board axes (named axes,
// rotation, arc plane), keeps the one-profile lookahead of the TC module
// ([APCI-TC] section 1: one profile is always held back while compensation
// runs), and applies the JOG, direct-command and SSF rules. The geometry is
// rwmos::geom's (PathCompensator); this file only maps between 8 board axes
// and the plane, and decides when to begin, push, finish or discard.
//
// It sees the TC module through a TcSettings snapshot taken at each call and
// reports what the TC module must record (ERROR bits, Run, ProfMarked) in the
// MotionResult; rwmos::MotionLayer does both against the Board's state.
// docs/motion.md states every rule with its source.
#pragma once

#include <cstdint>
#include <string_view>

#include "objif/status.h"
#include "rwmos/geometry/compensator.h"
#include "rwmos/motion/executor.h"
#include "rwmos/motion/fifo.h"
#include "rwmos/motion/types.h"

namespace rwmos::motion {

// The TC module's settings as the spooler needs them, read at each call.
struct TcSettings {
    bool present = false;           // firmware option optionTC
    bool objects_accessed = false;  // a TC object was accessed: arcs run in the active plane
    // The active plane (TcPlane through X/Y/Z-Axis-Nr): board axes of its
    // first and second axis (its third is the tool's, length_axis), and its G code (17, 18, 19).
    std::array<std::uint8_t, 2> plane_axes{0, 1};
    std::int32_t plane = 17;
    std::array<std::uint8_t, 3> axis_nr{0, 1, 2};  // X-, Y-, Z-Axis-Nr
    // Coordinate rotation in the active plane ([APCI-TC] section 2.1.1).
    double rot_angle = 0.0;  // degrees
    double rot_center_first = 0.0;
    double rot_center_second = 0.0;
    // Some group's ERROR is set: the spooler holds (takes no profile).
    bool error_pending = false;
    // The active group (its XAxis/YAxis span the active plane; 0: none) and
    // its settings. It compensates while `run`.
    std::int32_t active_group = 0;
    bool run = false;
    geom::Side side = geom::Side::kLeft;
    double radius = 0.0;
    geom::TransitionMode transition = geom::TransitionMode::kCircular;
    geom::ApproachMode approach = geom::ApproachMode::kPerpendicular;  // SelectionMode 237 / 139
    bool length_always = false;  // LengthMode 1: `length` on every profile, not only compensated
    std::uint8_t length_axis = 2;  // the group's ZAxis
    double length = 0.0;           // WkzLen of the group's current tool
    std::int32_t cutting_edge = 0;  // CuttingEdge of the group's current tool (0..9)
};

class Spooler {
  public:
    // A profile from the host. Checks it (nothing changes when it is bad),
    // then spools the moves it yields into `exec` (at most `capacity` moves
    // in the queue: kBusy and nothing taken when they do not fit). A profile
    // whose programmed move takes more than kMaxMoveCycles cycles of
    // `cycle_seconds` at its feed is refused (kValueTooLow).
    MotionResult spool(const Profile& p, const TcSettings& tc, Executor& exec, std::size_t capacity,
                       double cycle_seconds);

    // STATUS = 0 on `group`: the held profile is corrected and spooled with the
    // departure to its programmed end ([APCI-TC] section 1).
    MotionResult release_for_deactivation(std::int32_t group, const TcSettings& tc, Executor& exec,
                                          std::size_t capacity);
    // SSF command to the axes in `axes`. 2001 releases the held profile of the
    // compensating group if it owns one of those axes; the contour ends at its
    // compensated end (no departure) and the next profile re-approaches.
    MotionResult ssf(AxisMask axes, std::int32_t command, const TcSettings& tc, Executor& exec,
                     std::size_t capacity);
    // Direct command: discards the queue and the held profile ([APCI-TC]
    // section 1), then acts (JA: jog to the target; JS: stop). A jog longer
    // than kMaxMoveCycles cycles of `cycle_seconds` is refused (kValueTooLow).
    MotionResult direct(const DirectCommand& c, Executor& exec, double cycle_seconds);
    // RESET, Reset, Clean: the held profile of `group` is dropped unspooled.
    void discard_held(std::int32_t group);
    // ReInit, Reset, RESET, Clean ([APCI-TC] Table 2: "Intern gespeicherte
    // Verschiebungswerte der Korrekturachsen werden gelöscht"): the shift a
    // contour left between the programmed path and the queue's end (radius
    // offset without departure, WkzLen on the length axis) is forgotten: where
    // the queue ends becomes the programmed position, so the next profile starts
    // from a point the board no longer considers shifted. Nothing moves. No-op
    // while a contour is under way (the TC module refuses ReInit then).
    void clear_shift(const TcSettings& tc, const Executor& exec);

    // The group whose compensation is under way (0: none), and whether a
    // profile is held back for it (STATUS bit ProfMarked).
    std::int32_t compensating_group() const noexcept {
        return comp_.comp.running() ? comp_.group : 0;
    }
    bool holds_profile() const noexcept { return comp_.comp.holds_element(); }
    // The group of the last contour (0: none yet); its shift stays after the contour
    // ends without departure until a profile, a direct command or clear_shift() removes it.
    std::int32_t last_group() const noexcept { return comp_.group; }
    // The programmed position (program coordinates, before rotation) the next
    // profile starts from; unnamed axes keep it.
    const AxisVector& program_position() const noexcept { return program_; }
    // The same after rotation: where the programmed path is (no compensation).
    const AxisVector& path_position() const noexcept { return path_; }
    // How many profiles were taken so far: the moves of the n-th carry Move::profile n, so a
    // setting that acts from the next profile on (OTC's wear constant) acts from number
    // profiles_taken() + 1.
    std::uint64_t profiles_taken() const noexcept { return profiles_; }
    // The queue's end moved by `delta` on `axis` as the tool length changed there without a
    // motion (OTC's fold, Executor::shift_nominal): the length in the end changed with it.
    void length_shifted(int axis, double delta) noexcept {
        length_at_end_[static_cast<std::size_t>(axis)] += delta;
    }
    // The number of the oldest profile held back or waiting with it, whose moves are still to
    // be queued (0: none).
    std::uint64_t oldest_pending_profile() const noexcept {
        return pending_.empty() ? 0 : pending_.front().profile;
    }

  private:
    // The compensator and where it works (fixed when it begins). Calls work
    // on a copy and store it back only when everything fits.
    struct Compensation {
        geom::PathCompensator comp;
        std::int32_t group = 0;
        std::array<std::uint8_t, 2> plane_axes{0, 1};
        std::int32_t plane = 17;
        std::uint8_t length_axis = 2;
        double length = 0.0;  // WkzLen at the last profile compensated
        bool length_always = false;  // LengthMode 1 when the contour began (the departure keeps it)
        std::int8_t side = 0;  // +1 left, -1 right (Move::side)
        // The cutting edge position the contour began with, and the offset from the nose
        // centre to the imaginary tip it carries the compensated path over by (plane
        // coordinates; objif/map/cutting_edge.h).
        std::int32_t cutting_edge = 0;
        geom::Vec2 edge = geom::Vec2::Zero();
    };
    // A profile the compensator knows by index: held, or waiting with the held one.
    struct Pending {
        std::uint32_t index = 0;
        std::uint32_t tag = 0;
        double feed = 0.0;
        AxisVector start{};  // programmed start (rotated), without length compensation
        AxisVector end{};    // programmed end (rotated), without length compensation
        bool plane_free = false;
        bool traverse = false;  // a traverse profile (ProfileKind::kTraverse)
        std::uint64_t profile = 0;  // its number (profiles_taken)
    };
    // A profile resolved to board axes. resolve() sets program and path first thing (not
    // zero-filled before: a spool call's Resolved is written whole).
    struct Resolved {
        AxisVector program;  // named axes applied, program coordinates
        AxisVector path;     // after rotation: what the axes should follow
        std::array<std::uint8_t, 2> arc_axes{0, 1};
        double cx = 0.0, cy = 0.0;  // arc centre on arc_axes, after rotation
        bool ccw = false;
        std::int32_t plane = 0;  // G code of the arc's plane, 0 if not a TC plane
    };
    // The moves of one call, written in place at the back of the executor's queue as they are
    // built (no move copied into the queue). commit() keeps them when they all fit; a call that
    // returns without keeping them (refused, busy) drops them again with its Batch, so the
    // queue is as before the call.
    class Batch {
        Executor& exec_;
        std::size_t count_ = 0;

      public:
        Batch(Executor& exec, const AxisVector& length_at_end)
            : exec_(exec), end(exec.planned_end()), length(length_at_end) {}
        ~Batch() { exec_.drop_back(count_); }
        Batch(const Batch&) = delete;
        Batch& operator=(const Batch&) = delete;
        // A new move at the back of the queue for the caller to write (every member); then
        // end = its end.
        Move& next() {
            ++count_;
            return exec_.push_slot();
        }
        void add(const Move& m) {
            next() = m;
            end = m.end;
        }
        std::size_t count() const noexcept { return count_; }
        void keep() noexcept { count_ = 0; }
        // m ends with the tool length compensation `at_end` (per axis): its length_end, and
        // the change from the batch's its length_change.
        void length_at(Move& m, const AxisVector& at_end) noexcept {
            for (std::size_t a = 0; a < at_end.size(); ++a) m.length_change[a] = at_end[a] - length[a];
            m.length_end = at_end;
            length = at_end;
        }
        AxisVector end;  // where the last move ends (the queue's end before the first)
        AxisVector length;  // the tool length compensation in `end`
    };

    MotionResult resolve(const Profile& p, const TcSettings& tc, Resolved& out) const;
    Move programmed_move(const Profile& p, const Resolved& res, const Executor& exec) const;
    // The programmed move fits the board's limit (within_move_limit).
    bool programmed_move_fits(const Profile& p, const Resolved& res, const Executor& exec,
                              double cycle_seconds) const;
    // The compensator's segments as board-axis moves, appended to `batch`.
    // Departures are dropped unless `keep_departure`.
    void append_segments(const Compensation& c, const geom::SegmentBatch& segs, bool keep_departure,
                         Batch& batch) const;
    // spool()'s moves of a profile: uncompensated, or on the compensated contour `trial`.
    MotionResult spool_uncompensated(const Profile& p, const TcSettings& tc, const Resolved& res,
                                     double feed, std::uint64_t number, Batch& batch) const;
    MotionResult spool_compensated(const Profile& p, const TcSettings& tc, const Resolved& res,
                                   double feed, std::uint64_t number, Compensation& trial,
                                   Batch& batch);
    // Ends the contour under way into `batch`, with or without the departure.
    void end_contour(Compensation& c, bool keep_departure, Batch& batch);
    const Pending* pending(std::uint32_t index) const noexcept;
    void forget_finished();
    // kBusy if the batch's moves do not fit the queue (they are dropped with it), else keeps them.
    static MotionResult commit(Batch& batch, const Executor& exec, std::size_t capacity);

    Compensation comp_;
    Compensation comp_before_;  // comp_ as it was when spool() began (put back on a refusal)
    Fifo<Pending> pending_;
    std::uint32_t next_index_ = 1;
    std::uint64_t profiles_ = 0;  // profiles taken (profiles_taken)
    // SelectionMode 139: STATUS = 0 ended the contour without a departure; the next profile,
    // an uncompensated G01/G02/G03, departs from the last offset end (side: the contour's).
    std::int8_t departure_next_ = 0;
    AxisVector length_at_end_{};  // the tool length compensation in the queue's end
    AxisVector program_{};     // programmed position, program coordinates
    AxisVector path_{};        // programmed position after rotation (start of the next element)
    geom::SegmentBatch segs_;  // scratch
};

}  // namespace rwmos::motion
