// SPDX-License-Identifier: BSD-3-Clause
// BEST_VIEW: ownership of the hits by the views, then the triangles of the pixel quads
// of each view, one image row per work item.
#include "PiBestView.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

namespace pisurf
{
namespace triangulator
{

BestView::BestView(Triangulation& t, double sheetTolerance)
  : T(t)
  , C(t.C)
  , SheetTolerance(sheetTolerance)
{
}

void BestView::Run()
{
  this->SortHits();
  this->ComputeFacing();
  // PASS 1: ownership. A hit belongs to the view that sees it best: the largest |n·d|
  // among the views whose ray through it reaches it first (within a footprint).
  this->Owner.resize(C.N);
  vtkSMPTools::For(0, C.N, [&](vtkIdType b, vtkIdType e) { this->Own(b, e); });
  T.Algorithm->UpdateProgress(0.4);
  this->Triangulate();
}

void BestView::SortHits()
{
  auto& pixelStart = this->PixelStart;
  auto& first = this->First;
  auto& hits = this->Hits;
  pixelStart.assign(T.Views.size() + 1, 0);
  for (size_t v = 0; v < T.Views.size(); ++v)
  {
    pixelStart[v + 1] = pixelStart[v] + vtkIdType(T.Views[v].W) * T.Views[v].H;
  }
  auto pixelOf = [&](vtkIdType id)
  {
    const View& v = T.Views[C.ViewOf[id]];
    return pixelStart[C.ViewOf[id]] + vtkIdType(C.Pixel[2 * id + 1]) * v.W + C.Pixel[2 * id];
  };
  const vtkIdType pixels = pixelStart.back();
  first.assign(pixels + 1, 0);
  hits.resize(C.N);
  for (vtkIdType id = 0; id < C.N; ++id)
  {
    ++first[pixelOf(id) + 1];
  }
  for (vtkIdType p = 0; p < pixels; ++p)
  {
    first[p + 1] += first[p];
  }
  {
    std::vector<vtkIdType> fill(first.begin(), first.end() - 1);
    for (vtkIdType id = 0; id < C.N; ++id)
    {
      hits[fill[pixelOf(id)]++] = id;
    }
  }
  vtkSMPTools::For(0, pixels,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType p = b; p < e; ++p)
      {
        std::sort(hits.begin() + first[p], hits.begin() + first[p + 1],
          [&](vtkIdType x, vtkIdType y) { return C.Depth[x] < C.Depth[y]; });
      }
    });
}

void BestView::ComputeFacing()
{
  auto& facingOf = this->FacingOf;
  facingOf.resize(C.N);
  vtkSMPTools::For(0, C.N,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType id = b; id < e; ++id)
      {
        const View& v = T.Views[C.ViewOf[id]];
        double o[3], d[3];
        v.Ray(C.Pixel[2 * id], C.Pixel[2 * id + 1], o, d);
        facingOf[id] =
          C.Normal[3 * id] * d[0] + C.Normal[3 * id + 1] * d[1] + C.Normal[3 * id + 2] * d[2];
      }
    });
}

