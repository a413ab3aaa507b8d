// SPDX-License-Identifier: BSD-3-Clause
// The molecule field's approximations against exact evaluation over all atoms: the
// two-level far field (cells and supercells) stays within its stated bound and never
// changes a sign; ClassifyBox never decides wrongly; FirstRoot's vertex is within the
// tolerance of a true root with F > 0 before it.
#include "PiCoreTestUtilities.h"
#include "PiMoleculeField.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace
{
using Cluster = pisurf_test::MoleculeCluster;
Cluster MakeCluster(double radius, unsigned seed)
{
  return pisurf_test::MakeMoleculeCluster(radius, seed);
}
}

TEST(MoleculeField, FarFieldWithinItsBoundAndSignExact)
{
  // Radius 22 A: about 10^4 atoms, so most atoms are beyond the supercells' reach.
  const Cluster c = MakeCluster(22.0, 7);
  ASSERT_GT(c.Radii.size(), 8000u);
  pisurf::MoleculeSettings settings;
  pisurf::MoleculeField field(c.Centers, c.Radii, settings, c.Region);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-25.0, 25.0);
  int compared = 0;
  for (int n = 0; n < 400; ++n)
  {
    const double p[3] = { u(rng), u(rng), u(rng) };
    double exactLog, approxLog, bound;
    const int exactSign = field.EvaluateExactSignAndLog(p, exactLog);
    const int approxSign = field.EvaluateApproximateSignAndLog(p, approxLog, bound);
    ASSERT_EQ(exactSign, approxSign) << "at " << p[0] << " " << p[1] << " " << p[2];
    if (exactSign != 0)
    {
      EXPECT_LE(std::fabs(approxLog - exactLog), bound + 1e-7 * std::fabs(exactLog))
        << "at " << p[0] << " " << p[1] << " " << p[2];
      ++compared;
    }
    // Evaluate (approximation with the exact fallback) has the exact sign of F.
    const double F = field.Evaluate(p);
    const double level = field.GetLevel();
    const bool positive = exactSign > 0 && exactLog > std::log(level);
    EXPECT_EQ(F > 0, positive);
  }
  EXPECT_GT(compared, 300);
  EXPECT_GT(field.GetFarErrorBound(), 0.0); // the far field was used
}

TEST(MoleculeField, ClassifyBoxNeverWrong)
{
  const Cluster c = MakeCluster(14.0, 11);
  pisurf::MoleculeSettings settings;
  pisurf::MoleculeField field(c.Centers, c.Radii, settings, c.Region);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-18.0, 18.0), size(0.2, 4.0);
  int decided = 0;
  for (int n = 0; n < 300; ++n)
  {
    const double o[3] = { u(rng), u(rng), u(rng) };
    const double s = size(rng);
    const double box[6] = { o[0], o[0] + s, o[1], o[1] + s, o[2], o[2] + s };
    const int sign = field.ClassifyBox(box);
    if (sign == 0)
    {
      continue;
    }
    ++decided;
    for (int k = 0; k < 27; ++k)
    {
      const double p[3] = { o[0] + s * (k % 3) / 2.0, o[1] + s * ((k / 3) % 3) / 2.0,
        o[2] + s * (k / 9) / 2.0 };
      double logAbs;
      const int ps = field.EvaluateExactSignAndLog(p, logAbs);
      const bool positive = ps > 0 && logAbs > std::log(field.GetLevel());
      EXPECT_EQ(sign > 0, positive) << "box at " << o[0] << " " << o[1] << " " << o[2];
    }
  }
  EXPECT_GT(decided, 100);
}

