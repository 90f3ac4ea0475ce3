// SPDX-License-Identifier: MIT
// apcictl as a child process for the tests of its commands: the built program (APCICTL_PATH,
// set by the test's CMake target) with the given arguments, standard input and environment.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "process.h"

#ifndef APCICTL_PATH
#error "apcictl.h needs APCICTL_PATH, the path of the built apcictl"
#endif

namespace test_support {

// Runs apcictl with `args`; `input` is its standard input, `env` is added to its environment,
// and it runs in `cwd` (empty: the test's own working directory).
inline ProcessResult apcictl(std::vector<std::string> args, const std::string& input = {},
                             const std::vector<std::pair<std::string, std::string>>& env = {},
                             const std::string& cwd = {}) {
    args.insert(args.begin(), APCICTL_PATH);
    return run_process(args, input, env, cwd);
}

}  // namespace test_support
