// SPDX-License-Identifier: BSD-3-Clause
#include "PiProductField.h"

#include "PiFloat.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace pisurf
{

ProductField::ProductField(std::shared_ptr<const ProductKernel> kernel)
  : Kernel(std::move(kernel))
{
  if (!this->Kernel)
  {
    throw std::invalid_argument("ProductField needs a kernel");
  }
}

int ProductField::ClassifyBox(const double box[6]) const
{
  return this->Kernel->ClassifyBox(box);
}

double ProductField::Evaluate(const double p[3]) const
{
  return this->Kernel->Evaluate(p);
}

double ProductField::EvaluateCompressed(const double p[3]) const
{
  return this->Kernel->EvaluateCompressed(p);
}

void ProductField::EvaluateVertex(
  const double p[3], double normal[3], double& gradientNorm, int& nearest) const
{
  this->Kernel->EvaluateVertex(p, normal, gradientNorm, nearest);
}

int ProductField::ClassifyBoxAndOctants(const double box[6], int octants[8], bool allOctants) const
{
  return this->Kernel->ClassifyBoxAndOctants(box, octants, allOctants);
}

int ProductField::EvaluateSignAndLog(const double p[3], double& logAbs) const
{
  return this->Kernel->EvaluateSignAndLog(p, logAbs);
}

// Whether |∇F|·probe is at most `tolerance` times the largest of the six probe values
// |F| = |mantissa|·2^exponent. The largest |F| is found on the scaled values (exponent
// first, then mantissa: the same order as their magnitudes). Where |∇F| (`gradient`),
// that largest value and both products are normal doubles they are compared directly;
// otherwise in logarithms (no overflow).
static bool ProbesSayZeroGradient(double gradient, double logGradient, double probe,
  double tolerance, const double* mantissa, const long* exponent)
{
  double bestMantissa = 0.0;
  long bestExponent = 0;
  for (int a = 0; a < 6; ++a)
  {
    const double m = mantissa[a];
    const long e = exponent[a];
    if (m != 0.0 &&
      (bestMantissa == 0.0 || e > bestExponent ||
        (e == bestExponent && std::fabs(m) > bestMantissa)))
    {
      bestMantissa = std::fabs(m);
      bestExponent = e;
    }
  }
  if (bestMantissa != 0.0 && bestExponent > -900 && bestExponent < 900 && std::isnormal(gradient))
  {
    const double lhs = gradient * probe;
    const double rhs = tolerance * pisurf::Ldexp(bestMantissa, static_cast<int>(bestExponent));
    if (std::isnormal(lhs) && std::isnormal(rhs))
    {
      return lhs <= rhs;
    }
  }
  const double logProbe = bestMantissa == 0.0
    ? -std::numeric_limits<double>::infinity()
    : std::log(bestMantissa) + static_cast<double>(bestExponent) * std::log(2.0);
  return logGradient + std::log(probe) <= std::log(tolerance) + logProbe;
}

bool ProductField::ProbeVertex(const double p[3], double probe, double tolerance, double normal[3],
  double& gradientNorm, int& nearest) const
{
  double logGradient, mantissa[6];
  long exponent[6];
  this->Kernel->EvaluateVertexStar(
    p, probe, normal, gradientNorm, nearest, logGradient, mantissa, exponent);
  return ProbesSayZeroGradient(gradientNorm, logGradient, probe, tolerance, mantissa, exponent);
}
}
