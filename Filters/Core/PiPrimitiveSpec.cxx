// SPDX-License-Identifier: BSD-3-Clause
#include "PiPrimitiveSpec.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace pisurf
{
namespace
{
struct TypeNames
{
  const char* Key;
  const char* Label;
};
const TypeNames Names[] = {
  { "sphere", "Sphere" },
  { "ellipsoid", "Ellipsoid" },
  { "superellipsoid", "Superellipsoid" },
  { "torus", "Torus" },
  { "plane", "Plane" },
  { "cylinder", "Cylinder" },
  { "cone", "Cone" },
  { "hyperboloid1", "Hyperboloid1" },
  { "hyperboloid2", "Hyperboloid2" },
  { "paraboloid", "Paraboloid" },
  { "hyperbolic_paraboloid", "HyperbolicParaboloid" },
  { "polynomial", "Polynomial" },
};

constexpr double Pi = 3.14159265358979323846;

// No off-diagonal entry: each local axis is a world axis (scaled, translated).
bool IsDiagonal(const double A[3][3])
{
  return A[0][1] == 0 && A[0][2] == 0 && A[1][0] == 0 && A[1][2] == 0 && A[2][0] == 0 &&
    A[2][1] == 0;
}

bool Finite3(const double v[3])
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// |v| without overflow or underflow for extreme but finite components.
double Norm(const double v[3])
{
  const double m = std::max({ std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2]) });
  if (m == 0.0 || !std::isfinite(m))
  {
    return m;
  }
  const double x = v[0] / m, y = v[1] / m, z = v[2] / m;
  return m * std::sqrt(x * x + y * y + z * z);
}

// v / |v|, computed as (v / max|v_i|) / |v / max|v_i||, so that it never overflows.
void Unit(const double v[3], double u[3])
{
  const double m = std::max({ std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2]) });
  const double s[3] = { v[0] / m, v[1] / m, v[2] / m };
  const double n = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (int i = 0; i < 3; ++i)
  {
    u[i] = s[i] / n;
  }
}

Polynomial3 Var(int a)
{
  return Polynomial3::Variable(a);
}
Polynomial3 Const(double c)
{
  return Polynomial3::Constant(c);
}
Polynomial3 Sq(int a, double s)
{ // (var/s)^2
  return Var(a).Pow(2).Scaled(1.0 / (s * s));
}

// Rotation taking the unit vector a onto +z (the minimal one), so R·a = (0,0,1).
void AlignToZ(const double axis[3], double R[3][3])
{
  double a[3];
  Unit(axis, a);
  // Rotation about k = a × z by the angle between a and z.
  const double k[3] = { a[1], -a[0], 0.0 };
  const double s = Norm(k);
  const double c = a[2];
  if (s < 1e-15)
  {
    // Parallel or anti-parallel: identity or a half turn about x.
    const double sign = c > 0 ? 1.0 : -1.0;
    const double I[3][3] = { { 1, 0, 0 }, { 0, sign, 0 }, { 0, 0, sign } };
    std::copy(&I[0][0], &I[0][0] + 9, &R[0][0]);
    return;
  }
  RotationMatrix(k, std::atan2(s, c) * 180.0 / Pi, R);
}

bool Positive(double v, const char* what, std::string& error)
{
  if (!std::isfinite(v) || v <= 0.0)
  {
    error = std::string(what) + " must be a positive finite number";
    return false;
  }
  return true;
}
}

const char* TypeKey(PrimitiveType t)
{
  return Names[static_cast<int>(t)].Key;
}

const char* TypeLabel(PrimitiveType t)
{
  return Names[static_cast<int>(t)].Label;
}

bool TypeFromString(const std::string& s, PrimitiveType& t)
{
  for (int i = 0; i < static_cast<int>(PrimitiveType::NumberOfTypes); ++i)
  {
    if (s == Names[i].Key || s == Names[i].Label)
    {
      t = static_cast<PrimitiveType>(i);
      return true;
    }
  }
  return false;
}

