// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the primitives: BuildFactor, PolynomialFactor, RotationMatrix and the
// type names (PiPrimitiveSpec.h).
#include "PiCoreTestUtilities.h"
#include "PiPrimitiveSpec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

using namespace pisurf;
using namespace pisurf_test;

namespace
{
constexpr double Pi = 3.14159265358979323846;
using Closed = std::function<double(const double q[3])>;

/// The canonical polynomial of PiPrimitiveSpec.h in local coordinates, written directly
/// from the table (independent of BuildFactor).
Closed ClosedForm(const PrimitiveSpec& s)
{
  const double R = s.Radius;
  const double a = s.Radii[0], b = s.Radii[1], c = s.Radii[2];
  switch (s.Type)
  {
    case PrimitiveType::Sphere:
      return [=](const double* q) { return q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - R * R; };
    case PrimitiveType::Ellipsoid:
      return [=](const double* q)
      { return (q[0] / a) * (q[0] / a) + (q[1] / b) * (q[1] / b) + (q[2] / c) * (q[2] / c) - 1; };
    case PrimitiveType::Superellipsoid:
    {
      const int n = s.Exponent;
      return [=](const double* q)
      { return std::pow(q[0] / a, n) + std::pow(q[1] / b, n) + std::pow(q[2] / c, n) - 1; };
    }
    case PrimitiveType::Torus:
    {
      const double M = s.MajorRadius, m = s.MinorRadius;
      return [=](const double* q)
      {
        const double uv = q[0] * q[0] + q[1] * q[1];
        const double t = uv + q[2] * q[2] + M * M - m * m;
        return t * t - 4 * M * M * uv;
      };
    }
    case PrimitiveType::Plane:
    {
      const double n = std::sqrt(
        s.Normal[0] * s.Normal[0] + s.Normal[1] * s.Normal[1] + s.Normal[2] * s.Normal[2]);
      const double nx = s.Normal[0] / n, ny = s.Normal[1] / n, nz = s.Normal[2] / n;
      return [=](const double* q) { return nx * q[0] + ny * q[1] + nz * q[2]; };
    }
    case PrimitiveType::Cylinder:
      return [=](const double* q) { return q[0] * q[0] + q[1] * q[1] - R * R; };
    case PrimitiveType::Cone:
    {
      const double t = std::tan(s.Angle * Pi / 180.0);
      return [=](const double* q) { return q[0] * q[0] + q[1] * q[1] - t * t * q[2] * q[2]; };
    }
    case PrimitiveType::Hyperboloid1:
      return [=](const double* q)
      { return (q[0] / a) * (q[0] / a) + (q[1] / b) * (q[1] / b) - (q[2] / c) * (q[2] / c) - 1; };
    case PrimitiveType::Hyperboloid2:
      return [=](const double* q)
      { return (q[2] / c) * (q[2] / c) - (q[0] / a) * (q[0] / a) - (q[1] / b) * (q[1] / b) - 1; };
    case PrimitiveType::Paraboloid:
      return [=](const double* q)
      { return (q[0] / a) * (q[0] / a) + (q[1] / b) * (q[1] / b) - q[2]; };
    case PrimitiveType::HyperbolicParaboloid:
      return [=](const double* q)
      { return (q[0] / a) * (q[0] / a) - (q[1] / b) * (q[1] / b) - q[2]; };
    case PrimitiveType::Polynomial:
      // Only for the expression used below.
      return [=](const double* q) {
        return q[0] * q[0] * q[0] - 2 * q[0] * q[1] * q[2] + q[2] * q[2] * q[1] - 0.5 + 1.5 * q[1];
      };
    default:
      return nullptr;
  }
}
const char* TestExpression = "x^3 - 2*x*y*z + z^2*y - 0.5 + k*y";
const ParameterMap TestParameters = { { "k", 1.5 } };

/// A spec of the given type with random parameters (and default placement).
PrimitiveSpec RandomSpec(PrimitiveType t, Random& rng)
{
  PrimitiveSpec s;
  s.Type = t;
  s.Radius = rng.Uniform(0.5, 2.0);
  for (double& r : s.Radii)
  {
    r = rng.Uniform(0.5, 2.0);
  }
  s.MajorRadius = rng.Uniform(1.0, 2.0);
  s.MinorRadius = rng.Uniform(0.2, 0.8);
  s.Exponent = 2 * rng.Integer(1, 3);
  for (double& n : s.Normal)
  {
    n = rng.Uniform(-2.0, 2.0);
  }
  s.Angle = rng.Uniform(5.0, 80.0);
  s.Expression = TestExpression;
  return s;
}

/// Right-handed rotation by angle about axis (Rodrigues), written independently.
void Rodrigues(const double axis[3], double angleDeg, double M[3][3])
{
  const double n = std::hypot(axis[0], axis[1], axis[2]);
  const double k[3] = { axis[0] / n, axis[1] / n, axis[2] / n };
  const double th = angleDeg * Pi / 180.0;
  // M = I + sin·K + (1 − cos)·K², K the cross-product matrix of k.
  const double K[3][3] = { { 0, -k[2], k[1] }, { k[2], 0, -k[0] }, { -k[1], k[0], 0 } };
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      double k2 = 0.0;
      for (int l = 0; l < 3; ++l)
      {
        k2 += K[i][l] * K[l][j];
      }
      M[i][j] = (i == j ? 1.0 : 0.0) + std::sin(th) * K[i][j] + (1 - std::cos(th)) * k2;
    }
  }
}

