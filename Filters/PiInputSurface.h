// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file InputSurface.h
 * @brief the Pi-surface an algorithm of this module works on
 *
 * Pi Ray Cast and Pi Sample Function take their Pi-surface from their input's field-data
 * string `PiSurfaceModel` (written by Pi Surface, Pi Primitive, Pi Product, the model
 * reader and the molecular surface) when an input is connected, else from the one set
 * on them (SetPiSurface). Pi Ray Cast, Image Based Triangulation and Pi Sample Function
 * also take a molecule, of any size and either mode, from the compact arrays the
 * molecular surface writes (MoleculeInput), and then work on its own field.
 */
#ifndef PiInputSurface_h
#define PiInputSurface_h

#include "PiModel.h"
#include "PiMoleculeField.h"
#include "PiProductField.h"
#include "PiProductKernel.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkPiSurface.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <vector>

namespace pisurf
{

/// The model `input` carries, or `set` without an input; null with the reason in
/// `error` if the input carries no model or an invalid one, or there is neither.
inline vtkSmartPointer<vtkPiSurface> SurfaceOf(
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
  // Parsed here rather than by vtkPiSurface::SetModelJSON, which would report the error
  // itself: the calling algorithm reports it, once.
  pisurf::Model model;
  std::string reason;
  if (!pisurf::ParseModel(json->GetValue(0), model, reason))
  {
    error = "Invalid PiSurfaceModel: " + reason;
    return nullptr;
  }
  auto surface = vtkSmartPointer<vtkPiSurface>::New();
  surface->SetCoreModel(model);
  return surface;
}

/// The molecule a Molecular Pi Surface output carries in its field data:
/// `PiMoleculeCenters` (3 components per atom, Å), `PiMoleculeRadii` (Å) and
/// `PiMoleculeSettings` (9 values: Mode 0 = Global or 1 = Local, Blending,
/// InfluenceRadius, then the bounds x0, x1, y0, y1, z0, z1 it was meshed in).
struct MoleculeInput
{
  bool Present = false;
  std::vector<double> Centers, Radii;
  pisurf::MoleculeSettings Settings;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };

