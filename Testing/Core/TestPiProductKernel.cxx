// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of pisurf::ProductKernel (PiProductKernel.h): F = Π f_i − r and its gradient.
#include "PiCoreTestUtilities.h"
#include "PiFloat.h"
#include "PiProductKernel.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace pisurf;
using namespace pisurf_test;

namespace
{
constexpr double Pi = 3.14159265358979323846;

Factor FromSpec(const PrimitiveSpec& s, const ParameterMap& params = {})
{
  Factor f;
  f.IsPolynomial = true;
  std::string error;
  EXPECT_TRUE(BuildFactor(s, params, f.Polynomial, error)) << error;
  return f;
}

Factor Sphere(const double c[3], double radius)
{
  PrimitiveSpec s;
  s.Type = PrimitiveType::Sphere;
  std::copy(c, c + 3, s.Center);
  s.Radius = radius;
  return FromSpec(s);
}

Factor Plane(double nx, double ny, double nz, double offset = 0.0)
{
  PrimitiveSpec s;
  s.Type = PrimitiveType::Plane;
  s.Normal[0] = nx;
  s.Normal[1] = ny;
  s.Normal[2] = nz;
  const double n = std::hypot(nx, ny, nz);
  for (int i = 0; i < 3; ++i)
    s.Center[i] = offset * s.Normal[i] / n;
  return FromSpec(s);
}

Factor Generic(GenericFunction fn)
{
  Factor f;
  f.IsPolynomial = false;
  f.Generic = std::move(fn);
  return f;
}

/// A constant generic factor with a constant gradient.
Factor ConstantFactor(double value, double gradient = 0.0)
{
  return Generic(
    [value, gradient](const double*, double* g)
    {
      if (g)
      {
        g[0] = gradient;
        g[1] = -gradient;
        g[2] = 0.5 * gradient;
      }
      return value;
    });
}

/// sin(x) + y·z − 0.3, with its exact gradient.
Factor Wave()
{
  return Generic(
    [](const double* p, double* g)
    {
      if (g)
      {
        g[0] = std::cos(p[0]);
        g[1] = p[2];
        g[2] = p[1];
      }
      return std::sin(p[0]) + p[1] * p[2] - 0.3;
    });
}

/// 30 unit spheres about 1e5 away (about 2^33 each near the origin: their plain product,
/// 2^1000, and its gradient overflow a double).
std::vector<Factor> FarSpheres()
{
  std::vector<Factor> far;
  for (int i = 0; i < 30; ++i)
  {
    const double c[3] = { 1e5 + 10.0 * i, 3.0 * i, 0.0 };
    far.push_back(Sphere(c, 1.0));
  }
  return far;
}

/// A torus of major radius 1 and minor radius 0.25 about the z axis, centred at (x, 0, 0).
PrimitiveSpec SmallTorus(double x = 0.0)
{
  PrimitiveSpec torus;
  torus.Type = PrimitiveType::Torus;
  torus.MajorRadius = 1.0;
  torus.MinorRadius = 0.25;
  torus.Center[0] = x;
  return torus;
}

/// Random sizes for every type's parameters (radii, torus radii, exponent 4, cone angle).
void RandomSizes(Random& rng, PrimitiveSpec& s)
{
  s.Radius = rng.Uniform(0.5, 1.5);
  for (double& r : s.Radii)
    r = rng.Uniform(0.5, 1.5);
  s.MajorRadius = rng.Uniform(1.0, 1.5);
  s.MinorRadius = rng.Uniform(0.2, 0.5);
  s.Exponent = 4;
  s.Angle = rng.Uniform(10, 70);
}

/// A random primitive of any type, randomly placed.
Factor RandomPrimitive(Random& rng)
{
  PrimitiveSpec s;
  s.Type = static_cast<PrimitiveType>(rng.Integer(0, 11));
  RandomSizes(rng, s);
  s.Expression = "x*y - z^2 + 0.25*x^3 - 1";
  for (int i = 0; i < 3; ++i)
  {
    s.Normal[i] = rng.Uniform(-1, 1);
    s.Center[i] = rng.Uniform(-0.5, 0.5);
    s.RotationAxis[i] = rng.Uniform(-1, 1);
  }
  s.Orient = Orientation::Rotation;
  s.RotationAngle = rng.Uniform(-180, 180);
  s.Scale = rng.Uniform(0.5, 2.0);
  return FromSpec(s);
}

/// n random primitives (RandomPrimitive), then Wave() when `wave`.
std::vector<Factor> RandomFactors(Random& rng, int n, bool wave = false)
{
  std::vector<Factor> factors;
  for (int i = 0; i < n; ++i)
    factors.push_back(RandomPrimitive(rng));
  if (wave)
    factors.push_back(Wave());
  return factors;
}

/// Σ|c|·(|q|+1)^pow: the rounding scale of a polynomial factor's value at p.
double FactorScale(const Factor& f, const double p[3])
{
  if (!f.IsPolynomial)
  {
    return 2.0 + std::fabs(p[1] * p[2]);
  }
  double q[3];
  f.Polynomial.ToLocal(p, q);
  double v = 0.0;
  for (const auto& t : f.Polynomial.Poly.GetTerms())
  {
    v += std::fabs(t.Coefficient) * std::pow(std::fabs(q[0]) + 1, t.I) *
      std::pow(std::fabs(q[1]) + 1, t.J) * std::pow(std::fabs(q[2]) + 1, t.K);
  }
  return v;
}

struct Direct
{
  double F;
  double G[3];
  double ValueTolerance;    // rounding scale of F
  double GradientTolerance; // rounding scale of ∇F
};

/// F and ∇F straight from the definitions, with the scale of their rounding errors.
Direct DirectEvaluation(const std::vector<Factor>& factors, double r, const double p[3])
{
  const size_t n = factors.size();
  std::vector<double> f(n), scale(n), gn(n);
  std::vector<Point> g(n);
  for (size_t i = 0; i < n; ++i)
  {
    f[i] = factors[i].EvaluateWithGradient(p, g[i].data());
    scale[i] = FactorScale(factors[i], p);
    gn[i] = std::fabs(g[i][0]) + std::fabs(g[i][1]) + std::fabs(g[i][2]) + scale[i];
  }
  Direct d{};
  double P = 1.0, absP = 1.0;
  for (size_t i = 0; i < n; ++i)
  {
    P *= f[i];
    absP *= std::max(std::fabs(f[i]), scale[i]);
  }
  d.F = P - r;
  d.ValueTolerance = 1e-13 * (absP + std::fabs(r));
  double gscale = 0.0;
  for (size_t i = 0; i < n; ++i)
  {
    double others = 1.0, absOthers = 1.0;
    for (size_t j = 0; j < n; ++j)
    {
      if (j != i)
      {
        others *= f[j];
        absOthers *= std::max(std::fabs(f[j]), scale[j]);
      }
    }
    for (int k = 0; k < 3; ++k)
      d.G[k] += g[i][k] * others;
    gscale += gn[i] * absOthers;
  }
  d.GradientTolerance = 1e-13 * gscale;
  return d;
}

/// Σ_i rounding-condition of each factor: how much relative error the value may carry.
double Conditioning(const std::vector<Factor>& factors, const double p[3])
{
  double c = 0.0;
  for (const Factor& f : factors)
  {
    const double v = std::fabs(f.Evaluate(p));
    c += FactorScale(f, p) / std::max(v, 1e-300);
  }
  return c;
}
}

TEST(ProductKernel, Accessors)
{
  const double c[3] = { 0, 0, 0 };
  ProductKernel k({ Sphere(c, 1), Plane(0, 0, 1) }, 0.25);
  EXPECT_EQ(k.GetNumberOfFactors(), 2u);
  EXPECT_EQ(k.GetBlending(), 0.25);
  EXPECT_TRUE(k.IsPolynomial());
  EXPECT_TRUE(k.GetFactor(1).IsPolynomial);
  ProductKernel mixed({ Sphere(c, 1), Wave() }, 0.0);
  EXPECT_FALSE(mixed.IsPolynomial());
  EXPECT_FALSE(mixed.GetFactor(1).IsPolynomial);
}

TEST(ProductKernel, NoFactorsIsTheEmptyProduct)
{
  ProductKernel k({}, 0.25);
  const double p[3] = { 1, 2, 3 };
  EXPECT_DOUBLE_EQ(k.Evaluate(p), 0.75);
  double g[3] = { 9, 9, 9 };
  EXPECT_DOUBLE_EQ(k.EvaluateWithGradient(p, g), 0.75);
  EXPECT_EQ(g[0], 0.0);
  EXPECT_EQ(g[1], 0.0);
  EXPECT_EQ(g[2], 0.0);
  EXPECT_EQ(k.NearestFactor(p), -1);
}

TEST(ProductKernel, ValueAndGradientMatchTheDefinition)
{
  Random rng(41);
  for (int trial = 0; trial < 60; ++trial)
  {
    const int n = 2 + trial % 4; // 2..5 factors
    std::vector<Factor> factors;
    for (int i = 0; i < n; ++i)
    {
      factors.push_back(trial % 5 == 4 && i == 0 ? Wave() : RandomPrimitive(rng));
    }
    const double r = trial % 3 == 0 ? 0.0 : rng.Uniform(-0.5, 0.5);
    const ProductKernel k(factors, r);
    for (int m = 0; m < 10; ++m)
    {
      const Point p = rng.InBox(-2, 2);
      const Direct d = DirectEvaluation(factors, r, p.data());
      EXPECT_NEAR(k.Evaluate(p.data()), d.F, d.ValueTolerance) << n << " factors";
      double g[3];
      EXPECT_NEAR(k.EvaluateWithGradient(p.data(), g), d.F, d.ValueTolerance);
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(g[c], d.G[c], d.GradientTolerance) << n << " factors, component " << c;
      }
      // And against finite differences of F itself.
      const Point fd =
        FiniteDifferenceGradient([&](const double* x) { return k.Evaluate(x); }, p.data(), 1e-6);
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(g[c], fd[c], 1e-5 * (1.0 + d.GradientTolerance * 1e13)) << "component " << c;
      }
    }
  }
}

TEST(ProductKernel, GradientWithOneZeroFactor)
{
  // f1 = z is exactly 0 on z = 0, so ∇F = ∇f1 · f2 · f3 there (not 0, not NaN).
  const double c[3] = { 0.5, 0, 0.25 };
  std::vector<Factor> factors = { Plane(0, 0, 1), Sphere(c, 1.0), Wave() };
  const ProductKernel k(factors, 0.125);
  Random rng(42);
  for (int n = 0; n < 20; ++n)
  {
    const double p[3] = { rng.Uniform(-2, 2), rng.Uniform(-2, 2), 0.0 };
    double g[3];
    const double F = k.EvaluateWithGradient(p, g);
    EXPECT_EQ(F, -0.125);
    EXPECT_EQ(k.Evaluate(p), -0.125);
    const double others = factors[1].Evaluate(p) * factors[2].Evaluate(p);
    EXPECT_NEAR(g[0], 0.0, 1e-300);
    EXPECT_NEAR(g[1], 0.0, 1e-300);
    EXPECT_TRUE(Near(g[2], others, 1e-14));
    EXPECT_NE(g[2], 0.0);
  }
}

TEST(ProductKernel, GradientWithTwoZeroFactorsIsZero)
{
  const double c[3] = { 0.5, 0, 0.25 };
  std::vector<Factor> factors = { Plane(1, 0, 0), Sphere(c, 1.0), Plane(0, 1, 0), Wave() };
  const ProductKernel k(factors, 0.0);
  Random rng(43);
  for (int n = 0; n < 20; ++n)
  {
    const double p[3] = { 0.0, 0.0, rng.Uniform(-2, 2) };
    double g[3] = { 7, 7, 7 };
    EXPECT_EQ(k.EvaluateWithGradient(p, g), 0.0);
    EXPECT_EQ(g[0], 0.0);
    EXPECT_EQ(g[1], 0.0);
    EXPECT_EQ(g[2], 0.0);
    EXPECT_EQ(k.Evaluate(p), 0.0);
  }
}

