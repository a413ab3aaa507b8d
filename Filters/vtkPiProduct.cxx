// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiProduct.h"

#include "PiModel.h"

#include "vtkAlgorithm.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPiSurface.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkPiProduct);

vtkPiProduct::vtkPiProduct()
{
  this->SetNumberOfInputPorts(1);
  // The inputs show the primitives already.
  this->SetGeneratePrimitives(false);
}

vtkPiProduct::~vtkPiProduct() = default;

int vtkPiProduct::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  // Optional, so that an empty product reaches RequestData and is reported clearly.
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

bool vtkPiProduct::LoadModel(vtkInformationVector** inputVector, vtkPiSurface* surface)
{
  const int n = inputVector[0]->GetNumberOfInformationObjects();
  std::vector<pisurf::Model> models;
  models.reserve(n);
  for (int i = 0; i < n; ++i)
  {
    vtkDataObject* input = vtkDataObject::GetData(inputVector[0], i);
    vtkStringArray* json = input && input->GetFieldData()
      ? vtkStringArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("PiSurfaceModel"))
      : nullptr;
    if (!json || json->GetNumberOfValues() < 1)
    {
      vtkErrorMacro(<< "Input " << i + 1 << " (" << (input ? input->GetClassName() : "none")
                    << ") carries no PiSurfaceModel field data: connect Pi Primitive, Pi "
                       "Surface, Pi Surface Model Reader, Pi Product or Molecular Pi Surface "
                       "outputs (an invalid input also leaves its output empty)");
      return false;
    }
    pisurf::Model model;
    std::string error;
    if (!pisurf::ParseModel(json->GetValue(0), model, error))
    {
      vtkErrorMacro(<< "Input " << i + 1 << " carries an invalid PiSurfaceModel: " << error);
      return false;
    }
    models.push_back(std::move(model));
  }
  pisurf::Model product;
  std::string error;
  if (!pisurf::MultiplyModels(models, this->GetBlending(), product, error))
  {
    vtkErrorMacro(<< "Cannot form the product: " << error);
    return false;
  }
  const double* bounds = this->GetBounds();
  if (!pisurf::UnsetBounds(bounds))
  {
    if (!pisurf::ValidBounds(bounds))
    {
      vtkErrorMacro(<< "Bounds must be finite with x0 < x1, y0 < y1, z0 < z1 (or all 0)");
      return false;
    }
    // The output's model says where it was meshed (for the ray caster downstream).
    product.HasBounds = true;
    std::copy(bounds, bounds + 6, product.Bounds);
  }
  this->ProductModel = pisurf::WriteModel(product);
  if (!surface->SetModelJSON(this->ProductModel))
  {
    vtkErrorMacro(<< "Invalid Model: " << surface->GetErrorMessage());
    return false;
  }
  return true;
}

void vtkPiProduct::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Model: " << this->ProductModel << "\n";
}
