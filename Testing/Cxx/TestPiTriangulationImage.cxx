// SPDX-License-Identifier: BSD-3-Clause
// Regression image of the image-based triangulation: six first-hit axis views of a model
// at 48² pixels, triangulated on their ray lattice (vtkPiImageTriangulator), drawn flat
// with its edges so that the mesh itself (exact hits as vertices) is what is compared.
// Arguments: model dx dy dz ux uy uz (view direction, towards the model, and view up),
// then the regression-test options (-V baseline -T temporary directory).
#include "PiTestUtilities.h"
#include "vtkPiImageTriangulator.h"
#include "vtkPiRayCaster.h"
#include "vtkPiSurface.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestPiTriangulationImage(int argc, char* argv[])
{
  if (argc < 8)
  {
    std::cerr << "usage: TestPiTriangulationImage model dx dy dz ux uy uz [-V ...]\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkPiSurface> surface;
  if (!surface->LoadModel(pitest::ModelPath(argv[1]).c_str()))
  {
    return EXIT_FAILURE;
  }
  vtkNew<vtkPiRayCaster> caster;
  caster->SetPiSurface(surface);
  caster->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
  caster->SetResolution(48, 48);
  vtkNew<vtkPiImageTriangulator> triangulator;
  triangulator->SetInputConnection(caster->GetOutputPort(0));
  triangulator->SetMergeMode(vtkPiImageTriangulator::RAY_LATTICE);
  triangulator->Update();
  vtkPolyData* mesh = triangulator->GetOutput();
  if (mesh->GetNumberOfCells() < 1000)
  {
    std::cerr << "too few triangles: " << mesh->GetNumberOfCells() << "\n";
    return EXIT_FAILURE;
  }

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.85, 0.75, 0.55);
  actor->GetProperty()->SetInterpolationToFlat();
  actor->GetProperty()->EdgeVisibilityOn();
  actor->GetProperty()->SetEdgeColor(0.25, 0.2, 0.15);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(600, 450);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  double bounds[6];
  mesh->GetBounds(bounds);
  const double centre[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(centre);
  camera->SetPosition(
    centre[0] - std::atof(argv[2]), centre[1] - std::atof(argv[3]), centre[2] - std::atof(argv[4]));
  camera->SetViewUp(std::atof(argv[5]), std::atof(argv[6]), std::atof(argv[7]));
  renderer->ResetCamera(bounds);
  camera->Zoom(1.15);
  window->Render();

  return pitest::RegressionResult(argc, argv, window);
}
