// SPDX-License-Identifier: MIT
// The executor's core (run_context.h): spooling moves and arcs, the board access helpers, the
// clock, the trace and the executed segments read back, the record of errors and findings.
#include "run_context.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

#include "apci/nc/arc.h"
#include "apci/nc/move_time.h"

namespace apci::run::exec {

namespace {

namespace tc = objif::map::tc;
namespace c3 = objif::map::comp3d;
namespace otc = objif::map::otc;

// Clock calls without a trace run until idle in one go.
constexpr std::uint64_t kRunForever = std::uint64_t{1} << 62;

// The board's role codes up to APCI_ROLE_UNCOMPENSATED are the Role values; a rapid (or any
// other code) is uncompensated.
static_assert(APCI_ROLE_CONTOUR == static_cast<int>(Role::kContour) &&
              APCI_ROLE_TRANSITION == static_cast<int>(Role::kTransition) &&
              APCI_ROLE_APPROACH == static_cast<int>(Role::kApproach) &&
              APCI_ROLE_DEPARTURE == static_cast<int>(Role::kDeparture) &&
              APCI_ROLE_UNCOMPENSATED == static_cast<int>(Role::kUncompensated));
Role role_of(std::uint8_t role) noexcept {
    return role <= APCI_ROLE_UNCOMPENSATED ? static_cast<Role>(role) : Role::kUncompensated;
}

// ---- #TRAFO: the B head's tool-tip transformation (docs/design.md section 8; docs/otc.md)

Eigen::Vector3d tool_axis(double b_deg) noexcept {
    const double b = b_deg * (std::numbers::pi / 180.0);
    return {std::sin(b), 0.0, std::cos(b)};
}

}  // namespace

// The pivot (the machine's X, Y, Z) of a tool tip at tilt b: one tool length behind it.
Eigen::Vector3d RunContext::pivot_of(const Eigen::Vector3d& tip, double b_deg) const noexcept {
    return tip + head_.trafo_length * tool_axis(b_deg);
}

// The axes stop first, so the segments read back before belong to the old state. Under the
// transformation the tool length is its own (the pivot one length behind the tip along t(B)),
// so the TC groups stop applying theirs on the tool axis (LengthMode 0) until #TRAFO OFF.
bool RunContext::trafo(const BlockRef& at, const nc::TrafoChange& e) {
    if (e.on && head_.b_axis < 0)
        return record(at, "Unsupported", "no free board axis for the head's B");
    if (!run_clock()) return false;
    if (out_.otc_present &&
        !otc_.setting(at, otc::kIdxTrafo, e.on ? 1 : 0, e.on ? "#TRAFO ON" : "#TRAFO OFF"))
        return false;
    if (!tc_.length_mode(at, !e.on)) return false;
    head_.trafo = e.on;
    head_.trafo_length = e.tool_length;
    // The next segment starts where the last one ended; under the transformation its start is
    // turned back into the tip by the transformation alone, after it by the length on the axis.
    Eigen::Vector3d at_start = Eigen::Vector3d::Zero();
    const TcUnit::State& tc = tc_.state();
    if (!e.on && tc.length_always) at_start[plane_axes(tc.plane).third] = tc.length;
    switch_start_length_ = at_start;
    return true;
}

bool RunContext::head_turn(const BlockRef& at, const nc::HeadOrientation& e) {
    if (head_.b_axis < 0 || (klartext_ && head_.c_axis < 0))
        return record(at, "Unsupported",
                      klartext_ ? "no free board axes for the head's B and C"
                                : "no free board axis for the head's B");
    head_.pending = true;
    head_.at = at;
    head_.b = e.b;
    head_.c = e.c;
    return true;
}

// A block that only turns the head: the rotary axes move at the rapid feed.
bool RunContext::head_only_move(const BlockRef& at) {
    apci_profile p{};
    p.kind = APCI_PROFILE_RAPID;
    p.tag = encode_block_tag(at);
    add_head(p);
    head_.pending = false;
    apci::Result<apci_motion_result> r;
    if (!spool_profile(p, r)) return false;
    if (r.ok()) return true;
    return record(at, std::string(apci::status_name(r.status)), board_words());
}

PathSegment RunContext::line_segment(const BlockRef& at, SegmentKind kind,
                                    const Eigen::Vector3d& start, const Eigen::Vector3d& end) {
    PathSegment s;
    s.block = at;
    s.kind = kind;
    s.start = start;
    s.end = end;
    return s;
}

PathSegment RunContext::arc_segment(const BlockRef& at, const nc::ArcMove& a) {
    PathSegment s;
    s.block = at;
    s.kind = SegmentKind::kArc;
    s.start = a.start;
    s.end = a.end;
    s.plane = nc::g_number(a.plane);
    s.center = a.center;
    // The centre's coordinate on the third axis is the start's (nc/events.h).
    const int third = plane_axes(s.plane).third;
    s.center[third] = a.start[third];
    s.ccw = a.ccw;
    return s;
}

bool RunContext::move(const BlockRef& at, const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                     std::uint8_t kind, double feed) {
    const PathSegment s = line_segment(
        at, kind == APCI_PROFILE_RAPID ? SegmentKind::kRapid : SegmentKind::kLine, start, end);
    // [TNC-3D], peripheral milling: "L-Satz mit programmierten Drehachsen, M128 oder
    // FUNCTION TCPM aktiv, Korrekturrichtung mit Radiuskorrektur RL oder RR".
    const bool peripheral = klartext_ && kind == APCI_PROFILE_LINE && c3_.peripheral();
    if (peripheral) {
        if (!c3_.setting(at, c3::kIdxArm, c3::kArmLine, "Arm")) return false;
        return c3_.spool(at, s, profile(at, kind, end, feed));
    }
    // A G0 under G41/G42 is compensated like a G01 ([ISG-PROG] compensates every move in the
    // plane; LinuxCNC's interpreter likewise): the board compensates only interpolation
    // profiles, so it goes as a traverse, compensated as a G01 at the board's rapid feed (no
    // surprise motion: a Z lift stays beside the contour instead of crossing onto it) and still
    // a rapid ([ISG-OTC] section 2: "Eilgangssätze sind verschleißfrei!").
    if (kind == APCI_PROFILE_RAPID && tc_.state().comp_on) kind = APCI_PROFILE_TRAVERSE;
    const bool ok = spool(at, s, profile(at, kind, end, feed));
    head_.pending = false;
    return ok;
}

bool RunContext::arc(const BlockRef& at, const nc::ArcMove& a) {
    const PathSegment s = arc_segment(at, a);
    apci_profile p =
        profile(at, a.ccw ? APCI_PROFILE_ARC_CCW : APCI_PROFILE_ARC_CW, a.end, a.feed);
    const PlaneAxes pa = plane_axes(s.plane);
    p.arc_axes[0] = static_cast<std::uint8_t>(axis(pa.first));
    p.arc_axes[1] = static_cast<std::uint8_t>(axis(pa.second));
    const Eigen::Vector3d centre =
        head_.trafo ? pivot_of(a.center, head_.pending ? head_.b : head_.b_now) : a.center;
    p.center[0] = centre[pa.first];
    p.center[1] = centre[pa.second];
    return spool(at, s, p);
}

apci_profile RunContext::profile(const BlockRef& at, std::uint8_t kind, const Eigen::Vector3d& end,
                                double feed) noexcept {
    apci_profile p{};
    p.kind = kind;
    p.tag = encode_block_tag(at);
    p.feed = feed;
    const Eigen::Vector3d target =
        head_.trafo ? pivot_of(end, head_.pending ? head_.b : head_.b_now) : end;
    for (int i = 0; i < 3; ++i) {
        const std::int32_t a = axis(i);
        p.axes = static_cast<std::uint8_t>(p.axes | (1u << a));
        p.target[a] = target[i];
    }
    if (head_.pending) add_head(p);
    return p;
}

// The head's axes join the profile: B, and in Klartext C (DIN programs have no C).
void RunContext::add_head(apci_profile& p) noexcept {
    p.axes = static_cast<std::uint8_t>(p.axes | (1u << head_.b_axis));
    p.target[head_.b_axis] = head_.b;
    if (klartext_) {
        p.axes = static_cast<std::uint8_t>(p.axes | (1u << head_.c_axis));
        p.target[head_.c_axis] = head_.c;
    }
    head_.b_now = head_.b;
}

void RunContext::programmed(const PathSegment& s, std::uint32_t tag) {
    sink_.programmed(s);
    recent_.add(tag, s);
}

bool RunContext::spool(const BlockRef& at, const PathSegment& programmed_move,
                      const apci_profile& p) {
    // The board's limit on one move, in the board's own cycle (the front end counted in 1 ms
    // cycles): said in the program's words before the board refuses the profile with its own.
    // Most moves are told from a bound without roots or angles; the exact length only near it.
    const double cycle_s = static_cast<double>(cycle_us_) * 1e-6;
    if (p.feed > 0.0 && !surely_within_move_cycles(programmed_move, p.feed, cycle_s)) {
        std::string why = nc::check_move_cycles(segment_length(programmed_move), p.feed, cycle_s);
        if (!why.empty()) return record(at, "Value", std::move(why));
    }
    // The compensated stretch runs from G41/G42 to G40 (TcUnit): a G0 between goes as a
    // compensated traverse (move()), and its programmed move is a rapid, no contour element.
    programmed(programmed_move, p.tag);
    if (!sink_lets_go_on()) return false;
    apci::Result<apci_motion_result> r;
    if (!spool_profile(p, r)) return false;
    if (r.ok()) return true;
    // A TC error: the board's own words (the element at fault is the block the error
    // names; the call's status and tag say nothing more).
    const std::string_view said = board_.last_board_message();
    if (r.value.errors != 0)
        return tc_errors(decode_block_tag(r.value.tag), r.value.errors,
                         said.empty() ? board_words() : std::string(said));
    // Any other refusal: the board's words too, not the driver's call and tag.
    return record(at, std::string(apci::status_name(r.status)),
                  said.empty() ? board_words() : std::string(said));
}

// Spools p; Busy (the spooler is full) makes room and tries again. False when the clock could
// not make room (recorded); else `r` is the board's answer, which is not Busy.
bool RunContext::spool_profile(const apci_profile& p, apci::Result<apci_motion_result>& r) {
    for (;;) {
        r = board_.spool(p);
        if (r.status != APCI_BUSY) return true;
        if (!make_room()) return false;
    }
}

void RunContext::begin_stretch(const CompensatedStretch& s) {
    sink_.stretch_begin(s);
}

void RunContext::walls_on(bool on) {
    sink_.walls(on);
}

bool RunContext::end_stretch() {
    sink_.stretch_end();
    return sink_lets_go_on();
}

bool RunContext::sink_lets_go_on() {
    std::optional<RunError> stop = sink_.take_stop();
    if (!stop) return true;
    // The run's outputs end with the last segment the sink was given: the samples after it are
    // not read, and the time is counted to its end.
    stop_cycle_ = std::max(start_cycle_, given_end_cycle_);
    return record(stop->block, std::move(stop->code), std::move(stop->message));
}

// ---- board access

// Writes an object; Busy (the spooler cannot take what the write releases) runs the clock
// and tries again.
template <typename T>
bool RunContext::write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what) {
    for (;;) {
        const auto r = board_.write(o, value);
        if (r.ok()) return true;
        if (r.status == APCI_BUSY) {
            if (!make_room()) return false;
            continue;
        }
        return write_failure(at, r.status, what);
    }
}

