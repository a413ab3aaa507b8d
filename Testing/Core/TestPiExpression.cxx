// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of pisurf::ParseExpression and IsValidParameterName (PiExpression.h).
#include "PiCoreTestUtilities.h"
#include "PiExpression.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using pisurf::ParameterMap;
using pisurf::ParseExpression;
using pisurf::Polynomial3;
using namespace pisurf_test;

namespace
{
/// Parses text or fails the test with the parser's message.
Polynomial3 Parse(const std::string& text, const ParameterMap& params = {})
{
  Polynomial3 p;
  std::string error;
  EXPECT_TRUE(ParseExpression(text, params, p, error)) << "\"" << text << "\": " << error;
  return p;
}

/// Polynomial from (coefficient, i, j, k) terms.
Polynomial3 Terms(std::initializer_list<pisurf::Monomial> terms)
{
  Polynomial3 p;
  for (const auto& t : terms)
  {
    p.AddTerm(t.Coefficient, t.I, t.J, t.K);
  }
  return p;
}

/// Expects a parse error containing each fragment; returns the message.
std::string ExpectError(const std::string& text, const std::vector<std::string>& fragments,
  const ParameterMap& params = {})
{
  Polynomial3 p = Polynomial3::Constant(7.0);
  std::string error;
  const bool ok = ParseExpression(text, params, p, error);
  EXPECT_FALSE(ok) << "\"" << text.substr(0, 80) << "\" parsed as " << p.ToString();
  EXPECT_TRUE(HasFragments(error, fragments)) << "input \"" << text.substr(0, 80) << "\"";
  // On failure the result is untouched.
  EXPECT_TRUE(SameTerms(p, Polynomial3::Constant(7.0))) << "result changed on error";
  return error;
}
}

TEST(Expression, ExpandsProductsAndPowers)
{
  // (x − 1)² = x² − 2x + 1
  EXPECT_TRUE(
    SameTerms(Parse("(x-1)^2"), Terms({ { 1, 2, 0, 0 }, { -2, 1, 0, 0 }, { 1, 0, 0, 0 } })));
  // (x + y + z)² has the six expected terms.
  EXPECT_TRUE(SameTerms(Parse("(x + y + z)^2"),
    Terms({ { 1, 2, 0, 0 }, { 1, 0, 2, 0 }, { 1, 0, 0, 2 }, { 2, 1, 1, 0 }, { 2, 1, 0, 1 },
      { 2, 0, 1, 1 } })));
  EXPECT_TRUE(SameTerms(Parse("x*y*z"), Terms({ { 1, 1, 1, 1 } })));
  EXPECT_TRUE(SameTerms(Parse("(x+1)*(x-1)"), Terms({ { 1, 2, 0, 0 }, { -1, 0, 0, 0 } })));
  EXPECT_TRUE(SameTerms(Parse("x^0"), Polynomial3::Constant(1)));
  EXPECT_TRUE(Parse("0*x + y - y").IsZero());
  // The highest allowed degree.
  EXPECT_EQ(Parse("x^64").GetDegree(), pisurf::MaxDegree);
  EXPECT_EQ(Parse("(x*y)^32").GetDegree(), pisurf::MaxDegree);
  EXPECT_EQ(Parse("(x+y)^32 * (x-z)^32").GetDegree(), pisurf::MaxDegree);
}

TEST(Expression, UnaryMinusBindsLooserThanPower)
{
  // -x^2 is -(x^2), not (−x)².
  EXPECT_TRUE(SameTerms(Parse("-x^2"), Terms({ { -1, 2, 0, 0 } })));
  EXPECT_TRUE(SameTerms(Parse("-2^2"), Polynomial3::Constant(-4)));
  EXPECT_TRUE(SameTerms(Parse("(-2)^2"), Polynomial3::Constant(4)));
  EXPECT_TRUE(SameTerms(Parse("--x"), Terms({ { 1, 1, 0, 0 } })));
  EXPECT_TRUE(SameTerms(Parse("+x"), Terms({ { 1, 1, 0, 0 } })));
  EXPECT_TRUE(SameTerms(Parse("-3*x - -2"), Terms({ { -3, 1, 0, 0 }, { 2, 0, 0, 0 } })));
  EXPECT_TRUE(
    SameTerms(Parse("x - y - z"), Terms({ { 1, 1, 0, 0 }, { -1, 0, 1, 0 }, { -1, 0, 0, 1 } })));
  EXPECT_TRUE(SameTerms(Parse("8/2/2"), Polynomial3::Constant(2))) << "'/' is left-associative";
}

TEST(Expression, PowerIsRightAssociative)
{
  EXPECT_TRUE(SameTerms(Parse("2^3^2"), Polynomial3::Constant(512)));
  EXPECT_TRUE(SameTerms(Parse("(2^3)^2"), Polynomial3::Constant(64)));
  EXPECT_TRUE(SameTerms(Parse("x^2^0"), Terms({ { 1, 1, 0, 0 } }))); // x^(2^0)
  EXPECT_TRUE(SameTerms(Parse("x^(1+1)"), Terms({ { 1, 2, 0, 0 } })));
  EXPECT_TRUE(SameTerms(Parse("x^(6/3)"), Terms({ { 1, 2, 0, 0 } })));
  EXPECT_TRUE(SameTerms(Parse("y^2.0"), Terms({ { 1, 0, 2, 0 } })));
}