/// Σ|c|·|q|^pow of the factor's local polynomial: the rounding scale of a value.
double ValueScale(const PolynomialFactor& f, const double p[3])
{
  double q[3];
  f.ToLocal(p, q);
  double v = 0.0;
  for (const auto& t : f.Poly.GetTerms())
  {
    v += std::fabs(t.Coefficient) * std::pow(std::fabs(q[0]) + 1, t.I) *
      std::pow(std::fabs(q[1]) + 1, t.J) * std::pow(std::fabs(q[2]) + 1, t.K);
  }
  return std::max(1.0, v);
}

PolynomialFactor Build(const PrimitiveSpec& s, const ParameterMap& params = TestParameters)
{
  PolynomialFactor f;
  std::string error;
  EXPECT_TRUE(BuildFactor(s, params, f, error)) << TypeKey(s.Type) << ": " << error;
  return f;
}

/// Expects BuildFactor to fail with every fragment in the message.
void ExpectBuildError(const PrimitiveSpec& s, const std::vector<std::string>& fragments,
  const ParameterMap& params = TestParameters)
{
  PolynomialFactor f;
  std::string error;
  EXPECT_FALSE(BuildFactor(s, params, f, error)) << TypeKey(s.Type) << " was accepted";
  EXPECT_TRUE(HasFragments(error, fragments)) << TypeKey(s.Type);
}

/// Compares the factor with `sign`·closed(local(p)) (values and gradients) at random points.
void CompareWithClosedForm(const PolynomialFactor& f, const Closed& closed,
  const std::function<void(const double*, double*)>& local, double sign, Random& rng,
  const std::string& what)
{
  auto world = [&](const double* p)
  {
    double q[3];
    local(p, q);
    return sign * closed(q);
  };
  for (int n = 0; n < 25; ++n)
  {
    const Point p = rng.InBox(-3, 3);
    const double scale = ValueScale(f, p.data());
    const double expected = world(p.data());
    EXPECT_TRUE(Near(f.Evaluate(p.data()), expected, 1e-12 * scale)) << what;
    double g[3];
    const double v = f.EvaluateWithGradient(p.data(), g);
    EXPECT_TRUE(Near(v, expected, 1e-12 * scale)) << what;
    const Point fd = FiniteDifferenceGradient(world, p.data(), 1e-5);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_TRUE(Near(g[k], fd[k], 1e-6 * scale)) << what << ": gradient component " << k;
    }
    // The world polynomial (for export) is the same function.
    EXPECT_TRUE(Near(f.WorldPolynomial().Evaluate(p.data()), expected, 1e-11 * scale)) << what;
  }
}

bool IsBoundedType(PrimitiveType t)
{
  return t == PrimitiveType::Sphere || t == PrimitiveType::Ellipsoid ||
    t == PrimitiveType::Superellipsoid || t == PrimitiveType::Torus;
}

const PrimitiveType AllTypes[] = { PrimitiveType::Sphere, PrimitiveType::Ellipsoid,
  PrimitiveType::Superellipsoid, PrimitiveType::Torus, PrimitiveType::Plane,
  PrimitiveType::Cylinder, PrimitiveType::Cone, PrimitiveType::Hyperboloid1,
  PrimitiveType::Hyperboloid2, PrimitiveType::Paraboloid, PrimitiveType::HyperbolicParaboloid,
  PrimitiveType::Polynomial };
}

TEST(PrimitiveSpec, TypeNames)
{
  static_assert(
    sizeof(AllTypes) / sizeof(AllTypes[0]) == static_cast<size_t>(PrimitiveType::NumberOfTypes),
    "every type is tested");
  const char* keys[] = { "sphere", "ellipsoid", "superellipsoid", "torus", "plane", "cylinder",
    "cone", "hyperboloid1", "hyperboloid2", "paraboloid", "hyperbolic_paraboloid", "polynomial" };
  const char* labels[] = { "Sphere", "Ellipsoid", "Superellipsoid", "Torus", "Plane", "Cylinder",
    "Cone", "Hyperboloid1", "Hyperboloid2", "Paraboloid", "HyperbolicParaboloid", "Polynomial" };
  for (int i = 0; i < 12; ++i)
  {
    const PrimitiveType t = AllTypes[i];
    EXPECT_STREQ(TypeKey(t), keys[i]);
    EXPECT_STREQ(TypeLabel(t), labels[i]);
    PrimitiveType back = PrimitiveType::NumberOfTypes;
    EXPECT_TRUE(TypeFromString(keys[i], back));
    EXPECT_EQ(back, t);
    back = PrimitiveType::NumberOfTypes;
    EXPECT_TRUE(TypeFromString(labels[i], back));
    EXPECT_EQ(back, t);
  }
  PrimitiveType t = PrimitiveType::Cone;
  EXPECT_FALSE(TypeFromString("cube", t));
  EXPECT_FALSE(TypeFromString("SPHERE", t));
  EXPECT_FALSE(TypeFromString("", t));
  EXPECT_EQ(t, PrimitiveType::Cone) << "unchanged when unknown";
}

