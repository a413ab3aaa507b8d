// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiSurfaceSource
 * @brief meshes the Pi-surface of a .pisurf model given as JSON text
 *
 * A vtkPiModelMesher whose model is `Model`, the JSON text of a .pisurf model
 * (ParaView's "Pi Surface" source). The meshing settings (Method, Bounds, Resolution,
 * OuterEnvelope, ProjectVertices, the primitives on port 1, on by default here,
 * OverrideBlending and Blending) are vtkPiModelMesher's. An invalid model is an error
 * that names the key or the position; the output is then empty.
 *
 * The default Model is the paper's Figure 1(b): two unit spheres at x = ±0.9, r = 0.25.
 *
 * @sa vtkPiModelMesher vtkPiFlyingEdges vtkPiSurfaceModelReader vtkPiSurface
 */
#ifndef vtkPiSurfaceSource_h
#define vtkPiSurfaceSource_h

#include "vtkPiModelMesher.h"
#include "vtkPiSurfacesFiltersModule.h" // for export macro

#include <string> // for std::string

class VTKPISURFACESFILTERS_EXPORT vtkPiSurfaceSource : public vtkPiModelMesher
{
public:
  static vtkPiSurfaceSource* New();
  vtkTypeMacro(vtkPiSurfaceSource, vtkPiModelMesher);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The model as .pisurf JSON text (default: the paper's two spheres, d = 0.9).
  void SetModel(const char* json);
  const char* GetModel() { return this->ModelText.c_str(); }
  ///@}

protected:
  vtkPiSurfaceSource();
  ~vtkPiSurfaceSource() override;

  /// Parses Model into `surface`; false (with an error) if invalid.
  bool LoadModel(vtkInformationVector** inputs, vtkPiSurface* surface) override;

private:
  vtkPiSurfaceSource(const vtkPiSurfaceSource&) = delete;
  void operator=(const vtkPiSurfaceSource&) = delete;

  std::string ModelText;
};

#endif
