// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiImageTriangulator.h"
#include "PiBuffer.h"
#include "PiParallel.h"
#include "PiLargeArrays.h"
#include "PiEdgeFlips.h"
#include "PiInputModel.h"
#include "PiPieces.h"
#include "PiTiming.h"
#include "PiProduct.h"
#include "PiRayCast.h"
#include "vtkPiSurface.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "PiMarchingCubes.h"
#include "vtkMarchingCubesTriangleCases.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iostream>
#include <cstdlib>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkPiImageTriangulator);

namespace
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
    const double s = std::sqrt(std::min(vtkMath::Dot(this->U, this->U), vtkMath::Dot(this->V, this->V)));
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

// The marching-cubes polygons of each case: the triangles of vtkMarchingCubesTriangleCases
// grouped by shared diagonals, each group's outline as a cycle of cell edges. A case's
// triangles that do not form a disk stay triangles.
const std::array<std::vector<std::vector<int>>, 256>& PolygonTable()
{
  static const std::array<std::vector<std::vector<int>>, 256> table = [] {
    std::array<std::vector<std::vector<int>>, 256> t;
    vtkMarchingCubesTriangleCases* cases = vtkMarchingCubesTriangleCases::GetCases();
    for (int index = 0; index < 256; ++index)
    {
      std::vector<std::array<int, 3>> tris;
      for (const int* e = cases[index].edges; *e >= 0; e += 3)
      {
        tris.push_back({ e[0], e[1], e[2] });
      }
      const int k = static_cast<int>(tris.size());
      std::vector<int> group(k);
      for (int a = 0; a < k; ++a)
      {
        group[a] = a;
      }
      std::function<int(int)> root = [&](int a) { return group[a] == a ? a : root(group[a]); };
      for (int a = 0; a < k; ++a)
      {
        for (int b = a + 1; b < k; ++b)
        {
          int shared = 0;
          for (int x : tris[a])
          {
            shared += std::count(tris[b].begin(), tris[b].end(), x) ? 1 : 0;
          }
          if (shared == 2)
          {
            group[root(b)] = root(a);
          }
        }
      }
      for (int g = 0; g < k; ++g)
      {
        if (root(g) != g)
        {
          continue;
        }
        // Sides used once in the group form its outline.
        std::vector<std::pair<int, int>> sides;
        for (int a = 0; a < k; ++a)
        {
          if (root(a) != g)
          {
            continue;
          }
          for (int c = 0; c < 3; ++c)
          {
            sides.emplace_back(tris[a][c], tris[a][(c + 1) % 3]);
          }
        }
        std::vector<std::pair<int, int>> outline;
        for (const auto& x : sides)
        {
          int uses = 0;
          for (const auto& y : sides)
          {
            uses += (x == y || (x.first == y.second && x.second == y.first)) ? 1 : 0;
          }
          if (uses == 1)
          {
            outline.push_back(x);
          }
        }
        std::vector<int> cycle{ outline.empty() ? -1 : outline[0].first };
        bool disk = !outline.empty();
        while (disk && cycle.size() < outline.size())
        {
          int next = -1;
          for (const auto& x : outline)
          {
            const int from = cycle.back();
            const int previous = cycle.size() > 1 ? cycle[cycle.size() - 2] : -1;
            const int other = x.first == from ? x.second : x.second == from ? x.first : -1;
            if (other >= 0 && other != previous && other != cycle[0])
            {
              next = other;
              break;
            }
          }
          disk = next >= 0;
          cycle.push_back(next);
        }
        if (disk && cycle.size() == outline.size())
        {
          t[index].push_back(cycle);
        }
        else
        {
          for (int a = 0; a < k; ++a)
          {
            if (root(a) == g)
            {
              t[index].push_back({ tris[a][0], tris[a][1], tris[a][2] });
            }
          }
        }
      }
    }
    return t;
  }();
  return table;
}

// Output keys: input hits are their point id (>= 0), points computed along lattice
// lines −(index + 1), roots computed on a lattice edge EdgeBit | edge id.
constexpr std::int64_t EdgeBit = std::int64_t(1) << 62;

// The lattice of RAY_LATTICE: per axis N pixel centres and the two planes of the box.
struct Lattice
{
  int N[3];
  double H[3], B0[3], B1[3];
  vtkIdType LineStart[4]; // first line of each axis, and the total

  double X(int a, int m) const
  {
    return m <= 0 ? this->B0[a] : m > this->N[a] ? this->B1[a] : this->B0[a] + (m - 0.5) * this->H[a];
  }
  // The line of axis a through interior nodes mu (axis a+1) and mv (axis a+2), 1-based.
  vtkIdType Line(int a, int mu, int mv) const
  {
    return this->LineStart[a] + vtkIdType(mv - 1) * this->N[(a + 1) % 3] + (mu - 1);
  }
  bool HasLine(int a, int mu, int mv) const
  {
    return mu >= 1 && mu <= this->N[(a + 1) % 3] && mv >= 1 && mv <= this->N[(a + 2) % 3];
  }
};

// A root on a lattice line: 16 bytes (a line's few samples share a cache line).
struct Sample
{
  double X;            // coordinate along the line's axis
  std::int64_t Packed; // 2·(output key) + (1 if tangent); INT64_MIN: removed

  Sample() = default;
  Sample(double x, std::int64_t code, bool tangent)
    : X(x)
    , Packed(2 * code + (tangent ? 1 : 0))
  {
  }
  // The smallest sample at x (before every sample there).
  static Sample Lowest(double x)
  {
    Sample s;
    s.X = x;
    s.Packed = INT64_MIN;
    return s;
  }
  std::int64_t Code() const { return this->Packed >> 1; }
  bool Tangent() const { return (this->Packed & 1) != 0; }
  bool Removed() const { return this->Packed == INT64_MIN; }
  void Remove() { this->Packed = INT64_MIN; }
  void SetCode(std::int64_t code) { this->Packed = 2 * code + (this->Packed & 1); }
  // (by X, then by key: the key decides as before, since a line holds a key once)
  bool operator<(const Sample& o) const
  {
    return this->X < o.X || (this->X == o.X && this->Packed < o.Packed);
  }
};

// Reads a point array as doubles; nullptr if absent.
vtkDataArray* Array(vtkPointData* pd, const char* name, int components)
{
  vtkDataArray* a = pd->GetArray(name);
  return a && a->GetNumberOfComponents() == components ? a : nullptr;
}
}

vtkPiImageTriangulator::vtkPiImageTriangulator() = default;
vtkPiImageTriangulator::~vtkPiImageTriangulator() = default;

int vtkPiImageTriangulator::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

namespace
{
// The work of one execution: the cloud, the views, the model, and the output lists.
struct Triangulation
{
  vtkPiImageTriangulator* Algorithm;
  Cloud C;
  std::vector<View> Views;
  // The model: a product (PiSurfaceModel), or a molecule's field (PiInputModel.h), or
  // neither (all-hits views need none).
  std::shared_ptr<const pisurf::ProductKernel> Kernel;
  std::unique_ptr<pisurf::MoleculeField> Molecule;
  std::unique_ptr<pisurf::RayCaster> Caster;
  double Size = 1;
  std::vector<std::vector<std::int64_t>> Rows; // output keys, three per triangle, by row
  // computed points, by key (not initialized on allocation: the threads that compute
  // them write them)
  std::vector<Computed, pisurf::DefaultInitAllocator<Computed>> Points;
  std::atomic<bool> Abort{ false };
  bool ChooseDiagonals = true; // split lattice polygons by PiBend (else fan them)
  double Probe = 0, SingularTolerance = 0.1; // the singular test of computed points

  bool Aborted()
  {
    if (PiSingleThread() && this->Algorithm->CheckAbort())
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
    if (this->Molecule)
    {
      return this->Molecule->Evaluate(p) >= 0 ? 1 : 0;
    }
    return this->Kernel ? (this->Kernel->EvaluateSignAndLog(p, logAbs) >= 0 ? 1 : 0) : 1;
  }

  // +1/−1: F has that sign on the whole box; 0: it may vanish there (or no model).
  int Classify(const double box[6]) const
  {
    return this->Kernel ? this->Kernel->ClassifyBox(box)
                        : this->Molecule ? this->Molecule->ClassifyBox(box) : 1;
  }

  // sign(F)·ln(1 + |F|) (a model is there).
  double Compressed(const double p[3]) const
  {
    return this->Kernel ? this->Kernel->EvaluateCompressed(p) : this->Molecule->EvaluateCompressed(p);
  }

  // RAY_LATTICE ------------------------------------------------------------------
  bool FindLattice(Lattice& L) const;
  void RunLattice(const Lattice& L);

