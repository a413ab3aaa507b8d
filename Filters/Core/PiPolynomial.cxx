// SPDX-License-Identifier: BSD-3-Clause
#include "PiPolynomial.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <tuple>

namespace pisurf
{
namespace
{
bool TermLess(const Monomial& a, const Monomial& b)
{
  return std::tie(a.I, a.J, a.K) < std::tie(b.I, b.J, b.K);
}

// Powers x^0..x^n of one coordinate.
inline void Powers(double x, int n, double* out)
{
  out[0] = 1.0;
  for (int i = 1; i <= n; ++i)
  {
    out[i] = out[i - 1] * x;
  }
}

}

Polynomial3 Polynomial3::Constant(double c)
{
  Polynomial3 p;
  p.AddTerm(c, 0, 0, 0);
  return p;
}

Polynomial3 Polynomial3::Variable(int axis)
{
  Polynomial3 p;
  p.AddTerm(1.0, axis == 0, axis == 1, axis == 2);
  return p;
}

void Polynomial3::AddTerm(double c, int i, int j, int k)
{
  if (c == 0.0)
  {
    return;
  }
  Monomial m{ c, i, j, k };
  auto it = std::lower_bound(this->Terms.begin(), this->Terms.end(), m, TermLess);
  if (it != this->Terms.end() && it->I == i && it->J == j && it->K == k)
  {
    it->Coefficient += c;
    if (it->Coefficient == 0.0)
    {
      this->Terms.erase(it);
    }
  }
  else
  {
    this->Terms.insert(it, m);
  }
  this->Summarize();
}

void Polynomial3::Summarize()
{
  this->Degree = -1;
  std::fill(this->AxisDegree, this->AxisDegree + 3, 0);
  for (const auto& t : this->Terms)
  {
    this->Degree = std::max(this->Degree, t.I + t.J + t.K);
    this->AxisDegree[0] = std::max(this->AxisDegree[0], t.I);
    this->AxisDegree[1] = std::max(this->AxisDegree[1], t.J);
    this->AxisDegree[2] = std::max(this->AxisDegree[2], t.K);
  }
  this->Quadric = this->Degree <= 2;
  this->Scaled3.resize(3 * this->Terms.size());
  for (size_t n = 0; n < this->Terms.size(); ++n)
  {
    const Monomial& t = this->Terms[n];
    this->Scaled3[3 * n] = t.Coefficient * t.I;
    this->Scaled3[3 * n + 1] = t.Coefficient * t.J;
    this->Scaled3[3 * n + 2] = t.Coefficient * t.K;
  }
  for (int a = 0; a < 3; ++a)
  {
    // Counting sort of the terms by their power of variable a (stable).
    const int lo = a == 0 ? 1 : 0, hi = a == 2 ? 1 : 2;
    std::vector<int>& start = this->AxisStart[a];
    start.assign(static_cast<size_t>(this->AxisDegree[a]) + 2, 0);
    for (const auto& t : this->Terms)
    {
      const int e[3] = { t.I, t.J, t.K };
      ++start[e[a] + 1];
    }
    for (size_t m = 1; m < start.size(); ++m)
    {
      start[m] += start[m - 1];
    }
    std::vector<int> fill(start.begin(), start.end() - 1);
    this->ByAxis[a].resize(this->Terms.size());
    for (const auto& t : this->Terms)
    {
      const int e[3] = { t.I, t.J, t.K };
      this->ByAxis[a][fill[e[a]]++] = { t.Coefficient, e[lo], e[hi] };
    }
  }
  this->Nested.clear();
  const int n = this->Degree;
  const size_t dense = n >= 0 ? static_cast<size_t>((n + 1) * (n + 2) * (n + 3) / 6) : 0;
  if (n >= 3 && n <= NestedMaxDegree && 3 * this->Terms.size() >= dense)
  {
    this->Nested.assign(dense, 0.0);
    // Offset of (I, J, K) in the order K = n..0, J = n − K..0, I = n − J − K..0.
    std::vector<size_t> start(static_cast<size_t>(n + 1) * (n + 1), 0);
    size_t offset = 0;
    for (int k = n; k >= 0; --k)
    {
      for (int j = n - k; j >= 0; --j)
      {
        start[static_cast<size_t>(k) * (n + 1) + j] = offset;
        offset += static_cast<size_t>(n - j - k + 1);
      }
    }
    for (const auto& t : this->Terms)
    {
      this->Nested[start[static_cast<size_t>(t.K) * (n + 1) + t.J] + (n - t.J - t.K - t.I)] =
        t.Coefficient;
    }
  }
  std::fill(this->Q, this->Q + 10, 0.0);
  std::fill(this->Q2, this->Q2 + 10, 0.0);
  this->EvenQuartic = n == 4;
  for (const auto& t : this->Terms)
  {
    this->EvenQuartic = this->EvenQuartic && t.I % 2 == 0 && t.J % 2 == 0 && t.K % 2 == 0;
  }
  if (this->Quadric || this->EvenQuartic)
  {
    // (An even quartic's terms are those of a quadric in the squares: halve the powers.)
    const int h = this->EvenQuartic ? 2 : 1;
    for (const auto& t : this->Terms)
    {
      int slot = 0;
      const int key = (t.I / h) * 100 + (t.J / h) * 10 + t.K / h;
      switch (key)
      {
        case 0:
          slot = 0;
          break;
        case 100:
          slot = 1;
          break;
        case 10:
          slot = 2;
          break;
        case 1:
          slot = 3;
          break;
        case 200:
          slot = 4;
          break;
        case 20:
          slot = 5;
          break;
        case 2:
          slot = 6;
          break;
        case 110:
          slot = 7;
          break;
        case 101:
          slot = 8;
          break;
        default:
          slot = 9;
          break; // 011: yz
      }
      (this->EvenQuartic ? this->Q2 : this->Q)[slot] = t.Coefficient;
    }
  }
}

void Polynomial3::Finish()
{
  std::sort(this->Terms.begin(), this->Terms.end(), TermLess);
  std::vector<Monomial> merged;
  merged.reserve(this->Terms.size());
  for (const auto& t : this->Terms)
  {
    if (!merged.empty() && merged.back().I == t.I && merged.back().J == t.J &&
      merged.back().K == t.K)
    {
      merged.back().Coefficient += t.Coefficient;
    }
    else
    {
      merged.push_back(t);
    }
  }
  this->Terms.clear();
  for (const auto& t : merged)
  {
    if (t.Coefficient != 0.0)
    {
      this->Terms.push_back(t);
    }
  }
  this->Summarize();
}

double Polynomial3::GetCoefficient(int i, int j, int k) const
{
  Monomial m{ 0.0, i, j, k };
  auto it = std::lower_bound(this->Terms.begin(), this->Terms.end(), m, TermLess);
  if (it != this->Terms.end() && it->I == i && it->J == j && it->K == k)
  {
    return it->Coefficient;
  }
  return 0.0;
}

bool Polynomial3::IsFinite() const
{
  for (const auto& t : this->Terms)
  {
    if (!std::isfinite(t.Coefficient))
    {
      return false;
    }
  }
  return true;
}

Polynomial3 Polynomial3::operator+(const Polynomial3& o) const
{
  Polynomial3 r;
  r.Terms = this->Terms;
  r.Terms.insert(r.Terms.end(), o.Terms.begin(), o.Terms.end());
  r.Finish();
  return r;
}

Polynomial3 Polynomial3::operator-() const
{
  return this->Scaled(-1.0);
}

Polynomial3 Polynomial3::operator-(const Polynomial3& o) const
{
  return *this + (-o);
}

Polynomial3 Polynomial3::operator*(const Polynomial3& o) const
{
  // The products are summed in a dense (i, j, k) table, not sorted: sorting all n·m
  // products made (x+y+z+1)^64 take 16 s (found by ./run fuzz expression); the table
  // has at most 65³ entries and is read out in TermLess order.
  Polynomial3 r;
  if (this->Terms.empty() || o.Terms.empty())
  {
    r.Summarize();
    return r;
  }
  int n[3];
  for (int a = 0; a < 3; ++a)
  {
    n[a] = this->GetAxisDegree(a) + o.GetAxisDegree(a) + 1;
  }
  std::vector<double> table(size_t(n[0]) * n[1] * n[2], 0.0);
  for (const auto& a : this->Terms)
  {
    for (const auto& b : o.Terms)
    {
      const size_t at = (size_t(a.I + b.I) * n[1] + (a.J + b.J)) * n[2] + (a.K + b.K);
      table[at] += a.Coefficient * b.Coefficient;
    }
  }
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k)
      {
        const size_t at = (size_t(i) * n[1] + j) * n[2] + k;
        if (table[at] != 0.0)
        {
          r.Terms.push_back({ table[at], i, j, k });
        }
      }
  r.Summarize();
  return r;
}

