// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiMeshingMethod.h
 * @brief how a vtkPiModelMesher turns its Pi-surface into triangles
 *
 * A meshing method reads the mesher's settings (Bounds, Resolution, OuterEnvelope, ...)
 * and says what they mean for it: FlyingEdges hands them to an inner vtkPiFlyingEdges,
 * RayCastTriangulation turns them into a ray lattice for vtkPiRayCaster and
 * vtkPiImageTriangulator. Both serve the Primitives port with vtkPiFlyingEdges. Their
 * inner algorithms report progress and check cancel as the mesher's (pisurf::WorkFor).
 */
#ifndef PiMeshingMethod_h
#define PiMeshingMethod_h

#ifndef __VTK_WRAP__

#include "PiPieces.h"

#include <memory>

class vtkPiModelMesher;
class vtkPiSurface;
class vtkPolyData;

namespace pisurf
{

/// One execution of a method: which surface, which piece, which ports.
struct MeshingRequest
{
  vtkPiSurface* Surface = nullptr;
  Piece Asked;
  bool Mesh = true;       // port 0 wanted
  bool Primitives = true; // port 1 wanted (with GeneratePrimitives)
};

class MeshingMethod
{
public:
  virtual ~MeshingMethod() = default;
  /// Meshes into `mesh` (port 0) and `primitives` (port 1, may be null) for the
  /// settings of the mesher the method was made for. 0 (an error reported) on failure.
  virtual int Execute(
    const MeshingRequest& request, vtkPolyData* mesh, vtkPolyData* primitives) = 0;
  /// The resolution of the last execution (AutomaticResolution's choice); 0 if none.
  virtual int GetLastResolution() const { return 0; }
  /// Whether port 1 alone can be served from the grid of the last mesh (false: an
  /// execution always meshes port 0 too).
  virtual bool ServesPrimitivesAlone() const { return false; }
};

/// Flying edges (vtkPiFlyingEdges) for `mesher`.
std::unique_ptr<MeshingMethod> NewFlyingEdgesMethod(vtkPiModelMesher* mesher);
/// Ray-cast triangulation (vtkPiRayCaster, vtkPiImageTriangulator) for `mesher`.
std::unique_ptr<MeshingMethod> NewRayCastTriangulationMethod(vtkPiModelMesher* mesher);

}

#endif
#endif
