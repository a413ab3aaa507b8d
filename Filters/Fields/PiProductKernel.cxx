// SPDX-License-Identifier: BSD-3-Clause
#include "PiProductKernel.h"
#include "PiFloat.h"

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

double Clamp(double v)
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
double SafeLdexp(double m, long e)
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
    const double a = std::max({ std::fabs(this->P), std::fabs(this->G[0]), std::fabs(this->G[1]),
      std::fabs(this->G[2]) });
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
  this->StarFactorsOnly = this->AllPolynomial && !this->Factors.empty() &&
    this->Factors.size() <= MaxPlainVertex;
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
inline void QuadricGroupOnAxis(const V4* scale, const V4* shift, const V4* q, const double p[3],
  V4& c0, V4& c1, V4& c2)
{
  constexpr int u = (Axis + 1) % 3, w = (Axis + 2) % 3;
  const V4 qu = scale[u] * p[u] + shift[u], qw = scale[w] * p[w] + shift[w];
  QuadricOnAxisOf(q, qu, qw, Axis, c0, c1, c2);
}
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

void ProductKernel::RestrictLine(const double o[3], const double d[3], double* coefficients) const
{
  for (const Factor& f : this->Factors)
  {
    if (f.IsPolynomial)
    {
      f.Polynomial.RestrictToLine(o, d, coefficients);
      coefficients += std::max(f.Polynomial.Poly.GetDegree(), 0) + 1;
    }
  }
}

double ProductKernel::EvaluateRestricted(const double* coefficients, double t, const double p[3]) const
{
  double m = 1.0;
  long e = 0;
  for (const Factor& f : this->Factors)
  {
    if (f.IsPolynomial)
    {
      const int n = std::max(f.Polynomial.Poly.GetDegree(), 0) + 1;
      Accumulate(m, e, EvaluateUnivariate(coefficients, n, t));
      coefficients += n;
    }
    else
    {
      Accumulate(m, e, f.Generic(p, nullptr));
    }
  }
  return this->Finish(m, e);
}

PISURF_AVX2_CLONES
bool ProductKernel::RestrictToAxis(const double p[3], int axis, double* coefficients) const
{
  if (!this->AllPolynomial)
  {
    return false;
  }
  if (this->QuadricStride > 0)
  {
    // Four quadrics at a time: QuadricOnAxis's operations (its zeros beyond the axis
    // degree are the +0 these sums of +0 coefficients give).
    const size_t stride = this->QuadricStride, count = this->Factors.size();
    const double* rows = this->QuadricRows.data();
    for (size_t k0 = 0; k0 < stride; k0 += 4)
    {
      V4 scale[3], shift[3], q[10];
      LoadQuadricGroup(rows, stride, k0, scale, shift, q);
      V4 c0, c1, c2;
      // (A literal axis makes every index a constant: the group stays in registers.)
      switch (axis)
      {
        case 0: QuadricGroupOnAxis<0>(scale, shift, q, p, c0, c1, c2); break;
        case 1: QuadricGroupOnAxis<1>(scale, shift, q, p, c0, c1, c2); break;
        default: QuadricGroupOnAxis<2>(scale, shift, q, p, c0, c1, c2); break;
      }
      for (size_t l = 0; l < 4 && k0 + l < count; ++l)
      {
        double* out = coefficients + 3 * (k0 + l);
        out[0] = c0[l];
        out[1] = c1[l];
        out[2] = c2[l];
      }
    }
    return true;
  }
  for (const Factor& f : this->Factors)
  {
    const PolynomialFactor& pf = f.Polynomial;
    if (!pf.Diagonal)
    {
      return false;
    }
    const int n = std::max(pf.Poly.GetDegree(), 0) + 1;
    double q[3];
    pf.ToLocalDiagonal(p, q);
    // The axis degree may be below the degree: the rest are zeros.
    const int axisDegree = pf.Poly.GetAxisDegree(axis);
    for (int m = axisDegree + 1; m < n; ++m)
    {
      coefficients[m] = 0.0;
    }
    if (this->StarQuadric[&f - this->Factors.data()] && n > 1)
    {
      QuadricOnAxis(pf.Poly.GetQuadric(), q, axis, axisDegree, coefficients); // inline
    }
    else
    {
      pf.Poly.RestrictToAxis(q, axis, coefficients);
    }
    coefficients += n;
  }
  return true;
}

double ProductKernel::EvaluateOnAxis(const double* coefficients, int axis, double x) const
{
  // Plain doubles while every factor is 0 or within 2^±B, B = min(256, 1000 / factors)
  // (no partial product leaves the normal range, so the same bits as the scaled product
  // below, as in EvaluateRestrictedRow).
  const double bound = this->PlainBound, inverse = 1.0 / bound;
  double product = 1.0, hi = 0.0, lo = bound;
  const double* c = coefficients;
  for (const Factor& f : this->Factors)
  {
    const PolynomialFactor& pf = f.Polynomial;
    const int n = std::max(pf.Poly.GetDegree(), 0) + 1;
    const double v = EvaluateUnivariate(c, n, pf.A[axis][axis] * x + pf.B[axis]);
    product *= v;
    const double a = std::fabs(v);
    hi = std::max(hi, a);
    lo = std::min(lo, a == 0.0 ? bound : a);
    c += n;
  }
  if (hi <= bound && lo >= inverse && std::isfinite(product))
  {
    return Clamp(product - this->Blending);
  }
  double m = 1.0;
  long e = 0;
  for (const Factor& f : this->Factors)
  {
    const PolynomialFactor& pf = f.Polynomial;
    const int n = std::max(pf.Poly.GetDegree(), 0) + 1;
    const double u = pf.A[axis][axis] * x + pf.B[axis];
    Accumulate(m, e, EvaluateUnivariate(coefficients, n, u));
    coefficients += n;
  }
  return this->Finish(m, e);
}

