// SPDX-License-Identifier: BSD-3-Clause
// Regression image of the paper's Figure 1(b): two unit spheres at x = ±0.9 blended
// with r = 0.25; the primitives in colour under the translucent grey Pi-surface.
#include "vtkPiFlyingEdges.h"
#include "vtkPiPrimitive.h"
#include "vtkPiSurface.h"
#include "vtkPiSurfaceModelReader.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"

#include <string>

int TestPiTwoSpheresImage(int argc, char* argv[])
{
  vtkNew<vtkPiSurfaceModelReader> reader;
  reader->SetFileName((std::string(PISURF_MODELS_DIR) + "/two_spheres_d0.9.pisurf").c_str());
  reader->SetResolution(96);
  reader->Update();
  vtkPiSurface* surface = reader->GetPiSurface();
  double bounds[6];
  surface->GetModelBounds(bounds);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  renderer->SetUseDepthPeeling(true);
  double colours[][3] = { { 0.85, 0.2, 0.15 }, { 0.2, 0.4, 0.85 } };
  for (int i = 0; i < surface->GetNumberOfFactors(); ++i)
  {
    // Each primitive is the Pi-surface of its one factor with r = 0.
    vtkNew<vtkPiSurface> alone;
    alone->AddFactor(surface->GetFactor(i));
    vtkNew<vtkPiFlyingEdges> mesher;
    mesher->SetPiSurface(alone);
    mesher->SetBounds(bounds);
    mesher->SetResolution(96);
    mesher->Update();
    vtkNew<vtkPolyData> mesh;
    mesh->DeepCopy(mesher->GetOutput());
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(mesh);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(colours[i % 2]);
    renderer->AddActor(actor);
  }
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> pi;
  pi->SetMapper(mapper);
  pi->GetProperty()->SetColor(0.6, 0.6, 0.6);
  pi->GetProperty()->SetOpacity(0.45);
  pi->GetProperty()->SetSpecular(0.3);
  renderer->AddActor(pi);

  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 300);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.6, -6, 2.2);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCamera();
  camera->Zoom(1.3);
  window->Render();

  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(window);
    interactor->Start();
  }
  return result == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
