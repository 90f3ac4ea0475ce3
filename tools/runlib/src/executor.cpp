// SPDX-License-Identifier: MIT
#include "apci/run/executor.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

#include "apci/run/csv_writer.h"
#include "rwmos/object_map.h"

namespace apci::run {

namespace {

constexpr std::uint32_t kLineTagFlag = 0x80000000u;

}  // namespace

std::uint32_t encode_block_tag(const BlockRef& b) noexcept {
    if (b.number >= 0 && b.number < static_cast<std::int64_t>(kLineTagFlag))
        return static_cast<std::uint32_t>(b.number);
    return kLineTagFlag |
           static_cast<std::uint32_t>(std::min<std::uint64_t>(b.line, ~kLineTagFlag));
}

BlockRef decode_block_tag(std::uint32_t tag) noexcept {
    if ((tag & kLineTagFlag) != 0) return BlockRef{kNoBlock, tag & ~kLineTagFlag};
    return BlockRef{static_cast<std::int64_t>(tag), 0};
}

namespace {

namespace tc = rwmos::tc;
namespace bm = rwmos::board;

constexpr std::int32_t kGroups = tc::kGroupCount;
// Clock calls without a trace run until idle in one go.
constexpr std::uint64_t kRunForever = std::uint64_t{1} << 62;

// The plane each group compensates in (group g serves plane kGroupPlane[g - 1]).
constexpr std::array<int, kGroups> kGroupPlane{17, 18, 19};

ObjectDescriptor group_object(std::int32_t group, std::int32_t sub) noexcept {
    return apci::object(tc::kBus, tc::kDevGroups, group, sub);
}
ObjectDescriptor init_object(std::int32_t index, std::int32_t sub = 0) noexcept {
    return apci::object(tc::kBus, tc::kDevInit, index, sub);
}

BlockRef block_of(const nc::BlockOrigin& o) noexcept {
    return BlockRef{o.block == nc::kNoBlockNumber ? kNoBlock : o.block, o.line};
}

Role role_of(std::uint8_t role) noexcept {
    switch (role) {
        case APCI_ROLE_CONTOUR:
            return Role::kContour;
        case APCI_ROLE_TRANSITION:
            return Role::kTransition;
        case APCI_ROLE_APPROACH:
            return Role::kApproach;
        case APCI_ROLE_DEPARTURE:
            return Role::kDeparture;
        default:
            return Role::kUncompensated;
    }
}

// The roles whose end point carries the tool length compensation (rwmos spooler: the length is
// added on the compensated path and taken off by the departure).
bool ends_length_compensated(Role r) noexcept {
    return r == Role::kContour || r == Role::kApproach || r == Role::kTransition;
}

// A small ring of the last programmed moves, to place an error reported by block tag.
class RecentMoves {
  public:
    static constexpr std::size_t kSize = 64;
    void add(std::uint32_t tag, const PathSegment& s) noexcept {
        moves_[next_ % kSize] = Entry{tag, s};
        ++next_;
    }
    const PathSegment* find(std::uint32_t tag) const noexcept {
        const std::size_t n = std::min(next_, kSize);
        for (std::size_t i = 1; i <= n; ++i) {
            const Entry& e = moves_[(next_ - i) % kSize];
            if (e.tag == tag) return &e.segment;
        }
        return nullptr;
    }

  private:
    struct Entry {
        std::uint32_t tag = 0;
        PathSegment segment;
    };
    std::array<Entry, kSize> moves_{};
    std::size_t next_ = 0;
};

class Execution {
  public:
    Execution(apci::Board& board, RunSink& sink, const nc::ToolTable* tools)
        : board_(board), sink_(sink), tools_(tools) {
        segments_.resize(ProgramExecutor::kReadBatch);
        samples_.resize(ProgramExecutor::kReadBatch);
    }

    RunOutcome run(nc::EventStream& events) {
        set_up_ = setup();
        if (set_up_) {
            nc::Event ev;
            std::uint64_t count = 0;
            for (;;) {
                const auto next = events.next(ev);
                if (next == nc::EventStream::Next::kEnd) break;
                if (next == nc::EventStream::Next::kError) {
                    program_error(events.error());
                    break;
                }
                out_.totals.blocks_executed = events.blocks_read();
                if (!dispatch(ev)) {
                    draw_rest(events);
                    break;
                }
                if (++count % ProgramExecutor::kProgressEvery == 0)
                    sink_.progress(events.blocks_read());
            }
        }
        finish();
        return std::move(out_);
    }

