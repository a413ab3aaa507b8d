// SPDX-License-Identifier: BSD-3-Clause
// The README's VTK C++ program: two blended spheres meshed, the area printed. Built and
// run as the test Cxx.PiVTKExample against ParaView's VTK and against plain VTK.
#include "vtkMassProperties.h"
#include "vtkNew.h"
#include "vtkPiFlyingEdges.h"
#include "vtkPiPrimitive.h"
#include "vtkPiSurface.h"
#include "vtkPolyData.h"

#include <cstdio>

int main()
{
  vtkNew<vtkPiPrimitive> a, b; // two unit spheres
  a->SetCenter(0.9, 0, 0);
  b->SetCenter(-0.9, 0, 0);
  vtkNew<vtkPiSurface> surface; // F = f_a f_b - r
  surface->AddFactor(a);
  surface->AddFactor(b);
  surface->SetBlending(0.25);
  vtkNew<vtkPiFlyingEdges> mesher;
  mesher->SetPiSurface(surface);
  mesher->SetResolution(64);
  vtkNew<vtkMassProperties> area;
  area->SetInputConnection(mesher->GetOutputPort());
  area->Update();
  std::printf("%lld triangles, area %.3f\n",
    static_cast<long long>(mesher->GetOutput()->GetNumberOfPolys()), area->GetSurfaceArea());
  return area->GetSurfaceArea() > 15.0 && area->GetSurfaceArea() < 8 * 3.141593 ? 0 : 1;
}
