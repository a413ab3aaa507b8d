// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiCoreTestUtilities.h
 * @brief helpers shared by the unit tests of the PiSurfaces core kernels
 *
 * Seeded random points, central finite differences, relative comparisons and a matcher
 * for error messages ("fragment" and "at position N").
 */
#ifndef PiCoreTestUtilities_h
#define PiCoreTestUtilities_h

#include "PiPolynomial.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace pisurf_test
{
using Point = std::array<double, 3>;

/// A deterministic generator: every test starts from its own fixed seed.
class Random
{
public:
  explicit Random(unsigned seed = 12345)
    : Engine(seed)
  {
  }
  double Uniform(double lo, double hi)
  {
    return std::uniform_real_distribution<double>(lo, hi)(this->Engine);
  }
  int Integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(this->Engine); }
  Point InBox(double lo, double hi)
  {
    return { this->Uniform(lo, hi), this->Uniform(lo, hi), this->Uniform(lo, hi) };
  }
  /// A random polynomial of total degree <= maxDegree with `terms` monomials.
  pisurf::Polynomial3 Polynomial(int maxDegree, int terms)
  {
    pisurf::Polynomial3 p;
    for (int n = 0; n < terms; ++n)
    {
      const int d = this->Integer(0, maxDegree);
      const int i = this->Integer(0, d);
      const int j = this->Integer(0, d - i);
      p.AddTerm(this->Uniform(-2.0, 2.0), i, j, d - i - j);
    }
    return p;
  }

private:
  std::mt19937 Engine;
};

/// a and b have the same bits (so 0 and −0 differ, and so do NaNs of other payloads).
inline bool SameBits(double a, double b)
{
  std::uint64_t x, y;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}

/// |a - b| <= tol * max(1, |a|, |b|): relative for large values, absolute near 0.
inline ::testing::AssertionResult Near(double a, double b, double tol)
{
  const double scale = std::max({ 1.0, std::fabs(a), std::fabs(b) });
  if (std::fabs(a - b) <= tol * scale)
  {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << a << " and " << b << " differ by " << std::fabs(a - b)
                                       << " (> " << tol << " * " << scale << ")";
}

/// |a - b| <= tol * max(|a|, |b|), strictly relative.
inline ::testing::AssertionResult RelativelyNear(double a, double b, double tol)
{
  const double scale = std::max(std::fabs(a), std::fabs(b));
  if (std::fabs(a - b) <= tol * scale)
  {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
    << a << " and " << b << " differ by " << std::fabs(a - b) << " relative tolerance " << tol;
}

/// Central finite-difference gradient of f at p with step h (error O(h^2)).
inline Point FiniteDifferenceGradient(
  const std::function<double(const double*)>& f, const double p[3], double h = 1e-5)
{
  Point g;
  for (int k = 0; k < 3; ++k)
  {
    double a[3] = { p[0], p[1], p[2] };
    double b[3] = { p[0], p[1], p[2] };
    a[k] += h;
    b[k] -= h;
    g[k] = (f(a) - f(b)) / (2.0 * h);
  }
  return g;
}

/// Checks that an error message contains every fragment.
inline ::testing::AssertionResult HasFragments(
  const std::string& error, const std::vector<std::string>& fragments)
{
  for (const std::string& f : fragments)
  {
    if (error.find(f) == std::string::npos)
    {
      return ::testing::AssertionFailure()
        << "error \"" << error << "\" does not contain \"" << f << "\"";
    }
  }
  return ::testing::AssertionSuccess();
}

/// Coefficient-by-coefficient equality of two polynomials (exact).
inline ::testing::AssertionResult SameTerms(
  const pisurf::Polynomial3& a, const pisurf::Polynomial3& b)
{
  const auto& ta = a.GetTerms();
  const auto& tb = b.GetTerms();
  if (ta.size() != tb.size())
  {
    return ::testing::AssertionFailure()
      << "term counts differ: " << ta.size() << " vs " << tb.size() << " (" << a.ToString()
      << " vs " << b.ToString() << ")";
  }
  for (size_t n = 0; n < ta.size(); ++n)
  {
    if (ta[n].I != tb[n].I || ta[n].J != tb[n].J || ta[n].K != tb[n].K ||
      ta[n].Coefficient != tb[n].Coefficient)
    {
      return ::testing::AssertionFailure()
        << "term " << n << " differs: " << a.ToString() << " vs " << b.ToString();
    }
  }
  return ::testing::AssertionSuccess();
}

/// Coefficient-by-coefficient equality up to a relative tolerance on the largest one.
inline ::testing::AssertionResult SameTermsNear(
  const pisurf::Polynomial3& a, const pisurf::Polynomial3& b, double tol)
{
  double scale = 0.0;
  for (const auto& t : a.GetTerms())
  {
    scale = std::max(scale, std::fabs(t.Coefficient));
  }
  for (const auto& t : b.GetTerms())
  {
    scale = std::max(scale, std::fabs(t.Coefficient));
  }
  auto check = [&](const pisurf::Polynomial3& p,
                 const pisurf::Polynomial3& q) -> ::testing::AssertionResult
  {
    for (const auto& t : p.GetTerms())
    {
      const double c = q.GetCoefficient(t.I, t.J, t.K);
      if (std::fabs(c - t.Coefficient) > tol * scale)
      {
        return ::testing::AssertionFailure()
          << "coefficient of x^" << t.I << " y^" << t.J << " z^" << t.K << ": " << t.Coefficient
          << " vs " << c << " (" << a.ToString() << " vs " << b.ToString() << ")";
      }
    }
    return ::testing::AssertionSuccess();
  };
  ::testing::AssertionResult r = check(a, b);
  return r ? check(b, a) : r;
}

/// A protein-like cluster of atoms: centres on a jittered lattice of 1.6 A (about a
/// protein's atom density) inside a ball of `radius`, radii 1.5 to 1.8 A, and a region
/// 4 A beyond the ball.
struct MoleculeCluster
{
  std::vector<double> Centers, Radii;
  double Region[6];
};

inline MoleculeCluster MakeMoleculeCluster(double radius, unsigned seed)
{
  MoleculeCluster c;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.35, 0.35), r(1.5, 1.8);
  const int n = static_cast<int>(radius / 1.6);
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k)
      {
        const double p[3] = { 1.6 * i + jitter(rng), 1.6 * j + jitter(rng), 1.6 * k + jitter(rng) };
        if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > radius * radius)
        {
          continue;
        }
        c.Centers.insert(c.Centers.end(), p, p + 3);
        c.Radii.push_back(r(rng));
      }
  const double m = radius + 4.0;
  const double region[6] = { -m, m, -m, m, -m, m };
  std::copy(region, region + 6, c.Region);
  return c;
}
}

#endif
