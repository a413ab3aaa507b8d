// SPDX-License-Identifier: BSD-3-Clause
// Assembles the output mesh of vtkPiImageTriangulator from the triangles (keys, by row)
// and the computed points: output ids, hidden components dropped, vertex attributes,
// triangles oriented along the exact gradient and compacted, then the edge flips
// towards the curvature.
#ifndef PiMeshAssembly_h
#define PiMeshAssembly_h

#include "PiTiming.h"
#include "PiTriangulation.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"

#include <memory>
#include <vector>

namespace pisurf
{
namespace triangulator
{

// Reads T.Rows, T.Points and T.C (T.Rows and T.Points are consumed); fills the arrays
// below.
class MeshAssembly
{
public:
  MeshAssembly(Triangulation& t, pisurf::PassTimer& lap);
  void Run(int edgeFlipRounds);

  vtkNew<vtkPoints> Points;
  vtkNew<vtkCellArray> Polys;
  vtkNew<vtkFloatArray> Normals;
  vtkNew<vtkUnsignedCharArray> Singular;
  vtkNew<vtkIntArray> View;
  vtkNew<vtkIntArray> Factor;
  vtkIdType BoundaryEdges = 0;
  vtkIdType UsedHits = 0; // the input hits that are vertices

private:
  void NumberPoints();
  void Vertices();
  void OrientTriangles();
  void Compact(int edgeFlipRounds);

  Triangulation& T;
  pisurf::PassTimer& Lap;
  // Triangle corners of row r start at RowStart[r] (of all rows' corners).
  std::vector<vtkIdType> RowStart;
  std::unique_ptr<vtkIdType[]> HitOut; // the point id of each input hit, or −1
  vtkIdType Triangles = 0, RowCount = 0, Total = 0;
  std::unique_ptr<vtkIdType[]> NewId; // output id of each point id (negative: dropped)
  vtkIdType Count = 0;                // output points
  double* Xyz = nullptr;
  float* NrmOut = nullptr;
  std::unique_ptr<unsigned char[]> Keep; // per triangle: not degenerate
};

} // namespace triangulator
} // namespace pisurf

#endif
