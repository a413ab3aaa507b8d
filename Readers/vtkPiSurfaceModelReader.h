// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiSurfaceModelReader
 * @brief reads a .pisurf model and meshes its Pi-surface
 *
 * Reads a .pisurf model file (JSON, version 1: Documentation/pisurf-format.md) into a
 * vtkPiSurface and meshes F = 0: a vtkPiModelMesher whose model comes from FileName,
 * with its settings (Method, Bounds, Resolution, OuterEnvelope, ProjectVertices,
 * OverrideBlending/Blending, primitives on port 1). The output carries `Normals`,
 * `Factor` and the model JSON as the field-data string `PiSurfaceModel`, so downstream
 * filters can rebuild the exact function.
 *
 * A missing file, invalid JSON or an invalid model is an error that names the file and
 * the key or position; the output is then empty.
 *
 * @sa vtkPiModelMesher vtkPiSurfaceSource vtkPiFlyingEdges vtkPiSurface
 */
#ifndef vtkPiSurfaceModelReader_h
#define vtkPiSurfaceModelReader_h

#include "vtkPiModelMesher.h"
#include "vtkPiSurfacesReadersModule.h" // for export macro

class VTKPISURFACESREADERS_EXPORT vtkPiSurfaceModelReader : public vtkPiModelMesher
{
public:
  static vtkPiSurfaceModelReader* New();
  vtkTypeMacro(vtkPiSurfaceModelReader, vtkPiModelMesher);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .pisurf file to read (default none).
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  /// True if the file looks like a .pisurf model (a JSON object with a "pisurf" key).
  static int CanReadFile(const char* fileName);

protected:
  vtkPiSurfaceModelReader();
  ~vtkPiSurfaceModelReader() override;

  /// Loads FileName into `surface`; false (with an error naming the file) if it cannot.
  bool LoadModel(vtkInformationVector** inputs, vtkPiSurface* surface) override;

  char* FileName = nullptr;

private:
  vtkPiSurfaceModelReader(const vtkPiSurfaceModelReader&) = delete;
  void operator=(const vtkPiSurfaceModelReader&) = delete;
};

#endif
