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

#include "PiPieces.h"

class vtkAlgorithm;
class vtkInformation;
class vtkInformationVector;
class vtkPiSurface;
class vtkPolyData;

namespace pisurf
{

/// The primitives of `surface` on the grid (`bounds`, `dims`) for piece `piece` of
/// `pieces`, into `out`; stops between primitives when `owner` is cancelled.
void MeshPrimitives(vtkPiSurface* surface, const double bounds[6], const int dims[3], int piece,
  int pieces, bool projectVertices, vtkAlgorithm* owner, vtkPolyData* out);

/// The ports (0 the mesh, 1 the primitives) a REQUEST_DATA leaves as they are.
struct PortsNotGenerated
{
  bool Mesh = false, Primitives = false;
};

/// Answers REQUEST_DATA_NOT_GENERATED for `algorithm`'s two ports and returns the marks:
/// asked from port 0 with `primitivesOnDemand`, port 1 keeps its data; asked from port 1,
/// the mesh is kept when `haveMesh` (port 0 holds a mesh whose grid the primitives can
/// take, for `meshPiece`), it is up to date and of the piece asked for.
PortsNotGenerated MarkPortsNotGenerated(vtkAlgorithm* algorithm, vtkInformation* request,
  vtkInformationVector* outputs, bool primitivesOnDemand, bool haveMesh, const Piece& meshPiece);

}

#endif
