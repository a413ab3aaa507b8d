// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiSurfaceSource.h"

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
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

void vtkPiSurfaceSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Model: " << this->ModelText << "\n";
  os << indent << "OverrideBlending: " << this->OverrideBlending << "\n";
  os << indent << "Blending: " << this->Blending << "\n";
}
