// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiField.h
 * @brief the one interface every algorithm evaluates: an implicit function F
 *
 * The mesher, the ray caster, the image-based triangulator and the sample function
 * work on a `pisurf::Field`. Two fields implement it: the product of primitives
 * (ProductField, PiProductField.h) and a molecule's Global or Local field
 * (MoleculeField, PiMoleculeField.h). A field answers the four required questions
 * (ClassifyBox, Evaluate, EvaluateCompressed, EvaluateVertex); the others have a
 * general answer built on those four, which a field overrides where its structure
 * answers faster (a molecule restricts itself to the atoms near a box, an edge or a
 * ray).
 *
 * One capability is asked for once, when an algorithm sets up: GetProductKernel(), the
 * product's factor-wise fast paths (restriction of every factor to grid rows and rays,
 * vertex attributes four points at a time, monotony proofs on octants). An algorithm
 * that gets one runs its row and lane passes on it; with null it runs the general
 * passes on the questions below. No algorithm asks which concrete field it holds.
 *
 * Contract: the sign of F is exact; F is clamped to ±DBL_MAX; every method is const
 * and reentrant (many threads share one field); the same point always evaluates to the
 * same value, whichever block, edge or ray asks. Testing/Core/TestPiFieldConformance.cxx
 * checks this contract on every field.
 */
#ifndef PiField_h
#define PiField_h

#include "PiRayRoots.h"

#include <cmath>
#include <vector>

namespace pisurf
{
class ProductKernel;

class Field
{
public:
  virtual ~Field() = default;

  /// The product's factor-wise fast paths (row and line restriction, vertex lanes,
  /// monotony proofs), or null for a field without them. Asked once at set-up.
  virtual const ProductKernel* GetProductKernel() const { return nullptr; }

  /// Over the box [b0,b1]x[b2,b3]x[b4,b5]: +1 if F > 0 everywhere, −1 if F < 0
  /// everywhere, 0 if the surface may cross it. Must never be wrong when not 0.
  virtual int ClassifyBox(const double box[6]) const = 0;
  /// F(p), clamped to ±DBL_MAX with its exact sign.
  virtual double Evaluate(const double p[3]) const = 0;
  /// sign(F)·ln(1 + |F|) without overflow: the same zero set, for root finding where F
  /// is huge.
  virtual double EvaluateCompressed(const double p[3]) const = 0;
  /// At a surface vertex: unit normal ∇F/|∇F| (0 where ∇F = 0), |∇F| (clamped) and the
  /// factor (for a molecule: the atom) whose zero set is nearest.
  virtual void EvaluateVertex(
    const double p[3], double normal[3], double& gradientNorm, int& nearest) const = 0;
  /// ClassifyBox and, when that gives 0, the same for the box's eight octants (octant o
  /// takes the upper half on axis a when bit a of o is set, as OctantBox cuts it).
  /// Returns the box's sign; `octants` is written only when it is 0, and then only up
  /// to the first undecided octant (the ones after it are given 0), unless `allOctants`
  /// asks for every octant's sign. The default asks ClassifyBox nine times at most.
  virtual int ClassifyBoxAndOctants(
    const double box[6], int octants[8], bool allOctants = false) const;
  /// The sign of F(p) (−1, 0, 1) and ln|F(p)| without overflow. The default takes both
  /// from Evaluate, whose logarithm is that of the clamped value.
  virtual int EvaluateSignAndLog(const double p[3], double& logAbs) const;
  /// The roots of F along o + t·d for t in [t0, t1], in increasing t (only the first
  /// unless options.AllRoots), each within options.Tolerance (in units of t). The
  /// default scans the sign of EvaluateCompressed at 4096 equal steps and bisects each
  /// change: it can miss features thinner than one step. A field that can enclose F
  /// along a ray certifies every root instead.
  virtual void CastRay(const double o[3], const double d[3], double t0, double t1,
    const RayRootOptions& options, std::vector<RayRoot>& roots) const;
  /// The attributes of a surface point p (EvaluateVertex's unit normal, |∇F| and
  /// nearest factor) and whether p is singular on the scale `probe`: |∇F|·probe is at
  /// most `tolerance` times the largest |F| at the six points p ± probe·e_i (compared
  /// in logarithms, so it holds where |∇F| and F leave the double range).
  virtual bool ProbeVertex(const double p[3], double probe, double tolerance, double normal[3],
    double& gradientNorm, int& nearest) const;

