// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiFlyingEdges
 * @brief triangle mesh of a Pi-surface F = 0 by grid sampling and flying edges
 *
 * vtkPiFlyingEdges samples a vtkPiSurface on a regular grid over the model bounds and
 * extracts F = 0 with vtkFlyingEdges3D (Schroeder, Maynard, Geveci, "Flying edges: a
 * high-performance scalable isocontouring algorithm", LDAV 2015).
 *
 * Sampling pays no virtual call per point per factor: each grid row is a line, every
 * polynomial factor is restricted to it once (an exact univariate polynomial) and
 * evaluated by Horner's rule; rows are distributed over threads with vtkSMPTools. The
 * product is accumulated overflow-safely (see vtkPiSurface). The grid holds
 * sign(F)·ln(1 + |F|): the same signs and zero set as F, but always finite and with
 * finite differences between neighbours, so flying edges' interpolation never collapses
 * a vertex onto a grid point, even for products far beyond the double range.
 *
 * With ProjectVertices (default on) each vertex is then moved to the exact root of F on
 * its grid edge: the edge's samples have opposite signs (the sign of F is exact), so
 * the root is bracketed, and regula falsi (Illinois) on F, or on the overflow-free
 * sign(F)·ln(1 + |F|) where F is beyond 1e200, with bisection as a fallback, finds it to 1e-13 of the model size,
 * even where F spans thousands of orders of magnitude along the edge.
 *
 * Output point data: `Normals` (unit analytic gradient, pointing towards increasing F)
 * and `Factor` (index of the primitive whose zero set is nearest, so each primitive's
 * patch can be coloured). Field data: `PiSurfaceModel`, the model as .pisurf JSON, when
 * every factor is a polynomial.
 *
 * Grid: `Bounds` (all zero = the model's bounds, see vtkPiSurface::GetModelBounds);
 * `Resolution` cells along the longest side (default 128), the other sides get cells
 * of (nearly) the same size; or `SampleDimensions` (points per axis, each >= 2) for
 * exact control. Grids above `MaximumNumberOfSamples` (default 2^28 samples, 2 GiB of
 * doubles) are refused with the memory they would need.
 *
 * @warning Interior sheets (closed shells inside the solid where primitives overlap)
 * are kept: there is no outer-envelope extraction yet.
 *
 * @sa vtkPiSurface vtkFlyingEdges3D vtkSampleFunction
 */
#ifndef vtkPiFlyingEdges_h
#define vtkPiFlyingEdges_h

#include "vtkPiSurfacesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class vtkPiSurface;

class VTKPISURFACESFILTERS_EXPORT vtkPiFlyingEdges : public vtkPolyDataAlgorithm
{
public:
  static vtkPiFlyingEdges* New();
  vtkTypeMacro(vtkPiFlyingEdges, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The Pi-surface to mesh (required).
  void SetPiSurface(vtkPiSurface* surface);
  vtkGetObjectMacro(PiSurface, vtkPiSurface);
  ///@}

  ///@{
  /// Region to sample [x0,x1,y0,y1,z0,z1]; all zero (the default) = the model's bounds.
  vtkSetVector6Macro(Bounds, double);
  vtkGetVector6Macro(Bounds, double);
  ///@}

  ///@{
  /// Cells along the longest side of the bounds (default 128, at least 1).
  vtkSetMacro(Resolution, int);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /// Grid points per axis; all zero (the default) = derived from Resolution.
  vtkSetVector3Macro(SampleDimensions, int);
  vtkGetVector3Macro(SampleDimensions, int);
  ///@}

  ///@{
  /// Largest grid accepted, in samples (default 2^28, i.e. 2 GiB of doubles).
  vtkSetMacro(MaximumNumberOfSamples, vtkIdType);
  vtkGetMacro(MaximumNumberOfSamples, vtkIdType);
  ///@}

  ///@{
  /// Move each vertex to the root of F on its grid edge (default on), to 1e-13 of the
  /// model size; off, vertices are flying edges' linear interpolation of the
  /// compressed samples sign(F)·ln(1 + |F|).
  vtkSetMacro(ProjectVertices, bool);
  vtkGetMacro(ProjectVertices, bool);
  vtkBooleanMacro(ProjectVertices, bool);
  ///@}

  /// The grid the next execution uses: dims and spacing from bounds and settings.
  /// False (with an error) for invalid settings.
  bool ComputeGrid(const double bounds[6], int dims[3], double spacing[3]);

  vtkMTimeType GetMTime() override;

protected:
  vtkPiFlyingEdges();
  ~vtkPiFlyingEdges() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  void ReportReferences(vtkGarbageCollector*) override;

  vtkPiSurface* PiSurface = nullptr;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  int Resolution = 128;
  int SampleDimensions[3] = { 0, 0, 0 };
  vtkIdType MaximumNumberOfSamples = vtkIdType(1) << 28;
  bool ProjectVertices = true;

private:
  vtkPiFlyingEdges(const vtkPiFlyingEdges&) = delete;
  void operator=(const vtkPiFlyingEdges&) = delete;
};

#endif
