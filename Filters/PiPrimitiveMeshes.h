// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiPrimitiveMeshes.h
 * @brief each primitive of a Pi-surface meshed alone: the Primitives port (port 1)
 *
 * Each factor alone (r = 0, no outer envelope) is meshed by a vtkPiFlyingEdges on the
 * given grid and piece, its `Factor` array set to its index, and the meshes appended.
 */
#ifndef PiPrimitiveMeshes_h
#define PiPrimitiveMeshes_h

class vtkAlgorithm;
class vtkPiSurface;
class vtkPolyData;

namespace pisurf
{

/// The primitives of `surface` on the grid (`bounds`, `dims`) for piece `piece` of
/// `pieces`, into `out`; stops between primitives when `owner` is cancelled.
void MeshPrimitives(vtkPiSurface* surface, const double bounds[6], const int dims[3], int piece,
  int pieces, bool projectVertices, vtkAlgorithm* owner, vtkPolyData* out);

}

#endif
