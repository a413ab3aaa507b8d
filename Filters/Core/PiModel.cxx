// SPDX-License-Identifier: BSD-3-Clause
#include "PiModel.h"

#include "PiPrimitiveCatalogue.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

namespace pisurf
{
namespace
{
using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

struct ModelError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

[[noreturn]] void Fail(const std::string& path, const std::string& what)
{
  throw ModelError(path + ": " + what);
}

double Number(const json& v, const std::string& path)
{
  if (!v.is_number())
  {
    Fail(path, std::string("expected a number, got ") + v.type_name());
  }
  const double d = v.get<double>();
  if (!std::isfinite(d))
  {
    Fail(path, "must be a finite number");
  }
  return d;
}

void Vector(const json& v, const std::string& path, double* out, size_t n)
{
  if (!v.is_array() || v.size() != n)
  {
    Fail(path, "expected an array of " + std::to_string(n) + " numbers");
  }
  for (size_t i = 0; i < n; ++i)
  {
    out[i] = Number(v[i], path + "[" + std::to_string(i) + "]");
  }
}

std::string String(const json& v, const std::string& path)
{
  if (!v.is_string())
  {
    Fail(path, std::string("expected a string, got ") + v.type_name());
  }
  return v.get<std::string>();
}

// The types' keys, for the message that names an unknown one.
std::string TypeKeys()
{
  std::string list;
  for (const PrimitiveInfo& entry : PrimitiveCatalogue())
  {
    list += (list.empty() ? "" : ", ") + std::string(entry.Key);
  }
  return list;
}

// The value of one of the type's parameters (its key is present in `j`).
void ParseParameter(
  const json& v, const ParameterInfo& p, const std::string& path, PrimitiveSpec& s)
{
  switch (p.Kind)
  {
    case ParameterKind::Number:
      if (p.Count == 1)
        *p.Numbers(s) = Number(v, path);
      else
        Vector(v, path, p.Numbers(s), static_cast<size_t>(p.Count));
      break;
    case ParameterKind::Integer:
    {
      // Checked here, before the conversion to int (BuildFactor checks the int).
      const double e = Number(v, path);
      if (e != std::floor(e) || std::fabs(e) > 1e9 || !Allows(p.Rule, e))
      {
        Fail(path, "must be " + ConstraintText(p.Rule));
      }
      *p.Integer(s) = static_cast<int>(e);
      break;
    }
    case ParameterKind::Text:
    {
      std::string& text = *p.Text(s);
      text = String(v, path);
      if (text.find_first_not_of(" \t\r\n") == std::string::npos)
      {
        Fail(path, "empty " + std::string(p.Key));
      }
      break;
    }
  }
}

PrimitiveSpec ParsePrimitive(const json& j, const std::string& path)
{
  if (!j.is_object())
  {
    Fail(path, "expected an object");
  }
  PrimitiveSpec s;
  if (!j.contains("type"))
  {
    Fail(path, "missing key 'type'");
  }
  const std::string type = String(j["type"], path + ".type");
  if (!TypeFromString(type, s.Type))
  {
    Fail(path + ".type", "unknown primitive type '" + type + "' (" + TypeKeys() + ")");
  }
  const PrimitiveInfo& entry = CatalogueEntry(s.Type);
  std::set<std::string> allowed = { "type", "name", "center", "axis", "rotation", "scale",
    "negate" };
  for (const ParameterInfo& p : entry.Parameters)
  {
    allowed.insert(p.Key);
  }
  for (auto it = j.begin(); it != j.end(); ++it)
  {
    if (!allowed.count(it.key()))
    {
      std::string list;
      for (const auto& k : allowed)
      {
        list += (list.empty() ? "" : ", ") + k;
      }
      Fail(path, "unknown key '" + it.key() + "' for a " + type + " (allowed: " + list + ")");
    }
  }
  for (const ParameterInfo& p : entry.Parameters)
  {
    if (!j.contains(p.Key))
    {
      Fail(path, "a " + type + " needs the key '" + p.Key + "'");
    }
  }

  if (j.contains("name"))
    s.Name = String(j["name"], path + ".name");
  if (j.contains("center"))
    Vector(j["center"], path + ".center", s.Center, 3);
  if (j.contains("axis") && j.contains("rotation"))
  {
    Fail(path, "give either 'axis' or 'rotation', not both");
  }
  if (j.contains("axis"))
  {
    s.Orient = Orientation::Axis;
    Vector(j["axis"], path + ".axis", s.Axis, 3);
  }
  if (j.contains("rotation"))
  {
    const json& r = j["rotation"];
    const std::string rp = path + ".rotation";
    if (!r.is_object() || r.size() != 2 || !r.contains("axis") || !r.contains("angle"))
    {
      Fail(rp, "expected {\"axis\": [x, y, z], \"angle\": degrees}");
    }
    s.Orient = Orientation::Rotation;
    Vector(r["axis"], rp + ".axis", s.RotationAxis, 3);
    s.RotationAngle = Number(r["angle"], rp + ".angle");
  }
  if (j.contains("scale"))
    s.Scale = Number(j["scale"], path + ".scale");
  if (j.contains("negate"))
  {
    if (!j["negate"].is_boolean())
      Fail(path + ".negate", "expected true or false");
    s.Negate = j["negate"].get<bool>();
  }
  for (const ParameterInfo& p : entry.Parameters)
  {
    ParseParameter(j[p.Key], p, path + "." + p.Key, s);
  }
  return s;
}

void ParseTop(const json& j, Model& m)
{
  if (!j.is_object())
  {
    Fail("model", "the top level must be a JSON object");
  }
  static const std::set<std::string> allowed = { "pisurf", "blending", "bounds", "parameters",
    "primitives", "name", "description" };
  for (auto it = j.begin(); it != j.end(); ++it)
  {
    if (!allowed.count(it.key()))
    {
      Fail("model",
        "unknown key '" + it.key() +
          "' (allowed: pisurf, blending, bounds, parameters, primitives, name, description)");
    }
  }
  if (!j.contains("pisurf"))
    Fail("model", "missing key 'pisurf' (the format version, 1)");
  if (!j["pisurf"].is_number() || j["pisurf"].get<double>() != 1.0)
    Fail("pisurf", "unsupported version (this reader knows version 1)");
  if (!j.contains("blending"))
    Fail("model", "missing key 'blending' (the blending parameter r)");
  m.Blending = Number(j["blending"], "blending");
  if (j.contains("name"))
    m.Name = String(j["name"], "name");
  if (j.contains("description"))
    m.Description = String(j["description"], "description");
  if (j.contains("parameters"))
  {
    const json& p = j["parameters"];
    if (!p.is_object())
      Fail("parameters", "expected an object {name: number}");
    for (auto it = p.begin(); it != p.end(); ++it)
    {
      if (!IsValidParameterName(it.key()))
      {
        Fail(
          "parameters." + it.key(), "invalid parameter name (letters, digits, '_'; not x, y or z)");
      }
      m.Parameters[it.key()] = Number(it.value(), "parameters." + it.key());
    }
  }
  if (j.contains("bounds"))
  {
    Vector(j["bounds"], "bounds", m.Bounds, 6);
    if (!ValidBounds(m.Bounds))
      Fail("bounds", "expected [x0, x1, y0, y1, z0, z1] with x0 < x1, y0 < y1, z0 < z1");
    m.HasBounds = true;
  }
  if (!j.contains("primitives"))
    Fail("model", "missing key 'primitives'");
  const json& prims = j["primitives"];
  if (!prims.is_array())
    Fail("primitives", "expected an array");
  if (prims.empty())
    Fail("primitives", "a model needs at least one primitive");
  if (prims.size() > MaxPrimitives)
    Fail("primitives", "more than " + std::to_string(MaxPrimitives) + " primitives");
  bool unbounded = false;
  for (size_t i = 0; i < prims.size(); ++i)
  {
    const std::string path = "primitives[" + std::to_string(i) + "]";
    PrimitiveSpec s = ParsePrimitive(prims[i], path);
    PolynomialFactor f;
    std::string why;
    if (!BuildFactor(s, m.Parameters, f, why))
    {
      Fail(path + (s.Name.empty() ? "" : " ('" + s.Name + "')"), why);
    }
    unbounded = unbounded || !f.Bounded;
    m.Primitives.push_back(std::move(s));
  }
  if (unbounded && !m.HasBounds)
  {
    Fail("bounds",
      "required: the model has an unbounded primitive (plane, cylinder, cone, "
      "hyperboloid, paraboloid or polynomial)");
  }
}
// The deepest nesting of arrays and objects, counting brackets outside strings (for
// malformed text the count may be off, but the parser refuses that text anyway).
int NestingDepth(const std::string& text)
{
  int depth = 0, deepest = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i)
  {
    const char c = text[i];
    if (inString)
    {
      if (c == '\\')
      {
        ++i;
      }
      else if (c == '"')
      {
        inString = false;
      }
    }
    else if (c == '"')
    {
      inString = true;
    }
    else if (c == '[' || c == '{')
    {
      deepest = std::max(deepest, ++depth);
    }
    else if (c == ']' || c == '}')
    {
      --depth;
    }
  }
  return deepest;
}
}

