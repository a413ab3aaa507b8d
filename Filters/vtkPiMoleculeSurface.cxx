// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiMoleculeSurface.h"
#include "PiInnerAlgorithm.h"
#include "PiLargeArrays.h"
#include "PiPieces.h"
#include "PiTiming.h"

#include "PiModel.h"
#include "PiMoleculeField.h"
#include "vtkPiFlyingEdges.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkMath.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkCellArray.h"
#include "vtkSMPTools.h"
#include "vtkMolecule.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPeriodicTable.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

vtkStandardNewMacro(vtkPiMoleculeSurface);

namespace
{
// Global mode writes the model as .pisurf JSON up to this many atoms (beyond, only the
// compact arrays).
constexpr vtkIdType MaximumJsonAtoms = 10000;
// Automatic spacing: 0.25 Å unless the grid would exceed this many points.
constexpr double AutomaticSpacing = 0.25;
constexpr double AutomaticMaximumPoints = 16777216.0; // 2^24
constexpr double MaximumExtent = 1e6;                  // Å
constexpr double MinimumInfluenceRadius = 1e-3;          // Å
// Global mode: atoms x far-field cells, about a minute of sums on two cores.
constexpr double MaximumGlobalCost = 1e10;
}

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

namespace
{
// The mesh's area and the volume it encloses, Σ p0·(p1 × p2)/6 over its triangles (the
// divergence theorem; the triangles face ∇F, outwards on the outer envelope, so this is
// the volume of {F < 0} inside it, lens-shaped shells subtracted when OuterEnvelope is
// off). Threaded over fixed chunks of triangles whose sums are added in order: the same
// bits with any number of threads.
template <class Ids>
void AreaAndVolumeOf(vtkPoints* points, Ids* offsets, Ids* connectivity, double& area, double& volume)
{
  vtkDoubleArray* coordinates = vtkDoubleArray::SafeDownCast(points->GetData());
  const vtkIdType cellCount = offsets->GetNumberOfValues() - 1;
  const auto* offset = offsets->GetPointer(0);
  const auto* ids = connectivity->GetPointer(0);
  constexpr vtkIdType Chunk = 1 << 16;
  const vtkIdType chunks = (cellCount + Chunk - 1) / Chunk;
  std::vector<double> areas(chunks), volumes(chunks);
  vtkSMPTools::For(0, chunks, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType c = begin; c < end; ++c)
    {
      double a = 0.0, v = 0.0;
      for (vtkIdType t = c * Chunk; t < std::min(cellCount, (c + 1) * Chunk); ++t)
      {
        if (offset[t + 1] - offset[t] != 3)
        {
          continue; // the mesher makes triangles only
        }
        double p[3][3];
        for (int m = 0; m < 3; ++m)
        {
          const vtkIdType id = static_cast<vtkIdType>(ids[offset[t] + m]);
          if (coordinates)
          {
            const double* x = coordinates->GetPointer(3 * id);
            p[m][0] = x[0];
            p[m][1] = x[1];
            p[m][2] = x[2];
          }
          else
          {
            points->GetPoint(id, p[m]);
          }
        }
        const double e1[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
        const double e2[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
        double n[3];
        vtkMath::Cross(e1, e2, n);
        a += 0.5 * vtkMath::Norm(n);
        double q[3];
        vtkMath::Cross(p[1], p[2], q);
        v += vtkMath::Dot(p[0], q) / 6.0;
      }
      areas[c] = a;
      volumes[c] = v;
    }
  });
  area = volume = 0.0;
  for (vtkIdType c = 0; c < chunks; ++c)
  {
    area += areas[c];
    volume += volumes[c];
  }
}

void AreaAndVolume(vtkPolyData* mesh, double& area, double& volume)
{
  vtkCellArray* polys = mesh->GetPolys();
  if (polys->IsStorage64Bit())
  {
    AreaAndVolumeOf(mesh->GetPoints(), polys->GetOffsetsArray64(),
      polys->GetConnectivityArray64(), area, volume);
  }
  else
  {
    AreaAndVolumeOf(mesh->GetPoints(), polys->GetOffsetsArray32(),
      polys->GetConnectivityArray32(), area, volume);
  }
}
}

