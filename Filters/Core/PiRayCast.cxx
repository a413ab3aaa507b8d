// SPDX-License-Identifier: BSD-3-Clause
#include "PiRayCast.h"

#include "PiProduct.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pisurf
{

RayCaster::RayCaster(const ProductKernel& kernel)
  : Kernel(kernel)
{
  for (size_t f = 0; f < kernel.GetNumberOfFactors(); ++f)
  {
    const Factor& factor = kernel.GetFactor(f);
    if (factor.IsPolynomial)
    {
      this->Counts.push_back(std::max(factor.Polynomial.Poly.GetDegree(), 0) + 1);
    }
  }
}

void RayCaster::Cast(const double start[3], const double d[3], double length,
  const RayRootOptions& options, std::vector<RayRoot>& roots) const
{
  roots.clear();
  if (this->Kernel.IsPolynomial())
  {
    thread_local std::vector<double> coefficients;
    coefficients.resize(this->Kernel.GetLineCoefficientCount());
    this->Kernel.RestrictLine(start, d, coefficients.data());
    FindRayRoots(coefficients.data(), this->Counts.data(), static_cast<int>(this->Counts.size()),
      this->Kernel.GetBlending(), 0.0, length, options, roots);
    return;
  }
  // The documented fallback for non-polynomial factors: a sign scan and bisection.
  const int n = 4096;
  auto at = [&](double t) {
    const double p[3] = { start[0] + t * d[0], start[1] + t * d[1], start[2] + t * d[2] };
    return this->Kernel.EvaluateCompressed(p);
  };
  double ta = 0.0, va = at(0.0);
  for (int s = 1; s <= n && (options.AllRoots || roots.empty()); ++s)
  {
    const double tb = length * s / n, vb = at(tb);
    if ((va < 0) != (vb < 0))
    {
      roots.push_back({ BracketedRoot(at, ta, tb, va, vb, options.Tolerance, 0.0), false });
    }
    ta = tb;
    va = vb;
  }
}

bool RayCaster::IsSingular(
  const double p[3], double logGradient, double probe, double tolerance) const
{
  // Compare |∇F|·h with the largest |F| at p ± h·e_i, in logarithms (no overflow).
  double logProbe = -std::numeric_limits<double>::infinity();
  for (int a = 0; a < 6; ++a)
  {
    double q[3] = { p[0], p[1], p[2] };
    q[a / 2] += (a % 2 ? probe : -probe);
    double logAbs;
    if (this->Kernel.EvaluateSignAndLog(q, logAbs) != 0)
    {
      logProbe = std::max(logProbe, logAbs);
    }
  }
  return logGradient + std::log(probe) <= std::log(tolerance) + logProbe;
}
}
