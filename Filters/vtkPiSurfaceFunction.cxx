// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiSurfaceFunction.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkPiSurfaceFunction);

void vtkPiSurfaceFunction::SetModel(const char* json)
{
  const std::string text = json ? json : "";
  if (text != this->ModelText)
  {
    this->ModelText = text;
    this->Reload();
  }
}

void vtkPiSurfaceFunction::SetFileName(const char* path)
{
  const std::string text = path ? path : "";
  if (text != this->FileNameText)
  {
    this->FileNameText = text;
    this->Reload();
  }
}

void vtkPiSurfaceFunction::Reload()
{
  if (!this->FileNameText.empty())
  {
    this->LoadModel(this->FileNameText.c_str());
  }
  else if (this->ModelText.find_first_not_of(" \t\r\n") != std::string::npos)
  {
    this->SetModelJSON(this->ModelText);
  }
  this->Modified();
}

void vtkPiSurfaceFunction::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileNameText << "\n";
  os << indent << "Model: " << this->ModelText << "\n";
}
