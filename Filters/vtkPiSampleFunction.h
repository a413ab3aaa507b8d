// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiSampleFunction
 * @brief F of a Pi-surface on a regular grid, a row at a time
 *
 * What vtkSampleFunction does for any implicit function, without its virtual call per
 * point (and, over a composition of VTK functions, per factor): each factor is
 * restricted once to each grid row (an exact univariate polynomial) and evaluated
 * along it by Horner's rule, rows threaded with vtkSMPTools. The output is a
 * vtkImageData whose point scalars `F` (double) are F = Π f_i − r; where |F| exceeds
 * the double range it is ±VTK_DOUBLE_MAX with the exact sign (the product itself never
 * overflows, see vtkPiSurface). Contour it at 0 with vtkFlyingEdges3D, or volume-render
 * it.
 *
 * The Pi-surface comes from the input's `PiSurfaceModel` field data (the output of Pi
 * Surface, the model reader, Pi Product, Pi Primitive) when an input is connected,
 * otherwise from SetPiSurface. A molecule (the output of vtkPiMoleculeSurface: field
 * data `PiMoleculeCenters`, `PiMoleculeRadii`, `PiMoleculeSettings`) is sampled from
 * its own field instead, in either mode and at any size (pisurf::MoleculeField, point
 * by point from the atoms near each point: the mesher's values on the mesher's grid).
 * `SampleDimensions` (default 64³, at least 2 per axis) points span `ModelBounds` (all
 * 0, the default: the model's own bounds, or the molecule's mesh bounds, as the mesher
 * takes them). Grids above `MaximumNumberOfSamples` (2^28, 2 GiB of doubles) are
 * refused with the memory they would need.
 *
 * Pieces: the output produces any sub-extent (ParaView's MPI mode splits the grid),
 * each row of it evaluated exactly as in the whole grid. Progress and abort are
 * honoured between rows.
 *
 * @sa vtkPiSurface vtkPiFlyingEdges vtkSampleFunction
 */
#ifndef vtkPiSampleFunction_h
#define vtkPiSampleFunction_h

#include "vtkImageAlgorithm.h"
#include "vtkPiSurfacesFiltersModule.h" // for export macro

class vtkPiSurface;

class VTKPISURFACESFILTERS_EXPORT vtkPiSampleFunction : public vtkImageAlgorithm
{
public:
  static vtkPiSampleFunction* New();
  vtkTypeMacro(vtkPiSampleFunction, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The Pi-surface sampled when no input is connected.
  virtual void SetPiSurface(vtkPiSurface*);
  vtkGetObjectMacro(PiSurface, vtkPiSurface);
  ///@}

  ///@{
  /// Grid points per axis (default 64 64 64; at least 2 each).
  vtkSetVector3Macro(SampleDimensions, int);
  vtkGetVector3Macro(SampleDimensions, int);
  ///@}

  ///@{
  /// The box sampled (xmin, xmax, ymin, ymax, zmin, zmax); all 0 (default): the model's.
  vtkSetVector6Macro(ModelBounds, double);
  vtkGetVector6Macro(ModelBounds, double);
  ///@}

  ///@{
  /// The largest grid accepted, in points (default 2^28).
  vtkSetMacro(MaximumNumberOfSamples, vtkIdType);
  vtkGetMacro(MaximumNumberOfSamples, vtkIdType);
  ///@}

  vtkMTimeType GetMTime() override;

protected:
  vtkPiSampleFunction();
  ~vtkPiSampleFunction() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  void ReportReferences(vtkGarbageCollector*) override;

  vtkPiSurface* PiSurface = nullptr;
  int SampleDimensions[3] = { 64, 64, 64 };
  double ModelBounds[6] = { 0, 0, 0, 0, 0, 0 };
  vtkIdType MaximumNumberOfSamples = vtkIdType(1) << 28;

private:
  vtkPiSampleFunction(const vtkPiSampleFunction&) = delete;
  void operator=(const vtkPiSampleFunction&) = delete;
};

#endif
