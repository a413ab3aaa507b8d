// SPDX-License-Identifier: BSD-3-Clause
// Certified roots along a ray: thin features, near-touching and tangent cases, many
// factors, and agreement with a brute-force scan.
#include "PiPrimitiveSpec.h"
#include "PiRayRoots.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace pisurf;

namespace
{
// The primitive restricted to the ray o + t·d.
std::vector<double> Along(const PrimitiveSpec& s, const double o[3], const double d[3])
{
  PolynomialFactor f;
  std::string error;
  EXPECT_TRUE(BuildFactor(s, {}, f, error)) << error;
  return f.RestrictToLine(o, d);
}

PrimitiveSpec Sphere(double x, double y, double z, double radius)
{
  PrimitiveSpec s;
  s.Center[0] = x;
  s.Center[1] = y;
  s.Center[2] = z;
  s.Radius = radius;
  return s;
}

// 2 to 5 factors (2 + trial % 4; in every third trial the first a torus of minor radius
// 0.05 to 0.25, else spheres of radius 0.4 to 1) restricted to the ray from
// (−4, y, z) along x, and r: 0 in every fifth trial, else 0.01, 1 or 10 by trial % 3.
std::vector<std::vector<double>> SpheresAndTorus(std::mt19937& rng, int trial, double& r)
{
  std::uniform_real_distribution<double> c(-1.5, 1.5), radius(0.4, 1.0), unit(0.0, 1.0);
  std::vector<std::vector<double>> factors;
  const double o[3] = { -4.0, 0.5 * c(rng), 0.5 * c(rng) }, d[3] = { 1, 0, 0 };
  const int count = 2 + trial % 4;
  for (int i = 0; i < count; ++i)
  {
    if (i == 0 && trial % 3 == 0)
    {
      PrimitiveSpec torus;
      torus.Type = PrimitiveType::Torus;
      torus.Center[0] = 0.5 * c(rng);
      torus.Center[1] = 0.2 * c(rng);
      torus.MajorRadius = 1.0;
      torus.MinorRadius = 0.05 + 0.2 * unit(rng);
      factors.push_back(Along(torus, o, d));
    }
    else
    {
      factors.push_back(Along(Sphere(c(rng), 0.3 * c(rng), 0.3 * c(rng), radius(rng)), o, d));
    }
  }
  r = trial % 5 == 4 ? 0.0 : (trial % 3 == 0 ? 0.01 : (trial % 3 == 1 ? 1.0 : 10.0));
  return factors;
}

std::vector<RayRoot> Roots(
  const std::vector<std::vector<double>>& factors, double r, double t0, double t1, bool all = true)
{
  RayRootOptions options;
  options.AllRoots = all;
  std::vector<RayRoot> roots;
  EXPECT_TRUE(FindRayRoots(factors, r, t0, t1, options, roots));
  return roots;
}
// The product in long double (Horner per factor) minus r.
long double ProductMinus(const std::vector<std::vector<double>>& factors, double r, double t)
{
  long double p = 1.0L;
  for (const auto& f : factors)
  {
    long double v = 0.0L;
    for (size_t k = f.size(); k-- > 0;)
    {
      v = v * t + f[k];
    }
    p *= v;
  }
  return p - r;
}

// Its derivative in long double (Horner per factor and its derivative, the product rule).
long double ProductSlope(const std::vector<std::vector<double>>& factors, double t)
{
  long double p = 1.0L, dp = 0.0L;
  for (const auto& f : factors)
  {
    long double v = 0.0L, dv = 0.0L;
    for (size_t k = f.size(); k-- > 0;)
    {
      dv = dv * t + v;
      v = v * t + f[k];
    }
    dp = dp * v + p * dv;
    p *= v;
  }
  return dp;
}

// Against `samples` long-double samples of F on [0, length]: every sign change holds a
// root (within the tolerance), and every crossing root has F of opposite signs a
// tolerance before and after it. Returns the number of sign changes seen.
int ExpectRootsAtSignChanges(const std::vector<std::vector<double>>& factors, double r,
  double length, int samples, const std::vector<RayRoot>& roots, int trial)
{
  const double tolerance = RayRootOptions().Tolerance;
  auto F = [&](double t) { return ProductMinus(factors, r, t); };
  int changes = 0;
  long double previous = F(0.0);
  for (int s = 1; s <= samples; ++s)
  {
    const double ta = length * (s - 1) / samples, tb = length * s / samples;
    const long double value = F(tb);
    if ((value < 0) != (previous < 0))
    {
      EXPECT_TRUE(std::any_of(roots.begin(), roots.end(),
        [&](const RayRoot& x) { return x.T >= ta - tolerance && x.T <= tb + tolerance; }))
        << "trial " << trial << ": a sign change in [" << ta << ", " << tb << "] without a root";
      ++changes;
    }
    previous = value;
  }
  for (const RayRoot& x : roots)
  {
    if (!x.Tangent)
    {
      EXPECT_NE(F(x.T - tolerance) < 0, F(x.T + tolerance) < 0)
        << "trial " << trial << " root " << x.T;
    }
  }
  return changes;
}
}