int vtkPiMoleculeSurface::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // PISURF_TIMING=1: the wall time of each pass on stderr.
  pisurf::PassTimer lap("vtkPiMoleculeSurface");
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const pisurf::Piece request = pisurf::PieceOf(outInfo);
  const int piece = request.Piece, pieces = request.Pieces;
  if (!std::isfinite(this->Blending) || this->Blending < 0)
  {
    vtkErrorMacro(<< "Blending must be a finite number >= 0, not " << this->Blending);
    return 0;
  }
  // Below 0.001 Å the factors jump from the sphere's value to 1 within the rounding of
  // the grid's roots (at 1e-20 Å, ρ = R in doubles): no blend is left to mesh.
  if (!std::isfinite(this->InfluenceRadius) || !(this->InfluenceRadius >= MinimumInfluenceRadius))
  {
    vtkErrorMacro(<< "InfluenceRadius must be a finite number >= " << MinimumInfluenceRadius
                  << " Å, not " << this->InfluenceRadius);
    return 0;
  }
  if (!std::isfinite(this->Spacing) || this->Spacing < 0)
  {
    vtkErrorMacro(<< "Spacing must be 0 (automatic) or a positive number of Å, not "
                  << this->Spacing);
    return 0;
  }

  // The atoms: positions, atomic numbers, and the point data (for a radius array).
  vtkNew<vtkPoints> atoms;
  std::vector<int> numbers;
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
    if (n > 0 && !z && this->RadiusTable != POINT_ARRAY)
    {
      vtkErrorMacro(<< "The input polydata has no point array 'atom_type' or 'AtomicNumber' "
                       "(atomic numbers); use RadiusTable = point array with a radius array");
      return 0;
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
    vtkErrorMacro(<< "The input must be a vtkMolecule or a vtkPolyData of atoms");
    return 0;
  }
  const vtkIdType count = atoms->GetNumberOfPoints();
  if (count == 0)
  {
    vtkErrorMacro(<< "The input molecule has no atoms");
    return 0;
  }

  // PASS 1: radii.
  std::vector<double> centers(3 * count), radii(count);
  vtkNew<vtkPeriodicTable> table;
  vtkDataArray* radiusArray = nullptr;
  if (this->RadiusTable == POINT_ARRAY)
  {
    radiusArray = this->GetInputArrayToProcess(0, inputVector);
    if (!radiusArray && atomData)
    {
      radiusArray = atomData->GetArray("radius");
    }
    if (!radiusArray)
    {
      vtkErrorMacro(<< "RadiusTable is a point array, but the input has no such array "
                       "(set the input array to process, e.g. 'radius')");
      return 0;
    }
    if (radiusArray->GetNumberOfTuples() != count)
    {
      vtkErrorMacro(<< "The radius array '" << (radiusArray->GetName() ? radiusArray->GetName() : "")
                    << "' has " << radiusArray->GetNumberOfTuples() << " values for " << count
                    << " atoms");
      return 0;
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
        vtkErrorMacro(<< "Atom " << i << " has a coordinate that is not a finite number");
        return 0;
      }
    }
    const int z = numbers[i];
    double R = 0.0;
    switch (this->RadiusTable)
    {
      case BONDI:
        R = pisurf::BondiRadius(z);
        break;
      case BATSANOV:
        R = pisurf::BatsanovRadius(z);
        break;
      case BLUE_OBELISK:
        R = z > 0 && z <= table->GetNumberOfElements() ? table->GetVDWRadius(z) : 0.0;
        break;
      default:
        R = radiusArray->GetComponent(i, 0);
        if (!(std::isfinite(R) && R > 0 && R <= MaximumExtent))
        {
          vtkErrorMacro(<< "Atom " << i << " has the radius " << R << " in '"
                        << (radiusArray->GetName() ? radiusArray->GetName() : "") << "'");
          return 0;
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
    radii[i] = R * this->RadiusScale;
  }
  if (!missing.empty())
  {
    std::ostringstream list;
    for (const auto& m : missing)
    {
      list << " " << (m.first > 0 && m.first <= table->GetNumberOfElements() ? table->GetSymbol(m.first) : "X")
           << " (" << m.second << " atoms)";
    }
    vtkWarningMacro(<< "No radius in the chosen table for:" << list.str()
                    << "; using the Blue Obelisk radius (1.7 Å for unknown elements)");
  }

  pisurf::MoleculeSettings settings;
  settings.Mode = this->Mode == LOCAL ? pisurf::MoleculeMode::Local : pisurf::MoleculeMode::Global;
  settings.Blending = this->Blending;
  settings.InfluenceRadius = this->InfluenceRadius;

  // PASS 2: bounds. The atoms' boxes, grown until F > 0 on the whole boundary (checked
  // with interval bounds on 8 x 8 tiles of each face). Local: F = 1 − level > 0 beyond
  // every atom's influence, so R + InfluenceRadius always suffices.
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
    // Real molecules span at most a few thousand Å; beyond this, spacings and cell
    // sizes stop being meaningful (and products of extents overflow).
    if (!(atomBox[2 * a + 1] - atomBox[2 * a] <= MaximumExtent))
    {
      vtkErrorMacro(<< "The atoms span " << atomBox[2 * a + 1] - atomBox[2 * a] << " Å along "
                    << "axis " << a << ", more than " << MaximumExtent
                    << " Å: coordinates in the wrong unit or a corrupt file?");
      return 0;
    }
  }
  if (this->Mode == GLOBAL)
  {
    // Global mode sums every far atom once per 2 Å cell of the box (the cells are built
    // lazily, but the bounds search alone touches the faces): atoms x cells is the cost.
    double cells = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      cells *= std::ceil((atomBox[2 * a + 1] - atomBox[2 * a] + 2 * settings.NearDistance) /
                 settings.CellSize) + 1;
    }
    cells = std::min(cells, double(1 << 21)); // MoleculeField's cap on its cells
    if (double(count) * cells > MaximumGlobalCost)
    {
      vtkErrorMacro(<< "Global mode for " << count << " atoms in a box of " << cells
                    << " cells would sum about " << double(count) * cells
                    << " far-field terms (the limit is " << MaximumGlobalCost
                    << "): use Mode = Local, whose cost does not grow with the molecule");
      return 0;
    }
  }
  std::shared_ptr<const pisurf::MoleculeField> field;
  double bounds[6];
  double margin = this->Mode == LOCAL ? this->InfluenceRadius : 0.5;
  for (int attempt = 0;; ++attempt)
  {
    for (int a = 0; a < 6; ++a)
    {
      bounds[a] = atomBox[a] + (a % 2 ? margin : -margin);
    }
    if (this->Mode == LOCAL)
    {
      break; // F = 1 − level > 0 on the boundary: nothing to check (the field is built below)
    }
    field = std::make_shared<pisurf::MoleculeField>(centers, radii, settings, bounds);
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
      vtkWarningMacro(<< "F is not positive on the whole boundary of the bounds even "
                      << margin << " Å beyond the atoms: the mesh may be open (Blending "
                      << this->Blending << " is very large)");
      break;
    }
    margin *= 2;
  }

  lap("radii and bounds");
  // PASS 3: the grid. Automatic spacing: 0.25 Å, coarser if the grid would exceed 2^24
  // points.
  double volume = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    volume *= bounds[2 * a + 1] - bounds[2 * a];
  }
  double spacing = this->Spacing;
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
    vtkErrorMacro(<< "A grid of " << cells[0] + 1 << " x " << cells[1] + 1 << " x "
                  << cells[2] + 1 << " samples (Spacing " << spacing << " Å over a box of "
                  << bounds[1] - bounds[0] << " x " << bounds[3] - bounds[2] << " x "
                  << bounds[5] - bounds[4] << " Å) needs " << samples * sizeof(double) / (1 << 20)
                  << " MiB; the limit is " << maximumSamples * sizeof(double) / (1 << 20)
                  << " MiB: raise the Spacing (0 chooses it)");
    return 0;
  }
  int dims[3];
  for (int a = 0; a < 3; ++a)
  {
    const double side = bounds[2 * a + 1] - bounds[2 * a];
    dims[a] = static_cast<int>(cells[a]) + 1;
    // Centre the grid on the box with exactly this spacing.
    const double extra = (dims[a] - 1) * spacing - side;
    bounds[2 * a] -= 0.5 * extra;
    bounds[2 * a + 1] = bounds[2 * a] + (dims[a] - 1) * spacing;
  }
  this->LastSpacing = spacing;
  // The field's cells must cover the final bounds: rebuild (cheap, cells are lazy).
  field = std::make_shared<pisurf::MoleculeField>(centers, radii, settings, bounds);

  lap("grid");
  // PASS 4: mesh with the Pi-surface mesher.
  vtkNew<vtkPiFlyingEdges> mesher;
  mesher->SetField(field);
  mesher->SetBounds(bounds);
  mesher->SetSampleDimensions(dims);
  mesher->SetOuterEnvelope(this->OuterEnvelope);
  mesher->SetProjectVertices(this->ProjectVertices);
  mesher->SetGeneratePrimitives(false);
  // Forward the mesher's complaints (a grid too large, an empty mesh) as ours.
  vtkNew<vtkCallbackCommand> forward;
  struct Messages
  {
    std::string Error, Warning;
  } messages;
  forward->SetClientData(&messages);
  forward->SetCallback([](vtkObject*, unsigned long event, void* client, void* data) {
    auto* m = static_cast<Messages*>(client);
    (event == vtkCommand::ErrorEvent ? m->Error : m->Warning) = static_cast<const char*>(data);
  });
  mesher->AddObserver(vtkCommand::ErrorEvent, forward);
  mesher->AddObserver(vtkCommand::WarningEvent, forward);
  // The mesher is most of the time: its progress is ours (from 0.05 to 0.95), and a
  // cancel of this filter (AbortExecute, ParaView's cancel button) stops it.
  pisurf::WorkFor(mesher, this, 0.05, 0.9);
  this->UpdateProgress(0.05);
  // Piece p of n: the mesher's slab p of the grid; the union of the pieces is the
  // one-piece mesh.
  mesher->UpdatePiece(piece, pieces, 0);
  if (this->CheckAbort())
  {
    return 1; // cancelled: the executive empties the output
  }
  if (!messages.Error.empty())
  {
    vtkErrorMacro(<< "Meshing failed: " << messages.Error);
    return 0;
  }
  if (!messages.Warning.empty())
  {
    vtkWarningMacro(<< messages.Warning);
  }
  output->ShallowCopy(mesher->GetOutput());
  // (Lens-shaped shells where atoms overlap are bounded components of {F > 0}: the
  // envelope never enters them, see pisurf::MoleculeField::OffOuterSide.)

  lap("mesh");
  // PASS 5: attributes.
  vtkIntArray* factor = vtkIntArray::SafeDownCast(output->GetPointData()->GetArray("Factor"));
  vtkNew<vtkIntArray> atomicNumber;
  atomicNumber->SetName("AtomicNumber");
  const vtkIdType points = output->GetNumberOfPoints();
  pisurf::AllocateLargeArray(atomicNumber.GetPointer(), points);
  int* numberOut = atomicNumber->GetPointer(0);
  const int* atomOf = factor ? factor->GetPointer(0) : nullptr;
  vtkSMPTools::For(0, points, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType v = begin; v < end; ++v)
    {
      const int atom = atomOf ? atomOf[v] : -1;
      numberOut[v] = atom >= 0 && atom < count ? numbers[atom] : 0;
    }
  });
  output->GetPointData()->AddArray(atomicNumber);

  vtkFieldData* fd = output->GetFieldData();
  vtkNew<vtkDoubleArray> centerArray;
  centerArray->SetName("PiMoleculeCenters");
  centerArray->SetNumberOfComponents(3);
  centerArray->SetNumberOfTuples(count);
  vtkNew<vtkDoubleArray> radiusOut;
  radiusOut->SetName("PiMoleculeRadii");
  radiusOut->SetNumberOfTuples(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    centerArray->SetTypedTuple(i, &centers[3 * i]);
    radiusOut->SetValue(i, radii[i]);
  }
  fd->AddArray(centerArray);
  fd->AddArray(radiusOut);
  // With the mode, r, the influence radius and the bounds: Pi Ray Cast, Image Based
  // Triangulation and Pi Sample Function rebuild the field from these (pisurf::InputSurface.h),
  // for any size and either mode.
  vtkNew<vtkDoubleArray> settingsOut;
  settingsOut->SetName("PiMoleculeSettings");
  settingsOut->SetNumberOfTuples(9);
  const double settingValues[9] = { this->Mode == LOCAL ? 1.0 : 0.0, this->Blending,
    this->InfluenceRadius, bounds[0], bounds[1], bounds[2], bounds[3], bounds[4], bounds[5] };
  for (int k = 0; k < 9; ++k)
  {
    settingsOut->SetValue(k, settingValues[k]);
  }
  fd->AddArray(settingsOut);
  if (this->Mode == GLOBAL && count <= MaximumJsonAtoms)
  {
    pisurf::Model model;
    model.Name = "molecule";
    model.Blending = this->Blending;
    model.HasBounds = true;
    std::copy(bounds, bounds + 6, model.Bounds);
    model.Primitives.resize(count);
    for (vtkIdType i = 0; i < count; ++i)
    {
      pisurf::PrimitiveSpec& s = model.Primitives[i];
      s.Type = pisurf::PrimitiveType::Sphere;
      std::copy(&centers[3 * i], &centers[3 * i] + 3, s.Center);
      s.Radius = radii[i];
    }
    vtkNew<vtkStringArray> json;
    json->SetName("PiSurfaceModel");
    json->InsertNextValue(pisurf::WriteModel(model));
    fd->AddArray(json);
  }
  lap("attributes and model");
  // The area and volume of the whole surface (a piece's share of them would mislead:
  // in parallel runs use Integrate Variables).
  if (output->GetNumberOfCells() > 0 && pieces == 1)
  {
    double surfaceArea, volume;
    AreaAndVolume(output, surfaceArea, volume);
    vtkNew<vtkDoubleArray> area, enclosed;
    area->SetName("SurfaceArea");
    area->InsertNextValue(surfaceArea);
    enclosed->SetName("EnclosedVolume");
    enclosed->InsertNextValue(volume);
    fd->AddArray(area);
    fd->AddArray(enclosed);
  }
  lap("area and volume");
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
