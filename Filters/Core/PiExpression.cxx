// SPDX-License-Identifier: BSD-3-Clause
#include "PiExpression.h"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace pisurf
{
namespace
{
struct ParseError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

// Nested parentheses deeper than this are refused rather than risking the stack.
constexpr int MaxNesting = 200;

using NodePtr = std::shared_ptr<ExpressionNode>;

// A character for a message: 'c' if printable, else its byte value (a NUL in a message
// would cut it short: what() is a C string).
std::string Quote(char c)
{
  const unsigned char u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7f)
  {
    return std::string("'") + c + "'";
  }
  static const char* const hex = "0123456789abcdef";
  return std::string("byte 0x") + hex[u >> 4] + hex[u & 15];
}

NodePtr Node(ExpressionNode::Kind kind, NodePtr a = nullptr, NodePtr b = nullptr)
{
  auto n = std::make_shared<ExpressionNode>();
  n->Type = kind;
  n->A = std::move(a);
  n->B = std::move(b);
  return n;
}

NodePtr ConstantNode(double v)
{
  auto n = Node(ExpressionNode::Constant);
  n->Value = v;
  return n;
}

// A parsed sub-expression: its expanded polynomial and its tree as written.
struct Value
{
  Polynomial3 P;
  NodePtr N;
};

class Parser
{
public:
  Parser(const std::string& text, const ParameterMap& params)
    : Text(text)
    , Params(params)
  {
  }

  Value Parse()
  {
    this->SkipSpace();
    if (this->Pos >= this->Text.size())
    {
      this->Fail("empty expression", 0);
    }
    Value p = this->Expression();
    this->SkipSpace();
    if (this->Pos < this->Text.size())
    {
      this->Fail("unexpected " + Quote(this->Text[this->Pos]) +
        (std::isalpha(static_cast<unsigned char>(this->Text[this->Pos])) ||
              this->Text[this->Pos] == '('
            ? " (write '*' for multiplication)"
            : ""));
    }
    return p;
  }

private:
  [[noreturn]] void Fail(const std::string& what, size_t at)
  {
    throw ParseError(what + " at position " + std::to_string(at + 1));
  }
  [[noreturn]] void Fail(const std::string& what) { this->Fail(what, this->Pos); }

  void SkipSpace()
  {
    while (this->Pos < this->Text.size() &&
      std::isspace(static_cast<unsigned char>(this->Text[this->Pos])))
    {
      ++this->Pos;
    }
  }

  char Peek()
  {
    this->SkipSpace();
    return this->Pos < this->Text.size() ? this->Text[this->Pos] : '\0';
  }

  void Check(const Polynomial3& p, size_t at)
  {
    if (!p.IsFinite())
    {
      this->Fail("coefficient overflow (not a finite number)", at);
    }
  }

  Value Expression()
  {
    Value p = this->Term();
    for (char c = this->Peek(); c == '+' || c == '-'; c = this->Peek())
    {
      const size_t at = this->Pos++;
      Value q = this->Term();
      p.P = c == '+' ? p.P + q.P : p.P - q.P;
      p.N = Node(c == '+' ? ExpressionNode::Add : ExpressionNode::Subtract, p.N, q.N);
      this->Check(p.P, at);
    }
    return p;
  }

  Value Term()
  {
    Value p = this->Unary();
    for (char c = this->Peek(); c == '*' || c == '/'; c = this->Peek())
    {
      const size_t at = this->Pos++;
      const size_t operandAt = (this->SkipSpace(), this->Pos);
      Value q = this->Unary();
      if (c == '*')
      {
        if (p.P.GetDegree() + q.P.GetDegree() > MaxDegree)
        {
          this->Fail("degree above " + std::to_string(MaxDegree), at);
        }
        p.P = p.P * q.P;
        p.N = Node(ExpressionNode::Multiply, p.N, q.N);
      }
      else
      {
        if (!q.P.IsConstant())
        {
          this->Fail("division by a non-constant (only constants may divide)", operandAt);
        }
        const double d = q.P.GetCoefficient(0, 0, 0);
        if (d == 0.0)
        {
          this->Fail("division by zero", operandAt);
        }
        p.P = p.P.Scaled(1.0 / d);
        p.N = Node(ExpressionNode::Multiply, p.N, ConstantNode(1.0 / d));
      }
      this->Check(p.P, at);
    }
    return p;
  }

  Value Unary()
  {
    const char c = this->Peek();
    if (c == '-' || c == '+')
    {
      ++this->Pos;
      this->Enter();
      Value p = this->Unary();
      --this->Depth;
      if (c == '-')
      {
        p.P = -p.P;
        p.N = Node(ExpressionNode::Negate, p.N);
      }
      return p;
    }
    return this->Power();
  }

  Value Power()
  {
    Value base = this->Primary();
    if (this->Peek() != '^')
    {
      return base;
    }
    const size_t at = this->Pos++;
    const size_t exponentAt = (this->SkipSpace(), this->Pos);
    this->Enter();
    Value e = this->Unary();
    --this->Depth;
    if (!e.P.IsConstant())
    {
      this->Fail("exponent must be a constant", exponentAt);
    }
    const double n = e.P.GetCoefficient(0, 0, 0);
    if (n < 0 || n != std::floor(n))
    {
      this->Fail("exponent must be a non-negative integer", exponentAt);
    }
    if (base.P.IsConstant())
    {
      const double v = std::pow(base.P.GetCoefficient(0, 0, 0), n);
      if (!std::isfinite(v))
      {
        this->Fail("coefficient overflow (not a finite number)", at);
      }
      return { Polynomial3::Constant(v), ConstantNode(v) };
    }
    if (n * base.P.GetDegree() > MaxDegree)
    {
      this->Fail("degree above " + std::to_string(MaxDegree), at);
    }
    Value p{ base.P.Pow(static_cast<int>(n)), Node(ExpressionNode::Power, base.N) };
    p.N->Exponent = static_cast<int>(n);
    this->Check(p.P, at);
    return p;
  }

  Value Primary()
  {
    const char c = this->Peek();
    const size_t at = this->Pos;
    if (c == '(')
    {
      ++this->Pos;
      this->Enter();
      Value p = this->Expression();
      --this->Depth;
      if (this->Peek() != ')')
      {
        this->Fail(this->Pos < this->Text.size() ? "expected ')'" : "missing ')'");
      }
      ++this->Pos;
      return p;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.')
    {
      const double v = this->Number();
      return { Polynomial3::Constant(v), ConstantNode(v) };
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_')
    {
      size_t end = this->Pos;
      while (end < this->Text.size() &&
        (std::isalnum(static_cast<unsigned char>(this->Text[end])) || this->Text[end] == '_'))
      {
        ++end;
      }
      const std::string name = this->Text.substr(this->Pos, end - this->Pos);
      this->Pos = end;
      if (name == "x" || name == "y" || name == "z")
      {
        NodePtr n = Node(ExpressionNode::Variable);
        n->Axis = name[0] - 'x';
        return { Polynomial3::Variable(n->Axis), n };
      }
      auto it = this->Params.find(name);
      if (it == this->Params.end())
      {
        this->Fail("unknown name '" + name + "' (" + this->KnownNames() + ")", at);
      }
      if (!std::isfinite(it->second))
      {
        this->Fail("parameter '" + name + "' is not a finite number", at);
      }
      return { Polynomial3::Constant(it->second), ConstantNode(it->second) };
    }
    if (this->Pos >= this->Text.size())
    {
      this->Fail("unexpected end of expression");
    }
    if (c == '*' && this->Pos > 0 && this->Text[this->Pos - 1] == '*')
    {
      this->Fail("unexpected '*' (write '^' for a power, e.g. x^2)");
    }
    this->Fail("unexpected " + Quote(c));
  }

  // The names an expression may use, for the message about an unknown one.
  std::string KnownNames() const
  {
    if (this->Params.empty())
    {
      return "use x, y or z";
    }
    std::string names;
    for (const auto& entry : this->Params)
    {
      names += (names.empty() ? "" : ", ") + entry.first;
    }
    return "use x, y, z or a parameter of the model: " + names;
  }

  double Number()
  {
    const size_t start = this->Pos;
    size_t end = start;
    auto digits = [&]()
    {
      size_t n = 0;
      while (end < this->Text.size() && std::isdigit(static_cast<unsigned char>(this->Text[end])))
      {
        ++end;
        ++n;
      }
      return n;
    };
    size_t n = digits();
    if (end < this->Text.size() && this->Text[end] == '.')
    {
      ++end;
      n += digits();
    }
    if (n == 0)
    {
      this->Fail("malformed number", start);
    }
    if (end < this->Text.size() && (this->Text[end] == 'e' || this->Text[end] == 'E'))
    {
      size_t e = end + 1;
      if (e < this->Text.size() && (this->Text[e] == '+' || this->Text[e] == '-'))
      {
        ++e;
      }
      if (e >= this->Text.size() || !std::isdigit(static_cast<unsigned char>(this->Text[e])))
      {
        this->Fail("malformed number (exponent digits missing)", start);
      }
      end = e;
      digits();
    }
    const std::string token = this->Text.substr(start, end - start);
    const double v = std::strtod(token.c_str(), nullptr);
    if (!std::isfinite(v))
    {
      this->Fail("number out of range '" + token + "'", start);
    }
    this->Pos = end;
    return v;
  }

  void Enter()
  {
    if (++this->Depth > MaxNesting)
    {
      this->Fail("nesting deeper than " + std::to_string(MaxNesting));
    }
  }

  const std::string& Text;
  const ParameterMap& Params;
  size_t Pos = 0;
  int Depth = 0;
};
}

bool ParseExpression(const std::string& text, const ParameterMap& parameters, Polynomial3& result,
  std::string& error, std::shared_ptr<const ExpressionNode>* tree)
{
  try
  {
    Parser parser(text, parameters);
    Value v = parser.Parse();
    result = v.P;
    if (tree)
    {
      *tree = v.N;
    }
    return true;
  }
  catch (const ParseError& e)
  {
    error = e.what();
    return false;
  }
}

namespace
{
// Outward rounding: at least one ulp beyond each end (a rounded +, − or × is within half
// an ulp). |x|·ε is at least one ulp of x, so x ∓ (|x|·ε + the smallest subnormal)
// rounds to a double at or beyond the next one: a little wider than nextafter, without
// its library call.
Interval Outward(double lo, double hi)
{
  constexpr double Tiny = std::numeric_limits<double>::denorm_min();
  // (An infinite end stays as nextafter leaves it: −inf, or DBL_MAX below +inf.)
  lo = lo == HUGE_VAL ? DBL_MAX : lo - (std::fabs(lo) * DBL_EPSILON + Tiny);
  hi = hi == -HUGE_VAL ? -DBL_MAX : hi + (std::fabs(hi) * DBL_EPSILON + Tiny);
  return { lo, hi };
}
// x^n by IntegerPower (at most 2·log2(n) + 1 roundings), widened by 2n ulps relative.
double PowerDown(double x, int n)
{
  const double v = IntegerPower(x, n);
  return v - std::fabs(v) * 2.0 * n * DBL_EPSILON - DBL_MIN;
}
double PowerUp(double x, int n)
{
  const double v = IntegerPower(x, n);
  return v + std::fabs(v) * 2.0 * n * DBL_EPSILON + DBL_MIN;
}
}

namespace
{
void CountVariables(const ExpressionNode& n, int counts[3])
{
  if (n.Type == ExpressionNode::Variable)
  {
    ++counts[n.Axis];
  }
  if (n.A)
  {
    CountVariables(*n.A, counts);
  }
  if (n.B)
  {
    CountVariables(*n.B, counts);
  }
}
}

bool IsSingleUse(const ExpressionNode& node)
{
  int counts[3] = { 0, 0, 0 };
  CountVariables(node, counts);
  return counts[0] <= 1 && counts[1] <= 1 && counts[2] <= 1;
}

Interval EvaluateInterval(const ExpressionNode& n, const Interval box[3])
{
  // Outward-rounded: an enclosure of the exact real value of the expression as written.
  switch (n.Type)
  {
    case ExpressionNode::Constant:
      return { n.Value, n.Value };
    case ExpressionNode::Variable:
      return box[n.Axis];
    case ExpressionNode::Add:
    {
      const Interval a = EvaluateInterval(*n.A, box), b = EvaluateInterval(*n.B, box);
      return Outward(a.Lo + b.Lo, a.Hi + b.Hi);
    }
    case ExpressionNode::Subtract:
    {
      const Interval a = EvaluateInterval(*n.A, box), b = EvaluateInterval(*n.B, box);
      return Outward(a.Lo - b.Hi, a.Hi - b.Lo);
    }
    case ExpressionNode::Multiply:
    {
      const Interval a = EvaluateInterval(*n.A, box), b = EvaluateInterval(*n.B, box);
      const double c[4] = { a.Lo * b.Lo, a.Lo * b.Hi, a.Hi * b.Lo, a.Hi * b.Hi };
      return Outward(std::min({ c[0], c[1], c[2], c[3] }), std::max({ c[0], c[1], c[2], c[3] }));
    }
    case ExpressionNode::Negate:
    {
      const Interval a = EvaluateInterval(*n.A, box);
      return { -a.Hi, -a.Lo };
    }
    case ExpressionNode::Power:
    {
      const Interval a = EvaluateInterval(*n.A, box);
      const int e = n.Exponent;
      if (e == 0)
      {
        return { 1.0, 1.0 };
      }
      if (e % 2 == 0 && a.Lo < 0 && a.Hi > 0)
      {
        return { 0.0, std::max(PowerUp(a.Lo, e), PowerUp(a.Hi, e)) };
      }
      // Monotone on the interval (odd power, or one sign): the ends' powers, outward.
      const double p = IntegerPower(a.Lo, e), q = IntegerPower(a.Hi, e);
      const double lo = p <= q ? PowerDown(a.Lo, e) : PowerDown(a.Hi, e);
      const double hi = p <= q ? PowerUp(a.Hi, e) : PowerUp(a.Lo, e);
      return { e % 2 == 0 ? std::max(0.0, lo) : lo, hi };
    }
  }
  return { -HUGE_VAL, HUGE_VAL };
}

namespace
{
Polynomial3 Shifted(const ExpressionNode& n, const double shift[3])
{
  switch (n.Type)
  {
    case ExpressionNode::Constant:
      return Polynomial3::Constant(n.Value);
    case ExpressionNode::Variable:
      return shift[n.Axis] == 0.0
        ? Polynomial3::Variable(n.Axis)
        : Polynomial3::Variable(n.Axis) + Polynomial3::Constant(shift[n.Axis]);
    case ExpressionNode::Add:
      return Shifted(*n.A, shift) + Shifted(*n.B, shift);
    case ExpressionNode::Subtract:
      return Shifted(*n.A, shift) - Shifted(*n.B, shift);
    case ExpressionNode::Multiply:
      return Shifted(*n.A, shift) * Shifted(*n.B, shift);
    case ExpressionNode::Negate:
      return -Shifted(*n.A, shift);
    case ExpressionNode::Power:
      return Shifted(*n.A, shift).Pow(n.Exponent);
  }
  return Polynomial3();
}
}

bool ExpandShifted(const ExpressionNode& node, const double shift[3], Polynomial3& result)
{
  // (The degree is the parsed one: a shift does not raise it.)
  Polynomial3 p = Shifted(node, shift);
  if (!p.IsFinite())
  {
    return false;
  }
  result = p;
  return true;
}

bool IsValidParameterName(const std::string& name)
{
  if (name.empty() || name == "x" || name == "y" || name == "z")
  {
    return false;
  }
  if (!(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_'))
  {
    return false;
  }
  for (char c : name)
  {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_'))
    {
      return false;
    }
  }
  return true;
}
}
