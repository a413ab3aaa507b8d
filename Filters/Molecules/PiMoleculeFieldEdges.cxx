// SPDX-License-Identifier: BSD-3-Clause
// MoleculeField on the mesher's edges: the first root from the positive end and the one-pass edge
// vertex.
#include "PiMoleculeFieldInternals.h"

namespace pisurf
{
using namespace moleculefield;

namespace
{
// RefineEdge's terms at one point of its edge, four atoms per instruction: for m in
// [0, count), v = W[m] + shift, G[m] = LocalFactor(K[m] + v², ...) and DG[m] = its
// derivative along the edge, with LocalFactor's operations in its order (the same bits).
// The arrays are read up to count rounded up to 4 (the caller pads them).
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
  auto coefficients = [&](int i, double& B, double& C)
  {
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
  auto minimum = [&](double B, double C)
  {
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
  double* __restrict W, double* __restrict R2, double* __restrict Rho2, double* __restrict Inverse)
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

bool MoleculeField::RefineEdge(const double a[3], const double b[3], double va, double vb, int from,
  double tolerance, EdgeVertex& vertex) const
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
  const int count = GatherReaching(candidates, candidateCount, this->Atoms.data(), a, axis, lower,
    upper, ids, K, W, R2, Rho2, Inverse);
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
  auto phi = [&](double s, double& derivative)
  {
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
  auto narrow = [&](double at, double f)
  {
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
      const double probe = std::max(lo, std::min(hi, next + (next > s ? 0.5 : -0.5) * width));
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
  this->LocalVertex(
    x, ids, count, vertex.Normal, vertex.GradientNorm, vertex.Nearest, &vertex.OffOuterSide);
  return true;
}
}
