// SPDX-License-Identifier: BSD-3-Clause
// Progress and cancel as ParaView drives them: every long-running algorithm reports
// progress that only grows and ends at 1, through values in between; a cancel requested
// while it runs (ParaView's cancel button sets AbortExecute on the algorithm reporting
// progress) stops it with an empty output, also where the work is done by an inner
// algorithm (the molecule filter's mesher, the Pi Surface source's ray caster and
// triangulator); and the next run after the cancel is complete again.
#include "PiTestUtilities.h"

#include "vtkCMLMoleculeReader.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPiFlyingEdges.h"
#include "vtkPiImageTriangulator.h"
#include "vtkPiMoleculeSurface.h"
#include "vtkPiRayCaster.h"
#include "vtkPiSurfaceSource.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <vector>

namespace
{
struct Watch
{
  vtkAlgorithm* Target = nullptr;
  std::vector<double> Values;
  double CancelAt = 2.0; // cancel at the first report at or above this (never: 2)
};

void OnProgress(vtkObject*, unsigned long, void* client, void* data)
{
  Watch* watch = static_cast<Watch*>(client);
  const double value = *static_cast<double*>(data);
  watch->Values.push_back(value);
  if (value >= watch->CancelAt && value < 1.0)
  {
    watch->Target->SetAbortExecute(1);
  }
}

// `late` (if > 0): a cancel at the first report at or above it empties the output too
// (for the algorithms whose last pass is long: a cancel while it runs takes effect).
int Check(const char* name, vtkPolyDataAlgorithm* algorithm, double late = 0.0)
{
  int failures = 0;
  Watch watch;
  watch.Target = algorithm;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(OnProgress);
  callback->SetClientData(&watch);
  const unsigned long tag = algorithm->AddObserver(vtkCommand::ProgressEvent, callback);

  // A whole run: progress grows to 1 through at least two values in between.
  algorithm->Modified();
  algorithm->Update();
  const vtkIdType cells = algorithm->GetOutput()->GetNumberOfCells();
  PI_CHECK(cells > 0);
  PI_CHECK(!watch.Values.empty() && watch.Values.back() == 1.0);
  PI_CHECK(std::is_sorted(watch.Values.begin(), watch.Values.end()));
  std::set<double> between;
  for (double v : watch.Values)
  {
    if (v > 0.0 && v < 1.0)
    {
      between.insert(v);
    }
  }
  PI_CHECK(between.size() >= 2);

  // Cancelled at its first report after the start: it stops, with an empty output,
  // skipping the rest of its reports (VTK's executive still reports 1 at the end).
  const size_t reports = watch.Values.size();
  watch.Values.clear();
  watch.CancelAt = 1e-9;
  algorithm->Modified();
  algorithm->Update();
  PI_CHECK(algorithm->GetOutput()->GetNumberOfCells() == 0);
  PI_CHECK(watch.Values.size() < reports);

  if (late > 0)
  {
    algorithm->SetAbortExecute(0);
    watch.Values.clear();
    watch.CancelAt = late;
    algorithm->Modified();
    algorithm->Update();
    // The cancel happens only if a report in [late, 1) came before the end: the last
    // pass reports from one thread at the start of its chunks, and how many chunks
    // that thread gets, and when, depends on the scheduler and the machine's load.
    const bool cancelled = std::any_of(
      watch.Values.begin(), watch.Values.end(), [late](double v) { return v >= late && v < 1.0; });
    PI_CHECK(!cancelled || algorithm->GetOutput()->GetNumberOfCells() == 0);
  }

  // The cancel cleared, the next run is whole again.
  algorithm->SetAbortExecute(0);
  watch.Values.clear();
  watch.CancelAt = 2.0;
  algorithm->Modified();
  algorithm->Update();
  PI_CHECK(algorithm->GetOutput()->GetNumberOfCells() == cells);
  PI_CHECK(!watch.Values.empty() && watch.Values.back() == 1.0);

  algorithm->RemoveObserver(tag);
  if (failures)
  {
    std::cerr << "  in " << name << "\n";
  }
  return failures;
}
}

int TestPiProgressAbort(int, char*[])
{
  int failures = 0;

  vtkNew<vtkPiFlyingEdges> mesher;
  mesher->SetPiSurface(pitest::LoadModel("cup_a1.0"));
  mesher->SetResolution(96);
  // Also cancelled while it moves the vertices onto F = 0 (progress 0.75 to 1).
  failures += Check("vtkPiFlyingEdges", mesher, 0.8);

  vtkNew<vtkPiRayCaster> caster;
  caster->SetPiSurface(pitest::LoadModel("cup_a1.0"));
  caster->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
  caster->SetResolution(96, 96);
  failures += Check("vtkPiRayCaster", caster);

  vtkNew<vtkPiRayCaster> cloud;
  cloud->SetPiSurface(pitest::LoadModel("cup_a1.0"));
  cloud->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
  cloud->SetResolution(96, 96);
  cloud->Update();
  vtkNew<vtkPiImageTriangulator> triangulator;
  triangulator->SetInputData(cloud->GetOutput());
  failures += Check("vtkPiImageTriangulator", triangulator);

  // The Pi Surface source's ray-cast method: the work is in its inner caster and
  // triangulator.
  std::ifstream file(pitest::ModelPath("cup_a1.0"));
  std::stringstream json;
  json << file.rdbuf();
  vtkNew<vtkPiSurfaceSource> source;
  source->SetModel(json.str().c_str());
  source->SetMethod(vtkPiSurfaceSource::RAY_CAST_TRIANGULATION);
  source->SetResolution(64);
  failures += Check("vtkPiSurfaceSource (ray cast triangulation)", source);

  // The molecular surface: the work is in its inner mesher.
  vtkNew<vtkCMLMoleculeReader> reader;
  reader->SetFileName("/usr/share/chemical-structures/carboxylic_acids/formic_acid.cml");
  for (int mode : { vtkPiMoleculeSurface::GLOBAL, vtkPiMoleculeSurface::LOCAL })
  {
    vtkNew<vtkPiMoleculeSurface> surface;
    surface->SetInputConnection(reader->GetOutputPort());
    surface->SetMode(mode);
    surface->SetSpacing(0.2);
    // Also cancelled during its mesher's vertex pass (0.725 to 0.95 of its progress).
    failures += Check(mode == vtkPiMoleculeSurface::LOCAL ? "vtkPiMoleculeSurface (Local)"
                                                          : "vtkPiMoleculeSurface (Global)",
      surface, 0.75);
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
