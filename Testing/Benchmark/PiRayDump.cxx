// SPDX-License-Identifier: BSD-3-Clause
// Ray dump (a development tool, not a test): casts the views of every model in
// a directory and prints every hit, one line each, so that two builds of
// vtkPiRayCaster can be compared (Scripts/compare_ray_dumps.py). Also prints
// the CPU time per model.
//   PiRayDump MODELS_DIR [N] > dump.txt
#include "vtkPiRayCaster.h"
#include "vtkPiSurface.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <dirent.h>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: PiRayDump MODELS_DIR [N]\n");
    return 2;
  }
  const std::string dir = argv[1];
  const int n = argc > 2 ? std::atoi(argv[2]) : 96;
  vtkSMPTools::SetBackend("Sequential");
  std::vector<std::string> names;
  if (DIR* d = opendir(dir.c_str()))
  {
    while (dirent* e = readdir(d))
    {
      const std::string f = e->d_name;
      if (f.size() > 7 && f.substr(f.size() - 7) == ".pisurf")
      {
        names.push_back(f);
      }
    }
    closedir(d);
  }
  std::sort(names.begin(), names.end());
  for (const std::string& name : names)
  {
    vtkNew<vtkPiSurface> surface;
    if (!surface->LoadModel((dir + "/" + name).c_str()))
    {
      continue;
    }
    double b[6];
    const double none[6] = { 0, 0, 0, 0, 0, 0 };
    if (!surface->ResolveBounds(none, b))
    {
      continue;
    }
    const double c[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
    const double s = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
    struct Setup
    {
      const char* Label;
      int Mode;
      bool All;
      bool Parallel;
    };
    const Setup setups[] = { { "six", vtkPiRayCaster::SIX_AXIS_VIEWS, false, false },
      { "three-all", vtkPiRayCaster::THREE_AXIS_DIRECTIONS, true, false },
      { "six-all", vtkPiRayCaster::SIX_AXIS_VIEWS, true, false },
      { "camera", vtkPiRayCaster::CAMERA, false, false },
      { "camera-all", vtkPiRayCaster::CAMERA, true, false },
      { "parallel-all", vtkPiRayCaster::CAMERA, true, true } };
    const std::clock_t start = std::clock();
    for (const Setup& setup : setups)
    {
      vtkNew<vtkPiRayCaster> caster;
      caster->SetPiSurface(surface);
      caster->SetViewMode(setup.Mode);
      caster->SetAllHits(setup.All);
      caster->SetResolution(n, n + 3);
      caster->SetCameraPosition(c[0] + 1.7 * s, c[1] - 1.3 * s, c[2] + 0.9 * s);
      caster->SetCameraFocalPoint(c[0], c[1], c[2]);
      caster->SetCameraViewUp(0, 0, 1);
      caster->SetViewAngle(30);
      caster->SetParallelProjection(setup.Parallel);
      caster->SetParallelScale(0.6 * s);
      caster->Update();
      vtkPolyData* out = caster->GetOutput();
      vtkPointData* pd = out->GetPointData();
      vtkDataArray* pixel = pd->GetArray("PixelIndex");
      vtkDataArray* view = pd->GetArray("ViewIndex");
      vtkDataArray* index = pd->GetArray("HitIndex");
      vtkDataArray* depth = pd->GetArray("Depth");
      vtkDataArray* tangent = pd->GetArray("Tangent");
      vtkDataArray* singular = pd->GetArray("Singular");
      vtkDataArray* factor = pd->GetArray("Factor");
      for (vtkIdType k = 0; k < out->GetNumberOfPoints(); ++k)
      {
        std::printf("%s %s %d %d %d %d %.17g %d %d %d\n", name.c_str(), setup.Label,
          int(view->GetComponent(k, 0)), int(pixel->GetComponent(k, 0)),
          int(pixel->GetComponent(k, 1)), int(index->GetComponent(k, 0)), depth->GetComponent(k, 0),
          int(tangent->GetComponent(k, 0)), int(singular->GetComponent(k, 0)),
          int(factor->GetComponent(k, 0)));
      }
    }
    std::fprintf(
      stderr, "%-34s %.3f s CPU\n", name.c_str(), double(std::clock() - start) / CLOCKS_PER_SEC);
  }
  return 0;
}
