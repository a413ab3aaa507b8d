// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of pisurf::RayCaster's hit attributes (PiRayCaster.h): the singularity test
// and its shortcut (ProductKernel::EvaluateVertexIfRegular), which skips the six probes
// only where they could not have said "singular".
#include "PiCoreTestUtilities.h"
#include "PiModel.h"
#include "PiProductField.h"
#include "PiProductKernel.h"
#include "PiRayCaster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
// The field of a kernel the test keeps (an empty owner: the kernel is not deleted).
pisurf::ProductField Unowned(const pisurf::ProductKernel& k)
{
  return pisurf::ProductField(
    std::shared_ptr<const pisurf::ProductKernel>(std::shared_ptr<void>(), &k));
}
}

using namespace pisurf;
using pisurf_test::SameBits;

namespace
{
// Every model of the gallery, as the product kernel vtkPiSurface builds.
struct Loaded
{
  std::string Name;
  ProductKernel Kernel;
  double Bounds[6];
};

// A model's product kernel from its .pisurf text.
Loaded FromText(const std::string& name, const std::string& text)
{
  Model m;
  std::string error;
  EXPECT_TRUE(ParseModel(text, m, error)) << name << ": " << error;
  std::vector<Factor> factors;
  for (const PrimitiveSpec& s : m.Primitives)
  {
    Factor f;
    EXPECT_TRUE(BuildFactor(s, m.Parameters, f.Polynomial, error)) << name << ": " << error;
    f.Polynomial.PrepareIntervals();
    factors.push_back(f);
  }
  Loaded l{ name, ProductKernel(factors, m.Blending), {} };
  std::copy(m.Bounds, m.Bounds + 6, l.Bounds);
  return l;
}

std::vector<Loaded> GalleryModels()
{
  std::vector<std::string> names;
  if (DIR* dir = opendir(PISURF_MODELS_DIR))
  {
    while (dirent* entry = readdir(dir))
    {
      const std::string name = entry->d_name;
      if (name.size() > 7 && name.compare(name.size() - 7, 7, ".pisurf") == 0)
      {
        names.push_back(name);
      }
    }
    closedir(dir);
  }
  std::sort(names.begin(), names.end());
  std::vector<Loaded> models;
  for (const std::string& name : names)
  {
    std::ifstream in(std::string(PISURF_MODELS_DIR) + "/" + name);
    std::stringstream text;
    text << in.rdbuf();
    models.push_back(FromText(name, text.str()));
  }
  return models;
}

// The benchmark's 10 spheres (their centres in `centres` if asked).
Loaded TenSpheres(std::vector<std::array<double, 3>>* centres = nullptr)
{
  std::ostringstream text;
  text << "{\"pisurf\": 1, \"blending\": 0.5, \"bounds\": [-3.3, 3.3, -1.5, 1.5, -0.9, 1.8], "
       << "\"primitives\": [";
  for (int i = 0; i < 10; ++i)
  {
    const std::array<double, 3> c = { 1.2 * (i % 5) - 2.4, 1.2 * (i / 5) - 0.6, 0.1 * i };
    if (centres)
    {
      centres->push_back(c);
    }
    text << (i ? ", " : "") << "{\"type\": \"sphere\", \"center\": [" << c[0] << ", " << c[1]
         << ", " << c[2] << "], \"radius\": 0.8}";
  }
  text << "]}";
  return FromText("10 spheres", text.str());
}

// p moved onto the surface by up to 30 Newton steps along the gradient, each kept in
// `box` if given.
void ToSurface(const ProductKernel& k, double p[3], const double* box)
{
  for (int it = 0; it < 30; ++it)
  {
    double g[3];
    const double F = k.EvaluateWithGradient(p, g);
    const double g2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
    if (!(g2 > 0) || !std::isfinite(F))
    {
      break;
    }
    for (int a = 0; a < 3; ++a)
    {
      const double next = p[a] - F * g[a] / g2;
      p[a] = box ? std::min(box[2 * a + 1], std::max(box[2 * a], next)) : next;
    }
  }
}

// |∇F|·h over the largest |F| of the six probes, as RayCaster::Attributes's test sees
// them (EvaluateVertexStar); +inf where the probes are all 0.
double ProbeRatio(const ProductKernel& k, const double p[3], double h)
{
  double n[3], g, logG, m[6];
  long e[6];
  int nearest;
  k.EvaluateVertexStar(p, h, n, g, nearest, logG, m, e);
  double largest = 0.0;
  for (int a = 0; a < 6; ++a)
  {
    largest = std::max(largest, std::fabs(std::ldexp(m[a], static_cast<int>(e[a]))));
  }
  return largest > 0 ? g * h / largest : std::numeric_limits<double>::infinity();
}

// Points all over a model's box (on the surface, near it, far from it, where the
// gradient nearly vanishes: "singular" is common off the surface, where |F| is large at
// the probes): at a tolerance just above the probes' own ratio the probes say singular,
// so the shortcut must not say regular; at a tolerance just below they say regular, and
// where the shortcut says so too, its attributes must be EvaluateVertex's. A bound U
// below the probes' largest |F| fails the first check. Counts the regular surface
// points the shortcut certifies and those it refuses; `accepted(p)` is called on each
// certified surface point.
template <class Accepted>
void CheckSkippedProbes(const Loaded& model, std::mt19937& rng, int samples, int& certified,
  int& refused, Accepted&& accepted)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double* b = model.Bounds;
  const double size = std::sqrt(
    (b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  const double h = 1e-3 * size;
  const ProductKernel& k = model.Kernel;
  const ProductKernel::ProbeBounds bounds = k.PrepareProbes(b, h);
  for (int s = 0; s < samples; ++s)
  {
    double p[3];
    for (int a = 0; a < 3; ++a)
    {
      p[a] = b[2 * a] + unit(rng) * (b[2 * a + 1] - b[2 * a]);
    }
    if (s % 2 == 1)
    {
      ToSurface(k, p, b); // half the points on the surface
    }
    const double ratio = ProbeRatio(k, p, h);
    if (!(ratio > 0) || !std::isfinite(ratio))
    {
      continue;
    }
    double n[3], g, logG;
    int nearest;
    // Just above the ratio: the probes say singular.
    const bool above =
      k.EvaluateVertexIfRegular(p, bounds, ratio * (1 + 1e-9), n, g, nearest, &logG);
    EXPECT_FALSE(above) << model.Name << " at (" << p[0] << ", " << p[1] << ", " << p[2]
                        << "): regular claimed where the probes' ratio is " << ratio;
    // The ray caster's own tolerance (and its call, without the logarithm).
    const bool onSurface = s % 2 == 1;
    if (k.EvaluateVertexIfRegular(p, bounds, 0.1, n, g, nearest))
    {
      if (onSurface)
      {
        ++certified;
        accepted(p);
      }
      EXPECT_GT(ratio, 0.1) << model.Name;
      double n2[3], g2;
      int nearest2;
      k.EvaluateVertex(p, n2, g2, nearest2);
      EXPECT_EQ(g, g2);
      EXPECT_EQ(nearest, nearest2);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(n[a], n2[a]);
      }
    }
    else if (onSurface && ratio > 0.1)
    {
      ++refused; // a regular surface point the shortcut could not certify
    }
  }
}
}