TEST(ProductKernel, PointsAndLinesAgreeWithEvaluate)
{
  Random rng(44);
  for (int trial = 0; trial < 12; ++trial)
  {
    // (with the generic Wave factor in a third of the trials: both paths exercised)
    const std::vector<Factor> factors = RandomFactors(rng, 2 + trial % 4, trial % 3 == 2);
    const double r = trial % 2 ? 0.1 : 0.0;
    const ProductKernel k(factors, r);

    // A grid row of 300 points (more than one block of 128).
    const int count = 300;
    const Point origin = rng.InBox(-2, 2);
    const Point end = rng.InBox(-2, 2);
    const double step[3] = { (end[0] - origin[0]) / (count - 1), (end[1] - origin[1]) / (count - 1),
      (end[2] - origin[2]) / (count - 1) };
    std::vector<double> line(count), points(count), xyz(3 * count);
    k.EvaluateLine(origin.data(), step, count, line.data());
    for (int i = 0; i < count; ++i)
    {
      for (int a = 0; a < 3; ++a)
        xyz[3 * i + a] = origin[a] + i * step[a];
    }
    k.EvaluatePoints(xyz.data(), count, points.data());
    int withinRelative = 0;
    for (int i = 0; i < count; ++i)
    {
      const double* p = &xyz[3 * i];
      const double F = k.Evaluate(p);
      double P = 1.0;
      for (const Factor& f : factors)
        P *= f.Evaluate(p);
      // Same arithmetic per point: agreement to the last bits.
      EXPECT_TRUE(Near(points[i], F, 1e-15 * (std::fabs(P) + std::fabs(r))))
        << "EvaluatePoints at " << i;
      // Horner on the restricted polynomials rounds differently: ~1e-12 relative to
      // the product, more only where a factor nearly cancels (observed error
      // <= 1.5·1e-16·conditioning; allowed 1e-14·conditioning).
      const double cond = Conditioning(factors, p);
      const double tol = std::max(1e-12, 1e-14 * cond) * std::fabs(P) + 1e-15 * std::fabs(r);
      EXPECT_NEAR(line[i], F, tol) << "EvaluateLine at " << i << ", conditioning " << cond;
      if (std::fabs(line[i] - F) <= 1e-12 * std::fabs(P))
        ++withinRelative;
    }
    EXPECT_GE(withinRelative, count * 95 / 100) << "nearly all points agree to 1e-12 relative";
  }
  // n = 0 and n = 1 rows.
  const ProductKernel k({ Wave() }, 0.0);
  const double o[3] = { 0.3, 0.2, 0.1 }, s[3] = { 1, 1, 1 };
  double v = 12345.0;
  k.EvaluateLine(o, s, 0, &v);
  EXPECT_EQ(v, 12345.0);
  k.EvaluateLine(o, s, 1, &v);
  EXPECT_DOUBLE_EQ(v, k.Evaluate(o));
  k.EvaluatePoints(o, 0, &v);
  EXPECT_DOUBLE_EQ(v, k.Evaluate(o));
}

// The row evaluator (several points at a time, plain products where safe) must give
// EvaluateRestricted's bits at every point: the mesher's grid values, and so its mesh,
// do not depend on which of the two computed them.
TEST(ProductKernel, RowEvaluationHasTheBitsOfPointEvaluation)
{
  Random rng(45);
  auto check =
    [&](const ProductKernel& k, const double o[3], const double d[3], int count, const char* what)
  {
    std::vector<double> coefficients(k.GetLineCoefficientCount());
    k.RestrictLine(o, d, coefficients.data());
    const double t0 = -0.5 * (count - 1);
    const double start[3] = { o[0] + t0 * d[0], o[1] + t0 * d[1], o[2] + t0 * d[2] };
    std::vector<double> row(count);
    k.EvaluateRestrictedRow(coefficients.data(), t0, count, start, d, row.data());
    int differing = 0;
    for (int i = 0; i < count; ++i)
    {
      const double p[3] = { start[0] + i * d[0], start[1] + i * d[1], start[2] + i * d[2] };
      differing += !SameBits(row[i], k.EvaluateRestricted(coefficients.data(), t0 + i, p));
    }
    EXPECT_EQ(differing, 0) << what << ": points whose bits differ";
  };
  for (int trial = 0; trial < 20; ++trial)
  {
    const ProductKernel k(RandomFactors(rng, 1 + trial % 5), trial % 2 ? 0.25 : 0.0);
    const Point o = rng.InBox(-2, 2), e = rng.InBox(-2, 2);
    const double d[3] = { (e[0] - o[0]) / 77, (e[1] - o[1]) / 77, (e[2] - o[2]) / 77 };
    check(k, o.data(), d, 1 + trial * 13 % 150, "random primitives"); // partial chunks too
  }
  // Factors beyond 2^±256 (the scaled product rescales), exact zeros, and a product of
  // 300 spheres (the plain-product bound shrinks to 2^3): the same bits everywhere.
  const double c0[3] = { 0, 0, 0 }, far[3] = { 1e90, 0, 0 };
  const ProductKernel huge({ Sphere(far, 1.0), Sphere(far, 2.0), Sphere(far, 3.0) }, 1.0);
  const double along[3] = { 1e88, 1e-3, 0 };
  check(huge, c0, along, 100, "factors near 1e180 and products beyond the double range");
  const ProductKernel zero({ Plane(1, 0, 0), Sphere(c0, 1.0), Sphere(far, 1.0) }, 0.0);
  const double x[3] = { 0.25, 0, 0 };
  check(zero, c0, x, 41, "a factor exactly 0 at the middle point");
  std::vector<Factor> many;
  for (int i = 0; i < 300; ++i)
  {
    const double c[3] = { 0.01 * i, 0.0, 0.0 };
    many.push_back(Sphere(c, 0.5 + 0.001 * i));
  }
  const ProductKernel crowd(many, 1e-3);
  const double slant[3] = { 0.013, 0.007, 0.0 };
  check(crowd, c0, slant, 200, "300 spheres");
}

TEST(ProductKernel, GenericFactorsMixWithPolynomialOnes)
{
  const double c[3] = { 0.2, -0.1, 0.3 };
  std::vector<Factor> factors = { Sphere(c, 0.8), Wave(), Plane(1, 1, 0, 0.2),
    Generic(
      [](const double* p, double* g)
      {
        // e^x·(y − 1)
        if (g)
        {
          g[0] = std::exp(p[0]) * (p[1] - 1);
          g[1] = std::exp(p[0]);
          g[2] = 0.0;
        }
        return std::exp(p[0]) * (p[1] - 1);
      }) };
  const ProductKernel k(factors, 0.05);
  Random rng(45);
  for (int n = 0; n < 50; ++n)
  {
    const Point p = rng.InBox(-1.5, 1.5);
    const double x = p[0], y = p[1], z = p[2];
    const double f0 = (x - 0.2) * (x - 0.2) + (y + 0.1) * (y + 0.1) + (z - 0.3) * (z - 0.3) - 0.64;
    const double f1 = std::sin(x) + y * z - 0.3;
    const double f2 = (x + y) / std::sqrt(2.0) - 0.2;
    const double f3 = std::exp(x) * (y - 1);
    const double F = f0 * f1 * f2 * f3 - 0.05;
    const double scale =
      10.0 * (std::fabs(f0) + 1) * (std::fabs(f1) + 1) * (std::fabs(f2) + 1) * (std::fabs(f3) + 1);
    EXPECT_NEAR(k.Evaluate(p.data()), F, 1e-14 * scale);
    double g[3];
    EXPECT_NEAR(k.EvaluateWithGradient(p.data(), g), F, 1e-14 * scale);
    const double g0[3] = { 2 * (x - 0.2), 2 * (y + 0.1), 2 * (z - 0.3) };
    const double g1[3] = { std::cos(x), z, y };
    const double g2[3] = { 1 / std::sqrt(2.0), 1 / std::sqrt(2.0), 0 };
    const double g3[3] = { f3, std::exp(x), 0 };
    for (int a = 0; a < 3; ++a)
    {
      const double expected =
        g0[a] * f1 * f2 * f3 + f0 * g1[a] * f2 * f3 + f0 * f1 * g2[a] * f3 + f0 * f1 * f2 * g3[a];
      EXPECT_NEAR(g[a], expected, 1e-13 * scale * 10) << "component " << a;
    }
    double v;
    k.EvaluatePoints(p.data(), 1, &v);
    EXPECT_NEAR(v, F, 1e-14 * scale);
  }
  std::vector<double> line(200);
  const double o[3] = { -1, -1, 0.5 }, s[3] = { 0.01, 0.012, -0.003 };
  k.EvaluateLine(o, s, 200, line.data());
  for (int i = 0; i < 200; ++i)
  {
    const double p[3] = { o[0] + i * s[0], o[1] + i * s[1], o[2] + i * s[2] };
    EXPECT_NEAR(line[i], k.Evaluate(p), 1e-12 * (std::fabs(k.Evaluate(p)) + 1)) << i;
  }
}

TEST(ProductKernel, ScaledAndLogFormsAgreeWithEvaluate)
{
  Random rng(46);
  for (int trial = 0; trial < 20; ++trial)
  {
    const std::vector<Factor> factors = RandomFactors(rng, 3);
    const double r = trial % 2 ? 0.3 : 0.0;
    const ProductKernel k(factors, r);
    for (int n = 0; n < 20; ++n)
    {
      const Point p = rng.InBox(-2, 2);
      const double F = k.Evaluate(p.data());
      double m;
      long e;
      k.EvaluateScaled(p.data(), m, e);
      if (F == 0.0)
      {
        EXPECT_EQ(m, 0.0);
        continue;
      }
      EXPECT_GE(std::fabs(m), 0.5);
      EXPECT_LT(std::fabs(m), 1.0);
      double P = 1.0;
      for (const Factor& f : factors)
        P *= f.Evaluate(p.data());
      EXPECT_NEAR(std::ldexp(m, static_cast<int>(e)), F, 1e-15 * (std::fabs(P) + r));
      double logAbs;
      const int sign = k.EvaluateSignAndLog(p.data(), logAbs);
      EXPECT_EQ(sign, F > 0 ? 1 : -1);
      EXPECT_NEAR(
        logAbs, std::log(std::fabs(F)), 1e-13 * (std::fabs(P) + r) / std::fabs(F) + 1e-14);
    }
  }
  // Exactly zero: a factor vanishes and r = 0.
  const ProductKernel z({ Plane(0, 0, 1), Wave() }, 0.0);
  const double p0[3] = { 1, 2, 0 };
  double m = 1.0, logAbs = 0.0;
  long e = 5;
  z.EvaluateScaled(p0, m, e);
  EXPECT_EQ(m, 0.0);
  EXPECT_EQ(z.EvaluateSignAndLog(p0, logAbs), 0);
  EXPECT_TRUE(std::isinf(logAbs) && logAbs < 0);
  // A zero factor with r ≠ 0 gives F = −r.
  const ProductKernel zr({ Plane(0, 0, 1), Wave() }, 0.75);
  zr.EvaluateScaled(p0, m, e);
  EXPECT_EQ(std::ldexp(m, static_cast<int>(e)), -0.75);
  EXPECT_EQ(zr.EvaluateSignAndLog(p0, logAbs), -1);
  EXPECT_DOUBLE_EQ(logAbs, std::log(0.75));
}

TEST(ProductKernel, OverflowClampsWithTheExactSign)
{
  // 200 factors of 1e10: P = 1e2000. With one negative factor: −1e2000.
  for (int negative = 0; negative < 2; ++negative)
  {
    std::vector<Factor> factors;
    for (int i = 0; i < 200; ++i)
      factors.push_back(ConstantFactor(i == 7 && negative ? -1e10 : 1e10, 1e12));
    for (double r : { 0.0, 0.5, -3.0, 1e250 })
    {
      const ProductKernel k(factors, r);
      const double p[3] = { 0.1, 0.2, 0.3 };
      const double expected = negative ? -DBL_MAX : DBL_MAX;
      EXPECT_EQ(k.Evaluate(p), expected);
      double g[3];
      EXPECT_EQ(k.EvaluateWithGradient(p, g), expected);
      // ∇F = Σ_i ∇f_i Π_{j≠i} f_j: 200·1e12·(±1e1990), far beyond the range.
      EXPECT_EQ(g[0], expected);
      EXPECT_EQ(g[1], -expected);
      EXPECT_EQ(g[2], expected);
      double v;
      k.EvaluatePoints(p, 1, &v);
      EXPECT_EQ(v, expected);
      k.EvaluateLine(p, p, 1, &v);
      EXPECT_EQ(v, expected);
      double m;
      long e;
      k.EvaluateScaled(p, m, e);
      EXPECT_EQ(m > 0, !negative);
      // log2(1e2000) = 6643.856...
      EXPECT_NEAR(std::log2(std::fabs(m)) + e, 2000 * std::log2(10.0), 1e-9);
      double logAbs;
      EXPECT_EQ(k.EvaluateSignAndLog(p, logAbs), negative ? -1 : 1);
      EXPECT_TRUE(RelativelyNear(logAbs, 2000 * std::log(10.0), 1e-14));
    }
  }
}

