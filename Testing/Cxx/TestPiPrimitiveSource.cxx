// SPDX-License-Identifier: BSD-3-Clause
// vtkPiPrimitiveSource, vtkPiProduct and vtkPiSurfaceModelWriter: every type meshes
// with its one-primitive model; bad values are errors with an empty output; a product
// of primitive sources is the Pi Surface of the same model; the writer's file reads
// back to the same mesh; an empty product and inputs without a model are errors.
#include "PiTestUtilities.h"

#include "vtkPiPrimitive.h"
#include "vtkPiPrimitiveSource.h"
#include "vtkPiProduct.h"
#include "vtkPiSurface.h"
#include "vtkPiSurfaceModelReader.h"
#include "vtkPiSurfaceModelWriter.h"
#include "vtkPiSurfaceSource.h"

#include "vtkErrorCode.h"
#include "vtkFeatureEdges.h"
#include "vtkFieldData.h"
#include "vtkMassProperties.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace
{
double Area(vtkPolyData* mesh)
{
  if (mesh->GetNumberOfCells() == 0)
  {
    return 0.0;
  }
  vtkNew<vtkMassProperties> mass;
  mass->SetInputData(mesh);
  mass->Update();
  return mass->GetSurfaceArea();
}

vtkIdType OpenEdges(vtkPolyData* mesh)
{
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(mesh);
  edges->BoundaryEdgesOn();
  edges->NonManifoldEdgesOn();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->Update();
  return edges->GetOutput()->GetNumberOfCells();
}

std::string ModelOf(vtkPolyData* mesh)
{
  auto* json =
    vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray("PiSurfaceModel"));
  return json && json->GetNumberOfValues() > 0 ? json->GetValue(0) : std::string();
}

bool SameMesh(vtkPolyData* a, vtkPolyData* b)
{
  const double aa = Area(a), ab = Area(b);
  const bool same = a->GetNumberOfPoints() == b->GetNumberOfPoints() &&
    a->GetNumberOfCells() == b->GetNumberOfCells() && a->GetNumberOfCells() > 0 &&
    std::fabs(aa - ab) <= 1e-9 * std::max(aa, ab);
  if (!same)
  {
    std::cerr << "meshes differ: " << a->GetNumberOfPoints() << "/" << b->GetNumberOfPoints()
              << " points, " << a->GetNumberOfCells() << "/" << b->GetNumberOfCells()
              << " cells, area " << aa << "/" << ab << std::endl;
  }
  return same;
}
}

