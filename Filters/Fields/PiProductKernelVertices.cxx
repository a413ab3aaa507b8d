// SPDX-License-Identifier: BSD-3-Clause
// ProductKernel at surface points: unit normal, |∇F| and nearest factor, one point or
// four lanes at a time, and the singularity probe (probe bounds, the regular-point
// shortcut, the six-probe star).
#include "PiProductKernelInternals.h"

namespace pisurf
{

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
    const double a = std::fabs(f), g0 = std::fabs(g[0]), g1 = std::fabs(g[1]), g2 = std::fabs(g[2]);
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
__attribute__((always_inline)) static inline void FinishPlainVertices(const V4* f, const V4 (*g)[3],
  size_t factors, int count, double (*normal)[3], double* gradientNorm, int* nearest)
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
void ProductKernel::EvaluateVertices(
  int count, const double (*p)[3], double (*normal)[3], double* gradientNorm, int* nearest) const
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
    auto keeps = [](double v, const double w[3])
    {
      const double a =
        std::max({ std::fabs(v), std::fabs(w[0]), std::fabs(w[1]), std::fabs(w[2]) });
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
// clone as functions of their own, the four-point path is slower than four single
// points; Documentation/benchmark-history.md has the timings.)
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
  const double U =
    (std::fabs(F) + largest + rounding * (absProduct + magnitude + 2.0 * r)) * (1.0 + 1e-10);
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
  auto onePointAtATime = [&]()
  {
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
      RegularFromBounds(
        product[j], tj, grownj, factors, this->Blending, gradientNorm[j], bounds.Probe, tolerance);
  }
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

}
