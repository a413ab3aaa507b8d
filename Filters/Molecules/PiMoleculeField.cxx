// SPDX-License-Identifier: BSD-3-Clause
#include "PiMoleculeField.h"
#include "PiFloat.h"

#include "PiProductKernel.h"  // SignOfProductMinus
#include "PiRayRoots.h" // BracketedRoot
#include "PiScaledInterval.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>

namespace pisurf
{

namespace
{
// { atomic number, radius in Å }.
struct Entry
{
  int Z;
  double Radius;
};

// Bondi, J. Phys. Chem. 68 (1964) 441, Table I (the values in common use).
const Entry BondiTable[] = { { 1, 1.20 }, { 2, 1.40 }, { 3, 1.82 }, { 6, 1.70 }, { 7, 1.55 },
  { 8, 1.52 }, { 9, 1.47 }, { 10, 1.54 }, { 11, 2.27 }, { 12, 1.73 }, { 14, 2.10 },
  { 15, 1.80 }, { 16, 1.80 }, { 17, 1.75 }, { 18, 1.88 }, { 19, 2.75 }, { 28, 1.63 },
  { 29, 1.40 }, { 30, 1.39 }, { 31, 1.87 }, { 33, 1.85 }, { 34, 1.90 }, { 35, 1.85 },
  { 36, 2.02 }, { 46, 1.63 }, { 47, 1.72 }, { 48, 1.58 }, { 49, 1.93 }, { 50, 2.17 },
  { 52, 2.06 }, { 53, 1.98 }, { 54, 2.16 }, { 78, 1.72 }, { 79, 1.66 }, { 80, 1.55 },
  { 81, 1.96 }, { 82, 2.02 }, { 92, 1.86 } };

// Batsanov, Inorganic Materials 37 (2001) 871, crystallographic van der Waals radii;
// H from Rowland and Taylor, J. Phys. Chem. 100 (1996) 7384.
const Entry BatsanovTable[] = { { 1, 1.10 }, { 3, 2.20 }, { 4, 1.90 }, { 5, 1.80 },
  { 6, 1.70 }, { 7, 1.60 }, { 8, 1.55 }, { 9, 1.50 }, { 11, 2.40 }, { 12, 2.20 },
  { 13, 2.10 }, { 14, 2.10 }, { 15, 1.95 }, { 16, 1.80 }, { 17, 1.80 }, { 19, 2.80 },
  { 20, 2.40 }, { 21, 2.30 }, { 22, 2.15 }, { 23, 2.05 }, { 24, 2.05 }, { 25, 2.05 },
  { 26, 2.05 }, { 27, 2.00 }, { 28, 2.00 }, { 29, 2.00 }, { 30, 2.10 }, { 31, 2.10 },
  { 32, 2.10 }, { 33, 2.05 }, { 34, 1.90 }, { 35, 1.90 }, { 37, 2.90 }, { 38, 2.55 },
  { 39, 2.40 }, { 40, 2.30 }, { 41, 2.15 }, { 42, 2.10 }, { 43, 2.05 }, { 44, 2.05 },
  { 45, 2.00 }, { 46, 2.05 }, { 47, 2.10 }, { 48, 2.20 }, { 49, 2.20 }, { 50, 2.25 },
  { 51, 2.20 }, { 52, 2.10 }, { 53, 2.10 }, { 55, 3.00 } };

template <size_t N>
double Lookup(const Entry (&table)[N], int z)
{
  for (const Entry& e : table)
  {
    if (e.Z == z)
    {
      return e.Radius;
    }
  }
  return 0.0;
}

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
double Finish(const Scaled& s, double level, double& logAbsF)
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

double Distance2ToBox(const double c[3], const double box[6])
{
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double t = c[a] < box[2 * a] ? box[2 * a] - c[a]
                                       : (c[a] > box[2 * a + 1] ? c[a] - box[2 * a + 1] : 0.0);
    d2 += t * t;
  }
  return d2;
}

double FarthestDistance2(const double c[3], const double box[6])
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

// RefineEdge's terms at one point of its edge, four atoms per instruction: for m in
// [0, count), v = W[m] + shift, G[m] = LocalFactor(K[m] + v², ...) and DG[m] = its
// derivative along the edge, with LocalFactor's operations in its order (the same bits).
// The arrays are read up to count rounded up to 4 (the caller pads them).
typedef double MoleculeV4 __attribute__((vector_size(32)));
typedef double MoleculeV4Unaligned __attribute__((vector_size(32), aligned(8), may_alias));
PISURF_AVX2_CLONES
void LocalTerms(const double* K, const double* W, const double* R2, const double* Inverse,
  int count, double shift, double delta, double* G, double* DG)
{
  for (int m = 0; m < count; m += 4)
  {
    const MoleculeV4 v = *reinterpret_cast<const MoleculeV4Unaligned*>(W + m) + shift;
    const MoleculeV4 f = *reinterpret_cast<const MoleculeV4Unaligned*>(K + m) + v * v -
      *reinterpret_cast<const MoleculeV4Unaligned*>(R2 + m);
    const MoleculeV4 inverseSpan = *reinterpret_cast<const MoleculeV4Unaligned*>(Inverse + m);
    MoleculeV4 g, slope;
    LocalFactorOf(f, inverseSpan, g, slope);
    *reinterpret_cast<MoleculeV4Unaligned*>(G + m) = g;
    *reinterpret_cast<MoleculeV4Unaligned*>(DG + m) = slope * 2.0 * v * delta;
  }
}

// EvaluateBox's row update for one atom: row[m] *= LocalTerm(d²) for m in [lo, hi], d²
// from xs[m] − cx and the row's fixed offsets v1, v2, four points per instruction
// (LocalTerm's operations in its order: the same bits), the last few one by one.
PISURF_AVX2_CLONES
void MultiplyLocalRow(double* row, const double* xs, int lo, int hi, double cx, double v1,
  double v2, double r2, double rho2, double inverse)
{
  int m = lo;
  for (; m + 3 <= hi; m += 4)
  {
    const MoleculeV4 v0 = *reinterpret_cast<const MoleculeV4Unaligned*>(xs + m) - cx;
    const MoleculeV4 d2 = v0 * v0 + v1 * v1 + v2 * v2;
    MoleculeV4 term;
    LocalTermOf(d2, r2, rho2, inverse, term);
    MoleculeV4Unaligned* out = reinterpret_cast<MoleculeV4Unaligned*>(row + m);
    *out = *out * term;
  }
  for (; m <= hi; ++m)
  {
    const double v0 = xs[m] - cx;
    row[m] *= LocalTerm(v0 * v0 + v1 * v1 + v2 * v2, r2, rho2, inverse);
  }
}

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
          static_cast<int>((c[0] - half - this->Origin0) * this->InverseSpacing0) - 2 - this->First0);
        const int hi = std::min(this->N[0] - 1,
          static_cast<int>((c[0] + half - this->Origin0) * this->InverseSpacing0) + 2 - this->First0);
        visit(k, j, lo, hi, v1, v2);
      }
    }
  }
};
}

double BondiRadius(int z)
{
  return Lookup(BondiTable, z);
}