bool ValidBounds(const double b[6])
{
  for (int i = 0; i < 3; ++i)
  {
    // The side must be finite too: [-1e308, 1e308] would give infinite spacings.
    if (!std::isfinite(b[2 * i + 1] - b[2 * i]) || !(b[2 * i] < b[2 * i + 1]))
    {
      return false;
    }
  }
  return true;
}

bool UnsetBounds(const double requested[6])
{
  return std::all_of(requested, requested + 6, [](double v) { return v == 0; });
}

bool TakeBounds(const double requested[6], const char* own, double bounds[6], std::string& error)
{
  if (!ValidBounds(requested))
  {
    error = std::string("bounds must be finite with x0 < x1, y0 < y1, z0 < z1 (or all zero "
                        "for the ") +
      own + ")";
    return false;
  }
  std::copy(requested, requested + 6, bounds);
  return true;
}

bool ParseModel(const std::string& text, Model& model, std::string& error)
{
  json j;
  try
  {
    // The depth is checked before parsing, not by a parser callback: nlohmann's
    // callback parser rescans an array at the end of each of its objects, which made
    // 10^5 primitives take seconds and 10^6 hang for minutes.
    if (NestingDepth(text) > MaxJsonDepth)
    {
      throw ModelError("JSON nested deeper than " + std::to_string(MaxJsonDepth) + " levels");
    }
    j = json::parse(text);
  }
  catch (const json::parse_error& e)
  {
    // e.byte is the offset; report line and column, which editors show.
    size_t line = 1, column = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i)
    {
      if (text[i] == '\n')
      {
        ++line;
        column = 1;
      }
      else
      {
        ++column;
      }
    }
    std::string what = e.what();
    const size_t colon = what.find("syntax error");
    error = "invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) +
      ": " + (colon != std::string::npos ? what.substr(colon) : what);
    return false;
  }
  catch (const ModelError& e)
  {
    error = e.what();
    return false;
  }
  catch (const json::out_of_range& e)
  {
    // A number beyond the double range ("1e999"): say where it is.
    std::string what = e.what();
    const size_t q1 = what.find('\''), q2 = what.rfind('\'');
    std::string where;
    if (q1 != std::string::npos && q2 > q1)
    {
      const size_t at = text.find(what.substr(q1 + 1, q2 - q1 - 1));
      if (at != std::string::npos)
      {
        size_t line = 1, column = 1;
        for (size_t i = 0; i < at; ++i)
        {
          column = text[i] == '\n' ? 1 : column + 1;
          line += text[i] == '\n';
        }
        where = " at line " + std::to_string(line) + ", column " + std::to_string(column);
      }
    }
    const size_t colon = what.find("number overflow");
    error = "invalid JSON" + where + ": " +
      (colon != std::string::npos ? what.substr(colon) : what) + " (numbers must be finite)";
    return false;
  }
  catch (const std::exception& e)
  {
    error = std::string("invalid JSON: ") + e.what();
    return false;
  }
  try
  {
    Model m;
    ParseTop(j, m);
    model = std::move(m);
    return true;
  }
  catch (const ModelError& e)
  {
    error = e.what();
    return false;
  }
  catch (const json::exception& e)
  {
    error = std::string("invalid model: ") + e.what();
    return false;
  }
}

