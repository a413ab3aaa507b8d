// SPDX-License-Identifier: BSD-3-Clause
// The cast pass of vtkPiRayCaster: the roots of F along every ray of the rows, as hits.
#include "PiRayRowCaster.h"

#include "PiParallel.h"

#include "vtkAlgorithm.h"
#include "vtkMath.h"

#include <algorithm>
#include <utility>

namespace pisurf
{
namespace
{
// [t0, t1] ∩ [0, ∞) of the line o + t·d inside the box; false if it misses.
bool Clip(const double o[3], const double d[3], const double b[6], double& t0, double& t1)
{
  t0 = 0.0;
  t1 = VTK_DOUBLE_MAX;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      if (o[a] < b[2 * a] || o[a] > b[2 * a + 1])
      {
        return false;
      }
      continue;
    }
    double ta = (b[2 * a] - o[a]) / d[a], tb = (b[2 * a + 1] - o[a]) / d[a];
    if (ta > tb)
    {
      std::swap(ta, tb);
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 < t1;
}
}

// (Cast and operator() are inline, as when they were defined in the class, so that the
// compiler weighs inlining them into the loops over rows and rays as it did there.)
inline void RayRowCaster::Cast(const RayView& v, int viewIndex, int i, int j,
  std::vector<RayHit>& out, Buffers& buffers, const RayGrid* grid) const
{
  double o[3], d[3];
  double t0 = 0, t1 = v.Length;
  for (int k = 0; k < 3; ++k)
  {
    if (v.Perspective)
    {
      o[k] = v.O[k];
      d[k] = v.D[k] + i * v.U[k] + j * v.V[k];
    }
    else
    {
      o[k] = v.O[k] + i * v.U[k] + j * v.V[k];
      d[k] = v.D[k];
    }
  }
  // (a perspective ray's depth s along the view direction is t/|d|)
  const double norm = vtkMath::Normalize(d);
  if (!v.Axis && !Clip(o, d, this->Bounds, t0, t1))
  {
    return;
  }
  const RayViewSkipping& skipping = (*this->Skipping)[viewIndex];
  const RayDepthRange* range = nullptr;
  const RayDepthRange* rangeEnd = nullptr;
  if (skipping.Active)
  {
    const int column = (j / RayLeafSize) * skipping.Columns + i / RayLeafSize;
    range = skipping.Ranges.data() + skipping.Offsets[column];
    rangeEnd = skipping.Ranges.data() + skipping.Offsets[column + 1];
    if (range == rangeEnd)
    {
      return; // no root for any ray of the column
    }
  }
  const double depthToT = v.Perspective ? norm : 1.0;
  std::vector<RayRoot>& roots = buffers.Roots;
  RayRootOptions options;
  options.Tolerance = this->Tolerance;
  options.AllRoots = this->AllHits;
  // Orthographic views: the factors restricted from the row's coefficients, in the
  // grid's parameter s = t − h (t from the view plane).
  std::vector<double>& coefficients = buffers.Coefficients;
  double h = 0.0;
  if (grid)
  {
    coefficients.resize(this->Caster->GetLineCoefficientCount());
    grid->Restrict(buffers.Row, i, coefficients.data());
    h = grid->GetHalfLength();
  }
  // The roots on the segment [a, b] of the ray, as hits: from the grid's restriction,
  // or from the factors restricted about the segment's start (t' = t − a).
  int index = 0;
  // (pieces > 1: the grid's segment [cuts[0], cuts[pieces]] searched piece by piece,
  // each with its own monotony; the cuts in the grid's parameter s)
  std::vector<double>& cuts = buffers.Cuts;
  std::vector<int>& monotony = buffers.Monotony;
  auto search = [&](double a, double b, int pieces = 1)
  {
    if (grid)
    {
      if (pieces > 1)
      {
        this->Caster->CastRestricted(
          coefficients.data(), cuts.data(), monotony.data(), pieces, options, roots);
      }
      else
      {
        this->Caster->CastRestricted(coefficients.data(), a - h, b - h, options, roots);
      }
      for (const RayRoot& r : roots)
      {
        const double t = r.T + h;
        RayHit hit{ i, j, viewIndex, index++, t, r.Tangent, {} };
        for (int k = 0; k < 3; ++k)
        {
          hit.P[k] = o[k] + t * d[k];
        }
        out.push_back(hit);
      }
      return;
    }
    const double start[3] = { o[0] + a * d[0], o[1] + a * d[1], o[2] + a * d[2] };
    this->Caster->Cast(start, d, b - a, options, roots);
    for (const RayRoot& r : roots)
    {
      RayHit hit{ i, j, viewIndex, index++, a + r.T, r.Tangent, {} };
      for (int k = 0; k < 3; ++k)
      {
        hit.P[k] = start[k] + r.T * d[k];
      }
      out.push_back(hit);
    }
  };
  if (!range)
  {
    search(t0, t1);
    return;
  }
  // The column's ranges in increasing depth (no root lies between them). A run of
  // joined ranges is one segment, cut where the monotony changes: on the grid's rays
  // its pieces are searched with their own monotony in one cluster (a root on a cut
  // once); elsewhere (cameras, whose ranges are never joined) as one segment.
  while (range != rangeEnd)
  {
    const RayDepthRange* last = range + 1;
    while (last != rangeEnd && last->Joined)
    {
      ++last;
    }
    const double a = std::max(t0, range->Start * depthToT);
    const double b = std::min(t1, (last - 1)->End * depthToT);
    int pieces = 0;
    if (a < b && grid && last - range > 1)
    {
      cuts.assign(1, a - h);
      monotony.clear();
      for (const RayDepthRange* p = range; p != last; ++p)
      {
        const double end = p + 1 == last ? b : std::min(b, p->End * depthToT);
        if (end - h > cuts.back())
        {
          monotony.push_back(p->Monotone != 0);
          cuts.push_back(end - h);
          ++pieces;
        }
      }
    }
    // (A joined run as one segment, where its pieces are not searched apart, is not
    // proven monotone: its ranges' monotony differs from one to the next.)
    options.Monotone = last - range == 1 && range->Monotone != 0;
    range = last;
    if (!(a < b))
    {
      continue;
    }
    search(a, b, std::max(pieces, 1));
    if (!this->AllHits && !roots.empty())
    {
      return;
    }
  }
}

inline void RayRowCaster::operator()(vtkIdType begin, vtkIdType end)
{
  const bool single = pisurf::SingleThread();
  Buffers buffers;
  for (vtkIdType row = begin; row < end; ++row)
  {
    if (single && this->Algorithm->CheckAbort())
    {
      *this->Abort = true;
    }
    if (*this->Abort)
    {
      return;
    }
    // Rows are numbered view by view, RowEnd − RowBegin of them per view.
    const vtkIdType perView = this->RowEnd - this->RowBegin;
    const size_t vi = static_cast<size_t>(row / perView);
    const vtkIdType r = this->RowBegin + row % perView;
    const RayView& v = (*this->Views)[vi];
    std::vector<RayHit>& out = (*this->Rows)[row];
    out.reserve(static_cast<size_t>(v.W)); // (a hit per pixel, at first)
    const RayGrid* grid = (*this->Grids)[vi].get();
    if (grid)
    {
      grid->SetRow(static_cast<int>(r), buffers.Row);
    }
    for (int i = 0; i < v.W; ++i)
    {
      this->Cast(v, static_cast<int>(vi), i, static_cast<int>(r), out, buffers, grid);
    }
    // Casting is 80 % of the progress, reported from the main thread about every
    // percent.
    const vtkIdType finished = ++*this->Finished;
    if (single && finished * 100 / this->RowCount != (finished - 1) * 100 / this->RowCount)
    {
      this->Algorithm->UpdateProgress(0.8 * (static_cast<double>(finished) / this->RowCount));
    }
  }
}

void RayRowCaster::Run()
{
  // Rows differ a lot in cost (the model covers the middle of the image): small chunks
  // keep the threads balanced.
  pisurf::ParallelFor(0, this->RowCount, 8, *this);
}

std::vector<std::unique_ptr<RayGrid>> RayRowCaster::MakeGrids(
  const ProductKernel& kernel, const std::vector<RayView>& views, const double b[6])
{
  // About the middle of the box along the view.
  std::vector<std::unique_ptr<RayGrid>> grids(views.size());
  for (size_t k = 0; k < views.size(); ++k)
  {
    const RayView& v = views[k];
    if (v.Perspective)
    {
      continue;
    }
    double d[3] = { v.D[0], v.D[1], v.D[2] };
    vtkMath::Normalize(d);
    double length = v.Length;
    if (!v.Axis)
    {
      // Twice the distance from the view plane to the box centre along the rays.
      length = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        length += 2.0 * (0.5 * (b[2 * c] + b[2 * c + 1]) - v.O[c]) * d[c];
      }
    }
    grids[k] = std::make_unique<RayGrid>(kernel, v.O, v.U, v.V, d, v.W, v.H, length);
  }
  return grids;
}
}
