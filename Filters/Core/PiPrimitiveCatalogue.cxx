// SPDX-License-Identifier: BSD-3-Clause
#include "PiPrimitiveCatalogue.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace pisurf
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

Polynomial3 Var(int a)
{
  return Polynomial3::Variable(a);
}
Polynomial3 Const(double c)
{
  return Polynomial3::Constant(c);
}
Polynomial3 Sq(int a, double s)
{ // (var/s)^2
  return Var(a).Pow(2).Scaled(1.0 / (s * s));
}

// --- The polynomials (Documentation/pisurf-format.md). Their parameters have passed
// their constraints; the builders only compute.

bool BuildSphere(const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  out.Poly = Var(0).Pow(2) + Var(1).Pow(2) + Var(2).Pow(2) - Const(s.Radius * s.Radius);
  out.Half[0] = out.Half[1] = out.Half[2] = s.Radius;
  return true;
}

bool BuildEllipsoid(const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  out.Poly = Sq(0, s.Radii[0]) + Sq(1, s.Radii[1]) + Sq(2, s.Radii[2]) - Const(1);
  std::copy(s.Radii, s.Radii + 3, out.Half);
  return true;
}

bool BuildSuperellipsoid(
  const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  out.Poly = Var(0).Scaled(1.0 / s.Radii[0]).Pow(s.Exponent) +
    Var(1).Scaled(1.0 / s.Radii[1]).Pow(s.Exponent) +
    Var(2).Scaled(1.0 / s.Radii[2]).Pow(s.Exponent) - Const(1);
  std::copy(s.Radii, s.Radii + 3, out.Half);
  return true;
}

bool BuildTorus(const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  const double R2 = s.MajorRadius * s.MajorRadius, r2 = s.MinorRadius * s.MinorRadius;
  const Polynomial3 uv = Var(0).Pow(2) + Var(1).Pow(2);
  out.Poly = (uv + Var(2).Pow(2) + Const(R2 - r2)).Pow(2) - uv.Scaled(4.0 * R2);
  out.Half[0] = out.Half[1] = s.MajorRadius + s.MinorRadius;
  out.Half[2] = s.MinorRadius;
  return true;
}

bool BuildPlane(const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  double n[3];
  UnitVector(s.Normal, n);
  out.Poly = Var(0).Scaled(n[0]) + Var(1).Scaled(n[1]) + Var(2).Scaled(n[2]);
  return true;
}

bool BuildCylinder(const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  out.Poly = Var(0).Pow(2) + Var(1).Pow(2) - Const(s.Radius * s.Radius);
  return true;
}

bool BuildCone(const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  const double t = std::tan(s.Angle * Pi / 180.0);
  out.Poly = Var(0).Pow(2) + Var(1).Pow(2) - Var(2).Pow(2).Scaled(t * t);
  return true;
}

bool BuildHyperboloid1(
  const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  out.Poly = Sq(0, s.Radii[0]) + Sq(1, s.Radii[1]) - Sq(2, s.Radii[2]) - Const(1);
  return true;
}

bool BuildHyperboloid2(
  const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  out.Poly = Sq(2, s.Radii[2]) - Sq(0, s.Radii[0]) - Sq(1, s.Radii[1]) - Const(1);
  return true;
}

bool BuildParaboloid(const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  out.Poly = Sq(0, s.Radii[0]) + Sq(1, s.Radii[1]) - Var(2);
  return true;
}

bool BuildHyperbolicParaboloid(
  const PrimitiveSpec& s, const ParameterMap&, PrimitiveShape& out, std::string&)
{
  out.Poly = Sq(0, s.Radii[0]) - Sq(1, s.Radii[1]) - Var(2);
  return true;
}

