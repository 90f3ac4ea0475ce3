// SPDX-License-Identifier: MIT
// The Klartext (TNC) subset for the 3D tool compensation, as [TNC-3D] writes it:
// BEGIN PGM / END PGM, TOOL CALL, L, LN, FUNCTION PROG PATH, FUNCTION TCPM, FUNCTION RESET
// TCPM, FUNCTION CORRDATA TCS (the correction table row) and the M functions M2 M30 M107 M108
// M128 M129. One line is one block. The parser
// turns a line into a KlartextBlock (checking what can be checked inside the line); the
// interpreter checks the program rules against the modal state and emits events.
// docs/nc-programs.md is the specification.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "apci/nc/block.h"
#include "apci/nc/diagnostic.h"
#include "apci/nc/events.h"
#include "apci/nc/move_time.h"

namespace apci::nc {

class ToolTable;
class CorrectionTable;

// A programmed N or T vector whose length differs from 1 by more than this is refused
// ([TNC-3D], "Gerade LN": "Das CAM-generierte NC-Programm muss normierte Vektoren enthalten").
// Every unit vector written with 4 decimals passes (rounding changes its length by at most 8.7e-5);
// the board's 3D compensation uses the same value (rwmos/comp3d/tolerances.h).
inline constexpr double kVectorLengthTolerance = 1e-4;
// With TCPM and a programmed T, N may point against T by this much (N.T >= -this); the board's
// kNormalAgainstToolTolerance.
inline constexpr double kNormalAgainstToolTolerance = 1e-3;

enum class KlartextKind : std::uint8_t {
    kEmpty,       // blank, comment (';'), structure line ('*'), or a bare block number
    kBeginPgm,    // BEGIN PGM name MM
    kEndPgm,      // END PGM name MM
    kToolCall,    // TOOL CALL n [Z] [S] [DL] [DR] [DR2]
    kLine,        // L
    kVectorLine,  // LN
    kProgPath,    // FUNCTION PROG PATH IS CONTOUR | FUNCTION PROG PATH [IS] OFF
    kTcpm,        // FUNCTION TCPM [...] [REFPNT ...]
    kResetTcpm,   // FUNCTION RESET TCPM
    kCorrData,    // FUNCTION CORRDATA TCS #n | FUNCTION CORRDATA RESET TCS
    kMOnly,       // a block of M functions only
};

inline constexpr std::size_t kMaxMFunctions = 4;  // per block, as the TNC allows

struct KlartextBlock {
    std::uint64_t line = 0;
    Word<std::int64_t> number;  // the leading block number
    KlartextKind kind = KlartextKind::kEmpty;
    std::uint32_t kind_column = 0;  // column of the block's keyword

    // BEGIN PGM / END PGM: a view into the parsed line.
    std::string_view program_name;
    std::uint32_t program_name_column = 0;
    Word<bool> inch;  // the unit word: false MM, true INCH

    // TOOL CALL
    Word<int> tool;
    Word<char> tool_axis;  // 'X', 'Y' or 'Z'
    Word<double> spindle_speed, dl, dr, dr2;
    Word<double> call_feed;  // F: the feed F AUTO takes ([TNC-3D] "F, FMAX, FZ, FU oder F AUTO")

    // L and LN. axis_incremental[k]: IX/IY/IZ (L only).
    std::array<Word<double>, 3> axis;
    std::array<bool, 3> axis_incremental{};
    std::array<Word<double>, 3> normal;       // NX NY NZ (LN)
    std::array<Word<double>, 3> tool_vector;  // TX TY TZ (LN)
    Word<double> b, c;                        // rotary axes in degrees (L)
    Word<Compensation> radius_comp;           // R0 kOff, RL kLeft, RR kRight
    Word<double> feed;                        // F, mm/min
    Word<bool> fmax;                          // FMAX
    Word<double> feed_per_tooth;              // FZ, mm per tooth
    Word<double> feed_per_rev;                // FU, mm per revolution
    Word<bool> feed_auto;                     // F AUTO: the TOOL CALL's F

    // M functions in the order written.
    std::array<Word<int>, kMaxMFunctions> m{};
    std::size_t m_count = 0;

    // FUNCTION PROG PATH: true IS CONTOUR, false OFF.
    bool prog_path_contour = false;
    // FUNCTION TCPM: the programmed points' reference (REFPNT), kTip when not given.
    ToolReference reference = ToolReference::kTip;
    // FUNCTION CORRDATA: the row 1..1023, 0 for RESET TCS.
    Word<int> corr_row;

