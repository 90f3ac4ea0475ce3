// SPDX-License-Identifier: MIT
#include "apci/nc/expression.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string_view>
#include <utility>

namespace apci::nc {

namespace {

constexpr std::string_view kAxisLetters = "XYZABC";

bool keyword_is(std::string_view id, std::string_view upper) {
    if (id.size() != upper.size()) return false;
    for (std::size_t i = 0; i < id.size(); ++i)
        if (to_upper(id[i]) != upper[i]) return false;
    return true;
}

// Fills `err`: false.
bool expression_error(ExpressionError& err, ErrorKind kind, std::uint32_t column,
                      std::string message) {
    err.kind = kind;
    err.column = column;
    err.message = std::move(message);
    return false;
}

class Evaluator {
  public:
    Evaluator(LineCursor& c, const ExpressionContext* ctx, ExpressionError& err)
        : c_(c), ctx_(ctx), err_(err) {}

    bool expr(double& out) {
        if (!term(out)) return false;
        for (;;) {
            c_.skip_blanks();
            const char op = c_.peek();
            if (op != '+' && op != '-') return true;
            c_.advance();
            double rhs = 0.0;
            if (!term(rhs)) return false;
            out = op == '+' ? out + rhs : out - rhs;
            if (!finite(out, "the sum")) return false;
        }
    }

  private:
    bool fail(ErrorKind kind, std::uint32_t column, std::string message) {
        return expression_error(err_, kind, column, std::move(message));
    }
    bool finite(double v, std::string_view what) {
        if (std::isfinite(v)) return true;
        return fail(ErrorKind::kValue, c_.column(), fmt::format("{} is not a finite number", what));
    }

    bool term(double& out) {
        if (!unary(out)) return false;
        for (;;) {
            c_.skip_blanks();
            const char op = c_.peek();
            if (op != '*' && op != '/') return true;
            const std::uint32_t col = c_.column();
            c_.advance();
            double rhs = 0.0;
            if (!unary(rhs)) return false;
            if (op == '/') {
                if (rhs == 0.0) return fail(ErrorKind::kValue, col, "division by zero");
                out /= rhs;
            } else {
                out *= rhs;
            }
            if (!finite(out, op == '/' ? "the quotient" : "the product")) return false;
        }
    }

    bool unary(double& out) {
        c_.skip_blanks();
        const char ch = c_.peek();
        if (ch == '+' || ch == '-') {
            c_.advance();
            if (!unary(out)) return false;
            if (ch == '-') out = -out;
            return true;
        }
        return primary(out);
    }

    bool bracketed(double& out) {
        const std::uint32_t col = c_.column();
        c_.advance();  // '['
        if (!expr(out)) return false;
        c_.skip_blanks();
        if (c_.peek() != ']')
            return fail(ErrorKind::kSyntax, c_.column(),
                        fmt::format("expected ']' to close the '[' in column {}", col));
        c_.advance();
        return true;
    }

    bool primary(double& out) {
        c_.skip_blanks();
        const std::uint32_t col = c_.column();
        const char ch = c_.peek();
        if (ch == '[') return bracketed(out);
        if (is_digit(ch) || ch == '.') {
            if (c_.scan_number(out) != NumberScan::kOk)
                return fail(ErrorKind::kValue, col, "number out of range");
            return true;
        }
        if (to_upper(ch) == 'P' && is_digit(c_.peek_at(1))) return parameter(out);
        if (to_upper(ch) == 'V' && c_.peek_at(1) == '.') return variable(out);
        if (ch == '$' && at_setting_data(c_)) return variable(out);
        if (is_letter(ch)) return function(out);
        if (c_.at_end() || ch == ';' || ch == '(')
            return fail(ErrorKind::kSyntax, col, "expected a value: the expression ends here");
        return fail(ErrorKind::kSyntax, col,
                    fmt::format("expected a number, P parameter, variable, function or '[', "
                                "found '{}'",
                                ch));
    }

    bool parameter(double& out) {
        const std::uint32_t col = c_.column();
        c_.advance();  // 'P'
        const std::string_view digits = c_.scan_digits();
        const std::optional<std::uint64_t> v =
            whole_at_most(digits, static_cast<std::uint64_t>(kParameterCount - 1));
        if (!v)
            return fail(ErrorKind::kValue, col,
                        fmt::format("P parameter number P{} out of range 0..{}", digits,
                                    kParameterCount - 1));
        const int n = static_cast<int>(*v);
        if (ctx_ == nullptr || !ctx_->parameter(n, out))
            return fail(ErrorKind::kProgramRule, col,
                        fmt::format("P{} is used before it is set", n));
        return true;
    }

