// SPDX-License-Identifier: MIT
#include "apci/run/executor.h"
#include "apci/nc/arc.h"
#include "apci/run/self_approach.h"
#include "rwmos/geometry/tolerances.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>
#include <unordered_map>
#include <variant>

#include "apci/run/csv_writer.h"
#include "apci/run/plc_script.h"
#include "rwmos/comp3d/refusal.h"
#include "rwmos/object_map.h"
#include "rwmos/otc/errors.h"

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
namespace c3 = rwmos::comp3d;

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
ObjectDescriptor c3_object(std::int32_t index, std::int32_t sub = 0) noexcept {
    return apci::object(c3::kBus, c3::kDevSettings, index, sub);
}

// Feed of an LN with FMAX: spooled as a G01 (so that it is compensated) at the board's rapid
// feed (docs/motion.md: 60000 units/min).
constexpr double kLnRapidFeed = 60000.0;

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

namespace otc = rwmos::otc;
namespace tcomp = rwmos::tempcomp;

// The front end refuses the arcs the board's TC module would refuse with CenterError, no more.
static_assert(nc::kArcRadiusTolerance == rwmos::geom::kCenterRadiusTolerance);
// The front end checks $SC_TOOL_TEMP_COMP[i] against the range of the board's object.
static_assert(nc::kToolTempCompLimit == tcomp::kMaxValue);
static_assert(nc::kToolTempCompCount == 3);
// The correction table's rows and values fit the 3D module's table (DeviceNumber 2).
static_assert(nc::kMaxCorrectionRow == rwmos::comp3d::kCorrectionRows - 1);
static_assert(nc::kCorrectionLimit == rwmos::comp3d::kMaxValue);

ObjectDescriptor otc_object(std::int32_t dev, std::int32_t index, std::int32_t sub = 0) noexcept {
    return apci::object(otc::kBus, dev, index, sub);
}
ObjectDescriptor temp_object(std::int32_t index, std::int32_t sub = 0) noexcept {
    return apci::object(tcomp::kBus, tcomp::kDevice, index, sub);
}

class Execution {
  public:
    Execution(apci::Board& board, RunSink& sink, const nc::ToolTable* tools, const PlcScript* plc,
              const nc::CorrectionTable* corrections, SelfApproachMode self_approach)
        : board_(board),
          sink_(sink),
          tools_(tools),
          corrections_(corrections),
          plc_(plc),
          variables_(*this),
          self_approach_mode_(self_approach) {
        segments_.resize(ProgramExecutor::kReadBatch);
        samples_.resize(ProgramExecutor::kReadBatch);
        if (tools_ != nullptr) tools_mut_ = *tools_;
    }

