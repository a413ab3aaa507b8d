// SPDX-License-Identifier: BSD-3-Clause
#include "PiExpression.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
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

class Parser
{
public:
  Parser(const std::string& text, const ParameterMap& params)
    : Text(text)
    , Params(params)
  {
  }

  Polynomial3 Parse()
  {
    this->SkipSpace();
    if (this->Pos >= this->Text.size())
    {
      this->Fail("empty expression", 0);
    }
    Polynomial3 p = this->Expression();
    this->SkipSpace();
    if (this->Pos < this->Text.size())
    {
      this->Fail(std::string("unexpected '") + this->Text[this->Pos] + "'" +
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

  Polynomial3 Expression()
  {
    Polynomial3 p = this->Term();
    for (char c = this->Peek(); c == '+' || c == '-'; c = this->Peek())
    {
      const size_t at = this->Pos++;
      Polynomial3 q = this->Term();
      p = c == '+' ? p + q : p - q;
      this->Check(p, at);
    }
    return p;
  }

  Polynomial3 Term()
  {
    Polynomial3 p = this->Unary();
    for (char c = this->Peek(); c == '*' || c == '/'; c = this->Peek())
    {
      const size_t at = this->Pos++;
      const size_t operandAt = (this->SkipSpace(), this->Pos);
      Polynomial3 q = this->Unary();
      if (c == '*')
      {
        if (p.GetDegree() + q.GetDegree() > MaxDegree)
        {
          this->Fail("degree above " + std::to_string(MaxDegree), at);
        }
        p = p * q;
      }
      else
      {
        if (!q.IsConstant())
        {
          this->Fail("division by a non-constant (only constants may divide)", operandAt);
        }
        const double d = q.GetCoefficient(0, 0, 0);
        if (d == 0.0)
        {
          this->Fail("division by zero", operandAt);
        }
        p = p.Scaled(1.0 / d);
      }
      this->Check(p, at);
    }
    return p;
  }

  Polynomial3 Unary()
  {
    const char c = this->Peek();
    if (c == '-' || c == '+')
    {
      ++this->Pos;
      this->Enter();
      Polynomial3 p = this->Unary();
      --this->Depth;
      return c == '-' ? -p : p;
    }
    return this->Power();
  }

  Polynomial3 Power()
  {
    Polynomial3 base = this->Primary();
    if (this->Peek() != '^')
    {
      return base;
    }
    const size_t at = this->Pos++;
    const size_t exponentAt = (this->SkipSpace(), this->Pos);
    this->Enter();
    Polynomial3 e = this->Unary();
    --this->Depth;
    if (!e.IsConstant())
    {
      this->Fail("exponent must be a constant", exponentAt);
    }
    const double n = e.GetCoefficient(0, 0, 0);
    if (n < 0 || n != std::floor(n))
    {
      this->Fail("exponent must be a non-negative integer", exponentAt);
    }
    if (base.IsConstant())
    {
      const double v = std::pow(base.GetCoefficient(0, 0, 0), n);
      if (!std::isfinite(v))
      {
        this->Fail("coefficient overflow (not a finite number)", at);
      }
      return Polynomial3::Constant(v);
    }
    if (n * base.GetDegree() > MaxDegree)
    {
      this->Fail("degree above " + std::to_string(MaxDegree), at);
    }
    Polynomial3 p = base.Pow(static_cast<int>(n));
    this->Check(p, at);
    return p;
  }

  Polynomial3 Primary()
  {
    const char c = this->Peek();
    const size_t at = this->Pos;
    if (c == '(')
    {
      ++this->Pos;
      this->Enter();
      Polynomial3 p = this->Expression();
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
      return Polynomial3::Constant(this->Number());
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
        return Polynomial3::Variable(name[0] - 'x');
      }
      auto it = this->Params.find(name);
      if (it == this->Params.end())
      {
        this->Fail("unknown name '" + name + "' (use x, y, z or a model parameter)", at);
      }
      if (!std::isfinite(it->second))
      {
        this->Fail("parameter '" + name + "' is not a finite number", at);
      }
      return Polynomial3::Constant(it->second);
    }
    if (c == '\0')
    {
      this->Fail("unexpected end of expression");
    }
    this->Fail(std::string("unexpected '") + c + "'");
  }

  double Number()
  {
    const size_t start = this->Pos;
    size_t end = start;
    auto digits = [&]() {
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

bool ParseExpression(const std::string& text, const ParameterMap& parameters,
  Polynomial3& result, std::string& error)
{
  try
  {
    Parser parser(text, parameters);
    result = parser.Parse();
    return true;
  }
  catch (const ParseError& e)
  {
    error = e.what();
    return false;
  }
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