void RotationMatrix(const double axis[3], double angleDeg, double R[3][3])
{
  double u[3];
  Unit(axis, u);
  const double x = u[0], y = u[1], z = u[2];
  const double th = angleDeg * Pi / 180.0;
  const double c = std::cos(th), s = std::sin(th), t = 1.0 - c;
  R[0][0] = t * x * x + c;
  R[0][1] = t * x * y - s * z;
  R[0][2] = t * x * z + s * y;
  R[1][0] = t * x * y + s * z;
  R[1][1] = t * y * y + c;
  R[1][2] = t * y * z - s * x;
  R[2][0] = t * x * z - s * y;
  R[2][1] = t * y * z + s * x;
  R[2][2] = t * z * z + c;
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

void PolynomialFactor::EvaluateStar(const double p[3], double h, double values[7], double g[3]) const
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
    this->HasWorld = this->World.GetDegree() >= 0 && this->World.IsFinite() &&
      this->WorldMagnitude.IsFinite();
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
void AddClassSums(const double negatives[8], const double positives[8], unsigned classes,
  V4 lo[2], V4 hi[2])
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
  auto widen = [rounding](double l, double u) {
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

void PolynomialFactor::IntersectNatural(const double box[6], Interval& whole, Interval* octants) const
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

bool OrientationMatrix(const PrimitiveSpec& s, double R[3][3], std::string& error)
{
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      R[i][j] = i == j ? 1.0 : 0.0;
    }
  }
  if (s.Orient == Orientation::Axis)
  {
    if (!Finite3(s.Axis) || Norm(s.Axis) == 0.0)
    {
      error = "axis must be a non-zero vector of finite numbers";
      return false;
    }
    AlignToZ(s.Axis, R);
  }
  else if (s.Orient == Orientation::Rotation)
  {
    if (!Finite3(s.RotationAxis) || Norm(s.RotationAxis) == 0.0)
    {
      error = "rotation axis must be a non-zero vector of finite numbers";
      return false;
    }
    if (!std::isfinite(s.RotationAngle))
    {
      error = "rotation angle must be a finite number";
      return false;
    }
    double Rot[3][3];
    RotationMatrix(s.RotationAxis, s.RotationAngle, Rot);
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        R[i][j] = Rot[j][i]; // inverse of a rotation is its transpose
      }
    }
  }
  return true;
}

namespace
{
// A polynomial written about a point other than the origin (the cup's handle,
// ((x − 2.2)² + (z + 1)² + y² + 0.49)² − 2((x − 2.2)² + (z + 1)²)) expands to many more
// terms than about that point (35 instead of 10), and every evaluation pays for each.
// Per axis, the shift σ that removes the pure x^(m−1) term (m the highest power of x,
// present alone) centres it: σ = −c(m−1)/(m·c(m)). The expression as written is then
// expanded again in q + σ (ExpandShifted: shifts that cancel symbolically cancel
// exactly), and that form is kept if it has fewer terms.
void CentreExpression(const ExpressionNode& tree, Polynomial3& p, double shift[3])
{
  double sigma[3] = { 0, 0, 0 };
  bool any = false;
  for (int a = 0; a < 3; ++a)
  {
    const int m = p.GetAxisDegree(a);
    if (m < 2)
    {
      continue;
    }
    int top[3] = { 0, 0, 0 }, next[3] = { 0, 0, 0 };
    top[a] = m;
    next[a] = m - 1;
    const double cm = p.GetCoefficient(top[0], top[1], top[2]);
    const double cn = p.GetCoefficient(next[0], next[1], next[2]);
    const double s = cm != 0.0 ? -cn / (m * cm) : 0.0;
    if (s != 0.0 && std::isfinite(s))
    {
      sigma[a] = s;
      any = true;
    }
  }
  Polynomial3 centred;
  if (!any || !ExpandShifted(tree, sigma, centred) ||
    centred.GetTerms().size() >= p.GetTerms().size())
  {
    return;
  }
  p = centred;
  std::copy(sigma, sigma + 3, shift);
}
}

