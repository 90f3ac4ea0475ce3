// SPDX-License-Identifier: MIT
// The reader of `apcictl script`: text in, parsed commands out, nothing run
// and nothing printed, so the command and the fuzzer (tests/fuzz) share it.
#pragma once

#include <cstdint>
#include <functional>
#include <istream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "apci/nc/source.h"
#include "command.h"
#include "line_editor.h"

namespace apcictl {

// A script is read whole and every line checked before any runs, so what it may hold is
// bounded (`yes status | apcictl script -` grew by 42 MB a second; `apcictl shell` runs each
// line of a pipe as it comes instead): at most kMaxScriptLines lines and kMaxScriptBytes bytes,
// each line at most kMaxLineLength characters without its line end (as NC programs,
// apci::nc::LineSource; `apcictl shell` reading a pipe too).
inline constexpr std::uint64_t kMaxScriptLines = 100'000;
inline constexpr std::uint64_t kMaxScriptBytes = std::uint64_t{16} << 20;  // 16 MiB
inline constexpr std::size_t kMaxLineLength = apci::nc::LineSource::kMaxLineLength;

// A line that did not parse: its number and the usage error naming why.
struct ScriptLineError {
    std::uint64_t number = 0;
    Outcome outcome;
};

struct ParsedScript {
    std::vector<ScriptLine> lines;         // ascending line numbers (ScriptLine: command.h)
    std::vector<ScriptLineError> errors;   // ascending line numbers
    bool read_failed = false;              // the stream failed (not at its end)
    // Why the script was not read to its end: it passed kMaxScriptLines or kMaxScriptBytes
    // (nothing of it may run). Empty when it was read whole.
    std::string too_large;
};

// The commands a script line may hold, comma-separated, in table order.
std::string script_command_names();

// Reads every line (`next(max_consumed)` gives one at a time, read_plain_line of
// line_editor.h; one command a line, '#' comments, blank lines skipped) and parses each with
// the command table's declarations. A line longer than kMaxLineLength is that line's error.
ParsedScript parse_script(const std::function<PlainLine(std::uint64_t max_consumed)>& next);
ParsedScript parse_script(std::istream& in);

// Whitespace-separated words of one line, without its '#' comment (none: a
// blank or comment line).
std::vector<std::string> script_words(std::string_view line);

// Parses the words of one non-empty line, as a script line, into `line`
// (its command and text; the number is the caller's): success, or the usage
// error naming what is wrong. `apcictl script` and `apcictl shell` share it.
Outcome parse_script_line(const std::vector<std::string>& words, ScriptLine& line);

}  // namespace apcictl