template bool RunContext::write(ObjectDescriptor, std::int32_t, const BlockRef&, std::string_view);
template bool RunContext::write(ObjectDescriptor, double, const BlockRef&, std::string_view);

// A refused write: a TC error bit it set (InitError) names it, else the status does.
bool RunContext::write_failure(const BlockRef& at, apci::Status status, std::string_view what) {
    const std::string text = failure_words(what);
    if (out_.tc_present && status != APCI_NO_SUCH_DEVICE) {
        auto e = group_object(tc::kActiveGroupIndex, tc::kSubError);
        const auto bits = board_.read_int(e);
        if (bits && bits.value != 0) return tc_errors(at, bits.value, text);
    }
    return record(at, std::string(apci::status_name(status)), text);
}

// What needs a module the board does not have is refused by name.
bool RunContext::no_module(const BlockRef& at, std::string_view what, std::string_view module) {
    return record(at, "NoSuchDevice",
                  fmt::format("{} needs {}, which this board does not have", what, module));
}

bool RunContext::board_failure(const BlockRef& at, apci::Status status, std::string_view what) {
    return record(at, std::string(apci::status_name(status)), failure_words(what));
}

std::string RunContext::failure_words(std::string_view what) const {
    return fmt::format("{}: {}", what, board_words());
}