    RunOutcome run(nc::EventStream& events) {
        // The program reads the board's V.G. variables ([ISG-OTC] section 2.8).
        events.set_variable_source(&variables_);
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
                klartext_ = events.dialect() == nc::Dialect::kKlartext;
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
            } else if (const auto* v = std::get_if<nc::VectorLineMove>(&ev.data)) {
                sink_.programmed(line_segment(at, SegmentKind::kLine, v->start, v->end));
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
        if (!otc_setup()) return false;
        if (!temp_setup()) return false;

        sink_.axes(out_.axis_names);
        sink_.axis_numbers(axes_);
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
    // program's start state: G17, and the NC start corner mode (G25; the board's own default is
    // circular).
    bool setup_groups() {
        auto reset = group_object(1, tc::kSubReset);
        if (!write(reset, std::int32_t{1}, {}, "RESET")) return false;
        for (std::int32_t g = 1; g <= kGroups; ++g) {
            const PlaneAxes p = plane_axes(kGroupPlane[static_cast<std::size_t>(g - 1)]);
            auto x = group_object(g, tc::kSubXAxis);
            auto y = group_object(g, tc::kSubYAxis);
            auto z = group_object(g, tc::kSubZAxis);
            auto corner = group_object(g, tc::kSubCornerMode);
            if (!write(x, axis(p.first), {}, "XAxis") || !write(y, axis(p.second), {}, "YAxis") ||
                !write(z, axis(p.third), {}, "ZAxis") ||
                !write(corner, std::int32_t{nc::g_number(nc::kStartCornerMode)}, {}, "CornerMode"))
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
        // PLC writes due after the program's last move: the clock runs on to them.
        if (set_up_ && clock_ok_ && out_.errors.empty()) (void)plc_after_end();
        if (set_up_ && out_.otc_present) check_out_tool();
        if (set_up_) read_variables();
        out_.tools_after = tools_mut_;
        if (self_approach_.truncated())
            out_.notices.push_back(RunError{
                {},
                "SelfApproachTruncated",
                fmt::format("the self-approach check kept {} distinct elements per plane and did "
                            "not check those beyond",
                            SelfApproachCheck::kMaxElements)});
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
        // The head's rotary axes go with the block's move; a block that turns the head only
        // gets a move of its own.
        const bool is_move = std::holds_alternative<nc::RapidMove>(ev.data) ||
                             std::holds_alternative<nc::LineMove>(ev.data) ||
                             std::holds_alternative<nc::VectorLineMove>(ev.data);
        if (head_pending_ && !is_move && !head_only_move(head_at_)) return false;
        if (!plc_block(ev.origin)) return false;
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
                    return klartext_ ? klartext_compensation(at, e.side) : compensation(at, e.side);
                } else if constexpr (std::is_same_v<E, nc::CornerModeChange>) {
                    return corner(at, e.mode);
                } else if constexpr (std::is_same_v<E, nc::PlaneChange>) {
                    return plane(at, e.plane);
                } else if constexpr (std::is_same_v<E, nc::ProgramEnd>) {
                    return end_of_program(at);
                } else if constexpr (std::is_same_v<E, nc::ToolCallDeltas>) {
                    return tool_call(at, e);
                } else if constexpr (std::is_same_v<E, nc::TcpmChange>) {
                    return tcpm(at, e);
                } else if constexpr (std::is_same_v<E, nc::ProgPathChange>) {
                    return c3_setting(at, c3::kIdxProgPath, e.contour ? 1 : 0, "ProgPath");
                } else if constexpr (std::is_same_v<E, nc::OversizeChange>) {
                    return c3_setting(at, c3::kIdxAllowOversize, e.allowed ? 1 : 0,
                                      "AllowOversize");
                } else if constexpr (std::is_same_v<E, nc::HeadOrientation>) {
                    return head(at, e);
                } else if constexpr (std::is_same_v<E, nc::OtcChange>) {
                    return otc_command(at, e.command);
                } else if constexpr (std::is_same_v<E, nc::KinematicsSelect>) {
                    return otc_setting(at, otc::kIdxKinematics, e.id, "#KIN (Kinematics)");
                } else if constexpr (std::is_same_v<E, nc::TrafoChange>) {
                    return trafo(at, e);
                } else if constexpr (std::is_same_v<E, nc::NotEmulated>) {
                    out_.notices.push_back(RunError{
                        at, "NotEmulated",
                        fmt::format("{} is accepted and not emulated (docs/design.md section 8)",
                                    e.command)});
                    return true;
                } else if constexpr (std::is_same_v<E, nc::VariableWrite>) {
                    return variable_write(at, e);
                } else if constexpr (std::is_same_v<E, nc::CorrectionSelect>) {
                    return c3_setting(at, c3::kIdxCorrectionRow, e.row,
                                      "FUNCTION CORRDATA (CorrectionRow)");
                } else {
                    static_assert(std::is_same_v<E, nc::VectorLineMove>);
                    return vector_line(at, e);
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
        // [TNC-3D], peripheral milling: "L-Satz mit programmierten Drehachsen, M128 oder
        // FUNCTION TCPM aktiv, Korrekturrichtung mit Radiuskorrektur RL oder RR".
        const bool peripheral =
            klartext_ && kind == APCI_PROFILE_LINE && tcpm_ && side_ != nc::Compensation::kOff;
        if (peripheral) {
            if (!c3_setting(at, c3::kIdxArm, c3::kArmLine, "Arm")) return false;
            return c3_spool(at, s, profile(at, kind, end, feed));
        }
        const bool ok = spool(at, s, profile(at, kind, end, feed));
        head_pending_ = false;
        return ok;
    }

    bool arc(const BlockRef& at, const nc::ArcMove& a) {
        const PathSegment s = arc_segment(at, a);
        apci_profile p =
            profile(at, a.ccw ? APCI_PROFILE_ARC_CCW : APCI_PROFILE_ARC_CW, a.end, a.feed);
        const PlaneAxes pa = plane_axes(s.plane);
        p.arc_axes[0] = static_cast<std::uint8_t>(axis(pa.first));
        p.arc_axes[1] = static_cast<std::uint8_t>(axis(pa.second));
        const Eigen::Vector3d centre =
            trafo_ ? pivot_of(a.center, head_pending_ ? head_b_ : b_now_) : a.center;
        p.center[0] = centre[pa.first];
        p.center[1] = centre[pa.second];
        return spool(at, s, p);
    }

    apci_profile profile(const BlockRef& at, std::uint8_t kind, const Eigen::Vector3d& end,
                         double feed) noexcept {
        apci_profile p{};
        p.kind = kind;
        p.tag = encode_block_tag(at);
        p.feed = feed;
        const Eigen::Vector3d target = trafo_ ? pivot_of(end, head_pending_ ? head_b_ : b_now_) : end;
        for (int i = 0; i < 3; ++i) {
            const std::int32_t a = axis(i);
            p.axes = static_cast<std::uint8_t>(p.axes | (1u << a));
            p.target[a] = target[i];
        }
        if (head_pending_) add_head(p);
        return p;
    }

    void add_head(apci_profile& p) noexcept {
        p.axes = static_cast<std::uint8_t>(p.axes | (1u << head_b_axis_) | (1u << head_c_axis_));
        p.target[head_b_axis_] = head_b_;
        p.target[head_c_axis_] = head_c_;
        b_now_ = head_b_;
    }

    // ---- #TRAFO: the B head's tool-tip transformation (docs/design.md section 8; docs/otc.md)

    static Eigen::Vector3d tool_axis(double b_deg) noexcept {
        const double b = b_deg * (std::numbers::pi / 180.0);
        return {std::sin(b), 0.0, std::cos(b)};
    }
    // The pivot (the machine's X, Y, Z) of a tool tip at tilt b: one tool length behind it.
    Eigen::Vector3d pivot_of(const Eigen::Vector3d& tip, double b_deg) const noexcept {
        return tip + trafo_length_ * tool_axis(b_deg);
    }

    // The axes stop first, so the segments read back before belong to the old state.
    bool trafo(const BlockRef& at, const nc::TrafoChange& e) {
        if (e.on && head_b_axis_ < 0)
            return record(at, "Unsupported", "no free board axis for the head's B");
        if (!run_clock()) return false;
        if (out_.otc_present &&
            !otc_setting(at, otc::kIdxTrafo, e.on ? 1 : 0, e.on ? "#TRAFO ON" : "#TRAFO OFF"))
            return false;
        trafo_ = e.on;
        trafo_length_ = e.tool_length;
        return true;
    }

    bool spool(const BlockRef& at, const PathSegment& programmed, const apci_profile& p) {
        sink_.programmed(programmed);
        recent_.add(p.tag, programmed);
        if (comp_on_ && self_approach_mode_ != SelfApproachMode::kOff) {
            // A rapid ends the contour on the board; the next move approaches it anew.
            if (programmed.kind == SegmentKind::kRapid) {
                self_approach_.end(findings_);
                if (!take_findings()) return false;
            } else {
                if (!self_approach_.active()) self_approach_.begin(radius_, comp_plane_);
                self_approach_.programmed(programmed, findings_);
                if (!take_findings()) return false;
            }
        }
        for (;;) {
            const auto r = board_.spool(p);
            if (r.ok()) return true;
            if (r.status == APCI_BUSY) {
                if (!make_room()) return false;
                continue;
            }
            // A TC error: the board's own words (the element at fault is the block the error
            // names; the call's status and tag say nothing more).
            const std::string_view said = board_.last_board_message();
            if (r.value.errors != 0)
                return tc_errors(decode_block_tag(r.value.tag), r.value.errors,
                                 std::string(said.empty() ? board_.last_error() : said));
            return record(at, std::string(apci::status_name(r.status)),
                          std::string(board_.last_error()));
        }
    }

    bool tool(const BlockRef& at, int index) {
        if (out_.otc_present) {
            // [ISG-OTC] section 2.9: the wear of the tool going out reaches the tool list.
            if (!run_clock()) return false;
            check_out_tool();
            if (index != current_tool_) reported_radius_wear_ = reported_cont_wear_ = 0.0;
            if (!otc_tool(at, index)) return false;
        }
        current_tool_ = index;
        if (!out_.tc_present) return true;  // no TC module: nothing takes a tool
        const nc::ToolData* t = tools_ != nullptr && index > 0 ? tools_mut_.find(index) : nullptr;
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
        radius_ = radius;
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
        self_approach_.begin(radius_, plane_);
        if (!comp_plane_seen_) {
            comp_plane_seen_ = true;
            out_.plot_plane = plane_;
        }
        return true;
    }

    // STATUS = 0: the held profile is spooled with the departure ([APCI-TC] section 1).
    bool compensation_off(const BlockRef& at) {
        auto status = group_object(tc::kActiveGroupIndex, tc::kSubStatus);
        if (!write(status, std::int32_t{0}, at, "STATUS = 0")) return false;
        comp_on_ = false;
        self_approach_.end(findings_);
        return take_findings();
    }

    bool end_of_program(const BlockRef& at) {
        if (comp_on_ && !compensation_off(at)) return false;
        return run_clock();
    }

    // ---- Klartext 3D compensation (bus 1310; docs/apcictl.md "run", docs/object-map.md 6)

    // The first Klartext 3D event puts the module in the program's start state: no tool, no
    // deltas, PROG PATH OFF, TCPM off (tip), M108, R0, nothing armed; the head's B and C on the
    // first two board axes that are not X, Y or Z.
    bool c3_setup(const BlockRef& at) {
        if (c3_ready_) return true;
        std::array<bool, APCI_AXIS_COUNT> used{};
        for (const int a : axes_) used[static_cast<std::size_t>(a)] = true;
        std::array<std::int32_t, 2> head{-1, -1};
        std::size_t found = 0;
        for (std::int32_t a : {4, 5, 6, 7, 3}) {
            if (found < head.size() && !used[static_cast<std::size_t>(a)]) head[found++] = a;
        }
        head_b_axis_ = head[0];
        head_c_axis_ = head[1];
        auto probe = c3_object(c3::kIdxTool);
        if (board_.read_int(probe).status == APCI_NO_SUCH_DEVICE) {
            return record(at, "NoSuchDevice",
                          "Klartext LN lines, TOOL CALL deltas, TCPM and PROG PATH need the 3D "
                          "compensation module (bus 1310), which this board does not have");
        }
        c3_ready_ = true;
        const std::pair<std::int32_t, std::int32_t> settings[] = {
            {c3::kIdxAllowOversize, 1},
            {c3::kIdxTool, 0},
            {c3::kIdxCorrectionRow, 0},
            {c3::kIdxAllowOversize, 0},
            {c3::kIdxProgPath, 0},
            {c3::kIdxReference, 0},
            {c3::kIdxTcpm, 0},
            {c3::kIdxSide, 40},
            {c3::kIdxArm, 0},
            {c3::kIdxHeadAxisB, head_b_axis_},
            {c3::kIdxHeadAxisC, head_c_axis_}};
        for (int k = 0; k < 3; ++k) {
            auto o = c3_object(c3::kIdxCallDeltas, k);
            if (!c3_write(o, 0.0, at, "CallDeltas")) return false;
        }
        for (const auto& [index, value] : settings) {
            auto o = c3_object(index);
            if (!c3_write(o, value, at, "3D compensation setup")) return false;
        }
        // The correction table: row 0 (FUNCTION CORRDATA RESET TCS, the start) without
        // correction, then the rows of --corr.
        if (!c3_correction_row(at, nc::CorrectionRow{})) return false;
        if (corrections_ != nullptr)
            for (const nc::CorrectionRow& r : corrections_->rows())
                if (!c3_correction_row(at, r)) return false;
        return true;
    }

    bool c3_correction_row(const BlockRef& at, const nc::CorrectionRow& r) {
        const std::pair<std::int32_t, double> values[] = {
            {c3::kSubCorrDl, r.dl}, {c3::kSubCorrDr, r.dr}, {c3::kSubCorrDr2, r.dr2}};
        for (const auto& [sub, value] : values) {
            auto o = apci::object(c3::kBus, c3::kDevCorrections, r.row, sub);
            if (!c3_write(o, value, at, "correction table")) return false;
        }
        return true;
    }

    bool c3_setting(const BlockRef& at, std::int32_t index, std::int32_t value,
                    std::string_view what) {
        if (!c3_setup(at)) return false;
        auto o = c3_object(index);
        return c3_write(o, value, at, what);
    }

    // TOOL CALL n Z DL DR DR2: the tool list's R, R2 and deltas into the module's tool table
    // row n, the call's deltas, then Tool = n (the board checks the oversize rule).
    bool tool_call(const BlockRef& at, const nc::ToolCallDeltas& e) {
        if (!c3_setup(at)) return false;
        const nc::ToolData* t = tools_ != nullptr && e.tool > 0 ? tools_->find(e.tool) : nullptr;
        const double row[] = {t ? t->radius_mm() : 0.0, t ? t->r2_mm() : 0.0, t ? t->dl_mm() : 0.0,
                              t ? t->dr_mm() : 0.0, t ? t->dr2_mm() : 0.0};
        for (std::int32_t sub = c3::kSubR; sub <= c3::kSubDr2; ++sub) {
            auto o = apci::object(c3::kBus, c3::kDevTools, e.tool, sub);
            if (!c3_write(o, row[sub - c3::kSubR], at, "tool table")) return false;
        }
        const double call[] = {e.dl, e.dr, e.dr2};
        for (int k = 0; k < 3; ++k) {
            auto o = c3_object(c3::kIdxCallDeltas, k);
            if (!c3_write(o, call[k], at, "CallDeltas")) return false;
        }
        auto o = c3_object(c3::kIdxTool);
        return c3_write(o, std::int32_t{e.tool}, at, "TOOL CALL");
    }

    // M128 / FUNCTION TCPM / M129 / FUNCTION RESET TCPM. Lines with RL/RR under TCPM are the 3D
    // module's (peripheral milling), so a 2D radius compensation under way ends first.
    bool tcpm(const BlockRef& at, const nc::TcpmChange& e) {
        if (e.on && comp_on_ && !compensation_off(at)) return false;
        if (!c3_setting(at, c3::kIdxReference, e.reference == nc::ToolReference::kCentre ? 1 : 0,
                        "Reference") ||
            !c3_setting(at, c3::kIdxTcpm, e.on ? 1 : 0, "Tcpm"))
            return false;
        tcpm_ = e.on;
        return true;
    }

    // R0 / RL / RR of a Klartext program: the 3D module's side (LN lines, and L lines under
    // TCPM); without TCPM an L line's RL/RR is the TC module's 2D radius compensation.
    bool klartext_compensation(const BlockRef& at, nc::Compensation side) {
        side_ = side;
        const std::int32_t code = side == nc::Compensation::kLeft    ? tc::kSideLeft
                                  : side == nc::Compensation::kRight ? tc::kSideRight
                                                                     : tc::kSideNone;
        if (!c3_setting(at, c3::kIdxSide, code, "Side")) return false;
        if (tcpm_) return true;
        return compensation(at, side);
    }

    bool head(const BlockRef& at, const nc::HeadOrientation& e) {
        if (!c3_setup(at)) return false;
        if (head_b_axis_ < 0 || head_c_axis_ < 0)
            return record(at, "Unsupported", "no free board axes for the head's B and C");
        head_pending_ = true;
        head_at_ = at;
        head_b_ = e.b;
        head_c_ = e.c;
        return true;
    }

    // A block that only turns the head: the rotary axes move at the rapid feed.
    bool head_only_move(const BlockRef& at) {
        apci_profile p{};
        p.kind = APCI_PROFILE_RAPID;
        p.tag = encode_block_tag(at);
        add_head(p);
        head_pending_ = false;
        for (;;) {
            const auto r = board_.spool(p);
            if (r.ok()) return true;
            if (r.status == APCI_BUSY) {
                if (!make_room()) return false;
                continue;
            }
            return record(at, std::string(apci::status_name(r.status)),
                          std::string(board_.last_error()));
        }
    }

    // LN: N and T into the module, armed, then the line as a G01 profile; the board puts the
    // compensated tool tip into its end point.
    bool vector_line(const BlockRef& at, const nc::VectorLineMove& e) {
        if (!c3_setup(at)) return false;
        std::int32_t bits = 0;
        if (e.has_normal) {
            for (int k = 0; k < 3; ++k) {
                auto o = c3_object(c3::kIdxSurfaceNormal, k);
                if (!c3_write(o, e.normal[k], at, "SurfaceNormal")) return false;
            }
            bits |= c3::kArmNormal;
        }
        // Without TCPM a programmed T is ignored ([TNC-3D]); with TCPM and no T the board
        // takes N.
        if (e.has_tool_vector && e.tool_vector_programmed) {
            for (int k = 0; k < 3; ++k) {
                auto o = c3_object(c3::kIdxToolVector, k);
                if (!c3_write(o, e.tool_vector[k], at, "ToolVector")) return false;
            }
            bits |= c3::kArmToolVector;
        }
        if (bits == 0) bits = c3::kArmLine;
        auto arm = c3_object(c3::kIdxArm);
        if (!c3_write(arm, bits, at, "Arm")) return false;
        const PathSegment s = line_segment(at, SegmentKind::kLine, e.start, e.end);
        return c3_spool(at, s,
                        profile(at, APCI_PROFILE_LINE, e.end, e.rapid ? kLnRapidFeed : e.feed));
    }

    // A profile for the 3D module: its refusal is named by the module's LastError.
    bool c3_spool(const BlockRef& at, const PathSegment& programmed, const apci_profile& p) {
        sink_.programmed(programmed);
        recent_.add(p.tag, programmed);
        head_pending_ = false;
        for (;;) {
            const auto r = board_.spool(p);
            if (r.ok()) {
                ++c3_pending_[p.tag];
                return true;
            }
            if (r.status == APCI_BUSY) {
                if (!make_room()) return false;
                continue;
            }
            return c3_failure(at, r.status, "LN");
        }
    }

    template <typename T>
    bool c3_write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what) {
        const auto r = board_.write(o, value);
        if (r.ok()) return true;
        return c3_failure(at, r.status, what);
    }

    // The module's LastError names a refusal (rwmos::comp3d::Refusal); it is cleared for the
    // next one.
    bool c3_failure(const BlockRef& at, apci::Status status, std::string_view what) {
        const std::string text = fmt::format("{}: {}", what, board_.last_error());
        auto last = c3_object(c3::kIdxLastError);
        const auto code = board_.read_int(last);
        if (code && code.value != 0) {
            auto clear = c3_object(c3::kIdxLastError);
            (void)board_.write(clear, std::int32_t{0});
            return record(at, std::string(c3::refusal_name(static_cast<c3::Refusal>(code.value))),
                          fmt::format("{} ({})", text,
                                      c3::refusal_message(static_cast<c3::Refusal>(code.value))));
        }
        return record(at, std::string(apci::status_name(status)), text);
    }

    // ---- OTC (bus 1330): #OTC, #KIN, #TRAFO, the tool's grinding data, the PLC script,
    // the V.G. variables (docs/apcictl.md "run", docs/otc.md)

    // The program's start state: OTC off, LENGTH, AUTO, the tool's wear constant, ACC_WEIGHT
    // 100, no kinematics, the control units off; the B head's B on the first free board axis
    // (as the 3D module's). Without the module (NoSuchDevice) OTC events are refused by name.
    bool otc_setup() {
        auto active = otc_object(otc::kDevChannel, otc::kIdxActive);
        const auto r = board_.read_int(active);
        if (r.status == APCI_NO_SUCH_DEVICE) {
            out_.otc_present = false;
            return true;
        }
        if (!r) return board_failure({}, r.status, "read OTC Active");
        out_.otc_present = true;
        if (r.value != 0 && !otc_write(active, std::int32_t{0}, {}, "#OTC OFF (start)")) return false;
        std::array<bool, APCI_AXIS_COUNT> used{};
        for (const int a : axes_) used[static_cast<std::size_t>(a)] = true;
        std::int32_t b_axis = 4;
        for (std::int32_t a : {4, 5, 6, 7, 3}) {
            if (!used[static_cast<std::size_t>(a)]) {
                b_axis = a;
                break;
            }
        }
        const std::pair<std::int32_t, std::int32_t> settings[] = {
            {otc::kIdxTrafo, 0},
            {otc::kIdxKinematics, 0},
            {otc::kIdxToolAxisB, b_axis},
            {otc::kIdxProcessingType, 1},
            {otc::kIdxMode, 2},
            {otc::kIdxWearConstSource, 0},
            {otc::kIdxAccWeight, 100}};
        for (const auto& [index, value] : settings) {
            auto o = otc_object(otc::kDevChannel, index);
            if (!otc_write(o, value, {}, "OTC setup")) return false;
        }
        auto ch_enable = otc_object(otc::kDevChannel, otc::kIdxRadiusOffsetUnit, otc::kSubEnable);
        if (!otc_write(ch_enable, std::int32_t{0}, {}, "OTC setup")) return false;
        for (std::int32_t a = 0; a < APCI_AXIS_COUNT; ++a) {
            auto en = otc_object(otc::kDevAxisUnits, a, otc::kSubEnable);
            if (!otc_write(en, std::int32_t{0}, {}, "OTC setup")) return false;
        }
        return true;
    }

    bool otc_needed(const BlockRef& at, std::string_view what) {
        if (out_.otc_present) return true;
        return record(at, "NoSuchDevice",
                      fmt::format("{} needs the OTC module (bus 1330), which this board does not "
                                  "have",
                                  what));
    }

    // A refused OTC write is named by the module's LastError (rwmos/otc/errors.h), else by
    // the status; LastError is cleared for the next one. Busy (moves queued under #OTC ON/OFF)
    // runs the clock and writes again.
    template <typename T>
    bool otc_write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what) {
        std::uint64_t busy_clock = ~std::uint64_t{0};  // the clock at this write's last Busy
        for (;;) {
            const auto r = board_.write(o, value);
            if (r.ok()) return true;
            if (r.status == APCI_BUSY) {
                // Zero-length moves leave without a cycle: only a second Busy with the clock
                // standing still means the board holds.
                const bool stood_still = busy_clock == cycles_seen_;
                busy_clock = cycles_seen_;
                if (!run_clock()) return false;
                if (stood_still && cycles_seen_ == busy_clock)
                    return record(at, "Busy",
                                  fmt::format("{}: moves are queued and the clock does not run "
                                              "them (the board holds)",
                                              what));
                continue;
            }
            const std::string text = fmt::format("{}: {}", what, board_.last_error());
            auto last = otc_object(otc::kDevChannel, otc::kIdxLastError);
            const auto code = board_.read_int(last);
            if (code && code.value != 0) {
                (void)board_.write(last, std::int32_t{0});
                const auto e = static_cast<otc::Error>(code.value);
                return record(at, std::string(otc::error_name(e)),
                              fmt::format("{} ({})", text, otc::error_message(e)));
            }
            return record(at, std::string(apci::status_name(r.status)), text);
        }
    }