// A polynomial written about a point other than the origin (the cup's handle,
// ((x − 2.2)² + (z + 1)² + y² + 0.49)² − 2((x − 2.2)² + (z + 1)²)) expands to many more
// terms than about that point (35 instead of 10), and every evaluation pays for each.
// Per axis, the shift σ that removes the pure x^(m−1) term (m the highest power of x,
// present alone) centres it: σ = −c(m−1)/(m·c(m)). The expression as written is then
// expanded again in q + σ (ExpandShifted: shifts that cancel symbolically cancel
// exactly), and that form is kept if it has fewer terms.
void CentreExpression(const ExpressionNode& tree, Polynomial3& p, double shift[3])
{
  double sigma[3] = { 0, 0, 0 };
  bool any = false;
  for (int a = 0; a < 3; ++a)
  {
    const int m = p.GetAxisDegree(a);
    if (m < 2)
    {
      continue;
    }
    int top[3] = { 0, 0, 0 }, next[3] = { 0, 0, 0 };
    top[a] = m;
    next[a] = m - 1;
    const double cm = p.GetCoefficient(top[0], top[1], top[2]);
    const double cn = p.GetCoefficient(next[0], next[1], next[2]);
    const double s = cm != 0.0 ? -cn / (m * cm) : 0.0;
    if (s != 0.0 && std::isfinite(s))
    {
      sigma[a] = s;
      any = true;
    }
  }
  Polynomial3 centred;
  if (!any || !ExpandShifted(tree, sigma, centred) ||
    centred.GetTerms().size() >= p.GetTerms().size())
  {
    return;
  }
  p = centred;
  std::copy(sigma, sigma + 3, shift);
}

bool BuildPolynomial(
  const PrimitiveSpec& s, const ParameterMap& parameters, PrimitiveShape& out, std::string& error)
{
  std::string why;
  if (!ParseExpression(s.Expression, parameters, out.Poly, why, &out.Natural))
  {
    error = "expression: " + why;
    return false;
  }
  CentreExpression(*out.Natural, out.Poly, out.Shift);
  return true;
}

// --- The parameters. One constant per (key, count) that several types share.

double* RadiusOf(PrimitiveSpec& s)
{
  return &s.Radius;
}
double* RadiiOf(PrimitiveSpec& s)
{
  return s.Radii;
}
double* MajorRadiusOf(PrimitiveSpec& s)
{
  return &s.MajorRadius;
}
double* MinorRadiusOf(PrimitiveSpec& s)
{
  return &s.MinorRadius;
}
int* ExponentOf(PrimitiveSpec& s)
{
  return &s.Exponent;
}
double* NormalOf(PrimitiveSpec& s)
{
  return s.Normal;
}
double* AngleOf(PrimitiveSpec& s)
{
  return &s.Angle;
}
std::string* ExpressionOf(PrimitiveSpec& s)
{
  return &s.Expression;
}

using K = ParameterKind;
using C = Constraint;

const ParameterInfo Radius = { "radius", "Radius", K::Number, 1, { 1, 0, 0 }, nullptr, C::Positive,
  "Radius R", "R", "length", "Positive radius.", RadiusOf, nullptr, nullptr };
const ParameterInfo Radii3 = { "radii", "Radii", K::Number, 3, { 1, 1, 1 }, nullptr, C::Positive,
  "Semi-axes a, b, c", "a b c", "length", "Three positive semi-axes.", RadiiOf, nullptr, nullptr };
const ParameterInfo Radii2 = { "radii", "Radii", K::Number, 2, { 1, 1, 1 }, nullptr, C::Positive,
  "Semi-axes a, b", "a b", "length", "Two positive semi-axes.", RadiiOf, nullptr, nullptr };
const ParameterInfo Exponent = { "exponent", "Exponent", K::Integer, 1, { 4, 0, 0 }, nullptr,
  C::EvenExponent, "Exponent n (even integer)", "n", "", "An even integer, at least 2.", nullptr,
  ExponentOf, nullptr };
const ParameterInfo MajorRadius = { "major_radius", "MajorRadius", K::Number, 1, { 1, 0, 0 },
  nullptr, C::Positive, "Major radius R", "R", "length",
  "Distance from the centre to the tube's axis (positive).", MajorRadiusOf, nullptr, nullptr };
const ParameterInfo MinorRadius = { "minor_radius", "MinorRadius", K::Number, 1, { 0.25, 0, 0 },
  nullptr, C::Positive, "Minor radius \u03c1", "\u03c1", "length", "Radius of the tube (positive).",
  MinorRadiusOf, nullptr, nullptr };
const ParameterInfo Normal = { "normal", "Normal", K::Number, 3, { 0, 0, 1 }, nullptr,
  C::NonZeroVector, "Normal (x, y, z)", "n", "",
  "Normal direction (not zero); the plane passes through the centre.", NormalOf, nullptr, nullptr };
