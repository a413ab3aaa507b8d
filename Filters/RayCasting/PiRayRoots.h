// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiRayRoots.h
 * @brief certified roots of a Pi-surface along a ray: F(t) = Π p_i(t) − r on [t0, t1]
 *
 * Restricted to a ray o + t·d, every polynomial factor is a univariate polynomial p_i(t)
 * (see Polynomial3::RestrictToLine). The roots of F(t) = Π p_i(t) − r on [t0, t1] are
 * isolated by subdivision with enclosures that cannot miss anything:
 *
 * - each p_i over an interval is enclosed by its Bernstein coefficients there (the
 *   convex-hull property), and F by combining those in sign and log-magnitude, so a
 *   product of thousands of factors never overflows; an interval whose enclosure of F
 *   excludes 0 holds no root;
 * - F' = Σ p_i' Π_{j≠i} p_j is enclosed the same way; where it excludes 0, F is monotone,
 *   and a sign change between the ends means exactly one root, found by regula falsi
 *   (Illinois) with bisection to the tolerance;
 * - an interval shorter than the tolerance whose enclosure still contains 0 is a root:
 *   with a sign change it is a crossing, without one F touches zero there (a tangent
 *   root, flagged). Adjacent such intervals are reported once.
 *
 * Products of total degree up to 48 (the paper's models) take a faster path with the
 * same guarantees: the product itself in the Bernstein basis (a convolution of the
 * factors' power-of-two scaled Bernstein forms; its hull is never wider than the product
 * of the factors' hulls), exclusion by that hull, Descartes' rule of signs (one sign
 * variation among clearly signed coefficients = exactly one simple root) before the
 * monotonicity test, and Newton's method safeguarded by the bracket, from the control
 * polygon's zero crossing, that returns the midpoint of a bracket no longer than the
 * tolerance. Larger products (molecules) keep the general path above.
 *
 * Before that expansion, a segment of up to 16 factors is offered to a cheaper test
 * (the ray caster's octree leaves hand it short depth ranges, most of which need no
 * subdivision): each factor's centred form about the middle (its Taylor shift, widened
 * by the shift's rounding) encloses the factor and its derivative; a product enclosure
 * that misses r means no root, a derivative Σ p_i' Π_{j≠i} p_j of one sign (by the
 * product rule over the enclosures, or else by the logarithmic derivative Σ p_i'/p_i
 * where at most one factor may vanish: LogDerivativeSign) with F of
 * strictly opposite signs at the ends (beyond their rounding) means exactly one,
 * solved by the same Newton's method. Everything else goes on to the Bernstein form.
 * Where the caller already knows F to be monotone on the segment
 * (RayRootOptions::Monotone: the ray caster's octree proves it per leaf from enclosures
 * of the factors' derivatives over the leaf's box), the enclosures are skipped and the
 * signs at the ends decide.
 *
 * Thin features (a torus of minor radius 0.01, two spheres 1e-6 apart) are therefore
 * never skipped, unlike fixed-step marching. No VTK here.
 */
#ifndef PiRayRoots_h
#define PiRayRoots_h

#include <cmath>
#include <vector>

namespace pisurf
{

/// The root of phi in [a, b], where phi(a) = va and phi(b) = vb have opposite signs:
/// regula falsi with the Illinois modification (a stale end's value is halved), and
/// bisection where the secant leaves the bracket. Stops when the bracket is at most
/// `width` long or |phi| <= `small` (returns that point), after at most 200 steps.
template <class Function>
double BracketedRoot(
  const Function& phi, double a, double b, double va, double vb, double width, double small)
{
  int side = 0;
  for (int it = 0; it < 200 && b - a > width; ++it)
  {
    double t = 0.5 * (a + b);
    const double secant = b - vb * (b - a) / (vb - va);
    if (std::isfinite(secant) && secant > a && secant < b)
    {
      t = secant;
    }
    const double v = phi(t);
    if (std::fabs(v) <= small)
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

struct RayRoot
{
  double T;     ///< the parameter of the root
  bool Tangent; ///< F touches 0 there without changing sign
};

struct RayRootOptions
{
  double Tolerance = 1e-10; ///< length of the interval a root is known to
  bool AllRoots = true;     ///< false: stop at the first (smallest t) root
  int MaximumDepth = 200;   ///< subdivision depth guard
  /// The caller knows F to be strictly monotone on [t0, t1] (the ray caster's octree:
  /// ProductKernel::ClassifyBoxAndOctants on the leaf boxes the segment lies in): the
  /// enclosures that would prove it are skipped, and the segment holds a root exactly
  /// where F has opposite signs at its ends (an end within rounding of 0 still goes to
  /// the general search).
  bool Monotone = false;
};

/// The roots of the subdivision searches (FindRayRoots, MoleculeField::CastRay), which
/// arrive in increasing t. One within 2·tolerance of the last root added joins
/// its cluster: the tiny pieces on both sides of one root, or the chain of them where F
/// stays within the rounding slack around a multiple root (thousands of pieces wide
/// for a double root), report one root, at the middle of the cluster's first and last
/// members. A cluster is tangent when F has the same sign before and after it (at the
/// start of its first piece and the end of its last), or, where one of those values is
/// 0, when all its members are.
class RootCluster
{
public:
  RootCluster(std::vector<RayRoot>& roots, double tolerance)
    : Roots(roots)
    , Start(roots.size())
    , Tolerance(tolerance)
  {
  }
  // The root t of a piece where F is `before` at its start and `after` at its end.
  void Add(double t, bool tangent, double before, double after)
  {
    if (this->Roots.size() > this->Start && t - this->Last <= 2.0 * this->Tolerance)
    {
      this->Last = t;
      this->AllTangent = this->AllTangent && tangent;
      RayRoot& root = this->Roots.back();
      root.T = 0.5 * (this->First + this->Last);
      root.Tangent =
        this->Before != 0.0 && after != 0.0 ? (this->Before > 0) == (after > 0) : this->AllTangent;
      return;
    }
    this->Roots.push_back({ t, tangent });
    this->First = this->Last = t;
    this->Before = before;
    this->AllTangent = tangent;
  }

private:
  std::vector<RayRoot>& Roots;
  size_t Start;
  double Tolerance;
  double First = 0.0, Last = 0.0, Before = 0.0;
  bool AllTangent = true;
};

/// Roots of Π p_i(t) − r on [t0, t1], in increasing t. `factors[i]` holds the ascending
/// coefficients of p_i. Returns false (roots untouched) if an input is not finite.
bool FindRayRoots(const std::vector<std::vector<double>>& factors, double r, double t0, double t1,
  const RayRootOptions& options, std::vector<RayRoot>& roots);
/// The same with the factors' coefficients concatenated (`counts[i]` of them for p_i),
/// as ProductKernel::RestrictLine writes them. Allocation-free after warm-up (per-thread
/// work buffers), for casting millions of rays.
bool FindRayRoots(const double* coefficients, const int* counts, int factors, double r, double t0,
  double t1, const RayRootOptions& options, std::vector<RayRoot>& roots);
/// The same on the segment [cuts[0], cuts[pieces]] cut into `pieces` pieces
/// [cuts[k], cuts[k + 1]] (increasing), each with its own RayRootOptions::Monotone
/// (monotone[k]; options.Monotone is ignored). The roots of all pieces, in increasing t,
/// in one cluster: a root on a cut is reported once.
bool FindRayRoots(const double* coefficients, const int* counts, int factors, double r,
  const double* cuts, const int* monotone, int pieces, const RayRootOptions& options,
  std::vector<RayRoot>& roots);
}

#endif
