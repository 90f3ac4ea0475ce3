// SPDX-License-Identifier: MIT
// What the interpreter hands to the executor: moves in absolute coordinates and the modal
// changes the executor must act on, one event at a time, each with the block and line it came
// from. Coordinates are the programmed contour (tool centre before compensation) in program
// units (mm); compensation itself is the board's job (TC module, docs/design.md section 3).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <variant>

#include "apci/nc/block.h"
#include "apci/nc/diagnostic.h"
#include "apci/nc/expression.h"
#include "apci/nc/parser.h"

namespace apci::nc {

struct BlockOrigin {
    std::int64_t block = kNoBlockNumber;  // N number, kNoBlockNumber (-1) when the block has none
    std::uint64_t line = 0;               // 1-based source line
};

// G0: rapid move, no feed, never compensated.
struct RapidMove {
    Eigen::Vector3d start;
    Eigen::Vector3d end;
};

// G1: straight line at the feed rate.
struct LineMove {
    Eigen::Vector3d start;
    Eigen::Vector3d end;
    double feed = 0.0;  // mm/min, > 0
};

// G2 (clockwise) / G3 (counter-clockwise), seen looking from the positive axis normal to the
// plane towards the plane (G17: from +Z, G18: from +Y, G19: from +X). The centre's coordinate on
// the normal axis is the start's; an end differing from the start on that axis makes a helix.
// start == end in the plane is a full circle (only programmable with I/J/K).
struct ArcMove {
    Eigen::Vector3d start;
    Eigen::Vector3d end;
    Eigen::Vector3d center;
    bool ccw = false;
    Plane plane = Plane::kXY;
    double feed = 0.0;  // mm/min, > 0
};

// D n: select tool data set n (0: no tool). Sent for every D word, also when n is unchanged.
struct ToolSelect {
    int tool = 0;
};

// G40 / G41 / G42, sent when the side changes.
struct CompensationChange {
    Compensation side = Compensation::kOff;
};

// G25 / G26, sent when the mode changes, after the block's move (it acts on the corners after
// the move).
struct CornerModeChange {
    CornerMode mode = CornerMode::kLinear;
};

// G139 / G237, sent when the method changes, before the block's G40/G41/G42 (it shapes the
// approach of the selection and the departure of the deselection in the same block).
struct SelectionModeChange {
    SelectionMode mode = SelectionMode::kIndirect;
};

// CDON / CDOF, sent when it changes, before the block's move (it holds for the move of its own
// block): whether the compensated elements programmed from here on are walls of the part for
// the gouge check of `apcictl run` (docs/compensation.md, "What is a wall"), the bottleneck
// detection of the controls that have it (SINUMERIK's CDON / CDOF).
struct CollisionDetectionChange {
    bool on = true;
};

// G17 / G18 / G19, sent when the plane changes.
struct PlaneChange {
    Plane plane = Plane::kXY;
};

// M30 (DIN 66025); Klartext: M30 or M2, else END PGM.
struct ProgramEnd {};

// ---- Klartext ([TNC-3D]: 3D tool compensation), docs/nc-programs.md ----

// TOOL CALL n Z [S..] [DL..] [DR..] [DR2..]: the delta values of the tool call (mm), which the
// 3D compensation adds to those of the tool table and the correction table. Sent right after
// ToolSelect{n} (the tool data set, as D n); a TOOL CALL without delta words sends zeros, so
// the deltas of an earlier call do not carry over.
struct ToolCallDeltas {
    int tool = 0;
    double dl = 0.0;
    double dr = 0.0;
    double dr2 = 0.0;
    double spindle_speed = 0.0;  // S, 1/min; 0 when not programmed
};

// Where on the tool the programmed points lie (FUNCTION TCPM ... REFPNT): the tip (TIP-TIP,
// TIP-CENTER, M128) or the centre on the tool axis at height R2 above the tip (CENTER-CENTER).
enum class ToolReference : std::uint8_t { kTip, kCentre };

// M128 / FUNCTION TCPM (on) and M129 / FUNCTION RESET TCPM (off), sent when the state or the
// reference point changes.
struct TcpmChange {
    bool on = false;
    ToolReference reference = ToolReference::kTip;
};

// FUNCTION CORRDATA TCS #n (row n) / FUNCTION CORRDATA RESET TCS (row 0): the correction
// table row whose delta values the 3D compensation adds to the tool's. Sent for every such
// block.
struct CorrectionSelect {
    int row = 0;
};

// FUNCTION PROG PATH IS CONTOUR (contour = true) / OFF, sent when it changes.
struct ProgPathChange {
    bool contour = false;
};

// M107 (allowed = true: a tool with positive delta values may be called) / M108, sent when it
// changes.
struct OversizeChange {
    bool allowed = false;
};

// The rotary axes of the documented head (B tilts the tool in the Z-X plane, C turns the head
// about Z), programmed in an L block: the positions, in degrees, that the block's move (if
// any) reaches at its end. Each axis not programmed keeps its position.
struct HeadOrientation {
    double b = 0.0;
    double c = 0.0;
};

// LN: a straight line with the surface normal N and the tool vector T ([TNC-3D], "Gerade LN").
// Points are the programmed ones (tool tip, tool centre or contour point, by TcpmChange and
// ProgPathChange); the 3D compensation is the board's job.
struct VectorLineMove {
    Eigen::Vector3d start;
    Eigen::Vector3d end;
    // N, normalised; absent only in a peripheral-milling line with T under TCPM.
    bool has_normal = false;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    // The tool vector the line runs with under TCPM: the programmed T, or N when the line has
    // none (the tool stands perpendicular to the contour). Without TCPM has_tool_vector is
    // false: the machine's current tool axis applies, and a programmed T is ignored.
    bool has_tool_vector = false;
    bool tool_vector_programmed = false;  // the line gave TX TY TZ (even when ignored)
    Eigen::Vector3d tool_vector = Eigen::Vector3d::Zero();
    Compensation side = Compensation::kOff;  // R0 / RL / RR in force (RL = kLeft, RR = kRight)
    double feed = 0.0;                       // mm/min; 0 with FMAX
    bool rapid = false;                      // FMAX
};

// ---- ISG commands of the DIN 66025 dialect ([ISG-OTC]; docs/design.md section 8) ----

// #OTC ...: what the command sets (OtcCommand, parser.h). Sent as written; the interpreter has
// checked its rules (tool type 2 where the tool list tells, G40 before #OTC OFF in RADIUS, no
// parameter change while OTC is on).
struct OtcChange {
    OtcCommand command;
};

// #KIN ID[n] (0: none, 4: the B head, docs/design.md section 8).
struct KinematicsSelect {
    int id = 0;
};

// #TRAFO ON / OFF: with it the moves' X Y Z are the tool tip; the machine's pivot is
// `tool_length` (mm, the tool in force) behind it along t(B) = (sin B, 0, cos B) (docs/design.md
// section 8). At the switch the position in force is re-expressed (tip = pivot - length t(B)).
struct TrafoChange {
    bool on = false;
    double tool_length = 0.0;
};

// A command the front end accepts but the emulator does not emulate (#HSC): the executor reports
// it. `command` is a static string ("#HSC").
struct NotEmulated {
    std::string_view command;
};

// V.G.WZ_AKT.WEAR_CONST = value ([ISG-OTC] section 2.8): the executor writes the tool's wear
// constant (0.1 um/m). $SC_TOOL_TEMP_COMP[i] = value ([SIN-TEMP], SD 42960): the executor writes
// the temperature compensation's component i (mm) after the moves before it have run.
struct VariableWrite {
    VariableRef variable;
    double value = 0.0;
};

using EventData =
    std::variant<RapidMove, LineMove, ArcMove, ToolSelect, CompensationChange, CornerModeChange,
                 PlaneChange, ProgramEnd, ToolCallDeltas, TcpmChange, ProgPathChange,
                 OversizeChange, HeadOrientation, VectorLineMove, OtcChange, KinematicsSelect,
                 TrafoChange, NotEmulated, VariableWrite, CorrectionSelect, SelectionModeChange,
                 CollisionDetectionChange>;

struct Event {
    BlockOrigin origin;
    EventData data;
};

// "rapid", "line", "arc", "tool", "compensation", "corner", "plane", "end", "tool_call",
// "tcpm", "prog_path", "oversize", "head", "vector_line", "otc", "kinematics", "trafo",
// "not_emulated", "variable_write", "correction_row", "selection".
std::string_view event_name(const EventData& data) noexcept;

// The events of one block, in the order the executor must act on them (docs/nc-programs.md):
// DIN 66025: tool select, plane, selection method, compensation, the move, corner mode,
// program end.
// Klartext: tool select and tool call deltas (TOOL CALL blocks), or oversize, TCPM, prog path,
// compensation, head orientation, the move, program end. A DIN block adds the B head's
// orientation (B word) before its move; an ISG command line gives one event of its own.
class EventBatch {
  public:
    static constexpr std::size_t kCapacity = 8;

    void clear() noexcept { size_ = 0; }
    std::size_t size() const noexcept { return size_; }
    bool empty() const noexcept { return size_ == 0; }
    const Event& operator[](std::size_t i) const noexcept { return events_[i]; }
    const Event* begin() const noexcept { return events_; }
    const Event* end() const noexcept { return events_ + size_; }
    // The interpreter never adds more than kCapacity (one per kind above).
    // `data` is an EventData or one of its alternatives (assigned as that alternative: no
    // variant made and copied on the way). Not noexcept: std::variant does not declare its
    // converting assignment so, although none of these alternatives throws.
    template <typename Data>
    void push(const BlockOrigin& origin, Data&& data) {
        events_[size_].origin = origin;
        events_[size_].data = std::forward<Data>(data);
        ++size_;
    }

  private:
    Event events_[kCapacity];
    std::size_t size_ = 0;
};

}  // namespace apci::nc