TEST(Expression, DivisionByConstants)
{
  EXPECT_TRUE(SameTerms(Parse("x/4"), Terms({ { 0.25, 1, 0, 0 } })));
  EXPECT_TRUE(SameTerms(Parse("(x + 2*y)/(1+1)"), Terms({ { 0.5, 1, 0, 0 }, { 1, 0, 1, 0 } })));
  EXPECT_TRUE(SameTerms(Parse("z / 0.5"), Terms({ { 2, 0, 0, 1 } })));
}

TEST(Expression, Numbers)
{
  EXPECT_EQ(Parse("1e-3").GetCoefficient(0, 0, 0), 1e-3);
  EXPECT_EQ(Parse(".5").GetCoefficient(0, 0, 0), 0.5);
  EXPECT_EQ(Parse("3.").GetCoefficient(0, 0, 0), 3.0);
  EXPECT_EQ(Parse("2E+2").GetCoefficient(0, 0, 0), 200.0);
  EXPECT_EQ(Parse("1.5e1").GetCoefficient(0, 0, 0), 15.0);
  EXPECT_EQ(Parse("0.1").GetCoefficient(0, 0, 0), 0.1);
  EXPECT_EQ(Parse("123456789012345678").GetCoefficient(0, 0, 0), 123456789012345678.0);
  EXPECT_EQ(Parse(".5e-1*x").GetCoefficient(1, 0, 0), 0.05);
  // Too small for a double is zero, not an error.
  EXPECT_TRUE(Parse("1e-400").IsZero());
}

TEST(Expression, WhitespaceIsIgnored)
{
  EXPECT_TRUE(SameTerms(Parse(" \t x  *\n y ^ 2 \r"), Terms({ { 1, 1, 2, 0 } })));
}

TEST(Expression, Parameters)
{
  const ParameterMap params = { { "a", 2.0 }, { "b", -3.0 }, { "_r2", 0.5 }, { "X", 10.0 } };
  EXPECT_TRUE(SameTerms(Parse("a*x + b", params), Terms({ { 2, 1, 0, 0 }, { -3, 0, 0, 0 } })));
  EXPECT_TRUE(
    SameTerms(Parse("x^2 - _r2^2", params), Terms({ { 1, 2, 0, 0 }, { -0.25, 0, 0, 0 } })));
  EXPECT_TRUE(SameTerms(Parse("y^a", params), Terms({ { 1, 0, 2, 0 } }))) << "parameter exponent";
  EXPECT_TRUE(SameTerms(Parse("z/a", params), Terms({ { 0.5, 0, 0, 1 } })));
  EXPECT_TRUE(SameTerms(Parse("X*x", params), Terms({ { 10, 1, 0, 0 } })))
    << "names are case-sensitive";
}

TEST(Expression, EmptyInput)
{
  ExpectError("", { "empty expression" });
  ExpectError("   \t", { "empty expression" });
}

TEST(Expression, UnexpectedCharacter)
{
  ExpectError("x + $", { "unexpected '$'", "at position 5" });
  ExpectError("x)", { "unexpected ')'", "at position 2" });
  ExpectError("x + 1,5", { "unexpected ','", "at position 6" });
  ExpectError("x+", { "unexpected end of expression", "at position 3" });
  ExpectError("x * * y", { "unexpected '*'", "at position 5" });
}

TEST(Expression, MissingParenthesis)
{
  ExpectError("(x+1", { "missing ')'", "at position 5" });
  ExpectError("((x)", { "missing ')'", "at position 5" });
  ExpectError("(x+1 ]", { "expected ')'", "at position 6" });
}

TEST(Expression, UnknownName)
{
  ExpectError("x + foo", { "unknown name 'foo'", "at position 5" });
  ExpectError("2*w", { "unknown name 'w'", "at position 3" });
  ExpectError("a*x", { "unknown name 'a'", "at position 1" });
  ExpectError("xy", { "unknown name 'xy'", "at position 1" });
  // Without parameters the message names only the variables.
  ExpectError("a*x", { "(use x, y or z)" });
}

TEST(Expression, UnknownNameListsTheParameters)
{
  ExpectError("b*x", { "unknown name 'b' (use x, y, z or a parameter of the model: a, c)" },
    { { "a", 1.0 }, { "c", 2.0 } });
}

TEST(Expression, DoubleStarSuggestsCaret)
{
  ExpectError("x ** 2", { "unexpected '*' (write '^' for a power, e.g. x^2)", "at position 4" });
  // Two products with a space between are not a power.
  ExpectError("x * * y", { "unexpected '*' at position 5" });
}

TEST(Expression, ImplicitMultiplicationIsRefused)
{
  ExpectError("2x", { "unexpected 'x'", "'*'", "at position 2" });
  ExpectError("2 y", { "unexpected 'y'", "'*'", "at position 3" });
  ExpectError("(x+1)(x-1)", { "unexpected '('", "'*'", "at position 6" });
}

