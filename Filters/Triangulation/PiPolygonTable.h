// SPDX-License-Identifier: BSD-3-Clause
// The marching-cubes polygons of each of the 256 cases, from which the lattice cells
// pass triangulates along the diagonals the surface bends least along.
#ifndef PiPolygonTable_h
#define PiPolygonTable_h

#include <array>
#include <vector>

namespace pisurf
{
namespace triangulator
{
// The marching-cubes polygons of each case: the triangles of vtkMarchingCubesTriangleCases
// grouped by shared diagonals, each group's outline as a cycle of cell edges. A case's
// triangles that do not form a disk stay triangles.
const std::array<std::vector<std::vector<int>>, 256>& PolygonTable();

} // namespace triangulator
} // namespace pisurf

#endif
