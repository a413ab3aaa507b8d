// SPDX-License-Identifier: BSD-3-Clause
#include "PiPrimitiveSpec.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace pisurf
{
namespace
{
struct TypeNames
{
  const char* Key;
  const char* Label;
};
const TypeNames Names[] = {
  { "sphere", "Sphere" },
  { "ellipsoid", "Ellipsoid" },
  { "superellipsoid", "Superellipsoid" },
  { "torus", "Torus" },
  { "plane", "Plane" },
  { "cylinder", "Cylinder" },
  { "cone", "Cone" },
  { "hyperboloid1", "Hyperboloid1" },
  { "hyperboloid2", "Hyperboloid2" },
  { "paraboloid", "Paraboloid" },
  { "hyperbolic_paraboloid", "HyperbolicParaboloid" },
  { "polynomial", "Polynomial" },
};

constexpr double Pi = 3.14159265358979323846;

bool Finite3(const double v[3])
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// |v| without overflow or underflow for extreme but finite components.
double Norm(const double v[3])
{
  const double m = std::max({ std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2]) });
  if (m == 0.0 || !std::isfinite(m))
  {
    return m;
  }
  const double x = v[0] / m, y = v[1] / m, z = v[2] / m;
  return m * std::sqrt(x * x + y * y + z * z);
}

// v / |v|, computed as (v / max|v_i|) / |v / max|v_i||, so that it never overflows.
void Unit(const double v[3], double u[3])
{
  const double m = std::max({ std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2]) });
  const double s[3] = { v[0] / m, v[1] / m, v[2] / m };
  const double n = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (int i = 0; i < 3; ++i)
  {
    u[i] = s[i] / n;
  }
}

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

// Rotation taking the unit vector a onto +z (the minimal one), so R·a = (0,0,1).
void AlignToZ(const double axis[3], double R[3][3])
{
  double a[3];
  Unit(axis, a);
  // Rotation about k = a × z by the angle between a and z.
  const double k[3] = { a[1], -a[0], 0.0 };
  const double s = Norm(k);
  const double c = a[2];
  if (s < 1e-15)
  {
    // Parallel or anti-parallel: identity or a half turn about x.
    const double sign = c > 0 ? 1.0 : -1.0;
    const double I[3][3] = { { 1, 0, 0 }, { 0, sign, 0 }, { 0, 0, sign } };
    std::copy(&I[0][0], &I[0][0] + 9, &R[0][0]);
    return;
  }
  RotationMatrix(k, std::atan2(s, c) * 180.0 / Pi, R);
}

bool Positive(double v, const char* what, std::string& error)
{
  if (!std::isfinite(v) || v <= 0.0)
  {
    error = std::string(what) + " must be a positive finite number";
    return false;
  }
  return true;
}
}

const char* TypeKey(PrimitiveType t)
{
  return Names[static_cast<int>(t)].Key;
}

const char* TypeLabel(PrimitiveType t)
{
  return Names[static_cast<int>(t)].Label;
}

bool TypeFromString(const std::string& s, PrimitiveType& t)
{
  for (int i = 0; i < static_cast<int>(PrimitiveType::NumberOfTypes); ++i)
  {
    if (s == Names[i].Key || s == Names[i].Label)
    {
      t = static_cast<PrimitiveType>(i);
      return true;
    }
  }
  return false;
}

void RotationMatrix(const double axis[3], double angleDeg, double R[3][3])
{
  double u[3];
  Unit(axis, u);
  const double x = u[0], y = u[1], z = u[2];
  const double th = angleDeg * Pi / 180.0;
  const double c = std::cos(th), s = std::sin(th), t = 1.0 - c;
  R[0][0] = t * x * x + c;
  R[0][1] = t * x * y - s * z;
  R[0][2] = t * x * z + s * y;
  R[1][0] = t * x * y + s * z;
  R[1][1] = t * y * y + c;
  R[1][2] = t * y * z - s * x;
  R[2][0] = t * x * z - s * y;
  R[2][1] = t * y * z + s * x;
  R[2][2] = t * z * z + c;
}


