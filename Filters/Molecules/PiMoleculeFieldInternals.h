// SPDX-License-Identifier: BSD-3-Clause
// What the sources of MoleculeField share: the scaled product, the Local factor's
// formulas (one expression wherever a value is computed, so that every evaluation kind
// gives the same bits), the grid points of a box query, and the field's cell
// structures. Only MoleculeField's own sources include it.
#ifndef PiMoleculeFieldInternals_h
#define PiMoleculeFieldInternals_h

#include "PiFloat.h"
#include "PiMoleculeField.h"
#include "PiProductKernel.h" // SignOfProductMinus
#include "PiRayRoots.h"      // BracketedRoot
#include "PiScaledInterval.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <vector>

namespace pisurf
{
namespace moleculefield
{
constexpr double Big = 0x1p256;
constexpr double Small = 0x1p-256;
constexpr double Ln2 = 0.69314718055994530942;
// ln(DBL_MAX): beyond it a value is clamped.
constexpr double LogMax = 709.78;

// A product m·2^e with the gradient G sharing the exponent.
struct Scaled
{
  double M = 1.0;
  double G[3] = { 0, 0, 0 };
  long E = 0;

  void Renormalise(bool gradient)
  {
    double a = std::fabs(this->M);
    if (gradient)
    {
      a = std::max({ a, std::fabs(this->G[0]), std::fabs(this->G[1]), std::fabs(this->G[2]) });
    }
    if ((a > Big || a < Small) && a != 0.0 && std::isfinite(a))
    {
      int ex;
      pisurf::Frexp(a, &ex);
      this->M = pisurf::Ldexp(this->M, -ex);
      if (gradient)
      {
        for (double& g : this->G)
        {
          g = pisurf::Ldexp(g, -ex);
        }
      }
      this->E += ex;
    }
  }
  void Multiply(double f)
  {
    this->M *= f;
    this->Renormalise(false);
  }
  void Multiply(double f, const double gf[3])
  {
    for (int k = 0; k < 3; ++k)
    {
      this->G[k] = this->G[k] * f + this->M * gf[k];
    }
    this->M *= f;
    this->Renormalise(true);
  }
  // ln|m·2^e| (−inf for 0).
  double Log() const
  {
    return this->M == 0.0 ? -HUGE_VAL : std::log(std::fabs(this->M)) + this->E * Ln2;
  }
};

// F = m·2^e − level, clamped to ±DBL_MAX, with ln|F|.
inline double Finish(const Scaled& s, double level, double& logAbsF)
{
  const double logP = s.Log();
  if (logP > LogMax - 20)
  {
    logAbsF = logP; // level is negligible against |P| > 1e299
    return logP > LogMax ? std::copysign(DBL_MAX, s.M) : pisurf::Ldexp(s.M, s.E) - level;
  }
  if (level == 0.0 && s.M != 0.0 && logP < -740)
  {
    // Below the smallest double: keep the sign with the smallest denormal.
    logAbsF = logP;
    return std::copysign(std::numeric_limits<double>::denorm_min(), s.M);
  }
  const double F = (s.M == 0.0 ? 0.0 : pisurf::Ldexp(s.M, s.E)) - level;
  logAbsF = F == 0.0 ? -HUGE_VAL : std::log(std::fabs(F));
  return F;
}

inline double Distance2ToBox(const double c[3], const double box[6])
{
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double t =
      c[a] < box[2 * a] ? box[2 * a] - c[a] : (c[a] > box[2 * a + 1] ? c[a] - box[2 * a + 1] : 0.0);
    d2 += t * t;
  }
  return d2;
}

inline double FarthestDistance2(const double c[3], const double box[6])
{
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double t = std::max(std::fabs(c[a] - box[2 * a]), std::fabs(c[a] - box[2 * a + 1]));
    d2 += t * t;
  }
  return d2;
}

// The Local factor's formulas below are templates over the element type T: double, or
// a GCC vector of doubles (four atoms or grid points per instruction in RefineEdge and
// EvaluateBox). The same operations in the same order for every T, so each element has
// the bits of the double version. (Results go through references: a function returning
// a vector by value changes its ABI with AVX.)

// w(u) = 1 − smoothstep5(u) = 1 − u³(10 − 15u + 6u²) for u in [0, 1], as Weight and
// LocalTerm write it (the same expression: the same bits).
template <class T>
inline void WeightPolynomialOf(const T& u, T& w)
{
  w = 1.0 - u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
}
inline double WeightPolynomial(double u)
{
  double w;
  WeightPolynomialOf(u, w);
  return w;
}