TEST(RayRoots, SphereThroughTheCentre)
{
  const double o[3] = { -5, 0, 0 }, d[3] = { 1, 0, 0 };
  const auto roots = Roots({ Along(Sphere(0, 0, 0, 2), o, d) }, 0.0, 0, 10);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_NEAR(roots[0].T, 3.0, 1e-10);
  EXPECT_NEAR(roots[1].T, 7.0, 1e-10);
  EXPECT_FALSE(roots[0].Tangent);
  const auto first = Roots({ Along(Sphere(0, 0, 0, 2), o, d) }, 0.0, 0, 10, false);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_NEAR(first[0].T, 3.0, 1e-10);
}

TEST(RayRoots, ThinTorusIsNeverMissed)
{
  // Minor radius 0.01: the ray crosses the tube twice on each side of the ring.
  PrimitiveSpec torus;
  torus.Type = PrimitiveType::Torus;
  torus.MajorRadius = 1.0;
  torus.MinorRadius = 0.01;
  const double o[3] = { -3, 0.005, 0 }, d[3] = { 1, 0, 0 };
  const auto roots = Roots({ Along(torus, o, d) }, 0.0, 0, 6);
  ASSERT_EQ(roots.size(), 4u);
  // In the plane z = 0 the tube is the annulus 0.99 <= |(x, y)| <= 1.01.
  const double y = 0.005;
  const double outer = std::sqrt(1.01 * 1.01 - y * y), inner = std::sqrt(0.99 * 0.99 - y * y);
  EXPECT_NEAR(roots[0].T, 3 - outer, 1e-9);
  EXPECT_NEAR(roots[1].T, 3 - inner, 1e-9);
  EXPECT_NEAR(roots[2].T, 3 + inner, 1e-9);
  EXPECT_NEAR(roots[3].T, 3 + outer, 1e-9);
}

TEST(RayRoots, NearlyTouchingSpheresStayApart)
{
  // Unit spheres whose surfaces are 1e-6 apart on the ray, r = 0: four roots.
  const double gap = 1e-6;
  const double o[3] = { -3, 0, 0 }, d[3] = { 1, 0, 0 };
  const auto roots =
    Roots({ Along(Sphere(-1 - gap / 2, 0, 0, 1), o, d), Along(Sphere(1 + gap / 2, 0, 0, 1), o, d) },
      0.0, 0, 6);
  ASSERT_EQ(roots.size(), 4u);
  EXPECT_NEAR(roots[1].T, 3 - gap / 2, 1e-9);
  EXPECT_NEAR(roots[2].T, 3 + gap / 2, 1e-9);
}

TEST(RayRoots, TangentRootIsFlagged)
{
  // The ray y = 1 touches the unit sphere at x = 0.
  const double o[3] = { -3, 1, 0 }, d[3] = { 1, 0, 0 };
  const auto roots = Roots({ Along(Sphere(0, 0, 0, 1), o, d) }, 0.0, 0, 6);
  ASSERT_EQ(roots.size(), 1u);
  EXPECT_TRUE(roots[0].Tangent);
  EXPECT_NEAR(roots[0].T, 3.0, 1e-4); // a double root is only known to ~sqrt(tolerance)
  // A ray that misses by 1e-3 has no root.
  const double miss[3] = { -3, 1.001, 0 };
  EXPECT_TRUE(Roots({ Along(Sphere(0, 0, 0, 1), miss, d) }, 0.0, 0, 6).empty());
}

