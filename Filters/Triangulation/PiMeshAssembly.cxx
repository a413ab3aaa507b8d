// SPDX-License-Identifier: BSD-3-Clause
// The output mesh of vtkPiImageTriangulator, pass by pass over the rows of triangles
// (neighbouring triangles have neighbouring points, so every pass reads memory in
// order).
#include "PiMeshAssembly.h"
#include "PiEdgeFlips.h"
#include "PiHiddenComponents.h"
#include "PiLargeArrays.h"

#include "vtkSMPTools.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"

#include <algorithm>
#include <iostream>
#include <type_traits>

namespace pisurf
{
namespace triangulator
{

MeshAssembly::MeshAssembly(Triangulation& t, pisurf::PassTimer& timer)
  : T(t)
  , Lap(timer)
{
}

void MeshAssembly::Run(int edgeFlipRounds)
{
  this->NumberPoints();
  // Components that no ray of the views reaches are not what the views show:
  // components without an input hit are dropped.
  this->NewId = HiddenComponents(T.Rows, this->UsedHits, this->Total).Run(this->Count);
  this->Lap("components");
  this->Vertices();
  this->OrientTriangles();
  this->Compact(edgeFlipRounds);
}

// PASS 4: output ids. The hits used by a triangle come first, in input order, then the
// computed points in key order: the hidden roots (keys −1, −2, … as HitLattice numbers
// them, so reversed) and then the roots on lattice edges (EdgeBit keys, one copy per
// cell that used them: sorted and kept once).
void MeshAssembly::NumberPoints()
{
  pisurf::PassTimer& lap = this->Lap;
  const Cloud& C = T.C;
  auto& rowStart = this->RowStart;
  rowStart.assign(T.Rows.size() + 1, 0);
  for (size_t r = 0; r < T.Rows.size(); ++r)
  {
    rowStart[r + 1] = rowStart[r] + static_cast<vtkIdType>(T.Rows[r].size());
  }
  std::unique_ptr<std::atomic<unsigned char>[]> hitUsed(new std::atomic<unsigned char>[C.N]);
  vtkSMPTools::For(0, C.N,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType id = b; id < e; ++id)
      {
        hitUsed[id].store(0, std::memory_order_relaxed);
      }
    });
  vtkSMPTools::For(0, static_cast<vtkIdType>(T.Rows.size()),
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType r = b; r < e; ++r)
      {
        for (std::int64_t key : T.Rows[r])
        {
          if (key >= 0 && key < EdgeBit)
          {
            hitUsed[key].store(1, std::memory_order_relaxed);
          }
        }
      }
    });
  // Large arrays below are allocated uninitialized when a pass writes all of them (a
  // zeroing by one thread first would cost as much as the pass).
  this->HitOut.reset(new vtkIdType[C.N]);
  auto& hitOut = this->HitOut;
  vtkIdType& usedHits = this->UsedHits;
  for (vtkIdType id = 0; id < C.N; ++id)
  {
    hitOut[id] = hitUsed[id].load(std::memory_order_relaxed) ? usedHits++ : -1;
  }
  hitUsed.reset();
  const auto hiddenEnd = std::partition_point(
    T.Points.begin(), T.Points.end(), [](const Computed& c) { return c.Key < 0; });
  const vtkIdType hiddenCount = hiddenEnd - T.Points.begin();
  auto byKey = [](const Computed& x, const Computed& y) { return x.Key < y.Key; };
  std::sort(T.Points.begin() + hiddenCount, T.Points.end(), byKey);
  T.Points.erase(std::unique(T.Points.begin() + hiddenCount, T.Points.end(),
                   [](const Computed& x, const Computed& y) { return x.Key == y.Key; }),
    T.Points.end());
  std::vector<std::int64_t> edgeKeys;
  edgeKeys.reserve(T.Points.size() - hiddenCount);
  for (auto c = T.Points.begin() + hiddenCount; c != T.Points.end(); ++c)
  {
    edgeKeys.push_back(c->Key);
  }
  // Key −(index + 1) is at index; edge keys by binary search.
  auto computedId = [&](std::int64_t key) -> vtkIdType
  {
    return key < 0
      ? -key - 1
      : hiddenCount + (std::lower_bound(edgeKeys.begin(), edgeKeys.end(), key) - edgeKeys.begin());
  };
  const vtkIdType triangles = this->Triangles = rowStart.back() / 3;
  // The corners: each row's keys become point ids in place (no second array of all the
  // corners: its fresh pages would cost as much as filling it). The passes below go
  // through the rows; triangle t of the whole list is triangle t − rowStart[r] / 3 of
  // its row r.
  const vtkIdType rows = this->RowCount = static_cast<vtkIdType>(T.Rows.size());
  vtkSMPTools::For(0, rows,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType r = b; r < e; ++r)
      {
        for (std::int64_t& key : T.Rows[r])
        {
          key = key >= 0 && key < EdgeBit ? hitOut[key] : usedHits + computedId(key);
        }
      }
    });
  this->Total = usedHits + static_cast<vtkIdType>(T.Points.size());
  if (lap.IsEnabled())
  {
    std::cerr << "vtkPiImageTriangulator " << usedHits << " hits and " << T.Points.size()
              << " computed points in " << triangles << " triangles\n";
  }
  lap("output ids");
}

