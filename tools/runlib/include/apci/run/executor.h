// SPDX-License-Identifier: MIT
// The executor behind `apcictl run`: a PCAP application that drives a board through libapci's
// public API (apci.hpp) from an NC program's events (apci_nc), and reads back what the board
// executed. docs/apcictl.md ("run") states every mapping; in short:
//
//   start     RESET the TC groups; group 1 in X-Y, 2 in Z-X, 3 in Y-Z (XAxis, YAxis, ZAxis
//             from the board's X/Y/Z-Axis-Nr), so TcPlane picks the group (Index 0)
//   D n       WKZINDEX n, RADIUS and WkzLen of wz[n] (mm), in every group; waits until the
//             axes stop first (a tool change)
//   G17..G19  TcPlane (waits until the axes stop)
//   G25/G26   CornerMode of every group
//   G41/G42   Left/Right then STATUS = 1 on the active group (STATUS = 0 first when switching
//             sides); G40: STATUS = 0 (the held profile is spooled with the departure)
//   G0..G3    a spooled profile tagged with the block number; Busy: run the clock, retry
//   M30       STATUS = 0 if compensation is still on, then run until idle
//   #OTC      the OTC module (bus 1330): type, mode, WEAR_CONST, ACC_WEIGHT, then Active (Busy
//             until the moves before it have run); #KIN/#TRAFO its Kinematics/Trafo; D n also
//             the tool's grinding data (typ, P-TOOL-00030/31/138) after checking the old tool's
//             wear into the tool list ([ISG-OTC] section 2.9); V.G. variables read from it
//   $SC_TOOL_TEMP_COMP[i]  the temperature compensation (bus 1320): SD 42960 component i,
//             after the moves before it have run
//   --plc     a scripted PLC writing the OTC control units and the temperature compensation's
//             data at cycles or blocks (plc_script.h)
//   Klartext  the 3D compensation module (bus 1310): TOOL CALL into its tool table and Tool,
//             M107/M108, TCPM, PROG PATH, RL/RR as its Side, FUNCTION CORRDATA TCS #n as its
//             CorrectionRow (the --corr table written at its start); LN as armed N/T and a
//             G01 whose end
//             the board compensates; B/C of L lines as board axes 4 and 5 (the first free ones)
//
// The first board error stops the run: the axes finish the move under way (the board holds
// after a TC error), the error is recorded with its block and its Table 4 bit name (or the
// status name), and the registers are read.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "apci/apci.hpp"
#include "apci/nc/correction_table.h"
#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "apci/run/board_words.h"
#include "apci/run/cpu_placement.h"
#include "apci/run/path.h"
#include "apci/run/plc_script.h"
#include "apci/run/self_approach.h"
#include "apci/run/summary.h"