TEST(MoleculeField, FirstRootIsTheFirstCrossing)
{
  const Cluster c = MakeCluster(12.0, 13);
  pisurf::MoleculeSettings settings;
  pisurf::MoleculeField field(c.Centers, c.Radii, settings, c.Region);
  auto exactF = [&](const double p[3])
  {
    double logAbs;
    const int sign = field.EvaluateExactSignAndLog(p, logAbs);
    return sign > 0 && logAbs > std::log(field.GetLevel()) ? 1 : -1;
  };
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-15.0, 15.0), dir(-1.0, 1.0);
  (void)u;
  int answered = 0;
  const double tolerance = 1e-9;
  for (int n = 0; n < 4000 && answered < 200; ++n)
  {
    // Half the segments start 0.05 to 0.45 A outside a random atom's sphere and point
    // roughly at its centre; the others are anywhere.
    double d[3] = { dir(rng), dir(rng), dir(rng) };
    const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (double& x : d)
    {
      x /= norm;
    }
    double a[3] = { u(rng), u(rng), u(rng) };
    if (n % 2)
    {
      const size_t atom = rng() % c.Radii.size();
      const double gap = 0.05 + 0.4 * (rng() % 1000) / 1000.0;
      for (int k = 0; k < 3; ++k)
      {
        a[k] = c.Centers[3 * atom + k] + (c.Radii[atom] + gap) * d[k];
        d[k] = -d[k];
      }
    }
    const double b[3] = { a[0] + 0.5 * d[0], a[1] + 0.5 * d[1], a[2] + 0.5 * d[2] };
    if (exactF(a) < 0)
    {
      continue;
    }
    double s;
    if (!field.FirstRoot(a, b, tolerance, s))
    {
      continue;
    }
    ++answered;
    ASSERT_GT(s, 0.0);
    ASSERT_LE(s, 1.0);
    // F > 0 at sampled points before s − tolerance, F < 0 just after s + tolerance.
    for (int m = 0; m <= 16; ++m)
    {
      const double t = (s - 2 * tolerance / 0.5) * m / 16.0;
      const double p[3] = { a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]),
        a[2] + t * (b[2] - a[2]) };
      EXPECT_EQ(exactF(p), 1);
    }
    const double t = s + 2 * tolerance / 0.5;
    const double p[3] = { a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]),
      a[2] + t * (b[2] - a[2]) };
    EXPECT_EQ(exactF(p), -1);
  }
  EXPECT_GE(answered, 100);
}

// Local mode: a box evaluated at once gives Evaluate's values bit for bit (the mesher
// mixes both: blocks sample boxes, root finding and other passes evaluate points), for
// boxes inside the cluster, across its surface and beyond every atom's reach, with the
// mesher's strided layout.
TEST(MoleculeField, LocalBoxEqualsPointwise)
{
  const Cluster c = MakeCluster(10.0, 5);
  pisurf::MoleculeSettings settings;
  settings.Mode = pisurf::MoleculeMode::Local;
  pisurf::MoleculeField field(c.Centers, c.Radii, settings, c.Region);
  const double origin[3] = { -14.1, -13.9, -14.05 };
  const double spacing[3] = { 0.37, 0.41, 0.29 };
  std::mt19937 rng(3);
  size_t insideSphere = 0, farAway = 0, points = 0;
  for (int trial = 0; trial < 60; ++trial)
  {
    int first[3], last[3];
    for (int a = 0; a < 3; ++a)
    {
      first[a] = static_cast<int>(rng() % 80);
      last[a] = first[a] + static_cast<int>(rng() % 9); // 1 to 9 points
    }
    const long strideY = 9, strideZ = 81;
    std::vector<double> values(9 * 9 * 9, -12345.0);
    ASSERT_TRUE(field.EvaluateBox(origin, spacing, first, last, strideY, strideZ, values.data()));
    for (int k = first[2]; k <= last[2]; ++k)
      for (int j = first[1]; j <= last[1]; ++j)
        for (int i = first[0]; i <= last[0]; ++i)
        {
          const double p[3] = { origin[0] + i * spacing[0], origin[1] + j * spacing[1],
            origin[2] + k * spacing[2] };
          const double expected = field.Evaluate(p);
          const double got =
            values[(k - first[2]) * strideZ + (j - first[1]) * strideY + (i - first[0])];
          ASSERT_EQ(got, expected) << "at (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
          insideSphere += field.OffOuterSide(p);
          farAway += expected == 1.0 - field.GetLevel();
          ++points;
        }
  }
  // The boxes saw every kind of point.
  EXPECT_GT(insideSphere, points / 20);
  EXPECT_GT(farAway, points / 20);

  pisurf::MoleculeSettings global;
  pisurf::MoleculeField globalField(c.Centers, c.Radii, global, c.Region);
  const int first[3] = { 0, 0, 0 }, last[3] = { 1, 1, 1 };
  double values[8];
  EXPECT_FALSE(globalField.EvaluateBox(origin, spacing, first, last, 2, 4, values));
}