    bool variable(double& out) {
        const std::uint32_t col = c_.column();
        VariableRef v;
        if (!scan_variable(c_, v, err_)) return false;
        std::string why;
        if (ctx_ == nullptr) {
            return fail(ErrorKind::kProgramRule, col,
                        fmt::format("{} has no value here", variable_name(v)));
        }
        if (!ctx_->variable(v, out, why))
            return fail(ErrorKind::kProgramRule, col,
                        fmt::format("{} cannot be read: {}", variable_name(v), why));
        return true;
    }

    bool function(double& out) {
        const std::uint32_t col = c_.column();
        const std::string_view name = c_.scan_identifier();
        enum class Fn { kAbs, kSqrt, kSin, kCos, kTan, kAtan } fn;
        if (keyword_is(name, "ABS"))
            fn = Fn::kAbs;
        else if (keyword_is(name, "SQRT"))
            fn = Fn::kSqrt;
        else if (keyword_is(name, "SIN"))
            fn = Fn::kSin;
        else if (keyword_is(name, "COS"))
            fn = Fn::kCos;
        else if (keyword_is(name, "TAN"))
            fn = Fn::kTan;
        else if (keyword_is(name, "ATAN"))
            fn = Fn::kAtan;
        else
            return fail(ErrorKind::kSyntax, col,
                        fmt::format("unknown name '{}' in an expression (known: numbers, P "
                                    "parameters, V.G. variables, $SC_ setting data, ABS SQRT SIN COS "
                                    "TAN ATAN)",
                                    name));
        c_.skip_blanks();
        if (c_.peek() != '[')
            return fail(ErrorKind::kSyntax, c_.column(),
                        fmt::format("expected '[' after {}", name));
        double x = 0.0;
        if (!bracketed(x)) return false;
        constexpr double kDeg = std::numbers::pi / 180.0;
        switch (fn) {
            case Fn::kAbs:
                out = std::fabs(x);
                break;
            case Fn::kSqrt:
                if (x < 0.0) return fail(ErrorKind::kValue, col, "SQRT of a negative number");
                out = std::sqrt(x);
                break;
            case Fn::kSin:
                out = std::sin(x * kDeg);
                break;
            case Fn::kCos:
                out = std::cos(x * kDeg);
                break;
            case Fn::kTan:
                out = std::tan(x * kDeg);
                break;
            case Fn::kAtan:
                out = std::atan(x) / kDeg;
                break;
        }
        return finite(out, name);
    }