namespace apci::run {

// What the self-approach check needs of a compensated stretch: the tool radius, the plane (17,
// 18, 19), the side (+1 left, -1 right) and a turning tool's cutting edge offset in the plane
// ({first, second}; zero for others: the check measures the nose centre, nose_centre_path).
struct CompensatedStretch {
    double radius = 0.0;
    int plane = 17;
    int side = 1;
    Eigen::Vector2d edge = Eigen::Vector2d::Zero();
};

// Where the executor's output goes; every method is optional.
class RunSink {
  public:
    virtual ~RunSink() = default;
    // A move of the program (absolute, before compensation), as the executor sends it.
    virtual void programmed(const PathSegment& s) { (void)s; }
    // False where programmed() does nothing (a sink that writes only what was executed): a
    // pipeline in front of it does not hand the moves on. Asked as each move comes, on the
    // caller's thread: what it reads must not change while the run goes.
    virtual bool takes_programmed() const { return true; }
    // True to get the rest of the program's moves through programmed() after an error stopped
    // the run (a plot shows the whole contour).
    virtual bool wants_programmed() const { return false; }
    // A segment the board executed, in program coordinates (tool centre point), measured
    // (PathSegment::sweep and length) unless measures_executed().
    virtual void executed(const PathSegment& s) { (void)s; }
    // True when the sink measures the executed segments itself (measure(), off the executor's
    // thread) and sums their lengths as count_segment() does: the executor then hands them on
    // unmeasured and takes the sums from measured_lengths() at the end of the run. Asked once,
    // at the start of the run.
    virtual bool measures_executed() const { return false; }
    // The path and rapid lengths of every executed segment handed on so far, summed in their
    // order from 0 as count_segment() sums them (the same bits); waits until the sink has had
    // every one. Asked only when measures_executed().
    virtual void measured_lengths(double& path, double& rapid) {
        (void)path;
        (void)rapid;
    }
    // Before the first sample: the column names of the board's axes ("X", ..., "a7").
    virtual void axes(std::span<const std::string> names) { (void)names; }
    // Before the first sample: the board axes of X, Y and Z.
    virtual void axis_numbers(const std::array<int, 3>& xyz) { (void)xyz; }
    // True to record the axis positions of every interpolation cycle (costs time).
    virtual bool wants_samples() const { return false; }
    // One cycle: the clock value after it, its time, the positions of the board's axes.
    virtual void sample(std::uint64_t cycle, double time_s, std::span<const double> axes) {
        (void)cycle;
        (void)time_s;
        (void)axes;
    }
    // An error, and where on the programmed path it happened.
    virtual void error(const RunError& e, const Point& where) {
        (void)e;
        (void)where;
    }
    // A warning (the path comes near the contour, self_approach.h), and where.
    virtual void warning(const RunError& w, const Point& where) {
        (void)w;
        (void)where;
    }
    // ---- The tool radius compensation as the run goes (the facts the self-approach check,
    // self_approach_sink.h, works on; other sinks pass them on or ignore them).
    // A compensated stretch begins: given before its first move to programmed(). The moves
    // programmed while it is open, other than rapids, are its contour elements.
    virtual void stretch_begin(const CompensatedStretch& s) { (void)s; }
    // The stretch ends (G40, a change of side, M30 with compensation on; a G0 between goes as a
    // compensated traverse and leaves it open).
    virtual void stretch_end() {}
    // CDON (true) or CDOF: whether the moves programmed from here on are walls.
    virtual void walls(bool on) { (void)on; }
    // A sink that must stop the run (the self-approach check where a finding is the run's
    // error) hands the error here once; the executor asks after every programmed(),
    // executed() and stretch_end(), records it and stops. Sinks behind the output pipeline
    // (pipeline.h) are not asked: they cannot stop the run.
    virtual std::optional<RunError> take_stop() { return std::nullopt; }
    // Blocks read so far by the execution pass, and bytes of the program (the stream's
    // offset()), as the stream said them with the last event executed (called every few
    // thousand events).
    virtual void progress(std::uint64_t blocks, std::uint64_t offset) {
        (void)blocks;
        (void)offset;
    }
};

// The board's block tag: the N number, or (no N, or N beyond 2^31 - 1) the source line with
// the top bit set. Executed segments carry it back.
std::uint32_t encode_block_tag(const BlockRef& b) noexcept;
BlockRef decode_block_tag(std::uint32_t tag) noexcept;

struct RunOutcome {
    RunTotals totals;                       // file and blocks are the caller's to fill
    std::vector<RunError> errors;           // empty: the program ran to its end
    // What the run found questionable without stopping: moves left out by bottleneck
    // avoidance ("Bottleneck"), then, where a SelfApproachSink checked the run
    // (self_approach_sink.h, results()), the compensated path coming closer than the tool
    // radius to the contour where it comes back near itself ("SelfApproach").
    std::vector<RunError> warnings;
    // The self-approach check's findings behind those warnings (or the error), in the same
    // order: both blocks, the least distance, where (filled by the SelfApproachSink).
    std::vector<SelfApproachFinding> self_approach;
    std::vector<GroupRegisters> registers;  // groups 1..3 at the end; empty without optionTC
    int plot_plane = 17;  // the plane of the first compensation, else the last plane in force
    std::array<int, 3> axis_numbers{0, 1, 2};             // board axes of X, Y, Z
    std::array<std::string, APCI_AXIS_COUNT> axis_names;  // CSV columns: "X", ..., "B"
    bool tc_present = true;
    bool otc_present = false;  // the board has the OTC module (bus 1330)
    // Accepted commands the emulator does not emulate (#HSC), by block; not errors.
    std::vector<RunError> notices;
    // The readable NC variables at the end by their names in [ISG-OTC] (V.G.OTC_ACTIVE,
    // V.G.WZ_AKT.WEAR_RADIUS, ... with the OTC module; $SC_TOOL_TEMP_COMP[0..2] with the
    // temperature compensation).
    std::vector<std::pair<std::string, double>> variables;
    // The tool list as the run left it: the wear of every tool changed out (and of the last
    // one, at the end) folded into its radius and length, its wear fields added up.
    nc::ToolTable tools_after;
};

class ProgramExecutor {
  public:
    // Per-cycle samples are read in chunks of this many cycles (the board's trace ring holds
    // twice as many), so none is lost however long a move.
    static constexpr std::uint32_t kTraceChunk = 1u << 15;
    // Executed segments and samples read per call.
    static constexpr std::size_t kReadBatch = 256;
    // Events between two progress() calls.
    static constexpr std::uint64_t kProgressEvery = 4096;

