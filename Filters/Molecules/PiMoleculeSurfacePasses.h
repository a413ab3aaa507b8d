// SPDX-License-Identifier: BSD-3-Clause
// The passes of vtkPiMoleculeSurface, in order: read the atoms and their radii (PASS 1),
// choose the box the surface lies in (PASS 2) and the grid over it (PASS 3), mesh the
// molecule's field with vtkPiFlyingEdges (PASS 4), write the output's attributes, the
// molecule for further filters and its area and volume (PASS 5). Each reports its
// errors on the algorithm it is given and returns false after one.
#ifndef PiMoleculeSurfacePasses_h
#define PiMoleculeSurfacePasses_h

#include "PiMoleculeField.h"
#include "vtkType.h"

#include <memory>
#include <vector>

class vtkAlgorithm;
class vtkDataArray;
class vtkDataObject;
class vtkPolyData;

namespace pisurf
{
namespace molecule
{
// Real molecules span at most a few thousand Å; beyond this, spacings and cell sizes
// stop being meaningful (and products of extents overflow).
constexpr double MaximumExtent = 1e6; // Å
// Below this the factors jump from the sphere's value to 1 within the rounding of the
// grid's roots (at 1e-20 Å, ρ = R in doubles): no blend is left to mesh.
constexpr double MinimumInfluenceRadius = 1e-3; // Å
// Global mode: atoms x far-field cells, about a minute of sums on two cores.
constexpr double MaximumGlobalCost = 1e10;
// Automatic spacing: 0.25 Å unless the grid would exceed this many points.
constexpr double AutomaticSpacing = 0.25;
constexpr double AutomaticMaximumPoints = 16777216.0; // 2^24
// Global mode writes the model as .pisurf JSON up to this many atoms (beyond, only the
// compact arrays).
constexpr vtkIdType MaximumJsonAtoms = 10000;

/// PASS 1: the atoms of a vtkMolecule or of a polydata of atoms (point array
/// `atom_type` or `AtomicNumber`), with their radii from `radiusTable`
/// (vtkPiMoleculeSurface::RadiusTables) times `radiusScale`. With POINT_ARRAY the radii
/// come from `chosen`, else from the input's point array `radius`. An element missing
/// from the table takes its Blue Obelisk radius, with one warning.
struct Atoms
{
  std::vector<double> Centers; // 3 per atom, Å
  std::vector<double> Radii;   // Å
  std::vector<int> Numbers;    // atomic numbers (0: unknown)

  bool Read(vtkAlgorithm* algorithm, vtkDataObject* input, int radiusTable, vtkDataArray* chosen,
    double radiusScale);
  vtkIdType Count() const { return static_cast<vtkIdType>(this->Radii.size()); }
};

/// PASSES 2 and 3: the box and the grid the surface is meshed on, and the field over it.
struct Grid
{
  double Bounds[6];
  int Dims[3];
  double Spacing;
  std::shared_ptr<const MoleculeField> Field;

  /// PASS 2: the atoms' boxes, grown until F > 0 on the whole boundary (checked with
  /// interval bounds on 8 × 8 tiles of each face). Local: F = 1 − level > 0 beyond every
  /// atom's influence, so R + InfluenceRadius always suffices. Refuses atoms spread over
  /// more than MaximumExtent and Global molecules whose far field costs more than
  /// MaximumGlobalCost.
  bool ChooseBounds(vtkAlgorithm* algorithm, const Atoms& atoms, const MoleculeSettings& settings);
  /// PASS 3: `spacing` (0: AutomaticSpacing, coarser if the grid would exceed
  /// AutomaticMaximumPoints), the grid centred on the box with exactly that spacing,
  /// and the field's cells over it. Refuses grids over the mesher's sample cap.
  bool ChooseGrid(
    vtkAlgorithm* algorithm, const Atoms& atoms, const MoleculeSettings& settings, double spacing);
};

/// PASS 4: the field meshed on the grid by vtkPiFlyingEdges (piece `piece` of `pieces`:
/// its slab of the grid), into `output`. The mesher's errors and warnings are reported
/// as the algorithm's, its progress is the algorithm's from 0.05 to 0.95, and a cancel
/// of the algorithm stops it.
enum class MeshResult
{
  Failed,
  Cancelled,
  Meshed
};
MeshResult Mesh(vtkAlgorithm* algorithm, const Grid& grid, bool outerEnvelope, bool projectVertices,
  int piece, int pieces, vtkPolyData* output);

/// PASS 5: the point array `AtomicNumber` (from the mesher's `Factor`, the nearest atom),
/// the field data Pi Ray Cast, Image Based Triangulation and Pi Sample Function rebuild
/// the field from (`PiMoleculeCenters`, `PiMoleculeRadii`, `PiMoleculeSettings`; see
/// PiInputSurface.h), in Global mode up to MaximumJsonAtoms the model as
/// `PiSurfaceModel`, and for a whole surface (one piece) `SurfaceArea` and
/// `EnclosedVolume`.
void WriteOutput(const Atoms& atoms, const Grid& grid, const MoleculeSettings& settings, int pieces,
  vtkPolyData* output);
}
}

#endif