    LineCursor& c_;
    const ExpressionContext* ctx_;
    ExpressionError& err_;
};

}  // namespace

std::string variable_name(const VariableRef& v) {
    switch (v.variable) {
        case NcVariable::kWearRadius:
            return "V.G.WZ_AKT.WEAR_RADIUS";
        case NcVariable::kWearRadiusCont:
            return "V.G.WZ_AKT.WEAR_RADIUS_CONT";
        case NcVariable::kWear:
            return fmt::format("V.G.WZ_AKT.WEAR[{}]", v.index);
        case NcVariable::kWearConst:
            return "V.G.WZ_AKT.WEAR_CONST";
        case NcVariable::kOtcActive:
            return "V.G.OTC_ACTIVE";
        case NcVariable::kToolTempComp:
            return fmt::format("$SC_TOOL_TEMP_COMP[{}]", v.index);
    }
    return "?";
}

bool at_setting_data(const LineCursor& c) noexcept {
    return c.peek() == '$' && is_letter(c.peek_at(1)) && is_letter(c.peek_at(2)) &&
           c.peek_at(3) == '_';
}

namespace {

// After "[": blanks, a whole number below `count` into `n`, blanks and "]", which it passes;
// false where one is missing or the number is `count` or more.
bool scan_index(LineCursor& c, int count, int& n) {
    c.skip_blanks();
    n = 0;
    bool any = false;
    while (is_digit(c.peek())) {
        n = n * 10 + (c.peek() - '0');
        any = true;
        c.advance();
        if (n >= count) break;
    }
    c.skip_blanks();
    if (!any || n >= count || c.peek() != ']') return false;
    c.advance();
    return true;
}

// At "$": the setting data of [SIN-TEMP] (SD 42960 TOOL_TEMP_COMP[i], a channel setting datum,
// so $SC_); the machine data next to it are named, since programs do not write them.
bool scan_setting_data(LineCursor& c, VariableRef& out, ExpressionError& err) {
    const std::uint32_t col = c.column();
    auto fail = [&](std::string message) {
        return expression_error(err, ErrorKind::kSyntax, col, std::move(message));
    };
    c.advance();  // '$'
    const std::string_view name = c.scan_identifier();
    if (keyword_is(name, "SN_TOOL_TEMP_COMP") || keyword_is(name, "SA_TOOL_TEMP_COMP"))
        return fail(fmt::format("${}: SD 42960 TOOL_TEMP_COMP is a channel setting datum, "
                                "$SC_TOOL_TEMP_COMP[i]",
                                name));
    if (keyword_is(name, "MC_TOOL_TEMP_COMP_ON") || keyword_is(name, "MA_TEMP_COMP_TYPE"))
        return fail(fmt::format("${} is machine data (MD 20390 / MD 32750), which programs do "
                                "not write: it is set on the board (bus 1320), e.g. by the "
                                "apcictl run --plc script",
                                name));
    if (!keyword_is(name, "SC_TOOL_TEMP_COMP"))
        return fail(fmt::format("unknown setting datum ${} (known: $SC_TOOL_TEMP_COMP[i])", name));
    auto bad_index = [&] {
        return fail(fmt::format("$SC_TOOL_TEMP_COMP[i] takes a component index 0..{} (X, Y, Z "
                                "of the geometry axes)",
                                kToolTempCompCount - 1));
    };
    if (c.peek() != '[') return bad_index();
    c.advance();
    int n = 0;
    if (!scan_index(c, kToolTempCompCount, n)) return bad_index();
    out = {NcVariable::kToolTempComp, n};
    return true;
}

}  // namespace

bool scan_variable(LineCursor& c, VariableRef& out, ExpressionError& err) {
    if (c.peek() == '$') return scan_setting_data(c, out, err);
    const std::uint32_t col = c.column();
    auto fail = [&](std::string message) {
        return expression_error(err, ErrorKind::kSyntax, col, std::move(message));
    };
    constexpr std::string_view kKnown =
        "V.G.WZ_AKT.WEAR_RADIUS, V.G.WZ_AKT.WEAR_RADIUS_CONT, V.G.WZ_AKT.WEAR[i], "
        "V.G.WZ_AKT.WEAR.<axis>, V.G.WZ_AKT.WEAR_CONST, V.G.OTC_ACTIVE, $SC_TOOL_TEMP_COMP[i]";
    // The name: identifiers joined by '.', case-insensitive.
    auto part = [&](std::string_view upper) { return keyword_is(c.scan_identifier(), upper); };
    if (!part("V") || c.peek() != '.') return fail(fmt::format("expected a variable ({})", kKnown));
    c.advance();
    if (!part("G") || c.peek() != '.')
        return fail(fmt::format("unknown variable (known: {})", kKnown));
    c.advance();
    const std::string_view first = c.scan_identifier();
    if (keyword_is(first, "OTC_ACTIVE")) {
        out = {NcVariable::kOtcActive, 0};
        return true;
    }
    if (!keyword_is(first, "WZ_AKT") || c.peek() != '.')
        return fail(fmt::format("unknown variable V.G.{} (known: {})", first, kKnown));
    c.advance();
    const std::string_view second = c.scan_identifier();
    // The tool's values that are one number each.
    static constexpr std::pair<std::string_view, NcVariable> kScalars[] = {
        {"WEAR_RADIUS", NcVariable::kWearRadius},
        {"WEAR_RADIUS_CONT", NcVariable::kWearRadiusCont},
        {"WEAR_CONST", NcVariable::kWearConst}};
    for (const auto& [keyword, variable] : kScalars) {
        if (keyword_is(second, keyword)) {
            out = {variable, 0};
            return true;
        }
    }
    if (!keyword_is(second, "WEAR"))
        return fail(fmt::format("unknown variable V.G.WZ_AKT.{} (known: {})", second, kKnown));
    if (c.peek() == '[') {
        c.advance();
        int n = 0;
        if (!scan_index(c, kWearAxisCount, n))
            return fail(
                fmt::format("V.G.WZ_AKT.WEAR[i] takes an axis index 0..{}", kWearAxisCount - 1));
        out = {NcVariable::kWear, n};
        return true;
    }
    if (c.peek() == '.') {
        c.advance();
        const std::string_view axis = c.scan_identifier();
        if (axis.size() == 1) {
            const std::size_t i = kAxisLetters.find(to_upper(axis[0]));
            if (i != std::string_view::npos) {
                out = {NcVariable::kWear, static_cast<int>(i)};
                return true;
            }
        }
        return fail(fmt::format("V.G.WZ_AKT.WEAR.{}: unknown axis (X Y Z A B C)", axis));
    }
    return fail("V.G.WZ_AKT.WEAR needs an axis: WEAR[i] or WEAR.<axis>");
}

bool evaluate_expression(LineCursor& c, const ExpressionContext* ctx, double& out,
                         ExpressionError& err) {
    Evaluator e(c, ctx, err);
    return e.expr(out);
}

}  // namespace apci::nc
