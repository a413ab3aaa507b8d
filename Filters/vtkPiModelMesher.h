// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiModelMesher
 * @brief an algorithm whose output is the mesh of a Pi-surface model
 *
 * vtkPiModelMesher is the base of the algorithms that mesh a model: vtkPiSurfaceSource
 * (the model as JSON text), vtkPiSurfaceModelReader (a .pisurf file) and vtkPiProduct
 * (the product of its inputs' models). A subclass says only where the model comes from
 * (LoadModel); this class holds the meshing settings, the vtkPiSurface the model is
 * loaded into (GetPiSurface) and the meshing method that turns it into triangles:
 *
 * - FLYING_EDGES (default): an inner vtkPiFlyingEdges, configured from these settings
 *   at each execution and run for the same piece; see vtkPiFlyingEdges for what each
 *   setting means. Its outputs are shallow-copied to this algorithm's.
 * - RAY_CAST_TRIANGULATION, the paper's image-based way: vtkPiRayCaster casts
 *   Resolution × Resolution rays per axis view over the bounds (the six axis views'
 *   first hits when OuterEnvelope is on, so closed shells inside the solid are not seen;
 *   the three axis directions with all hits when it is off) and vtkPiImageTriangulator
 *   connects the hits on their ray lattice (at its defaults: the diagonals chosen by the
 *   exact normals, one round of edge flips). Its vertices are ray hits, exact without
 *   ProjectVertices; ComputeGradientMagnitude and AutomaticResolution do not apply. The
 *   ray lattice is not split into pieces: piece 0 holds the whole mesh.
 *
 * Output port 0 is the mesh (`Normals`, `Factor`, and the model as the field-data string
 * `PiSurfaceModel`); port 1 with GeneratePrimitives, each primitive meshed alone on the
 * mesh's grid (kept while only the blending changes; with PrimitivesOnDemand computed
 * only when port 1 itself is asked for).
 *
 * OverrideBlending (default off) replaces the model's r by Blending (default 0.25).
 *
 * A consumer that draws the model itself (ParaView's Pi Exact Surface representation)
 * sets MODEL_ONLY() to 1 in its request for port 0. Port 0 then holds the model alone:
 * the field-data string `PiSurfaceModel` (with the meshing box as its bounds), the
 * field-data integer `PiModelOnly` (1) and the box's 8 corners as points, no cells. Any
 * request without the key, or with 0, gets the mesh: data that holds the model alone is
 * computed again for it; a mesh serves a model-only request as it is. (Port 1, when
 * asked for in the same request, needs the mesh's grid: the mesh is computed then.)
 *
 * The model is loaded at each execution, so the time of the vtkPiSurface is not part of
 * this algorithm's: edit the model through the subclass (its text, file or inputs).
 *
 * @sa vtkPiFlyingEdges vtkPiSurfaceSource vtkPiSurfaceModelReader vtkPiProduct
 */
#ifndef vtkPiModelMesher_h
#define vtkPiModelMesher_h

#include "vtkPiSurfacesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr

class vtkInformationIntegerRequestKey;
class vtkPiSurface;

namespace pisurf
{
class LastValidOutput;
}

class VTKPISURFACESFILTERS_EXPORT vtkPiModelMesher : public vtkPolyDataAlgorithm
{
public:
  vtkTypeMacro(vtkPiModelMesher, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The Pi-surface the model is loaded into and meshed (owned; reloaded at each
  /// execution).
  vtkPiSurface* GetPiSurface();

  enum Methods
  {
    FLYING_EDGES = 0,
    RAY_CAST_TRIANGULATION
  };

  ///@{
  /// How the surface is meshed (default FLYING_EDGES).
  vtkSetClampMacro(Method, int, FLYING_EDGES, RAY_CAST_TRIANGULATION);
  vtkGetMacro(Method, int);
  ///@}

  ///@{
  /// Replace the model's blending r by Blending (default off).
  vtkSetMacro(OverrideBlending, bool);
  vtkGetMacro(OverrideBlending, bool);
  vtkBooleanMacro(OverrideBlending, bool);
  ///@}

  ///@{
  /// The r used when OverrideBlending is on (default 0.25).
  vtkSetMacro(Blending, double);
  vtkGetMacro(Blending, double);
  ///@}

  ///@{
  /// Region to mesh [x0,x1,y0,y1,z0,z1]; all zero (the default) = the model's bounds.
  vtkSetVector6Macro(Bounds, double);
  vtkGetVector6Macro(Bounds, double);
  ///@}

  ///@{
  /// Cells along the longest side of the bounds (default 128, at least 1); with
  /// RAY_CAST_TRIANGULATION, rays per axis of each view.
  vtkSetMacro(Resolution, int);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /// Choose the resolution automatically (default off; at most
  /// MaximumAutomaticResolution, default 512); LastResolution tells the choice (see
  /// vtkPiFlyingEdges).
  vtkSetMacro(AutomaticResolution, bool);
  vtkGetMacro(AutomaticResolution, bool);
  vtkBooleanMacro(AutomaticResolution, bool);
  vtkSetClampMacro(MaximumAutomaticResolution, int, 32, 4096);
  vtkGetMacro(MaximumAutomaticResolution, int);
  vtkGetMacro(LastResolution, int);
  ///@}

  ///@{
  /// Grid points per axis; all zero (the default) = derived from Resolution.
  vtkSetVector3Macro(SampleDimensions, int);
  vtkGetVector3Macro(SampleDimensions, int);
  ///@}

  ///@{
  /// Largest grid accepted, in samples (default 2^28).
  vtkSetMacro(MaximumNumberOfSamples, vtkIdType);
  vtkGetMacro(MaximumNumberOfSamples, vtkIdType);
  ///@}

  ///@{
  /// Move each vertex to the root of F on its grid edge (default on).
  vtkSetMacro(ProjectVertices, bool);
  vtkGetMacro(ProjectVertices, bool);
  vtkBooleanMacro(ProjectVertices, bool);
  ///@}

  ///@{
  /// Keep only the outer envelope (default on).
  vtkSetMacro(OuterEnvelope, bool);
  vtkGetMacro(OuterEnvelope, bool);
  vtkBooleanMacro(OuterEnvelope, bool);
  ///@}

  ///@{
  /// Also mesh each primitive on its own into output port 1 (default on; off in
  /// vtkPiProduct, whose inputs show the primitives).
  vtkSetMacro(GeneratePrimitives, bool);
  vtkGetMacro(GeneratePrimitives, bool);
  vtkBooleanMacro(GeneratePrimitives, bool);
  ///@}

  ///@{
  /// With GeneratePrimitives: compute port 1 only when port 1 itself is updated (default
  /// off; on in ParaView's proxies, whose server side, vtkPiSIOnDemandSourceProxy,
  /// updates port 1 only for a visible or filtering consumer).
  vtkSetMacro(PrimitivesOnDemand, bool);
  vtkGetMacro(PrimitivesOnDemand, bool);
  vtkBooleanMacro(PrimitivesOnDemand, bool);
  ///@}

  ///@{
  /// Add the point array `GradientMagnitude` (|∇F|; default off).
  vtkSetMacro(ComputeGradientMagnitude, bool);
  vtkGetMacro(ComputeGradientMagnitude, bool);
  vtkBooleanMacro(ComputeGradientMagnitude, bool);
  ///@}

  ///@{
  /// When an execution fails on a bad setting (an error is reported), keep the outputs
  /// of the last valid execution instead of empty ones (default off; ParaView's proxies
  /// turn it on).
  vtkSetMacro(KeepLastValidOutput, bool);
  vtkGetMacro(KeepLastValidOutput, bool);
  vtkBooleanMacro(KeepLastValidOutput, bool);
  ///@}

  /// The grid the next execution uses: dims and spacing from bounds and settings.
  /// False (with an error) for invalid settings.
  bool ComputeGrid(const double bounds[6], int dims[3], double spacing[3]);
  /// The same for a given resolution.
  bool ComputeGrid(const double bounds[6], int resolution, int dims[3], double spacing[3]);

  /// The request key of a consumer that needs only the model on port 0 (1), not the
  /// mesh (0 or absent); see the class documentation.
  static vtkInformationIntegerRequestKey* MODEL_ONLY();

  /// Whether port 0 of the last execution holds the model without its mesh.
  bool GetLastOutputModelOnly();

  /// Runs REQUEST_DATA through the last-valid-output guard (see KeepLastValidOutput) and
  /// answers REQUEST_DATA_NOT_GENERATED (see PrimitivesOnDemand).
  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs) override;

protected:
  vtkPiModelMesher();
  ~vtkPiModelMesher() override;

  /// Loads the model into `surface`; false (with an error) if there is none or it is
  /// invalid. The only thing a subclass provides.
  virtual bool LoadModel(vtkInformationVector** inputs, vtkPiSurface* surface) = 0;
  /// Whether OverrideBlending applies (true; vtkPiProduct's own r is Blending).
  virtual bool CanOverrideBlending() const { return true; }

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkPiModelMesher(const vtkPiModelMesher&) = delete;
  void operator=(const vtkPiModelMesher&) = delete;

  // Port 0 as the model alone (MODEL_ONLY() asked for); 0 with an error without bounds.
  int OutputModelOnly(vtkPolyData* output);

  // REQUEST_DATA_NOT_GENERATED: which of the two ports this execution leaves as they are.
  void MarkPortsNotGenerated(vtkInformation* request, vtkInformationVector* outputs);

  int Method = FLYING_EDGES;
  bool OverrideBlending = false;
  double Blending = 0.25;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  int Resolution = 128;
  int SampleDimensions[3] = { 0, 0, 0 };
  vtkIdType MaximumNumberOfSamples = vtkIdType(1) << 28;
  bool ProjectVertices = true;
  bool OuterEnvelope = true;
  bool ComputeGradientMagnitude = false;
  bool GeneratePrimitives = true;
  bool PrimitivesOnDemand = false;
  bool AutomaticResolution = false;
  int MaximumAutomaticResolution = 512;
  int LastResolution = 0;
  bool KeepLastValidOutput = false;
  std::unique_ptr<pisurf::LastValidOutput> LastValid;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
