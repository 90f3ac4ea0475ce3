// SPDX-License-Identifier: MIT
// The executor (executor.h): one run of a program against a board, its setup and finish, and the
// dispatch of each event to the unit of its module (run_context.h, module_unit.h).
#include "apci/run/executor.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <type_traits>
#include <variant>

#include "apci/run/csv_writer.h"
#include "apci/run/read_ahead.h"
#include "apci/run/self_approach.h"
#include "bottleneck.h"
#include "objif/map/object_map.h"
#include "run_context.h"

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

namespace exec {

namespace {

namespace tc = objif::map::tc;
namespace bm = objif::map::board;
namespace c3 = objif::map::comp3d;
namespace otc = objif::map::otc;

BlockRef block_of(const nc::BlockOrigin& o) noexcept {
    return BlockRef{o.block == nc::kNoBlockNumber ? kNoBlock : o.block, o.line};
}

}  // namespace

RunContext::RunContext(apci::Board& board, RunSink& sink, const nc::ToolTable* tools,
                       const PlcScript* plc, const nc::CorrectionTable* corrections,
                       int bottleneck_blocks, std::string lost_link_hint)
    : board_(board),
      sink_(sink),
      tools_(tools),
      bottleneck_blocks_(bottleneck_blocks),
      lost_link_hint_(std::move(lost_link_hint)),
      tc_(*this),
      otc_(*this),
      c3_(*this, corrections),
      temp_(*this),
      plc_(*this, plc),
      variables_(*this) {
    segments_.resize(ProgramExecutor::kReadBatch);
    samples_.resize(ProgramExecutor::kReadBatch);
    if (tools_ != nullptr) tools_mut_ = *tools_;
}

namespace {

// The reader of a ReadAhead ends before the run finishes; a stream read directly has nothing
// to end.
void stop_reading(ReadAhead& events) noexcept {
    events.stop();
}
void stop_reading(nc::EventStream& events) noexcept {
    (void)events;
}

}  // namespace

RunOutcome RunContext::run(nc::EventStream& events, bool read_ahead, const CpuPlacement* cpus,
                           HelperCpu where, const RingFill* follows) {
    if (!read_ahead) return run_events(events);
    ReadAhead ahead(events, cpus, where, follows);  // stopped and joined on every path out
    return run_events(ahead);
}

namespace {

// The next event: read into `storage`, or (read ahead) where it waits in the ring.
nc::EventStream::Next next_event(nc::EventStream& events, nc::Event& storage,
                                 const nc::Event*& event) {
    event = &storage;
    return events.next(storage);
}
nc::EventStream::Next next_event(ReadAhead& events, nc::Event& /*storage*/,
                                 const nc::Event*& event) {
    return events.next(event);
}

// Read ahead, the reader starts before the run is set up (the board asked, the outputs' first
// lines written), and reads meanwhile; a stream read here waits for its first next().
void begin_reading(nc::EventStream& /*events*/) {}
void begin_reading(ReadAhead& events) {
    events.begin();
}

}  // namespace

template <typename Events>
RunOutcome RunContext::run_events(Events& events) {
    // The program reads the board's V.G. variables ([ISG-OTC] section 2.8).
    events.set_variable_source(&variables_);
    begin_reading(events);
    sink_measures_ = sink_.measures_executed();
    set_up_ = setup();
    if (set_up_) {
        nc::Event storage;
        std::uint64_t count = 0;
        // Bottleneck avoidance (bottleneck.h) between the program and the units: the events as
        // it gives them on, after it held those of the moves it compares.
        std::optional<detail::BottleneckAvoider> avoider;
        if (bottleneck_blocks_ > 0) avoider.emplace(bottleneck_blocks_);
        std::vector<nc::Event> given;
        std::vector<detail::Bottleneck> avoided;
        bool stopped = false;
        const auto dispatch_given = [&]() {
            for (const detail::Bottleneck& b : avoided) report_bottleneck(b);
            avoided.clear();
            for (const nc::Event& e : given)
                if (!stopped && !dispatch(e)) stopped = true;
            given.clear();
            return !stopped;
        };
        for (;;) {
            const nc::Event* event = nullptr;
            const auto next = next_event(events, storage, event);
            if (next == nc::EventStream::Next::kEnd) {
                if (avoider) {
                    avoider->flush(given);
                    (void)dispatch_given();
                }
                break;
            }
            if (next == nc::EventStream::Next::kError) {
                if (avoider) {
                    avoider->flush(given);
                    (void)dispatch_given();
                }
                program_error(events.error());
                break;
            }
            out_.totals.blocks_executed = events.blocks_read();
            klartext_ = events.dialect() == nc::Dialect::kKlartext;
            bool ok = true;
            if (avoider) {
                avoider->take(*event, tc_.state().radius, tc_.state().plane, given, avoided);
                ok = dispatch_given();
            } else {
                ok = dispatch(*event);
            }
            if (!ok) {
                draw_rest(events);
                break;
            }
            if (++count % ProgramExecutor::kProgressEvery == 0)
                sink_.progress(events.blocks_read(), events.offset());
        }
    }
    stop_reading(events);
    finish();
    // The variables unit ends with this run; a caller that reads on (nc::SinglePass::finish)
    // reads with the front end's own view.
    events.set_variable_source(nullptr);
    if (sink_measures_) sink_.measured_lengths(out_.totals.path_length, out_.totals.rapid_length);
    return std::move(out_);
}

// A bottleneck avoided: a warning naming the blocks left out and where the paths cross.
void RunContext::report_bottleneck(const detail::Bottleneck& b) {
    const auto name = [](const nc::BlockOrigin& o) {
        return o.block >= 0 ? fmt::format("N{}", o.block) : fmt::format("line {}", o.line);
    };
    const int comp_plane = tc_.state().comp_plane;
    const PlaneAxes a = plane_axes(comp_plane);
    const std::string left_out =
        b.first.line == b.last.line ? name(b.first) : name(b.first) + " to " + name(b.last);
    RunError w{block_of(b.first), "Bottleneck",
               fmt::format("{} left out: the tool paths of {} and {} cross at ({:.4f}, {:.4f}) "
                           "in the {} plane, and the tool goes from the one to the other there "
                           "(--avoid-bottlenecks {}, as SINUMERIK's CDON)",
                           left_out, name(b.before), name(b.after), b.where[a.first],
                           b.where[a.second], plane_name(comp_plane), bottleneck_blocks_)};
    out_.warnings.push_back(w);
    sink_.warning(out_.warnings.back(), b.where);
}

// After an error the rest of the program still goes to a plot, so the place of the error
// is seen in its contour; nothing more goes to the board.
template <typename Events>
void RunContext::draw_rest(Events& events) {
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

bool RunContext::setup() {
    for (std::size_t i = 0; i < out_.axis_names.size(); ++i)
        out_.axis_names[i] = "a" + std::to_string(i);
    auto st = board_.motion_status();
    if (!st) return board_failure({}, st.status, "motion status");
    if (st.value.fill > 0 && !discard_earlier_moves(st.value)) return false;
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
    place_head();
    for (std::size_t i = 0; i < out_.axis_names.size(); ++i)
        out_.axis_names[i] = axis_column_name(static_cast<int>(i));
    if (out_.tc_present && !tc_.setup()) return false;
    if (!otc_.setup()) return false;
    if (!temp_.setup()) return false;

    sink_.axes(out_.axis_names);
    sink_.axis_numbers(axes_);
    if (sink_.wants_samples()) {
        const auto r = board_.trace_enable(2 * ProgramExecutor::kTraceChunk);
        if (!r) return board_failure({}, r.status, "trace on");
        tracing_ = true;
    }
    return true;
}

// Moves in the spooler before the run are an earlier program's, and would run as this one's
// (under its block numbers) once its clock runs. Held after a compensation error (that program
// stopped there and the board never ran them), they are discarded as a reset discards them,
// by a direct command (JS: the spooler and the held profile are dropped, [APCI-TC] section 1),
// with a notice; the segments the board logged before are not this run's either and are read
// and dropped. Not held, they are another program's that has not run them yet: the run is
// refused before anything changes (docs/apcictl.md, "Run"). `st`, the status that found them,
// is the status after the discard on return.
bool RunContext::discard_earlier_moves(apci_motion_status& st) {
    const bool one = st.fill == 1;
    const std::string moves = fmt::format("{} move{}", st.fill, one ? "" : "s");
    const char* const its = one ? "its" : "their";
    const char* const them = one ? "it" : "them";
    if ((st.flags & APCI_MOTION_HELD) == 0)
        return record({}, "SpoolerInUse",
                      fmt::format("the board's spooler holds {0} that another program spooled "
                                  "and the board has not run to {1} end: {2} would run as this "
                                  "program's. Let {3} run to {1} end (apcictl step) or discard "
                                  "{3} (apcictl direct js), then run again; nothing was moved",
                                  moves, its, one ? "it" : "they", them));
    apci_direct_command js{};
    js.code = APCI_DIRECT_JS;
    if (const auto r = board_.direct(js); !r)
        return board_failure({}, r.status, "discard the earlier program's moves (JS)");
    const auto after = board_.motion_status();
    if (!after) return board_failure({}, after.status, "motion status");
    st = after.value;
    if (!drop_segments(st.segments_pending)) return false;
    out_.notices.push_back(RunError{
        {}, "Discarded",
        fmt::format("the board's spooler held {} of an earlier program that stopped at a "
                    "compensation error: discarded before this run, as a reset discards {} (the "
                    "axes stay where they stood)",
                    moves, them)});
    return true;
}

// X/Y/Z-Axis-Nr; their absence (NoSuchDevice) means the firmware has no optionTC.
bool RunContext::read_axis_numbers() {
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

// The head's B and C on the first two board axes that are not X, Y or Z (4 and 5 by default).
void RunContext::place_head() noexcept {
    std::array<bool, APCI_AXIS_COUNT> used{};
    for (const int a : axes_) used[static_cast<std::size_t>(a)] = true;
    std::array<std::int32_t, 2> found{-1, -1};
    std::size_t n = 0;
    for (std::int32_t a : {4, 5, 6, 7, 3})
        if (n < found.size() && !used[static_cast<std::size_t>(a)]) found[n++] = a;
    head_.b_axis = found[0];
    head_.c_axis = found[1];
}

void RunContext::finish() {
    // The move under way ends (after a TC error the board holds the rest). A clock that
    // failed already is not asked again; its error is recorded.
    // A link to the board that was lost (a daemon that stopped, a board unplugged) is not
    // asked again: every call would fail as the one that found it, and the run has that error.
    const bool linked = board_.connected();
    if (set_up_ && clock_ok_ && linked) (void)run_clock();
    // PLC writes due after the program's last move: the clock runs on to them.
    if (set_up_ && clock_ok_ && linked && out_.errors.empty()) (void)plc_.after_end();
    if (set_up_ && linked && out_.otc_present) otc_.check_out_tool();
    if (set_up_ && linked) variables_.read_all();
    out_.tools_after = tools_mut_;
    if (out_.tc_present && linked) tc_.read_registers();
    out_.totals.cycles = stop_cycle_.value_or(cycles_seen_) - start_cycle_;
    if (!tc_.state().comp_plane_seen) out_.plot_plane = tc_.state().plane;
}

// ---- events: the one table of which unit handles which event

bool RunContext::dispatch(const nc::Event& ev) {
    const BlockRef at = block_of(ev.origin);
    // The head's rotary axes go with the block's move; a block that turns the head only
    // gets a move of its own.
    const bool is_move = std::holds_alternative<nc::RapidMove>(ev.data) ||
                         std::holds_alternative<nc::LineMove>(ev.data) ||
                         std::holds_alternative<nc::VectorLineMove>(ev.data);
    if (head_.pending && !is_move && !head_only_move(head_.at)) return false;
    if (!plc_.block(ev.origin)) return false;
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
                return tc_.tool(at, e.tool);
            } else if constexpr (std::is_same_v<E, nc::CompensationChange>) {
                return klartext_ ? c3_.compensation(at, e.side) : tc_.compensation(at, e.side);
            } else if constexpr (std::is_same_v<E, nc::CornerModeChange>) {
                return tc_.corner(at, e.mode);
            } else if constexpr (std::is_same_v<E, nc::CollisionDetectionChange>) {
                walls_on(e.on);
                return true;
            } else if constexpr (std::is_same_v<E, nc::SelectionModeChange>) {
                return tc_.selection(at, e.mode);
            } else if constexpr (std::is_same_v<E, nc::PlaneChange>) {
                return tc_.plane(at, e.plane);
            } else if constexpr (std::is_same_v<E, nc::ProgramEnd>) {
                return end_of_program(at);
            } else if constexpr (std::is_same_v<E, nc::ToolCallDeltas>) {
                return c3_.tool_call(at, e);
            } else if constexpr (std::is_same_v<E, nc::TcpmChange>) {
                return c3_.tcpm(at, e);
            } else if constexpr (std::is_same_v<E, nc::ProgPathChange>) {
                return c3_.setting(at, c3::kIdxProgPath, e.contour ? 1 : 0, "ProgPath");
            } else if constexpr (std::is_same_v<E, nc::OversizeChange>) {
                return c3_.setting(at, c3::kIdxAllowOversize, e.allowed ? 1 : 0, "AllowOversize");
            } else if constexpr (std::is_same_v<E, nc::HeadOrientation>) {
                // DIN's B is the B head's (#KIN, docs/design.md section 8); Klartext's B and C
                // are the 3D module's head_.
                return klartext_ ? c3_.head(at, e) : head_turn(at, e);
            } else if constexpr (std::is_same_v<E, nc::OtcChange>) {
                return otc_.command(at, e.command);
            } else if constexpr (std::is_same_v<E, nc::KinematicsSelect>) {
                return otc_.setting(at, otc::kIdxKinematics, e.id, "#KIN (Kinematics)");
            } else if constexpr (std::is_same_v<E, nc::TrafoChange>) {
                return trafo(at, e);
            } else if constexpr (std::is_same_v<E, nc::NotEmulated>) {
                out_.notices.push_back(RunError{
                    at, "NotEmulated",
                    fmt::format("{} is accepted and not emulated (docs/design.md section 8)",
                                e.command)});
                return true;
            } else if constexpr (std::is_same_v<E, nc::VariableWrite>) {
                return variables_.write(at, e);
            } else if constexpr (std::is_same_v<E, nc::CorrectionSelect>) {
                return c3_.setting(at, c3::kIdxCorrectionRow, e.row,
                                   "FUNCTION CORRDATA (CorrectionRow)");
            } else {
                static_assert(std::is_same_v<E, nc::VectorLineMove>);
                return c3_.vector_line(at, e);
            }
        },
        ev.data);
}