void BestView::Own(vtkIdType b, vtkIdType e)
{
  const auto& pixelStart = this->PixelStart;
  const auto& first = this->First;
  const auto& hits = this->Hits;
  auto& owner = this->Owner;
  for (vtkIdType id = b; id < e; ++id)
  {
    const double* p = C.P.data() + 3 * id;
    int best = C.ViewOf[id];
    double bestCos = std::fabs(this->Facing(id));
    for (size_t w = 0; w < T.Views.size(); ++w)
    {
      if (static_cast<int>(w) == C.ViewOf[id] || C.Singular[id])
      {
        continue;
      }
      const View& v = T.Views[w];
      double fi, fj;
      if (!v.Project(p, fi, fj))
      {
        continue;
      }
      double o[3], d[3];
      v.Ray(fi, fj, o, d);
      const double c = std::fabs(
        C.Normal[3 * id] * d[0] + C.Normal[3 * id + 1] * d[1] + C.Normal[3 * id + 2] * d[2]);
      if (c <= bestCos)
      {
        continue;
      }
      // Visible in w: one of the four nearest pixels' first hits lies at p.
      const double reach = 2.0 * v.Footprint(std::sqrt(vtkMath::Distance2BetweenPoints(p, v.O)));
      bool seen = false;
      for (int q = 0; q < 4 && !seen; ++q)
      {
        const int pi = static_cast<int>(std::floor(fi)) + q % 2;
        const int pj = static_cast<int>(std::floor(fj)) + q / 2;
        if (pi < 0 || pj < 0 || pi >= v.W || pj >= v.H)
        {
          continue;
        }
        const vtkIdType px = pixelStart[w] + vtkIdType(pj) * v.W + pi;
        if (first[px] < first[px + 1])
        {
          const vtkIdType h = hits[first[px]];
          seen = vtkMath::Distance2BetweenPoints(p, C.P.data() + 3 * h) <= reach * reach;
        }
      }
      if (seen)
      {
        best = static_cast<int>(w);
        bestCos = c;
      }
    }
    owner[id] = best;
  }
}

// Two hits of neighbouring pixels of one view are on one sheet: same facing, and the
// depth of one within SheetTolerance footprints of the other's tangent plane.
inline bool BestView::Linked(vtkIdType a, vtkIdType b) const
{
  const View& v = T.Views[C.ViewOf[a]];
  const double fa = this->Facing(a), fb = this->Facing(b);
  if (!C.Singular[a] && !C.Singular[b] && (fa < 0) != (fb < 0))
  {
    return false;
  }
  const double tolerance = this->SheetTolerance * v.Footprint(0.5 * (C.Depth[a] + C.Depth[b]));
  auto predicted = [&](vtkIdType x, vtkIdType y)
  {
    // |depth where y's ray meets x's tangent plane − y's depth|, over the tolerance
    // grown as the plane turns away from the view (a tangent plane predicts a depth
    // change of footprint·tan θ, and its error grows like 1/cos θ), at most 4 times.
    double o[3], d[3];
    v.Ray(C.Pixel[2 * y], C.Pixel[2 * y + 1], o, d);
    const float* n = C.Normal.data() + 3 * x;
    const double* px = C.P.data() + 3 * x;
    const double nd = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
    const double w = n[0] * (px[0] - o[0]) + n[1] * (px[1] - o[1]) + n[2] * (px[2] - o[2]);
    const double* py = C.P.data() + 3 * y;
    const double ty = (py[0] - o[0]) * d[0] + (py[1] - o[1]) * d[1] + (py[2] - o[2]) * d[2];
    return std::fabs(nd) > 1e-12 ? std::fabs(w / nd - ty) * std::max(std::fabs(nd), 0.25)
                                 : VTK_DOUBLE_MAX;
  };
  double error = VTK_DOUBLE_MAX;
  if (!C.Singular[a])
  {
    error = std::min(error, predicted(a, b));
  }
  if (!C.Singular[b])
  {
    error = std::min(error, predicted(b, a));
  }
  if (C.Singular[a] && C.Singular[b])
  {
    error = std::sqrt(vtkMath::Distance2BetweenPoints(C.P.data() + 3 * a, C.P.data() + 3 * b)) -
      2 * tolerance;
  }
  return error <= tolerance;
}

// The hit of pixel px on the sheet of hit a, or −1.
inline vtkIdType BestView::Match(vtkIdType a, vtkIdType px) const
{
  const auto& first = this->First;
  const auto& hits = this->Hits;
  vtkIdType best = -1;
  double bestGap = VTK_DOUBLE_MAX;
  for (vtkIdType k = first[px]; k < first[px + 1]; ++k)
  {
    const vtkIdType b = hits[k];
    const double gap = std::fabs(C.Depth[b] - C.Depth[a]);
    if (gap < bestGap && this->Linked(a, b))
    {
      best = b;
      bestGap = gap;
    }
  }
  return best;
}

