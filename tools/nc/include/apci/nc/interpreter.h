// SPDX-License-Identifier: MIT
// The DIN 66025 interpreter: modal state plus one block in, the block's events out. Pure: no
// I/O and no board; the executor drives the board from the events.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "apci/nc/block.h"
#include "apci/nc/diagnostic.h"
#include "apci/nc/events.h"

namespace apci::nc {

class ToolTable;

struct ModalState {
    std::optional<Motion> motion;                        // none until G0..G3 is programmed
    Plane plane = Plane::kXY;                            // G17
    DistanceMode distance = DistanceMode::kAbsolute;     // G90
    Compensation compensation = Compensation::kOff;      // G40
    CornerMode corner = CornerMode::kCircular;           // G26 (DESIGN.md section 3: the default)
    double feed = 0.0;                                   // mm/min; 0 until F is programmed
    int tool = 0;                                        // D0: no tool
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  // absolute, mm
    bool ended = false;                                  // M30 seen
};

struct InterpreterOptions {
    // Where the tool stands when the program starts (mm); the first move starts here.
    Eigen::Vector3d start_position = Eigen::Vector3d::Zero();
    // With a tool table, D n (n > 0) must name a valid tool (wz[n].gueltig 1). Not owned; must
    // outlive the interpreter. Without one, any D 0..1023 is accepted.
    const ToolTable* tools = nullptr;
};

class Interpreter {
  public:
    explicit Interpreter(InterpreterOptions options = {});

    // Applies one block: checks the program rules against the modal state, then commits the new
    // state and fills `out` (cleared first) with the block's events. On error returns false,
    // fills err (with `file`, the block's line and the column of the offending word) and changes
    // no state.
    bool apply(const Block& block, std::string_view file, EventBatch& out, Diagnostic& err);

    const ModalState& state() const noexcept { return state_; }
    const InterpreterOptions& options() const noexcept { return options_; }

  private:
    InterpreterOptions options_;
    ModalState state_;
};

}  // namespace apci::nc