  // BEST_VIEW --------------------------------------------------------------------
  void RunBestView(double sheetTolerance);
};

bool Triangulation::FindLattice(Lattice& L) const
{
  // Every view must be an axis view; each defines the lattice along its u and v axes
  // and the box along its own axis. All of them must agree.
  bool defined[3] = { false, false, false }, box[3] = { false, false, false };
  bool axis[3] = { false, false, false };
  const double tol = 1e-9 * this->Size;
  auto define = [&](int a, int n, double h, double b0) {
    if (!(h > 0) || n < 1)
    {
      return false;
    }
    if (!defined[a])
    {
      defined[a] = true;
      L.N[a] = n;
      L.H[a] = h;
      L.B0[a] = b0;
      return true;
    }
    return L.N[a] == n && std::fabs(L.H[a] - h) <= tol && std::fabs(L.B0[a] - b0) <= tol;
  };
  double range[3][2];
  for (const View& v : this->Views)
  {
    if (v.Axis < 0)
    {
      return false;
    }
    const int a = v.Axis, ua = (a + 1) % 3, va = (a + 2) % 3;
    if (!define(ua, v.W, v.U[ua], v.O[ua] - 0.5 * v.U[ua]) ||
      !define(va, v.H, v.V[va], v.O[va] - 0.5 * v.V[va]))
    {
      return false;
    }
    const double lo = v.Sense < 0 ? v.O[a] - v.Length : v.O[a];
    const double hi = lo + v.Length;
    if (box[a] && (std::fabs(range[a][0] - lo) > tol || std::fabs(range[a][1] - hi) > tol))
    {
      return false;
    }
    box[a] = true;
    axis[a] = true;
    range[a][0] = lo;
    range[a][1] = hi;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!axis[a] || !defined[a] ||
      std::fabs(L.B0[a] - range[a][0]) > tol ||
      std::fabs(L.B0[a] + L.N[a] * L.H[a] - range[a][1]) > tol)
    {
      return false;
    }
    L.B1[a] = range[a][1];
  }
  L.LineStart[0] = 0;
  for (int a = 0; a < 3; ++a)
  {
    L.LineStart[a + 1] = L.LineStart[a] + vtkIdType(L.N[(a + 1) % 3]) * L.N[(a + 2) % 3];
  }
  return true;
}

