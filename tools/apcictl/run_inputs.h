// SPDX-License-Identifier: MIT
// What an NC run reads besides the program, as `run` and `diff` take it from the command line:
// --tools, --corr and --plc, declared and handed to the one way a program is run
// (apci/run/program_run.h) in one place.
#pragma once

#include <CLI/CLI.hpp>
#include <array>
#include <string>
#include <string_view>
#include <utility>

#include "apci/nc/diagnostic.h"
#include "apci/run/program_run.h"
#include "command.h"

namespace apcictl {

struct RunInputOptions {
    std::string tools;
    std::string corr;
    std::string plc;

    // Declares --tools, --corr and --plc on `app`.
    void declare(CLI::App& app);
    // The options with their values, for the check that no output is an input.
    std::array<std::pair<std::string_view, const std::string*>, 3> named() const {
        return {{{"--tools", &tools}, {"--plc", &plc}, {"--corr", &corr}}};
    }
    // The inputs given (an empty option: not given), named in a refusal as the options that
    // give them ("no --tools file given").
    apci::run::RunInputFiles files() const;
    // Loads them (apci::run::load_run_inputs): a file that cannot be read is a usage error,
    // one that does not parse a program error.
    Outcome load(apci::run::RunInputs& in) const;
};

// A program, tool list or other input that cannot be read is a usage error; one that does not
// parse is a program error (exit 1). Either way nothing ran.
Outcome nc_failure(const apci::nc::Diagnostic& d);

}  // namespace apcictl