TEST(PrimitiveSpec, EveryTypeMatchesItsClosedFormAtTheOrigin)
{
  Random rng(21);
  for (PrimitiveType t : AllTypes)
  {
    for (int trial = 0; trial < 4; ++trial)
    {
      const PrimitiveSpec s = RandomSpec(t, rng);
      const PolynomialFactor f = Build(s);
      CompareWithClosedForm(
        f, ClosedForm(s),
        [](const double* p, double* q)
        {
          q[0] = p[0];
          q[1] = p[1];
          q[2] = p[2];
        },
        1.0, rng, TypeKey(t));
    }
  }
}

TEST(PrimitiveSpec, EveryTypeMatchesItsClosedFormWithCenterScaleAndNegate)
{
  Random rng(22);
  for (PrimitiveType t : AllTypes)
  {
    for (int trial = 0; trial < 4; ++trial)
    {
      PrimitiveSpec s = RandomSpec(t, rng);
      const Point c = rng.InBox(-1, 1);
      std::copy(c.begin(), c.end(), s.Center);
      s.Scale = rng.Uniform(0.2, 3.0) * (trial % 2 ? -1 : 1);
      s.Negate = trial >= 2;
      const PolynomialFactor f = Build(s);
      CompareWithClosedForm(
        f, ClosedForm(s),
        [c](const double* p, double* q)
        {
          for (int i = 0; i < 3; ++i)
            q[i] = p[i] - c[i];
        },
        s.Scale * (s.Negate ? -1.0 : 1.0), rng, TypeKey(t));
    }
  }
}

TEST(PrimitiveSpec, EveryTypeMatchesItsClosedFormUnderRotation)
{
  Random rng(23);
  for (PrimitiveType t : AllTypes)
  {
    for (int trial = 0; trial < 4; ++trial)
    {
      PrimitiveSpec s = RandomSpec(t, rng);
      const Point c = rng.InBox(-1, 1);
      std::copy(c.begin(), c.end(), s.Center);
      s.Orient = Orientation::Rotation;
      const Point axis = rng.InBox(-1, 1);
      std::copy(axis.begin(), axis.end(), s.RotationAxis);
      s.RotationAngle = rng.Uniform(-360, 360);
      double M[3][3];
      Rodrigues(s.RotationAxis, s.RotationAngle, M);
      // world = center + M·local, so local = Mᵀ·(p − center).
      const PolynomialFactor f = Build(s);
      CompareWithClosedForm(
        f, ClosedForm(s),
        [&](const double* p, double* q)
        {
          for (int i = 0; i < 3; ++i)
          {
            q[i] = M[0][i] * (p[0] - c[0]) + M[1][i] * (p[1] - c[1]) + M[2][i] * (p[2] - c[2]);
          }
        },
        1.0, rng, TypeKey(t));
    }
  }
}

TEST(PrimitiveSpec, AxisOrientationPutsWAlongTheAxis)
{
  Random rng(24);
  const double axes[][3] = { { 0, 0, 1 }, { 0, 0, -1 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 },
    { -1, 2, 3 }, { 0.3, -0.2, -5 }, { 1e-9, 0, 1 } };
  for (const auto& a : axes)
  {
    PrimitiveSpec s = RandomSpec(PrimitiveType::Paraboloid, rng);
    s.Orient = Orientation::Axis;
    std::copy(a, a + 3, s.Axis);
    const Point c = rng.InBox(-1, 1);
    std::copy(c.begin(), c.end(), s.Center);
    const PolynomialFactor f = Build(s);
    const double n = std::hypot(a[0], a[1], a[2]);
    const double u[3] = { a[0] / n, a[1] / n, a[2] / n };
    // A is a proper rotation with A·â = +z.
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        double d = 0.0;
        for (int k = 0; k < 3; ++k)
          d += f.A[i][k] * f.A[j][k];
        EXPECT_NEAR(d, i == j ? 1.0 : 0.0, 1e-14)
          << "A·Aᵀ for axis " << a[0] << " " << a[1] << " " << a[2];
      }
      EXPECT_NEAR(
        f.A[i][0] * u[0] + f.A[i][1] * u[1] + f.A[i][2] * u[2], i == 2 ? 1.0 : 0.0, 1e-14);
      // B = −A·center.
      EXPECT_NEAR(f.B[i], -(f.A[i][0] * c[0] + f.A[i][1] * c[1] + f.A[i][2] * c[2]), 1e-14);
    }
    const double det = f.A[0][0] * (f.A[1][1] * f.A[2][2] - f.A[1][2] * f.A[2][1]) -
      f.A[0][1] * (f.A[1][0] * f.A[2][2] - f.A[1][2] * f.A[2][0]) +
      f.A[0][2] * (f.A[1][0] * f.A[2][1] - f.A[1][1] * f.A[2][0]);
    EXPECT_NEAR(det, 1.0, 1e-14);
  }
  // The default orientation and an axis along +z are the identity.
  const PolynomialFactor f = Build(RandomSpec(PrimitiveType::Cone, rng));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_EQ(f.A[i][j], i == j ? 1.0 : 0.0);
}

