// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of pisurf::Polynomial3 (PiPolynomial.h).
#include "PiCoreTestUtilities.h"
#include "PiExpression.h"
#include "PiPolynomial.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using pisurf::Polynomial3;
using namespace pisurf_test;

namespace
{
/// Σ |c|·|x|^i·|y|^j·|z|^k: the scale of the rounding errors of an evaluation.
double AbsEvaluate(const Polynomial3& p, const double q[3])
{
  double v = 0.0;
  for (const auto& t : p.GetTerms())
  {
    v += std::fabs(t.Coefficient) * std::pow(std::fabs(q[0]), t.I) *
      std::pow(std::fabs(q[1]), t.J) * std::pow(std::fabs(q[2]), t.K);
  }
  return v;
}

/// Straightforward evaluation with std::pow, independent of Polynomial3::Evaluate.
double NaiveEvaluate(const Polynomial3& p, const double q[3])
{
  double v = 0.0;
  for (const auto& t : p.GetTerms())
  {
    v += t.Coefficient * std::pow(q[0], t.I) * std::pow(q[1], t.J) * std::pow(q[2], t.K);
  }
  return v;
}

Polynomial3 X()
{
  return Polynomial3::Variable(0);
}
Polynomial3 Y()
{
  return Polynomial3::Variable(1);
}
Polynomial3 Z()
{
  return Polynomial3::Variable(2);
}
Polynomial3 C(double c)
{
  return Polynomial3::Constant(c);
}
}

TEST(Polynomial3, ConstantsAndVariables)
{
  const Polynomial3 zero;
  EXPECT_TRUE(zero.IsZero());
  EXPECT_TRUE(zero.IsConstant());
  EXPECT_EQ(zero.GetDegree(), -1);
  EXPECT_EQ(zero.ToString(), "0");
  const double p[3] = { 1.5, -2.0, 3.0 };
  EXPECT_EQ(zero.Evaluate(p), 0.0);

  const Polynomial3 c = C(2.5);
  EXPECT_TRUE(c.IsConstant());
  EXPECT_FALSE(c.IsZero());
  EXPECT_EQ(c.GetDegree(), 0);
  EXPECT_EQ(c.Evaluate(p), 2.5);
  EXPECT_TRUE(C(0.0).IsZero()) << "a zero constant has no terms";

  for (int a = 0; a < 3; ++a)
  {
    const Polynomial3 v = Polynomial3::Variable(a);
    EXPECT_EQ(v.GetDegree(), 1);
    EXPECT_FALSE(v.IsConstant());
    EXPECT_EQ(v.Evaluate(p), p[a]);
    EXPECT_EQ(v.GetAxisDegree(a), 1);
    EXPECT_EQ(v.GetAxisDegree((a + 1) % 3), 0);
    EXPECT_EQ(v.GetCoefficient(a == 0, a == 1, a == 2), 1.0);
  }
}

TEST(Polynomial3, AddTermMergesSortsAndCancels)
{
  Polynomial3 p;
  p.AddTerm(3.0, 0, 2, 1);
  p.AddTerm(1.0, 2, 0, 0);
  p.AddTerm(-1.0, 0, 0, 0);
  p.AddTerm(2.0, 2, 0, 0); // merges with x^2
  EXPECT_EQ(p.GetTerms().size(), 3u);
  EXPECT_EQ(p.GetCoefficient(2, 0, 0), 3.0);
  EXPECT_EQ(p.GetCoefficient(0, 2, 1), 3.0);
  EXPECT_EQ(p.GetCoefficient(0, 0, 0), -1.0);
  EXPECT_EQ(p.GetCoefficient(1, 1, 1), 0.0);
  EXPECT_EQ(p.GetDegree(), 3);
  EXPECT_EQ(p.GetAxisDegree(0), 2);
  EXPECT_EQ(p.GetAxisDegree(1), 2);
  EXPECT_EQ(p.GetAxisDegree(2), 1);
  // Sorted by (i, j, k).
  const auto& t = p.GetTerms();
  for (size_t n = 1; n < t.size(); ++n)
  {
    EXPECT_LT(
      std::make_tuple(t[n - 1].I, t[n - 1].J, t[n - 1].K), std::make_tuple(t[n].I, t[n].J, t[n].K));
  }
  // Cancelling the degree-3 term lowers the degree.
  p.AddTerm(-3.0, 0, 2, 1);
  EXPECT_EQ(p.GetTerms().size(), 2u);
  EXPECT_EQ(p.GetDegree(), 2);
  EXPECT_EQ(p.GetCoefficient(0, 2, 1), 0.0);
  // Adding a zero coefficient changes nothing.
  p.AddTerm(0.0, 5, 5, 5);
  EXPECT_EQ(p.GetDegree(), 2);
  EXPECT_EQ(p.GetTerms().size(), 2u);
}

