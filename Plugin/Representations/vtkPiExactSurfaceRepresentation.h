// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiExactSurfaceRepresentation
 * @brief ParaView's "Pi Exact Surface" representation: the surface ray-cast per pixel
 *
 * A vtkGeometryRepresentationWithFaces (the Surface representation's class) whose mapper and LOD
 * mapper are vtkPiExactSurfaceMapper: everything else (colouring, the property, delivery, bounds,
 * LOD decisions) is the Surface representation's. The mappers cast the model of the input's field
 * data `PiSurfaceModel` (a copy of the input's field data taken at each update), so an edit of the
 * model re-casts without a mesh ever being drawn. Both mappers cast one ray per
 * InteractiveReduction × InteractiveReduction pixels in the view's interactive renders (the
 * camera moving, a widget dragging: vtkPVRenderView asks the window for 5 frames a second),
 * whether or not the view uses LOD, and every pixel in still renders.
 *
 * Its update asks the producer for the model alone (vtkPiModelMesher::MODEL_ONLY() set
 * to 1 in its request), so Pi Surface, the model reader and Pi Product compute no mesh
 * for it. The key is set back to 0 when the view renders (its updates done) and when the
 * representation is hidden, so that another consumer of the same output that updates
 * later (a Surface display, a filter) gets the mesh.
 *
 * Its actor is ForceOpaque (ParaView's depth peeling would need shader code the mapper's quad
 * does not have); a translucent one is moved last among the renderer's props at each render,
 * so that its first hits blend over every opaque object behind them.
 *
 * An input without a model is reported once (a warning naming the input's producer)
 * and draws nothing. In parallel, rank p of n casts the rows [h·p/n, h·(p+1)/n) of the
 * view and ParaView's depth compositing assembles the image.
 */
#ifndef vtkPiExactSurfaceRepresentation_h
#define vtkPiExactSurfaceRepresentation_h

#include "vtkGeometryRepresentationWithFaces.h"
#include "vtkPiSurfacesRepresentationsModule.h" // for export macro

#include "vtkNew.h" // for vtkNew

class vtkPiExactSurfaceMapper;
class vtkPolyData;

class VTKPISURFACESREPRESENTATIONS_EXPORT vtkPiExactSurfaceRepresentation
  : public vtkGeometryRepresentationWithFaces
{
public:
  static vtkPiExactSurfaceRepresentation* New();
  vtkTypeMacro(vtkPiExactSurfaceRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Paint the pixels whose hit is singular red (default off).
  void SetMarkSingular(bool mark);
  bool GetMarkSingular();

  /// One ray per n × n pixels in interactive renders (1 to 16, default 2).
  void SetInteractiveReduction(int n);
  int GetInteractiveReduction();

  /// The mapper of still renders (for tests: its cast count and timing).
  vtkPiExactSurfaceMapper* GetExactMapper();

  /// The lowest and highest image row of this process's hits in the last still render
  /// (-1, -1 without hits): in parallel, the rows of this rank's piece that hit.
  int* GetHitRows() VTK_SIZEHINT(2);

  int ProcessViewRequest(vtkInformationRequestKey* request_type, vtkInformation* inInfo,
    vtkInformation* outInfo) override;

  /// Hidden, the representation asks its producer for the mesh again.
  void SetVisibility(bool visible) override;

protected:
  vtkPiExactSurfaceRepresentation();
  ~vtkPiExactSurfaceRepresentation() override;

  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // Sets MODEL_ONLY() in the producer's output information: 1 (the model alone) for this
  // representation's update, 0 (the mesh) for whoever updates next.
  void SetModelOnlyRequest(int modelOnly);

  vtkNew<vtkPolyData> ModelCarrier; // the input's field data
  void* WarnedProducer = nullptr;   // the producer last warned about

private:
  vtkPiExactSurfaceRepresentation(const vtkPiExactSurfaceRepresentation&) = delete;
  void operator=(const vtkPiExactSurfaceRepresentation&) = delete;
};

#endif