void Triangulation::RunLattice(const Lattice& L)
{
  // PISURF_TIMING=1: the wall time of each pass on stderr.
  PiPassTimer lap("vtkPiImageTriangulator");
  const double tol = 1e-9 * this->Size;
  const vtkIdType lines = L.LineStart[3];

  // PASS 1: the hits of every lattice line, sorted along it; duplicates (the same
  // root seen from both ends of a line) kept once.
  // (counted and filled by all threads: the order of a line's samples is then the
  // threads' order, and the sort below makes it the same every time)
  // first[l]: where the samples of line l start (first[lines]: their number). It counts
  // each line's hits, becomes by the sums the end of each line, and the fill (from each
  // end backwards) leaves it at each line's start.
  std::unique_ptr<std::atomic<vtkIdType>[]> first(new std::atomic<vtkIdType>[lines + 1]);
  auto lineOf = [&](vtkIdType id) {
    const View& v = this->Views[this->C.ViewOf[id]];
    return L.Line(v.Axis, this->C.Pixel[2 * id] + 1, this->C.Pixel[2 * id + 1] + 1);
  };
  vtkSMPTools::For(0, lines + 1, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType l = b; l < e; ++l)
    {
      first[l].store(0, std::memory_order_relaxed);
    }
  });
  vtkSMPTools::For(0, this->C.N, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType id = b; id < e; ++id)
    {
      first[lineOf(id)].fetch_add(1, std::memory_order_relaxed);
    }
  });
  for (vtkIdType l = 1; l < lines; ++l)
  {
    first[l].store(first[l].load(std::memory_order_relaxed) + first[l - 1].load(std::memory_order_relaxed),
      std::memory_order_relaxed);
  }
  first[lines].store(this->C.N, std::memory_order_relaxed);
  std::unique_ptr<Sample[]> samples(new Sample[this->C.N]);
  vtkSMPTools::For(0, this->C.N, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType id = b; id < e; ++id)
    {
      const View& v = this->Views[this->C.ViewOf[id]];
      samples[first[lineOf(id)].fetch_sub(1, std::memory_order_relaxed) - 1] = {
        this->C.P[3 * id + v.Axis], id, this->C.Tangent[id] != 0
      };
    }
  });

  // Which part of each line the views have not seen: all-hits views see everything;
  // a first-hit view looking along −a sees down to its first hit, one along +a up to
  // its first hit. The hidden part is cast here with the certified root finder.
  bool allHits[3] = { false, false, false }, minus[3] = { false, false, false },
       plus[3] = { false, false, false };
  for (const View& v : this->Views)
  {
    allHits[v.Axis] |= v.AllHits;
    (v.Sense < 0 ? minus : plus)[v.Axis] = true;
  }
  lap("lines filled");
  // The hidden roots: their number per line, and the roots themselves per range of
  // lines that one call of the functor below casts (in line order).
  std::unique_ptr<std::int32_t[]> hiddenCount(new std::int32_t[lines]);
  struct HiddenRange
  {
    vtkIdType Begin;
    std::vector<Sample> Roots;
  };
  std::vector<HiddenRange> hiddenRanges;
  std::mutex hiddenMutex;
  std::atomic<bool> missingModel{ false };
  // The lines of axis a are the rays of an orthographic grid (the pixels of the views
  // along a): polynomial products restrict them from one composition per axis
  // (pisurf::RayGrid) instead of a trivariate restriction per line.
  std::unique_ptr<pisurf::RayGrid> grids[3];
  if (this->Kernel && this->Kernel->IsPolynomial())
  {
    for (int a = 0; a < 3; ++a)
    {
      const int ua = (a + 1) % 3, va = (a + 2) % 3;
      double o[3], u[3] = { 0, 0, 0 }, v[3] = { 0, 0, 0 }, d[3] = { 0, 0, 0 };
      o[a] = L.B0[a];
      o[ua] = L.X(ua, 1);
      o[va] = L.X(va, 1);
      u[ua] = L.H[ua];
      v[va] = L.H[va];
      d[a] = 1;
      grids[a] = std::make_unique<pisurf::RayGrid>(
        *this->Kernel, o, u, v, d, L.N[ua], L.N[va], L.B1[a] - L.B0[a]);
    }
  }
  PiFor(0, lines, 2048, [&](vtkIdType begin, vtkIdType end) {
    std::vector<pisurf::RayRoot> roots;
    std::vector<double> row, coefficients;
    std::vector<Sample> found;
    vtkIdType rowOf = -1; // the (axis, mv) whose row coefficients `row` holds
    std::fill(hiddenCount.get() + begin, hiddenCount.get() + end, 0);
    for (vtkIdType l = begin; l < end && !this->Abort; ++l)
    {
      const int a = l >= L.LineStart[2] ? 2 : l >= L.LineStart[1] ? 1 : 0;
      Sample* s0 = samples.get() + first[l];
      Sample* s1 = samples.get() + first[l + 1];
      std::sort(s0, s1);
      if (allHits[a])
      {
        continue;
      }
      double lo = L.B0[a], hi = L.B1[a];
      bool empty = false;
      for (int sense = -1; sense <= 1; sense += 2)
      {
        if (!(sense < 0 ? minus : plus)[a])
        {
          continue;
        }
        // The first hit of that view on this line.
        const Sample* hit = nullptr;
        for (Sample* s = s0; s != s1; ++s)
        {
          if (this->Views[this->C.ViewOf[s->Code()]].Sense == sense)
          {
            if (!hit || (sense < 0 ? s->X > hit->X : s->X < hit->X))
            {
              hit = s;
            }
          }
        }
        if (!hit)
        {
          empty = true; // the view's ray missed: no root anywhere on the line
        }
        else if (sense < 0)
        {
          hi = hit->X;
        }
        else
        {
          lo = hit->X;
        }
      }
      if (empty || hi - lo <= 2 * tol)
      {
        continue;
      }
      // The views' hits end the hidden part; roots within tol of them are those hits
      // (dropped below), so the cast leaves them out instead of refining them again.
      lo += tol;
      hi -= tol;
      if (!this->Caster)
      {
        missingModel = true;
        continue;
      }
      const vtkIdType k = l - L.LineStart[a];
      const int mu = static_cast<int>(k % L.N[(a + 1) % 3]) + 1;
      const int mv = static_cast<int>(k / L.N[(a + 1) % 3]) + 1;
      pisurf::RayRootOptions options;
      options.Tolerance = 1e-10 * this->Size;
      double origin = lo; // roots come as X − origin
      if (const pisurf::RayGrid* grid = grids[a].get())
      {
        const vtkIdType rowKey = 3 * vtkIdType(mv) + a;
        if (rowKey != rowOf)
        {
          grid->SetRow(mv - 1, row);
          rowOf = rowKey;
        }
        coefficients.resize(this->Caster->GetLineCoefficientCount());
        grid->Restrict(row, mu - 1, coefficients.data());
        origin = L.B0[a] + grid->GetHalfLength();
        this->Caster->CastRestricted(coefficients.data(), lo - origin, hi - origin, options, roots);
      }
      else
      {
        double o[3], d[3] = { 0, 0, 0 };
        o[a] = lo;
        o[(a + 1) % 3] = L.X((a + 1) % 3, mu);
        o[(a + 2) % 3] = L.X((a + 2) % 3, mv);
        d[a] = 1;
        this->Caster->Cast(o, d, hi - lo, options, roots);
      }
      for (const pisurf::RayRoot& r : roots)
      {
        const double x = origin + r.T;
        if (x > lo && x < hi)
        {
          found.push_back({ x, 0, r.Tangent });
          ++hiddenCount[l];
        }
      }
    }
    if (!found.empty())
    {
      std::lock_guard<std::mutex> lock(hiddenMutex);
      hiddenRanges.push_back({ begin, std::move(found) });
    }
  });
  lap("sorted lines, hidden parts cast");
  if (missingModel)
  {
    vtkErrorWithObjectMacro(this->Algorithm,
      << "First-hit views hide part of the surface, and the input carries no "
         "PiSurfaceModel to compute it: use all hits or keep the model field data");
    this->Abort = true;
  }
  if (this->Abort)
  {
    return;
  }
  this->Algorithm->UpdateProgress(0.3);

  // The hidden roots become computed points on the rays of a view along their axis;
  // the lines are merged again.
  int lineView[3] = { -1, -1, -1 };
  for (size_t v = this->Views.size(); v-- > 0;)
  {
    lineView[this->Views[v].Axis] = static_cast<int>(v);
  }
  pisurf::Buffer<vtkIdType> start, hiddenStart;
  start.Allocate(lines + 1);
  hiddenStart.Allocate(lines + 1);
  start[0] = hiddenStart[0] = 0;
  for (vtkIdType l = 0; l < lines; ++l)
  {
    const vtkIdType h = hiddenCount[l];
    start[l + 1] = start[l] + (first[l + 1] - first[l]) + h;
    hiddenStart[l + 1] = hiddenStart[l] + h;
  }
  hiddenCount.reset();
  // All hidden roots in line order: each range's roots go where its first line's go.
  std::unique_ptr<Sample[]> hidden(new Sample[hiddenStart[lines]]);
  PiFor(0, static_cast<vtkIdType>(hiddenRanges.size()), 1, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType k = b; k < e; ++k)
    {
      const HiddenRange& range = hiddenRanges[k];
      std::copy(range.Roots.begin(), range.Roots.end(), hidden.get() + hiddenStart[range.Begin]);
    }
  });
  hiddenRanges.clear();
  // (not initialized on allocation: the threads below write every sample)
  std::unique_ptr<Sample[]> line(new Sample[start[lines]]);
  const size_t base = this->Points.size();
  this->Points.resize(base + hiddenStart[lines]);
  // (small ranges of lines: the hidden roots, whose attributes cost most here, crowd on
  // the lines through the solid's hidden parts, and eight ranges per thread would leave
  // one thread working alone at the end)
  PiFor(0, lines, 2048, [&](vtkIdType lb, vtkIdType le) {
    for (vtkIdType l = lb; l < le; ++l)
    {
      const int a = l >= L.LineStart[2] ? 2 : l >= L.LineStart[1] ? 1 : 0;
      Sample* out = line.get() + start[l];
      std::copy(samples.get() + first[l], samples.get() + first[l + 1], out);
      Sample* o = out + (first[l + 1] - first[l]);
      const vtkIdType k = l - L.LineStart[a];
      size_t index = base + hiddenStart[l];
      for (vtkIdType q = hiddenStart[l]; q < hiddenStart[l + 1]; ++q)
      {
        Sample s = hidden[q];
        Computed& c = this->Points[index];
        c.Key = -static_cast<std::int64_t>(index) - 1;
        c.P[a] = s.X;
        c.P[(a + 1) % 3] = L.X((a + 1) % 3, static_cast<int>(k % L.N[(a + 1) % 3]) + 1);
        c.P[(a + 2) % 3] = L.X((a + 2) % 3, static_cast<int>(k / L.N[(a + 1) % 3]) + 1);
        c.View = lineView[a];
        this->Attributes(c);
        s.SetCode(c.Key);
        ++index;
        *o++ = s;
      }
      std::sort(out, o);
      // A root seen from both ends of the line is one sample; the other copy is marked
      // removed in place, so the line stays sorted.
      const Sample* kept = nullptr;
      for (Sample* s = out; s != o; ++s)
      {
        if (kept && s->X - kept->X <= tol)
        {
          s->Remove();
          continue;
        }
        kept = s;
      }
    }
  });
  hidden.reset();
  samples.reset();

  // The valid samples of line l with X in [x0, x1), and the first non-tangent one.
  auto firstCrossing = [&](vtkIdType l, double x0, double x1) -> const Sample* {
    const Sample* b = line.get() + start[l];
    const Sample* e = line.get() + start[l + 1];
    const Sample* s = std::lower_bound(b, e, Sample::Lowest(x0));
    for (; s != e && s->X < x1; ++s)
    {
      if (!s->Removed() && !s->Tangent())
      {
        return s;
      }
    }
    return nullptr;
  };

  lap("lines merged");
  // PASS 2: the sign of F (1 outside, 0 inside) at the nodes of every z column:
  // on a lattice line the parity of the crossings below the node, on the planes of the
  // box F itself (certified constant on a whole face when interval bounds allow).
  const int nx = L.N[0] + 2, ny = L.N[1] + 2, nz = L.N[2] + 2;
  int faceSign[6];
  for (int f = 0; f < 6; ++f)
  {
    double b[6] = { L.B0[0], L.B1[0], L.B0[1], L.B1[1], L.B0[2], L.B1[2] };
    const int a = f / 2;
    b[2 * a] = b[2 * a + 1] = (f % 2 ? L.B1[a] : L.B0[a]);
    const int c = this->Classify(b);
    faceSign[f] = c == 0 ? -1 : (c > 0 ? 1 : 0);
  }
  auto nodeSign = [&](int i, int j, int m) {
    const double p[3] = { L.X(0, i), L.X(1, j), L.X(2, m) };
    return this->Sign(p);
  };
  // The z column through nodes (i, j): its sign at level 0, and the levels m after
  // which its sign flips (sorted; the sign at level m' > m is toggled).
  auto flipLevel = [&](double x) {
    int g = static_cast<int>(std::floor((x - L.B0[2]) / L.H[2] + 0.5));
    g = std::max(0, std::min(g, nz - 1));
    while (g + 1 < nz && L.X(2, g + 1) <= x)
    {
      ++g;
    }
    while (g > 0 && L.X(2, g) > x)
    {
      --g;
    }
    return g;
  };
  auto columnFlips = [&](int i, int j, std::vector<int>& flips,
                       std::vector<pisurf::RayRoot>& roots) -> unsigned char {
    const bool boundary = i == 0 || i == nx - 1 || j == 0 || j == ny - 1;
    if (boundary)
    {
      const int f = i == 0 ? 0 : i == nx - 1 ? 1 : j == 0 ? 2 : 3;
      if (faceSign[f] >= 0)
      {
        return static_cast<unsigned char>(faceSign[f]);
      }
      const int s0 = nodeSign(i, j, 0);
      if (this->Caster)
      {
        // A column on a plane of the box that no view casts: its roots, certified.
        const double o[3] = { L.X(0, i), L.X(1, j), L.B0[2] }, d[3] = { 0, 0, 1 };
        pisurf::RayRootOptions options;
        options.Tolerance = 1e-10 * this->Size;
        this->Caster->Cast(o, d, L.B1[2] - L.B0[2], options, roots);
        for (const pisurf::RayRoot& r : roots)
        {
          const int level = flipLevel(L.B0[2] + r.T);
          if (!r.Tangent && level < nz - 1)
          {
            flips.push_back(level);
          }
        }
        return static_cast<unsigned char>(s0);
      }
      int previous = s0;
      for (int m = 1; m < nz; ++m)
      {
        const int sm = nodeSign(i, j, m);
        if (sm != previous)
        {
          flips.push_back(m - 1);
        }
        previous = sm;
      }
      return static_cast<unsigned char>(s0);
    }
    const unsigned char sign = faceSign[4] >= 0 ? faceSign[4] : nodeSign(i, j, 0);
    const vtkIdType l = L.Line(2, i, j);
    for (const Sample* c = line.get() + start[l]; c != line.get() + start[l + 1]; ++c)
    {
      const int level = flipLevel(c->X);
      if (!c->Removed() && !c->Tangent() && level < nz - 1)
      {
        flips.push_back(level);
      }
    }
    return sign;
  };

  lap("node signs");
  // PASS 3: the marching-cubes triangles of every cell, one row of columns (fixed j)
  // per work item; vertices are the crossings on the cell's edges, looked up on their
  // lattice lines, or computed on the edge where no line carries one.
  const auto& polygons = PolygonTable();
  std::vector<std::vector<std::int64_t>> rowTriangles(ny - 1);
  std::vector<std::vector<Computed>> rowPoints(ny - 1);
  vtkSMPTools::For(0, ny - 1, [&](vtkIdType jb, vtkIdType je) {
    // Per row, the flips of the columns through (i, j) and (i, j + 1), as CSR lists.
    // (Side 1 of row j is side 0 of row j + 1: each column is computed once per chunk.)
    std::vector<int> flips[2];
    std::vector<size_t> offset[2];
    std::vector<unsigned char> startSign[2];
    std::vector<pisurf::RayRoot> roots;
    auto fillSide = [&](int side, int jn) {
      flips[side].clear();
      offset[side].assign(1, 0);
      startSign[side].clear();
      for (int i = 0; i < nx; ++i)
      {
        startSign[side].push_back(columnFlips(i, jn, flips[side], roots));
        offset[side].push_back(flips[side].size());
      }
    };
    size_t previousRow = 0; // keys of the row before: the next one has about as many
    for (vtkIdType jj = jb; jj < je && !this->Aborted(); ++jj)
    {
      const int j = static_cast<int>(jj);
      if (PiSingleThread())
      {
        this->Algorithm->UpdateProgress(0.3 + 0.6 * j / (ny - 1));
      }
      if (jj == jb)
      {
        fillSide(0, j);
      }
      else
      {
        std::swap(flips[0], flips[1]);
        std::swap(offset[0], offset[1]);
        std::swap(startSign[0], startSign[1]);
      }
      fillSide(1, j + 1);
      std::vector<std::int64_t>& tris = rowTriangles[j];
      tris.reserve(previousRow + previousRow / 4);
      std::vector<Computed>& pts = rowPoints[j];
      // The vertex on the edge along axis a from node (i, jn, m): its key, position and
      // normal (an edge root is computed into `c`).
      struct Ref
      {
        std::int64_t Key;
        const double* P;
        const float* N;
      };
      auto vertex = [&](int a, int i, int jn, int m, Computed& c) -> Ref {
        const int n[3] = { i, jn, m };
        const int mu = n[(a + 1) % 3], mv = n[(a + 2) % 3];
        if (L.HasLine(a, mu, mv))
        {
          if (const Sample* s = firstCrossing(L.Line(a, mu, mv), L.X(a, n[a]), L.X(a, n[a] + 1)))
          {
            const std::int64_t code = s->Code();
            if (code >= 0)
            {
              return { code, C.P.data() + 3 * code, C.Normal.data() + 3 * code };
            }
            const Computed& h = this->Points[-code - 1];
            return { code, h.P, h.N };
          }
        }
        // No line carries it (a plane of the box, or a root within 1e-10 of a node):
        // the root of F on the edge itself.
        const std::int64_t key =
          EdgeBit | ((((std::int64_t(m) * ny + jn) * nx + i) * 3) + a);
        c.Key = key;
        c.View = -1;
        double p0[3] = { L.X(0, i), L.X(1, jn), L.X(2, m) };
        c.P[0] = p0[0];
        c.P[1] = p0[1];
        c.P[2] = p0[2];
        if (this->Caster)
        {
          const double x0 = L.X(a, n[a]), x1 = L.X(a, n[a] + 1);
          auto phi = [&](double x) {
            double q[3] = { p0[0], p0[1], p0[2] };
            q[a] = x;
            return this->Compressed(q);
          };
          const double v0 = phi(x0), v1 = phi(x1);
          c.P[a] = (v0 < 0) != (v1 < 0)
            ? pisurf::BracketedRoot(phi, x0, x1, v0, v1, 1e-10 * this->Size, 0.0)
            : 0.5 * (x0 + x1);
        }
        else
        {
          c.P[a] = 0.5 * (L.X(a, n[a]) + L.X(a, n[a] + 1));
        }
        this->Attributes(c);
        pts.push_back(c);
        return { key, c.P, c.N };
      };
      auto emitCell = [&](int i, int m, const unsigned char* bottom, const unsigned char* top) {
        int index = 0;
        for (int q = 0; q < 4; ++q)
        {
          index |= (bottom[q] << q) | (top[q] << (q + 4));
        }
        if (index == 0 || index == 255)
        {
          return;
        }
        // Each polygon of the case (one per sheet through the cell) is triangulated
        // along the diagonals the surface bends least along (the least total PiBend,
        // dynamic programming over the polygon's triangulations; ties: the first).
        for (const std::vector<int>& polygon : polygons[index])
        {
          const int size = static_cast<int>(polygon.size());
          Ref v[12];
          Computed local[12];
          bool distinct = true;
          for (int k = 0; k < size; ++k)
          {
            // The marching-cubes edge as a lattice edge: axis and lower corner.
            const pisurf::mc::EdgeStart& x = pisurf::mc::EdgeStarts.Of[polygon[k]];
            v[k] = vertex(x.Axis, i + x.Lo[0], j + x.Lo[1], m + x.Lo[2], local[k]);
            for (int q = 0; q < k; ++q)
            {
              distinct = distinct && v[q].Key != v[k].Key;
            }
          }
          if (size == 3 || !distinct || !this->ChooseDiagonals)
          {
            // A fan from the first corner: no choice to make, EdgeFlipRounds 0, or two
            // corners on one hit (degenerate triangles are dropped later).
            for (int k = 1; k + 1 < size; ++k)
            {
              tris.push_back(v[0].Key);
              tris.push_back(v[k].Key);
              tris.push_back(v[k + 1].Key);
            }
            continue;
          }
          if (size == 4)
          {
            // (the common case: the shorter bend of the two diagonals)
            const int d = PiBend(v[0].P, v[0].N, v[2].P, v[2].N) <= PiBend(v[1].P, v[1].N, v[3].P, v[3].N) ? 0 : 1;
            for (int t = 0; t < 2; ++t)
            {
              tris.push_back(v[d].Key);
              tris.push_back(v[d + 1 + t].Key);
              tris.push_back(v[(d + 2 + t) % 4].Key);
            }
            continue;
          }
          double cost[12][12];
          int split[12][12];
          auto bend = [&](int a, int b) {
            return b == a + 1 || (a == 0 && b == size - 1) ? 0.0 : PiBend(v[a].P, v[a].N, v[b].P, v[b].N);
          };
          for (int k = 0; k + 1 < size; ++k)
          {
            cost[k][k + 1] = 0;
          }
          for (int length = 2; length < size; ++length)
          {
            for (int a = 0; a + length < size; ++a)
            {
              const int b = a + length;
              cost[a][b] = std::numeric_limits<double>::infinity();
              for (int k = a + 1; k < b; ++k)
              {
                const double c = cost[a][k] + cost[k][b] + bend(a, k) + bend(k, b);
                if (c < cost[a][b])
                {
                  cost[a][b] = c;
                  split[a][b] = k;
                }
              }
            }
          }
          int stack[24], top = 0;
          stack[top++] = 0;
          stack[top++] = size - 1;
          while (top > 0)
          {
            const int b = stack[--top], a = stack[--top];
            if (b - a < 2)
            {
              continue;
            }
            const int k = split[a][b];
            tris.push_back(v[a].Key);
            tris.push_back(v[k].Key);
            tris.push_back(v[b].Key);
            stack[top++] = a;
            stack[top++] = k;
            stack[top++] = k;
            stack[top++] = b;
          }
        }
      };
      for (int i = 0; i + 1 < nx; ++i)
      {
        // The four columns of the cells (i, j, ·) in marching-cubes corner order. Their
        // signs are constant between flips: a run of cells where the four disagree is
        // a wall (all active), where they agree it is skipped.
        const int side[4] = { 0, 0, 1, 1 }, column[4] = { i, i + 1, i + 1, i };
        const int* f[4];
        const int* fe[4];
        unsigned char sg[4];
        for (int q = 0; q < 4; ++q)
        {
          f[q] = flips[side[q]].data() + offset[side[q]][column[q]];
          fe[q] = flips[side[q]].data() + offset[side[q]][column[q] + 1];
          sg[q] = startSign[side[q]][column[q]];
        }
        for (int m = 0;;)
        {
          int e = nz - 1;
          for (int q = 0; q < 4; ++q)
          {
            if (f[q] != fe[q])
            {
              e = std::min(e, *f[q]);
            }
          }
          if (!(sg[0] == sg[1] && sg[1] == sg[2] && sg[2] == sg[3]))
          {
            for (int c = m; c < e && c < nz - 1; ++c)
            {
              emitCell(i, c, sg, sg);
            }
          }
          if (e >= nz - 1)
          {
            break;
          }
          unsigned char top[4] = { sg[0], sg[1], sg[2], sg[3] };
          for (int q = 0; q < 4; ++q)
          {
            for (; f[q] != fe[q] && *f[q] == e; ++f[q])
            {
              top[q] ^= 1;
            }
          }
          emitCell(i, e, sg, top);
          std::copy(top, top + 4, sg);
          m = e + 1;
        }
      }
      previousRow = tris.size();
    }
  });
  lap("cells");
  if (this->Abort)
  {
    return;
  }
  this->Rows = std::move(rowTriangles);
  for (auto& p : rowPoints)
  {
    this->Points.insert(this->Points.end(), p.begin(), p.end());
  }
}

