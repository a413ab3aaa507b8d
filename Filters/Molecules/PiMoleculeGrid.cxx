// SPDX-License-Identifier: BSD-3-Clause
// PASSES 2 to 4 of vtkPiMoleculeSurface: the box, the grid and the mesh (see
// PiMoleculeSurfacePasses.h).
#include "PiMoleculeSurfacePasses.h"

#include "PiInnerAlgorithm.h"
#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPiFlyingEdges.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace pisurf
{
namespace molecule
{
bool Grid::ChooseBounds(
  vtkAlgorithm* algorithm, const Atoms& atoms, const MoleculeSettings& settings)
{
  const std::vector<double>& centers = atoms.Centers;
  const std::vector<double>& radii = atoms.Radii;
  const vtkIdType count = atoms.Count();
  const bool local = settings.Mode == MoleculeMode::Local;
  double atomBox[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (vtkIdType i = 0; i < count; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      atomBox[2 * a] = std::min(atomBox[2 * a], centers[3 * i + a] - radii[i]);
      atomBox[2 * a + 1] = std::max(atomBox[2 * a + 1], centers[3 * i + a] + radii[i]);
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!(atomBox[2 * a + 1] - atomBox[2 * a] <= MaximumExtent))
    {
      vtkErrorWithObjectMacro(algorithm, << "The atoms span " << atomBox[2 * a + 1] - atomBox[2 * a]
                                         << " Å along "
                                         << "axis " << a << ", more than " << MaximumExtent
                                         << " Å: coordinates in the wrong unit or a corrupt file?");
      return false;
    }
  }
  if (!local)
  {
    // Global mode sums every far atom once per 2 Å cell of the box (the cells are built
    // lazily, but the bounds search alone touches the faces): atoms x cells is the cost.
    double cells = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      cells *= std::ceil((atomBox[2 * a + 1] - atomBox[2 * a] + 2 * settings.NearDistance) /
                 settings.CellSize) +
        1;
    }
    cells = std::min(cells, double(1 << 21)); // MoleculeField's cap on its cells
    if (double(count) * cells > MaximumGlobalCost)
    {
      vtkErrorWithObjectMacro(algorithm,
        << "Global mode for " << count << " atoms in a box of " << cells
        << " cells would sum about " << double(count) * cells << " far-field terms (the limit is "
        << MaximumGlobalCost << "): use Mode = Local, whose cost does not grow with the molecule");
      return false;
    }
  }
  std::shared_ptr<const MoleculeField> field;
  double* bounds = this->Bounds;
  double margin = local ? settings.InfluenceRadius : 0.5;
  for (int attempt = 0;; ++attempt)
  {
    for (int a = 0; a < 6; ++a)
    {
      bounds[a] = atomBox[a] + (a % 2 ? margin : -margin);
    }
    if (local)
    {
      break; // F = 1 − level > 0 on the boundary: nothing to check (the field is built below)
    }
    field = std::make_shared<MoleculeField>(centers, radii, settings, bounds);
    bool positive = true;
    for (int a = 0; a < 3 && positive; ++a)
    {
      const int u = (a + 1) % 3, w = (a + 2) % 3;
      for (int side = 0; side < 2 && positive; ++side)
        for (int p = 0; p < 8 && positive; ++p)
          for (int q = 0; q < 8 && positive; ++q)
          {
            double tile[6];
            tile[2 * a] = tile[2 * a + 1] = bounds[2 * a + side];
            tile[2 * u] = bounds[2 * u] + p * (bounds[2 * u + 1] - bounds[2 * u]) / 8;
            tile[2 * u + 1] = bounds[2 * u] + (p + 1) * (bounds[2 * u + 1] - bounds[2 * u]) / 8;
            tile[2 * w] = bounds[2 * w] + q * (bounds[2 * w + 1] - bounds[2 * w]) / 8;
            tile[2 * w + 1] = bounds[2 * w] + (q + 1) * (bounds[2 * w + 1] - bounds[2 * w]) / 8;
            positive = field->ClassifyBox(tile) > 0;
          }
    }
    if (positive)
    {
      break;
    }
    if (attempt == 12)
    {
      vtkWarningWithObjectMacro(
        algorithm, << "F is not positive on the whole boundary of the bounds even " << margin
                   << " Å beyond the atoms: the mesh may be open (Blending " << settings.Blending
                   << " is very large)");
      break;
    }
    margin *= 2;
  }
  return true;
}

bool Grid::ChooseGrid(
  vtkAlgorithm* algorithm, const Atoms& atoms, const MoleculeSettings& settings, double spacing)
{
  double* bounds = this->Bounds;
  int* dims = this->Dims;
  double volume = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    volume *= bounds[2 * a + 1] - bounds[2 * a];
  }
  if (spacing == 0.0)
  {
    spacing = std::max(AutomaticSpacing, std::cbrt(volume / AutomaticMaximumPoints) * 1.01);
  }
  // Refused before any cast to int: a tiny Spacing or atoms far apart make huge grids.
  double samples = 1.0;
  double cells[3];
  for (int a = 0; a < 3; ++a)
  {
    cells[a] = std::ceil((bounds[2 * a + 1] - bounds[2 * a]) / spacing);
    samples *= cells[a] + 1;
  }
  const vtkIdType maximumSamples = vtkNew<vtkPiFlyingEdges>()->GetMaximumNumberOfSamples();
  if (!(samples <= static_cast<double>(maximumSamples)))
  {
    vtkErrorWithObjectMacro(algorithm,
      << "A grid of " << cells[0] + 1 << " x " << cells[1] + 1 << " x " << cells[2] + 1
      << " samples (Spacing " << spacing << " Å over a box of " << bounds[1] - bounds[0] << " x "
      << bounds[3] - bounds[2] << " x " << bounds[5] - bounds[4] << " Å) needs "
      << samples * sizeof(double) / (1 << 20) << " MiB; the limit is "
      << maximumSamples * sizeof(double) / (1 << 20) << " MiB: raise the Spacing (0 chooses it)");
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    const double side = bounds[2 * a + 1] - bounds[2 * a];
    dims[a] = static_cast<int>(cells[a]) + 1;
    // Centre the grid on the box with exactly this spacing.
    const double extra = (dims[a] - 1) * spacing - side;
    bounds[2 * a] -= 0.5 * extra;
    bounds[2 * a + 1] = bounds[2 * a] + (dims[a] - 1) * spacing;
  }
  this->Spacing = spacing;
  // The field's cells must cover the final bounds: rebuild (cheap, cells are lazy).
  this->Field = std::make_shared<MoleculeField>(atoms.Centers, atoms.Radii, settings, bounds);
  return true;
}

