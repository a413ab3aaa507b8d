// SPDX-License-Identifier: BSD-3-Clause
// Regression image of the ray caster's shaded first hits (output port 1), the paper's
// "immediate visualization". Arguments: model px py pz fx fy fz ux uy uz, then the
// regression-test options (-V baseline -T temporary directory).
#include "PiTestUtilities.h"
#include "vtkPiRayCaster.h"
#include "vtkPiSurface.h"

#include "vtkExtractVOI.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkTesting.h"
#include "vtkTrivialProducer.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestPiRayCastImage(int argc, char* argv[])
{
  if (argc < 11)
  {
    std::cerr << "usage: TestPiRayCastImage model px py pz fx fy fz ux uy uz [-V ...]\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkPiSurface> surface;
  if (!surface->LoadModel(pitest::ModelPath(argv[1]).c_str()))
  {
    return EXIT_FAILURE;
  }
  vtkNew<vtkPiRayCaster> caster;
  caster->SetPiSurface(surface);
  caster->SetViewMode(vtkPiRayCaster::CAMERA);
  caster->SetResolution(320, 240);
  caster->SetCameraPosition(std::atof(argv[2]), std::atof(argv[3]), std::atof(argv[4]));
  caster->SetCameraFocalPoint(std::atof(argv[5]), std::atof(argv[6]), std::atof(argv[7]));
  caster->SetCameraViewUp(std::atof(argv[8]), std::atof(argv[9]), std::atof(argv[10]));
  caster->SetViewAngle(30);
  caster->Update();
  if (caster->GetOutput(0)->GetNumberOfPoints() < 1000)
  {
    std::cerr << "too few hits\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkExtractVOI> slice;
  slice->SetInputConnection(caster->GetOutputPort(1));
  slice->SetVOI(0, 319, 0, 239, 0, 0);
  slice->Update();
  // Compare the colours only (the Depth channel is checked elsewhere).
  vtkNew<vtkImageData> colours;
  colours->ShallowCopy(slice->GetOutput());
  colours->GetPointData()->RemoveArray("Depth");
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(colours);

  vtkNew<vtkTesting> testing;
  for (int i = 11; i < argc; ++i)
  {
    testing->AddArgument(argv[i]);
  }
  const int result = testing->RegressionTest(producer, 10.0);
  return result == vtkTesting::PASSED ? EXIT_SUCCESS : EXIT_FAILURE;
}
