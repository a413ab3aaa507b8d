// SPDX-License-Identifier: BSD-3-Clause
// The molecule field's approximations against exact evaluation over all atoms: the
// two-level far field (cells and supercells) stays within its stated bound and never
// changes a sign; ClassifyBox never decides wrongly; FirstRoot's vertex is within the
// tolerance of a true root with F > 0 before it.
#include "PiMolecule.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace
{
// A protein-like cluster: atoms on a jittered lattice of 1.6 A (about a protein's atom
// density) inside a ball, radii 1.5 to 1.8 A.
struct Cluster
{
  std::vector<double> Centers, Radii;
  double Region[6];
};

Cluster MakeCluster(double radius, unsigned seed)
{
  Cluster c;
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
  auto exactF = [&](const double p[3]) {
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
