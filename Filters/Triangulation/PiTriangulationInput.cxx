// SPDX-License-Identifier: BSD-3-Clause
// Unpacks the views (PiRayViews), the cloud (the input's arrays themselves when they
// have the caster's types), the model and the size of the scene.
#include "PiTriangulationInput.h"

#include "vtkFieldData.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"

#include <functional>
#include <limits>
#include <string>
#include <type_traits>

namespace pisurf
{
namespace triangulator
{
namespace
{
// Reads a point array as doubles; nullptr if absent.
vtkDataArray* Array(vtkPointData* pd, const char* name, int components)
{
  vtkDataArray* a = pd->GetArray(name);
  return a && a->GetNumberOfComponents() == components ? a : nullptr;
}
}

bool TriangulationInput::Read(vtkPolyData* input, Triangulation& T, pisurf::PassTimer& lap)
{
  // The pixel structure: PixelIndex, ViewIndex, Depth, Normals and PiRayViews.
  vtkPointData* pd = input->GetPointData();
  vtkDataArray* pixel = this->Pixel = Array(pd, "PixelIndex", 2);
  vtkDataArray* viewIndex = this->ViewIndex = Array(pd, "ViewIndex", 1);
  vtkDataArray* depth = this->Depth = Array(pd, "Depth", 1);
  vtkDataArray* normals = this->Normals = Array(pd, "Normals", 3);
  auto* viewData =
    vtkDataArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("PiRayViews"));
  if (!pixel || !viewIndex || !depth || !normals || !viewData ||
    viewData->GetNumberOfComponents() < 16)
  {
    vtkErrorWithObjectMacro(
      T.Algorithm, << "The input has no pixel structure: it needs the point arrays PixelIndex, "
                      "ViewIndex, Depth and Normals and the field data PiRayViews of a Pi Ray "
                      "Cast (vtkPiRayCaster) output");
    return false;
  }
  if (!this->ReadViews(viewData, T) || !this->ReadCloud(input, T) || !this->CheckCloud(T))
  {
    return false;
  }
  lap("input unpacked");
  if (!this->ReadModel(input, T))
  {
    return false;
  }
  this->MeasureSize(T);
  lap("model and size");
  return true;
}

bool TriangulationInput::ReadViews(vtkDataArray* viewData, Triangulation& T)
{
  for (vtkIdType v = 0; v < viewData->GetNumberOfTuples(); ++v)
  {
    double t[17] = {};
    for (int c = 0; c < std::min(17, viewData->GetNumberOfComponents()); ++c)
    {
      t[c] = viewData->GetComponent(v, c);
    }
    View view;
    view.Perspective = t[0] != 0;
    view.W = static_cast<int>(t[1]);
    view.H = static_cast<int>(t[2]);
    std::copy(t + 3, t + 6, view.O);
    std::copy(t + 6, t + 9, view.U);
    std::copy(t + 9, t + 12, view.V);
    std::copy(t + 12, t + 15, view.D);
    view.Length = t[15];
    view.AllHits = t[16] != 0;
    bool finite = true;
    for (double x : t)
    {
      finite = finite && std::isfinite(x);
    }
    if (!finite || view.W < 1 || view.H < 1 || !(vtkMath::Norm(view.D) > 0) ||
      !(vtkMath::Norm(view.U) > 0) || !(vtkMath::Norm(view.V) > 0) || view.Length < 0)
    {
      vtkErrorWithObjectMacro(
        T.Algorithm, << "PiRayViews: view " << v << " is not a valid view definition");
      return false;
    }
    // An axis view: rays along ±e_a, u along e_(a+1), v along e_(a+2), as the caster
    // casts them.
    if (!view.Perspective)
    {
      for (int a = 0; a < 3; ++a)
      {
        const int ua = (a + 1) % 3, va = (a + 2) % 3;
        const double d = vtkMath::Norm(view.D);
        if (std::fabs(std::fabs(view.D[a]) - d) <= 1e-12 * d && view.U[ua] > 0 && view.V[va] > 0 &&
          view.U[a] == 0 && view.U[va] == 0 && view.V[a] == 0 && view.V[ua] == 0)
        {
          view.Axis = a;
          view.Sense = view.D[a] < 0 ? -1 : 1;
        }
      }
    }
    T.Views.push_back(view);
  }
  if (T.Views.empty())
  {
    vtkErrorWithObjectMacro(T.Algorithm, << "PiRayViews holds no view");
    return false;
  }
  return true;
}

// The cloud: the input's arrays themselves when they have the caster's types,
// converted copies otherwise (filled in parallel).
bool TriangulationInput::ReadCloud(vtkPolyData* input, Triangulation& t)
{
  vtkPointData* pd = input->GetPointData();
  Cloud& C = t.C;
  C.N = input->GetNumberOfPoints();
  vtkDataArray* singular = Array(pd, "Singular", 1);
  vtkDataArray* tangent = Array(pd, "Tangent", 1);
  vtkDataArray* factor = Array(pd, "Factor", 1);
  vtkDataArray* xyzIn = C.N > 0 ? input->GetPoints()->GetData() : nullptr;
  struct Copy
  {
    vtkDataArray* From;
    int Components;
    std::function<void(vtkIdType, const double*)> To;
  };
  std::vector<Copy> copies;
  auto column = [&](auto& c, vtkDataArray* a, int components, double absent)
  {
    using T = typename std::decay<decltype(c.Store)>::type::value_type;
    if (a && c.Borrow(a))
    {
      return;
    }
    T* out = c.Allocate(static_cast<size_t>(components) * C.N, static_cast<T>(absent));
    if (a)
    {
      copies.push_back({ a, components,
        [out, components](vtkIdType id, const double* v)
        {
          for (int k = 0; k < components; ++k)
          {
            // (integers out of range become −1: an invalid pixel or view)
            out[components * id + k] = std::is_integral<T>::value &&
                !(v[k] >= std::numeric_limits<T>::lowest() && v[k] <= std::numeric_limits<T>::max())
              ? static_cast<T>(-1)
              : static_cast<T>(v[k]);
          }
        } });
    }
  };
  column(C.P, xyzIn, 3, 0);
  column(C.Normal, this->Normals, 3, 0);
  column(C.Pixel, this->Pixel, 2, 0);
  column(C.ViewOf, this->ViewIndex, 1, 0);
  column(C.Depth, this->Depth, 1, 0);
  column(C.Singular, singular, 1, 0);
  column(C.Tangent, tangent, 1, 0);
  column(C.Factor, factor, 1, -1);
  if (!copies.empty())
  {
    vtkSMPTools::For(0, C.N,
      [&](vtkIdType b, vtkIdType e)
      {
        double v[9];
        for (vtkIdType id = b; id < e; ++id)
        {
          for (const Copy& c : copies)
          {
            c.From->GetTuple(id, v);
            if (c.From == singular || c.From == tangent)
            {
              v[0] = v[0] != 0 ? 1 : 0;
            }
            c.To(id, v);
          }
        }
      });
  }
  return true;
}

bool TriangulationInput::CheckCloud(Triangulation& T)
{
  const Cloud& C = T.C;
  // Checked in parallel; the first bad point (lowest id) is reported.
  std::atomic<vtkIdType> badPixel{ C.N }, badValue{ C.N };
  auto lower = [](std::atomic<vtkIdType>& bad, vtkIdType id)
  {
    vtkIdType seen = bad.load();
    while (id < seen && !bad.compare_exchange_weak(seen, id))
    {
    }
  };
  const int viewCount = static_cast<int>(T.Views.size());
  vtkSMPTools::For(0, C.N,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType id = b; id < e; ++id)
      {
        const int v = C.ViewOf[id], i = C.Pixel[2 * id], j = C.Pixel[2 * id + 1];
        if (v < 0 || v >= viewCount || i < 0 || j < 0 || i >= T.Views[v].W || j >= T.Views[v].H)
        {
          lower(badPixel, id);
          continue;
        }
        const double* p = C.P.data() + 3 * id;
        const float* n = C.Normal.data() + 3 * id;
        if (!std::isfinite(p[0] + p[1] + p[2]) || !std::isfinite(n[0] + n[1] + n[2]))
        {
          lower(badValue, id);
        }
      }
    });
  if (badPixel < C.N && badPixel <= badValue)
  {
    const vtkIdType id = badPixel;
    vtkErrorWithObjectMacro(T.Algorithm,
      << "Point " << id << ": pixel (" << this->Pixel->GetComponent(id, 0) << ", "
      << this->Pixel->GetComponent(id, 1) << ") of view " << this->ViewIndex->GetComponent(id, 0)
      << " is outside the views of PiRayViews");
    return false;
  }
  if (badValue < C.N)
  {
    vtkErrorWithObjectMacro(
      T.Algorithm, << "Point " << badValue.load() << " has a non-finite position or normal");
    return false;
  }
  return true;
}

