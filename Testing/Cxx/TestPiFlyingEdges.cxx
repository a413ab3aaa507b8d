// SPDX-License-Identifier: BSD-3-Clause
// vtkPiFlyingEdges: a closed mesh on the surface with exact normals and factor
// indices, bad settings refused with clear errors, and products of 10^4 factors.
#include "PiTestUtilities.h"

#include "vtkPiFlyingEdges.h"
#include "vtkPiPrimitive.h"
#include "vtkPiSurface.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFeatureEdges.h"
#include "vtkFieldData.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "vtkPolyDataNormals.h"
#include "vtkStringArray.h"

int TestPiFlyingEdges(int, char*[])
{
  int failures = 0;
  // The paper's two spheres, d = 0.9, r = 0.25.
  vtkNew<vtkPiSurface> surface;
  for (double d : { 0.9, -0.9 })
  {
    vtkNew<vtkPiPrimitive> s;
    s->SetCenter(d, 0, 0);
    surface->AddFactor(s);
  }
  surface->SetBlending(0.25);
  vtkNew<vtkPiFlyingEdges> mesher;
  pitest::Watch watch(mesher);
  mesher->SetPiSurface(surface);
  mesher->SetResolution(96);
  mesher->Update();
  PI_CHECK(watch.Quiet());
  vtkPolyData* mesh = mesher->GetOutput();
  PI_CHECK(mesh->GetNumberOfPolys() > 1000);
  // Ids that fit 32 bits: vtkCellArray's 32-bit storage, as documented.
  PI_CHECK(!mesh->GetPolys()->IsStorage64Bit());

  // Closed, one component.
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(mesh);
  edges->BoundaryEdgesOn();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->NonManifoldEdgesOn();
  edges->Update();
  PI_CHECK(edges->GetOutput()->GetNumberOfCells() == 0);
  vtkNew<vtkPolyDataConnectivityFilter> connectivity;
  connectivity->SetInputData(mesh);
  connectivity->SetExtractionModeToAllRegions();
  connectivity->Update();
  PI_CHECK(connectivity->GetNumberOfExtractedRegions() == 1);

  // Vertices near F = 0 (within a cell), unit normals along the gradient, factors 0/1.
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  vtkDataArray* factor = mesh->GetPointData()->GetArray("Factor");
  PI_CHECK(normals && factor);
  const double h = 5.0 / 96; // cell size along x
  double maxDistance = 0;
  for (vtkIdType i = 0; normals && factor && i < mesh->GetNumberOfPoints(); i += 7)
  {
    double p[3], g[3], n[3];
    mesh->GetPoint(i, p);
    surface->EvaluateGradient(p, g);
    normals->GetTuple(i, n);
    const double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    maxDistance = std::max(maxDistance, std::fabs(surface->EvaluateFunction(p)) / gn);
    PI_CHECK_NEAR(n[0] * g[0] / gn + n[1] * g[1] / gn + n[2] * g[2] / gn, 1.0, 1e-6);
    const int expected = p[0] > 0.05 ? 0 : (p[0] < -0.05 ? 1 : -1);
    if (expected >= 0)
    {
      PI_CHECK(factor->GetTuple1(i) == expected);
    }
  }
  PI_CHECK_NEAR(maxDistance, 0.0, 1e-12 * 6); // projected onto F = 0
  // Triangles face the same way as the normals (towards increasing F).
  vtkNew<vtkPolyDataNormals> faceNormals;
  faceNormals->SetInputData(mesh);
  faceNormals->ComputeCellNormalsOn();
  faceNormals->ComputePointNormalsOff();
  faceNormals->ConsistencyOff();
  faceNormals->AutoOrientNormalsOff();
  faceNormals->SplittingOff();
  faceNormals->Update();
  vtkDataArray* cellNormals = faceNormals->GetOutput()->GetCellData()->GetNormals();
  int misoriented = 0;
  for (vtkIdType c = 0; cellNormals && c < mesh->GetNumberOfCells(); ++c)
  {
    const vtkIdType* ids;
    vtkIdType npts;
    mesh->GetCellPoints(c, npts, ids);
    double nc[3], nv[3];
    cellNormals->GetTuple(c, nc);
    normals->GetTuple(ids[0], nv);
    misoriented += (nc[0] * nv[0] + nc[1] * nv[1] + nc[2] * nv[2]) < 0;
  }
  PI_CHECK(cellNormals && misoriented == 0);
  // The neck radius on x = 0 is sqrt(1.5 − d²).
  double neck = 0;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    if (std::fabs(p[0]) < 0.5 * h)
    {
      neck = std::max(neck, std::sqrt(p[1] * p[1] + p[2] * p[2]));
    }
  }
  PI_CHECK_NEAR(neck, std::sqrt(1.5 - 0.81), 0.02);
  vtkStringArray* model =
    vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray("PiSurfaceModel"));
  PI_CHECK(model && model->GetNumberOfValues() == 1);
  if (model)
  {
    vtkNew<vtkPiSurface> rebuilt;
    PI_CHECK(rebuilt->SetModelJSON(model->GetValue(0)));
    double p[3] = { 0.1, 0.7, -0.3 };
    PI_CHECK_NEAR(rebuilt->EvaluateFunction(p), surface->EvaluateFunction(p), 1e-15);
  }

  // Bad settings are clear errors, not empty or absurd output.
  mesher->SetResolution(0);
  mesher->Update();
  PI_CHECK(watch.Error("Resolution must be at least 1"));
  mesher->SetResolution(-5);
  mesher->Update();
  PI_CHECK(watch.Error("Resolution must be at least 1"));
  mesher->SetResolution(100000);
  mesher->Update();
  PI_CHECK(watch.Error("MaximumNumberOfSamples"));
  mesher->SetResolution(32);
  mesher->SetBounds(1, -1, -1, 1, -1, 1);
  mesher->Update();
  PI_CHECK(watch.Error("x0 < x1"));
  mesher->SetBounds(0, 0, 0, 0, 0, 0);
  mesher->SetSampleDimensions(1, 10, 10);
  mesher->Update();
  PI_CHECK(watch.Error("SampleDimensions must be at least 2"));
  mesher->SetSampleDimensions(0, 0, 0);
  mesher->SetBounds(5, 6, 5, 6, 5, 6);
  mesher->Update();
  PI_CHECK(watch.Observer->GetWarning());
  PI_CHECK(watch.Observer->GetWarningMessage().find("does not cross") != std::string::npos);
  watch.Observer->Clear();
  vtkNew<vtkPiFlyingEdges> noSurface;
  pitest::Watch noWatch(noSurface);
  noSurface->Update();
  PI_CHECK(noWatch.Error("SetPiSurface"));

  // 10^4 sphere factors: the product overflows a double many times over, yet the mesh
  // is found, with finite vertices on F = 0 and unit normals.
  vtkNew<vtkPiSurface> many;
  vtkNew<vtkMinimalStandardRandomSequence> rng;
  rng->SetSeed(3);
  for (int i = 0; i < 10000; ++i)
  {
    vtkNew<vtkPiPrimitive> s;
    double c[3];
    for (double& ci : c)
    {
      rng->Next();
      ci = rng->GetRangeValue(0, 40);
    }
    s->SetCenter(c);
    s->SetRadius(0.3);
    many->AddFactor(s);
  }
  many->SetBlending(1.0);
  vtkNew<vtkPiFlyingEdges> manyMesher;
  pitest::Watch manyWatch(manyMesher);
  manyMesher->SetPiSurface(many);
  manyMesher->SetBounds(10, 16, 10, 16, 10, 16);
  manyMesher->SetResolution(48);
  manyMesher->Update();
  PI_CHECK(manyWatch.Quiet());
  vtkPolyData* manyMesh = manyMesher->GetOutput();
  PI_CHECK(manyMesh->GetNumberOfPoints() > 100);
  vtkDataArray* manyNormals = manyMesh->GetPointData()->GetNormals();
  for (vtkIdType i = 0; manyNormals && i < manyMesh->GetNumberOfPoints(); i += 13)
  {
    double p[3], n[3];
    manyMesh->GetPoint(i, p);
    manyNormals->GetTuple(i, n);
    PI_CHECK(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
    PI_CHECK_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-5);
    // On the surface: F changes sign within a cell around the vertex along the normal.
    const double step = 0.01;
    double a[3], b[3];
    for (int k = 0; k < 3; ++k)
    {
      a[k] = p[k] - step * n[k];
      b[k] = p[k] + step * n[k];
    }
    double la, lb;
    const int sa = many->EvaluateSignAndLog(a, la), sb = many->EvaluateSignAndLog(b, lb);
    if (sa == sb)
    {
      std::cerr << "no sign change across vertex " << i << " at (" << p[0] << ", " << p[1] << ", "
                << p[2] << ") n = (" << n[0] << ", " << n[1] << ", " << n[2] << ")" << std::endl;
      ++failures;
    }
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