void ProductKernel::EvaluateOnAxisLog(const double* coefficients, int axis, double x,
  double& value, int& productSign, double& logProduct, double& logSlope) const
{
  double m = 1.0, slope = 0.0;
  long e = 0;
  bool zero = false;
  for (const Factor& f : this->Factors)
  {
    const PolynomialFactor& pf = f.Polynomial;
    const int n = std::max(pf.Poly.GetDegree(), 0) + 1;
    const double u = pf.A[axis][axis] * x + pf.B[axis];
    double d;
    const double v = EvaluateUnivariateWithDerivative(coefficients, n, u, d);
    if (v == 0.0)
    {
      zero = true;
    }
    else
    {
      slope += d * pf.A[axis][axis] / v;
    }
    Accumulate(m, e, v);
    coefficients += n;
  }
  value = this->Finish(m, e);
  if (zero || m == 0.0)
  {
    productSign = 0;
    logProduct = -std::numeric_limits<double>::infinity();
    logSlope = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  productSign = m > 0 ? 1 : -1;
  int ex;
  const double mantissa = pisurf::Frexp(std::fabs(m), &ex);
  logProduct = std::log(mantissa) + static_cast<double>(e + ex) * 0.69314718055994530942;
  logSlope = slope;
}

// One factor of EvaluateOnAxisWithSlope / EvaluateRestrictedWithSlope: the univariate
// polynomial c (n coefficients) and its derivative at u, the derivative scaled to the
// caller's parameter by `scale`, multiplied into product and derivative (product rule);
// false where the factor is beyond `bound` or below `inverse` = 1 / bound (0 allowed).
static inline bool MultiplyWithSlope(const double* c, int n, double u, double scale,
  double bound, double inverse, double& product, double& derivative)
{
  double v, d;
  if (n == 3)
  {
    // A quadric (most factors): EvaluateUnivariateWithDerivative's operations, unrolled.
    const double v1 = c[2] * u + c[1];
    d = c[2] * u + v1;
    v = v1 * u + c[0];
  }
  else if (n == 5)
  {
    // A quartic (tori): the loop unrolled, the same operations.
    v = EvaluateUnivariateWithDerivative(c, 5, u, d);
  }
  else
  {
    v = EvaluateUnivariateWithDerivative(c, n, u, d);
  }
  const double a = std::fabs(v);
  if (a > bound || (a != 0.0 && a < inverse))
  {
    return false;
  }
  derivative = derivative * v + product * d * scale;
  product *= v;
  return true;
}

PISURF_AVX2_CLONES
bool ProductKernel::EvaluateOnAxisWithSlope(
  const double* coefficients, int axis, double x, double& value, double& slope) const
{
  const double bound = this->PlainBound, inverse = 1.0 / bound;
  double product = 1.0, derivative = 0.0;
  if (this->QuadricStride > 0)
  {
    // The loop below, with each factor's frame read from the packed rows instead of
    // its Factor.
    const size_t stride = this->QuadricStride, count = this->Factors.size();
    const double* scale = this->QuadricRows.data() + axis * stride;
    const double* shift = this->QuadricRows.data() + (3 + axis) * stride;
    for (size_t k = 0; k < count; ++k, coefficients += 3)
    {
      if (!MultiplyWithSlope(
            coefficients, 3, scale[k] * x + shift[k], scale[k], bound, inverse, product, derivative))
      {
        return false;
      }
    }
    value = product - this->Blending;
    slope = derivative;
    return std::isfinite(value) && std::isfinite(slope);
  }
  for (const Factor& f : this->Factors)
  {
    const PolynomialFactor& pf = f.Polynomial;
    const int n = std::max(pf.Poly.GetDegree(), 0) + 1;
    if (!MultiplyWithSlope(coefficients, n, pf.A[axis][axis] * x + pf.B[axis],
          pf.A[axis][axis], bound, inverse, product, derivative))
    {
      return false;
    }
    coefficients += n;
  }
  value = product - this->Blending;
  slope = derivative;
  return std::isfinite(value) && std::isfinite(slope);
}

bool ProductKernel::EvaluateRestrictedWithSlope(
  const double* coefficients, double t, double& value, double& slope) const
{
  if (!this->AllPolynomial)
  {
    return false;
  }
  const double bound = this->PlainBound, inverse = 1.0 / bound;
  double product = 1.0, derivative = 0.0;
  for (const Factor& f : this->Factors)
  {
    const int n = std::max(f.Polynomial.Poly.GetDegree(), 0) + 1;
    if (!MultiplyWithSlope(coefficients, n, t, 1.0, bound, inverse, product, derivative))
    {
      return false;
    }
    coefficients += n;
  }
  value = product - this->Blending;
  slope = derivative;
  return std::isfinite(value) && std::isfinite(slope);
}

// EvaluateRestrictedRow's Horner chains: acc[v] = Σ c[q]·t[v]^q for the group's vectors,
// T terms (T > 0: the loop unrolled, the same operations) or `terms`.
template <int T, int Vectors>
inline void HornerGroup(V4* acc, const V4* t, const double* c, int terms)
{
  const int n = T > 0 ? T : terms;
  for (int q = n - 1; q >= 0; --q)
  {
    const double cq = c[q];
    for (int v = 0; v < Vectors; ++v)
    {
      acc[v] = acc[v] * t[v] + cq;
    }
  }
}

// Cloned for AVX2 where the CPU has it (4 points per instruction instead of 2; no FMA,
// so the values keep their bits), chosen at load time.
PISURF_AVX2_CLONES
void ProductKernel::EvaluateRestrictedRow(const double* coefficients, double t0, int n,
  const double origin[3], const double step[3], double* values) const
{
  auto pointAt = [&](int i, double p[3]) {
    for (int k = 0; k < 3; ++k)
    {
      p[k] = origin[k] + i * step[k];
    }
  };
  if (!this->AllPolynomial)
  {
    for (int i = 0; i < n; ++i)
    {
      double p[3];
      pointAt(i, p);
      values[i] = this->EvaluateRestricted(coefficients, t0 + i, p);
    }
    return;
  }
  // Groups of 16 points held in registers (four vectors of 4 doubles: four independent
  // Horner chains hide each step's latency): per factor, its Horner chain for every
  // point of the group, multiplied into the products, with the smallest and largest
  // |factor value| of the group; no array round trips through memory. If every factor
  // value of the group is 0 or within 2^±B, B = min(256, 1000 / factors), no partial
  // product leaves the normal range, so the plain product has the same bits as the
  // scaled one (whose rescaling is by exact powers of two); and F must be finite.
  // Otherwise the point goes through EvaluateRestricted. The same operations in the
  // same order per point (no FMA: see PISURF_AVX2_CLONES), so the same bits.
  constexpr int Lanes = 4, Vectors = 4, Group = Lanes * Vectors;
  const double bound = this->PlainBound;
  const double inverse = 1.0 / bound;
  const double r = this->Blending;
  const V4 zero = { 0.0, 0.0, 0.0, 0.0 };
  const V4 boundV = zero + bound;
  // The last group's lanes past the row repeat its last point (so they change neither
  // the group's range test nor anything written).
  for (int start = 0; start < n; start += Group)
  {
    V4 t[Vectors], product[Vectors];
    for (int v = 0; v < Vectors; ++v)
    {
      for (int l = 0; l < Lanes; ++l)
      {
        t[v][l] = t0 + std::min(start + Lanes * v + l, n - 1);
      }
      product[v] = zero + 1.0;
    }
    V4 hi = zero, lo = boundV;
    const double* c = coefficients;
    for (const Factor& f : this->Factors)
    {
      const int terms = std::max(f.Polynomial.Poly.GetDegree(), 0) + 1;
      V4 acc[Vectors];
      for (int v = 0; v < Vectors; ++v)
      {
        acc[v] = zero;
      }
      // (The usual term counts with the loop unrolled: the same operations.)
      switch (terms)
      {
        case 3: HornerGroup<3, Vectors>(acc, t, c, 3); break;
        case 5: HornerGroup<5, Vectors>(acc, t, c, 5); break;
        case 7: HornerGroup<7, Vectors>(acc, t, c, 7); break;
        default: HornerGroup<0, Vectors>(acc, t, c, terms); break;
      }
      for (int v = 0; v < Vectors; ++v)
      {
        product[v] *= acc[v];
        const V4 m = PISURF_ABS4(acc[v]);
        // As std::max(hi, a) and std::min(lo, a): a NaN leaves them; a factor exactly 0
        // makes lo 0, so its points take EvaluateRestricted (rare, and the same bits).
        hi = hi < m ? m : hi;
        lo = m < lo ? m : lo;
      }
      c += terms;
    }
    double highest = 0.0, lowest = bound;
    for (int l = 0; l < Lanes; ++l)
    {
      highest = std::max(highest, hi[l]);
      lowest = std::min(lowest, lo[l]);
    }
    const bool fast = highest <= bound && lowest >= inverse;
    const int count = std::min(Group, n - start);
    if (fast && count == Group)
    {
      // A whole group with every F finite: F = product − r stored four at a time (what
      // Clamp(p − r) gives each point; a NaN or an infinity takes the loop below).
      V4 result[Vectors];
      V4 largest = zero;
      for (int v = 0; v < Vectors; ++v)
      {
        result[v] = product[v] - r;
        const V4 m = PISURF_ABS4(result[v]);
        largest = m <= largest ? largest : m; // a NaN makes it NaN
      }
      bool finite = true;
      for (int l = 0; l < Lanes; ++l)
      {
        finite = finite && largest[l] <= DBL_MAX;
      }
      if (finite)
      {
        for (int v = 0; v < Vectors; ++v)
        {
          PISURF_STORE4(values + start + Lanes * v, result[v]);
        }
        continue;
      }
    }
    for (int i = 0; i < count; ++i)
    {
      const double p = product[i / Lanes][i % Lanes];
      if (fast && std::isfinite(p))
      {
        values[start + i] = Clamp(p - r); // Finish(product, 0)
      }
      else
      {
        double x[3];
        pointAt(start + i, x);
        values[start + i] = this->EvaluateRestricted(coefficients, t0 + (start + i), x);
      }
    }
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
static void ScaledMinus(double m, long e, double r, double& mantissa, long& exponent)
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

// The scaled product and its gradient at p, factor by factor.
static ScaledProduct ProductAndGradient(const std::vector<Factor>& factors, const double p[3])
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

// The nearest factor so far (NearestFactor's order): factor k with value f and gradient
// g replaces it if its squared first-order distance f²/|∇f|² is smaller.
static void KeepNearest(double f, const double g[3], int k, int& nearest, double& best)
{
  const double g2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
  const double d = g2 > 0 ? f * f / g2 : (f == 0 ? 0.0 : std::numeric_limits<double>::infinity());
  // (Selected without a branch: which factor is nearest changes from point to point
  // unpredictably.)
  const bool take = (nearest < 0) | (d < best);
  nearest = take ? k : nearest;
  best = take ? d : best;
}

// The end of EvaluateVertex(Star): unit normal, |∇F| and, if asked, ln|∇F| (−inf where
// ∇F = 0) from the scaled product's gradient G·2^E.
static void FinishVertex(
  const ScaledProduct& s, double normal[3], double& gradientNorm, double* logGradientNorm)
{
  const double gn = std::sqrt(s.G[0] * s.G[0] + s.G[1] * s.G[1] + s.G[2] * s.G[2]);
  gradientNorm = SafeLdexp(gn, s.E);
  if (logGradientNorm)
  {
    *logGradientNorm = gn > 0 ? std::log(gn) + static_cast<double>(s.E) * std::log(2.0)
                              : -std::numeric_limits<double>::infinity();
  }
  for (int k = 0; k < 3; ++k)
  {
    normal[k] = gn > 0 && std::isfinite(gn) ? s.G[k] / gn : 0.0;
  }
}

// PlainVertexFactors' test, one factor at a time (interleaved with the evaluations,
// where its chains of products cost nothing): every value non-zero, Π min(1, |f_k|) >=
// 2^-250 and Π max(1, |f_k|, |∇f_k|∞) <= 2^250: every partial product of the values then
// lies within 2^±250, and every partial gradient below 32·2^250 (NaN fails the
// comparisons).
struct PlainTest
{
  bool Finite = true;
  double SmallProduct = 1.0, BigProduct = 1.0;
  void Add(double f, const double g[3])
  {
    const double a = std::fabs(f), g0 = std::fabs(g[0]), g1 = std::fabs(g[1]),
                 g2 = std::fabs(g[2]);
    // (& rather than &&: no branch per comparison; the same value.)
    this->Finite = this->Finite & (a > 0.0) & (a <= Big) & (g0 <= Big) & (g1 <= Big) & (g2 <= Big);
    this->SmallProduct *= std::min(1.0, a);
    this->BigProduct *= std::max(std::max(std::max(1.0, a), std::max(g0, g1)), g2);
  }
  bool Plain() const
  {
    return this->Finite && this->SmallProduct >= 0x1p-250 && this->BigProduct <= 0x1p250;
  }
};

// The coordinates of up to four points as lanes: xyz[a][l] = p[l][a] (point 0 repeated
// in the lanes from `count` on).
__attribute__((always_inline)) static inline void Lanes(const double (*p)[3], int count, V4* xyz)
{
  for (int a = 0; a < 3; ++a)
  {
    for (int l = 0; l < 4; ++l)
    {
      xyz[a][l] = p[l < count ? l : 0][a];
    }
  }
}

// v[i] = {c[i], c[i], c[i], c[i]} for i < n.
__attribute__((always_inline)) static inline void Splat(const double* c, int n, V4* v)
{
  for (int i = 0; i < n; ++i)
  {
    v[i] = V4{ c[i], c[i], c[i], c[i] };
  }
}

// A quadric (quartic false) or a quartic in the squares (true) in the diagonal frame of
// pf at the four points p (world coordinates as lanes, see Lanes): its value v and world
// gradient g, with
// PolynomialFactor::EvaluateWithGradient's operations (ToLocalDiagonal, the local value
// and gradient as pisurf::QuadricWithGradient or Polynomial3::EvaluateWithGradient's
// quadric of the squares, A's diagonal times that): the same bits. False (nothing
// written) where a quartic's local coordinate reaches 1e30 at some lane (Polynomial3
// then takes its term-wise path).
__attribute__((always_inline)) static inline bool StarFactorAt(
  const PolynomialFactor& pf, bool quartic, const V4* p, V4& v, V4* g)
{
  const V4 x = pf.A[0][0] * p[0] + pf.B[0], y = pf.A[1][1] * p[1] + pf.B[1],
           z = pf.A[2][2] * p[2] + pf.B[2];
  V4 gl[3];
  V4 q[10] = {};
  if (!quartic)
  {
    Splat(pf.Poly.GetQuadric(), 10, q);
    QuadricGradientOf(q, x, y, z, gl);
    QuadricValueOf(q, x, y, z, v);
  }
  else
  {
    bool near = true;
    for (int l = 0; l < 4; ++l)
    {
      near = near && std::fabs(x[l]) < 1e30 && std::fabs(y[l]) < 1e30 && std::fabs(z[l]) < 1e30;
    }
    if (!near)
    {
      return false;
    }
    Splat(pf.Poly.GetEvenQuadric(), 10, q);
    const V4 a = x * x, b = y * y, c = z * z;
    V4 gs[3];
    QuadricValueOf(q, a, b, c, v);
    QuadricGradientOf(q, a, b, c, gs);
    gl[0] = 2.0 * x * gs[0];
    gl[1] = 2.0 * y * gs[1];
    gl[2] = 2.0 * z * gs[2];
  }
  for (int a = 0; a < 3; ++a)
  {
    g[a] = pf.A[a][a] * gl[a];
  }
  return true;
}

// PlainTest at four points (lanes), with its operations: the same verdicts.
struct PlainTest4
{
  I4 Finite = I4{ 0, 0, 0, 0 } - 1;
  V4 SmallProduct = V4{ 1, 1, 1, 1 }, BigProduct = V4{ 1, 1, 1, 1 };
  void Add(const V4& f, const V4* g)
  {
    const V4 a = PISURF_ABS4(f), g0 = PISURF_ABS4(g[0]), g1 = PISURF_ABS4(g[1]),
             g2 = PISURF_ABS4(g[2]);
    const V4 zero = V4{ 0, 0, 0, 0 }, one = V4{ 1, 1, 1, 1 }, big = zero + Big;
    this->Finite = this->Finite & (a > zero) & (a <= big) & (g0 <= big) & (g1 <= big) & (g2 <= big);
    // std::min(x, y) is y < x ? y : x, std::max(x, y) is x < y ? y : x (NaN included)
    this->SmallProduct *= a < one ? a : one;
    const V4 m1 = one < a ? a : one, m2 = g0 < g1 ? g1 : g0, m3 = m1 < m2 ? m2 : m1;
    this->BigProduct *= m3 < g2 ? g2 : m3;
  }
  bool Plain(int l) const
  {
    return this->Finite[l] != 0 && this->SmallProduct[l] >= 0x1p-250 &&
      this->BigProduct[l] <= 0x1p250;
  }
};

// FinishPlainVertex's plain path at four points (lanes; the first `count` written) from
// each factor's values f[k] and gradients g[k] there: its operations in its order (the
// same bits). (FinishVertex's SafeLdexp(|G|, 0) is |G| itself.)
__attribute__((always_inline)) static inline void FinishPlainVertices(const V4* f,
  const V4 (*g)[3], size_t factors, int count, double (*normal)[3], double* gradientNorm,
  int* nearest)
{
  const V4 zero = V4{ 0, 0, 0, 0 }, infinity = zero + std::numeric_limits<double>::infinity();
  V4 best = infinity, index = zero;
  V4 P = zero + 1.0, G[3] = { zero, zero, zero };
  for (size_t k = 0; k < factors; ++k)
  {
    // (KeepNearest: at k = 0 every lane takes)
    const V4 g2 = g[k][0] * g[k][0] + g[k][1] * g[k][1] + g[k][2] * g[k][2];
    const V4 d = g2 > zero ? f[k] * f[k] / g2 : (f[k] == zero ? zero : infinity);
    const I4 take = (d < best) | (I4{ 0, 0, 0, 0 } - (k == 0 ? 1 : 0));
    index = take ? zero + static_cast<double>(k) : index;
    best = take ? d : best;
    for (int c = 0; c < 3; ++c)
    {
      G[c] = G[c] * f[k] + P * g[k][c];
    }
    P *= f[k];
  }
  const V4 squared = G[0] * G[0] + G[1] * G[1] + G[2] * G[2];
  for (int l = 0; l < count; ++l)
  {
    const double gn = std::sqrt(squared[l]);
    gradientNorm[l] = gn;
    for (int c = 0; c < 3; ++c)
    {
      normal[l][c] = gn > 0 && std::isfinite(gn) ? G[c][l] / gn : 0.0;
    }
    nearest[l] = static_cast<int>(index[l]);
  }
}

// One group of four quadrics (as LoadQuadricGroup reads them) at p: the values and
// gradients of factors k0.. (of `count`) into f and g, each added to the plain test;
// QuadricWithGradient's operations, four at a time.
__attribute__((always_inline)) static inline void QuadricGroupAt(const V4 scale[3],
  const V4 shift[3], const V4 q[10], const double p[3], size_t k0, size_t count, double* f,
  double (*g)[3], PlainTest& test)
{
  const V4 x = scale[0] * p[0] + shift[0], y = scale[1] * p[1] + shift[1],
           z = scale[2] * p[2] + shift[2];
  V4 v, gl[3];
  QuadricGradientOf(q, x, y, z, gl);
  QuadricValueOf(q, x, y, z, v);
  const V4 gx = scale[0] * gl[0], gy = scale[1] * gl[1], gz = scale[2] * gl[2];
  for (size_t l = 0; l < 4 && k0 + l < count; ++l)
  {
    const size_t k = k0 + l;
    f[k] = v[l];
    g[k][0] = gx[l];
    g[k][1] = gy[l];
    g[k][2] = gz[l];
    test.Add(f[k], g[k]);
  }
}

PISURF_AVX2_CLONES
bool ProductKernel::PlainVertexFactors(const double p[3], double* f, double (*g)[3]) const
{
  const size_t count = this->Factors.size();
  PlainTest test;
  if (this->QuadricStride > 0)
  {
    // Four quadrics at a time: PolynomialFactor::QuadricWithGradient's operations.
    const size_t stride = this->QuadricStride;
    const double* rows = this->QuadricRows.data();
    for (size_t k0 = 0; k0 < stride; k0 += 4)
    {
      V4 scale[3], shift[3], q[10];
      LoadQuadricGroup(rows, stride, k0, scale, shift, q);
      QuadricGroupAt(scale, shift, q, p, k0, count, f, g, test);
    }
    return test.Plain();
  }
  for (size_t k = 0; k < count; ++k)
  {
    const PolynomialFactor& pf = this->Factors[k].Polynomial;
    f[k] = this->StarQuadric[k] ? pf.QuadricWithGradient(p, g[k]) // inline
                                : pf.EvaluateWithGradient(p, g[k]);
    test.Add(f[k], g[k]);
  }
  return test.Plain();
}

PISURF_AVX2_CLONES
void ProductKernel::EvaluateVertices(int count, const double (*p)[3], double (*normal)[3],
  double* gradientNorm, int* nearest) const
{
  const size_t factors = this->Factors.size();
  if (!this->AllPolynomial || factors == 0 || factors > MaxPlainVertex || count > MaxVertices)
  {
    for (int j = 0; j < count; ++j)
    {
      this->EvaluateVertex(p[j], normal[j], gradientNorm[j], nearest[j]);
    }
    return;
  }
  // PlainVertexFactors and FinishPlainVertex at every point: factor by factor, the
  // points side by side.
  double f[MaxVertices][MaxPlainVertex], g[MaxVertices][MaxPlainVertex][3];
  // The points as lanes (the first repeated where there are fewer than four), for the
  // quadrics and quartics in the squares in diagonal frames: each evaluated at the four
  // points at once, with the scalar path's operations in its order (the same bits).
  static_assert(MaxVertices == 4, "the lanes of V4");
  V4 x[3] = {};
  Lanes(p, count, x);
  // Each factor's values and gradients at the lanes, tested lane by lane (PlainTest4).
  V4 fv[MaxPlainVertex], gv[MaxPlainVertex][3];
  PlainTest4 plain;
  for (size_t k = 0; k < factors; ++k)
  {
    const PolynomialFactor& pf = this->Factors[k].Polynomial;
    const bool done = (this->StarQuadric[k] || this->StarEvenQuartic[k]) &&
      StarFactorAt(pf, this->StarEvenQuartic[k] != 0, x, fv[k], gv[k]);
    if (!done)
    {
      for (int l = 0; l < 4; ++l)
      {
        double gl[3];
        fv[k][l] = pf.EvaluateWithGradient(p[l < count ? l : 0], gl);
        for (int a = 0; a < 3; ++a)
        {
          gv[k][a][l] = gl[a];
        }
      }
    }
    plain.Add(fv[k], gv[k]);
  }
  bool allPlain = true;
  for (int j = 0; j < count; ++j)
  {
    allPlain = allPlain && plain.Plain(j);
  }
  if (allPlain)
  {
    FinishPlainVertices(fv, gv, factors, count, normal, gradientNorm, nearest);
    return;
  }
  // (Some point needs the scaled product: each point by FinishPlainVertex.)
  for (int j = 0; j < count; ++j)
  {
    for (size_t k = 0; k < factors; ++k)
    {
      f[j][k] = fv[k][j];
      for (int a = 0; a < 3; ++a)
      {
        g[j][k][a] = gv[k][a][j];
      }
    }
    this->FinishPlainVertex(
      f[j], g[j], normal[j], gradientNorm[j], nearest[j], nullptr, plain.Plain(j));
  }
}

PISURF_AVX2_CLONES
void ProductKernel::EvaluateOnSegments(int count, const double (*a)[3], const double (*d)[3],
  const double* s, double* value, double* slope, bool* ok) const
{
  // The points as lanes (the first repeated where there are fewer than four), each
  // factor's value and gradient there (StarFactorAt), its slope ∇f·d, multiplied into
  // F and dF/ds by the product rule (MultiplyWithSlope's bound test and operations).
  double at[MaxVertices][3];
  for (int j = 0; j < count; ++j)
  {
    for (int c = 0; c < 3; ++c)
    {
      at[j][c] = a[j][c] + s[j] * d[j][c];
    }
  }
  V4 x[3] = {}, dx[3] = {};
  Lanes(at, count, x);
  Lanes(d, count, dx);
  const V4 zero = V4{ 0, 0, 0, 0 };
  const V4 bound = zero + this->PlainBound, inverse = zero + 1.0 / this->PlainBound;
  V4 product = zero + 1.0, derivative = zero;
  I4 inRange = I4{ 0, 0, 0, 0 } - 1;
  const size_t factors = this->Factors.size();
  for (size_t k = 0; k < factors; ++k)
  {
    V4 v, g[3];
    if (!StarFactorAt(this->Factors[k].Polynomial, this->StarEvenQuartic[k] != 0, x, v, g))
    {
      for (int j = 0; j < count; ++j)
      {
        ok[j] = false;
      }
      return;
    }
    const V4 m = PISURF_ABS4(v);
    inRange = inRange & ~((m > bound) | ((m != zero) & (m < inverse)));
    const V4 along = g[0] * dx[0] + g[1] * dx[1] + g[2] * dx[2];
    derivative = derivative * v + product * along;
    product *= v;
  }
  const V4 F = product - this->Blending;
  for (int j = 0; j < count; ++j)
  {
    value[j] = F[j];
    slope[j] = derivative[j];
    ok[j] = inRange[j] != 0 && std::isfinite(value[j]) && std::isfinite(slope[j]);
  }
}

void ProductKernel::FinishPlainVertex(const double* f, const double (*g)[3], double normal[3],
  double& gradientNorm, int& nearest, double* logGradientNorm, bool plain) const
{
  const size_t count = this->Factors.size();
  double best = std::numeric_limits<double>::infinity();
  nearest = -1;
  ScaledProduct s;
  for (size_t k = 0; k < count; ++k)
  {
    KeepNearest(f[k], g[k], static_cast<int>(k), nearest, best);
  }
  if (!plain)
  {
    // ScaledProduct rescales only a factor or a partial product whose largest magnitude
    // (of value and gradient) is finite, non-zero and outside [Small, Big]; where none
    // is, its operations are exactly these plain ones.
    auto keeps = [](double v, const double w[3]) {
      const double a = std::max({ std::fabs(v), std::fabs(w[0]), std::fabs(w[1]), std::fabs(w[2]) });
      return (a >= Small && a <= Big) || a == 0.0 || !std::isfinite(a);
    };
    bool unscaled = true;
    for (size_t k = 0; k < count && unscaled; ++k)
    {
      unscaled = keeps(f[k], g[k]);
      for (int c = 0; c < 3; ++c)
      {
        s.G[c] = s.G[c] * f[k] + s.P * g[k][c];
      }
      s.P *= f[k];
      unscaled = unscaled && keeps(s.P, s.G);
    }
    if (!unscaled)
    {
      // The general path's product (ScaledProduct), on the values already computed.
      s = ScaledProduct();
      for (size_t k = 0; k < count; ++k)
      {
        s.Multiply(f[k], g[k]);
      }
    }
    FinishVertex(s, normal, gradientNorm, logGradientNorm);
    return;
  }
  for (size_t k = 0; k < count; ++k)
  {
    for (int c = 0; c < 3; ++c)
    {
      s.G[c] = s.G[c] * f[k] + s.P * g[k][c];
    }
    s.P *= f[k];
  }
  FinishVertex(s, normal, gradientNorm, logGradientNorm);
}

void ProductKernel::EvaluateVertex(const double p[3], double normal[3], double& gradientNorm,
  int& nearest, double* logGradientNorm) const
{
  // Up to 32 polynomial factors: all values and gradients first (independent
  // evaluations), then the product rule in plain doubles when the values and gradients
  // keep every partial product within 2^±250 (PlainVertexFactors): no partial product
  // or gradient then leaves [2^-256, 2^256], where ScaledProduct never rescales, so the
  // same operations give the same bits. Otherwise (a factor far from the
  // surface's own, as around a product of many spheres) ScaledProduct multiplies the
  // same values: the general path's bits without evaluating the factors again.
  const size_t count = this->Factors.size();
  if (this->AllPolynomial && count > 0 && count <= MaxPlainVertex)
  {
    double f[MaxPlainVertex], g[MaxPlainVertex][3];
    const bool plain = this->PlainVertexFactors(p, f, g);
    this->FinishPlainVertex(f, g, normal, gradientNorm, nearest, logGradientNorm, plain);
    return;
  }
  ScaledProduct s;
  double gi[3];
  double best = std::numeric_limits<double>::infinity();
  nearest = -1;
  for (size_t k = 0; k < this->Factors.size(); ++k)
  {
    const double fi = this->Factors[k].EvaluateWithGradient(p, gi);
    KeepNearest(fi, gi, static_cast<int>(k), nearest, best);
    s.Multiply(fi, gi);
  }
  FinishVertex(s, normal, gradientNorm, logGradientNorm);
}

// An upper bound of |P| over the box: the smaller of the term-wise interval bound and
// the centred form's (Σ|b| of the Taylor coefficients about the box's centre, scaled to
// its half-widths, plus their rounding): on a small box about a point where the expanded
// terms cancel ((8z + 5)^4 near z = −5/8) the centred form is tighter by orders.
static double MaxAbsOver(const Polynomial3& p, const Interval box[3])
{
  double magnitude = 0.0;
  const Interval range = p.EvaluateInterval(box, &magnitude);
  double bound = std::max(std::fabs(range.Lo), std::fabs(range.Hi));
  const int n = p.GetDegree();
  if (n >= 0 && n <= TaylorMaxDegree)
  {
    double c[3], h[3];
    for (int a = 0; a < 3; ++a)
    {
      c[a] = 0.5 * (box[a].Lo + box[a].Hi);
      h[a] = std::max(box[a].Hi - c[a], c[a] - box[a].Lo) * (1.0 + 4.0 * DBL_EPSILON);
    }
    constexpr int M = TaylorMaxDegree + 1;
    double b[M * M * M];
    if (p.ExpandAbout(c, h, b) == n)
    {
      const int m = n + 1;
      double sum = 0.0;
      for (int k = 0; k < m * m * m; ++k)
      {
        sum += std::fabs(b[k]);
      }
      bound = std::min(bound, sum * (1.0 + 1e-12) + 8.0 * (n + 1) * DBL_EPSILON * magnitude);
    }
  }
  return bound;
}

ProductKernel::ProbeBounds ProductKernel::PrepareProbes(const double box[6], double probe) const
{
  ProbeBounds bounds;
  bounds.Probe = probe;
  std::copy(box, box + 6, bounds.Box);
  const size_t count = this->Factors.size();
  const double inf = std::numeric_limits<double>::infinity();
  bounds.Slack.assign(3 * count, inf);
  double corner[3];
  for (int a = 0; a < 3; ++a)
  {
    corner[a] = probe + std::max(std::fabs(box[2 * a]), std::fabs(box[2 * a + 1]));
    if (!(box[2 * a] <= box[2 * a + 1]) || !std::isfinite(corner[a]))
    {
      return bounds;
    }
  }
  if (!(probe > 0) || !std::isfinite(probe))
  {
    return bounds;
  }
  // Per factor and axis: the derivatives of order 2 and up along the axis (their
  // enclosures over each cell bound the Taylor remainder) and the rounding part of the
  // slack, from the magnitude polynomials (coefficients not negative: largest at the
  // corner of largest |x|, |y|, |z|).
  struct Part
  {
    std::vector<Polynomial3> Derivatives; // orders 2, 3, ...
    double Rounding = std::numeric_limits<double>::infinity();
  };
  std::vector<Part> parts(3 * count);
  size_t work = 0;
  bool curved = false; // some factor of degree above 2 (remainders that vary in space)
  for (size_t i = 0; i < count; ++i)
  {
    const Factor& factor = this->Factors[i];
    if (!factor.IsPolynomial || !factor.Polynomial.HasWorld)
    {
      continue;
    }
    const PolynomialFactor& pf = factor.Polynomial;
    // The value at p and at a probe, each within RoundingBound of the local terms'
    // magnitude (which WorldMagnitude bounds), twice over for the frame change's rounding.
    const double value = 2.0 * pf.Poly.RoundingBound(pf.WorldMagnitude.Evaluate(corner));
    curved = curved || pf.World.GetDegree() > 2;
    for (int a = 0; a < 3; ++a)
    {
      Part& part = parts[3 * i + a];
      const double gradient =
        2.0 * pf.Poly.RoundingBound(pf.WorldMagnitude.Derivative(a).Evaluate(corner));
      part.Rounding = 2.0 * value + probe * gradient;
      Polynomial3 derivative = pf.World.Derivative(a);
      for (int k = 2; k <= pf.World.GetDegree(); ++k)
      {
        derivative = derivative.Derivative(a);
        if (derivative.IsZero())
        {
          break;
        }
        part.Derivatives.push_back(derivative);
        work += derivative.GetTerms().size() + 1;
      }
    }
  }
  // Cells: the remainders of high-degree factors vary by orders of magnitude over a box
  // (the table top's (8z + 5)^6), so each cell of up to 8³ has its own, within a budget
  // of interval evaluations.
  int n = curved ? 8 : 1;
  while (n > 1 && work * static_cast<size_t>(n * n * n) > 400000)
  {
    n /= 2;
  }
  for (int a = 0; a < 3; ++a)
  {
    bounds.Cells[a] = n;
  }
  const size_t cells = static_cast<size_t>(n) * n * n;
  bounds.Slack.assign(cells * 3 * count, inf);
  for (size_t cell = 0; cell < cells; ++cell)
  {
    const int ci[3] = { static_cast<int>(cell % n), static_cast<int>((cell / n) % n),
      static_cast<int>(cell / (static_cast<size_t>(n) * n)) };
    // The cell grown by the probe and a little more (the rounding of p ± h, and of the
    // cell a point is found in).
    Interval grown[3];
    for (int a = 0; a < 3; ++a)
    {
      const double lo = box[2 * a], width = (box[2 * a + 1] - lo) / n;
      const double reach = probe * (1.0 + 1e-6) + 1e-9 * width +
        1e-12 * (std::fabs(box[2 * a]) + std::fabs(box[2 * a + 1]));
      grown[a] = { lo + ci[a] * width - reach, lo + (ci[a] + 1) * width + reach };
    }
    for (size_t i = 0; i < count; ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        const Part& part = parts[3 * i + a];
        double remainder = 0.0, power = probe, factorial = 1.0;
        for (size_t d = 0; d < part.Derivatives.size(); ++d)
        {
          power *= probe;
          factorial *= static_cast<double>(d + 2);
          remainder += power / factorial * MaxAbsOver(part.Derivatives[d], grown);
        }
        const double slack = (remainder + part.Rounding) * (1.0 + 1e-10);
        bounds.Slack[(cell * count + i) * 3 + a] = std::isfinite(slack) ? slack : inf;
      }
    }
  }
  return bounds;
}

// EvaluateVertexIfRegular's slack for p: the bounds' row of the cell of their box that
// holds p (null where p is outside the box, or the bounds are not for these factors).
// (This and RegularFromBounds are inlined: called from EvaluateVerticesIfRegular's AVX2
// clone as functions of their own, the four-point path took longer than four single
// points, 80 against 70 ms for 400 000 points of the cup; inlined, 25 ms.)
__attribute__((always_inline)) static inline const double* ProbeSlack(
  const ProductKernel::ProbeBounds& bounds, size_t factors, const double p[3])
{
  if (bounds.Slack.size() != 3 * factors * bounds.Cells[0] * bounds.Cells[1] * bounds.Cells[2])
  {
    return nullptr;
  }
  size_t cell = 0;
  for (int a = 3; a-- > 0;)
  {
    const double lo = bounds.Box[2 * a], hi = bounds.Box[2 * a + 1];
    if (!(p[a] >= lo && p[a] <= hi))
    {
      return nullptr;
    }
    const int n = bounds.Cells[a];
    const int c = hi > lo ? static_cast<int>((p[a] - lo) / (hi - lo) * n) : 0;
    cell = cell * n + static_cast<size_t>(std::max(0, std::min(n - 1, c)));
  }
  return bounds.Slack.data() + cell * 3 * factors;
}

// EvaluateVertexIfRegular's verdict from the product's value, the bounds' sums t (the
// largest change of a probe's product along each axis) and grown (the largest product
// of the moved factors) and |∇F|.
__attribute__((always_inline)) static inline bool RegularFromBounds(double product,
  const double t[3], const double grown[3], size_t count, double blending, double gradientNorm,
  double h, double tolerance)
{
  const double absProduct = std::fabs(product);
  const double largest = std::max({ 0.0, t[0], t[1], t[2] });
  const double magnitude = std::max({ 0.0, grown[0], grown[1], grown[2] });
  // |F| at a probe, as computed there: at most |F(p)| (with its rounding) + T, plus the
  // rounding of the probe's own product and subtraction; with a relative margin.
  const double r = std::fabs(blending);
  const double unit = std::numeric_limits<double>::epsilon();
  const double rounding = 4.0 * (static_cast<double>(count) + 2.0) * unit;
  const double F = product - blending;
  const double U = (std::fabs(F) + largest + rounding * (absProduct + magnitude + 2.0 * r)) *
    (1.0 + 1e-10);
  return std::isfinite(U) && std::isnormal(gradientNorm) && gradientNorm * h > tolerance * U;
}

bool ProductKernel::EvaluateVertexIfRegular(const double p[3], const ProbeBounds& bounds,
  double tolerance, double normal[3], double& gradientNorm, int& nearest,
  double* logGradientNorm) const
{
  const size_t count = this->Factors.size();
  if (!this->AllPolynomial || count == 0 || count > MaxPlainVertex)
  {
    return false;
  }
  const double* slack = ProbeSlack(bounds, count, p);
  if (!slack)
  {
    return false;
  }
  double f[MaxPlainVertex], g[MaxPlainVertex][3];
  if (!this->PlainVertexFactors(p, f, g))
  {
    return false;
  }
  // Along axis a every factor moves by at most Δ_i = h·|∂_a f_i|·(1 + 1e-12) + slack
  // between p and a probe (in their computed values), so the probe's product differs
  // from P(p) by at most T = Π(|f_i| + Δ_i) − Π|f_i|, summed without cancellation as
  // T_i = T_{i−1}·(|f_i| + Δ_i) + Δ_i·Π_{j<i}|f_j|. Every term is plain (each partial
  // product of the |f_j| within 2^±250, PlainVertexFactors) unless a Δ is huge: then T
  // is inf and the test below fails.
  // (The three axes in one pass over the factors: three independent chains, and the
  // partial products q of the |f_j| shared; the same operations per axis as one axis at
  // a time.)
  const double h = bounds.Probe;
  double product = 1.0, q = 1.0;
  double t[3] = { 0.0, 0.0, 0.0 }, grown[3] = { 1.0, 1.0, 1.0 };
  for (size_t k = 0; k < count; ++k)
  {
    const double af = std::fabs(f[k]);
    for (int a = 0; a < 3; ++a)
    {
      const double delta = h * std::fabs(g[k][a]) * (1.0 + 1e-12) + slack[3 * k + a];
      t[a] = t[a] * (af + delta) + delta * q;
      grown[a] *= af + delta;
    }
    q *= af;
    product *= f[k];
  }
  this->FinishPlainVertex(f, g, normal, gradientNorm, nearest, logGradientNorm);
  return RegularFromBounds(product, t, grown, count, this->Blending, gradientNorm, h, tolerance);
}

PISURF_AVX2_CLONES
void ProductKernel::EvaluateVerticesIfRegular(int count, const double (*p)[3],
  const ProbeBounds& bounds, double tolerance, double (*normal)[3], double* gradientNorm,
  int* nearest, bool* regular) const
{
  const size_t factors = this->Factors.size();
  auto onePointAtATime = [&]() {
    for (int j = 0; j < count; ++j)
    {
      regular[j] = this->EvaluateVertexIfRegular(
        p[j], bounds, tolerance, normal[j], gradientNorm[j], nearest[j]);
    }
  };
  // (StarFactorsOnly holds for at most MaxPlainVertex factors: the arrays below.)
  if (!this->StarFactorsOnly || count > MaxVertices)
  {
    onePointAtATime();
    return;
  }
  // Each point's slack row (a point outside the box is not regular; its lane computes
  // with zero slack, unused).
  static_assert(MaxVertices == 4, "the lanes of V4");
  const double* slack[MaxVertices];
  static const double zeros[3 * MaxPlainVertex] = {};
  bool inside[MaxVertices], any = false;
  for (int l = 0; l < MaxVertices; ++l)
  {
    slack[l] = l < count ? ProbeSlack(bounds, factors, p[l]) : nullptr;
    inside[l] = slack[l] != nullptr;
    any = any || inside[l];
    slack[l] = inside[l] ? slack[l] : zeros;
  }
  if (!any)
  {
    std::fill(regular, regular + count, false);
    return;
  }
  // The factors at the four points (as EvaluateVertices), PlainVertexFactors' test, and
  // the bounds' sums of EvaluateVertexIfRegular, lane by lane with its operations.
  V4 x[3] = {};
  Lanes(p, count, x);
  V4 fv[MaxPlainVertex], gv[MaxPlainVertex][3];
  PlainTest4 plain;
  const V4 zero = V4{ 0, 0, 0, 0 }, one = zero + 1.0, h = zero + bounds.Probe;
  V4 product = one, q = one, t[3] = { zero, zero, zero }, grown[3] = { one, one, one };
  for (size_t k = 0; k < factors; ++k)
  {
    const PolynomialFactor& pf = this->Factors[k].Polynomial;
    if (!StarFactorAt(pf, this->StarEvenQuartic[k] != 0, x, fv[k], gv[k]))
    {
      onePointAtATime(); // (a quartic's local coordinate reaches 1e30)
      return;
    }
    plain.Add(fv[k], gv[k]);
    const V4 af = PISURF_ABS4(fv[k]);
    for (int a = 0; a < 3; ++a)
    {
      const size_t i = 3 * k + a;
      const V4 s = V4{ slack[0][i], slack[1][i], slack[2][i], slack[3][i] };
      const V4 delta = h * PISURF_ABS4(gv[k][a]) * (1.0 + 1e-12) + s;
      t[a] = t[a] * (af + delta) + delta * q;
      grown[a] *= af + delta;
    }
    q *= af;
    product *= fv[k];
  }
  FinishPlainVertices(fv, gv, factors, count, normal, gradientNorm, nearest);
  for (int j = 0; j < count; ++j)
  {
    const double tj[3] = { t[0][j], t[1][j], t[2][j] };
    const double grownj[3] = { grown[0][j], grown[1][j], grown[2][j] };
    regular[j] = inside[j] && plain.Plain(j) &&
      RegularFromBounds(product[j], tj, grownj, factors, this->Blending, gradientNorm[j],
        bounds.Probe, tolerance);
  }
}

// F = m·2^e − r as mantissa·2^exponent, the end of EvaluateScaled.
static void FinishScaled(double m, long e, double r, double& mantissa, long& exponent)
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

void ProductKernel::EvaluateVertexStar(const double p[3], double probe, double normal[3],
  double& gradientNorm, int& nearest, double& logGradientNorm, double probeMantissa[6],
  long probeExponent[6]) const
{
  // The factors' values (at p and the six probes) and gradients, then their products:
  // in plain doubles when no product can leave the double range (at most 15 factors,
  // every value and gradient component 0 or within 2^±64), else in the scaled form.
  constexpr size_t MaxPlain = 15;
  const size_t count = this->Factors.size();
  double values[MaxPlain][7], gradients[MaxPlain][3];
  bool plain = count <= MaxPlain;
  ScaledProduct s;
  double m[6] = { 1, 1, 1, 1, 1, 1 };
  long e[6] = { 0, 0, 0, 0, 0, 0 };
  double best = std::numeric_limits<double>::infinity();
  nearest = -1;
  for (size_t k = 0; k < count; ++k)
  {
    const Factor& f = this->Factors[k];
    double local[7], localG[3];
    double* v = plain ? values[k] : local;
    double* gi = plain ? gradients[k] : localG;
    if (this->StarQuadric[k])
    {
      // Inline: the most common factor, whose two calls cost as much as its work.
      f.Polynomial.QuadricStar(p, probe, v, gi);
    }
    else if (f.IsPolynomial)
    {
      f.Polynomial.EvaluateStar(p, probe, v, gi);
    }
    else
    {
      v[0] = f.Generic(p, gi);
      for (int a = 0; a < 6; ++a)
      {
        double r[3] = { p[0], p[1], p[2] };
        r[a / 2] += a % 2 ? probe : -probe;
        v[1 + a] = f.Generic(r, nullptr);
      }
    }
    const double fi = v[0];
    if (plain)
    {
      // (the nearest factor is chosen after the loop from the stored values: no
      // data-dependent branch between the factors' evaluations)
      bool inRange = true;
      for (int c = 0; c < 10; ++c)
      {
        const double a = std::fabs(c < 7 ? v[c] : gi[c - 7]);
        inRange &= a == 0.0 || (a >= 0x1p-64 && a <= 0x1p64);
      }
      plain = inRange;
      if (!plain)
      {
        // Out of the plain range: the factors so far go to the scaled form.
        for (size_t q = 0; q <= k; ++q)
        {
          KeepNearest(values[q][0], gradients[q], static_cast<int>(q), nearest, best);
          s.Multiply(values[q][0], gradients[q]);
          for (int a = 0; a < 6; ++a)
          {
            Accumulate(m[a], e[a], values[q][1 + a]);
          }
        }
      }
    }
    else
    {
      KeepNearest(fi, gi, static_cast<int>(k), nearest, best);
      s.Multiply(fi, gi);
      for (int a = 0; a < 6; ++a)
      {
        Accumulate(m[a], e[a], v[1 + a]);
      }
    }
  }
  if (plain)
  {
    for (size_t k = 0; k < count; ++k)
    {
      KeepNearest(values[k][0], gradients[k], static_cast<int>(k), nearest, best);
    }
    for (size_t k = 0; k < count; ++k)
    {
      const double f = values[k][0];
      for (int c = 0; c < 3; ++c)
      {
        s.G[c] = s.G[c] * f + s.P * gradients[k][c];
      }
      s.P *= f;
      for (int a = 0; a < 6; ++a)
      {
        m[a] *= values[k][1 + a];
      }
    }
  }
  FinishVertex(s, normal, gradientNorm, &logGradientNorm);
  for (int a = 0; a < 6; ++a)
  {
    FinishScaled(m[a], e[a], this->Blending, probeMantissa[a], probeExponent[a]);
  }
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

int SignOfProductMinus(const std::vector<Interval>& enclosures, double r)
{
  return SignOfProductMinus(enclosures.data(), enclosures.size(), r);
}

int SignOfProductMinus(const Interval* enclosures, size_t count, double r)
{
  if (count <= 16)
  {
    // Plain doubles when no end can leave the normal range: |ends| in [2^-60, 2^60] or
    // 0, at most 16 factors, so every partial product is within 2^±960.
    constexpr double Top = 1152921504606846976.0; // 2^60
    constexpr double Bottom = 1.0 / Top;
    bool plain = true;
    for (size_t i = 0; i < count && plain; ++i)
    {
      for (const double x : { enclosures[i].Lo, enclosures[i].Hi })
      {
        const double a = std::fabs(x);
        plain = plain && (a == 0.0 || (a >= Bottom && a <= Top));
      }
      plain = plain && enclosures[i].Lo <= enclosures[i].Hi;
    }
    if (plain)
    {
      double lo = 1.0, hi = 1.0;
      for (size_t i = 0; i < count; ++i)
      {
        const Interval& v = enclosures[i];
        const double c[4] = { lo * v.Lo, lo * v.Hi, hi * v.Lo, hi * v.Hi };
        lo = std::min({ c[0], c[1], c[2], c[3] });
        hi = std::max({ c[0], c[1], c[2], c[3] });
      }
      // Each product rounds by at most half an ulp of a normal number: widen by
      // count ulps (relative), then compare with r exactly.
      const double widen = 2.0 * static_cast<double>(count + 1) * DBL_EPSILON;
      lo -= std::fabs(lo) * widen;
      hi += std::fabs(hi) * widen;
      if (lo > r)
      {
        return 1;
      }
      if (hi < r)
      {
        return -1;
      }
      return 0;
    }
  }
  // |P| ∈ [exp(logMin), exp(logMax)]; sign fixed unless a factor spans zero.
  double logMin = 0.0, logMax = 0.0;
  int sign = 1;
  bool spansZero = false;
  for (size_t i = 0; i < count; ++i)
  {
    const Interval& v = enclosures[i];
    if (!(v.Lo <= v.Hi)) // NaN
    {
      return 0;
    }
    const double maxAbs = std::max(std::fabs(v.Lo), std::fabs(v.Hi));
    logMax += std::log(maxAbs);
    if (v.Lo > 0 || v.Hi < 0)
    {
      logMin += std::log(std::min(std::fabs(v.Lo), std::fabs(v.Hi)));
      sign = v.Lo > 0 ? sign : -sign;
    }
    else
    {
      spansZero = true;
    }
  }
  if (spansZero)
  {
    // P ∈ [−|P|max, |P|max] (or half of it): excludes r only if it cannot reach |r|.
    if (r != 0.0 && logMax < std::log(std::fabs(r)) - 1e-9)
    {
      return r > 0 ? -1 : 1;
    }
    return 0;
  }
  // P has sign `sign` and |P| ∈ [e^logMin, e^logMax].
  if (r == 0.0 || (r > 0) != (sign > 0))
  {
    return sign; // F = P − r has the sign of P
  }
  const double logR = std::log(std::fabs(r));
  if (logMin > logR + 1e-9)
  {
    return sign; // |P| > |r|
  }
  if (logMax < logR - 1e-9)
  {
    return -sign; // |P| < |r|
  }
  return 0;
}

int ProductKernel::ClassifyBox(const double box[6]) const
{
  if (!this->AllPolynomial)
  {
    return 0;
  }
  // On the stack for the usual few factors (a thread_local vector costs a TLS lookup
  // per call in a shared library).
  constexpr size_t Small = 32;
  Interval local[Small] = {}; // (every element is written below; this quiets GCC)
  char expandedLocal[Small];
  const size_t n = this->Factors.size();
  Interval* enclosures = local;
  char* expanded = expandedLocal;
  if (n > Small)
  {
    thread_local std::vector<Interval> large;
    thread_local std::vector<char> expandedLarge;
    large.resize(n);
    expandedLarge.resize(n);
    enclosures = large.data();
    expanded = expandedLarge.data();
  }
  // The Taylor forms alone first; only where they cannot decide, intersected with the
  // expressions as written (narrower enclosures can only confirm a decided sign).
  bool natural = false;
  for (size_t i = 0; i < n; ++i)
  {
    const PolynomialFactor& f = this->Factors[i].Polynomial;
    expanded[i] = f.EvaluateTaylor(box, enclosures[i], nullptr, false);
    if (!expanded[i])
    {
      enclosures[i] = f.EvaluateInterval(box);
    }
    else
    {
      natural = natural || f.HasNaturalForm();
    }
  }
  const int sign = SignOfProductMinus(enclosures, n, this->Blending);
  if (sign != 0 || !natural)
  {
    return sign;
  }
  for (size_t i = 0; i < n; ++i)
  {
    const PolynomialFactor& f = this->Factors[i].Polynomial;
    if (expanded[i] && f.HasNaturalForm())
    {
      f.IntersectNatural(box, enclosures[i], nullptr);
    }
  }
  return SignOfProductMinus(enclosures, n, this->Blending);
}

// +1 / −1 where Σ ∂f_i·Π_{j≠i} f_j over the enclosures has that sign beyond 1e-9 of its
// terms (far beyond the rounding of these products, round to nearest), else 0; 0 also
// where a magnitude leaves 2^±60 (the plain products could lose range).
static int DerivativeSign(const Interval* f, const Interval* df, size_t n)
{
  constexpr double Range = 0x1p60;
  constexpr size_t MaxFactors = 16;
  if (n == 0 || n > MaxFactors)
  {
    return 0;
  }
  for (size_t i = 0; i < n; ++i)
  {
    const double fm = std::max(std::fabs(f[i].Lo), std::fabs(f[i].Hi));
    const double dm = std::max(std::fabs(df[i].Lo), std::fabs(df[i].Hi));
    if (!(fm <= Range && dm <= Range && (fm == 0.0 || fm >= 1.0 / Range) &&
          (dm == 0.0 || dm >= 1.0 / Range)))
    {
      return 0;
    }
  }
  Interval prefix[MaxFactors + 1];
  PrefixProducts(f, static_cast<int>(n), prefix);
  double lo, hi, magnitude;
  ProductRule(f, df, static_cast<int>(n), prefix, lo, hi, magnitude);
  if (!std::isfinite(magnitude))
  {
    return 0;
  }
  const double slack = 1e-9 * magnitude + 1e-290;
  return lo > slack ? 1 : hi < -slack ? -1 : LogDerivativeSign(f, df, static_cast<int>(n), 1e-9);
}

int ProductKernel::ClassifyBoxAndOctants(
  const double box[6], int octants[8], bool allOctants, int* monotone, int axis) const
{
  if (monotone)
  {
    std::fill(monotone, monotone + 8, 0);
  }
  if (!this->AllPolynomial)
  {
    return 0;
  }
  const size_t n = this->Factors.size();
  constexpr size_t Small = 16;
  Interval wholeLocal[Small] = {}, partsLocal[8 * Small]; // (see ClassifyBox)
  char expandedLocal[Small];
  Interval* whole = wholeLocal;
  Interval* parts = partsLocal;
  char* expanded = expandedLocal;
  if (n > Small)
  {
    thread_local std::vector<Interval> wholeLarge, partsLarge;
    thread_local std::vector<char> expandedLarge;
    wholeLarge.resize(n);
    partsLarge.resize(8 * n);
    expandedLarge.resize(n);
    whole = wholeLarge.data();
    parts = partsLarge.data();
    expanded = expandedLarge.data();
  }
  // ∂f_i/∂x_axis on each octant, when asked for (up to 16 factors, each with a Taylor
  // form: else no octant is reported monotone).
  constexpr size_t MonotoneFactors = 16;
  Interval derivatives[8 * MonotoneFactors];
  bool derivativesKnown = monotone && axis >= 0 && axis <= 2 && n <= MonotoneFactors;
  // The Taylor forms alone first; the expressions as written only where they cannot
  // decide the box (as in ClassifyBox).
  bool natural = false;
  for (size_t i = 0; i < n; ++i)
  {
    const PolynomialFactor& f = this->Factors[i].Polynomial;
    Interval octant[8], derivative[8];
    expanded[i] = f.EvaluateTaylor(
      box, whole[i], octant, false, derivativesKnown ? derivative : nullptr, axis);
    derivativesKnown = derivativesKnown && expanded[i];
    if (derivativesKnown)
    {
      for (int o = 0; o < 8; ++o)
      {
        derivatives[o * n + i] = derivative[o];
      }
    }
    if (expanded[i])
    {
      natural = natural || f.HasNaturalForm();
      for (int o = 0; o < 8; ++o)
      {
        parts[o * n + i] = octant[o];
      }
    }
    else
    {
      whole[i] = f.EvaluateInterval(box);
    }
  }
  int sign = SignOfProductMinus(whole, n, this->Blending);
  if (sign == 0 && natural)
  {
    for (size_t i = 0; i < n; ++i)
    {
      const PolynomialFactor& f = this->Factors[i].Polynomial;
      if (expanded[i] && f.HasNaturalForm())
      {
        Interval octant[8];
        for (int o = 0; o < 8; ++o)
        {
          octant[o] = parts[o * n + i];
        }
        f.IntersectNatural(box, whole[i], octant);
        for (int o = 0; o < 8; ++o)
        {
          parts[o * n + i] = octant[o];
        }
      }
    }
    sign = SignOfProductMinus(whole, n, this->Blending);
  }
  if (sign != 0)
  {
    return sign;
  }
  for (int o = 0; o < 8; ++o)
  {
    double sub[6];
    OctantBox(box, o, sub);
    for (size_t i = 0; i < n; ++i)
    {
      if (!expanded[i])
      {
        parts[o * n + i] = this->Factors[i].Polynomial.EvaluateInterval(sub);
      }
    }
    octants[o] = SignOfProductMinus(parts + o * n, n, this->Blending);
    if (octants[o] == 0 && derivativesKnown)
    {
      monotone[o] = DerivativeSign(parts + o * n, derivatives + o * n, n);
    }
    if (octants[o] == 0 && !allOctants)
    {
      // The box holds the surface as far as the octants can tell: the rest are not
      // needed to know that (reported undecided).
      std::fill(octants + o + 1, octants + 8, 0);
      break;
    }
  }
  return 0;
}

int ProductKernel::NearestFactor(const double p[3]) const
{
  double normal[3], gradientNorm;
  int nearest;
  this->EvaluateVertex(p, normal, gradientNorm, nearest);
  return nearest;
}
}