void Triangulation::RunBestView(double sheetTolerance)
{
  const Cloud& C = this->C;
  // Per view and pixel, the hits sorted by depth (CSR).
  std::vector<vtkIdType> pixelStart(this->Views.size() + 1, 0);
  for (size_t v = 0; v < this->Views.size(); ++v)
  {
    pixelStart[v + 1] = pixelStart[v] + vtkIdType(this->Views[v].W) * this->Views[v].H;
  }
  auto pixelOf = [&](vtkIdType id) {
    const View& v = this->Views[C.ViewOf[id]];
    return pixelStart[C.ViewOf[id]] + vtkIdType(C.Pixel[2 * id + 1]) * v.W + C.Pixel[2 * id];
  };
  const vtkIdType pixels = pixelStart.back();
  std::vector<vtkIdType> first(pixels + 1, 0), hits(C.N);
  for (vtkIdType id = 0; id < C.N; ++id)
  {
    ++first[pixelOf(id) + 1];
  }
  for (vtkIdType p = 0; p < pixels; ++p)
  {
    first[p + 1] += first[p];
  }
  {
    std::vector<vtkIdType> fill(first.begin(), first.end() - 1);
    for (vtkIdType id = 0; id < C.N; ++id)
    {
      hits[fill[pixelOf(id)]++] = id;
    }
  }
  vtkSMPTools::For(0, pixels, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType p = b; p < e; ++p)
    {
      std::sort(hits.begin() + first[p], hits.begin() + first[p + 1],
        [&](vtkIdType x, vtkIdType y) { return C.Depth[x] < C.Depth[y]; });
    }
  });

  // n·d of every hit with its own ray, once (the links ask for it many times).
  std::vector<double> facingOf(C.N);
  vtkSMPTools::For(0, C.N, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType id = b; id < e; ++id)
    {
      const View& v = this->Views[C.ViewOf[id]];
      double o[3], d[3];
      v.Ray(C.Pixel[2 * id], C.Pixel[2 * id + 1], o, d);
      facingOf[id] =
        C.Normal[3 * id] * d[0] + C.Normal[3 * id + 1] * d[1] + C.Normal[3 * id + 2] * d[2];
    }
  });
  auto facing = [&](vtkIdType id) { return facingOf[id]; };

  // PASS 1: ownership. A hit belongs to the view that sees it best: the largest |n·d|
  // among the views whose ray through it reaches it first (within a footprint).
  std::vector<int> owner(C.N);
  vtkSMPTools::For(0, C.N, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType id = b; id < e; ++id)
    {
      const double* p = C.P.data() + 3 * id;
      int best = C.ViewOf[id];
      double bestCos = std::fabs(facing(id));
      for (size_t w = 0; w < this->Views.size(); ++w)
      {
        if (static_cast<int>(w) == C.ViewOf[id] || C.Singular[id])
        {
          continue;
        }
        const View& v = this->Views[w];
        double fi, fj;
        if (!v.Project(p, fi, fj))
        {
          continue;
        }
        double o[3], d[3];
        v.Ray(fi, fj, o, d);
        const double c = std::fabs(C.Normal[3 * id] * d[0] + C.Normal[3 * id + 1] * d[1] +
          C.Normal[3 * id + 2] * d[2]);
        if (c <= bestCos)
        {
          continue;
        }
        // Visible in w: one of the four nearest pixels' first hits lies at p.
        const double reach = 2.0 * v.Footprint(std::sqrt(vtkMath::Distance2BetweenPoints(p, v.O)));
        bool seen = false;
        for (int q = 0; q < 4 && !seen; ++q)
        {
          const int pi = static_cast<int>(std::floor(fi)) + q % 2;
          const int pj = static_cast<int>(std::floor(fj)) + q / 2;
          if (pi < 0 || pj < 0 || pi >= v.W || pj >= v.H)
          {
            continue;
          }
          const vtkIdType px = pixelStart[w] + vtkIdType(pj) * v.W + pi;
          if (first[px] < first[px + 1])
          {
            const vtkIdType h = hits[first[px]];
            seen = vtkMath::Distance2BetweenPoints(p, C.P.data() + 3 * h) <= reach * reach;
          }
        }
        if (seen)
        {
          best = static_cast<int>(w);
          bestCos = c;
        }
      }
      owner[id] = best;
    }
  });
  this->Algorithm->UpdateProgress(0.4);

  // Two hits of neighbouring pixels of one view are on one sheet: same facing, and the
  // depth of one within SheetTolerance footprints of the other's tangent plane.
  auto linked = [&](vtkIdType a, vtkIdType b) {
    const View& v = this->Views[C.ViewOf[a]];
    const double fa = facing(a), fb = facing(b);
    if (!C.Singular[a] && !C.Singular[b] && (fa < 0) != (fb < 0))
    {
      return false;
    }
    const double tolerance = sheetTolerance * v.Footprint(0.5 * (C.Depth[a] + C.Depth[b]));
    auto predicted = [&](vtkIdType x, vtkIdType y) {
      // |depth where y's ray meets x's tangent plane − y's depth|, over the tolerance
      // grown as the plane turns away from the view (a tangent plane predicts a depth
      // change of footprint·tan θ, and its error grows like 1/cos θ), at most 4 times.
      double o[3], d[3];
      v.Ray(C.Pixel[2 * y], C.Pixel[2 * y + 1], o, d);
      const float* n = C.Normal.data() + 3 * x;
      const double* px = C.P.data() + 3 * x;
      const double nd = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
      const double w = n[0] * (px[0] - o[0]) + n[1] * (px[1] - o[1]) + n[2] * (px[2] - o[2]);
      const double* py = C.P.data() + 3 * y;
      const double ty = (py[0] - o[0]) * d[0] + (py[1] - o[1]) * d[1] + (py[2] - o[2]) * d[2];
      return std::fabs(nd) > 1e-12 ? std::fabs(w / nd - ty) * std::max(std::fabs(nd), 0.25)
                                   : VTK_DOUBLE_MAX;
    };
    double error = VTK_DOUBLE_MAX;
    if (!C.Singular[a])
    {
      error = std::min(error, predicted(a, b));
    }
    if (!C.Singular[b])
    {
      error = std::min(error, predicted(b, a));
    }
    if (C.Singular[a] && C.Singular[b])
    {
      error = std::sqrt(vtkMath::Distance2BetweenPoints(C.P.data() + 3 * a, C.P.data() + 3 * b)) - 2 * tolerance;
    }
    return error <= tolerance;
  };
  // The hit of pixel px on the sheet of hit a, or −1.
  auto match = [&](vtkIdType a, vtkIdType px) -> vtkIdType {
    vtkIdType best = -1;
    double bestGap = VTK_DOUBLE_MAX;
    for (vtkIdType k = first[px]; k < first[px + 1]; ++k)
    {
      const vtkIdType b = hits[k];
      const double gap = std::fabs(C.Depth[b] - C.Depth[a]);
      if (gap < bestGap && linked(a, b))
      {
        best = b;
        bestGap = gap;
      }
    }
    return best;
  };

  // PASS 2: per view and image row, the triangles of the pixel quads.
  std::vector<std::pair<size_t, int>> rows;
  for (size_t v = 0; v < this->Views.size(); ++v)
  {
    for (int j = 0; j + 1 < this->Views[v].H; ++j)
    {
      rows.emplace_back(v, j);
    }
  }
  std::vector<std::vector<std::int64_t>> rowTriangles(rows.size());
  vtkSMPTools::For(0, static_cast<vtkIdType>(rows.size()), [&](vtkIdType rb, vtkIdType re) {
    for (vtkIdType r = rb; r < re && !this->Aborted(); ++r)
    {
      const int v = static_cast<int>(rows[r].first), j = rows[r].second;
      const View& view = this->Views[v];
      std::vector<std::int64_t>& tris = rowTriangles[r];
      auto emit = [&](vtkIdType a, vtkIdType b, vtkIdType c) {
        if (owner[a] == v && owner[b] == v && owner[c] == v)
        {
          tris.push_back(a);
          tris.push_back(b);
          tris.push_back(c);
        }
      };
      for (int i = 0; i + 1 < view.W; ++i)
      {
        const vtkIdType px[4] = { pixelStart[v] + vtkIdType(j) * view.W + i,
          pixelStart[v] + vtkIdType(j) * view.W + i + 1,
          pixelStart[v] + vtkIdType(j + 1) * view.W + i + 1,
          pixelStart[v] + vtkIdType(j + 1) * view.W + i };
        // Quads and triangles with a hit at corner 0.
        std::vector<vtkIdType> used;
        for (vtkIdType k = first[px[0]]; k < first[px[0] + 1]; ++k)
        {
          const vtkIdType a = hits[k];
          const vtkIdType m1 = match(a, px[1]), m2 = match(a, px[2]), m3 = match(a, px[3]);
          if (m1 >= 0 && m2 >= 0 && m3 >= 0)
          {
            // The diagonal through a singular corner, else the shorter one.
            bool diagonal02 = C.Singular[a] || C.Singular[m2];
            if (!diagonal02 && !C.Singular[m1] && !C.Singular[m3])
            {
              diagonal02 = vtkMath::Distance2BetweenPoints(C.P.data() + 3 * a, C.P.data() + 3 * m2) <=
                vtkMath::Distance2BetweenPoints(C.P.data() + 3 * m1, C.P.data() + 3 * m3);
            }
            if (diagonal02)
            {
              emit(a, m1, m2);
              emit(a, m2, m3);
            }
            else
            {
              emit(a, m1, m3);
              emit(m1, m2, m3);
            }
            used.push_back(m1);
          }
          else if (m1 >= 0 && m3 >= 0 && linked(m1, m3))
          {
            emit(a, m1, m3);
          }
          else if (m1 >= 0 && m2 >= 0)
          {
            emit(a, m1, m2);
          }
          else if (m2 >= 0 && m3 >= 0)
          {
            emit(a, m2, m3);
          }
        }
        // The triangle without corner 0.
        for (vtkIdType k = first[px[1]]; k < first[px[1] + 1]; ++k)
        {
          const vtkIdType b = hits[k];
          if (std::find(used.begin(), used.end(), b) != used.end())
          {
            continue;
          }
          bool withCorner0 = false;
          for (vtkIdType q = first[px[0]]; q < first[px[0] + 1] && !withCorner0; ++q)
          {
            withCorner0 = linked(hits[q], b);
          }
          const vtkIdType m2 = match(b, px[2]), m3 = match(b, px[3]);
          if (!withCorner0 && m2 >= 0 && m3 >= 0 && linked(m2, m3))
          {
            emit(b, m2, m3);
          }
        }
      }
    }
  });
  this->Rows = std::move(rowTriangles);
}
}