// One error per Table 4 bit set.
bool RunContext::tc_errors(const BlockRef& at, std::int32_t bits, const std::string& text) {
    const PathSegment* move = recent_.find(encode_block_tag(at));
    const std::string radii =
        (static_cast<std::uint32_t>(bits) & APCI_TC_ERROR_CALC) != 0 && move != nullptr
            ? concave_arc_radii(*move, tc_.state())
            : std::string();
    for (int bit = 0; bit < 32; ++bit) {
        if ((static_cast<std::uint32_t>(bits) & (1u << bit)) == 0) continue;
        const char* name = apci_tc_error_bit_name(bit);
        const bool calc = (1u << bit) == APCI_TC_ERROR_CALC;
        record(at, name != nullptr ? std::string(name) : fmt::format("bit{}", bit),
               calc ? text + radii : text);
    }
    return false;
}

std::string concave_arc_radii(const PathSegment& s, const TcUnit::State& tc) {
    if (!tc.comp_on || s.kind != SegmentKind::kArc || s.plane != tc.comp_plane) return {};
    // G41 (left) on a counter-clockwise arc, G42 on a clockwise one: the centre on the
    // tool's side.
    if ((tc.comp_side > 0) != s.ccw) return {};
    const double r0 = arc_radius(s), r1 = arc_end_radius(s);
    if (std::min(r0, r1) >= tc.radius) return {};
    if (std::abs(r1 - r0) <= 5e-5)
        return fmt::format("; arc radius {:.4f} mm, tool radius {:.4f} mm", r0, tc.radius);
    return fmt::format("; arc radius {:.4f} to {:.4f} mm, tool radius {:.4f} mm", r0, r1,
                       tc.radius);
}

