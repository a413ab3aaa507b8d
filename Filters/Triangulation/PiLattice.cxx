// SPDX-License-Identifier: BSD-3-Clause
// Finds the lattice of RAY_LATTICE and runs its passes: the hits of the lattice lines
// (HitLattice), then the marching-cubes polygons of the cells (LatticeCells).
#include "PiLattice.h"
#include "PiHitLattice.h"
#include "PiLatticeCells.h"
#include "PiTiming.h"

#include <cmath>

namespace pisurf
{
namespace triangulator
{

bool FindLattice(const Triangulation& T, Lattice& L)
{
  // Every view must be an axis view; each defines the lattice along its u and v axes
  // and the box along its own axis. All of them must agree.
  bool defined[3] = { false, false, false }, box[3] = { false, false, false };
  bool axis[3] = { false, false, false };
  const double tol = 1e-9 * T.Size;
  auto define = [&](int a, int n, double h, double b0)
  {
    if (!(h > 0) || n < 1)
    {
      return false;
    }
    if (!defined[a])
    {
      defined[a] = true;
      L.N[a] = n;
      L.H[a] = h;
      L.B0[a] = b0;
      return true;
    }
    return L.N[a] == n && std::fabs(L.H[a] - h) <= tol && std::fabs(L.B0[a] - b0) <= tol;
  };
  double range[3][2];
  for (const View& v : T.Views)
  {
    if (v.Axis < 0)
    {
      return false;
    }
    const int a = v.Axis, ua = (a + 1) % 3, va = (a + 2) % 3;
    if (!define(ua, v.W, v.U[ua], v.O[ua] - 0.5 * v.U[ua]) ||
      !define(va, v.H, v.V[va], v.O[va] - 0.5 * v.V[va]))
    {
      return false;
    }
    const double lo = v.Sense < 0 ? v.O[a] - v.Length : v.O[a];
    const double hi = lo + v.Length;
    if (box[a] && (std::fabs(range[a][0] - lo) > tol || std::fabs(range[a][1] - hi) > tol))
    {
      return false;
    }
    box[a] = true;
    axis[a] = true;
    range[a][0] = lo;
    range[a][1] = hi;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!axis[a] || !defined[a] || std::fabs(L.B0[a] - range[a][0]) > tol ||
      std::fabs(L.B0[a] + L.N[a] * L.H[a] - range[a][1]) > tol)
    {
      return false;
    }
    L.B1[a] = range[a][1];
  }
  L.LineStart[0] = 0;
  for (int a = 0; a < 3; ++a)
  {
    L.LineStart[a + 1] = L.LineStart[a] + vtkIdType(L.N[(a + 1) % 3]) * L.N[(a + 2) % 3];
  }
  return true;
}

void RunLattice(Triangulation& T, const Lattice& L)
{
  // PISURF_TIMING=1: the wall time of each pass on stderr.
  pisurf::PassTimer lap("vtkPiImageTriangulator");
  HitLattice hits(T, L);
  if (!hits.Run(lap))
  {
    return;
  }
  LatticeCells(T, L, hits.Lines()).Run(lap);
}

} // namespace triangulator
} // namespace pisurf
