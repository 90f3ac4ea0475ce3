// SPDX-License-Identifier: MIT
// The spooler state machine (spooler.h). Rules and their sources are
// listed in docs/motion.md; the comments here name the rule they implement.
#include "rwmos/motion/spooler.h"

#include "objif/map/cutting_edge.h"

#include <cmath>

#include "rwmos/geometry/shared.h"
#include "rwmos/geometry/errors.h"

namespace rwmos::motion {

using objif::Status;

namespace {

MotionResult refuse(Status s, std::string_view why) {
    MotionResult r;
    r.status = s;
    r.message = why;
    return r;
}

// A TC error: recorded in `group`'s ERROR, Run cleared, the spooler holds.
MotionResult tc_error(std::int32_t group, geom::ErrorBits bits, std::uint32_t tag,
                      std::string_view why) {
    MotionResult r;
    r.status = Status::kWrongDeviceState;
    r.group = group;
    r.errors = static_cast<std::int32_t>(bits);
    r.tag = tag;
    r.message = why;
    return r;
}
MotionResult tc_error(std::int32_t group, geom::Reason reason, std::uint32_t tag) {
    return tc_error(group, geom::reason_bits(reason), tag, geom::reason_message(reason));
}

Status check_coordinate(double v) {
    if (!std::isfinite(v)) return Status::kInvalidValue;
    if (v > kMaxCoordinate) return Status::kValueTooHigh;
    if (v < -kMaxCoordinate) return Status::kValueTooLow;
    return Status::kOk;
}

// Checks the feed of a move: `rapid` moves accept 0 (kDefaultRapidFeed).
MotionResult check_feed(double feed, bool rapid) {
    if (!std::isfinite(feed)) return refuse(Status::kInvalidValue, "feed is NaN or infinite");
    if (feed < 0.0) return refuse(Status::kValueTooLow, "feed is negative");
    if (feed == 0.0 && !rapid)
        return refuse(Status::kValueTooLow, "G01/G02/G03 need a feed above 0 (units per minute)");
    if (feed > kMaxFeed) return refuse(Status::kValueTooHigh, "feed above 1e9 units per minute");
    return {};
}

MotionResult check_targets(AxisMask axes, const AxisVector& target) {
    // Almost always every named coordinate lies within the limit (NaN does not): one test an
    // axis without a branch, the reason only for a coordinate that is not.
    bool within = true;
#pragma GCC unroll 8
    for (int a = 0; a < kAxisCount; ++a)
        within &= (axes & (1u << a)) == 0 || std::fabs(target[a]) <= kMaxCoordinate;
    if (within) return {};
    for (int a = 0; a < kAxisCount; ++a) {
        if ((axes & (1u << a)) == 0) continue;
        const Status s = check_coordinate(target[a]);
        if (!objif::ok(s))
            return refuse(
                s, "a target coordinate is beyond the board's limit of +-100000, or not finite");
    }
    return {};
}

MotionResult check_profile(const Profile& p) {
    if (static_cast<std::uint8_t>(p.kind) > static_cast<std::uint8_t>(ProfileKind::kTraverse))
        return refuse(Status::kInvalidValue,
                      "profile kind is not G00, G01, G02, G03 or a traverse (4)");
    if (MotionResult r = check_feed(p.feed, is_rapid(p.kind)); !r.ok()) return r;
    if (MotionResult r = check_targets(p.axes, p.target); !r.ok()) return r;
    if (is_arc(p.kind)) {
        if (p.arc_axes[0] >= kAxisCount || p.arc_axes[1] >= kAxisCount)
            return refuse(Status::kValueTooHigh, "arc axis number above 7");
        if (p.arc_axes[0] == p.arc_axes[1])
            return refuse(Status::kInvalidValue, "arc axes must be two different axes");
        for (double c : p.center)
            if (const Status s = check_coordinate(c); !objif::ok(s))
                return refuse(s,
                              "an arc centre coordinate is beyond the board's limit of +-100000, "
                              "or not finite");
    }
    return {};
}

// The board's limit on one move (interpolator.h kMaxMoveCycles); static text (MotionResult).
static_assert(kMaxMoveCycles == 1'000'000'000, "kTooLong names the limit");
constexpr std::string_view kTooLong =
    "the move takes more than 1000000000 interpolation cycles at this feed (11.6 days at 1 ms): "
    "raise the feed";

SegmentRole role_of(geom::SegmentRole r) {
    switch (r) {
        case geom::SegmentRole::kContour:
            return SegmentRole::kContour;
        case geom::SegmentRole::kTransition:
            return SegmentRole::kTransition;
        case geom::SegmentRole::kApproach:
            return SegmentRole::kApproach;
        case geom::SegmentRole::kDeparture:
            return SegmentRole::kDeparture;
    }
    return SegmentRole::kContour;
}

geom::Vec2 on_plane(const AxisVector& v, const std::array<std::uint8_t, 2>& axes) {
    return {v[axes[0]], v[axes[1]]};
}

// The G code of the plane the two axes span in this order, 0 if none.
std::int32_t plane_code_of(std::array<std::uint8_t, 2> axes,
                           const std::array<std::uint8_t, 3>& nr) {
    if (axes[0] == nr[0] && axes[1] == nr[1]) return 17;
    if (axes[0] == nr[2] && axes[1] == nr[0]) return 18;
    if (axes[0] == nr[1] && axes[1] == nr[2]) return 19;
    return 0;
}

}  // namespace

// ---- Resolving a profile to board axes

MotionResult Spooler::resolve(const Profile& p, const TcSettings& tc, Resolved& out) const {
    out.program = program_;
#pragma GCC unroll 8
    for (int a = 0; a < kAxisCount; ++a)
        if ((p.axes & (1u << a)) != 0) out.program[a] = p.target[a];
    out.path = out.program;
    if (p.kind == ProfileKind::kRapid) return {};

    const std::array<std::uint8_t, 2> plane{tc.plane_axes[0], tc.plane_axes[1]};
    out.ccw = p.kind == ProfileKind::kArcCcw;
    out.arc_axes = p.arc_axes;
    out.cx = p.center[0];
    out.cy = p.center[1];
    if (is_arc(p.kind)) {
        if (tc.present && tc.objects_accessed) {
            // [APCI-TC] section 2.2 "Wichtiger Hinweis": once a TC object was
            // accessed, arcs run in the active plane, not in the plane of the
            // axes named first. An arc named in other axes is outside it.
            const bool same_order = p.arc_axes[0] == plane[0] && p.arc_axes[1] == plane[1];
            const bool swapped = p.arc_axes[0] == plane[1] && p.arc_axes[1] == plane[0];
            if (!same_order && !swapped) {
                if (tc.active_group == 0)
                    return refuse(Status::kWrongDeviceState,
                                  "arc outside the active plane (PlaneError; no active group "
                                  "to record it)");
                return tc_error(tc.active_group, geom::bits(geom::ErrorBit::kPlaneError), p.tag,
                                "arc outside the active plane");
            }
            out.arc_axes = plane;
            if (swapped) std::swap(out.cx, out.cy);
            out.plane = tc.plane;
        } else {
            out.plane = plane_code_of(p.arc_axes, tc.axis_nr);
        }
    }
    // [APCI-TC] section 2.1.1: the rotation acts on interpolation profiles in
    // the active plane; it needs no compensation object. A zero angle leaves
    // the coordinates untouched (bit for bit).
    if (tc.present && tc.rot_angle != 0.0) {
        const geom::Vec2 centre{tc.rot_center_first, tc.rot_center_second};
        const geom::Vec2 q = geom::rotate_about(on_plane(out.program, plane), centre, tc.rot_angle);
        out.path[plane[0]] = q.x();
        out.path[plane[1]] = q.y();
        if (is_arc(p.kind)) {
            // Arcs run in the active plane here (rotation means TC objects were accessed).
            const geom::Vec2 c = geom::rotate_about({out.cx, out.cy}, centre, tc.rot_angle);
            out.cx = c.x();
            out.cy = c.y();
        }
    }
    return {};
}

// ---- Compensator output to moves

const Spooler::Pending* Spooler::pending(std::uint32_t index) const noexcept {
    for (const Pending& p : pending_)
        if (p.index == index) return &p;
    return nullptr;
}

void Spooler::forget_finished() {
    if (!comp_.comp.running()) {
        pending_.clear();
        return;
    }
    const std::uint32_t keep = comp_.comp.holds_element() ? comp_.comp.held_index() : next_index_;
    while (!pending_.empty() && pending_.front().index < keep) pending_.pop_front();
}

void Spooler::append_segments(const Compensation& c, const geom::SegmentBatch& segs,
                              bool keep_departure, Batch& batch) const {
    const std::uint8_t z = c.length_axis;
    for (const geom::Segment& seg : segs) {
        if (seg.role == geom::SegmentRole::kDeparture && !keep_departure) continue;
        const Pending* pd = pending(seg.index);
        if (pd == nullptr) continue;  // cannot happen: every index pushed is pending
        const bool arc = geom::is_arc(seg.path);
        const bool edge = c.edge.x() != 0.0 || c.edge.y() != 0.0;
        // A turning tool's first carried element where the compensator's approach was too short
        // to emit (the tool stood on the nose centre's path): the approach is the offset alone.
        const bool carried_start =
            seg.role == geom::SegmentRole::kContour || seg.role == geom::SegmentRole::kTransition;
        const bool unreached =
            edge && carried_start &&
            (geom::Vec2(batch.end[c.plane_axes[0]], batch.end[c.plane_axes[1]]) -
             (seg.path.start + c.edge))
                    .norm() > geom::kPointTolerance;
        if ((seg.role == geom::SegmentRole::kApproach && arc && edge) || unreached) {
            // An approach arc of a turning tool: the tool moves by the cutting edge's offset
            // first, so that the arc, carried over whole, stays an arc (as LinuxCNC's lathe
            // entry, interp_convert.cc); likewise onto a first element the approach missed.
            Move& shift = batch.next();
            shift.start = batch.end;
            shift.end = batch.end;
            const geom::Vec2 to = seg.path.start + c.edge;
            shift.end[c.plane_axes[0]] = to.x();
            shift.end[c.plane_axes[1]] = to.y();
            line_move_into(shift, pd->feed, SegmentRole::kApproach, pd->tag);
            shift.side = c.side;
            shift.traverse = pd->traverse;
            shift.profile = pd->profile;
            batch.length_at(shift, batch.length);
            batch.end = shift.end;
        }
        // Written where it will run (no Move built and copied there).
        Move& m = batch.next();
        // The axes outside the plane: the third axis runs linearly along the
        // plane element (with WkzLen added while compensating), the others too.
        AxisVector& end = m.end;
        switch (seg.role) {
            case geom::SegmentRole::kContour:
                end = pd->end;
                end[z] += c.length;
                break;
            case geom::SegmentRole::kApproach:
                // A plane-free element before the first plane element is
                // consumed by its (zero-length) approach, so it goes to its end; the
                // indirect and the direct approach are their element's whole move.
                end = pd->plane_free || c.comp.config().approach != geom::ApproachMode::kPerpendicular
                          ? pd->end
                          : pd->start;
                end[z] += c.length;
                break;
            case geom::SegmentRole::kTransition:
                end = batch.end;  // at the corner: only the plane axes move
                break;
            case geom::SegmentRole::kDeparture:
                // Back to the programmed end, length compensation removed (LengthMode 0) or
                // kept (LengthMode 1).
                end = path_;
                if (c.length_always) end[z] += c.length;
                break;
        }
        // The nose centre's path carried over to the imaginary tip of a turning tool
        // (CuttingEdge): the offset elements and their transitions whole, the approach from the
        // tool's position to it, the departure from it back to the programmed end.
        const geom::Vec2 to_start =
            seg.role == geom::SegmentRole::kApproach && !arc ? geom::Vec2::Zero() : c.edge;
        const geom::Vec2 to_end =
            seg.role == geom::SegmentRole::kDeparture ? geom::Vec2::Zero() : c.edge;
        m.start = batch.end;
        m.start[c.plane_axes[0]] = seg.path.start.x() + to_start.x();
        m.start[c.plane_axes[1]] = seg.path.start.y() + to_start.y();
        end[c.plane_axes[0]] = seg.path.end.x() + to_end.x();
        end[c.plane_axes[1]] = seg.path.end.y() + to_end.y();
        if (arc) {
            // Offset arcs, transitions and approach arcs: carried over whole, centre too.
            arc_move_into(m, c.plane_axes, seg.path.centre.x() + c.edge.x(),
                          seg.path.centre.y() + c.edge.y(), seg.path.ccw, pd->feed,
                          role_of(seg.role), pd->tag);
            m.plane = c.plane;
        } else {
            line_move_into(m, pd->feed, role_of(seg.role), pd->tag);
        }
        m.side = c.side;
        // Every segment of a traverse's element (its offset, the transition at its end) is a
        // rapid move on the compensated path.
        m.traverse = pd->traverse;
        m.profile = pd->profile;
        // The length in its end: WkzLen on z, but for a transition (at the corner, as before)
        // and a departure under LengthMode 0 (taken out).
        AxisVector length = batch.length;
        if (seg.role != geom::SegmentRole::kTransition) {
            length = {};
            if (seg.role != geom::SegmentRole::kDeparture || c.length_always) length[z] = c.length;
        }
        batch.length_at(m, length);
        batch.end = m.end;
    }
}

void Spooler::end_contour(Compensation& c, bool keep_departure, Batch& batch) {
    // finish() fails only when not running; callers check running() first.
    c.comp.finish(segs_);
    append_segments(c, segs_, keep_departure, batch);
}

MotionResult Spooler::commit(Batch& batch, const Executor& exec, std::size_t capacity) {
    // The batch's moves are in the queue already.
    if (exec.fill() > capacity)
        return refuse(Status::kBusy, "spooler full: nothing taken; run the clock and try again");
    batch.keep();
    return {};
}

// ---- Calls

MotionResult Spooler::spool(const Profile& p, const TcSettings& tc, Executor& exec,
                            std::size_t capacity, double cycle_seconds) {
    if (MotionResult r = check_profile(p); !r.ok()) return r;
    if (tc.error_pending)
        return refuse(Status::kWrongDeviceState,
                      "the spooler holds after a TC error: write ERROR to clear it");
    Resolved res;
    if (MotionResult r = resolve(p, tc, res); !r.ok()) return r;
    if (!programmed_move_fits(p, res, exec, cycle_seconds))
        return refuse(Status::kValueTooLow, kTooLong);

    // The contour goes on in comp_ itself; what it was is kept (one copy, not a trial copy and
    // a copy back) and put back wherever the call takes nothing.
    comp_before_ = comp_;
    Batch batch(exec, length_at_end_);
    // [APCI-TC] section 1: only G01/G02/G03 are compensated, by the active
    // group while it runs. Anything else ends the contour under way ([APCI-TC]
    // section 2.4: a JOG/G00 makes the compensation ineffective; the next
    // interpolation profile approaches the compensated path anew). No
    // departure: the tool leaves from where the compensated path ended.
    const bool compensate =
        is_interpolation(p.kind) && tc.present && tc.run && tc.active_group != 0;
    if (comp_.comp.running() && (!compensate || comp_.group != tc.active_group))
        end_contour(comp_, /*keep_departure=*/false, batch);

    const double feed = p.feed == 0.0 ? kDefaultRapidFeed : p.feed;
    const std::uint64_t number = profiles_ + 1;  // this profile's, once taken
    // Everything but a compensated G01/G02/G03 goes uncompensated.
    const bool compensated = p.kind != ProfileKind::kRapid && compensate;
    if (MotionResult r = compensated
                             ? spool_compensated(p, tc, res, feed, number, comp_, batch)
                             : spool_uncompensated(p, tc, res, feed, number, batch);
        !r.ok()) {
        comp_ = comp_before_;
        return r;
    }
    const bool pushed = compensated;  // a Pending entry, for this profile

    if (MotionResult r = commit(batch, exec, capacity); !r.ok()) {
        if (pushed) pending_.pop_back();
        comp_ = comp_before_;
        return r;
    }
    length_at_end_ = batch.length;
    program_ = res.program;
    path_ = p.kind == ProfileKind::kRapid ? res.program : res.path;
    profiles_ = number;
    departure_next_ = 0;
    if (pushed) ++next_index_;
    forget_finished();
    return {};
}

// A profile spooled without compensation: a rapid (no rotation, [APCI-TC] section 2.1.1), a
// traverse, or a G01/G02/G03 while no group runs, with the tool length of LengthMode 1.
MotionResult Spooler::spool_uncompensated(const Profile& p, const TcSettings& tc,
                                          const Resolved& res, double feed, std::uint64_t number,
                                          Batch& batch) const {
    // SelectionMode 139: the profile after STATUS = 0 is the departure when it runs
    // uncompensated from the last offset end (docs/compensation.md "Approach and departure").
    const bool departs = departure_next_ != 0 && p.kind != ProfileKind::kRapid;
    const SegmentRole uncompensated = departs ? SegmentRole::kDeparture : SegmentRole::kUncompensated;
    const std::int8_t uncompensated_side = departs ? departure_next_ : std::int8_t{0};
    // LengthMode 1: the tool length acts on every profile, compensated or not (design,
    // docs/compensation.md "Tool length"); compensated ones get it as always
    // (append_segments).
    AxisVector length{};
    if (tc.present && tc.active_group != 0 && tc.length_always) length[tc.length_axis] = tc.length;
    const auto lengthened = [&length](AxisVector v) {
        for (int a = 0; a < kAxisCount; ++a) v[a] += length[a];
        return v;
    };
    if (p.kind == ProfileKind::kRapid) {
        // [APCI-TC] section 2.1.1: no rotation for JOG moves; no compensation.
        Move m = line_move(batch.end, lengthened(res.program), feed, SegmentRole::kRapid, p.tag);
        m.profile = number;
        batch.length_at(m, length);
        batch.add(m);
        return {};
    }
    if (is_arc(p.kind)) {
        const geom::Element e =
            geom::make_arc(on_plane(batch.end, res.arc_axes), on_plane(res.path, res.arc_axes),
                           {res.cx, res.cy}, res.ccw);
        if (const geom::Reason why = geom::check_element(e); why != geom::Reason::kNone) {
            if (tc.present && tc.objects_accessed && tc.active_group != 0)
                return tc_error(tc.active_group, why, p.tag);
            return refuse(Status::kInvalidValue, geom::reason_message(why));
        }
        // The length axis is the third of the TC plane, outside an arc of that plane; an arc
        // in another plane that holds it keeps its end as programmed (its circle would move).
        const bool in_arc_plane =
            tc.length_axis == res.arc_axes[0] || tc.length_axis == res.arc_axes[1];
        Move m =
            arc_move(batch.end, in_arc_plane ? res.path : lengthened(res.path), res.arc_axes,
                     res.cx, res.cy, res.ccw, feed, uncompensated, p.tag);
        m.plane = res.plane;
        m.profile = number;
        m.side = uncompensated_side;
        batch.length_at(m, in_arc_plane ? AxisVector{} : length);
        batch.add(m);
    } else {
        Move m = line_move(batch.end, lengthened(res.path), feed, uncompensated, p.tag);
        m.traverse = p.kind == ProfileKind::kTraverse;
        m.profile = number;
        m.side = uncompensated_side;
        batch.length_at(m, length);
        batch.add(m);
    }
    return {};
}

// A compensated G01/G02/G03: the contour of `trial` goes on with it (or begins, or ends and
// begins anew where its settings changed); its Pending entry is pushed, and popped again when
// the compensator refuses the element.
MotionResult Spooler::spool_compensated(const Profile& p, const TcSettings& tc,
                                        const Resolved& res, double feed, std::uint64_t number,
                                        Compensation& trial, Batch& batch) {
    const std::array<std::uint8_t, 2> plane{tc.plane_axes[0], tc.plane_axes[1]};
    if (trial.comp.running()) {
        const geom::CompensatorConfig& now = trial.comp.config();
        if (now.tool_radius != tc.radius || now.side != tc.side ||
            trial.cutting_edge != tc.cutting_edge) {
            // A new RADIUS applies from the next profile: the contour ends at
            // the held profile's offset end and this one approaches the new path.
            end_contour(trial, /*keep_departure=*/false, batch);
        } else if (now.transition != tc.transition) {
            // CornerMode (G25/G26) applies from the next corner; the contour goes on.
            trial.comp.set_transition(tc.transition);
        }
    }
    if (!trial.comp.running()) {
        trial.group = tc.active_group;
        trial.plane_axes = plane;
        trial.plane = tc.plane;
        trial.length_axis = tc.length_axis;
        trial.side = tc.side == geom::Side::kRight ? std::int8_t{-1} : std::int8_t{1};
        trial.cutting_edge = tc.cutting_edge;
        const auto edge = objif::map::tc::cutting_edge_offset(tc.cutting_edge, tc.radius);
        trial.edge = geom::Vec2(edge[0], edge[1]);
        const geom::CompensatorConfig config{tc.side, tc.radius, tc.transition, tc.approach};
        const geom::StepResult begun = trial.comp.begin(config, on_plane(batch.end, plane));
        if (!begun.ok()) return tc_error(tc.active_group, begun.reason, p.tag);
    }
    trial.length = tc.length;
    trial.length_always = tc.length_always;
    const geom::Element e =
        is_arc(p.kind) ? geom::make_arc(on_plane(path_, plane), on_plane(res.path, plane),
                                        {res.cx, res.cy}, res.ccw)
                       : geom::make_line(on_plane(path_, plane), on_plane(res.path, plane));
    pending_.push_back(Pending{next_index_, p.tag, feed, path_, res.path,
                               geom::is_plane_free(e), p.kind == ProfileKind::kTraverse,
                               number});
    const geom::StepResult step = trial.comp.push(e, next_index_, segs_);
    if (!step.ok()) {
        pending_.pop_back();
        const Pending* at = pending(step.index);
        return tc_error(tc.active_group, step.reason, at != nullptr ? at->tag : p.tag);
    }
    append_segments(trial, segs_, /*keep_departure=*/false, batch);
    return {};
}

// The profile's move as programmed (before compensation and tool length): from where the
// programmed path stands (a rapid: from where the queue ends) to its end, at its feed.
Move Spooler::programmed_move(const Profile& p, const Resolved& res, const Executor& exec) const {
    const double feed = p.feed == 0.0 ? kDefaultRapidFeed : p.feed;
    if (p.kind == ProfileKind::kRapid)
        return line_move(exec.planned_end(), res.program, feed, SegmentRole::kRapid, p.tag);
    if (is_arc(p.kind))
        return arc_move(path_, res.path, res.arc_axes, res.cx, res.cy, res.ccw, feed,
                        SegmentRole::kUncompensated, p.tag);
    return line_move(path_, res.path, feed, SegmentRole::kUncompensated, p.tag);
}

bool Spooler::programmed_move_fits(const Profile& p, const Resolved& res, const Executor& exec,
                                   double cycle_seconds) const {
    // Almost every move is far within the limit: a bound of its length says so without the
    // move's roots and angles.
    const double feed = p.feed == 0.0 ? kDefaultRapidFeed : p.feed;
    const bool rapid = p.kind == ProfileKind::kRapid;
    if (surely_within_move_limit(rapid ? exec.planned_end() : path_, rapid ? res.program : res.path,
                                 is_arc(p.kind) ? &res.arc_axes : nullptr, res.cx, res.cy, feed,
                                 cycle_seconds))
        return true;
    return within_move_limit(programmed_move(p, res, exec), cycle_seconds);
}

MotionResult Spooler::release_for_deactivation(std::int32_t group, const TcSettings& tc,
                                               Executor& exec, std::size_t capacity) {
    if (comp_.group != group || !comp_.comp.running()) return {};
    // [APCI-TC] section 1: "Beim Deaktivieren der Werkzeugradius-Korrektur wird
    // auch das letzte zwischengespeicherte Verfahrprofil gespoolt."
    Compensation trial = comp_;
    Batch batch(exec, length_at_end_);
    // Perpendicular (G237): a departure at right angles back to the programmed end. Indirect
    // (G139): none; the tool stays at the last offset end and the next profile departs from
    // there (docs/compensation.md "Approach and departure").
    const bool perpendicular = tc.approach == geom::ApproachMode::kPerpendicular;
    end_contour(trial, /*keep_departure=*/perpendicular, batch);
    if (MotionResult r = commit(batch, exec, capacity); !r.ok()) return r;
    comp_ = trial;
    length_at_end_ = batch.length;
    forget_finished();
    departure_next_ = perpendicular ? std::int8_t{0} : comp_.side;
    return {};
}

MotionResult Spooler::ssf(AxisMask axes, std::int32_t command, const TcSettings&, Executor& exec,
                          std::size_t capacity) {
    if (axes == 0) return refuse(Status::kInvalidValue, "SSF command names no axis");
    if (command != kSsfReleaseHeldProfile)
        return refuse(Status::kInvalidValue, "SSF command not emulated (only 2001)");
    if (!comp_.comp.running()) return {};
    const AxisMask group_axes =
        static_cast<AxisMask>((1u << comp_.plane_axes[0]) | (1u << comp_.plane_axes[1]));
    if ((axes & group_axes) == 0) return {};
    // [APCI-TC] section 1: "Alternativ dazu kann auch das SSF-Kommando 2001 an
    // die entsprechenden Achsen gesendet werden": the held profile is spooled.
    Compensation trial = comp_;
    Batch batch(exec, length_at_end_);
    end_contour(trial, /*keep_departure=*/false, batch);
    if (MotionResult r = commit(batch, exec, capacity); !r.ok()) return r;
    comp_ = trial;
    length_at_end_ = batch.length;
    forget_finished();
    return {};
}

MotionResult Spooler::direct(const DirectCommand& c, Executor& exec, double cycle_seconds) {
    if (c.code != DirectCode::kJA && c.code != DirectCode::kJS)
        return refuse(Status::kInvalidValue, "direct command is not JA or JS");
    // The jog starts where the path stands (offsets such as OTC's stay on top of it); the
    // discard below stops the move under way there.
    AxisVector end = exec.nominal_position();
    Move jog;
    if (c.code == DirectCode::kJA) {
        if (c.axes == 0) return refuse(Status::kInvalidValue, "JA names no axis");
        if (MotionResult r = check_feed(c.feed, /*rapid=*/true); !r.ok()) return r;
        if (MotionResult r = check_targets(c.axes, c.target); !r.ok()) return r;
        for (int a = 0; a < kAxisCount; ++a)
            if ((c.axes & (1u << a)) != 0) end[a] = c.target[a];
        jog = line_move(exec.nominal_position(), end, c.feed == 0.0 ? kDefaultRapidFeed : c.feed,
                        SegmentRole::kRapid, 0);
        if (!within_move_limit(jog, cycle_seconds)) return refuse(Status::kValueTooLow, kTooLong);
    } else if (c.axes != 0) {
        return refuse(Status::kInvalidValue, "JS stops every axis and takes no axes");
    }
    // [APCI-TC] section 1: "Beim Aufruf eines direkten Befehls (z.B. JA, oder
    // JS) wird der komplette Spooler-Inhalt und das zwischengespeicherte
    // Verfahrprofil verworfen."
    comp_.comp.discard();
    pending_.clear();
    departure_next_ = 0;
    length_at_end_ = {};  // the programmed path is where the axes are (path_ below)
    exec.discard();
    if (c.code == DirectCode::kJA) {
        jog.direct = true;
        exec.push(jog);
    }
    program_ = end;
    path_ = end;
    return {};
}

void Spooler::discard_held(std::int32_t group) {
    if (comp_.group != group || !comp_.comp.running()) return;
    comp_.comp.discard();
    pending_.clear();
    departure_next_ = 0;
}

void Spooler::clear_shift(const TcSettings& tc, const Executor& exec) {
    if (comp_.comp.running()) return;
    const AxisVector& end = exec.planned_end();
    AxisVector d{};
    bool shifted = false;
    for (int a = 0; a < kAxisCount; ++a) {
        d[a] = end[a] - path_[a];
        shifted = shifted || d[a] != 0.0;
    }
    if (!shifted) return;
    // program_ is path_ before the rotation of the active plane: turn the
    // plane part of the shift back so that both name the queue's end.
    if (tc.present && tc.rot_angle != 0.0) {
        const std::array<std::uint8_t, 2> plane{tc.plane_axes[0], tc.plane_axes[1]};
        const geom::Vec2 q = geom::rotate_about(on_plane(d, plane), {0.0, 0.0}, -tc.rot_angle);
        d[plane[0]] = q.x();
        d[plane[1]] = q.y();
    }
    for (int a = 0; a < kAxisCount; ++a) program_[a] += d[a];
    path_ = end;
    length_at_end_ = {};  // the shift took it into the programmed path
}

}  // namespace rwmos::motion
