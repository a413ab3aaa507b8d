// SPDX-License-Identifier: BSD-3-Clause
// PASSES 5 and 6 of the mesher, run over the active blocks: count the crossing edges
// and triangles per block, number them, then write each vertex's edge and the
// triangles' point ids; and the triangles as the output's cell array.
#ifndef PiTriangleAssembly_h
#define PiTriangleAssembly_h

#include "PiBlockGrid.h"
#include "PiMeshingWork.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkTypeInt32Array.h"

namespace pisurf
{
class PassTimer;
}
class vtkCellArray;

namespace pisurf
{
class OuterEnvelope;

class TriangleAssembly
{
public:
  /// Contours g's active blocks (with `envelope`'s signs where it is not null): the
  /// vertices' edge keys, crossing parameters and end values into work's VertexEdge,
  /// VertexT and VertexEnds, the triangles of slab's blocks into the connectivity. With
  /// several pieces only the vertices the piece's triangles use are kept.
  void Run(const BlockGrid& g, const OuterEnvelope* envelope, const PieceSlab& slab,
    MeshingWork& work, pisurf::PassTimer& lap);

  vtkIdType GetNumberOfVertices() const { return this->Vertices; }

  /// The triangles, facing ∇F, in vtkCellArray's 32-bit storage when the ids fit.
  vtkSmartPointer<vtkCellArray> NewCells() const;

private:
  // Keeps the vertices the triangles use, in order, and renumbers the triangles.
  void KeepUsedVertices(MeshingWork& work);

  vtkIdType Vertices = 0, Triangles = 0;
  bool Narrow = false;
  vtkNew<vtkIdTypeArray> Connectivity;
  vtkNew<vtkTypeInt32Array> Connectivity32;
};
}

#endif
