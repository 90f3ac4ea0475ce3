// SPDX-License-Identifier: MIT
// DIN 66025 block parser (the subset the programs of [ISG-OTC] use) and the dialect detection hook.
//
// One line at a time: the parser turns a line into a Block, checking everything that can be
// checked inside the line (known words, numbers, words that exclude each other). Modal rules that
// need the program state live in the Interpreter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include <optional>

#include "apci/nc/block.h"
#include "apci/nc/diagnostic.h"
#include "apci/nc/expression.h"

namespace apci::nc {

// The dialect is told by content (docs/design.md section 8): a program whose first significant line
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
    kTapeMark,     // "%" alone: the tape's start or end mark (ISO 6983), first or after M30
    kBlock,        // at least one word (an "N10" alone is a block)
    kIsg,          // an ISG command: #OTC, #KIN, #TRAFO, #HSC, $FOR, $ENDFOR (after an optional N)
    kAssignment,   // "P1 = expr", "V.G.WZ_AKT.WEAR_CONST = expr" or
                   // "$SC_TOOL_TEMP_COMP[i] = expr" (after an optional N)
};

// #OTC ON | OFF [ RADIUS | LENGTH | TOOL_DIR | SURF_NORM_DIR  DISC | CONT | AUTO
//                 WEAR_CONST=.. | WEAR_CONST_TOOL  ACC_WEIGHT=.. ] ([ISG-OTC] section 2.1): each
// part is optional; a command without ON/OFF only sets the parameters ("Die Parametrierung kann
// vorab oder zusammen mit #OTC ON erfolgen").
struct OtcCommand {
    std::optional<bool> on;
    std::optional<OtcType> type;
    std::optional<OtcMode> mode;
    WearConstChoice wear_const = WearConstChoice::kUnchanged;
    double wear_const_value = 0.0;  // 0.1 um/m, >= 0
    std::optional<int> acc_weight;  // percent, 1..100
};

// $FOR Pn = start, end, step: Pn runs from start while it has not passed end (step > 0: Pn <=
// end; step < 0: Pn >= end), step added at $ENDFOR. Bounds are evaluated at $FOR.
struct ForLoop {
    int parameter = 0;
    double start = 0.0;
    double end = 0.0;
    double step = 1.0;
};

enum class IsgKind : std::uint8_t { kOtc, kKin, kTrafo, kHsc, kFor, kEndFor };
struct IsgLine {
    IsgKind kind = IsgKind::kOtc;
    std::uint32_t column = 0;  // of the '#' or '$'
    OtcCommand otc;            // kOtc
    int kinematics = 0;        // kKin: #KIN ID[n]
    bool on = false;           // kTrafo, kHsc: ON / OFF (#HSC [..] without either: false)
    ForLoop loop;              // kFor
};

struct Assignment {
    bool to_parameter = true;
    int parameter = 0;      // to_parameter
    VariableRef variable;   // otherwise (only writable variables)
    double value = 0.0;
    std::uint32_t column = 0;
};

struct ParsedLine {
    LineKind kind = LineKind::kEmpty;
    std::string_view program_name;  // kProgramName: a view into the parsed line
    std::uint32_t program_name_column = 0;
    Block block;  // kBlock (cleared for every line); the N number of kIsg and kAssignment too
    IsgLine isg;  // kIsg
    Assignment assignment;  // kAssignment
};

// Parses one line of a DIN 66025 program. On error returns false and fills err (file, line,
// column, what was expected); `out` is then unspecified. Expressions (`X[..]`, assignments,
// $FOR bounds, #OTC values) are evaluated with `ctx` (null: only numbers, no P parameters or
// variables).
bool parse_din_line(std::string_view line, std::uint64_t line_number, std::string_view file,
                    ParsedLine& out, Diagnostic& err, const ExpressionContext* ctx = nullptr);

namespace parser_detail {
// parse_din_line without its path for plain blocks: the general parser alone, which gives
// every error (tests compare the two).
bool parse_din_line_general(std::string_view line, std::uint64_t line_number, std::string_view file,
                            ParsedLine& out, Diagnostic& err,
                            const ExpressionContext* ctx = nullptr);
}  // namespace parser_detail

// True when the line is "$FOR ..." or "$ENDFOR" (after an optional N number): how a loop whose
// condition fails at once is skipped to its $ENDFOR without evaluating the body.
enum class LoopMarker : std::uint8_t { kNone, kFor, kEndFor };
LoopMarker loop_marker(std::string_view line) noexcept;

}  // namespace apci::nc
