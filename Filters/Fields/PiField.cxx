// SPDX-License-Identifier: BSD-3-Clause
#include "PiField.h"

#include "PiPolynomial.h"

#include <algorithm>
#include <cmath>

namespace pisurf
{

int Field::ClassifyBoxAndOctants(const double box[6], int octants[8], bool allOctants) const
{
  const int sign = this->ClassifyBox(box);
  if (sign != 0)
  {
    return sign;
  }
  for (int o = 0; o < 8; ++o)
  {
    double sub[6];
    OctantBox(box, o, sub);
    octants[o] = this->ClassifyBox(sub);
    if (octants[o] == 0 && !allOctants)
    {
      std::fill(octants + o + 1, octants + 8, 0);
      break;
    }
  }
  return 0;
}

int Field::EvaluateSignAndLog(const double p[3], double& logAbs) const
{
  const double f = this->Evaluate(p);
  logAbs = std::log(std::fabs(f));
  return f > 0 ? 1 : f < 0 ? -1 : 0;
}

void Field::CastRay(const double o[3], const double d[3], double t0, double t1,
  const RayRootOptions& options, std::vector<RayRoot>& roots) const
{
  roots.clear();
  const int n = 4096;
  auto at = [&](double t)
  {
    const double p[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
    return this->EvaluateCompressed(p);
  };
  double ta = t0, va = at(t0);
  for (int s = 1; s <= n && (options.AllRoots || roots.empty()); ++s)
  {
    const double tb = t0 + (t1 - t0) * s / n, vb = at(tb);
    if ((va < 0) != (vb < 0))
    {
      roots.push_back({ BracketedRoot(at, ta, tb, va, vb, options.Tolerance, 0.0), false });
    }
    ta = tb;
    va = vb;
  }
}

bool Field::ProbeVertex(const double p[3], double probe, double tolerance, double normal[3],
  double& gradientNorm, int& nearest) const
{
  this->EvaluateVertex(p, normal, gradientNorm, nearest);
  const double logProbe = LargestLogAtProbes(p, probe,
    [this](const double* q)
    {
      double logAbs;
      this->EvaluateSignAndLog(q, logAbs);
      return logAbs;
    });
  return std::log(gradientNorm) + std::log(probe) <= std::log(tolerance) + logProbe;
}
}
