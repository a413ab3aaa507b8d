// SPDX-License-Identifier: BSD-3-Clause
// Regression image of one of the paper's figures, rendered as ./run demo's gallery does:
// the primitives (output port 1) coloured by Factor under the translucent grey
// Pi-surface (or the opaque Pi-surface under translucent primitives where it lies
// inside them). Arguments: model dx dy dz ux uy uz inside, then the regression-test
// options (-V baseline -T temporary directory).
#include "PiTestUtilities.h"
#include "vtkPiSurface.h"
#include "vtkPiSurfaceModelReader.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestPiGalleryImage(int argc, char* argv[])
{
  if (argc < 9)
  {
    std::cerr << "usage: TestPiGalleryImage model dx dy dz ux uy uz inside [-V ...]\n";
    return EXIT_FAILURE;
  }
  const std::string model = argv[1];
  double direction[3], up[3];
  for (int k = 0; k < 3; ++k)
  {
    direction[k] = std::atof(argv[2 + k]);
    up[k] = std::atof(argv[5 + k]);
  }
  const bool inside = std::atoi(argv[8]) != 0;

  vtkNew<vtkPiSurfaceModelReader> reader;
  reader->SetFileName(pitest::ModelPath(model).c_str());
  reader->SetResolution(96);
  reader->Update();
  vtkPiSurface* surface = reader->GetPiSurface();
  double bounds[6];
  if (!surface->GetModelBounds(bounds) || reader->GetOutput()->GetNumberOfCells() == 0)
  {
    std::cerr << model << ": no surface\n";
    return EXIT_FAILURE;
  }

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  renderer->SetUseDepthPeeling(true);
  // The gallery's palette (Scripts/gallery.py).
  const double palette[][3] = { { 0.85, 0.22, 0.18 }, { 0.22, 0.42, 0.85 }, { 0.25, 0.7, 0.3 },
    { 0.95, 0.6, 0.15 }, { 0.6, 0.3, 0.75 }, { 0.15, 0.7, 0.7 }, { 0.9, 0.8, 0.2 },
    { 0.8, 0.4, 0.6 } };
  const int n = surface->GetNumberOfFactors();
  vtkNew<vtkLookupTable> colours;
  colours->SetNumberOfTableValues(n);
  colours->SetTableRange(0, std::max(n - 1, 1));
  for (int i = 0; i < n; ++i)
  {
    const double* c = palette[i % 8];
    colours->SetTableValue(i, c[0], c[1], c[2], 1.0);
  }
  vtkNew<vtkPolyDataMapper> primitiveMapper;
  primitiveMapper->SetInputConnection(reader->GetOutputPort(1));
  primitiveMapper->SetScalarModeToUsePointFieldData();
  primitiveMapper->SelectColorArray("Factor");
  primitiveMapper->SetLookupTable(colours);
  primitiveMapper->UseLookupTableScalarRangeOn();
  primitiveMapper->SetRelativeCoincidentTopologyPolygonOffsetParameters(2, 2);
  vtkNew<vtkActor> primitives;
  primitives->SetMapper(primitiveMapper);
  primitives->GetProperty()->SetOpacity(inside ? 0.35 : 1.0);
  renderer->AddActor(primitives);

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort(0));
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> pi;
  pi->SetMapper(mapper);
  pi->GetProperty()->SetColor(0.62, 0.62, 0.62);
  pi->GetProperty()->SetOpacity(inside ? 1.0 : 0.42);
  pi->GetProperty()->SetSpecular(0.3);
  renderer->AddActor(pi);

  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 300);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  const double centre[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] + direction[0], centre[1] + direction[1], centre[2] + direction[2]);
  camera->SetViewUp(up);
  renderer->ResetCamera(reader->GetOutput()->GetBounds());
  camera->Zoom(1.15);
  window->Render();

  return pitest::RegressionResult(argc, argv, window);
}
