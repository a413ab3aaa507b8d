// SPDX-License-Identifier: BSD-3-Clause
// The contract of pisurf::Field (PiField.h), checked on every field the algorithms
// mesh, ray-cast and sample: the product of primitives (gallery models, and a product
// far beyond a double's range) and the molecule's Global and Local fields. A new field
// is done when it passes this suite:
// - the same point evaluates to the same bits, from any thread;
// - the optional box answers (EvaluateBox, OffOuterSideBox) equal the point answers bit
//   for bit;
// - ClassifyBox is never wrong against dense sampling of random boxes;
// - EvaluateCompressed has F's sign, and F's sign stays exact where |F| leaves the
//   double range (clamped to ±DBL_MAX, never inf or NaN);
// - EvaluateVertex's normal agrees with finite differences of F;
// - RefineEdge and FirstRoot, where answered, bracket a true sign change of F within
//   their tolerance;
// - ClassifyBoxAndOctants is never wrong on the box nor on any octant it decides;
// - EvaluateSignAndLog gives F's sign and ln|F| where F is a normal double;
// - CastRay finds a root in every interval where F changes sign between samples of
//   the ray (at 1/1024 of its length), in increasing order and inside the segment;
// - ProbeVertex gives EvaluateVertex's attributes and says regular at most points
//   where |F| is small against |∇F|·probe.
#include "PiCoreTestUtilities.h"
#include "PiModel.h"
#include "PiMoleculeField.h"
#include "PiPolynomial.h"
#include "PiProductField.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace
{
using pisurf_test::Point;
using pisurf_test::Random;
using pisurf_test::SameBits;

struct FieldCase
{
  std::string Name;
  std::shared_ptr<const pisurf::Field> Field;
  double Region[6]; // where the surface and its surroundings lie
  double Scale;     // the size of the model, for tolerances
  // 1 − cos of the largest angle between EvaluateVertex's normal and the difference
  // quotient of the values: a field whose values approximate F far from the surface
  // within a stated bound (the molecule's Global far field) differs there by more
  // than rounding.
  double NormalTolerance = 1e-6;
  // Whether |F| and |∇F| stay within the double range somewhere in the region (not for
  // products of hundreds of factors).
  bool InRange = true;
};

std::shared_ptr<const pisurf::Field> ProductOf(std::vector<pisurf::PrimitiveSpec> primitives,
  const pisurf::ParameterMap& parameters, double blending)
{
  std::vector<pisurf::Factor> factors;
  for (const pisurf::PrimitiveSpec& spec : primitives)
  {
    pisurf::Factor factor;
    std::string error;
    if (!pisurf::BuildFactor(spec, parameters, factor.Polynomial, error))
    {
      throw std::runtime_error(error);
    }
    factors.push_back(factor);
  }
  return std::make_shared<pisurf::ProductField>(
    std::make_shared<pisurf::ProductKernel>(std::move(factors), blending));
}

FieldCase GalleryCase(const std::string& name, const double region[6])
{
  std::ifstream in(std::string(PISURF_MODELS_DIR) + "/" + name + ".pisurf");
  std::stringstream text;
  text << in.rdbuf();
  pisurf::Model model;
  std::string error;
  if (!pisurf::ParseModel(text.str(), model, error))
  {
    throw std::runtime_error(name + ": " + error);
  }
  FieldCase c{ "product/" + name, ProductOf(model.Primitives, model.Parameters, model.Blending), {},
    0.0 };
  std::copy(region, region + 6, c.Region);
  c.Scale = std::max({ region[1] - region[0], region[3] - region[2], region[5] - region[4] });
  return c;
}

// 2000 unit spheres along x, 3 apart: the product reaches 10^±4000 away from the spheres.
FieldCase LongProductCase()
{
  std::vector<pisurf::PrimitiveSpec> spheres(2000);
  for (size_t i = 0; i < spheres.size(); ++i)
  {
    spheres[i].Type = pisurf::PrimitiveType::Sphere;
    spheres[i].Center[0] = 3.0 * static_cast<double>(i);
    spheres[i].Radius = 1.0;
  }
  FieldCase c{ "product/2000_spheres", ProductOf(spheres, {}, 1.0),
    { -2.0, 20.0, -2.0, 2.0, -2.0, 2.0 }, 22.0 };
  c.InRange = false;
  return c;
}

FieldCase MoleculeCase(pisurf::MoleculeMode mode)
{
  const pisurf_test::MoleculeCluster cluster = pisurf_test::MakeMoleculeCluster(7.0, 21);
  pisurf::MoleculeSettings settings;
  settings.Mode = mode;
  FieldCase c{ mode == pisurf::MoleculeMode::Global ? "molecule/global" : "molecule/local",
    std::make_shared<pisurf::MoleculeField>(
      cluster.Centers, cluster.Radii, settings, cluster.Region),
    {}, 0.0 };
  std::copy(cluster.Region, cluster.Region + 6, c.Region);
  c.Scale = cluster.Region[1] - cluster.Region[0];
  c.NormalTolerance = mode == pisurf::MoleculeMode::Global ? 1e-3 : 1e-6;
  c.InRange = mode == pisurf::MoleculeMode::Local; // Local's F = Π g_i − r/(1 + r) is moderate
  return c;
}

// The field named `name` (one of FieldNames()).
FieldCase MakeField(const std::string& name)
{
  const double cup[6] = { -1.6, 1.6, -1.6, 1.6, -1.2, 1.6 };
  const double table[6] = { -1.8, 1.8, -1.8, 1.8, -1.5, 1.5 };
  const double eggplant[6] = { -2.2, 2.2, -1.6, 1.6, -1.6, 1.6 };
  const double cylinders[6] = { -2.0, 2.0, -2.0, 2.0, -2.0, 2.0 };
  if (name == "product/cup_a1.0")
    return GalleryCase("cup_a1.0", cup);
  if (name == "product/table")
    return GalleryCase("table", table);
  if (name == "product/eggplant_r0.25")
    return GalleryCase("eggplant_r0.25", eggplant);
  if (name == "product/crossed_cylinders_r0.001")
    return GalleryCase("crossed_cylinders_r0.001", cylinders);
  if (name == "product/2000_spheres")
    return LongProductCase();
  if (name == "molecule/global")
    return MoleculeCase(pisurf::MoleculeMode::Global);
  if (name == "molecule/local")
    return MoleculeCase(pisurf::MoleculeMode::Local);
  throw std::invalid_argument("no field case " + name);
}

Point InRegion(Random& random, const double region[6])
{
  return { random.Uniform(region[0], region[1]), random.Uniform(region[2], region[3]),
    random.Uniform(region[4], region[5]) };
}

int Sign(double v)
{
  return (v > 0) - (v < 0);
}

// gtest prints a failing case's parameter: its name, not its bytes.
// The cases by name. Every test process (ctest runs one per test) instantiates the
// suite's parameters, so they are names, and a field is built only where a test of it
// runs.
std::vector<std::string> FieldNames()
{
  return { "product/cup_a1.0", "product/table", "product/eggplant_r0.25",
    "product/crossed_cylinders_r0.001", "product/2000_spheres", "molecule/global",
    "molecule/local" };
}

const FieldCase& Case(const std::string& name)
{
  static std::map<std::string, FieldCase> built;
  auto found = built.find(name);
  if (found == built.end())
  {
    found = built.emplace(name, MakeField(name)).first;
  }
  return found->second;
}

class FieldConformance : public ::testing::TestWithParam<std::string>
{
protected:
  const FieldCase& Field() const { return Case(this->GetParam()); }
};

TEST_P(FieldConformance, ValuesAreFiniteAndTheSameFromEveryThread)
{
  const FieldCase& c = this->Field();
  Random random(1);
  std::vector<Point> points(3000);
  for (Point& p : points)
  {
    p = InRegion(random, c.Region);
  }
  std::vector<double> serial(points.size());
  for (size_t i = 0; i < points.size(); ++i)
  {
    serial[i] = c.Field->Evaluate(points[i].data());
    ASSERT_TRUE(std::isfinite(serial[i])) << c.Name << " at point " << i;
    ASSERT_TRUE(SameBits(serial[i], c.Field->Evaluate(points[i].data()))) << c.Name;
  }
  std::vector<std::vector<double>> threaded(4, std::vector<double>(points.size()));
  std::vector<std::thread> threads;
  for (size_t t = 0; t < threaded.size(); ++t)
  {
    threads.emplace_back(
      [&, t]
      {
        // Each thread walks the points from its own start, so they meet at different points.
        for (size_t n = 0; n < points.size(); ++n)
        {
          const size_t i = (n + t * points.size() / 4) % points.size();
          threaded[t][i] = c.Field->Evaluate(points[i].data());
        }
      });
  }
  for (std::thread& thread : threads)
  {
    thread.join();
  }
  for (const std::vector<double>& values : threaded)
  {
    for (size_t i = 0; i < points.size(); ++i)
    {
      ASSERT_TRUE(SameBits(values[i], serial[i])) << c.Name << " at point " << i;
    }
  }
}

TEST_P(FieldConformance, BoxAnswersEqualPointAnswers)
{
  const FieldCase& c = this->Field();
  const double h = c.Scale / 23.0;
  const double origin[3] = { c.Region[0], c.Region[2], c.Region[4] };
  const double spacing[3] = { h, h, h };
  const int first[3] = { 3, 5, 2 }, last[3] = { 14, 11, 17 };
  const long nx = last[0] - first[0] + 1, ny = last[1] - first[1] + 1;
  const long count = nx * ny * (last[2] - first[2] + 1);
  std::vector<double> values(count);
  std::vector<unsigned char> flags(count);
  const bool box = c.Field->EvaluateBox(origin, spacing, first, last, nx, nx * ny, values.data());
  const bool off =
    c.Field->OffOuterSideBox(origin, spacing, first, last, nx, nx * ny, flags.data());
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i)
      {
        const double p[3] = { origin[0] + i * spacing[0], origin[1] + j * spacing[1],
          origin[2] + k * spacing[2] };
        const long at = (k - first[2]) * nx * ny + (j - first[1]) * nx + (i - first[0]);
        if (box)
        {
          ASSERT_TRUE(SameBits(values[at], c.Field->Evaluate(p))) << c.Name;
        }
        if (off)
        {
          ASSERT_EQ(flags[at] != 0, c.Field->OffOuterSide(p)) << c.Name;
        }
      }
}

