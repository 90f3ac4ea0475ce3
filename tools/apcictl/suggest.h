// SPDX-License-Identifier: MIT
// Parse errors that say what was meant: an unknown command or option is named with the
// closest known one ("unknown command 'raed'; did you mean 'read'?"), on the command line and
// in script lines alike.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>

#include "objif/names.h"

namespace apcictl {

// The Damerau-Levenshtein distance, ignoring ASCII case (objif/names.h, which suggests object
// names with it).
using objif::edit_distance;

// The candidate closest to `typed`, or empty when none is close enough: a distance of at most
// 2, and at most (n - 1) / 2 where n is the longer of the two names without their leading
// dashes (so "-x" suggests nothing for "-d", "raed" suggests "read"). Ties: the first.
std::string closest_name(std::string_view typed, std::span<const std::string> candidates);

// One line saying what is wrong with the arguments `app` failed to parse (with `error`): an
// unknown command or option named, with the one meant if there is a close one, else CLI11's
// message. `app` is apcictl's command line or the parser of one script line.
std::string explain_parse_error(const CLI::App& app, const CLI::ParseError& error);
// The same for apcictl's command line, where a command's argument not given also names the
// command and its help ("run: PROGRAM is required (see 'apcictl run --help')"), and an unknown
// option typed before the command points to apcictl's own help (`words`: the command line as
// typed, without the program's name); a script line names its words itself.
std::string explain_command_line_error(const CLI::App& app, const CLI::ParseError& error,
                                       std::span<const std::string> words = {});

}  // namespace apcictl