  /// Present stays false without the three arrays; false with the reason in `error`
  /// when they are there but inconsistent or not finite.
  bool Read(vtkDataObject* input, std::string& error)
  {
    vtkFieldData* fd = input ? input->GetFieldData() : nullptr;
    vtkDataArray* centers = fd ? fd->GetArray("PiMoleculeCenters") : nullptr;
    vtkDataArray* radii = fd ? fd->GetArray("PiMoleculeRadii") : nullptr;
    vtkDataArray* settings = fd ? fd->GetArray("PiMoleculeSettings") : nullptr;
    if (!centers || !radii || !settings)
    {
      return true;
    }
    const vtkIdType n = radii->GetNumberOfTuples();
    if (centers->GetNumberOfComponents() != 3 || centers->GetNumberOfTuples() != n ||
      radii->GetNumberOfComponents() != 1 || settings->GetNumberOfValues() != 9 || n == 0)
    {
      error = "Malformed molecule field data: PiMoleculeCenters (3 components), "
              "PiMoleculeRadii (one per atom, at least one) and PiMoleculeSettings (9 values) "
              "must agree";
      return false;
    }
    this->Centers.resize(3 * n);
    this->Radii.resize(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        this->Centers[3 * i + k] = centers->GetComponent(i, k);
      }
      this->Radii[i] = radii->GetComponent(i, 0);
      if (!(this->Radii[i] > 0 && std::isfinite(this->Radii[i])) ||
        !std::isfinite(this->Centers[3 * i] + this->Centers[3 * i + 1] + this->Centers[3 * i + 2]))
      {
        error = "Malformed molecule field data: atom " + std::to_string(i) +
          " has a non-finite centre or a radius that is not positive";
        return false;
      }
    }
    double v[9];
    for (int k = 0; k < 9; ++k)
    {
      v[k] = settings->GetComponent(
        k / settings->GetNumberOfComponents(), k % settings->GetNumberOfComponents());
    }
    std::copy(v + 3, v + 9, this->Bounds);
    if ((v[0] != 0 && v[0] != 1) || !(v[1] >= 0 && std::isfinite(v[1])) ||
      !(v[2] > 0 && std::isfinite(v[2])) || !pisurf::ValidBounds(this->Bounds))
    {
      error = "Malformed PiMoleculeSettings: expected Mode 0 or 1, Blending >= 0, "
              "InfluenceRadius > 0 and valid bounds";
      return false;
    }
    this->Settings.Mode = v[0] == 1 ? pisurf::MoleculeMode::Local : pisurf::MoleculeMode::Global;
    this->Settings.Blending = v[1];
    this->Settings.InfluenceRadius = v[2];
    this->Present = true;
    return true;
  }

  /// The box to work in: `requested` unless all zero (then the molecule's bounds);
  /// false with the reason if `requested` is not a valid box.
  bool ResolveBounds(const double requested[6], double bounds[6], std::string& error) const
  {
    if (pisurf::UnsetBounds(requested))
    {
      std::copy(this->Bounds, this->Bounds + 6, bounds);
      return true;
    }
    return pisurf::TakeBounds(requested, "molecule's", bounds, error);
  }

  /// The molecule's field with cells over `region`; null with the reason if it cannot be
  /// built.
  std::unique_ptr<pisurf::MoleculeField> MakeField(const double region[6], std::string& error) const
  {
    try
    {
      return std::make_unique<pisurf::MoleculeField>(
        this->Centers, this->Radii, this->Settings, region);
    }
    catch (const std::exception& e)
    {
      error = std::string("Invalid molecule: ") + e.what();
      return nullptr;
    }
  }

  /// Passes the three arrays on to `output` (so the molecule reaches further filters).
  static void Forward(vtkDataObject* input, vtkDataObject* output)
  {
    for (const char* name : { "PiMoleculeCenters", "PiMoleculeRadii", "PiMoleculeSettings" })
    {
      output->GetFieldData()->AddArray(input->GetFieldData()->GetAbstractArray(name));
    }
  }
};

/// What Pi Ray Cast and Pi Sample Function work on: the input's molecule when it
/// carries one (`Molecule.Present`), else the product of its PiSurfaceModel or the one
/// set (`Surface`, `Kernel`, with at least one factor); MakeField gives either as the
/// one Field the algorithms evaluate.
struct InputSurface
{
  MoleculeInput Molecule;
  vtkSmartPointer<vtkPiSurface> Surface;
  std::shared_ptr<const pisurf::ProductKernel> Kernel;

  /// False with the reason in `error` if there is neither or it is invalid.
  bool Read(vtkDataObject* input, vtkPiSurface* set, std::string& error)
  {
    if (!this->Molecule.Read(input, error))
    {
      return false;
    }
    if (this->Molecule.Present)
    {
      return true;
    }
    this->Surface = SurfaceOf(input, set, error);
    if (!this->Surface)
    {
      return false;
    }
    this->Kernel = this->Surface->GetKernel();
    if (!this->Kernel || this->Kernel->GetNumberOfFactors() == 0)
    {
      error = "The Pi-surface is invalid or has no factors";
      return false;
    }
    return true;
  }

  /// The field to evaluate: the molecule's, with its cells over `region`, or the
  /// product's; null with the reason in `error` if it cannot be built.
  std::shared_ptr<const pisurf::Field> MakeField(const double region[6], std::string& error) const
  {
    if (this->Molecule.Present)
    {
      return this->Molecule.MakeField(region, error);
    }
    return std::make_shared<pisurf::ProductField>(this->Kernel);
  }

  /// The box to work in: `requested`, or where it is all zero the molecule's bounds or
  /// the model's; false with the reason in `error` if there is none.
  bool ResolveBounds(const double requested[6], double bounds[6], std::string& error) const
  {
    if (this->Molecule.Present)
    {
      return this->Molecule.ResolveBounds(requested, bounds, error);
    }
    if (!this->Surface->ResolveBounds(requested, bounds))
    {
      error = this->Surface->GetErrorMessage();
      return false;
    }
    return true;
  }
};

}

#endif
