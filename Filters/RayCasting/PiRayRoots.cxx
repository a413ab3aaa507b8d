// SPDX-License-Identifier: BSD-3-Clause
#include "PiRayRoots.h"
#include "PiFloat.h"
#include "PiScaledInterval.h"

#include "PiPolynomial.h"
#include "PiProductKernel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pisurf
{

bool ProductDerivativeHasOneSign(const Interval* f, const Interval* df, size_t n,
  std::vector<ScaledInterval>& prefix, std::vector<ScaledInterval>& suffix)
{
  prefix.assign(n + 1, ScaledInterval());
  suffix.assign(n + 1, ScaledInterval());
  for (size_t i = 0; i < n; ++i)
  {
    prefix[i + 1] = prefix[i];
    prefix[i + 1].Multiply(f[i]);
  }
  for (size_t i = n; i > 0; --i)
  {
    suffix[i - 1] = suffix[i];
    suffix[i - 1].Multiply(f[i - 1]);
  }
  // Terms with their exponents; summed at the largest exponent.
  long top = std::numeric_limits<long>::min();
  for (size_t i = 0; i < n; ++i)
  {
    ScaledInterval t = prefix[i];
    t.Multiply(df[i]);
    t.Multiply({ suffix[i + 1].Lo, suffix[i + 1].Hi });
    t.E += suffix[i + 1].E;
    prefix[i] = t; // prefix[i] is not needed any more: reuse it for the term
    top = std::max(top, t.E);
  }
  double lo = 0.0, hi = 0.0;
  for (size_t i = 0; i < n; ++i)
  {
    const ScaledInterval& t = prefix[i];
    const long shift = std::max<long>(t.E - top, -2000);
    lo += pisurf::Ldexp(t.Lo, static_cast<int>(shift));
    hi += pisurf::Ldexp(t.Hi, static_cast<int>(shift));
  }
  const double slack = 1e-12 * (std::fabs(lo) + std::fabs(hi));
  return lo - slack > 0.0 || hi + slack < 0.0;
}

namespace
{
// The n + 1 coefficients q of p become those of s -> p(a + (b − a)s): the Taylor shift
// to a by repeated synthetic division, then the scaling by (b − a)^j. Degree N when
// N >= 0 (the loops unrolled: the same operations), else `degree`.
template <int N = -1>
inline void ShiftToUnit(double* q, int degree, double a, double b)
{
  const int n = N >= 0 ? N : degree;
  for (int i = 0; i < n; ++i)
  {
    for (int k = n - 1; k >= i; --k)
    {
      q[k] += a * q[k + 1];
    }
  }
  double h = 1.0;
  for (int j = 0; j <= n; ++j)
  {
    q[j] *= h;
    h *= (b - a);
  }
}

// Bernstein coefficients on [a, b] of a polynomial given by `count` ascending monomial
// coefficients in t, into `bern`; `q` is scratch of the same size.
void ToBernstein(const double* c, int count, double a, double b, double* q, double* bern)
{
  const int n = count - 1;
  // q(s) = p(a + (b − a)s).
  std::copy(c, c + count, q);
  ShiftToUnit(q, n, a, b);
  // Power basis to Bernstein: b_k = Σ_{j<=k} C(k, j) / C(n, j) q_j.
  for (int k = 0; k <= n; ++k)
  {
    double ckj = 1.0; // C(k, j)
    double cnj = 1.0; // C(n, j)
    double sum = 0.0;
    for (int j = 0; j <= k; ++j)
    {
      sum += ckj / cnj * q[j];
      ckj = ckj * (k - j) / (j + 1);
      cnj = cnj * (n - j) / (j + 1);
    }
    bern[k] = sum;
  }
}

Interval Hull(const double* b, int count)
{
  double lo = b[0], hi = b[0];
  for (int k = 1; k < count; ++k)
  {
    lo = std::min(lo, b[k]);
    hi = std::max(hi, b[k]);
  }
  const double slack = 1e-12 * (std::fabs(lo) + std::fabs(hi)) + 1e-300;
  return { lo - slack, hi + slack };
}

// De Casteljau at 1/2 for a count known at compile time: the same operations in the
// same order as Split, the coefficients held in registers instead of stored and
// reloaded at every step.
template <int N>
void SplitFixed(const double* b, double* left, double* right)
{
  double w[N];
  for (int k = 0; k < N; ++k)
  {
    w[k] = b[k];
  }
  // (fully unrolled: no loop branches at all)
#pragma GCC unroll 32
  for (int r = 0; r < N; ++r)
  {
    left[r] = w[0];
    right[N - 1 - r] = w[N - 1 - r];
#pragma GCC unroll 32
    for (int k = 0; k < N - 1 - r; ++k)
    {
      w[k] = 0.5 * (w[k] + w[k + 1]);
    }
  }
}

// De Casteljau at 1/2: the Bernstein coefficients of both halves.
void Split(const double* b, int count, double* left, double* right)
{
  switch (count)
  {
    // (the degrees of common products: quadrics and quartics, up to ten quadrics; the
    // unrolled loops also spare the branch predictor the general loop's varying trip
    // counts)
    case 3:
      return SplitFixed<3>(b, left, right);
    case 5:
      return SplitFixed<5>(b, left, right);
    case 7:
      return SplitFixed<7>(b, left, right);
    case 9:
      return SplitFixed<9>(b, left, right);
    case 11:
      return SplitFixed<11>(b, left, right);
    case 13:
      return SplitFixed<13>(b, left, right);
    case 15:
      return SplitFixed<15>(b, left, right);
    case 17:
      return SplitFixed<17>(b, left, right);
    case 19:
      return SplitFixed<19>(b, left, right);
    case 21:
      return SplitFixed<21>(b, left, right);
    default:
      break;
  }
  double w[MaxDegree + 1];
  std::copy(b, b + count, w);
  for (int r = 0; r < count; ++r)
  {
    left[r] = w[0];
    right[count - 1 - r] = w[count - 1 - r];
    for (int k = 0; k < count - 1 - r; ++k)
    {
      w[k] = 0.5 * (w[k] + w[k + 1]);
    }
  }
}

struct Piece
{
  double A, B;
  int Depth;
  size_t Offset; // of its factors' Bernstein coefficients in the pool
};

// Per-thread work buffers, reused from ray to ray.
struct Workspace
{
  std::vector<double> Pool; // the pieces' coefficients, a stack following the DFS
  std::vector<Piece> Stack;
  std::vector<Interval> F, DF;
  std::vector<ScaledInterval> Prefix, Suffix;
  std::vector<size_t> Offsets;
  double Scratch[MaxDegree + 1];
};

// The general path's buffers of this thread.
Workspace& GeneralWorkspace()
{
  thread_local Workspace workspace;
  return workspace;
}

class Solver
{
public:
  Solver(const double* coefficients, const int* counts, int factors, double r,
    const RayRootOptions& o, Workspace& w)
    : Coefficients(coefficients)
    , Counts(counts)
    , N(factors)
    , R(r)
    , Options(o)
    , W(w)
  {
    w.Offsets.resize(factors + 1);
    w.Offsets[0] = 0;
    for (int i = 0; i < factors; ++i)
    {
      w.Offsets[i + 1] = w.Offsets[i] + counts[i];
    }
    this->Total = w.Offsets[factors];
  }

  // sign(F)·ln(1 + |F|) at t, without overflow.
  double Compressed(double t) const
  {
    double m = 1.0;
    long e = 0;
    for (int i = 0; i < this->N; ++i)
    {
      const double v =
        EvaluateUnivariate(this->Coefficients + this->W.Offsets[i], this->Counts[i], t);
      if (v == 0.0)
      {
        m = 0.0;
        break;
      }
      int ex;
      m *= pisurf::Frexp(v, &ex);
      e += ex;
      int em;
      m = pisurf::Frexp(m, &em);
      e += em;
    }
    double F;
    if (m == 0.0)
    {
      F = -this->R;
    }
    else if (e <= -1000 && this->R == 0.0)
    {
      return std::copysign(std::numeric_limits<double>::denorm_min(), m); // tiny, signed
    }
    else if (e < 1000 && e > -1000)
    {
      F = pisurf::Ldexp(m, static_cast<int>(e)) - this->R;
    }
    else
    {
      // Beyond the double range the product dominates r (or r dominates it).
      if (e > 0)
      {
        const double logAbs = std::log(std::fabs(m)) + e * std::log(2.0);
        return std::copysign(logAbs, m);
      }
      F = -this->R;
    }
    return std::copysign(std::log1p(std::fabs(F)), F);
  }

  const double* Bernstein(const Piece& p, int i) const
  {
    return this->W.Pool.data() + p.Offset + this->W.Offsets[i];
  }

  // +1/−1: F has that sign on the whole piece; 0: it may vanish there.
  int Sign(const Piece& p) const
  {
    this->W.F.resize(this->N);
    for (int i = 0; i < this->N; ++i)
    {
      this->W.F[i] = Hull(this->Bernstein(p, i), this->Counts[i]);
    }
    return SignOfProductMinus(this->W.F, this->R);
  }

  // True if F' cannot vanish on the piece (so F is strictly monotone there). Uses the
  // factor enclosures Sign() left in W.F.
  bool Monotone(const Piece& p) const
  {
    const int n = this->N;
    std::vector<Interval>& f = this->W.F;
    std::vector<Interval>& df = this->W.DF;
    df.resize(n);
    for (int i = 0; i < n; ++i)
    {
      const double* b = this->Bernstein(p, i);
      const int count = this->Counts[i];
      if (count < 2)
      {
        df[i] = { 0.0, 0.0 };
        continue;
      }
      // p' in Bernstein form on [A, B]: (count − 1)(b_{k+1} − b_k)/(B − A).
      double* d = this->W.Scratch;
      for (int k = 0; k + 1 < count; ++k)
      {
        d[k] = (count - 1) * (b[k + 1] - b[k]) / (p.B - p.A);
      }
      df[i] = Hull(d, count - 1);
    }
    // F' = Σ_i p_i' Π_{j≠i} p_j of one sign?
    return ProductDerivativeHasOneSign(f.data(), df.data(), n, this->W.Prefix, this->W.Suffix);
  }

  // The single root of a monotone piece with a sign change.
  double Refine(double a, double b, double va, double vb) const
  {
    return BracketedRoot(
      [this](double t) { return this->Compressed(t); }, a, b, va, vb, this->Options.Tolerance, 0.0);
  }

  void Run(double t0, double t1, std::vector<RayRoot>& roots)
  {
    RootCluster cluster(roots, this->Options.Tolerance);
    this->Run(t0, t1, cluster, roots);
  }

  // The same, adding to a cluster the caller shares (the fast path hands pieces over).
  void Run(double t0, double t1, RootCluster& cluster, std::vector<RayRoot>& roots)
  {
    std::vector<double>& pool = this->W.Pool;
    std::vector<Piece>& stack = this->W.Stack;
    stack.clear();
    pool.resize(this->Total);
    for (int i = 0; i < this->N; ++i)
    {
      ToBernstein(this->Coefficients + this->W.Offsets[i], this->Counts[i], t0, t1, this->W.Scratch,
        pool.data() + this->W.Offsets[i]);
    }
    stack.push_back({ t0, t1, 0, 0 });
    while (!stack.empty())
    {
      const Piece p = stack.back();
      stack.pop_back();
      pool.resize(p.Offset + this->Total); // drop what finished subtrees used
      if (this->Sign(p) != 0)
      {
        continue; // no root in this piece
      }
      const double va = this->Compressed(p.A), vb = this->Compressed(p.B);
      const bool change = (va < 0 && vb > 0) || (va > 0 && vb < 0);
      if (this->Monotone(p))
      {
        if (change)
        {
          cluster.Add(this->Refine(p.A, p.B, va, vb), false, va, vb);
        }
        else if (va == 0.0 || vb == 0.0)
        {
          cluster.Add(va == 0.0 ? p.A : p.B, false, va, vb);
        }
        if (!this->Options.AllRoots && !roots.empty())
        {
          return;
        }
        continue;
      }
      if (p.B - p.A <= this->Options.Tolerance || p.Depth >= this->Options.MaximumDepth)
      {
        // F may vanish here and is not provably monotone: a root (tangent without a
        // sign change).
        cluster.Add(0.5 * (p.A + p.B), !change, va, vb);
        if (!this->Options.AllRoots)
        {
          return;
        }
        continue;
      }
      // Split; the right half goes below the left on the stack, so the left (smaller t)
      // is processed first. Their coefficients go after this piece's in the pool, the
      // right half's first: popping the left one truncates the pool above its own.
      const size_t right = p.Offset + this->Total, left = right + this->Total;
      pool.resize(left + this->Total);
      for (int i = 0; i < this->N; ++i)
      {
        const size_t o = this->W.Offsets[i];
        Split(pool.data() + p.Offset + o, this->Counts[i], pool.data() + left + o,
          pool.data() + right + o);
      }
      const double mid = 0.5 * (p.A + p.B);
      stack.push_back({ mid, p.B, p.Depth + 1, right });
      stack.push_back({ p.A, mid, p.Depth + 1, left });
    }
  }

private:
  const double* Coefficients;
  const int* Counts;
  int N;
  double R;
  RayRootOptions Options;
  Workspace& W;
  size_t Total = 0;
};

// The fast path for products of modest total degree: the product itself as one
// polynomial in the Bernstein basis of [t0, t1].
//
// Each factor's Bernstein coefficients are scaled by a power of two to a largest
// magnitude in [0.5, 1) (exact), the product's coefficients follow from those of the
// factors by a convolution of the binomially weighted forms (every product coefficient
// is a convex combination of products of factor coefficients, so the product's
// enclosure is never wider than the product of the factors' hulls the general path
// uses), and r is scaled by the same power of two. On a piece:
// - all coefficients of F beyond `slack` with one sign: no root (the convex-hull
//   property);
// - every coefficient clearly signed and exactly one sign variation: exactly one root,
//   a simple one (Descartes' rule of signs in the Bernstein basis);
// - otherwise the differences of consecutive coefficients (F' in Bernstein form) of one
//   sign: F monotone, as in the general path;
// - else the piece is split (de Casteljau at 1/2) down to the tolerance, where a piece
//   that still may hold a zero is a root (tangent without a sign change).
// The slack covers rounding: 1e-12 relative per factor as the general path's, r compared
// to 1e-9 relative, and the product's own rounding as an absolute floor (see below).
constexpr int FastDegree = 48;
// The zeros around the product's coefficients during its convolution (the highest
// degree with unrolled loops).
constexpr int FastPad = 4;

// The single root of phi in [a, b] (phi(a) = va, opposite signs at the ends): Newton's
// method safeguarded by the bracket (bisection where a step leaves it), from t.
// `phid(t, derivative)` returns phi(t) and its derivative. Once a step is shorter than
// a quarter of `width`, the sign a quarter width beyond the predicted root is tried:
// a change closes a bracket shorter than width/2 at once. The result is the midpoint
// of a bracket of width at most `width` (or a point where phi is exactly 0), as
// BracketedRoot's, in a few steps instead of regula falsi's dozen.
template <class Function>
double NewtonRoot(const Function& phid, double a, double b, double va, double width, double t)
{
  if (!(t > a && t < b))
  {
    t = 0.5 * (a + b);
  }
  for (int it = 0; it < 200 && b - a > width; ++it)
  {
    double dv;
    const double v = phid(t, dv);
    if (v == 0.0)
    {
      return t;
    }
    if ((v < 0) == (va < 0))
    {
      a = t;
      va = v;
    }
    else
    {
      b = t;
    }
    if (b - a <= width)
    {
      break;
    }
    const double step = v / dv;
    double next = t - step;
    // (Tested before the bracket: a step below t's rounding leaves next = t, an end of
    // the bracket, where the test below would bisect a bracket whose root is at hand.)
    if (std::isfinite(next) && std::fabs(step) < 0.25 * width)
    {
      // Close: [t, u] around the predicted root, u a quarter width beyond it.
      const double u =
        step < 0 ? std::min(next + 0.25 * width, b) : std::max(next - 0.25 * width, a);
      double du;
      const double vu = phid(u, du);
      if (vu == 0.0)
      {
        return u;
      }
      if ((vu < 0) != (v < 0))
      {
        return 0.5 * (t + u);
      }
      if ((vu < 0) == (va < 0))
      {
        a = u;
        va = vu;
      }
      else
      {
        b = u;
      }
      t = 0.5 * (a + b);
      continue;
    }
    if (!std::isfinite(next) || !(next > a && next < b))
    {
      t = 0.5 * (a + b);
      continue;
    }
    t = next;
  }
  return 0.5 * (a + b);
}

struct FastWorkspace
{
  std::vector<double> Pool; // piece coefficients, a stack following the DFS
  std::vector<Piece> Stack;
  std::vector<double> Scaled; // the factors' coefficients scaled by 2^-e_i
  double Binomial[FastDegree + 1][FastDegree + 1];
  FastWorkspace()
  {
    for (int n = 0; n <= FastDegree; ++n)
    {
      this->Binomial[n][0] = this->Binomial[n][n] = 1.0;
      for (int k = 1; k < n; ++k)
      {
        this->Binomial[n][k] = this->Binomial[n - 1][k - 1] + this->Binomial[n - 1][k];
      }
    }
  }
};

// Levels of re-expansion (see below), each with its own buffers.
constexpr int FastLevels = 4;

// Horner's rule for P(t) and for Σ|c_k|·|t|^k (a bound on every term), for n
// coefficients (N of them when N > 0: the loop unrolled, the same operations).
template <int N>
inline double HornerWithMagnitude(const double* c, int n, double t, double at, double& magnitude)
{
  const int count = N > 0 ? N : n;
  double f = 0.0, a = 0.0;
  for (int k = count - 1; k >= 0; --k)
  {
    f = f * t + c[k];
    a = a * at + std::fabs(c[k]);
  }
  magnitude = a;
  return f;
}

// Π p_i(t) − r and its derivative: Horner for each factor and its derivative, then the
// product rule (Newton's function on a monotone piece). Count > 0: every factor has
// Count coefficients (no dispatch per factor); 0: as `counts` says. The same operations.
template <int Count>
inline double ProductMinusWithSlope(const double* coefficients, const int* counts, int factors,
  double r, double t, double& derivative)
{
  double v = 1.0, dv = 0.0;
  for (int i = 0, offset = 0; i<factors; offset += Count> 0 ? Count : counts[i], ++i)
  {
    const double* c = coefficients + offset;
    double f, df;
    if (Count > 0)
    {
      f = EvaluateUnivariateWithDerivative(c, Count, t, df);
    }
    else
    {
      switch (counts[i])
      {
        // (Literal counts for quadrics and quartics: the loop unrolls once inlined.)
        case 3:
          f = EvaluateUnivariateWithDerivative(c, 3, t, df);
          break;
        case 5:
          f = EvaluateUnivariateWithDerivative(c, 5, t, df);
          break;
        default:
          f = EvaluateUnivariateWithDerivative(c, counts[i], t, df);
          break;
      }
    }
    dv = dv * f + v * df;
    v *= f;
  }
  derivative = dv;
  return v - r;
}

// NewtonRoot (from t, in [a, b], phi(a) = va) on Π p_i − r: products of quadratics only
// (spheres, ellipsoids, cylinders: the usual Π-surface) without the dispatch per factor.
inline double ProductNewtonRoot(const double* coefficients, const int* counts, int factors,
  double r, double a, double b, double va, double width, double t)
{
  bool quadratics = true;
  for (int i = 0; i < factors; ++i)
  {
    quadratics = quadratics && counts[i] == 3;
  }
  if (quadratics)
  {
    return NewtonRoot([&](double x, double& derivative)
      { return ProductMinusWithSlope<3>(coefficients, counts, factors, r, x, derivative); },
      a, b, va, width, t);
  }
  return NewtonRoot([&](double x, double& derivative)
    { return ProductMinusWithSlope<0>(coefficients, counts, factors, r, x, derivative); },
    a, b, va, width, t);
}

// QuickSegment's centred form of one factor (degree D, or d when D < 0) about m: its
// Taylor shift q, the shift of |c| at |m| (M), and the enclosures f ∈ q_0 ± width and
// f' ∈ q_1 ± dwidth over |τ| <= h (see QuickSegment).
template <int D>
inline void CentredForm(const double* c, double m, double am, double h, double* q, double* M,
  Interval& f, Interval& df, int degree = D)
{
  constexpr double U = 0x1p-53;
  const int d = D >= 0 ? D : degree;
  for (int k = 0; k <= d; ++k)
  {
    q[k] = c[k];
    M[k] = std::fabs(q[k]);
  }
  for (int a = 0; a < d; ++a)
  {
    for (int k = d - 1; k >= a; --k)
    {
      q[k] += m * q[k + 1];
      M[k] += am * M[k + 1];
    }
  }
  // Each q_k is within γ·M_k of the exact shift (at most 2d roundings per term it
  // sums); generously γ = 4(d + 1)u.
  const double gamma = 4.0 * (d + 1) * U;
  double spread = 0.0, dspread = 0.0, wide = 0.0, dwide = 0.0, hk = 1.0;
  for (int k = 1; k <= d; ++k)
  {
    // hk = h^(k−1) here
    dwide += k * M[k] * hk;
    if (k >= 2)
    {
      dspread += k * std::fabs(q[k]) * hk;
    }
    hk *= h;
    spread += std::fabs(q[k]) * hk;
    wide += M[k] * hk;
  }
  const double q1 = d >= 1 ? q[1] : 0.0;
  const double width = spread + gamma * (M[0] + wide) + (d + 2) * U * (std::fabs(q[0]) + spread);
  const double dwidth = dspread + gamma * dwide + (d + 2) * U * (std::fabs(q1) + dspread);
  f = { q[0] - width, q[0] + width };
  df = { q1 - dwidth, q1 + dwidth };
}

// At most this many factors take QuickSegment (its enclosures live on the stack).
constexpr int QuickFactors = 16;

// The common case decided without the product's Bernstein form: a short segment (an
// octree leaf's depth range) on which F − r provably keeps one sign, or is provably
// monotone. Each factor's centred form about the middle m, from its Taylor shift q
// (f(m + τ) = Σ q_k τ^k, |τ| <= h): f ∈ q_0 ± Σ_{k>=1} |q_k| h^k and
// f' ∈ q_1 ± Σ_{k>=2} k |q_k| h^(k−1), each widened by the rounding of the shift (the
// same shift of |c| at |m| bounds every term it sums) and of the sums. Then:
//   the product's enclosure excludes r (beyond 1e-12 of its size): no root;
//   Σ f_i' Π_{j≠i} f_j has one sign (intervals, by the product rule or else by the
//   logarithmic derivative, LogDerivativeSign; 1e-12 slack): at most one root, which
//   exists if F has strictly opposite signs at the ends (each beyond its evaluation's
//   rounding), and is found by NewtonRoot to the tolerance.
// Anything else (a possible tangency, two roots, an end within rounding of 0, a value
// beyond 2^±60 where the plain interval products could lose range) is left undecided:
// false, nothing added, and the Bernstein path decides. Sound, not identical: a piece
// the Bernstein path would subdivide down to a tangent root within its relative slack
// of 0 (F's true minimum above 0 by less than 1e-12 of F) is excluded here. With
// options.Monotone (the caller proved F monotone on the segment) the enclosures are
// skipped: the ends decide as in the monotone case.
bool QuickSegment(const double* coefficients, const int* counts, int factors, double r, double t0,
  double t1, const RayRootOptions& options, RootCluster& cluster, bool& found)
{
  found = false;
  if (factors > QuickFactors || factors == 0 || !(t1 > t0))
  {
    return false;
  }
  constexpr double U = 0x1p-53;
  // (Skipped where the caller knows F to be monotone on the segment: the ends decide.)
  if (!options.Monotone)
  {
    constexpr double Range = 0x1p60;
    const double m = 0.5 * (t0 + t1), h = 0.5 * (t1 - t0), am = std::fabs(m);
    Interval f[QuickFactors], df[QuickFactors];
    double q[MaxDegree + 1], M[MaxDegree + 1];
    for (int i = 0, offset = 0; i < factors; offset += counts[i], ++i)
    {
      const int d = counts[i] - 1;
      switch (d)
      {
        // (The usual degrees with the loops unrolled: the same operations.)
        case 2:
          CentredForm<2>(coefficients + offset, m, am, h, q, M, f[i], df[i]);
          break;
        case 4:
          CentredForm<4>(coefficients + offset, m, am, h, q, M, f[i], df[i]);
          break;
        default:
          CentredForm<-1>(coefficients + offset, m, am, h, q, M, f[i], df[i], d);
          break;
      }
      const double fm = std::max(std::fabs(f[i].Lo), std::fabs(f[i].Hi));
      const double dm = std::max(std::fabs(df[i].Lo), std::fabs(df[i].Hi));
      if (!(fm <= Range && dm <= Range))
      {
        return false; // (also NaN)
      }
    }
    // Prefix products (prefix[i] = Π_{j<i} f_j), then the whole product.
    Interval prefix[QuickFactors + 1];
    PrefixProducts(f, factors, prefix);
    // Rounding of the products (round to nearest, not outwards) and the underflow of a
    // tiny end: a relative and an absolute margin far above both.
    const Interval& whole = prefix[factors];
    const double size = std::max({ std::fabs(whole.Lo), std::fabs(whole.Hi), std::fabs(r) });
    const double slack = 1e-12 * size + 1e-290;
    if (whole.Lo - r > slack || whole.Hi - r < -slack)
    {
      return true; // F − r keeps one sign: no root
    }
    // The derivative Σ f_i' Π_{j≠i} f_j with suffix products formed on the way back.
    double lo, hi, magnitude;
    ProductRule(f, df, factors, prefix, lo, hi, magnitude);
    const double dslack = 1e-12 * magnitude + 1e-290;
    if (!(lo > dslack || hi < -dslack) && LogDerivativeSign(f, df, factors, 1e-12) == 0)
    {
      return false; // F may turn: the Bernstein path decides
    }
  }
  // Monotone: F at the ends, with a bound on each evaluation's rounding (Horner of |c|
  // at |t| bounds every term; γ as above, for the products too).
  auto valueAt = [&](double t, double& bound)
  {
    double v = 1.0, a = 1.0;
    const double at = std::fabs(t);
    int n = 0;
    for (int i = 0, offset = 0; i < factors; offset += counts[i], ++i)
    {
      const double* c = coefficients + offset;
      double fi, ai;
      switch (counts[i])
      {
        case 3:
          fi = HornerWithMagnitude<3>(c, 3, t, at, ai);
          break;
        case 5:
          fi = HornerWithMagnitude<5>(c, 5, t, at, ai);
          break;
        default:
          fi = HornerWithMagnitude<0>(c, counts[i], t, at, ai);
          break;
      }
      v *= fi;
      a *= ai;
      n += counts[i] + 1;
    }
    bound = 4.0 * (n + 2) * U * (a + std::fabs(r)) + 1e-290;
    return v - r;
  };
  double ba, bb;
  const double va = valueAt(t0, ba), vb = valueAt(t1, bb);
  if (!(std::fabs(va) > ba && std::fabs(vb) > bb) || !std::isfinite(va) || !std::isfinite(vb))
  {
    return false; // an end within rounding of a root: the Bernstein path decides
  }
  if ((va > 0) == (vb > 0))
  {
    return true; // monotone without a change of sign: no root
  }
  cluster.Add(ProductNewtonRoot(coefficients, counts, factors, r, t0, t1, va, options.Tolerance,
                t0 + (t1 - t0) * va / (va - vb)),
    false, va, vb);
  found = true;
  return true;
}

// Returns false, before adding any root, when the fast path does not apply (the caller
// then takes the general one): total degree above FastDegree, a factor identically zero
// on the segment, a scale that leaves the double range, or terms that cancel beyond its
// slack. Roots go to `cluster` (shared with the re-expansions of its pieces).
// FastRayRoots's step for one factor (degree D, or `degree` when D < 0): its weighted
// Bernstein coefficients on [t0, t1] scaled by 2^-e (e added to `exponent`; the factor's
// coefficients scaled alike into `scaled`), convolved with the product so far (degree
// `current`) into next; `bound` multiplied by the largest |b_k| of the scaled factor (in
// [1/2, 1)). False where the factor is 0 or leaves the exponent range (the caller gives
// up the fast path).
template <int D>
inline bool BernsteinFactor(const double* c, int degree, double t0, double t1,
  const FastWorkspace& w, const double* product, int current, double* next, double* scaled,
  long& exponent, double& bound)
{
  const int d = D >= 0 ? D : degree, count = d + 1;
  double bern[MaxDegree + 1], q[MaxDegree + 1];
  // Taylor shift to t0 and scaling to [0, 1] (as ToBernstein), then the weighted
  // Bernstein coefficients C(d, k)·b_k = Σ_{j<=k} C(d − j, k − j)·q_j directly: no
  // divisions.
  for (int k = 0; k < count; ++k)
  {
    q[k] = c[k];
  }
  ShiftToUnit<D>(q, d, t0, t1);
  for (int k = 0; k <= d; ++k)
  {
    double sum = 0.0;
    for (int j = 0; j <= k; ++j)
    {
      sum += w.Binomial[d - j][k - j] * q[j];
    }
    bern[k] = sum;
  }
  double m = 0.0;
  for (int k = 0; k < count; ++k)
  {
    m = std::max(m, std::fabs(bern[k]) / w.Binomial[d][k]);
  }
  if (!(m > 0.0) || !std::isfinite(m))
  {
    return false;
  }
  int e;
  pisurf::Frexp(m, &e);
  if (e > 1000 || e < -1000)
  {
    return false;
  }
  exponent += e;
  const double scale = pisurf::Ldexp(1.0, -e); // exact: multiplying by it only rescales
  bound *= m * scale;
  for (int k = 0; k < count; ++k)
  {
    bern[k] *= scale;
  }
  for (int k = 0; k < count; ++k)
  {
    scaled[k] = c[k] * scale;
  }
  // (each coefficient summed in a register, in the order of increasing a as before:
  // accumulating into next[a + b] in memory makes every step wait for the store of
  // the one before). The usual degrees (D >= 0) read the product padded with
  // FastPad >= D zeros on both sides (see FastRayRoots): every coefficient sums D + 1
  // terms with no bounds to compute (the zero terms leave each sum as it is: the same
  // results).
  constexpr bool padded = D >= 0;
  for (int k = 0; k <= current + d; ++k)
  {
    double sum = 0.0;
    const int last = padded ? 0 : std::max(0, k - current);
    for (int b = padded ? d : std::min(d, k); b >= last; --b)
    {
      sum += product[k - b] * bern[b];
    }
    next[k] = sum;
  }
  for (int k = current + d + 1; k <= current + d + FastPad; ++k)
  {
    next[k] = 0.0; // (the padding after the new product)
  }
  return true;
}

bool FastRayRoots(const double* coefficients, const int* counts, int factors, double r, double t0,
  double t1, const RayRootOptions& options, std::vector<RayRoot>& roots, RootCluster& cluster,
  int level)
{
  int degree = 0, total = 0;
  for (int i = 0; i < factors; ++i)
  {
    degree += counts[i] - 1;
    total += counts[i];
  }
  if (degree > FastDegree || factors == 0)
  {
    return false;
  }
  bool found;
  if (QuickSegment(coefficients, counts, factors, r, t0, t1, options, cluster, found))
  {
    return true;
  }
  thread_local FastWorkspace spaces[FastLevels];
  FastWorkspace& w = spaces[level];
  const int n = degree + 1;
  // The product in scaled (binomially weighted) Bernstein form, factor by factor.
  // (the product and the next one alternate between two buffers)
  // (with FastPad zeros before the first coefficient and after the last, as
  // BernsteinFactor's unrolled degrees read them)
  double buffers[2][FastDegree + 1 + 2 * FastPad];
  for (int b = 0; b < 2; ++b)
  {
    for (int k = 0; k < 2 * FastPad + 1; ++k)
    {
      buffers[b][k] = 0.0;
    }
  }
  double* product = buffers[0] + FastPad;
  double* next = buffers[1] + FastPad;
  product[0] = 1.0;
  int current = 0; // degree of the product so far
  long exponent = 0;
  // The product of the scaled factors' largest |b_k|: it bounds the terms each product
  // coefficient sums, hence its rounding (see below).
  double bound = 1.0;
  w.Scaled.resize(total);
  for (int i = 0, offset = 0; i < factors; offset += counts[i], ++i)
  {
    const int d = counts[i] - 1;
    const double* c = coefficients + offset;
    double* scaled = w.Scaled.data() + offset;
    bool ok;
    // (The usual degrees with the loops unrolled: the same operations.)
    switch (d)
    {
      case 2:
        ok = BernsteinFactor<2>(c, 2, t0, t1, w, product, current, next, scaled, exponent, bound);
        break;
      case 4:
        ok = BernsteinFactor<4>(c, 4, t0, t1, w, product, current, next, scaled, exponent, bound);
        break;
      default:
        ok = BernsteinFactor<-1>(c, d, t0, t1, w, product, current, next, scaled, exponent, bound);
        break;
    }
    if (!ok)
    {
      return false;
    }
    current += d;
    std::swap(product, next);
  }
  double rs = 0.0;
  if (r != 0.0)
  {
    if (exponent > 900 || exponent < -900)
    {
      return false;
    }
    rs = pisurf::Ldexp(r, static_cast<int>(-exponent));
    if (!(std::fabs(rs) > 1e-290) || !std::isfinite(rs))
    {
      return false;
    }
  }
  // The Bernstein coefficients of F·2^-exponent on [t0, t1].
  std::vector<double>& pool = w.Pool;
  std::vector<Piece>& stack = w.Stack;
  pool.resize(n);
  for (int k = 0; k < n; ++k)
  {
    pool[k] = product[k] / w.Binomial[degree][k] - rs;
  }
  const double rslack = 1e-9 * std::fabs(rs);
  const double fslack = 1e-12 * (factors + 1);
  // Rounding: every coefficient of the product carries the error of its convolution, at
  // most 2·(degree + factors)·u (u = 2^-52) times the sum of its terms' absolute values.
  // With B_i the largest |b_k| of scaled factor i (|C(d_i, k)·b_k| <= C(d_i, k)·B_i),
  // that sum for the weighted coefficient k of the product is at most C(n, k)·Π B_i
  // (Vandermonde: the C(d_i, k_i) over k_1 + ... = k sum to C(n, k)), so every plain
  // coefficient's error is at most `rounding` = 2·(degree + factors)·u·Π B_i (the
  // de Casteljau splits then only average, adding rounding relative to what they
  // average). Every piece inherits it, however small its own values: it enters each
  // piece's slack as an absolute floor.
  // Where it exceeds even the top level's relative slack (the terms cancel by 1e30, as
  // with 20 atom spheres across 13 Å), the general path decides the whole segment, factor
  // by factor, each accurate to its own size; a piece that only this floor leaves
  // undecided, its values within 1e3 times it, is expanded afresh (below). Where the
  // relative slack dominates (the chains of tiny pieces at a double root) nothing
  // changes, so such a chain stays one root whatever the segment.
  double largest = 0.0;
  for (int k = 0; k < n; ++k)
  {
    largest = std::max(largest, std::fabs(pool[k] + rs));
  }
  // (with a margin for the rounding of the bound's own product)
  const double rounding = bound * (2.0 * (degree + factors) * 0x1p-52) * (1.0 + 1e-10);
  if (!(rounding <= fslack * largest))
  {
    return false;
  }
  const double* scaled = w.Scaled.data();
  stack.clear();
  stack.push_back({ t0, t1, 0, 0 });
  while (!stack.empty())
  {
    const Piece p = stack.back();
    stack.pop_back();
    pool.resize(p.Offset + n);
    const double* f = pool.data() + p.Offset;
    // The product's magnitude on the piece sets the rounding slack.
    double lo = f[0], hi = f[0];
    for (int k = 1; k < n; ++k)
    {
      lo = std::min(lo, f[k]);
      hi = std::max(hi, f[k]);
    }
    const double relative = fslack * (std::max(std::fabs(lo + rs), std::fabs(hi + rs))) + rslack;
    const double slack = relative + rounding + 1e-300;
    if (lo > slack || hi < -slack)
    {
      continue; // no root in this piece
    }
    const double va = f[0], vb = f[degree];
    const bool change = (va < 0 && vb > 0) || (va > 0 && vb < 0);
    // Descartes: every coefficient clearly signed and one sign variation.
    // (Counted over all coefficients without early exits or a branch per coefficient:
    // the variations matter only where all are clear.)
    int unclear = 0, variations = 0;
    for (int k = 0; k < n; ++k)
    {
      unclear += !(std::fabs(f[k]) > slack);
    }
    for (int k = 1; k < n; ++k)
    {
      variations += (f[k] < 0) != (f[k - 1] < 0);
    }
    bool single = unclear == 0 && variations == 1;
    bool monotone = single;
    if (!single)
    {
      // F' in Bernstein form: degree·(f_{k+1} − f_k)/(b − a); its sign is that of the
      // differences. The slack of F bounds their rounding (twice).
      bool up = true, down = true;
      for (int k = 0; k < degree && (up || down); ++k)
      {
        const double dk = f[k + 1] - f[k];
        up = up && dk > 2.0 * slack;
        down = down && dk < -2.0 * slack;
      }
      monotone = degree > 0 && (up || down);
    }
    if (monotone)
    {
      if (change)
      {
        // Start where the control polygon first crosses zero: close to the root (the
        // polygon converges quadratically to F as pieces shrink).
        double start = 0.5;
        for (int k = 0; k < degree; ++k)
        {
          if ((f[k] < 0) != (f[k + 1] < 0))
          {
            start = (k + f[k] / (f[k] - f[k + 1])) / degree;
            break;
          }
        }
        cluster.Add(ProductNewtonRoot(scaled, counts, factors, rs, p.A, p.B, va, options.Tolerance,
                      p.A + start * (p.B - p.A)),
          false, va, vb);
      }
      else if (va == 0.0 || vb == 0.0)
      {
        cluster.Add(va == 0.0 ? p.A : p.B, false, va, vb);
      }
      if (!options.AllRoots && !roots.empty())
      {
        return true;
      }
      continue;
    }
    if (rounding > relative && std::max(std::fabs(lo), std::fabs(hi)) <= 1e3 * rounding)
    {
      // Undecided for the rounding this expansion carries, its values near it (two
      // factors' zeros a hair apart): the product expanded afresh on the piece,
      // whose terms are the piece's own size, decides it (the general path if that
      // cannot or after FastLevels expansions).
      if (!(level + 1 < FastLevels &&
            FastRayRoots(
              coefficients, counts, factors, r, p.A, p.B, options, roots, cluster, level + 1)))
      {
        Solver(coefficients, counts, factors, r, options, GeneralWorkspace())
          .Run(p.A, p.B, cluster, roots);
      }
      if (!options.AllRoots && !roots.empty())
      {
        return true;
      }
      continue;
    }
    if (p.B - p.A <= options.Tolerance || p.Depth >= options.MaximumDepth)
    {
      cluster.Add(0.5 * (p.A + p.B), !change, va, vb);
      if (!options.AllRoots)
      {
        return true;
      }
      continue;
    }
    // Split: the right half below the left on the stack (the left is processed first);
    // the right half's coefficients first in the pool, so popping the left truncates
    // the pool above its own.
    const size_t right = p.Offset + n, left = right + n;
    pool.resize(left + n);
    Split(pool.data() + p.Offset, n, pool.data() + left, pool.data() + right);
    const double mid = 0.5 * (p.A + p.B);
    stack.push_back({ mid, p.B, p.Depth + 1, right });
    stack.push_back({ p.A, mid, p.Depth + 1, left });
  }
  return true;
}
}

bool FindRayRoots(const double* coefficients, const int* counts, int factors, double r, double t0,
  double t1, const RayRootOptions& options, std::vector<RayRoot>& roots)
{
  const double cuts[2] = { t0, t1 };
  const int monotone = options.Monotone ? 1 : 0;
  return FindRayRoots(coefficients, counts, factors, r, cuts, &monotone, 1, options, roots);
}

bool FindRayRoots(const double* coefficients, const int* counts, int factors, double r,
  const double* cuts, const int* monotone, int pieces, const RayRootOptions& options,
  std::vector<RayRoot>& roots)
{
  if (!std::isfinite(r) || pieces < 1 || !(options.Tolerance > 0) || factors < 0)
  {
    return false;
  }
  for (int k = 0; k <= pieces; ++k)
  {
    if (!std::isfinite(cuts[k]) || (k > 0 && !(cuts[k - 1] <= cuts[k])))
    {
      return false;
    }
  }
  size_t total = 0;
  for (int i = 0; i < factors; ++i)
  {
    if (counts[i] < 1 || counts[i] > MaxDegree + 1)
    {
      return false;
    }
    total += counts[i];
  }
  // Every coefficient finite: c·0 is 0 for a finite c and NaN for ±inf or NaN, so the
  // sum is NaN exactly when one is not (no branch per coefficient; four partial sums, so
  // that the additions do not wait for each other: this runs for every depth range).
  double poison[4] = { 0.0, 0.0, 0.0, 0.0 };
  size_t k = 0;
  for (; k + 4 <= total; k += 4)
  {
    for (int l = 0; l < 4; ++l)
    {
      poison[l] += coefficients[k + l] * 0.0;
    }
  }
  for (; k < total; ++k)
  {
    poison[0] += coefficients[k] * 0.0;
  }
  if ((poison[0] + poison[1]) + (poison[2] + poison[3]) != 0.0)
  {
    return false;
  }
  roots.clear();
  // One cluster over all pieces: a root on a cut, found by the pieces on both sides,
  // is reported once (as a root inside one piece is).
  RootCluster cluster(roots, options.Tolerance);
  RayRootOptions piece = options;
  for (int k = 0; k < pieces; ++k)
  {
    piece.Monotone = monotone[k] != 0;
    if (!FastRayRoots(
          coefficients, counts, factors, r, cuts[k], cuts[k + 1], piece, roots, cluster, 0))
    {
      // (the fast path added nothing for this piece)
      Solver(coefficients, counts, factors, r, piece, GeneralWorkspace())
        .Run(cuts[k], cuts[k + 1], cluster, roots);
    }
    if (!options.AllRoots && !roots.empty())
    {
      break;
    }
  }
  return true;
}

bool FindRayRoots(const std::vector<std::vector<double>>& factors, double r, double t0, double t1,
  const RayRootOptions& options, std::vector<RayRoot>& roots)
{
  std::vector<double> flat;
  std::vector<int> counts;
  for (const auto& f : factors)
  {
    flat.insert(flat.end(), f.begin(), f.end());
    counts.push_back(static_cast<int>(f.size()));
  }
  return FindRayRoots(
    flat.data(), counts.data(), static_cast<int>(counts.size()), r, t0, t1, options, roots);
}
}