void RunContext::program_error(const nc::Diagnostic& d) {
    record(BlockRef{d.block == nc::kNoBlockNumber ? kNoBlock : d.block, d.line},
           std::string(nc::error_kind_name(d.kind)), d.to_string());
}

// Records an error; returns false (the run stops).
bool RunContext::record(BlockRef at, std::string code, std::string message) {
    // A board error names the block by its tag (its N); the line comes from the spooled move.
    if (at.line == 0 && at.number != kNoBlock)
        if (const PathSegment* s = recent_.find(encode_block_tag(at))) at.line = s->block.line;
    RunError e{at, std::move(code), std::move(message)};
    sink_.error(e, where(at));
    out_.errors.push_back(std::move(e));
    return false;
}

// Midway along the programmed move of the block, else where the axes stand.
Point RunContext::where(const BlockRef& at) {
    if (const PathSegment* s = recent_.find(encode_block_tag(at))) return point_along(*s, 0.5);
    const auto st = board_.motion_status();
    Point p = Point::Zero();
    if (st)
        for (int i = 0; i < 3; ++i) p[i] = st.value.position[axis(i)];
    return p;
}

// Busy: the spooler is full; running until idle empties it. Progress is a move consumed (each
// logs one executed segment) or a cycle run: zero-length moves take no cycle, so a spooler full
// of them empties with the clock standing still.
bool RunContext::make_room() {
    const std::uint64_t cycles_before = cycles_seen_;
    const std::uint64_t segments_before = out_.totals.segments;
    if (!run_clock()) return false;
    if (cycles_seen_ == cycles_before && out_.totals.segments == segments_before)
        return record({}, "Busy", "the spooler is full and the clock does not move it");
    return true;
}