  private:
    // After an error the rest of the program still goes to a plot, so the place of the error
    // is seen in its contour; nothing more goes to the board.
    void draw_rest(nc::EventStream& events) {
        if (!sink_.wants_programmed()) return;
        nc::Event ev;
        while (events.next(ev) == nc::EventStream::Next::kEvent) {
            const BlockRef at = block_of(ev.origin);
            if (const auto* r = std::get_if<nc::RapidMove>(&ev.data)) {
                sink_.programmed(line_segment(at, SegmentKind::kRapid, r->start, r->end));
            } else if (const auto* l = std::get_if<nc::LineMove>(&ev.data)) {
                sink_.programmed(line_segment(at, SegmentKind::kLine, l->start, l->end));
            } else if (const auto* a = std::get_if<nc::ArcMove>(&ev.data)) {
                sink_.programmed(arc_segment(at, *a));
            }
        }
    }

    // ---- setup and end

    bool setup() {
        for (std::size_t i = 0; i < out_.axis_names.size(); ++i)
            out_.axis_names[i] = "a" + std::to_string(i);
        const auto st = board_.motion_status();
        if (!st) return board_failure({}, st.status, "motion status");
        start_cycle_ = st.value.now;
        cycles_seen_ = st.value.now;
        segments_lost_ = st.value.segments_lost;
        trace_lost_ = st.value.trace_lost;

        auto cycle = apci::object(bm::kBus, bm::kDevice, bm::kIdxInterpolationCycle, 0);
        const auto us = board_.read_int(cycle);
        if (!us) return board_failure({}, us.status, "read InterpolationCycle");
        cycle_us_ = us.value;
        out_.totals.cycle_seconds = static_cast<double>(cycle_us_) * 1e-6;
        // Program units are mm; so is everything the board is told.
        auto pu = apci::object(bm::kBus, bm::kDevice, bm::kIdxPu, 0);
        if (!write(pu, std::int32_t{bm::kPuMillimetre}, {}, "PU")) return false;

        if (!read_axis_numbers()) return false;
        for (std::size_t i = 0; i < out_.axis_names.size(); ++i)
            out_.axis_names[i] =
                axis_column_name(static_cast<int>(i), axes_[0], axes_[1], axes_[2]);
        if (out_.tc_present && !setup_groups()) return false;

        sink_.axes(out_.axis_names);
        if (sink_.wants_samples()) {
            const auto r = board_.trace_enable(2 * ProgramExecutor::kTraceChunk);
            if (!r) return board_failure({}, r.status, "trace on");
            tracing_ = true;
        }
        return true;
    }

    // X/Y/Z-Axis-Nr; their absence (NoSuchDevice) means the firmware has no optionTC.
    bool read_axis_numbers() {
        for (int i = 0; i < 3; ++i) {
            auto o = init_object(tc::kIdxAxisNr, i);
            const auto r = board_.read_int(o);
            if (r.status == APCI_NO_SUCH_DEVICE) {
                out_.tc_present = false;
                axes_ = {0, 1, 2};
                break;
            }
            if (!r) return board_failure({}, r.status, "read Axis-Nr");
            axes_[static_cast<std::size_t>(i)] = r.value;
        }
        out_.axis_numbers = axes_;
        return true;
    }

    // RESET (every group to power-on), then group g in the plane kGroupPlane[g - 1], and the
    // program's start state: G17.
    bool setup_groups() {
        auto reset = group_object(1, tc::kSubReset);
        if (!write(reset, std::int32_t{1}, {}, "RESET")) return false;
        for (std::int32_t g = 1; g <= kGroups; ++g) {
            const PlaneAxes p = plane_axes(kGroupPlane[static_cast<std::size_t>(g - 1)]);
            auto x = group_object(g, tc::kSubXAxis);
            auto y = group_object(g, tc::kSubYAxis);
            auto z = group_object(g, tc::kSubZAxis);
            if (!write(x, axis(p.first), {}, "XAxis") || !write(y, axis(p.second), {}, "YAxis") ||
                !write(z, axis(p.third), {}, "ZAxis"))
                return false;
        }
        auto plane = init_object(tc::kIdxTcPlane);
        return write(plane, std::int32_t{17}, {}, "TcPlane");
    }

    std::int32_t axis(int program_axis) const noexcept {
        return axes_[static_cast<std::size_t>(program_axis)];
    }