// Every gallery model.
TEST(RayCast, SkippedProbesNeverContradictTheProbes)
{
  std::mt19937 rng(7);
  int certified = 0, refused = 0, models = 0;
  for (const Loaded& model : GalleryModels())
  {
    ++models;
    CheckSkippedProbes(model, rng, 4000, certified, refused, [](const double*) {});
  }
  EXPECT_GE(models, 20);
  // The shortcut does its job: most regular surface points are certified.
  EXPECT_GT(certified, 10 * refused);
}

// Products of many spheres, whose surface hugs each sphere where the others' product is
// large (~1e9 for the benchmark's 10 spheres): there one factor is tiny (below 1e-8 on
// a fifth of the ray hits), which the shortcut must still certify, with the same
// answers. (With 20 such spheres the others' product reaches 1e20 and the surface lies
// within the rounding of |p − c|² − R² of the spheres: no test of attributes there.)
TEST(RayCast, SkippedProbesCertifyTinyFactorsOfManySpheres)
{
  std::mt19937 rng(11);
  std::vector<std::array<double, 3>> centres;
  const Loaded model = TenSpheres(&centres);
  int certified = 0, refused = 0, tiny = 0;
  CheckSkippedProbes(model, rng, 4000, certified, refused,
    [&](const double* p)
    {
      double smallest = HUGE_VAL;
      for (const auto& c : centres)
      {
        const double d2 = (p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) +
          (p[2] - c[2]) * (p[2] - c[2]);
        smallest = std::min(smallest, std::fabs(d2 - 0.64));
      }
      tiny += smallest < 1e-8 ? 1 : 0;
    });
  std::printf("10 spheres: %d surface points certified, %d refused, %d with a factor below "
              "1e-8\n",
    certified, refused, tiny);
  EXPECT_GT(certified, 10 * refused);
  EXPECT_GT(tiny, certified / 20);
}