double BatsanovRadius(int z)
{
  return Lookup(BatsanovTable, z);
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

MoleculeField::MoleculeField(std::vector<double> centers, std::vector<double> radii,
  const MoleculeSettings& settings, const double region[6])
  : Centers(std::move(centers))
  , Radii(std::move(radii))
  , Settings(settings)
{
  if (this->Centers.size() != 3 * this->Radii.size())
  {
    throw std::invalid_argument("MoleculeField: 3 coordinates per radius expected");
  }
  const double r = this->Settings.Blending;
  this->Level = this->Settings.Mode == MoleculeMode::Local ? r / (1.0 + r) : r;
  double box[6] = { region[0], region[1], region[2], region[3], region[4], region[5] };
  for (size_t i = 0; i < this->Radii.size(); ++i)
  {
    this->MaxReach = std::max(this->MaxReach, this->Reach(i));
    this->MaxRadius = std::max(this->MaxRadius, this->Radii[i]);
    for (int a = 0; a < 3; ++a)
    {
      box[2 * a] = std::min(box[2 * a], this->Centers[3 * i + a] - this->Reach(i));
      box[2 * a + 1] = std::max(box[2 * a + 1], this->Centers[3 * i + a] + this->Reach(i));
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!std::isfinite(box[2 * a + 1] - box[2 * a]))
    {
      throw std::invalid_argument("MoleculeField: the atoms and region span a non-finite extent");
    }
  }
  // Cells of CellSize, coarser if there would be more than MaxCells of them (atoms far
  // apart): the far-field bound is computed per cell, so any size is correct, and the
  // cells' memory (about 150 bytes each) stays bounded.
  constexpr double MaxCells = double(1 << 21);
  auto cellCount = [&](double size) {
    double n = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      n *= std::ceil((box[2 * a + 1] - box[2 * a]) / size) + 1;
    }
    return n;
  };
  while (cellCount(this->Settings.CellSize) > MaxCells)
  {
    this->Settings.CellSize *= 2;
  }
  const double s = this->Settings.CellSize;
  for (int a = 0; a < 3; ++a)
  {
    this->Origin[a] = box[2 * a] - 0.5 * s;
    this->Dims[a] = std::max(1, static_cast<int>(std::ceil((box[2 * a + 1] - box[2 * a]) / s)) + 1);
  }
  const size_t count = size_t(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  // Atoms by cell, for the neighbourhood queries.
  std::vector<int> cellOf(this->Radii.size());
  this->BinStart.assign(count + 1, 0);
  for (size_t i = 0; i < this->Radii.size(); ++i)
  {
    int c[3];
    for (int a = 0; a < 3; ++a)
    {
      c[a] = std::min(this->Dims[a] - 1,
        std::max(0, static_cast<int>(std::floor((this->Centers[3 * i + a] - this->Origin[a]) / s))));
    }
    cellOf[i] = (c[2] * this->Dims[1] + c[1]) * this->Dims[0] + c[0];
    ++this->BinStart[cellOf[i] + 1];
  }
  for (size_t c = 0; c < count; ++c)
  {
    this->BinStart[c + 1] += this->BinStart[c];
  }
  this->BinAtoms.resize(this->Radii.size());
  std::vector<int> fill(this->BinStart.begin(), this->BinStart.end() - 1);
  for (size_t i = 0; i < this->Radii.size(); ++i)
  {
    this->BinAtoms[fill[cellOf[i]]++] = static_cast<int>(i);
  }
  this->Cells.resize(count);
  this->Once.reset(new std::once_flag[count]);
  this->Ready.reset(new std::atomic<char>[count]);
  for (size_t c = 0; c < count; ++c)
  {
    this->Ready[c].store(0, std::memory_order_relaxed);
  }
  for (int a = 0; a < 3; ++a)
  {
    this->SuperDims[a] = (this->Dims[a] + SuperCells - 1) / SuperCells;
  }
  const size_t supers = size_t(this->SuperDims[0]) * this->SuperDims[1] * this->SuperDims[2];
  this->Supers.resize(supers);
  this->SuperOnce.reset(new std::once_flag[supers]);
  if (this->Settings.Mode == MoleculeMode::Local)
  {
    const size_t n = this->Radii.size();
    this->Atoms.resize(n);
    for (size_t i = 0; i < n; ++i)
    {
      LocalAtom& atom = this->Atoms[i];
      const double rho = this->Radii[i] + this->Settings.InfluenceRadius;
      for (int k = 0; k < 3; ++k)
      {
        atom.C[k] = this->Centers[3 * i + k];
      }
      atom.R = this->Radii[i];
      atom.R2 = this->Radii[i] * this->Radii[i];
      atom.Rho2 = rho * rho;
      // Finite even where ρ = R in doubles (an influence radius below rounding): every
      // use multiplies it by f or by w'(u), which vanishes where u is clamped.
      atom.InverseSpan = std::min(1e300, 1.0 / (atom.Rho2 - atom.R2));
    }
  }
}

MoleculeField::~MoleculeField() = default;

double MoleculeField::Reach(size_t i) const
{
  return this->Radii[i] +
    (this->Settings.Mode == MoleculeMode::Local ? this->Settings.InfluenceRadius
                                                : this->Settings.NearDistance);
}

double MoleculeField::AtomFactor(size_t i, const double p[3], double* g) const
{
  const double* c = &this->Centers[3 * i];
  const double v[3] = { p[0] - c[0], p[1] - c[1], p[2] - c[2] };
  const double R2 = this->Radii[i] * this->Radii[i];
  const double f = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - R2;
  if (this->Settings.Mode == MoleculeMode::Global)
  {
    if (g)
    {
      for (int k = 0; k < 3; ++k)
      {
        g[k] = 2.0 * v[k];
      }
    }
    return f;
  }
  const double rho = this->Radii[i] + this->Settings.InfluenceRadius;
  const double span = rho * rho - R2;
  const double u = f / span;
  double dw;
  const double w = Weight(u, dw);
  if (g)
  {
    // ∇g = w ∇f + (f − 1) w'(u) ∇u with ∇f = 2v, ∇u = 2v / span.
    const double s = 2.0 * (w + (f - 1.0) * dw / span);
    for (int k = 0; k < 3; ++k)
    {
      g[k] = s * v[k];
    }
  }
  return 1.0 + (f - 1.0) * w;
}

const MoleculeField::Cell* MoleculeField::CellAt(const double p[3]) const
{
  int c[3];
  for (int a = 0; a < 3; ++a)
  {
    const double t = std::floor((p[a] - this->Origin[a]) / this->Settings.CellSize);
    if (!(t >= 0 && t < this->Dims[a]))
    {
      return nullptr;
    }
    c[a] = static_cast<int>(t);
  }
  const long id = (long(c[2]) * this->Dims[1] + c[1]) * this->Dims[0] + c[0];
  Cell& cell = this->Cells[id];
  if (!this->Ready[id].load(std::memory_order_acquire))
  {
    std::call_once(this->Once[id], [&] { this->BuildCell(id, cell); });
    this->Ready[id].store(1, std::memory_order_release);
  }
  return &cell;
}

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

void MoleculeField::BuildCell(long id, Cell& cell) const
{
  const double s = this->Settings.CellSize;
  const int c[3] = { int(id % this->Dims[0]), int((id / this->Dims[0]) % this->Dims[1]),
    int(id / (long(this->Dims[0]) * this->Dims[1])) };
  double box[6];
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = this->Origin[a] + c[a] * s;
    box[2 * a + 1] = box[2 * a] + s;
  }
  // Near atoms: within their reach of the box.
  this->ForAtomsNear(box, this->MaxReach, [&](int i) {
    const double R = this->Reach(i);
    if (Distance2ToBox(&this->Centers[3 * i], box) < R * R)
    {
      cell.Near.push_back(i);
    }
    return false;
  });
  std::sort(cell.Near.begin(), cell.Near.end());
  if (this->Settings.Mode == MoleculeMode::Local)
  {
    for (int i : cell.Near)
    {
      // A relative slack far above rounding: an atom too many costs one test.
      if (Distance2ToBox(&this->Centers[3 * i], box) < this->Atoms[i].R2 * (1.0 + 1e-9))
      {
        cell.Inner.push_back(i);
      }
    }
    return;
  }
  // Far atoms. Those beyond R_j + SuperNear of the cell's supercell come through the
  // supercell's expansion (built once for 4³ cells); the others ("mid") are summed here.
  cell.Far.reset(new FarField);
  FarField& far = *cell.Far;
  for (int a = 0; a < 3; ++a)
  {
    far.Center[a] = box[2 * a] + 0.5 * s;
  }
  const Super& super = this->SuperAt(c);
  std::vector<int> mid, candidates;
  this->ForAtomsNear(super.Box, this->MaxRadius + SuperNear, [&](int i) {
    const double reach = this->Radii[i] + SuperNear;
    if (Distance2ToBox(&this->Centers[3 * i], super.Box) < reach * reach)
    {
      candidates.push_back(i); // not in the supercell's outer set
    }
    return false;
  });
  std::sort(candidates.begin(), candidates.end());
  std::set_difference(candidates.begin(), candidates.end(), cell.Near.begin(), cell.Near.end(),
    std::back_inserter(mid));
  const double h = 0.5 * std::sqrt(3.0) * s;
  Expansion local;
  AddFar(mid, far.Center, box, h, local);
  // The supercell's quadratic re-centred on the cell (exact for a quadratic); its bound
  // holds over the supercell, hence over the cell.
  const double d0[3] = { far.Center[0] - super.Center[0], far.Center[1] - super.Center[1],
    far.Center[2] - super.Center[2] };
  const double* H = super.Far.H;
  const double Hd[3] = { H[0] * d0[0] + H[3] * d0[1] + H[4] * d0[2],
    H[3] * d0[0] + H[1] * d0[1] + H[5] * d0[2], H[4] * d0[0] + H[5] * d0[1] + H[2] * d0[2] };
  far.L0 = local.L0 + super.Far.L0 + super.Far.G[0] * d0[0] + super.Far.G[1] * d0[1] +
    super.Far.G[2] * d0[2] + 0.5 * (d0[0] * Hd[0] + d0[1] * Hd[1] + d0[2] * Hd[2]);
  for (int k = 0; k < 3; ++k)
  {
    far.G[k] = local.G[k] + super.Far.G[k] + Hd[k];
  }
  for (int k = 0; k < 6; ++k)
  {
    far.H[k] = local.H[k] + H[k];
  }
  far.HasFar = local.Count + super.Far.Count > 0;
  far.Bound = local.Bound + super.Far.Bound;
  far.FarLogMin = local.LogMin + super.Far.LogMin;
  double seen = this->MaxBound.load();
  while (far.Bound > seen && !this->MaxBound.compare_exchange_weak(seen, far.Bound))
  {
  }
}

void MoleculeField::AddFar(const std::vector<int>& atoms, const double centre[3],
  const double box[6], double h, Expansion& out) const
{
  // The Taylor polynomial of Σ ln f_j about `centre`, the rigorous bound of its
  // remainder over `box` (half-diagonal h), and ln Π min f_j over `box` grown by
  // FarMargin (every atom here is more than R + FarMargin from the box).
  double boundSum = 0.0;
  Scaled farMin;
  for (int i : atoms)
  {
    const double* ci = &this->Centers[3 * i];
    const double v[3] = { centre[0] - ci[0], centre[1] - ci[1], centre[2] - ci[2] };
    const double R2 = this->Radii[i] * this->Radii[i];
    const double q = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - R2;
    out.L0 += std::log(q);
    for (int k = 0; k < 3; ++k)
    {
      out.G[k] += 2.0 * v[k] / q;
    }
    const double q2 = q * q;
    out.H[0] += 2.0 / q - 4.0 * v[0] * v[0] / q2;
    out.H[1] += 2.0 / q - 4.0 * v[1] * v[1] / q2;
    out.H[2] += 2.0 / q - 4.0 * v[2] * v[2] / q2;
    out.H[3] -= 4.0 * v[0] * v[1] / q2;
    out.H[4] -= 4.0 * v[0] * v[2] / q2;
    out.H[5] -= 4.0 * v[1] * v[2] / q2;
    const double e2 = Distance2ToBox(ci, box);
    const double e = std::sqrt(e2);
    const double qe = e2 - R2;
    boundSum += std::max(4.0 / std::pow(qe, 1.5), e * (4.0 * e2 + 12.0 * R2) / (qe * qe * qe));
    farMin.Multiply((e - FarMargin) * (e - FarMargin) - R2);
  }
  out.Count += atoms.size();
  out.Bound += h * h * h / 6.0 * boundSum;
  out.LogMin += atoms.empty() ? 0.0 : farMin.Log();
}

