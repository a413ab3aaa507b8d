// SPDX-License-Identifier: BSD-3-Clause
// vtkPiSurfaceModelReader: every paper model reads and meshes; the output carries the
// model; OverrideBlending inflates; bad files are clear errors with an empty output.
#include "PiTestUtilities.h"

#include "vtkPiSurface.h"
#include "vtkPiSurfaceModelReader.h"

#include "vtkDirectory.h"
#include "vtkFeatureEdges.h"
#include "vtkFieldData.h"
#include "vtkMassProperties.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTriangleFilter.h"

#include <fstream>
#include <string>

namespace
{
double Area(vtkPolyData* mesh)
{
  vtkNew<vtkMassProperties> mass;
  mass->SetInputData(mesh);
  mass->Update();
  return mass->GetSurfaceArea();
}

std::string WriteTemp(const std::string& name, const std::string& text)
{
  const std::string path = std::string(PISURF_TEMP_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}
}

int TestPiSurfaceModelReader(int, char*[])
{
  int failures = 0;
  const std::string dir = PISURF_MODELS_DIR;

  // Every paper model loads and gives a non-empty mesh carrying its model.
  vtkNew<vtkDirectory> listing;
  PI_CHECK(listing->Open(dir.c_str()));
  int models = 0;
  for (vtkIdType i = 0; i < listing->GetNumberOfFiles(); ++i)
  {
    const std::string file = listing->GetFile(i);
    if (file.size() < 7 || file.substr(file.size() - 7) != ".pisurf")
    {
      continue;
    }
    ++models;
    const std::string path = dir + "/" + file;
    PI_CHECK(vtkPiSurfaceModelReader::CanReadFile(path.c_str()));
    vtkNew<vtkPiSurfaceModelReader> reader;
    pitest::Watch watch(reader);
    reader->SetFileName(path.c_str());
    reader->SetResolution(64);
    reader->Update();
    vtkPolyData* mesh = reader->GetOutput();
    if (!watch.Quiet() || mesh->GetNumberOfPolys() < 50)
    {
      std::cerr << file << ": " << mesh->GetNumberOfPolys() << " triangles" << std::endl;
      ++failures;
    }
    PI_CHECK(mesh->GetPointData()->GetNormals() != nullptr);
    PI_CHECK(mesh->GetPointData()->GetArray("Factor") != nullptr);
    auto* json =
      vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray("PiSurfaceModel"));
    PI_CHECK(json != nullptr);
    if (json)
    {
      vtkNew<vtkPiSurface> again;
      PI_CHECK(again->SetModelJSON(json->GetValue(0)));
      PI_CHECK(again->GetNumberOfFactors() == reader->GetPiSurface()->GetNumberOfFactors());
    }
  }
  std::cout << models << " paper models read" << std::endl;
  PI_CHECK(models >= 20);

  // The two spheres: a closed surface; a larger r inflates it.
  vtkNew<vtkPiSurfaceModelReader> reader;
  pitest::Watch watch(reader);
  reader->SetFileName((dir + "/two_spheres_d0.9.pisurf").c_str());
  reader->SetResolution(64);
  reader->Update();
  PI_CHECK(watch.Quiet());
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputConnection(reader->GetOutputPort());
  edges->BoundaryEdgesOn();
  edges->NonManifoldEdgesOn();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->Update();
  PI_CHECK(edges->GetOutput()->GetNumberOfCells() == 0);
  PI_CHECK_NEAR(reader->GetPiSurface()->GetBlending(), 0.25, 0.0);
  const double area = Area(reader->GetOutput());
  reader->OverrideBlendingOn();
  reader->SetBlending(2.0);
  reader->Update();
  PI_CHECK_NEAR(reader->GetPiSurface()->GetBlending(), 2.0, 0.0);
  PI_CHECK(Area(reader->GetOutput()) > 1.1 * area);
  reader->OverrideBlendingOff();

  // Bad files: an error that names the problem, and an empty output.
  struct BadCase
  {
    const char* Name;
    const char* Text;
    const char* Message;
  };
  const BadCase cases[] = {
    { "syntax.pisurf", "{\"pisurf\": 1, \"blending\": 0.2,,}", "invalid JSON at line 1" },
    { "key.pisurf",
      "{\"pisurf\": 1, \"blending\": 0.2, \"primitives\": [{\"type\": \"sphere\", \"radius\": 1, "
      "\"colour\": \"red\"}]}",
      "unknown key 'colour'" },
    { "version.pisurf", "{\"pisurf\": 2, \"blending\": 0.2, \"primitives\": []}",
      "unsupported version" },
    { "empty.pisurf", "", "invalid JSON" },
    { "unbounded.pisurf",
      "{\"pisurf\": 1, \"blending\": 0.2, \"primitives\": [{\"type\": \"plane\", \"normal\": "
      "[1, 0, 0]}]}",
      "bounds: required" },
  };
  for (const BadCase& c : cases)
  {
    reader->SetFileName(WriteTemp(c.Name, c.Text).c_str());
    reader->Update();
    PI_CHECK(watch.Error(c.Message));
    PI_CHECK(reader->GetOutput()->GetNumberOfPoints() == 0);
  }
  reader->SetFileName("/nonexistent.pisurf");
  reader->Update();
  PI_CHECK(watch.Error("cannot open model file"));
  PI_CHECK(!vtkPiSurfaceModelReader::CanReadFile("/nonexistent.pisurf"));
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