// A cube in the region: its centre drawn first, then its half side, between `smallest`
// and 0.1 of the model's size.
void RandomCube(Random& random, const FieldCase& c, double smallest, double box[6])
{
  const Point centre = InRegion(random, c.Region);
  const double half = c.Scale * random.Uniform(smallest, 0.1);
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = centre[a] - half;
    box[2 * a + 1] = centre[a] + half;
  }
}

// Dense sampling of `box` (9³ points) agrees with `sign`.
::testing::AssertionResult SignHoldsOn(const FieldCase& c, const double box[6], int sign)
{
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j)
      for (int k = 0; k <= 8; ++k)
      {
        const double p[3] = { box[0] + (box[1] - box[0]) * i / 8.0,
          box[2] + (box[3] - box[2]) * j / 8.0, box[4] + (box[5] - box[4]) * k / 8.0 };
        if (Sign(c.Field->Evaluate(p)) != sign)
        {
          return ::testing::AssertionFailure()
            << "F = " << c.Field->Evaluate(p) << " where the sign " << sign << " was claimed";
        }
      }
  return ::testing::AssertionSuccess();
}

TEST_P(FieldConformance, ClassifyBoxIsNeverWrong)
{
  const FieldCase& c = this->Field();
  Random random(2);
  int decided = 0;
  for (int n = 0; n < 300; ++n)
  {
    double box[6];
    RandomCube(random, c, 0.002, box);
    const int sign = c.Field->ClassifyBox(box);
    if (sign == 0)
    {
      continue;
    }
    ++decided;
    ASSERT_TRUE(SignHoldsOn(c, box, sign)) << c.Name << ": box " << n << " classified " << sign;
  }
  EXPECT_GT(decided, 30) << c.Name << ": ClassifyBox decides some boxes";
}