// The Local weight w(u) = 1 − smoothstep5(u) on [0, 1] and its derivative.
inline double Weight(double u, double& derivative)
{
  if (u <= 0.0)
  {
    derivative = 0.0;
    return 1.0;
  }
  if (u >= 1.0)
  {
    derivative = 0.0;
    return 0.0;
  }
  derivative = -30.0 * u * u * (1.0 - u) * (1.0 - u);
  return WeightPolynomial(u);
}
// The Local factor g of an atom at squared distance d2 from its centre, as the product
// of F multiplies it (1 beyond ρ; f itself inside the sphere): the one expression of
// ComputeLocal and EvaluateBox, so that both give the same bits.
template <class T>
inline void LocalTermOf(const T& d2, double r2, double rho2, double inverseSpan, T& term)
{
  const T zero{}, one = zero + 1.0;
  const T f = d2 - r2;
  const T u = f * inverseSpan;
  T w;
  WeightPolynomialOf(u, w);
  const T g = f <= zero ? f : 1.0 + (f - 1.0) * w;
  term = d2 < rho2 ? g : one;
}
inline double LocalTerm(double d2, double r2, double rho2, double inverseSpan)
{
  double term;
  LocalTermOf(d2, r2, rho2, inverseSpan, term);
  return term;
}

// The Local factor as a function of f = d² − R²: g = f·w + (1 − w) with u = f/(ρ² − R²)
// clamped to [0, 1], without branches (g = f exactly inside the sphere, 1 exactly
// beyond ρ), and its derivative dg/df = w + (f − 1) w'(u)/(ρ² − R²).
template <class T>
inline void LocalFactorOf(const T& f, const T& inverseSpan, T& g, T& slope)
{
  const T zero{}, one = zero + 1.0;
  T u = f * inverseSpan;
  u = u > zero ? u : zero;
  u = u < one ? u : one;
  const T uu = u * u;
  const T w = 1.0 - uu * u * (10.0 - 15.0 * u + 6.0 * uu);
  const T dw = -30.0 * uu * (1.0 - u) * (1.0 - u);
  // (No branch here: a data-dependent one costs a quarter of the edge roots' time.)
  slope = w + (f - 1.0) * dw * inverseSpan;
  g = f * w + (1.0 - w);
}
inline double LocalFactor(double f, double inverseSpan, double& slope)
{
  double g;
  LocalFactorOf(f, inverseSpan, g, slope);
  return g;
}

// Four doubles per vector instruction (LocalTerms, MultiplyLocalRow).
typedef double MoleculeV4 __attribute__((vector_size(32)));
typedef double MoleculeV4Unaligned __attribute__((vector_size(32), aligned(8), may_alias));

// The grid points of a box query (EvaluateBox, OffOuterSideBox): how many per axis, the
// box they span and their coordinates, computed as the mesher computes them (origin +
// index·spacing). The coordinates live in a per-thread buffer until the next query.
struct BoxPoints
{
  int N[3];
  int First0;
  double Origin0, InverseSpacing0;
  double Box[6];
  const double* X[3];

  bool Set(const double origin[3], const double spacing[3], const int first[3], const int last[3])
  {
    thread_local std::vector<double> coordinates;
    size_t total = 0;
    for (int a = 0; a < 3; ++a)
    {
      this->N[a] = last[a] - first[a] + 1;
      if (this->N[a] <= 0 || !(spacing[a] > 0))
      {
        return false;
      }
      this->Box[2 * a] = origin[a] + first[a] * spacing[a];
      this->Box[2 * a + 1] = origin[a] + last[a] * spacing[a];
      total += this->N[a];
    }
    coordinates.resize(total);
    double* x = coordinates.data();
    for (int a = 0; a < 3; ++a)
    {
      for (int i = 0; i < this->N[a]; ++i)
      {
        x[i] = origin[a] + (first[a] + i) * spacing[a];
      }
      this->X[a] = x;
      x += this->N[a];
    }
    this->First0 = first[0];
    this->Origin0 = origin[0];
    this->InverseSpacing0 = 1.0 / spacing[0];
    return true;
  }

  // Calls visit(k, j, lo, hi, v1, v2) for each row (j, k) of points (along x) that may
  // come within sqrt(r2) of c: v1, v2 = the row's y and z minus c's, [lo, hi] the
  // points of the row within that distance, widened by two points on each side (the
  // caller's exact test decides). A row is skipped only when v1² + v2² >= r2, which
  // (v0² + v1²) + v2² then is too in floating point (rounding is monotone).
  template <class Visit>
  void ForRowsNear(const double c[3], double r2, Visit&& visit) const
  {
    for (int k = 0; k < this->N[2]; ++k)
    {
      const double v2 = this->X[2][k] - c[2];
      if (v2 * v2 >= r2)
      {
        continue;
      }
      for (int j = 0; j < this->N[1]; ++j)
      {
        const double v1 = this->X[1][j] - c[1];
        const double across = v1 * v1 + v2 * v2;
        if (across >= r2)
        {
          continue;
        }
        const double half = std::sqrt(r2 - across);
        // The conversions truncate: two points of margin cover them.
        const int lo = std::max(0,
          static_cast<int>((c[0] - half - this->Origin0) * this->InverseSpacing0) - 2 -
            this->First0);
        const int hi = std::min(this->N[0] - 1,
          static_cast<int>((c[0] + half - this->Origin0) * this->InverseSpacing0) + 2 -
            this->First0);
        visit(k, j, lo, hi, v1, v2);
      }
    }
  }
};
}

