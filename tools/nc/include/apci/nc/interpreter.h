// SPDX-License-Identifier: MIT
// The DIN 66025 interpreter: modal state plus one block in, the block's events out. Pure: no
// I/O and no board; the executor drives the board from the events.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "apci/nc/parser.h"

#include "apci/nc/block.h"
#include "apci/nc/diagnostic.h"
#include "apci/nc/events.h"
#include "apci/nc/move_time.h"

namespace apci::nc {

class ToolTable;
class CorrectionTable;

// The corner mode a program starts in: G25, linear transitions, the modal default of the ISG
// kernel's programming manual ([ISG-PROG], "G25/G26"). (The board's TC module starts in its
// own default, circular; `apcictl run` sets the board to this at the start of a program.)
inline constexpr CornerMode kStartCornerMode = CornerMode::kLinear;

// The selection method a program starts in: G139, indirect, the initial state of [ISG-PROG].
// (The board's TC module starts perpendicular, G237; `apcictl run` sets the board to this.)
inline constexpr SelectionMode kStartSelectionMode = SelectionMode::kIndirect;

struct ModalState {
    std::optional<Motion> motion;                        // none until G0..G3 is programmed
    Plane plane = Plane::kXY;                            // G17
    DistanceMode distance = DistanceMode::kAbsolute;     // G90
    Compensation compensation = Compensation::kOff;      // G40
    CornerMode corner = kStartCornerMode;                // G25
    SelectionMode selection = kStartSelectionMode;       // G139
    Units units = Units::kMetric;                        // G71
    double feed = 0.0;                                   // mm/min; 0 until F is programmed
    int tool = 0;                                        // D0: no tool
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  // absolute, mm
    double b = 0.0;                                      // B head tilt, degrees
    bool ended = false;                                  // M30 seen
    bool collision = true;                               // CDON (the start), CDOF
    // ISG OTC ([ISG-OTC] section 2.1) as programmed: on/off and the parameters in force.
    bool otc_active = false;
    // G40 under G138 or G139 in a block without a move: the departure is still to come
    // ([ISG-OTC] section 2.2 "Hinweis": a path motion between G40 and #OTC OFF, else error
    // 90050), in the selection method of that G40.
    bool departure_pending = false;
    SelectionMode departing = SelectionMode::kIndirect;
    OtcType otc_type = OtcType::kLength;  // [ISG-OTC]: LENGTH "(Standard)"
    OtcMode otc_mode = OtcMode::kAuto;    // [ISG-OTC]: AUTO "(Standard)"
    int otc_acc_weight = 100;
    bool otc_programmed_wear_const = false;  // WEAR_CONST=.. in force (else the tool's)
    double otc_wear_const = 0.0;             // the WEAR_CONST=.. value
    // V.G.WZ_AKT.WEAR_CONST written by the program (the tool's constant from then on).
    std::optional<double> tool_wear_const;
    // $SC_TOOL_TEMP_COMP[0..2] (SD 42960, [SIN-TEMP]) as written by the program, 0 before.
    std::array<double, kToolTempCompCount> tool_temp_comp{};
    int kinematics = 0;  // #KIN ID
    bool trafo = false;  // #TRAFO ON: positions are the tool tip (docs/design.md section 8)
    double trafo_length = 0.0;  // the tool length (mm) the transformation uses
};

// The blocks $FOR loops may run in one pass over a program, every repetition of a body counted
// (blocks outside loops are not counted: a long program is bounded by its file). A loop whose
// body sets its own parameter back, or `$FOR P1 = 0, 1e15, 1`, ends with an error naming the
// loop instead of running on for hours (docs/nc-programs.md "Limits"). 10^7 blocks: ~10 s of
// validation, far beyond the loops of real programs ([ISG-OTC]'s examples run 21 times).
inline constexpr std::uint64_t kMaxLoopBlocks = 10'000'000;

struct InterpreterOptions {
    // Where the tool stands when the program starts (mm); the first move starts here.
    Eigen::Vector3d start_position = Eigen::Vector3d::Zero();
    // With a tool table, D n (n > 0) must name a valid tool (wz[n].gueltig 1). Not owned; must
    // outlive the interpreter. Without one, any D 0..1023 is accepted.
    const ToolTable* tools = nullptr;
    // Klartext: FUNCTION CORRDATA TCS #n must name a row of this table (KlartextOptions). Not
    // owned; null: any row 1..1023.
    const CorrectionTable* corrections = nullptr;
    // The board's interpolation cycle (s): a G1/G2/G3 whose feed makes it take more than
    // kMaxMoveCycles of them is an error naming its block (move_time.h).
    double cycle_seconds = kDefaultCycleSeconds;
    // $FOR loops run at most this many blocks in all, every repetition counted (program.h).
    std::uint64_t max_loop_blocks = kMaxLoopBlocks;
};

// The refusal of a block after M30 (the interpreter's and the program stream's).
inline constexpr std::string_view kBlockAfterEnd = "block after M30: the program has already ended";

class Interpreter {
  public:
    explicit Interpreter(const InterpreterOptions& options = {});

    // Applies one block: checks the program rules against the modal state, then commits the new
    // state and fills `out` (cleared first) with the block's events. On error returns false,
    // fills err (with `file`, the block's line and the column of the offending word) and changes
    // no state.
    // Under G70 the block's lengths and feed are taken in inches (converted to mm first).
    bool apply(const Block& block, std::string_view file, EventBatch& out, Diagnostic& err);
    // An ISG command line (#OTC, #KIN, #TRAFO, #HSC; $FOR/$ENDFOR are the stream's): checks its
    // rules, commits, fills `out`. `block` carries the line's N number and line.
    bool apply_isg(const IsgLine& isg, const Block& block, std::string_view file, EventBatch& out,
                   Diagnostic& err);
    // V.G.WZ_AKT.WEAR_CONST = value, $SC_TOOL_TEMP_COMP[i] = value.
    bool apply_variable_write(const Assignment& a, const Block& block, std::string_view file,
                              EventBatch& out, Diagnostic& err);
    // The front end's own view of a variable (docs/nc-programs.md): V.G.OTC_ACTIVE as
    // programmed, V.G.WZ_AKT.WEAR_CONST from the tool list or as written, $SC_TOOL_TEMP_COMP[i]
    // as written (0 before); the wear itself is the board's (0 here; the executor supplies the
    // board's values through a VariableSource).
    double model_variable(const VariableRef& v) const noexcept;

    // apply() without its path for plain moves: the general rule checks alone (tests compare
    // the two).
    bool apply_general(const Block& block, std::string_view file, EventBatch& out, Diagnostic& err);

  private:
    // apply() of a block whose lengths are in mm, `units` the block's input units.
    bool apply_mm(const Block& block, Units units, std::string_view file, EventBatch& out,
                  Diagnostic& err);
    double tool_length_mm(int tool) const noexcept;

  public:

    const ModalState& state() const noexcept { return state_; }
    const InterpreterOptions& options() const noexcept { return options_; }

  private:
    InterpreterOptions options_;
    ModalState state_;
};

}  // namespace apci::nc