const MoleculeField::Super& MoleculeField::SuperAt(const int cell[3]) const
{
  int c[3];
  for (int a = 0; a < 3; ++a)
  {
    c[a] = cell[a] / SuperCells;
  }
  const long id = (long(c[2]) * this->SuperDims[1] + c[1]) * this->SuperDims[0] + c[0];
  Super& super = this->Supers[id];
  std::call_once(this->SuperOnce[id], [&] {
    const double s = this->Settings.CellSize * SuperCells;
    for (int a = 0; a < 3; ++a)
    {
      super.Box[2 * a] = this->Origin[a] + c[a] * s;
      super.Box[2 * a + 1] = super.Box[2 * a] + s;
      super.Center[a] = super.Box[2 * a] + 0.5 * s;
    }
    // Outer atoms: beyond R_j + SuperNear of the supercell's box.
    std::vector<int> outer;
    for (size_t i = 0; i < this->Radii.size(); ++i)
    {
      const double reach = this->Radii[i] + SuperNear;
      if (Distance2ToBox(&this->Centers[3 * i], super.Box) >= reach * reach)
      {
        outer.push_back(static_cast<int>(i));
      }
    }
    this->AddFar(outer, super.Center, super.Box, 0.5 * std::sqrt(3.0) * s, super.Far);
  });
  return super;
}

int MoleculeField::EvaluateExactSignAndLog(const double p[3], double& logAbs) const
{
  Scaled s;
  for (size_t i = 0; i < this->Radii.size(); ++i)
  {
    s.Multiply(this->AtomFactor(i, p, nullptr));
  }
  logAbs = s.Log();
  return s.M > 0 ? 1 : (s.M < 0 ? -1 : 0);
}

int MoleculeField::EvaluateApproximateSignAndLog(
  const double p[3], double& logAbs, double& bound) const
{
  const Cell* cell = this->CellAt(p);
  if (!cell)
  {
    bound = 0.0;
    return this->EvaluateExactSignAndLog(p, logAbs);
  }
  Scaled s;
  for (int i : cell->Near)
  {
    s.Multiply(this->AtomFactor(i, p, nullptr));
  }
  logAbs = s.Log();
  const FarField& far = cell->GetFar();
  bound = far.Bound;
  if (far.HasFar)
  {
    logAbs += far.Log(p);
  }
  return s.M > 0 ? 1 : (s.M < 0 ? -1 : 0);
}

double MoleculeField::ComputeExact(const double p[3], double& logAbsF) const
{
  Scaled s;
  for (size_t i = 0; i < this->Radii.size(); ++i)
  {
    s.Multiply(this->AtomFactor(i, p, nullptr));
  }
  return Finish(s, this->Level, logAbsF);
}

double MoleculeField::ComputeLocal(const Cell* cell, const double p[3]) const
{
  if (!cell)
  {
    return 1.0 - this->Level; // beyond every atom's influence: the product is 1
  }
  // The same arithmetic as AtomFactor, in the same (sorted) atom order.
  const double* centers = this->Centers.data();
  double product = 1.0;
  for (int i : cell->Near)
  {
    const double* c = centers + 3 * i;
    const double v0 = p[0] - c[0], v1 = p[1] - c[1], v2 = p[2] - c[2];
    const double d2 = v0 * v0 + v1 * v1 + v2 * v2;
    const LocalAtom& atom = this->Atoms[i];
    if (d2 < atom.Rho2) // (beyond ρ, g = 1)
    {
      product *= LocalTerm(d2, atom.R2, atom.Rho2, atom.InverseSpan);
    }
  }
  return product - this->Level;
}

double MoleculeField::Compute(const double p[3], double& logAbsF) const
{
  const Cell* cell = this->CellAt(p);
  if (this->Settings.Mode == MoleculeMode::Local)
  {
    const double F = this->ComputeLocal(cell, p);
    logAbsF = F == 0.0 ? -HUGE_VAL : std::log(std::fabs(F));
    return F;
  }
  if (!cell)
  {
    return this->ComputeExact(p, logAbsF);
  }
  Scaled s;
  for (int i : cell->Near)
  {
    s.Multiply(this->AtomFactor(i, p, nullptr));
  }
  const FarField& far = cell->GetFar();
  if (!far.HasFar)
  {
    return Finish(s, this->Level, logAbsF); // every atom that matters is exact
  }
  double approxLog = s.Log();
  approxLog += far.Log(p);
  const double logP = approxLog, bound = far.Bound;
  const double level = this->Level;
  if (s.M == 0.0)
  {
    logAbsF = level == 0.0 ? -HUGE_VAL : std::log(level);
    return -level;
  }
  if (s.M > 0 && level > 0 && std::fabs(logP - std::log(level)) <= bound + 1e-9)
  {
    // The approximation cannot decide the sign of P − r here: exact over all atoms.
    ++this->ExactCount;
    return this->ComputeExact(p, logAbsF);
  }
  // The sign of F is decided; |P| = e^logP within a factor e^±bound.
  const double sign = s.M > 0 ? 1.0 : -1.0;
  if (logP > LogMax - 20)
  {
    logAbsF = logP;
    return logP > LogMax ? sign * DBL_MAX : sign * std::exp(logP) - level;
  }
  if (level == 0.0 && logP < -740)
  {
    logAbsF = logP;
    return sign * std::numeric_limits<double>::denorm_min();
  }
  const double F = sign * std::exp(logP) - level;
  logAbsF = std::log(std::fabs(F));
  return F;
}

double MoleculeField::Evaluate(const double p[3]) const
{
  if (this->Settings.Mode == MoleculeMode::Local)
  {
    return this->ComputeLocal(this->CellAt(p), p);
  }
  double logAbsF;
  return this->Compute(p, logAbsF);
}

double MoleculeField::EvaluateCompressed(const double p[3]) const
{
  double logAbsF;
  const double F = this->Compute(p, logAbsF);
  if (F == 0.0)
  {
    return 0.0;
  }
  const double magnitude = std::fabs(F) < 1e200 ? std::log1p(std::fabs(F)) : logAbsF;
  return std::copysign(magnitude, F);
}

bool MoleculeField::FirstRoot(
  const double from[3], const double to[3], double tolerance, double& s) const
{
  if (this->Settings.Mode != MoleculeMode::Global || !(this->Level > 0))
  {
    return false;
  }
  const Cell* cell = this->CellAt(from);
  const double delta[3] = { to[0] - from[0], to[1] - from[1], to[2] - from[2] };
  const double A = delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2];
  const double length = std::sqrt(A);
  // Every atom that can vanish on the segment is near `from`'s cell (Near holds the
  // atoms within R + NearDistance of the cell's box) if the segment is shorter than
  // NearDistance.
  if (!cell || !(length > 0) || length > FarMargin || this->Settings.NearDistance <= FarMargin)
  {
    return false;
  }
  // q_i(u) = |from + u·delta − c_i|² − R_i² = A u² + B_i u + C_i on u in [0, 1].
  auto coefficients = [&](int i, double& B, double& C) {
    const double* c = &this->Centers[3 * i];
    const double v[3] = { from[0] - c[0], from[1] - c[1], from[2] - c[2] };
    B = 2.0 * (v[0] * delta[0] + v[1] * delta[1] + v[2] * delta[2]);
    C = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - this->Radii[i] * this->Radii[i];
  };
  // s1: the first u in (0, 1] where a near factor vanishes.
  double s1 = HUGE_VAL;
  for (int i : cell->Near)
  {
    double B, C;
    coefficients(i, B, C);
    if (!(C > 0))
    {
      return false; // `from` inside or on a sphere: not the outside case this handles
    }
    const double disc = B * B - 4.0 * A * C;
    if (disc < 0 || B >= 0)
    {
      continue; // no real root, or both roots at u < 0 (C > 0, B >= 0)
    }
    // The smaller root, without cancellation: 2C / (−B + sqrt(disc)).
    const double u = 2.0 * C / (-B + std::sqrt(disc));
    if (u <= 1.0)
    {
      s1 = std::min(s1, u);
    }
  }
  if (!(s1 <= 1.0))
  {
    return false; // no sphere entered: a root of another kind (P dips below the level)
  }
  const double eps = tolerance / length;
  const double u1 = s1 - eps;
  if (!(u1 > 0))
  {
    return false;
  }
  // ln of a lower bound of |P| on [0, u1]: the near factors' exact minima there (none
  // vanishes before s1), the far factors' minima over the whole segment.
  auto minimum = [&](double B, double C) {
    // min over [0, u1] of A u² + B u + C (positive there).
    double m = std::min(C, (A * u1 + B) * u1 + C);
    const double vertex = -B / (2.0 * A);
    if (vertex > 0 && vertex < u1)
    {
      m = std::min(m, C - B * B / (4.0 * A));
    }
    return m;
  };
  Scaled bound;
  for (int i : cell->Near)
  {
    double B, C;
    coefficients(i, B, C);
    const double m = minimum(B, C);
    if (!(m > 0))
    {
      return false; // rounding: let the general method decide
    }
    bound.Multiply(m);
  }
  double logBound = bound.Log() + (cell->GetFar().HasFar ? cell->GetFar().FarLogMin : 0.0);
  // Rounding in the minima: a relative 1e-12 per factor, far below the margin asked.
  const double margin = 1e-9 * static_cast<double>(this->Radii.size()) + 1.0;
  if (!(logBound > std::log(this->Level) + margin))
  {
    return false;
  }
  s = s1 - 0.5 * eps;
  return true;
}

