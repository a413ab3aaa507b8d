// SPDX-License-Identifier: BSD-3-Clause
/**
 * The roots of a Pi-surface along one ray segment and the attributes of a hit: the
 * shared core of vtkPiRayCaster (which casts every pixel) and vtkPiImageTriangulator
 * (which casts the few lattice lines its views could not see). No VTK here.
 *
 * Polynomial products are restricted exactly to the ray and their roots certified by
 * FindRayRoots (PiRayRoots.h). Products with a non-polynomial factor fall back to a sign
 * scan of 4096 samples with bisection: such a scan can miss features thinner than one
 * sample, and it says so in the algorithms' documentation.
 */
#ifndef PiRayCast_h
#define PiRayCast_h

#include "PiRayRoots.h"

#include <vector>

namespace pisurf
{
class ProductKernel;

/// Casts rays at one product. Reentrant: several threads may cast with one caster.
class RayCaster
{
public:
  explicit RayCaster(const ProductKernel& kernel);

  /// Roots of F(start + t·d) on [0, length], in increasing t (d need not be unit; t is
  /// then in units of |d|). `options.AllRoots` false stops at the first.
  void Cast(const double start[3], const double d[3], double length,
    const RayRootOptions& options, std::vector<RayRoot>& roots) const;

  /// Whether the gradient vanishes at p on the scale `probe`: |∇F|·probe is at most
  /// `tolerance` times the largest |F| at the six points p ± probe·e_i. `logGradient`
  /// is log|∇F(p)|. Scale-free, so it holds for products whose |∇F| varies by orders of
  /// magnitude over the surface.
  bool IsSingular(const double p[3], double logGradient, double probe, double tolerance) const;

private:
  const ProductKernel& Kernel;
  std::vector<int> Counts; // line coefficients per polynomial factor
};
}

#endif