    // `tools` may be null: every D n then has radius and length 0. `plc` (may be null) is a
    // scripted PLC; `corrections` (may be null) the 3D compensation's correction table, written
    // to the board with the module's start state. Both must outlive run().
    ProgramExecutor(apci::Board& board, RunSink& sink, const nc::ToolTable* tools,
                    const PlcScript* plc = nullptr,
                    const nc::CorrectionTable* corrections = nullptr) noexcept
        : board_(board), sink_(sink), tools_(tools), plc_(plc), corrections_(corrections) {}

    // Where the board's X, Y, Z axes stand (program units): the interpreter's start position.
    // Zero when the board cannot say (run() then reports why).
    Point position();
    // The board's interpolation cycle in seconds: the interpreter counts a move's cycles in it.
    // The default 1 ms when the board cannot say (run() then reports why).
    double cycle_seconds();
    // The NC front end's options for a program this executor runs: it starts where the board's
    // axes stand (position()), counts a move's cycles in the board's interpolation cycle
    // (cycle_seconds()), and checks D n and CORRDATA against the tool list and correction table
    // the executor was given. Every caller (apcictl run and diff, the Python module) takes them
    // from here, so their runs cannot drift apart.
    nc::InterpreterOptions interpreter_options();
    // Executes the stream to its end or to the first error.
    RunOutcome run(nc::EventStream& events);
    // Bottleneck avoidance as SINUMERIK's CDON does it (docs/compensation.md, "Avoidance"):
    // 0 off (the default), else how many moves back the path of each compensated move is
    // compared with (kMinBottleneckBlocks..kMaxBottleneckBlocks): where two paths cross, the
    // moves between are left out in the plane, with a warning "Bottleneck".
    static constexpr int kMinBottleneckBlocks = 2;
    static constexpr int kMaxBottleneckBlocks = 64;
    void set_avoid_bottlenecks(int blocks) noexcept { bottleneck_blocks_ = blocks; }
    // With read-ahead, run() reads the stream through a ReadAhead (read_ahead.h): the NC front
    // end on a thread of its own, the same events, errors and variable reads at the same
    // places. The stream is the caller's again when run() returns. With `cpus` (which must
    // outlive run()), the reader runs where that places helpers (cpu_placement.h), on the CPU
    // `where` says, and with `follows` (which must outlive run() too) where that ring's fill
    // says (ReadAhead).
    void set_read_ahead(bool on, const CpuPlacement* cpus = nullptr,
                        HelperCpu where = HelperCpu::kOther,
                        const RingFill* follows = nullptr) noexcept {
        read_ahead_ = on;
        read_ahead_cpus_ = cpus;
        read_ahead_where_ = where;
        read_ahead_follows_ = follows;
    }

    // What the run's errors say after a lost link's cause (RunSettings::lost_link_hint).
    void set_lost_link_hint(std::string hint) { lost_link_hint_ = std::move(hint); }

  private:
    apci::Board& board_;
    RunSink& sink_;
    const nc::ToolTable* tools_;
    const PlcScript* plc_;
    const nc::CorrectionTable* corrections_;
    int bottleneck_blocks_ = 0;
    bool read_ahead_ = false;
    const CpuPlacement* read_ahead_cpus_ = nullptr;
    HelperCpu read_ahead_where_ = HelperCpu::kOther;
    const RingFill* read_ahead_follows_ = nullptr;
    std::string lost_link_hint_ = std::string(kLostLinkHint);
};

}  // namespace apci::run