// Runs the clock until the axes stop (in chunks while samples are recorded), reading the
// executed segments and samples as they come.
bool RunContext::run_clock() {
    if (run_clock_until_idle()) return true;
    clock_ok_ = false;
    return false;
}

bool RunContext::run_clock_until_idle() {
    for (;;) {
        if (!plc_.due()) return false;
        std::uint64_t chunk = tracing_ ? ProgramExecutor::kTraceChunk : kRunForever;
        if (const std::uint64_t* due = plc_.next_cycle())
            chunk = std::min(chunk, *due - (cycles_seen_ - start_cycle_));
        const auto st = board_.run_until_idle(chunk);
        if (!clocked(st, "run clock")) return false;
        if (st.value.segments_lost != segments_lost_ || st.value.trace_lost != trace_lost_) {
            segments_lost_ = st.value.segments_lost;
            trace_lost_ = st.value.trace_lost;
            return record({}, "Lost",
                          "executed segments or samples were lost before they were read");
        }
        if ((st.value.flags & APCI_MOTION_IDLE) != 0) return plc_.due();
    }
}

// Steps the clock by exactly `cycles` (idle cycles included), reading what it produced.
bool RunContext::step_clock(std::uint64_t cycles) {
    while (cycles > 0) {
        const std::uint64_t chunk =
            tracing_ ? std::min<std::uint64_t>(cycles, ProgramExecutor::kTraceChunk) : cycles;
        const auto st = board_.step(chunk);
        if (!clocked(st, "step clock")) return false;
        cycles -= chunk;
    }
    return true;
}

// What a clock call produced: the cycle it reached, and the executed segments and samples,
// read.
bool RunContext::clocked(const apci::Result<apci_motion_status>& st, std::string_view what) {
    if (!st) return board_failure({}, st.status, what);
    cycles_seen_ = st.value.now;
    const bool segments = drain_segments(st.value.segments_pending);
    // Where the sink stopped the run among these segments, the samples up to its stop are the
    // run's still (drain_samples leaves out those after it).
    if (!tracing_ || (!segments && !stop_cycle_)) return segments;
    return drain_samples(st.value.trace_pending) && segments;
}

// Reads the `pending` items a clock call reported with `read` in batches of at most the
// buffer's size (asking for no more than are there keeps each read small) and gives each to
// `each`, which says whether to go on.
template <class Item, class Read, class Each>
bool RunContext::drain(std::uint64_t pending, std::vector<Item>& buffer, std::string_view what,
                       Read read, Each each) {
    while (pending > 0) {
        const std::size_t want =
            static_cast<std::size_t>(std::min<std::uint64_t>(pending, buffer.size()));
        const auto r = read(buffer.data(), want);
        if (!r) return board_failure({}, r.status, what);
        for (std::size_t i = 0; i < r.value; ++i)
            if (!each(buffer[i])) return false;
        if (r.value == 0) break;
        pending -= std::min<std::uint64_t>(pending, r.value);
    }
    return true;
}

bool RunContext::drain_segments(std::uint64_t pending) {
    return drain(
        pending, segments_, "read segments",
        [this](apci_segment* out, std::size_t n) { return board_.read_segments(out, n); },
        [this](const apci_segment& b) {
            const PathSegment s = convert(b);
            if (sink_measures_) {
                ++out_.totals.segments;  // the lengths are the sink's to measure and sum
            } else {
                count_segment(out_.totals, s);
            }
            sink_.executed(s);
            given_end_cycle_ = s.end_cycle;
            return sink_lets_go_on();
        });
}

