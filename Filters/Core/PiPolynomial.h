// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiPolynomial.h
 * @brief sparse trivariate polynomials with exact algebra, evaluation and line restriction
 *
 * The primitives of a Pi-surface are polynomials in local coordinates (u, v, w).
 * A Polynomial3 keeps its monomials sorted and merged, so two polynomials that are
 * mathematically equal compare equal term by term. No VTK here.
 */
#ifndef PiPolynomial_h
#define PiPolynomial_h

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace pisurf
{

/// The largest total degree a polynomial may reach: beyond it algebra is refused
/// (a degree-64 trivariate polynomial already has ~48k monomials).
constexpr int MaxDegree = 64;

/// The highest degree ExpandAbout handles (dense (n+1)³ coefficients on the stack).
constexpr int TaylorMaxDegree = 8;

/// A closed interval [Lo, Hi] of reals.
struct Interval
{
  double Lo, Hi;
  bool Contains(double v) const { return this->Lo <= v && v <= this->Hi; }
};

/// x·y over intervals, each bound rounded to nearest (callers widen by their own slack).
inline Interval TimesNearest(const Interval& x, const Interval& y)
{
  const double c[4] = { x.Lo * y.Lo, x.Lo * y.Hi, x.Hi * y.Lo, x.Hi * y.Hi };
  return Interval{ std::min({ c[0], c[1], c[2], c[3] }), std::max({ c[0], c[1], c[2], c[3] }) };
}

/// prefix[i] = Π_{j<i} f_j over intervals (prefix[0] = [1, 1]), for i = 0..n.
inline void PrefixProducts(const Interval* f, int n, Interval* prefix)
{
  prefix[0] = { 1.0, 1.0 };
  for (int i = 0; i < n; ++i)
  {
    prefix[i + 1] = TimesNearest(prefix[i], f[i]);
  }
}

/// The product rule over enclosures, Σ_i df_i·Π_{j≠i} f_j, as [lo, hi] (each term
/// prefix_i·df_i·suffix_i, the suffixes formed on the way back), and the sum of the
/// terms' magnitudes (for the caller's rounding slack). `prefix` from PrefixProducts.
inline void ProductRule(const Interval* f, const Interval* df, int n, const Interval* prefix,
  double& lo, double& hi, double& magnitude)
{
  Interval suffix = { 1.0, 1.0 };
  lo = hi = magnitude = 0.0;
  for (int i = n - 1; i >= 0; --i)
  {
    const Interval term = TimesNearest(TimesNearest(prefix[i], df[i]), suffix);
    lo += term.Lo;
    hi += term.Hi;
    magnitude += std::max(std::fabs(term.Lo), std::fabs(term.Hi));
    suffix = TimesNearest(suffix, f[i]);
  }
}

/// The sign of (Π f_i)' = Σ_i df_i·Π_{j≠i} f_j over enclosures, from the logarithmic
/// derivative, where every f_i but at most one (a) keeps one sign:
///   (Π f)' = Π_{j≠a} f_j · (df_a + f_a·Σ_{j≠a} df_j / f_j)
/// (without an a: Π f · Σ df_j / f_j). Each quotient's enclosure is only as wide as its
/// own two intervals, where each of ProductRule's terms carries the widths of all the
/// other factors: with many factors it proves a sign where ProductRule cannot. Returns
/// +1 / −1 where the bracket has that sign beyond `relative` of its terms' magnitudes
/// (far beyond the rounding of these operations, round to nearest), else 0 (also where a
/// quotient overflows, two factors may vanish, or a bound is NaN).
inline int LogDerivativeSign(const Interval* f, const Interval* df, int n, double relative)
{
  int vanishing = -1, sign = 1;
  double lo = 0.0, hi = 0.0, magnitude = 0.0;
  for (int i = 0; i < n; ++i)
  {
    if (!(f[i].Lo > 0.0 || f[i].Hi < 0.0))
    {
      if (vanishing >= 0)
      {
        return 0;
      }
      vanishing = i;
      continue;
    }
    sign = f[i].Hi < 0.0 ? -sign : sign;
    const Interval q = TimesNearest(df[i], Interval{ 1.0 / f[i].Hi, 1.0 / f[i].Lo });
    lo += q.Lo;
    hi += q.Hi;
    magnitude += std::max(std::fabs(q.Lo), std::fabs(q.Hi));
  }
  if (vanishing >= 0)
  {
    const Interval& fa = f[vanishing];
    const Interval& da = df[vanishing];
    const Interval t = TimesNearest(fa, Interval{ lo, hi });
    lo = da.Lo + t.Lo;
    hi = da.Hi + t.Hi;
    magnitude = std::max(std::fabs(da.Lo), std::fabs(da.Hi)) +
      std::max(std::fabs(fa.Lo), std::fabs(fa.Hi)) * magnitude;
  }
  if (!std::isfinite(magnitude))
  {
    return 0;
  }
  const double slack = relative * magnitude + 1e-290;
  return lo > slack ? sign : hi < -slack ? -sign : 0;
}

/// Octant o of the box [b0,b1]x[b2,b3]x[b4,b5]: the upper half [c, hi] on axis a when
/// bit a of o is set, the lower half [lo, c] otherwise, c = (lo + hi)/2 as computed.
inline void OctantBox(const double box[6], int o, double sub[6])
{
  for (int a = 0; a < 3; ++a)
  {
    const double mid = 0.5 * (box[2 * a] + box[2 * a + 1]);
    sub[2 * a] = (o >> a) & 1 ? mid : box[2 * a];
    sub[2 * a + 1] = (o >> a) & 1 ? box[2 * a + 1] : mid;
  }
}

struct Monomial
{
  double Coefficient;
  int I, J, K; // powers of x, y, z (or u, v, w)
};

class Polynomial3
{
public:
  Polynomial3() = default;
  static Polynomial3 Constant(double c);
  /// The variable x (axis 0), y (axis 1) or z (axis 2).
  static Polynomial3 Variable(int axis);

  const std::vector<Monomial>& GetTerms() const { return this->Terms; }
  /// Adds c·x^i y^j z^k (merging with an existing term). Cost: O(log terms + terms).
  void AddTerm(double c, int i, int j, int k);
  double GetCoefficient(int i, int j, int k) const;
  int GetDegree() const { return this->Degree; }
  /// Largest power of each variable separately.
  int GetAxisDegree(int axis) const { return this->AxisDegree[axis]; }
  bool IsConstant() const { return this->Degree <= 0; }
  bool IsZero() const { return this->Terms.empty(); }
  /// True if every coefficient is finite.
  bool IsFinite() const;

  Polynomial3 operator+(const Polynomial3& o) const;
  Polynomial3 operator-(const Polynomial3& o) const;
  Polynomial3 operator-() const;
  /// Product; the caller must make sure the degrees add up to at most MaxDegree.
  Polynomial3 operator*(const Polynomial3& o) const;
  Polynomial3 Scaled(double s) const;
  /// this^n by repeated squaring; the caller checks n·degree <= MaxDegree.
  Polynomial3 Pow(int n) const;

  /// Value at p. Cost: O(degree + terms).
  double Evaluate(const double p[3]) const;
  /// Value and gradient at p. Cost: O(degree + 3·terms), or for dense polynomials of
  /// degree 3 to 6 nested Horner's rule, or for quartics in x², y², z² only a quadric of
  /// the squares (its value may then differ from Evaluate's in the last bits).
  double EvaluateWithGradient(const double p[3], double g[3]) const;
  /// Degree <= 2 (spheres, cylinders, quadrics): GetQuadric() gives its dense
  /// coefficients 1, x, y, z, x², y², z², xy, xz, yz (all 0 for the zero polynomial),
  /// for QuadricStar.
  bool IsQuadric() const { return this->Quadric; }
  /// Degree 4 with only even powers of x, y and z (a quadric of their squares).
  bool IsEvenQuartic() const { return this->EvenQuartic; }
  const double* GetQuadric() const { return this->Q; }
  /// IsEvenQuartic(): the dense coefficients of the quadric of the squares (x², y², z²),
  /// in GetQuadric()'s order.
  const double* GetEvenQuadric() const { return this->Q2; }
  /// At p and at the six points p ± step[a]·e_a, with the gradient at p, in one pass:
  /// the terms are summed by the power of each variable separately (three partial-sum
  /// polynomials, 6 multiplications per term), then each axis is a univariate Horner
  /// evaluation. values[0] = P(p), values[1 + 2a] = P(p − step[a]·e_a),
  /// values[2 + 2a] = P(p + step[a]·e_a). The sums are formed in another order than
  /// Evaluate's, so the results may differ from it in the last bits.
  void EvaluateStar(const double p[3], const double step[3], double values[7], double g[3]) const;
  /// An enclosure of P over the box x ∈ box[0], y ∈ box[1], z ∈ box[2] (term-wise
  /// interval arithmetic; exact powers, so squares are never negative). Cost: O(terms).
  /// It also holds every value our evaluations compute there (Evaluate, the gradient's
  /// centre value, row restrictions): it is widened by RoundingBound(M), M = Σ|c_t|·
  /// max|x^i y^j z^k| over the box, not by a fraction of the result, so terms that
  /// cancel (1e48 − 1e48) cannot leave the rounding of their values outside. `magnitude`
  /// (optional) receives M.
  Interval EvaluateInterval(const Interval box[3], double* magnitude = nullptr) const;
  /// A bound on the rounding error of evaluating P at a point where Σ|c_t·x^t| <= M.
  double RoundingBound(double magnitude) const;
  /// ∂P/∂(axis) (exact).
  Polynomial3 Derivative(int axis) const;
  /// Coefficients c[0..degree] of t -> P(o + t·d) (exact substitution, ascending powers).
  std::vector<double> RestrictToLine(const double o[3], const double d[3]) const;
  /// The same into out[0..degree] without allocating (hot path of grid sampling);
  /// quadrics (and quartics in the squares only) from their dense coefficients.
  void RestrictToLine(const double o[3], const double d[3], double* out) const;
  /// The coefficients of u -> P(c + h∘u) (a Taylor shift to c on each axis, then the
  /// scaling by h), dense: b[(i·(n+1) + j)·(n+1) + k] multiplies u^i v^j w^k, n the
  /// degree (entries with i+j+k > n are 0). Needs (n+1)³ doubles at b. Returns n, or −1
  /// (nothing written) for the zero polynomial or a degree above TaylorMaxDegree.
  /// Cost: O(n⁴). Each coefficient is within (3n+3)·ε of the same computation on |P|
  /// at |c|, |h| (the caller's rounding bound: RoundingBound of P's magnitude).
  int ExpandAbout(const double c[3], const double h[3], double* b) const;
  /// The polynomial of the coefficients' absolute values (magnitude bounds).
  Polynomial3 Absolute() const;
  /// Coefficients out[0..GetAxisDegree(axis)] of u -> P(q with q[axis] = u): the terms
  /// summed by their power of that variable, the others fixed at q. Cost: O(terms).
  void RestrictToAxis(const double q[3], int axis, double* out) const;
  /// Substitutes the affine map q = A·p + b (q is this polynomial's variable).
  Polynomial3 Compose(const double A[3][3], const double b[3]) const;

  /// Text in the expression grammar (x y z, ^, *), with round-trip precision.
  std::string ToString() const;

private:
  void Finish();    // sorts, merges, drops zeros, then Summarize()
  void Summarize(); // recomputes the degree and the quadric fast path
  // Powers 0..degree of each coordinate of p.
  void PowerTables(const double p[3], double* px, double* py, double* pz) const;
  std::vector<Monomial> Terms;
  int Degree = -1;                 // -1 for the zero polynomial
  int AxisDegree[3] = { 0, 0, 0 }; // largest power of each variable (Summarize)
  // Degree <= 2 (spheres, cylinders, quadrics: most factors) is evaluated from dense
  // coefficients: 1, x, y, z, x², y², z², xy, xz, yz.
  bool Quadric = true;
  // Per term: its coefficient times each power, c·i, c·j, c·k (Summarize), so the
  // gradient needs no branch or conversion per term.
  std::vector<double> Scaled3;
  double Q[10] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
  // Per axis a, the terms grouped by their power of that variable (stable: term order
  // within a group), with the powers of the two other variables, lower axis first:
  // the group of power m is ByAxis[a][AxisStart[a][m] .. AxisStart[a][m + 1]). Each
  // partial sum of RestrictToAxis and EvaluateStar then accumulates in a register
  // instead of a scattered store and reload per term (Summarize).
  struct AxisTerm
  {
    double C;
    int Lo, Hi;
  };
  std::vector<AxisTerm> ByAxis[3];
  std::vector<int> AxisStart[3];
  // Degree 3 to NestedMaxDegree with at least a third of the dense coefficients present
  // (tori, expanded products): every coefficient of the dense form, for K = n..0,
  // J = n − K..0, I = n − J − K..0, so EvaluateWithGradient is nested Horner's rule in
  // x, then y, then z (value and gradient in ~C(n+3, 3) multiply-adds instead of a dozen
  // multiplications and table reads per term). Empty otherwise (Summarize).
  static constexpr int NestedMaxDegree = 6;
  std::vector<double> Nested;
  // Quartics with only even powers (tori and superquadrics of exponent 4 about their
  // centre): a quadric of the squares (x², y², z²), whose dense coefficients are Q2 (Q's
  // order). EvaluateWithGradient, RestrictToAxis, RestrictToLine and ExpandAbout then
  // evaluate that quadric (Summarize).
  bool EvenQuartic = false;
  double Q2[10] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
  // Σ over the group of power m on axis a of (C·lo^Lo)·hi^Hi, or with `inner` C·(lo^Lo·hi^Hi).
  template <bool Inner>
  double AxisSum(int a, int m, const double* lo, const double* hi) const;
};

/// The formulas of a dense quadric (coefficients q: 1, x, y, z, x², y², z², xy, xz, yz)
/// for any element type T: double, or a GCC vector of doubles that evaluates several
/// quadrics at once (ProductKernel's packed quadrics). The same operations in the same
/// order for every T, so each element has the bits of the double version. (Results go
/// through references: a function returning a vector by value changes its ABI with AVX.)
template <class T>
inline void QuadricValueOf(const T* q, const T& x, const T& y, const T& z, T& v)
{
  v = q[0] + x * (q[1] + q[4] * x + q[7] * y + q[8] * z) + y * (q[2] + q[5] * y + q[9] * z) +
    z * (q[3] + q[6] * z);
}
template <class T>
inline void QuadricGradientOf(const T* q, const T& x, const T& y, const T& z, T* g)
{
  g[0] = q[1] + 2 * q[4] * x + q[7] * y + q[8] * z;
  g[1] = q[2] + 2 * q[5] * y + q[7] * x + q[9] * z;
  g[2] = q[3] + 2 * q[6] * z + q[8] * x + q[9] * y;
}
/// Slots of the dense quadric coefficients: the linear term and the square of axis a,
/// and the cross term of axes a != b (−1 on the diagonal).
constexpr int QuadricLinear[3] = { 1, 2, 3 }, QuadricSquare[3] = { 4, 5, 6 };
constexpr int QuadricCross[3][3] = { { -1, 7, 8 }, { 7, -1, 9 }, { 8, 9, -1 } };

/// The coefficients c0 + c1·s + c2·s² of s -> Q(p with p[axis] = s), where qu and qw are
/// p's other two coordinates (axis + 1 and axis + 2, cyclically).
template <class T>
inline void QuadricOnAxisOf(const T* Q, const T& qu, const T& qw, int axis, T& c0, T& c1, T& c2)
{
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  c0 = Q[0] + Q[QuadricLinear[u]] * qu + Q[QuadricLinear[w]] * qw + Q[QuadricSquare[u]] * qu * qu +
    Q[QuadricSquare[w]] * qw * qw + Q[QuadricCross[u][w]] * qu * qw;
  c1 = Q[QuadricLinear[axis]] + Q[QuadricCross[axis][u]] * qu + Q[QuadricCross[axis][w]] * qw;
  c2 = Q[QuadricSquare[axis]];
}

/// The value of a dense quadric.
inline double QuadricValue(const double* q, double x, double y, double z)
{
  double v;
  QuadricValueOf(q, x, y, z, v);
  return v;
}

/// Polynomial3::RestrictToAxis of a quadric (dense coefficients Q, axis degree n on
/// `axis`), inline: out[0..n] of s -> Q(p with p[axis] = s) = c0 + c1·s + c2·s².
inline void QuadricOnAxis(const double* Q, const double p[3], int axis, int n, double* out)
{
  double c[3];
  QuadricOnAxisOf(Q, p[(axis + 1) % 3], p[(axis + 2) % 3], axis, c[0], c[1], c[2]);
  // (Written one by one: a loop of n + 1 copies becomes a library memcpy call.)
  out[0] = c[0];
  if (n >= 1)
  {
    out[1] = c[1];
  }
  if (n >= 2)
  {
    out[2] = c[2];
  }
}

/// Polynomial3::EvaluateWithGradient of a quadric (dense coefficients q), inline.
inline double QuadricWithGradient(const double* q, const double p[3], double g[3])
{
  QuadricGradientOf(q, p[0], p[1], p[2], g);
  return QuadricValue(q, p[0], p[1], p[2]);
}

/// Polynomial3::EvaluateStar of a quadric (dense coefficients q): along an axis a
/// quadric is its exact second-order Taylor polynomial, P(p ± h·e_a) = P(p) ± h·∂_a P +
/// h²·Q_aa. Inline, for callers that evaluate many quadrics per point.
inline void QuadricStar(
  const double* q, const double p[3], const double step[3], double values[7], double g[3])
{
  const double v = QuadricWithGradient(q, p, g);
  values[0] = v;
  for (int a = 0; a < 3; ++a)
  {
    const double h = step[a];
    const double curvature = h * h * q[4 + a];
    values[1 + 2 * a] = (v + curvature) - h * g[a];
    values[2 + 2 * a] = (v + curvature) + h * g[a];
  }
}

/// x^n for n >= 0 by repeated squaring (exact for small n, much cheaper than std::pow).
inline double IntegerPower(double x, int n)
{
  double r = 1.0;
  while (n > 0)
  {
    if (n & 1)
    {
      r *= x;
    }
    x *= x;
    n >>= 1;
  }
  return r;
}

/// Horner evaluation of c[0] + c[1]·t + ... .
inline double EvaluateUnivariate(const double* c, int n, double t)
{
  double v = 0.0;
  for (int i = n - 1; i >= 0; --i)
  {
    v = v * t + c[i];
  }
  return v;
}

/// The same and its derivative (the two Horner chains side by side).
inline double EvaluateUnivariateWithDerivative(const double* c, int n, double t, double& d)
{
  double v = 0.0;
  d = 0.0;
  for (int i = n - 1; i >= 0; --i)
  {
    d = d * t + v;
    v = v * t + c[i];
  }
  return v;
}

} // namespace pisurf

#endif
