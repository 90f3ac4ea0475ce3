// SPDX-License-Identifier: MIT
// Arguments as apcictl takes them, on the command line and in script lines alike:
// numbers parsed with their range checked (a usage error names the argument and its
// range), and negative numbers as values (-.5, -inf, -nan), which CLI11 would take for
// options.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace apcictl {

// Parses TEXT as a whole number (decimal, or hexadecimal after 0x; an optional sign) within
// min..max. Empty on success, else why not: "CYCLES '-1' is not a whole number in 1..1000000000".
std::string parse_integer(std::string_view name, std::string_view text, std::int64_t min,
                          std::int64_t max, std::int64_t& out);
// The same for an int32 (object addresses: the whole int32 range).
std::string parse_int32_argument(std::string_view name, std::string_view text, std::int32_t& out);
// Parses TEXT as a finite number >= 0: "--tolerance 'nan' is not a finite number >= 0".
std::string parse_non_negative(std::string_view name, std::string_view text, double& out);

// CLI11 takes an argument that starts with '-' and a character that is not a digit (-.5, -inf,
// -nan) for an option. protect_negative_numbers marks each such argument that reads as a number
// so that CLI11 takes it as a value; accept_negative_numbers makes every option and positional of
// `app` (declared before the call) take the value without the mark; plain_text takes the marks
// out of a text shown to the user (a parse error).
void protect_negative_numbers(std::vector<std::string>& args);
void accept_negative_numbers(CLI::App& app);
std::string plain_text(std::string text);

}  // namespace apcictl