std::string WriteModel(const Model& m)
{
  ojson j;
  j["pisurf"] = 1;
  if (!m.Name.empty())
    j["name"] = m.Name;
  if (!m.Description.empty())
    j["description"] = m.Description;
  j["blending"] = m.Blending;
  if (m.HasBounds)
    j["bounds"] = std::vector<double>(m.Bounds, m.Bounds + 6);
  if (!m.Parameters.empty())
  {
    ojson p = ojson::object();
    for (const auto& kv : m.Parameters)
      p[kv.first] = kv.second;
    j["parameters"] = p;
  }
  ojson prims = ojson::array();
  for (const PrimitiveSpec& s : m.Primitives)
  {
    ojson q;
    q["type"] = TypeKey(s.Type);
    if (!s.Name.empty())
      q["name"] = s.Name;
    q["center"] = std::vector<double>(s.Center, s.Center + 3);
    if (s.Orient == Orientation::Axis)
      q["axis"] = std::vector<double>(s.Axis, s.Axis + 3);
    else if (s.Orient == Orientation::Rotation)
      q["rotation"] = { { "axis", std::vector<double>(s.RotationAxis, s.RotationAxis + 3) },
        { "angle", s.RotationAngle } };
    for (const ParameterInfo& p : CatalogueEntry(s.Type).Parameters)
    {
      PrimitiveSpec& values = const_cast<PrimitiveSpec&>(s); // the accessors only read here
      if (p.Kind == ParameterKind::Integer)
        q[p.Key] = *p.Integer(values);
      else if (p.Kind == ParameterKind::Text)
        q[p.Key] = *p.Text(values);
      else if (p.Count == 1)
        q[p.Key] = *p.Numbers(values);
      else
        q[p.Key] = std::vector<double>(p.Numbers(values), p.Numbers(values) + p.Count);
    }
    if (s.Scale != 1.0)
      q["scale"] = s.Scale;
    if (s.Negate)
      q["negate"] = true;
    prims.push_back(q);
  }
  j["primitives"] = prims;
  return j.dump(2) + "\n";
}