  /// The first root of F on the segment from `from` to `to`, where F(from) > 0, as the
  /// fraction s of the way, certified to within `tolerance` (a length): return true only
  /// when F > 0 provably holds before s − tolerance and a root lies within `tolerance` of
  /// s. A field with structure to exploit (a molecule, whose product is astronomically
  /// large away from its spheres) answers in one pass; the default says false, and the
  /// mesher's general root finding runs.
  virtual bool FirstRoot(
    const double from[3], const double to[3], double tolerance, double& s) const
  {
    (void)from;
    (void)to;
    (void)tolerance;
    (void)s;
    return false;
  }
  /// True only where p provably lies off the closure of the outer (unbounded) component
  /// of {F > 0}: in a bounded component of {F > 0}, or on its boundary. The outer
  /// envelope's flood fill does not pass such points, and a vertex root-found there is
  /// moved to the surface nearest the outside, so a grid too coarse to resolve the thin
  /// wall around such a component (the lens where two atom spheres overlap, at small r)
  /// cannot leak into it. The default knows nothing and says false.
  virtual bool OffOuterSide(const double p[3]) const
  {
    (void)p;
    return false;
  }
  /// Whether OffOuterSide (and OffOuterSideBox) may ever say true: the outer envelope
  /// asks once, and skips the per-point question for a field that never marks a point.
  virtual bool HasOffOuterSide() const { return false; }

  /// F at the grid points origin + (i, j, k)·spacing for first <= (i, j, k) <= last
  /// (the point computed as origin[a] + index·spacing[a], as the mesher does), written
  /// to values[(k − first[2])·strideZ + (j − first[1])·strideY + (i − first[0])], each
  /// clamped to ±DBL_MAX and equal bit for bit to Evaluate at that point. A field that
  /// can share work between the points of a box (a molecule: the atoms near the box are
  /// found once, and each atom visits only the points it reaches) answers; the default
  /// says false and the mesher evaluates point by point.
  virtual bool EvaluateBox(const double* /*origin*/, const double* /*spacing*/,
    const int* /*first*/, const int* /*last*/, long /*strideY*/, long /*strideZ*/,
    double* /*values*/) const
  {
    return false;
  }

  /// OffOuterSide at the same grid points as EvaluateBox, written as 1 (true) or 0 to
  /// flags[(k − first[2])·strideZ + (j − first[1])·strideY + (i − first[0])], each equal
  /// to OffOuterSide at that point. The default says false (not answered).
  virtual bool OffOuterSideBox(const double* /*origin*/, const double* /*spacing*/,
    const int* /*first*/, const int* /*last*/, long /*strideY*/, long /*strideZ*/,
    unsigned char* /*flags*/) const
  {
    return false;
  }

  /// A vertex on the mesher's edge from `a` to `b`.
  struct EdgeVertex
  {
    double S = 0.0; ///< the root, as the fraction of the way from a to b
    double Normal[3] = { 0, 0, 0 };
    double GradientNorm = 0.0;
    int Nearest = -1;
    bool OffOuterSide = false; ///< OffOuterSide(a + S·(b − a))
  };
  /// A vertex on the segment [a, b] where F(a) = va and F(b) = vb (the grid's values):
  /// with `from` = −1 and va, vb of opposite signs, a root within `tolerance` (a
  /// length), as the mesher's bracketed root finding would return; with `from` = 0 or 1
  /// (the end a or b), the first sign change met in 16 equal steps from that end and a
  /// root within it, as the mesher's search for the sheet nearest an end (a thin wall
  /// the grid does not resolve) would return; false if there is none. With the root,
  /// EvaluateVertex's answers at x = a + S·(b − a) (computed component by component with
  /// that formula) and whether x is OffOuterSide. A field that can restrict itself to
  /// the segment once (a molecule: the few atoms that reach it) answers in a fraction of
  /// the time of repeated Evaluate calls; the default says false.
  virtual bool RefineEdge(const double* /*a*/, const double* /*b*/, double /*va*/, double /*vb*/,
    int /*from*/, double /*tolerance*/, EdgeVertex& /*vertex*/) const
  {
    return false;
  }

protected:
  /// The largest of logAt(q) at the six probe points q = p ± probe·e_i (in the order
  /// −x, +x, −y, +y, −z, +z): ProbeVertex's right-hand side, for a field's own ln|F|.
  template <class LogAt>
  static double LargestLogAtProbes(const double p[3], double probe, LogAt&& logAt)
  {
    double largest = -HUGE_VAL;
    for (int k = 0; k < 6; ++k)
    {
      double q[3] = { p[0], p[1], p[2] };
      q[k / 2] += (k % 2 ? probe : -probe);
      const double value = logAt(q);
      largest = value > largest ? value : largest;
    }
    return largest;
  }
};
}

#endif
