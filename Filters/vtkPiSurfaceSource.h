// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiSurfaceSource
 * @brief meshes the Pi-surface of a .pisurf model given as JSON text
 *
 * A vtkPiFlyingEdges whose vtkPiSurface comes from `Model`, the JSON text of a .pisurf
 * model (ParaView's "Pi Surface" source). OverrideBlending (default off) replaces the
 * model's r by Blending (default 0.25), for the paper's inflate/shrink experiments.
 * Everything else (Bounds, Resolution, OuterEnvelope, ProjectVertices, the primitives
 * on port 1, which are on by default here) is the mesher's. An invalid model is an error that names
 * the key or the position; the output is then empty.
 *
 * Method chooses how F = 0 becomes triangles: FLYING_EDGES (default, vtkPiFlyingEdges
 * with all its settings) or RAY_CAST_TRIANGULATION, the paper's image-based way:
 * vtkPiRayCaster casts Resolution × Resolution rays per axis view over the bounds (the
 * six axis views' first hits when OuterEnvelope is on, so closed shells inside the
 * solid are not seen; the three axis directions with all hits when it is off) and
 * vtkPiImageTriangulator connects the hits on their ray lattice (at its defaults: the
 * diagonals chosen by the exact normals, one round of edge flips). Its vertices are ray
 * hits, exact without ProjectVertices; ComputeGradientMagnitude does not apply.
 *
 * The default Model is the paper's Figure 1(b): two unit spheres at x = ±0.9, r = 0.25.
 *
 * @sa vtkPiFlyingEdges vtkPiSurfaceModelReader vtkPiSurface
 */
#ifndef vtkPiSurfaceSource_h
#define vtkPiSurfaceSource_h

#include "vtkPiFlyingEdges.h"
#include "vtkPiSurfacesFiltersModule.h" // for export macro

#include <string> // for std::string

class VTKPISURFACESFILTERS_EXPORT vtkPiSurfaceSource : public vtkPiFlyingEdges
{
public:
  static vtkPiSurfaceSource* New();
  vtkTypeMacro(vtkPiSurfaceSource, vtkPiFlyingEdges);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The model as .pisurf JSON text (default: the paper's two spheres, d = 0.9).
  void SetModel(const char* json);
  const char* GetModel() { return this->ModelText.c_str(); }
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

  /// The model changes only when the settings do (RequestData rewrites the surface).
  vtkMTimeType GetMTime() override;

protected:
  vtkPiSurfaceSource();
  ~vtkPiSurfaceSource() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// Loads the model into this->PiSurface; false (with an error) if invalid.
  virtual bool ReadModel();
  // RAY_CAST_TRIANGULATION: ray cast, triangulate, and the primitives on port 1.
  int RayCastTriangulation(vtkInformationVector* outputVector);

  bool OverrideBlending = false;
  double Blending = 0.25;
  int Method = FLYING_EDGES;
  std::string ModelText;

private:
  vtkPiSurfaceSource(const vtkPiSurfaceSource&) = delete;
  void operator=(const vtkPiSurfaceSource&) = delete;
};

#endif
