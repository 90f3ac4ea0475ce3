// SPDX-License-Identifier: MIT
#include "run_report.h"

#include <fmt/format.h>

#include "apci/run/summary.h"

namespace apcictl {

std::string at_block(const apci::run::BlockRef& b, std::string_view lead, std::string_view tail) {
    if (b.number == apci::run::kNoBlock && b.line == 0) return {};
    return fmt::format("{}{}{}", lead, apci::run::block_text(b), tail);
}

void print_warnings_and_notices(std::FILE* to, const apci::run::RunOutcome& result) {
    for (const apci::run::RunError& w : result.warnings)
        fmt::print(to, "warning: {}{}: {}\n", at_block(w.block, "", ": "), w.code, w.message);
    for (const apci::run::RunError& n : result.notices)
        fmt::print(to, "notice: {}{}\n", at_block(n.block, "", ": "), n.message);
}

std::string stopped_run(std::string_view file, const apci::run::RunError& first) {
    return fmt::format("run {}: stopped{}: {}", file, at_block(first.block, " at "), first.code);
}

std::string unfinished_run(std::string_view file, const apci::run::RunError& lost) {
    return fmt::format(
        "run {}: no output written (any old ones are kept): the run did not finish{}: {}", file,
        at_block(lost.block, ", "), lost.message);
}

}  // namespace apcictl
