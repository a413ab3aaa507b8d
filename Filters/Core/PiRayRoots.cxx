// SPDX-License-Identifier: BSD-3-Clause
#include "PiRayRoots.h"

#include "PiPolynomial.h"
#include "PiProduct.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pisurf
{
namespace
{
// An interval scaled by 2^E, so that products of many factors stay representable.
struct ScaledInterval
{
  double Lo = 1.0, Hi = 1.0;
  long E = 0;

  void Normalize()
  {
    const double a = std::max(std::fabs(this->Lo), std::fabs(this->Hi));
    if (a != 0.0 && std::isfinite(a) && (a > 0x1p256 || a < 0x1p-256))
    {
      int ex;
      std::frexp(a, &ex);
      this->Lo = std::ldexp(this->Lo, -ex);
      this->Hi = std::ldexp(this->Hi, -ex);
      this->E += ex;
    }
  }
  void Multiply(const Interval& v)
  {
    // Bring v near 1 first, as the product kernel does.
    double lo = v.Lo, hi = v.Hi;
    const double a = std::max(std::fabs(lo), std::fabs(hi));
    if (a != 0.0 && std::isfinite(a) && (a > 0x1p256 || a < 0x1p-256))
    {
      int ex;
      std::frexp(a, &ex);
      lo = std::ldexp(lo, -ex);
      hi = std::ldexp(hi, -ex);
      this->E += ex;
    }
    const double c[4] = { this->Lo * lo, this->Lo * hi, this->Hi * lo, this->Hi * hi };
    this->Lo = std::min({ c[0], c[1], c[2], c[3] });
    this->Hi = std::max({ c[0], c[1], c[2], c[3] });
    this->Normalize();
  }
};

// Bernstein coefficients of a polynomial (ascending monomial coefficients in t) on [a, b].
std::vector<double> ToBernstein(const std::vector<double>& c, double a, double b)
{
  const int n = static_cast<int>(c.size()) - 1;
  // q(s) = p(a + (b − a)s): Taylor shift to a, then scale by (b − a)^j.
  std::vector<double> q(c);
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
  // Power basis to Bernstein: b_k = Σ_{j<=k} C(k, j) / C(n, j) q_j.
  std::vector<double> bern(n + 1, 0.0);
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
  return bern;
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

// De Casteljau at 1/2: the Bernstein coefficients of both halves.
void Split(const double* b, int count, double* left, double* right)
{
  std::vector<double> w(b, b + count);
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
  std::vector<double> Bernstein; // all factors, concatenated
};

class Solver
{
public:
  Solver(const std::vector<std::vector<double>>& factors, double r, const RayRootOptions& o)
    : Factors(factors)
    , R(r)
    , Options(o)
  {
    for (const auto& f : factors)
    {
      this->Offsets.push_back(this->Total);
      this->Counts.push_back(static_cast<int>(f.size()));
      this->Total += f.size();
    }
  }

  // sign(F)·ln(1 + |F|) at t, without overflow.
  double Compressed(double t) const
  {
    double m = 1.0;
    long e = 0;
    for (const auto& f : this->Factors)
    {
      const double v = EvaluateUnivariate(f.data(), static_cast<int>(f.size()), t);
      if (v == 0.0)
      {
        m = 0.0;
        break;
      }
      int ex;
      m *= std::frexp(v, &ex);
      e += ex;
      int em;
      m = std::frexp(m, &em);
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
      F = std::ldexp(m, static_cast<int>(e)) - this->R;
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

  // +1/−1: F has that sign on the whole piece; 0: it may vanish there.
  int Sign(const Piece& p) const
  {
    std::vector<Interval> enclosures(this->Factors.size());
    for (size_t i = 0; i < this->Factors.size(); ++i)
    {
      enclosures[i] = Hull(p.Bernstein.data() + this->Offsets[i], this->Counts[i]);
    }
    return SignOfProductMinus(enclosures, this->R);
  }

  // True if F' cannot vanish on the piece (so F is strictly monotone there).
  bool Monotone(const Piece& p) const
  {
    const size_t n = this->Factors.size();
    std::vector<Interval> f(n), df(n);
    for (size_t i = 0; i < n; ++i)
    {
      const double* b = p.Bernstein.data() + this->Offsets[i];
      const int count = this->Counts[i];
      f[i] = Hull(b, count);
      if (count < 2)
      {
        df[i] = { 0.0, 0.0 };
        continue;
      }
      // p' in Bernstein form on [A, B]: (count − 1)(b_{k+1} − b_k)/(B − A).
      std::vector<double> d(count - 1);
      for (int k = 0; k + 1 < count; ++k)
      {
        d[k] = (count - 1) * (b[k + 1] - b[k]) / (p.B - p.A);
      }
      df[i] = Hull(d.data(), count - 1);
    }
    // Σ_i p_i' Π_{j≠i} p_j with prefix and suffix products, scaled.
    std::vector<ScaledInterval> prefix(n + 1), suffix(n + 1);
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
    std::vector<ScaledInterval> terms(n);
    long top = std::numeric_limits<long>::min();
    for (size_t i = 0; i < n; ++i)
    {
      terms[i] = prefix[i];
      terms[i].Multiply(df[i]);
      const ScaledInterval& s = suffix[i + 1];
      terms[i].Multiply({ s.Lo, s.Hi });
      terms[i].E += s.E;
      top = std::max(top, terms[i].E);
    }
    double lo = 0.0, hi = 0.0;
    for (const ScaledInterval& t : terms)
    {
      const long shift = std::max<long>(t.E - top, -2000);
      lo += std::ldexp(t.Lo, static_cast<int>(shift));
      hi += std::ldexp(t.Hi, static_cast<int>(shift));
    }
    const double slack = 1e-12 * (std::fabs(lo) + std::fabs(hi));
    return lo - slack > 0.0 || hi + slack < 0.0;
  }

  // The single root of a monotone piece with a sign change: Illinois with bisection.
  double Refine(double a, double b, double va, double vb) const
  {
    int side = 0;
    for (int it = 0; it < 200 && b - a > this->Options.Tolerance; ++it)
    {
      double t = 0.5 * (a + b);
      const double secant = b - vb * (b - a) / (vb - va);
      if (std::isfinite(secant) && secant > a && secant < b)
      {
        t = secant;
      }
      const double v = this->Compressed(t);
      if (v == 0.0)
      {
        return t;
      }
      if ((v < 0) == (va < 0))
      {
        a = t;
        va = v;
        if (side == -1)
        {
          vb *= 0.5;
        }
        side = -1;
      }
      else
      {
        b = t;
        vb = v;
        if (side == 1)
        {
          va *= 0.5;
        }
        side = 1;
      }
    }
    return 0.5 * (a + b);
  }

  void Run(double t0, double t1, std::vector<RayRoot>& roots)
  {
    std::vector<Piece> stack;
    Piece first{ t0, t1, 0, {} };
    first.Bernstein.reserve(this->Total);
    for (const auto& f : this->Factors)
    {
      const std::vector<double> b = ToBernstein(f, t0, t1);
      first.Bernstein.insert(first.Bernstein.end(), b.begin(), b.end());
    }
    stack.push_back(std::move(first));
    while (!stack.empty())
    {
      Piece p = std::move(stack.back());
      stack.pop_back();
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
          this->Add(roots, { this->Refine(p.A, p.B, va, vb), false });
        }
        else if (va == 0.0 || vb == 0.0)
        {
          this->Add(roots, { va == 0.0 ? p.A : p.B, false });
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
        this->Add(roots, { 0.5 * (p.A + p.B), !change });
        if (!this->Options.AllRoots)
        {
          return;
        }
        continue;
      }
      // Split; push the right half first so the left (smaller t) is processed first.
      Piece left{ p.A, 0.5 * (p.A + p.B), p.Depth + 1, std::vector<double>(this->Total) };
      Piece right{ left.B, p.B, p.Depth + 1, std::vector<double>(this->Total) };
      for (size_t i = 0; i < this->Factors.size(); ++i)
      {
        Split(p.Bernstein.data() + this->Offsets[i], this->Counts[i],
          left.Bernstein.data() + this->Offsets[i], right.Bernstein.data() + this->Offsets[i]);
      }
      stack.push_back(std::move(right));
      stack.push_back(std::move(left));
    }
  }

private:
  // Adjacent tiny pieces around one root report it once.
  void Add(std::vector<RayRoot>& roots, const RayRoot& root) const
  {
    if (!roots.empty() && root.T - roots.back().T <= 2.0 * this->Options.Tolerance)
    {
      roots.back().Tangent = roots.back().Tangent && root.Tangent;
      return;
    }
    roots.push_back(root);
  }

  const std::vector<std::vector<double>>& Factors;
  double R;
  RayRootOptions Options;
  std::vector<size_t> Offsets;
  std::vector<int> Counts;
  size_t Total = 0;
};
}

bool FindRayRoots(const std::vector<std::vector<double>>& factors, double r, double t0,
  double t1, const RayRootOptions& options, std::vector<RayRoot>& roots)
{
  if (!std::isfinite(r) || !std::isfinite(t0) || !std::isfinite(t1) || !(t0 <= t1) ||
    !(options.Tolerance > 0))
  {
    return false;
  }
  for (const auto& f : factors)
  {
    if (f.empty())
    {
      return false;
    }
    for (double c : f)
    {
      if (!std::isfinite(c))
      {
        return false;
      }
    }
  }
  roots.clear();
  Solver(factors, r, options).Run(t0, t1, roots);
  return true;
}
}