// Through RayCaster::Attributes: the same Singular answer with the probes prepared as
// without, on the crossed cylinders at r = 0 (a singular curve where they meet).
TEST(RayCast, PreparedProbesKeepTheSingularCurve)
{
  std::vector<Factor> factors(2);
  std::string error;
  PrimitiveSpec a, c;
  a.Type = PrimitiveType::Cylinder;
  a.Radius = 1;
  a.Axis[0] = 1;
  a.Axis[1] = 0;
  a.Axis[2] = 0;
  c = a;
  c.Axis[0] = 0;
  c.Axis[1] = 1;
  ASSERT_TRUE(BuildFactor(a, {}, factors[0].Polynomial, error)) << error;
  ASSERT_TRUE(BuildFactor(c, {}, factors[1].Polynomial, error)) << error;
  for (Factor& f : factors)
  {
    f.Polynomial.PrepareIntervals();
  }
  const ProductKernel k(factors, 0.0);
  const ProductField field = Unowned(k);
  RayCaster plain(field), prepared(field);
  const double box[6] = { -2, 2, -2, 2, -2, 2 };
  const double h = 1e-3 * std::sqrt(48.0);
  prepared.PrepareProbes(box, h);
  int singular = 0;
  for (int s = 0; s <= 2000; ++s)
  {
    // Points on the first cylinder (y² + z² = 1), crossing the curve where it meets the
    // second (x² + z² = 1) at x = ±y.
    const double angle = 0.3 + 0.001 * s, x = std::sin(angle) + 1e-4 * (s % 7);
    const double p[3] = { x, std::sin(angle), std::cos(angle) };
    double n1[3], n2[3], g1, g2;
    int f1, f2;
    const bool s1 = plain.Attributes(p, h, 0.1, n1, g1, f1);
    const bool s2 = prepared.Attributes(p, h, 0.1, n2, g2, f2);
    EXPECT_EQ(s1, s2) << "at angle " << angle;
    singular += s1 ? 1 : 0;
  }
  EXPECT_GT(singular, 0);
}