bool TriangulationInput::ReadModel(vtkPolyData* input, Triangulation& T)
{
  // The model, when the input carries it (needed for what the views did not see): a
  // molecule's field (any size, either mode), else the product of PiSurfaceModel.
  auto* json = this->Json =
    vtkStringArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("PiSurfaceModel"));
  pisurf::MoleculeInput& molecule = this->Molecule;
  std::string moleculeError;
  if (!molecule.Read(input, moleculeError))
  {
    vtkErrorWithObjectMacro(T.Algorithm, << moleculeError);
    return false;
  }
  if (molecule.Present)
  {
    T.Model = molecule.MakeField(molecule.Bounds, moleculeError);
    if (!T.Model)
    {
      vtkErrorWithObjectMacro(T.Algorithm, << moleculeError);
      return false;
    }
  }
  else if (json && json->GetNumberOfValues() > 0)
  {
    if (!this->Surface->SetModelJSON(json->GetValue(0)))
    {
      vtkErrorWithObjectMacro(
        T.Algorithm, << "Invalid PiSurfaceModel: " << this->Surface->GetErrorMessage());
      return false;
    }
    std::shared_ptr<const pisurf::ProductKernel> kernel = this->Surface->GetKernel();
    if (!kernel)
    {
      vtkErrorWithObjectMacro(T.Algorithm, << "Invalid PiSurfaceModel: it has no product");
      return false;
    }
    T.Model = std::make_shared<pisurf::ProductField>(std::move(kernel));
  }
  if (T.Model)
  {
    T.Kernel = T.Model->GetProductKernel();
    T.Caster.reset(new pisurf::RayCaster(*T.Model));
  }
  return true;
}

