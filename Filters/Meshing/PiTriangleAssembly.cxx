// SPDX-License-Identifier: BSD-3-Clause
// PASSES 5 and 6 of the mesher: the contouring's driver (see PiTriangleAssembly.h).
#include "PiTriangleAssembly.h"

#include "PiBlockContour.h"
#include "PiEdgeFlips.h"
#include "PiLargeArrays.h"
#include "PiParallel.h"
#include "PiTiming.h"
#include "vtkCellArray.h"

#include <iostream>
#include <type_traits>
#include <vector>

namespace pisurf
{
void TriangleAssembly::Run(const BlockGrid& g, const OuterEnvelope* envelope, const PieceSlab& slab,
  MeshingWork& work, pisurf::PassTimer& lap)
{
  const int slabBegin = slab.SlabBegin, slabEnd = slab.SlabEnd;
  const vtkIdType activeCount = static_cast<vtkIdType>(g.Active.size());
  std::vector<vtkIdType> vertexCount(activeCount + 1, 0), triangleCount(activeCount + 1, 0);
  // (not initialized on allocation: the Write pass writes every entry)
  pisurf::Buffer<vtkIdType>& vertexEdge = work.VertexEdge;
  pisurf::Buffer<double>& vertexT = work.VertexT;
  pisurf::Buffer<double>& vertexEnds = work.VertexEnds;
  // Triangles per marching-cubes case.
  std::uint8_t trianglesOfCase[256];
  for (int index = 0; index < 256; ++index)
  {
    int count = 0;
    for (const int* e = vtkMarchingCubesTriangleCases::GetCases()[index].edges; *e >= 0; e += 3)
    {
      ++count;
    }
    trianglesOfCase[index] = static_cast<std::uint8_t>(count);
  }
  BlockContour contour{ &g, envelope, vtkMarchingCubesTriangleCases::GetCases(), &vertexCount,
    &triangleCount, &vertexEdge, &vertexT, &vertexEnds, nullptr, nullptr, BlockContour::Count,
    slabBegin, slabEnd, nullptr, nullptr, nullptr, trianglesOfCase };
  pisurf::Buffer<std::uint16_t>& rowSigns = work.RowSigns;
  pisurf::Buffer<std::uint16_t>& edgeOffsets = work.EdgeOffsets;
  pisurf::Buffer<std::uint8_t>& edgeMasks = work.EdgeMasks;
  rowSigns.Reserve(size_t(activeCount) * BlockContour::Rows);
  edgeMasks.Reserve(size_t(activeCount) * BlockContour::EdgeRows);
  edgeOffsets.Reserve(size_t(activeCount) * BlockContour::EdgeRows);
  contour.RowSigns = rowSigns.GetPointer();
  contour.EdgeMasks = edgeMasks.GetPointer();
  contour.EdgeOffsets = edgeOffsets.GetPointer();
  pisurf::ParallelFor(0, activeCount, 8, contour);
  vtkIdType vertices = 0, triangles = 0;
  if (lap.IsEnabled())
  {
    // How many active blocks the enclosures could not rule out but hold no surface.
    vtkIdType crossed = 0;
    for (vtkIdType s = 0; s < activeCount; ++s)
    {
      crossed += vertexCount[s] > 0 || triangleCount[s] > 0;
    }
    std::cerr << crossed << " of " << activeCount << " active blocks hold the surface\n";
  }
  for (vtkIdType s = 0; s < activeCount; ++s)
  {
    int c[3];
    g.BlockCoordinates(g.Active[s], c);
    const vtkIdType nv = vertexCount[s];
    const vtkIdType nt = c[2] >= slabBegin && c[2] < slabEnd ? triangleCount[s] : 0;
    vertexCount[s] = vertices;
    triangleCount[s] = triangles;
    vertices += nv;
    triangles += nt;
  }
  vertexCount[activeCount] = vertices;
  triangleCount[activeCount] = triangles;
  vertexEdge.Reserve(vertices);
  vertexT.Reserve(vertices);
  vertexEnds.Reserve(2 * vertices);
  // The cells in vtkCellArray's 32-bit storage when the ids fit (half the memory).
  const bool narrow = pisurf::FitsInt32Cells(triangles, vertices);
  vtkIdTypeArray* connectivity = this->Connectivity;
  vtkTypeInt32Array* connectivity32 = this->Connectivity32;
  if (narrow)
  {
    pisurf::AllocateLargeArray(connectivity32, 3 * triangles);
    contour.TriangleIds32 = connectivity32->GetPointer(0);
  }
  else
  {
    pisurf::AllocateLargeArray(connectivity, 3 * triangles);
    contour.TriangleIds = connectivity->GetPointer(0);
  }
  // The vertices' edges and the triangles (which look up neighbours' Count tables).
  contour.Pass = BlockContour::Write;
  pisurf::ParallelFor(0, activeCount, 8, contour);
  this->Vertices = vertices;
  this->Triangles = triangles;
  this->Narrow = narrow;
  if (slab.Pieces > 1)
  {
    this->KeepUsedVertices(work);
  }
}

void TriangleAssembly::KeepUsedVertices(MeshingWork& work)
{
  const bool narrow = this->Narrow;
  const vtkIdType vertices = this->Vertices, triangles = this->Triangles;
  vtkIdTypeArray* connectivity = this->Connectivity;
  vtkTypeInt32Array* connectivity32 = this->Connectivity32;
  Buffer<vtkIdType>& vertexEdge = work.VertexEdge;
  Buffer<double>& vertexT = work.VertexT;
  Buffer<double>& vertexEnds = work.VertexEnds;
  // Keep only the vertices this piece's triangles use (the seams' vertices are shared
  // with the neighbouring piece, at identical positions).
  std::vector<vtkIdType> renumber(vertices, -1);
  auto id = [&](vtkIdType t) -> vtkIdType
  { return narrow ? connectivity32->GetPointer(0)[t] : connectivity->GetPointer(0)[t]; };
  for (vtkIdType t = 0; t < 3 * triangles; ++t)
  {
    renumber[id(t)] = 0;
  }
  vtkIdType used = 0;
  for (vtkIdType v = 0; v < vertices; ++v)
  {
    if (renumber[v] == 0)
    {
      vertexEdge[used] = vertexEdge[v];
      vertexT[used] = vertexT[v];
      vertexEnds[2 * used] = vertexEnds[2 * v];
      vertexEnds[2 * used + 1] = vertexEnds[2 * v + 1];
      renumber[v] = used++;
    }
  }
  for (vtkIdType t = 0; t < 3 * triangles; ++t)
  {
    if (narrow)
    {
      connectivity32->SetValue(t, static_cast<std::int32_t>(renumber[id(t)]));
    }
    else
    {
      connectivity->SetValue(t, renumber[id(t)]);
    }
  }
  this->Vertices = used;
}

vtkSmartPointer<vtkCellArray> TriangleAssembly::NewCells() const
{
  const vtkIdType triangles = this->Triangles;
  const bool narrow = this->Narrow;
  vtkIdTypeArray* connectivity = this->Connectivity.GetPointer();
  vtkTypeInt32Array* connectivity32 = this->Connectivity32.GetPointer();
  // Triangles face ∇F, like the Normals, so renderers light the side they see (the
  // Triangles pass wound them so). The offsets are written here: vtkCellArray takes both
  // arrays as they are (SetData with a cell size would copy the connectivity and fill the
  // offsets on one thread).
  vtkNew<vtkCellArray> polys;
  auto fillOffsets = [triangles](auto* offset)
  {
    using Id = typename std::remove_pointer<decltype(offset)>::type;
    pisurf::ParallelFor(0, triangles + 1, 0,
      [offset](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType t = begin; t < end; ++t)
        {
          offset[t] = static_cast<Id>(3 * t);
        }
      });
  };
  if (narrow)
  {
    vtkNew<vtkTypeInt32Array> offsets;
    pisurf::AllocateLargeArray(offsets.GetPointer(), triangles + 1);
    fillOffsets(offsets->GetPointer(0));
    polys->SetData(offsets, connectivity32);
  }
  else
  {
    vtkNew<vtkIdTypeArray> offsets;
    pisurf::AllocateLargeArray(offsets.GetPointer(), triangles + 1);
    fillOffsets(offsets->GetPointer(0));
    polys->SetData(offsets, connectivity);
  }
  return polys;
}
}
