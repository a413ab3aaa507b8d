// SPDX-License-Identifier: BSD-3-Clause
// The meshing issue's promises on the paper's models: the outer envelope, exact
// vertices, the neck radius of two blended spheres, shrinking onto the union as r -> 0,
// the same triangles as vtkSampleFunction + vtkFlyingEdges3D, and the primitives port.
#include "PiTestUtilities.h"

#include "vtkPiFlyingEdges.h"
#include "vtkPiSurface.h"
#include "vtkPiSurfaceModelReader.h"
#include "vtkPiSurfaceSource.h"

#include "vtkDataArray.h"
#include "vtkFlyingEdges3D.h"
#include "vtkMassProperties.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "vtkSampleFunction.h"

#include <string>

namespace
{
int Components(vtkPolyData* mesh)
{
  vtkNew<vtkPolyDataConnectivityFilter> connectivity;
  connectivity->SetInputData(mesh);
  connectivity->SetExtractionModeToAllRegions();
  connectivity->Update();
  return connectivity->GetNumberOfExtractedRegions();
}

std::string Model(const char* name)
{
  return pitest::ModelPath(name);
}

std::string TwoSpheres(double d, double r)
{
  return "{\"pisurf\": 1, \"blending\": " + std::to_string(r) +
    ", \"primitives\": [{\"type\": \"sphere\", \"center\": [" + std::to_string(d) +
    ", 0, 0], \"radius\": 1}, {\"type\": \"sphere\", \"center\": [" + std::to_string(-d) +
    ", 0, 0], \"radius\": 1}]}";
}
}