int TestPiPrimitiveSource(int, char*[])
{
  int failures = 0;

  // Every type meshes; bounded ones are closed; the model holds the one primitive.
  for (int type = vtkPiPrimitive::SPHERE; type <= vtkPiPrimitive::POLYNOMIAL; ++type)
  {
    vtkNew<vtkPiPrimitiveSource> source;
    pitest::Watch watch(source);
    source->SetType(type);
    source->SetCenter(0.25, 0.5, -1);
    source->SetResolution(32);
    if (type == vtkPiPrimitive::POLYNOMIAL)
    {
      source->SetExpression("x^2+2*y^2+z^2-1");
    }
    source->Update();
    vtkPolyData* mesh = source->GetOutput();
    const std::string name = source->GetPrimitive()->GetTypeAsString();
    if (!watch.Quiet() || mesh->GetNumberOfCells() < 100)
    {
      std::cerr << name << ": " << mesh->GetNumberOfCells() << " cells" << std::endl;
      ++failures;
    }
    PI_CHECK(mesh->GetPointData()->GetArray("Factor") != nullptr);
    vtkNew<vtkPiSurface> model;
    PI_CHECK(model->SetModelJSON(ModelOf(mesh)));
    PI_CHECK(model->GetNumberOfFactors() == 1);
    PI_CHECK(model->GetBlending() == 0.0);
    auto* p = vtkPiPrimitive::SafeDownCast(model->GetFactor(0));
    PI_CHECK(p && p->GetType() == type);
    double x[3] = { 0.7, -0.3, 0.4 };
    if (p)
    {
      PI_CHECK_NEAR(p->EvaluateFunction(x), source->GetPrimitive()->EvaluateFunction(x), 1e-12);
    }
    if (source->GetPrimitive()->IsBounded())
    {
      PI_CHECK(OpenEdges(mesh) == 0);
    }
    else
    {
      // Clipped to the automatic box: the cube of half-side 2 s about the centre.
      double b[6];
      mesh->GetBounds(b);
      PI_CHECK(model->HasModelBounds());
      PI_CHECK(b[0] >= 0.25 - 4 - 1e-9 && b[1] <= 0.25 + 4 + 1e-9);
    }
  }

  // Bad values: one error naming the parameter, an empty output; then it recovers.
  {
    vtkNew<vtkPiPrimitiveSource> source;
    pitest::Watch watch(source);
    source->SetRadius(-1);
    source->Update();
    PI_CHECK(watch.Error("radius"));
    PI_CHECK(source->GetOutput()->GetNumberOfCells() == 0);
    source->SetRadius(1);
    source->SetType(vtkPiPrimitive::SUPERELLIPSOID);
    source->SetExponent(5);
    source->Update();
    PI_CHECK(watch.Error("exponent"));
    PI_CHECK(source->GetOutput()->GetNumberOfCells() == 0);
    source->SetType(vtkPiPrimitive::POLYNOMIAL);
    source->SetExpression("x^2+(y");
    source->Update();
    PI_CHECK(watch.Error("xpression"));
    PI_CHECK(source->GetOutput()->GetNumberOfCells() == 0);
    source->SetType(vtkPiPrimitive::SPHERE);
    source->SetBounds(0, 1, 0, 1, 1, 0);
    source->Update();
    PI_CHECK(watch.Error("Bounds"));
    source->SetBounds(0, 0, 0, 0, 0, 0);
    source->Update();
    PI_CHECK(watch.Quiet());
    PI_CHECK(source->GetOutput()->GetNumberOfCells() > 100);
  }

  // A product of two primitive sources is the Pi Surface of the same model, and
  // follows its inputs.
  vtkNew<vtkPiPrimitiveSource> right, left;
  right->SetCenter(0.9, 0, 0);
  left->SetCenter(-0.9, 0, 0);
  vtkNew<vtkPiProduct> product;
  product->AddInputConnection(right->GetOutputPort());
  product->AddInputConnection(left->GetOutputPort());
  product->SetBlending(0.25);
  product->SetResolution(64);
  product->Update();
  vtkNew<vtkPiSurfaceSource> reference; // default model: these two spheres, r = 0.25
  reference->SetResolution(64);
  reference->Update();
  PI_CHECK(SameMesh(product->GetOutput(), reference->GetOutput()));
  const double before = product->GetOutput()->GetBounds()[1];
  right->SetCenter(1.2, 0, 0);
  product->Update();
  PI_CHECK(product->GetOutput()->GetBounds()[1] > before + 0.2);

  // The writer: the product's model read back meshes to the same surface.
  const std::string path = std::string(PISURF_TEMP_DIR) + "/TestPiPrimitiveSource.pisurf";
  std::remove(path.c_str());
  vtkNew<vtkPiSurfaceModelWriter> writer;
  writer->SetInputConnection(product->GetOutputPort());
  writer->SetFileName(path.c_str());
  PI_CHECK(writer->Write() == 1);
  PI_CHECK(writer->GetErrorCode() == vtkErrorCode::NoError);
  vtkNew<vtkPiSurfaceModelReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetResolution(64);
  reader->Update();
  PI_CHECK(SameMesh(reader->GetOutput(), product->GetOutput()));
  PI_CHECK(reader->GetPiSurface()->GetNumberOfFactors() == 2);
  PI_CHECK(reader->GetPiSurface()->GetBlending() == 0.25);
  // An unbounded primitive's file keeps its box.
  {
    vtkNew<vtkPiPrimitiveSource> plane;
    plane->SetType(vtkPiPrimitive::PLANE);
    plane->SetNormal(1, 1, 1);
    plane->SetBounds(-1, 1, -2, 2, -3, 3);
    vtkNew<vtkPiSurfaceModelWriter> planeWriter;
    planeWriter->SetInputConnection(plane->GetOutputPort());
    const std::string planePath =
      std::string(PISURF_TEMP_DIR) + "/TestPiPrimitiveSource_plane.pisurf";
    planeWriter->SetFileName(planePath.c_str());
    PI_CHECK(planeWriter->Write() == 1);
    vtkNew<vtkPiSurfaceModelReader> planeReader;
    planeReader->SetFileName(planePath.c_str());
    planeReader->SetResolution(64);
    planeReader->Update();
    plane->SetResolution(64);
    plane->Update();
    PI_CHECK(SameMesh(planeReader->GetOutput(), plane->GetOutput()));
  }
  // Writer errors: no model on the input, no file name, an unwritable path.
  {
    vtkNew<vtkSphereSource> sphere;
    vtkNew<vtkPiSurfaceModelWriter> bad;
    pitest::Watch watch(bad);
    bad->SetInputConnection(sphere->GetOutputPort());
    bad->SetFileName((std::string(PISURF_TEMP_DIR) + "/no_model.pisurf").c_str());
    bad->Write();
    PI_CHECK(watch.Error("PiSurfaceModel"));
    PI_CHECK(bad->GetErrorCode() != vtkErrorCode::NoError);
    PI_CHECK(!std::ifstream(std::string(PISURF_TEMP_DIR) + "/no_model.pisurf"));
    bad->SetInputConnection(product->GetOutputPort());
    bad->SetFileName("/nonexistent-directory/x.pisurf");
    bad->Write();
    PI_CHECK(watch.Error("Cannot write"));
  }

  // Errors of the product: no input, an input without a model, an invalid input.
  {
    vtkNew<vtkPiProduct> empty;
    pitest::Watch watch(empty);
    empty->Update();
    PI_CHECK(watch.Error("no factors"));
    PI_CHECK(empty->GetOutput()->GetNumberOfCells() == 0);
    vtkNew<vtkSphereSource> sphere;
    empty->AddInputConnection(right->GetOutputPort());
    empty->AddInputConnection(sphere->GetOutputPort());
    empty->Update();
    PI_CHECK(watch.Error("Input 2"));
    PI_CHECK(empty->GetOutput()->GetNumberOfCells() == 0);
  }
  return failures;
}