bool MoleculeField::OffOuterSide(const double p[3]) const
{
  if (!(this->Level > 0))
  {
    return false; // F = −level >= 0 on the spheres: the argument does not hold
  }
  if (this->Settings.Mode == MoleculeMode::Local)
  {
    // The cell's atoms whose sphere meets its box (a Local cell is cheap to build); no
    // cell: p is beyond every atom's reach.
    const Cell* cell = this->CellAt(p);
    if (!cell)
    {
      return false;
    }
    for (int i : cell->Inner)
    {
      const double* c = &this->Centers[3 * i];
      const double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2];
      if (dx * dx + dy * dy + dz * dz < this->Radii[i] * this->Radii[i])
      {
        return true;
      }
    }
    return false;
  }
  // The atoms binned within the largest radius of p (no cell is built: in Global mode
  // that costs a pass over all atoms).
  const double point[6] = { p[0], p[0], p[1], p[1], p[2], p[2] };
  return this->ForAtomsNear(point, this->MaxRadius, [&](int i) {
    const double* c = &this->Centers[3 * i];
    const double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2];
    return dx * dx + dy * dy + dz * dz < this->Radii[i] * this->Radii[i];
  });
}

void MoleculeField::EvaluateVertex(
  const double p[3], double normal[3], double& gradientNorm, int& nearest) const
{
  double logGradientNorm;
  this->EvaluateVertex(p, normal, gradientNorm, nearest, logGradientNorm);
}

double MoleculeField::EvaluateWithLog(const double p[3], double& logAbsF) const
{
  return this->Compute(p, logAbsF);
}

bool MoleculeField::ProbeVertex(const double p[3], double probe, double tolerance,
  double normal[3], double& gradientNorm, int& nearest) const
{
  // ln|∇F| + ln probe <= ln tolerance + ln max|F(probes)|.
  double logGradient;
  this->EvaluateVertex(p, normal, gradientNorm, nearest, logGradient);
  double logProbe = -HUGE_VAL;
  for (int k = 0; k < 6; ++k)
  {
    double q[3] = { p[0], p[1], p[2] };
    q[k / 2] += (k % 2 ? probe : -probe);
    double logAbs;
    this->EvaluateWithLog(q, logAbs);
    logProbe = std::max(logProbe, logAbs);
  }
  return logGradient + std::log(probe) <= std::log(tolerance) + logProbe;
}

void MoleculeField::EvaluateVertex(const double p[3], double normal[3], double& gradientNorm,
  int& nearest, double& logGradientNorm) const
{
  const Cell* cell = this->CellAt(p);
  if (this->Settings.Mode == MoleculeMode::Local)
  {
    this->LocalVertex(p, cell ? cell->Near.data() : nullptr, cell ? cell->Near.size() : 0,
      normal, gradientNorm, nearest, nullptr);
    logGradientNorm = gradientNorm > 0 ? std::log(gradientNorm) : -HUGE_VAL;
    return;
  }
  std::vector<int> all;
  const std::vector<int>* atoms = nullptr;
  if (cell)
  {
    atoms = &cell->Near;
  }
  else if (this->Settings.Mode == MoleculeMode::Global)
  {
    all.resize(this->Radii.size());
    for (size_t i = 0; i < all.size(); ++i)
    {
      all[i] = static_cast<int>(i);
    }
    atoms = &all;
  }
  Scaled s;
  nearest = -1;
  double best = HUGE_VAL;
  if (atoms)
  {
    for (int i : *atoms)
    {
      double g[3];
      const double f = this->AtomFactor(i, p, g);
      s.Multiply(f, g);
      const double* c = &this->Centers[3 * i];
      const double d = std::sqrt((p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) +
        (p[2] - c[2]) * (p[2] - c[2]));
      const double distance = std::fabs(d - this->Radii[i]);
      if (distance < best)
      {
        best = distance;
        nearest = i;
      }
    }
  }
  // ∇P = 2^e e^L (G + m ∇L) with L the far atoms' log-sum.
  double grad[3] = { s.G[0], s.G[1], s.G[2] };
  double logScale = s.E * Ln2;
  if (cell && cell->GetFar().HasFar)
  {
    const FarField& far = cell->GetFar();
    double gl[3];
    far.Gradient(p, gl);
    for (int k = 0; k < 3; ++k)
    {
      grad[k] += s.M * gl[k];
    }
    logScale += far.Log(p);
  }
  const double norm = std::sqrt(grad[0] * grad[0] + grad[1] * grad[1] + grad[2] * grad[2]);
  if (norm == 0.0 || !std::isfinite(norm))
  {
    normal[0] = normal[1] = normal[2] = 0.0;
    gradientNorm = 0.0;
    logGradientNorm = -HUGE_VAL;
    return;
  }
  for (int k = 0; k < 3; ++k)
  {
    normal[k] = grad[k] / norm;
  }
  const double logNorm = std::log(norm) + logScale;
  gradientNorm = logNorm > LogMax ? DBL_MAX : std::exp(logNorm);
  logGradientNorm = logNorm;
}

bool MoleculeField::EvaluateBox(const double origin[3], const double spacing[3],
  const int first[3], const int last[3], long strideY, long strideZ, double* values) const
{
  BoxPoints points;
  if (this->Settings.Mode != MoleculeMode::Local || !points.Set(origin, spacing, first, last))
  {
    return false;
  }
  const int* n = points.N;
  // Every atom that reaches a point of the box (with a slack far above rounding: an
  // extra atom multiplies by exactly 1 where it is skipped), in ascending order as in
  // the cells' lists, so that each point's product is Evaluate's, factor by factor.
  thread_local std::vector<int> atoms;
  atoms.clear();
  this->ForAtomsNear(points.Box, this->MaxReach, [&](int i) {
    if (Distance2ToBox(&this->Centers[3 * i], points.Box) < this->Atoms[i].Rho2 * (1.0 + 1e-9))
    {
      atoms.push_back(i);
    }
    return false;
  });
  std::sort(atoms.begin(), atoms.end());
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      std::fill_n(values + k * strideZ + j * strideY, n[0], 1.0);
    }
  }
  const double* xs = points.X[0];
  for (int i : atoms)
  {
    const double* c = &this->Centers[3 * i];
    const LocalAtom& atom = this->Atoms[i];
    const double rho2 = atom.Rho2, r2 = atom.R2, inverse = atom.InverseSpan;
    const double cx = c[0];
    points.ForRowsNear(c, rho2, [&](int k, int j, int lo, int hi, double v1, double v2) {
      // ComputeLocal's arithmetic, term by term (the multiply by exactly 1 where the atom
      // is beyond ρ changes nothing).
      MultiplyLocalRow(
        values + k * strideZ + j * strideY, xs, lo, hi, cx, v1, v2, r2, rho2, inverse);
    });
  }
  const double level = this->Level;
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      double* row = values + k * strideZ + j * strideY;
      for (int m = 0; m < n[0]; ++m)
      {
        row[m] -= level;
      }
    }
  }
  return true;
}

bool MoleculeField::OffOuterSideBox(const double origin[3], const double spacing[3],
  const int first[3], const int last[3], long strideY, long strideZ, unsigned char* flags) const
{
  BoxPoints points;
  if (!points.Set(origin, spacing, first, last))
  {
    return false;
  }
  const int* n = points.N;
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      std::fill_n(flags + k * strideZ + j * strideY, n[0], static_cast<unsigned char>(0));
    }
  }
  if (!(this->Level > 0))
  {
    return true; // OffOuterSide is false everywhere
  }
  const double* xs = points.X[0];
  this->ForAtomsNear(points.Box, this->MaxRadius, [&](int i) {
    const double* c = &this->Centers[3 * i];
    const double r2 = this->Radii[i] * this->Radii[i];
    if (Distance2ToBox(c, points.Box) < r2 * (1.0 + 1e-9))
    {
      points.ForRowsNear(c, r2, [&](int k, int j, int lo, int hi, double dy, double dz) {
        unsigned char* row = flags + k * strideZ + j * strideY;
        for (int m = lo; m <= hi; ++m)
        {
          // OffOuterSide's test, term by term.
          const double dx = xs[m] - c[0];
          row[m] |= dx * dx + dy * dy + dz * dz < r2;
        }
      });
    }
    return false;
  });
  return true;
}

