// SPDX-License-Identifier: MIT
// Tab completion of `apcictl shell`, as pure functions of the text before the cursor and the
// candidate lists: the line editor (line_editor.h) only inserts or lists what they return.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace apcictl {

// The words a TAB may complete the word before the cursor to (the word is the text after the
// last blank; empty after a blank):
// - the first word of the line: the `commands` that start with it (the shell's own words
//   help, quit, exit among them);
// - the second word after `help`: the `commands`; after `status`: "on" and "off";
// - any later word of another command: the `objects` (dotted object names) that start with it,
//   one part at a time: each is cut after the first '.' or '[' past the typed text ("t" gives
//   "tc." and "tempcomp.", "tc.group[1].r" gives "tc.group[1].radius");
// - nothing inside a '#' comment, after quit/exit, or past help's and status's one argument.
// In the order of the lists, each word once.
std::vector<std::string> complete(std::string_view line_before_cursor,
                                  std::span<const std::string> commands,
                                  std::span<const std::string> objects);

// The longest text every candidate starts with ("" for none).
std::string common_prefix(std::span<const std::string> candidates);

// What a TAB does with the candidates of complete(): one candidate is inserted whole with a
// blank after it (none after a name's part ending in '.' or '[': the name goes on); several are
// extended to their common prefix, or, when that adds nothing, listed; none does nothing (the
// editor rings the bell).
struct TabAction {
    std::string insert;               // the text to insert at the cursor ("" for none)
    std::vector<std::string> listed;  // the candidates to show below the line
};
TabAction tab_action(std::string_view line_before_cursor,
                     const std::vector<std::string>& candidates);

// The candidates in columns as wide as the longest, as many as fit `width` characters (at
// least one), filled row by row; each row ends with '\n'. More than `max_listed` candidates are
// not listed: one line says how many there are instead.
std::string candidate_columns(std::span<const std::string> candidates, std::size_t width,
                              std::size_t max_listed = 200);

}  // namespace apcictl
