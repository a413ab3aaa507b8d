// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiScaledInterval.h
 * @brief interval products of many factors without overflow, and the sign of a
 * product's derivative from enclosures of its factors
 *
 * Shared by the general ray-root path (FindRayRoots) and the molecule's ray search
 * (MoleculeField::CastRay). No VTK here.
 */
#ifndef PiScaledInterval_h
#define PiScaledInterval_h

#include "PiFloat.h"
#include "PiPolynomial.h" // Interval

#include <algorithm>
#include <cmath>
#include <vector>

namespace pisurf
{

/// An interval [Lo, Hi]·2^E, so that products of many factors stay representable.
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
      pisurf::Frexp(a, &ex);
      this->Lo = pisurf::Ldexp(this->Lo, -ex);
      this->Hi = pisurf::Ldexp(this->Hi, -ex);
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
      pisurf::Frexp(a, &ex);
      lo = pisurf::Ldexp(lo, -ex);
      hi = pisurf::Ldexp(hi, -ex);
      this->E += ex;
    }
    const double c[4] = { this->Lo * lo, this->Lo * hi, this->Hi * lo, this->Hi * hi };
    this->Lo = std::min({ c[0], c[1], c[2], c[3] });
    this->Hi = std::max({ c[0], c[1], c[2], c[3] });
    this->Normalize();
  }
};

/// Whether the derivative of a product, Σ_i f_i' Π_{j≠i} f_j, provably has one sign on a
/// piece where `f[i]` encloses factor i and `df[i]` its derivative: prefix and suffix
/// products (scaled, no overflow), the terms summed at the largest exponent, a relative
/// slack of 1e-12 for rounding. `prefix` and `suffix` are work buffers.
bool ProductDerivativeHasOneSign(const Interval* f, const Interval* df, size_t n,
  std::vector<ScaledInterval>& prefix, std::vector<ScaledInterval>& suffix);
}

#endif