// Regression (fixed): Finish() clamps the out-of-range product to ±DBL_MAX *before*
// subtracting r, so for a blending comparable to DBL_MAX the result is no longer ±DBL_MAX
// and can even lose its sign (DBL_MAX − DBL_MAX = 0), while EvaluateScaled() is right.
TEST(ProductKernel, OverflowClampIsExactForHugeBlending)
{
  std::vector<Factor> factors;
  for (int i = 0; i < 200; ++i)
    factors.push_back(ConstantFactor(1e10)); // P = 1e2000
  const double p[3] = { 0, 0, 0 };
  for (double r : { DBL_MAX, 1e308, -1e300 })
  {
    const ProductKernel k(factors, r);
    double m;
    long e;
    k.EvaluateScaled(p, m, e);
    EXPECT_GT(m, 0.0) << "r = " << r;
    EXPECT_NEAR(std::log2(m) + e, 2000 * std::log2(10.0), 1e-9) << "r = " << r;
    EXPECT_EQ(k.Evaluate(p), DBL_MAX) << "F = 1e2000 − r is beyond the range, r = " << r;
  }
}

TEST(ProductKernel, EdgeOfTheDoubleRange)
{
  const double p[3] = { 0, 0, 0 };
  // Exactly DBL_MAX = (2 − 2^-52)·2^1023 is representable: no clamping, no change.
  {
    const ProductKernel k({ ConstantFactor(0x1.fffffffffffffp511, 0x1.fffffffffffffp511),
                            ConstantFactor(0x1p512, 0.0) },
      0.0);
    EXPECT_EQ(k.Evaluate(p), DBL_MAX);
    double g[3];
    EXPECT_EQ(k.EvaluateWithGradient(p, g), DBL_MAX);
    EXPECT_EQ(g[0], DBL_MAX);
    EXPECT_EQ(g[1], -DBL_MAX);
    EXPECT_EQ(g[2], 0x1.fffffffffffffp1022);
  }
  // 1.5·2^1024: just beyond; value and gradient clamp, neither becomes inf.
  {
    const ProductKernel k(
      { ConstantFactor(0x1.8p512, 0x1.8p512), ConstantFactor(0x1p512, 0.0) }, 0.0);
    EXPECT_EQ(k.Evaluate(p), DBL_MAX);
    double g[3];
    EXPECT_EQ(k.EvaluateWithGradient(p, g), DBL_MAX);
    EXPECT_EQ(g[0], DBL_MAX);
    EXPECT_EQ(g[1], -DBL_MAX);
    EXPECT_EQ(g[2], 0x1.8p1023);
  }
  // The smallest normal and denormal products are exact.
  {
    const ProductKernel k({ ConstantFactor(0x1p-511), ConstantFactor(-0x1p-511) }, 0.0);
    EXPECT_EQ(k.Evaluate(p), -0x1p-1022);
    const ProductKernel d({ ConstantFactor(0x1p-537), ConstantFactor(0x1p-537) }, 0.0);
    EXPECT_EQ(d.Evaluate(p), 0x1p-1074);
    const ProductKernel d6({ ConstantFactor(0x1.8p-536), ConstantFactor(-0x1p-536) }, 0.0);
    EXPECT_EQ(d6.Evaluate(p), -0x1.8p-1072); // 6·2^-1074, a denormal
  }
}

TEST(ProductKernel, IntermediateOverflowAndUnderflowCancel)
{
  // 1e-300·1e-300·1e-300·1e300·1e300·1e300·2 = 2, in any order.
  std::vector<Factor> a, b;
  for (int i = 0; i < 3; ++i)
    a.push_back(ConstantFactor(1e-300, 1e-300));
  for (int i = 0; i < 3; ++i)
    a.push_back(ConstantFactor(1e300, 1e300));
  a.push_back(ConstantFactor(2.0, 0.0));
  for (int i = 6; i >= 0; --i)
    b.push_back(a[i]);
  for (const auto& factors : { a, b })
  {
    const ProductKernel k(factors, 0.5);
    const double p[3] = { 0, 0, 0 };
    EXPECT_TRUE(RelativelyNear(k.Evaluate(p), 1.5, 1e-14));
    double g[3];
    EXPECT_TRUE(RelativelyNear(k.EvaluateWithGradient(p, g), 1.5, 1e-14));
    // ∇F = Σ_i g_i·Π_{j≠i} f_j = 2·(3·1e-300·1e300 + 3·1e300·1e-300)/1 ... per factor:
    // the six non-constant factors each contribute 2·(g_i/f_i) = 2 (since g_i = f_i).
    EXPECT_TRUE(RelativelyNear(g[0], 12.0, 1e-13));
    EXPECT_TRUE(RelativelyNear(g[1], -12.0, 1e-13));
    EXPECT_TRUE(RelativelyNear(g[2], 6.0, 1e-13));
    double m;
    long e;
    k.EvaluateScaled(p, m, e);
    EXPECT_TRUE(RelativelyNear(std::ldexp(m, static_cast<int>(e)), 1.5, 1e-14));
  }
}

TEST(ProductKernel, UnderflowKeepsTheSign)
{
  // 201 (odd) or 200 (even) spheres of radius 1e-2 about the origin: each is −1e-4 there,
  // so P = ∓1e-804 (far below the smallest denormal, ~4.9e-324).
  const double c[3] = { 0, 0, 0 };
  for (int count : { 200, 201 })
  {
    std::vector<Factor> factors;
    for (int i = 0; i < count; ++i)
      factors.push_back(Sphere(c, 1e-2));
    const double sign = count % 2 ? -1.0 : 1.0;
    const double p[3] = { 0, 0, 0 };
    const double tiny = sign * std::numeric_limits<double>::denorm_min();
    const ProductKernel k(factors, 0.0);
    EXPECT_EQ(k.Evaluate(p), tiny) << count << " factors";
    double g[3];
    EXPECT_EQ(k.EvaluateWithGradient(p, g), tiny);
    EXPECT_EQ(g[0], 0.0); // every ∇f_i vanishes at the centre
    double v;
    k.EvaluatePoints(p, 1, &v);
    EXPECT_EQ(v, tiny);
    std::vector<double> row(3);
    const double o[3] = { -1e-6, 0, 0 }, s[3] = { 1e-6, 0, 0 };
    k.EvaluateLine(o, s, 3, row.data());
    for (double x : row)
    {
      EXPECT_EQ(std::signbit(x), sign < 0);
      EXPECT_NE(x, 0.0);
      EXPECT_LE(std::fabs(x), 1e-300);
    }
    // With r ≠ 0 the product is negligible: F = −r.
    const ProductKernel kr(factors, 0.25);
    EXPECT_EQ(kr.Evaluate(p), -0.25);
    double m;
    long e;
    kr.EvaluateScaled(p, m, e);
    EXPECT_EQ(std::ldexp(m, static_cast<int>(e)), -0.25);
  }
}

// Regression (fixed): with r = 0, EvaluateScaled() computes F at the scale
// top = max(e, er) with er = 0 (r has no exponent), so a product below 2^-1074 is
// flushed to 0 (and below 2^-1022 loses bits): EvaluateScaled returns 0 and
// EvaluateSignAndLog returns sign 0 and -inf, although the product is ±1e-800.
TEST(ProductKernel, ScaledFormsOfAnUnderflowingProduct)
{
  const double c[3] = { 0, 0, 0 };
  for (int count : { 200, 201 })
  {
    std::vector<Factor> factors;
    for (int i = 0; i < count; ++i)
      factors.push_back(Sphere(c, 1e-2));
    const ProductKernel k(factors, 0.0);
    const double p[3] = { 0, 0, 0 };
    const int sign = count % 2 ? -1 : 1;
    double m;
    long e;
    k.EvaluateScaled(p, m, e);
    EXPECT_EQ(m > 0 ? 1 : (m < 0 ? -1 : 0), sign) << count << " factors";
    EXPECT_NEAR(std::log10(std::fabs(m)) + e * std::log10(2.0), -4.0 * count, 1e-9);
    double logAbs;
    EXPECT_EQ(k.EvaluateSignAndLog(p, logAbs), sign);
    EXPECT_TRUE(RelativelyNear(logAbs, -4.0 * count * std::log(10.0), 1e-13));
  }
  // Just below the normal range (2^-1030): F must keep all 53 bits.
  std::vector<Factor> factors = { ConstantFactor(0x1.23456789abcdfp-515),
    ConstantFactor(-0x1.fedcba9876543p-515) };
  const ProductKernel k(factors, 0.0);
  const double p[3] = { 0, 0, 0 };
  double m;
  long e;
  k.EvaluateScaled(p, m, e);
  EXPECT_EQ(e, -1028);
  EXPECT_EQ(m, -0x1.23456789abcdfp0 * 0x1.fedcba9876543p0 / 4);
}

TEST(ProductKernel, DistanceAndNormalMatchTheGradient)
{
  Random rng(49);
  for (int trial = 0; trial < 30; ++trial)
  {
    std::vector<Factor> factors;
    const int n = 2 + trial % 4;
    for (int i = 0; i < n; ++i)
      factors.push_back(trial % 7 == 3 && i == 1 ? Wave() : RandomPrimitive(rng));
    const double r = trial % 2 ? 0.2 : 0.0;
    const ProductKernel k(factors, r);
    for (int m = 0; m < 10; ++m)
    {
      const Point p = rng.InBox(-2, 2);
      double g[3], normal[3];
      const double F = k.EvaluateWithGradient(p.data(), g);
      const double gn = std::hypot(g[0], g[1], g[2]);
      const double d = k.EvaluateDistance(p.data(), normal);
      ASSERT_GT(gn, 0.0);
      EXPECT_TRUE(Near(d, F / gn, 1e-12)) << "F = " << F << ", |grad F| = " << gn;
      for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(normal[a], g[a] / gn, 1e-13);
      EXPECT_NEAR(std::hypot(normal[0], normal[1], normal[2]), 1.0, 1e-14);
    }
  }
  // A plane: the distance is exact and the normal is the unit normal.
  const ProductKernel plane({ Plane(0, 3, 4, 1.0) }, 0.5);
  const double p[3] = { 9, 0.6, 0.8 }; // n̂·p − 1 = 0, so F = −0.5
  double normal[3];
  EXPECT_NEAR(plane.EvaluateDistance(p, normal), -0.5, 1e-15);
  EXPECT_NEAR(normal[0], 0.0, 1e-16);
  EXPECT_NEAR(normal[1], 0.6, 1e-15);
  EXPECT_NEAR(normal[2], 0.8, 1e-15);
}

TEST(ProductKernel, DistanceWhereTheGradientVanishes)
{
  double normal[3] = { 5, 5, 5 };
  // Two zero factors, r = 0: F = 0 and ∇F = 0: distance 0, normal 0.
  const ProductKernel two({ Plane(1, 0, 0), Plane(0, 1, 0), Wave() }, 0.0);
  const double axis[3] = { 0, 0, 0.7 };
  EXPECT_EQ(two.EvaluateDistance(axis, normal), 0.0);
  EXPECT_EQ(normal[0], 0.0);
  EXPECT_EQ(normal[1], 0.0);
  EXPECT_EQ(normal[2], 0.0);
  // The centre of a sphere: ∇F = 0 and F = −1 − r: distance −inf.
  const double c[3] = { 1, 2, 3 };
  const ProductKernel ball({ Sphere(c, 1) }, 0.5);
  normal[0] = 5;
  const double d = ball.EvaluateDistance(c, normal);
  EXPECT_TRUE(std::isinf(d) && d < 0) << d;
  EXPECT_EQ(normal[0], 0.0);
  // Two zero factors with r > 0: F = −r, ∇F = 0: −inf.
  const ProductKernel twoR({ Plane(1, 0, 0), Plane(0, 1, 0) }, 0.25);
  const double dr = twoR.EvaluateDistance(axis, normal);
  EXPECT_TRUE(std::isinf(dr) && dr < 0) << dr;
}