Polynomial3 Polynomial3::Scaled(double s) const
{
  Polynomial3 r = *this;
  for (auto& t : r.Terms)
  {
    t.Coefficient *= s;
  }
  r.Finish();
  return r;
}

Polynomial3 Polynomial3::Pow(int n) const
{
  Polynomial3 result = Constant(1.0);
  Polynomial3 base = *this;
  while (n > 0)
  {
    if (n & 1)
    {
      result = result * base;
    }
    n >>= 1;
    if (n > 0)
    {
      base = base * base;
    }
  }
  return result;
}

void Polynomial3::PowerTables(const double p[3], double* px, double* py, double* pz) const
{
  const int n = std::max(this->Degree, 0);
  Powers(p[0], n, px);
  Powers(p[1], n, py);
  Powers(p[2], n, pz);
}

template <bool Inner>
double Polynomial3::AxisSum(int a, int m, const double* lo, const double* hi) const
{
  const AxisTerm* t = this->ByAxis[a].data();
  const int end = this->AxisStart[a][m + 1];
  double sum = 0.0;
  for (int k = this->AxisStart[a][m]; k < end; ++k)
  {
    sum += Inner ? t[k].C * (lo[t[k].Lo] * hi[t[k].Hi]) : t[k].C * lo[t[k].Lo] * hi[t[k].Hi];
  }
  return sum;
}