namespace
{
// RefineEdge's atoms: of the candidates (atom ids), those whose ρ reaches the segment
// [lower, upper] along `axis` through a, with per atom its id, the squared distance K
// across the axis, W = a[axis] − c[axis], R², ρ² and 1/(ρ² − R²); returns their number.
// Each candidate is written in any case and kept (the count advanced) only if it
// reaches: no branch to mispredict. (A function of its own with restrict pointers: as a
// lambda over references, every store reloaded the count and the array pointers.)
int GatherReaching(const int* candidates, size_t n, const LocalAtom* atoms, const double a[3],
  int axis, double lower, double upper, int* __restrict ids, double* __restrict K,
  double* __restrict W, double* __restrict R2, double* __restrict Rho2,
  double* __restrict Inverse)
{
  const int u1 = (axis + 1) % 3, u2 = (axis + 2) % 3;
  const double a1 = a[u1], a2 = a[u2], aa = a[axis];
  int count = 0;
  for (size_t m = 0; m < n; ++m)
  {
    const int i = candidates[m];
    const LocalAtom& atom = atoms[i];
    const double* c = atom.C;
    const double x1 = a1 - c[u1], x2 = a2 - c[u2];
    const double across = x1 * x1 + x2 * x2;
    const double below = lower - c[axis], above = c[axis] - upper;
    const double along = below > 0.0 ? below : (above > 0.0 ? above : 0.0);
    const double reach = atom.Rho2;
    ids[count] = i;
    K[count] = across;
    W[count] = aa - c[axis];
    R2[count] = atom.R2;
    Rho2[count] = reach;
    Inverse[count] = atom.InverseSpan;
    count += across + along * along < reach * (1.0 + 1e-9);
  }
  return count;
}
}

bool MoleculeField::RefineEdge(const double a[3], const double b[3], double va, double vb,
  int from, double tolerance, EdgeVertex& vertex) const
{
  const bool bracket = (va < 0 && vb > 0) || (va > 0 && vb < 0);
  if (this->Settings.Mode != MoleculeMode::Local || (from < 0 && !bracket) || from > 1)
  {
    return false;
  }
  // Along one axis, no longer than a cell: the segment lies in the boxes of the cells of
  // its ends, whose Near lists hold every atom that reaches it.
  int axis = -1;
  for (int k = 0; k < 3; ++k)
  {
    if (a[k] != b[k])
    {
      if (axis >= 0)
      {
        return false;
      }
      axis = k;
    }
  }
  if (axis < 0)
  {
    return false;
  }
  const double length = std::fabs(b[axis] - a[axis]);
  if (!(length <= this->Settings.CellSize))
  {
    return false;
  }
  const Cell* ca = this->CellAt(a);
  const Cell* cb = this->CellAt(b);
  if (!ca || !cb)
  {
    return false;
  }
  // The atoms reaching the segment, ascending (the two sorted lists merged): per atom
  // its id, the squared distance K across the axis, W = a[axis] − c[axis], R², ρ² and
  // 1/(ρ² − R²), as arrays.
  const std::vector<int>& p = ca->Near;
  const std::vector<int>& q = cb->Near;
  struct Terms
  {
    std::vector<int> Id;
    std::vector<double> Values; // K, W, R², ρ², 1/span, g, dg/ds: 7 arrays
    size_t Size = 0;
  };
  thread_local Terms buffer;
  // (+4: LocalTerms reads whole groups of four; the padding is set below.)
  if (buffer.Size < p.size() + q.size() + 4)
  {
    buffer.Size = p.size() + q.size() + 4;
    buffer.Id.resize(buffer.Size);
    buffer.Values.resize(7 * buffer.Size);
  }
  int* const ids = buffer.Id.data();
  double* const K = buffer.Values.data();
  double* const W = K + buffer.Size;
  double* const R2 = W + buffer.Size;
  double* const Rho2 = R2 + buffer.Size;
  double* const Inverse = Rho2 + buffer.Size;
  double* const G = Inverse + buffer.Size;
  double* const DG = G + buffer.Size;
  const double lower = std::min(a[axis], b[axis]), upper = std::max(a[axis], b[axis]);
  // The candidates: the cell's list, or the union of the two cells' (sorted) lists.
  const int* candidates = p.data();
  size_t candidateCount = p.size();
  thread_local std::vector<int> merged;
  if (cb != ca)
  {
    merged.resize(p.size() + q.size());
    candidates = merged.data();
    candidateCount = static_cast<size_t>(
      std::set_union(p.begin(), p.end(), q.begin(), q.end(), merged.begin()) - merged.begin());
  }
  const int count = GatherReaching(candidates, candidateCount, this->Atoms.data(), a, axis,
    lower, upper, ids, K, W, R2, Rho2, Inverse);
  // F on the segment and its derivative in s (LocalFactor: the same g as AtomFactor,
  // without branches).
  const double delta = b[axis] - a[axis];
  const double level = this->Level;
  // Each term's g and dg/ds at s, then their product and its derivative in two
  // interleaved partial products (half the chain of dependent multiplies).
  // Padding up to a multiple of four: terms that are 1 (LocalTerms computes them but
  // the products below stop at count).
  for (int m = count; m < count + 3; ++m)
  {
    K[m] = 2.0;
    W[m] = 0.0;
    R2[m] = 1.0;
    Inverse[m] = 1.0;
  }
  auto phi = [&](double s, double& derivative) {
    LocalTerms(K, W, R2, Inverse, count, s * delta, delta, G, DG);
    double p0 = 1.0, p1 = 1.0, d0 = 0.0, d1 = 0.0;
    int m = 0;
    for (; m + 1 < count; m += 2)
    {
      d0 = d0 * G[m] + p0 * DG[m];
      p0 *= G[m];
      d1 = d1 * G[m + 1] + p1 * DG[m + 1];
      p1 *= G[m + 1];
    }
    if (m < count)
    {
      d0 = d0 * G[m] + p0 * DG[m];
      p0 *= G[m];
    }
    derivative = d0 * p1 + p0 * d1;
    return p0 * p1 - level;
  };
  // The bracket [lo, hi] (F's value flo at lo, fhi at hi): the edge, or the first step
  // of 16 from the end `from` where F changes sign.
  double lo = 0.0, hi = 1.0, flo = va, fhi = vb;
  if (from >= 0)
  {
    constexpr int Steps = 16;
    double s0 = from, f0 = from == 0 ? va : vb;
    bool found = false;
    for (int m = 1; m <= Steps && !found; ++m)
    {
      const double s1 = from == 0 ? double(m) / Steps : 1.0 - double(m) / Steps;
      double unused;
      const double f1 = m == Steps ? (from == 0 ? vb : va) : phi(s1, unused);
      if ((f0 > 0) != (f1 > 0) || f1 == 0.0)
      {
        found = true;
        lo = std::min(s0, s1);
        hi = std::max(s0, s1);
        flo = s0 < s1 ? f0 : f1;
        fhi = s0 < s1 ? f1 : f0;
      }
      s0 = s1;
      f0 = f1;
    }
    if (!found)
    {
      return false; // F keeps its sign at every step: the general method decides
    }
  }
  // Newton's method kept inside the bracket (bisection where a step leaves it), from
  // the linear interpolation of its ends: a smooth F on a short edge converges in a few
  // steps. When a step is below half the tolerance, F is evaluated just beyond the new
  // estimate: a sign change there certifies a root within the tolerance, as the
  // mesher's own root finding does (or |F| below 1e-12 of its values at the edge's
  // ends).
  const double width = tolerance / length;
  const double small = 1e-12 * std::max(std::fabs(va), std::fabs(vb));
  double s = flo == 0.0 ? lo : (fhi == 0.0 ? hi : lo + (hi - lo) * flo / (flo - fhi));
  bool certified = flo == 0.0 || fhi == 0.0;
  auto narrow = [&](double at, double f) {
    if ((f < 0) == (flo < 0))
    {
      lo = at;
      flo = f;
    }
    else
    {
      hi = at;
    }
  };
  for (int iteration = 0; iteration < 100 && !certified && hi - lo > width; ++iteration)
  {
    double derivative;
    const double f = phi(s, derivative);
    if (std::fabs(f) <= small)
    {
      certified = true;
      break;
    }
    narrow(s, f);
    double next = s - f / derivative;
    if (!(next > lo && next < hi))
    {
      next = 0.5 * (lo + hi);
    }
    else if (std::fabs(next - s) <= 0.5 * width)
    {
      // Just beyond the estimate, away from s: a sign change brackets the root within
      // [s, probe], shorter than the tolerance.
      const double probe =
        std::max(lo, std::min(hi, next + (next > s ? 0.5 : -0.5) * width));
      double unused;
      const double fp = phi(probe, unused);
      narrow(probe, fp);
      if (hi - lo <= width)
      {
        s = next;
        certified = true;
        break;
      }
      next = probe;
    }
    s = next;
  }
  if (!certified)
  {
    s = std::max(lo, std::min(hi, s));
  }
  vertex.S = s;
  double x[3];
  for (int k = 0; k < 3; ++k)
  {
    x[k] = a[k] + vertex.S * (b[k] - a[k]);
  }
  // EvaluateVertex's answers and OffOuterSide at x, over the same atoms (every atom
  // within ρ of x is among them).
  this->LocalVertex(x, ids, count, vertex.Normal, vertex.GradientNorm, vertex.Nearest,
    &vertex.OffOuterSide);
  return true;
}

