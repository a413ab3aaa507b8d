// SPDX-License-Identifier: BSD-3-Clause
// Marching-cubes corner offsets and edges (corner pairs) in VTK's hexahedron order, as
// vtkMarchingCubesTriangleCases numbers them; shared by vtkPiFlyingEdges and
// vtkPiImageTriangulator. Private to the Filters module.
#ifndef PiMarchingCubes_h
#define PiMarchingCubes_h

namespace pisurf
{
namespace mc
{
constexpr int Corner[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 },
  { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
constexpr int Edge[12][2] = { { 0, 1 }, { 1, 2 }, { 3, 2 }, { 0, 3 }, { 4, 5 }, { 5, 6 }, { 7, 6 },
  { 4, 7 }, { 0, 4 }, { 1, 5 }, { 3, 7 }, { 2, 6 } };

/// An edge as the cell offset of its lower corner and its axis.
struct EdgeStart
{
  int Lo[3];
  int Axis;
};
struct EdgeStartTable
{
  EdgeStart Of[12];
};
constexpr EdgeStartTable MakeEdgeStarts()
{
  EdgeStartTable t{};
  for (int e = 0; e < 12; ++e)
  {
    for (int a = 0; a < 3; ++a)
    {
      const int c0 = Corner[Edge[e][0]][a], c1 = Corner[Edge[e][1]][a];
      t.Of[e].Lo[a] = c0 < c1 ? c0 : c1;
      if (c0 != c1)
      {
        t.Of[e].Axis = a;
      }
    }
  }
  return t;
}
constexpr EdgeStartTable EdgeStarts = MakeEdgeStarts();
}
}

#endif
