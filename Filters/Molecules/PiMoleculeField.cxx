// SPDX-License-Identifier: BSD-3-Clause
// MoleculeField: construction, cells, supercells and the far-field expansions.
#include "PiMoleculeFieldInternals.h"

namespace pisurf
{
using namespace moleculefield;

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
  auto cellCount = [&](double size)
  {
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
        std::max(
          0, static_cast<int>(std::floor((this->Centers[3 * i + a] - this->Origin[a]) / s))));
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
  this->ForAtomsNear(box, this->MaxReach,
    [&](int i)
    {
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
  this->ForAtomsNear(super.Box, this->MaxRadius + SuperNear,
    [&](int i)
    {
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
  std::call_once(this->SuperOnce[id],
    [&]
    {
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
}