    bool otc_setting(const BlockRef& at, std::int32_t index, std::int32_t value,
                     std::string_view what) {
        if (!otc_needed(at, what)) return false;
        auto o = otc_object(otc::kDevChannel, index);
        return otc_write(o, value, at, what);
    }

    // #OTC: the parameters first, then ON/OFF (the board answers Busy until the moves before
    // it have run: OTC switches at its place in the program).
    bool otc_command(const BlockRef& at, const nc::OtcCommand& c) {
        if (!otc_needed(at, "#OTC")) return false;
        if (c.type && !otc_setting(at, otc::kIdxProcessingType, static_cast<std::int32_t>(*c.type),
                                   "#OTC processing type"))
            return false;
        if (c.mode && !otc_setting(at, otc::kIdxMode, static_cast<std::int32_t>(*c.mode), "#OTC mode"))
            return false;
        if (c.acc_weight && !otc_setting(at, otc::kIdxAccWeight, *c.acc_weight, "#OTC ACC_WEIGHT"))
            return false;
        if (c.wear_const == nc::WearConstChoice::kProgrammed) {
            auto o = otc_object(otc::kDevChannel, otc::kIdxWearConst);
            if (!otc_write(o, c.wear_const_value, at, "#OTC WEAR_CONST")) return false;
        } else if (c.wear_const == nc::WearConstChoice::kTool &&
                   !otc_setting(at, otc::kIdxWearConstSource, 0, "#OTC WEAR_CONST_TOOL")) {
            return false;
        }
        if (!c.on) return true;
        if (!otc_setting(at, otc::kIdxActive, *c.on ? 1 : 0, *c.on ? "#OTC ON" : "#OTC OFF"))
            return false;
        // The wear folded into the tool's length: the segments read back from here on carry
        // the new length.
        if (!*c.on && out_.tc_present) {
            auto len = group_object(1, tc::kSubWkzLen);
            const auto l = board_.read_double(len);
            if (l) length_ = l.value;
        }
        return true;
    }

