// SPDX-License-Identifier: BSD-3-Clause
#include "PiPrimitiveSpec.h"

#include "PiPrimitiveCatalogue.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace pisurf
{
namespace
{
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

// Rotation taking the unit vector a onto +z (the minimal one), so R·a = (0,0,1).
void AlignToZ(const double axis[3], double R[3][3])
{
  double a[3];
  UnitVector(axis, a);
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

}

void UnitVector(const double v[3], double u[3])
{
  const double m = std::max({ std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2]) });
  const double s[3] = { v[0] / m, v[1] / m, v[2] / m };
  const double n = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (int i = 0; i < 3; ++i)
  {
    u[i] = s[i] / n;
  }
}

const char* TypeKey(PrimitiveType t)
{
  return CatalogueEntry(t).Key;
}

const char* TypeLabel(PrimitiveType t)
{
  return CatalogueEntry(t).Label;
}

bool TypeFromString(const std::string& s, PrimitiveType& t)
{
  for (const PrimitiveInfo& entry : PrimitiveCatalogue())
  {
    if (s == entry.Key || s == entry.Label)
    {
      t = entry.Type;
      return true;
    }
  }
  return false;
}

void RotationMatrix(const double axis[3], double angleDeg, double R[3][3])
{
  double u[3];
  UnitVector(axis, u);
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

bool BuildFactor(const PrimitiveSpec& s, const ParameterMap& parameters, PolynomialFactor& factor,
  std::string& error)
{
  if (!IsPrimitiveType(static_cast<int>(s.Type)))
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

  const PrimitiveInfo& entry = CatalogueEntry(s.Type);
  for (const ParameterInfo& parameter : entry.Parameters)
  {
    if (!CheckParameter(s, parameter, error))
    {
      return false;
    }
  }
  PrimitiveShape shape;
  if (!entry.Build(s, parameters, shape, error))
  {
    return false;
  }
  Polynomial3& p = shape.Poly;
  const std::shared_ptr<const ExpressionNode>& natural = shape.Natural;
  const double* shift = shape.Shift; // polynomials: the expression's variables are q + shift
  const double* half = shape.Half;   // local half extents; negative: unbounded
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
