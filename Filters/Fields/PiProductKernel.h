// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiProductKernel.h
 * @brief overflow-safe evaluation of F = Π f_i − r and its exact gradient
 *
 * A product of thousands of factors leaves the double range long before the surface
 * does (near F = 0 the product equals r, but the partial products on the way there may
 * be 10^±5000). The kernel therefore carries the product P and its gradient G with one
 * shared binary exponent: (P, G)·2^e, renormalised whenever max(|P|, |G|) leaves
 * [2^-256, 2^256]. The gradient follows the product rule factor by factor,
 *   G ← G·f_i + P·∇f_i,   P ← P·f_i,
 * which is exactly ∇F = Σ_i ∇f_i Π_{j≠i} f_j, including factors that are exactly zero.
 *
 * What the double-returning methods give when |F| is outside the double range:
 * F and each gradient component are clamped to ±DBL_MAX (sign exact); a non-zero
 * product too small for a double is kept as ±(smallest denormal) when r = 0, so the sign
 * of F is always exact and F is 0 only where a factor is 0 (or the product equals r).
 * EvaluateScaled() gives F itself as mantissa·2^exponent, without any clamping.
 *
 * The kernel is immutable once built and all methods are const and reentrant: any
 * number of threads may share one kernel.
 */
#ifndef PiProductKernel_h
#define PiProductKernel_h

#include "PiPrimitiveSpec.h"

#include <functional>
#include <vector>

namespace pisurf
{

/// A factor that is not a polynomial: returns f(p) and, when g is not null, ∇f(p).
/// Must be reentrant.
using GenericFunction = std::function<double(const double p[3], double* g)>;

struct Factor
{
  bool IsPolynomial = true;
  PolynomialFactor Polynomial;
  GenericFunction Generic;

  double Evaluate(const double p[3]) const
  {
    return this->IsPolynomial ? this->Polynomial.Evaluate(p) : this->Generic(p, nullptr);
  }
  double EvaluateWithGradient(const double p[3], double g[3]) const
  {
    return this->IsPolynomial ? this->Polynomial.EvaluateWithGradient(p, g) : this->Generic(p, g);
  }
};

/// +1 if Π f_i − r > 0 for every choice of f_i in enclosures[i], −1 if < 0 for every
/// choice, 0 otherwise. Magnitudes are combined as logarithms: never overflows.
int SignOfProductMinus(const std::vector<Interval>& enclosures, double r);
/// The same for n enclosures at e; where every end is 0 or within 2^±60 (and n <= 16)
/// the product is formed in doubles, widened by its rounding, without logarithms.
int SignOfProductMinus(const Interval* e, size_t n, double r);

class ProductKernel
{
public:
  ProductKernel(std::vector<Factor> factors, double blending);

  size_t GetNumberOfFactors() const { return this->Factors.size(); }
  const Factor& GetFactor(size_t i) const { return this->Factors[i]; }
  double GetBlending() const { return this->Blending; }
  /// True if every factor is a polynomial (exact restriction to lines is available).
  bool IsPolynomial() const { return this->AllPolynomial; }