double Polynomial3::Evaluate(const double p[3]) const
{
  if (this->Quadric)
  {
    return QuadricValue(this->Q, p[0], p[1], p[2]);
  }
  double px[MaxDegree + 1], py[MaxDegree + 1], pz[MaxDegree + 1];
  this->PowerTables(p, px, py, pz);
  double v = 0.0;
  for (const auto& t : this->Terms)
  {
    v += t.Coefficient * px[t.I] * py[t.J] * pz[t.K];
  }
  return v;
}

namespace
{
// Nested Horner's rule with the gradient on Polynomial3::Nested's layout, degree N.
template <int N>
double NestedWithGradient(const double* c, const double p[3], double g[3])
{
  const double x = p[0], y = p[1], z = p[2];
  double P = 0.0, Px = 0.0, Py = 0.0, Pz = 0.0;
  for (int k = N; k >= 0; --k)
  {
    double Q = 0.0, Qx = 0.0, Qy = 0.0;
    for (int j = N - k; j >= 0; --j)
    {
      double R = *c++, Rx = 0.0;
      for (int i = N - j - k; i > 0; --i)
      {
        Rx = Rx * x + R;
        R = R * x + *c++;
      }
      Qy = Qy * y + Q;
      Q = Q * y + R;
      Qx = Qx * y + Rx;
    }
    Pz = Pz * z + P;
    P = P * z + Q;
    Px = Px * z + Qx;
    Py = Py * z + Qy;
  }
  g[0] = Px;
  g[1] = Py;
  g[2] = Pz;
  return P;
}
}

double Polynomial3::EvaluateWithGradient(const double p[3], double g[3]) const
{
  if (this->Quadric)
  {
    return QuadricWithGradient(this->Q, p, g);
  }
  // (Far points, whose powers may overflow, take the term-wise path below.)
  const bool near = std::fabs(p[0]) < 1e30 && std::fabs(p[1]) < 1e30 && std::fabs(p[2]) < 1e30;
  if (this->EvenQuartic && near)
  {
    // Q2(x², y², z²) and the chain rule ∂/∂x = 2x·∂Q2/∂(x²).
    const double a = p[0] * p[0], b = p[1] * p[1], c = p[2] * p[2];
    double v, gs[3];
    QuadricValueOf(this->Q2, a, b, c, v);
    QuadricGradientOf(this->Q2, a, b, c, gs);
    for (int k = 0; k < 3; ++k)
    {
      g[k] = 2.0 * p[k] * gs[k];
    }
    return v;
  }
  if (!this->Nested.empty() && near)
  {
    switch (this->Degree)
    {
      case 3:
        return NestedWithGradient<3>(this->Nested.data(), p, g);
      case 4:
        return NestedWithGradient<4>(this->Nested.data(), p, g);
      case 5:
        return NestedWithGradient<5>(this->Nested.data(), p, g);
      case 6:
        return NestedWithGradient<6>(this->Nested.data(), p, g);
      default:
        break;
    }
  }
  // Power tables shifted by one, with a zero below x^0: px[i − 1] is 0 for i = 0, so
  // every term adds its three partials without a branch (c·i is 0 there anyway).
  double bx[MaxDegree + 2], by[MaxDegree + 2], bz[MaxDegree + 2];
  bx[0] = by[0] = bz[0] = 0.0;
  double* px = bx + 1;
  double* py = by + 1;
  double* pz = bz + 1;
  this->PowerTables(p, px, py, pz);
  const int n = std::max(this->Degree, 0);
  if (!(std::isfinite(px[n]) && std::isfinite(py[n]) && std::isfinite(pz[n])))
  {
    // A power overflowed (far outside any model): the terms without that variable
    // must not meet 0·inf. Term by term with branches, as the partials are defined.
    double v = 0.0;
    g[0] = g[1] = g[2] = 0.0;
    for (const auto& t : this->Terms)
    {
      const double c = t.Coefficient;
      v += c * px[t.I] * py[t.J] * pz[t.K];
      if (t.I > 0)
      {
        g[0] += c * t.I * px[t.I - 1] * py[t.J] * pz[t.K];
      }
      if (t.J > 0)
      {
        g[1] += c * t.J * px[t.I] * py[t.J - 1] * pz[t.K];
      }
      if (t.K > 0)
      {
        g[2] += c * t.K * px[t.I] * py[t.J] * pz[t.K - 1];
      }
    }
    return v;
  }
  double v = 0.0, g0 = 0.0, g1 = 0.0, g2 = 0.0;
  const double* scaled = this->Scaled3.data();
  for (const auto& t : this->Terms)
  {
    const double c = t.Coefficient;
    v += c * px[t.I] * py[t.J] * pz[t.K];
    g0 += scaled[0] * px[t.I - 1] * py[t.J] * pz[t.K];
    g1 += scaled[1] * px[t.I] * py[t.J - 1] * pz[t.K];
    g2 += scaled[2] * px[t.I] * py[t.J] * pz[t.K - 1];
    scaled += 3;
  }
  g[0] = g0;
  g[1] = g1;
  g[2] = g2;
  return v;
}

