// SPDX-License-Identifier: BSD-3-Clause
// ProductKernel restricted to lines: exact univariate coefficients along a line or a
// grid axis, and their evaluation (one point, with slope, a row of points, logarithms).
#include "PiProductKernelInternals.h"

namespace pisurf
{
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

double ProductKernel::EvaluateRestricted(
  const double* coefficients, double t, const double p[3]) const
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
        case 0:
          QuadricGroupOnAxis<0>(scale, shift, q, p, c0, c1, c2);
          break;
        case 1:
          QuadricGroupOnAxis<1>(scale, shift, q, p, c0, c1, c2);
          break;
        default:
          QuadricGroupOnAxis<2>(scale, shift, q, p, c0, c1, c2);
          break;
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

void ProductKernel::EvaluateOnAxisLog(const double* coefficients, int axis, double x, double& value,
  int& productSign, double& logProduct, double& logSlope) const
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
static inline bool MultiplyWithSlope(const double* c, int n, double u, double scale, double bound,
  double inverse, double& product, double& derivative)
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
      if (!MultiplyWithSlope(coefficients, 3, scale[k] * x + shift[k], scale[k], bound, inverse,
            product, derivative))
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
    if (!MultiplyWithSlope(coefficients, n, pf.A[axis][axis] * x + pf.B[axis], pf.A[axis][axis],
          bound, inverse, product, derivative))
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
  auto pointAt = [&](int i, double p[3])
  {
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
        case 3:
          HornerGroup<3, Vectors>(acc, t, c, 3);
          break;
        case 5:
          HornerGroup<5, Vectors>(acc, t, c, 5);
          break;
        case 7:
          HornerGroup<7, Vectors>(acc, t, c, 7);
          break;
        default:
          HornerGroup<0, Vectors>(acc, t, c, terms);
          break;
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

}