TEST(ProductKernel, DistanceOfHugeAndTinyProducts)
{
  // 200 spheres of radius 1e-2 about the origin, at p = (1e-3, 0, 0): each factor is
  // 1e-6 − 1e-4 = −9.9e-5 with gradient (2e-3, 0, 0), so P = (9.9e-5)^200 ≈ 1e-802 and
  // ∇P/P = 200·(2e-3/−9.9e-5, 0, 0): F/|∇F| = −9.9e-5/(200·2e-3) when r = 0.
  const double c[3] = { 0, 0, 0 };
  for (int count : { 200, 201 })
  {
    std::vector<Factor> factors;
    for (int i = 0; i < count; ++i)
      factors.push_back(Sphere(c, 1e-2));
    const double sign = count % 2 ? -1.0 : 1.0;
    const double p[3] = { 1e-3, 0, 0 };
    const double f = 1e-6 - 1e-4;
    double normal[3];
    const ProductKernel k(factors, 0.0);
    const double d = k.EvaluateDistance(p, normal);
    EXPECT_TRUE(RelativelyNear(d, sign * std::fabs(f) / (count * 2e-3), 1e-12)) << count;
    // ∇P = P·Σ∇f_i/f_i: along −x times the sign of P.
    EXPECT_NEAR(normal[0], -sign, 1e-15);
    EXPECT_EQ(normal[1], 0.0);
    EXPECT_EQ(normal[2], 0.0);
    // With r > 0 the distance is −r/|∇F|, ~1e798: far away, outside, never NaN.
    const ProductKernel kr(factors, 0.25);
    const double dr = kr.EvaluateDistance(p, normal);
    EXPECT_LT(dr, -1e300);
    EXPECT_NEAR(normal[0], -sign, 1e-15);
  }
  // 100 factors of (x + 1e10) at x = 0: P = 1e1000, ∇P/P = (100/1e10, 0, 0), so the
  // distance is 1e10/100 = 1e8 with normal +x, although F itself is clamped.
  std::vector<Factor> big;
  for (int i = 0; i < 100; ++i)
    big.push_back(Plane(1, 0, 0, -1e10));
  const ProductKernel kb(big, 0.5);
  const double o[3] = { 0, 0, 0 };
  double normal[3];
  EXPECT_EQ(kb.Evaluate(o), DBL_MAX);
  EXPECT_TRUE(RelativelyNear(kb.EvaluateDistance(o, normal), 1e8, 1e-13));
  EXPECT_NEAR(normal[0], 1.0, 1e-15);
}

TEST(ProductKernel, SharedBetweenThreads)
{
  // "Any number of threads may share one kernel": rows evaluated concurrently give the
  // same bits as sequentially (EvaluateLine and RestrictToLine keep per-thread buffers).
  Random rng(50);
  const ProductKernel k(RandomFactors(rng, 6, true), 0.1);
  const int rows = 64, count = 300;
  std::vector<Point> origins(rows), steps(rows);
  for (int r = 0; r < rows; ++r)
  {
    origins[r] = rng.InBox(-2, 2);
    steps[r] = rng.InBox(-0.01, 0.01);
  }
  std::vector<double> expected(rows * count), got(rows * count);
  for (int r = 0; r < rows; ++r)
    k.EvaluateLine(origins[r].data(), steps[r].data(), count, &expected[r * count]);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
  {
    threads.emplace_back(
      [&, t]()
      {
        for (int rep = 0; rep < 5; ++rep)
          for (int r = t; r < rows; r += 4)
            k.EvaluateLine(origins[r].data(), steps[r].data(), count, &got[r * count]);
      });
  }
  for (auto& th : threads)
    th.join();
  for (int i = 0; i < rows * count; ++i)
    ASSERT_EQ(got[i], expected[i]) << "value " << i;
}

TEST(ProductKernel, NearestFactor)
{
  const double c0[3] = { 0, 0, 0 }, c1[3] = { 3, 0, 0 }, c2[3] = { 0, 3, 0 };
  const ProductKernel k({ Sphere(c0, 1), Sphere(c1, 1), Sphere(c2, 1), Plane(0, 0, 1, 5) }, 0.5);
  const double a[3] = { 1.1, 0, 0 };   // 0.1 from sphere 0
  const double b[3] = { 1.8, 0, 0 };   // 0.2 from sphere 1
  const double d[3] = { 0, 2.05, 0 };  // 0.05 from sphere 2
  const double e[3] = { 10, 10, 4.9 }; // 0.1 from the plane z = 5
  EXPECT_EQ(k.NearestFactor(a), 0);
  EXPECT_EQ(k.NearestFactor(b), 1);
  EXPECT_EQ(k.NearestFactor(d), 2);
  EXPECT_EQ(k.NearestFactor(e), 3);
  // The distance is |f|/|∇f|, not |f|: a sphere scaled by 100 at 0.1 is nearer than a
  // plain one at 0.2.
  PrimitiveSpec big;
  big.Type = PrimitiveType::Sphere;
  big.Scale = 100;
  const ProductKernel s({ Sphere(c1, 1), FromSpec(big) }, 0.0);
  const double between[3] = { 1.1, 0, 0 }; // 0.1 from the scaled sphere, 0.9 from the other
  EXPECT_EQ(s.NearestFactor(between), 1);
  const double nearOther[3] = { 1.8, 0, 0 }; // 0.8 from the scaled one, 0.2 from sphere 0
  EXPECT_EQ(s.NearestFactor(nearOther), 0);
  // On a zero set exactly, at the centre of a sphere (whose gradient vanishes there).
  const ProductKernel z({ Sphere(c0, 1), Plane(0, 0, 1) }, 0.0);
  EXPECT_EQ(z.NearestFactor(c0), 1);
  const double above[3] = { 0, 0, 0.5 };
  EXPECT_EQ(z.NearestFactor(above), 1); // sphere: 0.75/1 = 0.75 > plane: 0.5
}

// ---------------------------------------------------------------------------------------
// 10⁴ unit spheres at random centres in [0, 10]³, r = 0.5: the product is 10^(±thousands).
class ManySpheres : public ::testing::Test
{
protected:
  static constexpr int Count = 10000;
  static constexpr double Blending = 0.5;

  static void SetUpTestSuite()
  {
    Random rng(47);
    Centers = new std::vector<Point>();
    std::vector<Factor> factors;
    for (int i = 0; i < Count; ++i)
    {
      Centers->push_back(rng.InBox(0, 10));
      factors.push_back(Sphere(Centers->back().data(), 1.0));
    }
    Kernel = new ProductKernel(std::move(factors), Blending);
  }
  static void TearDownTestSuite()
  {
    delete Kernel;
    delete Centers;
    Kernel = nullptr;
    Centers = nullptr;
  }

  struct Reference
  {
    int SignP = 1;         // sign of Π f_i
    long double LogP = 0;  // Σ ln|f_i|
    long double Slack = 0; // how far the double evaluation may be off in LogP
    bool HasZero = false;
  };

  /// Σ ln|f_i| and Π sign f_i, in long double, independently of the kernel.
  static Reference LogSum(const double p[3])
  {
    Reference ref;
    for (const Point& c : *Centers)
    {
      // The kernel subtracts the centre in double (q = p + (−c)), then evaluates.
      long double d2 = 0;
      long double scale = 1;
      for (int a = 0; a < 3; ++a)
      {
        const long double q = static_cast<long double>(p[a]) - c[a];
        d2 += q * q;
      }
      scale += d2;
      const long double f = d2 - 1;
      if (f == 0)
      {
        ref.HasZero = true;
        continue;
      }
      if (f < 0)
        ref.SignP = -ref.SignP;
      ref.LogP += std::log(std::fabs(f));
      ref.Slack += 4 * DBL_EPSILON * scale / std::fabs(f);
    }
    return ref;
  }

  /// ln|P − r| and its sign from the reference; false where too close to call.
  static bool ExpectedF(const Reference& ref, int& sign, long double& logAbs)
  {
    const long double logR = std::log(static_cast<long double>(Blending));
    if (ref.HasZero)
      return false;
    if (ref.SignP < 0)
    {
      sign = -1; // −|P| − r
      const long double hi = std::max(ref.LogP, logR), lo = std::min(ref.LogP, logR);
      logAbs = hi + std::log1p(std::exp(lo - hi));
      return true;
    }
    const long double gap = ref.LogP - logR;
    if (std::fabs(gap) < 1e-6L + ref.Slack)
      return false;
    sign = gap > 0 ? 1 : -1;
    const long double hi = std::max(ref.LogP, logR), lo = std::min(ref.LogP, logR);
    logAbs = hi + std::log1p(-std::exp(lo - hi));
    return true;
  }

  static std::vector<Point>* Centers;
  static ProductKernel* Kernel;
};
std::vector<Point>* ManySpheres::Centers = nullptr;
ProductKernel* ManySpheres::Kernel = nullptr;

TEST_F(ManySpheres, GridIsFiniteAndSignsMatchTheLogSum)
{
  const int n = 11;
  const double lo = -1.5, hi = 11.5, h = (hi - lo) / (n - 1);
  std::vector<double> xyz;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        xyz.push_back(lo + i * h);
        xyz.push_back(lo + j * h + 0.013); // off the lattice of round numbers
        xyz.push_back(lo + k * h - 0.007);
      }
  const size_t count = xyz.size() / 3;
  std::vector<double> points(count);
  Kernel->EvaluatePoints(xyz.data(), count, points.data());
  std::vector<double> line(count);
  for (size_t row = 0; row < count; row += n)
  {
    const double step[3] = { h, 0, 0 };
    Kernel->EvaluateLine(&xyz[3 * row], step, n, &line[row]);
  }
  const long double logMax = std::log(static_cast<long double>(DBL_MAX));
  int positive = 0, negative = 0, clamped = 0, checkedLogs = 0;
  for (size_t i = 0; i < count; ++i)
  {
    const double* p = &xyz[3 * i];
    const double F = Kernel->Evaluate(p);
    double g[3];
    const double Fg = Kernel->EvaluateWithGradient(p, g);
    ASSERT_TRUE(std::isfinite(F)) << "point " << i;
    ASSERT_TRUE(std::isfinite(Fg)) << "point " << i;
    ASSERT_TRUE(std::isfinite(points[i])) << "point " << i;
    ASSERT_TRUE(std::isfinite(line[i])) << "point " << i;
    for (double gk : g)
      ASSERT_TRUE(std::isfinite(gk)) << "gradient at point " << i;

    const Reference ref = LogSum(p);
    int sign;
    long double logAbs;
    if (!ExpectedF(ref, sign, logAbs))
      continue;
    (sign > 0 ? positive : negative)++;
    EXPECT_EQ(F > 0 ? 1 : -1, sign)
      << "Evaluate at point " << i << ", log|P| = " << (double)ref.LogP;
    EXPECT_EQ(Fg > 0 ? 1 : -1, sign) << "EvaluateWithGradient at point " << i;
    EXPECT_EQ(points[i] > 0 ? 1 : -1, sign) << "EvaluatePoints at point " << i;
    EXPECT_EQ(line[i] > 0 ? 1 : -1, sign) << "EvaluateLine at point " << i;

    // Beyond the double range: exactly ±DBL_MAX.
    if (logAbs > logMax + 1)
    {
      ++clamped;
      EXPECT_EQ(F, sign * DBL_MAX) << "point " << i;
      EXPECT_EQ(Fg, sign * DBL_MAX) << "point " << i;
      EXPECT_EQ(points[i], sign * DBL_MAX) << "point " << i;
      EXPECT_EQ(line[i], sign * DBL_MAX) << "point " << i;
    }
    else if (logAbs < logMax - 1)
    {
      EXPECT_TRUE(RelativelyNear(F, sign * std::exp(static_cast<double>(logAbs)),
        1e-9 + 2 * static_cast<double>(ref.Slack)));
    }

    // The scaled forms carry the magnitude exactly.
    double m;
    long e;
    Kernel->EvaluateScaled(p, m, e);
    EXPECT_EQ(m > 0 ? 1 : -1, sign) << "EvaluateScaled at point " << i;
    EXPECT_GE(std::fabs(m), 0.5);
    EXPECT_LT(std::fabs(m), 1.0);
    const long double scaledLog =
      std::log(std::fabs(static_cast<long double>(m))) + e * std::log(static_cast<long double>(2));
    const long double tol = 1e-9L + 2 * ref.Slack + 1e-13L * std::fabs(logAbs);
    EXPECT_NEAR(
      static_cast<double>(scaledLog), static_cast<double>(logAbs), static_cast<double>(tol))
      << "EvaluateScaled at point " << i;
    // Distance and normal, from Σ∇f_i/f_i (long double, independent of the kernel).
    {
      long double S[3] = { 0, 0, 0 };
      for (const Point& c : *Centers)
      {
        long double q[3], d2 = 0;
        for (int a = 0; a < 3; ++a)
        {
          q[a] = static_cast<long double>(p[a]) - c[a];
          d2 += q[a] * q[a];
        }
        for (int a = 0; a < 3; ++a)
          S[a] += 2 * q[a] / (d2 - 1);
      }
      const long double sn = std::sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
      const long double expectedD =
        (ref.SignP - std::exp(std::log(static_cast<long double>(Blending)) - ref.LogP)) / sn;
      double normal[3];
      const double dist = Kernel->EvaluateDistance(p, normal);
      ASSERT_TRUE(std::isfinite(dist)) << "point " << i;
      EXPECT_EQ(dist > 0 ? 1 : -1, sign) << "EvaluateDistance at point " << i;
      EXPECT_TRUE(RelativelyNear(
        dist, static_cast<double>(expectedD), 1e-9 + 2 * static_cast<double>(ref.Slack)))
        << "EvaluateDistance at point " << i;
      for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(normal[a], static_cast<double>(ref.SignP * S[a] / sn),
          1e-9 + 2 * static_cast<double>(ref.Slack))
          << "normal at point " << i;
    }
    double la;
    EXPECT_EQ(Kernel->EvaluateSignAndLog(p, la), sign) << "EvaluateSignAndLog at point " << i;
    EXPECT_NEAR(la, static_cast<double>(logAbs), static_cast<double>(tol)) << "point " << i;
    ++checkedLogs;
  }
  EXPECT_GT(positive, 0);
  EXPECT_GT(negative, 0);
  EXPECT_GT(clamped, static_cast<int>(count) / 2) << "the test must exercise the clamping";
  EXPECT_GT(checkedLogs, static_cast<int>(count) * 9 / 10);
}

