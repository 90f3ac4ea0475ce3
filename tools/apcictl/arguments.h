// SPDX-License-Identifier: MIT
// Arguments as apcictl takes them, on the command line and in script lines alike:
// negative numbers as values (-.5, -inf, -nan), which CLI11 would take for options.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace apcictl {

// CLI11 takes an argument that starts with '-' and a character that is not a digit (-.5, -inf,
// -nan) for an option. protect_negative_numbers marks each such argument that reads as a number
// so that CLI11 takes it as a value; accept_negative_numbers makes every option and positional of
// `app` (declared before the call) take the value without the mark; plain_text takes the marks
// out of a text shown to the user (a parse error).
void protect_negative_numbers(std::vector<std::string>& args);
void accept_negative_numbers(CLI::App& app);
std::string plain_text(std::string text);

}  // namespace apcictl