TEST_P(FieldConformance, SignIsExactBeyondTheDoubleRange)
{
  const FieldCase& c = this->Field();
  Random random(3);
  for (int n = 0; n < 3000; ++n)
  {
    const Point p = InRegion(random, c.Region);
    const double f = c.Field->Evaluate(p.data());
    const double compressed = c.Field->EvaluateCompressed(p.data());
    ASSERT_TRUE(std::isfinite(f) && std::isfinite(compressed)) << c.Name;
    ASSERT_EQ(Sign(compressed), Sign(f)) << c.Name << " at " << p[0] << " " << p[1];
    ASSERT_LE(std::fabs(f), DBL_MAX) << c.Name;
  }
  if (c.Name != "product/2000_spheres")
  {
    return;
  }
  // Between spheres i and i+1 every factor is positive: F = +huge − r. Inside sphere i
  // one factor is negative: F = −huge. Both far beyond 10^308.
  const double between[3] = { 1.5, 0.0, 0.0 }, inside[3] = { 3.0 * 700 + 0.5, 0.0, 0.0 };
  EXPECT_EQ(c.Field->Evaluate(between), DBL_MAX);
  EXPECT_EQ(c.Field->Evaluate(inside), -DBL_MAX);
  EXPECT_GT(c.Field->EvaluateCompressed(between), 700.0);
  EXPECT_LT(c.Field->EvaluateCompressed(inside), -700.0);
}

