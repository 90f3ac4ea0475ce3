// SPDX-License-Identifier: MIT
// The end of a forked benchmark child: it becomes the program argv[0] names, with argv as its
// arguments; exit status 127 when that cannot be executed.
#pragma once

#include <unistd.h>

#include <string>
#include <vector>

[[noreturn]] inline void exec_argv(const std::vector<std::string>& argv) {
    std::vector<char*> args;
    args.reserve(argv.size() + 1);
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    ::_exit(127);
}