TEST_F(ManySpheres, NearestFactorPicksTheSphereUnderThePoint)
{
  Random rng(48);
  for (int n = 0; n < 30; ++n)
  {
    const int k = rng.Integer(0, Count - 1);
    // A point on sphere k (up to rounding).
    Point d = rng.InBox(-1, 1);
    const double len = std::hypot(d[0], d[1], d[2]);
    const Point& c = (*Centers)[k];
    const double p[3] = { c[0] + d[0] / len, c[1] + d[1] / len, c[2] + d[2] / len };
    EXPECT_EQ(Kernel->NearestFactor(p), k);
    // A point 0.01 outside sphere k, checked against the brute-force nearest surface.
    const double q[3] = { c[0] + 1.01 * d[0] / len, c[1] + 1.01 * d[1] / len,
      c[2] + 1.01 * d[2] / len };
    int best = -1;
    double bestD = 1e300;
    for (int i = 0; i < Count; ++i)
    {
      const Point& ci = (*Centers)[i];
      const double r = std::hypot(q[0] - ci[0], q[1] - ci[1], q[2] - ci[2]);
      // First-order distance of d² − 1: |r² − 1| / (2r).
      const double dist = std::fabs(r * r - 1) / (2 * r);
      if (dist < bestD)
      {
        bestD = dist;
        best = i;
      }
    }
    EXPECT_EQ(Kernel->NearestFactor(q), best);
  }
}

// The six points p ± probe·e_a in EvaluateVertexStar's order (−x, +x, −y, +y, −z, +z).
static void StarProbes(const double p[3], double probe, double q[18])
{
  for (int a = 0; a < 6; ++a)
  {
    for (int c = 0; c < 3; ++c)
      q[3 * a + c] = p[c];
    q[3 * a + a / 2] += a % 2 ? probe : -probe;
  }
}

// The one-pass attributes of a surface point (EvaluateVertexStar): the normal, |∇F|,
// the nearest factor and the six probe values agree with EvaluateVertex and
// EvaluateScaled at each probe (rotated primitives, expressions and generic factors
// included).
TEST(ProductKernel, StarEvaluationAgreesWithSeparateEvaluations)
{
  Random rng(45);
  for (int trial = 0; trial < 40; ++trial)
  {
    const std::vector<Factor> factors = RandomFactors(rng, 1 + trial % 5, trial % 4 == 3);
    const double r = trial % 2 ? 0.05 : 0.0;
    const ProductKernel k(factors, r);
    for (int s = 0; s < 20; ++s)
    {
      const Point p = rng.InBox(-2, 2);
      const double probe = trial % 3 == 0 ? 1e-3 : 0.05;
      double n1[3], n2[3], g1, g2, log1, log2, m1[6], m2[6];
      long e1[6], e2[6];
      int near1, near2;
      k.EvaluateVertex(p.data(), n1, g1, near1, &log1);
      k.EvaluateVertexStar(p.data(), probe, n2, g2, near2, log2, m2, e2);
      double q[18];
      StarProbes(p.data(), probe, q);
      for (int a = 0; a < 6; ++a)
        k.EvaluateScaled(q + 3 * a, m1[a], e1[a]);
      const double cond = Conditioning(factors, p.data());
      const double tol = std::max(1e-12, 1e-14 * cond);
      EXPECT_NEAR(g2, g1, tol * std::fabs(g1)) << "trial " << trial;
      EXPECT_NEAR(log2, log1, tol + 1e-12) << "trial " << trial;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(n2[c], n1[c], tol) << "trial " << trial << " normal " << c;
      EXPECT_EQ(near2, near1);
      for (int a = 0; a < 6; ++a)
      {
        const double v1 = std::ldexp(m1[a], static_cast<int>(e1[a]));
        const double v2 = std::ldexp(m2[a], static_cast<int>(e2[a]));
        double P = 1.0;
        for (const Factor& f : factors)
          P *= f.Evaluate(q + 3 * a);
        const double probeCond = Conditioning(factors, q + 3 * a);
        EXPECT_NEAR(v2, v1, std::max(1e-12, 1e-14 * probeCond) * std::fabs(P) + 1e-15 * r)
          << "trial " << trial << " probe " << a;
      }
    }
  }
}

// The same where plain doubles would overflow: 300 far spheres (a product of about
// 10^1200, beyond the double range: the scaled form from the start) and a factor
// with values beyond 2^64 after plain ones (the switch to the scaled form midway).
TEST(ProductKernel, StarEvaluationOfHugeProducts)
{
  auto check = [](const ProductKernel& k, const double p[3], double probe)
  {
    double n1[3], n2[3], g1, g2, log1, log2, m1[6], m2[6];
    long e1[6], e2[6];
    int near1, near2;
    k.EvaluateVertex(p, n1, g1, near1, &log1);
    k.EvaluateVertexStar(p, probe, n2, g2, near2, log2, m2, e2);
    double q[18];
    StarProbes(p, probe, q);
    for (int a = 0; a < 6; ++a)
      k.EvaluateScaled(q + 3 * a, m1[a], e1[a]);
    EXPECT_NEAR(log2, log1, 1e-10 * std::fabs(log1));
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(n2[c], n1[c], 1e-10);
    EXPECT_EQ(near2, near1);
    for (int a = 0; a < 6; ++a)
    {
      EXPECT_EQ(e2[a], e1[a]) << "probe " << a;
      EXPECT_NEAR(m2[a], m1[a], 1e-10) << "probe " << a;
    }
  };
  std::vector<Factor> far;
  for (int i = 0; i < 300; ++i)
  {
    const double c[3] = { 100.0 + i, 50.0, -20.0 };
    far.push_back(Sphere(c, 0.5));
  }
  const double p[3] = { 0.3, -0.2, 0.1 };
  check(ProductKernel(far, 1.0), p, 1e-3);
  const double o[3] = { 0, 0, 0 }, big[3] = { 1e25, 0, 0 };
  check(ProductKernel({ Sphere(o, 1.0), Sphere(big, 1.0), Plane(0, 0, 1) }, 0.25), p, 1e-2);
  // 30 spheres about 1e5 away (about 2^33 each: their plain product, 2^1000, and its
  // gradient overflow) and a near one, within the 32 factors whose values EvaluateVertex
  // computes first: the product of those values must be the scaled one.
  std::vector<Factor> many = FarSpheres();
  many.push_back(Sphere(o, 1.0));
  const ProductKernel manyKernel(many, 1.0);
  check(manyKernel, p, 1e-3);
  double n[3], g, logG;
  int nearest;
  manyKernel.EvaluateVertex(p, n, g, nearest, &logG);
  EXPECT_EQ(nearest, 30);
  EXPECT_TRUE(std::isfinite(logG));
  EXPECT_GT(logG, 600.0); // |∇F| far beyond the double range: its logarithm is finite
  EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-12);
}

// EvaluateVertices (the flying-edges mesher's vertices, four at a time: the quadrics and
// quartics in the squares of axis-aligned primitives evaluated at the four points per
// instruction, the product and normal likewise) gives each point EvaluateVertex's bits:
// axis-aligned and rotated primitives, tori and superellipsoids (quartics in the
// squares), centred expressions, generic factors; 1 to 4 points; points where a factor
// is exactly 0, where the plain product overflows (the scaled path) and far points.
TEST(ProductKernel, VerticesFourAtATimeHaveTheSingleVertexBits)
{
  auto check = [&](const ProductKernel& k, const std::vector<Point>& points, const char* what)
  {
    const int count = static_cast<int>(points.size());
    double p[ProductKernel::MaxVertices][3], n[ProductKernel::MaxVertices][3];
    double g[ProductKernel::MaxVertices];
    int nearest[ProductKernel::MaxVertices];
    for (int j = 0; j < count; ++j)
      std::copy(points[j].begin(), points[j].end(), p[j]);
    k.EvaluateVertices(count, p, n, g, nearest);
    for (int j = 0; j < count; ++j)
    {
      double n1[3], g1;
      int near1;
      k.EvaluateVertex(p[j], n1, g1, near1);
      EXPECT_TRUE(SameBits(g[j], g1)) << what << " point " << j << ": " << g[j] << " vs " << g1;
      for (int c = 0; c < 3; ++c)
        EXPECT_TRUE(SameBits(n[j][c], n1[c])) << what << " point " << j << " normal " << c;
      EXPECT_EQ(nearest[j], near1) << what << " point " << j;
    }
  };
  auto aligned = [](Random& rng)
  {
    PrimitiveSpec s;
    const int types[] = { 0, 1, 2, 3, 5, 6, 9, 11 };
    s.Type = static_cast<PrimitiveType>(types[rng.Integer(0, 7)]);
    RandomSizes(rng, s);
    // (centred about (0.7, −0.2, 0.4): a quartic in the squares there)
    s.Expression = "((x-0.7)^2 + (y+0.2)^2 + 2*(z-0.4)^2 + 0.3)^2 - 3*((x-0.7)^2 + (y+0.2)^2)";
    for (int i = 0; i < 3; ++i)
      s.Center[i] = rng.Uniform(-0.5, 0.5);
    s.Orient = rng.Integer(0, 1) ? Orientation::Default : Orientation::Axis;
    const int axis = rng.Integer(0, 2);
    s.Axis[0] = axis == 0;
    s.Axis[1] = axis == 1;
    s.Axis[2] = axis == 2;
    s.Scale = rng.Uniform(0.5, 2.0) * (rng.Integer(0, 1) ? 1 : -1);
    return FromSpec(s);
  };
  Random rng(46);
  int evenQuartics = 0;
  for (int trial = 0; trial < 200; ++trial)
  {
    std::vector<Factor> factors;
    const int n = 1 + trial % 6;
    for (int i = 0; i < n; ++i)
      factors.push_back(trial % 5 == 4 && i == 0 ? RandomPrimitive(rng) : aligned(rng));
    if (trial % 7 == 6)
      factors.push_back(Wave());
    for (Factor f : factors)
    {
      f.Polynomial.PrepareIntervals(); // (sets Diagonal, as the kernel does)
      evenQuartics += f.IsPolynomial && f.Polynomial.Poly.IsEvenQuartic() && f.Polynomial.Diagonal;
    }
    const ProductKernel k(factors, trial % 2 ? 0.05 : 0.0);
    std::vector<Point> points;
    for (int j = 0; j < 1 + trial % 4; ++j)
      points.push_back(rng.InBox(-2, 2));
    check(k, points, "random");
  }
  EXPECT_GT(evenQuartics, 50); // (the case the four-point path is for)
  // A point exactly on a sphere (its factor 0: not plain) beside ordinary ones.
  const double o[3] = { 0, 0, 0 }, c1[3] = { 3, 0, 0 };
  const PrimitiveSpec torus = SmallTorus();
  const ProductKernel onSphere({ Sphere(o, 1.0), FromSpec(torus), Sphere(c1, 0.5) }, 0.1);
  check(onSphere, { { 0.3, 0.2, 0.1 }, { 1.0, 0.0, 0.0 }, { -0.5, 0.5, 0.2 }, { 2, 1, 0 } },
    "zero factor");
  // 30 spheres about 1e5 away and a near one, with a torus: the plain product overflows.
  std::vector<Factor> many = FarSpheres();
  many.push_back(FromSpec(torus));
  check(ProductKernel(many, 1.0), { { 0.3, -0.2, 0.1 }, { 1.1, 0.2, 0.0 }, { 0, 1, 0.2 } },
    "scaled product");
  // A point whose local coordinates reach 1e30 (the quartic's term-wise path) among near
  // ones.
  check(ProductKernel({ FromSpec(torus), Sphere(o, 2.0) }, 0.5),
    { { 0.5, 0.5, 0.0 }, { 2e30, 0.0, 1.0 }, { 1.25, 0.0, 0.0 } }, "far point");
}

