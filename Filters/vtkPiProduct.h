// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiProduct
 * @brief the Pi-surface of the product of its inputs' models: F = Π f_i − r
 *
 * vtkPiProduct (ParaView's "Pi Product") takes any number of inputs, each a dataset
 * whose field data carries `PiSurfaceModel` (vtkPiPrimitiveSource, vtkPiSurfaceSource,
 * the model reader, another vtkPiProduct, vtkPiMoleculeSurface in Global mode),
 * multiplies all their primitives with one blending r (Blending; the inputs' own r are
 * not used) and meshes F = 0 like vtkPiSurfaceSource (Resolution, Bounds,
 * OuterEnvelope, ProjectVertices, Method, ...). The output carries the combined model
 * as `PiSurfaceModel`, so vtkPiRayCaster and further products work downstream.
 *
 * Combining models (pisurf::MultiplyModels): primitives in input order; parameters
 * merged, a name two inputs give different values renamed in the later input's
 * expressions (a -> a_2); bounds the union of the bounds of the inputs with an
 * unbounded primitive, none (automatic, growing with r) if every primitive is bounded.
 * Bounds, when set, replaces them and is written into the output's model.
 *
 * Errors (vtkErrorMacro; an empty output, or the last valid one with
 * KeepLastValidOutput): no input, an input without `PiSurfaceModel` (or with an invalid
 * one), a non-finite Blending.
 *
 * GeneratePrimitives is off by default here: the inputs already show the primitives.
 *
 * @sa vtkPiPrimitiveSource vtkPiSurfaceSource vtkPiSurface
 */
#ifndef vtkPiProduct_h
#define vtkPiProduct_h

#include "vtkPiSurfaceSource.h"
#include "vtkPiSurfacesFiltersModule.h" // for export macro

class VTKPISURFACESFILTERS_EXPORT vtkPiProduct : public vtkPiSurfaceSource
{
public:
  static vtkPiProduct* New();
  vtkTypeMacro(vtkPiProduct, vtkPiSurfaceSource);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // Blending (default 0.25) is the product's r; OverrideBlending has no effect here.
  // GetModel() returns the last product's model (JSON), SetModel is not used.

protected:
  vtkPiProduct();
  ~vtkPiProduct() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkPiProduct(const vtkPiProduct&) = delete;
  void operator=(const vtkPiProduct&) = delete;
};

#endif