int vtkPiImageTriangulator::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkPiImageTriangulator::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The views are merged and their seams closed across the whole lattice: every piece
  // triangulates the whole cloud (piece 0 of 1 of the input) and keeps its share.
  PiRequestWholeInput(inputVector[0]);
  return 1;
}

int vtkPiImageTriangulator::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // PISURF_TIMING=1: the wall time of each pass on stderr.
  PiPassTimer lap("vtkPiImageTriangulator");
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  Triangulation T;
  T.Algorithm = this;

  // The pixel structure: PixelIndex, ViewIndex, Depth, Normals and PiRayViews.
  vtkPointData* pd = input->GetPointData();
  vtkDataArray* pixel = Array(pd, "PixelIndex", 2);
  vtkDataArray* viewIndex = Array(pd, "ViewIndex", 1);
  vtkDataArray* depth = Array(pd, "Depth", 1);
  vtkDataArray* normals = Array(pd, "Normals", 3);
  auto* viewData = vtkDataArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("PiRayViews"));
  if (!pixel || !viewIndex || !depth || !normals || !viewData ||
    viewData->GetNumberOfComponents() < 16)
  {
    vtkErrorMacro(<< "The input has no pixel structure: it needs the point arrays PixelIndex, "
                     "ViewIndex, Depth and Normals and the field data PiRayViews of a Pi Ray "
                     "Cast (vtkPiRayCaster) output");
    return 0;
  }
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
      vtkErrorMacro(<< "PiRayViews: view " << v << " is not a valid view definition");
      return 0;
    }
    // An axis view: rays along ±e_a, u along e_(a+1), v along e_(a+2), as the caster
    // casts them.
    if (!view.Perspective)
    {
      for (int a = 0; a < 3; ++a)
      {
        const int ua = (a + 1) % 3, va = (a + 2) % 3;
        const double d = vtkMath::Norm(view.D);
        if (std::fabs(std::fabs(view.D[a]) - d) <= 1e-12 * d && view.U[ua] > 0 &&
          view.V[va] > 0 && view.U[a] == 0 && view.U[va] == 0 && view.V[a] == 0 &&
          view.V[ua] == 0)
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
    vtkErrorMacro(<< "PiRayViews holds no view");
    return 0;
  }

  // The cloud: the input's arrays themselves when they have the caster's types,
  // converted copies otherwise (filled in parallel).
  Cloud& C = T.C;
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
  auto column = [&](auto& c, vtkDataArray* a, int components, double absent) {
    using T = typename std::decay<decltype(c.Store)>::type::value_type;
    if (a && c.Borrow(a))
    {
      return;
    }
    T* out = c.Allocate(static_cast<size_t>(components) * C.N, static_cast<T>(absent));
    if (a)
    {
      copies.push_back({ a, components, [out, components](vtkIdType id, const double* v) {
                          for (int k = 0; k < components; ++k)
                          {
                            // (integers out of range become −1: an invalid pixel or view)
                            out[components * id + k] = std::is_integral<T>::value &&
                                !(v[k] >= std::numeric_limits<T>::lowest() &&
                                  v[k] <= std::numeric_limits<T>::max())
                              ? static_cast<T>(-1)
                              : static_cast<T>(v[k]);
                          }
                        } });
    }
  };
  column(C.P, xyzIn, 3, 0);
  column(C.Normal, normals, 3, 0);
  column(C.Pixel, pixel, 2, 0);
  column(C.ViewOf, viewIndex, 1, 0);
  column(C.Depth, depth, 1, 0);
  column(C.Singular, singular, 1, 0);
  column(C.Tangent, tangent, 1, 0);
  column(C.Factor, factor, 1, -1);
  if (!copies.empty())
  {
    vtkSMPTools::For(0, C.N, [&](vtkIdType b, vtkIdType e) {
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
  // Checked in parallel; the first bad point (lowest id) is reported.
  std::atomic<vtkIdType> badPixel{ C.N }, badValue{ C.N };
  auto lower = [](std::atomic<vtkIdType>& bad, vtkIdType id) {
    vtkIdType seen = bad.load();
    while (id < seen && !bad.compare_exchange_weak(seen, id))
    {
    }
  };
  const int viewCount = static_cast<int>(T.Views.size());
  vtkSMPTools::For(0, C.N, [&](vtkIdType b, vtkIdType e) {
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
    vtkErrorMacro(<< "Point " << id << ": pixel (" << pixel->GetComponent(id, 0) << ", "
                  << pixel->GetComponent(id, 1) << ") of view " << viewIndex->GetComponent(id, 0)
                  << " is outside the views of PiRayViews");
    return 0;
  }
  if (badValue < C.N)
  {
    vtkErrorMacro(<< "Point " << badValue.load() << " has a non-finite position or normal");
    return 0;
  }

  lap("input unpacked");
  // The model, when the input carries it (needed for what the views did not see): a
  // molecule's field (any size, either mode), else the product of PiSurfaceModel.
  auto* json = vtkStringArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("PiSurfaceModel"));
  vtkNew<vtkPiSurface> surface;
  PiMoleculeInput molecule;
  std::string moleculeError;
  if (!molecule.Read(input, moleculeError))
  {
    vtkErrorMacro(<< moleculeError);
    return 0;
  }
  if (molecule.Present)
  {
    T.Molecule = molecule.MakeField(molecule.Bounds, moleculeError);
    if (!T.Molecule)
    {
      vtkErrorMacro(<< moleculeError);
      return 0;
    }
    T.Caster.reset(new pisurf::RayCaster(*T.Molecule));
  }
  else if (json && json->GetNumberOfValues() > 0)
  {
    if (!surface->SetModelJSON(json->GetValue(0)))
    {
      vtkErrorMacro(<< "Invalid PiSurfaceModel: " << surface->GetErrorMessage());
      return 0;
    }
    T.Kernel = surface->GetKernel();
    T.Caster.reset(new pisurf::RayCaster(*T.Kernel));
  }

  // The size of the scene: the extent of the views' rays and of the hits.
  double box[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
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

  lap("model and size");
  Lattice L;
  const bool lattice = T.FindLattice(L);
  int mode = this->MergeMode;
  if (mode == AUTOMATIC)
  {
    mode = lattice ? RAY_LATTICE : BEST_VIEW;
  }
  if (mode == RAY_LATTICE)
  {
    if (!lattice)
    {
      vtkErrorMacro(<< "RAY_LATTICE needs axis views over one box covering the three axes "
                       "with matching resolutions (Six Axis Views or Three Axis Directions)");
      return 0;
    }
    const double cells = double(L.N[0] + 1) * (L.N[1] + 1) * (L.N[2] + 1);
    if (cells > 1.1e10)
    {
      vtkErrorMacro(<< "The ray lattice of " << cells << " cells is too large");
      return 0;
    }
    T.ChooseDiagonals = this->EdgeFlipRounds > 0;
    T.Probe = 1e-3 * T.Size;
    if (T.Caster && box[0] <= box[1] && box[2] <= box[3] && box[4] <= box[5])
    {
      // Points computed off the rays' box take the probes (see RayCaster::PrepareProbes).
      T.Caster->PrepareProbes(box, T.Probe);
    }
    T.SingularTolerance = this->SingularTolerance;
    T.RunLattice(L);
  }
  else
  {
    T.RunBestView(this->SheetTolerance);
  }
  if (T.Abort)
  {
    output->Initialize();
    return 1;
  }

  lap("triangles of the views");
  // PASS 4: output ids. The hits used by a triangle come first, in input order, then
  // the computed points in key order: the hidden roots (keys −1, −2, … as RunLattice
  // numbers them, so reversed) and then the roots on lattice edges (EdgeBit keys, one
  // copy per cell that used them: sorted and kept once).
  std::vector<vtkIdType> rowStart(T.Rows.size() + 1, 0);
  for (size_t r = 0; r < T.Rows.size(); ++r)
  {
    rowStart[r + 1] = rowStart[r] + static_cast<vtkIdType>(T.Rows[r].size());
  }
  std::unique_ptr<std::atomic<unsigned char>[]> hitUsed(new std::atomic<unsigned char>[C.N]);
  vtkSMPTools::For(0, C.N, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType id = b; id < e; ++id)
    {
      hitUsed[id].store(0, std::memory_order_relaxed);
    }
  });
  vtkSMPTools::For(0, static_cast<vtkIdType>(T.Rows.size()), [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType r = b; r < e; ++r)
    {
      for (std::int64_t key : T.Rows[r])
      {
        if (key >= 0 && key < EdgeBit)
        {
          hitUsed[key].store(1, std::memory_order_relaxed);
        }
      }
    }
  });
  // Large arrays below are allocated uninitialized when a pass writes all of them (a
  // zeroing by one thread first would cost as much as the pass).
  std::unique_ptr<vtkIdType[]> hitOut(new vtkIdType[C.N]);
  vtkIdType usedHits = 0;
  for (vtkIdType id = 0; id < C.N; ++id)
  {
    hitOut[id] = hitUsed[id].load(std::memory_order_relaxed) ? usedHits++ : -1;
  }
  hitUsed.reset();
  const auto hiddenEnd = std::partition_point(T.Points.begin(), T.Points.end(),
    [](const Computed& c) { return c.Key < 0; });
  const vtkIdType hiddenCount = hiddenEnd - T.Points.begin();
  auto byKey = [](const Computed& x, const Computed& y) { return x.Key < y.Key; };
  std::sort(T.Points.begin() + hiddenCount, T.Points.end(), byKey);
  T.Points.erase(std::unique(T.Points.begin() + hiddenCount, T.Points.end(),
                   [](const Computed& x, const Computed& y) { return x.Key == y.Key; }),
    T.Points.end());
  std::vector<std::int64_t> edgeKeys;
  edgeKeys.reserve(T.Points.size() - hiddenCount);
  for (auto c = T.Points.begin() + hiddenCount; c != T.Points.end(); ++c)
  {
    edgeKeys.push_back(c->Key);
  }
  // Key −(index + 1) is at index; edge keys by binary search.
  auto computedId = [&](std::int64_t key) -> vtkIdType {
    return key < 0 ? -key - 1
                   : hiddenCount + (std::lower_bound(edgeKeys.begin(), edgeKeys.end(), key) -
                                     edgeKeys.begin());
  };
  const vtkIdType triangles = rowStart.back() / 3;
  // The corners: each row's keys become point ids in place (no second array of all the
  // corners: its fresh pages would cost as much as filling it). The passes below go
  // through the rows; triangle t of the whole list is triangle t − rowStart[r] / 3 of
  // its row r.
  const vtkIdType rows = static_cast<vtkIdType>(T.Rows.size());
  vtkSMPTools::For(0, rows, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType r = b; r < e; ++r)
    {
      for (std::int64_t& key : T.Rows[r])
      {
        key = key >= 0 && key < EdgeBit ? hitOut[key] : usedHits + computedId(key);
      }
    }
  });
  const vtkIdType total = usedHits + static_cast<vtkIdType>(T.Points.size());
  if (lap.IsEnabled())
  {
    std::cerr << "vtkPiImageTriangulator " << usedHits << " hits and " << T.Points.size()
              << " computed points in " << triangles << " triangles\n";
  }
  lap("output ids");

  // Components that no ray of the views reaches (closed shells inside the solid, found
  // on the hidden parts of first-hit rays) are not what the views show: components
  // without an input hit are dropped. Hits are all kept; a computed point is kept if
  // it shares a triangle with a hit, or is joined to such a point by triangles of
  // computed points only (a union-find over the computed points alone).
  const vtkIdType computedCount = total - usedHits;
  // A union-find over the computed points that all threads share: a root is linked to
  // the smaller of the two roots by a compare-and-swap that fails if it stopped being a
  // root meanwhile (then the union is tried again); paths are halved on the way. The
  // components, and so the points kept, do not depend on the order of the unions.
  std::unique_ptr<std::atomic<vtkIdType>[]> parent(new std::atomic<vtkIdType>[computedCount]);
  std::unique_ptr<std::atomic<unsigned char>[]> marked(new std::atomic<unsigned char>[computedCount]);
  vtkSMPTools::For(0, computedCount, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType k = b; k < e; ++k)
    {
      parent[k].store(k, std::memory_order_relaxed);
      marked[k].store(0, std::memory_order_relaxed);
    }
  });
  auto find = [&](vtkIdType x) {
    for (;;)
    {
      vtkIdType p = parent[x].load(std::memory_order_relaxed);
      if (p == x)
      {
        return x;
      }
      const vtkIdType g = parent[p].load(std::memory_order_relaxed);
      if (g != p)
      {
        // (an ancestor stays an ancestor: a lost race only skips the halving)
        parent[x].compare_exchange_weak(p, g, std::memory_order_relaxed);
      }
      x = g;
    }
  };
  auto unite = [&](vtkIdType x, vtkIdType y) {
    for (;;)
    {
      x = find(x);
      y = find(y);
      if (x == y)
      {
        return;
      }
      vtkIdType high = std::max(x, y);
      const vtkIdType low = std::min(x, y);
      if (parent[high].compare_exchange_strong(high, low, std::memory_order_relaxed))
      {
        return;
      }
    }
  };
  // The computed points of triangles with a hit are visible; triangles of computed
  // points only join their points.
  vtkSMPTools::For(0, rows, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType r = b; r < e; ++r)
    {
      const std::vector<std::int64_t>& row = T.Rows[r];
      for (size_t q = 0; q < row.size(); q += 3)
      {
        const std::int64_t* c = row.data() + q;
        if (c[0] >= usedHits && c[1] >= usedHits && c[2] >= usedHits)
        {
          unite(c[0] - usedHits, c[1] - usedHits);
          unite(c[0] - usedHits, c[2] - usedHits);
          continue;
        }
        for (int k = 0; k < 3; ++k)
        {
          if (c[k] >= usedHits)
          {
            marked[c[k] - usedHits].store(1, std::memory_order_relaxed);
          }
        }
      }
    }
  });
  // A component is kept if one of its points is marked (its root then is, below).
  std::vector<unsigned char> visible(computedCount, 0);
  for (vtkIdType k = 0; k < computedCount; ++k)
  {
    if (marked[k].load(std::memory_order_relaxed))
    {
      visible[find(k)] = 1;
    }
  }
  marked.reset();
  // Output points in the order the triangles first use them (rows of the lattice), so
  // that neighbouring triangles have neighbouring points: every later pass (and the
  // user's filters) reads memory in order. newId: −1 for a point to number, −2 for a
  // point of a dropped component (negative: not in the output, as a point no triangle
  // uses).
  std::unique_ptr<vtkIdType[]> newId(new vtkIdType[total]);
  vtkSMPTools::For(0, total, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType k = b; k < e; ++k)
    {
      newId[k] = k < usedHits || visible[find(k - usedHits)] ? -1 : -2;
    }
  });
  parent.reset();
  vtkIdType n = 0;
  for (const std::vector<std::int64_t>& row : T.Rows)
  {
    for (const std::int64_t k : row)
    {
      if (newId[k] == -1)
      {
        newId[k] = n++;
      }
    }
  }
  lap("components");
  // The vertices: input hits copy their attributes, computed points take them from
  // the exact gradient.
  vtkNew<vtkPoints> points;
  PiAllocateLargePoints(points, n);
  vtkNew<vtkFloatArray> outNormals;
  outNormals->SetName("Normals");
  outNormals->SetNumberOfComponents(3);
  PiAllocateLarge(outNormals.GetPointer(), n);
  vtkNew<vtkUnsignedCharArray> outSingular;
  outSingular->SetName("Singular");
  PiAllocateLarge(outSingular.GetPointer(), n);
  vtkNew<vtkIntArray> outView;
  outView->SetName("ViewIndex");
  PiAllocateLarge(outView.GetPointer(), n);
  vtkNew<vtkIntArray> outFactor;
  outFactor->SetName("Factor");
  PiAllocateLarge(outFactor.GetPointer(), n);
  auto* xyz = vtkDoubleArray::SafeDownCast(points->GetData())->GetPointer(0);
  float* nrmOut = outNormals->GetPointer(0);
  // In input order (read in sequence, written where each point goes: scattered writes
  // cost less than scattered reads): hits copy, computed points evaluate.
  int* viewOut = outView->GetPointer(0);
  int* factorOut = outFactor->GetPointer(0);
  unsigned char* singularOut = outSingular->GetPointer(0);
  vtkSMPTools::For(0, C.N, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType id = b; id < e; ++id)
    {
      const vtkIdType k = hitOut[id] < 0 ? -1 : newId[hitOut[id]];
      if (k < 0)
      {
        continue;
      }
      for (int a = 0; a < 3; ++a)
      {
        xyz[3 * k + a] = C.P[3 * id + a];
        nrmOut[3 * k + a] = C.Normal[3 * id + a];
      }
      singularOut[k] = C.Singular[id];
      viewOut[k] = C.ViewOf[id];
      factorOut[k] = C.Factor[id];
    }
  });
  vtkSMPTools::For(0, computedCount, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType q = b; q < e; ++q)
    {
      const vtkIdType k = newId[usedHits + q];
      if (k < 0)
      {
        continue;
      }
      const Computed& c = T.Points[q];
      for (int a = 0; a < 3; ++a)
      {
        xyz[3 * k + a] = c.P[a];
        nrmOut[3 * k + a] = c.N[a];
      }
      viewOut[k] = c.View;
      singularOut[k] = c.Singular ? 1 : 0;
      factorOut[k] = c.Nearest;
    }
  });

  lap("vertices");
  // Triangles, oriented so that their normals agree with the exact gradient (outward);
  // degenerate ones (two corners on one hit) are dropped.
  std::unique_ptr<unsigned char[]> keep(new unsigned char[triangles]);
  vtkSMPTools::For(0, rows, [&](vtkIdType rb, vtkIdType re) {
    for (vtkIdType r = rb; r < re; ++r)
    {
      for (vtkIdType t = rowStart[r] / 3; t < rowStart[r + 1] / 3; ++t)
      {
        std::int64_t* corner = T.Rows[r].data() + (3 * t - rowStart[r]);
        keep[t] = 0;
        vtkIdType id[3];
        for (int c = 0; c < 3; ++c)
        {
          id[c] = newId[corner[c]];
        }
        if (id[0] < 0 || id[0] == id[1] || id[1] == id[2] || id[0] == id[2])
        {
          continue;
        }
        double u[3], v[3], nt[3], average[3] = { 0, 0, 0 };
        const double* p0 = xyz + 3 * id[0];
        for (int k = 0; k < 3; ++k)
        {
          u[k] = xyz[3 * id[1] + k] - p0[k];
          v[k] = xyz[3 * id[2] + k] - p0[k];
          for (int c = 0; c < 3; ++c)
          {
            average[k] += nrmOut[3 * id[c] + k];
          }
        }
        vtkMath::Cross(u, v, nt);
        if (vtkMath::Dot(nt, average) < 0)
        {
          std::swap(id[1], id[2]);
        }
        std::copy(id, id + 3, corner);
        keep[t] = 1;
      }
    }
  });
  // The kept triangles, compacted in parallel: counted per row, then copied.
  std::vector<vtkIdType> blockStart(rows + 1, 0);
  vtkSMPTools::For(0, rows, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType r = b; r < e; ++r)
    {
      blockStart[r + 1] = std::count(keep.get() + rowStart[r] / 3, keep.get() + rowStart[r + 1] / 3, 1);
    }
  });
  for (vtkIdType r = 0; r < rows; ++r)
  {
    blockStart[r + 1] += blockStart[r];
  }
  const vtkIdType kept = blockStart[rows];
  // The cells in vtkCellArray's 32-bit storage when the ids fit (half the memory of
  // 64-bit ids for the flips below and every filter downstream), else 64-bit.
  vtkNew<vtkCellArray> polys;
  PiEdgeFlipResult flipped;
  auto compact = [&](auto* offsets, auto* cells) {
    using Id = std::remove_pointer_t<decltype(cells->GetPointer(0))>;
    PiAllocateLarge(cells, 3 * kept);
    PiAllocateLarge(offsets, kept + 1);
    Id* cellIds = cells->GetPointer(0);
    Id* offsetIds = offsets->GetPointer(0);
    vtkSMPTools::For(0, rows, [&](vtkIdType b, vtkIdType e) {
      for (vtkIdType r = b; r < e; ++r)
      {
        vtkIdType out = blockStart[r];
        const std::int64_t* corner = T.Rows[r].data();
        for (vtkIdType t = rowStart[r] / 3; t < rowStart[r + 1] / 3; ++t, corner += 3)
        {
          if (keep[t])
          {
            for (int c = 0; c < 3; ++c)
            {
              cellIds[3 * out + c] = static_cast<Id>(corner[c]);
            }
            offsetIds[out] = static_cast<Id>(3 * out);
            ++out;
          }
        }
        std::vector<std::int64_t>().swap(T.Rows[r]);
      }
    });
    offsetIds[kept] = static_cast<Id>(3 * kept);
    polys->SetData(offsets, cells);
    lap("triangles");
    // Boundary edges (used by one triangle), then the edge flips towards the curvature
    // (PiEdgeFlips.h): vertices stay, the boundary and the topology too.
    flipped = PiFlipEdgesToCurvature(cellIds, kept, n, xyz, nrmOut, this->EdgeFlipRounds);
  };
  if (PiFitsInt32Cells(kept, n))
  {
    vtkNew<vtkTypeInt32Array> offsets, cells;
    compact(offsets.Get(), cells.Get());
  }
  else
  {
    vtkNew<vtkTypeInt64Array> offsets, cells;
    compact(offsets.Get(), cells.Get());
  }
  const vtkIdType boundary = flipped.BoundaryEdges;
  if (lap.IsEnabled())
  {
    std::cerr << "vtkPiImageTriangulator " << flipped.Flips << " edges flipped in "
              << flipped.Rounds << " rounds\n";
  }
  lap("boundary edges and flips");
  output->SetPoints(points);
  output->SetPolys(polys);
  output->GetPointData()->SetNormals(outNormals);
  output->GetPointData()->AddArray(outSingular);
  output->GetPointData()->AddArray(outView);
  output->GetPointData()->AddArray(outFactor);
  if (molecule.Present)
  {
    PiMoleculeInput::Forward(input, output);
  }
  else if (json)
  {
    output->GetFieldData()->AddArray(json);
  }
  vtkNew<vtkIdTypeArray> boundaryEdges;
  boundaryEdges->SetName("BoundaryEdges");
  boundaryEdges->InsertNextValue(boundary);
  output->GetFieldData()->AddArray(boundaryEdges);
  vtkNew<vtkIdTypeArray> unused;
  unused->SetName("UnusedHits");
  unused->InsertNextValue(C.N - usedHits);
  output->GetFieldData()->AddArray(unused);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const PiPiece request = PiPieceOf(outInfo);
  const int piece = request.Piece, pieces = request.Pieces;
  if (pieces > 1)
  {
    KeepShare(output, piece, pieces);
  }
  lap.Total("total");
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPiImageTriangulator::KeepShare(vtkPolyData* mesh, int piece, int pieces)
{
  // Piece p of n keeps the triangles [T p / n, T (p + 1) / n) of the whole mesh and the
  // points they use (a point on the cut is in both pieces, at the same position).
  const vtkIdType triangles = mesh->GetNumberOfPolys();
  const vtkIdType first = triangles * piece / pieces, last = triangles * (piece + 1) / pieces;
  std::vector<vtkIdType> map(mesh->GetNumberOfPoints(), -1);
  vtkNew<vtkIdList> keep;
  vtkNew<vtkCellArray> polys;
  vtkCellArray* all = mesh->GetPolys();
  vtkNew<vtkIdList> cell;
  for (vtkIdType t = first; t < last; ++t)
  {
    all->GetCellAtId(t, cell);
    for (vtkIdType k = 0; k < cell->GetNumberOfIds(); ++k)
    {
      vtkIdType& id = map[cell->GetId(k)];
      if (id < 0)
      {
        id = keep->GetNumberOfIds();
        keep->InsertNextId(cell->GetId(k));
      }
      cell->SetId(k, id);
    }
    polys->InsertNextCell(cell);
  }
  vtkNew<vtkPoints> points;
  points->SetDataType(mesh->GetPoints()->GetDataType());
  points->SetNumberOfPoints(keep->GetNumberOfIds());
  mesh->GetPoints()->GetPoints(keep, points);
  vtkNew<vtkPointData> pd;
  pd->CopyAllocate(mesh->GetPointData(), keep->GetNumberOfIds());
  pd->CopyData(mesh->GetPointData(), keep);
  vtkNew<vtkPolyData> share;
  share->SetPoints(points);
  share->SetPolys(polys);
  share->GetPointData()->ShallowCopy(pd);
  share->GetFieldData()->ShallowCopy(mesh->GetFieldData());
  mesh->ShallowCopy(share);
}

void vtkPiImageTriangulator::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MergeMode: " << this->MergeMode << "\n";
  os << indent << "SheetTolerance: " << this->SheetTolerance << "\n";
  os << indent << "SingularTolerance: " << this->SingularTolerance << "\n";
  os << indent << "EdgeFlipRounds: " << this->EdgeFlipRounds << "\n";
}