  /// F(p), clamped as described above. Cost: one pass over the factors.
  double Evaluate(const double p[3]) const;
  /// F(p) and ∇F(p) (exact product rule), clamped as above.
  double EvaluateWithGradient(const double p[3], double g[3]) const;
  /// The first-order signed distance F/|∇F| to the surface and the unit normal
  /// ∇F/|∇F|, computed from the scaled product so that neither overflows however large
  /// the product is. Where ∇F = 0 the normal is 0 and the distance ±inf (or 0 on F = 0).
  double EvaluateDistance(const double p[3], double normal[3]) const;
  /// sign(F)·ln(1 + |F|) without overflow: the same signs and zero set as F, nearly F
  /// where |F| is small. Value only (no gradient): the cheap function for root finding.
  double EvaluateCompressed(const double p[3]) const;
  /// At a vertex, in one pass over the factors: the unit normal ∇F/|∇F| (0 where
  /// ∇F = 0), |∇F| (clamped to DBL_MAX), the nearest factor (see NearestFactor) and,
  /// if asked, ln|∇F| without clamping (−inf where ∇F = 0).
  void EvaluateVertex(const double p[3], double normal[3], double& gradientNorm, int& nearest,
    double* logGradientNorm = nullptr) const;
  /// EvaluateVertex at `count` points (up to MaxVertices), the same results (bit for
  /// bit): each factor is evaluated at every point before the next factor, the points
  /// as the four lanes of vector instructions where the factor is a quadric or a quartic
  /// in the squares in a diagonal frame (spheres, ellipsoids, axis-aligned cylinders,
  /// tori and superquadrics of exponent 4, centred expressions), and the product rule,
  /// normal and nearest factor likewise where the plain product holds at every point
  /// (the mesher's vertices, four at a time).
  static constexpr int MaxVertices = 4;
  void EvaluateVertices(
    int count, const double (*p)[3], double (*normal)[3], double* gradientNorm, int* nearest) const;
  /// Every factor (at most MaxVertices·8 of them) is a quadric or a quartic in the
  /// squares in a diagonal frame (spheres, ellipsoids, axis-aligned cylinders, tori,
  /// superquadrics of exponent 4, centred expressions): EvaluateOnSegments applies.
  bool HasStarFactorsOnly() const { return this->StarFactorsOnly; }
  /// Where HasStarFactorsOnly(): F and dF/ds = ∇F·d at the points a[j] + s[j]·d[j],
  /// j < count (up to MaxVertices; the mesher's Newton steps along grid edges, d the
  /// edge), from the factors' values and gradients, four points per vector
  /// instruction. ok[j] is false (as for EvaluateOnAxisWithSlope) where a factor's
  /// value is beyond 2^min(256, 1000 / factors) or non-zero below its inverse, where F
  /// or the slope is not finite, or where a local coordinate reaches 1e30.
  void EvaluateOnSegments(int count, const double (*a)[3], const double (*d)[3], const double* s,
    double* value, double* slope, bool* ok) const;
  /// EvaluateVertex and the values of F at the six points p ± probe·e_a (as mantissa·
  /// 2^exponent, ordered as Polynomial3::EvaluateStar: −x, +x, −y, +y, −z, +z) in one
  /// pass over the factors, each factor's terms read once (PolynomialFactor::
  /// EvaluateStar): the attributes of a surface point and its singularity probes
  /// (RayCaster::Attributes) for a third of the separate evaluations' work. The results
  /// may differ from EvaluateVertex's and EvaluateScaled's in the last bits.
  void EvaluateVertexStar(const double p[3], double probe, double normal[3], double& gradientNorm,
    int& nearest, double& logGradientNorm, double probeMantissa[6], long probeExponent[6]) const;
  /// What EvaluateVertexIfRegular needs for one probe length h and a box holding every
  /// point it will be asked about (PrepareProbes): per factor i and axis a, a bound on
  /// how far the factor's computed value at p ± s·e_a (|s| <= h) can be from its
  /// computed value at p plus s·∂_a f_i(p): Σ_{k>=2} h^k/k!·max|∂^k_a f_i| over the cell
  /// of the box that holds p, grown by h (up to 8³ cells where a factor's degree is above
  /// 2, fewer for big products: at most ~400 000 terms of interval evaluation), plus the
  /// rounding of the values and h times that of the gradient. +inf
  /// where no bound is known (a factor that is not a polynomial or of degree above
  /// TaylorMaxDegree): that factor's points then always take the probes.
  struct ProbeBounds
  {
    double Probe = 0.0;
    double Box[6] = { 0, -1, 0, -1, 0, -1 }; // points outside it take the probes
    int Cells[3] = { 1, 1, 1 };              // the box cut into cells, each its own slack
    std::vector<double> Slack;               // per cell (x fastest), factor and axis
  };
  ProbeBounds PrepareProbes(const double box[6], double probe) const;
  /// EvaluateVertex's attributes at p (the same bits), and whether p is certainly not
  /// singular on the probes' scale: true when |∇F|·h > tolerance·U, U an upper bound of
  /// the largest |F| at the six points p ± h·e_a as EvaluateVertexStar computes them
  /// (from F(p), the factors' values and gradients at p and the bounds' slack: the
  /// product rule with every factor moved by its largest change, no cancellation). Then
  /// RayCaster::Attributes's probe test cannot say singular and the six probes are
  /// skipped. False when it cannot tell (the outputs are then not to be used): p outside
  /// the bounds' box, products
  /// of more than 32 factors or outside the plain double range, non-polynomial factors,
  /// and points near a vanishing gradient. ln|∇F| only if asked (a logarithm per point).
  bool EvaluateVertexIfRegular(const double p[3], const ProbeBounds& bounds, double tolerance,
    double normal[3], double& gradientNorm, int& nearest, double* logGradientNorm = nullptr) const;
  /// EvaluateVertexIfRegular at `count` points (up to MaxVertices): the same results,
  /// bit for bit, regular[j] being its answer at p[j]. Where HasStarFactorsOnly(), the
  /// factors, the plain-range test, the bound of the probes' |F| and the product rule
  /// are evaluated at the four points at once, as the lanes of vector instructions
  /// (EvaluateVertices' kernels), with the scalar operations in their order; else one
  /// point at a time. (A ray's hits, four at a time: RayCaster::Attributes.)
  void EvaluateVerticesIfRegular(int count, const double (*p)[3], const ProbeBounds& bounds,
    double tolerance, double (*normal)[3], double* gradientNorm, int* nearest, bool* regular) const;
  /// F(p) = mantissa·2^exponent with mantissa in ±[0.5, 1) or 0; never overflows.
  void EvaluateScaled(const double p[3], double& mantissa, long& exponent) const;
  /// ln|F(p)| (−inf where F = 0) and the sign of F (−1, 0, 1); never overflows.
  int EvaluateSignAndLog(const double p[3], double& logAbs) const;

