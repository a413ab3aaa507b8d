// SPDX-License-Identifier: BSD-3-Clause
// PASS 5 of vtkPiMoleculeSurface: the output's attributes, the molecule for further
// filters, and the area and volume (see PiMoleculeSurfacePasses.h).
#include "PiMoleculeSurfacePasses.h"

#include "PiLargeArrays.h"
#include "PiModel.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <vector>

namespace pisurf
{
namespace molecule
{
namespace
{
// The mesh's area and the volume it encloses, Σ p0·(p1 × p2)/6 over its triangles (the
// divergence theorem; the triangles face ∇F, outwards on the outer envelope, so this is
// the volume of {F < 0} inside it, lens-shaped shells subtracted when OuterEnvelope is
// off). Threaded over fixed chunks of triangles whose sums are added in order: the same
// bits with any number of threads.
template <class Ids>
void AreaAndVolumeOf(
  vtkPoints* points, Ids* offsets, Ids* connectivity, double& area, double& volume)
{
  vtkDoubleArray* coordinates = vtkDoubleArray::SafeDownCast(points->GetData());
  const vtkIdType cellCount = offsets->GetNumberOfValues() - 1;
  const auto* offset = offsets->GetPointer(0);
  const auto* ids = connectivity->GetPointer(0);
  constexpr vtkIdType Chunk = 1 << 16;
  const vtkIdType chunks = (cellCount + Chunk - 1) / Chunk;
  std::vector<double> areas(chunks), volumes(chunks);
  vtkSMPTools::For(0, chunks,
    [&](vtkIdType begin, vtkIdType end)
    {
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
    AreaAndVolumeOf(
      mesh->GetPoints(), polys->GetOffsetsArray64(), polys->GetConnectivityArray64(), area, volume);
  }
  else
  {
    AreaAndVolumeOf(
      mesh->GetPoints(), polys->GetOffsetsArray32(), polys->GetConnectivityArray32(), area, volume);
  }
}
}

void WriteOutput(const Atoms& atoms, const Grid& grid, const MoleculeSettings& settings, int pieces,
  vtkPolyData* output)
{
  const vtkIdType count = atoms.Count();
  const std::vector<int>& numbers = atoms.Numbers;
  const std::vector<double>& centers = atoms.Centers;
  const std::vector<double>& radii = atoms.Radii;
  const double* bounds = grid.Bounds;
  const bool local = settings.Mode == MoleculeMode::Local;
  vtkIntArray* factor = vtkIntArray::SafeDownCast(output->GetPointData()->GetArray("Factor"));
  vtkNew<vtkIntArray> atomicNumber;
  atomicNumber->SetName("AtomicNumber");
  const vtkIdType points = output->GetNumberOfPoints();
  AllocateLargeArray(atomicNumber.GetPointer(), points);
  int* numberOut = atomicNumber->GetPointer(0);
  const int* atomOf = factor ? factor->GetPointer(0) : nullptr;
  vtkSMPTools::For(0, points,
    [&](vtkIdType begin, vtkIdType end)
    {
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
  const double settingValues[9] = { local ? 1.0 : 0.0, settings.Blending, settings.InfluenceRadius,
    bounds[0], bounds[1], bounds[2], bounds[3], bounds[4], bounds[5] };
  for (int k = 0; k < 9; ++k)
  {
    settingsOut->SetValue(k, settingValues[k]);
  }
  fd->AddArray(settingsOut);
  if (!local && count <= MaximumJsonAtoms)
  {
    Model model;
    model.Name = "molecule";
    model.Blending = settings.Blending;
    model.HasBounds = true;
    std::copy(bounds, bounds + 6, model.Bounds);
    model.Primitives.resize(count);
    for (vtkIdType i = 0; i < count; ++i)
    {
      PrimitiveSpec& s = model.Primitives[i];
      s.Type = PrimitiveType::Sphere;
      std::copy(&centers[3 * i], &centers[3 * i] + 3, s.Center);
      s.Radius = radii[i];
    }
    vtkNew<vtkStringArray> json;
    json->SetName("PiSurfaceModel");
    json->InsertNextValue(WriteModel(model));
    fd->AddArray(json);
  }
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
}
}
}
