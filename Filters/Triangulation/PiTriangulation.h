// SPDX-License-Identifier: BSD-3-Clause
// The state every pass of vtkPiImageTriangulator shares: the views and the cloud of the
// input, the model that computes what the views did not see, and the output lists
// (triangles as keys, by row, and the points computed on F = 0).
#ifndef PiTriangulation_h
#define PiTriangulation_h

#include "PiBuffer.h"
#include "PiInputSurface.h"
#include "PiParallel.h"
#include "PiProductKernel.h"
#include "PiRayCaster.h"
#include "vtkPiImageTriangulator.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

// (a namespace of its own: the passes' short names stay clear of the other filters')
namespace pisurf
{
namespace triangulator
{
// A view as vtkPiRayCaster describes it in `PiRayViews`.
struct View
{
  bool Perspective = false;
  int W = 0, H = 0;
  double O[3], U[3], V[3], D[3];
  double Length = 0;
  bool AllHits = false;
  int Axis = -1; // an axis view: the axis of its rays, and their sense (±1)
  int Sense = 0;

  // The ray of pixel (i, j): origin and unit direction.
  void Ray(double i, double j, double o[3], double d[3]) const
  {
    for (int k = 0; k < 3; ++k)
    {
      o[k] = this->Perspective ? this->O[k] : this->O[k] + i * this->U[k] + j * this->V[k];
      d[k] = this->Perspective ? this->D[k] + i * this->U[k] + j * this->V[k] : this->D[k];
    }
    vtkMath::Normalize(d);
  }

  // Continuous pixel coordinates of p; false if p is behind a perspective eye.
  bool Project(const double p[3], double& i, double& j) const
  {
    double w[3] = { p[0] - this->O[0], p[1] - this->O[1], p[2] - this->O[2] };
    if (this->Perspective)
    {
      // p − eye = λ (D + iU + jV), with U and V orthogonal to the view axis.
      double f[3];
      vtkMath::Cross(this->U, this->V, f);
      if (vtkMath::Dot(f, this->D) < 0)
      {
        vtkMath::MultiplyScalar(f, -1.0);
      }
      const double lambda = vtkMath::Dot(w, f) / vtkMath::Dot(this->D, f);
      if (!(lambda > 0))
      {
        return false;
      }
      for (int k = 0; k < 3; ++k)
      {
        w[k] = w[k] / lambda - this->D[k];
      }
    }
    i = vtkMath::Dot(w, this->U) / vtkMath::Dot(this->U, this->U);
    j = vtkMath::Dot(w, this->V) / vtkMath::Dot(this->V, this->V);
    return true;
  }

  // The lateral distance between neighbouring rays at depth t.
  double Footprint(double t) const
  {
    const double s =
      std::sqrt(std::min(vtkMath::Dot(this->U, this->U), vtkMath::Dot(this->V, this->V)));
    return this->Perspective ? s * t / vtkMath::Norm(this->D) : s;
  }
};

// One attribute of the input cloud: the input array's own memory when it holds T (as
// vtkPiRayCaster's outputs do), or a converted copy.
template <typename T, typename ArrayT>
struct Column
{
  const T* Data = nullptr;
  std::vector<T> Store;

  // Borrows `a`; false (and nothing borrowed) if it is not an ArrayT.
  bool Borrow(vtkDataArray* a)
  {
    if (auto* typed = ArrayT::SafeDownCast(a))
    {
      this->Data = typed->GetPointer(0);
      return true;
    }
    return false;
  }
  T* Allocate(size_t n, T value)
  {
    this->Store.assign(n, value);
    this->Data = this->Store.data();
    return this->Store.data();
  }
  const T& operator[](size_t i) const { return this->Data[i]; }
  const T* data() const { return this->Data; }
};

// The input cloud.
struct Cloud
{
  vtkIdType N = 0;
  Column<double, vtkDoubleArray> P;
  Column<float, vtkFloatArray> Normal;
  Column<int, vtkIntArray> Pixel, ViewOf, Factor;
  Column<double, vtkDoubleArray> Depth;
  Column<unsigned char, vtkUnsignedCharArray> Singular, Tangent;
};

// A vertex of the output: an input hit, or a point computed on F = 0.
struct Computed
{
  std::int64_t Key;
  double P[3];
  int View;
  // From the exact gradient (Triangulation::Attributes): unit normal, the nearest
  // factor, the singular test.
  float N[3];
  int Nearest;
  bool Singular;
};

// Output keys: input hits are their point id (>= 0), points computed along lattice
// lines −(index + 1), roots computed on a lattice edge EdgeBit | edge id.
constexpr std::int64_t EdgeBit = std::int64_t(1) << 62;

// The work of one execution: the cloud, the views, the model, and the output lists.
struct Triangulation
{
  vtkPiImageTriangulator* Algorithm;
  Cloud C;
  std::vector<View> Views;
  // The model (pisurf::InputSurface::MakeField: a product or a molecule's field), or
  // null (all-hits views need none); Kernel: its product fast paths, or null.
  std::shared_ptr<const pisurf::Field> Model;
  const pisurf::ProductKernel* Kernel = nullptr;
  std::unique_ptr<pisurf::RayCaster> Caster;
  double Size = 1;
  std::vector<std::vector<std::int64_t>> Rows; // output keys, three per triangle, by row
  // computed points, by key (not initialized on allocation: the threads that compute
  // them write them)
  std::vector<Computed, pisurf::DefaultInitAllocator<Computed>> Points;
  std::atomic<bool> Abort{ false };
  bool ChooseDiagonals = true; // split lattice polygons by pisurf::Bend (else fan them)
  double Probe = 0, SingularTolerance = 0.1; // the singular test of computed points

  bool Aborted()
  {
    if (pisurf::SingleThread() && this->Algorithm->CheckAbort())
    {
      this->Abort = true;
    }
    return this->Abort;
  }

  // The exact-gradient attributes of a computed point (and its singular test, as the
  // ray caster's for its hits).
  void Attributes(Computed& c) const
  {
    double nrm[3] = { 0, 0, 0 }, g = 0;
    c.Nearest = -1;
    c.Singular = false;
    if (this->Caster)
    {
      c.Singular =
        this->Caster->Attributes(c.P, this->Probe, this->SingularTolerance, nrm, g, c.Nearest);
    }
    for (int k = 0; k < 3; ++k)
    {
      c.N[k] = static_cast<float>(nrm[k]);
    }
  }

  int Sign(const double p[3]) const
  {
    double logAbs;
    return this->Model ? (this->Model->EvaluateSignAndLog(p, logAbs) >= 0 ? 1 : 0) : 1;
  }

  // +1/−1: F has that sign on the whole box; 0: it may vanish there (or no model).
  int Classify(const double box[6]) const
  {
    return this->Model ? this->Model->ClassifyBox(box) : 1;
  }

  // sign(F)·ln(1 + |F|) (a model is there).
  double Compressed(const double p[3]) const { return this->Model->EvaluateCompressed(p); }
};

} // namespace triangulator
} // namespace pisurf

#endif