    // D n: the grinding data of wz[n] ([ISG-OTC] section 2.6) become the OTC module's current
    // tool. A new ToolNumber starts the tool's wear from 0 on the board (section 2.9).
    bool otc_tool(const BlockRef& at, int index) {
        const nc::ToolData* t = index > 0 ? tools_mut_.find(index) : nullptr;
        auto number = otc_object(otc::kDevTool, otc::kIdxToolNumber);
        auto typ = otc_object(otc::kDevTool, otc::kIdxToolType);
        auto wear = otc_object(otc::kDevTool, otc::kIdxToolWearConst);
        auto infeed = otc_object(otc::kDevTool, otc::kIdxToolMaxInfeed);
        auto tilt = otc_object(otc::kDevTool, otc::kIdxToolTiltAngle);
        return otc_write(number, std::int32_t{index}, at, "OTC ToolNumber") &&
               otc_write(typ, std::int32_t{t != nullptr ? t->typ : 0}, at, "OTC typ") &&
               otc_write(wear, t != nullptr ? t->grinding_wear_const : 0.0, at,
                         "OTC grinding_wear_const") &&
               otc_write(infeed, t != nullptr ? t->grinding_max_infeed : 0.0, at,
                         "OTC grinding_max_infeed") &&
               otc_write(tilt, t != nullptr ? t->grinding_disc_tilt_angle : 0.0, at,
                         "OTC grinding_disc_tilt_angle");
    }

