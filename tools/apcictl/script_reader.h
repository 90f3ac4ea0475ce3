// SPDX-License-Identifier: MIT
// The reader of `apcictl script`: text in, parsed commands out, nothing run
// and nothing printed, so the command and the fuzzer (tests/fuzz) share it.
#pragma once

#include <istream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "command.h"

namespace apcictl {

// A line that did not parse: its number and the usage error naming why.
struct ScriptLineError {
    int number = 0;
    Outcome outcome;
};

struct ParsedScript {
    std::vector<ScriptLine> lines;         // ascending line numbers (ScriptLine: command.h)
    std::vector<ScriptLineError> errors;   // ascending line numbers
    bool read_failed = false;              // the stream failed (not at its end)
};

// The commands a script line may hold, comma-separated, in table order.
std::string script_command_names();

// Reads every line of `in` (one command a line, '#' comments, blank lines
// skipped) and parses each with the command table's declarations.
ParsedScript parse_script(std::istream& in);

// Whitespace-separated words of one line, without its '#' comment (none: a
// blank or comment line).
std::vector<std::string> script_words(std::string_view line);

// Parses the words of one non-empty line, as a script line, into `line`
// (its command and text; the number is the caller's): success, or the usage
// error naming what is wrong. `apcictl script` and `apcictl shell` share it.
Outcome parse_script_line(const std::vector<std::string>& words, ScriptLine& line);

}  // namespace apcictl