TEST(RayRoots, DoubleRootIsOneTangentHit)
{
  // Crossed unit cylinders with r = 1 along their common axis: F = (t² − 1)² − 1 =
  // t²(t² − 2) touches 0 at t = 0, where |F| stays within the rounding slack over
  // thousands of tolerance-wide pieces, and crosses it at √2: two roots, the first
  // tangent (each tiny piece used to report its own root: about 8000 of them).
  const std::vector<std::vector<double>> f = { { -1, 0, 1 }, { -1, 0, 1 } };
  const auto roots = Roots(f, 1.0, -1, 2);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_TRUE(roots[0].Tangent);
  EXPECT_NEAR(roots[0].T, 0.0, 1e-4);
  EXPECT_FALSE(roots[1].Tangent);
  EXPECT_NEAR(roots[1].T, std::sqrt(2.0), 1e-9);
  // The same on the general path (more than 48 degrees: 24 more factors equal to 1).
  std::vector<std::vector<double>> many = f;
  many.resize(26, { 1, 0, 1e-300 });
  const auto general = Roots(many, 1.0, -1, 2);
  ASSERT_EQ(general.size(), 2u);
  EXPECT_TRUE(general[0].Tangent);
  EXPECT_NEAR(general[0].T, 0.0, 1e-4);
  EXPECT_NEAR(general[1].T, std::sqrt(2.0), 1e-9);
}

TEST(RayRoots, BlendedSpheresAgreeWithABruteForceScan)
{
  // The paper's two spheres at d = 0.9, r = 0.25, on random rays: every sign change of a
  // fine scan is a reported root, and every reported root has F ≈ 0.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int ray = 0; ray < 200; ++ray)
  {
    const double o[3] = { -4, 1.5 * u(rng), 1.5 * u(rng) };
    double d[3] = { 1, 0.3 * u(rng), 0.3 * u(rng) };
    const std::vector<std::vector<double>> f = { Along(Sphere(0.9, 0, 0, 1), o, d),
      Along(Sphere(-0.9, 0, 0, 1), o, d) };
    const auto F = [&](double t)
    {
      double p = 1;
      for (const auto& c : f)
        p *= EvaluateUnivariate(c.data(), static_cast<int>(c.size()), t);
      return p - 0.25;
    };
    const auto roots = Roots(f, 0.25, 0, 8);
    int changes = 0;
    const int n = 20000;
    for (int k = 0; k < n; ++k)
    {
      changes += (F(8.0 * k / n) < 0) != (F(8.0 * (k + 1) / n) < 0);
    }
    int crossings = 0;
    for (const auto& r : roots)
    {
      EXPECT_NEAR(F(r.T), 0.0, 1e-8);
      crossings += !r.Tangent;
    }
    EXPECT_EQ(crossings, changes) << "ray " << ray;
  }
}

TEST(RayRoots, ThousandsOfFactorsDoNotOverflow)
{
  // 3000 unit spheres spread along x at spacing 3; the ray along x crosses each twice.
  std::vector<std::vector<double>> f;
  const double o[3] = { -2, 0, 0 }, d[3] = { 1, 0, 0 };
  for (int i = 0; i < 3000; ++i)
  {
    f.push_back(Along(Sphere(3.0 * i, 0, 0, 1), o, d));
  }
  // The first 10 spheres' 20 roots, each within the tolerance of sphere ± 1 (the interval
  // ends between the 10th and the 11th sphere).
  const auto roots = Roots(f, 1.0, 0, 30.5);
  ASSERT_EQ(roots.size(), 20u);
  for (int k = 0; k < 20; ++k)
  {
    const double centre = 2 + 3.0 * (k / 2);
    EXPECT_NEAR(roots[k].T, centre + (k % 2 ? 1 : -1), 1e-6);
    EXPECT_TRUE(std::isfinite(roots[k].T));
  }
}

TEST(RayRoots, BadInputIsRefused)
{
  std::vector<RayRoot> roots;
  RayRootOptions options;
  EXPECT_FALSE(FindRayRoots({ { 1, NAN } }, 0, 0, 1, options, roots));
  EXPECT_FALSE(FindRayRoots({ { 1, 2 }, { HUGE_VAL, 1, 3 } }, 0, 0, 1, options, roots));
  EXPECT_FALSE(FindRayRoots({ { 1, 2 }, { 1, -HUGE_VAL, 3 } }, 0, 0, 1, options, roots));
  EXPECT_TRUE(FindRayRoots({ { 1, 2 }, { 1e300, 1, 3 } }, 0, 0, 1, options, roots));
  EXPECT_FALSE(FindRayRoots({ { 1, 1 } }, NAN, 0, 1, options, roots));
  EXPECT_FALSE(FindRayRoots({ { 1, 1 } }, 0, 1, 0, options, roots));
  EXPECT_FALSE(FindRayRoots({ {} }, 0, 0, 1, options, roots));
  options.Tolerance = 0;
  EXPECT_FALSE(FindRayRoots({ { 1, 1 } }, 0, 0, 1, options, roots));
}