void MoleculeField::LocalVertex(const double p[3], const int* atoms, size_t count,
  double normal[3], double& gradientNorm, int& nearest, bool* inside) const
{
  // Plain doubles (see ComputeLocal); only atoms within their ρ change the product, and
  // the nearest sphere is among them (F = 0 needs some g_i != 1, and an atom beyond ρ is
  // farther than InfluenceRadius from its sphere).
  // In two passes without data-dependent branches (whether an atom is within its ρ
  // follows no pattern): the atoms within their ρ of p are kept first, then only they
  // enter the product, in the same order (the same bits as skipping the others).
  thread_local std::vector<int> kept;
  thread_local std::vector<double> keptD2;
  if (kept.size() < count)
  {
    kept.resize(count);
    keptD2.resize(count);
  }
  int* const ids = kept.data();
  double* const squares = keptD2.data();
  size_t near = 0;
  bool within = false;
  for (size_t m = 0; m < count; ++m)
  {
    const int i = atoms[m];
    const LocalAtom& atom = this->Atoms[i];
    const double v0 = p[0] - atom.C[0], v1 = p[1] - atom.C[1], v2 = p[2] - atom.C[2];
    const double d2 = v0 * v0 + v1 * v1 + v2 * v2;
    within |= d2 < atom.R2; // OffOuterSide's test
    ids[near] = i;
    squares[near] = d2;
    near += d2 < atom.Rho2;
  }
  if (inside)
  {
    *inside = this->Level > 0 && within;
  }
  double product = 1.0, grad[3] = { 0, 0, 0 }, best = HUGE_VAL;
  nearest = -1;
  for (size_t m = 0; m < near; ++m)
  {
    const int i = ids[m];
    const LocalAtom& atom = this->Atoms[i];
    const double* c = atom.C;
    const double v[3] = { p[0] - c[0], p[1] - c[1], p[2] - c[2] };
    const double d2 = squares[m];
    // g and ∇g = (dg/df)·2v, AtomFactor's values without its branches and division.
    double slope;
    const double g = LocalFactor(d2 - atom.R2, atom.InverseSpan, slope);
    for (int k = 0; k < 3; ++k)
    {
      grad[k] = grad[k] * g + product * 2.0 * slope * v[k];
    }
    product *= g;
    const double distance = std::fabs(std::sqrt(d2) - atom.R);
    const bool better = distance < best;
    nearest = better ? i : nearest;
    best = better ? distance : best;
  }
  const double norm = std::sqrt(grad[0] * grad[0] + grad[1] * grad[1] + grad[2] * grad[2]);
  gradientNorm = std::isfinite(norm) ? norm : 0.0;
  for (int k = 0; k < 3; ++k)
  {
    normal[k] = norm > 0 && std::isfinite(norm) ? grad[k] / norm : 0.0;
  }
}

int MoleculeField::ClassifyBox(const double box[6]) const
{
  std::vector<Interval> enclosures;
  // Global: the atoms within R + NearDistance of the box enter with their exact ranges;
  // every other atom is at least NearDistance outside its sphere there, so its factor is
  // at least (R + d)² − R² >= d² (d = NearDistance): the far product is at least
  // d^(2·far) (no upper bound is used). Cost: the atoms near the box, not all atoms.
  const double nearDistance = this->Settings.NearDistance;
  size_t nearCount = 0;
  auto add = [&](size_t i) {
    const double* c = &this->Centers[3 * i];
    const double R2 = this->Radii[i] * this->Radii[i];
    const double dmin2 = Distance2ToBox(c, box);
    const double fmin = dmin2 - R2, fmax = FarthestDistance2(c, box) - R2;
    if (this->Settings.Mode == MoleculeMode::Global)
    {
      const double reach = this->Radii[i] + nearDistance;
      if (dmin2 < reach * reach)
      {
        enclosures.push_back({ fmin, fmax });
        ++nearCount;
      }
      return;
    }
    const double rho = this->Radii[i] + this->Settings.InfluenceRadius;
    if (dmin2 >= rho * rho)
    {
      return; // g = 1 on the whole box
    }
    // g lies between f and 1 (g = f where f < 0).
    enclosures.push_back({ std::min(fmin, 1.0), std::max(fmax, 1.0) });
  };
  // The atoms binned within MaxReach (R + NearDistance or R + InfluenceRadius at most)
  // of the box: every atom that enters exactly.
  this->ForAtomsNear(box, this->MaxReach, [&](int i) {
    add(static_cast<size_t>(i));
    return false;
  });
  const size_t farCount = this->Radii.size() - nearCount;
  if (this->Settings.Mode == MoleculeMode::Global && farCount > 0 && nearDistance > 0)
  {
    // P = P_near · P_far with P_far >= d^(2·far) > 0: decided only where P_near alone
    // decides, or P_near > 0 and its minimum times that bound exceeds the level.
    double logMin = 2.0 * static_cast<double>(farCount) * std::log(nearDistance);
    int sign = 1;
    for (const Interval& v : enclosures)
    {
      if (!(v.Lo <= v.Hi) || !(v.Lo > 0 || v.Hi < 0))
      {
        return 0; // NaN, or a factor spans zero: undecided
      }
      logMin += std::log(std::min(std::fabs(v.Lo), std::fabs(v.Hi)));
      sign = v.Lo > 0 ? sign : -sign;
    }
    if (sign < 0)
    {
      return -1; // P < 0 < level
    }
    return logMin > std::log(this->Level) + 1e-9 ? 1 : 0;
  }
  return SignOfProductMinus(enclosures, this->Level);
}

// ---------------------------------------------------------------------------------------
// CastRay: certified roots along a ray.

namespace
{
// P·e^[lo, hi] (natural logarithms; false if too wide to represent).
bool MultiplyExp(ScaledInterval& P, double lo, double hi)
{
  if (!(hi - lo < 600.0))
  {
    return false;
  }
  const double e = std::floor(lo / Ln2);
  P.Multiply({ std::exp(lo - e * Ln2), std::exp(hi - e * Ln2) });
  P.E += static_cast<long>(e);
  return true;
}

// +1: every value of P exceeds `level` (>= 0); −1: every value is below it; 0: undecided.
int Compare(const ScaledInterval& P, double level)
{
  double l = level;
  if (level != 0.0)
  {
    l = P.E > 2000 ? 0.0 : P.E < -2000 ? HUGE_VAL : std::ldexp(level, static_cast<int>(-P.E));
  }
  if (P.Lo > l)
  {
    return 1;
  }
  return P.Hi < l ? -1 : 0;
}

// The range of a·s² + b·s + c over [s0, s1].
inline void QuadraticRange(double a, double b, double c, double s0, double s1, double& lo, double& hi)
{
  const double v0 = (a * s0 + b) * s0 + c, v1 = (a * s1 + b) * s1 + c;
  lo = std::min(v0, v1);
  hi = std::max(v0, v1);
  if (a != 0.0)
  {
    const double sv = -b / (2.0 * a);
    if (sv > s0 && sv < s1)
    {
      const double vv = (a * sv + b) * sv + c;
      lo = std::min(lo, vv);
      hi = std::max(hi, vv);
    }
  }
}
}

// CastRay tries the monotonicity test from this depth (a sixteenth of a cell) down: on
// longer pieces F is rarely monotone (1ubq, 256² six views, best of 3 CPU: depth 0,
// 0.52/0.39 s Global/Local; 4, 0.43/0.30 s; 6, 0.43/0.33 s).
constexpr int MonotoneDepth = 4;
// One atom's factor restricted to the ray: f(s) = A·s² + B·s + C, s = t − the chunk's
// middle; Span = ρ² − R² in Local mode.
struct MoleculeField::RaySearch
{
  struct Atom
  {
    double A, B, C, Span, InverseSpan;
  };
  struct Piece
  {
    double A, B;
    int Depth;
    size_t Offset, Count; // its atoms in the pool
  };

  // Work buffers, per thread, reused from ray to ray.
  struct Buffers
  {
    std::vector<Atom> Atoms, AllAtoms;
    std::vector<Piece> Stack;
    std::vector<int> Pool, Keep;
    std::vector<Interval> Values, Slopes;
    std::vector<ScaledInterval> Prefix, Suffix;
  };

  const MoleculeField& M;
  const double* O;
  const double* D;
  RayRootOptions Options;
  std::vector<RayRoot>& Roots;
  RootCluster Cluster;
  bool Local;
  double Level;
  // The chunk: its middle, its atoms and far field T(s) = T0 + T1·s + T2·s² ± Bound.
  double Mid = 0.0;
  std::vector<Atom>& Atoms;
  std::vector<Atom>& AllAtoms;
  bool HasFar = false;
  double T0 = 0.0, T1 = 0.0, T2 = 0.0, Bound = 0.0;
  std::vector<Piece>& Stack;
  std::vector<int>& Pool;
  std::vector<int>& Keep;
  // Monotone's factor and slope enclosures and product buffers.
  std::vector<Interval>& Values;
  std::vector<Interval>& Slopes;
  std::vector<ScaledInterval>& Prefix;
  std::vector<ScaledInterval>& Suffix;
  bool Searching = false;

  RaySearch(const MoleculeField& m, const double* o, const double* d, const RayRootOptions& options,
    std::vector<RayRoot>& roots, Buffers& buffers)
    : M(m)
    , O(o)
    , D(d)
    , Options(options)
    , Roots(roots)
    , Cluster(roots, options.Tolerance)
    , Local(m.Settings.Mode == MoleculeMode::Local)
    , Level(m.Level)
    , Atoms(buffers.Atoms)
    , AllAtoms(buffers.AllAtoms)
    , Stack(buffers.Stack)
    , Pool(buffers.Pool)
    , Keep(buffers.Keep)
    , Values(buffers.Values)
    , Slopes(buffers.Slopes)
    , Prefix(buffers.Prefix)
    , Suffix(buffers.Suffix)
  {
  }