bool RunContext::drop_segments(std::uint64_t pending) {
    return drain(
        pending, segments_, "read segments",
        [this](apci_segment* out, std::size_t n) { return board_.read_segments(out, n); },
        [](const apci_segment&) { return true; });
}

bool RunContext::drain_samples(std::uint64_t pending) {
    return drain(
        pending, samples_, "read trace",
        [this](apci_trace_sample* out, std::size_t n) { return board_.read_trace(out, n); },
        [this](const apci_trace_sample& t) {
            if (stop_cycle_ && t.cycle > *stop_cycle_) return true;  // after the sink's stop
            const double time =
                static_cast<double>(t.cycle * static_cast<std::uint64_t>(cycle_us_)) / 1e6;
            sink_.sample(t.cycle, time, std::span<const double>(t.position, APCI_AXIS_COUNT));
            return true;
        });
}

// A board segment in program coordinates: X, Y, Z from their board axes, the tool length
// compensation the board reports taken off (the tool centre point, docs/design.md section 7).
PathSegment RunContext::convert(const apci_segment& b) {
    PathSegment s;
    s.block = decode_block_tag(b.tag);
    s.role = role_of(b.role);
    s.start_cycle = b.start_cycle;
    s.end_cycle = b.end_cycle;
    // A traverse's straight segments are rapid moves on the compensated path: kind rapid,
    // their role the compensation's (a circular transition at its end stays an arc).
    s.kind = b.kind == APCI_SEGMENT_ARC ? SegmentKind::kArc
             : b.role == APCI_ROLE_RAPID || b.traverse != 0 ? SegmentKind::kRapid
                                                            : SegmentKind::kLine;
    for (int i = 0; i < 3; ++i) {
        const std::int32_t a = axis(i);
        s.start[i] = b.start[a];
        s.end[i] = b.end[a];
        s.center[i] = b.center[a];
    }
    if (s.kind == SegmentKind::kArc) arc_plane(b, s);
    if (head_.trafo) {
        // Back to the tool tip, at the B each end has (a B that turns along a line moves the
        // pivot linearly, so the tip is exact at the ends).
        const double b0 = b.start[head_.b_axis], b1 = b.end[head_.b_axis];
        s.start -= head_.trafo_length * tool_axis(b0);
        s.end -= head_.trafo_length * tool_axis(b1);
        s.center -= head_.trafo_length * tool_axis(b0);
    }
    // The tool length compensation the board added, taken off where the board says it acted.
    for (int i = 0; i < 3; ++i) {
        const std::int32_t a = axis(i);
        const double at_start = switch_start_length_ ? (*switch_start_length_)[i] : b.length_start[a];
        s.start[i] -= at_start;
        s.center[i] -= at_start;
        s.end[i] -= b.length_end[a];
    }
    switch_start_length_.reset();
    // Sweep and length once, for the totals and the writers: here, or by a sink that measures
    // them off this thread (RunSink::measures_executed).
    if (!sink_measures_) measure(s);
    return s;
}

// The arc's plane code and sense in program axes.
void RunContext::arc_plane(const apci_segment& b, PathSegment& s) const noexcept {
    int first = -1, second = -1;
    for (int i = 0; i < 3; ++i) {
        if (axis(i) == b.plane_axes[0]) first = i;
        if (axis(i) == b.plane_axes[1]) second = i;
    }
    s.ccw = b.ccw != 0;
    s.plane = 17;
    if (first < 0 || second < 0 || first == second) return;
    // The plane is the one whose normal is the third axis (17 Z, 18 Y, 19 X); its first axis
    // follows the third (plane_axes: X-Y, Z-X, Y-Z). Named the other way round, the arc is seen
    // from the other side.
    const int third = 3 - first - second;
    s.plane = third == 2 ? 17 : third == 1 ? 18 : 19;
    if (first != (third + 1) % 3) s.ccw = !s.ccw;
}

}  // namespace apci::run::exec