void Polynomial3::EvaluateStar(
  const double p[3], const double step[3], double values[7], double g[3]) const
{
  if (this->Quadric)
  {
    QuadricStar(this->Q, p, step, values, g);
    return;
  }
  const int n = std::max(this->Degree, 0);
  double px[MaxDegree + 1], py[MaxDegree + 1], pz[MaxDegree + 1];
  this->PowerTables(p, px, py, pz);
  // sum[a][m]: the terms with power m of variable a, without that variable's power
  // ((c·lo)·hi, the two other variables in axis order, each group in term order).
  double sum[3][MaxDegree + 1];
  const double* powers[3] = { px, py, pz };
  for (int a = 0; a < 3; ++a)
  {
    const double* lo = powers[a == 0 ? 1 : 0];
    const double* hi = powers[a == 2 ? 1 : 2];
    const int top = this->Terms.empty() ? -1 : this->AxisDegree[a];
    for (int m = 0; m <= top; ++m)
    {
      sum[a][m] = this->AxisSum<false>(a, m, lo, hi);
    }
    std::fill(sum[a] + top + 1, sum[a] + n + 1, 0.0);
  }
  for (int a = 0; a < 3; ++a)
  {
    int top = n;
    while (top > 0 && sum[a][top] == 0.0)
    {
      --top;
    }
    const double* c = sum[a];
    double v = 0.0, d = 0.0, minus = 0.0, plus = 0.0;
    const double x = p[a], xm = p[a] - step[a], xp = p[a] + step[a];
    for (int m = top; m >= 0; --m)
    {
      d = d * x + v;
      v = v * x + c[m];
      minus = minus * xm + c[m];
      plus = plus * xp + c[m];
    }
    if (a == 0)
    {
      values[0] = v;
    }
    g[a] = d;
    values[1 + 2 * a] = minus;
    values[2 + 2 * a] = plus;
  }
}

namespace
{
// [a, b]^n with exact handling of even powers.
Interval PowerInterval(const Interval& x, int n)
{
  if (n == 0)
  {
    return { 1.0, 1.0 };
  }
  const double a = IntegerPower(x.Lo, n), b = IntegerPower(x.Hi, n);
  if (n % 2 == 1 || x.Lo >= 0)
  {
    return { std::min(a, b), std::max(a, b) };
  }
  if (x.Hi <= 0)
  {
    return { std::min(a, b), std::max(a, b) };
  }
  return { 0.0, std::max(a, b) };
}

Interval Multiply(const Interval& x, const Interval& y)
{
  const double c[4] = { x.Lo * y.Lo, x.Lo * y.Hi, x.Hi * y.Lo, x.Hi * y.Hi };
  return { std::min({ c[0], c[1], c[2], c[3] }), std::max({ c[0], c[1], c[2], c[3] }) };
}
}

