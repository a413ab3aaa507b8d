// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiPolynomialFactor.h
 * @brief a primitive's polynomial in its local frame, ready to evaluate: values,
 * gradients, interval enclosures on boxes and restriction to lines
 *
 * BuildFactor (PiPrimitiveSpec.h) makes one from a validated PrimitiveSpec.
 */
#ifndef PiPolynomialFactor_h
#define PiPolynomialFactor_h

#include "PiExpression.h"
#include "PiPolynomial.h"

#include <memory>
#include <vector>

namespace pisurf
{

/// A primitive ready to evaluate: Poly in local coordinates q = A·p + B, with the scale
/// and sign folded into its coefficients. Bounded primitives know their world box.
struct PolynomialFactor
{
  Polynomial3 Poly;
  double A[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  double B[3] = { 0, 0, 0 };
  bool Bounded = false;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  /// The expression as written (polynomial primitives) and the factor it is scaled by:
  /// its interval enclosure is intersected with the others.
  std::shared_ptr<const ExpressionNode> Natural;
  double NaturalScale = 1.0;
  /// Natural is a single-use expression (IsSingleUse): the classifiers intersect with
  /// it (HasNaturalForm).
  bool NaturalSingleUse = false;
  /// The expression's variables are the local coordinates plus this (a polynomial
  /// primitive written about another point is centred there: see BuildFactor).
  double NaturalShift[3] = { 0, 0, 0 };
  /// ∂Poly/∂u, ∂v, ∂w: filled by PrepareIntervals() for the mean-value enclosure.
  Polynomial3 Gradient[3];
  bool HasGradient = false;
  /// Poly composed with the affine map (world coordinates) and the same composition of
  /// the coefficients' absolute values (a bound on every term's magnitude): filled by
  /// PrepareIntervals() when the degree is at most TaylorMaxDegree, for EvaluateTaylor.
  Polynomial3 World, WorldMagnitude;
  bool HasWorld = false;
  /// A is diagonal (translated and scaled primitives, expressions): a world axis is a
  /// local axis. Set by PrepareIntervals().
  bool Diagonal = false;

  /// Precomputes what EvaluateInterval needs for its tighter (mean-value) enclosure.
  void PrepareIntervals();

  void ToLocal(const double p[3], double q[3]) const
  {
    for (int i = 0; i < 3; ++i)
    {
      q[i] = this->A[i][0] * p[0] + this->A[i][1] * p[1] + this->A[i][2] * p[2] + this->B[i];
    }
  }
  /// ToLocal for a diagonal A (Diagonal), without its zeros.
  void ToLocalDiagonal(const double p[3], double q[3]) const
  {
    for (int i = 0; i < 3; ++i)
    {
      q[i] = this->A[i][i] * p[i] + this->B[i];
    }
  }
  double Evaluate(const double p[3]) const
  {
    double q[3];
    this->ToLocal(p, q);
    return this->Poly.Evaluate(q);
  }
  /// EvaluateWithGradient and EvaluateStar inline, for a quadric (Poly.IsQuadric()) in a
  /// diagonal frame (Diagonal): the same arithmetic, so the same bits, without the two
  /// calls (for callers that evaluate many factors per point).
  double QuadricWithGradient(const double p[3], double g[3]) const
  {
    double q[3], gl[3];
    this->ToLocalDiagonal(p, q);
    const double v = pisurf::QuadricWithGradient(this->Poly.GetQuadric(), q, gl);
    for (int j = 0; j < 3; ++j)
    {
      g[j] = this->A[j][j] * gl[j];
    }
    return v;
  }
  void QuadricStar(const double p[3], double h, double values[7], double g[3]) const
  {
    double q[3], gl[3];
    this->ToLocal(p, q);
    const double step[3] = { h * this->A[0][0], h * this->A[1][1], h * this->A[2][2] };
    pisurf::QuadricStar(this->Poly.GetQuadric(), q, step, values, gl);
    for (int a = 0; a < 3; ++a)
    {
      g[a] = this->A[a][a] * gl[a];
    }
  }
  double EvaluateWithGradient(const double p[3], double g[3]) const;
  /// f and ∇f at p and f at the six points p ± h·e_a (world axes), as
  /// Polynomial3::EvaluateStar orders them. One pass over the terms when the local
  /// frame is axis-aligned (A diagonal: translated and scaled primitives, expressions);
  /// otherwise seven evaluations.
  void EvaluateStar(const double p[3], double h, double values[7], double g[3]) const;
  /// An enclosure of f over the axis-aligned world box [b0,b1]x[b2,b3]x[b4,b5]: the
  /// intersection of the term-wise interval evaluation and, after PrepareIntervals(),
  /// the mean-value form f(c) + Σ ∂f(box)·[−h, h], whose width shrinks as h².
  Interval EvaluateInterval(const double box[6]) const;
  /// Enclosures of f over the box and, when `octants` is not null, over its eight
  /// octants (octant o is the upper half [c, hi] on axis a when bit a of o is set, the
  /// lower half [lo, c] otherwise, c = (lo + hi)/2 as computed), from one Taylor
  /// expansion of World about c: f(c + h∘u) = Σ b_α u^α, u ∈ [−1, 1]³, so each term
  /// ranges over ±|b_α| (over [0, b_α] when every power is even; over 0 and ±b_α with
  /// the octant's signs). The width shrinks with the box like |∇f|·h, without the
  /// cancellation of the monomial form far from the origin. Widened like
  /// EvaluateInterval by the rounding of our evaluations and of the expansions, bounded
  /// by the magnitude WorldMagnitude(|c| + h). False (nothing written) when
  /// PrepareIntervals() did not fill World. Cost: O(degree⁴) for the expansion, then
  /// O(terms) per octant. Where HasNaturalForm() the enclosures are intersected with
  /// the expression as written (IntersectNatural) unless `natural` is false: then they are
  /// the Taylor form's alone (wider or equal), for callers that intersect only where
  /// the Taylor form cannot decide.
  /// With `derivatives` (and `octants`): also each octant's enclosure of ∂f/∂x_axis,
  /// from the same expansion (∂/∂u_axis term by term, over the octant's half ranges),
  /// widened by degree² times the expansion's rounding and 1e-12 of its terms: it holds
  /// the exact derivative.
  bool EvaluateTaylor(const double box[6], Interval& whole, Interval* octants, bool natural = true,
    Interval* derivatives = nullptr, int axis = -1) const;
  /// Whether EvaluateTaylor intersects with the expression as written (IntersectNatural):
  /// a degree above 2 and a single-use expression, whose enclosure is the exact range.
  /// Other expressions are not used: on the paper's cup (two tori written as squares of
  /// sums, each variable three times) the intersection decided no box of the mesher or
  /// the ray caster that the Taylor forms left undecided, and cost 2 to 5 % of their
  /// instructions; on the table's top, (8z + 5)^6, it decides 13 % of the blocks.
  bool HasNaturalForm() const
  {
    return this->Natural && this->NaturalSingleUse && this->Poly.GetDegree() > 2;
  }
  /// EvaluateTaylor's last step on its natural = false enclosures of the same box: the
  /// enclosure of the expression as written over the box, intersected with `whole` if
  /// narrower than it, and then also each octant's with the octant's own.
  void IntersectNatural(const double box[6], Interval& whole, Interval* octants) const;
  /// The local box (an enclosure of the affine image) of a world box.
  void LocalBox(const double box[6], Interval local[3]) const;
  /// The enclosure of Natural (which must be set) over a local box, scaled and widened
  /// by the rounding of our evaluations where terms of magnitude up to `magnitude` cancel.
  Interval NaturalInterval(const Interval local[3], double magnitude) const;
  /// Coefficients of t -> f(o + t·d).
  std::vector<double> RestrictToLine(const double o[3], const double d[3]) const;
  /// The same into out[0..degree] without allocating.
  void RestrictToLine(const double o[3], const double d[3], double* out) const;
  /// The same polynomial expanded in world coordinates (for export).
  Polynomial3 WorldPolynomial() const;
};
}

#endif
