// SPDX-License-Identifier: MIT
// apcictl as a child process for the tests of its commands: the built program (APCICTL_PATH,
// set by the test's CMake target) with the given arguments, standard input and environment.
#pragma once

#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "process.h"
#include "text.h"

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

// The arguments of the command an example program's header documents (its line
// "; ./build/bin/apcictl ARGS"), with the paths under examples/ made paths in `source_dir`;
// empty when the program has no such line.
inline std::vector<std::string> documented_command(const std::string& program,
                                                   const std::string& source_dir) {
    const std::string text = read_text(program);
    const std::string marker = "; ./build/bin/apcictl ";
    const std::size_t at = text.find(marker);
    if (at == std::string::npos) return {};
    std::stringstream words(
        text.substr(at + marker.size(), text.find('\n', at) - at - marker.size()));
    std::vector<std::string> args;
    for (std::string word; words >> word;)
        args.push_back(word.rfind("examples/", 0) == 0 ? source_dir + "/" + word : word);
    return args;
}

}  // namespace test_support