    // [ISG-OTC] section 2.9: "Beim Auswechseln des Werkzeugs wird der externen
    // Werkzeugverwaltung der Verschleiß durch die CNC mitgeteilt" (wear_radius,
    // wear_radius_cont); the tool management folds it into the tool's geometry. The board has
    // folded it into its tool table at #OTC OFF: the tool list takes the board's radius and
    // length of the tool and adds the wear to its wear fields.
    void check_out_tool() {
        if (current_tool_ <= 0) return;
        nc::ToolData* t = tools_mut_.find_mutable(current_tool_);
        if (t == nullptr) return;
        auto wr = otc_object(otc::kDevTool, otc::kIdxWearRadius);
        auto wc = otc_object(otc::kDevTool, otc::kIdxWearRadiusCont);
        const auto radius_wear = board_.read_double(wr);
        const auto cont_wear = board_.read_double(wc);
        if (radius_wear && cont_wear) {
            t->set_wear_radius_mm(t->wear_radius_mm() + radius_wear.value - reported_radius_wear_);
            t->set_wear_radius_cont_mm(t->wear_radius_cont_mm() + cont_wear.value -
                                       reported_cont_wear_);
            reported_radius_wear_ = radius_wear.value;
            reported_cont_wear_ = cont_wear.value;
        }
        if (out_.tc_present) {
            auto r = group_object(1, tc::kSubRadius);
            auto l = group_object(1, tc::kSubWkzLen);
            const auto radius = board_.read_double(r);
            const auto length = board_.read_double(l);
            if (radius && length) {
                t->set_radius_mm(radius.value);
                t->set_length_mm(length.value);
            }
        }
    }

