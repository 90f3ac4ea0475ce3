// SPDX-License-Identifier: MIT
// The NC expression evaluator (apci/nc/expression.h, docs/nc-programs.md).
#include "apci/nc/expression.h"

#include <gtest/gtest.h>

#include <cmath>

namespace apci::nc {
namespace {

struct Ctx : ExpressionContext {
    bool parameter(int n, double& out) const override {
        if (n == 1) {
            out = 4.0;
            return true;
        }
        return false;
    }
    bool variable(const VariableRef& v, double& out, std::string&) const override {
        out = v.variable == NcVariable::kOtcActive ? 1.0 : 2.5;
        return true;
    }
};

double eval(std::string_view text) {
    Ctx ctx;
    LineCursor c(text);
    double v = 0.0;
    ExpressionError e;
    EXPECT_TRUE(evaluate_expression(c, &ctx, v, e)) << text << ": " << e.message;
    return v;
}

std::string fails(std::string_view text, const ExpressionContext* ctx = nullptr) {
    Ctx own;
    LineCursor c(text);
    double v = 0.0;
    ExpressionError e;
    if (evaluate_expression(c, ctx != nullptr ? ctx : &own, v, e)) return "";
    return std::to_string(e.column) + ": " + e.message;
}

TEST(Expression, PrecedenceAndBrackets) {
    EXPECT_EQ(eval("1 + 2 * 3"), 7.0);
    EXPECT_EQ(eval("[1 + 2] * 3"), 9.0);
    EXPECT_EQ(eval("-2 * -3"), 6.0);
    EXPECT_EQ(eval("10 / 4 - 1"), 1.5);
    EXPECT_EQ(eval("2 - 3 - 4"), -5.0);
    EXPECT_EQ(eval("+.5"), 0.5);
}

TEST(Expression, ParametersVariablesAndFunctions) {
    EXPECT_EQ(eval("P1 * 2"), 8.0);
    EXPECT_EQ(eval("V.G.OTC_ACTIVE + V.G.WZ_AKT.WEAR.X"), 3.5);
    EXPECT_EQ(eval("SQRT[P1]"), 2.0);
    EXPECT_EQ(eval("ABS[-3]"), 3.0);
    EXPECT_NEAR(eval("SIN[30]"), 0.5, 1e-15);
    EXPECT_NEAR(eval("COS[60]"), 0.5, 1e-15);
    EXPECT_NEAR(eval("TAN[45]"), 1.0, 1e-15);
    EXPECT_NEAR(eval("ATAN[1]"), 45.0, 1e-13);
}

TEST(Expression, StopsBeforeWhatCannotContinueIt) {
    Ctx ctx;
    LineCursor c("3*2, 7");
    double v = 0.0;
    ExpressionError e;
    ASSERT_TRUE(evaluate_expression(c, &ctx, v, e));
    EXPECT_EQ(v, 6.0);
    EXPECT_EQ(c.peek(), ',');
}

TEST(Expression, ErrorsNameWhatWasWrong) {
    EXPECT_EQ(fails("1/0"), "2: division by zero");
    EXPECT_EQ(fails("SQRT[-1]"), "1: SQRT of a negative number");
    EXPECT_EQ(fails("P7 + 1"), "1: P7 is used before it is set");
    EXPECT_EQ(fails("[1 + 2"), "7: expected ']' to close the '[' in column 1");
    EXPECT_EQ(fails("FOO[1]").find("unknown name 'FOO'"), 3u);
    EXPECT_EQ(fails("1 +"), "4: expected a value: the expression ends here");
}

TEST(Expression, WithoutContextOnlyNumbers) {
    LineCursor c("P1");
    double v = 0.0;
    ExpressionError e;
    EXPECT_FALSE(evaluate_expression(c, nullptr, v, e));
    EXPECT_EQ(e.message, "P1 is used before it is set");
    LineCursor d("2*[3+4]");
    EXPECT_TRUE(evaluate_expression(d, nullptr, v, e));
    EXPECT_EQ(v, 14.0);
}

TEST(Expression, ResultsAreFinite) {
    EXPECT_NE(fails("99999999999999999999*99999999999999999999*99999999999999999999*"
                    "99999999999999999999*99999999999999999999*99999999999999999999*"
                    "99999999999999999999*99999999999999999999*99999999999999999999*"
                    "99999999999999999999*99999999999999999999*99999999999999999999*"
                    "99999999999999999999*99999999999999999999*99999999999999999999*"
                    "99999999999999999999*99999999999999999999"),
              "");
}

}  // namespace
}  // namespace apci::nc