  bool Finished() const { return !this->Options.AllRoots && !this->Roots.empty(); }

  // The atoms of `indices` restricted about the chunk's middle, into `out`.
  template <class Indices>
  void Restrict(const Indices& indices, std::vector<Atom>& out) const
  {
    out.clear();
    const double* d = this->D;
    const double p[3] = { this->O[0] + this->Mid * d[0], this->O[1] + this->Mid * d[1],
      this->O[2] + this->Mid * d[2] };
    const double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    for (int i : indices)
    {
      const double* c = &this->M.Centers[3 * i];
      const double v[3] = { p[0] - c[0], p[1] - c[1], p[2] - c[2] };
      const double R2 = this->M.Radii[i] * this->M.Radii[i];
      Atom atom{ a, 2.0 * (d[0] * v[0] + d[1] * v[1] + d[2] * v[2]),
        v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - R2, 0.0, 0.0 };
      if (this->Local)
      {
        atom.Span = this->M.Atoms[i].Rho2 - this->M.Atoms[i].R2;
        atom.InverseSpan = this->M.Atoms[i].InverseSpan;
      }
      out.push_back(atom);
    }
  }

  // The sign of F on the piece [a, b] of the chunk (0: undecided), from `atoms[list]`
  // and, with `far`, the far field (its bound B too with `bound`). Appends to `keep` the
  // atoms that still matter on the piece (Local: those whose influence reaches it).
  // Of the last Enclose: how many factors may vanish on the piece, and the last of them.
  mutable int Straddling = 0, Straddler = -1;

  // f's range over [s0, s1] (sm = max |s|), widened by its rounding: of the terms (a few
  // ulps of their magnitude) and of the result.
  static void FactorRange(const Atom& q, double s0, double s1, double sm, double& lo, double& hi)
  {
    QuadraticRange(q.A, q.B, q.C, s0, s1, lo, hi);
    const double slack = 1e-14 * (q.A * sm * sm + std::fabs(q.B) * sm + std::fabs(q.C)) +
      1e-12 * std::max(std::fabs(lo), std::fabs(hi));
    lo -= slack;
    hi += slack;
  }

  // Local: g = 1 + (f − 1)·w(u), u = f/(ρ² − R²) clamped to [0, 1], w decreasing from 1
  // to 0 (g = f inside the sphere, where u = 0), enclosed from f's range [lo, hi] by
  // interval arithmetic on each part; with u's and w's ranges.
  struct LocalRange
  {
    double G0, G1, U0, U1, W0, W1;
  };
  static LocalRange LocalFactorRange(const Atom& q, double lo, double hi)
  {
    LocalRange r;
    r.U0 = std::min(1.0, std::max(0.0, lo * q.InverseSpan));
    r.U1 = std::min(1.0, std::max(0.0, hi * q.InverseSpan));
    r.W0 = std::max(0.0, WeightPolynomial(r.U1) - 1e-14);
    r.W1 = std::min(1.0, WeightPolynomial(r.U0) + 1e-14);
    const double m0 = lo - 1.0, m1 = hi - 1.0;
    r.G0 = 1.0 + (m0 < 0 ? m0 * r.W1 : m0 * r.W0);
    r.G1 = 1.0 + (m1 > 0 ? m1 * r.W1 : m1 * r.W0);
    const double gs = 1e-14 * (1.0 + std::max(std::fabs(r.G0), std::fabs(r.G1)));
    r.G0 -= gs;
    r.G1 += gs;
    return r;
  }

  int Enclose(double a, double b, const std::vector<Atom>& atoms, const int* list, size_t count,
    bool far, bool bound, std::vector<int>* keep) const
  {
    this->Straddling = 0;
    const double s0 = a - this->Mid, s1 = b - this->Mid;
    const double sm = std::max(std::fabs(s0), std::fabs(s1));
    ScaledInterval P;
    for (size_t k = 0; k < count; ++k)
    {
      const Atom& q = atoms[list[k]];
      double lo, hi;
      FactorRange(q, s0, s1, sm, lo, hi);
      if (lo <= 0.0 && hi >= 0.0)
      {
        ++this->Straddling;
        this->Straddler = list[k];
      }
      if (this->Local)
      {
        if (lo >= q.Span)
        {
          continue; // beyond ρ on the whole piece: g = 1
        }
        const LocalRange g = LocalFactorRange(q, lo, hi);
        P.Multiply({ g.G0, g.G1 });
      }
      else
      {
        P.Multiply({ lo, hi });
      }
      if (keep)
      {
        keep->push_back(list[k]);
      }
    }
    if (far && this->HasFar)
    {
      double lo, hi;
      QuadraticRange(this->T2, this->T1, this->T0, s0, s1, lo, hi);
      const double slack = 1e-13 * (std::fabs(this->T0) + std::fabs(this->T1) * sm +
                                     std::fabs(this->T2) * sm * sm) +
        1e-13 + (bound ? this->Bound : 0.0);
      if (!MultiplyExp(P, lo - slack, hi + slack))
      {
        return 0;
      }
    }
    return Compare(P, this->Level);
  }

  // Whether F is strictly monotone on [a, b]: an enclosure of F' = E·(Σ_i g_i' Π_{j≠i} g_j
  // + P·L') excludes 0, with E = e^L > 0 the far field (Global; L' within T' ± B' where
  // B' = 3B/h bounds the Taylor remainder's slope as B its value, h the cell's
  // half-diagonal, which is conservative for the supercell's part) and each g_i' by
  // interval arithmetic (Global: f_i' = 2A·s + B; Local: dg/df·f_i' with dg/df =
  // w + (f − 1)·w'(u)/(ρ² − R²)). Only the atoms that matter on the piece are given.
  bool Monotone(double a, double b, const std::vector<Atom>& atoms, const int* list, size_t count,
    bool far) const
  {
    const double s0 = a - this->Mid, s1 = b - this->Mid;
    const double sm = std::max(std::fabs(s0), std::fabs(s1));
    std::vector<Interval>& g = this->Values;
    std::vector<Interval>& dg = this->Slopes;
    g.clear();
    dg.clear();
    for (size_t k = 0; k < count; ++k)
    {
      const Atom& q = atoms[list[k]];
      double lo, hi;
      FactorRange(q, s0, s1, sm, lo, hi);
      double d0 = 2.0 * q.A * s0 + q.B, d1 = 2.0 * q.A * s1 + q.B; // f' (increasing in s)
      const double ds = 1e-14 * (std::fabs(d0) + std::fabs(d1) + std::fabs(q.B)) + 1e-300;
      d0 -= ds;
      d1 += ds;
      double g0 = lo, g1 = hi;
      if (this->Local)
      {
        if (lo >= q.Span)
        {
          continue; // g = 1 on the piece: g' = 0
        }
        const LocalRange range = LocalFactorRange(q, lo, hi);
        g0 = range.G0;
        g1 = range.G1;
        const double u0 = range.U0, u1 = range.U1, w0 = range.W0, w1 = range.W1;
        const double m0 = lo - 1.0, m1 = hi - 1.0;
        // w'(u) = −30 u²(1 − u)² on [u0, u1]: 0 at both ends of [0, 1], −1.875 at 1/2.
        auto slope = [](double u) { return -30.0 * u * u * (1.0 - u) * (1.0 - u); };
        double p0 = std::min(slope(u0), slope(u1)), p1 = std::max(slope(u0), slope(u1));
        if (u0 < 0.5 && u1 > 0.5)
        {
          p0 = -1.875;
        }
        p0 = p0 * q.InverseSpan - 1e-14;
        p1 = p1 * q.InverseSpan + 1e-14;
        // dg/df = w + (f − 1)·w'/(ρ² − R²), then times f'.
        const double c[4] = { m0 * p0, m0 * p1, m1 * p0, m1 * p1 };
        const double e0 = w0 + std::min({ c[0], c[1], c[2], c[3] });
        const double e1 = w1 + std::max({ c[0], c[1], c[2], c[3] });
        const double c2[4] = { e0 * d0, e0 * d1, e1 * d0, e1 * d1 };
        d0 = std::min({ c2[0], c2[1], c2[2], c2[3] });
        d1 = std::max({ c2[0], c2[1], c2[2], c2[3] });
        const double es = 1e-12 * (std::fabs(d0) + std::fabs(d1)) + 1e-300;
        d0 -= es;
        d1 += es;
      }
      g.push_back({ g0, g1 });
      dg.push_back({ d0, d1 });
    }
    if (far && this->HasFar)
    {
      // P·L' enters as the term of one more factor, 1 with slope L' = T1 + 2·T2·s ± B'·|d|.
      const double l0 = this->T1 + 2.0 * this->T2 * s0, l1 = this->T1 + 2.0 * this->T2 * s1;
      const double h = 0.5 * std::sqrt(3.0) * this->M.Settings.CellSize;
      const double norm = std::sqrt(this->D[0] * this->D[0] + this->D[1] * this->D[1] + this->D[2] * this->D[2]);
      const double slack = 3.0 * this->Bound / h * norm + 1e-13 * (std::fabs(l0) + std::fabs(l1)) + 1e-13;
      g.push_back({ 1.0, 1.0 });
      dg.push_back({ std::min(l0, l1) - slack, std::max(l0, l1) + slack });
    }
    return ProductDerivativeHasOneSign(g.data(), dg.data(), g.size(), this->Prefix, this->Suffix);
  }