TEST(Polynomial3, EqualPolynomialsHaveEqualTerms)
{
  // (x + 1)(x − 1) and x² − 1 built differently compare equal term by term.
  const Polynomial3 a = (X() + C(1)) * (X() - C(1));
  Polynomial3 b;
  b.AddTerm(-1.0, 0, 0, 0);
  b.AddTerm(1.0, 2, 0, 0);
  EXPECT_TRUE(SameTerms(a, b));
  // x − x is the zero polynomial, with degree −1.
  const Polynomial3 d = X() - X();
  EXPECT_TRUE(d.IsZero());
  EXPECT_EQ(d.GetDegree(), -1);
  // Scaling by 0 drops every term.
  EXPECT_TRUE((X() * Y() + C(3)).Scaled(0.0).IsZero());
}

TEST(Polynomial3, IsFinite)
{
  EXPECT_TRUE((X() * C(1e300)).IsFinite());
  EXPECT_FALSE((X() * C(1e300) * C(1e300)).IsFinite());
  Polynomial3 p = Y();
  p.AddTerm(std::numeric_limits<double>::quiet_NaN(), 1, 0, 0);
  EXPECT_FALSE(p.IsFinite());
}

TEST(Polynomial3, EvaluateKnownValues)
{
  // 3x²y − 2z + 5 at (1, 2, 3) = 6 − 6 + 5.
  Polynomial3 p = C(3) * X().Pow(2) * Y() - Z().Scaled(2.0) + C(5);
  const double q[3] = { 1.0, 2.0, 3.0 };
  EXPECT_DOUBLE_EQ(p.Evaluate(q), 5.0);
  double g[3];
  EXPECT_DOUBLE_EQ(p.EvaluateWithGradient(q, g), 5.0);
  EXPECT_DOUBLE_EQ(g[0], 12.0); // 6xy
  EXPECT_DOUBLE_EQ(g[1], 3.0);  // 3x²
  EXPECT_DOUBLE_EQ(g[2], -2.0);
  // 0^0 = 1: the constant term at the origin.
  const double o[3] = { 0, 0, 0 };
  EXPECT_EQ(p.Evaluate(o), 5.0);
}

TEST(Polynomial3, EvaluateMatchesNaiveEvaluation)
{
  Random rng(1);
  for (int n = 0; n < 50; ++n)
  {
    const Polynomial3 p = rng.Polynomial(8, 12);
    const Point q = rng.InBox(-1.5, 1.5);
    EXPECT_TRUE(Near(p.Evaluate(q.data()), NaiveEvaluate(p, q.data()),
      1e-13 * std::max(1.0, AbsEvaluate(p, q.data()))))
      << p.ToString();
  }
}

TEST(Polynomial3, HighestDegreeEvaluates)
{
  const Polynomial3 p = X().Pow(pisurf::MaxDegree) + Y() * Z().Pow(pisurf::MaxDegree - 1);
  EXPECT_EQ(p.GetDegree(), pisurf::MaxDegree);
  const double q[3] = { 1.01, 0.5, -1.02 };
  const double expected =
    std::pow(1.01, pisurf::MaxDegree) + 0.5 * std::pow(-1.02, pisurf::MaxDegree - 1);
  EXPECT_TRUE(RelativelyNear(p.Evaluate(q), expected, 1e-13));
}

