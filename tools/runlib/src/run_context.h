// SPDX-License-Identifier: MIT
// The executor's shared context and core (executor.h; the units' interface is module_unit.h):
// one run of a program against a board. The core sets the board up and finishes the run
// (executor.cpp), dispatches each event to the unit of its module (RunContext::dispatch, the one
// table), and spools moves and arcs, reaches the board, runs the clock, reads the trace and the
// executed segments back, records errors and gives the compensated stretches to the sink
// (run_context.cpp). (The name says what it is: the context of one run, apart from the host's
// ProgramExecutor that makes it and the board's rwmos::motion::Executor.) The
// units: TC (tc_unit.cpp), OTC (otc_unit.cpp), Klartext 3D (comp3d_unit.cpp), temperature
// (temp_unit.cpp), the scripted PLC (plc_unit.cpp), the NC variables (variables_unit.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "apci/apci.hpp"
#include "apci/nc/events.h"
#include "apci/run/board_words.h"
#include "apci/run/executor.h"
#include "objif/map/limits.h"
#include "apci/run/self_approach.h"
#include "bottleneck.h"
#include "comp3d_unit.h"
#include "otc_unit.h"
#include "plc_unit.h"
#include "tc_unit.h"
#include "temp_unit.h"
#include "variables_unit.h"

namespace apci::run::exec {

// Feed of a rapid that must be compensated (a G0 under G41/G42, an LN with FMAX): spooled as a
// G01 at the board's rapid feed (docs/motion.md: 60000 units/min).
inline constexpr double kRapidFeed = objif::map::kRapidFeed;

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

// The head: its B (and, in Klartext, C) axis, and #TRAFO's tool-tip transformation of the B
// head (docs/design.md section 8; docs/otc.md). The axes are placed once, at setup, on the
// first two board axes that are not X, Y or Z (-1: none free); the OTC module's B (#KIN) and
// the 3D module's B and C are these.
struct HeadState {
    bool trafo = false;         // #TRAFO ON: programs give the tool tip
    double trafo_length = 0.0;  // the tool length it uses (mm)
    double b_now = 0.0;         // the B the spooled moves end at
    std::int32_t b_axis = -1;
    std::int32_t c_axis = -1;
    bool pending = false;  // a B/C programmed and not yet spooled with a move
    BlockRef at{};
    double b = 0.0;
    double c = 0.0;
};

// The board's CalcError compares an arc's radius with the tool's on the arc's concave side
// ([APCI-TC] Table 4): where the programmed move `s` is such an arc under the compensation
// `tc`, smaller than the tool, both radii, so that the user sees by how much ("; arc radius
// 4.0000 mm, tool radius 5.0000 mm"; a spiral's "4.0000 to 4.0010 mm"); else "".
std::string concave_arc_radii(const PathSegment& s, const TcUnit::State& tc);

class RunContext {
  public:
    RunContext(apci::Board& board, RunSink& sink, const nc::ToolTable* tools, const PlcScript* plc,
              const nc::CorrectionTable* corrections, int bottleneck_blocks,
              std::string lost_link_hint);

    // With `read_ahead` the stream is read through a ReadAhead (read_ahead.h), its reader
    // placed by `cpus`, `where` and `follows` (ProgramExecutor::set_read_ahead).
    RunOutcome run(nc::EventStream& events, bool read_ahead, const CpuPlacement* cpus,
                   HelperCpu where, const RingFill* follows);

    // ---- what the units reach through the context

    apci::Board& board() noexcept { return board_; }
    // libapci's words for the board's last call, a lost link's with the run's hint
    // (RunSettings::lost_link_hint).
    std::string board_words() const { return apci::run::board_words(board_, lost_link_hint_); }
    // How a run names a board call that failed: "WHAT: " and board_words().
    std::string failure_words(std::string_view what) const;
    const nc::ToolTable* tools() const noexcept { return tools_; }
    TcUnit& tc_unit() noexcept { return tc_; }
    OtcUnit& otc_unit() noexcept { return otc_; }
    TempUnit& temp_unit() noexcept { return temp_; }

    std::int32_t axis(int program_axis) const noexcept {
        return axes_[static_cast<std::size_t>(program_axis)];
    }
    // The board axis of channel axis i (0 X, 1 Y, 2 Z through Axis-Nr; the others as numbered).
    std::int32_t channel_axis(int i) const noexcept { return i < 3 ? axis(i) : i; }
    std::uint64_t cycles_seen() const noexcept { return cycles_seen_; }
    // Cycles since the run's start.
    std::uint64_t cycles_run() const noexcept { return cycles_seen_ - start_cycle_; }

    template <typename T>
    bool write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what);
    bool board_failure(const BlockRef& at, apci::Status status, std::string_view what);
    bool no_module(const BlockRef& at, std::string_view what, std::string_view module);
    bool record(BlockRef at, std::string code, std::string message);
    bool run_clock();
    bool step_clock(std::uint64_t cycles);

