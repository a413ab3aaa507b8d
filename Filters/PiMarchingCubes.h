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
constexpr int Edge[12][2] = { { 0, 1 }, { 1, 2 }, { 3, 2 }, { 0, 3 }, { 4, 5 }, { 5, 6 },
  { 7, 6 }, { 4, 7 }, { 0, 4 }, { 1, 5 }, { 3, 7 }, { 2, 6 } };
}
}

#endif