TEST(PrimitiveSpec, AxiallySymmetricTypesAlongAnArbitraryAxis)
{
  // With w = (p − c)·â and u² + v² = |p − c|² − w², the rotationally symmetric types
  // have closed forms that do not depend on the choice of u and v.
  Random rng(25);
  for (int trial = 0; trial < 8; ++trial)
  {
    const Point a = rng.InBox(-1, 1);
    const Point c = rng.InBox(-1, 1);
    const double n = std::hypot(a[0], a[1], a[2]);
    const Point ah = { a[0] / n, a[1] / n, a[2] / n };
    auto wOf = [&](const double* p)
    { return (p[0] - c[0]) * ah[0] + (p[1] - c[1]) * ah[1] + (p[2] - c[2]) * ah[2]; };
    auto rho2 = [&](const double* p)
    {
      const double d2 = (p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) +
        (p[2] - c[2]) * (p[2] - c[2]);
      const double w = wOf(p);
      return d2 - w * w;
    };
    for (PrimitiveType t : { PrimitiveType::Cylinder, PrimitiveType::Cone, PrimitiveType::Torus,
           PrimitiveType::Paraboloid, PrimitiveType::Hyperboloid1, PrimitiveType::Hyperboloid2 })
    {
      PrimitiveSpec s = RandomSpec(t, rng);
      s.Radii[1] = s.Radii[0]; // symmetric about w
      s.Orient = Orientation::Axis;
      std::copy(a.begin(), a.end(), s.Axis);
      std::copy(c.begin(), c.end(), s.Center);
      const Closed closed = ClosedForm(s);
      const PolynomialFactor f = Build(s);
      CompareWithClosedForm(
        f, closed,
        [&](const double* p, double* q)
        {
          q[0] = std::sqrt(std::max(0.0, rho2(p)));
          q[1] = 0.0;
          q[2] = wOf(p);
        },
        1.0, rng, TypeKey(t));
    }
  }
}

TEST(PrimitiveSpec, CylinderAlongYIsXSquaredPlusZSquared)
{
  PrimitiveSpec s;
  s.Type = PrimitiveType::Cylinder;
  s.Radius = 1.5;
  s.Orient = Orientation::Axis;
  s.Axis[0] = 0;
  s.Axis[1] = 3; // need not be unit
  s.Axis[2] = 0;
  const PolynomialFactor f = Build(s);
  const Polynomial3 w = f.WorldPolynomial();
  Polynomial3 expected;
  expected.AddTerm(1, 2, 0, 0);
  expected.AddTerm(1, 0, 0, 2);
  expected.AddTerm(-2.25, 0, 0, 0);
  EXPECT_TRUE(SameTermsNear(w, expected, 1e-15));
  Random rng(26);
  for (int n = 0; n < 20; ++n)
  {
    const Point p = rng.InBox(-3, 3);
    EXPECT_TRUE(Near(f.Evaluate(p.data()), p[0] * p[0] + p[2] * p[2] - 2.25, 1e-14));
  }
  EXPECT_FALSE(f.Bounded);
}

TEST(PrimitiveSpec, QuarterTurnAboutZMapsLocalUToWorldY)
{
  // Ellipsoid with semi-axes (3, 1, 0.5) turned 90° about z: its long axis is world y.
  PrimitiveSpec s;
  s.Type = PrimitiveType::Ellipsoid;
  s.Radii[0] = 3;
  s.Radii[1] = 1;
  s.Radii[2] = 0.5;
  s.Center[0] = 1;
  s.Center[1] = 2;
  s.Center[2] = 3;
  s.Orient = Orientation::Rotation;
  s.RotationAxis[2] = 1;
  s.RotationAngle = 90;
  const PolynomialFactor f = Build(s);
  const double onY[3] = { 1, 2 + 3, 3 }, onMinusY[3] = { 1, 2 - 3, 3 };
  const double onX[3] = { 1 + 1, 2, 3 }, onZ[3] = { 1, 2, 3 + 0.5 };
  const double farX[3] = { 1 + 3, 2, 3 };
  EXPECT_NEAR(f.Evaluate(onY), 0.0, 1e-14);
  EXPECT_NEAR(f.Evaluate(onMinusY), 0.0, 1e-14);
  EXPECT_NEAR(f.Evaluate(onX), 0.0, 1e-14);
  EXPECT_NEAR(f.Evaluate(onZ), 0.0, 1e-14);
  EXPECT_NEAR(f.Evaluate(farX), 8.0, 1e-13); // (3/1)² − 1
  ASSERT_TRUE(f.Bounded);
  const double expected[6] = { 0, 2, -1, 5, 2.5, 3.5 };
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_NEAR(f.Bounds[i], expected[i], 1e-14) << "bound " << i;
  }
  // A hyperbolic paraboloid turned the same way: along world y it rises as (s/a)².
  PrimitiveSpec h;
  h.Type = PrimitiveType::HyperbolicParaboloid;
  h.Radii[0] = 2;
  h.Radii[1] = 1;
  h.Orient = Orientation::Rotation;
  h.RotationAxis[2] = 1;
  h.RotationAngle = 90;
  const PolynomialFactor g = Build(h);
  const double py[3] = { 0, 4, 0 }, px[3] = { 4, 0, 0 }, pz[3] = { 0, 0, 1 };
  EXPECT_NEAR(g.Evaluate(py), 4.0, 1e-14);   // (4/2)²
  EXPECT_NEAR(g.Evaluate(px), -16.0, 1e-13); // −(4/1)²
  EXPECT_NEAR(g.Evaluate(pz), -1.0, 1e-15);
}