TEST_P(FieldConformance, NormalAgreesWithFiniteDifferences)
{
  // The direction is compared with the difference quotient of EvaluateCompressed,
  // sign(F)·ln(1 + |F|), whose gradient points along ∇F and stays in range where F
  // does not; |∇F| with that of F where F is moderate.
  const FieldCase& c = this->Field();
  Random random(4);
  const auto f = [&](const double* q) { return c.Field->Evaluate(q); };
  const auto compressed = [&](const double* q) { return c.Field->EvaluateCompressed(q); };
  const double h = 1e-6 * c.Scale;
  int directions = 0, magnitudes = 0;
  for (int n = 0; n < 2000; ++n)
  {
    const Point p = InRegion(random, c.Region);
    double normal[3], norm;
    int nearest;
    c.Field->EvaluateVertex(p.data(), normal, norm, nearest);
    const Point g = pisurf_test::FiniteDifferenceGradient(compressed, p.data(), h);
    const double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    if (!(gn > 0.1) || !(norm > 0))
    {
      continue; // near a critical point the difference quotient says nothing
    }
    const double cosine = (g[0] * normal[0] + g[1] * normal[1] + g[2] * normal[2]) / gn;
    ASSERT_GT(cosine, 1.0 - c.NormalTolerance)
      << c.Name << " at " << p[0] << " " << p[1] << " " << p[2];
    ++directions;
    // |∇F| where the difference quotient of F resolves it: rounding of F over 2h
    // below 1e-7 of the gradient.
    const double value = std::fabs(f(p.data()));
    if (norm < 1e300 && value < 1e300 && 1e-16 * value < 1e-7 * h * norm)
    {
      const Point gf = pisurf_test::FiniteDifferenceGradient(f, p.data(), h);
      const double gfn = std::sqrt(gf[0] * gf[0] + gf[1] * gf[1] + gf[2] * gf[2]);
      ASSERT_TRUE(pisurf_test::RelativelyNear(norm, gfn, 1e-4)) << c.Name;
      ++magnitudes;
    }
  }
  EXPECT_GT(directions, 100) << c.Name;
  if (c.InRange)
  {
    EXPECT_GT(magnitudes, 20) << c.Name;
  }
}

