// SPDX-License-Identifier: BSD-3-Clause
// MoleculeField on boxes: classification, and the values and outer-side flags of grid boxes.
#include "PiMoleculeFieldInternals.h"

namespace pisurf
{
using namespace moleculefield;

namespace
{
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
}

bool MoleculeField::EvaluateBox(const double origin[3], const double spacing[3], const int first[3],
  const int last[3], long strideY, long strideZ, double* values) const
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
  this->ForAtomsNear(points.Box, this->MaxReach,
    [&](int i)
    {
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
    points.ForRowsNear(c, rho2,
      [&](int k, int j, int lo, int hi, double v1, double v2)
      {
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
  this->ForAtomsNear(points.Box, this->MaxRadius,
    [&](int i)
    {
      const double* c = &this->Centers[3 * i];
      const double r2 = this->Radii[i] * this->Radii[i];
      if (Distance2ToBox(c, points.Box) < r2 * (1.0 + 1e-9))
      {
        points.ForRowsNear(c, r2,
          [&](int k, int j, int lo, int hi, double dy, double dz)
          {
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

int MoleculeField::ClassifyBox(const double box[6]) const
{
  std::vector<Interval> enclosures;
  // Global: the atoms within R + NearDistance of the box enter with their exact ranges;
  // every other atom is at least NearDistance outside its sphere there, so its factor is
  // at least (R + d)² − R² >= d² (d = NearDistance): the far product is at least
  // d^(2·far) (no upper bound is used). Cost: the atoms near the box, not all atoms.
  const double nearDistance = this->Settings.NearDistance;
  size_t nearCount = 0;
  auto add = [&](size_t i)
  {
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
  this->ForAtomsNear(box, this->MaxReach,
    [&](int i)
    {
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
}