TEST(PrimitiveSpec, RotationMatrix)
{
  Random rng(27);
  for (int n = 0; n < 20; ++n)
  {
    const Point axis = rng.InBox(-2, 2);
    const double angle = rng.Uniform(-400, 400);
    double R[3][3], M[3][3];
    RotationMatrix(axis.data(), angle, R);
    Rodrigues(axis.data(), angle, M);
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        EXPECT_NEAR(R[i][j], M[i][j], 1e-14);
      }
      // The axis is fixed.
      const double n = std::hypot(axis[0], axis[1], axis[2]);
      EXPECT_NEAR(
        R[i][0] * axis[0] + R[i][1] * axis[1] + R[i][2] * axis[2], axis[i], 1e-14 * n * 4);
    }
  }
  // Right-handed: 90° about z takes x to y.
  const double z[3] = { 0, 0, 5 };
  double R[3][3];
  RotationMatrix(z, 90, R);
  EXPECT_NEAR(R[0][0], 0, 1e-15);
  EXPECT_NEAR(R[1][0], 1, 1e-15);
  EXPECT_NEAR(R[2][0], 0, 1e-15);
  EXPECT_NEAR(R[0][1], -1, 1e-15);
}

TEST(PrimitiveSpec, PlaneIsTheSignedDistance)
{
  PrimitiveSpec s;
  s.Type = PrimitiveType::Plane;
  s.Normal[0] = 0;
  s.Normal[1] = 0;
  s.Normal[2] = 2;
  s.Center[2] = 1;
  const PolynomialFactor f = Build(s);
  const double p[3] = { 7, -3, 4 };
  double g[3];
  EXPECT_DOUBLE_EQ(f.EvaluateWithGradient(p, g), 3.0);
  EXPECT_EQ(g[0], 0.0);
  EXPECT_EQ(g[1], 0.0);
  EXPECT_DOUBLE_EQ(g[2], 1.0);
  EXPECT_EQ(f.Poly.GetDegree(), 1);
}