// PASS 2: per view and image row, the triangles of the pixel quads.
void BestView::Triangulate()
{
  auto& rows = this->QuadRows;
  for (size_t v = 0; v < T.Views.size(); ++v)
  {
    for (int j = 0; j + 1 < T.Views[v].H; ++j)
    {
      rows.emplace_back(v, j);
    }
  }
  this->RowTriangles.resize(rows.size());
  vtkSMPTools::For(0, static_cast<vtkIdType>(rows.size()),
    [&](vtkIdType rb, vtkIdType re)
    {
      for (vtkIdType r = rb; r < re && !T.Aborted(); ++r)
      {
        this->Row(r);
      }
    });
  T.Rows = std::move(this->RowTriangles);
}

void BestView::Row(vtkIdType r)
{
  const auto& rows = this->QuadRows;
  const auto& pixelStart = this->PixelStart;
  const auto& first = this->First;
  const auto& hits = this->Hits;
  const auto& owner = this->Owner;
  const int v = static_cast<int>(rows[r].first), j = rows[r].second;
  const View& view = T.Views[v];
  std::vector<std::int64_t>& tris = this->RowTriangles[r];
  auto emit = [&](vtkIdType a, vtkIdType b, vtkIdType c)
  {
    if (owner[a] == v && owner[b] == v && owner[c] == v)
    {
      tris.push_back(a);
      tris.push_back(b);
      tris.push_back(c);
    }
  };
  for (int i = 0; i + 1 < view.W; ++i)
  {
    const vtkIdType px[4] = { pixelStart[v] + vtkIdType(j) * view.W + i,
      pixelStart[v] + vtkIdType(j) * view.W + i + 1,
      pixelStart[v] + vtkIdType(j + 1) * view.W + i + 1,
      pixelStart[v] + vtkIdType(j + 1) * view.W + i };
    // Quads and triangles with a hit at corner 0.
    std::vector<vtkIdType> used;
    for (vtkIdType k = first[px[0]]; k < first[px[0] + 1]; ++k)
    {
      const vtkIdType a = hits[k];
      const vtkIdType m1 = this->Match(a, px[1]), m2 = this->Match(a, px[2]),
                      m3 = this->Match(a, px[3]);
      if (m1 >= 0 && m2 >= 0 && m3 >= 0)
      {
        // The diagonal through a singular corner, else the shorter one.
        bool diagonal02 = C.Singular[a] || C.Singular[m2];
        if (!diagonal02 && !C.Singular[m1] && !C.Singular[m3])
        {
          diagonal02 = vtkMath::Distance2BetweenPoints(C.P.data() + 3 * a, C.P.data() + 3 * m2) <=
            vtkMath::Distance2BetweenPoints(C.P.data() + 3 * m1, C.P.data() + 3 * m3);
        }
        if (diagonal02)
        {
          emit(a, m1, m2);
          emit(a, m2, m3);
        }
        else
        {
          emit(a, m1, m3);
          emit(m1, m2, m3);
        }
        used.push_back(m1);
      }
      else if (m1 >= 0 && m3 >= 0 && this->Linked(m1, m3))
      {
        emit(a, m1, m3);
      }
      else if (m1 >= 0 && m2 >= 0)
      {
        emit(a, m1, m2);
      }
      else if (m2 >= 0 && m3 >= 0)
      {
        emit(a, m2, m3);
      }
    }
    // The triangle without corner 0.
    for (vtkIdType k = first[px[1]]; k < first[px[1] + 1]; ++k)
    {
      const vtkIdType b = hits[k];
      if (std::find(used.begin(), used.end(), b) != used.end())
      {
        continue;
      }
      bool withCorner0 = false;
      for (vtkIdType q = first[px[0]]; q < first[px[0] + 1] && !withCorner0; ++q)
      {
        withCorner0 = this->Linked(hits[q], b);
      }
      const vtkIdType m2 = this->Match(b, px[2]), m3 = this->Match(b, px[3]);
      if (!withCorner0 && m2 >= 0 && m3 >= 0 && this->Linked(m2, m3))
      {
        emit(b, m2, m3);
      }
    }
  }
}

} // namespace triangulator
} // namespace pisurf