    // V.G.WZ_AKT.WEAR_CONST = value: the tool's wear constant, on the board and in the list.
    // $SC_TOOL_TEMP_COMP[i] = value: the setting datum on the board, after the moves before it
    // have run (the axes stop: it takes effect at its place in the program).
    bool variable_write(const BlockRef& at, const nc::VariableWrite& e) {
        if (e.variable.variable == nc::NcVariable::kToolTempComp) {
            const std::string what = nc::variable_name(e.variable);
            if (!temp_needed(at, what) || !run_clock()) return false;
            return temp_write(temp_object(tcomp::kIdxToolTempComp, e.variable.index), e.value, at,
                              what);
        }
        if (!otc_needed(at, "V.G.WZ_AKT.WEAR_CONST")) return false;
        auto o = otc_object(otc::kDevTool, otc::kIdxToolWearConst);
        if (!otc_write(o, e.value, at, "V.G.WZ_AKT.WEAR_CONST")) return false;
        if (nc::ToolData* t = current_tool_ > 0 ? tools_mut_.find_mutable(current_tool_) : nullptr)
            t->grinding_wear_const = e.value;
        return true;
    }

    // The board axis of channel axis i (0 X, 1 Y, 2 Z through Axis-Nr; the others as numbered).
    std::int32_t channel_axis(int i) const noexcept { return i < 3 ? axis(i) : i; }

    bool read_variable(const nc::VariableRef& v, double& out, std::string& why) {
        if (v.variable == nc::NcVariable::kToolTempComp) {
            if (!temp_present_) {
                why = "the board has no temperature compensation (bus 1320)";
                return false;
            }
            auto o = temp_object(tcomp::kIdxToolTempComp, v.index);
            const auto r = board_.read_double(o);
            if (!r) {
                why = std::string(board_.last_error());
                return false;
            }
            out = r.value;
            return true;
        }
        if (!out_.otc_present) {
            why = "the board has no OTC module (bus 1330)";
            return false;
        }
        ObjectDescriptor o{};
        bool is_int = false;
        switch (v.variable) {
            case nc::NcVariable::kWearRadius:
                o = otc_object(otc::kDevTool, otc::kIdxWearRadius);
                break;
            case nc::NcVariable::kWearRadiusCont:
                o = otc_object(otc::kDevTool, otc::kIdxWearRadiusCont);
                break;
            case nc::NcVariable::kWear:
                o = otc_object(otc::kDevTool, otc::kIdxWear, channel_axis(v.index));
                break;
            case nc::NcVariable::kWearConst:
                o = otc_object(otc::kDevTool, otc::kIdxToolWearConst);
                break;
            case nc::NcVariable::kOtcActive:
                o = otc_object(otc::kDevChannel, otc::kIdxActive);
                is_int = true;
                break;
            case nc::NcVariable::kToolTempComp:
                break;  // above
        }
        if (is_int) {
            const auto r = board_.read_int(o);
            if (!r) {
                why = std::string(board_.last_error());
                return false;
            }
            out = r.value;
            return true;
        }
        const auto r = board_.read_double(o);
        if (!r) {
            why = std::string(board_.last_error());
            return false;
        }
        out = r.value;
        return true;
    }

