// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiSurfaceSource.h"

#include "vtkPiSurface.h"

#include "vtkObjectFactory.h"

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

bool vtkPiSurfaceSource::LoadModel(vtkInformationVector**, vtkPiSurface* surface)
{
  if (!surface->SetModelJSON(this->ModelText))
  {
    vtkErrorMacro(<< "Invalid Model: " << surface->GetErrorMessage());
    return false;
  }
  return true;
}

void vtkPiSurfaceSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Model: " << this->ModelText << "\n";
}