bool OrientationMatrix(const PrimitiveSpec& s, double R[3][3], std::string& error)
{
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      R[i][j] = i == j ? 1.0 : 0.0;
    }
  }
  if (s.Orient == Orientation::Axis)
  {
    if (!Finite3(s.Axis) || Norm(s.Axis) == 0.0)
    {
      error = "axis must be a non-zero vector of finite numbers";
      return false;
    }
    AlignToZ(s.Axis, R);
  }
  else if (s.Orient == Orientation::Rotation)
  {
    if (!Finite3(s.RotationAxis) || Norm(s.RotationAxis) == 0.0)
    {
      error = "rotation axis must be a non-zero vector of finite numbers";
      return false;
    }
    if (!std::isfinite(s.RotationAngle))
    {
      error = "rotation angle must be a finite number";
      return false;
    }
    double Rot[3][3];
    RotationMatrix(s.RotationAxis, s.RotationAngle, Rot);
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        R[i][j] = Rot[j][i]; // inverse of a rotation is its transpose
      }
    }
  }
  return true;
}

namespace
{
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
}

bool BuildFactor(const PrimitiveSpec& s, const ParameterMap& parameters,
  PolynomialFactor& factor, std::string& error)
{
  const int type = static_cast<int>(s.Type);
  if (type < 0 || type >= static_cast<int>(PrimitiveType::NumberOfTypes))
  {
    error = "unknown primitive type";
    return false;
  }
  if (!Finite3(s.Center))
  {
    error = "center must be three finite numbers";
    return false;
  }
  if (!std::isfinite(s.Scale) || s.Scale == 0.0)
  {
    error = "scale must be a non-zero finite number";
    return false;
  }

  // Orientation: local = R·(p − center).
  double R[3][3];
  if (!OrientationMatrix(s, R, error))
  {
    return false;
  }

  auto radii = [&](int n) {
    static const char* names[3] = { "radii[0]", "radii[1]", "radii[2]" };
    for (int i = 0; i < n; ++i)
    {
      if (!Positive(s.Radii[i], names[i], error))
      {
        return false;
      }
    }
    return true;
  };

  Polynomial3 p;
  std::shared_ptr<const ExpressionNode> natural;
  double shift[3] = { 0, 0, 0 }; // polynomials: the expression's variables are q + shift
  double half[3] = { -1, -1, -1 }; // local half extents; negative: unbounded
  switch (s.Type)
  {
    case PrimitiveType::Sphere:
      if (!Positive(s.Radius, "radius", error))
        return false;
      p = Var(0).Pow(2) + Var(1).Pow(2) + Var(2).Pow(2) - Const(s.Radius * s.Radius);
      half[0] = half[1] = half[2] = s.Radius;
      break;
    case PrimitiveType::Ellipsoid:
      if (!radii(3))
        return false;
      p = Sq(0, s.Radii[0]) + Sq(1, s.Radii[1]) + Sq(2, s.Radii[2]) - Const(1);
      std::copy(s.Radii, s.Radii + 3, half);
      break;
    case PrimitiveType::Superellipsoid:
      if (!radii(3))
        return false;
      if (s.Exponent < 2 || s.Exponent % 2 != 0 || s.Exponent > MaxDegree)
      {
        error = "exponent must be an even integer from 2 to " + std::to_string(MaxDegree) +
          " (got " + std::to_string(s.Exponent) + ")";
        return false;
      }
      p = Var(0).Scaled(1.0 / s.Radii[0]).Pow(s.Exponent) +
        Var(1).Scaled(1.0 / s.Radii[1]).Pow(s.Exponent) +
        Var(2).Scaled(1.0 / s.Radii[2]).Pow(s.Exponent) - Const(1);
      std::copy(s.Radii, s.Radii + 3, half);
      break;
    case PrimitiveType::Torus:
    {
      if (!Positive(s.MajorRadius, "major_radius", error) ||
        !Positive(s.MinorRadius, "minor_radius", error))
        return false;
      const double R2 = s.MajorRadius * s.MajorRadius, r2 = s.MinorRadius * s.MinorRadius;
      const Polynomial3 uv = Var(0).Pow(2) + Var(1).Pow(2);
      p = (uv + Var(2).Pow(2) + Const(R2 - r2)).Pow(2) - uv.Scaled(4.0 * R2);
      half[0] = half[1] = s.MajorRadius + s.MinorRadius;
      half[2] = s.MinorRadius;
      break;
    }
    case PrimitiveType::Plane:
    {
      if (!Finite3(s.Normal) || Norm(s.Normal) == 0.0)
      {
        error = "normal must be a non-zero vector of finite numbers";
        return false;
      }
      double n[3];
      Unit(s.Normal, n);
      p = Var(0).Scaled(n[0]) + Var(1).Scaled(n[1]) + Var(2).Scaled(n[2]);
      break;
    }
    case PrimitiveType::Cylinder:
      if (!Positive(s.Radius, "radius", error))
        return false;
      p = Var(0).Pow(2) + Var(1).Pow(2) - Const(s.Radius * s.Radius);
      break;
    case PrimitiveType::Cone:
    {
      if (!std::isfinite(s.Angle) || s.Angle <= 0.0 || s.Angle >= 90.0)
      {
        error = "angle must be a half-angle in degrees strictly between 0 and 90";
        return false;
      }
      const double t = std::tan(s.Angle * Pi / 180.0);
      p = Var(0).Pow(2) + Var(1).Pow(2) - Var(2).Pow(2).Scaled(t * t);
      break;
    }
    case PrimitiveType::Hyperboloid1:
      if (!radii(3))
        return false;
      p = Sq(0, s.Radii[0]) + Sq(1, s.Radii[1]) - Sq(2, s.Radii[2]) - Const(1);
      break;
    case PrimitiveType::Hyperboloid2:
      if (!radii(3))
        return false;
      p = Sq(2, s.Radii[2]) - Sq(0, s.Radii[0]) - Sq(1, s.Radii[1]) - Const(1);
      break;
    case PrimitiveType::Paraboloid:
      if (!radii(2))
        return false;
      p = Sq(0, s.Radii[0]) + Sq(1, s.Radii[1]) - Var(2);
      break;
    case PrimitiveType::HyperbolicParaboloid:
      if (!radii(2))
        return false;
      p = Sq(0, s.Radii[0]) - Sq(1, s.Radii[1]) - Var(2);
      break;
    case PrimitiveType::Polynomial:
    {
      std::string why;
      if (!ParseExpression(s.Expression, parameters, p, why, &natural))
      {
        error = "expression: " + why;
        return false;
      }
      CentreExpression(*natural, p, shift);
      break;
    }
    default:
      error = "unknown primitive type";
      return false;
  }
  p = p.Scaled(s.Negate ? -s.Scale : s.Scale);
  if (!p.IsFinite())
  {
    error = "the parameters (with the scale) overflow the polynomial's coefficients";
    return false;
  }

  factor = PolynomialFactor();
  factor.Poly = p;
  factor.Natural = natural;
  factor.NaturalSingleUse = natural && IsSingleUse(*natural);
  factor.NaturalScale = s.Negate ? -s.Scale : s.Scale;
  std::copy(&R[0][0], &R[0][0] + 9, &factor.A[0][0]);
  for (int i = 0; i < 3; ++i)
  {
    factor.B[i] = -(R[i][0] * s.Center[0] + R[i][1] * s.Center[1] + R[i][2] * s.Center[2]);
    // A centred expression: its local coordinates are the written ones minus the shift.
    if (shift[i] != 0.0)
    {
      factor.B[i] -= shift[i];
      factor.NaturalShift[i] = shift[i];
    }
  }
  if (half[0] >= 0.0)
  {
    // World box of the local box: p = center + Rᵀ·q, so each world half extent is
    // Σ_j |R[j][i]|·half[j].
    factor.Bounded = true;
    for (int i = 0; i < 3; ++i)
    {
      double h = 0.0;
      for (int j = 0; j < 3; ++j)
      {
        h += std::fabs(R[j][i]) * half[j];
      }
      factor.Bounds[2 * i] = s.Center[i] - h;
      factor.Bounds[2 * i + 1] = s.Center[i] + h;
    }
  }
  return true;
}
}