// Local mode: RefineEdge on grid edges that cross the surface returns a root of F
// within the tolerance (F changes sign across it, |F|/|grad F| small), with
// EvaluateVertex's normal and gradient norm (to rounding) and atom at that point, and
// OffOuterSide.
TEST(MoleculeField, LocalRefineEdgeFindsTheRoot)
{
  const Cluster c = MakeCluster(10.0, 9);
  pisurf::MoleculeSettings settings;
  settings.Mode = pisurf::MoleculeMode::Local;
  pisurf::MoleculeField field(c.Centers, c.Radii, settings, c.Region);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-13.0, 13.0);
  const double h = 0.5, tolerance = 1e-10;
  int refined = 0, offOuter = 0, small = 0, walls = 0;
  for (int n = 0; n < 200000 && refined < 2000; ++n)
  {
    const int axis = static_cast<int>(rng() % 3);
    double a[3] = { u(rng), u(rng), u(rng) }, b[3] = { a[0], a[1], a[2] };
    b[axis] += h;
    const double va = field.Evaluate(a), vb = field.Evaluate(b);
    if (!((va < 0 && vb > 0) || (va > 0 && vb < 0)))
    {
      pisurf::Field::EdgeVertex v;
      EXPECT_FALSE(field.RefineEdge(a, b, va, vb, -1, tolerance, v)); // no bracket
      // From an end: the first of 16 steps where F changes sign (found here with
      // Evaluate), and a root in it; none: false.
      const int from = static_cast<int>(rng() % 2);
      double crossing[2] = { -1, -1 };
      double s0 = from, f0 = from ? vb : va;
      for (int m = 1; m <= 16; ++m)
      {
        const double s1 = from ? 1.0 - m / 16.0 : m / 16.0;
        double p[3];
        for (int k = 0; k < 3; ++k)
        {
          p[k] = a[k] + s1 * (b[k] - a[k]);
        }
        const double f1 = m == 16 ? (from ? va : vb) : field.Evaluate(p);
        if ((f0 > 0) != (f1 > 0))
        {
          crossing[0] = std::min(s0, s1);
          crossing[1] = std::max(s0, s1);
          break;
        }
        s0 = s1;
        f0 = f1;
      }
      const bool found = field.RefineEdge(a, b, va, vb, from, tolerance, v);
      EXPECT_EQ(found, crossing[0] >= 0);
      if (found && crossing[0] >= 0)
      {
        ++walls;
        EXPECT_GE(v.S, crossing[0] - 1e-12);
        EXPECT_LE(v.S, crossing[1] + 1e-12);
      }
      continue;
    }
    pisurf::Field::EdgeVertex v;
    ASSERT_TRUE(field.RefineEdge(a, b, va, vb, -1, tolerance, v));
    ++refined;
    ASSERT_GE(v.S, 0.0);
    ASSERT_LE(v.S, 1.0);
    double x[3];
    for (int k = 0; k < 3; ++k)
    {
      x[k] = a[k] + v.S * (b[k] - a[k]);
    }
    double normal[3], gradientNorm;
    int nearest;
    field.EvaluateVertex(x, normal, gradientNorm, nearest);
    ASSERT_GT(gradientNorm, 0.0);
    // Either |F| is below 1e-12 of its values at the ends (the mesher's rule too: the
    // ends can differ by ten orders of magnitude where atoms crowd), or |F|/|grad F|,
    // the distance to the surface to first order, is within the tolerance and the sign
    // changes within a few tolerances of the vertex along the edge.
    const double F = field.Evaluate(x);
    if (std::fabs(F) / gradientNorm <= tolerance)
    {
      double before[3], after[3];
      for (int k = 0; k < 3; ++k)
      {
        before[k] = x[k] - (b[k] - a[k]) / h * 10 * tolerance;
        after[k] = x[k] + (b[k] - a[k]) / h * 10 * tolerance;
      }
      EXPECT_NE(field.Evaluate(before) > 0, field.Evaluate(after) > 0);
    }
    else
    {
      EXPECT_LE(std::fabs(F), 1e-12 * std::max(std::fabs(va), std::fabs(vb)));
      ++small;
    }
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(v.Normal[k], normal[k], 1e-12);
    }
    EXPECT_NEAR(v.GradientNorm, gradientNorm, 1e-12 * gradientNorm);
    EXPECT_EQ(v.Nearest, nearest);
    EXPECT_EQ(v.OffOuterSide, field.OffOuterSide(x));
    offOuter += v.OffOuterSide;
  }
  EXPECT_GE(refined, 2000);
  EXPECT_LT(small, refined / 100);
  EXPECT_GT(walls, 20);   // edges with a thin wall between ends of one sign
  EXPECT_GT(offOuter, 0); // lens sheets were among them

  // A diagonal segment or a Global field: not handled (the mesher's general method).
  const double a[3] = { 0, 0, 0 }, b[3] = { 0.1, 0.1, 0 };
  pisurf::Field::EdgeVertex v;
  EXPECT_FALSE(field.RefineEdge(a, b, 1.0, -1.0, -1, tolerance, v));
  pisurf::MoleculeSettings global;
  pisurf::MoleculeField globalField(c.Centers, c.Radii, global, c.Region);
  const double b2[3] = { 0.5, 0, 0 };
  EXPECT_FALSE(globalField.RefineEdge(a, b2, 1.0, -1.0, -1, tolerance, v));
}

