// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiSampleFunction.h"
#include "PiInputSurface.h"
#include "PiLargeArrays.h"
#include "PiParallel.h"
#include "PiPieces.h"

#include "PiProductKernel.h"
#include "vtkPiSurface.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkGarbageCollector.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <vector>

vtkStandardNewMacro(vtkPiSampleFunction);
vtkCxxSetObjectMacro(vtkPiSampleFunction, PiSurface, vtkPiSurface);

vtkPiSampleFunction::vtkPiSampleFunction()
{
  this->SetNumberOfInputPorts(1);
}

vtkPiSampleFunction::~vtkPiSampleFunction()
{
  this->SetPiSurface(nullptr);
}

int vtkPiSampleFunction::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

vtkMTimeType vtkPiSampleFunction::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  return this->PiSurface ? std::max(t, this->PiSurface->GetMTime()) : t;
}

void vtkPiSampleFunction::ReportReferences(vtkGarbageCollector* collector)
{
  this->Superclass::ReportReferences(collector);
  vtkGarbageCollectorReport(collector, this->PiSurface, "PiSurface");
}

int vtkPiSampleFunction::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // The extent only (the box comes with the model, in RequestData).
  const int* d = this->SampleDimensions;
  const int extent[6] = { 0, std::max(d[0], 1) - 1, 0, std::max(d[1], 1) - 1, 0,
    std::max(d[2], 1) - 1 };
  vtkInformation* info = outputVector->GetInformationObject(0);
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  info->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_DOUBLE, 1);
  return 1;
}

int vtkPiSampleFunction::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Only the input's model is used: any piece of it carries it; ask for the first.
  pisurf::RequestWholeInput(inputVector[0]);
  return 1;
}

int vtkPiSampleFunction::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  output->Initialize();

  // The surface: a molecule's field (Molecular Pi Surface output, any size or mode), else
  // the input's model, or the one set.
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  std::string error;
  pisurf::InputSurface in;
  if (!in.Read(input, this->PiSurface, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const int* d = this->SampleDimensions;
  if (d[0] < 2 || d[1] < 2 || d[2] < 2)
  {
    vtkErrorMacro(<< "SampleDimensions must be at least 2 points per axis (got " << d[0] << ", "
                  << d[1] << ", " << d[2] << ")");
    return 0;
  }
  const double samples = double(d[0]) * d[1] * d[2];
  if (samples > static_cast<double>(this->MaximumNumberOfSamples))
  {
    vtkErrorMacro(<< "A grid of " << d[0] << " x " << d[1] << " x " << d[2] << " = " << samples
                  << " samples needs " << samples * sizeof(double) / (1 << 20)
                  << " MiB; the limit is "
                  << double(this->MaximumNumberOfSamples) * sizeof(double) / (1 << 20)
                  << " MiB (MaximumNumberOfSamples = " << this->MaximumNumberOfSamples << ")");
    return 0;
  }
  double b[6];
  if (!in.ResolveBounds(this->ModelBounds, b, error))
  {
    vtkErrorMacro(<< "No bounds to sample: " << error);
    return 0;
  }
  double origin[3], spacing[3];
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = b[2 * a];
    spacing[a] = (b[2 * a + 1] - b[2 * a]) / (d[a] - 1);
  }

  // The requested piece of the grid (all of it by default).
  int extent[6] = { 0, d[0] - 1, 0, d[1] - 1, 0, d[2] - 1 };
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent);
  }
  output->SetExtent(extent);
  output->SetOrigin(origin);
  output->SetSpacing(spacing);
  const int nx = extent[1] - extent[0] + 1, ny = extent[3] - extent[2] + 1,
            nz = extent[5] - extent[4] + 1;
  vtkNew<vtkDoubleArray> values;
  values->SetName("F");
  if (nx <= 0 || ny <= 0 || nz <= 0)
  {
    output->GetPointData()->SetScalars(values);
    return 1; // an empty piece
  }
  pisurf::AllocateLargeArray(values.GetPointer(), vtkIdType(nx) * ny * nz);
  double* out = values->GetPointer(0);

  // One x row per work item: the factors restricted to it once, about the middle of the
  // whole grid's row (so a piece's values have the bits of the whole grid's, and of the
  // mesher's on the same grid), then Horner's rule several points at a time.
  const vtkIdType rows = vtkIdType(ny) * nz;
  const std::shared_ptr<const pisurf::Field> field = in.MakeField(b, error);
  if (!field)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  // The product's rows restricted at once, else the field point by point.
  const pisurf::ProductKernel* kernel = field->GetProductKernel();
  const double step[3] = { spacing[0], 0.0, 0.0 };
  const double mid = 0.5 * (d[0] - 1);
  std::atomic<bool> abort{ false };
  std::atomic<vtkIdType> done{ 0 };
  pisurf::ParallelFor(0, rows, 16,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType r = begin; r < end && !abort; ++r)
      {
        const int j = extent[2] + static_cast<int>(r % ny),
                  k = extent[4] + static_cast<int>(r / ny);
        if (!kernel)
        {
          // The field point by point (a molecule's cells hold the atoms near each point),
          // at the points the mesher would take: origin + index·spacing.
          for (int i = 0; i < nx; ++i)
          {
            const double p[3] = { origin[0] + (extent[0] + i) * spacing[0],
              origin[1] + j * spacing[1], origin[2] + k * spacing[2] };
            out[r * nx + i] = field->Evaluate(p);
          }
          continue;
        }
        thread_local std::vector<double> coefficients;
        coefficients.resize(kernel->GetLineCoefficientCount());
        const double middle[3] = { origin[0] + mid * spacing[0], origin[1] + j * spacing[1],
          origin[2] + k * spacing[2] };
        kernel->RestrictLine(middle, step, coefficients.data());
        const double start[3] = { origin[0] + extent[0] * spacing[0], middle[1], middle[2] };
        kernel->EvaluateRestrictedRow(
          coefficients.data(), extent[0] - mid, nx, start, step, out + r * nx);
      }
      const vtkIdType finished = done += end - begin;
      // Progress and abort from the thread that may call into the pipeline.
      if (pisurf::SingleThread())
      {
        this->UpdateProgress(double(finished) / rows);
        if (this->CheckAbort())
        {
          abort = true;
        }
      }
    });
  output->GetPointData()->SetScalars(values);
  if (abort)
  {
    output->Initialize();
  }
  return 1;
}

void vtkPiSampleFunction::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PiSurface: " << this->PiSurface << "\n";
  os << indent << "SampleDimensions: " << this->SampleDimensions[0] << " "
     << this->SampleDimensions[1] << " " << this->SampleDimensions[2] << "\n";
  os << indent << "ModelBounds: " << this->ModelBounds[0] << " " << this->ModelBounds[1] << " "
     << this->ModelBounds[2] << " " << this->ModelBounds[3] << " " << this->ModelBounds[4] << " "
     << this->ModelBounds[5] << "\n";
  os << indent << "MaximumNumberOfSamples: " << this->MaximumNumberOfSamples << "\n";
}