MeshResult Mesh(vtkAlgorithm* algorithm, const Grid& grid, bool outerEnvelope, bool projectVertices,
  int piece, int pieces, vtkPolyData* output)
{
  vtkNew<vtkPiFlyingEdges> mesher;
  mesher->SetField(grid.Field);
  mesher->SetBounds(grid.Bounds);
  mesher->SetSampleDimensions(grid.Dims);
  mesher->SetOuterEnvelope(outerEnvelope);
  mesher->SetProjectVertices(projectVertices);
  mesher->SetGeneratePrimitives(false);
  // Forward the mesher's complaints (a grid too large, an empty mesh) as ours.
  vtkNew<vtkCallbackCommand> forward;
  struct Messages
  {
    std::string Error, Warning;
  } messages;
  forward->SetClientData(&messages);
  forward->SetCallback(
    [](vtkObject*, unsigned long event, void* client, void* data)
    {
      auto* m = static_cast<Messages*>(client);
      (event == vtkCommand::ErrorEvent ? m->Error : m->Warning) = static_cast<const char*>(data);
    });
  mesher->AddObserver(vtkCommand::ErrorEvent, forward);
  mesher->AddObserver(vtkCommand::WarningEvent, forward);
  // The mesher is most of the time: its progress is ours (from 0.05 to 0.95), and a
  // cancel of this filter (AbortExecute, ParaView's cancel button) stops it.
  pisurf::WorkFor(mesher, algorithm, 0.05, 0.9);
  algorithm->UpdateProgress(0.05);
  // Piece p of n: the mesher's slab p of the grid; the union of the pieces is the
  // one-piece mesh.
  mesher->UpdatePiece(piece, pieces, 0);
  if (algorithm->CheckAbort())
  {
    return MeshResult::Cancelled;
  }
  if (!messages.Error.empty())
  {
    vtkErrorWithObjectMacro(algorithm, << "Meshing failed: " << messages.Error);
    return MeshResult::Failed;
  }
  if (!messages.Warning.empty())
  {
    vtkWarningWithObjectMacro(algorithm, << messages.Warning);
  }
  output->ShallowCopy(mesher->GetOutput());
  // (Lens-shaped shells where atoms overlap are bounded components of {F > 0}: the
  // envelope never enters them, see pisurf::MoleculeField::OffOuterSide.)
  return MeshResult::Meshed;
}
}
}
