// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiField.h
 * @brief an implicit function F the mesher can work on without a ProductKernel
 *
 * vtkPiFlyingEdges meshes a ProductKernel (a product of polynomial factors, restricted
 * to grid rows) or, through this interface, any function that answers the same four
 * questions. A function whose factors are not worth evaluating at every point, such as
 * a molecule of 10^5 atoms where only the atoms near a point matter, implements it with
 * its own spatial structures (see PiMoleculeField.h).
 *
 * Contract, shared with ProductKernel: the sign of F is exact; F is clamped to
 * ±DBL_MAX; every method is const and reentrant (many threads share one field); the
 * same point always evaluates to the same value, whichever block or edge asks.
 */
#ifndef PiField_h
#define PiField_h

namespace pisurf
{

class Field
{
public:
  virtual ~Field() = default;

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
  /// True only where p provably lies off the closure of the outer (unbounded) component
  /// of {F > 0}: in a bounded component of {F > 0}, or on its boundary. The outer
  /// envelope's flood fill does not pass such points, and a vertex root-found there is
  /// moved to the surface nearest the outside, so a grid too coarse to resolve the thin
  /// wall around such a component (the lens where two atom spheres overlap, at small r)
  /// cannot leak into it. The default knows nothing and says false.
  /// The first root of F on the segment from `from` to `to`, where F(from) > 0, as the
  /// fraction s of the way, certified to within `tolerance` (a length): return true only
  /// when F > 0 provably holds before s − tolerance and a root lies within `tolerance` of
  /// s. A field with structure to exploit (a molecule, whose product is astronomically
  /// large away from its spheres) answers in one pass; the default says false, and the
  /// mesher's general root finding runs.
  virtual bool FirstRoot(const double from[3], const double to[3], double tolerance, double& s) const
  {
    (void)from;
    (void)to;
    (void)tolerance;
    (void)s;
    return false;
  }
  virtual bool OffOuterSide(const double p[3]) const
  {
    (void)p;
    return false;
  }

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
    double S = 0.0;          ///< the root, as the fraction of the way from a to b
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
  virtual bool RefineEdge(const double* /*a*/, const double* /*b*/, double /*va*/,
    double /*vb*/, int /*from*/, double /*tolerance*/, EdgeVertex& /*vertex*/) const
  {
    return false;
  }
};
}

#endif
