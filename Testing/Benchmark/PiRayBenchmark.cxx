// SPDX-License-Identifier: BSD-3-Clause
// Ray benchmark (./run bench): vtkPiRayCaster's certified first hits against a fixed-step
// marcher with bisection given the same time budget, on 1024² rays of the −Y view.
// Prints a Markdown table (each time the best of five executions): rays per second (from
// wall-clock time, and for the Sequential backend also from the process CPU time, which
// other processes on a shared machine disturb less), the all-hits time over the first-hit
// time, both casts' hit counts, and the hits the marcher misses. PIRAY_BENCH_QUICK=1 skips the
// marcher and the spheres (for profiling).
#include "PiProductKernel.h"
#include "vtkPiPrimitive.h"
#include "vtkPiRayCaster.h"
#include "vtkPiSurface.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

namespace
{
double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double CpuSeconds(std::clock_t start)
{
  return double(std::clock() - start) / CLOCKS_PER_SEC;
}

// First-hit depth per pixel of the −Y view by fixed steps and bisection (−1: no hit).
std::vector<double> March(const pisurf::ProductKernel& kernel, const double b[6], int n, int steps)
{
  std::vector<double> depth(size_t(n) * n, -1.0);
  const double length = b[3] - b[2];
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType j = begin; j < end; ++j)
      {
        for (int i = 0; i < n; ++i)
        {
          // Image axes (z, x) for the −Y view, rays from y1 along −y.
          const double z = b[4] + (i + 0.5) * (b[5] - b[4]) / n;
          const double x = b[0] + (j + 0.5) * (b[1] - b[0]) / n;
          auto at = [&](double t)
          {
            const double p[3] = { x, b[3] - t, z };
            return kernel.EvaluateCompressed(p);
          };
          double ta = 0.0, va = at(0.0);
          for (int s = 1; s <= steps; ++s)
          {
            const double tb = length * s / steps, vb = at(tb);
            if ((va < 0) != (vb < 0))
            {
              double lo = ta, hi = tb;
              for (int it = 0; it < 40; ++it)
              {
                const double mid = 0.5 * (lo + hi);
                if ((at(mid) < 0) == (va < 0))
                  lo = mid;
                else
                  hi = mid;
              }
              depth[size_t(j) * n + i] = 0.5 * (lo + hi);
              break;
            }
            ta = tb;
            va = vb;
          }
        }
      }
    });
  return depth;
}

