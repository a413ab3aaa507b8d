// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiInputModel.h
 * @brief the Pi-surface an algorithm of this module works on
 *
 * Pi Ray Cast and Pi Sample Function take their Pi-surface from their input's field-data
 * string `PiSurfaceModel` (written by Pi Surface, Pi Primitive, Pi Product, the model
 * reader and the molecular surface) when an input is connected, else from the one set
 * on them (SetPiSurface).
 */
#ifndef PiInputModel_h
#define PiInputModel_h

#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkPiSurface.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <string>

/// The model `input` carries, or `set` without an input; null with the reason in
/// `error` if the input carries no model or an invalid one, or there is neither.
inline vtkSmartPointer<vtkPiSurface> PiSurfaceOf(
  vtkDataObject* input, vtkPiSurface* set, std::string& error)
{
  if (!input)
  {
    if (!set)
    {
      error = "No Pi-surface: connect an input with a PiSurfaceModel or call SetPiSurface()";
    }
    return set;
  }
  auto* json =
    vtkStringArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("PiSurfaceModel"));
  if (!json || json->GetNumberOfValues() < 1)
  {
    error = "The input carries no PiSurfaceModel field data (use the output of a Pi Surface, "
            "Pi Primitive, Pi Product or the model reader)";
    return nullptr;
  }
  auto surface = vtkSmartPointer<vtkPiSurface>::New();
  if (!surface->SetModelJSON(json->GetValue(0)))
  {
    error = std::string("Invalid PiSurfaceModel: ") + surface->GetErrorMessage();
    return nullptr;
  }
  return surface;
}

#endif