Polynomial3 Polynomial3::Derivative(int axis) const
{
  Polynomial3 r;
  for (const auto& t : this->Terms)
  {
    const int p[3] = { t.I, t.J, t.K };
    if (p[axis] > 0)
    {
      int q[3] = { t.I, t.J, t.K };
      --q[axis];
      r.Terms.push_back({ t.Coefficient * p[axis], q[0], q[1], q[2] });
    }
  }
  r.Finish();
  return r;
}

double Polynomial3::RoundingBound(double magnitude) const
{
  // Each term: at most degree + 3 roundings; the sum: one per term. Times 64 for the
  // row restrictions (binomial expansion about a row's middle) and double rounding.
  const double operations =
    std::max(this->Degree, 0) + 4.0 + static_cast<double>(this->Terms.size());
  return 64.0 * operations * DBL_EPSILON * magnitude;
}

Interval Polynomial3::EvaluateInterval(const Interval box[3], double* magnitude) const
{
  Interval px[MaxDegree + 1], py[MaxDegree + 1], pz[MaxDegree + 1];
  const int n = std::max(this->Degree, 0);
  for (int k = 0; k <= n; ++k)
  {
    px[k] = PowerInterval(box[0], k);
    py[k] = PowerInterval(box[1], k);
    pz[k] = PowerInterval(box[2], k);
  }
  Interval sum{ 0.0, 0.0 };
  double size = 0.0;
  for (const auto& t : this->Terms)
  {
    const Interval m = Multiply(Multiply(px[t.I], py[t.J]), pz[t.K]);
    const Interval c = t.Coefficient >= 0 ? Interval{ t.Coefficient * m.Lo, t.Coefficient * m.Hi }
                                          : Interval{ t.Coefficient * m.Hi, t.Coefficient * m.Lo };
    sum.Lo += c.Lo;
    sum.Hi += c.Hi;
    size += std::max(std::fabs(c.Lo), std::fabs(c.Hi));
  }
  if (magnitude)
  {
    *magnitude = size;
  }
  // Rounding: widen by the rounding of the terms' magnitudes (see the header), at least
  // a relative ulp-scale margin of the result.
  const double slack =
    std::max(1e-12 * (std::fabs(sum.Lo) + std::fabs(sum.Hi)), this->RoundingBound(size)) + 1e-300;
  return { sum.Lo - slack, sum.Hi + slack };
}

std::vector<double> Polynomial3::RestrictToLine(const double o[3], const double d[3]) const
{
  std::vector<double> r(std::max(this->Degree, 0) + 1, 0.0);
  this->RestrictToLine(o, d, r.data());
  return r;
}

