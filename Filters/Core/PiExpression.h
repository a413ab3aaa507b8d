// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiExpression.h
 * @brief parser of polynomial expressions in x, y, z and named parameters
 *
 * Grammar (whitespace is ignored):
 *   expression := term (('+' | '-') term)*
 *   term       := unary (('*' | '/') unary)*          division only by a constant
 *   unary      := ('-' | '+') unary | power
 *   power      := primary ('^' unary)?                 exponent: a constant non-negative integer
 *   primary    := number | name | '(' expression ')'   names: x, y, z or a parameter
 * Numbers are decimal or scientific (1, 0.5, .5, 2e-3). `-x^2` is `-(x^2)`, and
 * `a^b^c` is `a^(b^c)`. Errors name what went wrong and the 1-based character position.
 */
#ifndef PiExpression_h
#define PiExpression_h

#include "PiPolynomial.h"

#include <map>
#include <memory>
#include <string>

namespace pisurf
{
using ParameterMap = std::map<std::string, double>;

/// An expression as written (before expansion): interval evaluation of this form is
/// much tighter than of the expanded polynomial, e.g. for (8z+5)^6.
struct ExpressionNode
{
  enum Kind
  {
    Constant,
    Variable,
    Add,
    Subtract,
    Multiply,
    Negate,
    Power
  };
  Kind Type = Constant;
  double Value = 0.0;
  int Axis = 0;
  int Exponent = 0;
  std::shared_ptr<ExpressionNode> A, B;
};

/// An enclosure of the expression over the box (x, y, z) ∈ box[0..2].
Interval EvaluateInterval(const ExpressionNode& node, const Interval box[3]);

/// True when each of x, y and z occurs at most once in the expression (a single-use
/// expression, as 0.1x^6 + 0.1y^6 + (8z + 5)^6 − 1): its interval evaluation then gives
/// the exact range over a box, up to rounding. Where a variable occurs twice, as in a
/// torus (x² + y² + z² + R² − r²)² − 4R²(x² + y²), each occurrence ranges independently
/// and the enclosure can be far wider than the range.
bool IsSingleUse(const ExpressionNode& node);

/// Parses `text` into `result` (and, if `tree` is given, the expression as written).
/// Returns false and sets `error` (result untouched) on any syntax error, unknown name,
/// non-constant or negative/fractional exponent, division by a non-constant or by zero,
/// a degree above MaxDegree or a non-finite coefficient.
bool ParseExpression(const std::string& text, const ParameterMap& parameters, Polynomial3& result,
  std::string& error, std::shared_ptr<const ExpressionNode>* tree = nullptr);

/// The expression expanded with every variable v replaced by v + shift[v] (the parser's
/// algebra, term by term: constants that cancel symbolically, as (x + 2.2) − 2.2, cancel
/// exactly), i.e. P(q + shift) for the parsed P. False if a coefficient is not finite.
bool ExpandShifted(const ExpressionNode& node, const double shift[3], Polynomial3& result);
/// True if `name` may be a parameter: [A-Za-z_][A-Za-z0-9_]* and not x, y or z.
bool IsValidParameterName(const std::string& name);
}

#endif
