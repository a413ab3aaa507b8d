// SPDX-License-Identifier: BSD-3-Clause
// ProductKernel on boxes: interval sign of the product, box and octant classification
// with monotony proofs.
#include "PiProductKernelInternals.h"

namespace pisurf
{
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
    expanded[i] =
      f.EvaluateTaylor(box, whole[i], octant, false, derivativesKnown ? derivative : nullptr, axis);
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

}