TEST(PrimitiveSpec, BoundsContainTheZeroSet)
{
  Random rng(28);
  for (PrimitiveType t : AllTypes)
  {
    for (int trial = 0; trial < 6; ++trial)
    {
      PrimitiveSpec s = RandomSpec(t, rng);
      const Point c = rng.InBox(-2, 2);
      std::copy(c.begin(), c.end(), s.Center);
      if (trial % 3 == 1)
      {
        s.Orient = Orientation::Axis;
        const Point a = rng.InBox(-1, 1);
        std::copy(a.begin(), a.end(), s.Axis);
      }
      else if (trial % 3 == 2)
      {
        s.Orient = Orientation::Rotation;
        const Point a = rng.InBox(-1, 1);
        std::copy(a.begin(), a.end(), s.RotationAxis);
        s.RotationAngle = rng.Uniform(-180, 180);
      }
      const PolynomialFactor f = Build(s);
      ASSERT_EQ(f.Bounded, IsBoundedType(t)) << TypeKey(t);
      if (!f.Bounded)
      {
        continue;
      }
      for (int i = 0; i < 3; ++i)
      {
        EXPECT_LT(f.Bounds[2 * i], c[i]);
        EXPECT_GT(f.Bounds[2 * i + 1], c[i]);
      }
      // Points of the zero set in local coordinates, mapped to the world by p = Aᵀ(q − B).
      double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
      for (int n = 0; n < 4000; ++n)
      {
        double q[3];
        if (t == PrimitiveType::Torus)
        {
          const double th = rng.Uniform(0, 2 * Pi), ph = rng.Uniform(0, 2 * Pi);
          const double r = s.MajorRadius + s.MinorRadius * std::cos(ph);
          q[0] = r * std::cos(th);
          q[1] = r * std::sin(th);
          q[2] = s.MinorRadius * std::sin(ph);
        }
        else
        {
          // Star-shaped about the local origin: scale a direction onto the surface.
          Point d = rng.InBox(-1, 1);
          if (n < 6)
          {
            d = { 0, 0, 0 };
            d[n / 2] = n % 2 ? 1 : -1; // the extreme points along the local axes
          }
          const double* rr = t == PrimitiveType::Sphere ? nullptr : s.Radii;
          const int e = t == PrimitiveType::Superellipsoid ? s.Exponent : 2;
          double sum = 0.0;
          for (int i = 0; i < 3; ++i)
          {
            sum += std::pow(std::fabs(d[i]) / (rr ? rr[i] : s.Radius), e);
          }
          const double k = std::pow(sum, -1.0 / e);
          for (int i = 0; i < 3; ++i)
            q[i] = k * d[i];
        }
        double p[3];
        for (int i = 0; i < 3; ++i)
        {
          p[i] =
            f.A[0][i] * (q[0] - f.B[0]) + f.A[1][i] * (q[1] - f.B[1]) + f.A[2][i] * (q[2] - f.B[2]);
        }
        ASSERT_NEAR(f.Evaluate(p), 0.0, 1e-10 * ValueScale(f, p)) << TypeKey(t) << " sample";
        for (int i = 0; i < 3; ++i)
        {
          EXPECT_GE(p[i], f.Bounds[2 * i] - 1e-12) << TypeKey(t) << " axis " << i;
          EXPECT_LE(p[i], f.Bounds[2 * i + 1] + 1e-12) << TypeKey(t) << " axis " << i;
          lo[i] = std::min(lo[i], p[i]);
          hi[i] = std::max(hi[i], p[i]);
        }
      }
      // Not absurdly loose: within a factor sqrt(3) of the sampled extent.
      for (int i = 0; i < 3; ++i)
      {
        EXPECT_LE(f.Bounds[2 * i + 1] - f.Bounds[2 * i], 1.75 * (hi[i] - lo[i])) << TypeKey(t);
      }
      if (s.Orient == Orientation::Default && t != PrimitiveType::Torus)
      {
        // Axis-aligned: the box is exact.
        for (int i = 0; i < 3; ++i)
        {
          const double h = t == PrimitiveType::Sphere ? s.Radius : s.Radii[i];
          EXPECT_DOUBLE_EQ(f.Bounds[2 * i], c[i] - h);
          EXPECT_DOUBLE_EQ(f.Bounds[2 * i + 1], c[i] + h);
        }
      }
    }
  }
}

TEST(PrimitiveSpec, FactorRestrictionToLines)
{
  Random rng(29);
  for (PrimitiveType t : AllTypes)
  {
    PrimitiveSpec s = RandomSpec(t, rng);
    s.Orient = Orientation::Rotation;
    const Point a = rng.InBox(-1, 1);
    std::copy(a.begin(), a.end(), s.RotationAxis);
    s.RotationAngle = 37;
    s.Center[0] = 0.5;
    const PolynomialFactor f = Build(s);
    const Point o = rng.InBox(-1, 1), d = rng.InBox(-1, 1);
    const std::vector<double> c = f.RestrictToLine(o.data(), d.data());
    EXPECT_EQ(c.size(), static_cast<size_t>(f.Poly.GetDegree() + 1));
    std::vector<double> buffer(c.size() + 1, -7.0);
    f.RestrictToLine(o.data(), d.data(), buffer.data());
    for (size_t k = 0; k < c.size(); ++k)
      EXPECT_EQ(buffer[k], c[k]) << TypeKey(t);
    EXPECT_EQ(buffer.back(), -7.0) << TypeKey(t) << ": wrote past out[degree]";
    for (double tt : { -2.0, -0.3, 0.0, 0.9, 1.7 })
    {
      const double p[3] = { o[0] + tt * d[0], o[1] + tt * d[1], o[2] + tt * d[2] };
      EXPECT_TRUE(Near(EvaluateUnivariate(c.data(), static_cast<int>(c.size()), tt), f.Evaluate(p),
        1e-11 * ValueScale(f, p)))
        << TypeKey(t);
    }
  }
}

TEST(PrimitiveSpec, PolynomialPrimitiveUsesLocalCoordinatesAndParameters)
{
  // "x^2 + y^2 - r^2" along the axis (1, 0, 0) is the cylinder y² + z² − r².
  PrimitiveSpec s;
  s.Type = PrimitiveType::Polynomial;
  s.Expression = "x^2 + y^2 - r^2";
  s.Orient = Orientation::Axis;
  s.Axis[0] = 1;
  s.Axis[1] = 0;
  s.Axis[2] = 0;
  s.Center[1] = 1;
  const PolynomialFactor f = Build(s, { { "r", 0.5 } });
  Random rng(30);
  for (int n = 0; n < 20; ++n)
  {
    const Point p = rng.InBox(-2, 2);
    EXPECT_TRUE(Near(f.Evaluate(p.data()), (p[1] - 1) * (p[1] - 1) + p[2] * p[2] - 0.25, 1e-14));
  }
  EXPECT_FALSE(f.Bounded);
}

