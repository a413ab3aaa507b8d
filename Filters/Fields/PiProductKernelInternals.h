// SPDX-License-Identifier: BSD-3-Clause
// What the files of ProductKernel share: the scaled-product arithmetic and the four-lane
// vector types. Internal to PiProductKernel*.cxx.
#ifndef PiProductKernelInternals_h
#define PiProductKernelInternals_h

#include "PiFloat.h"
#include "PiProductKernel.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace pisurf
{
namespace
{
constexpr double Big = 0x1p256;
constexpr double Small = 0x1p-256;
constexpr int BlockSize = 128;

inline double Clamp(double v)
{
  if (v > DBL_MAX)
  {
    return DBL_MAX;
  }
  if (v < -DBL_MAX)
  {
    return -DBL_MAX;
  }
  return v;
}

// ldexp that saturates at ±DBL_MAX instead of returning ±inf.
inline double SafeLdexp(double m, long e)
{
  if (m == 0.0)
  {
    return 0.0;
  }
  int ex;
  pisurf::Frexp(m, &ex);
  if (e + ex > DBL_MAX_EXP)
  {
    return m > 0 ? DBL_MAX : -DBL_MAX;
  }
  if (e + ex < DBL_MIN_EXP - DBL_MANT_DIG - 1)
  {
    return 0.0;
  }
  return pisurf::Ldexp(m, static_cast<int>(e));
}

// Product P and gradient G of the factors with a shared exponent e.
struct ScaledProduct
{
  double P = 1.0;
  double G[3] = { 0, 0, 0 };
  long E = 0;

  void Multiply(double f, const double gIn[3])
  {
    // Bring a huge or tiny factor (and its gradient) near 1 first, so that the
    // products below can neither overflow nor underflow.
    double g[3] = { gIn[0], gIn[1], gIn[2] };
    const double a = std::max({ std::fabs(f), std::fabs(g[0]), std::fabs(g[1]), std::fabs(g[2]) });
    if ((a > Big || a < Small) && a != 0.0 && std::isfinite(a))
    {
      int ex;
      pisurf::Frexp(a, &ex);
      f = pisurf::Ldexp(f, -ex);
      for (double& gk : g)
      {
        gk = pisurf::Ldexp(gk, -ex);
      }
      this->E += ex;
    }
    for (int k = 0; k < 3; ++k)
    {
      this->G[k] = this->G[k] * f + this->P * g[k];
    }
    this->P *= f;
    this->Normalize();
  }

  void Normalize()
  {
    const double a = std::max(
      { std::fabs(this->P), std::fabs(this->G[0]), std::fabs(this->G[1]), std::fabs(this->G[2]) });
    if ((a > Big || a < Small) && a != 0.0 && std::isfinite(a))
    {
      int ex;
      pisurf::Frexp(a, &ex);
      this->P = pisurf::Ldexp(this->P, -ex);
      for (double& gk : this->G)
      {
        gk = pisurf::Ldexp(gk, -ex);
      }
      this->E += ex;
    }
  }
};
}

namespace
{
typedef double V4 __attribute__((vector_size(32)));
typedef long long I4 __attribute__((vector_size(32)));
// Four doubles in memory aligned to 8 bytes only (no functions taking or returning V4:
// their ABI depends on whether AVX is enabled).
typedef double V4Unaligned __attribute__((vector_size(32), aligned(8), may_alias));
}
#define PISURF_LOAD4(p) (*reinterpret_cast<const V4Unaligned*>(p))
// |v| of each lane (std::fabs: the sign bit cleared).
#define PISURF_ABS4(v) ((V4)((I4)(v) & (I4{ 0, 0, 0, 0 } + 0x7fffffffffffffffLL)))
#define PISURF_STORE4(p, v) (*reinterpret_cast<V4Unaligned*>(p) = (v))

namespace
{
// Quadrics k0..k0 + 3 from ProductKernel's packed rows: each axis's scale A_aa and
// shift B_a, and the ten coefficients.
inline void LoadQuadricGroup(
  const double* rows, size_t stride, size_t k0, V4* scale, V4* shift, V4* q)
{
  for (int a = 0; a < 3; ++a)
  {
    scale[a] = PISURF_LOAD4(rows + a * stride + k0);
    shift[a] = PISURF_LOAD4(rows + (3 + a) * stride + k0);
  }
  for (int m = 0; m < 10; ++m)
  {
    q[m] = PISURF_LOAD4(rows + (6 + m) * stride + k0);
  }
}

// Such a group restricted to the line through p along Axis (QuadricOnAxisOf on the two
// other local coordinates).
template <int Axis>
inline void QuadricGroupOnAxis(
  const V4* scale, const V4* shift, const V4* q, const double p[3], V4& c0, V4& c1, V4& c2)
{
  constexpr int u = (Axis + 1) % 3, w = (Axis + 2) % 3;
  const V4 qu = scale[u] * p[u] + shift[u], qw = scale[w] * p[w] + shift[w];
  QuadricOnAxisOf(q, qu, qw, Axis, c0, c1, c2);
}
}

inline void ProductKernel::Accumulate(double& m, long& e, double f)
{
  const double af = std::fabs(f);
  if ((af > Big || af < Small) && af != 0.0 && std::isfinite(af))
  {
    int ex;
    f = pisurf::Frexp(f, &ex);
    e += ex;
  }
  m *= f;
  const double a = std::fabs(m);
  if ((a > Big || a < Small) && a != 0.0)
  {
    int ex;
    m = pisurf::Frexp(m, &ex);
    e += ex;
  }
}

// F = m·2^e − r as mantissa·2^exponent (mantissa in ±[0.5, 1) or 0), exact up to one
// rounding: both terms are brought to the larger of the two scales first.
inline void ScaledMinus(double m, long e, double r, double& mantissa, long& exponent)
{
  int ex;
  if (m == 0.0)
  {
    mantissa = pisurf::Frexp(-r, &ex);
    exponent = r == 0.0 ? 0 : ex;
    return;
  }
  m = pisurf::Frexp(m, &ex);
  e += ex;
  long top = e;
  if (r != 0.0)
  {
    int er;
    pisurf::Frexp(r, &er);
    top = std::max<long>(e, er);
  }
  const double shift = e - top < -2100 ? 0.0 : pisurf::Ldexp(m, static_cast<int>(e - top));
  const double F = shift - (r == 0.0 ? 0.0 : pisurf::Ldexp(r, static_cast<int>(-top)));
  mantissa = pisurf::Frexp(F, &ex);
  exponent = F == 0.0 ? 0 : top + ex;
}

// The scaled product and its gradient at p, factor by factor.
inline ScaledProduct ProductAndGradient(const std::vector<Factor>& factors, const double p[3])
{
  ScaledProduct s;
  double gi[3];
  for (const Factor& f : factors)
  {
    const double fi = f.EvaluateWithGradient(p, gi);
    s.Multiply(fi, gi);
  }
  return s;
}
// F = m·2^e − r as mantissa·2^exponent, the end of EvaluateScaled.
inline void FinishScaled(double m, long e, double r, double& mantissa, long& exponent)
{
  // The common case (the product never left ±2^256, |r| in [2^-400, 2^400] or 0):
  // m − r directly. ScaledMinus would scale both terms by the same power of two first,
  // keeping them normal numbers there, which changes neither the rounding nor the result.
  const double am = std::fabs(m), ar = std::fabs(r);
  if (e == 0 && (am == 0.0 || (am >= 0x1p-400 && am <= 0x1p400)) &&
    (ar == 0.0 || (ar >= 0x1p-400 && ar <= 0x1p400)))
  {
    int ex;
    const double F = m - r;
    mantissa = pisurf::Frexp(F, &ex);
    exponent = F == 0.0 ? 0 : ex;
    return;
  }
  ScaledMinus(m, e, r, mantissa, exponent);
}
}

#endif