    void clear(std::uint64_t line_number) noexcept {
        *this = KlartextBlock();
        line = line_number;
    }

    bool has_axis_word() const noexcept {
        return axis[0].present() || axis[1].present() || axis[2].present();
    }
    bool has_m(int code) const noexcept {
        for (std::size_t i = 0; i < m_count; ++i) {
            if (m[i].value == code) return true;
        }
        return false;
    }
    std::int64_t block_number() const noexcept { return number.present() ? number.value : -1; }
};

// Parses one line of a Klartext program. On error returns false and fills err (file, line,
// column, what was expected); `out` is then unspecified.
bool parse_klartext_line(std::string_view line, std::uint64_t line_number, std::string_view file,
                         KlartextBlock& out, Diagnostic& err);

// How the feed of L and LN blocks is given ([TNC-3D], "Gerade LN": "F, FMAX, FZ, FU oder
// F AUTO").
enum class KlartextFeed : std::uint8_t { kPerMinute, kPerTooth, kPerRevolution, kAuto };

struct KlartextState {
    bool begun = false;  // BEGIN PGM seen
    bool inch = false;
    bool ended = false;                             // M2/M30 seen: only END PGM may follow
    bool closed = false;                            // END PGM seen
    Compensation radius_comp = Compensation::kOff;  // R0
    // The feed in force ([TNC-3D], "Gerade LN": F, FMAX, FZ, FU or F AUTO), modal: F in mm/min;
    // FZ per tooth and FU per revolution, turned into mm/min at every move with the spindle
    // speed and the tool in force then; F AUTO the F of the TOOL CALL in force.
    KlartextFeed feed_mode = KlartextFeed::kPerMinute;
    double feed = 0.0;            // mm/min (F), 0 until a feed is programmed
    double feed_per_tooth = 0.0;  // FZ, mm
    double feed_per_rev = 0.0;    // FU, mm
    double spindle_speed = 0.0;   // S of the TOOL CALLs, 1/min; 0 until one gives it
    double call_feed = 0.0;       // F of the TOOL CALL in force, mm/min; 0: none
    int tool = 0;                                   // no tool
    double call_dl = 0.0, call_dr = 0.0, call_dr2 = 0.0;
    int corr_row = 0;  // FUNCTION CORRDATA TCS #n in force; 0: none
    // The called tool's summed deltas (list + call + correction row) are positive.
    bool tool_oversize = false;
    bool tcpm = false;
    ToolReference reference = ToolReference::kTip;
    bool prog_path_contour = false;  // FUNCTION PROG PATH OFF
    bool m107 = false;               // positive oversize not allowed
    double b = 0.0, c = 0.0;         // head rotary axes, degrees
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

struct KlartextOptions {
    Eigen::Vector3d start_position = Eigen::Vector3d::Zero();
    // With a tool table, TOOL CALL n (n > 0) must name a valid tool whose R2 <= R, and the
    // summed deltas of table and call are checked (effective tool, oversize without M107).
    // Not owned.
    const ToolTable* tools = nullptr;
    // With a correction table, FUNCTION CORRDATA TCS #n must name one of its rows, and the
    // row's deltas join the checks above. Without one any row 1..1023 is accepted and its
    // deltas are unknown (0 here). Not owned.
    const CorrectionTable* corrections = nullptr;
    // The board's interpolation cycle (s): an L or LN whose feed makes it take more than
    // kMaxMoveCycles of them is an error naming its block (move_time.h).
    double cycle_seconds = kDefaultCycleSeconds;
};

class KlartextInterpreter {
  public:
    explicit KlartextInterpreter(const KlartextOptions& options = {});

    // Applies one block: checks the program rules against the modal state, then commits the
    // new state and fills `out` (cleared first). On error returns false, fills err and changes
    // no state.
    bool apply(const KlartextBlock& block, std::string_view file, EventBatch& out, Diagnostic& err);

    const KlartextState& state() const noexcept { return state_; }
    // The name of BEGIN PGM (empty before it).
    const std::string& program_name() const noexcept { return program_name_; }

  private:
    KlartextOptions options_;
    KlartextState state_;
    std::string program_name_;
};

}  // namespace apci::nc
