// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiRayCaster.h"
#include "PiInputSurface.h"
#include "PiLargeArrays.h"
#include "PiParallel.h"
#include "PiPieces.h"
#include "PiTiming.h"

#include "PiModel.h"
#include "PiProductKernel.h"
#include "PiRayCaster.h"
#include "RayCasting/PiRayHitAttributes.h"
#include "RayCasting/PiRayImage.h"
#include "RayCasting/PiRayPieceRows.h"
#include "RayCasting/PiRayPointOutput.h"
#include "RayCasting/PiRayRowCaster.h"
#include "RayCasting/PiRaySkipping.h"
#include "RayCasting/PiRayView.h"
#include "RayCasting/PiRayViews.h"
#include "vtkPiSurface.h"

#include "vtkCellArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkGarbageCollector.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerRequestKey.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTypeInt32Array.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <limits>
#include <memory>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkPiRayCaster);
vtkCxxSetObjectMacro(vtkPiRayCaster, PiSurface, vtkPiSurface);

using pisurf::RayHit;
using pisurf::RayView;

namespace
{
bool CheckSettings(const int resolution[2], double singularTolerance, std::string& error)
{
  std::ostringstream message;
  if (resolution[0] < 1 || resolution[1] < 1)
  {
    message << "Resolution must be at least 1 x 1 (got " << resolution[0] << " x " << resolution[1]
            << ")";
  }
  else if (!(singularTolerance >= 0 && std::isfinite(singularTolerance)))
  {
    message << "SingularTolerance must be a finite number >= 0, not " << singularTolerance;
  }
  error = message.str();
  return error.empty();
}

}

vtkPiRayCaster::vtkPiRayCaster()
  : Rows(new pisurf::RayHitRows)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
}

int vtkPiRayCaster::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkImageData");
  return 1;
}

int vtkPiRayCaster::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // The image: w × h pixels, one slice per view (the number of views is known here).
  const int views = this->ViewMode == SIX_AXIS_VIEWS ? 6
    : this->ViewMode == THREE_AXIS_DIRECTIONS        ? 3
                                                     : 1;
  const int extent[6] = { 0, std::max(this->Resolution[0], 1) - 1, 0,
    std::max(this->Resolution[1], 1) - 1, 0, views - 1 };
  vtkInformation* info = outputVector->GetInformationObject(1);
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  // Pieces (ParaView's MPI mode) are slabs of image rows, the same rows of every view:
  // piece p of n casts rows [h p / n, h (p + 1) / n). The image port produces the same
  // row slabs as sub-extents.
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  info->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  info->Set(
    vtkExtentTranslator::UPDATE_SPLIT_MODE(), static_cast<int>(vtkExtentTranslator::Y_SLAB_MODE));
  return 1;
}

vtkPiRayCaster::~vtkPiRayCaster()
{
  this->SetPiSurface(nullptr);
  delete this->Rows;
}

int vtkPiRayCaster::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

vtkMTimeType vtkPiRayCaster::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->PiSurface)
  {
    t = std::max(t, this->PiSurface->GetMTime());
  }
  return t;
}

void vtkPiRayCaster::ReportReferences(vtkGarbageCollector* collector)
{
  this->Superclass::ReportReferences(collector);
  vtkGarbageCollectorReport(collector, this->PiSurface, "PiSurface");
}

