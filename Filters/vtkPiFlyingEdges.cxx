// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiFlyingEdges.h"

#include "PiModel.h"
#include "PiProduct.h"
#include "vtkPiSurface.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkFloatArray.h"
#include "vtkGarbageCollector.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"

#include <atomic>
#include <cmath>

vtkStandardNewMacro(vtkPiFlyingEdges);
vtkCxxSetObjectMacro(vtkPiFlyingEdges, PiSurface, vtkPiSurface);

vtkPiFlyingEdges::vtkPiFlyingEdges()
{
  this->SetNumberOfInputPorts(0);
}

vtkPiFlyingEdges::~vtkPiFlyingEdges()
{
  this->SetPiSurface(nullptr);
}

vtkMTimeType vtkPiFlyingEdges::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->PiSurface)
  {
    t = std::max(t, this->PiSurface->GetMTime());
  }
  return t;
}

void vtkPiFlyingEdges::ReportReferences(vtkGarbageCollector* collector)
{
  this->Superclass::ReportReferences(collector);
  vtkGarbageCollectorReport(collector, this->PiSurface, "PiSurface");
}

namespace
{
// Samples F on the grid, one row (fixed j, k) per work item.
struct SampleRows
{
  const pisurf::ProductKernel* Kernel;
  const int* Dims;
  const double* Origin;
  const double* Spacing;
  double* Values;
  vtkPiFlyingEdges* Algorithm;
  std::atomic<bool>* Abort;

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const bool single = vtkSMPTools::GetSingleThread();
    const double step[3] = { this->Spacing[0], 0.0, 0.0 };
    for (vtkIdType row = begin; row < end; ++row)
    {
      if (single && (row - begin) % 64 == 0 && this->Algorithm->CheckAbort())
      {
        *this->Abort = true;
      }
      if (*this->Abort)
      {
        return;
      }
      const vtkIdType j = row % this->Dims[1], k = row / this->Dims[1];
      const double o[3] = { this->Origin[0], this->Origin[1] + j * this->Spacing[1],
        this->Origin[2] + k * this->Spacing[2] };
      this->Kernel->EvaluateLine(o, step, this->Dims[0], this->Values + row * this->Dims[0]);
    }
  }
};

// Exact normals and the nearest factor at each vertex.
struct VertexAttributes
{
  const pisurf::ProductKernel* Kernel;
  vtkPoints* Points;
  vtkFloatArray* Normals;
  vtkIntArray* Factor;

  void operator()(vtkIdType begin, vtkIdType end)
  {
    double p[3], g[3];
    for (vtkIdType i = begin; i < end; ++i)
    {
      this->Points->GetPoint(i, p);
      this->Kernel->EvaluateWithGradient(p, g);
      const double n = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      float nf[3] = { 0.f, 0.f, 0.f };
      if (n > 0 && std::isfinite(n))
      {
        nf[0] = static_cast<float>(g[0] / n);
        nf[1] = static_cast<float>(g[1] / n);
        nf[2] = static_cast<float>(g[2] / n);
      }
      this->Normals->SetTypedTuple(i, nf);
      this->Factor->SetValue(i, this->Kernel->NearestFactor(p));
    }
  }
};
}