// An expression written about another point (the cup's handle torus about
// (2.2a, 0, −1), the bowl's base about z = −2, a rotated cylinder's offset) is centred
// there: far fewer terms, the same values as the expression, and its natural (as
// written) enclosure still holds every value over a box.
TEST(PrimitiveSpec, OffCentreExpressionsAreCentred)
{
  struct Case
  {
    const char* Expression;
    double Shift[3];
    size_t MaximumTerms;
  };
  const Case cases[] = {
    { "((x-2.2*a)^2+(z+1)^2+y^2+0.5-0.01)^2-2*((x-2.2*a)^2+(z+1)^2)", { 2.2, 0, -1 }, 10 },
    { "1/8*x^2+1/8*y^2+(z+2)^2-0.1", { 0, 0, -2 }, 4 },
    { "((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)", { 0, 0, -1 }, 10 },
    { "((x+1)/0.1)^2+((y+1)/0.1)^2+(z/0.9)^2-0.5", { -1, -1, 0 }, 4 },
  };
  Random rng(31);
  for (const Case& c : cases)
  {
    PrimitiveSpec s;
    s.Type = PrimitiveType::Polynomial;
    s.Expression = c.Expression;
    s.Center[1] = 0.25; // the spec's own centre composes with the centring
    PolynomialFactor f = Build(s, { { "a", 1.0 } });
    f.PrepareIntervals();
    EXPECT_LE(f.Poly.GetTerms().size(), c.MaximumTerms) << c.Expression;
    Polynomial3 written;
    std::string error;
    ASSERT_TRUE(ParseExpression(c.Expression, { { "a", 1.0 } }, written, error));
    EXPECT_GT(written.GetTerms().size(), f.Poly.GetTerms().size()) << c.Expression;
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(f.NaturalShift[a], c.Shift[a]) << c.Expression << " axis " << a;
    }
    for (int n = 0; n < 200; ++n)
    {
      const Point p = rng.InBox(-3, 3);
      const double q[3] = { p[0], p[1] - 0.25, p[2] };
      const double expected = written.Evaluate(q);
      EXPECT_TRUE(Near(f.Evaluate(p.data()), expected, 1e-12 * ValueScale(f, p.data())))
        << c.Expression << " at " << p[0] << " " << p[1] << " " << p[2];
      // A small box about p: the enclosure holds the values at its corners and centre.
      const double h = n % 2 ? 0.01 : 0.3;
      const double box[6] = { p[0] - h, p[0] + h, p[1] - h, p[1] + h, p[2] - h, p[2] + h };
      const Interval range = f.EvaluateInterval(box);
      for (int corner = 0; corner < 9; ++corner)
      {
        double x[3];
        for (int a = 0; a < 3; ++a)
        {
          x[a] = corner == 8 ? p[a] : box[2 * a + ((corner >> a) & 1)];
        }
        const double v = f.Evaluate(x);
        EXPECT_TRUE(range.Lo <= v && v <= range.Hi)
          << c.Expression << ": " << v << " outside [" << range.Lo << ", " << range.Hi << "]";
      }
    }
  }
}