int vtkPiRayCaster::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // PISURF_TIMING=1: the time of each pass on stderr (PiTiming.h).
  pisurf::PassTimer lap("vtkPiRayCaster");
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkImageData* image = vtkImageData::GetData(outputVector, 1);

  // The surface: a molecule's (Molecular Pi Surface output, any size or mode), else the
  // input's model, or the one set.
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  std::string error;
  pisurf::InputSurface in;
  if (!in.Read(input, this->PiSurface, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const pisurf::MoleculeInput& molecule = in.Molecule;
  const vtkSmartPointer<vtkPiSurface>& surface = in.Surface;
  if (!CheckSettings(this->Resolution, this->SingularTolerance, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  double b[6];
  if (!in.ResolveBounds(this->Bounds, b, error))
  {
    vtkErrorMacro(<< "No bounds for the rays: " << error);
    return 0;
  }

  // The views.
  const int w = this->Resolution[0], h = this->Resolution[1];
  std::vector<RayView> views;
  const pisurf::RayCamera camera{ this->CameraPosition, this->CameraFocalPoint, this->CameraViewUp,
    this->ViewAngle, this->ParallelProjection, this->ParallelScale };
  if (!pisurf::RayViews::Make(this->ViewMode, w, h, b, camera, views, error) ||
    !pisurf::RayViews::CheckMemory(w, h, views.size(), error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const bool allHits = this->AllHits || this->ViewMode == THREE_AXIS_DIRECTIONS;
  const double size = std::sqrt(
    (b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));

  const pisurf::RayPieceRows pieceRows = pisurf::RayPieceRows::Of(outputVector, image, h);
  const int rowBegin = pieceRows.RowBegin, rowEnd = pieceRows.RowEnd;
  if (rowEnd <= rowBegin)
  {
    // More pieces than rows: this one is empty.
    if (image)
    {
      image->Initialize();
    }
    return 1;
  }

  // PASS 1: cast the rays, one image row per work item.
  const vtkIdType rowCount = static_cast<vtkIdType>(views.size()) * (rowEnd - rowBegin);
  std::vector<std::vector<RayHit>>& rows = this->Rows->Reset(static_cast<size_t>(rowCount));
  std::atomic<bool> abort{ false };
  const std::shared_ptr<const pisurf::Field> field = in.MakeField(b, error);
  if (!field)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  pisurf::RayCaster caster(*field);
  // Orthographic row restriction and the empty-space octree: polynomial products only.
  const pisurf::ProductKernel* kernel = field->GetProductKernel();
  const bool polynomial = kernel && kernel->IsPolynomial();
  // Orthographic views of polynomial products restrict their rays from per-view
  // compositions (pisurf::RayGrid).
  std::vector<std::unique_ptr<pisurf::RayGrid>> grids(views.size());
  if (polynomial)
  {
    grids = pisurf::RayRowCaster::MakeGrids(*kernel, views, b);
  }
  // Per view, the depth ranges of each leaf column that may hold roots.
  std::vector<pisurf::RayViewSkipping> skipping(views.size());
  if (polynomial && this->SkipEmptySpace)
  {
    pisurf::RaySkipping::Build(*kernel, views, b, rowBegin, rowEnd, allHits, skipping);
  }
  lap("tiles");
  if (lap.IsEnabled())
  {
    pisurf::RaySkipping::PrintCounts(skipping, std::cerr);
  }
  std::atomic<vtkIdType> finished{ 0 };
  pisurf::RayRowCaster cast{ &views, b, allHits, 1e-10 * size, &rows, &caster, &grids, &skipping,
    this, &abort, rowBegin, rowEnd, &finished, rowCount };
  lap("setup");
  cast.Run();
  lap("roots");
  if (abort || this->CheckAbort())
  {
    return 1;
  }
  this->UpdateProgress(0.8);

  // PASS 2: the hits' attributes from the exact gradient (of every hit the image
  // shows; the points are then this piece's rows).
  pisurf::RayHitAttributes hits;
  hits.Compute(rows, caster, b, size, this->SingularTolerance);
  pisurf::RayHitAttributes::ReleaseLargeRows(rows);
  lap("attributes");
  if (this->CheckAbort())
  {
    return 1;
  }
  this->UpdateProgress(0.9);
  pisurf::RayPointOutput::SetPoints(hits, pieceRows, output);
  pisurf::RayPointOutput::AddViews(views, allHits, output);
  if (molecule.Present)
  {
    molecule.Forward(input, output); // the molecule goes downstream
  }
  else
  {
    pisurf::RayPointOutput::AddModel(*surface, b, output);
  }
  lap("output");
  if (image)
  {
    pisurf::RayImage::Shade(views, w, rowBegin, rowEnd, hits.RowOffsets.data(),
      hits.Depth->GetPointer(0), hits.Pixel->GetPointer(0), hits.HitIndex->GetPointer(0),
      hits.Normals, hits.Singular, image);
    if (pieceRows.ExtraRows())
    {
      pisurf::RayImage::MarkGhosts(pieceRows, w, image);
    }
  }
  lap("shading");
  if (hits.GetNumberOfHits() == 0 && pieceRows.Pieces == 1)
  {
    vtkWarningMacro(<< "No ray hits the Pi-surface");
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPiRayCaster::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PiSurface: " << this->PiSurface << "\n";
  os << indent << "ViewMode: " << this->ViewMode << "\n";
  os << indent << "Resolution: " << this->Resolution[0] << " x " << this->Resolution[1] << "\n";
  os << indent << "AllHits: " << this->AllHits << "\n";
  os << indent << "Bounds: (" << this->Bounds[0] << ", " << this->Bounds[1] << ", "
     << this->Bounds[2] << ", " << this->Bounds[3] << ", " << this->Bounds[4] << ", "
     << this->Bounds[5] << ")\n";
  os << indent << "CameraPosition: (" << this->CameraPosition[0] << ", " << this->CameraPosition[1]
     << ", " << this->CameraPosition[2] << ")\n";
  os << indent << "CameraFocalPoint: (" << this->CameraFocalPoint[0] << ", "
     << this->CameraFocalPoint[1] << ", " << this->CameraFocalPoint[2] << ")\n";
  os << indent << "CameraViewUp: (" << this->CameraViewUp[0] << ", " << this->CameraViewUp[1]
     << ", " << this->CameraViewUp[2] << ")\n";
  os << indent << "ViewAngle: " << this->ViewAngle << "\n";
  os << indent << "ParallelProjection: " << this->ParallelProjection << "\n";
  os << indent << "ParallelScale: " << this->ParallelScale << "\n";
  os << indent << "SingularTolerance: " << this->SingularTolerance << "\n";
  os << indent << "SkipEmptySpace: " << this->SkipEmptySpace << "\n";
}