// Both modes: OffOuterSideBox marks exactly the points OffOuterSide says true for.
TEST(MoleculeField, OffOuterSideBoxEqualsPointwise)
{
  const Cluster c = MakeCluster(8.0, 11);
  for (int mode = 0; mode < 2; ++mode)
  {
    pisurf::MoleculeSettings settings;
    settings.Mode = mode ? pisurf::MoleculeMode::Local : pisurf::MoleculeMode::Global;
    pisurf::MoleculeField field(c.Centers, c.Radii, settings, c.Region);
    const double origin[3] = { -12.1, -11.9, -12.05 };
    const double spacing[3] = { 0.33, 0.41, 0.29 };
    std::mt19937 rng(7 + mode);
    size_t marked = 0, points = 0;
    for (int trial = 0; trial < 40; ++trial)
    {
      int first[3], last[3];
      for (int a = 0; a < 3; ++a)
      {
        first[a] = static_cast<int>(rng() % 70);
        last[a] = first[a] + static_cast<int>(rng() % 9);
      }
      std::vector<unsigned char> flags(9 * 9 * 9, 7);
      ASSERT_TRUE(field.OffOuterSideBox(origin, spacing, first, last, 9, 81, flags.data()));
      for (int k = first[2]; k <= last[2]; ++k)
        for (int j = first[1]; j <= last[1]; ++j)
          for (int i = first[0]; i <= last[0]; ++i)
          {
            const double p[3] = { origin[0] + i * spacing[0], origin[1] + j * spacing[1],
              origin[2] + k * spacing[2] };
            const unsigned char got =
              flags[(k - first[2]) * 81 + (j - first[1]) * 9 + (i - first[0])];
            ASSERT_EQ(got, field.OffOuterSide(p) ? 1 : 0);
            marked += got;
            ++points;
          }
    }
    EXPECT_GT(marked, points / 20);
    EXPECT_LT(marked, points - points / 10);
  }
}