void Run(const std::string& name, vtkPiSurface* surface, int n)
{
  double b[6];
  surface->GetModelBounds(b);
  // Best of five executions (wall clock and CPU time each), as the mesh benchmark
  // measures, the first-hit and the all-hits casts taking turns: one run on a shared
  // machine is at the mercy of its neighbours, in phases that would otherwise favour
  // one side of the ratio.
  auto once = [](vtkPiRayCaster* c, double& wall, double& cpu)
  {
    c->Modified();
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpuStart = std::clock();
    c->Update();
    wall = std::min(wall, Seconds(start));
    cpu = std::min(cpu, CpuSeconds(cpuStart));
  };
  vtkNew<vtkPiRayCaster> caster;
  caster->SetPiSurface(surface);
  caster->SetViewMode(vtkPiRayCaster::MINUS_Y);
  caster->SetResolution(n, n);
  caster->SetBounds(b);
  // The same rays with every hit.
  vtkNew<vtkPiRayCaster> all;
  all->SetPiSurface(surface);
  all->SetViewMode(vtkPiRayCaster::MINUS_Y);
  all->SetResolution(n, n);
  all->SetBounds(b);
  all->SetAllHits(true);
  double ours = 1e300, oursCpu = 1e300, allTime = 1e300, allCpu = 1e300;
  for (int k = 0; k < 5; ++k)
  {
    once(caster, ours, oursCpu);
    once(all, allTime, allCpu);
  }
  vtkPolyData* hits = caster->GetOutput();
  const bool sequential = std::string(vtkSMPTools::GetBackend()) == "Sequential";
  char cpuRate[32] = "-";
  if (sequential)
  {
    std::snprintf(cpuRate, sizeof(cpuRate), "%.2f M", double(n) * n / oursCpu / 1e6);
  }
  const double ratio = sequential ? allCpu / oursCpu : allTime / ours;
  // The hits of both casts: per-hit work (roots, normals, the singularity test) makes
  // the time ratio follow the hit ratio.
  const long firstHits = static_cast<long>(hits->GetNumberOfPoints());
  const long allHits = static_cast<long>(all->GetOutput()->GetNumberOfPoints());
  char hitRatio[64];
  std::snprintf(hitRatio, sizeof(hitRatio), "%ld / %ld (%.2f)", allHits, firstHits,
    firstHits > 0 ? double(allHits) / firstHits : 0.0);
  if (std::getenv("PIRAY_BENCH_QUICK"))
  {
    std::printf("| %s | %s | %.3f s | %.2f M | %s | %.2f | %s |\n", name.c_str(),
      vtkSMPTools::GetBackend(), ours, double(n) * n / ours / 1e6, cpuRate, ratio, hitRatio);
    std::fflush(stdout);
    return;
  }
  std::vector<char> hit(size_t(n) * n, 0);
  vtkDataArray* pixel = hits->GetPointData()->GetArray("PixelIndex");
  for (vtkIdType k = 0; k < hits->GetNumberOfPoints(); ++k)
  {
    // PixelIndex (i, j): i along z, j along x for the −Y view.
    hit[size_t(pixel->GetComponent(k, 1)) * n + size_t(pixel->GetComponent(k, 0))] = 1;
  }
  auto kernel = surface->GetKernel();
  // Calibrate the marcher's step count to the same time budget.
  auto start = std::chrono::steady_clock::now();
  March(*kernel, b, n / 8, 64);
  const double perStep = Seconds(start) / (double(n / 8) * (n / 8) * 64);
  const int steps = std::max(2, static_cast<int>(ours / (perStep * n * n)));
  start = std::chrono::steady_clock::now();
  const std::vector<double> depth = March(*kernel, b, n, steps);
  const double marcher = Seconds(start);
  long missed = 0;
  for (size_t p = 0; p < hit.size(); ++p)
  {
    missed += hit[p] && depth[p] < 0;
  }
  std::printf("| %s | %s | %.3f s | %.2f M | %s | %.2f | %s | %d | %.3f s | %ld of %ld |\n",
    name.c_str(), vtkSMPTools::GetBackend(), ours, double(n) * n / ours / 1e6, cpuRate, ratio,
    hitRatio, steps, marcher, missed, firstHits);
  std::fflush(stdout);
}
}

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: PiRayBenchmark MODELS_DIR [N]\n");
    return 2;
  }
  const std::string models = argv[1];
  const int n = argc > 2 ? std::atoi(argv[2]) : 1024;
  std::printf("\n%d x %d first-hit rays, -Y view\n\n", n, n);
  const bool quick = std::getenv("PIRAY_BENCH_QUICK") != nullptr;
  std::printf(
    "| model | backend | vtkPiRayCaster | rays/s (wall) | rays/s (CPU) | "
    "all hits / first hit (time) | hits, all / first |%s\n|---|---|---|---|---|---|---|%s\n",
    quick ? "" : " marcher steps (same time) | marcher | hits the marcher misses |",
    quick ? "" : "---|---|---|");
  for (const char* backend : { "Sequential", "STDThread" })
  {
    // PIRAY_BENCH_BACKEND=Sequential runs only that backend.
    const char* onlyBackend = std::getenv("PIRAY_BENCH_BACKEND");
    if (onlyBackend && std::string(onlyBackend) != backend)
    {
      continue;
    }
    vtkSMPTools::SetBackend(backend);
    if (!quick)
    {
      vtkNew<vtkPiSurface> spheres;
      for (int i = 0; i < 10; ++i)
      {
        vtkNew<vtkPiPrimitive> s;
        s->SetCenter(1.2 * (i % 5) - 2.4, 1.2 * (i / 5) - 0.6, 0.1 * i);
        s->SetRadius(0.8);
        spheres->AddFactor(s);
      }
      spheres->SetBlending(0.5);
      Run("10 spheres", spheres, n);
    }
    for (const char* name : { "cup_a1.0", "table" })
    {
      // PIRAY_BENCH_MODELS=cup_a1.0 runs only the models it names.
      const char* only = std::getenv("PIRAY_BENCH_MODELS");
      if (only && std::string(only).find(name) == std::string::npos)
      {
        continue;
      }
      vtkNew<vtkPiSurface> model;
      model->LoadModel((models + "/" + name + ".pisurf").c_str());
      Run(name, model, n);
    }
  }
  return 0;
}
