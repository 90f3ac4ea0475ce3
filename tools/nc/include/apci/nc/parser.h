// SPDX-License-Identifier: MIT
// DIN 66025 block parser (the subset the ISG seed writes) and the dialect detection hook.
//
// One line at a time: the parser turns a line into a Block, checking everything that can be
// checked inside the line (known words, numbers, words that exclude each other). Modal rules that
// need the program state live in the Interpreter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "apci/nc/block.h"
#include "apci/nc/diagnostic.h"

namespace apci::nc {

// The dialect is told by content (DESIGN.md section 8): a program whose first significant line
// is "[n] BEGIN PGM ..." is Klartext (TNC), anything else DIN 66025 (ISG).
enum class Dialect : std::uint8_t { kUndecided, kDin66025, kKlartext };

struct DialectProbe {
    Dialect dialect = Dialect::kUndecided;  // kUndecided: the line is blank or only comments
    std::size_t offset = 0;                 // byte offset of "BEGIN" for kKlartext
};
DialectProbe detect_dialect(std::string_view line) noexcept;

enum class LineKind : std::uint8_t {
    kEmpty,        // blank, or only comments
    kProgramName,  // "%name"
    kBlock,        // at least one word (an "N10" alone is a block)
};

struct ParsedLine {
    LineKind kind = LineKind::kEmpty;
    std::string_view program_name;  // kProgramName: a view into the parsed line
    std::uint32_t program_name_column = 0;
    Block block;  // kBlock (cleared for every line)
};

// Parses one line of a DIN 66025 program. On error returns false and fills err (file, line,
// column, what was expected); `out` is then unspecified.
bool parse_din_line(std::string_view line, std::uint64_t line_number, std::string_view file,
                    ParsedLine& out, Diagnostic& err);

}  // namespace apci::nc
