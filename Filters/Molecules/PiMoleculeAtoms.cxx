// SPDX-License-Identifier: BSD-3-Clause
// PASS 1 of vtkPiMoleculeSurface: the atoms and their radii (see PiMoleculeSurfacePasses.h).
#include "PiMoleculeSurfacePasses.h"

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkMolecule.h"
#include "vtkNew.h"
#include "vtkPeriodicTable.h"
#include "vtkPiMoleculeSurface.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cmath>
#include <map>
#include <sstream>

namespace pisurf
{
namespace molecule
{
bool Atoms::Read(vtkAlgorithm* algorithm, vtkDataObject* input, int radiusTable,
  vtkDataArray* chosen, double radiusScale)
{
  // The atoms: positions, atomic numbers, and the point data (for a radius array).
  vtkNew<vtkPoints> atoms;
  std::vector<int>& numbers = this->Numbers;
  numbers.clear();
  this->Centers.clear();
  this->Radii.clear();
  vtkDataSetAttributes* atomData = nullptr;
  if (auto molecule = vtkMolecule::SafeDownCast(input))
  {
    const vtkIdType n = molecule->GetNumberOfAtoms();
    atoms->SetNumberOfPoints(n);
    numbers.resize(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      double x[3];
      molecule->GetAtomPosition(i, x);
      atoms->SetPoint(i, x);
      numbers[i] = molecule->GetAtomAtomicNumber(i);
    }
    atomData = molecule->GetVertexData();
  }
  else if (auto poly = vtkPolyData::SafeDownCast(input))
  {
    const vtkIdType n = poly->GetNumberOfPoints();
    vtkDataArray* z = poly->GetPointData()->GetArray("atom_type");
    if (!z)
    {
      z = poly->GetPointData()->GetArray("AtomicNumber");
    }
    if (n > 0 && !z && radiusTable != vtkPiMoleculeSurface::POINT_ARRAY)
    {
      vtkErrorWithObjectMacro(
        algorithm, << "The input polydata has no point array 'atom_type' or 'AtomicNumber' "
                      "(atomic numbers); use RadiusTable = point array with a radius array");
      return false;
    }
    atoms->SetNumberOfPoints(n);
    numbers.assign(n, 0);
    for (vtkIdType i = 0; i < n; ++i)
    {
      atoms->SetPoint(i, poly->GetPoint(i));
      if (z)
      {
        numbers[i] = static_cast<int>(z->GetComponent(i, 0));
      }
    }
    atomData = poly->GetPointData();
  }
  else
  {
    vtkErrorWithObjectMacro(
      algorithm, << "The input must be a vtkMolecule or a vtkPolyData of atoms");
    return false;
  }
  const vtkIdType count = atoms->GetNumberOfPoints();
  if (count == 0)
  {
    vtkErrorWithObjectMacro(algorithm, << "The input molecule has no atoms");
    return false;
  }

  // PASS 1: radii.
  std::vector<double>& centers = this->Centers;
  std::vector<double>& radii = this->Radii;
  centers.resize(3 * count);
  radii.resize(count);
  vtkNew<vtkPeriodicTable> table;
  vtkDataArray* radiusArray = nullptr;
  if (radiusTable == vtkPiMoleculeSurface::POINT_ARRAY)
  {
    radiusArray = chosen;
    if (!radiusArray && atomData)
    {
      radiusArray = atomData->GetArray("radius");
    }
    if (!radiusArray)
    {
      vtkErrorWithObjectMacro(
        algorithm, << "RadiusTable is a point array, but the input has no such array "
                      "(set the input array to process, e.g. 'radius')");
      return false;
    }
    if (radiusArray->GetNumberOfTuples() != count)
    {
      vtkErrorWithObjectMacro(algorithm,
        << "The radius array '" << (radiusArray->GetName() ? radiusArray->GetName() : "")
        << "' has " << radiusArray->GetNumberOfTuples() << " values for " << count << " atoms");
      return false;
    }
  }
  std::map<int, int> missing; // element -> atoms that fell back to Blue Obelisk
  for (vtkIdType i = 0; i < count; ++i)
  {
    atoms->GetPoint(i, &centers[3 * i]);
    for (int a = 0; a < 3; ++a)
    {
      if (!std::isfinite(centers[3 * i + a]))
      {
        vtkErrorWithObjectMacro(
          algorithm, << "Atom " << i << " has a coordinate that is not a finite number");
        return false;
      }
    }
    const int z = numbers[i];
    double R = 0.0;
    switch (radiusTable)
    {
      case vtkPiMoleculeSurface::BONDI:
        R = pisurf::BondiRadius(z);
        break;
      case vtkPiMoleculeSurface::BATSANOV:
        R = pisurf::BatsanovRadius(z);
        break;
      case vtkPiMoleculeSurface::BLUE_OBELISK:
        R = z > 0 && z <= table->GetNumberOfElements() ? table->GetVDWRadius(z) : 0.0;
        break;
      default:
        R = radiusArray->GetComponent(i, 0);
        if (!(std::isfinite(R) && R > 0 && R <= MaximumExtent))
        {
          vtkErrorWithObjectMacro(
            algorithm, << "Atom " << i << " has the radius " << R << " in '"
                       << (radiusArray->GetName() ? radiusArray->GetName() : "") << "'");
          return false;
        }
    }
    if (R <= 0)
    {
      ++missing[z];
      R = z > 0 && z <= table->GetNumberOfElements() ? table->GetVDWRadius(z) : 0.0;
      if (!(R > 0))
      {
        R = 1.7; // an unknown element (X): carbon's Bondi radius
      }
    }
    radii[i] = R * radiusScale;
  }
  if (!missing.empty())
  {
    std::ostringstream list;
    for (const auto& m : missing)
    {
      list << " "
           << (m.first > 0 && m.first <= table->GetNumberOfElements() ? table->GetSymbol(m.first)
                                                                      : "X")
           << " (" << m.second << " atoms)";
    }
    vtkWarningWithObjectMacro(
      algorithm, << "No radius in the chosen table for:" << list.str()
                 << "; using the Blue Obelisk radius (1.7 Å for unknown elements)");
  }
  return true;
}
}
}
