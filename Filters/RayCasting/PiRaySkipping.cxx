// SPDX-License-Identifier: BSD-3-Clause
// The empty-space skipping pass of vtkPiRayCaster: per view, each leaf column's depth
// ranges that may hold roots, from the octrees of its tiles (PiRaySkipping.h).
#include "PiRaySkipping.h"

#include "PiParallel.h"
#include "PiRayTileOctree.h"

#include "vtkMath.h"

#include <algorithm>
#include <ostream>

namespace pisurf
{
void RaySkipping::Build(const ProductKernel& kernel, const std::vector<RayView>& views,
  const double b[6], int rowBegin, int rowEnd, bool allHits, std::vector<RayViewSkipping>& skipping)
{
  for (size_t k = 0; k < views.size(); ++k)
  {
    const RayView& v = views[k];
    if (!v.Axis && !v.Perspective)
    {
      // A parallel camera: its rays already restrict cheaply from the view's grid and
      // the boxes of its oblique tiles are loose; the octree cost about what it saved.
      continue;
    }
    double s0, s1;
    int axis;
    if (!DepthExtent(v, b, s0, s1, axis))
    {
      continue;
    }
    // Per tile, its columns' ranges (then gathered into the view's CSR).
    std::vector<std::vector<int>> tileOffsets;
    std::vector<std::vector<RayDepthRange>> tileRanges;
    Tiles(kernel, v, axis, s0, s1, rowBegin, rowEnd, allHits, tileOffsets, tileRanges);
    Gather(v, rowBegin, rowEnd, tileOffsets, tileRanges, skipping[k]);
  }
}

bool RaySkipping::DepthExtent(
  const RayView& v, const double b[6], double& s0, double& s1, int& axis)
{
  // The depths [s0, s1] the rays can meet the bounds at: the whole segment of an
  // axis view; for a camera view, the bounds' corners along the view direction
  // (perspective: D + i·U + j·V has depth 1 along it).
  s0 = 0.0;
  s1 = v.Length;
  axis = -1;
  if (v.Axis)
  {
    axis = 0;
    while (axis < 2 && v.D[axis] == 0.0)
    {
      ++axis;
    }
  }
  else
  {
    double dir[3] = { v.D[0], v.D[1], v.D[2] };
    if (v.Perspective)
    {
      // The view direction: D without its parts along U and V (both orthogonal to it).
      for (const double* e : { v.U, v.V })
      {
        const double scale = vtkMath::Dot(dir, e) / vtkMath::Dot(e, e);
        for (int c = 0; c < 3; ++c)
        {
          dir[c] -= scale * e[c];
        }
      }
    }
    s0 = VTK_DOUBLE_MAX;
    s1 = -VTK_DOUBLE_MAX;
    for (int corner = 0; corner < 8; ++corner)
    {
      double depth = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        depth += (b[2 * c + ((corner >> c) & 1)] - v.O[c]) * dir[c];
      }
      s0 = std::min(s0, depth);
      s1 = std::max(s1, depth);
    }
    s0 = std::max(s0, 0.0);
    if (!(s1 > s0))
    {
      return false; // the bounds are behind the camera: every ray misses them
    }
  }
  return true;
}

void RaySkipping::Tiles(const ProductKernel& kernel, const RayView& v, int axis, double s0,
  double s1, int rowBegin, int rowEnd, bool allHits, std::vector<std::vector<int>>& tileOffsets,
  std::vector<std::vector<RayDepthRange>>& tileRanges)
{
  const int tw = (v.W + RayTileSize - 1) / RayTileSize;
  const int tileRowBegin = rowBegin / RayTileSize, tileRowEnd = (rowEnd - 1) / RayTileSize + 1;
  const int tileCount = tw * (tileRowEnd - tileRowBegin);
  tileOffsets.resize(tileCount);
  tileRanges.resize(tileCount);
  // (one tile per task: a tile's cost depends on how much of the model it sees)
  pisurf::ParallelFor(0, tileCount, 1,
    [&](vtkIdType begin, vtkIdType end)
    {
      RayTileOctree octree;
      octree.Kernel = &kernel;
      octree.V = &v;
      octree.Axis = axis;
      octree.U = (axis + 1) % 3;
      octree.W = (axis + 2) % 3;
      octree.PixelSize = std::max(vtkMath::Norm(v.U), vtkMath::Norm(v.V));
      octree.RowBegin = rowBegin;
      octree.RowEnd = rowEnd;
      // (axis views only: a camera's boxes reach beyond the bounds, where its rays,
      // clipped to them, do not search, so a sign change there proves no hit)
      octree.FirstHit = !allHits && axis >= 0;
      for (vtkIdType id = begin; id < end; ++id)
      {
        octree.TileI = static_cast<int>(id % tw) * RayTileSize;
        octree.TileJ = (tileRowBegin + static_cast<int>(id / tw)) * RayTileSize;
        octree.Leaves.clear();
        octree.ResetCuts();
        octree.Visit(octree.TileI, octree.TileJ, RayTileSize, s0, s1);
        // Counting sort by column (stable: each column keeps increasing depth), merging
        // ranges that touch.
        MergeColumns(octree.Leaves, tileOffsets[id], tileRanges[id]);
      }
    });
}

