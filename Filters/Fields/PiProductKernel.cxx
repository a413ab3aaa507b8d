// SPDX-License-Identifier: BSD-3-Clause
// ProductKernel: construction and evaluation at points (value, gradient, distance,
// compressed, scaled, sign and logarithm, batches of points and lines).
#include "PiProductKernelInternals.h"

namespace pisurf
{
ProductKernel::ProductKernel(std::vector<Factor> factors, double blending)
  : Factors(std::move(factors))
  , Blending(blending)
{
  this->PlainBound = pisurf::Ldexp(
    1.0, std::min(256, 1000 / std::max<int>(1, static_cast<int>(this->Factors.size()))));
  this->AllPolynomial = std::all_of(
    this->Factors.begin(), this->Factors.end(), [](const Factor& f) { return f.IsPolynomial; });
  this->StarQuadric.assign(this->Factors.size(), 0);
  this->StarEvenQuartic.assign(this->Factors.size(), 0);
  this->StarFactorsOnly =
    this->AllPolynomial && !this->Factors.empty() && this->Factors.size() <= MaxPlainVertex;
  for (size_t k = 0; k < this->Factors.size(); ++k)
  {
    Factor& f = this->Factors[k];
    if (f.IsPolynomial)
    {
      f.Polynomial.PrepareIntervals();
      this->LineCoefficients += static_cast<size_t>(std::max(f.Polynomial.Poly.GetDegree(), 0)) + 1;
      // (PrepareIntervals sets Diagonal)
      this->StarQuadric[k] = f.Polynomial.Poly.IsQuadric() && f.Polynomial.Diagonal;
      this->StarEvenQuartic[k] = f.Polynomial.Poly.IsEvenQuartic() && f.Polynomial.Diagonal;
      this->StarFactorsOnly =
        this->StarFactorsOnly && (this->StarQuadric[k] || this->StarEvenQuartic[k]);
    }
  }
  this->PackQuadrics();
}

void ProductKernel::PackQuadrics()
{
  this->QuadricRows.clear();
  this->QuadricStride = 0;
  const size_t count = this->Factors.size();
  if (count == 0 || count > MaxPlainVertex || !this->AllPolynomial)
  {
    return;
  }
  for (size_t k = 0; k < count; ++k)
  {
    if (!this->StarQuadric[k] || this->Factors[k].Polynomial.Poly.GetDegree() != 2)
    {
      return;
    }
  }
  const size_t stride = (count + 3) / 4 * 4;
  this->QuadricRows.assign(16 * stride, 0.0);
  for (size_t k = 0; k < stride; ++k)
  {
    const PolynomialFactor& pf = this->Factors[std::min(k, count - 1)].Polynomial;
    double* column = this->QuadricRows.data() + k;
    for (int a = 0; a < 3; ++a)
    {
      column[a * stride] = pf.A[a][a];
      column[(3 + a) * stride] = pf.B[a];
    }
    for (int m = 0; m < 10; ++m)
    {
      column[(6 + m) * stride] = pf.Poly.GetQuadric()[m];
    }
  }
  this->QuadricStride = stride;
}

double ProductKernel::Finish(double m, long e) const
{
  if (e == 0)
  {
    return Clamp(m - this->Blending); // the common case: the product never left ±2^256
  }
  if (m == 0.0)
  {
    return -this->Blending;
  }
  int ex;
  pisurf::Frexp(m, &ex);
  if (std::labs(e + ex) < 960)
  {
    return Clamp(pisurf::Ldexp(m, static_cast<int>(e)) - this->Blending);
  }
  // Far from the double range: subtract r at a common scale, then clamp.
  double fm;
  long fe;
  ScaledMinus(m, e, this->Blending, fm, fe);
  if (fm == 0.0)
  {
    return 0.0;
  }
  const double F = SafeLdexp(fm, fe);
  return F == 0.0 ? std::copysign(std::numeric_limits<double>::denorm_min(), fm) : F;
}

double ProductKernel::Evaluate(const double p[3]) const
{
  double m = 1.0;
  long e = 0;
  for (const Factor& f : this->Factors)
  {
    Accumulate(m, e, f.Evaluate(p));
  }
  return this->Finish(m, e);
}

double ProductKernel::EvaluateWithGradient(const double p[3], double g[3]) const
{
  const ScaledProduct s = ProductAndGradient(this->Factors, p);
  for (int k = 0; k < 3; ++k)
  {
    g[k] = SafeLdexp(s.G[k], s.E);
  }
  return this->Finish(s.P, s.E);
}

double ProductKernel::EvaluateDistance(const double p[3], double normal[3]) const
{
  const ScaledProduct s = ProductAndGradient(this->Factors, p);
  // F·2^-E = P − r·2^-E and ∇F·2^-E = G: the common scale cancels in the ratio.
  const double Fs = s.P - (this->Blending == 0.0 ? 0.0 : SafeLdexp(this->Blending, -s.E));
  const double gn = std::sqrt(s.G[0] * s.G[0] + s.G[1] * s.G[1] + s.G[2] * s.G[2]);
  if (!(gn > 0.0) || !std::isfinite(gn))
  {
    normal[0] = normal[1] = normal[2] = 0.0;
    return Fs == 0.0 ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(), Fs);
  }
  for (int k = 0; k < 3; ++k)
  {
    normal[k] = s.G[k] / gn;
  }
  return Fs / gn;
}

