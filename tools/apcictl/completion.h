// SPDX-License-Identifier: MIT
// Completion of apcictl's command line for bash and zsh (completions/), from the command table
// and each command's declared options: the shells' scripts are small and fixed, and ask
// `apcictl __complete WORDS...` for the candidates, so they never drift from the program and
// need no build step that runs it (docs/apcictl.md, "Shell completion").
#pragma once

#include <CLI/CLI.hpp>
#include <span>
#include <string>
#include <vector>

namespace apcictl {

// What the shell may complete the last of `words` to. `words` are the words after "apcictl"
// up to the cursor, the last one the word being typed ("" after a blank). `app` is apcictl's
// command line (its subcommands the command table, plus help). Candidates are whole words
// that start with the typed word, in the order of the table; object names one part at a time
// (shell_complete.h). `files`: the word is a file name, for the shell's own file completion.
struct LineCompletion {
    std::vector<std::string> words;
    bool files = false;
};
LineCompletion complete_command_line(const CLI::App& app, std::span<const std::string> words,
                                     std::span<const std::string> objects);

// What `apcictl __complete` prints: the candidates one a line, or the line ":files".
std::string completion_output(const LineCompletion& completion);

}  // namespace apcictl
