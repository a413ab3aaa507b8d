// SPDX-License-Identifier: BSD-3-Clause
// MoleculeField at points: F, its sign and logarithm, the outer-side test and the vertex
// attributes.
#include "PiMoleculeFieldInternals.h"

namespace pisurf
{
using namespace moleculefield;

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
  return this->ForAtomsNear(point, this->MaxRadius,
    [&](int i)
    {
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

bool MoleculeField::ProbeVertex(const double p[3], double probe, double tolerance, double normal[3],
  double& gradientNorm, int& nearest) const
{
  // ln|∇F| + ln probe <= ln tolerance + ln max|F(probes)|.
  double logGradient;
  this->EvaluateVertex(p, normal, gradientNorm, nearest, logGradient);
  const double logProbe = LargestLogAtProbes(p, probe,
    [this](const double* q)
    {
      double logAbs;
      this->EvaluateWithLog(q, logAbs);
      return logAbs;
    });
  return logGradient + std::log(probe) <= std::log(tolerance) + logProbe;
}

void MoleculeField::EvaluateVertex(const double p[3], double normal[3], double& gradientNorm,
  int& nearest, double& logGradientNorm) const
{
  const Cell* cell = this->CellAt(p);
  if (this->Settings.Mode == MoleculeMode::Local)
  {
    this->LocalVertex(p, cell ? cell->Near.data() : nullptr, cell ? cell->Near.size() : 0, normal,
      gradientNorm, nearest, nullptr);
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

void MoleculeField::LocalVertex(const double p[3], const int* atoms, size_t count, double normal[3],
  double& gradientNorm, int& nearest, bool* inside) const
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
}