TEST(Expression, BadExponents)
{
  ExpectError("x^1.5", { "exponent must be a non-negative integer", "at position 3" });
  ExpectError("x^-2", { "exponent must be a non-negative integer", "at position 3" });
  ExpectError("x^ y", { "exponent must be a constant", "at position 4" });
  ExpectError("2^(x+1)", { "exponent must be a constant", "at position 3" });
  ExpectError("x^0.5", { "non-negative integer" }, {});
}

TEST(Expression, BadDivisions)
{
  ExpectError("1/x", { "division by a non-constant", "at position 3" });
  ExpectError("y / (x + 1)", { "division by a non-constant", "at position 5" });
  ExpectError("x/0", { "division by zero", "at position 3" });
  ExpectError("x/(2-2)", { "division by zero", "at position 3" });
  ExpectError("x / a", { "division by zero", "at position 5" }, { { "a", 0.0 } });
}

TEST(Expression, DegreeAboveMaxDegree)
{
  ExpectError("x^65", { "degree above 64", "at position 2" });
  ExpectError("x^40*y^30", { "degree above 64", "at position 5" });
  ExpectError("(x^2)^33", { "degree above 64" });
  ExpectError("x^1e300", { "degree above 64" });
}

TEST(Expression, Overflow)
{
  ExpectError("1e200^2", { "overflow", "at position 6" });
  ExpectError("x*1e200*1e200", { "overflow" });
  ExpectError("1e308 + 1e308", { "overflow", "at position 7" });
  ExpectError("1/1e-320", { "overflow" });
  ExpectError("(1e100*x + 1)^4", { "overflow" });
  ExpectError("1e999", { "number out of range", "at position 1" });
}

TEST(Expression, MalformedNumbers)
{
  ExpectError("1e", { "malformed number", "at position 1" });
  ExpectError("x + 1e", { "malformed number", "at position 5" });
  ExpectError("2e+", { "malformed number" });
  ExpectError("1ex", { "malformed number" });
  ExpectError(".", { "malformed number", "at position 1" });
  ExpectError("x*.e3", { "malformed number", "at position 3" });
}

TEST(Expression, DeepNestingIsAnErrorNotACrash)
{
  const std::string parens = std::string(1000, '(') + "x" + std::string(1000, ')');
  ExpectError(parens, { "nesting deeper than" });
  ExpectError(std::string(100000, '('), { "nesting deeper than" });
  ExpectError(std::string(1000, '-') + "x", { "nesting deeper than" });
  std::string towers = "x";
  for (int i = 0; i < 1000; ++i)
  {
    towers += "^1";
  }
  ExpectError(towers, { "nesting deeper than" });
  // Moderate nesting is fine.
  const std::string fifty = std::string(50, '(') + "x+1" + std::string(50, ')');
  EXPECT_TRUE(SameTerms(Parse(fifty), Terms({ { 1, 1, 0, 0 }, { 1, 0, 0, 0 } })));
}

// PiExpression.h: ParseExpression "returns false ... on ... a non-finite coefficient".
// A parameter that is not finite must therefore be refused, also when it appears alone.
TEST(Expression, NonFiniteParametersAreRefused)
{
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ExpectError("x*a", { "not a finite number" }, { { "a", inf } });
  ExpectError("x + a", { "not a finite number" }, { { "a", nan } });
  // Regression (fixed): a lone parameter, or a negated one, is returned unchecked.
  ExpectError("a", {}, { { "a", inf } });
  ExpectError("-a", {}, { { "a", nan } });
}

TEST(Expression, ParameterNames)
{
  for (const char* good : { "a", "_b", "r2", "radius_1", "X", "xx", "Z9_" })
  {
    EXPECT_TRUE(pisurf::IsValidParameterName(good)) << good;
  }
  for (const char* bad : { "", "x", "y", "z", "2a", "a-b", "a b", "é", "a.b", "$" })
  {
    EXPECT_FALSE(pisurf::IsValidParameterName(bad)) << bad;
  }
}

// The classifiers intersect with an expression as written only where each variable
// occurs once (its interval evaluation is then the exact range): the table's top, not
// the cup's tori.
TEST(Expression, SingleUse)
{
  const struct
  {
    const char* Text;
    bool SingleUse;
  } cases[] = { { "0.1*x^6+0.1*y^6+(8*z+5)^6-1", true }, { "x*y*z-1", true },
    { "((x-1)/0.1)^2+((y+1)/0.1)^2+(z/0.9)^2-0.5", true }, { "x*x", false },
    { "((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)", false }, { "(x+y)^2-y", false },
    { "3", true } };
  for (const auto& c : cases)
  {
    pisurf::Polynomial3 p;
    std::string error;
    std::shared_ptr<const pisurf::ExpressionNode> tree;
    ASSERT_TRUE(ParseExpression(c.Text, {}, p, error, &tree)) << c.Text << ": " << error;
    ASSERT_TRUE(tree);
    EXPECT_EQ(pisurf::IsSingleUse(*tree), c.SingleUse) << c.Text;
  }
}