    // The variables at the end of the run, by their names in [ISG-OTC] (docs/design.md section 7 JSON).
    void read_variables() {
        auto add = [&](std::string name, nc::VariableRef v) {
            double value = 0.0;
            std::string why;
            if (read_variable(v, value, why)) out_.variables.emplace_back(std::move(name), value);
        };
        if (out_.otc_present) {
            add("V.G.OTC_ACTIVE", {nc::NcVariable::kOtcActive, 0});
            add("V.G.WZ_AKT.WEAR_CONST", {nc::NcVariable::kWearConst, 0});
            add("V.G.WZ_AKT.WEAR_RADIUS", {nc::NcVariable::kWearRadius, 0});
            add("V.G.WZ_AKT.WEAR_RADIUS_CONT", {nc::NcVariable::kWearRadiusCont, 0});
            for (int i = 0; i < APCI_AXIS_COUNT; ++i)
                add(fmt::format("V.G.WZ_AKT.WEAR[{}]", i), {nc::NcVariable::kWear, i});
        }
        for (int i = 0; i < nc::kToolTempCompCount; ++i) {
            const nc::VariableRef v{nc::NcVariable::kToolTempComp, i};
            add(nc::variable_name(v), v);
        }
    }

    // ---- temperature compensation (bus 1320; docs/temperature-compensation.md)

    // Only whether the board has it: its setting and machine data are the machine's, kept from
    // run to run as on a control (the PLC or the program writes the setting data).
    bool temp_setup() {
        auto on = temp_object(tcomp::kIdxToolTempCompOn);
        const auto r = board_.read_int(on);
        if (r.status == APCI_NO_SUCH_DEVICE) return true;
        if (!r) return board_failure({}, r.status, "read TOOL_TEMP_COMP_ON");
        temp_present_ = true;
        return true;
    }

    bool temp_needed(const BlockRef& at, std::string_view what) {
        if (temp_present_) return true;
        return record(at, "NoSuchDevice",
                      fmt::format("{} needs the temperature compensation (bus 1320, firmware "
                                  "option 0x04), which this board does not have",
                                  what));
    }