void RaySkipping::MergeColumns(const std::vector<std::pair<int, RayDepthRange>>& leaves,
  std::vector<int>& offsets, std::vector<RayDepthRange>& ranges)
{
  constexpr int PerTile = (RayTileSize / RayLeafSize) * (RayTileSize / RayLeafSize);
  offsets.assign(PerTile + 1, 0);
  for (const auto& leaf : leaves)
  {
    ++offsets[leaf.first + 1];
  }
  for (int c = 0; c < PerTile; ++c)
  {
    offsets[c + 1] += offsets[c];
  }
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  std::vector<RayDepthRange> sorted(leaves.size());
  for (const auto& leaf : leaves)
  {
    sorted[fill[leaf.first]++] = leaf.second;
  }
  ranges.clear();
  int kept = 0;
  for (int c = 0; c < PerTile; ++c)
  {
    const int first = kept;
    for (int m = offsets[c]; m < offsets[c + 1]; ++m)
    {
      // (Overlapping ranges are merged whatever their monotony.)
      const bool touches = kept > first && ranges.back().End >= sorted[m].Start;
      if (touches &&
        (ranges.back().Monotone == sorted[m].Monotone || ranges.back().End > sorted[m].Start))
      {
        ranges.back().End = std::max(ranges.back().End, sorted[m].End);
        // (F monotone the same way on both parts is so on their union)
        if (ranges.back().Monotone != sorted[m].Monotone)
        {
          ranges.back().Monotone = 0;
        }
      }
      else
      {
        ranges.push_back(sorted[m]);
        ranges.back().Joined = touches;
        ++kept;
      }
    }
    offsets[c] = first;
  }
  offsets[PerTile] = kept;
}

void RaySkipping::Gather(const RayView& v, int rowBegin, int rowEnd,
  const std::vector<std::vector<int>>& tileOffsets,
  const std::vector<std::vector<RayDepthRange>>& tileRanges, RayViewSkipping& view)
{
  const int tw = (v.W + RayTileSize - 1) / RayTileSize;
  const int tileRowBegin = rowBegin / RayTileSize, tileRowEnd = (rowEnd - 1) / RayTileSize + 1;
  const int tileCount = tw * (tileRowEnd - tileRowBegin);
  constexpr int PerTile = (RayTileSize / RayLeafSize) * (RayTileSize / RayLeafSize);
  // The view's CSR over its leaf columns (rows of columns outside the piece: none).
  view.Active = true;
  view.Columns = tw * (RayTileSize / RayLeafSize);
  const int columnRows = ((v.H + RayTileSize - 1) / RayTileSize) * (RayTileSize / RayLeafSize);
  view.Offsets.assign(static_cast<size_t>(view.Columns) * columnRows + 1, 0);
  // The view's column of column c of tile `id`.
  auto column = [&](int id, int c)
  {
    const int ci = (id % tw) * (RayTileSize / RayLeafSize) + c % (RayTileSize / RayLeafSize);
    const int cj =
      (tileRowBegin + id / tw) * (RayTileSize / RayLeafSize) + c / (RayTileSize / RayLeafSize);
    return static_cast<size_t>(cj) * view.Columns + ci;
  };
  for (int id = 0; id < tileCount; ++id)
  {
    for (int c = 0; c < PerTile; ++c)
    {
      view.Offsets[column(id, c) + 1] = tileOffsets[id][c + 1] - tileOffsets[id][c];
    }
  }
  for (size_t c = 1; c < view.Offsets.size(); ++c)
  {
    view.Offsets[c] += view.Offsets[c - 1];
  }
  view.Ranges.resize(static_cast<size_t>(view.Offsets.back()));
  for (int id = 0; id < tileCount; ++id)
  {
    for (int c = 0; c < PerTile; ++c)
    {
      std::copy(tileRanges[id].begin() + tileOffsets[id][c],
        tileRanges[id].begin() + tileOffsets[id][c + 1],
        view.Ranges.begin() + view.Offsets[column(id, c)]);
    }
  }
}

void RaySkipping::PrintCounts(const std::vector<RayViewSkipping>& skipping, std::ostream& os)
{
  size_t ranges = 0, monotone = 0;
  for (const RayViewSkipping& view : skipping)
  {
    ranges += view.Ranges.size();
    for (const RayDepthRange& r : view.Ranges)
    {
      monotone += r.Monotone != 0;
    }
  }
  os << ranges << " depth ranges to search, " << monotone << " of them monotone\n";
}
}