  // Whether F changes sign between values va and vb (a crossing root lies between).
  static bool Crosses(double va, double vb) { return (va < 0 && vb > 0) || (va > 0 && vb < 0); }

  // F's value at t (exact sign: the field's evaluation).
  double At(double t) const
  {
    const double p[3] = { this->O[0] + t * this->D[0], this->O[1] + t * this->D[1],
      this->O[2] + t * this->D[2] };
    double logAbs;
    return this->M.Compute(p, logAbs);
  }

  // The roots on [a, b] of the chunk from `atoms` (all of them at first) and, with
  // `far`, the far field.
  void Search(double a, double b, const std::vector<Atom>& atoms, bool far)
  {
    // (the chunk's search reuses the members' buffers; the rare nested one of Exact has
    // its own)
    std::vector<Piece> ownStack;
    std::vector<int> ownPool, ownKeep;
    const bool nested = this->Searching;
    this->Searching = true;
    std::vector<Piece>& stack = nested ? ownStack : this->Stack;
    std::vector<int>& pool = nested ? ownPool : this->Pool;
    std::vector<int>& keep = nested ? ownKeep : this->Keep;
    stack.clear();
    pool.resize(atoms.size());
    for (size_t k = 0; k < atoms.size(); ++k)
    {
      pool[k] = static_cast<int>(k);
    }
    stack.push_back({ a, b, 0, 0, atoms.size() });
    while (!stack.empty() && !this->Finished())
    {
      const Piece p = stack.back();
      stack.pop_back();
      pool.resize(p.Offset + p.Count); // drop what finished subtrees used
      keep.clear();
      const int sign = this->Enclose(p.A, p.B, atoms, pool.data() + p.Offset, p.Count, far, true, &keep);
      if (sign != 0)
      {
        continue;
      }
      const int straddling = this->Straddling, straddler = this->Straddler;
      if (far && this->HasFar && straddling == 0 &&
        this->Enclose(p.A, p.B, atoms, pool.data() + p.Offset, p.Count, true, false, nullptr) != 0)
      {
        // Only the far field's bound leaves the piece undecided: every atom exactly.
        this->Exact(p.A, p.B);
        continue;
      }
      if (!this->Local && straddling == 1 && p.B - p.A > this->Options.Tolerance &&
        p.Depth < this->Options.MaximumDepth &&
        this->Isolate(p, atoms, pool.data() + p.Offset, far, straddler))
      {
        continue;
      }
      if (p.B - p.A > this->Options.Tolerance && p.Depth >= MonotoneDepth &&
        this->Monotone(p.A, p.B, atoms, pool.data() + p.Offset, p.Count, far))
      {
        // One root at most: where F changes sign between the ends.
        const double va = this->At(p.A), vb = this->At(p.B);
        if (Crosses(va, vb))
        {
          const double t = BracketedRoot([this](double x) { return this->At(x); }, p.A, p.B, va,
            vb, this->Options.Tolerance, 0.0);
          this->Cluster.Add(t, false, va, vb);
        }
        else if (va == 0.0 || vb == 0.0)
        {
          this->Cluster.Add(va == 0.0 ? p.A : p.B, false, va, vb);
        }
        continue;
      }
      if (p.B - p.A <= this->Options.Tolerance || p.Depth >= this->Options.MaximumDepth)
      {
        const double va = this->At(p.A), vb = this->At(p.B);
        this->Cluster.Add(0.5 * (p.A + p.B), !Crosses(va, vb), va, vb);
        continue;
      }
      // Both halves share the atoms that still matter; the right half goes below the
      // left on the stack (the left, smaller t, first).
      const size_t offset = pool.size();
      pool.insert(pool.end(), keep.begin(), keep.end());
      const double mid = 0.5 * (p.A + p.B);
      stack.push_back({ mid, p.B, p.Depth + 1, offset, keep.size() });
      stack.push_back({ p.A, mid, p.Depth + 1, offset, keep.size() });
    }
    this->Searching = nested;
  }

  // Global mode, a shortcut past the halvings: where the one factor that may vanish on
  // the piece (`straddler`) does, a guess t of the root (in a protein the product of
  // the others is so large that F's root lies within rounding of that sphere), certified
  // by enclosures that exclude the level on both sides of [t − tolerance/2,
  // t + tolerance/2]; true if they do (that middle then treated as a leaf). (In Local
  // mode, or at a blended root, an enclosure of a piece that ends next to a root cannot
  // exclude it: halvings.)
  bool Isolate(const Piece& p, const std::vector<Atom>& atoms, const int* list, bool far, int straddler)
  {
    // The roots of A s² + B s + C (A > 0), the numerically stable way; one on the piece.
    const Atom& q = atoms[straddler];
    const double disc = q.B * q.B - 4.0 * q.A * q.C;
    if (!(disc >= 0))
    {
      return false;
    }
    const double m = -0.5 * (q.B + std::copysign(std::sqrt(disc), q.B));
    const double r0 = m / q.A, r1 = m != 0.0 ? q.C / m : r0;
    const double s0 = p.A - this->Mid, s1 = p.B - this->Mid;
    const bool in0 = r0 > s0 && r0 < s1, in1 = r1 > s0 && r1 < s1;
    if (in0 == in1)
    {
      return false;
    }
    const double t = this->Mid + (in0 ? r0 : r1), h = 0.5 * this->Options.Tolerance;
    if (!(t - h > p.A && t + h < p.B))
    {
      return false;
    }
    if (this->Enclose(p.A, t - h, atoms, list, p.Count, far, true, nullptr) == 0 ||
      this->Enclose(t + h, p.B, atoms, list, p.Count, far, true, nullptr) == 0)
    {
      return false;
    }
    // The middle, as a leaf of the halvings: no root if its enclosure excludes the level
    // (a sphere crossed inside another atom, where F < 0 on both sides).
    if (this->Enclose(t - h, t + h, atoms, list, p.Count, far, true, nullptr) == 0)
    {
      const double va = this->At(t - h), vb = this->At(t + h);
      this->Cluster.Add(t, !Crosses(va, vb), va, vb);
    }
    return true;
  }

  // Every atom of the molecule, exactly, on [a, b] (no far field).
  void Exact(double a, double b)
  {
    if (this->AllAtoms.empty())
    {
      std::vector<int> all(this->M.Radii.size());
      for (size_t i = 0; i < all.size(); ++i)
      {
        all[i] = static_cast<int>(i);
      }
      this->Restrict(all, this->AllAtoms);
    }
    this->Search(a, b, this->AllAtoms, false); // (no far field: no nested Exact)
  }

  void Chunk(double a, double b)
  {
    this->Mid = 0.5 * (a + b);
    this->AllAtoms.clear();
    const double p[3] = { this->O[0] + this->Mid * this->D[0], this->O[1] + this->Mid * this->D[1],
      this->O[2] + this->Mid * this->D[2] };
    const Cell* cell = this->M.CellAt(p);
    this->HasFar = false;
    if (!cell)
    {
      if (!this->Local)
      {
        this->Exact(a, b); // outside the cells: every atom (F = 1 − level > 0 in Local)
      }
      return;
    }
    if (this->Local && cell->Near.empty())
    {
      return; // no atom reaches the cell: F = 1 − level > 0
    }
    this->Restrict(cell->Near, this->Atoms);
    const FarField& far = cell->GetFar();
    if (far.HasFar)
    {
      this->HasFar = true;
      double g[3];
      far.Gradient(p, g);
      const double* d = this->D;
      const double* H = far.H;
      this->T0 = far.Log(p);
      this->T1 = g[0] * d[0] + g[1] * d[1] + g[2] * d[2];
      this->T2 = 0.5 * (H[0] * d[0] * d[0] + H[1] * d[1] * d[1] + H[2] * d[2] * d[2]) +
        H[3] * d[0] * d[1] + H[4] * d[0] * d[2] + H[5] * d[1] * d[2];
      this->Bound = far.Bound;
    }
    this->Search(a, b, this->Atoms, true);
  }
};

void MoleculeField::CastRay(const double o[3], const double d[3], double t0, double t1,
  const RayRootOptions& options, std::vector<RayRoot>& roots) const
{
  roots.clear();
  if (!(t1 > t0) || !std::isfinite(t0) || !std::isfinite(t1) ||
    !std::isfinite(o[0] + o[1] + o[2] + d[0] + d[1] + d[2]))
  {
    return;
  }
  // The segment cut where it crosses the cells' planes: each chunk lies in one cell.
  thread_local std::vector<double> cuts;
  cuts.assign({ t0, t1 });
  const double s = this->Settings.CellSize;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      continue;
    }
    const double x0 = o[a] + t0 * d[a], x1 = o[a] + t1 * d[a];
    const double k0 = std::max(0.0, std::ceil((std::min(x0, x1) - this->Origin[a]) / s));
    const double k1 = std::min(double(this->Dims[a]), std::floor((std::max(x0, x1) - this->Origin[a]) / s));
    for (double k = k0; k <= k1; ++k)
    {
      const double t = (this->Origin[a] + k * s - o[a]) / d[a];
      if (t > t0 && t < t1)
      {
        cuts.push_back(t);
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());
  thread_local RaySearch::Buffers buffers;
  RaySearch search(*this, o, d, options, roots, buffers);
  for (size_t c = 0; c + 1 < cuts.size() && !search.Finished(); ++c)
  {
    if (cuts[c + 1] > cuts[c])
    {
      search.Chunk(cuts[c], cuts[c + 1]);
    }
  }
}
}
