// SPDX-License-Identifier: BSD-3-Clause
// Thread determinism: every threaded algorithm (the mesher, the ray caster, the image
// triangulator, the molecular surface, the grid sampler) gives bit-identical output with
// vtkSMPTools' Sequential and STDThread backends (4 threads on any machine, so work is really
// split). Points, cells, every point-data array and numeric field data are compared exactly.
#include "PiTestUtilities.h"

#include "vtkAbstractArray.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMolecule.h"
#include "vtkNew.h"
#include "vtkPiFlyingEdges.h"
#include "vtkPiImageTriangulator.h"
#include "vtkPiMoleculeReader.h"
#include "vtkPiMoleculeSurface.h"
#include "vtkPiRayCaster.h"
#include "vtkPiSampleFunction.h"
#include "vtkPiSurface.h"
#include "vtkPiSurfaceModelReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <string>

namespace
{
using Run = std::function<vtkSmartPointer<vtkDataObject>()>;

vtkSmartPointer<vtkDataObject> WithBackend(const char* backend, const Run& run)
{
  if (!vtkSMPTools::SetBackend(backend))
  {
    std::cerr << "backend " << backend << " is not available" << std::endl;
    return nullptr;
  }
  vtkSMPTools::Initialize(std::strcmp(backend, "Sequential") == 0 ? 1 : 4);
  return run();
}

// Bytes of every value of a data array (exact comparison, NaN-safe).
bool SameArray(vtkAbstractArray* a, vtkAbstractArray* b, const std::string& what)
{
  if (!a || !b || a->GetNumberOfValues() != b->GetNumberOfValues() ||
    a->GetDataType() != b->GetDataType() ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents())
  {
    std::cerr << what << ": arrays differ in presence, size, type or components" << std::endl;
    return false;
  }
  auto* da = vtkDataArray::SafeDownCast(a);
  auto* db = vtkDataArray::SafeDownCast(b);
  if (!da || !db)
  {
    for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
    {
      if (a->GetVariantValue(i) != b->GetVariantValue(i))
      {
        std::cerr << what << ": value " << i << " differs" << std::endl;
        return false;
      }
    }
    return true;
  }
  const size_t bytes = size_t(a->GetNumberOfValues()) * a->GetDataTypeSize();
  if (bytes && std::memcmp(da->GetVoidPointer(0), db->GetVoidPointer(0), bytes) != 0)
  {
    std::cerr << what << ": values differ" << std::endl;
    return false;
  }
  return true;
}

bool SameFieldData(vtkFieldData* a, vtkFieldData* b, const std::string& what)
{
  bool same = a->GetNumberOfArrays() == b->GetNumberOfArrays();
  for (int i = 0; same && i < a->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* x = a->GetAbstractArray(i);
    same = SameArray(x, b->GetAbstractArray(x->GetName()), what + "." + x->GetName());
  }
  if (!same)
  {
    std::cerr << what << ": different arrays" << std::endl;
  }
  return same;
}

bool SamePolyData(vtkPolyData* a, vtkPolyData* b, const std::string& what)
{
  if (!a || !b)
  {
    return false;
  }
  if (a->GetNumberOfPoints() != b->GetNumberOfPoints() ||
    a->GetNumberOfCells() != b->GetNumberOfCells())
  {
    std::cerr << what << ": " << a->GetNumberOfPoints() << " vs " << b->GetNumberOfPoints()
              << " points, " << a->GetNumberOfCells() << " vs " << b->GetNumberOfCells() << " cells"
              << std::endl;
    return false;
  }
  bool same = a->GetNumberOfPoints() == 0 ||
    SameArray(a->GetPoints()->GetData(), b->GetPoints()->GetData(), what + ".points");
  vtkCellArray* ca[2] = { a->GetPolys(), a->GetVerts() };
  vtkCellArray* cb[2] = { b->GetPolys(), b->GetVerts() };
  for (int k = 0; k < 2; ++k)
  {
    same = same &&
      SameArray(
        ca[k]->GetConnectivityArray(), cb[k]->GetConnectivityArray(), what + ".connectivity");
    same = same && SameArray(ca[k]->GetOffsetsArray(), cb[k]->GetOffsetsArray(), what + ".offsets");
  }
  same = same && SameFieldData(a->GetPointData(), b->GetPointData(), what + ".pointdata");
  same = same && SameFieldData(a->GetFieldData(), b->GetFieldData(), what + ".fielddata");
  return same;
}

// Runs the algorithm with both backends; the outputs must be identical and non-empty.
int Compare(const std::string& what, const Run& run)
{
  int failures = 0;
  vtkSmartPointer<vtkDataObject> sequential = WithBackend("Sequential", run);
  vtkSmartPointer<vtkDataObject> threaded = WithBackend("STDThread", run);
  if (auto* image = vtkImageData::SafeDownCast(sequential))
  {
    // A sampled grid: the same extent and the same bits in every point array.
    auto* other = vtkImageData::SafeDownCast(threaded);
    int e[6] = { 0, -1, 0, -1, 0, -1 }, f[6] = { 0, 0, 0, 0, 0, 0 };
    image->GetExtent(e);
    if (other)
    {
      other->GetExtent(f);
    }
    PI_CHECK(image->GetNumberOfPoints() > 100 && other && std::equal(e, e + 6, f));
    PI_CHECK(other && SameFieldData(image->GetPointData(), other->GetPointData(), what));
    std::cout << what << ": " << image->GetNumberOfPoints() << " grid values compared" << std::endl;
    return failures;
  }
  auto* a = vtkPolyData::SafeDownCast(sequential);
  auto* b = vtkPolyData::SafeDownCast(threaded);
  PI_CHECK(a && a->GetNumberOfPoints() > 100);
  PI_CHECK(SamePolyData(a, b, what));
  std::cout << what << ": " << (a ? a->GetNumberOfPoints() : 0) << " points compared" << std::endl;
  return failures;
}

}