    void finish() {
        // The move under way ends (after a TC error the board holds the rest). A clock that
        // failed already is not asked again; its error is recorded.
        if (set_up_ && clock_ok_) (void)run_clock();
        if (out_.tc_present) read_registers();
        out_.totals.cycles = cycles_seen_ - start_cycle_;
        if (!comp_plane_seen_) out_.plot_plane = plane_;
    }

    void read_registers() {
        for (std::int32_t g = 1; g <= kGroups; ++g) {
            GroupRegisters r;
            r.group = g;
            auto e = group_object(g, tc::kSubError);
            auto s = group_object(g, tc::kSubStatus);
            const auto error = board_.read_int(e);
            const auto status = board_.read_int(s);
            r.readable = error.ok() && status.ok();
            r.error = error.value_or(0);
            r.status = status.value_or(0);
            out_.registers.push_back(r);
        }
    }

    // ---- events

    bool dispatch(const nc::Event& ev) {
        const BlockRef at = block_of(ev.origin);
        return std::visit(
            [&](const auto& e) -> bool {
                using E = std::decay_t<decltype(e)>;
                if constexpr (std::is_same_v<E, nc::RapidMove>) {
                    return move(at, e.start, e.end, APCI_PROFILE_RAPID, 0.0);
                } else if constexpr (std::is_same_v<E, nc::LineMove>) {
                    return move(at, e.start, e.end, APCI_PROFILE_LINE, e.feed);
                } else if constexpr (std::is_same_v<E, nc::ArcMove>) {
                    return arc(at, e);
                } else if constexpr (std::is_same_v<E, nc::ToolSelect>) {
                    return tool(at, e.tool);
                } else if constexpr (std::is_same_v<E, nc::CompensationChange>) {
                    return compensation(at, e.side);
                } else if constexpr (std::is_same_v<E, nc::CornerModeChange>) {
                    return corner(at, e.mode);
                } else if constexpr (std::is_same_v<E, nc::PlaneChange>) {
                    return plane(at, e.plane);
                } else if constexpr (std::is_same_v<E, nc::ProgramEnd>) {
                    return end_of_program(at);
                } else {
                    // The Klartext 3D events (TOOL CALL deltas, TCPM, PROG PATH, M107, head
                    // orientation, LN) belong to the board's 3D compensation module (bus
                    // 1310), which this executor does not drive yet: refused by name, never
                    // run approximately.
                    return record(at, "Unsupported",
                                  fmt::format("'{}' events are not executed by apcictl run yet "
                                              "(the 3D compensation module, bus 1310, is not "
                                              "driven by the executor)",
                                              nc::event_name(ev.data)));
                }
            },
            ev.data);
    }

    static PathSegment line_segment(const BlockRef& at, SegmentKind kind,
                                    const Eigen::Vector3d& start, const Eigen::Vector3d& end) {
        PathSegment s;
        s.block = at;
        s.kind = kind;
        s.start = start;
        s.end = end;
        return s;
    }

