// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiSurfaceSource.h"
#include "PiInnerAlgorithm.h"
#include "PiPieces.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkPiImageTriangulator.h"
#include "vtkPiRayCaster.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "vtkPiSurface.h"

#include "vtkObjectFactory.h"

#include <cmath>

vtkStandardNewMacro(vtkPiSurfaceSource);

namespace
{
// The paper's Figure 1(b); the same text is the XML default of the "Pi Surface" source.
const char* const DefaultModel =
  "{\"pisurf\": 1, \"blending\": 0.25, \"primitives\": [{\"type\": \"sphere\", \"center\": "
  "[0.9, 0, 0], \"radius\": 1}, {\"type\": \"sphere\", \"center\": [-0.9, 0, 0], \"radius\": 1}]}";
}

vtkPiSurfaceSource::vtkPiSurfaceSource()
  : ModelText(DefaultModel)
{
  vtkNew<vtkPiSurface> surface;
  this->SetPiSurface(surface);
  this->GeneratePrimitives = true; // ParaView users see the primitives by default
}

vtkPiSurfaceSource::~vtkPiSurfaceSource() = default;

void vtkPiSurfaceSource::SetModel(const char* json)
{
  const std::string text = json ? json : "";
  if (text != this->ModelText)
  {
    this->ModelText = text;
    this->Modified();
  }
}

vtkMTimeType vtkPiSurfaceSource::GetMTime()
{
  // Not the surface's time: RequestData rewrites the surface from the model.
  return this->vtkPolyDataAlgorithm::GetMTime();
}

bool vtkPiSurfaceSource::ReadModel()
{
  if (!this->PiSurface->SetModelJSON(this->ModelText))
  {
    vtkErrorMacro(<< "Invalid Model: " << this->PiSurface->GetErrorMessage());
    return false;
  }
  return true;
}

int vtkPiSurfaceSource::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (this->OverrideBlending && !std::isfinite(this->Blending))
  {
    vtkErrorMacro(<< "Blending must be a finite number");
    return 0;
  }
  if (!this->PiSurface || !this->ReadModel())
  {
    return 0;
  }
  if (this->OverrideBlending)
  {
    this->PiSurface->SetBlending(this->Blending);
  }
  if (this->Method == RAY_CAST_TRIANGULATION)
  {
    return this->RayCastTriangulation(outputVector);
  }
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

int vtkPiSurfaceSource::RayCastTriangulation(vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* primitives = vtkPolyData::GetData(outputVector, 1);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (pisurf::PieceOf(outInfo).Piece > 0)
  {
    // The ray lattice is not split into pieces: the first piece holds the whole mesh.
    return 1;
  }
  double bounds[6];
  if (!this->PiSurface->ResolveBounds(this->Bounds, bounds))
  {
    vtkErrorMacro(<< "No bounds to mesh in: " << this->PiSurface->GetErrorMessage());
    return 0;
  }
  int dims[3];
  double spacing[3];
  if (!this->ComputeGrid(bounds, dims, spacing))
  {
    return 0;
  }
  // One lattice resolution on the three axes (the views share their pixel counts).
  const int n = std::max(dims[0], std::max(dims[1], dims[2])) - 1;
  vtkNew<vtkPiRayCaster> caster;
  caster->SetPiSurface(this->PiSurface);
  caster->SetBounds(bounds);
  caster->SetResolution(n, n);
  caster->SetViewMode(
    this->OuterEnvelope ? vtkPiRayCaster::SIX_AXIS_VIEWS : vtkPiRayCaster::THREE_AXIS_DIRECTIONS);
  vtkNew<vtkPiImageTriangulator> triangulator;
  triangulator->SetInputConnection(caster->GetOutputPort());
  triangulator->SetMergeMode(vtkPiImageTriangulator::RAY_LATTICE);
  // Their progress is ours (the casts from 0 to 0.5, the triangulation from 0.5 to 1),
  // and so is our cancel.
  pisurf::WorkFor(caster, this, 0.0, 0.5);
  pisurf::WorkFor(triangulator, this, 0.5, 0.5);
  caster->Update();
  if (this->CheckAbort())
  {
    return 1; // cancelled while casting: the triangulator has nothing to do
  }
  triangulator->Update();
  if (this->CheckAbort())
  {
    return 1;
  }
  output->ShallowCopy(triangulator->GetOutput());
  if (this->GeneratePrimitives && primitives)
  {
    this->MeshPrimitives(bounds, dims, 0, 1, primitives);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPiSurfaceSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Model: " << this->ModelText << "\n";
  os << indent << "OverrideBlending: " << this->OverrideBlending << "\n";
  os << indent << "Blending: " << this->Blending << "\n";
  os << indent << "Method: " << this->Method << "\n";
}