int TestPiThreads(int, char*[])
{
  int failures = 0;
  const std::string original = vtkSMPTools::GetBackend();

  // The mesher: the cup (polynomial factors, octant classification, envelope flood).
  failures += Compare("mesher cup",
    []
    {
      vtkNew<vtkPiFlyingEdges> mesher;
      mesher->SetPiSurface(pitest::LoadModel("cup_a1.0.pisurf"));
      mesher->SetResolution(96);
      mesher->SetComputeGradientMagnitude(true);
      mesher->Update();
      return vtkSmartPointer<vtkDataObject>(mesher->GetOutput());
    });
  // Formic acid at r = 1: the envelope flood (in parallel rounds) removes the two
  // lens-shaped interior shells.
  failures += Compare("mesher formic acid envelope",
    []
    {
      vtkNew<vtkPiFlyingEdges> mesher;
      mesher->SetPiSurface(pitest::LoadModel("formic_acid.pisurf"));
      mesher->SetResolution(96);
      mesher->Update();
      return vtkSmartPointer<vtkDataObject>(mesher->GetOutput());
    });
  // All sheets (no envelope) of the eggplant.
  failures += Compare("mesher eggplant all sheets",
    []
    {
      vtkNew<vtkPiFlyingEdges> mesher;
      mesher->SetPiSurface(pitest::LoadModel("eggplant_r0.25.pisurf"));
      mesher->SetResolution(80);
      mesher->SetOuterEnvelope(false);
      mesher->Update();
      return vtkSmartPointer<vtkDataObject>(mesher->GetOutput());
    });
  // The ray caster: six axis views with all hits (the hits, their arrays, the views).
  failures += Compare("ray caster table",
    []
    {
      vtkNew<vtkPiRayCaster> caster;
      caster->SetPiSurface(pitest::LoadModel("table.pisurf"));
      caster->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
      caster->SetAllHits(true);
      caster->SetResolution(96, 80);
      caster->Update();
      return vtkSmartPointer<vtkDataObject>(caster->GetOutput());
    });
  // A perspective camera.
  failures += Compare("ray caster camera",
    []
    {
      vtkNew<vtkPiRayCaster> caster;
      caster->SetPiSurface(pitest::LoadModel("cup_a1.0.pisurf"));
      caster->SetViewMode(vtkPiRayCaster::CAMERA);
      caster->SetCameraPosition(0.6, -9, 1.5);
      caster->SetCameraFocalPoint(0.6, 0, -1.15);
      caster->SetCameraViewUp(0, 0, 1);
      caster->SetResolution(120, 90);
      caster->Update();
      return vtkSmartPointer<vtkDataObject>(caster->GetOutput());
    });
  // The image triangulator in both merge modes.
  for (int mode : { vtkPiImageTriangulator::RAY_LATTICE, vtkPiImageTriangulator::BEST_VIEW })
  {
    failures += Compare(std::string("triangulator mode ") + std::to_string(mode),
      [mode]
      {
        vtkNew<vtkPiRayCaster> caster;
        caster->SetPiSurface(pitest::LoadModel("eggplant_r0.25.pisurf"));
        caster->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
        caster->SetResolution(64, 64);
        vtkNew<vtkPiImageTriangulator> triangulator;
        triangulator->SetInputConnection(caster->GetOutputPort());
        triangulator->SetMergeMode(mode);
        triangulator->Update();
        return vtkSmartPointer<vtkDataObject>(triangulator->GetOutput());
      });
  }
  // The molecular surface of a protein in both modes (far-field cells built lazily by
  // whichever thread comes first).
  for (int mode : { vtkPiMoleculeSurface::GLOBAL, vtkPiMoleculeSurface::LOCAL })
  {
    failures += Compare(std::string("molecule 1ubq mode ") + std::to_string(mode),
      [mode]
      {
        vtkNew<vtkPiMoleculeReader> reader;
        reader->SetFileName("/usr/share/freesasa/test-data/1ubq.pdb");
        vtkNew<vtkPiMoleculeSurface> surface;
        surface->SetInputConnection(reader->GetOutputPort());
        surface->SetMode(mode);
        surface->SetSpacing(0.6);
        surface->Update();
        return vtkSmartPointer<vtkDataObject>(surface->GetOutput());
      });
  }
  // The grid sampler: rows split between threads.
  failures += Compare("sampler cup",
    []
    {
      vtkNew<vtkPiSampleFunction> sampler;
      sampler->SetPiSurface(pitest::LoadModel("cup_a1.0.pisurf"));
      sampler->SetSampleDimensions(70, 50, 40);
      sampler->Update();
      return vtkSmartPointer<vtkDataObject>(sampler->GetOutput());
    });
  vtkSMPTools::SetBackend(original.c_str());
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