void MeshAssembly::Vertices()
{
  pisurf::PassTimer& lap = this->Lap;
  const Cloud& C = T.C;
  const vtkIdType n = this->Count, usedHits = this->UsedHits;
  const vtkIdType computedCount = this->Total - usedHits;
  const auto& hitOut = this->HitOut;
  const auto& newId = this->NewId;
  // The vertices: input hits copy their attributes, computed points take them from
  // the exact gradient.
  pisurf::AllocateLargePoints(this->Points, n);
  this->Normals->SetName("Normals");
  this->Normals->SetNumberOfComponents(3);
  pisurf::AllocateLargeArray(this->Normals.GetPointer(), n);
  this->Singular->SetName("Singular");
  pisurf::AllocateLargeArray(this->Singular.GetPointer(), n);
  this->View->SetName("ViewIndex");
  pisurf::AllocateLargeArray(this->View.GetPointer(), n);
  this->Factor->SetName("Factor");
  pisurf::AllocateLargeArray(this->Factor.GetPointer(), n);
  double* xyz = this->Xyz = vtkDoubleArray::SafeDownCast(this->Points->GetData())->GetPointer(0);
  float* nrmOut = this->NrmOut = this->Normals->GetPointer(0);
  // In input order (read in sequence, written where each point goes: scattered writes
  // cost less than scattered reads): hits copy, computed points evaluate.
  int* viewOut = this->View->GetPointer(0);
  int* factorOut = this->Factor->GetPointer(0);
  unsigned char* singularOut = this->Singular->GetPointer(0);
  vtkSMPTools::For(0, C.N,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType id = b; id < e; ++id)
      {
        const vtkIdType k = hitOut[id] < 0 ? -1 : newId[hitOut[id]];
        if (k < 0)
        {
          continue;
        }
        for (int a = 0; a < 3; ++a)
        {
          xyz[3 * k + a] = C.P[3 * id + a];
          nrmOut[3 * k + a] = C.Normal[3 * id + a];
        }
        singularOut[k] = C.Singular[id];
        viewOut[k] = C.ViewOf[id];
        factorOut[k] = C.Factor[id];
      }
    });
  vtkSMPTools::For(0, computedCount,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType q = b; q < e; ++q)
      {
        const vtkIdType k = newId[usedHits + q];
        if (k < 0)
        {
          continue;
        }
        const Computed& c = T.Points[q];
        for (int a = 0; a < 3; ++a)
        {
          xyz[3 * k + a] = c.P[a];
          nrmOut[3 * k + a] = c.N[a];
        }
        viewOut[k] = c.View;
        singularOut[k] = c.Singular ? 1 : 0;
        factorOut[k] = c.Nearest;
      }
    });

  lap("vertices");
}