    static PathSegment arc_segment(const BlockRef& at, const nc::ArcMove& a) {
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

    bool move(const BlockRef& at, const Eigen::Vector3d& start, const Eigen::Vector3d& end,
              std::uint8_t kind, double feed) {
        const PathSegment s = line_segment(
            at, kind == APCI_PROFILE_RAPID ? SegmentKind::kRapid : SegmentKind::kLine, start, end);
        return spool(at, s, profile(at, kind, end, feed));
    }

    bool arc(const BlockRef& at, const nc::ArcMove& a) {
        const PathSegment s = arc_segment(at, a);
        apci_profile p =
            profile(at, a.ccw ? APCI_PROFILE_ARC_CCW : APCI_PROFILE_ARC_CW, a.end, a.feed);
        const PlaneAxes pa = plane_axes(s.plane);
        p.arc_axes[0] = static_cast<std::uint8_t>(axis(pa.first));
        p.arc_axes[1] = static_cast<std::uint8_t>(axis(pa.second));
        p.center[0] = a.center[pa.first];
        p.center[1] = a.center[pa.second];
        return spool(at, s, p);
    }

    apci_profile profile(const BlockRef& at, std::uint8_t kind, const Eigen::Vector3d& end,
                         double feed) const noexcept {
        apci_profile p{};
        p.kind = kind;
        p.tag = encode_block_tag(at);
        p.feed = feed;
        for (int i = 0; i < 3; ++i) {
            const std::int32_t a = axis(i);
            p.axes = static_cast<std::uint8_t>(p.axes | (1u << a));
            p.target[a] = end[i];
        }
        return p;
    }

    bool spool(const BlockRef& at, const PathSegment& programmed, const apci_profile& p) {
        sink_.programmed(programmed);
        recent_.add(p.tag, programmed);
        for (;;) {
            const auto r = board_.spool(p);
            if (r.ok()) return true;
            if (r.status == APCI_BUSY) {
                if (!make_room()) return false;
                continue;
            }
            const std::string text(board_.last_error());
            if (r.value.errors != 0)
                return tc_errors(decode_block_tag(r.value.tag), r.value.errors, text);
            return record(at, std::string(apci::status_name(r.status)), text);
        }
    }

    bool tool(const BlockRef& at, int index) {
        if (!out_.tc_present) return true;  // no TC module: nothing takes a tool
        const nc::ToolData* t = tools_ != nullptr && index > 0 ? tools_->find(index) : nullptr;
        const double radius = t != nullptr ? t->radius_mm() : 0.0;
        const double length = t != nullptr ? t->length_mm() : 0.0;
        // A tool change: the axes stop first, so every segment read back so far ran with the
        // old tool's length.
        if (!run_clock()) return false;
        for (std::int32_t g = 1; g <= kGroups; ++g) {
            auto index_object = group_object(g, tc::kSubWkzIndex);
            auto radius_object = group_object(g, tc::kSubRadius);
            auto length_object = group_object(g, tc::kSubWkzLen);
            if (!write(index_object, std::int32_t{index}, at, "WKZINDEX") ||
                !write(radius_object, radius, at, "RADIUS") ||
                !write(length_object, length, at, "WkzLen"))
                return false;
        }
        length_ = length;
        return true;
    }

    bool plane(const BlockRef& at, nc::Plane p) {
        plane_ = nc::g_number(p);
        if (!out_.tc_present) return true;
        // The length axis changes with the plane: segments of the last contour are read first.
        if (!run_clock()) return false;
        auto o = init_object(tc::kIdxTcPlane);
        return write(o, std::int32_t{plane_}, at, "TcPlane");
    }

    bool corner(const BlockRef& at, nc::CornerMode m) {
        if (!out_.tc_present) return true;
        for (std::int32_t g = 1; g <= kGroups; ++g) {
            auto o = group_object(g, tc::kSubCornerMode);
            if (!write(o, std::int32_t{nc::g_number(m)}, at, "CornerMode")) return false;
        }
        return true;
    }

    bool compensation(const BlockRef& at, nc::Compensation side) {
        if (!out_.tc_present) {
            return record(at, "NoSuchDevice",
                          fmt::format("G{} needs the TC module (bus 1300), and this board's "
                                      "firmware has no optionTC",
                                      nc::g_number(side)));
        }
        if (comp_on_ && !compensation_off(at)) return false;
        if (side == nc::Compensation::kOff) return true;
        auto select = group_object(tc::kActiveGroupIndex,
                                   side == nc::Compensation::kLeft ? tc::kSubLeft : tc::kSubRight);
        auto status = group_object(tc::kActiveGroupIndex, tc::kSubStatus);
        if (!write(select, std::int32_t{1}, at,
                   side == nc::Compensation::kLeft ? "Left" : "Right") ||
            !write(status, std::int32_t{1}, at, "STATUS = 1"))
            return false;
        comp_on_ = true;
        comp_plane_ = plane_;
        if (!comp_plane_seen_) {
            comp_plane_seen_ = true;
            out_.plot_plane = plane_;
        }
        return true;
    }

    // STATUS = 0: the held profile is spooled with the departure (seed 003 section 1).
    bool compensation_off(const BlockRef& at) {
        auto status = group_object(tc::kActiveGroupIndex, tc::kSubStatus);
        if (!write(status, std::int32_t{0}, at, "STATUS = 0")) return false;
        comp_on_ = false;
        return true;
    }

    bool end_of_program(const BlockRef& at) {
        if (comp_on_ && !compensation_off(at)) return false;
        return run_clock();
    }

    // ---- board access

    // Writes an object; Busy (the spooler cannot take what the write releases) runs the clock
    // and tries again.
    template <typename T>
    bool write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what) {
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

    // A refused write: a TC error bit it set (InitError) names it, else the status does.
    bool write_failure(const BlockRef& at, apci::Status status, std::string_view what) {
        const std::string text = fmt::format("{}: {}", what, board_.last_error());
        if (out_.tc_present && status != APCI_NO_SUCH_DEVICE) {
            auto e = group_object(tc::kActiveGroupIndex, tc::kSubError);
            const auto bits = board_.read_int(e);
            if (bits && bits.value != 0) return tc_errors(at, bits.value, text);
        }
        return record(at, std::string(apci::status_name(status)), text);
    }

    bool board_failure(const BlockRef& at, apci::Status status, std::string_view what) {
        return record(at, std::string(apci::status_name(status)),
                      fmt::format("{}: {}", what, board_.last_error()));
    }

    // One error per Table 4 bit set.
    bool tc_errors(const BlockRef& at, std::int32_t bits, const std::string& text) {
        for (int bit = 0; bit < 32; ++bit) {
            if ((static_cast<std::uint32_t>(bits) & (1u << bit)) == 0) continue;
            const char* name = apci_tc_error_bit_name(bit);
            record(at, name != nullptr ? std::string(name) : fmt::format("bit{}", bit), text);
        }
        return false;
    }

    void program_error(const nc::Diagnostic& d) {
        record(BlockRef{d.block == nc::kNoBlockNumber ? kNoBlock : d.block, d.line},
               std::string(nc::error_kind_name(d.kind)), d.to_string());
    }

    // Records an error; returns false (the run stops).
    bool record(const BlockRef& at, std::string code, std::string message) {
        RunError e{at, std::move(code), std::move(message)};
        sink_.error(e, where(at));
        out_.errors.push_back(std::move(e));
        return false;
    }

    // Midway along the programmed move of the block, else where the axes stand.
    Point where(const BlockRef& at) {
        if (const PathSegment* s = recent_.find(encode_block_tag(at))) return point_along(*s, 0.5);
        const auto st = board_.motion_status();
        Point p = Point::Zero();
        if (st)
            for (int i = 0; i < 3; ++i) p[i] = st.value.position[axis(i)];
        return p;
    }

    // Busy: the spooler is full; running until idle empties it.
    bool make_room() {
        const std::uint64_t before = cycles_seen_;
        if (!run_clock()) return false;
        if (cycles_seen_ == before)
            return record({}, "Busy", "the spooler is full and the clock does not move it");
        return true;
    }

    // Runs the clock until the axes stop (in chunks while samples are recorded), reading the
    // executed segments and samples as they come.
    bool run_clock() {
        if (run_clock_until_idle()) return true;
        clock_ok_ = false;
        return false;
    }

    bool run_clock_until_idle() {
        for (;;) {
            const auto st =
                board_.run_until_idle(tracing_ ? ProgramExecutor::kTraceChunk : kRunForever);
            if (!st) return board_failure({}, st.status, "run clock");
            cycles_seen_ = st.value.now;
            if (!drain_segments(st.value.segments_pending) ||
                (tracing_ && !drain_samples(st.value.trace_pending)))
                return false;
            if (st.value.segments_lost != segments_lost_ || st.value.trace_lost != trace_lost_) {
                segments_lost_ = st.value.segments_lost;
                trace_lost_ = st.value.trace_lost;
                return record({}, "Lost",
                              "executed segments or samples were lost before they were read");
            }
            if ((st.value.flags & APCI_MOTION_IDLE) != 0) return true;
        }
    }

    // Reads the `pending` executed segments the clock call reported, in batches of at most
    // kReadBatch (asking for no more than are there keeps each read small).
    bool drain_segments(std::uint64_t pending) {
        while (pending > 0) {
            const std::size_t want =
                static_cast<std::size_t>(std::min<std::uint64_t>(pending, segments_.size()));
            const auto r = board_.read_segments(segments_.data(), want);
            if (!r) return board_failure({}, r.status, "read segments");
            for (std::size_t i = 0; i < r.value; ++i) {
                const PathSegment s = convert(segments_[i]);
                count_segment(out_.totals, s);
                sink_.executed(s);
            }
            if (r.value == 0) break;
            pending -= std::min<std::uint64_t>(pending, r.value);
        }
        return true;
    }

    bool drain_samples(std::uint64_t pending) {
        while (pending > 0) {
            const std::size_t want =
                static_cast<std::size_t>(std::min<std::uint64_t>(pending, samples_.size()));
            const auto r = board_.read_trace(samples_.data(), want);
            if (!r) return board_failure({}, r.status, "read trace");
            for (std::size_t i = 0; i < r.value; ++i) {
                const apci_trace_sample& t = samples_[i];
                const double time =
                    static_cast<double>(t.cycle * static_cast<std::uint64_t>(cycle_us_)) / 1e6;
                sink_.sample(t.cycle, time, std::span<const double>(t.position, APCI_AXIS_COUNT));
            }
            if (r.value == 0) break;
            pending -= std::min<std::uint64_t>(pending, r.value);
        }
        return true;
    }

    // A board segment in program coordinates: X, Y, Z from their board axes, the tool length
    // compensation taken off (the tool centre point, DESIGN.md section 7).
    PathSegment convert(const apci_segment& b) {
        PathSegment s;
        s.block = decode_block_tag(b.tag);
        s.role = role_of(b.role);
        s.start_cycle = b.start_cycle;
        s.end_cycle = b.end_cycle;
        s.kind = b.role == APCI_ROLE_RAPID    ? SegmentKind::kRapid
                 : b.kind == APCI_SEGMENT_ARC ? SegmentKind::kArc
                                              : SegmentKind::kLine;
        for (int i = 0; i < 3; ++i) {
            const std::int32_t a = axis(i);
            s.start[i] = b.start[a];
            s.end[i] = b.end[a];
            s.center[i] = b.center[a];
        }
        if (s.kind == SegmentKind::kArc) arc_plane(b, s);
        const int z = plane_axes(comp_plane_).third;
        const double end_offset = ends_length_compensated(s.role) ? length_ : 0.0;
        s.start[z] -= start_offset_;
        s.center[z] -= start_offset_;
        s.end[z] -= end_offset;
        start_offset_ = end_offset;
        return s;
    }

    // The arc's plane code and sense in program axes.
    void arc_plane(const apci_segment& b, PathSegment& s) const noexcept {
        int first = -1, second = -1;
        for (int i = 0; i < 3; ++i) {
            if (axis(i) == b.plane_axes[0]) first = i;
            if (axis(i) == b.plane_axes[1]) second = i;
        }
        s.ccw = b.ccw != 0;
        s.plane = 17;
        for (const int code : {17, 18, 19}) {
            const PlaneAxes p = plane_axes(code);
            if (p.first == first && p.second == second) {
                s.plane = code;
            } else if (p.first == second && p.second == first) {
                s.plane = code;  // named the other way round: seen from the other side
                s.ccw = !s.ccw;
            }
        }
    }

    apci::Board& board_;
    RunSink& sink_;
    const nc::ToolTable* tools_;
    RunOutcome out_;
    std::array<int, 3> axes_{0, 1, 2};
    std::int32_t cycle_us_ = 1000;
    std::uint64_t start_cycle_ = 0;
    std::uint64_t cycles_seen_ = 0;
    std::uint64_t segments_lost_ = 0;
    std::uint64_t trace_lost_ = 0;
    bool tracing_ = false;
    bool set_up_ = false;   // setup() succeeded: the board was configured for the run
    bool clock_ok_ = true;  // no clock call failed
    int plane_ = 17;
    int comp_plane_ = 17;  // the plane of the compensation under way or last run
    bool comp_on_ = false;
    bool comp_plane_seen_ = false;
    double length_ = 0.0;        // WkzLen of the current tool
    double start_offset_ = 0.0;  // length compensation at the end of the last segment read
    RecentMoves recent_;
    std::vector<apci_segment> segments_;
    std::vector<apci_trace_sample> samples_;
};

}  // namespace

Point ProgramExecutor::position() {
    std::array<int, 3> axes{0, 1, 2};
    for (int i = 0; i < 3; ++i) {
        auto o = init_object(tc::kIdxAxisNr, i);
        const auto r = board_.read_int(o);
        if (!r) {
            axes = {0, 1, 2};
            break;
        }
        axes[static_cast<std::size_t>(i)] = r.value;
    }
    const auto st = board_.motion_status();
    Point p = Point::Zero();
    if (st)
        for (int i = 0; i < 3; ++i) p[i] = st.value.position[axes[static_cast<std::size_t>(i)]];
    return p;
}

RunOutcome ProgramExecutor::run(nc::EventStream& events) {
    auto execution = std::make_unique<Execution>(board_, sink_, tools_);
    return execution->run(events);
}

}  // namespace apci::run