const ParameterInfo Angle = { "angle", "Angle", K::Number, 1, { 30, 0, 0 }, nullptr,
  C::OpenRightAngle, "Half-angle \u03b8", "\u03b8", "degrees",
  "Between 0 and 90 degrees, exclusive.", AngleOf, nullptr, nullptr };
// A new polynomial starts as the unit sphere (vtkPiPrimitive's Expression starts empty,
// as the XML's: a Polynomial needs one typed).
const ParameterInfo Expression = { "expression", "Expression", K::Text, 1, { 0, 0, 0 },
  "x^2 + y^2 + z^2 - 1", C::Expression, "Expression in x, y, z", nullptr, "",
  "A polynomial in the local coordinates x, y, z and the model's parameters.", nullptr, nullptr,
  ExpressionOf };

using T = PrimitiveType;
using W = WidgetKind;

const std::vector<PrimitiveInfo>& Entries()
{
  static const std::vector<PrimitiveInfo> entries = {
    { T::Sphere, "sphere", "Sphere", { Radius }, true, BuildSphere, W::Sphere, "Radius", nullptr },
    { T::Ellipsoid, "ellipsoid", "Ellipsoid", { Radii3 }, true, BuildEllipsoid, W::Box, "Radii",
      nullptr },
    { T::Superellipsoid, "superellipsoid", "Superellipsoid", { Radii3, Exponent }, true,
      BuildSuperellipsoid, W::Box, "Radii", nullptr },
    { T::Torus, "torus", "Torus", { MajorRadius, MinorRadius }, true, BuildTorus, W::Cylinder,
      "MajorRadius", "Axis" },
    { T::Plane, "plane", "Plane", { Normal }, false, BuildPlane, W::Plane, nullptr, "Normal" },
    { T::Cylinder, "cylinder", "Cylinder", { Radius }, false, BuildCylinder, W::Cylinder, "Radius",
      "Axis" },
    { T::Cone, "cone", "Cone", { Angle }, false, BuildCone, W::Plane, nullptr, "Axis" },
    { T::Hyperboloid1, "hyperboloid1", "Hyperboloid1", { Radii3 }, false, BuildHyperboloid1, W::Box,
      "Radii", nullptr },
    { T::Hyperboloid2, "hyperboloid2", "Hyperboloid2", { Radii3 }, false, BuildHyperboloid2, W::Box,
      "Radii", nullptr },
    { T::Paraboloid, "paraboloid", "Paraboloid", { Radii2 }, false, BuildParaboloid, W::Box,
      "Radii", nullptr },
    { T::HyperbolicParaboloid, "hyperbolic_paraboloid", "HyperbolicParaboloid", { Radii2 }, false,
      BuildHyperbolicParaboloid, W::Box, "Radii", nullptr },
    { T::Polynomial, "polynomial", "Polynomial", { Expression }, false, BuildPolynomial, W::Handle,
      nullptr, nullptr },
  };
  return entries;
}

const char* KindName(ParameterKind k)
{
  switch (k)
  {
    case K::Number:
      return "number";
    case K::Integer:
      return "integer";
    default:
      return "text";
  }
}

const char* WidgetName(WidgetKind w)
{
  switch (w)
  {
    case W::Sphere:
      return "sphere";
    case W::Cylinder:
      return "cylinder";
    case W::Plane:
      return "plane";
    case W::Box:
      return "box";
    default:
      return "handle";
  }
}
}

const std::vector<PrimitiveInfo>& PrimitiveCatalogue()
{
  return Entries();
}

const PrimitiveInfo& CatalogueEntry(PrimitiveType t)
{
  return Entries()[static_cast<size_t>(t)];
}

bool IsPrimitiveType(int t)
{
  return t >= 0 && static_cast<size_t>(t) < Entries().size();
}

const ParameterInfo* FindParameter(const PrimitiveInfo& entry, const std::string& name)
{
  for (const ParameterInfo& p : entry.Parameters)
  {
    if (name == p.Key || name == p.Property)
    {
      return &p;
    }
  }
  return nullptr;
}

