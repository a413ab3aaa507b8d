// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiSurfaceModelReader
 * @brief reads a .pisurf model and meshes its Pi-surface
 *
 * Reads a .pisurf model file (JSON, version 1: see the README) into a vtkPiSurface and
 * meshes F = 0: it is a vtkPiFlyingEdges whose surface comes from the file, so it has
 * the mesher's Bounds, Resolution and SampleDimensions. The output carries `Normals`, `Factor` and the
 * model JSON as the field-data string `PiSurfaceModel`, so downstream filters can
 * rebuild the exact function.
 *
 * OverrideBlending (default off) replaces the file's r with Blending (default 0.25),
 * for the paper's inflate/shrink experiments. Bounds (all zero = the model's) and
 * Resolution (default 128) are passed to the mesher.
 *
 * A missing file, invalid JSON or an invalid model is an error that names the file and
 * the key or position; the output is then empty.
 *
 * @sa vtkPiSurface vtkPiFlyingEdges
 */
#ifndef vtkPiSurfaceModelReader_h
#define vtkPiSurfaceModelReader_h

#include "vtkPiSurfacesReadersModule.h" // for export macro
#include "vtkPiFlyingEdges.h"

class VTKPISURFACESREADERS_EXPORT vtkPiSurfaceModelReader : public vtkPiFlyingEdges
{
public:
  static vtkPiSurfaceModelReader* New();
  vtkTypeMacro(vtkPiSurfaceModelReader, vtkPiFlyingEdges);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .pisurf file to read (default none).
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
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

  /// The reader's model changes only when the file or the settings do.
  vtkMTimeType GetMTime() override;

  /// True if the file looks like a .pisurf model (a JSON object with a "pisurf" key).
  static int CanReadFile(const char* fileName);

protected:
  vtkPiSurfaceModelReader();
  ~vtkPiSurfaceModelReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  bool OverrideBlending = false;
  double Blending = 0.25;

private:
  vtkPiSurfaceModelReader(const vtkPiSurfaceModelReader&) = delete;
  void operator=(const vtkPiSurfaceModelReader&) = delete;
};

#endif
