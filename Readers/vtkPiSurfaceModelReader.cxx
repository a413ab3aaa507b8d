// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiSurfaceModelReader.h"

#include "vtkPiSurface.h"

#include "vtkObjectFactory.h"

#include <fstream>
#include <string>

vtkStandardNewMacro(vtkPiSurfaceModelReader);

vtkPiSurfaceModelReader::vtkPiSurfaceModelReader() = default;

vtkPiSurfaceModelReader::~vtkPiSurfaceModelReader()
{
  this->SetFileName(nullptr);
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

bool vtkPiSurfaceModelReader::LoadModel(vtkInformationVector**, vtkPiSurface* surface)
{
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "No FileName given");
    return false;
  }
  if (!surface->LoadModel(this->FileName))
  {
    vtkErrorMacro(<< surface->GetErrorMessage());
    return false;
  }
  return true;
}

void vtkPiSurfaceModelReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