// EvaluateOnSegments (the mesher's Newton steps along grid edges, four at a time): F at
// a + s·d is the product of the factors' values minus r, in factor order (the same bits
// as multiplying EvaluateWithGradient's values), its slope is ∇F·d; ok is false where
// the plain product cannot be used or a point is far; and it applies only to products
// of axis-aligned quadrics and quartics in the squares.
TEST(ProductKernel, SegmentEvaluationGivesFAndItsSlopeAlongTheEdge)
{
  const PrimitiveSpec torus = SmallTorus(0.3);
  PrimitiveSpec ellipsoid;
  ellipsoid.Type = PrimitiveType::Ellipsoid;
  ellipsoid.Radii[0] = 1.5;
  ellipsoid.Radii[1] = 0.7;
  ellipsoid.Radii[2] = 0.9;
  PrimitiveSpec cup;
  cup.Type = PrimitiveType::Polynomial;
  cup.Expression = "((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)";
  const double o[3] = { 0.2, -0.1, 0.4 };
  const std::vector<Factor> factors = { FromSpec(torus), FromSpec(ellipsoid), FromSpec(cup),
    Sphere(o, 0.8) };
  const double r = 0.3;
  const ProductKernel k(factors, r);
  ASSERT_TRUE(k.HasStarFactorsOnly());
  Random rng(47);
  for (int trial = 0; trial < 100; ++trial)
  {
    const int count = 1 + trial % 4;
    double a[4][3], d[4][3], s[4], value[4], slope[4];
    bool ok[4];
    for (int j = 0; j < count; ++j)
    {
      const Point p = rng.InBox(-2, 2);
      std::copy(p.begin(), p.end(), a[j]);
      for (int c = 0; c < 3; ++c)
        d[j][c] = 0.0;
      d[j][rng.Integer(0, 2)] = rng.Uniform(0.01, 0.1);
      s[j] = rng.Uniform(0, 1);
    }
    k.EvaluateOnSegments(count, a, d, s, value, slope, ok);
    for (int j = 0; j < count; ++j)
    {
      const double x[3] = { a[j][0] + s[j] * d[j][0], a[j][1] + s[j] * d[j][1],
        a[j][2] + s[j] * d[j][2] };
      double P = 1.0;
      for (const Factor& f : factors)
      {
        double g[3];
        P *= f.EvaluateWithGradient(x, g);
      }
      const Direct direct = DirectEvaluation(factors, r, x);
      ASSERT_TRUE(ok[j]) << "trial " << trial;
      EXPECT_EQ(value[j], P - r) << "trial " << trial;
      const double along = direct.G[0] * d[j][0] + direct.G[1] * d[j][1] + direct.G[2] * d[j][2];
      const double length = std::fabs(d[j][0]) + std::fabs(d[j][1]) + std::fabs(d[j][2]);
      EXPECT_NEAR(slope[j], along, direct.GradientTolerance * length) << "trial " << trial;
    }
  }
  // A far point (the quartic's coordinates beyond 1e30) and a product beyond the plain
  // range: not ok, the caller's general path.
  double a[2][3] = { { 0.5, 0.5, 0.0 }, { 2e30, 0.0, 0.0 } },
         d[2][3] = { { 0.1, 0, 0 }, { 0.1, 0, 0 } };
  double s[2] = { 0.5, 0.5 }, value[2], slope[2];
  bool ok[2];
  k.EvaluateOnSegments(2, a, d, s, value, slope, ok);
  EXPECT_FALSE(ok[0] && ok[1]);
  const ProductKernel huge(FarSpheres(), 1.0);
  ASSERT_TRUE(huge.HasStarFactorsOnly());
  huge.EvaluateOnSegments(1, a, d, s, value, slope, ok);
  EXPECT_FALSE(ok[0]);
  // A rotated torus or a generic factor: not applicable.
  PrimitiveSpec tilted = torus;
  tilted.Orient = Orientation::Rotation;
  tilted.RotationAxis[0] = 1.0;
  tilted.RotationAngle = 30.0;
  EXPECT_FALSE(ProductKernel({ FromSpec(tilted), Sphere(o, 1.0) }, r).HasStarFactorsOnly());
  EXPECT_FALSE(ProductKernel({ FromSpec(torus), Wave() }, r).HasStarFactorsOnly());
}

// pisurf::Frexp and pisurf::Ldexp replace std::frexp and std::ldexp in the products and
// the ray roots: they must give the same bits for every double, the special ones too.
TEST(Float, FrexpAndLdexpHaveTheLibraryBits)
{
  auto same = [](double a, double b) { return SameBits(a, b) || (std::isnan(a) && std::isnan(b)); };
  std::vector<double> values = { 0.0, -0.0, 1.0, -1.0, 0.5, 3.0, 1e-300, -1e300,
    std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
    std::numeric_limits<double>::min(), std::numeric_limits<double>::denorm_min(), -4.9e-320,
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::quiet_NaN() };
  std::mt19937_64 random(7);
  for (int k = 0; k < 20000; ++k)
  {
    std::uint64_t bits = random();
    double v;
    std::memcpy(&v, &bits, sizeof v);
    values.push_back(v);
  }
  const int shifts[] = { 0, 1, -1, 7, -64, 300, -300, 1022, -1022, 1074, -1074, 2000, -2000 };
  for (double v : values)
  {
    int e1 = 12345, e2 = 12345;
    const double m1 = std::frexp(v, &e1), m2 = pisurf::Frexp(v, &e2);
    ASSERT_TRUE(same(m1, m2)) << v;
    if (std::isfinite(v))
    {
      ASSERT_EQ(e1, e2) << v;
    }
    for (int n : shifts)
    {
      ASSERT_TRUE(same(std::ldexp(v, n), pisurf::Ldexp(v, n))) << v << " " << n;
    }
  }
}

namespace
{
// Factors of every kind the Taylor enclosure meets: quadrics, a torus, a rotated
// cone, a superellipsoid of degree 6, expressions far from the origin, and a degree-10
// expression that takes the fallback.
std::vector<Factor> EnclosureFactors()
{
  std::vector<Factor> fs;
  const double c0[3] = { 0.3, -0.2, 0.1 };
  fs.push_back(Sphere(c0, 0.8));
  PrimitiveSpec torus;
  torus.Type = PrimitiveType::Torus;
  torus.MajorRadius = 0.7;
  torus.MinorRadius = 0.1;
  torus.Center[0] = 2.2;
  torus.Center[2] = -1.0;
  torus.Orient = Orientation::Axis;
  torus.Axis[0] = 0;
  torus.Axis[1] = 1;
  torus.Axis[2] = 0;
  fs.push_back(FromSpec(torus));
  PrimitiveSpec cone;
  cone.Type = PrimitiveType::Cone;
  cone.Angle = 25.0;
  cone.Orient = Orientation::Rotation;
  cone.RotationAxis[0] = 1;
  cone.RotationAxis[1] = 2;
  cone.RotationAxis[2] = -0.5;
  cone.RotationAngle = 37.0;
  cone.Center[1] = 0.4;
  fs.push_back(FromSpec(cone));
  PrimitiveSpec superellipsoid;
  superellipsoid.Type = PrimitiveType::Superellipsoid;
  superellipsoid.Exponent = 6;
  superellipsoid.Radii[0] = 1.5;
  superellipsoid.Radii[1] = 0.7;
  superellipsoid.Radii[2] = 1.1;
  fs.push_back(FromSpec(superellipsoid));
  const char* expressions[] = { "((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)",
    "0.1*x^6+0.1*y^6+(8*z+5)^6-1", "((x-1)/0.1)^2+((y+1)/0.1)^2+(z/0.9)^2-0.5",
    "(x-30)^3*(y+20)-x*y*z+40", "x^10+y^10+z^10-2" };
  for (const char* e : expressions)
  {
    PrimitiveSpec s;
    s.Type = PrimitiveType::Polynomial;
    s.Expression = e;
    fs.push_back(FromSpec(s));
  }
  return fs;
}

// EnclosureFactors, ready for the enclosures (PrepareIntervals).
std::vector<Factor> PreparedEnclosureFactors()
{
  std::vector<Factor> fs = EnclosureFactors();
  for (Factor& f : fs)
  {
    f.Polynomial.PrepareIntervals();
  }
  return fs;
}

// Box n of the enclosure tests: 1e-4 to 10 wide, within 3 of the origin, every fourth
// within 30. Returns its size.
double RandomEnclosureBox(std::mt19937& rng, int n, double box[6])
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double size = std::pow(10.0, -4.0 + 5.0 * u(rng));
  const double far = n % 4 == 0 ? 30.0 : 3.0;
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = far * (2.0 * u(rng) - 1.0);
    box[2 * a + 1] = box[2 * a] + size * (0.2 + u(rng));
  }
  return size;
}
}

// The Taylor enclosures (PolynomialFactor::EvaluateTaylor) hold every value our
// evaluations compute in the box and in each octant: by points (Evaluate) and by grid
// rows (ProductKernel::EvaluateLine's restrictions), on boxes from 1e-4 to 10 wide,
// near the origin and 30 units away.
TEST(ProductKernel, TaylorEnclosuresHoldEverySample)
{
  std::vector<Factor> fs = PreparedEnclosureFactors();
  std::mt19937 rng(11);
  int expanded = 0, fallbacks = 0;
  for (size_t f = 0; f < fs.size(); ++f)
  {
    const PolynomialFactor& factor = fs[f].Polynomial;
    ProductKernel single({ fs[f] }, 0.0);
    for (int n = 0; n < 200; ++n)
    {
      double box[6];
      const double size = RandomEnclosureBox(rng, n, box);
      Interval whole, octants[8];
      if (!factor.EvaluateTaylor(box, whole, octants))
      {
        ++fallbacks;
        continue;
      }
      ++expanded;
      ASSERT_LE(whole.Lo, whole.Hi);
      constexpr int Samples = 7;
      for (int k = 0; k < Samples; ++k)
        for (int j = 0; j < Samples; ++j)
        {
          double origin[3] = { box[0], box[2] + (box[3] - box[2]) * j / (Samples - 1),
            box[4] + (box[5] - box[4]) * k / (Samples - 1) };
          const double step[3] = { (box[1] - box[0]) / (Samples - 1), 0.0, 0.0 };
          double row[Samples];
          single.EvaluateLine(origin, step, Samples, row);
          for (int i = 0; i < Samples; ++i)
          {
            const double p[3] = { i == Samples - 1 ? box[1] : box[0] + step[0] * i, origin[1],
              origin[2] };
            const double values[2] = { factor.Evaluate(p), row[i] };
            int o = 0;
            for (int a = 0; a < 3; ++a)
            {
              o |= p[a] >= 0.5 * (box[2 * a] + box[2 * a + 1]) ? 1 << a : 0;
            }
            for (const double v : values)
            {
              EXPECT_TRUE(whole.Contains(v))
                << "factor " << f << " box " << box[0] << " " << box[2] << " " << box[4] << " size "
                << size << ": " << v << " outside [" << whole.Lo << ", " << whole.Hi << "]";
              EXPECT_TRUE(octants[o].Contains(v))
                << "factor " << f << " octant " << o << ": " << v << " outside [" << octants[o].Lo
                << ", " << octants[o].Hi << "]";
            }
          }
        }
    }
  }
  EXPECT_EQ(fallbacks, 200); // only the degree-10 expression
  EXPECT_EQ(expanded, 200 * (static_cast<int>(fs.size()) - 1));
}

