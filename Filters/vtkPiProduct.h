// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiProduct
 * @brief the Pi-surface of the product of its inputs' models: F = Π f_i − r
 *
 * vtkPiProduct (ParaView's "Pi Product") takes any number of inputs, each a dataset
 * whose field data carries `PiSurfaceModel` (vtkPiPrimitiveSource, vtkPiSurfaceSource,
 * the model reader, another vtkPiProduct, vtkPiMoleculeSurface in Global mode),
 * multiplies all their primitives with one blending r (Blending; the inputs' own r are
 * not used) and meshes F = 0 with vtkPiModelMesher's settings (Resolution, Bounds,
 * OuterEnvelope, ProjectVertices, Method, ...; OverrideBlending has no effect: Blending
 * is the product's r). The output carries the combined model
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
 * @sa vtkPiModelMesher vtkPiPrimitiveSource vtkPiSurfaceSource vtkPiSurface
 */
#ifndef vtkPiProduct_h
#define vtkPiProduct_h

#include "vtkPiModelMesher.h"
#include "vtkPiSurfacesFiltersModule.h" // for export macro

#include <string> // for std::string

class VTKPISURFACESFILTERS_EXPORT vtkPiProduct : public vtkPiModelMesher
{
public:
  static vtkPiProduct* New();
  vtkTypeMacro(vtkPiProduct, vtkPiModelMesher);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The model of the last execution, the product (JSON; empty before the first).
  /// SetModel is not used: the model is the product of the inputs.
  const char* GetModel() { return this->ProductModel.c_str(); }
  void SetModel(const char*) {}
  ///@}

protected:
  vtkPiProduct();
  ~vtkPiProduct() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// Multiplies the inputs' models with Blending as r into `surface`; false (with an
  /// error) for no input, an input without a valid model, or a non-finite Blending.
  bool LoadModel(vtkInformationVector** inputs, vtkPiSurface* surface) override;
  bool CanOverrideBlending() const override { return false; }

private:
  vtkPiProduct(const vtkPiProduct&) = delete;
  void operator=(const vtkPiProduct&) = delete;

  std::string ProductModel;
};

#endif