void MeshAssembly::OrientTriangles()
{
  const vtkIdType rows = this->RowCount;
  const auto& rowStart = this->RowStart;
  const auto& newId = this->NewId;
  const double* xyz = this->Xyz;
  const float* nrmOut = this->NrmOut;
  // Triangles, oriented so that their normals agree with the exact gradient (outward);
  // degenerate ones (two corners on one hit) are dropped.
  this->Keep.reset(new unsigned char[this->Triangles]);
  auto& keep = this->Keep;
  vtkSMPTools::For(0, rows,
    [&](vtkIdType rb, vtkIdType re)
    {
      for (vtkIdType r = rb; r < re; ++r)
      {
        for (vtkIdType t = rowStart[r] / 3; t < rowStart[r + 1] / 3; ++t)
        {
          std::int64_t* corner = T.Rows[r].data() + (3 * t - rowStart[r]);
          keep[t] = 0;
          vtkIdType id[3];
          for (int c = 0; c < 3; ++c)
          {
            id[c] = newId[corner[c]];
          }
          if (id[0] < 0 || id[0] == id[1] || id[1] == id[2] || id[0] == id[2])
          {
            continue;
          }
          double u[3], v[3], nt[3], average[3] = { 0, 0, 0 };
          const double* p0 = xyz + 3 * id[0];
          for (int k = 0; k < 3; ++k)
          {
            u[k] = xyz[3 * id[1] + k] - p0[k];
            v[k] = xyz[3 * id[2] + k] - p0[k];
            for (int c = 0; c < 3; ++c)
            {
              average[k] += nrmOut[3 * id[c] + k];
            }
          }
          vtkMath::Cross(u, v, nt);
          if (vtkMath::Dot(nt, average) < 0)
          {
            std::swap(id[1], id[2]);
          }
          std::copy(id, id + 3, corner);
          keep[t] = 1;
        }
      }
    });
}

void MeshAssembly::Compact(int edgeFlipRounds)
{
  pisurf::PassTimer& lap = this->Lap;
  const vtkIdType rows = this->RowCount, n = this->Count;
  const auto& rowStart = this->RowStart;
  const auto& keep = this->Keep;
  double* xyz = this->Xyz;
  float* nrmOut = this->NrmOut;
  // The kept triangles, compacted in parallel: counted per row, then copied.
  std::vector<vtkIdType> blockStart(rows + 1, 0);
  vtkSMPTools::For(0, rows,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType r = b; r < e; ++r)
      {
        blockStart[r + 1] =
          std::count(keep.get() + rowStart[r] / 3, keep.get() + rowStart[r + 1] / 3, 1);
      }
    });
  for (vtkIdType r = 0; r < rows; ++r)
  {
    blockStart[r + 1] += blockStart[r];
  }
  const vtkIdType kept = blockStart[rows];
  // The cells in vtkCellArray's 32-bit storage when the ids fit (half the memory of
  // 64-bit ids for the flips below and every filter downstream), else 64-bit.
  pisurf::EdgeFlipResult flipped;
  auto compact = [&](auto* offsets, auto* cells)
  {
    using Id = std::remove_pointer_t<decltype(cells->GetPointer(0))>;
    pisurf::AllocateLargeArray(cells, 3 * kept);
    pisurf::AllocateLargeArray(offsets, kept + 1);
    Id* cellIds = cells->GetPointer(0);
    Id* offsetIds = offsets->GetPointer(0);
    vtkSMPTools::For(0, rows,
      [&](vtkIdType b, vtkIdType e)
      {
        for (vtkIdType r = b; r < e; ++r)
        {
          vtkIdType out = blockStart[r];
          const std::int64_t* corner = T.Rows[r].data();
          for (vtkIdType t = rowStart[r] / 3; t < rowStart[r + 1] / 3; ++t, corner += 3)
          {
            if (keep[t])
            {
              for (int c = 0; c < 3; ++c)
              {
                cellIds[3 * out + c] = static_cast<Id>(corner[c]);
              }
              offsetIds[out] = static_cast<Id>(3 * out);
              ++out;
            }
          }
          std::vector<std::int64_t>().swap(T.Rows[r]);
        }
      });
    offsetIds[kept] = static_cast<Id>(3 * kept);
    this->Polys->SetData(offsets, cells);
    lap("triangles");
    // Boundary edges (used by one triangle), then the edge flips towards the curvature
    // (PiEdgeFlips.h): vertices stay, the boundary and the topology too.
    flipped = pisurf::FlipEdgesToCurvature(cellIds, kept, n, xyz, nrmOut, edgeFlipRounds);
  };
  if (pisurf::FitsInt32Cells(kept, n))
  {
    vtkNew<vtkTypeInt32Array> offsets, cells;
    compact(offsets.Get(), cells.Get());
  }
  else
  {
    vtkNew<vtkTypeInt64Array> offsets, cells;
    compact(offsets.Get(), cells.Get());
  }
  this->BoundaryEdges = flipped.BoundaryEdges;
  if (lap.IsEnabled())
  {
    std::cerr << "vtkPiImageTriangulator " << flipped.Flips << " edges flipped in "
              << flipped.Rounds << " rounds\n";
  }
  lap("boundary edges and flips");
}

} // namespace triangulator
} // namespace pisurf