    static PathSegment line_segment(const BlockRef& at, SegmentKind kind,
                                    const Eigen::Vector3d& start, const Eigen::Vector3d& end);
    apci_profile profile(const BlockRef& at, std::uint8_t kind, const Eigen::Vector3d& end,
                         double feed) noexcept;
    void add_head(apci_profile& p) noexcept;
    // A B (C) word: the head turns with the block's move (DIN: a B word; Klartext: L .. B C).
    bool head_turn(const BlockRef& at, const nc::HeadOrientation& e);
    // A programmed move on its way to the board: to the sink, and to the recent moves.
    void programmed(const PathSegment& s, std::uint32_t tag);
    bool spool_profile(const apci_profile& p, apci::Result<apci_motion_result>& r);
    // The compensated stretch (RunSink::stretch_begin, stretch_end), from G41/G42 to G40
    // (TcUnit). end_stretch: false when a sink stopped the run.
    void begin_stretch(const CompensatedStretch& s);
    bool end_stretch();
    // The sink's error that stops the run (RunSink::take_stop), recorded; false when there
    // was one.
    bool sink_lets_go_on();
    // CDON / CDOF: whether the moves programmed from now on are walls for the check.
    void walls_on(bool on);

    // ---- what the run keeps for all units (each module's own state is its unit's: TcUnit's
    // TcUnit::State, ...)
    // The run's record: errors, notices, registers, variables (every unit adds its own).
    RunOutcome& outcome() noexcept { return out_; }
    // The tool list as the run changes it (the OTC module folds the wear in at tool change).
    nc::ToolTable& tool_list() noexcept { return tools_mut_; }
    // The head's axes and #TRAFO (set by the executor at setup and by #TRAFO and B/C words).
    const HeadState& head() const noexcept { return head_; }
    // The programmed B/C went to the board with a move (the 3D module spooled it).
    void head_spooled() noexcept { head_.pending = false; }

  private:
    // The run, reading `events`: an nc::EventStream or a ReadAhead over one.
    template <typename Events>
    RunOutcome run_events(Events& events);
    template <typename Events>
    void draw_rest(Events& events);
    bool setup();
    bool discard_earlier_moves(apci_motion_status& st);
    bool read_axis_numbers();
    void finish();
    bool dispatch(const nc::Event& ev);
    bool end_of_program(const BlockRef& at);
    void place_head() noexcept;
    bool head_only_move(const BlockRef& at);
    bool trafo(const BlockRef& at, const nc::TrafoChange& e);

    static PathSegment arc_segment(const BlockRef& at, const nc::ArcMove& a);
    bool move(const BlockRef& at, const Eigen::Vector3d& start, const Eigen::Vector3d& end,
              std::uint8_t kind, double feed);
    bool arc(const BlockRef& at, const nc::ArcMove& a);
    Eigen::Vector3d pivot_of(const Eigen::Vector3d& tip, double b_deg) const noexcept;
    bool spool(const BlockRef& at, const PathSegment& programmed, const apci_profile& p);

    bool write_failure(const BlockRef& at, apci::Status status, std::string_view what);
    bool tc_errors(const BlockRef& at, std::int32_t bits, const std::string& text);
    void program_error(const nc::Diagnostic& d);
    void report_bottleneck(const detail::Bottleneck& b);
    Point where(const BlockRef& at);
    bool make_room();
    bool run_clock_until_idle();
    bool clocked(const apci::Result<apci_motion_status>& st, std::string_view what);
    bool drain_segments(std::uint64_t pending);
    // Reads `pending` segments and drops them (logged before the run: not its own).
    bool drop_segments(std::uint64_t pending);
    bool drain_samples(std::uint64_t pending);
    template <class Item, class Read, class Each>
    bool drain(std::uint64_t pending, std::vector<Item>& buffer, std::string_view what, Read read,
               Each each);
    PathSegment convert(const apci_segment& b);
    void arc_plane(const apci_segment& b, PathSegment& s) const noexcept;

    RunOutcome out_;
    std::array<int, 3> axes_{0, 1, 2};
    nc::ToolTable tools_mut_;
    HeadState head_;
    apci::Board& board_;
    RunSink& sink_;
    const nc::ToolTable* tools_;
    int bottleneck_blocks_ = 0;  // 0: no bottleneck avoidance (bottleneck.h)
    std::string lost_link_hint_;
    std::int32_t cycle_us_ = 1000;
    bool tracing_ = false;
    bool set_up_ = false;   // setup() succeeded: the board was configured for the run
    bool clock_ok_ = true;  // no clock call failed
    bool klartext_ = false;
    bool sink_measures_ = false;  // the sink measures the executed segments (measures_executed)
    std::uint64_t start_cycle_ = 0;
    std::uint64_t cycles_seen_ = 0;
    // The end cycle of the last executed segment given to the sink, and, once the sink stopped
    // the run (sink_lets_go_on), that cycle: the outputs and the time end there, though the
    // board ran on with what was spooled (the embedded emulator's own dry run).
    std::uint64_t given_end_cycle_ = 0;
    std::optional<std::uint64_t> stop_cycle_;
    std::uint64_t segments_lost_ = 0;
    std::uint64_t trace_lost_ = 0;
    // #TRAFO switched the frame the host reads the axes in: the standing point's tool tip is
    // read in the new one, so the first segment after the switch starts with this length on
    // the program axes instead of the board's (ON: none, the transformation alone; OFF: the
    // length LengthMode 1 adds from there on). Empty otherwise.
    std::optional<Eigen::Vector3d> switch_start_length_;
    RecentMoves recent_;
    std::vector<apci_segment> segments_;
    std::vector<apci_trace_sample> samples_;

    // The units, one per module.
    TcUnit tc_;
    OtcUnit otc_;
    Comp3dUnit c3_;
    TempUnit temp_;
    PlcUnit plc_;
    VariablesUnit variables_;
};

}  // namespace apci::run::exec
