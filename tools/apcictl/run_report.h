// SPDX-License-Identifier: MIT
// The words `apcictl run` reports a run with, besides the summary (apci/run/summary.h): where
// a message of a block names it, the warnings and notices after the summary, and the one line
// of a run that stopped or did not finish.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

#include "apci/run/executor.h"

namespace apcictl {

// "<lead>line 4 (N60)<tail>" for a message of a block; nothing for one of none (the board's
// clock, a lost link found between blocks, what the run did before its first block).
std::string at_block(const apci::run::BlockRef& b, std::string_view lead,
                     std::string_view tail = {});
// "warning: line 9 (N80): SelfApproach: ..." and "notice: ..." lines, one each, in order.
void print_warnings_and_notices(std::FILE* to, const apci::run::RunOutcome& result);
// "run p.nc: stopped at line 4 (N60): KorrError" ("run p.nc: stopped: TransportError").
std::string stopped_run(std::string_view file, const apci::run::RunError& first);
// "run p.nc: no output written (any old ones are kept): the run did not finish, line 4 (N60):
// ..." for a run whose board went away under it (`lost`, its error).
std::string unfinished_run(std::string_view file, const apci::run::RunError& lost);

}  // namespace apcictl