TEST(RayRoots, ManyFactorsBlendedAcrossALongSegment)
{
  // 20 unit-ish spheres in a 5-wide cluster, a ray 13 long through it, r = 0.01: along the
  // ray the product's Bernstein terms reach 1e30 times its values where P = r, a blended
  // region with shallow roots. Every sign change among 40000 samples of the product (in
  // long double) holds a root, and every crossing root has opposite signs a tolerance
  // before and after it. (The fast path's relative slack alone missed 12 of 16 roots.)
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> c(-2.0, 2.0), radius(1.0, 1.3);
  int checked = 0;
  for (int trial = 0; trial < 8; ++trial)
  {
    std::vector<std::vector<double>> factors;
    const double o[3] = { -6.5, 0.3 * c(rng), 0.3 * c(rng) }, d[3] = { 1, 0, 0 };
    for (int i = 0; i < 20; ++i)
    {
      factors.push_back(Along(Sphere(c(rng), c(rng), c(rng), radius(rng)), o, d));
    }
    const double r = 0.01, length = 13.0;
    const auto roots = Roots(factors, r, 0.0, length);
    checked += ExpectRootsAtSignChanges(factors, r, length, 40000, roots, trial);
  }
  EXPECT_GT(checked, 40);
}

TEST(RayRoots, ShortSegmentsFindWhatTheWholeRayFinds)
{
  // The ray caster searches octree leaves' short depth ranges, which a quick test
  // decides from centred forms of the factors (one sign, or monotone with a sign change)
  // before any Bernstein expansion. Cut into 97 pieces (leaf-like lengths, ends at
  // arbitrary places; in every other trial also cut exactly at the whole ray's roots, so
  // that pieces end on a root), products of spheres and tori at r = 0, 0.01, 1 and 10 must
  // give the roots the whole ray gives (each within 2 tolerances, a root at a shared end
  // counted once), every sign change among 20000 long-double samples must hold one, and
  // every crossing root must have opposite signs a tolerance either side.
  std::mt19937 rng(11);
  const double tolerance = RayRootOptions().Tolerance;
  int compared = 0, changes = 0;
  for (int trial = 0; trial < 60; ++trial)
  {
    double r;
    const auto factors = SpheresAndTorus(rng, trial, r);
    const double length = 8.0;
    const auto whole = Roots(factors, r, 0.0, length);
    // Uneven cuts: the ends fall anywhere relative to the roots (or on them).
    const int n = 97;
    std::vector<double> cuts{ 0.0, length };
    for (int s = 0; s < n - 1; ++s)
    {
      cuts.push_back(length * (s + 0.37) / n);
    }
    if (trial % 2 == 1)
    {
      for (const RayRoot& x : whole)
      {
        cuts.push_back(x.T);
      }
    }
    std::sort(cuts.begin(), cuts.end());
    std::vector<RayRoot> pieces;
    for (size_t s = 0; s + 1 < cuts.size(); ++s)
    {
      const double a = cuts[s], b = cuts[s + 1];
      for (const RayRoot& x : Roots(factors, r, a, b))
      {
        if (pieces.empty() || x.T - pieces.back().T > 2.0 * tolerance)
        {
          pieces.push_back(x);
        }
      }
    }
    ASSERT_EQ(pieces.size(), whole.size()) << "trial " << trial;
    for (size_t k = 0; k < whole.size(); ++k)
    {
      EXPECT_NEAR(pieces[k].T, whole[k].T, 2.0 * tolerance) << "trial " << trial << " root " << k;
      EXPECT_EQ(pieces[k].Tangent, whole[k].Tangent) << "trial " << trial << " root " << k;
      ++compared;
    }
    changes += ExpectRootsAtSignChanges(factors, r, length, 20000, pieces, trial);
  }
  EXPECT_GT(compared, 100);
  EXPECT_GT(changes, 100);
}