  /// F at n points (xyz interleaved), factor by factor over blocks of points, so no
  /// per-point dispatch on the factor kind. Cost: n·Σ(terms of f_i).
  void EvaluatePoints(const double* xyz, size_t n, double* values) const;
  /// F at the n points origin + i·step (a grid row). Polynomial factors are restricted
  /// to the line once and evaluated by Horner's rule: cost per point O(Σ deg f_i).
  void EvaluateLine(const double origin[3], const double step[3], int n, double* values) const;

  /// Over the box [b0,b1]x[b2,b3]x[b4,b5]: +1 if F > 0 everywhere, −1 if F < 0
  /// everywhere, 0 if the surface may cross it (or a factor is not a polynomial). From
  /// enclosures of the factors (PolynomialFactor::EvaluateTaylor up to degree 8, else
  /// EvaluateInterval), multiplied in doubles where nothing can overflow, else combined
  /// in sign and log-magnitude, so it never overflows. Cost: O(Σ degree⁴ + terms).
  int ClassifyBox(const double box[6]) const;
  /// ClassifyBox and, when that gives 0, the same for the box's eight octants (octant o
  /// takes the upper half on axis a when bit a of o is set; halves split at
  /// (lo + hi)/2), from one Taylor expansion of each factor about the box's centre
  /// (PolynomialFactor::EvaluateTaylor; factors without one use EvaluateInterval on
  /// each octant). Returns the box's sign; `octants` is written only when it is 0, and
  /// then only up to the first undecided octant (the ones after it are given 0: once
  /// an octant may hold the surface, so may the box), unless `allOctants` asks for
  /// every octant's sign (for a traversal that skips the decided ones).
  ///
  /// With `monotone` (and a world `axis`): for each undecided octant, +1 if F is
  /// strictly increasing along that axis throughout it, −1 if strictly decreasing, 0 if
  /// it may turn or the test does not apply (decided octants, more than 16 factors, a
  /// factor without a Taylor form, magnitudes beyond 2^±60). From each factor's
  /// enclosures on the octant and of its derivative (PolynomialFactor::EvaluateTaylor,
  /// the same expansion) by the product rule ∂F = Σ ∂f_i Π_{j≠i} f_j in interval
  /// arithmetic, which must exclude 0 by 1e-9 of its terms' magnitude (far beyond the
  /// rounding of the products and of any evaluation of F there), or else by the
  /// logarithmic derivative where at most one factor may vanish on the octant
  /// (LogDerivativeSign: tighter with many factors, the same margin). A segment along that
  /// axis in the octant then holds at most one root of F, and one exactly where F has
  /// opposite signs at its ends.
  int ClassifyBoxAndOctants(const double box[6], int octants[8], bool allOctants = false,
    int* monotone = nullptr, int axis = -1) const;

  /// Row restriction in two steps, for callers that evaluate the same line many times:
  /// RestrictLine fills GetLineCoefficientCount() coefficients (every polynomial
  /// factor restricted to t -> o + t·d), EvaluateRestricted gives F at parameter t
  /// (p = o + t·d is needed only for factors that are not polynomials). The result
  /// depends only on (coefficients, t): the same point evaluates identically however
  /// often it is asked for. F is clamped as by Evaluate.
  size_t GetLineCoefficientCount() const { return this->LineCoefficients; }
  void RestrictLine(const double o[3], const double d[3], double* coefficients) const;
  double EvaluateRestricted(const double* coefficients, double t, const double p[3]) const;
  /// EvaluateRestricted at the n parameters t0, t0 + 1, ..., t0 + n − 1 (points
  /// origin + i·step), bit-identical to it point by point, several points at a time: the
  /// factors' Horner chains of neighbouring points interleave (instruction-level
  /// parallelism) and the product is plain doubles wherever every factor and partial
  /// product stays within 2^±256 (where the scaled product would not rescale either);
  /// other points go through EvaluateRestricted.
  void EvaluateRestrictedRow(const double* coefficients, double t0, int n, const double origin[3],
    const double step[3], double* values) const;
  /// F and dF/dt at parameter t of a RestrictLine restriction, in plain doubles (the
  /// product rule over the factors), for Newton steps along a grid row; false if a
  /// factor is not a polynomial, leaves 2^±min(256, 1000 / factors) or a result is not
  /// finite (as EvaluateOnAxisWithSlope).
  bool EvaluateRestrictedWithSlope(
    const double* coefficients, double t, double& value, double& slope) const;

