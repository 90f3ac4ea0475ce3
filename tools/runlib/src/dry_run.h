// SPDX-License-Identifier: MIT
// The dry run of a program whose self-approach findings must stop it before anything moves
// (docs/apcictl.md "run", step 8): on a board that moves a machine (a daemon's, a real one) the
// check sees a finding only once the board has executed the moves, so the program runs first
// on an embedded emulator set up as the board stands, and a finding there is the refusal.
#pragma once

#include <optional>

#include "apci/apci.hpp"
#include "apci/nc/diagnostic.h"
#include "apci/run/program_run.h"

namespace apci::run::detail {

// The first self-approach finding of `source` run on an embedded emulator with the board's
// settings that shape the path copied from `board` (the TC module's read-write initialisation
// objects: axis numbers, plane, rotation; the interpolation cycle) and its axes moved to where
// the board's stand, as a refusal naming the block; nullopt when it finds none, or when the
// board has no TC module (nothing is compensated). `settings` says how to run it (threads);
// its self-approach mode is taken as an error.
std::optional<nc::Diagnostic> self_approach_dry_run(apci::Board& board, const RunInputs& inputs,
                                                    const ProgramSource& source,
                                                    const RunSettings& settings);

}  // namespace apci::run::detail