TEST(RayRoots, CutSegmentReportsEachRootOnce)
{
  // The ray caster hands a run of touching octree leaves over as one segment cut where
  // F's proven monotony changes, each piece with its own Monotone flag, the roots of all
  // pieces in one cluster. Products of spheres and tori: cut into 23 pieces (in every
  // other trial also exactly at the whole ray's roots), each piece flagged monotone
  // where 4000 long-double samples of F' over it keep one sign with a margin of one
  // sample beyond each end (the flag must be true: the pieces then skip the
  // enclosures), the roots must be the whole ray's: none lost, none reported twice on a
  // cut, the same tangency; with AllRoots off, the whole ray's first root alone.
  std::mt19937 rng(23);
  const double tolerance = RayRootOptions().Tolerance;
  int compared = 0, flagged = 0, onCuts = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    double r;
    const auto factors = SpheresAndTorus(rng, trial, r);
    const int count = static_cast<int>(factors.size());
    const double length = 8.0;
    const auto whole = Roots(factors, r, 0.0, length);
    std::vector<double> cuts{ 0.0, length };
    for (int s = 0; s < 22; ++s)
    {
      cuts.push_back(length * (s + 0.61) / 23);
    }
    if (trial % 2 == 1)
    {
      for (const RayRoot& x : whole)
      {
        cuts.push_back(x.T);
        ++onCuts;
      }
    }
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    const int pieces = static_cast<int>(cuts.size()) - 1;
    std::vector<int> monotone(pieces, 0);
    const int samples = 4000;
    for (int k = 0; k < pieces; ++k)
    {
      const double step = length / samples, a = cuts[k] - step, b = cuts[k + 1] + step;
      int positive = 0, negative = 0;
      for (double t = a; t <= b; t += 0.25 * step)
      {
        const long double s = ProductSlope(factors, t);
        positive += s > 0;
        negative += !(s > 0);
      }
      monotone[k] = positive == 0 || negative == 0;
      flagged += monotone[k];
    }
    std::vector<double> flat;
    std::vector<int> counts;
    for (const auto& f : factors)
    {
      flat.insert(flat.end(), f.begin(), f.end());
      counts.push_back(static_cast<int>(f.size()));
    }
    RayRootOptions options;
    std::vector<RayRoot> cut;
    ASSERT_TRUE(FindRayRoots(
      flat.data(), counts.data(), count, r, cuts.data(), monotone.data(), pieces, options, cut));
    ASSERT_EQ(cut.size(), whole.size()) << "trial " << trial;
    for (size_t k = 0; k < whole.size(); ++k)
    {
      EXPECT_NEAR(cut[k].T, whole[k].T, 2.0 * tolerance) << "trial " << trial << " root " << k;
      EXPECT_EQ(cut[k].Tangent, whole[k].Tangent) << "trial " << trial << " root " << k;
      ++compared;
    }
    options.AllRoots = false;
    std::vector<RayRoot> first;
    ASSERT_TRUE(FindRayRoots(
      flat.data(), counts.data(), count, r, cuts.data(), monotone.data(), pieces, options, first));
    ASSERT_EQ(first.size(), whole.empty() ? 0u : 1u) << "trial " << trial;
    if (!whole.empty())
    {
      EXPECT_NEAR(first[0].T, whole[0].T, 2.0 * tolerance) << "trial " << trial;
    }
  }
  EXPECT_GT(compared, 60);
  EXPECT_GT(flagged, 200);
  EXPECT_GT(onCuts, 20);
  // Cuts that are not increasing or not finite are refused.
  const double coefficients[2] = { -1.0, 2.0 };
  const int counts[1] = { 2 }, flags[2] = { 0, 0 };
  const double backwards[3] = { 0.0, 0.7, 0.6 }, nan[3] = { 0.0, NAN, 1.0 };
  std::vector<RayRoot> roots;
  RayRootOptions options;
  EXPECT_FALSE(FindRayRoots(coefficients, counts, 1, 0.0, backwards, flags, 2, options, roots));
  EXPECT_FALSE(FindRayRoots(coefficients, counts, 1, 0.0, nan, flags, 2, options, roots));
  EXPECT_FALSE(FindRayRoots(coefficients, counts, 1, 0.0, nan, flags, 0, options, roots));
}
