// SPDX-License-Identifier: MIT
// NC expressions and variables: the small evaluator behind `X[P1*2]`, `P1 = P1 + 1`,
// `$FOR P1 = 0, 20, 1`, `#OTC [WEAR_CONST=[P2*10]]` and the OTC variables of [ISG-OTC]
// ([ISG-OTC] section 2.8: V.G.WZ_AKT.WEAR_RADIUS, ..._CONT, .WEAR[i], .WEAR.<axis>,
// .WEAR_CONST, V.G.OTC_ACTIVE) and the SINUMERIK setting data of the temperature compensation
// ([SIN-TEMP]: $SC_TOOL_TEMP_COMP[i], SD 42960). docs/nc-programs.md ("Expressions and
// variables") is the spec.
//
// Grammar (blanks allowed between tokens; '(' starts a comment in NC lines, so brackets group):
//   expr    := ['+'|'-'] term { ('+'|'-') term }
//   term    := unary { ('*'|'/') unary }
//   unary   := ('+'|'-') unary | primary
//   primary := number | 'P' digits | variable | '$' setting | '[' expr ']'
//            | ('ABS'|'SQRT'|'SIN'|'COS'|'TAN'|'ATAN') '[' expr ']'     (angles in degrees)
// Expressions are evaluated while the line is parsed, with the values in force at that line.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "apci/nc/diagnostic.h"
#include "apci/nc/lexer.h"

namespace apci::nc {

// P parameters P0..P(kParameterCount - 1).
inline constexpr int kParameterCount = 1000;

// The variables by their names in [ISG-OTC].
enum class NcVariable : std::uint8_t {
    kWearRadius,      // V.G.WZ_AKT.WEAR_RADIUS (mm, read)
    kWearRadiusCont,  // V.G.WZ_AKT.WEAR_RADIUS_CONT (mm, read)
    kWear,            // V.G.WZ_AKT.WEAR[i] / .WEAR.<axis> (mm, read); index = axis
    kWearConst,       // V.G.WZ_AKT.WEAR_CONST (0.1 um/m, read and write)
    kOtcActive,       // V.G.OTC_ACTIVE (0/1, read)
    kToolTempComp,    // $SC_TOOL_TEMP_COMP[i], SD 42960 (mm, read and write); index 0..2
};
// Axis index of .WEAR[i] and .WEAR.<axis>: 0 X, 1 Y, 2 Z, 3 A, 4 B, 5 C, 6 and 7 further axes.
inline constexpr int kWearAxisCount = 8;

struct VariableRef {
    NcVariable variable = NcVariable::kOtcActive;
    int index = 0;  // kWear: the axis; kToolTempComp: the component 0..2
    bool operator==(const VariableRef&) const = default;
};
// SD 42960 TOOL_TEMP_COMP[0..2]: three components ([SIN-TEMP]), each within the range of its
// object on the board (bus 1320 Index 1, docs/object-map.md section 7; the executor checks
// that the two agree).
inline constexpr int kToolTempCompCount = 3;
inline constexpr double kToolTempCompLimit = 1e5;
// "V.G.WZ_AKT.WEAR[2]", "V.G.OTC_ACTIVE", "$SC_TOOL_TEMP_COMP[1]", ...
std::string variable_name(const VariableRef& v);
constexpr bool variable_writable(const VariableRef& v) noexcept {
    return v.variable == NcVariable::kWearConst || v.variable == NcVariable::kToolTempComp;
}
// True at a setting datum the cursor can read as a variable: '$', two letters, '_' ($SC_..,
// and the other SINUMERIK prefixes, which scan_variable names as unknown).
bool at_setting_data(const LineCursor& c) noexcept;

// Where the values come from while a line is evaluated.
class ExpressionContext {
  public:
    virtual ~ExpressionContext() = default;
    // P parameter n (0 <= n < kParameterCount); false when it was never set.
    virtual bool parameter(int n, double& out) const = 0;
    // A variable's value now; false with `why` when it cannot be read.
    virtual bool variable(const VariableRef& v, double& out, std::string& why) const = 0;
};

// Why an expression failed: the column (1-based) and the message; kind kSyntax, kValue or
// kProgramRule (a P parameter or variable without value).
struct ExpressionError {
    ErrorKind kind = ErrorKind::kSyntax;
    std::uint32_t column = 0;
    std::string message;
};

// Evaluates the expression at the cursor (it stops before anything that cannot continue it: a
// ',', ']', ';', '(' comment or the end). `ctx` may be null: then P parameters and variables
// are errors. The result is finite.
bool evaluate_expression(LineCursor& c, const ExpressionContext* ctx, double& out,
                         ExpressionError& err);

// At "V.G." or at a setting datum ("$SC_"): reads a variable name; false with err (cursor
// unspecified) when it names none.
bool scan_variable(LineCursor& c, VariableRef& out, ExpressionError& err);

}  // namespace apci::nc
