// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiSurfaceModelWriter.h"

#include "vtkPiSurface.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkStringArray.h"

#include <cstdio>
#include <fstream>
#include <string>

vtkStandardNewMacro(vtkPiSurfaceModelWriter);

vtkPiSurfaceModelWriter::vtkPiSurfaceModelWriter() = default;

vtkPiSurfaceModelWriter::~vtkPiSurfaceModelWriter()
{
  this->SetFileName(nullptr);
}

int vtkPiSurfaceModelWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

void vtkPiSurfaceModelWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "No FileName given");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  vtkStringArray* json = input && input->GetFieldData()
    ? vtkStringArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("PiSurfaceModel"))
    : nullptr;
  if (!json || json->GetNumberOfValues() < 1)
  {
    vtkErrorMacro(<< "The input carries no PiSurfaceModel field data: nothing to write to "
                  << this->FileName);
    this->SetErrorCode(vtkErrorCode::UserError);
    return;
  }
  // Validated by reading it, written as the surface writes models.
  vtkNew<vtkPiSurface> surface;
  vtkNew<vtkCallbackCommand> quiet;
  surface->AddObserver(vtkCommand::ErrorEvent, quiet);
  std::string text;
  if (!surface->SetModelJSON(json->GetValue(0)) || (text = surface->GetModelJSON()).empty())
  {
    vtkErrorMacro(<< "The input's PiSurfaceModel is invalid (" << surface->GetErrorMessage()
                  << "): not written");
    this->SetErrorCode(vtkErrorCode::UserError);
    return;
  }
  // Write beside the target, then rename: a failed write leaves no half file.
  const std::string temporary = std::string(this->FileName) + ".part";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    if (file)
    {
      file << text;
      file.close();
    }
    if (!file)
    {
      std::remove(temporary.c_str());
      vtkErrorMacro(<< "Cannot write " << this->FileName);
      this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
      return;
    }
  }
  if (std::rename(temporary.c_str(), this->FileName) != 0)
  {
    std::remove(temporary.c_str());
    vtkErrorMacro(<< "Cannot write " << this->FileName);
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

void vtkPiSurfaceModelWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