void Polynomial3::RestrictToLine(const double o[3], const double d[3], double* out) const
{
  const int degree = std::max(this->Degree, 0);
  const int n = degree + 1;
  if (this->Quadric && this->Degree == 2)
  {
    // Q(o + t·d) = Q(o) + (∇Q(o)·d)·t + Q₂(d)·t², Q₂ the quadratic part.
    const double* q = this->Q;
    double g[3];
    QuadricValueOf(q, o[0], o[1], o[2], out[0]);
    QuadricGradientOf(q, o[0], o[1], o[2], g);
    out[1] = g[0] * d[0] + g[1] * d[1] + g[2] * d[2];
    out[2] = d[0] * (q[4] * d[0] + q[7] * d[1] + q[8] * d[2]) + d[1] * (q[5] * d[1] + q[9] * d[2]) +
      q[6] * d[2] * d[2];
    return;
  }
  if (this->EvenQuartic)
  {
    // Q2 of the squares s_k(t) = (o_k + t·d_k)², each a quadratic in t:
    // Q2 = q0 + s0·(q1 + q4·s0 + q7·s1 + q8·s2) + s1·(q2 + q5·s1 + q9·s2) + s2·(q3 + q6·s2).
    const double* q = this->Q2;
    double sq[3][3];
    for (int k = 0; k < 3; ++k)
    {
      sq[k][0] = o[k] * o[k];
      sq[k][1] = 2.0 * o[k] * d[k];
      sq[k][2] = d[k] * d[k];
    }
    double inner[3][3];
    for (int m = 0; m < 3; ++m)
    {
      inner[0][m] = (m == 0 ? q[1] : 0.0) + q[4] * sq[0][m] + q[7] * sq[1][m] + q[8] * sq[2][m];
      inner[1][m] = (m == 0 ? q[2] : 0.0) + q[5] * sq[1][m] + q[9] * sq[2][m];
      inner[2][m] = (m == 0 ? q[3] : 0.0) + q[6] * sq[2][m];
    }
    std::fill(out, out + n, 0.0);
    out[0] = q[0];
    for (int k = 0; k < 3; ++k)
    {
      for (int i = 0; i < 3; ++i)
      {
        for (int j = 0; j < 3; ++j)
        {
          out[i + j] += sq[k][i] * inner[k][j];
        }
      }
    }
    return;
  }
  // A line along one axis (grid rows of unrotated primitives): only that axis's
  // binomial expansion, the other two variables are powers of o. The products are
  // formed in the general path's order, whose other terms are exact zeros here, so the
  // coefficients are the same numbers.
  const int moving = (d[1] == 0.0 && d[2] == 0.0) ? 0
    : (d[0] == 0.0 && d[2] == 0.0)                ? 1
    : (d[0] == 0.0 && d[1] == 0.0)                ? 2
                                                  : -1;
  if (moving >= 0)
  {
    double line[MaxDegree + 1][MaxDegree + 1]; // line[k][m]: t^m in (o + t d)^k
    double power[3][MaxDegree + 1];            // o^k for the fixed axes
    const int nm = this->GetAxisDegree(moving);
    line[0][0] = 1.0;
    for (int k = 1; k <= nm; ++k)
    {
      for (int m = 0; m <= k; ++m)
      {
        line[k][m] = o[moving] * (m < k ? line[k - 1][m] : 0.0) +
          (m > 0 ? d[moving] * line[k - 1][m - 1] : 0.0);
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      power[a][0] = 1.0;
      for (int k = 1; a != moving && k <= this->GetAxisDegree(a); ++k)
      {
        power[a][k] = o[a] * power[a][k - 1] + 0.0;
      }
    }
    std::fill(out, out + n, 0.0);
    if (moving == 0)
    {
      // Grid rows: the loop below for moving == 0 with each term's fixed powers read once
      // (the same operations).
      for (const auto& t : this->Terms)
      {
        const double py = power[1][t.J], pz = power[2][t.K], c = t.Coefficient;
        const double* lk = line[t.I];
        for (int m = 0; m <= t.I; ++m)
        {
          const double lm = lk[m];
          if (lm == 0.0)
          {
            continue;
          }
          const double cm = c * (lm * py);
          if (cm != 0.0)
          {
            out[m] += cm * pz;
          }
        }
      }
      return;
    }
    for (const auto& t : this->Terms)
    {
      const int e[3] = { t.I, t.J, t.K };
      const int k = e[moving];
      // As the general path: (x part)·(y part), times the coefficient, times (z part).
      for (int m = 0; m <= k; ++m)
      {
        const double lm = line[k][m];
        double xy, z;
        if (moving == 0)
        {
          if (lm == 0.0)
          {
            continue;
          }
          xy = lm * power[1][t.J];
          z = power[2][t.K];
        }
        else if (moving == 1)
        {
          xy = power[0][t.I] * lm;
          z = power[2][t.K];
        }
        else
        {
          xy = power[0][t.I] * power[1][t.J];
          z = lm;
        }
        const double cm = t.Coefficient * xy;
        if (cm != 0.0)
        {
          out[m] += cm * z;
        }
      }
    }
    return;
  }
  // pw[a][k][m]: coefficient of t^m in (o_a + t·d_a)^k, from the binomial theorem.
  thread_local std::vector<double> scratch;
  scratch.assign(static_cast<size_t>(3) * n * n, 0.0);
  auto pw = [&](int a, int k, int m) -> double& { return scratch[(a * n + k) * n + m]; };
  for (int a = 0; a < 3; ++a)
  {
    const int na = this->GetAxisDegree(a);
    pw(a, 0, 0) = 1.0;
    for (int k = 1; k <= na; ++k)
    {
      for (int m = 0; m <= k; ++m)
      {
        pw(a, k, m) =
          o[a] * (m < k ? pw(a, k - 1, m) : 0.0) + (m > 0 ? d[a] * pw(a, k - 1, m - 1) : 0.0);
      }
    }
  }
  std::fill(out, out + n, 0.0);
  double xy[MaxDegree + 1];
  for (const auto& t : this->Terms)
  {
    // (x part)·(y part), then ·(z part), accumulated into out.
    std::fill(xy, xy + t.I + t.J + 1, 0.0);
    for (int i = 0; i <= t.I; ++i)
    {
      const double ci = pw(0, t.I, i);
      if (ci == 0.0)
        continue;
      for (int j = 0; j <= t.J; ++j)
      {
        xy[i + j] += ci * pw(1, t.J, j);
      }
    }
    for (int m = 0; m <= t.I + t.J; ++m)
    {
      const double cm = t.Coefficient * xy[m];
      if (cm == 0.0)
        continue;
      for (int k = 0; k <= t.K; ++k)
      {
        out[m + k] += cm * pw(2, t.K, k);
      }
    }
  }
}

void Polynomial3::RestrictToAxis(const double q[3], int axis, double* out) const
{
  const int n = this->AxisDegree[axis];
  if (this->Quadric && !this->Terms.empty())
  {
    // Q: 1, x, y, z, x², y², z², xy, xz, yz. With u, w the fixed variables of this axis:
    // c0 + c1·s + c2·s².
    QuadricOnAxis(this->Q, q, axis, n, out);
    return;
  }
  if (this->EvenQuartic)
  {
    // Q2 along the axis, in s² (c0 + c1·s² + c2·s⁴), the other squares fixed.
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    double c0, c1, c2;
    QuadricOnAxisOf(this->Q2, q[u] * q[u], q[w] * q[w], axis, c0, c1, c2);
    const double even[5] = { c0, 0.0, c1, 0.0, c2 };
    std::copy(even, even + n + 1, out);
    return;
  }
  std::fill(out, out + n + 1, 0.0);
  if (this->Terms.empty())
  {
    return;
  }
  // Powers of the two fixed variables only; each coefficient c·(lo·hi) summed in
  // term order (the product of the two powers commutes: the same bits in either order).
  const int lo = axis == 0 ? 1 : 0, hi = axis == 2 ? 1 : 2;
  double plo[MaxDegree + 1], phi[MaxDegree + 1];
  Powers(q[lo], this->AxisDegree[lo], plo);
  Powers(q[hi], this->AxisDegree[hi], phi);
  for (int m = 0; m <= n; ++m)
  {
    out[m] = this->AxisSum<true>(axis, m, plo, phi);
  }
}

namespace
{
// ExpandAbout's shifts and scalings for degree N (a compile-time constant: the loops
// unroll and the strides fold; the same operations in the same order for every N).
template <int N>
void ShiftAndScale(const double c[3], const double h[3], double* b)
{
  constexpr int m = N + 1;
  constexpr int stride[3] = { m * m, m, 1 };
  for (int a = 0; a < 3; ++a)
  {
    const int u = (a + 1) % 3, w = (a + 2) % 3;
    const double s = c[a], scale = h[a];
    const int st = stride[a];
    for (int pu = 0; pu <= N; ++pu)
    {
      for (int pw = 0; pw + pu <= N; ++pw)
      {
        double* line = b + pu * stride[u] + pw * stride[w];
        const int deg = N - pu - pw;
        if (s != 0.0)
        {
          for (int i = 0; i < deg; ++i)
          {
            for (int l = deg - 1; l >= i; --l)
            {
              line[l * st] += s * line[(l + 1) * st];
            }
          }
        }
        double power = scale;
        for (int l = 1; l <= deg; ++l)
        {
          line[l * st] *= power;
          power *= scale;
        }
      }
    }
  }
}
}

int Polynomial3::ExpandAbout(const double c[3], const double h[3], double* b) const
{
  const int n = this->Degree;
  if (n < 0 || n > TaylorMaxDegree)
  {
    return -1;
  }
  const int m = n + 1;
  std::fill(b, b + m * m * m, 0.0);
  if (this->Quadric && n == 2)
  {
    // Q(c + h∘u): the value and gradient at c (QuadricValueOf, QuadricGradientOf) times
    // h, the squares' and cross terms' coefficients times their h's (at most 6
    // roundings per coefficient: within the (3n+3)·ε above).
    const double* q = this->Q;
    double v, g[3];
    QuadricValueOf(q, c[0], c[1], c[2], v);
    QuadricGradientOf(q, c[0], c[1], c[2], g);
    const int stride[3] = { m * m, m, 1 };
    b[0] = v;
    for (int a = 0; a < 3; ++a)
    {
      b[stride[a]] = g[a] * h[a];
      b[2 * stride[a]] = q[QuadricSquare[a]] * (h[a] * h[a]);
      for (int e = a + 1; e < 3; ++e)
      {
        b[stride[a] + stride[e]] = q[QuadricCross[a][e]] * (h[a] * h[e]);
      }
    }
    return n;
  }
  if (this->EvenQuartic)
  {
    // Q2 of the squares s_a(u) = (c_a + h_a·u)² = c_a² + 2c_a·h_a·u + h_a²·u²: the
    // linear terms and squares of one axis, and the products of two axes' quadratics
    // (at most 4 roundings per product and 9 per sum: within the (3n+3)·ε above).
    const int stride[3] = { m * m, m, 1 };
    double sq[3][3];
    for (int a = 0; a < 3; ++a)
    {
      sq[a][0] = c[a] * c[a];
      sq[a][1] = 2.0 * (c[a] * h[a]);
      sq[a][2] = h[a] * h[a];
    }
    const double* q = this->Q2;
    b[0] = q[0];
    for (int a = 0; a < 3; ++a)
    {
      for (int i = 0; i < 3; ++i)
      {
        b[i * stride[a]] += q[QuadricLinear[a]] * sq[a][i];
        for (int j = 0; j < 3; ++j)
        {
          b[(i + j) * stride[a]] += q[QuadricSquare[a]] * sq[a][i] * sq[a][j];
        }
      }
      for (int e = a + 1; e < 3; ++e)
      {
        const double qc = q[QuadricCross[a][e]];
        for (int i = 0; i < 3; ++i)
        {
          for (int j = 0; j < 3; ++j)
          {
            b[i * stride[a] + j * stride[e]] += qc * sq[a][i] * sq[e][j];
          }
        }
      }
    }
    return n;
  }
  for (const auto& t : this->Terms)
  {
    b[(t.I * m + t.J) * m + t.K] = t.Coefficient;
  }
  // One axis at a time: every line of coefficients along the axis is a univariate
  // polynomial of degree n − (the other two powers), shifted to c by repeated synthetic
  // division, then scaled by h^l.
  static_assert(TaylorMaxDegree == 8, "ShiftAndScale is instantiated for degrees 0 to 8");
  switch (n)
  {
    case 0:
      break;
    case 1:
      ShiftAndScale<1>(c, h, b);
      break;
    case 2:
      ShiftAndScale<2>(c, h, b);
      break;
    case 3:
      ShiftAndScale<3>(c, h, b);
      break;
    case 4:
      ShiftAndScale<4>(c, h, b);
      break;
    case 5:
      ShiftAndScale<5>(c, h, b);
      break;
    case 6:
      ShiftAndScale<6>(c, h, b);
      break;
    case 7:
      ShiftAndScale<7>(c, h, b);
      break;
    default:
      ShiftAndScale<8>(c, h, b);
      break;
  }
  return n;
}

Polynomial3 Polynomial3::Absolute() const
{
  Polynomial3 r = *this;
  for (auto& t : r.Terms)
  {
    t.Coefficient = std::fabs(t.Coefficient);
  }
  r.Finish();
  return r;
}

Polynomial3 Polynomial3::Compose(const double A[3][3], const double b[3]) const
{
  Polynomial3 q[3];
  for (int a = 0; a < 3; ++a)
  {
    q[a] = Constant(b[a]) + Variable(0).Scaled(A[a][0]) + Variable(1).Scaled(A[a][1]) +
      Variable(2).Scaled(A[a][2]);
  }
  std::vector<Polynomial3> powers[3];
  for (int a = 0; a < 3; ++a)
  {
    const int n = this->GetAxisDegree(a);
    powers[a].resize(n + 1);
    powers[a][0] = Constant(1.0);
    for (int k = 1; k <= n; ++k)
    {
      powers[a][k] = powers[a][k - 1] * q[a];
    }
  }
  Polynomial3 r;
  for (const auto& t : this->Terms)
  {
    r = r + (powers[0][t.I] * powers[1][t.J] * powers[2][t.K]).Scaled(t.Coefficient);
  }
  return r;
}

std::string Polynomial3::ToString() const
{
  if (this->Terms.empty())
  {
    return "0";
  }
  std::string s;
  char buf[64];
  // Highest degree first reads naturally.
  for (auto it = this->Terms.rbegin(); it != this->Terms.rend(); ++it)
  {
    std::snprintf(buf, sizeof(buf), "%.17g", std::fabs(it->Coefficient));
    if (!s.empty())
    {
      s += it->Coefficient < 0 ? " - " : " + ";
    }
    else if (it->Coefficient < 0)
    {
      s += "-";
    }
    s += buf;
    const char* names = "xyz";
    const int pw[3] = { it->I, it->J, it->K };
    for (int a = 0; a < 3; ++a)
    {
      if (pw[a] == 1)
      {
        s += std::string("*") + names[a];
      }
      else if (pw[a] > 1)
      {
        s += std::string("*") + names[a] + "^" + std::to_string(pw[a]);
      }
    }
  }
  return s;
}

} // namespace pisurf
