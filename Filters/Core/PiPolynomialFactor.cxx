// SPDX-License-Identifier: BSD-3-Clause
#include "PiPolynomialFactor.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace pisurf
{
namespace
{
// No off-diagonal entry: each local axis is a world axis (scaled, translated).
bool IsDiagonal(const double A[3][3])
{
  return A[0][1] == 0 && A[0][2] == 0 && A[1][0] == 0 && A[1][2] == 0 && A[2][0] == 0 &&
    A[2][1] == 0;
}
}

double PolynomialFactor::EvaluateWithGradient(const double p[3], double g[3]) const
{
  double q[3], gl[3];
  if (this->Diagonal)
  {
    // (ToLocal's and the transposed product's terms without the zeros of A)
    this->ToLocalDiagonal(p, q);
    const double v = this->Poly.EvaluateWithGradient(q, gl);
    for (int j = 0; j < 3; ++j)
    {
      g[j] = this->A[j][j] * gl[j];
    }
    return v;
  }
  this->ToLocal(p, q);
  const double v = this->Poly.EvaluateWithGradient(q, gl);
  for (int j = 0; j < 3; ++j)
  {
    g[j] = this->A[0][j] * gl[0] + this->A[1][j] * gl[1] + this->A[2][j] * gl[2];
  }
  return v;
}

void PolynomialFactor::EvaluateStar(
  const double p[3], double h, double values[7], double g[3]) const
{
  const double(*A)[3] = this->A;
  if (IsDiagonal(A))
  {
    // p ± h·e_a is q ± h·A_aa·e_a in the local frame.
    double q[3], gl[3];
    this->ToLocal(p, q);
    const double step[3] = { h * A[0][0], h * A[1][1], h * A[2][2] };
    this->Poly.EvaluateStar(q, step, values, gl);
    for (int a = 0; a < 3; ++a)
    {
      g[a] = A[a][a] * gl[a];
    }
    return;
  }
  values[0] = this->EvaluateWithGradient(p, g);
  for (int a = 0; a < 3; ++a)
  {
    for (int side = 0; side < 2; ++side)
    {
      double r[3] = { p[0], p[1], p[2] };
      r[a] += side ? h : -h;
      values[1 + 2 * a + side] = this->Evaluate(r);
    }
  }
}

void PolynomialFactor::LocalBox(const double box[6], Interval local[3]) const
{
  // The local box of the affine image: centre mapped, half extents through |A|.
  for (int i = 0; i < 3; ++i)
  {
    double c = this->B[i], h = 0.0;
    for (int j = 0; j < 3; ++j)
    {
      c += this->A[i][j] * 0.5 * (box[2 * j] + box[2 * j + 1]);
      h += std::fabs(this->A[i][j]) * 0.5 * (box[2 * j + 1] - box[2 * j]);
    }
    h += 1e-15 * (std::fabs(c) + h);
    local[i] = { c - h, c + h };
  }
}

Interval PolynomialFactor::NaturalInterval(const Interval local[3], double magnitude) const
{
  // The expression as written encloses the exact value; the expanded polynomial's
  // computed values may differ from it by their rounding (terms that cancel), so the
  // natural enclosure is widened by that.
  // (The expression's variables are the local coordinates plus NaturalShift, the
  // centring of BuildFactor: the box shifted back, outward.)
  Interval written[3];
  for (int a = 0; a < 3; ++a)
  {
    written[a] = local[a];
    const double sh = this->NaturalShift[a];
    if (sh != 0.0)
    {
      const double lo = local[a].Lo + sh, hi = local[a].Hi + sh;
      written[a] = { lo - (std::fabs(lo) * DBL_EPSILON + DBL_MIN),
        hi + (std::fabs(hi) * DBL_EPSILON + DBL_MIN) };
    }
  }
  const Interval n = pisurf::EvaluateInterval(*this->Natural, written);
  const double a = this->NaturalScale * n.Lo, b = this->NaturalScale * n.Hi;
  const double slack =
    std::max(1e-12 * (std::fabs(a) + std::fabs(b)), this->Poly.RoundingBound(magnitude)) + 1e-300;
  return { std::min(a, b) - slack, std::max(a, b) + slack };
}

Interval PolynomialFactor::EvaluateInterval(const double box[6]) const
{
  Interval local[3];
  this->LocalBox(box, local);
  double magnitude = 0.0;
  Interval naive = this->Poly.EvaluateInterval(local, &magnitude);
  if (this->Natural)
  {
    const Interval n = this->NaturalInterval(local, magnitude);
    naive.Lo = std::max(naive.Lo, n.Lo);
    naive.Hi = std::min(naive.Hi, n.Hi);
  }
  if (!this->HasGradient)
  {
    return naive;
  }
  double centre[3];
  for (int i = 0; i < 3; ++i)
  {
    centre[i] = 0.5 * (local[i].Lo + local[i].Hi);
  }
  const double fc = this->Poly.Evaluate(centre);
  double lo = fc, hi = fc;
  for (int i = 0; i < 3; ++i)
  {
    const Interval g = this->Gradient[i].EvaluateInterval(local);
    const double h = 0.5 * (local[i].Hi - local[i].Lo);
    const double m = std::max(std::fabs(g.Lo), std::fabs(g.Hi)) * h;
    lo -= m;
    hi += m;
  }
  const double slack = 1e-12 * (std::fabs(lo) + std::fabs(hi)) + 1e-300;
  return { std::max(naive.Lo, lo - slack), std::min(naive.Hi, hi + slack) };
}

void PolynomialFactor::PrepareIntervals()
{
  for (int i = 0; i < 3; ++i)
  {
    this->Gradient[i] = this->Poly.Derivative(i);
  }
  this->HasGradient = true;
  this->Diagonal = IsDiagonal(this->A);
  this->HasWorld = false;
  if (this->Poly.GetDegree() >= 0 && this->Poly.GetDegree() <= TaylorMaxDegree)
  {
    double absA[3][3], absB[3];
    for (int i = 0; i < 3; ++i)
    {
      absB[i] = std::fabs(this->B[i]);
      for (int j = 0; j < 3; ++j)
      {
        absA[i][j] = std::fabs(this->A[i][j]);
      }
    }
    this->World = this->Poly.Compose(this->A, this->B);
    this->WorldMagnitude = this->Poly.Absolute().Compose(absA, absB);
    this->HasWorld =
      this->World.GetDegree() >= 0 && this->World.IsFinite() && this->WorldMagnitude.IsFinite();
  }
}

namespace
{
typedef double V4 __attribute__((vector_size(32)));
// OctantSigns[odd][h][l]: −1 where octant o = 4h + l gives u^α a negative sign, α's odd
// powers being the bits of `odd` (the lower half of axis a where bit a of o is clear).
struct OctantSignTable
{
  V4 Signs[8][2];
  OctantSignTable()
  {
    for (int odd = 0; odd < 8; ++odd)
    {
      for (int o = 0; o < 8; ++o)
      {
        this->Signs[odd][o / 4][o % 4] = __builtin_parity(odd & ~o) ? -1.0 : 1.0;
      }
    }
  }
};
const OctantSignTable OctantSignsTable;
const V4 (&OctantSigns)[8][2] = OctantSignsTable.Signs;

// EvaluateTaylor's octant sums from its class sums: each octant (lanes o = 0..3 and
// 4..7) adds, for every class c of odd powers present (bit c of `classes`), the class's
// negative and positive parts where its terms keep their sign there (σ = +1), else
// minus its positive and negative parts.
void AddClassSums(
  const double negatives[8], const double positives[8], unsigned classes, V4 lo[2], V4 hi[2])
{
  const V4 zero = { 0.0, 0.0, 0.0, 0.0 };
  for (int c = 0; c < 8; ++c)
  {
    if (!((classes >> c) & 1u))
    {
      continue;
    }
    const V4 negative = zero + negatives[c], positive = zero + positives[c];
    for (int h4 = 0; h4 < 2; ++h4)
    {
      const auto up = OctantSigns[c][h4] > zero; // σ = +1 in these lanes
      lo[h4] += up ? negative : -positive;
      hi[h4] += up ? positive : -negative;
    }
  }
}
}

namespace
{
// EvaluateTaylor's expansion centre c and half-widths h of a box (c ± h covers the box
// despite the rounding of c and h), and |c| + h.
void TaylorFrame(const double box[6], double c[3], double h[3], double reach[3])
{
  for (int a = 0; a < 3; ++a)
  {
    c[a] = 0.5 * (box[2 * a] + box[2 * a + 1]);
    h[a] = std::max(box[2 * a + 1] - c[a], c[a] - box[2 * a]) * (1.0 + 4.0 * DBL_EPSILON);
    reach[a] = std::fabs(c[a]) + h[a];
  }
}
}

bool PolynomialFactor::EvaluateTaylor(const double box[6], Interval& whole, Interval* octants,
  bool natural, Interval* derivatives, int axis) const
{
  if (!this->HasWorld)
  {
    return false;
  }
  constexpr int M = TaylorMaxDegree + 1;
  double b[M * M * M];
  double c[3], h[3], reach[3];
  TaylorFrame(box, c, h, reach);
  if (derivatives && !(octants && axis >= 0 && axis <= 2 && h[axis] > 0.0))
  {
    derivatives = nullptr;
  }
  double derivativeScale = derivatives ? 1.0 / h[axis] : 0.0; // world: d/dx = d/du / h
  int n;
  if (this->Diagonal && this->Poly.IsEvenQuartic())
  {
    // World(c + h∘u) = Poly(A·c + B + (A·h)∘u) for a diagonal A: the local polynomial's
    // own expansion (a quadric of squares: a few dozen operations instead of the dense
    // quartic's shifts), about the local centre, its rounding covered by widening the
    // local half-widths (the sign of A keeps each octant's orientation). The octants
    // split at the rounded local centre, within 2ε of the exact image of c: P changes
    // by at most 2ε·n·(its magnitude) across that sliver, far inside the rounding
    // bound added below.
    double lc[3], lh[3];
    for (int a = 0; a < 3; ++a)
    {
      lc[a] = this->A[a][a] * c[a] + this->B[a];
      const double width = this->A[a][a] * h[a];
      const double slack = 4.0 * DBL_EPSILON * (std::fabs(lc[a]) + std::fabs(width)) + DBL_MIN;
      lh[a] = width + (width < 0 ? -slack : slack);
    }
    n = this->Poly.ExpandAbout(lc, lh, b);
    if (derivatives)
    {
      // d/dx_axis = (A_aa / lh_a)·d/du_axis, positive (lh keeps the sign of A)
      derivativeScale = this->A[axis][axis] / lh[axis];
    }
  }
  else
  {
    n = this->World.ExpandAbout(c, h, b);
  }
  if (n < 0)
  {
    return false;
  }
  const int m = n + 1;
  // Every term's magnitude over the box, in our evaluations (local form: |q| <= |A||p| +
  // |B|) and in the expansions (World and its shift): at most WorldMagnitude(|c| + h).
  const double magnitude = this->WorldMagnitude.Evaluate(reach) * (1.0 + 1e-12);
  const double rounding =
    this->Poly.RoundingBound(magnitude) + this->World.RoundingBound(magnitude) + 1e-300;
  // The pure powers of one axis with degree <= 2 (b₁u + b₂u²: most of a quadric) are
  // bounded exactly on [−1, 1] and on each half, by their ends and vertex; every other
  // term by its own range.
  const int stride[3] = { m * m, m, 1 };
  bool exact[3];
  double axisLo[3][3], axisHi[3][3]; // per axis: on [−1, 0], [0, 1], [−1, 1]
  for (int a = 0; a < 3; ++a)
  {
    exact[a] = true;
    for (int l = 3; l <= n; ++l)
    {
      exact[a] = exact[a] && b[l * stride[a]] == 0.0;
    }
    const double g = n >= 1 ? b[stride[a]] : 0.0, q = n >= 2 ? b[2 * stride[a]] : 0.0;
    const double ends[3][2] = { { -1.0, 0.0 }, { 0.0, 1.0 }, { -1.0, 1.0 } };
    for (int part = 0; part < 3; ++part)
    {
      const double s = ends[part][0], t = ends[part][1];
      const double vs = g * s + q * s * s, vt = g * t + q * t * t;
      axisLo[a][part] = std::min(vs, vt);
      axisHi[a][part] = std::max(vs, vt);
      if (q != 0.0)
      {
        const double v = -g / (2.0 * q);
        if (v > s && v < t)
        {
          const double w = g * v + q * v * v;
          axisLo[a][part] = std::min(axisLo[a][part], w);
          axisHi[a][part] = std::max(axisHi[a][part], w);
        }
      }
    }
  }
  double lo = b[0], hi = b[0];
  double olo[8], ohi[8];
  for (int a = 0; a < 3; ++a)
  {
    if (exact[a])
    {
      lo += axisLo[a][2];
      hi += axisHi[a][2];
    }
  }
  for (int o = 0; o < 8; ++o)
  {
    olo[o] = ohi[o] = b[0];
    for (int a = 0; a < 3; ++a)
    {
      if (exact[a])
      {
        olo[o] += axisLo[a][(o >> a) & 1];
        ohi[o] += axisHi[a][(o >> a) & 1];
      }
    }
  }
  // The octants' sums: in octant o a term b_α·u^α ranges over b_α·σ·[0, 1], σ = ±1 set
  // by the odd powers of α (its class, 0..7) and the octant's halves. So the terms are
  // summed per class, their negative parts N and positive parts P, and each octant then
  // adds N and P (σ = +1) or −P and −N (σ = −1) of each class: eight sums per
  // coefficient become two. (A reordering of the same sums: its rounding, like the
  // lanes' before, is within the expansion's rounding bound added below.)
  const V4 zero = { 0.0, 0.0, 0.0, 0.0 };
  V4 octLo[2], octHi[2];
  for (int o = 0; o < 8; ++o)
  {
    octLo[o / 4][o % 4] = olo[o];
    octHi[o / 4][o % 4] = ohi[o];
  }
  double classLo[8] = { 0, 0, 0, 0, 0, 0, 0, 0 }, classHi[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
  unsigned classes = 0; // the classes with a term
  for (int i = 0; i <= n; ++i)
  {
    for (int j = 0; i + j <= n; ++j)
    {
      for (int k = (i + j == 0 ? 1 : 0); i + j + k <= n; ++k)
      {
        const double v = b[(i * m + j) * m + k];
        if (v == 0.0)
        {
          continue;
        }
        // A pure power of one axis already bounded exactly?
        const int axes = (i > 0) + (j > 0) + (k > 0);
        if (axes == 1)
        {
          const int a = i > 0 ? 0 : j > 0 ? 1 : 2;
          if (exact[a])
          {
            continue;
          }
        }
        if (((i | j | k) & 1) == 0)
        {
          // u^α ∈ [0, 1] everywhere, in every octant.
          lo += std::min(v, 0.0);
          hi += std::max(v, 0.0);
          classLo[0] += std::min(v, 0.0);
          classHi[0] += std::max(v, 0.0);
          classes |= 1u;
          continue;
        }
        lo -= std::fabs(v);
        hi += std::fabs(v);
        // In octant o, u^α has the sign Π (−1)^α_a over the lower halves.
        const int odd = (i & 1) | (j & 1) << 1 | (k & 1) << 2;
        classLo[odd] += std::min(v, 0.0);
        classHi[odd] += std::max(v, 0.0);
        classes |= 1u << odd;
      }
    }
  }
  if (octants)
  {
    AddClassSums(classLo, classHi, classes, octLo, octHi);
  }
  for (int o = 0; o < 8; ++o)
  {
    olo[o] = octLo[o / 4][o % 4];
    ohi[o] = octHi[o / 4][o % 4];
  }
  auto widen = [rounding](double l, double u)
  {
    const double slack = std::max(1e-12 * (std::fabs(l) + std::fabs(u)), rounding);
    return Interval{ l - slack, u + slack };
  };
  if (derivatives)
  {
    // ∂/∂u_axis = Σ α_axis·b_α·u^β (β = α − e_axis) over each octant, as the values
    // above: u^β ranges over [0, 1] with the octant's sign where a power of β is odd.
    // Widened by n² times the expansion's rounding (Σ α_axis·|δb_α| <= n·Σ|δb_α|) and
    // 1e-12 of the terms, then scaled to d/dx_axis.
    const int stride[3] = { m * m, m, 1 };
    const double linear = n >= 1 ? b[stride[axis]] : 0.0;
    V4 dLo[2] = { zero + linear, zero + linear }, dHi[2] = { zero + linear, zero + linear };
    double terms = std::fabs(linear);
    // (Summed per class of β's odd powers, as the values above.)
    double dClassLo[8] = { 0, 0, 0, 0, 0, 0, 0, 0 }, dClassHi[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
    unsigned dClasses = 0;
    for (int i = 0; i <= n; ++i)
    {
      for (int j = 0; i + j <= n; ++j)
      {
        for (int k = 0; i + j + k <= n; ++k)
        {
          const int power = axis == 0 ? i : axis == 1 ? j : k;
          const double v = b[(i * m + j) * m + k];
          if (power == 0 || v == 0.0 || i + j + k == 1)
          {
            continue;
          }
          const double coefficient = power * v;
          terms += std::fabs(coefficient);
          int beta[3] = { i, j, k };
          --beta[axis];
          const int odd = (beta[0] & 1) | (beta[1] & 1) << 1 | (beta[2] & 1) << 2;
          dClassLo[odd] += std::min(coefficient, 0.0);
          dClassHi[odd] += std::max(coefficient, 0.0);
          dClasses |= 1u << odd;
        }
      }
    }
    AddClassSums(dClassLo, dClassHi, dClasses, dLo, dHi);
    const double slack = double(n) * n * rounding + 1e-12 * terms;
    for (int o = 0; o < 8; ++o)
    {
      derivatives[o] = { (dLo[o / 4][o % 4] - slack) * derivativeScale,
        (dHi[o / 4][o % 4] + slack) * derivativeScale };
    }
  }
  whole = widen(lo, hi);
  if (octants)
  {
    for (int o = 0; o < 8; ++o)
    {
      octants[o] = widen(olo[o], ohi[o]);
    }
  }
  if (natural && this->HasNaturalForm())
  {
    this->IntersectNatural(box, whole, octants);
  }
  return true;
}

void PolynomialFactor::IntersectNatural(
  const double box[6], Interval& whole, Interval* octants) const
{
  // Above degree 2 the expression as written can be tighter (the table top's
  // (8z+5)^6, whose terms the expansion bounds one by one): intersect with it, and on
  // the octants too where it was tighter on the whole box. (The magnitude is
  // EvaluateTaylor's, from the same box.)
  double c[3], h[3], reach[3];
  TaylorFrame(box, c, h, reach);
  const double magnitude = this->WorldMagnitude.Evaluate(reach) * (1.0 + 1e-12);
  Interval local[3];
  this->LocalBox(box, local);
  const Interval natural = this->NaturalInterval(local, magnitude);
  if (natural.Hi - natural.Lo < whole.Hi - whole.Lo)
  {
    whole.Lo = std::max(whole.Lo, natural.Lo);
    whole.Hi = std::min(whole.Hi, natural.Hi);
    for (int o = 0; octants && o < 8; ++o)
    {
      double sub[6];
      OctantBox(box, o, sub);
      this->LocalBox(sub, local);
      const Interval part = this->NaturalInterval(local, magnitude);
      octants[o].Lo = std::max(octants[o].Lo, part.Lo);
      octants[o].Hi = std::min(octants[o].Hi, part.Hi);
    }
  }
}

std::vector<double> PolynomialFactor::RestrictToLine(const double o[3], const double d[3]) const
{
  std::vector<double> r(std::max(this->Poly.GetDegree(), 0) + 1);
  this->RestrictToLine(o, d, r.data());
  return r;
}

void PolynomialFactor::RestrictToLine(const double o[3], const double d[3], double* out) const
{
  double lo[3], ld[3];
  this->ToLocal(o, lo);
  for (int i = 0; i < 3; ++i)
  {
    ld[i] = this->A[i][0] * d[0] + this->A[i][1] * d[1] + this->A[i][2] * d[2];
  }
  this->Poly.RestrictToLine(lo, ld, out);
}

Polynomial3 PolynomialFactor::WorldPolynomial() const
{
  return this->Poly.Compose(this->A, this->B);
}
}