TEST(Polynomial3, AlgebraMatchesDirectEvaluation)
{
  Random rng(2);
  for (int n = 0; n < 40; ++n)
  {
    const Polynomial3 a = rng.Polynomial(4, 8);
    const Polynomial3 b = rng.Polynomial(4, 8);
    const double s = rng.Uniform(-3, 3);
    for (int k = 0; k < 5; ++k)
    {
      const Point q = rng.InBox(-1.5, 1.5);
      const double va = a.Evaluate(q.data()), vb = b.Evaluate(q.data());
      const double sa = AbsEvaluate(a, q.data()), sb = AbsEvaluate(b, q.data());
      const double tolSum = 1e-13 * std::max(1.0, sa + sb);
      EXPECT_TRUE(Near((a + b).Evaluate(q.data()), va + vb, tolSum));
      EXPECT_TRUE(Near((a - b).Evaluate(q.data()), va - vb, tolSum));
      EXPECT_TRUE(Near((-a).Evaluate(q.data()), -va, 1e-15));
      EXPECT_TRUE(Near(a.Scaled(s).Evaluate(q.data()), s * va, 1e-13 * std::max(1.0, 3 * sa)));
      EXPECT_TRUE(Near((a * b).Evaluate(q.data()), va * vb, 1e-12 * std::max(1.0, sa * sb)))
        << a.ToString() << " times " << b.ToString();
    }
    // Degrees add up under the product (non-zero leading parts never cancel in
    // exact arithmetic; random coefficients make it almost sure in floating point).
    if (!a.IsZero() && !b.IsZero())
    {
      EXPECT_EQ((a * b).GetDegree(), a.GetDegree() + b.GetDegree());
    }
  }
}

TEST(Polynomial3, PowMatchesRepeatedProductAndEvaluation)
{
  Random rng(3);
  for (int n = 0; n < 20; ++n)
  {
    const Polynomial3 a = rng.Polynomial(3, 6);
    Polynomial3 repeated = C(1);
    for (int e = 0; e <= 7; ++e)
    {
      const Polynomial3 pw = a.Pow(e);
      EXPECT_TRUE(SameTermsNear(pw, repeated, 1e-13)) << "power " << e;
      if (!a.IsZero())
      {
        EXPECT_EQ(pw.GetDegree(), e * std::max(a.GetDegree(), 0));
      }
      const Point q = rng.InBox(-1.2, 1.2);
      const double sa = AbsEvaluate(a, q.data());
      EXPECT_TRUE(Near(pw.Evaluate(q.data()), std::pow(a.Evaluate(q.data()), e),
        1e-12 * std::max(1.0, std::pow(sa, e))))
        << "power " << e << " of " << a.ToString();
      repeated = repeated * a;
    }
  }
  // Pow(0) of anything, even of the zero polynomial, is the constant 1.
  EXPECT_TRUE(SameTerms(Polynomial3().Pow(0), C(1)));
  EXPECT_TRUE(SameTerms((X() + Y()).Pow(0), C(1)));
  // (x + y)^3 by the binomial theorem.
  const Polynomial3 b = (X() + Y()).Pow(3);
  EXPECT_EQ(b.GetCoefficient(3, 0, 0), 1.0);
  EXPECT_EQ(b.GetCoefficient(2, 1, 0), 3.0);
  EXPECT_EQ(b.GetCoefficient(1, 2, 0), 3.0);
  EXPECT_EQ(b.GetCoefficient(0, 3, 0), 1.0);
  EXPECT_EQ(b.GetTerms().size(), 4u);
}