double ProductKernel::EvaluateCompressed(const double p[3]) const
{
  double m = 1.0;
  long e = 0;
  for (const Factor& f : this->Factors)
  {
    Accumulate(m, e, f.Evaluate(p));
  }
  int ex;
  if (m != 0.0)
  {
    pisurf::Frexp(m, &ex);
    if (std::labs(e + ex) < 960)
    {
      const double F = pisurf::Ldexp(m, static_cast<int>(e)) - this->Blending;
      return std::copysign(std::log1p(std::fabs(F)), F);
    }
  }
  double fm;
  long fe;
  ScaledMinus(m, e, this->Blending, fm, fe);
  if (fm == 0.0)
  {
    return 0.0;
  }
  // ln(1 + |F|) = ln|F| + ln(1 + 1/|F|); beyond the double range the second term is 0.
  const double logAbs = std::log(std::fabs(fm)) + static_cast<double>(fe) * std::log(2.0);
  const double value = logAbs > 700 ? logAbs : std::log1p(std::exp(logAbs));
  return std::copysign(value, fm);
}

void ProductKernel::EvaluateScaled(const double p[3], double& mantissa, long& exponent) const
{
  double m = 1.0;
  long e = 0;
  for (const Factor& f : this->Factors)
  {
    Accumulate(m, e, f.Evaluate(p));
  }
  FinishScaled(m, e, this->Blending, mantissa, exponent);
}

int ProductKernel::EvaluateSignAndLog(const double p[3], double& logAbs) const
{
  double m;
  long e;
  this->EvaluateScaled(p, m, e);
  if (m == 0.0)
  {
    logAbs = -std::numeric_limits<double>::infinity();
    return 0;
  }
  logAbs = std::log(std::fabs(m)) + static_cast<double>(e) * std::log(2.0);
  return m > 0 ? 1 : -1;
}

void ProductKernel::EvaluatePoints(const double* xyz, size_t n, double* values) const
{
  double m[BlockSize], f[BlockSize];
  long e[BlockSize];
  for (size_t start = 0; start < n; start += BlockSize)
  {
    const int count = static_cast<int>(std::min<size_t>(BlockSize, n - start));
    const double* pts = xyz + 3 * start;
    std::fill(m, m + count, 1.0);
    std::fill(e, e + count, 0L);
    for (const Factor& factor : this->Factors)
    {
      if (factor.IsPolynomial)
      {
        const PolynomialFactor& pf = factor.Polynomial;
        for (int i = 0; i < count; ++i)
        {
          f[i] = pf.Evaluate(pts + 3 * i);
        }
      }
      else
      {
        for (int i = 0; i < count; ++i)
        {
          f[i] = factor.Generic(pts + 3 * i, nullptr);
        }
      }
      for (int i = 0; i < count; ++i)
      {
        Accumulate(m[i], e[i], f[i]);
      }
    }
    for (int i = 0; i < count; ++i)
    {
      values[start + i] = this->Finish(m[i], e[i]);
    }
  }
}

void ProductKernel::EvaluateLine(
  const double origin[3], const double step[3], int n, double* values) const
{
  if (n <= 0)
  {
    return;
  }
  // Restrict about the middle of the row: smaller |t| keeps Horner's rule accurate.
  const double mid = 0.5 * (n - 1);
  const double o[3] = { origin[0] + mid * step[0], origin[1] + mid * step[1],
    origin[2] + mid * step[2] };
  thread_local std::vector<double> coefficients;
  coefficients.resize(this->LineCoefficients);
  this->RestrictLine(o, step, coefficients.data());
  this->EvaluateRestrictedRow(coefficients.data(), -mid, n, origin, step, values);
}

int ProductKernel::NearestFactor(const double p[3]) const
{
  double normal[3], gradientNorm;
  int nearest;
  this->EvaluateVertex(p, normal, gradientNorm, nearest);
  return nearest;
}

}
