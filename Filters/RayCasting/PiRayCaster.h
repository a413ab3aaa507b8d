// SPDX-License-Identifier: BSD-3-Clause
/**
 * The roots of a Pi-surface along one ray segment and the attributes of a hit: the
 * shared core of vtkPiRayCaster (which casts every pixel) and vtkPiImageTriangulator
 * (which casts the few lattice lines its views could not see). No VTK here.
 *
 * The caster works on a Field. Where the field offers the product's fast paths
 * (Field::GetProductKernel), polynomial products are restricted exactly to the ray and
 * their roots certified by FindRayRoots (PiRayRoots.h), and hits are attributed four at
 * a time; otherwise the field casts the ray itself (Field::CastRay: a molecule
 * certifies its roots; the general answer, used for products with a non-polynomial
 * factor, is a sign scan of 4096 samples with bisection, which can miss features
 * thinner than one sample, as the algorithms' documentation says).
 */
#ifndef PiRayCaster_h
#define PiRayCaster_h

#include "PiField.h"
#include "PiProductKernel.h"
#include "PiRayRoots.h"

#include <vector>

namespace pisurf
{

/// Casts rays at one field, which must outlive the caster. Reentrant: several threads
/// may cast with one caster.
class RayCaster
{
public:
  explicit RayCaster(const Field& field);

  /// Roots of F(start + t·d) on [0, length], in increasing t (d need not be unit; t is
  /// then in units of |d|). `options.AllRoots` false stops at the first.
  void Cast(const double start[3], const double d[3], double length, const RayRootOptions& options,
    std::vector<RayRoot>& roots) const;

  /// The attributes of a surface point (Field::ProbeVertex): unit normal, |∇F|, nearest
  /// factor; returns whether it is singular, i.e. whether
  /// the gradient vanishes at p on the scale `probe`: |∇F|·probe is at most `tolerance`
  /// times the largest |F| at the six points p ± probe·e_i. Scale-free, so it holds for
  /// products whose |∇F| varies by orders of magnitude over the surface.
  bool Attributes(const double p[3], double probe, double tolerance, double normal[3],
    double& gradientNorm, int& nearest) const;
  /// Attributes at `count` points (up to ProductKernel::MaxVertices), the same results:
  /// singular[j] its answer at p[j]. With prepared probes, the points that the factors
  /// prove regular take ProductKernel::EvaluateVerticesIfRegular, four at a time.
  void Attributes(int count, const double (*p)[3], double probe, double tolerance,
    double (*normal)[3], double* gradientNorm, int* nearest, bool* singular) const;
  /// Lets Attributes skip the six probes where the factors' values and gradients at p
  /// already prove the point regular (ProductKernel::EvaluateVertexIfRegular), for
  /// points in `box` and this probe length. The same answers, with EvaluateVertex's
  /// normal and |∇F| (which may differ from EvaluateVertexStar's in the last bits).
  /// Not thread-safe: call it before casting.
  void PrepareProbes(const double box[6], double probe);

  /// Roots on [t0, t1] of the product whose polynomial factors are already restricted
  /// to the ray (GetLineCoefficientCount() coefficients, as ProductKernel::RestrictLine
  /// or RayGrid::Restrict write them). Only for polynomial kernels.
  void CastRestricted(const double* coefficients, double t0, double t1,
    const RayRootOptions& options, std::vector<RayRoot>& roots) const;
  /// The same on [cuts[0], cuts[pieces]] cut into pieces, each monotone or not (see
  /// FindRayRoots).
  void CastRestricted(const double* coefficients, const double* cuts, const int* monotone,
    int pieces, const RayRootOptions& options, std::vector<RayRoot>& roots) const;
  size_t GetLineCoefficientCount() const { return this->LineCoefficients; }

private:
  // Attributes without the shortcut: the field's six probes.
  bool ProbedAttributes(const double p[3], double probe, double tolerance, double normal[3],
    double& gradientNorm, int& nearest) const;

  const Field* TheField;
  const ProductKernel* Kernel;       // the field's fast paths, or null
  ProductKernel::ProbeBounds Probes; // Probe 0: not prepared
  std::vector<int> Counts;           // line coefficients per polynomial factor
  size_t LineCoefficients = 0;
};

/// The rays of an orthographic grid, restricted cheaply: pixel (i, j) has its ray
/// start + t·D with start = O + i·U + j·V, t in [0, length]. Each polynomial factor is
/// composed once with the affine map (i, j, s) -> O + i·U + j·V + (length/2 + s)·D
/// (about the grid's centre and the rays' middle, so the expansion stays accurate);
/// SetRow substitutes j, Restrict then gives a pixel's coefficients in s by Horner's
/// rule in i: (deg + 1)(deg + 2)/2 multiply-adds per factor of degree deg, instead of
/// a full restriction of the trivariate polynomial per ray.
class RayGrid
{
public:
  /// Only for kernels whose factors are all polynomials.
  RayGrid(const ProductKernel& kernel, const double O[3], const double U[3], const double V[3],
    const double D[3], int w, int h, double length);

  /// The coefficients of row j (into `row`, resized as needed).
  void SetRow(int j, std::vector<double>& row) const;
  /// The restricted factors of pixel (i, row) into GetLineCoefficientCount() coefficients,
  /// in the parameter s = t − length/2 ∈ [−length/2, length/2].
  void Restrict(const std::vector<double>& row, int i, double* coefficients) const;
  double GetHalfLength() const { return this->HalfLength; }

private:
  struct Composed
  {
    int Degree;
    size_t Offset;    // of its (deg+1)^3 coefficients g[(m·(deg+1) + a)·(deg+1) + b]
    size_t RowOffset; // of its (deg+1)^2 row coefficients h[m·(deg+1) + a]
  };
  std::vector<Composed> Factors;
  std::vector<double> G;
  size_t RowSize = 0;
  double CentreI, CentreJ, HalfLength;
};
}

#endif
