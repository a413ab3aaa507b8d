// SPDX-License-Identifier: BSD-3-Clause
// MoleculeField along rays: certified roots.
#include "PiMoleculeFieldInternals.h"

namespace pisurf
{
using namespace moleculefield;

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
inline void QuadraticRange(
  double a, double b, double c, double s0, double s1, double& lo, double& hi)
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
      const double slack =
        1e-13 * (std::fabs(this->T0) + std::fabs(this->T1) * sm + std::fabs(this->T2) * sm * sm) +
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
      const double norm =
        std::sqrt(this->D[0] * this->D[0] + this->D[1] * this->D[1] + this->D[2] * this->D[2]);
      const double slack =
        3.0 * this->Bound / h * norm + 1e-13 * (std::fabs(l0) + std::fabs(l1)) + 1e-13;
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
      const int sign =
        this->Enclose(p.A, p.B, atoms, pool.data() + p.Offset, p.Count, far, true, &keep);
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
          const double t = BracketedRoot([this](double x) { return this->At(x); }, p.A, p.B, va, vb,
            this->Options.Tolerance, 0.0);
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
  bool Isolate(
    const Piece& p, const std::vector<Atom>& atoms, const int* list, bool far, int straddler)
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
    const bool in0 = r0 > s0 && r0<s1, in1 = r1> s0 && r1 < s1;
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
    const double k1 =
      std::min(double(this->Dims[a]), std::floor((std::max(x0, x1) - this->Origin[a]) / s));
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