bool RunContext::end_of_program(const BlockRef& at) {
    if (tc_.state().comp_on) {
        // The board ends the compensation at M30 (STATUS = 0): under G139 the tool stays at the
        // last compensated point, under G237 it departs at right angles. Said, as controls do.
        out_.notices.push_back(RunError{
            at, "CompensationOnAtEnd",
            "the program ends with radius compensation still on: M30 switches it off where the "
            "tool stands (program G40 with a move to leave the contour)"});
        if (!tc_.compensation_off(at)) return false;
    }
    return run_clock();
}

}  // namespace exec

double ProgramExecutor::cycle_seconds() {
    auto cycle = apci::object(objif::map::board::kBus, objif::map::board::kDevice,
                              objif::map::board::kIdxInterpolationCycle, 0);
    const auto us = board_.read_int(cycle);
    if (!us || us.value <= 0) return nc::kDefaultCycleSeconds;
    return static_cast<double>(us.value) * 1e-6;
}

nc::InterpreterOptions ProgramExecutor::interpreter_options() {
    nc::InterpreterOptions options;
    options.start_position = position();
    options.cycle_seconds = cycle_seconds();
    options.tools = tools_;
    options.corrections = corrections_;
    return options;
}

Point ProgramExecutor::position() {
    std::array<int, 3> axes{0, 1, 2};
    for (int i = 0; i < 3; ++i) {
        auto o = exec::init_object(objif::map::tc::kIdxAxisNr, i);
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
    auto context = std::make_unique<exec::RunContext>(board_, sink_, tools_, plc_, corrections_,
                                                      bottleneck_blocks_, lost_link_hint_);
    return context->run(events, read_ahead_, read_ahead_cpus_, read_ahead_where_,
                        read_ahead_follows_);
}

}  // namespace apci::run