bool BuildFactor(const PrimitiveSpec& s, const ParameterMap& parameters,
  PolynomialFactor& factor, std::string& error)
{
  const int type = static_cast<int>(s.Type);
  if (type < 0 || type >= static_cast<int>(PrimitiveType::NumberOfTypes))
  {
    error = "unknown primitive type";
    return false;
  }
  if (!Finite3(s.Center))
  {
    error = "center must be three finite numbers";
    return false;
  }
  if (!std::isfinite(s.Scale) || s.Scale == 0.0)
  {
    error = "scale must be a non-zero finite number";
    return false;
  }

  // Orientation: local = R·(p − center).
  double R[3][3];
  if (!OrientationMatrix(s, R, error))
  {
    return false;
  }

  auto radii = [&](int n) {
    static const char* names[3] = { "radii[0]", "radii[1]", "radii[2]" };
    for (int i = 0; i < n; ++i)
    {
      if (!Positive(s.Radii[i], names[i], error))
      {
        return false;
      }
    }
    return true;
  };

  Polynomial3 p;
  std::shared_ptr<const ExpressionNode> natural;
  double shift[3] = { 0, 0, 0 }; // polynomials: the expression's variables are q + shift
  double half[3] = { -1, -1, -1 }; // local half extents; negative: unbounded
  switch (s.Type)
  {
    case PrimitiveType::Sphere:
      if (!Positive(s.Radius, "radius", error))
        return false;
      p = Var(0).Pow(2) + Var(1).Pow(2) + Var(2).Pow(2) - Const(s.Radius * s.Radius);
      half[0] = half[1] = half[2] = s.Radius;
      break;
    case PrimitiveType::Ellipsoid:
      if (!radii(3))
        return false;
      p = Sq(0, s.Radii[0]) + Sq(1, s.Radii[1]) + Sq(2, s.Radii[2]) - Const(1);
      std::copy(s.Radii, s.Radii + 3, half);
      break;
    case PrimitiveType::Superellipsoid:
      if (!radii(3))
        return false;
      if (s.Exponent < 2 || s.Exponent % 2 != 0 || s.Exponent > MaxDegree)
      {
        error = "exponent must be an even integer from 2 to " + std::to_string(MaxDegree) +
          " (got " + std::to_string(s.Exponent) + ")";
        return false;
      }
      p = Var(0).Scaled(1.0 / s.Radii[0]).Pow(s.Exponent) +
        Var(1).Scaled(1.0 / s.Radii[1]).Pow(s.Exponent) +
        Var(2).Scaled(1.0 / s.Radii[2]).Pow(s.Exponent) - Const(1);
      std::copy(s.Radii, s.Radii + 3, half);
      break;
    case PrimitiveType::Torus:
    {
      if (!Positive(s.MajorRadius, "major_radius", error) ||
        !Positive(s.MinorRadius, "minor_radius", error))
        return false;
      const double R2 = s.MajorRadius * s.MajorRadius, r2 = s.MinorRadius * s.MinorRadius;
      const Polynomial3 uv = Var(0).Pow(2) + Var(1).Pow(2);
      p = (uv + Var(2).Pow(2) + Const(R2 - r2)).Pow(2) - uv.Scaled(4.0 * R2);
      half[0] = half[1] = s.MajorRadius + s.MinorRadius;
      half[2] = s.MinorRadius;
      break;
    }
    case PrimitiveType::Plane:
    {
      if (!Finite3(s.Normal) || Norm(s.Normal) == 0.0)
      {
        error = "normal must be a non-zero vector of finite numbers";
        return false;
      }
      double n[3];
      Unit(s.Normal, n);
      p = Var(0).Scaled(n[0]) + Var(1).Scaled(n[1]) + Var(2).Scaled(n[2]);
      break;
    }
    case PrimitiveType::Cylinder:
      if (!Positive(s.Radius, "radius", error))
        return false;
      p = Var(0).Pow(2) + Var(1).Pow(2) - Const(s.Radius * s.Radius);
      break;
    case PrimitiveType::Cone:
    {
      if (!std::isfinite(s.Angle) || s.Angle <= 0.0 || s.Angle >= 90.0)
      {
        error = "angle must be a half-angle in degrees strictly between 0 and 90";
        return false;
      }
      const double t = std::tan(s.Angle * Pi / 180.0);
      p = Var(0).Pow(2) + Var(1).Pow(2) - Var(2).Pow(2).Scaled(t * t);
      break;
    }
    case PrimitiveType::Hyperboloid1:
      if (!radii(3))
        return false;
      p = Sq(0, s.Radii[0]) + Sq(1, s.Radii[1]) - Sq(2, s.Radii[2]) - Const(1);
      break;
    case PrimitiveType::Hyperboloid2:
      if (!radii(3))
        return false;
      p = Sq(2, s.Radii[2]) - Sq(0, s.Radii[0]) - Sq(1, s.Radii[1]) - Const(1);
      break;
    case PrimitiveType::Paraboloid:
      if (!radii(2))
        return false;
      p = Sq(0, s.Radii[0]) + Sq(1, s.Radii[1]) - Var(2);
      break;
    case PrimitiveType::HyperbolicParaboloid:
      if (!radii(2))
        return false;
      p = Sq(0, s.Radii[0]) - Sq(1, s.Radii[1]) - Var(2);
      break;
    case PrimitiveType::Polynomial:
    {
      std::string why;
      if (!ParseExpression(s.Expression, parameters, p, why, &natural))
      {
        error = "expression: " + why;
        return false;
      }
      CentreExpression(*natural, p, shift);
      break;
    }
    default:
      error = "unknown primitive type";
      return false;
  }
  p = p.Scaled(s.Negate ? -s.Scale : s.Scale);
  if (!p.IsFinite())
  {
    error = "the parameters (with the scale) overflow the polynomial's coefficients";
    return false;
  }

  factor = PolynomialFactor();
  factor.Poly = p;
  factor.Natural = natural;
  factor.NaturalSingleUse = natural && IsSingleUse(*natural);
  factor.NaturalScale = s.Negate ? -s.Scale : s.Scale;
  std::copy(&R[0][0], &R[0][0] + 9, &factor.A[0][0]);
  for (int i = 0; i < 3; ++i)
  {
    factor.B[i] = -(R[i][0] * s.Center[0] + R[i][1] * s.Center[1] + R[i][2] * s.Center[2]);
    // A centred expression: its local coordinates are the written ones minus the shift.
    if (shift[i] != 0.0)
    {
      factor.B[i] -= shift[i];
      factor.NaturalShift[i] = shift[i];
    }
  }
  if (half[0] >= 0.0)
  {
    // World box of the local box: p = center + Rᵀ·q, so each world half extent is
    // Σ_j |R[j][i]|·half[j].
    factor.Bounded = true;
    for (int i = 0; i < 3; ++i)
    {
      double h = 0.0;
      for (int j = 0; j < 3; ++j)
      {
        h += std::fabs(R[j][i]) * half[j];
      }
      factor.Bounds[2 * i] = s.Center[i] - h;
      factor.Bounds[2 * i + 1] = s.Center[i] + h;
    }
  }
  return true;
}
}