// Global mode: the far atoms of a cell, T(p) = L0 + G·d + ½ dᵀHd (d = p − Center) the
// Taylor polynomial of their log-product about the cell's centre, Bound the bound of
// its error over the cell, FarLogMin a lower bound of the log-product over the cell's
// box grown by FarMargin.
struct MoleculeField::FarField
{
  bool HasFar = false;
  double Center[3] = { 0, 0, 0 };
  double L0 = 0.0;
  double G[3] = { 0, 0, 0 };
  double H[6] = { 0, 0, 0, 0, 0, 0 }; // xx yy zz xy xz yz
  double Bound = 0.0;
  double FarLogMin = 0.0;

  double Log(const double p[3]) const
  {
    const double d[3] = { p[0] - this->Center[0], p[1] - this->Center[1], p[2] - this->Center[2] };
    const double* h = this->H;
    return this->L0 + this->G[0] * d[0] + this->G[1] * d[1] + this->G[2] * d[2] +
      0.5 * (h[0] * d[0] * d[0] + h[1] * d[1] * d[1] + h[2] * d[2] * d[2]) + h[3] * d[0] * d[1] +
      h[4] * d[0] * d[2] + h[5] * d[1] * d[2];
  }
  void Gradient(const double p[3], double g[3]) const
  {
    const double d[3] = { p[0] - this->Center[0], p[1] - this->Center[1], p[2] - this->Center[2] };
    const double* h = this->H;
    g[0] = this->G[0] + h[0] * d[0] + h[3] * d[1] + h[4] * d[2];
    g[1] = this->G[1] + h[3] * d[0] + h[1] * d[1] + h[5] * d[2];
    g[2] = this->G[2] + h[4] * d[0] + h[5] * d[1] + h[2] * d[2];
  }
};

struct MoleculeField::Cell
{
  std::vector<int> Near;
  // Local: the atoms whose sphere (radius R) meets the cell's box, ascending.
  std::vector<int> Inner;
  // Global: the far field (null in Local mode, where a cell is only its atoms).
  std::unique_ptr<FarField> Far;

  const FarField& GetFar() const
  {
    static const FarField none;
    return this->Far ? *this->Far : none;
  }
};

// Segments that start in a cell and are at most this long use its FarLogMin.
constexpr double FarMargin = 1.0;
// Supercells: SuperCells³ cells. Atoms beyond R + SuperNear of a supercell's box enter
// its cells through one expansion per supercell (the two-level far field).
constexpr int SuperCells = 4;
constexpr double SuperNear = 8.0;

struct MoleculeField::Expansion
{
  double L0 = 0.0;
  double G[3] = { 0, 0, 0 };
  double H[6] = { 0, 0, 0, 0, 0, 0 };
  double Bound = 0.0;
  double LogMin = 0.0;
  size_t Count = 0;
};

struct MoleculeField::Super
{
  double Box[6] = { 0, 0, 0, 0, 0, 0 };
  double Center[3] = { 0, 0, 0 };
  Expansion Far;
};

template <class Visit>
bool MoleculeField::ForAtomsNear(const double box[6], double margin, Visit&& visit) const
{
  const double s = this->Settings.CellSize;
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    const double t0 = std::floor((box[2 * a] - margin - this->Origin[a]) / s);
    const double t1 = std::floor((box[2 * a + 1] + margin - this->Origin[a]) / s);
    if (!(t1 >= 0 && t0 < this->Dims[a]))
    {
      return false; // beyond every bin
    }
    lo[a] = static_cast<int>(std::max(0.0, t0));
    hi[a] = static_cast<int>(std::min<double>(this->Dims[a] - 1, t1));
  }
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x)
      {
        const int bin = (z * this->Dims[1] + y) * this->Dims[0] + x;
        for (int k = this->BinStart[bin]; k < this->BinStart[bin + 1]; ++k)
        {
          if (visit(this->BinAtoms[k]))
          {
            return true;
          }
        }
      }
  return false;
}
}

#endif