std::string ConstraintText(Constraint rule)
{
  switch (rule)
  {
    case C::Positive:
      return "a positive finite number";
    case C::NonZeroVector:
      return "a non-zero vector of finite numbers";
    case C::EvenExponent:
      return "an even integer from 2 to " + std::to_string(MaxDegree);
    case C::OpenRightAngle:
      return "a half-angle in degrees strictly between 0 and 90";
    default:
      return "a polynomial expression";
  }
}

bool Allows(Constraint rule, double v)
{
  switch (rule)
  {
    case C::Positive:
      return std::isfinite(v) && v > 0.0;
    case C::NonZeroVector:
      return std::isfinite(v);
    case C::EvenExponent:
      return v == std::floor(v) && v >= 2 && v <= MaxDegree && static_cast<int>(v) % 2 == 0;
    case C::OpenRightAngle:
      return std::isfinite(v) && v > 0.0 && v < 90.0;
    default:
      return true;
  }
}

bool CheckParameter(const PrimitiveSpec& spec, const ParameterInfo& p, std::string& error)
{
  PrimitiveSpec& s = const_cast<PrimitiveSpec&>(spec); // the accessors only read here
  if (p.Kind == K::Integer)
  {
    const int v = *p.Integer(s);
    if (!Allows(p.Rule, v))
    {
      error = std::string(p.Key) + " must be " + ConstraintText(p.Rule) + " (got " +
        std::to_string(v) + ")";
      return false;
    }
    return true;
  }
  if (p.Kind == K::Text)
  {
    return true; // the builder parses the expression and says what is wrong
  }
  const double* v = p.Numbers(s);
  if (p.Rule == C::NonZeroVector)
  {
    bool finite = true, zero = true;
    for (int i = 0; i < p.Count; ++i)
    {
      finite = finite && std::isfinite(v[i]);
      zero = zero && v[i] == 0.0;
    }
    if (!finite || zero)
    {
      error = std::string(p.Key) + " must be " + ConstraintText(p.Rule);
      return false;
    }
    return true;
  }
  for (int i = 0; i < p.Count; ++i)
  {
    if (!Allows(p.Rule, v[i]))
    {
      error = std::string(p.Key) + (p.Count == 1 ? "" : "[" + std::to_string(i) + "]") +
        " must be " + ConstraintText(p.Rule);
      return false;
    }
  }
  return true;
}

void SetDefault(PrimitiveSpec& s, const ParameterInfo& p)
{
  switch (p.Kind)
  {
    case K::Number:
      std::copy(p.Default, p.Default + p.Count, p.Numbers(s));
      break;
    case K::Integer:
      *p.Integer(s) = static_cast<int>(p.Default[0]);
      break;
    case K::Text:
      *p.Text(s) = p.DefaultText ? p.DefaultText : "";
      break;
  }
}

PrimitiveSpec DefaultPrimitive(PrimitiveType t)
{
  PrimitiveSpec s;
  s.Type = t;
  for (const ParameterInfo& p : CatalogueEntry(t).Parameters)
  {
    SetDefault(s, p);
  }
  return s;
}

std::string CatalogueJSON()
{
  using ojson = nlohmann::ordered_json;
  auto orNull = [](const char* text) { return text ? ojson(text) : ojson(nullptr); };
  ojson all = ojson::array();
  for (const PrimitiveInfo& e : Entries())
  {
    ojson parameters = ojson::array();
    for (const ParameterInfo& p : e.Parameters)
    {
      ojson q;
      q["key"] = p.Key;
      q["property"] = p.Property;
      q["kind"] = KindName(p.Kind);
      q["count"] = p.Count;
      if (p.Kind == K::Text)
        q["default"] = p.DefaultText ? p.DefaultText : "";
      else
        q["default"] = std::vector<double>(p.Default, p.Default + p.Count);
      q["constraint"] = ConstraintText(p.Rule);
      q["label"] = p.Label;
      q["unit"] = p.Unit;
      q["tooltip"] = p.Tooltip;
      parameters.push_back(q);
    }
    ojson j;
    j["type"] = static_cast<int>(e.Type);
    j["key"] = e.Key;
    j["label"] = e.Label;
    j["bounded"] = e.Bounded;
    j["widget"] = WidgetName(e.Widget);
    j["widget_size"] = orNull(e.WidgetSize);
    j["widget_direction"] = orNull(e.WidgetDirection);
    j["parameters"] = parameters;
    all.push_back(j);
  }
  return all.dump(1);
}
}