// RayCaster::Attributes at up to four points at once (the ray caster's hits, side by
// side; ProductKernel::EvaluateVerticesIfRegular where every factor is an axis-aligned
// quadric or quartic in the squares) gives each point's single-point answers, bit for
// bit: Singular, normal, |∇F| and nearest factor. On every gallery model and the 10
// spheres, at points in and around the box (outside it the shortcut does not apply),
// half of them on the surface, at three tolerances.
TEST(RayCast, HitsFourAtATimeHaveTheSingleHitAnswers)
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-0.1, 1.1);
  std::vector<Loaded> models = GalleryModels();
  models.push_back(TenSpheres());
  int starModels = 0, fourLaneRegular = 0, fourLaneSingular = 0, borderline = 0;
  for (const Loaded& model : models)
  {
    const ProductKernel& k = model.Kernel;
    const bool star = k.HasStarFactorsOnly();
    starModels += star ? 1 : 0;
    const double* b = model.Bounds;
    const double h = 1e-3 *
      std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
        (b[5] - b[4]) * (b[5] - b[4]));
    const ProductField field = Unowned(k);
    RayCaster caster(field);
    caster.PrepareProbes(b, h);
    const ProductKernel::ProbeBounds bounds = k.PrepareProbes(b, h);
    for (int group = 0; group < 300; ++group)
    {
      const int count = 1 + group % ProductKernel::MaxVertices;
      double p[ProductKernel::MaxVertices][3];
      for (int j = 0; j < count; ++j)
      {
        for (int a = 0; a < 3; ++a)
        {
          p[j][a] = b[2 * a] + unit(rng) * (b[2 * a + 1] - b[2 * a]);
        }
        if ((group + j) % 2 == 1)
        {
          ToSurface(k, p[j], nullptr); // (not kept in the box: some points lie outside)
        }
      }
      const double tolerance = group % 3 == 0 ? 0.1 : group % 3 == 1 ? 1e-4 : 30.0;
      double n[ProductKernel::MaxVertices][3], g[ProductKernel::MaxVertices];
      int nearest[ProductKernel::MaxVertices];
      bool singular[ProductKernel::MaxVertices];
      caster.Attributes(count, p, h, tolerance, n, g, nearest, singular);
      for (int j = 0; j < count; ++j)
      {
        double n1[3], g1;
        int nearest1;
        const bool singular1 = caster.Attributes(p[j], h, tolerance, n1, g1, nearest1);
        EXPECT_EQ(singular[j], singular1) << model.Name << " group " << group << " point " << j;
        EXPECT_TRUE(SameBits(g[j], g1))
          << model.Name << " group " << group << ": " << g[j] << " vs " << g1;
        for (int c = 0; c < 3; ++c)
        {
          EXPECT_TRUE(SameBits(n[j][c], n1[c])) << model.Name << " group " << group;
        }
        EXPECT_EQ(nearest[j], nearest1) << model.Name << " group " << group;
        if (star)
        {
          (singular1 ? fourLaneSingular : fourLaneRegular) += 1;
        }
      }
      // At the tolerance where the shortcut's verdict at one of the points flips (by
      // bisection on the single-point function): the same verdicts just below and just
      // above it (a bound of the probes' |F| off in its last bits changes them).
      const int J = group % count;
      double below = 1e-300, above = 1e300, n1[3], g1;
      int nearest1;
      if (k.EvaluateVertexIfRegular(p[J], bounds, below, n1, g1, nearest1))
      {
        for (int it = 0; it < 200 && above > below * (1 + 1e-12); ++it)
        {
          const double mid = std::sqrt(below) * std::sqrt(above);
          (k.EvaluateVertexIfRegular(p[J], bounds, mid, n1, g1, nearest1) ? below : above) = mid;
        }
        for (const double t : { below, above })
        {
          bool regular[ProductKernel::MaxVertices];
          k.EvaluateVerticesIfRegular(count, p, bounds, t, n, g, nearest, regular);
          EXPECT_EQ(regular[J], t == below) << model.Name << " group " << group;
          borderline += star ? 1 : 0;
        }
      }
    }
  }
  // (the models the four-point path is for, and both answers there)
  EXPECT_GE(starModels, 3);
  EXPECT_GT(fourLaneRegular, 500);
  EXPECT_GT(fourLaneSingular, 20);
  EXPECT_GT(borderline, 1000);
}
