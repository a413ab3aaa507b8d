// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiSurfaceModelReader.h"

#include "vtkPiSurface.h"

#include "vtkObjectFactory.h"

#include <cmath>
#include <fstream>

vtkStandardNewMacro(vtkPiSurfaceModelReader);

vtkPiSurfaceModelReader::vtkPiSurfaceModelReader()
{
  vtkNew<vtkPiSurface> surface;
  this->SetPiSurface(surface);
}

vtkPiSurfaceModelReader::~vtkPiSurfaceModelReader()
{
  this->SetFileName(nullptr);
}

vtkMTimeType vtkPiSurfaceModelReader::GetMTime()
{
  // Not the surface's time: RequestData rewrites the surface from the file.
  return this->vtkPolyDataAlgorithm::GetMTime();
}

int vtkPiSurfaceModelReader::CanReadFile(const char* fileName)
{
  std::ifstream file(fileName ? fileName : "");
  if (!file)
  {
    return 0;
  }
  char head[4096] = { 0 };
  file.read(head, sizeof(head) - 1);
  const std::string text(head);
  const size_t brace = text.find_first_not_of(" \t\r\n");
  return brace != std::string::npos && text[brace] == '{' &&
    text.find("\"pisurf\"") != std::string::npos;
}

int vtkPiSurfaceModelReader::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "No FileName given");
    return 0;
  }
  if (this->OverrideBlending && !std::isfinite(this->Blending))
  {
    vtkErrorMacro(<< "Blending must be a finite number");
    return 0;
  }
  if (!this->PiSurface->LoadModel(this->FileName))
  {
    vtkErrorMacro(<< this->PiSurface->GetErrorMessage());
    return 0;
  }
  if (this->OverrideBlending)
  {
    this->PiSurface->SetBlending(this->Blending);
  }
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

void vtkPiSurfaceModelReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "OverrideBlending: " << this->OverrideBlending << "\n";
  os << indent << "Blending: " << this->Blending << "\n";
}