TEST(Polynomial3, ComposeMatchesEvaluationOfTheAffineMap)
{
  Random rng(4);
  for (int n = 0; n < 30; ++n)
  {
    const Polynomial3 p = rng.Polynomial(5, 10);
    double A[3][3], b[3];
    for (int i = 0; i < 3; ++i)
    {
      b[i] = rng.Uniform(-1, 1);
      for (int j = 0; j < 3; ++j)
      {
        A[i][j] = rng.Uniform(-1, 1);
      }
    }
    const Polynomial3 c = p.Compose(A, b);
    EXPECT_LE(c.GetDegree(), p.GetDegree());
    for (int k = 0; k < 5; ++k)
    {
      const Point x = rng.InBox(-1, 1);
      double q[3];
      for (int i = 0; i < 3; ++i)
      {
        q[i] = A[i][0] * x[0] + A[i][1] * x[1] + A[i][2] * x[2] + b[i];
      }
      // The expansion's rounding scale: |p| evaluated with |A|·|x| + |b|.
      double qa[3];
      for (int i = 0; i < 3; ++i)
      {
        qa[i] = std::fabs(A[i][0] * x[0]) + std::fabs(A[i][1] * x[1]) + std::fabs(A[i][2] * x[2]) +
          std::fabs(b[i]);
      }
      EXPECT_TRUE(
        Near(c.Evaluate(x.data()), p.Evaluate(q), 1e-12 * std::max(1.0, AbsEvaluate(p, qa))))
        << p.ToString();
    }
  }
  // A known case: x² composed with x ← 2y + 1 is 4y² + 4y + 1.
  const double A[3][3] = { { 0, 2, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  const double b[3] = { 1, 0, 0 };
  const Polynomial3 c = X().Pow(2).Compose(A, b);
  EXPECT_EQ(c.GetCoefficient(0, 2, 0), 4.0);
  EXPECT_EQ(c.GetCoefficient(0, 1, 0), 4.0);
  EXPECT_EQ(c.GetCoefficient(0, 0, 0), 1.0);
  EXPECT_EQ(c.GetTerms().size(), 3u);
}

TEST(Polynomial3, GradientMatchesFiniteDifferences)
{
  Random rng(5);
  for (int n = 0; n < 50; ++n)
  {
    const Polynomial3 p = rng.Polynomial(6, 10);
    const Point q = rng.InBox(-1.2, 1.2);
    double g[3];
    const double v = p.EvaluateWithGradient(q.data(), g);
    EXPECT_TRUE(Near(v, p.Evaluate(q.data()), 1e-14 * std::max(1.0, AbsEvaluate(p, q.data()))));
    const Point fd =
      FiniteDifferenceGradient([&](const double* x) { return p.Evaluate(x); }, q.data(), 1e-5);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_TRUE(Near(g[k], fd[k], 1e-6 * std::max(1.0, AbsEvaluate(p, q.data()) * 36)))
        << "component " << k << " of the gradient of " << p.ToString();
    }
  }
}

// EvaluateWithGradient at q against the term sums and the exact derivatives.
static void ExpectValueAndGradient(const Polynomial3& p, const Point& q)
{
  double g[3];
  const double v = p.EvaluateWithGradient(q.data(), g);
  const double magnitude = std::max(1.0, AbsEvaluate(p, q.data()));
  EXPECT_TRUE(Near(v, NaiveEvaluate(p, q.data()), 1e-13 * magnitude)) << p.ToString();
  for (int a = 0; a < 3; ++a)
  {
    const Polynomial3 d = p.Derivative(a);
    EXPECT_TRUE(Near(g[a], d.Evaluate(q.data()),
      1e-13 * std::max(1.0, AbsEvaluate(d, q.data())) * std::max(p.GetDegree(), 1)))
      << "component " << a << " of the gradient of " << p.ToString();
  }
}

// Dense polynomials of degree 3 to 6 (tori, expanded products) take nested Horner's
// rule: value and gradient as the term sums and the exact derivatives give them, also
// with some coefficients absent, and the polynomial's own frame of large coordinates.
TEST(Polynomial3, DenseGradientIsTheDerivativesValue)
{
  Random rng(11);
  for (int trial = 0; trial < 200; ++trial)
  {
    const int degree = 3 + trial % 4;
    Polynomial3 p;
    for (int k = 0; k <= degree; ++k)
    {
      for (int j = 0; j + k <= degree; ++j)
      {
        for (int i = 0; i + j + k <= degree; ++i)
        {
          if (rng.Uniform(0, 1) < 0.7 || i + j + k == degree)
          {
            p.AddTerm(rng.Uniform(-2.0, 2.0), i, j, k);
          }
        }
      }
    }
    const double scale = trial % 3 == 0 ? 30.0 : 1.5;
    ExpectValueAndGradient(p, rng.InBox(-scale, scale));
  }
}

// Quartics with only even powers (a torus or a superquadric about its centre) are
// evaluated as a quadric of the squares: the value, the gradient and the axis
// restrictions are the polynomial's.
TEST(Polynomial3, EvenQuarticIsItsQuadricOfSquares)
{
  Random rng(12);
  const int squares[10][3] = { { 0, 0, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, { 0, 0, 2 }, { 4, 0, 0 },
    { 0, 4, 0 }, { 0, 0, 4 }, { 2, 2, 0 }, { 2, 0, 2 }, { 0, 2, 2 } };
  for (int trial = 0; trial < 200; ++trial)
  {
    Polynomial3 p;
    for (int m = 0; m < 10; ++m)
    {
      if (m >= 4 && m <= 6 ? true : rng.Uniform(0, 1) < 0.6)
      {
        p.AddTerm(rng.Uniform(-2.0, 2.0), squares[m][0], squares[m][1], squares[m][2]);
      }
    }
    const double scale = trial % 3 == 0 ? 30.0 : 1.5;
    const Point q = rng.InBox(-scale, scale);
    ExpectValueAndGradient(p, q);
    for (int a = 0; a < 3; ++a)
    {
      double c[5];
      p.RestrictToAxis(q.data(), a, c);
      const int n = p.GetAxisDegree(a);
      for (int k = 0; k < 3; ++k)
      {
        double x[3] = { q[0], q[1], q[2] };
        x[a] = rng.Uniform(-scale, scale);
        double along = 0.0;
        for (int m = n; m >= 0; --m)
        {
          along = along * x[a] + c[m];
        }
        EXPECT_TRUE(Near(along, NaiveEvaluate(p, x), 1e-13 * std::max(1.0, AbsEvaluate(p, x))))
          << "axis " << a << " of " << p.ToString();
      }
    }
    // Along a line in any direction (and along an axis: grid rows).
    const Point o = rng.InBox(-scale, scale);
    Point d = rng.InBox(-1, 1);
    if (trial % 4 == 0)
    {
      d = Point{ 0.0, 0.0, 0.0 };
      d[trial % 3] = 0.7;
    }
    double c[5];
    p.RestrictToLine(o.data(), d.data(), c);
    for (double t : { -2.0, -0.3, 0.6, 1.5 })
    {
      const double x[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
      const double along = (((c[4] * t + c[3]) * t + c[2]) * t + c[1]) * t + c[0];
      EXPECT_TRUE(Near(along, NaiveEvaluate(p, x), 1e-13 * std::max(1.0, AbsEvaluate(p, x)) * 8))
        << "line restriction of " << p.ToString() << " at t = " << t;
    }
  }
}

// ExpandAbout: the dense coefficients b of u -> P(c + h∘u) give P's values at c + h∘u,
// for random polynomials of degree 0 to 6 and the forms with their own paths (quadrics,
// quartics in the squares only).
TEST(Polynomial3, ExpandAboutGivesTheShiftedPolynomial)
{
  Random rng(13);
  for (int trial = 0; trial < 300; ++trial)
  {
    Polynomial3 p;
    const int kind = trial % 3;
    const int degree = kind == 0 ? trial % 7 : (kind == 1 ? 2 : 4);
    for (int k = 0; k <= degree; ++k)
      for (int j = 0; j + k <= degree; ++j)
        for (int i = 0; i + j + k <= degree; ++i)
        {
          const bool even = i % 2 == 0 && j % 2 == 0 && k % 2 == 0;
          if ((kind != 2 || even) && (rng.Uniform(0, 1) < 0.7 || i + j + k == degree))
          {
            p.AddTerm(rng.Uniform(-2.0, 2.0), i, j, k);
          }
        }
    if (kind == 2)
    {
      ASSERT_TRUE(p.IsEvenQuartic()) << p.ToString();
    }
    const Point c = rng.InBox(-3, 3);
    const Point h = rng.InBox(-1, 1);
    double b[9 * 9 * 9];
    const int n = p.ExpandAbout(c.data(), h.data(), b);
    ASSERT_EQ(n, p.GetDegree());
    if (n < 0)
    {
      continue;
    }
    const int m = n + 1;
    for (int s = 0; s < 5; ++s)
    {
      const Point u = rng.InBox(-1, 1);
      double value = 0.0;
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j)
          for (int k = 0; k <= n; ++k)
          {
            const double bk = b[(i * m + j) * m + k];
            if (i + j + k > n)
            {
              EXPECT_EQ(bk, 0.0);
            }
            value += bk * std::pow(u[0], i) * std::pow(u[1], j) * std::pow(u[2], k);
          }
      const double x[3] = { c[0] + h[0] * u[0], c[1] + h[1] * u[1], c[2] + h[2] * u[2] };
      EXPECT_TRUE(Near(value, NaiveEvaluate(p, x), 1e-12 * std::max(1.0, AbsEvaluate(p, x))))
        << p.ToString() << " about " << c[0] << " " << c[1] << " " << c[2];
    }
  }
}

TEST(Polynomial3, GradientIsExactForAKnownPolynomial)
{
  // P = x³y²z − 4xz² + 7y: ∇P = (3x²y²z − 4z², 2x³yz + 7, x³y² − 8xz).
  const Polynomial3 p =
    X().Pow(3) * Y().Pow(2) * Z() - (X() * Z().Pow(2)).Scaled(4) + Y().Scaled(7);
  Random rng(6);
  for (int n = 0; n < 20; ++n)
  {
    const Point q = rng.InBox(-2, 2);
    const double x = q[0], y = q[1], z = q[2];
    double g[3];
    p.EvaluateWithGradient(q.data(), g);
    EXPECT_TRUE(Near(g[0], 3 * x * x * y * y * z - 4 * z * z, 1e-13));
    EXPECT_TRUE(Near(g[1], 2 * x * x * x * y * z + 7, 1e-13));
    EXPECT_TRUE(Near(g[2], x * x * x * y * y - 8 * x * z, 1e-13));
  }
}

TEST(Polynomial3, RestrictToLineReproducesValuesAlongTheLine)
{
  Random rng(7);
  for (int n = 0; n < 80; ++n)
  {
    const Polynomial3 p = rng.Polynomial(7, 12);
    const Point o = rng.InBox(-1, 1);
    Point d = rng.InBox(-1, 1);
    if (n >= 40)
    {
      // Lines along one axis (grid rows) take the one-axis expansion.
      for (int a = 0; a < 3; ++a)
        d[a] = a == n % 3 ? d[a] : 0.0;
    }
    const std::vector<double> c = p.RestrictToLine(o.data(), d.data());
    ASSERT_EQ(c.size(), static_cast<size_t>(std::max(p.GetDegree(), 0) + 1));
    for (double t : { -1.3, -0.5, 0.0, 0.25, 0.7, 1.1 })
    {
      const double q[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
      const double qa[3] = { std::fabs(o[0]) + std::fabs(t * d[0]),
        std::fabs(o[1]) + std::fabs(t * d[1]), std::fabs(o[2]) + std::fabs(t * d[2]) };
      const double v = pisurf::EvaluateUnivariate(c.data(), static_cast<int>(c.size()), t);
      EXPECT_TRUE(Near(v, p.Evaluate(q), 1e-12 * std::max(1.0, AbsEvaluate(p, qa))))
        << p.ToString() << " at t = " << t;
    }
  }
  // A known case: x² + y along (1, 0, 0) + t·(1, 2, 0) is 1 + 4t + t².
  const double o[3] = { 1, 0, 0 }, d[3] = { 1, 2, 0 };
  const std::vector<double> c = (X().Pow(2) + Y()).RestrictToLine(o, d);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0], 1.0);
  EXPECT_EQ(c[1], 4.0);
  EXPECT_EQ(c[2], 1.0);
  // The zero polynomial restricts to the single coefficient 0.
  const std::vector<double> z = Polynomial3().RestrictToLine(o, d);
  ASSERT_EQ(z.size(), 1u);
  EXPECT_EQ(z[0], 0.0);
}

TEST(Polynomial3, RestrictToLineIntoABufferMatchesTheVectorForm)
{
  Random rng(9);
  // Alternate high and low degrees so that any reused scratch space shrinks and grows.
  for (int n = 0; n < 40; ++n)
  {
    const Polynomial3 p = rng.Polynomial(n % 2 ? 2 : 12, n % 2 ? 3 : 20);
    const Point o = rng.InBox(-1, 1), d = rng.InBox(-1, 1);
    const std::vector<double> v = p.RestrictToLine(o.data(), d.data());
    const size_t size = static_cast<size_t>(std::max(p.GetDegree(), 0) + 1);
    ASSERT_EQ(v.size(), size);
    std::vector<double> buffer(size + 4, 12345.0);
    p.RestrictToLine(o.data(), d.data(), buffer.data());
    for (size_t k = 0; k < size; ++k)
    {
      EXPECT_EQ(buffer[k], v[k]) << "coefficient " << k;
    }
    for (size_t k = size; k < buffer.size(); ++k)
    {
      EXPECT_EQ(buffer[k], 12345.0) << "wrote past out[degree]";
    }
  }
  // Exact coefficients of a known case: (x + 2y)^3 on (1, 0, 0) + t·(0, 1, 0) is (1 + 2t)^3.
  const Polynomial3 c = (X() + Y().Scaled(2)).Pow(3);
  const double o[3] = { 1, 0, 0 }, d[3] = { 0, 1, 0 };
  double out[4];
  c.RestrictToLine(o, d, out);
  EXPECT_EQ(out[0], 1.0);
  EXPECT_EQ(out[1], 6.0);
  EXPECT_EQ(out[2], 12.0);
  EXPECT_EQ(out[3], 8.0);
}

TEST(Polynomial3, EvaluateUnivariateIsHorner)
{
  const double c[4] = { 1.0, -2.0, 0.5, 3.0 }; // 1 − 2t + t²/2 + 3t³
  for (double t : { -2.0, 0.0, 0.3, 1.0, 4.0 })
  {
    EXPECT_DOUBLE_EQ(pisurf::EvaluateUnivariate(c, 4, t), 1 - 2 * t + 0.5 * t * t + 3 * t * t * t);
  }
  EXPECT_EQ(pisurf::EvaluateUnivariate(c, 0, 2.0), 0.0);
}

TEST(Polynomial3, ToStringRoundTripsThroughTheParser)
{
  Random rng(8);
  for (int n = 0; n < 60; ++n)
  {
    Polynomial3 p;
    const int terms = rng.Integer(1, 15);
    for (int k = 0; k < terms; ++k)
    {
      const int d = rng.Integer(0, 10);
      const int i = rng.Integer(0, d);
      const int j = rng.Integer(0, d - i);
      // Coefficients that need all 17 digits, of every magnitude and sign.
      const double c = rng.Uniform(-1, 1) * std::pow(10.0, rng.Integer(-30, 30)) / 3.0;
      p.AddTerm(c, i, j, d - i - j);
    }
    const std::string text = p.ToString();
    Polynomial3 q;
    std::string error;
    ASSERT_TRUE(pisurf::ParseExpression(text, {}, q, error)) << text << ": " << error;
    EXPECT_TRUE(SameTerms(p, q)) << text;
  }
  // Special values: the zero polynomial, a negative leading term, tiny and huge numbers.
  for (const Polynomial3& p : { Polynomial3(), C(-1.0), X().Scaled(-1e-300) + C(1e300),
         (X() - Y()).Pow(5) - Z().Scaled(5e-324) })
  {
    Polynomial3 q = C(42); // must be replaced
    std::string error;
    ASSERT_TRUE(pisurf::ParseExpression(p.ToString(), {}, q, error))
      << p.ToString() << ": " << error;
    EXPECT_TRUE(SameTerms(p, q)) << p.ToString();
  }
}

// LogDerivativeSign decides the sign of (Π f)' from enclosures of the factors and their
// derivatives. Products of ten sphere-like quadratics (f_i(t) = (t − m_i)² + k_i, as a
// ray meets ten spheres) on short ranges, with exact enclosures: every sign it claims
// holds at every sampled point, it never contradicts the product rule, and it decides
// more ranges than the product rule (the ray caster's monotone ranges depend on that).
TEST(Intervals, LogDerivativeSignIsSoundAndSharperThanTheProductRule)
{
  using pisurf::Interval;
  Random rng(2026);
  constexpr int n = 10;
  int byProductRule = 0, byLogarithm = 0, checked = 0;
  for (int trial = 0; trial < 20000; ++trial)
  {
    double m[n], k[n];
    for (int i = 0; i < n; ++i)
    {
      m[i] = rng.Uniform(-3.0, 3.0);
      k[i] = rng.Uniform(-0.64, 2.0);
    }
    const double width = std::pow(10.0, rng.Uniform(-3.0, -0.5));
    const double a = rng.Uniform(-3.0, 3.0), b = a + width;
    Interval f[n], df[n];
    for (int i = 0; i < n; ++i)
    {
      const double ua = a - m[i], ub = b - m[i];
      const double low = ua <= 0.0 && ub >= 0.0 ? 0.0 : std::min(ua * ua, ub * ub);
      f[i] = { low + k[i], std::max(ua * ua, ub * ub) + k[i] };
      df[i] = { 2.0 * ua, 2.0 * ub };
    }
    Interval prefix[n + 1];
    pisurf::PrefixProducts(f, n, prefix);
    double lo, hi, magnitude;
    pisurf::ProductRule(f, df, n, prefix, lo, hi, magnitude);
    const double slack = 1e-12 * magnitude;
    const int rule = lo > slack ? 1 : hi < -slack ? -1 : 0;
    const int sign = pisurf::LogDerivativeSign(f, df, n, 1e-12);
    byProductRule += rule != 0;
    byLogarithm += sign != 0;
    if (rule != 0 && sign != 0)
    {
      ASSERT_EQ(rule, sign) << "trial " << trial;
    }
    if (sign == 0)
    {
      continue;
    }
    ++checked;
    for (int s = 0; s <= 32; ++s)
    {
      const long double t = a + (b - a) * s / 32.0L;
      long double derivative = 0.0L;
      for (int i = 0; i < n; ++i)
      {
        long double term = 2.0L * (t - m[i]);
        for (int j = 0; j < n; ++j)
        {
          term *= j == i ? 1.0L : (t - m[j]) * (t - m[j]) + k[j];
        }
        derivative += term;
      }
      ASSERT_EQ(derivative > 0 ? 1 : -1, sign) << "trial " << trial << " at t = " << double(t);
    }
  }
  EXPECT_GT(checked, 1000);
  EXPECT_GT(byLogarithm, byProductRule + byProductRule / 10)
    << byLogarithm << " ranges decided against " << byProductRule;
}

TEST(Intervals, LogDerivativeSignCases)
{
  using pisurf::Interval;
  // One factor crossing 0 (t on [−0.01, 0.01]) times a nearly constant positive one:
  // the product rises.
  const Interval f1[2] = { { -0.01, 0.01 }, { 2.0, 2.01 } };
  const Interval d1[2] = { { 1.0, 1.0 }, { -0.001, 0.001 } };
  EXPECT_EQ(pisurf::LogDerivativeSign(f1, d1, 2, 1e-12), 1);
  // The same with the other factor negative: the product falls.
  const Interval f2[2] = { { -0.01, 0.01 }, { -2.01, -2.0 } };
  EXPECT_EQ(pisurf::LogDerivativeSign(f2, d1, 2, 1e-12), -1);
  // Two factors that may vanish: undecided.
  const Interval f3[2] = { { -0.01, 0.01 }, { -0.01, 0.01 } };
  const Interval d3[2] = { { 1.0, 1.0 }, { 1.0, 1.0 } };
  EXPECT_EQ(pisurf::LogDerivativeSign(f3, d3, 2, 1e-12), 0);
  // A derivative enclosure holding 0: undecided.
  const Interval f4[2] = { { 1.0, 2.0 }, { 3.0, 4.0 } };
  const Interval d4[2] = { { -1.0, 1.0 }, { 0.0, 0.0 } };
  EXPECT_EQ(pisurf::LogDerivativeSign(f4, d4, 2, 1e-12), 0);
  // NaN and a quotient that overflows: undecided.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Interval f5[2] = { { 1.0, 2.0 }, { nan, nan } };
  EXPECT_EQ(pisurf::LogDerivativeSign(f5, d3, 2, 1e-12), 0);
  const Interval f6[2] = { { 1e-320, 1.0 }, { 1.0, 1.0 } };
  const Interval d6[2] = { { 1e300, 1e300 }, { 0.0, 0.0 } };
  EXPECT_EQ(pisurf::LogDerivativeSign(f6, d6, 2, 1e-12), 0);
}