bool vtkPiFlyingEdges::ComputeGrid(const double b[6], int dims[3], double spacing[3])
{
  const double side[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
  const int* sd = this->SampleDimensions;
  if (sd[0] != 0 || sd[1] != 0 || sd[2] != 0)
  {
    if (sd[0] < 2 || sd[1] < 2 || sd[2] < 2)
    {
      vtkErrorMacro(<< "SampleDimensions must be at least 2 points per axis (got " << sd[0]
                    << ", " << sd[1] << ", " << sd[2] << "); set all to 0 to use Resolution");
      return false;
    }
    std::copy(sd, sd + 3, dims);
  }
  else
  {
    if (this->Resolution < 1)
    {
      vtkErrorMacro(<< "Resolution must be at least 1 (got " << this->Resolution << ")");
      return false;
    }
    const double h = std::max({ side[0], side[1], side[2] }) / this->Resolution;
    for (int a = 0; a < 3; ++a)
    {
      const double cells = std::max(1.0, std::ceil(side[a] / h - 1e-9));
      if (cells > 1e9)
      {
        vtkErrorMacro(<< "Grid too fine along axis " << a);
        return false;
      }
      dims[a] = static_cast<int>(cells) + 1;
    }
  }
  const double samples = double(dims[0]) * dims[1] * dims[2];
  if (samples > static_cast<double>(this->MaximumNumberOfSamples))
  {
    vtkErrorMacro(<< "A grid of " << dims[0] << " x " << dims[1] << " x " << dims[2] << " = "
                  << samples << " samples needs " << samples * sizeof(double) / (1 << 20)
                  << " MiB; the limit (MaximumNumberOfSamples) is "
                  << this->MaximumNumberOfSamples << " samples");
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    spacing[a] = side[a] / (dims[a] - 1);
  }
  return true;
}

int vtkPiFlyingEdges::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!this->PiSurface)
  {
    vtkErrorMacro(<< "No Pi-surface to mesh: call SetPiSurface()");
    return 0;
  }
  auto kernel = this->PiSurface->GetKernel();
  if (!kernel || kernel->GetNumberOfFactors() == 0)
  {
    vtkErrorMacro(<< "The Pi-surface is invalid or has no factors"
                  << (*this->PiSurface->GetErrorMessage() ? ": " : "")
                  << this->PiSurface->GetErrorMessage());
    return 0;
  }

  double bounds[6];
  const bool automatic = std::all_of(this->Bounds, this->Bounds + 6, [](double v) { return v == 0; });
  if (automatic)
  {
    if (!this->PiSurface->GetModelBounds(bounds))
    {
      vtkErrorMacro(<< "No bounds to mesh in: " << this->PiSurface->GetErrorMessage());
      return 0;
    }
  }
  else
  {
    if (!pisurf::ValidBounds(this->Bounds))
    {
      vtkErrorMacro(<< "Bounds must be finite with x0 < x1, y0 < y1, z0 < z1 (or all zero "
                       "for the model's bounds)");
      return 0;
    }
    std::copy(this->Bounds, this->Bounds + 6, bounds);
  }

  int dims[3];
  double spacing[3];
  if (!this->ComputeGrid(bounds, dims, spacing))
  {
    return 0;
  }
  const double origin[3] = { bounds[0], bounds[2], bounds[4] };

  // PASS 1: sample F row by row.
  vtkNew<vtkImageData> image;
  image->SetDimensions(dims);
  image->SetOrigin(origin);
  image->SetSpacing(spacing);
  vtkNew<vtkDoubleArray> values;
  values->SetName("F");
  values->SetNumberOfTuples(vtkIdType(dims[0]) * dims[1] * dims[2]);
  image->GetPointData()->SetScalars(values);
  std::atomic<bool> abort{ false };
  SampleRows sample{ kernel.get(), dims, origin, spacing, values->GetPointer(0), this, &abort };
  vtkSMPTools::For(0, vtkIdType(dims[1]) * dims[2], sample);
  if (abort || this->CheckAbort())
  {
    return 1;
  }
  this->UpdateProgress(0.5);

  // PASS 2: contour F = 0.
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(image);
  contour->SetValue(0, 0.0);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  contour->InterpolateAttributesOff();
  contour->Update();
  output->ShallowCopy(contour->GetOutput());
  output->GetPointData()->Initialize();
  this->UpdateProgress(0.8);
  if (this->CheckAbort())
  {
    return 1;
  }

  // PASS 3: analytic normals and the primitive of each vertex.
  const vtkIdType n = output->GetNumberOfPoints();
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  vtkNew<vtkIntArray> factor;
  factor->SetName("Factor");
  factor->SetNumberOfTuples(n);
  if (n > 0)
  {
    VertexAttributes attributes{ kernel.get(), output->GetPoints(), normals, factor };
    vtkSMPTools::For(0, n, attributes);
  }
  output->GetPointData()->SetNormals(normals);
  output->GetPointData()->AddArray(factor);

  pisurf::Model model;
  if (this->PiSurface->GetCoreModel(model))
  {
    vtkNew<vtkStringArray> json;
    json->SetName("PiSurfaceModel");
    json->InsertNextValue(pisurf::WriteModel(model));
    output->GetFieldData()->AddArray(json);
  }
  if (n == 0)
  {
    vtkWarningMacro(<< "The Pi-surface does not cross the bounds [" << bounds[0] << ", "
                    << bounds[1] << "] x [" << bounds[2] << ", " << bounds[3] << "] x ["
                    << bounds[4] << ", " << bounds[5] << "] at this resolution: empty mesh");
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPiFlyingEdges::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PiSurface: " << this->PiSurface << "\n";
  os << indent << "Bounds: (" << this->Bounds[0] << ", " << this->Bounds[1] << ", "
     << this->Bounds[2] << ", " << this->Bounds[3] << ", " << this->Bounds[4] << ", "
     << this->Bounds[5] << ")\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "SampleDimensions: (" << this->SampleDimensions[0] << ", "
     << this->SampleDimensions[1] << ", " << this->SampleDimensions[2] << ")\n";
  os << indent << "MaximumNumberOfSamples: " << this->MaximumNumberOfSamples << "\n";
}