void TriangulationInput::MeasureSize(Triangulation& T)
{
  const Cloud& C = T.C;
  double* box = this->Box;
  // The size of the scene: the extent of the views' rays and of the hits.
  const double empty[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  std::copy(empty, empty + 6, box);
  for (const View& v : T.Views)
  {
    for (int c = 0; c < 4; ++c)
    {
      double o[3], d[3];
      v.Ray(c % 2 ? v.W - 1 : 0, c / 2 ? v.H - 1 : 0, o, d);
      for (int k = 0; k < 3; ++k)
      {
        for (double p : { o[k], o[k] + v.Length * d[k] })
        {
          box[2 * k] = std::min(box[2 * k], p);
          box[2 * k + 1] = std::max(box[2 * k + 1], p);
        }
      }
    }
  }
  for (vtkIdType id = 0; id < C.N; ++id)
  {
    for (int k = 0; k < 3; ++k)
    {
      box[2 * k] = std::min(box[2 * k], C.P[3 * id + k]);
      box[2 * k + 1] = std::max(box[2 * k + 1], C.P[3 * id + k]);
    }
  }
  T.Size = std::sqrt((box[1] - box[0]) * (box[1] - box[0]) + (box[3] - box[2]) * (box[3] - box[2]) +
    (box[5] - box[4]) * (box[5] - box[4]));
  if (!(T.Size > 0))
  {
    T.Size = 1;
  }
}

} // namespace triangulator
} // namespace pisurf