    template <typename T>
    bool temp_write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what) {
        const auto r = board_.write(o, value);
        if (r.ok()) return true;
        return board_failure(at, r.status, what);
    }

    // ---- the scripted PLC (apcictl run --plc)

    const std::uint64_t* next_plc_cycle() const noexcept {
        if (plc_ == nullptr || plc_next_cycle_ >= plc_->cycle_writes().size()) return nullptr;
        return &plc_->cycle_writes()[plc_next_cycle_].at;
    }

    // Writes every cycle entry whose cycle has come.
    bool plc_due() {
        while (const std::uint64_t* due = next_plc_cycle()) {
            if (*due > cycles_seen_ - start_cycle_) break;
            if (!plc_write(plc_->cycle_writes()[plc_next_cycle_++])) return false;
        }
        return true;
    }

    // After the program: the clock runs on to the remaining cycle entries.
    bool plc_after_end() {
        while (const std::uint64_t* due = next_plc_cycle()) {
            const std::uint64_t now = cycles_seen_ - start_cycle_;
            if (*due > now && !step_clock(*due - now)) return false;
            if (!plc_due()) return false;
        }
        return true;
    }

    // The first event of a block: its block entries, after the moves before it have run.
    bool plc_block(const nc::BlockOrigin& o) {
        if (plc_ == nullptr || plc_->block_writes().empty()) return true;
        if (o.block == plc_last_block_ && o.line == plc_last_line_) return true;
        plc_last_block_ = o.block;
        plc_last_line_ = o.line;
        if (o.block < 0) return true;
        bool synced = false;
        for (const PlcWrite& w : plc_->block_writes()) {
            if (w.at != static_cast<std::uint64_t>(o.block)) continue;
            if (!synced && !run_clock()) return false;
            synced = true;
            if (!plc_write(w)) return false;
        }
        return true;
    }

    bool plc_write(const PlcWrite& w) {
        const BlockRef at = w.when == PlcWrite::When::kBlock
                                ? BlockRef{static_cast<std::int64_t>(w.at), 0}
                                : BlockRef{};
        const std::string what =
            fmt::format("{}:{}: PLC {} = {}", plc_->file(), w.line, plc_unit_name(w), w.value);
        switch (w.unit) {
            case PlcWrite::Unit::kToolTempComp:
                return temp_needed(at, what) &&
                       temp_write(temp_object(tcomp::kIdxToolTempComp, w.index), w.value, at, what);
            case PlcWrite::Unit::kToolTempCompOn:
                return temp_needed(at, what) &&
                       temp_write(temp_object(tcomp::kIdxToolTempCompOn),
                                  static_cast<std::int32_t>(w.value), at, what);
            case PlcWrite::Unit::kTempCompType:
                return temp_needed(at, what) &&
                       temp_write(temp_object(tcomp::kIdxTempCompType, channel_axis(w.index)),
                                  static_cast<std::int32_t>(w.value), at, what);
            case PlcWrite::Unit::kToolHolder:
            case PlcWrite::Unit::kToolHolderAxisB:
            case PlcWrite::Unit::kToolHolderAxisC: {
                const std::int32_t index =
                    w.unit == PlcWrite::Unit::kToolHolder        ? tcomp::kIdxToolHolder
                    : w.unit == PlcWrite::Unit::kToolHolderAxisB ? tcomp::kIdxHeadAxisB
                                                                 : tcomp::kIdxHeadAxisC;
                return temp_needed(at, what) &&
                       temp_write(temp_object(index), static_cast<std::int32_t>(w.value), at, what);
            }
            case PlcWrite::Unit::kTempRampVelocity:
                return temp_needed(at, what) &&
                       temp_write(temp_object(tcomp::kIdxRampVelocity), w.value, at, what);
            case PlcWrite::Unit::kOtcRadiusOffset:
            case PlcWrite::Unit::kOtcOffset:
                break;
        }
        if (!otc_needed(at, what)) return false;
        const std::int32_t sub = w.field == PlcWrite::Field::kCommand ? otc::kSubCommand : otc::kSubEnable;
        auto o = w.unit == PlcWrite::Unit::kOtcRadiusOffset
                     ? otc_object(otc::kDevChannel, otc::kIdxRadiusOffsetUnit, sub)
                     : otc_object(otc::kDevAxisUnits, channel_axis(w.index), sub);
        return otc_write(o, static_cast<std::int32_t>(w.value), at, what);
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

    // Self-approach findings (self_approach.h): warnings, or with --self-approach=error the
    // first one is the run's error (the run stops).
    bool take_findings() {
        for (const SelfApproachFinding& f : findings_) {
            if (self_approach_mode_ == SelfApproachMode::kError) {
                findings_.clear();
                return record(f.path_block, "SelfApproach", describe(f));
            }
            out_.warnings.push_back(RunError{f.path_block, "SelfApproach", describe(f)});
            sink_.warning(out_.warnings.back(), f.where);
        }
        findings_.clear();
        return true;
    }

    // Records an error; returns false (the run stops).
    bool record(BlockRef at, std::string code, std::string message) {
        // A board error names the block by its tag (its N); the line comes from the spooled move.
        if (at.line == 0 && at.number != kNoBlock)
            if (const PathSegment* s = recent_.find(encode_block_tag(at))) at.line = s->block.line;
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
            if (!plc_due()) return false;
            std::uint64_t chunk = tracing_ ? ProgramExecutor::kTraceChunk : kRunForever;
            if (const std::uint64_t* due = next_plc_cycle())
                chunk = std::min(chunk, *due - (cycles_seen_ - start_cycle_));
            const auto st = board_.run_until_idle(chunk);
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
            if ((st.value.flags & APCI_MOTION_IDLE) != 0) return plc_due();
        }
    }

    // Steps the clock by exactly `cycles` (idle cycles included), reading what it produced.
    bool step_clock(std::uint64_t cycles) {
        while (cycles > 0) {
            const std::uint64_t chunk =
                tracing_ ? std::min<std::uint64_t>(cycles, ProgramExecutor::kTraceChunk) : cycles;
            const auto st = board_.step(chunk);
            if (!st) return board_failure({}, st.status, "step clock");
            cycles_seen_ = st.value.now;
            cycles -= chunk;
            if (!drain_segments(st.value.segments_pending) ||
                (tracing_ && !drain_samples(st.value.trace_pending)))
                return false;
        }
        return true;
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
                if (self_approach_mode_ != SelfApproachMode::kOff) {
                    self_approach_.executed(s, findings_);
                    if (!take_findings()) return false;
                }
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
    // compensation taken off (the tool centre point, docs/design.md section 7).
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
        if (trafo_) {
            // Back to the tool tip, at the B each end has (a B that turns along a line moves the
            // pivot linearly, so the tip is exact at the ends).
            const double b0 = b.start[head_b_axis_], b1 = b.end[head_b_axis_];
            s.start -= trafo_length_ * tool_axis(b0);
            s.end -= trafo_length_ * tool_axis(b1);
            s.center -= trafo_length_ * tool_axis(b0);
        }
        const int z = plane_axes(comp_plane_).third;
        const double end_offset = ends_length_compensated(s.role) ? length_ : 0.0;
        s.start[z] -= start_offset_;
        s.center[z] -= start_offset_;
        s.end[z] -= end_offset;
        start_offset_ = end_offset;
        // A line the 3D module compensated is a contour element (the board's spooler, which
        // knows only the TC module, calls it uncompensated; the TC's length compensation did
        // not act on it, as the offsets above say).
        if (s.role == Role::kUncompensated && b.role != APCI_ROLE_RAPID) {
            const auto it = c3_pending_.find(b.tag);
            if (it != c3_pending_.end()) {
                s.role = Role::kContour;
                if (--it->second == 0) c3_pending_.erase(it);
            }
        }
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
    double length_ = 0.0;  // WkzLen of the current tool
    double radius_ = 0.0;  // RADIUS of the current tool
    // Klartext (3D compensation module, bus 1310).
    // ---- OTC (bus 1330; docs/otc.md, docs/apcictl.md "run")
    const nc::CorrectionTable* corrections_;  // --corr, may be null
    const PlcScript* plc_;
    std::size_t plc_next_cycle_ = 0;  // next entry of plc_->cycle_writes()
    std::int64_t plc_last_block_ = std::numeric_limits<std::int64_t>::min();
    std::uint64_t plc_last_line_ = 0;
    nc::ToolTable tools_mut_;  // the tool list as the run changes it (wear at tool change)
    int current_tool_ = 0;
    double reported_radius_wear_ = 0.0;  // the board's wear variables already in the list
    double reported_cont_wear_ = 0.0;
    bool temp_present_ = false;  // the board has the temperature compensation (bus 1320)

    class BoardVariables final : public nc::VariableSource {
      public:
        explicit BoardVariables(Execution& e) : e_(e) {}
        bool read(const nc::VariableRef& v, double& out, std::string& why) override {
            return e_.read_variable(v, out, why);
        }

      private:
        Execution& e_;
    };
    BoardVariables variables_;

    bool trafo_ = false;          // #TRAFO ON: programs give the tool tip
    double trafo_length_ = 0.0;   // the tool length it uses (mm)
    double b_now_ = 0.0;          // the B the spooled moves end at

    bool klartext_ = false;
    bool c3_ready_ = false;
    bool tcpm_ = false;
    nc::Compensation side_ = nc::Compensation::kOff;
    std::int32_t head_b_axis_ = 4;
    std::int32_t head_c_axis_ = 5;
    bool head_pending_ = false;
    std::unordered_map<std::uint32_t, std::uint32_t> c3_pending_;  // 3D lines not yet read back
    BlockRef head_at_{};
    double head_b_ = 0.0;
    double head_c_ = 0.0;
    double start_offset_ = 0.0;  // length compensation at the end of the last segment read
    RecentMoves recent_;
    std::vector<apci_segment> segments_;
    std::vector<apci_trace_sample> samples_;
    SelfApproachMode self_approach_mode_;
    SelfApproachCheck self_approach_;
    std::vector<SelfApproachFinding> findings_;
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
    auto execution =
        std::make_unique<Execution>(board_, sink_, tools_, plc_, corrections_, self_approach_);
    return execution->run(events);
}

}  // namespace apci::run