  /// Along the line through p parallel to world axis `axis`: each factor as a
  /// univariate polynomial in its local coordinate along that axis
  /// (GetLineCoefficientCount() doubles, each factor's degree + 1), for EvaluateOnAxis:
  /// one pass over the terms, then a few operations per evaluation. False (nothing
  /// usable written) if a factor is not a polynomial or has a rotated frame.
  bool RestrictToAxis(const double p[3], int axis, double* coefficients) const;
  /// F at the point of that line whose coordinate `axis` is x, overflow-safe and clamped
  /// as Evaluate (it may differ from Evaluate in the last bits).
  double EvaluateOnAxis(const double* coefficients, int axis, double x) const;
  /// F and dF/dx there in plain doubles (the product rule over the factors), for Newton
  /// steps; false where a factor leaves 2^±min(256, 1000 / factors) or a result is not
  /// finite (then use EvaluateOnAxis).
  bool EvaluateOnAxisWithSlope(
    const double* coefficients, int axis, double x, double& value, double& slope) const;
  /// The same point for products of any size: F (clamped, exact sign, as
  /// EvaluateOnAxis), the sign of P = Π f_i (0 if a factor is 0), ln|P| and its
  /// derivative d ln|P| / dx = Σ f_i'/f_i (NaN where P = 0), from the scaled product:
  /// never overflows. Newton's step on F is then (1 − r/P) / Σ f_i'/f_i with r/P from
  /// the logarithms, where F itself leaves the double range.
  void EvaluateOnAxisLog(const double* coefficients, int axis, double x, double& value,
    int& productSign, double& logProduct, double& logSlope) const;

  /// The factor with the smallest first-order distance |f_i|/|∇f_i| to its own zero set
  /// at p (the primitive whose patch p lies on); −1 without factors.
  int NearestFactor(const double p[3]) const;

private:
  // EvaluateVertex's first step for up to MaxPlainVertex polynomial factors: their values
  // and gradients at p into f and g; true if every value is non-zero, the product of
  // the values below 1 is at least 2^-250 and that of max(1, |f|, |∇f|∞) at most 2^250
  // (so every partial product lies within 2^±250: the plain path).
  static constexpr size_t MaxPlainVertex = 32;
  bool PlainVertexFactors(const double p[3], double* f, double (*g)[3]) const;
  // Its second step: nearest factor, product rule, unit normal and |∇F|; in plain
  // doubles if `plain` (PlainVertexFactors' answer), else with ScaledProduct (the
  // general path's bits).
  void FinishPlainVertex(const double* f, const double (*g)[3], double normal[3],
    double& gradientNorm, int& nearest, double* logGradientNorm, bool plain = true) const;
  // Accumulates one factor value into a per-point scaled product.
  static void Accumulate(double& m, long& e, double f);
  double Finish(double m, long e) const;

  std::vector<Factor> Factors;
  // 2^min(256, 1000 / factors): factor values within 2^± this multiply in plain doubles
  // with the scaled product's bits.
  double PlainBound = 1.0;
  double Blending;
  bool AllPolynomial;
  size_t LineCoefficients = 0;
  // Per factor: a quadric in a diagonal frame (evaluated inline by EvaluateVertex,
  // EvaluateVertexStar and RestrictToAxis).
  std::vector<unsigned char> StarQuadric;
  // Per factor: a quartic in the squares (IsEvenQuartic) in a diagonal frame (tori and
  // superquadrics about their centre, centred expressions): EvaluateVertices evaluates
  // it, like the StarQuadric ones, at four points per instruction.
  std::vector<unsigned char> StarEvenQuartic;
  bool StarFactorsOnly = false; // (HasStarFactorsOnly)
  // When every factor is a quadric of degree 2 in a diagonal frame (spheres, ellipsoids,
  // axis-aligned cylinders: the commonest products) and there are at most
  // MaxPlainVertex of them: their frames and coefficients as 16 rows (A00 A11 A22 B0 B1
  // B2 Q0..Q9) of QuadricStride doubles each, a multiple of 4 (the last factor repeated),
  // so that the per-vertex loops (PlainVertexFactors, RestrictToAxis,
  // EvaluateOnAxisWithSlope) evaluate four factors per instruction. The same arithmetic
  // per factor as the scalar code: the same bits.
  std::vector<double> QuadricRows;
  size_t QuadricStride = 0; // 0: not all factors are such quadrics
  void PackQuadrics();
};
}

#endif