TEST(PrimitiveSpec, InvalidParametersNameTheParameter)
{
  auto spec = [](PrimitiveType t)
  {
    PrimitiveSpec s;
    s.Type = t;
    s.Expression = "x + y";
    return s;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : { -1.0, 0.0, nan, inf })
  {
    PrimitiveSpec s = spec(PrimitiveType::Sphere);
    s.Radius = bad;
    ExpectBuildError(s, { "radius", "positive" });
    s.Type = PrimitiveType::Cylinder;
    ExpectBuildError(s, { "radius", "positive" });
  }
  for (PrimitiveType t :
    { PrimitiveType::Ellipsoid, PrimitiveType::Superellipsoid, PrimitiveType::Hyperboloid1,
      PrimitiveType::Hyperboloid2, PrimitiveType::Paraboloid, PrimitiveType::HyperbolicParaboloid })
  {
    const int count =
      (t == PrimitiveType::Paraboloid || t == PrimitiveType::HyperbolicParaboloid) ? 2 : 3;
    for (int i = 0; i < count; ++i)
    {
      for (double bad : { 0.0, -2.0, nan })
      {
        PrimitiveSpec s = spec(t);
        s.Radii[i] = bad;
        ExpectBuildError(s, { "radii[" + std::to_string(i) + "]" });
      }
    }
    if (count == 2)
    {
      // The third radius of a paraboloid is not used.
      PrimitiveSpec s = spec(t);
      s.Radii[2] = -1;
      Build(s);
    }
  }
  for (int bad : { 1, 3, 0, -2, 5, 66 })
  {
    PrimitiveSpec s = spec(PrimitiveType::Superellipsoid);
    s.Exponent = bad;
    ExpectBuildError(s, { "exponent", "even", "got " + std::to_string(bad) });
  }
  {
    PrimitiveSpec s = spec(PrimitiveType::Superellipsoid);
    s.Exponent = 64;
    Build(s);
  }
  {
    PrimitiveSpec s = spec(PrimitiveType::Torus);
    s.MajorRadius = 0;
    ExpectBuildError(s, { "major_radius" });
    s.MajorRadius = 1;
    s.MinorRadius = -0.1;
    ExpectBuildError(s, { "minor_radius" });
  }
  for (const Point& n : { Point{ 0, 0, 0 }, Point{ nan, 0, 1 }, Point{ 0, inf, 0 } })
  {
    PrimitiveSpec s = spec(PrimitiveType::Plane);
    std::copy(n.begin(), n.end(), s.Normal);
    ExpectBuildError(s, { "normal" });
  }
  for (double bad : { 0.0, 90.0, -10.0, 120.0, nan })
  {
    PrimitiveSpec s = spec(PrimitiveType::Cone);
    s.Angle = bad;
    ExpectBuildError(s, { "angle" });
  }
  for (PrimitiveType t : AllTypes)
  {
    PrimitiveSpec s = spec(t);
    s.Center[1] = nan;
    ExpectBuildError(s, { "center" });
    s = spec(t);
    s.Center[2] = inf;
    ExpectBuildError(s, { "center" });
    s = spec(t);
    s.Scale = 0.0;
    ExpectBuildError(s, { "scale" });
    s.Scale = nan;
    ExpectBuildError(s, { "scale" });
    s = spec(t);
    s.Orient = Orientation::Axis;
    s.Axis[0] = s.Axis[1] = s.Axis[2] = 0;
    ExpectBuildError(s, { "axis" });
    s.Axis[2] = nan;
    ExpectBuildError(s, { "axis" });
    s = spec(t);
    s.Orient = Orientation::Rotation;
    s.RotationAxis[0] = s.RotationAxis[1] = s.RotationAxis[2] = 0;
    ExpectBuildError(s, { "rotation axis" });
    s.RotationAxis[0] = 1;
    s.RotationAngle = inf;
    ExpectBuildError(s, { "rotation angle" });
  }
  {
    PrimitiveSpec s = spec(PrimitiveType::Polynomial);
    s.Expression = "";
    ExpectBuildError(s, { "expression", "empty" });
    s.Expression = "x +";
    ExpectBuildError(s, { "expression", "position 4" });
    s.Expression = "2x";
    ExpectBuildError(s, { "expression", "'*'" });
    s.Expression = "x*a";
    ExpectBuildError(s, { "expression", "unknown name 'a'" });
    s.Expression = "x^70";
    ExpectBuildError(s, { "expression", "degree" });
  }
  {
    // Parameters that overflow the coefficients.
    PrimitiveSpec s = spec(PrimitiveType::Sphere);
    s.Radius = 1e200;
    ExpectBuildError(s, { "overflow" });
    s = spec(PrimitiveType::Superellipsoid);
    s.Exponent = 64;
    s.Radii[0] = 1e-10;
    ExpectBuildError(s, { "overflow" });
  }
}

// Regression (fixed): BuildFactor checks the polynomial for overflow before folding in
// `scale`, so a finite polynomial times a finite scale can yield infinite coefficients
// that BuildFactor accepts.
TEST(PrimitiveSpec, ScaleOverflowIsRefused)
{
  PrimitiveSpec s;
  s.Type = PrimitiveType::Sphere;
  s.Radius = 1e154; // R² = 1e308 is still finite
  s.Scale = 1e10;   // but 1e10·1e308 is not
  PolynomialFactor f;
  std::string error;
  const bool ok = BuildFactor(s, {}, f, error);
  if (ok)
  {
    EXPECT_TRUE(f.Poly.IsFinite())
      << "accepted with non-finite coefficients: " << f.Poly.ToString();
  }
  else
  {
    EXPECT_TRUE(HasFragments(error, { "overflow" }));
  }
}

// Regression (fixed): the normal and the axis are normalised with a plain sqrt(x²+y²+z²),
// which overflows for components near 1e200 and underflows to 0 near 1e-200: a valid,
// finite, non-zero vector then gives a zero polynomial, a wrong axis or a refusal.
TEST(PrimitiveSpec, ExtremeButValidVectorsAreNormalised)
{
  const double p[3] = { 0.7, -0.4, 0.2 };
  for (double m : { 1e200, 1e-200 })
  {
    PrimitiveSpec plane;
    plane.Type = PrimitiveType::Plane;
    plane.Normal[0] = m;
    plane.Normal[1] = 0;
    plane.Normal[2] = 0;
    PolynomialFactor f;
    std::string error;
    EXPECT_TRUE(BuildFactor(plane, {}, f, error)) << "normal (" << m << ", 0, 0): " << error;
    EXPECT_NEAR(f.Evaluate(p), 0.7, 1e-15) << "plane with normal (" << m << ", 0, 0) must be x";

    PrimitiveSpec cyl;
    cyl.Type = PrimitiveType::Cylinder;
    cyl.Orient = Orientation::Axis;
    cyl.Axis[0] = 0;
    cyl.Axis[1] = m;
    cyl.Axis[2] = 0;
    PolynomialFactor g;
    EXPECT_TRUE(BuildFactor(cyl, {}, g, error)) << "axis (0, " << m << ", 0): " << error;
    EXPECT_NEAR(g.Evaluate(p), 0.7 * 0.7 + 0.2 * 0.2 - 1, 1e-15)
      << "cylinder along (0, " << m << ", 0) must be x² + z² − 1";
  }
}