int TestPiMeshing(int, char*[])
{
  int failures = 0;

  // Formic acid at r = 1: one outer surface and two interior lens shells.
  vtkNew<vtkPiSurfaceModelReader> formic;
  pitest::Watch watch(formic);
  formic->SetFileName(Model("formic_acid").c_str());
  formic->OuterEnvelopeOff();
  formic->Update();
  PI_CHECK(Components(formic->GetOutput()) == 3);
  formic->OuterEnvelopeOn();
  formic->Update();
  PI_CHECK(Components(formic->GetOutput()) == 1);
  // Port 1: the three atoms, each coloured by its factor.
  vtkPolyData* atoms = formic->GetOutput(1);
  PI_CHECK(Components(atoms) == 3);
  vtkDataArray* atomFactor = atoms->GetPointData()->GetArray("Factor");
  PI_CHECK(atomFactor && atomFactor->GetRange()[0] == 0 && atomFactor->GetRange()[1] == 2);
  PI_CHECK(watch.Quiet());

  // Exact vertices on the paper's models: |F|/|∇F| <= 1e-9 × model size.
  for (const char* name : { "formic_acid", "cup_a1.0", "table", "eggplant_r0.25", "sword" })
  {
    vtkNew<vtkPiSurfaceModelReader> reader;
    reader->SetFileName(Model(name).c_str());
    reader->SetResolution(64);
    reader->GeneratePrimitivesOff();
    reader->Update();
    vtkPiSurface* surface = reader->GetPiSurface();
    double b[6];
    reader->GetOutput()->GetBounds(b);
    const double size = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
      (b[5] - b[4]) * (b[5] - b[4]));
    double worst = 0;
    vtkPolyData* mesh = reader->GetOutput();
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3], g[3];
      mesh->GetPoint(i, p);
      surface->EvaluateGradient(p, g);
      const double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      if (gn > 0)
      {
        worst = std::max(worst, std::fabs(surface->EvaluateFunction(p)) / gn);
      }
    }
    if (!(worst <= 1e-9 * size))
    {
      std::cerr << name << ": worst |F|/|grad F| = " << worst << " (size " << size << ")\n";
      ++failures;
    }
  }

  // Two spheres at ±d, r = 0.25: the neck on x = 0 has radius sqrt(1.5 − d²), within
  // 0.5% at the default resolution; d = 1.1 is still one component.
  for (double d : { 0.8, 0.9, 1.0, 1.1 })
  {
    vtkNew<vtkPiSurfaceSource> source;
    source->SetModel(TwoSpheres(d, 0.25).c_str());
    source->GeneratePrimitivesOff();
    source->Update();
    vtkPolyData* mesh = source->GetOutput();
    PI_CHECK(Components(mesh) == 1);
    // The neck: the smallest distance from the x axis over the vertices near x = 0.
    double neck = 1e9;
    double b[6];
    mesh->GetBounds(b);
    const double h = (b[1] - b[0]) / 128;
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3];
      mesh->GetPoint(i, p);
      if (std::fabs(p[0]) < h)
      {
        // Correct for the distance from the plane: on the surface near x = 0 the radius
        // grows as ρ(x) ≈ ρ0 + κx²; with |x| < h the error is far below 0.5 %.
        neck = std::min(neck, std::sqrt(p[1] * p[1] + p[2] * p[2]));
      }
    }
    const double exact = std::sqrt(1.5 - d * d);
    if (!(std::fabs(neck - exact) <= 0.005 * exact))
    {
      std::cerr << "d = " << d << ": neck " << neck << " vs " << exact << "\n";
      ++failures;
    }
  }

  // r -> 0 shrinks the envelope onto the union of the spheres: the largest distance from
  // the mesh to the union decreases over r = 1, 0.1, 0.01, 0.001.
  double previous = 1e9;
  for (double r : { 1.0, 0.1, 0.01, 0.001 })
  {
    vtkNew<vtkPiSurfaceSource> source;
    source->SetModel(TwoSpheres(0.7, r).c_str());
    source->SetBounds(-2.5, 2.5, -1.6, 1.6, -1.6, 1.6);
    source->SetResolution(160);
    source->GeneratePrimitivesOff();
    source->Update();
    vtkPolyData* mesh = source->GetOutput();
    double hausdorff = 0;
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3];
      mesh->GetPoint(i, p);
      const double d1 = std::sqrt((p[0] - 0.7) * (p[0] - 0.7) + p[1] * p[1] + p[2] * p[2]) - 1;
      const double d2 = std::sqrt((p[0] + 0.7) * (p[0] + 0.7) + p[1] * p[1] + p[2] * p[2]) - 1;
      hausdorff = std::max(hausdorff, std::fabs(std::min(d1, d2)));
    }
    if (!(hausdorff < previous))
    {
      std::cerr << "r = " << r << ": distance to the union " << hausdorff
                << " did not decrease from " << previous << "\n";
      ++failures;
    }
    std::cout << "r = " << r << ": largest distance to the union " << hausdorff << "\n";
    previous = hausdorff;
  }
  PI_CHECK(previous < 0.03); // at r = 0.001 the neck stays about sqrt(r)/2 away

  // Without projection and envelope: the same triangles as vtkSampleFunction +
  // vtkFlyingEdges3D on the same grid (the cup, whose blocks are partly skipped).
  vtkNew<vtkPiSurfaceModelReader> cup;
  cup->SetFileName(Model("cup_a1.0").c_str());
  cup->SetSampleDimensions(70, 60, 40);
  cup->ProjectVerticesOff();
  cup->OuterEnvelopeOff();
  cup->GeneratePrimitivesOff();
  cup->Update();
  double bounds[6];
  cup->GetPiSurface()->GetModelBounds(bounds);
  vtkNew<vtkSampleFunction> sample;
  sample->SetImplicitFunction(cup->GetPiSurface());
  sample->SetModelBounds(bounds);
  sample->SetSampleDimensions(70, 60, 40);
  sample->ComputeNormalsOff();
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputConnection(sample->GetOutputPort());
  contour->SetValue(0, 0.0);
  contour->Update();
  PI_CHECK(cup->GetOutput()->GetNumberOfCells() > 1000);
  PI_CHECK(cup->GetOutput()->GetNumberOfCells() == contour->GetOutput()->GetNumberOfCells());
  PI_CHECK(cup->GetOutput()->GetNumberOfPoints() == contour->GetOutput()->GetNumberOfPoints());

  // AutomaticResolution: settles where the thin table legs are all there.
  vtkNew<vtkPiSurfaceModelReader> automatic;
  automatic->SetFileName(Model("table").c_str());
  automatic->AutomaticResolutionOn();
  automatic->GeneratePrimitivesOff();
  automatic->Update();
  vtkNew<vtkPiSurfaceModelReader> fine;
  fine->SetFileName(Model("table").c_str());
  fine->SetResolution(256);
  fine->GeneratePrimitivesOff();
  fine->Update();
  std::cout << "automatic resolution for the table: " << automatic->GetLastResolution() << "\n";
  PI_CHECK(automatic->GetLastResolution() >= 64 && automatic->GetLastResolution() <= 512);
  PI_CHECK(Components(automatic->GetOutput()) == Components(fine->GetOutput()));
  vtkNew<vtkMassProperties> massAutomatic, massFine;
  massAutomatic->SetInputData(automatic->GetOutput());
  massFine->SetInputData(fine->GetOutput());
  massAutomatic->Update();
  massFine->Update();
  PI_CHECK_NEAR(
    massAutomatic->GetSurfaceArea(), massFine->GetSurfaceArea(), 0.02 * massFine->GetSurfaceArea());

  // A bad model in the source: an error naming the key, an empty output.
  vtkNew<vtkPiSurfaceSource> bad;
  pitest::Watch badWatch(bad);
  bad->SetModel("{\"pisurf\": 1, \"blending\": 0.1, \"primitives\": [{\"type\": \"torus\"}]}");
  bad->Update();
  PI_CHECK(badWatch.Error("needs the key 'major_radius'"));
  PI_CHECK(bad->GetOutput()->GetNumberOfPoints() == 0);
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