std::string RenameParameter(
  const std::string& expression, const std::string& from, const std::string& to)
{
  auto isNameStart = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
  auto isNameChar = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  std::string out;
  size_t i = 0;
  while (i < expression.size())
  {
    const char c = expression[i];
    // Numbers first, so that the exponent of 2e5 is not read as a name.
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.')
    {
      size_t j = i;
      while (j < expression.size() &&
        (std::isdigit(static_cast<unsigned char>(expression[j])) || expression[j] == '.'))
        ++j;
      if (j < expression.size() && (expression[j] == 'e' || expression[j] == 'E'))
      {
        size_t k = j + 1;
        if (k < expression.size() && (expression[k] == '+' || expression[k] == '-'))
          ++k;
        if (k < expression.size() && std::isdigit(static_cast<unsigned char>(expression[k])))
        {
          j = k;
          while (j < expression.size() && std::isdigit(static_cast<unsigned char>(expression[j])))
            ++j;
        }
      }
      out.append(expression, i, j - i);
      i = j;
    }
    else if (isNameStart(c))
    {
      size_t j = i;
      while (j < expression.size() && isNameChar(expression[j]))
        ++j;
      const std::string name = expression.substr(i, j - i);
      out += name == from ? to : name;
      i = j;
    }
    else
    {
      out += c;
      ++i;
    }
  }
  return out;
}

bool MultiplyModels(
  const std::vector<Model>& models, double blending, Model& product, std::string& error)
{
  if (models.empty())
  {
    error = "the product has no factors: give it at least one input with a model";
    return false;
  }
  if (!std::isfinite(blending))
  {
    error = "the blending r must be a finite number";
    return false;
  }
  Model m;
  m.Blending = blending;
  bool anyUnbounded = false;
  for (size_t i = 0; i < models.size(); ++i)
  {
    const Model& in = models[i];
    if (in.Primitives.empty())
    {
      error = "model " + std::to_string(i + 1) + " has no primitives";
      return false;
    }
    // Renames of this model's parameters that clash with earlier ones.
    std::map<std::string, std::string> renamed;
    for (const auto& kv : in.Parameters)
    {
      auto it = m.Parameters.find(kv.first);
      if (it == m.Parameters.end())
      {
        m.Parameters[kv.first] = kv.second;
        continue;
      }
      if (it->second == kv.second)
        continue;
      std::string name;
      for (int n = 2;; ++n)
      {
        name = kv.first + "_" + std::to_string(n);
        if (!m.Parameters.count(name) && !in.Parameters.count(name))
          break;
      }
      m.Parameters[name] = kv.second;
      renamed[kv.first] = name;
    }
    bool unbounded = false;
    for (PrimitiveSpec s : in.Primitives)
    {
      for (const auto& r : renamed)
        s.Expression = RenameParameter(s.Expression, r.first, r.second);
      PolynomialFactor f;
      std::string why;
      if (!BuildFactor(s, m.Parameters, f, why))
      {
        error = "model " + std::to_string(i + 1) + ", primitive " +
          (s.Name.empty() ? std::to_string(m.Primitives.size() + 1) : "'" + s.Name + "'") + ": " +
          why;
        return false;
      }
      unbounded = unbounded || !f.Bounded;
      m.Primitives.push_back(std::move(s));
    }
    if (unbounded)
    {
      if (!in.HasBounds)
      {
        error = "model " + std::to_string(i + 1) + " has an unbounded primitive but no bounds";
        return false;
      }
      for (int a = 0; a < 3; ++a)
      {
        m.Bounds[2 * a] =
          anyUnbounded ? std::min(m.Bounds[2 * a], in.Bounds[2 * a]) : in.Bounds[2 * a];
        m.Bounds[2 * a + 1] =
          anyUnbounded ? std::max(m.Bounds[2 * a + 1], in.Bounds[2 * a + 1]) : in.Bounds[2 * a + 1];
      }
      anyUnbounded = true;
    }
  }
  m.HasBounds = anyUnbounded;
  if (m.Primitives.size() > MaxPrimitives)
  {
    error = "more than " + std::to_string(MaxPrimitives) + " primitives";
    return false;
  }
  product = std::move(m);
  return true;
}
}