TEST_P(FieldConformance, RootsBracketASignChange)
{
  const FieldCase& c = this->Field();
  Random random(5);
  const double tolerance = 1e-9 * c.Scale;
  int refined = 0, first = 0;
  for (int n = 0; n < 3000 && refined + first < 200; ++n)
  {
    const Point a = InRegion(random, c.Region);
    Point b = a;
    b[n % 3] += c.Scale * 0.05;
    const double va = c.Field->Evaluate(a.data()), vb = c.Field->Evaluate(b.data());
    const auto at = [&](double s)
    {
      const double q[3] = { a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]),
        a[2] + s * (b[2] - a[2]) };
      return c.Field->Evaluate(q);
    };
    const double length = c.Scale * 0.05;
    const double slack = 4.0 * tolerance / length;
    if (Sign(va) * Sign(vb) < 0)
    {
      pisurf::Field::EdgeVertex vertex;
      if (c.Field->RefineEdge(a.data(), b.data(), va, vb, -1, tolerance, vertex))
      {
        ASSERT_GE(vertex.S, 0.0);
        ASSERT_LE(vertex.S, 1.0);
        const double lo = std::max(0.0, vertex.S - slack), hi = std::min(1.0, vertex.S + slack);
        ASSERT_LE(Sign(at(lo)) * Sign(at(hi)), 0) << c.Name << ": no sign change at S";
        ++refined;
      }
    }
    if (va > 0)
    {
      double s = 0.0;
      if (c.Field->FirstRoot(a.data(), b.data(), tolerance, s))
      {
        for (int i = 0; i <= 64; ++i)
        {
          const double before = (s - slack) * i / 64.0;
          if (before > 0)
          {
            ASSERT_GT(at(before), 0.0) << c.Name << ": F <= 0 before FirstRoot";
          }
        }
        ASSERT_LE(Sign(at(std::max(0.0, s - slack))) * Sign(at(std::min(1.0, s + slack))), 0)
          << c.Name << ": no sign change at FirstRoot";
        ++first;
      }
    }
  }
  // Fields that answer neither keep the defaults, which say false: nothing to check.
  SUCCEED() << refined << " edges refined, " << first << " first roots";
}

TEST_P(FieldConformance, OctantClassificationIsNeverWrong)
{
  const FieldCase& c = this->Field();
  Random random(6);
  int decidedOctants = 0;
  for (int n = 0; n < 200; ++n)
  {
    double box[6];
    RandomCube(random, c, 0.005, box);
    for (const bool all : { false, true })
    {
      int octants[8];
      const int sign = c.Field->ClassifyBoxAndOctants(box, octants, all);
      if (sign != 0)
      {
        ASSERT_TRUE(SignHoldsOn(c, box, sign)) << c.Name << ": box " << n;
        continue;
      }
      for (int o = 0; o < 8; ++o)
      {
        if (octants[o] == 0)
        {
          if (!all)
          {
            break; // the octants after the first undecided one are not asked for
          }
          continue;
        }
        double sub[6];
        pisurf::OctantBox(box, o, sub);
        ASSERT_TRUE(SignHoldsOn(c, sub, octants[o])) << c.Name << ": box " << n << " octant " << o;
        ++decidedOctants;
      }
    }
  }
  EXPECT_GT(decidedOctants, 10) << c.Name << ": some octants of undecided boxes are decided";
}

TEST_P(FieldConformance, SignAndLogAgreeWithTheValue)
{
  const FieldCase& c = this->Field();
  Random random(7);
  int compared = 0;
  for (int n = 0; n < 3000; ++n)
  {
    const Point p = InRegion(random, c.Region);
    const double f = c.Field->Evaluate(p.data());
    double logAbs;
    const int sign = c.Field->EvaluateSignAndLog(p.data(), logAbs);
    ASSERT_EQ(sign, Sign(f)) << c.Name << " at " << p[0] << " " << p[1] << " " << p[2];
    ASSERT_FALSE(std::isnan(logAbs)) << c.Name;
    if (std::fabs(f) > 1e-300 && std::fabs(f) < 1e300)
    {
      ASSERT_NEAR(logAbs, std::log(std::fabs(f)), 1e-9 * std::max(1.0, std::fabs(logAbs)))
        << c.Name;
      ++compared;
    }
  }
  if (c.InRange)
  {
    EXPECT_GT(compared, 100) << c.Name;
  }
}

