// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiMoleculeSurface.h"
#include "Molecules/PiMoleculeSurfacePasses.h"
#include "PiPieces.h"
#include "PiTiming.h"

#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <cmath>

vtkStandardNewMacro(vtkPiMoleculeSurface);

vtkPiMoleculeSurface::vtkPiMoleculeSurface()
{
  // RadiusTable = POINT_ARRAY reads this array (ParaView's PDB reader writes "radius").
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "radius");
}
vtkPiMoleculeSurface::~vtkPiMoleculeSurface() = default;

int vtkPiMoleculeSurface::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMolecule");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkPiMoleculeSurface::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Pieces are the mesher's slabs of the grid (ParaView's MPI mode: one per rank).
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkPiMoleculeSurface::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Every piece needs every atom (the grid, the far field and the envelope are the whole
  // molecule's): ask for the whole input. Readers that do not split molecules (this
  // plugin's, VTK's CML and XYZ readers, ParaView's PDB reader) give only their first
  // piece a molecule, so each rank asks for that one.
  pisurf::RequestWholeInput(inputVector[0]);
  return 1;
}

int vtkPiMoleculeSurface::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  namespace molecule = pisurf::molecule;
  // PISURF_TIMING=1: the wall time of each pass on stderr.
  pisurf::PassTimer lap("vtkPiMoleculeSurface");
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  const pisurf::Piece request = pisurf::PieceOf(outputVector->GetInformationObject(0));
  if (!std::isfinite(this->Blending) || this->Blending < 0)
  {
    vtkErrorMacro(<< "Blending must be a finite number >= 0, not " << this->Blending);
    return 0;
  }
  if (!std::isfinite(this->InfluenceRadius) ||
    !(this->InfluenceRadius >= molecule::MinimumInfluenceRadius))
  {
    vtkErrorMacro(<< "InfluenceRadius must be a finite number >= "
                  << molecule::MinimumInfluenceRadius << " Å, not " << this->InfluenceRadius);
    return 0;
  }
  if (!std::isfinite(this->Spacing) || this->Spacing < 0)
  {
    vtkErrorMacro(<< "Spacing must be 0 (automatic) or a positive number of Å, not "
                  << this->Spacing);
    return 0;
  }

  // PASS 1: the atoms and their radii.
  molecule::Atoms atoms;
  vtkDataArray* chosen =
    this->RadiusTable == POINT_ARRAY ? this->GetInputArrayToProcess(0, inputVector) : nullptr;
  if (!atoms.Read(this, input, this->RadiusTable, chosen, this->RadiusScale))
  {
    return 0;
  }
  pisurf::MoleculeSettings settings;
  settings.Mode = this->Mode == LOCAL ? pisurf::MoleculeMode::Local : pisurf::MoleculeMode::Global;
  settings.Blending = this->Blending;
  settings.InfluenceRadius = this->InfluenceRadius;

  // PASS 2: the box the surface lies in.
  molecule::Grid grid;
  if (!grid.ChooseBounds(this, atoms, settings))
  {
    return 0;
  }
  lap("radii and bounds");
  // PASS 3: the grid over it.
  if (!grid.ChooseGrid(this, atoms, settings, this->Spacing))
  {
    return 0;
  }
  this->LastSpacing = grid.Spacing;
  lap("grid");

  // PASS 4: the mesh (piece p of n: the mesher's slab p of the grid; the union of the
  // pieces is the one-piece mesh).
  switch (molecule::Mesh(
    this, grid, this->OuterEnvelope, this->ProjectVertices, request.Piece, request.Pieces, output))
  {
    case molecule::MeshResult::Failed:
      return 0;
    case molecule::MeshResult::Cancelled:
      return 1; // the executive empties the output
    case molecule::MeshResult::Meshed:
      break;
  }
  lap("mesh");

  // PASS 5: attributes, the molecule for further filters, area and volume.
  molecule::WriteOutput(atoms, grid, settings, request.Pieces, output);
  lap("attributes, model, area and volume");
  return 1;
}

void vtkPiMoleculeSurface::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RadiusTable: " << this->RadiusTable << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "Mode: " << (this->Mode == LOCAL ? "Local" : "Global") << "\n";
  os << indent << "Blending: " << this->Blending << "\n";
  os << indent << "InfluenceRadius: " << this->InfluenceRadius << "\n";
  os << indent << "Spacing: " << this->Spacing << "\n";
  os << indent << "OuterEnvelope: " << (this->OuterEnvelope ? "On" : "Off") << "\n";
  os << indent << "ProjectVertices: " << (this->ProjectVertices ? "On" : "Off") << "\n";
  os << indent << "LastSpacing: " << this->LastSpacing << "\n";
}
