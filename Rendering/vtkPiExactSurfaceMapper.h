// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiExactSurfaceMapper
 * @brief draws a Pi-surface by casting one ray per pixel at every render
 *
 * The exact view: at each render, the mapper casts the rays of the renderer's viewport
 * (its tiled size, the active camera, perspective or parallel) with vtkPiRayCaster in
 * CAMERA mode, first hits only, and draws the hits as one full-viewport quad whose
 * fragment shader writes each hit's colour and its depth (gl_FragDepth: the hit point
 * through the camera's composite projection matrix), so that the surface composites by
 * depth with every other prop of the renderer. Pixels whose ray misses are discarded.
 *
 * The surface is the model of the field data `PiSurfaceModel`, or for a molecule
 * (Molecular Pi Surface in either mode) its `PiMolecule*` arrays, of ModelData when set,
 * else of the mapper's input (a data set, or the first leaf of a composite data set that
 * has the model; the render updates the input's pipeline first unless Static is on). Without a
 * model the mapper draws nothing and, when WarnMissingModel is on, warns once per input.
 *
 * Shading happens on the CPU with the renderer's lights (switched-on lights, taken as
 * directional from their transformed position to their focal point; two-sided):
 * ambient, diffuse and a Blinn-Phong highlight from the actor's property (Ambient,
 * Diffuse, Specular, SpecularPower, SpecularColor, Opacity). The diffuse colour is the
 * property's colour, or, when scalar visibility is on and the selected colour array is
 * `Factor`, the lookup table's colour of the primitive each hit lies on (the table's
 * range is the mapper's ScalarRange unless UseLookupTableScalarRange is on).
 * MarkSingular paints hits the caster classifies singular in red.
 *
 * Opacity below 1 blends the first hits over what the renderer drew before them (with
 * their depth written), in the opaque pass when the actor's ForceOpaque is on, or in a
 * translucent pass without depth peeling or order-independent translucency. Those two
 * need shader code the quad does not carry: a translucent actor then draws nothing,
 * with one warning. (ParaView's representation turns ForceOpaque on.)
 *
 * ReductionFactor r > 1 casts one ray per r × r pixels and fills the blocks.
 * InteractiveReductionFactor (default 2) does the same in interactive renders only: the
 * renders whose window asks for at least one frame a second (GetDesiredUpdateRate() >= 1:
 * VTK's interactor while the mouse moves, ParaView's interactive renders), so that the
 * still render after the interaction casts every pixel again. A viewport whose full cast would
 * exceed the caster's memory cap is cast at the smallest reduction that fits (with one warning).
 * Piece/NumberOfPieces cast only the rows [h·piece/n, h·(piece+1)/n) of the image (vtkPiRayCaster's
 * pieces), for parallel rendering with depth compositing.
 *
 * A model the caster refuses (invalid, not finite) gets the caster's error once and draws
 * nothing; it is not cast again until the model changes.
 *
 * The cast and the images are kept while the camera, the viewport, the model and the
 * settings stay the same; a render then only colours and draws them again.
 *
 * @sa vtkPiRayCaster
 */
#ifndef vtkPiExactSurfaceMapper_h
#define vtkPiExactSurfaceMapper_h

#include "vtkMapper.h"
#include "vtkPiSurfacesRenderingModule.h" // for export macro

#include <memory> // for std::unique_ptr

class vtkFieldData;
class vtkPiRayCaster;

class VTKPISURFACESRENDERING_EXPORT vtkPiExactSurfaceMapper : public vtkMapper
{
public:
  static vtkPiExactSurfaceMapper* New();
  vtkTypeMacro(vtkPiExactSurfaceMapper, vtkMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(vtkRenderer* ren, vtkActor* actor) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  using vtkMapper::GetBounds;
  double* GetBounds() VTK_SIZEHINT(6) override;

  ///@{
  /// The data object whose field data holds the model; null (default) = the input.
  void SetModelData(vtkDataObject* data);
  vtkGetObjectMacro(ModelData, vtkDataObject);
  ///@}

  ///@{
  /// One ray per ReductionFactor × ReductionFactor pixels (1 to 16, default 1).
  vtkSetClampMacro(ReductionFactor, int, 1, 16);
  vtkGetMacro(ReductionFactor, int);
  ///@}

  ///@{
  /// One ray per n × n pixels in interactive renders (1 to 16, default 2; see above).
  vtkSetClampMacro(InteractiveReductionFactor, int, 1, 16);
  vtkGetMacro(InteractiveReductionFactor, int);
  ///@}

  ///@{
  /// Paint singular hits red (default off).
  vtkSetMacro(MarkSingular, bool);
  vtkGetMacro(MarkSingular, bool);
  vtkBooleanMacro(MarkSingular, bool);
  ///@}

  ///@{
  /// Warn once per input that has no model (default on).
  vtkSetMacro(WarnMissingModel, bool);
  vtkGetMacro(WarnMissingModel, bool);
  ///@}

  ///@{
  /// This process casts the rows of piece Piece of NumberOfPieces (default 0 of 1).
  vtkSetClampMacro(Piece, int, 0, VTK_INT_MAX);
  vtkGetMacro(Piece, int);
  vtkSetClampMacro(NumberOfPieces, int, 1, VTK_INT_MAX);
  vtkGetMacro(NumberOfPieces, int);
  ///@}

  /// The field data of `data`, or of the first leaf of a composite `data`, that holds
  /// the field-data string `PiSurfaceModel` or a molecule's `PiMoleculeSettings`; null if
  /// none does.
  static vtkFieldData* FindModelFieldData(vtkDataObject* data);

  /// The ray caster the mapper runs (its settings other than the camera, the
  /// resolution, the view mode and AllHits may be changed, e.g. SingularTolerance).
  vtkPiRayCaster* GetRayCaster();

  /// How many casts the mapper has run, and the wall-clock seconds of the last one.
  vtkGetMacro(CastCount, int);
  vtkGetMacro(LastCastSeconds, double);
  /// The resolution of the last cast (w, h rays).
  vtkGetVector2Macro(CastResolution, int);
  /// The lowest and highest row (of the cast image) holding a hit of this process's last
  /// cast; -1, -1 without hits. With pieces, the rows lie in this process's piece.
  vtkGetVector2Macro(HitRows, int);
  /// Whether the last render found a model and drew it.
  vtkGetMacro(Drawn, bool);

  vtkMTimeType GetMTime() override;

protected:
  vtkPiExactSurfaceMapper();
  ~vtkPiExactSurfaceMapper() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  void ReportReferences(vtkGarbageCollector* collector) override;
  // Updates the input's pipeline (when connected and not Static).
  void UpdateInput();

  vtkDataObject* ModelData = nullptr;
  int ReductionFactor = 1;
  int InteractiveReductionFactor = 2;
  bool MarkSingular = false;
  bool WarnMissingModel = true;
  int Piece = 0;
  int NumberOfPieces = 1;
  int CastCount = 0;
  double LastCastSeconds = 0.0;
  int CastResolution[2] = { 0, 0 };
  int HitRows[2] = { -1, -1 };
  bool Drawn = false;

private:
  struct Internals;
  std::unique_ptr<Internals> Internal;

  vtkPiExactSurfaceMapper(const vtkPiExactSurfaceMapper&) = delete;
  void operator=(const vtkPiExactSurfaceMapper&) = delete;
};

#endif