TEST_P(FieldConformance, CastRayFindsEverySignChange)
{
  const FieldCase& c = this->Field();
  Random random(8);
  pisurf::RayRootOptions options;
  options.Tolerance = 1e-9;
  options.AllRoots = true;
  std::vector<pisurf::RayRoot> roots;
  int changes = 0;
  for (int n = 0; n < 40; ++n)
  {
    // A ray across the region: from a point on one face to a point on the opposite one.
    const int axis = n % 3;
    Point o = InRegion(random, c.Region), e = InRegion(random, c.Region);
    o[axis] = c.Region[2 * axis];
    e[axis] = c.Region[2 * axis + 1];
    const double d[3] = { e[0] - o[0], e[1] - o[1], e[2] - o[2] };
    c.Field->CastRay(o.data(), d, 0.0, 1.0, options, roots);
    for (size_t r = 0; r < roots.size(); ++r)
    {
      ASSERT_GE(roots[r].T, -options.Tolerance) << c.Name;
      ASSERT_LE(roots[r].T, 1.0 + options.Tolerance) << c.Name;
      if (r > 0)
      {
        ASSERT_GE(roots[r].T, roots[r - 1].T) << c.Name << ": roots out of order";
      }
    }
    const int samples = 1024;
    auto negative = [&](int i)
    {
      const double t = double(i) / samples;
      const double q[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
      return c.Field->Evaluate(q) < 0;
    };
    bool before = negative(0);
    for (int i = 1; i <= samples; ++i)
    {
      const bool now = negative(i);
      if (now != before)
      {
        ++changes;
        const double lo = double(i - 1) / samples - options.Tolerance,
                     hi = double(i) / samples + options.Tolerance;
        bool found = false;
        for (const pisurf::RayRoot& root : roots)
        {
          found = found || (root.T >= lo && root.T <= hi);
        }
        ASSERT_TRUE(found) << c.Name << ": ray " << n << " changes sign in [" << lo << ", " << hi
                           << "] but CastRay gives no root there";
      }
      before = now;
    }
  }
  EXPECT_GT(changes, 5) << c.Name << ": the rays cross the surface";
}

TEST_P(FieldConformance, ProbeVertexTellsRegularFromSingular)
{
  const FieldCase& c = this->Field();
  Random random(9);
  const double probe = 1e-3 * c.Scale;
  int regular = 0, near = 0;
  for (int n = 0; n < 500; ++n)
  {
    const Point p = InRegion(random, c.Region);
    double normal[3], norm, reference[3], referenceNorm;
    int nearest, referenceNearest;
    const bool singular = c.Field->ProbeVertex(p.data(), probe, 0.1, normal, norm, nearest);
    c.Field->EvaluateVertex(p.data(), reference, referenceNorm, referenceNearest);
    ASSERT_EQ(nearest, referenceNearest) << c.Name;
    ASSERT_TRUE(pisurf_test::RelativelyNear(norm, referenceNorm, 1e-9)) << c.Name;
    for (int k = 0; k < 3; ++k)
    {
      ASSERT_NEAR(normal[k], reference[k], 1e-9) << c.Name;
    }
    // Where F is moderate and |∇F|·probe dominates F's values at the probes, the point
    // is regular.
    const double f = std::fabs(c.Field->Evaluate(p.data()));
    if (norm > 0 && norm < 1e300 && f < 0.1 * norm * probe)
    {
      // |F| at the probes is at most |F(p)| + |∇F|·probe + O(probe²): the test
      // |∇F|·probe <= 0.1·max|F(probes)| fails unless the curvature term dominates.
      regular += singular ? 0 : 1;
      ++near;
    }
  }
  EXPECT_GE(2 * regular, near) << c.Name << ": most points near the surface are regular";
}

INSTANTIATE_TEST_SUITE_P(EveryField, FieldConformance, ::testing::ValuesIn(FieldNames()),
  [](const ::testing::TestParamInfo<std::string>& info)
  {
    std::string name = info.param;
    for (char& ch : name)
    {
      if (!std::isalnum(static_cast<unsigned char>(ch)))
      {
        ch = '_';
      }
    }
    return name;
  });
}