// CastRay against references along random rays through small clusters: in Global mode
// the certified roots of the product of all the atoms' quadratics restricted to the ray
// (FindRayRoots), the same count, each within the tolerance, the same Tangent flags; in
// Local mode (no polynomial reference: g is piecewise) every sign change of F between
// 20000 samples holds a root, every crossing root has F of opposite signs a tolerance
// before and after it. Roots strictly increase in both.
TEST(MoleculeField, CastRayFindsEveryRoot)
{
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  int compared = 0, roots = 0;
  for (const double size : { 2.5, 4.0 })
  {
    const Cluster c = MakeCluster(size, 5);
    for (const double r : { 0.01, 1.0, 30.0 })
    {
      for (const pisurf::MoleculeMode mode :
        { pisurf::MoleculeMode::Global, pisurf::MoleculeMode::Local })
      {
        pisurf::MoleculeSettings settings;
        settings.Mode = mode;
        settings.Blending = r;
        const pisurf::MoleculeField field(c.Centers, c.Radii, settings, c.Region);
        const double length = 2.0 * c.Region[1];
        pisurf::RayRootOptions options;
        options.Tolerance = 1e-10 * length;
        for (int ray = 0; ray < 60; ++ray)
        {
          // Through a random point of the cluster, in a random or an axis direction.
          double d[3] = { normal(rng), normal(rng), normal(rng) };
          if (ray % 4 == 0)
          {
            d[0] = d[1] = d[2] = 0.0;
            d[ray / 4 % 3] = ray % 8 ? 1.0 : -1.0;
          }
          const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
          double o[3];
          for (int k = 0; k < 3; ++k)
          {
            d[k] /= norm;
            o[k] = 0.5 * size * normal(rng) * 0.5 - 0.5 * length * d[k];
          }
          std::vector<pisurf::RayRoot> found;
          options.AllRoots = true;
          field.CastRay(o, d, 0.0, length, options, found);
          for (size_t k = 1; k < found.size(); ++k)
          {
            ASSERT_LT(found[k - 1].T, found[k].T) << "ray " << ray << " root " << k;
          }
          std::vector<pisurf::RayRoot> first;
          options.AllRoots = false;
          field.CastRay(o, d, 0.0, length, options, first);
          ASSERT_EQ(first.size(), found.empty() ? 0u : 1u);
          if (!found.empty())
          {
            EXPECT_NEAR(first[0].T, found[0].T, 2 * options.Tolerance);
          }
          auto F = [&](double t)
          {
            const double p[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
            return field.Evaluate(p);
          };
          roots += static_cast<int>(found.size());
          if (mode == pisurf::MoleculeMode::Global)
          {
            std::vector<std::vector<double>> factors;
            for (size_t i = 0; i < c.Radii.size(); ++i)
            {
              const double* ci = &c.Centers[3 * i];
              const double v[3] = { o[0] - ci[0], o[1] - ci[1], o[2] - ci[2] };
              factors.push_back({ v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - c.Radii[i] * c.Radii[i],
                2.0 * (d[0] * v[0] + d[1] * v[1] + d[2] * v[2]), 1.0 });
            }
            std::vector<pisurf::RayRoot> reference;
            options.AllRoots = true;
            ASSERT_TRUE(pisurf::FindRayRoots(factors, r, 0.0, length, options, reference));
            ASSERT_EQ(found.size(), reference.size()) << "ray " << ray << " r " << r;
            for (size_t k = 0; k < found.size(); ++k)
            {
              EXPECT_NEAR(found[k].T, reference[k].T, 2 * options.Tolerance);
              EXPECT_EQ(found[k].Tangent, reference[k].Tangent);
            }
            ++compared;
            continue;
          }
          const int samples = 20000;
          double ta = 0.0, va = F(0.0);
          for (int s = 1; s <= samples; ++s)
          {
            const double tb = length * s / samples, vb = F(tb);
            if ((va < 0) != (vb < 0))
            {
              const bool hit = std::any_of(found.begin(), found.end(),
                [&](const pisurf::RayRoot& x)
                { return x.T >= ta - options.Tolerance && x.T <= tb + options.Tolerance; });
              EXPECT_TRUE(hit) << "a sign change in [" << ta << ", " << tb << "] without a root";
            }
            ta = tb;
            va = vb;
          }
          for (const pisurf::RayRoot& x : found)
          {
            if (!x.Tangent)
            {
              const double before = F(x.T - options.Tolerance), after = F(x.T + options.Tolerance);
              EXPECT_TRUE((before < 0) != (after < 0)) << "root " << x.T << " is no crossing";
            }
          }
          ++compared;
        }
      }
    }
  }
  EXPECT_EQ(compared, 2 * 3 * 2 * 60);
  EXPECT_GT(roots, 500);
}