// EvaluateTaylor's derivative enclosures (the ray caster's monotone leaves) hold the
// exact derivative along their axis at every sample of each octant, for every kind of
// factor (local even quartics, dense world expansions, rotated frames, degree 6), on
// boxes from 1e-4 to 10 wide, and are tight enough to give the derivative a sign on many
// octants.
TEST(ProductKernel, TaylorDerivativeEnclosuresHoldTheGradient)
{
  std::vector<Factor> fs = PreparedEnclosureFactors();
  std::mt19937 rng(13);
  int checked = 0, signedOctants = 0;
  for (size_t f = 0; f < fs.size(); ++f)
  {
    const PolynomialFactor& factor = fs[f].Polynomial;
    for (int n = 0; n < 150; ++n)
    {
      double box[6];
      const double size = RandomEnclosureBox(rng, n, box);
      const int axis = n % 3;
      Interval whole, octants[8], derivatives[8];
      for (Interval& d : derivatives)
      {
        d = { 1.0, -1.0 }; // (empty: must be written)
      }
      if (!factor.EvaluateTaylor(box, whole, octants, true, derivatives, axis))
      {
        continue;
      }
      constexpr int Samples = 5;
      for (int k = 0; k < Samples; ++k)
        for (int j = 0; j < Samples; ++j)
          for (int i = 0; i < Samples; ++i)
          {
            const int idx[3] = { i, j, k };
            double p[3];
            int o = 0;
            for (int a = 0; a < 3; ++a)
            {
              p[a] = idx[a] == Samples - 1
                ? box[2 * a + 1]
                : box[2 * a] + (box[2 * a + 1] - box[2 * a]) * idx[a] / (Samples - 1);
              o |= p[a] >= 0.5 * (box[2 * a] + box[2 * a + 1]) ? 1 << a : 0;
            }
            double g[3];
            factor.EvaluateWithGradient(p, g);
            // The sampled gradient has its own rounding: 1e-9 of the enclosure's width.
            const double w = 1e-9 * (std::fabs(derivatives[o].Lo) + std::fabs(derivatives[o].Hi));
            EXPECT_LE(derivatives[o].Lo, g[axis] + w)
              << "factor " << f << " axis " << axis << " octant " << o << " size " << size;
            EXPECT_GE(derivatives[o].Hi, g[axis] - w)
              << "factor " << f << " axis " << axis << " octant " << o << " size " << size;
            ++checked;
          }
      for (const Interval& d : derivatives)
      {
        ASSERT_LE(d.Lo, d.Hi);
        signedOctants += d.Lo > 0 || d.Hi < 0;
      }
    }
  }
  EXPECT_GT(checked, 100000);
  EXPECT_GT(signedOctants, 1000); // the enclosures are tight enough to decide signs
}

// The ray caster's monotone leaves: where ClassifyBoxAndOctants reports an octant
// monotone along an axis, F's derivative along it has that sign at every sample (the
// cup, the table's top and a leg, ten spheres), decided octants are never reported, and
// many octants the size of an octree leaf on the surface are shown monotone (measured:
// 67 % on the cup, 43 % on the table, 18 % on the ten spheres).
TEST(ProductKernel, MonotoneOctantsAreMonotone)
{
  auto expressions = [](std::initializer_list<const char*> list)
  {
    std::vector<Factor> fs;
    for (const char* e : list)
    {
      PrimitiveSpec s;
      s.Type = PrimitiveType::Polynomial;
      s.Expression = e;
      fs.push_back(FromSpec(s));
    }
    return fs;
  };
  std::vector<Factor> spheres;
  for (int i = 0; i < 10; ++i)
  {
    const double c[3] = { 1.2 * (i % 5) - 2.4, 1.2 * (i / 5) - 0.6, 0.1 * i };
    spheres.push_back(Sphere(c, 0.8));
  }
  struct Case
  {
    const char* Name;
    std::vector<Factor> Factors;
    double Blending;
    double Bounds[6];
    double Monotone; // the least share of undecided octants shown monotone
  };
  const Case cases[] = {
    { "cup",
      expressions({ "((x-2.2)^2+(z+1)^2+y^2+0.5-0.01)^2-2*((x-2.2)^2+(z+1)^2)",
        "1/8*x^2+1/8*y^2+(z+2)^2-0.1", "((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)" }),
      10.0, { -2.2, 3.4, -2.1, 2.1, -2.55, 0.25 }, 0.5 },
    { "table",
      expressions({ "0.1*x^6+0.1*y^6+(8*z+5)^6-1", "((x-1)/0.1)^2+((y-1)/0.1)^2+(z/0.9)^2-0.5" }),
      0.5, { -2.0, 2.0, -2.0, 2.0, -1.5, 0.5 }, 0.3 },
    // (ten factors: the product rule's interval terms overlap more)
    { "ten spheres", spheres, 0.5, { -3.5, 3.5, -1.7, 1.7, -0.9, 1.8 }, 0.1 },
  };
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const Case& c : cases)
  {
    const ProductKernel kernel(c.Factors, c.Blending);
    int undecided = 0, monotone = 0, samples = 0;
    for (int n = 0; n < 30000; ++n)
    {
      // Boxes of 16 to 32 pixels of a 1024² view of the bounds (the octree's parents of
      // 8-pixel leaves), at random places; the undecided ones hold the surface.
      const double size = (c.Bounds[1] - c.Bounds[0]) / 1024.0 * 16.0 * (1.0 + u(rng));
      double box[6];
      for (int a = 0; a < 3; ++a)
      {
        box[2 * a] = c.Bounds[2 * a] + (c.Bounds[2 * a + 1] - c.Bounds[2 * a]) * u(rng);
        box[2 * a + 1] = box[2 * a] + size;
      }
      const int axis = n % 3;
      int octants[8], monotony[8];
      if (kernel.ClassifyBoxAndOctants(box, octants, true, monotony, axis) != 0)
      {
        for (int o = 0; o < 8; ++o)
        {
          EXPECT_EQ(monotony[o], 0);
        }
        continue;
      }
      for (int o = 0; o < 8; ++o)
      {
        if (octants[o] != 0)
        {
          EXPECT_EQ(monotony[o], 0) << c.Name << ": a decided octant";
          continue;
        }
        ++undecided;
        if (monotony[o] == 0)
        {
          continue;
        }
        ++monotone;
        double sub[6];
        pisurf::OctantBox(box, o, sub);
        for (int k = 0; k < 27; ++k)
        {
          double p[3];
          for (int a = 0; a < 3; ++a)
          {
            p[a] = sub[2 * a] + (sub[2 * a + 1] - sub[2 * a]) * u(rng);
          }
          double normal[3], gradientNorm;
          int nearest;
          kernel.EvaluateVertex(p, normal, gradientNorm, nearest);
          EXPECT_GT(normal[axis] * monotony[o], 0.0)
            << c.Name << ": octant " << o << " of a box at " << box[0] << " " << box[2] << " "
            << box[4] << " reported " << monotony[o] << " along axis " << axis;
          ++samples;
        }
      }
    }
    EXPECT_GT(undecided, 500) << c.Name;
    EXPECT_GT(monotone, c.Monotone * undecided) << c.Name;
    std::printf("%s: %d of %d undecided octants monotone (%d samples)\n", c.Name, monotone,
      undecided, samples);
  }
}

// The classifiers take the Taylor forms alone first and intersect them with the
// expressions as written only where those cannot decide: EvaluateTaylor without the
// natural form, then IntersectNatural, must give EvaluateTaylor's own bits, and the
// Taylor form alone must contain them.
TEST(ProductKernel, NaturalIntersectionAfterwardsIsTheSame)
{
  std::vector<Factor> fs = EnclosureFactors();
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int natural = 0;
  for (Factor& factor : fs)
  {
    PolynomialFactor& f = factor.Polynomial;
    f.PrepareIntervals();
    natural += f.HasNaturalForm() ? 1 : 0;
    for (int n = 0; n < 100; ++n)
    {
      const double size = std::pow(10.0, -3.0 + 4.0 * u(rng));
      double box[6];
      for (int a = 0; a < 3; ++a)
      {
        box[2 * a] = 3.0 * (2.0 * u(rng) - 1.0);
        box[2 * a + 1] = box[2 * a] + size * (0.2 + u(rng));
      }
      Interval whole, octants[8], lazy, lazyOctants[8];
      if (!f.EvaluateTaylor(box, whole, octants))
      {
        continue;
      }
      ASSERT_TRUE(f.EvaluateTaylor(box, lazy, lazyOctants, false));
      EXPECT_LE(lazy.Lo, whole.Lo);
      EXPECT_GE(lazy.Hi, whole.Hi);
      if (f.HasNaturalForm())
      {
        f.IntersectNatural(box, lazy, lazyOctants);
      }
      EXPECT_EQ(lazy.Lo, whole.Lo);
      EXPECT_EQ(lazy.Hi, whole.Hi);
      for (int o = 0; o < 8; ++o)
      {
        EXPECT_EQ(lazyOctants[o].Lo, octants[o].Lo) << "octant " << o;
        EXPECT_EQ(lazyOctants[o].Hi, octants[o].Hi) << "octant " << o;
      }
    }
  }
  EXPECT_GT(natural, 0); // the test reaches IntersectNatural
}

