// SPDX-License-Identifier: BSD-3-Clause
// RAY_LATTICE, passes 2 and 3: node signs, then the triangles of every cell, one row of
// columns (fixed j) per work item. A column's signs are constant between its flips, so
// runs of cells where the four columns of a row agree are skipped without a look.
#include "PiLatticeCells.h"
#include "PiEdgeFlips.h"
#include "PiMarchingCubes.h"
#include "PiRayRoots.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pisurf
{
namespace triangulator
{

LatticeCells::LatticeCells(Triangulation& t, const Lattice& l, const LatticeLines& lines)
  : T(t)
  , L(l)
  , Lines(lines)
  , nx(l.N[0] + 2)
  , ny(l.N[1] + 2)
  , nz(l.N[2] + 2)
  , Polygons(PolygonTable())
{
}

void LatticeCells::Run(pisurf::PassTimer& lap)
{
  // PASS 2: the sign of F (1 outside, 0 inside) at the nodes of every z column:
  // on a lattice line the parity of the crossings below the node, on the planes of the
  // box F itself (certified constant on a whole face when interval bounds allow).
  this->ClassifyFaces();
  lap("node signs");
  // PASS 3: vertices are the crossings on the cells' edges, looked up on their lattice
  // lines, or computed on the edge where no line carries one.
  this->RowTriangles.resize(ny - 1);
  this->RowPoints.resize(ny - 1);
  vtkSMPTools::For(0, ny - 1, [&](vtkIdType jb, vtkIdType je) { this->Rows(jb, je); });
  lap("cells");
  if (T.Abort)
  {
    return;
  }
  T.Rows = std::move(this->RowTriangles);
  for (auto& p : this->RowPoints)
  {
    T.Points.insert(T.Points.end(), p.begin(), p.end());
  }
}

void LatticeCells::ClassifyFaces()
{
  int* faceSign = this->FaceSign;
  for (int f = 0; f < 6; ++f)
  {
    double b[6] = { L.B0[0], L.B1[0], L.B0[1], L.B1[1], L.B0[2], L.B1[2] };
    const int a = f / 2;
    b[2 * a] = b[2 * a + 1] = (f % 2 ? L.B1[a] : L.B0[a]);
    const int c = T.Classify(b);
    faceSign[f] = c == 0 ? -1 : (c > 0 ? 1 : 0);
  }
}

inline int LatticeCells::NodeSign(int i, int j, int m) const
{
  const double p[3] = { L.X(0, i), L.X(1, j), L.X(2, m) };
  return T.Sign(p);
}

// The level after which a column's sign flips at x.
inline int LatticeCells::FlipLevel(double x) const
{
  int g = static_cast<int>(std::floor((x - L.B0[2]) / L.H[2] + 0.5));
  g = std::max(0, std::min(g, nz - 1));
  while (g + 1 < nz && L.X(2, g + 1) <= x)
  {
    ++g;
  }
  while (g > 0 && L.X(2, g) > x)
  {
    --g;
  }
  return g;
}

// The z column through nodes (i, j): its sign at level 0, and the levels m after which
// its sign flips (sorted; the sign at level m' > m is toggled).
unsigned char LatticeCells::ColumnFlips(
  int i, int j, std::vector<int>& flips, std::vector<pisurf::RayRoot>& roots) const
{
  const int* faceSign = this->FaceSign;
  const bool boundary = i == 0 || i == nx - 1 || j == 0 || j == ny - 1;
  if (boundary)
  {
    const int f = i == 0 ? 0 : i == nx - 1 ? 1 : j == 0 ? 2 : 3;
    if (faceSign[f] >= 0)
    {
      return static_cast<unsigned char>(faceSign[f]);
    }
    const int s0 = this->NodeSign(i, j, 0);
    if (T.Caster)
    {
      // A column on a plane of the box that no view casts: its roots, certified.
      const double o[3] = { L.X(0, i), L.X(1, j), L.B0[2] }, d[3] = { 0, 0, 1 };
      pisurf::RayRootOptions options;
      options.Tolerance = 1e-10 * T.Size;
      T.Caster->Cast(o, d, L.B1[2] - L.B0[2], options, roots);
      for (const pisurf::RayRoot& r : roots)
      {
        const int level = this->FlipLevel(L.B0[2] + r.T);
        if (!r.Tangent && level < nz - 1)
        {
          flips.push_back(level);
        }
      }
      return static_cast<unsigned char>(s0);
    }
    int previous = s0;
    for (int m = 1; m < nz; ++m)
    {
      const int sm = this->NodeSign(i, j, m);
      if (sm != previous)
      {
        flips.push_back(m - 1);
      }
      previous = sm;
    }
    return static_cast<unsigned char>(s0);
  }
  const unsigned char sign = faceSign[4] >= 0 ? faceSign[4] : this->NodeSign(i, j, 0);
  const vtkIdType l = L.Line(2, i, j);
  for (const Sample* c = this->Lines.Begin(l); c != this->Lines.End(l); ++c)
  {
    const int level = this->FlipLevel(c->X);
    if (!c->Removed() && !c->Tangent() && level < nz - 1)
    {
      flips.push_back(level);
    }
  }
  return sign;
}

void LatticeCells::FillSide(Sides& s, int side, int jn) const
{
  s.Flips[side].clear();
  s.Offset[side].assign(1, 0);
  s.StartSign[side].clear();
  for (int i = 0; i < nx; ++i)
  {
    s.StartSign[side].push_back(this->ColumnFlips(i, jn, s.Flips[side], s.Roots));
    s.Offset[side].push_back(s.Flips[side].size());
  }
}

void LatticeCells::Rows(vtkIdType jb, vtkIdType je)
{
  Sides s;
  auto& flips = s.Flips;
  auto& offset = s.Offset;
  auto& startSign = s.StartSign;
  size_t previousRow = 0; // keys of the row before: the next one has about as many
  for (vtkIdType jj = jb; jj < je && !T.Aborted(); ++jj)
  {
    const int j = static_cast<int>(jj);
    const double progress = 0.3 + 0.6 * j / (ny - 1);
    if (pisurf::SingleThread() && progress > this->ReportedProgress)
    {
      this->ReportedProgress = progress;
      T.Algorithm->UpdateProgress(progress);
    }
    if (jj == jb)
    {
      this->FillSide(s, 0, j);
    }
    else
    {
      std::swap(flips[0], flips[1]);
      std::swap(offset[0], offset[1]);
      std::swap(startSign[0], startSign[1]);
    }
    this->FillSide(s, 1, j + 1);
    std::vector<std::int64_t>& tris = this->RowTriangles[j];
    tris.reserve(previousRow + previousRow / 4);
    std::vector<Computed>& pts = this->RowPoints[j];
    this->Row(j, s, tris, pts);
    previousRow = tris.size();
  }
}

// The cells (i, j, ·) of row j, column by column.
void LatticeCells::Row(
  int j, const Sides& s, std::vector<std::int64_t>& tris, std::vector<Computed>& pts)
{
  const auto& flips = s.Flips;
  const auto& offset = s.Offset;
  const auto& startSign = s.StartSign;
  for (int i = 0; i + 1 < nx; ++i)
  {
    // The four columns of the cells (i, j, ·) in marching-cubes corner order. Their
    // signs are constant between flips: a run of cells where the four disagree is
    // a wall (all active), where they agree it is skipped.
    const int side[4] = { 0, 0, 1, 1 }, column[4] = { i, i + 1, i + 1, i };
    const int* f[4];
    const int* fe[4];
    unsigned char sg[4];
    for (int q = 0; q < 4; ++q)
    {
      f[q] = flips[side[q]].data() + offset[side[q]][column[q]];
      fe[q] = flips[side[q]].data() + offset[side[q]][column[q] + 1];
      sg[q] = startSign[side[q]][column[q]];
    }
    for (int m = 0;;)
    {
      int e = nz - 1;
      for (int q = 0; q < 4; ++q)
      {
        if (f[q] != fe[q])
        {
          e = std::min(e, *f[q]);
        }
      }
      if (!(sg[0] == sg[1] && sg[1] == sg[2] && sg[2] == sg[3]))
      {
        for (int c = m; c < e && c < nz - 1; ++c)
        {
          this->EmitCell(i, j, c, sg, sg, tris, pts);
        }
      }
      if (e >= nz - 1)
      {
        break;
      }
      unsigned char top[4] = { sg[0], sg[1], sg[2], sg[3] };
      for (int q = 0; q < 4; ++q)
      {
        for (; f[q] != fe[q] && *f[q] == e; ++f[q])
        {
          top[q] ^= 1;
        }
      }
      this->EmitCell(i, j, e, sg, top, tris, pts);
      std::copy(top, top + 4, sg);
      m = e + 1;
    }
  }
}

// Each polygon of the case (one per sheet through the cell) is triangulated along the
// diagonals the surface bends least along (the least total pisurf::Bend, dynamic programming
// over the polygon's triangulations; ties: the first).
inline void LatticeCells::EmitCell(int i, int j, int m, const unsigned char* bottom,
  const unsigned char* top, std::vector<std::int64_t>& tris, std::vector<Computed>& pts)
{
  int index = 0;
  for (int q = 0; q < 4; ++q)
  {
    index |= (bottom[q] << q) | (top[q] << (q + 4));
  }
  if (index == 0 || index == 255)
  {
    return;
  }
  for (const std::vector<int>& polygon : this->Polygons[index])
  {
    const int size = static_cast<int>(polygon.size());
    Ref v[12];
    Computed local[12];
    bool distinct = true;
    for (int k = 0; k < size; ++k)
    {
      // The marching-cubes edge as a lattice edge: axis and lower corner.
      const pisurf::mc::EdgeStart& x = pisurf::mc::EdgeStarts.Of[polygon[k]];
      v[k] = this->Vertex(x.Axis, i + x.Lo[0], j + x.Lo[1], m + x.Lo[2], local[k], pts);
      for (int q = 0; q < k; ++q)
      {
        distinct = distinct && v[q].Key != v[k].Key;
      }
    }
    if (size == 3 || !distinct || !T.ChooseDiagonals)
    {
      // A fan from the first corner: no choice to make, EdgeFlipRounds 0, or two
      // corners on one hit (degenerate triangles are dropped later).
      for (int k = 1; k + 1 < size; ++k)
      {
        tris.push_back(v[0].Key);
        tris.push_back(v[k].Key);
        tris.push_back(v[k + 1].Key);
      }
      continue;
    }
    if (size == 4)
    {
      // (the common case: the shorter bend of the two diagonals)
      const int d =
        pisurf::Bend(v[0].P, v[0].N, v[2].P, v[2].N) <= pisurf::Bend(v[1].P, v[1].N, v[3].P, v[3].N)
        ? 0
        : 1;
      for (int t = 0; t < 2; ++t)
      {
        tris.push_back(v[d].Key);
        tris.push_back(v[d + 1 + t].Key);
        tris.push_back(v[(d + 2 + t) % 4].Key);
      }
      continue;
    }
    SplitPolygon(v, size, tris);
  }
}

// The triangulation of the least total bend of a polygon of 5 or more corners.
void LatticeCells::SplitPolygon(const Ref* v, int size, std::vector<std::int64_t>& tris)
{
  double cost[12][12];
  int split[12][12];
  auto bend = [&](int a, int b)
  {
    return b == a + 1 || (a == 0 && b == size - 1) ? 0.0
                                                   : pisurf::Bend(v[a].P, v[a].N, v[b].P, v[b].N);
  };
  for (int k = 0; k + 1 < size; ++k)
  {
    cost[k][k + 1] = 0;
  }
  for (int length = 2; length < size; ++length)
  {
    for (int a = 0; a + length < size; ++a)
    {
      const int b = a + length;
      cost[a][b] = std::numeric_limits<double>::infinity();
      for (int k = a + 1; k < b; ++k)
      {
        const double c = cost[a][k] + cost[k][b] + bend(a, k) + bend(k, b);
        if (c < cost[a][b])
        {
          cost[a][b] = c;
          split[a][b] = k;
        }
      }
    }
  }
  int stack[24], top = 0;
  stack[top++] = 0;
  stack[top++] = size - 1;
  while (top > 0)
  {
    const int b = stack[--top], a = stack[--top];
    if (b - a < 2)
    {
      continue;
    }
    const int k = split[a][b];
    tris.push_back(v[a].Key);
    tris.push_back(v[k].Key);
    tris.push_back(v[b].Key);
    stack[top++] = a;
    stack[top++] = k;
    stack[top++] = k;
    stack[top++] = b;
  }
}

// The vertex on the edge along axis a from node (i, jn, m): its key, position and
// normal (an edge root is computed into `c`).
inline LatticeCells::Ref LatticeCells::Vertex(
  int a, int i, int jn, int m, Computed& c, std::vector<Computed>& pts)
{
  const int n[3] = { i, jn, m };
  const int mu = n[(a + 1) % 3], mv = n[(a + 2) % 3];
  if (L.HasLine(a, mu, mv))
  {
    if (const Sample* s =
          this->Lines.FirstCrossing(L.Line(a, mu, mv), L.X(a, n[a]), L.X(a, n[a] + 1)))
    {
      const std::int64_t code = s->Code();
      if (code >= 0)
      {
        return { code, T.C.P.data() + 3 * code, T.C.Normal.data() + 3 * code };
      }
      const Computed& h = T.Points[-code - 1];
      return { code, h.P, h.N };
    }
  }
  // No line carries it (a plane of the box, or a root within 1e-10 of a node):
  // the root of F on the edge itself.
  const std::int64_t key = EdgeBit | ((((std::int64_t(m) * ny + jn) * nx + i) * 3) + a);
  c.Key = key;
  c.View = -1;
  double p0[3] = { L.X(0, i), L.X(1, jn), L.X(2, m) };
  c.P[0] = p0[0];
  c.P[1] = p0[1];
  c.P[2] = p0[2];
  if (T.Caster)
  {
    const double x0 = L.X(a, n[a]), x1 = L.X(a, n[a] + 1);
    auto phi = [&](double x)
    {
      double q[3] = { p0[0], p0[1], p0[2] };
      q[a] = x;
      return T.Compressed(q);
    };
    const double v0 = phi(x0), v1 = phi(x1);
    c.P[a] = (v0 < 0) != (v1 < 0) ? pisurf::BracketedRoot(phi, x0, x1, v0, v1, 1e-10 * T.Size, 0.0)
                                  : 0.5 * (x0 + x1);
  }
  else
  {
    c.P[a] = 0.5 * (L.X(a, n[a]) + L.X(a, n[a] + 1));
  }
  T.Attributes(c);
  pts.push_back(c);
  return { key, c.P, c.N };
}

} // namespace triangulator
} // namespace pisurf