// The product's classification of a box and its octants never contradicts the signs of
// F in them, and it decides what the paper's cup needs decided: on the 32³ boxes of its
// bounds (the mesher's blocks at 256³), the Taylor form decides 26 700 (the monomial,
// expression and mean-value forms together decided 23 500); a leg of the table is
// positive on a box next to it where the monomial form spans zero.
TEST(ProductKernel, ClassificationIsRightAndTight)
{
  const char* cup[] = { "((x-2.2)^2+(z+1)^2+y^2+0.5-0.01)^2-2*((x-2.2)^2+(z+1)^2)",
    "1/8*x^2+1/8*y^2+(z+2)^2-0.1", "((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)" };
  std::vector<Factor> fs;
  for (const char* e : cup)
  {
    PrimitiveSpec s;
    s.Type = PrimitiveType::Polynomial;
    s.Expression = e;
    fs.push_back(FromSpec(s));
  }
  const ProductKernel kernel(fs, 10.0);
  const double bounds[6] = { -2.2, 3.4, -2.1, 2.1, -2.55, 0.25 };
  const int n = 32;
  int decided = 0, octantsDecided = 0, allDecided = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
      {
        const int idx[3] = { x, y, z };
        double box[6];
        for (int a = 0; a < 3; ++a)
        {
          const double w = (bounds[2 * a + 1] - bounds[2 * a]) / n;
          box[2 * a] = bounds[2 * a] + idx[a] * w;
          box[2 * a + 1] = box[2 * a] + w;
        }
        int octants[8], all[8];
        const int sign = kernel.ClassifyBoxAndOctants(box, octants);
        EXPECT_EQ(sign, kernel.ClassifyBox(box));
        decided += sign != 0;
        // Every octant (the ray caster's octree): the same signs up to the first
        // undecided octant, then the rest too (each checked against F below).
        EXPECT_EQ(kernel.ClassifyBoxAndOctants(box, all, true), sign);
        if (sign == 0)
        {
          bool prefix = true;
          for (int o = 0; o < 8; ++o)
          {
            allDecided += all[o] != 0;
            if (prefix)
            {
              EXPECT_EQ(all[o], octants[o]);
              prefix = octants[o] != 0;
            }
          }
        }
        for (int q = 0; q < 27; ++q)
        {
          const int t[3] = { q % 3, (q / 3) % 3, q / 9 };
          double p[3];
          int o = 0;
          for (int a = 0; a < 3; ++a)
          {
            p[a] = box[2 * a] + 0.5 * t[a] * (box[2 * a + 1] - box[2 * a]);
            o |= t[a] >= 1 ? 1 << a : 0;
          }
          const double F = kernel.Evaluate(p);
          const int expected = sign != 0 ? sign : octants[o];
          if (expected != 0)
          {
            EXPECT_EQ(expected > 0, F > 0) << p[0] << " " << p[1] << " " << p[2];
          }
          if (sign == 0 && all[o] != 0)
          {
            EXPECT_EQ(all[o] > 0, F > 0) << p[0] << " " << p[1] << " " << p[2];
          }
          // The centre plane belongs to both halves: the lower octant must agree too.
          if (sign == 0 && (t[0] == 1 || t[1] == 1 || t[2] == 1))
          {
            const int lower =
              o & ~((t[0] == 1 ? 1 : 0) | (t[1] == 1 ? 2 : 0) | (t[2] == 1 ? 4 : 0));
            if (octants[lower] != 0)
            {
              EXPECT_EQ(octants[lower] > 0, F > 0);
            }
            if (all[lower] != 0)
            {
              EXPECT_EQ(all[lower] > 0, F > 0);
            }
          }
        }
        if (sign == 0)
        {
          for (int o = 0; o < 8; ++o)
          {
            octantsDecided += octants[o] != 0;
          }
        }
      }
  EXPECT_GE(decided, 26500);
  EXPECT_GT(octantsDecided, 0);
  // Past the first undecided octant the rest are still worth deciding (the ray caster's
  // octree skips them): the all-octants mode decides more of them.
  EXPECT_GT(allDecided, octantsDecided);

  PrimitiveSpec leg;
  leg.Type = PrimitiveType::Polynomial;
  leg.Expression = "((x+1)/0.1)^2+((y+1)/0.1)^2+(z/0.9)^2-0.5";
  Factor f = FromSpec(leg);
  f.Polynomial.PrepareIntervals();
  const double box[6] = { -1.09375, -0.984375, -1.09375, -0.984375, -0.9, -0.848438 };
  Interval local[3];
  f.Polynomial.LocalBox(box, local);
  // (Written about (−1, −1, 0), the leg is centred there by BuildFactor: term by term,
  // the expansion about the origin gave a negative lower bound here.)
  EXPECT_GT(f.Polynomial.Poly.EvaluateInterval(local).Lo, 0.3);
  Interval whole;
  ASSERT_TRUE(f.Polynomial.EvaluateTaylor(box, whole, nullptr));
  EXPECT_GT(whole.Lo, 0.3);
}

// Along a world axis, the factors' univariate restrictions (RestrictToAxis) give F as
// the trivariate evaluation does, and the slope of EvaluateOnAxisWithSlope is ∂F/∂axis;
// a rotated factor refuses (its local axes are not world axes).
TEST(ProductKernel, AxisRestrictionMatchesEvaluation)
{
  std::vector<Factor> fs;
  const double c0[3] = { 0.3, -0.2, 0.1 }, c1[3] = { -0.4, 0.5, 0.2 };
  fs.push_back(Sphere(c0, 0.8));
  fs.push_back(Sphere(c1, 0.6));
  for (const char* e : { "((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)",
         "0.1*x^6+0.1*y^6+(8*z+5)^6-1", "x*y*z+x^2*z-3*y+0.5" })
  {
    PrimitiveSpec s;
    s.Type = PrimitiveType::Polynomial;
    s.Expression = e;
    s.Center[0] = 0.25;
    s.Scale = 0.01;
    fs.push_back(FromSpec(s));
  }
  PrimitiveSpec flipped; // axis −z: a diagonal frame with negative entries
  flipped.Type = PrimitiveType::Torus;
  flipped.MajorRadius = 0.9;
  flipped.MinorRadius = 0.3;
  flipped.Center[2] = 0.4;
  flipped.Orient = Orientation::Axis;
  flipped.Axis[0] = 0;
  flipped.Axis[1] = 0;
  flipped.Axis[2] = -1;
  fs.push_back(FromSpec(flipped));
  const ProductKernel kernel(fs, 0.3);
  ASSERT_TRUE(kernel.GetFactor(fs.size() - 1).Polynomial.Diagonal);
  std::vector<double> line(kernel.GetLineCoefficientCount());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  for (int n = 0; n < 300; ++n)
  {
    double p[3] = { u(rng), u(rng), u(rng) };
    const int axis = n % 3;
    ASSERT_TRUE(kernel.RestrictToAxis(p, axis, line.data()));
    for (const double dx : { 0.0, 0.013, -0.21 })
    {
      double q[3] = { p[0], p[1], p[2] };
      q[axis] += dx;
      double g[3];
      const double F = kernel.EvaluateWithGradient(q, g);
      const double scale = 1e-11 * (1.0 + std::fabs(F));
      EXPECT_NEAR(kernel.EvaluateOnAxis(line.data(), axis, q[axis]), F, scale);
      double value, slope;
      ASSERT_TRUE(kernel.EvaluateOnAxisWithSlope(line.data(), axis, q[axis], value, slope));
      EXPECT_NEAR(value, F, scale);
      EXPECT_NEAR(slope, g[axis], 1e-10 * (1.0 + std::fabs(g[axis])));
    }
  }
  PrimitiveSpec cone;
  cone.Type = PrimitiveType::Cone;
  cone.Orient = Orientation::Rotation;
  cone.RotationAxis[0] = 1;
  cone.RotationAngle = 30.0;
  fs.push_back(FromSpec(cone));
  const ProductKernel rotated(fs, 0.3);
  std::vector<double> line2(rotated.GetLineCoefficientCount());
  const double p[3] = { 0.1, 0.2, 0.3 };
  EXPECT_FALSE(rotated.RestrictToAxis(p, 0, line2.data()));
}

// For products far outside the double range, EvaluateOnAxisLog gives ln|P| as the
// overflow-safe evaluation does (r = 0: F = P), F's exact sign with r ≠ 0, and
// d ln|P|/dx as a difference quotient of ln|P| shows.
TEST(ProductKernel, AxisLogarithmOfHugeProducts)
{
  std::vector<Factor> fs;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 400; ++i)
  {
    const double c[3] = { u(rng), u(rng), u(rng) };
    fs.push_back(Sphere(c, 0.3));
  }
  const ProductKernel product(fs, 0.0), blended(fs, 0.01);
  std::vector<double> line(product.GetLineCoefficientCount());
  int checked = 0;
  for (int n = 0; n < 100; ++n)
  {
    const double p[3] = { 2.0 * u(rng), 2.0 * u(rng), 2.0 * u(rng) };
    const int axis = n % 3;
    ASSERT_TRUE(product.RestrictToAxis(p, axis, line.data()));
    double F, logP, slope;
    int sign;
    product.EvaluateOnAxisLog(line.data(), axis, p[axis], F, sign, logP, slope);
    double logAbs;
    const int expected = product.EvaluateSignAndLog(p, logAbs);
    ASSERT_EQ(sign, expected);
    if (sign == 0)
    {
      continue;
    }
    ++checked;
    EXPECT_NEAR(logP, logAbs, 1e-9 * (1.0 + std::fabs(logAbs)));
    EXPECT_GT(std::fabs(logP), 100.0); // far beyond the double range's ~709
    const double h = 1e-6;
    double F1, logP1, slope1, F0, logP0, slope0;
    int s1, s0;
    product.EvaluateOnAxisLog(line.data(), axis, p[axis] + h, F1, s1, logP1, slope1);
    product.EvaluateOnAxisLog(line.data(), axis, p[axis] - h, F0, s0, logP0, slope0);
    EXPECT_NEAR(slope, (logP1 - logP0) / (2 * h), 1e-4 * (1.0 + std::fabs(slope)));
    // With r: the sign of F = P − r, as the scaled evaluation gives it.
    double Fr, logPr, sloper;
    int signr;
    blended.EvaluateOnAxisLog(line.data(), axis, p[axis], Fr, signr, logPr, sloper);
    const double direct = blended.Evaluate(p);
    EXPECT_EQ(Fr > 0, direct > 0);
    EXPECT_EQ(Fr < 0, direct < 0);
  }
  EXPECT_GT(checked, 90);
}

// Products of diagonal quadrics (spheres, ellipsoids, axis-aligned cylinders) are
// evaluated four factors at a time from packed arrays. Their vertex attributes, axis
// restrictions and Newton values must have the bits of the factor-by-factor code: the
// same product with a polynomial factor 1 appended (which multiplies exactly and turns
// the packing off).
TEST(ProductKernel, PackedQuadricsHaveTheBitsOfFactorByFactorEvaluation)
{
  Random rng(77);
  for (int trial = 0; trial < 12; ++trial)
  {
    std::vector<Factor> factors;
    const int count = 1 + (trial * 7) % 31; // 1 to 31 factors: partial groups of four
    for (int i = 0; i < count; ++i)
    {
      PrimitiveSpec s;
      s.Type = i % 3 == 0 ? PrimitiveType::Sphere
                          : (i % 3 == 1 ? PrimitiveType::Ellipsoid : PrimitiveType::Cylinder);
      const Point c = rng.InBox(-1, 1);
      std::copy(c.begin(), c.end(), s.Center);
      s.Radius = rng.Uniform(0.3, 1.0);
      s.Radii[0] = rng.Uniform(0.3, 1.0);
      s.Radii[1] = rng.Uniform(0.3, 1.0);
      s.Radii[2] = rng.Uniform(0.3, 1.0);
      factors.push_back(FromSpec(s));
      if (i % 4 == 3)
      {
        // A general quadric (cross terms too) in a scaled, translated frame.
        Factor g;
        g.Polynomial.Poly = rng.Polynomial(2, 10) + Polynomial3::Constant(-0.5);
        g.Polynomial.Poly.AddTerm(1.0, 2, 0, 0);
        for (int a = 0; a < 3; ++a)
        {
          g.Polynomial.A[a][a] = rng.Uniform(0.5, 2.0);
          g.Polynomial.B[a] = rng.Uniform(-0.3, 0.3);
        }
        factors.back() = g;
      }
    }
    const double r = trial % 2 ? 0.25 : 1e-3;
    const ProductKernel packed(factors, r);
    ASSERT_TRUE(packed.GetFactor(0).Polynomial.Diagonal);
    Factor one;
    one.Polynomial.Poly = Polynomial3::Constant(1.0);
    factors.push_back(one);
    const ProductKernel plain(factors, r);
    std::vector<double> lineA(packed.GetLineCoefficientCount() + 1),
      lineB(plain.GetLineCoefficientCount());
    for (int n = 0; n < 200; ++n)
    {
      const Point p = rng.InBox(-1.5, 1.5);
      double nA[3], nB[3], gA, gB, lA, lB;
      int fA, fB;
      packed.EvaluateVertex(p.data(), nA, gA, fA, &lA);
      plain.EvaluateVertex(p.data(), nB, gB, fB, &lB);
      EXPECT_EQ(gA, gB);
      EXPECT_EQ(lA, lB);
      EXPECT_EQ(fA, fB);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(nA[a], nB[a]);
      }
      const int axis = n % 3;
      ASSERT_TRUE(packed.RestrictToAxis(p.data(), axis, lineA.data()));
      ASSERT_TRUE(plain.RestrictToAxis(p.data(), axis, lineB.data()));
      for (size_t m = 0; m + 1 < lineB.size(); ++m)
      {
        EXPECT_EQ(lineA[m], lineB[m]) << "coefficient " << m;
      }
      double vA, vB, sA, sB;
      const double x = p[axis] + rng.Uniform(-0.05, 0.05);
      const bool okA = packed.EvaluateOnAxisWithSlope(lineA.data(), axis, x, vA, sA);
      const bool okB = plain.EvaluateOnAxisWithSlope(lineB.data(), axis, x, vB, sB);
      EXPECT_EQ(okA, okB);
      if (okA && okB)
      {
        EXPECT_EQ(vA, vB);
        EXPECT_EQ(sA, sB);
      }
    }
  }
}
