// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiFlyingEdges.h"
#include "PiPieces.h"
#include "PiTiming.h"

#include "PiLastValidOutput.h"

#include "PiBuffer.h"
#include "PiLargeArrays.h"
#include "PiParallel.h"
#include "PiEdgeFlips.h"
#include "PiField.h"
#include "PiModel.h"
#include "PiProduct.h"
#include "PiRayRoots.h"
#include "vtkPiSurface.h"

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkGarbageCollector.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "PiMarchingCubes.h"
#include "vtkMarchingCubesTriangleCases.h"
#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkMassProperties.h"
#include "vtkPolyData.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTypeInt32Array.h"

#include <algorithm>
#include <cstdint>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <cmath>
#include <deque>
#include <memory>
#include <type_traits>
#include <utility>
#include <new>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

vtkStandardNewMacro(vtkPiFlyingEdges);
vtkCxxSetObjectMacro(vtkPiFlyingEdges, PiSurface, vtkPiSurface);

// Work buffers kept between executions: interactive re-meshing (and every execution
// after the first) does not pay for fresh memory again.
//
//
// Incremental re-meshing: each polynomial factor's restrictions to the grid rows are
// kept too, keyed by the factor's content (terms and placement) and the grid. When a
// live edit changes one factor (a moved primitive), the others are not restricted
// again. The restrictions are the same numbers a fresh execution computes, so the mesh
// is bit-identical.
namespace
{
struct FactorCache
{
  std::vector<double> Key;   // the factor's content (see FactorKey)
  int Coefficients = 0;      // per row: degree + 1
  pisurf::LargeVector<double> Rows; // per grid row (j, k): the restricted coefficients
                                    // (uninitialized until RowDone says so)
  std::vector<char> RowDone; // per grid row: Rows holds it
  bool Used = false;          // matched by a factor of the current execution
};

// What a factor's restrictions and values depend on: its terms and its placement.
std::vector<double> FactorKey(const pisurf::PolynomialFactor& f)
{
  std::vector<double> key;
  for (const pisurf::Monomial& m : f.Poly.GetTerms())
  {
    key.insert(key.end(), { m.Coefficient, double(m.I), double(m.J), double(m.K) });
  }
  for (const auto& row : f.A)
  {
    key.insert(key.end(), row, row + 3);
  }
  key.insert(key.end(), f.B, f.B + 3);
  return key;
}
}

struct vtkPiFlyingEdges::vtkInternals
{
  // The active blocks' values, grown (never shrunk) as executions need: uninitialized
  // (the sample pass writes every value; pisurf::AllocateLarge).
  pisurf::Buffer<double> Values;
  // The rows the active blocks need and their factors' restrictions (kept between
  // executions, like Values, so that a re-execution does not fault their pages in again).
  // (In AllocateLarge's memory, for a new mesher's sake: see pisurf::DefaultInitAllocator.)
  pisurf::LargeVector<vtkIdType> RowIndex;
  std::vector<vtkIdType> Rows;
  pisurf::LargeVector<double> Coefficients;
  std::shared_ptr<const pisurf::Field> Field;
  std::vector<double> CacheGrid; // the grid the factor caches belong to
  std::vector<FactorCache> Factors;
  // The envelope's and the contouring's work arrays (per active block: free and reached
  // points, row signs, crossing-edge masks and offsets; per vertex: edge key, crossing
  // parameter, end values), kept between
  // executions below WorkLimit bytes in all: a re-execution then writes memory that is
  // already mapped (at 256³ the cup's contouring faulted ~20 MB in each time, a tenth
  // of its time with two threads). Larger ones are released after use.
  pisurf::Buffer<vtkIdType> VertexEdge;
  pisurf::Buffer<double> VertexT, VertexEnds;
  pisurf::Buffer<std::uint16_t> RowSigns, EdgeOffsets;
  pisurf::Buffer<std::uint8_t> EdgeMasks;
  pisurf::Buffer<std::uint16_t> EnvelopeFree, EnvelopeReached; // (see Envelope)
  static constexpr size_t WorkLimit = size_t(256) << 20;
  void ReleaseLargeWork()
  {
    const size_t bytes = this->VertexEdge.GetSize() * sizeof(vtkIdType) +
      (this->VertexT.GetSize() + this->VertexEnds.GetSize()) * sizeof(double) +
      (this->RowSigns.GetSize() + this->EdgeOffsets.GetSize() + this->EnvelopeFree.GetSize() +
        this->EnvelopeReached.GetSize()) * sizeof(std::uint16_t) +
      this->EdgeMasks.GetSize();
    if (bytes > WorkLimit)
    {
      this->VertexEdge.Release();
      this->VertexT.Release();
      this->VertexEnds.Release();
      this->RowSigns.Release();
      this->EdgeOffsets.Release();
      this->EdgeMasks.Release();
      this->EnvelopeFree.Release();
      this->EnvelopeReached.Release();
    }
  }
};

void vtkPiFlyingEdges::SetField(std::shared_ptr<const pisurf::Field> field)
{
  if (field != this->Internals->Field)
  {
    this->Internals->Field = std::move(field);
    this->Modified();
  }
}

vtkPiFlyingEdges::vtkPiFlyingEdges()
  : LastValid(new PiLastValidOutput)
  , Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
}

vtkPiFlyingEdges::~vtkPiFlyingEdges()
{
  this->SetPiSurface(nullptr);
}

vtkTypeBool vtkPiFlyingEdges::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs)
{
  return this->LastValid->Process(request, this->KeepLastValidOutput, outputs,
    [&]() { return this->Superclass::ProcessRequest(request, inputs, outputs); });
}

vtkMTimeType vtkPiFlyingEdges::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->PiSurface)
  {
    t = std::max(t, this->PiSurface->GetMTime());
  }
  return t;
}

void vtkPiFlyingEdges::ReportReferences(vtkGarbageCollector* collector)
{
  this->Superclass::ReportReferences(collector);
  vtkGarbageCollectorReport(collector, this->PiSurface, "PiSurface");
}

namespace
{
// What the passes evaluate: the Pi-surface's product kernel or, when set, a field with
// its own evaluation structures (SetField). Only the product has row restriction.
struct Evaluator
{
  const pisurf::ProductKernel* Kernel = nullptr;
  const pisurf::Field* Field = nullptr;

  int ClassifyBox(const double box[6]) const
  {
    return this->Field ? this->Field->ClassifyBox(box) : this->Kernel->ClassifyBox(box);
  }
  // A block: ClassifyBox, and where that cannot decide, its octants (enclosures
  // tighten on smaller boxes: if all eight exclude the surface, so does the block, F
  // having no zero in it and so one sign throughout).
  int ClassifyBlock(const double box[6]) const
  {
    int octants[8];
    int sign = 0;
    if (this->Field)
    {
      sign = this->Field->ClassifyBox(box);
      for (int o = 0; o < 8 && sign == 0; ++o)
      {
        double sub[6];
        pisurf::OctantBox(box, o, sub);
        octants[o] = this->Field->ClassifyBox(sub);
        if (octants[o] == 0)
        {
          return 0;
        }
      }
      return sign != 0 ? sign : octants[7];
    }
    sign = this->Kernel->ClassifyBoxAndOctants(box, octants);
    if (sign != 0)
    {
      return sign;
    }
    for (int o = 0; o < 8; ++o)
    {
      if (octants[o] == 0)
      {
        return 0;
      }
    }
    return octants[0];
  }
  double Evaluate(const double p[3]) const
  {
    return this->Field ? this->Field->Evaluate(p) : this->Kernel->Evaluate(p);
  }
  double EvaluateCompressed(const double p[3]) const
  {
    return this->Field ? this->Field->EvaluateCompressed(p) : this->Kernel->EvaluateCompressed(p);
  }
  bool OffOuterSide(const double p[3]) const
  {
    return this->Field && this->Field->OffOuterSide(p);
  }
  void EvaluateVertex(const double p[3], double n[3], double& gradientNorm, int& nearest) const
  {
    if (this->Field)
    {
      this->Field->EvaluateVertex(p, n, gradientNorm, nearest);
    }
    else
    {
      this->Kernel->EvaluateVertex(p, n, gradientNorm, nearest);
    }
  }
};

// The grid is cut into blocks of BlockCells³ cells. A block whose interval bound
// excludes the surface is "skipped": its sign is known and nothing in it is evaluated
// or contoured. The others are "active".
constexpr int BlockCells = 8;
constexpr int BlockPoints = BlockCells + 1;
// Grid::Sign of a block outside the layers a piece works on (see GenerateMesh's pieces):
// neither classified nor sampled; the passes never visit it.
constexpr signed char AbsentBlock = 3;
constexpr double ValueLimit = 1e300;
// Bit i set where row[i] >= 0, for i < count (at most 16): two points per comparison
// where SSE2 is there (the x86-64 baseline).
inline unsigned SignBits(const double* row, int count)
{
  unsigned bits = 0;
  int i = 0;
#if defined(__SSE2__)
  const __m128d zero = _mm_setzero_pd();
  for (; i + 2 <= count; i += 2)
  {
    bits |= unsigned(_mm_movemask_pd(_mm_cmpge_pd(_mm_loadu_pd(row + i), zero))) << i;
  }
#endif
  for (; i < count; ++i)
  {
    bits |= unsigned(row[i] >= 0) << i;
  }
  return bits;
}

// F as the passes store it: within ±ValueLimit, so that differences of neighbours stay
// finite (the sign of F is exact, whatever its magnitude).
inline double Limited(double F)
{
  return std::max(-ValueLimit, std::min(ValueLimit, F));
}
// Limited on v[0..n), two values per instruction where SSE2 is there (the same results:
// min(x, L) gives L for a NaN, as std::min(L, x) does).
inline void LimitRow(double* v, int n)
{
  int i = 0;
#if defined(__SSE2__)
  const __m128d hi = _mm_set1_pd(ValueLimit), lo = _mm_set1_pd(-ValueLimit);
  for (; i + 2 <= n; i += 2)
  {
    _mm_storeu_pd(v + i, _mm_max_pd(_mm_min_pd(_mm_loadu_pd(v + i), hi), lo));
  }
#endif
  for (; i < n; ++i)
  {
    v[i] = Limited(v[i]);
  }
}

using pisurf::mc::Corner;

struct Grid
{
  int Dims[3];
  double Origin[3];
  double Spacing[3];
  int Count[3];                  // blocks per axis
  std::vector<signed char> Sign; // per block: +1/−1 skipped with that sign, 0 active
  std::vector<int> Active;       // active block ids
  std::vector<int> Slot;         // per block: index in Active, or −1
  double* Values = nullptr; // per active block: BlockPoints³ values of F (not owned)

  vtkIdType BlockId(int bx, int by, int bz) const
  {
    return (vtkIdType(bz) * this->Count[1] + by) * this->Count[0] + bx;
  }
  vtkIdType PointId(int i, int j, int k) const
  {
    return (vtkIdType(k) * this->Dims[1] + j) * this->Dims[0] + i;
  }
  void BlockCoordinates(vtkIdType b, int c[3]) const
  {
    c[0] = static_cast<int>(b % this->Count[0]);
    c[1] = static_cast<int>((b / this->Count[0]) % this->Count[1]);
    c[2] = static_cast<int>(b / (vtkIdType(this->Count[0]) * this->Count[1]));
  }
  // Cells [first, last) of block c along axis a.
  int First(const int c[3], int a) const { return c[a] * BlockCells; }
  /// The middle of grid row `row` (= k·Dims[1] + j, along x): where the factors are
  /// restricted to it, so that every block sees the same coefficients.
  void RowMiddle(vtkIdType row, double o[3]) const
  {
    const int j = static_cast<int>(row % this->Dims[1]);
    const int k = static_cast<int>(row / this->Dims[1]);
    o[0] = this->Origin[0] + 0.5 * (this->Dims[0] - 1) * this->Spacing[0];
    o[1] = this->Origin[1] + j * this->Spacing[1];
    o[2] = this->Origin[2] + k * this->Spacing[2];
  }
  int Last(const int c[3], int a) const
  {
    return std::min(c[a] * BlockCells + BlockCells, this->Dims[a] - 1);
  }
  // The points [first, last] of block c on the three axes.
  void Range(const int c[3], int first[3], int last[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      first[a] = this->First(c, a);
      last[a] = this->Last(c, a);
    }
  }
  // The cells of block c along each axis (8, fewer in the last blocks): its points run
  // over the local indices 0..n[a].
  void CellCounts(const int c[3], int n[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      n[a] = this->Last(c, a) - this->First(c, a);
    }
  }
  // f(neighbour block id, offset d) for each of the (up to) 26 blocks sharing points
  // with block c.
  template <typename Function>
  void ForEachNeighbour(const int c[3], Function f) const
  {
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int m[3] = { c[0] + dx, c[1] + dy, c[2] + dz };
          if ((dx == 0 && dy == 0 && dz == 0) || m[0] < 0 || m[1] < 0 || m[2] < 0 ||
            m[0] >= this->Count[0] || m[1] >= this->Count[1] || m[2] >= this->Count[2])
          {
            continue;
          }
          const int d[3] = { dx, dy, dz };
          f(this->BlockId(m[0], m[1], m[2]), d);
        }
  }
  // Blocks along one axis whose point range contains index i.
  int Containing(int i, int a, int out[2]) const
  {
    int n = 0;
    if (i / BlockCells < this->Count[a])
    {
      out[n++] = i / BlockCells;
    }
    if (i % BlockCells == 0 && i > 0)
    {
      out[n++] = i / BlockCells - 1;
    }
    return n;
  }
  // A skipped block containing point (i, j, k), or −1.
  vtkIdType SkippedBlockOf(int i, int j, int k) const
  {
    int xs[2], ys[2], zs[2];
    const int nx = this->Containing(i, 0, xs), ny = this->Containing(j, 1, ys),
              nz = this->Containing(k, 2, zs);
    for (int a = 0; a < nx; ++a)
      for (int b = 0; b < ny; ++b)
        for (int c = 0; c < nz; ++c)
        {
          const vtkIdType id = this->BlockId(xs[a], ys[b], zs[c]);
          if (this->Sign[id] != 0)
          {
            return id;
          }
        }
    return -1;
  }
  // The stored value of a point of some active block (the caller knows it has one).
  double ActiveValue(int i, int j, int k) const
  {
    int xs[2], ys[2], zs[2];
    this->Containing(i, 0, xs);
    this->Containing(j, 1, ys);
    this->Containing(k, 2, zs);
    const int c[3] = { xs[0], ys[0], zs[0] };
    const int slot = this->Slot[this->BlockId(c[0], c[1], c[2])];
    return this->Values[size_t(slot) * BlockPoints * BlockPoints * BlockPoints +
      size_t((k - c[2] * BlockCells) * BlockPoints + (j - c[1] * BlockCells)) * BlockPoints +
      (i - c[0] * BlockCells)];
  }
};

// PASS 1: interval bounds of F over each block still undecided.
//
// With `Corners` (a product kernel), a block whose corners (grid points) have F of both
// signs, or 0 at one, holds the surface: it is active without its enclosures, which
// could not have decided it either (the same active blocks). Each corner is evaluated
// once, by whichever block asks first (`Corners` starts at Unknown; two threads that
// ask at once store the same sign).
struct ClassifyBlocks
{
  const Evaluator* Kernel;
  Grid* G;
  const std::vector<vtkIdType>* Blocks; // the blocks to classify
  std::atomic<signed char>* Corners = nullptr; // per corner of the block lattice
  static constexpr signed char Unknown = 2;

  // The sign of F at corner (x, y, z) of the block lattice: grid point
  // min(8·x, dims − 1) along each axis, the corner of the blocks that meet there.
  int CornerSign(const int corner[3]) const
  {
    const Grid& g = *this->G;
    const size_t id =
      (size_t(corner[2]) * (g.Count[1] + 1) + corner[1]) * (g.Count[0] + 1) + corner[0];
    signed char sign = this->Corners[id].load(std::memory_order_relaxed);
    if (sign == Unknown)
    {
      double p[3];
      for (int a = 0; a < 3; ++a)
      {
        p[a] = g.Origin[a] + std::min(corner[a] * BlockCells, g.Dims[a] - 1) * g.Spacing[a];
      }
      const double f = this->Kernel->Evaluate(p);
      sign = static_cast<signed char>(f > 0 ? 1 : (f < 0 ? -1 : 0)); // (NaN: 0, active)
      this->Corners[id].store(sign, std::memory_order_relaxed);
    }
    return sign;
  }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    for (vtkIdType n = begin; n < end; ++n)
    {
      const vtkIdType b = (*this->Blocks)[n];
      int c[3];
      this->G->BlockCoordinates(b, c);
      if (this->Corners)
      {
        bool positive = false, negative = false;
        for (int k = 0; k < 8 && !(positive && negative); ++k)
        {
          const int corner[3] = { c[0] + (k & 1), c[1] + ((k >> 1) & 1), c[2] + ((k >> 2) & 1) };
          const int sign = this->CornerSign(corner);
          positive = positive || sign >= 0;
          negative = negative || sign <= 0;
        }
        if (positive && negative)
        {
          this->G->Sign[b] = 0;
          continue;
        }
      }
      double box[6];
      for (int a = 0; a < 3; ++a)
      {
        box[2 * a] = this->G->Origin[a] + this->G->First(c, a) * this->G->Spacing[a];
        box[2 * a + 1] = this->G->Origin[a] + this->G->Last(c, a) * this->G->Spacing[a];
      }
      this->G->Sign[b] = static_cast<signed char>(this->Kernel->ClassifyBlock(box));
    }
  }
};

// PASS 2: the rows (j, k) that cross an active block get their factors restricted once,
// about the middle of the whole row, so every point evaluates identically whichever
// block asks for it (no cracks between blocks).
struct RestrictRows
{
  const pisurf::ProductKernel* Kernel;
  const Grid* G;
  const std::vector<vtkIdType>* Rows;
  pisurf::LargeVector<double>* Coefficients;

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const size_t n = this->Kernel->GetLineCoefficientCount();
    const double step[3] = { this->G->Spacing[0], 0.0, 0.0 };
    for (vtkIdType r = begin; r < end; ++r)
    {
      const vtkIdType row = (*this->Rows)[r];
      double o[3];
      this->G->RowMiddle(row, o);
      this->Kernel->RestrictLine(o, step, this->Coefficients->data() + r * n);
    }
  }
};

// PASS 3: the points of each active block: F, clamped to ±ValueLimit so that differences
// of neighbours stay finite (the sign of F is exact, whatever its magnitude).
struct SampleBlocks
{
  const pisurf::ProductKernel* Kernel; // null when sampling Field
  const pisurf::Field* Field;
  Grid* G;
  const pisurf::LargeVector<vtkIdType>* RowIndex; // per row (j, k): its index in the coefficients
  const pisurf::LargeVector<double>* Coefficients;
  vtkPiFlyingEdges* Algorithm;
  std::atomic<bool>* Abort;

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const bool single = PiSingleThread();
    const size_t n = this->Kernel ? this->Kernel->GetLineCoefficientCount() : 0;
    const double mid = 0.5 * (this->G->Dims[0] - 1);
    for (vtkIdType s = begin; s < end; ++s)
    {
      if (single && this->Algorithm->CheckAbort())
      {
        *this->Abort = true;
      }
      if (*this->Abort)
      {
        return;
      }
      int c[3];
      this->G->BlockCoordinates(this->G->Active[s], c);
      double* v = this->G->Values + size_t(s) * BlockPoints * BlockPoints * BlockPoints;
      if (this->Field)
      {
        // A field that evaluates a whole box at once (bit for bit as point by point).
        int first[3], last[3];
        this->G->Range(c, first, last);
        if (this->Field->EvaluateBox(this->G->Origin, this->G->Spacing, first, last, BlockPoints,
              BlockPoints * BlockPoints, v))
        {
          for (int k = 0; k <= last[2] - first[2]; ++k)
            for (int j = 0; j <= last[1] - first[1]; ++j)
              for (int i = 0; i <= last[0] - first[0]; ++i)
              {
                double& x = v[(k * BlockPoints + j) * BlockPoints + i];
                x = Limited(x);
              }
          continue;
        }
      }
      for (int k = this->G->First(c, 2); k <= this->G->Last(c, 2); ++k)
      {
        for (int j = this->G->First(c, 1); j <= this->G->Last(c, 1); ++j)
        {
          const double* coefficients = this->Kernel
            ? this->Coefficients->data() + (*this->RowIndex)[vtkIdType(k) * this->G->Dims[1] + j] * n
            : nullptr;
          double* out = v + size_t((k - c[2] * BlockCells) * BlockPoints + (j - c[1] * BlockCells)) *
              BlockPoints;
          const int first = this->G->First(c, 0), last = this->G->Last(c, 0);
          if (this->Kernel && this->Kernel->IsPolynomial())
          {
            // The block's part of the row, several points at a time (the same values as
            // EvaluateRestricted point by point; the points are not needed).
            double* row = out + (first - c[0] * BlockCells);
            const double unused[3] = { 0, 0, 0 };
            this->Kernel->EvaluateRestrictedRow(
              coefficients, first - mid, last - first + 1, unused, unused, row);
            for (int i = 0; i <= last - first; ++i)
            {
              row[i] = Limited(row[i]);
            }
            continue;
          }
          for (int i = first; i <= last; ++i)
          {
            const double p[3] = { this->G->Origin[0] + i * this->G->Spacing[0],
              this->G->Origin[1] + j * this->G->Spacing[1],
              this->G->Origin[2] + k * this->G->Spacing[2] };
            const double F = this->Kernel
              ? this->Kernel->EvaluateRestricted(coefficients, i - mid, p)
              : this->Field->Evaluate(p);
            out[i - c[0] * BlockCells] = Limited(F);
          }
        }
      }
    }
  }
};

// PASS 3 for a product of polynomials: row by row. Each grid row (j, k) that crosses an
// active block is evaluated once over the runs of consecutive x blocks it needs (one
// call per run, several points at a time), and its values are copied into every active
// block that holds the row (up to four, where j or k is on a block boundary): each grid
// point is evaluated once, not once per block sharing it. The values are those of
// SampleBlocks (EvaluateRestrictedRow depends only on the coefficients and t).
struct SampleRows
{
  const pisurf::ProductKernel* Kernel;
  Grid* G;
  const std::vector<vtkIdType>* Rows; // the rows (k·Dims[1] + j) in coefficient order
  const pisurf::LargeVector<double>* Coefficients;
  vtkPiFlyingEdges* Algorithm;
  std::atomic<bool>* Abort;
  // Per block row (bz·Count[1] + by): its first and one past its last active x block.
  std::vector<std::pair<int, int>> Span;

  // (Not named Initialize: vtkSMPTools would take it for a per-thread initializer.)
  void Prepare()
  {
    const int* count = this->G->Count;
    this->Span.assign(size_t(count[1]) * count[2], { count[0], 0 });
    for (const int b : this->G->Active)
    {
      int c[3];
      this->G->BlockCoordinates(b, c);
      std::pair<int, int>& span = this->Span[size_t(c[2]) * count[1] + c[1]];
      span.first = std::min(span.first, c[0]);
      span.second = std::max(span.second, c[0] + 1);
    }
  }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const bool single = PiSingleThread();
    const size_t n = this->Kernel->GetLineCoefficientCount();
    const int* d = this->G->Dims;
    const double mid = 0.5 * (d[0] - 1);
    const double unused[3] = { 0, 0, 0 };
    // Locals, not thread_local: a thread_local in a shared library costs a call to find
    // it at every use (several per row); one allocation per chunk of rows is nothing.
    std::vector<double> values(d[0]);
    std::vector<char> need(this->G->Count[0]);
    for (vtkIdType r = begin; r < end; ++r)
    {
      if (single && (r & 255) == 0 && this->Algorithm->CheckAbort())
      {
        *this->Abort = true;
      }
      if (*this->Abort)
      {
        return;
      }
      const vtkIdType row = (*this->Rows)[r];
      const int j = static_cast<int>(row % d[1]), k = static_cast<int>(row / d[1]);
      int ys[2], zs[2];
      const int ny = this->G->Containing(j, 1, ys), nz = this->G->Containing(k, 2, zs);
      // Only the x blocks between the first and last active ones of these block rows.
      int from = this->G->Count[0], to = 0;
      for (int a = 0; a < ny; ++a)
        for (int b = 0; b < nz; ++b)
        {
          const std::pair<int, int>& span = this->Span[size_t(zs[b]) * this->G->Count[1] + ys[a]];
          from = std::min(from, span.first);
          to = std::max(to, span.second);
        }
      for (int bx = from; bx < to; ++bx)
      {
        char any = 0;
        for (int a = 0; a < ny; ++a)
          for (int b = 0; b < nz; ++b)
          {
            any |= this->G->Slot[this->G->BlockId(bx, ys[a], zs[b])] >= 0;
          }
        need[bx] = any;
      }
      const double* coefficients = this->Coefficients->data() + r * n;
      for (int bx = from; bx < to;)
      {
        if (!need[bx])
        {
          ++bx;
          continue;
        }
        int last = bx;
        while (last + 1 < to && need[last + 1])
        {
          ++last;
        }
        const int first = bx * BlockCells;
        const int stop = std::min((last + 1) * BlockCells, d[0] - 1);
        this->Kernel->EvaluateRestrictedRow(
          coefficients, first - mid, stop - first + 1, unused, unused, values.data() + first);
        LimitRow(values.data() + first, stop - first + 1);
        bx = last + 1;
      }
      for (int bx = from; bx < to; ++bx)
      {
        if (!need[bx])
        {
          continue;
        }
        const int first = bx * BlockCells;
        const int count = std::min(first + BlockCells, d[0] - 1) - first + 1;
        for (int a = 0; a < ny; ++a)
          for (int b = 0; b < nz; ++b)
          {
            const int slot = this->G->Slot[this->G->BlockId(bx, ys[a], zs[b])];
            if (slot < 0)
            {
              continue;
            }
            double* out = this->G->Values +
              size_t(slot) * BlockPoints * BlockPoints * BlockPoints +
              size_t((k - zs[b] * BlockCells) * BlockPoints + (j - ys[a] * BlockCells)) *
                BlockPoints;
            // (A block row: at most 9 values, copied inline rather than by a call.)
            const double* in = values.data() + first;
            if (count == BlockPoints)
            {
              for (int i = 0; i < BlockPoints; ++i)
              {
                out[i] = in[i];
              }
            }
            else
            {
              for (int i = 0; i < count; ++i)
              {
                out[i] = in[i];
              }
            }
          }
      }
    }
  }
};

// The factor caches of this execution: per factor of the kernel, its cache (null for a
// factor that is not a polynomial; factors of equal content share one), or none at all
// (empty) for a field or when the restrictions of every row would exceed 64 MiB.
std::vector<FactorCache*> PrepareFactorCaches(std::vector<double>& gridKey,
  std::vector<FactorCache>& store, const pisurf::ProductKernel* kernel, const Grid& g)
{
  size_t polynomials = 0;
  for (size_t f = 0; kernel && f < kernel->GetNumberOfFactors(); ++f)
  {
    polynomials += kernel->GetFactor(f).IsPolynomial;
  }
  constexpr double MaximumCoefficients = double(1 << 23); // 64 MiB of doubles
  if (polynomials == 0 ||
    double(g.Dims[1]) * g.Dims[2] * kernel->GetLineCoefficientCount() > MaximumCoefficients)
  {
    store.clear();
    return {};
  }
  const std::vector<double> grid{ double(g.Dims[0]), double(g.Dims[1]), double(g.Dims[2]),
    g.Origin[0], g.Origin[1], g.Origin[2], g.Spacing[0], g.Spacing[1], g.Spacing[2] };
  if (grid != gridKey)
  {
    store.clear();
    gridKey = grid;
  }
  for (FactorCache& cache : store)
  {
    cache.Used = false;
  }
  const size_t rows = size_t(g.Dims[1]) * g.Dims[2];
  std::vector<std::ptrdiff_t> index(kernel->GetNumberOfFactors(), -1);
  for (size_t f = 0; f < kernel->GetNumberOfFactors(); ++f)
  {
    const pisurf::Factor& factor = kernel->GetFactor(f);
    if (!factor.IsPolynomial)
    {
      continue;
    }
    std::vector<double> key = FactorKey(factor.Polynomial);
    auto found = std::find_if(
      store.begin(), store.end(), [&](const FactorCache& c) { return c.Key == key; });
    if (found == store.end())
    {
      FactorCache cache;
      cache.Key = std::move(key);
      cache.Coefficients = std::max(factor.Polynomial.Poly.GetDegree(), 0) + 1;
      cache.Rows.resize(rows * cache.Coefficients);
      cache.RowDone.assign(rows, 0);
      store.push_back(std::move(cache));
      found = store.end() - 1;
    }
    found->Used = true;
    index[f] = found - store.begin();
  }
  // Factors no longer in the product (a moved primitive's old placement) are dropped.
  std::vector<FactorCache> kept;
  std::vector<std::ptrdiff_t> renumber(store.size(), -1);
  for (size_t c = 0; c < store.size(); ++c)
  {
    if (store[c].Used)
    {
      renumber[c] = static_cast<std::ptrdiff_t>(kept.size());
      kept.push_back(std::move(store[c]));
    }
  }
  store = std::move(kept);
  std::vector<FactorCache*> caches(kernel->GetNumberOfFactors(), nullptr);
  for (size_t f = 0; f < caches.size(); ++f)
  {
    if (index[f] >= 0)
    {
      caches[f] = &store[renumber[index[f]]];
    }
  }
  return caches;
}

// PASS 2, incremental: each factor is restricted to the rows it has not been restricted
// to on this grid yet, about the middle of the row as in RestrictRows; the row's
// coefficients are then gathered from the caches in RestrictRows's layout.
struct RestrictCachedRows
{
  const Grid* G;
  const std::vector<vtkIdType>* Rows;
  const std::vector<FactorCache*>* Caches;
  const pisurf::ProductKernel* Kernel;
  pisurf::LargeVector<double>* Coefficients;

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const size_t n = this->Kernel->GetLineCoefficientCount();
    const double step[3] = { this->G->Spacing[0], 0.0, 0.0 };
    for (vtkIdType r = begin; r < end; ++r)
    {
      const vtkIdType row = (*this->Rows)[r];
      double o[3];
      this->G->RowMiddle(row, o);
      double* out = this->Coefficients->data() + r * n;
      for (size_t f = 0; f < this->Caches->size(); ++f)
      {
        FactorCache* cache = (*this->Caches)[f];
        if (!cache)
        {
          continue;
        }
        double* coefficients = cache->Rows.data() + row * cache->Coefficients;
        if (!cache->RowDone[row])
        {
          this->Kernel->GetFactor(f).Polynomial.RestrictToLine(o, step, coefficients);
          cache->RowDone[row] = 1;
        }
        std::copy(coefficients, coefficients + cache->Coefficients, out);
        out += cache->Coefficients;
      }
    }
  }
};

// The outer envelope: which points are connected to the boundary of the grid through
// points of the outside sign ("free" points). Skipped blocks are handled whole; in an
// active block each point row along x is a bit mask (bit i: point i), the block's free
// points and the reached ones, so a block floods in a few sweeps of bit operations.
// Blocks share their face points: a block that reaches points on a face hands them to
// the neighbour across it, and the flood goes block by block until nothing changes.
class Envelope
{
public:
  static constexpr int Rows = BlockPoints * BlockPoints; // row (j, k) at k·9 + j

  // `field` (may be null) marks points of bounded positive components, which the flood
  // fill does not pass (see pisurf::Field::OffOuterSide).
  // `free` and `reached`: its work arrays (the mesher keeps them between executions).
  Envelope(const Grid& g, int outside, const pisurf::Field* field,
    pisurf::Buffer<std::uint16_t>& free, pisurf::Buffer<std::uint16_t>& reached)
    : G(g)
    , Outside(outside)
    , BlockState(g.Sign.size(), 0)
    , Free(free)
    , Reached(reached)
  {
    const size_t active = g.Active.size();
    this->Free.Reserve(active * Rows);
    this->Reached.Reserve(active * Rows);
    // PASS 4a. Skipped blocks of the outside sign are free as a whole, except, for a
    // field, those in a bounded component (F keeps its sign over the block, so the whole
    // block is in the component of its centre): those count as the other sign.
    char* blockState = this->BlockState.data();
    const Grid* grid = &this->G;
    PiFor(0, static_cast<vtkIdType>(g.Sign.size()), 0, [=](vtkIdType begin, vtkIdType end) {
      for (vtkIdType b = begin; b < end; ++b)
      {
        if (grid->Sign[b] != outside)
        {
          continue;
        }
        bool free = true;
        if (field && outside > 0)
        {
          int c[3];
          grid->BlockCoordinates(b, c);
          double centre[3];
          for (int a = 0; a < 3; ++a)
          {
            centre[a] = grid->Origin[a] +
              0.5 * (grid->First(c, a) + grid->Last(c, a)) * grid->Spacing[a];
          }
          free = !field->OffOuterSide(centre);
        }
        blockState[b] = free ? FreeBlock : 0;
      }
    });
    // The free points of the active blocks: the outside sign (and, for a field, not off
    // the outer side); points shared with a skipped block take that block's verdict.
    std::uint16_t* freeRows = this->Free.GetPointer();
    std::uint16_t* reachedRows = this->Reached.GetPointer();
    PiFor(0, static_cast<vtkIdType>(active), 0, [=](vtkIdType begin, vtkIdType end) {
      for (vtkIdType s = begin; s < end; ++s)
      {
        int c[3];
        grid->BlockCoordinates(grid->Active[s], c);
        int first[3], last[3], n[3];
        grid->Range(c, first, last);
        grid->CellCounts(c, n);
        const double* v = grid->Values + size_t(s) * BlockPoints * BlockPoints * BlockPoints;
        unsigned char off[BlockPoints * BlockPoints * BlockPoints];
        const bool checkField = field && outside > 0;
        const bool boxed = checkField &&
          field->OffOuterSideBox(grid->Origin, grid->Spacing, first, last, BlockPoints,
            BlockPoints * BlockPoints, off);
        std::uint16_t* fr = freeRows + size_t(s) * Rows;
        std::fill(reachedRows + size_t(s) * Rows, reachedRows + size_t(s + 1) * Rows, 0);
        for (int lk = 0; lk <= n[2]; ++lk)
          for (int lj = 0; lj <= n[1]; ++lj)
          {
            const int q = (lk * BlockPoints + lj) * BlockPoints;
            unsigned bits = 0;
            if (!checkField)
            {
              // The sign alone, without the field's branches in the loop.
              bits = SignBits(v + q, n[0] + 1);
              fr[lk * BlockPoints + lj] =
                static_cast<std::uint16_t>(outside > 0 ? bits : ~bits & ((2u << n[0]) - 1u));
              continue;
            }
            for (int li = 0; li <= n[0]; ++li)
            {
              bool free = (v[q + li] >= 0) == (outside > 0);
              if (free && checkField)
              {
                if (boxed)
                {
                  free = !off[q + li];
                }
                else
                {
                  const double p[3] = { grid->Origin[0] + (first[0] + li) * grid->Spacing[0],
                    grid->Origin[1] + (first[1] + lj) * grid->Spacing[1],
                    grid->Origin[2] + (first[2] + lk) * grid->Spacing[2] };
                  free = !field->OffOuterSide(p);
                }
              }
              bits |= unsigned(free) << li;
            }
            fr[lk * BlockPoints + lj] = static_cast<std::uint16_t>(bits);
          }
        // Skipped neighbours (all 26) decide their shared points: free where they are
        // free blocks, not free otherwise (clearing wins).
        for (int pass = 0; pass < 2; ++pass)
        {
          grid->ForEachNeighbour(c, [&](vtkIdType nb, const int d[3]) {
            if (grid->Sign[nb] == 0 || grid->Sign[nb] == AbsentBlock ||
              (blockState[nb] == FreeBlock) != (pass == 0))
            {
              return;
            }
            int lo[3], hi[3];
            for (int a = 0; a < 3; ++a)
            {
              SharedPoints(d[a], n[a], lo[a], hi[a]);
            }
            const unsigned xs = PointMask(lo[0], hi[0]);
            for (int lk = lo[2]; lk <= hi[2]; ++lk)
              for (int lj = lo[1]; lj <= hi[1]; ++lj)
              {
                std::uint16_t& row = fr[lk * BlockPoints + lj];
                row = static_cast<std::uint16_t>(pass == 0 ? row | xs : row & ~xs);
              }
          });
        }
      }
    });
  }

  // The flood fill from the boundary, in rounds: each round processes the blocks the
  // last one reached (in parallel), each followed by up to 64 blocks it reaches
  // (depth first), and queues the rest of what it reaches for the next. A block's
  // reached rows only gain bits, by atomic ORs (several blocks may add to one
  // neighbour at once, and it may be flooding itself meanwhile), and a block that gains
  // any is queued for the next round: the rounds end at the fixed point, the set of free
  // points connected to the boundary, whatever the order (the same result as a serial
  // flood).
  void Flood()
  {
    const int* count = this->G.Count;
    this->Queued.assign(this->G.Sign.size(), 0);
    std::vector<vtkIdType> frontier;
    // Seeds: every free point on the boundary of the grid (in the layers it floods).
    Pusher seeds{ this, &frontier };
    for (vtkIdType b = 0; b < static_cast<vtkIdType>(this->G.Sign.size()); ++b)
    {
      int c[3];
      this->G.BlockCoordinates(b, c);
      const bool boundary = c[0] == 0 || c[1] == 0 || c[2] == 0 || c[0] == count[0] - 1 ||
        c[1] == count[1] - 1 || c[2] == count[2] - 1;
      if (!boundary || !this->FloodsLayer(c[2]))
      {
        continue;
      }
      if (this->G.Sign[b] != 0)
      {
        this->ReachSkipped(b, seeds);
        continue;
      }
      int n[3];
      this->G.CellCounts(c, n);
      bool any = false;
      for (int a = 0; a < 3; ++a)
      {
        for (int side = 0; side < 2; ++side)
        {
          if (c[a] != (side ? count[a] - 1 : 0))
          {
            continue;
          }
          int lo[3] = { 0, 0, 0 }, hi[3] = { n[0], n[1], n[2] };
          lo[a] = hi[a] = side ? n[a] : 0;
          any = this->Seed(this->G.Slot[b], lo, hi) || any;
        }
      }
      if (any)
      {
        seeds.Push(b);
      }
    }
    this->Run(frontier);
  }

  // Only the block layers [begin, end) along z are flooded (a piece's slab, see
  // FloodAcrossPieces); the default is every layer.
  void SetFloodLayers(int begin, int end)
  {
    this->FloodBegin = begin;
    this->FloodEnd = end;
  }

  // Flood's fixed point over the pieces' slabs together (ParaView's MPI mode: piece p of
  // n on process p, each flooding its own slab, after Flood). Neighbouring slabs share
  // the plane of points between them (each holds it in its own blocks), so what one
  // reached there is reached in the other too: in rounds, each piece sends the reached
  // points of its bottom and top planes to the pieces below and above, adds theirs and
  // floods on from them, until a round adds nothing anywhere. The set reached is the
  // serial flood's (the free points connected to the boundary through free points,
  // whichever slabs the path crosses). Every process must call this.
  // Returns the number of rounds.
  int FloodAcrossPieces(vtkMultiProcessController* controller, int piece, int pieces)
  {
    const vtkIdType size = vtkIdType(this->G.Dims[0]) * this->G.Dims[1];
    std::vector<unsigned char> bottom, top, fromBelow(size, 0), fromAbove(size, 0);
    const bool below = piece > 0, above = piece + 1 < pieces;
    // A piece without layers (more pieces than layers) has one plane, its neighbours'
    // shared one: it hands on what comes from below upwards and what comes from above
    // downwards, in the same round.
    const bool empty = this->FloodBegin >= this->FloodEnd;
    for (int round = 1;; ++round)
    {
      if (below && !empty)
      {
        this->ReadPlane(this->FloodBegin, false, bottom);
      }
      if (above && !empty)
      {
        this->ReadPlane(this->FloodEnd - 1, true, top);
      }
      // Up the chain of pieces, then down (each receive meets the send before it: no
      // cycle of waiting processes).
      if (below)
      {
        controller->Receive(fromBelow.data(), size, piece - 1, PlaneUpTag);
      }
      if (above)
      {
        controller->Send(empty ? fromBelow.data() : top.data(), size, piece + 1, PlaneUpTag);
        controller->Receive(fromAbove.data(), size, piece + 1, PlaneDownTag);
      }
      if (below)
      {
        controller->Send(empty ? fromAbove.data() : bottom.data(), size, piece - 1, PlaneDownTag);
      }
      std::vector<vtkIdType> frontier;
      if (below && !empty)
      {
        this->SeedPlane(this->FloodBegin, false, fromBelow, frontier);
      }
      if (above && !empty)
      {
        this->SeedPlane(this->FloodEnd - 1, true, fromAbove, frontier);
      }
      int added = frontier.empty() ? 0 : 1, anywhere = 0;
      controller->AllReduce(&added, &anywhere, 1, vtkCommunicator::MAX_OP);
      if (!anywhere)
      {
        return round;
      }
      this->Run(frontier);
    }
  }

  // The blocks of layer `ghost` (the layer above a piece's slab: contoured only to number
  // the vertices on the plane it shares with the slab) take the slab's reached points on
  // that plane, their bottom one. (Their other points stay unreached: no triangle of the
  // piece uses them.)
  void CopyTopPlaneTo(int ghost)
  {
    std::vector<unsigned char> plane;
    this->ReadPlane(this->FloodEnd - 1, true, plane);
    const Grid& g = this->G;
    this->ForEachBlockOfLayer(ghost, [&](vtkIdType b, const int c[3], const int n[3]) {
      if (g.Sign[b] != 0 || g.Slot[b] < 0)
      {
        return;
      }
      const size_t base = size_t(g.Slot[b]) * Rows;
      for (int lj = 0; lj <= n[1]; ++lj)
      {
        this->Reached.GetPointer()[base + lj] = static_cast<std::uint16_t>(
          this->PlaneRow(plane, c, lj, n[0]) & this->Free.GetPointer()[base + lj]);
      }
    });
  }

private:
  // Message tags of FloodAcrossPieces.
  static constexpr int PlaneUpTag = 924101;
  static constexpr int PlaneDownTag = 924102;

  // Flood's rounds from `frontier` to the fixed point.
  void Run(std::vector<vtkIdType>& frontier)
  {
    vtkSMPThreadLocal<std::vector<vtkIdType>> next;
    while (!frontier.empty())
    {
      // Blocks reached again from now on are queued for the next round.
      for (vtkIdType b : frontier)
      {
        this->Queued[b] = 0;
      }
      Envelope* self = this;
      const std::vector<vtkIdType>* blocks = &frontier;
      PiFor(0, static_cast<vtkIdType>(frontier.size()), 8,
        [self, blocks, &next](vtkIdType begin, vtkIdType end) {
          std::vector<vtkIdType>& stack = next.Local();
          Pusher push{ self, &stack };
          for (vtkIdType m = begin; m < end; ++m)
          {
            self->Visit((*blocks)[m], push);
            // Then what that reached, depth first, up to a budget (a serial flood's
            // order: a region is usually finished before its blocks are met again);
            // the rest waits for the next round.
            for (int budget = 64; budget > 0 && !stack.empty(); --budget)
            {
              const vtkIdType b = stack.back();
              stack.pop_back();
              __atomic_store_n(&self->Queued[b], char(0), __ATOMIC_RELAXED);
              self->Visit(b, push);
            }
          }
        });
      frontier.clear();
      for (std::vector<vtkIdType>& local : next)
      {
        frontier.insert(frontier.end(), local.begin(), local.end());
        local.clear();
      }
      // In block order: each thread then works on its own stretch of the grid.
      std::sort(frontier.begin(), frontier.end());
    }
  }

  // Whether the flood enters the blocks of layer z, and block b.
  bool FloodsLayer(vtkIdType z) const { return z >= this->FloodBegin && z < this->FloodEnd; }
  bool Floods(vtkIdType b) const
  {
    if (this->FloodBegin == 0 && this->FloodEnd >= this->G.Count[2])
    {
      return true; // (every layer: no division)
    }
    return this->FloodsLayer(b / (vtkIdType(this->G.Count[0]) * this->G.Count[1]));
  }

  // f(block id, its cell counts n) for each block of layer `layer`.
  template <typename Function>
  void ForEachBlockOfLayer(int layer, Function f) const
  {
    const Grid& g = this->G;
    for (int by = 0; by < g.Count[1]; ++by)
      for (int bx = 0; bx < g.Count[0]; ++bx)
      {
        const int c[3] = { bx, by, layer };
        int n[3];
        g.CellCounts(c, n);
        f(g.BlockId(bx, by, layer), c, n);
      }
  }

  // Where row lj of block c's part of a plane starts in ReadPlane's layout (one byte per
  // point, at j·Dims[0] + i).
  size_t PlaneOffset(const int c[3], int lj) const
  {
    return size_t(c[1] * BlockCells + lj) * this->G.Dims[0] + c[0] * BlockCells;
  }

  // The plane's points of row lj of block c's plane, as a row mask of n0 + 1 bits.
  unsigned PlaneRow(const std::vector<unsigned char>& plane, const int c[3], int lj, int n0) const
  {
    const unsigned char* in = plane.data() + this->PlaneOffset(c, lj);
    unsigned bits = 0;
    for (int li = 0; li <= n0; ++li)
    {
      bits |= unsigned(in[li] != 0) << li;
    }
    return bits;
  }

  // The reached points of the bottom (or top) plane of block layer `layer` in that
  // layout: from its active blocks' rows, and every point of its reached skipped blocks.
  void ReadPlane(int layer, bool topPlane, std::vector<unsigned char>& plane) const
  {
    const Grid& g = this->G;
    plane.assign(size_t(g.Dims[0]) * g.Dims[1], 0);
    this->ForEachBlockOfLayer(layer, [&](vtkIdType b, const int c[3], const int n[3]) {
      const bool active = g.Sign[b] == 0;
      if (!active && this->BlockState[b] != ReachedBlock)
      {
        return;
      }
      const std::uint16_t* rr =
        active ? this->Reached.GetPointer() + size_t(g.Slot[b]) * Rows : nullptr;
      const int lk = topPlane ? n[2] : 0;
      for (int lj = 0; lj <= n[1]; ++lj)
      {
        const unsigned bits = active ? LoadRow(rr + lk * BlockPoints + lj) : 0x1ffu;
        unsigned char* out = plane.data() + this->PlaneOffset(c, lj);
        for (int li = 0; li <= n[0]; ++li)
        {
          out[li] |= static_cast<unsigned char>((bits >> li) & 1u);
        }
      }
    });
  }

  // Adds the points set in `plane` (ReadPlane's layout) to the blocks of layer `layer`
  // on its bottom (or top) plane, queueing in `frontier` each block that gains any.
  void SeedPlane(int layer, bool topPlane, const std::vector<unsigned char>& plane,
    std::vector<vtkIdType>& frontier)
  {
    const Grid& g = this->G;
    Pusher push{ this, &frontier };
    this->ForEachBlockOfLayer(layer, [&](vtkIdType b, const int c[3], const int n[3]) {
      const bool active = g.Sign[b] == 0;
      if (!active && this->BlockState[b] != FreeBlock)
      {
        return;
      }
      const size_t base = active ? size_t(g.Slot[b]) * Rows : 0;
      const int lk = topPlane ? n[2] : 0;
      bool added = false, any = false;
      for (int lj = 0; lj <= n[1]; ++lj)
      {
        const unsigned bits = this->PlaneRow(plane, c, lj, n[0]);
        any = any || bits != 0;
        if (active && bits)
        {
          std::uint16_t* row = this->Reached.GetPointer() + base + lk * BlockPoints + lj;
          const unsigned add =
            bits & this->Free.GetPointer()[base + lk * BlockPoints + lj] & ~LoadRow(row);
          added = (add && AddToRow(row, add)) || added;
        }
      }
      if (active && added)
      {
        push.Push(b);
      }
      else if (!active && any)
      {
        this->ReachSkipped(b, push);
      }
    });
  }

public:
  int GetOutside() const { return this->Outside; }

  /// The row masks the contouring sees in active block `slot`: bit i set where the sign
  /// is positive (the outside sign where connected to the boundary, the other sign
  /// everywhere else).
  unsigned PositiveRow(int slot, int row) const
  {
    const unsigned reached = this->Reached[size_t(slot) * Rows + row];
    return this->Outside > 0 ? reached : ~reached & 0x1ffu;
  }

private:
  static constexpr char FreeBlock = 1;
  static constexpr char ReachedBlock = 2;

  // The local indices [lo, hi] on one axis of a block (n cells there) that it shares
  // with its neighbour at offset d (−1, 0 or +1) on that axis.
  static void SharedPoints(int d, int n, int& lo, int& hi)
  {
    lo = d > 0 ? n : 0;
    hi = d < 0 ? 0 : n;
  }
  // The bits lo..hi of a row mask.
  static unsigned PointMask(int lo, int hi)
  {
    return ((1u << (hi + 1)) - 1u) & ~((1u << lo) - 1u);
  }

  // A row of reached bits, read and grown atomically (Flood's rounds are parallel).
  static unsigned LoadRow(const std::uint16_t* row) { return __atomic_load_n(row, __ATOMIC_RELAXED); }
  // Adds `bits` (not 0) to the row; true if any was not there yet.
  static bool AddToRow(std::uint16_t* row, unsigned bits)
  {
    const unsigned old = __atomic_fetch_or(row, static_cast<std::uint16_t>(bits), __ATOMIC_RELAXED);
    return (bits & ~old) != 0u;
  }

  // Queues blocks for the next round of the flood, each once per round.
  struct Pusher
  {
    Envelope* Self;
    std::vector<vtkIdType>* Out;
    void Push(vtkIdType b)
    {
      // (A plain look first: most blocks are met several times per round, and a write
      // to a shared cache line costs more than the read.)
      char* queued = &this->Self->Queued[b];
      if (__atomic_load_n(queued, __ATOMIC_RELAXED) == 0 &&
        __atomic_exchange_n(queued, char(1), __ATOMIC_RELAXED) == 0)
      {
        this->Out->push_back(b);
      }
    }
  };

  // A skipped block met by the flood: reached (and queued) if it is a free one.
  void ReachSkipped(vtkIdType b, Pusher& push)
  {
    char expected = FreeBlock;
    if (this->BlockState[b] == FreeBlock &&
      __atomic_compare_exchange_n(&this->BlockState[b], &expected, ReachedBlock, false,
        __ATOMIC_RELAXED, __ATOMIC_RELAXED))
    {
      push.Push(b);
    }
  }

  // One block of a round: a reached skipped block reaches every neighbour sharing
  // points with it; an active block floods itself, then hands its reached face points
  // to its six face neighbours.
  void Visit(vtkIdType b, Pusher& push)
  {
    const int* count = this->G.Count;
    int c[3];
    this->G.BlockCoordinates(b, c);
    if (this->G.Sign[b] != 0)
    {
      this->G.ForEachNeighbour(c, [&](vtkIdType nb, const int d[3]) {
        if (!this->Floods(nb))
        {
          return;
        }
        if (this->G.Sign[nb] != 0)
        {
          this->ReachSkipped(nb, push);
          return;
        }
        // The neighbour's points shared with this block (it sees this block at −d).
        int m[3], nn[3], lo[3], hi[3];
        this->G.BlockCoordinates(nb, m);
        this->G.CellCounts(m, nn);
        for (int a = 0; a < 3; ++a)
        {
          SharedPoints(-d[a], nn[a], lo[a], hi[a]);
        }
        if (this->Seed(this->G.Slot[nb], lo, hi))
        {
          push.Push(nb);
        }
      });
      return;
    }
    const int slot = this->G.Slot[b];
    this->FloodBlock(slot);
    int n[3];
    this->G.CellCounts(c, n);
    const std::uint16_t* reached = this->Reached.GetPointer() + size_t(slot) * Rows;
    for (int a = 0; a < 3; ++a)
    {
      for (int side = 0; side < 2; ++side)
      {
        int m[3] = { c[0], c[1], c[2] };
        m[a] += side ? 1 : -1;
        if (m[a] < 0 || m[a] >= count[a] || (a == 2 && !this->FloodsLayer(m[2])))
        {
          continue;
        }
        const vtkIdType nb = this->G.BlockId(m[0], m[1], m[2]);
        const int plane = side ? n[a] : 0;
        if (this->G.Sign[nb] != 0)
        {
          if (this->FaceReached(reached, a, plane, n))
          {
            this->ReachSkipped(nb, push);
          }
          continue;
        }
        int nn[3];
        this->G.CellCounts(m, nn);
        if (this->PassFace(reached, a, plane, n, this->G.Slot[nb], side ? 0 : nn[a]))
        {
          push.Push(nb);
        }
      }
    }
  }

  // Marks the free points of rows [lo, hi] of block `slot` reached; true if any is new.
  bool Seed(int slot, const int lo[3], const int hi[3])
  {
    const std::uint16_t* fr = this->Free.GetPointer() + size_t(slot) * Rows;
    std::uint16_t* rr = this->Reached.GetPointer() + size_t(slot) * Rows;
    const unsigned xs = PointMask(lo[0], hi[0]);
    bool added = false;
    for (int lk = lo[2]; lk <= hi[2]; ++lk)
      for (int lj = lo[1]; lj <= hi[1]; ++lj)
      {
        const int r = lk * BlockPoints + lj;
        const unsigned add = fr[r] & xs & ~LoadRow(rr + r);
        if (add && AddToRow(rr + r, add))
        {
          added = true;
        }
      }
    return added;
  }

  // Any reached point on the plane `plane` of axis a? (Only that plane's rows.)
  static bool FaceReached(const std::uint16_t* reached, int a, int plane, const int n[3])
  {
    if (a == 0)
    {
      for (int lk = 0; lk <= n[2]; ++lk)
        for (int lj = 0; lj <= n[1]; ++lj)
        {
          if ((LoadRow(reached + lk * BlockPoints + lj) >> plane) & 1u)
          {
            return true;
          }
        }
      return false;
    }
    const int count = a == 1 ? n[2] : n[1];
    for (int q = 0; q <= count; ++q)
    {
      const int row = a == 1 ? q * BlockPoints + plane : plane * BlockPoints + q;
      if (LoadRow(reached + row) != 0)
      {
        return true;
      }
    }
    return false;
  }

  // Copies the reached points of plane `plane` (axis a) into plane `target` of the
  // active block `slot` (the same points); true if any is new there. (Only the plane's
  // rows.)
  bool PassFace(const std::uint16_t* reached, int a, int plane, const int n[3], int slot, int target)
  {
    const std::uint16_t* fr = this->Free.GetPointer() + size_t(slot) * Rows;
    std::uint16_t* rr = this->Reached.GetPointer() + size_t(slot) * Rows;
    bool added = false;
    auto pass = [&](unsigned in, int to) {
      const unsigned add = in & fr[to] & ~LoadRow(rr + to);
      if (add && AddToRow(rr + to, add))
      {
        added = true;
      }
    };
    if (a == 0)
    {
      for (int lk = 0; lk <= n[2]; ++lk)
        for (int lj = 0; lj <= n[1]; ++lj)
        {
          const int row = lk * BlockPoints + lj;
          pass(((LoadRow(reached + row) >> plane) & 1u) << target, row);
        }
    }
    else if (a == 1)
    {
      for (int lk = 0; lk <= n[2]; ++lk)
      {
        pass(LoadRow(reached + lk * BlockPoints + plane), lk * BlockPoints + target);
      }
    }
    else
    {
      for (int lj = 0; lj <= n[1]; ++lj)
      {
        pass(LoadRow(reached + plane * BlockPoints + lj), target * BlockPoints + lj);
      }
    }
    return added;
  }


  // The reached points of an active block grown through its free points to a fixed
  // point: along x by shifts within a row, along y and z into the neighbouring rows. A
  // worklist of rows (bit r of `dirty`: row r may reach further), at first every row
  // holding reached points; a row taken from it grows within itself, then passes its
  // points to its four neighbouring rows, and a neighbour that gains any joins the
  // list. (Other threads may add points to the block meanwhile: they queue the block
  // again, see Run.)
  void FloodBlock(int slot)
  {
    int c[3];
    this->G.BlockCoordinates(this->G.Active[slot], c);
    int n[3];
    this->G.CellCounts(c, n);
    const int ny = n[1], nz = n[2];
    const std::uint16_t* fr = this->Free.GetPointer() + size_t(slot) * Rows;
    std::uint16_t* rr = this->Reached.GetPointer() + size_t(slot) * Rows;
    static_assert(Rows <= 128, "two words of row bits");
    std::uint64_t dirty[2] = { 0, 0 };
    for (int lk = 0; lk <= nz; ++lk)
      for (int lj = 0; lj <= ny; ++lj)
      {
        const int r = lk * BlockPoints + lj;
        if (LoadRow(rr + r) != 0)
        {
          dirty[r >> 6] |= std::uint64_t(1) << (r & 63);
        }
      }
    auto pass = [&](unsigned from, int to) {
      const unsigned add = from & fr[to] & ~LoadRow(rr + to);
      if (add && AddToRow(rr + to, add))
      {
        dirty[to >> 6] |= std::uint64_t(1) << (to & 63);
      }
    };
    while (dirty[0] | dirty[1])
    {
      const int word = dirty[0] ? 0 : 1;
      const int r = 64 * word + __builtin_ctzll(dirty[word]);
      dirty[word] &= dirty[word] - 1;
      // Within the row: the free runs that hold a reached point.
      const unsigned f = fr[r];
      const unsigned old = LoadRow(rr + r);
      unsigned x = old;
      for (;;)
      {
        const unsigned next = (x | (x << 1) | (x >> 1)) & f;
        if (next == x)
        {
          break;
        }
        x = next;
      }
      if (x != old)
      {
        AddToRow(rr + r, x & ~old);
      }
      const int lj = r % BlockPoints, lk = r / BlockPoints;
      if (lj > 0)
      {
        pass(x, r - 1);
      }
      if (lj < ny)
      {
        pass(x, r + 1);
      }
      if (lk > 0)
      {
        pass(x, r - BlockPoints);
      }
      if (lk < nz)
      {
        pass(x, r + BlockPoints);
      }
    }
  }

  const Grid& G;
  int Outside;
  std::vector<char> BlockState; // skipped blocks: FreeBlock, ReachedBlock or 0
  pisurf::Buffer<std::uint16_t>& Free;    // per active block: Rows masks each
  pisurf::Buffer<std::uint16_t>& Reached; // (the same)
  std::vector<char> Queued; // per block: queued for the flood's next round
  int FloodBegin = 0, FloodEnd = 1 << 30; // the block layers flooded
};

// PASS 5 and 6: marching cubes over the cells of the active blocks. Each crossing edge
// belongs to the block that holds its lower end point (half-open ranges, closed at the
// end of the grid), which numbers its vertex; triangles then find their edges' vertices
// in the owner's edge masks and row offsets. Mode Count builds the masks and counts
// both; Write then writes each block's vertices' edges and its triangles (a block's
// own edges' ids from a table it fills as it writes them, other blocks' edges from
// their masks: Count's, so the blocks need no order).
struct Contour
{
  enum Mode
  {
    Count,
    Write
  };
  const Grid* G;
  const Envelope* Outer; // null: plain signs
  vtkMarchingCubesTriangleCases* Cases;
  std::vector<vtkIdType>* VertexCount;   // per active block: count, then first id
  std::vector<vtkIdType>* TriangleCount; // per active block: count, then first index
  pisurf::Buffer<vtkIdType>* VertexEdge; // per vertex: point id · 3 + axis
  pisurf::Buffer<double>* VertexT;       // per vertex: crossing parameter along the edge
  pisurf::Buffer<double>* VertexEnds;    // per vertex: F at the edge's two end points
  // The triangles' point ids, in vtkCellArray's 64-bit or (when the ids fit) 32-bit
  // storage: exactly one of the two is set. Written facing ∇F (see GenerateMesh).
  vtkIdType* TriangleIds;
  std::int32_t* TriangleIds32;
  Mode Pass = Count;
  int SlabBegin = 0, SlabEnd = 1 << 30; // this piece's block layers along z

  // Per active block, filled by Count: the signs the contouring sees as bit masks, one
  // per point row along x (bit i: point i of row (j, k) is positive), and, per axis and
  // row (k, j) of the edges the block owns (lower end at local 0..7 on every axis), the
  // crossing edges as a bit mask and the number of the block's vertices before that
  // row. A block's vertices are numbered by axis, then k, j, i: any edge's vertex id is
  // its owner's first id + the row's offset + the crossings before it in the row.
  std::uint16_t* RowSigns;
  std::uint8_t* EdgeMasks;
  std::uint16_t* EdgeOffsets;
  const std::uint8_t* TrianglesOfCase; // per marching-cubes case: its triangle count

  static constexpr int Rows = BlockPoints * BlockPoints;
  static constexpr int EdgeRows = 3 * BlockCells * BlockCells;

  static int Local(int li, int lj, int lk) { return (lk * BlockPoints + lj) * BlockPoints + li; }
  // The set bits of an 8-bit mask (a table: the baseline x86-64 has no POPCNT
  // instruction, and __builtin_popcount then calls a library routine).
  static int BitCount(unsigned mask)
  {
    static constexpr struct Table
    {
      unsigned char Of[256];
      constexpr Table()
        : Of()
      {
        for (int m = 0; m < 256; ++m)
        {
          this->Of[m] = static_cast<unsigned char>((m & 1) + (m >> 1 & 1) + (m >> 2 & 1) +
            (m >> 3 & 1) + (m >> 4 & 1) + (m >> 5 & 1) + (m >> 6 & 1) + (m >> 7 & 1));
        }
      }
    } table{};
    return table.Of[mask & 0xffu];
  }
  static int EdgeRow(int axis, int lk, int lj) { return (axis * BlockCells + lk) * BlockCells + lj; }
  // Where Write keeps the id of the owned edge at local lower end (li, lj, lk) on `axis`.
  static int OwnedSlot(int axis, int li, int lj, int lk) { return EdgeRow(axis, lk, lj) * BlockCells + li; }

  // The vertex id of the crossing edge its block `slot` owns at local lower end
  // (li, lj, lk), each in 0..7: the block's first id, the row's offset and the
  // crossings before it in the row.
  vtkIdType OwnedVertex(int slot, int li, int lj, int lk, int axis) const
  {
    const size_t row = size_t(slot) * EdgeRows + EdgeRow(axis, lk, lj);
    return (*this->VertexCount)[slot] + this->EdgeOffsets[row] +
      BitCount(this->EdgeMasks[row] & ((1u << li) - 1u));
  }

  // The vertex id of the crossing edge (i, j, k, axis) (grid indices of its lower end).
  vtkIdType VertexOf(int i, int j, int k, int axis) const
  {
    const int c[3] = { i / BlockCells, j / BlockCells, k / BlockCells };
    const int slot = this->G->Slot[this->G->BlockId(c[0], c[1], c[2])];
    return this->OwnedVertex(
      slot, i - c[0] * BlockCells, j - c[1] * BlockCells, k - c[2] * BlockCells, axis);
  }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    for (vtkIdType s = begin; s < end; ++s)
    {
      int c[3];
      this->G->BlockCoordinates(this->G->Active[s], c);
      const double* v = this->G->Values + size_t(s) * BlockPoints * BlockPoints * BlockPoints;
      int f[3], l[3], n[3];
      this->G->Range(c, f, l);
      // Cells along each axis in this block, and the last owned lower end.
      this->G->CellCounts(c, n);
      const int h[3] = { std::min(n[0], BlockCells - 1), std::min(n[1], BlockCells - 1),
        std::min(n[2], BlockCells - 1) };
      std::uint16_t* rows = this->RowSigns + size_t(s) * Rows;
      std::uint8_t* masks = this->EdgeMasks + size_t(s) * EdgeRows;
      std::uint16_t* offsets = this->EdgeOffsets + size_t(s) * EdgeRows;
      if (this->Pass == Count)
      {
        // The signs the contouring sees, once per point of the block.
        for (int lk = 0; lk <= n[2]; ++lk)
          for (int lj = 0; lj <= n[1]; ++lj)
          {
            const double* row = v + Local(0, lj, lk);
            unsigned bits = 0;
            if (this->Outer)
            {
              bits = this->Outer->PositiveRow(static_cast<int>(s), lk * BlockPoints + lj) &
                ((2u << n[0]) - 1u);
            }
            else
            {
              bits = SignBits(row, n[0] + 1);
            }
            rows[lk * BlockPoints + lj] = static_cast<std::uint16_t>(bits);
          }
        // The owned crossing edges, row by row, numbered in key order.
        const unsigned owned = (1u << (h[0] + 1)) - 1u;
        const unsigned xEdges = (1u << std::min(n[0], BlockCells)) - 1u;
        unsigned vertex = 0;
        for (int axis = 0; axis < 3; ++axis)
          for (int lk = 0; lk < BlockCells; ++lk)
            for (int lj = 0; lj < BlockCells; ++lj)
            {
              const int row = EdgeRow(axis, lk, lj);
              unsigned mask = 0;
              if (lk <= h[2] && lj <= h[1])
              {
                const unsigned r = rows[lk * BlockPoints + lj];
                if (axis == 0)
                {
                  mask = (r ^ (r >> 1)) & xEdges;
                }
                else if (axis == 1 && lj + 1 <= n[1])
                {
                  mask = (r ^ rows[lk * BlockPoints + lj + 1]) & owned;
                }
                else if (axis == 2 && lk + 1 <= n[2])
                {
                  mask = (r ^ rows[(lk + 1) * BlockPoints + lj]) & owned;
                }
              }
              masks[row] = static_cast<std::uint8_t>(mask);
              offsets[row] = static_cast<std::uint16_t>(vertex);
              vertex += BitCount(mask);
            }
        (*this->VertexCount)[s] = vertex;
      }
      // Write: the vertex id of each owned crossing edge, by its local lower end and
      // axis, for this block's triangles (an owned edge's id without the masks' sums).
      vtkIdType ids[3 * BlockCells * BlockCells * BlockCells];
      if (this->Pass == Write)
      {
        // The next block's values, long evicted since the sampling: fetched while this
        // block's edges are read (their loads were the pass's main stall).
        if (s + 1 < end)
        {
          const char* next = reinterpret_cast<const char*>(v + BlockPoints * BlockPoints * BlockPoints);
          for (size_t byte = 0; byte < sizeof(double) * BlockPoints * BlockPoints * BlockPoints;
               byte += 64)
          {
            __builtin_prefetch(next + byte);
          }
        }
        vtkIdType vertex = (*this->VertexCount)[s];
        for (int axis = 0; axis < 3; ++axis)
          for (int lk = 0; lk < BlockCells; ++lk)
            for (int lj = 0; lj < BlockCells; ++lj)
            {
              unsigned mask = masks[EdgeRow(axis, lk, lj)];
              while (mask)
              {
                const int li = __builtin_ctz(mask);
                mask &= mask - 1;
                int m[3] = { li, lj, lk };
                const int q0 = Local(li, lj, lk);
                ++m[axis];
                const int q1 = Local(m[0], m[1], m[2]);
                const bool positive0 = (rows[lk * BlockPoints + lj] >> li) & 1;
                const bool positive1 = (rows[m[2] * BlockPoints + m[1]] >> m[0]) & 1;
                (*this->VertexEdge)[vertex] =
                  this->G->PointId(f[0] + li, f[1] + lj, f[2] + lk) * 3 + axis;
                const double v0 = v[q0], v1 = v[q1];
                const bool own0 = (v0 >= 0) == positive0;
                const bool own1 = (v1 >= 0) == positive1;
                // Both ends of one sign (the envelope gave one the other sign): start at
                // the end whose sign is its own; Refine looks for the surface nearest to
                // it along the edge.
                const double t = !(own0 && own1) ? (own0 ? 0.0 : 1.0)
                                                : (v0 == v1 ? 0.5 : v0 / (v0 - v1));
                (*this->VertexT)[vertex] = std::max(0.0, std::min(1.0, t));
                (*this->VertexEnds)[2 * vertex] = v0;
                (*this->VertexEnds)[2 * vertex + 1] = v1;
                ids[OwnedSlot(axis, li, lj, lk)] = vertex;
                ++vertex;
              }
            }
      }
      if (c[2] < this->SlabBegin || c[2] >= this->SlabEnd)
      {
        if (this->Pass == Count)
        {
          (*this->TriangleCount)[s] = 0;
        }
        continue;
      }
      // The cells with both signs among their corners, row by row (i ascending).
      vtkIdType triangle = this->Pass == Count ? 0 : (*this->TriangleCount)[s];
      const unsigned cells = (1u << n[0]) - 1u;
      for (int lk = 0; lk < n[2]; ++lk)
        for (int lj = 0; lj < n[1]; ++lj)
        {
          const unsigned a = rows[lk * BlockPoints + lj], b = rows[lk * BlockPoints + lj + 1],
                         cc = rows[(lk + 1) * BlockPoints + lj],
                         d = rows[(lk + 1) * BlockPoints + lj + 1];
          const unsigned all = a & b & cc & d, any = a | b | cc | d;
          unsigned mixed = ((any | (any >> 1)) & ~(all & (all >> 1))) & cells;
          while (mixed)
          {
            const int li = __builtin_ctz(mixed);
            mixed &= mixed - 1;
            // Corners in VTK's hexahedron order (pisurf::mc::Corner).
            const unsigned index = ((a >> li) & 1) | ((a >> li) & 2) | (((b >> li) & 2) << 1) |
              (((b >> li) & 1) << 3) | (((cc >> li) & 1) << 4) | (((cc >> li) & 2) << 4) |
              (((d >> li) & 2) << 5) | (((d >> li) & 1) << 7);
            if (this->Pass == Count)
            {
              triangle += this->TrianglesOfCase[index];
              continue;
            }
            const int* list = this->Cases[index].edges;
            const int i = f[0] + li, j = f[1] + lj, k = f[2] + lk;
            for (int e = 0; list[e] >= 0; e += 3, ++triangle)
            {
              for (int q = 0; q < 3; ++q)
              {
                const pisurf::mc::EdgeStart& edge = pisurf::mc::EdgeStarts.Of[list[e + q]];
                const int ei = li + edge.Lo[0], ej = lj + edge.Lo[1], ek = lk + edge.Lo[2];
                // An edge this block owns (lower end at local 0..7): the id written
                // above; another block's: from its masks (VertexOf).
                const vtkIdType id = (ei < BlockCells && ej < BlockCells && ek < BlockCells)
                  ? ids[OwnedSlot(edge.Axis, ei, ej, ek)]
                  : this->VertexOf(i + edge.Lo[0], j + edge.Lo[1], k + edge.Lo[2], edge.Axis);
                // Corners 1 and 2 swapped: the table winds triangles for "inside =
                // positive", ours face ∇F.
                const vtkIdType at = 3 * triangle + (q == 0 ? 0 : 3 - q);
                if (this->TriangleIds32)
                {
                  this->TriangleIds32[at] = static_cast<std::int32_t>(id);
                }
                else
                {
                  this->TriangleIds[at] = id;
                }
              }
            }
          }
        }
      if (this->Pass == Count)
      {
        (*this->TriangleCount)[s] = triangle;
      }
    }
  }
};

// PASS 7: vertex positions, each moved to the root of F on its edge (optional), then
// the exact normal, |∇F| and the nearest factor there.
//
// The edge's end points have opposite signs (the sign of F is exact, overflow-safe), so
// the edge brackets a root; the Illinois variant of regula falsi on F (or, where F is
// beyond 1e200 at an end, on the overflow-free sign(F)·ln(1 + |F|)), with bisection
// where the secant leaves the bracket, finds it even where F varies over thousands of
// orders of magnitude along the edge.
struct VertexAttributes
{
  const Evaluator* Kernel;
  const Grid* G;
  const pisurf::Buffer<vtkIdType>* VertexEdge;
  const pisurf::Buffer<double>* VertexT;
  const pisurf::Buffer<double>* VertexEnds;
  vtkPoints* Points;
  vtkFloatArray* Normals;
  vtkIntArray* Factor;
  vtkDoubleArray* GradientMagnitude; // may be null
  bool Project;
  double Tolerance; // stop when the bracket is shorter than this
  bool PositiveEnvelope; // the outer envelope is on and its outside sign is +
  // Progress from 0.75 to 1 and cancel, through the main thread (this pass is the
  // longest for a large molecule).
  vtkPiFlyingEdges* Algorithm;
  std::atomic<bool>* Abort;
  std::atomic<vtkIdType>* Done;
  vtkIdType Total;
  // The sampling's row restrictions (PASS 2), per row (j, k) its index or −1; null for
  // a field.
  const pisurf::LargeVector<vtkIdType>* RowIndex;
  const pisurf::LargeVector<double>* RowCoefficients;
  size_t RowCoefficientCount;

  // Newton's method on F along the edge x = x0 + s·dx, s ∈ [0, 1], from s = t, kept in
  // the bracket the signs give (bisection when a step leaves it), on the factors'
  // restrictions to the edge's line: stops when |F| <= small or a step is shorter than
  // `width` (Newton's error is then about the square of that step). −1 where the plain
  // product cannot be used (then the caller's regula falsi decides).
  static double Newton(const pisurf::ProductKernel* kernel, const double* line, int axis,
    double x0, double dx, double t, double va, double small, double width)
  {
    return NewtonOn(
      [&](double s, double& v, double& slope) {
        const bool ok = kernel->EvaluateOnAxisWithSlope(line, axis, x0 + s * dx, v, slope);
        slope *= dx;
        return ok;
      },
      t, va, small, width);
  }

  // The same along an x edge from grid point i of a row whose factors RestrictLine gave
  // (the sampling's own restriction, parameter t = i − mid at the edge's start, one unit
  // per cell): no restriction of its own to compute.
  static double RowNewton(const pisurf::ProductKernel* kernel, const double* row, double t0,
    double t, double va, double small, double width)
  {
    return NewtonOn(
      [&](double s, double& v, double& slope) {
        return kernel->EvaluateRestrictedWithSlope(row, t0 + s, v, slope);
      },
      t, va, small, width);
  }

  // Newton's method as a state: Step takes F and dF/ds at S (ok false where they cannot
  // be had) and either moves S or finishes with Result (−1: the plain product cannot be
  // used). NewtonOn runs one; the vertex loop runs up to MaxLanes side by side
  // (NewtonLanes), whose chains of dependent operations then overlap.
  struct NewtonLane
  {
    NewtonLane(double t, double va, double small, double width)
      : Va(va)
      , Small(small)
      , Width(width)
      , S(std::max(0.0, std::min(1.0, t)))
    {
    }
    void Step(bool ok, double v, double slope)
    {
      if (!ok)
      {
        this->Finish(-1.0);
        return;
      }
      if (std::fabs(v) <= this->Small)
      {
        this->Finish(this->S);
        return;
      }
      ((v < 0) == (this->Va < 0) ? this->Lo : this->Hi) = this->S;
      if (this->Hi - this->Lo <= this->Width)
      {
        this->Finish(0.5 * (this->Lo + this->Hi));
        return;
      }
      double next = this->S - v / slope;
      const bool newton = next > this->Lo && next < this->Hi;
      if (!newton)
      {
        next = 0.5 * (this->Lo + this->Hi);
      }
      const double step = std::fabs(next - this->S);
      this->S = next;
      if (step <= this->Width)
      {
        this->Finish(this->S);
        return;
      }
      // Converging quadratically (this step at most a quarter of the last): the error
      // after it is about C·step² with C ≈ step / last², so when step³ / last² is below
      // a sixteenth of the width the next evaluation would only confirm it.
      const double last = this->Last;
      if (newton && last > 0.0 && step <= 0.25 * last &&
        step * step * step <= this->Width * last * last / 16)
      {
        this->Finish(this->S);
        return;
      }
      this->Last = newton ? step : 0.0;
      if (++this->Iterations >= 60)
      {
        this->Finish(this->S);
      }
    }
    void Finish(double result)
    {
      this->Result = result;
      this->Done = true;
    }
    double Va, Small, Width;
    double Lo = 0.0, Hi = 1.0, S;
    double Last = 0.0; // the last Newton step (0: none, or a bisection)
    int Iterations = 0;
    bool Done = false;
    double Result = -1.0;
  };

  // Newton's loop for both: `evaluate(s, F, dF/ds)`, false where it cannot.
  template <typename Evaluate>
  static double NewtonOn(Evaluate&& evaluate, double t, double va, double small, double width)
  {
    NewtonLane lane(t, va, small, width);
    while (!lane.Done)
    {
      double v, slope;
      const bool ok = evaluate(lane.S, v, slope);
      lane.Step(ok, v, slope);
    }
    return lane.Result;
  }

  // The same for products whose F leaves the double range (thousands of factors, or F
  // beyond 1e200 at an end): Newton's method on F with the product kept as a logarithm
  // (the step (1 − r/P) / Σ f_i'/f_i needs only ln|P| and Σ f_i'/f_i), safeguarded by
  // bisection in the bracket the exact sign of F gives.
  // −1 when r = 0 (the roots are a factor's zeros: the caller's regula falsi).
  static double LogNewton(const pisurf::ProductKernel* kernel, const double* line, int axis,
    double x0, double dx, double t, double va, double width)
  {
    const double r = kernel->GetBlending();
    if (r == 0.0)
    {
      return -1.0;
    }
    const double logR = std::log(std::fabs(r));
    const int signR = r > 0 ? 1 : -1;
    double lo = 0.0, hi = 1.0, s = std::max(0.0, std::min(1.0, t));
    double last = 1.0, older = 1.0; // the last two steps
    for (int it = 0; it < 100; ++it)
    {
      double F, logP, slope;
      int signP;
      kernel->EvaluateOnAxisLog(line, axis, x0 + s * dx, F, signP, logP, slope);
      if (F == 0.0)
      {
        return s;
      }
      ((F < 0) == (va < 0) ? lo : hi) = s;
      if (hi - lo <= width)
      {
        return 0.5 * (lo + hi);
      }
      // F' = P·Σ f_i'/f_i, so the Newton step on F is (1 − r/P) / Σ f_i'/f_i, with r/P
      // from the logarithms (never overflows; inf only where P is far below r);
      // bisection where P = 0, where the step leaves the bracket, or where it is not
      // half the step before the last (Newton crawling down an exponential-like F).
      double next = 0.5 * (lo + hi);
      if (signP != 0 && std::isfinite(slope) && slope != 0.0)
      {
        const double ratio = (signP == signR ? 1.0 : -1.0) * std::exp(logR - logP);
        const double newton = s - (1.0 - ratio) / (slope * dx);
        if (newton > lo && newton < hi && std::fabs(newton - s) <= 0.5 * older)
        {
          next = newton;
        }
      }
      const double step = std::fabs(next - s);
      older = last;
      last = step;
      s = next;
      if (step <= width)
      {
        return s;
      }
    }
    return 0.5 * (lo + hi);
  }

  // `row`: for an x edge, its grid row's restriction from the sampling (RestrictLine's
  // coefficients, the edge starting at parameter rowT0), or null.
  double Refine(const double a[3], const double b[3], double t, double va, double vb,
    const double* row = nullptr, double rowT0 = 0.0) const
  {
    // A field that can certify the first root from the positive end in one pass (see
    // pisurf::Field::FirstRoot): the root nearest the outside, as the general method
    // below would pick.
    if (this->Kernel->Field)
    {
      const bool bracket = (va > 0 && vb < 0) || (va < 0 && vb > 0);
      const bool thinWall = va > 0 && vb > 0 && (t == 0.0 || t == 1.0);
      if (bracket || thinWall)
      {
        const bool fromA = bracket ? va > 0 : t == 0.0;
        double s;
        if (this->Kernel->Field->FirstRoot(fromA ? a : b, fromA ? b : a, this->Tolerance, s))
        {
          return fromA ? s : 1.0 - s;
        }
      }
    }
    // F itself is nearly linear along a short edge, and cheapest (its values at the ends
    // are the grid's); where it is beyond 1e200 at an end, its compressed form
    // sign(F)·ln(1 + |F|) is used instead.
    bool compressed = false;
    auto phi = [&](const double x[3]) {
      return compressed ? this->Kernel->EvaluateCompressed(x) : this->Kernel->Evaluate(x);
    };
    if (!(std::fabs(va) < 1e200 && std::fabs(vb) < 1e200))
    {
      compressed = true;
      va = phi(a);
      vb = phi(b);
    }
    auto pointAt = [&](double s, double x[3]) {
      for (int k = 0; k < 3; ++k)
      {
        x[k] = a[k] + s * (b[k] - a[k]);
      }
    };
    // A product of axis-aligned polynomial factors restricted to the edge's line once
    // (one pass over each factor's terms); each step is then Horner's rule on the
    // univariate polynomials instead of a trivariate evaluation.
    int axis = 0;
    while (axis < 2 && a[axis] == b[axis])
    {
      ++axis;
    }
    const pisurf::ProductKernel* kernel = this->Kernel->Field ? nullptr : this->Kernel->Kernel;
    const double length = std::fabs(b[0] - a[0]) + std::fabs(b[1] - a[1]) + std::fabs(b[2] - a[2]);
    if (row && kernel && !compressed && ((va < 0 && vb > 0) || (va > 0 && vb < 0)))
    {
      // An x edge: Newton's method on the row's restriction, already made for the
      // sampling (a product kernel has no outer-side test: its root is the answer).
      const double root = RowNewton(kernel, row, rowT0, t, va,
        1e-12 * std::max(std::fabs(va), std::fabs(vb)), this->Tolerance / length);
      if (root >= 0.0)
      {
        return root;
      }
    }
    // On the stack for the usual few factors (a thread_local costs a TLS lookup per
    // vertex in a shared library).
    constexpr size_t StackCoefficients = 256;
    double stackLine[StackCoefficients];
    double* line = stackLine;
    if (kernel && kernel->GetLineCoefficientCount() > StackCoefficients)
    {
      thread_local std::vector<double> heapLine;
      heapLine.resize(kernel->GetLineCoefficientCount());
      line = heapLine.data();
    }
    const bool restricted = kernel && kernel->RestrictToAxis(a, axis, line);
    const bool onAxis = restricted && !compressed;
    auto along = [&](double s) {
      if (onAxis)
      {
        return kernel->EvaluateOnAxis(line, axis, a[axis] + s * (b[axis] - a[axis]));
      }
      double x[3];
      pointAt(s, x);
      return phi(x);
    };
    auto offOuterSide = [&](double s) {
      double x[3];
      pointAt(s, x);
      return this->Kernel->OffOuterSide(x);
    };
    // The root between s0 and s1 (either order), where F is f0 and f1 of opposite signs.
    auto rootBetween = [&](double s0, double f0, double s1, double f1) {
      const double lo = std::min(s0, s1), hi = std::max(s0, s1);
      const double flo = s0 < s1 ? f0 : f1, fhi = s0 < s1 ? f1 : f0;
      return pisurf::BracketedRoot(along, lo, hi, flo, fhi, this->Tolerance / length,
        1e-12 * std::max(std::fabs(flo), std::fabs(fhi)));
    };
    // The first sign change stepping from the end `from` (0 or 1) towards the other:
    // the surface nearest that end; `from` itself if F keeps its sign at every step.
    auto firstCrossing = [&](double from) {
      constexpr int Steps = 16;
      double s0 = from, f0 = from == 0.0 ? va : vb;
      for (int m = 1; m <= Steps; ++m)
      {
        const double s1 = from == 0.0 ? double(m) / Steps : 1.0 - double(m) / Steps;
        const double f1 = m == Steps ? (from == 0.0 ? vb : va) : along(s1);
        if (f1 == 0.0)
        {
          return s1;
        }
        if ((f0 > 0) != (f1 > 0))
        {
          return rootBetween(s0, f0, s1, f1);
        }
        s0 = s1;
        f0 = f1;
      }
      return from;
    };
    // From the positive end `from` (on the outer side) to `to` (off it): where the edge
    // leaves the outer side, found by bisection; if F is negative just before it (the
    // thin wall), the root in between is on the outer sheet. -1 if not.
    auto outerCrossing = [&](double from, double to) {
      double out = from, off = to;
      for (int m = 0; m < 64 && std::fabs(off - out) * length > this->Tolerance; ++m)
      {
        const double mid = 0.5 * (out + off);
        (offOuterSide(mid) ? off : out) = mid;
      }
      const double fOut = along(out), fFrom = from == 0.0 ? va : vb;
      if (!(fFrom > 0))
      {
        return -1.0;
      }
      if (fOut < 0)
      {
        return rootBetween(from, fFrom, out, fOut);
      }
      // F huge (the surface hugs the wall): the root is within the tolerance after `out`.
      const double fOff = along(off);
      return fOff < 0 ? rootBetween(out, fOut, off, fOff) : out;
    };
    if ((va > 0 && vb > 0) || (va < 0 && vb < 0))
    {
      // Ends of one sign: the edge enters a thin wall the grid does not resolve (the
      // envelope gave the far end the other sign, see Contour's Write pass, and t is the end
      // whose sign is its own): the surface nearest to that end.
      if (t != 0.0 && t != 1.0)
      {
        return t;
      }
      const double crossing = firstCrossing(t);
      if (this->PositiveEnvelope && va > 0 && (crossing == t || offOuterSide(crossing)) &&
        offOuterSide(1.0 - t))
      {
        const double outer = outerCrossing(t, 1.0 - t);
        return outer >= 0 ? outer : crossing;
      }
      return crossing;
    }
    if (!(va < 0 && vb > 0) && !(va > 0 && vb < 0))
    {
      return t; // no strict bracket (an end exactly on F = 0): keep the interpolation
    }
    // |F| below 1e-12 of its values at the ends: the root is within ~1e-12 of an edge.
    const double small = 1e-12 * std::max(std::fabs(va), std::fabs(vb));
    double root = -1.0;
    if (onAxis)
    {
      root = this->Newton(kernel, line, axis, a[axis], b[axis] - a[axis], t, va, small,
        this->Tolerance / length);
    }
    if (root < 0.0 && restricted)
    {
      // (Where F is beyond 1e200 at an end, t leans on that end: start from the
      // interpolation of sign(F)·ln(1 + |F|) instead.)
      const double start = compressed && va != vb ? va / (va - vb) : t;
      root = LogNewton(
        kernel, line, axis, a[axis], b[axis] - a[axis], start, va, this->Tolerance / length);
    }
    if (root < 0.0)
    {
      root = pisurf::BracketedRoot(along, 0.0, 1.0, va, vb, this->Tolerance / length, small);
    }
    if (this->PositiveEnvelope && offOuterSide(root))
    {
      // A root of a bounded component's sheet (the edge runs outside, wall, lens, wall):
      // the outer sheet is the crossing nearest the positive end.
      const double from = va > 0 ? 0.0 : 1.0;
      const double crossing = firstCrossing(from);
      if (crossing != from && !offOuterSide(crossing))
      {
        return crossing;
      }
      const double outer = outerCrossing(from, root);
      return outer >= 0 ? outer : root;
    }
    return root;
  }

  // One vertex's edge: its ends a and b (from the edge key), the grid's values there and
  // the linear interpolation t.
  struct Edge
  {
    double A[3], B[3];
    int Axis, Index[3];
    double T, Va, Vb;
  };

  void Decode(vtkIdType id, bool narrow, Edge& e) const
  {
    const int* d = this->G->Dims;
    const vtkIdType key = (*this->VertexEdge)[id];
    if (narrow)
    {
      const std::uint32_t k32 = static_cast<std::uint32_t>(key);
      std::uint32_t p = k32 / 3;
      e.Axis = static_cast<int>(k32 - 3 * p);
      const std::uint32_t row = p / static_cast<std::uint32_t>(d[0]);
      e.Index[0] = static_cast<int>(p - row * static_cast<std::uint32_t>(d[0]));
      const std::uint32_t plane = row / static_cast<std::uint32_t>(d[1]);
      e.Index[1] = static_cast<int>(row - plane * static_cast<std::uint32_t>(d[1]));
      e.Index[2] = static_cast<int>(plane);
    }
    else
    {
      e.Axis = static_cast<int>(key % 3);
      const vtkIdType p = key / 3;
      e.Index[0] = static_cast<int>(p % d[0]);
      e.Index[1] = static_cast<int>((p / d[0]) % d[1]);
      e.Index[2] = static_cast<int>(p / (vtkIdType(d[0]) * d[1]));
    }
    for (int k = 0; k < 3; ++k)
    {
      e.A[k] = this->G->Origin[k] + e.Index[k] * this->G->Spacing[k];
      e.B[k] = e.A[k] + (k == e.Axis ? this->G->Spacing[k] : 0.0);
    }
    e.T = (*this->VertexT)[id];
    e.Va = (*this->VertexEnds)[2 * id];
    e.Vb = (*this->VertexEnds)[2 * id + 1];
  }

  // An x edge's row restriction from the sampling, or null (rowT0: the edge's start on it).
  const double* RowOf(const Edge& e, double& rowT0) const
  {
    rowT0 = 0.0;
    if (e.Axis != 0 || !this->RowIndex || !this->RowCoefficients || this->RowCoefficients->empty())
    {
      return nullptr;
    }
    const int* d = this->G->Dims;
    const vtkIdType r = (*this->RowIndex)[vtkIdType(e.Index[2]) * d[1] + e.Index[1]];
    if (r < 0)
    {
      return nullptr;
    }
    rowT0 = e.Index[0] - 0.5 * (d[0] - 1);
    return this->RowCoefficients->data() + r * this->RowCoefficientCount;
  }

  // Refine's usual case for a product kernel, set up to run beside other vertices': a
  // strict bracket of plain values, Newton's method on the factors evaluated at the
  // edge's points, four edges per vector instruction, where every factor is an
  // axis-aligned quadric or quartic in the squares (ProductKernel::HasStarFactorsOnly);
  // otherwise on the row's restriction (an x edge) or on the factors restricted to the
  // edge's line. Where Newton cannot decide (−1), Refine takes the vertex from the start
  // (the same steps, then its fallbacks).
  static constexpr int MaxLanes = pisurf::ProductKernel::MaxVertices;
  struct Lane
  {
    Edge E;
    const double* Row = nullptr;
    double RowT0 = 0.0;
    double Line[256]; // RestrictToAxis's coefficients, for the other edges
    double X0 = 0.0, Dx = 0.0;
    NewtonLane Newton{ 0.0, 0.0, 0.0, 0.0 };
    vtkIdType Id = 0;
  };

  // Sets `lane` up for the vertex whose edge is e; false where Refine's usual case does
  // not apply (the caller then takes the general path).
  bool Prepare(const Edge& e, Lane& lane) const
  {
    const pisurf::ProductKernel* kernel = this->Kernel->Kernel;
    const bool bracket = (e.Va < 0 && e.Vb > 0) || (e.Va > 0 && e.Vb < 0);
    if (!this->Project || this->Kernel->Field || !kernel || !bracket ||
      !(std::fabs(e.Va) < 1e200 && std::fabs(e.Vb) < 1e200))
    {
      return false;
    }
    const int axis = e.Axis;
    // (Star factors only: NewtonLanes evaluates them at the edge's points themselves.)
    const bool star = kernel->HasStarFactorsOnly();
    lane.Row = star ? nullptr : this->RowOf(e, lane.RowT0);
    if (!star && !lane.Row)
    {
      if (kernel->GetLineCoefficientCount() > sizeof(lane.Line) / sizeof(double) ||
        !kernel->RestrictToAxis(e.A, axis, lane.Line))
      {
        return false;
      }
    }
    lane.E = e;
    lane.X0 = e.A[axis];
    lane.Dx = e.B[axis] - e.A[axis];
    const double length =
      std::fabs(e.B[0] - e.A[0]) + std::fabs(e.B[1] - e.A[1]) + std::fabs(e.B[2] - e.A[2]);
    lane.Newton = NewtonLane(
      e.T, e.Va, 1e-12 * std::max(std::fabs(e.Va), std::fabs(e.Vb)), this->Tolerance / length);
    return true;
  }

  // F and dF/ds at the lane's s: RowNewton's and Newton's evaluations.
  bool EvaluateLane(const Lane& lane, double& v, double& slope) const
  {
    const pisurf::ProductKernel* kernel = this->Kernel->Kernel;
    const double s = lane.Newton.S;
    if (lane.Row)
    {
      return kernel->EvaluateRestrictedWithSlope(lane.Row, lane.RowT0 + s, v, slope);
    }
    const bool ok =
      kernel->EvaluateOnAxisWithSlope(lane.Line, lane.E.Axis, lane.X0 + s * lane.Dx, v, slope);
    slope *= lane.Dx;
    return ok;
  }

  // Newton's method on several lanes at once (each lane's own steps, interleaved): the
  // evaluations of all unfinished lanes, then their steps.
  void NewtonLanes(Lane* lanes, int count) const
  {
    // Star factors only: every lane at once, as vector lanes (ProductKernel::
    // EvaluateOnSegments), the finished ones too (their results unused).
    const pisurf::ProductKernel* kernel = this->Kernel->Kernel;
    const bool star = kernel->HasStarFactorsOnly();
    double a[MaxLanes][3], d[MaxLanes][3];
    for (int k = 0; star && k < count; ++k)
    {
      for (int c = 0; c < 3; ++c)
      {
        a[k][c] = lanes[k].E.A[c];
        d[k][c] = lanes[k].E.B[c] - lanes[k].E.A[c];
      }
    }
    for (;;)
    {
      double s[MaxLanes], v[MaxLanes], slope[MaxLanes];
      bool ok[MaxLanes];
      bool any = false;
      for (int k = 0; k < count; ++k)
      {
        s[k] = lanes[k].Newton.S;
        any = any || !lanes[k].Newton.Done;
      }
      if (!any)
      {
        return;
      }
      if (star)
      {
        kernel->EvaluateOnSegments(count, a, d, s, v, slope, ok);
      }
      else
      {
        for (int k = 0; k < count; ++k)
        {
          if (!lanes[k].Newton.Done)
          {
            ok[k] = this->EvaluateLane(lanes[k], v[k], slope[k]);
          }
        }
      }
      for (int k = 0; k < count; ++k)
      {
        if (!lanes[k].Newton.Done)
        {
          lanes[k].Newton.Step(ok[k], v[k], slope[k]);
        }
      }
    }
  }

  // Output arrays, for Write.
  struct Outputs
  {
    double* Xyz;
    float* Normals;
    int* Factors;
    double* Magnitudes; // may be null
  };

  // The vertex at x: the exact normal, |∇F| and the nearest factor there, written out.
  void Finish(vtkIdType id, const double x[3], const Outputs& out) const
  {
    double n[3], gradientNorm;
    int nearest;
    this->Kernel->EvaluateVertex(x, n, gradientNorm, nearest);
    this->Write(id, x, n, gradientNorm, nearest, out);
  }

  static void Write(vtkIdType id, const double x[3], const double n[3], double gradientNorm,
    int nearest, const Outputs& out)
  {
    for (int k = 0; k < 3; ++k)
    {
      out.Xyz[3 * id + k] = x[k];
      out.Normals[3 * id + k] = static_cast<float>(n[k]);
    }
    out.Factors[id] = nearest;
    if (out.Magnitudes)
    {
      out.Magnitudes[id] = gradientNorm;
    }
  }

  // Every other vertex: a field's one-pass edge (RefineEdge), or Refine's general path.
  void General(vtkIdType id, const Edge& e, const Outputs& out) const
  {
    const double va = e.Va, vb = e.Vb;
    double t = e.T;
    // The field restricted to the edge, in one call: Refine's root of a strict bracket,
    // or the crossing nearest the end t where the ends have one sign (a thin wall),
    // and EvaluateVertex's answers there. A root off the outer side takes the general
    // path below, which looks for the outer sheet.
    const bool bracket = (va < 0 && vb > 0) || (va > 0 && vb < 0);
    const bool thinWall = ((va > 0 && vb > 0) || (va < 0 && vb < 0)) && (t == 0.0 || t == 1.0);
    pisurf::Field::EdgeVertex fast;
    double x[3];
    if (this->Project && this->Kernel->Field && (bracket || thinWall) &&
      std::fabs(va) < 1e200 && std::fabs(vb) < 1e200 &&
      this->Kernel->Field->RefineEdge(
        e.A, e.B, va, vb, bracket ? -1 : static_cast<int>(t), this->Tolerance, fast) &&
      !(this->PositiveEnvelope && fast.OffOuterSide))
    {
      for (int k = 0; k < 3; ++k)
      {
        x[k] = e.A[k] + fast.S * (e.B[k] - e.A[k]);
      }
      this->Write(id, x, fast.Normal, fast.GradientNorm, fast.Nearest, out);
      return;
    }
    if (this->Project)
    {
      double rowT0;
      const double* row = this->RowOf(e, rowT0);
      t = this->Refine(e.A, e.B, t, va, vb, row, rowT0);
    }
    for (int k = 0; k < 3; ++k)
    {
      x[k] = e.A[k] + t * (e.B[k] - e.A[k]);
    }
    this->Finish(id, x, out);
  }

  // The lanes' vertices once their Newton has finished: each root (Refine's general path
  // where Newton could not decide), then the attributes there, all lanes at once.
  void FinishLanes(const Lane* lanes, int count, const Outputs& out) const
  {
    double x[MaxLanes][3], n[MaxLanes][3], gradientNorm[MaxLanes];
    int nearest[MaxLanes];
    for (int j = 0; j < count; ++j)
    {
      const Edge& e = lanes[j].E;
      double t = lanes[j].Newton.Result;
      if (t < 0.0)
      {
        double rowT0;
        const double* row = this->RowOf(e, rowT0);
        t = this->Refine(e.A, e.B, e.T, e.Va, e.Vb, row, rowT0);
      }
      for (int k = 0; k < 3; ++k)
      {
        x[j][k] = e.A[k] + t * (e.B[k] - e.A[k]);
      }
    }
    // (Lanes exist only for a product kernel.)
    this->Kernel->Kernel->EvaluateVertices(count, x, n, gradientNorm, nearest);
    for (int j = 0; j < count; ++j)
    {
      this->Write(lanes[j].Id, x[j], n[j], gradientNorm[j], nearest[j], out);
    }
  }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    if (PiSingleThread())
    {
      if (this->Algorithm->CheckAbort())
      {
        *this->Abort = true;
      }
      else
      {
        this->Algorithm->UpdateProgress(
          0.75 + 0.25 * (static_cast<double>(*this->Done) / std::max<vtkIdType>(this->Total, 1)));
      }
    }
    if (*this->Abort)
    {
      return;
    }
    *this->Done += end - begin;
    const int* d = this->G->Dims;
    // Edge keys of grids below 2^32 keys decode with 32-bit divisions (several times
    // faster than 64-bit ones on common CPUs).
    const bool narrow = 3.0 * d[0] * d[1] * d[2] < 4294967296.0;
    const Outputs out{ vtkDoubleArray::FastDownCast(this->Points->GetData())->GetPointer(0),
      this->Normals->GetPointer(0), this->Factor->GetPointer(0),
      this->GradientMagnitude ? this->GradientMagnitude->GetPointer(0) : nullptr };
    // Vertices MaxLanes at a time where they take Refine's usual case (their Newton
    // chains side by side); any other vertex takes the general path at once.
    Lane lanes[MaxLanes];
    int ready = 0;
    for (vtkIdType id = begin; id < end; ++id)
    {
      Edge e;
      this->Decode(id, narrow, e);
      if (!this->Prepare(e, lanes[ready]))
      {
        this->General(id, e, out);
        continue;
      }
      lanes[ready].Id = id;
      if (++ready == MaxLanes || id + 1 == end)
      {
        this->NewtonLanes(lanes, ready);
        this->FinishLanes(lanes, ready, out);
        ready = 0;
      }
    }
    if (ready > 0)
    {
      this->NewtonLanes(lanes, ready);
      this->FinishLanes(lanes, ready, out);
    }
  }
};
}

int vtkPiFlyingEdges::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Pieces are slabs of blocks along z (see RequestData).
  for (int port = 0; port < this->GetNumberOfOutputPorts(); ++port)
  {
    outputVector->GetInformationObject(port)->Set(
      vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  }
  return 1;
}

bool vtkPiFlyingEdges::ComputeGrid(const double b[6], int dims[3], double spacing[3])
{
  return this->ComputeGrid(b, this->Resolution, dims, spacing);
}

bool vtkPiFlyingEdges::ComputeGrid(
  const double b[6], int resolution, int dims[3], double spacing[3])
{
  const double side[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
  const int* sd = this->SampleDimensions;
  // Points per axis as doubles: checked against the cap before any cast to int.
  double points[3];
  if (sd[0] != 0 || sd[1] != 0 || sd[2] != 0)
  {
    if (sd[0] < 2 || sd[1] < 2 || sd[2] < 2)
    {
      vtkErrorMacro(<< "SampleDimensions must be at least 2 points per axis (got " << sd[0]
                    << ", " << sd[1] << ", " << sd[2] << "); set all to 0 to use Resolution");
      return false;
    }
    std::copy(sd, sd + 3, points);
  }
  else
  {
    if (resolution < 1)
    {
      vtkErrorMacro(<< "Resolution must be at least 1 (got " << resolution << ")");
      return false;
    }
    const double h = std::max({ side[0], side[1], side[2] }) / resolution;
    for (int a = 0; a < 3; ++a)
    {
      points[a] = std::max(1.0, std::ceil(side[a] / h - 1e-9)) + 1;
    }
  }
  const double samples = points[0] * points[1] * points[2];
  if (!(samples <= static_cast<double>(this->MaximumNumberOfSamples)) ||
    std::max({ points[0], points[1], points[2] }) > VTK_INT_MAX)
  {
    vtkErrorMacro(<< "A grid of " << points[0] << " x " << points[1] << " x " << points[2]
                  << " = " << samples << " samples needs up to "
                  << samples * sizeof(double) / (1 << 20) << " MiB; the limit is "
                  << this->MaximumNumberOfSamples * sizeof(double) / (1 << 20)
                  << " MiB (MaximumNumberOfSamples = " << this->MaximumNumberOfSamples
                  << " samples)");
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = static_cast<int>(points[a]);
  }
  for (int a = 0; a < 3; ++a)
  {
    spacing[a] = side[a] / (dims[a] - 1);
  }
  return true;
}

int vtkPiFlyingEdges::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  try
  {
    return this->GenerateMesh(outputVector);
  }
  catch (const std::bad_alloc&)
  {
    // The sizes are checked against MaximumNumberOfSamples first; this is a machine
    // with less memory than that cap assumes.
    vtkPolyData::GetData(outputVector, 0)->Initialize();
    vtkErrorMacro(<< "Out of memory while meshing: lower the Resolution or "
                     "MaximumNumberOfSamples");
    return 0;
  }
}

int vtkPiFlyingEdges::GenerateMesh(vtkInformationVector* outputVector)
{
  // PISURF_TIMING=1: the wall time of each pass on stderr.
  PiPassTimer lap("vtkPiFlyingEdges");
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* primitives = vtkPolyData::GetData(outputVector, 1);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const PiPiece request = PiPieceOf(outInfo);
  const int piece = request.Piece, pieces = request.Pieces;
  const std::shared_ptr<const pisurf::Field> field = this->Internals->Field;
  std::shared_ptr<const pisurf::ProductKernel> kernel;
  double bounds[6];
  if (field)
  {
    std::copy(this->Bounds, this->Bounds + 6, bounds);
    if (!(bounds[0] < bounds[1] && bounds[2] < bounds[3] && bounds[4] < bounds[5]))
    {
      vtkErrorMacro(<< "A field is meshed in explicit Bounds: set them");
      return 0;
    }
  }
  else
  {
    if (!this->PiSurface)
    {
      vtkErrorMacro(<< "No Pi-surface to mesh: call SetPiSurface()");
      return 0;
    }
    kernel = this->PiSurface->GetKernel();
    if (!kernel || kernel->GetNumberOfFactors() == 0)
    {
      vtkErrorMacro(<< "The Pi-surface is invalid or has no factors"
                    << (*this->PiSurface->GetErrorMessage() ? ": " : "")
                    << this->PiSurface->GetErrorMessage());
      return 0;
    }
    if (!this->PiSurface->ResolveBounds(this->Bounds, bounds))
    {
      vtkErrorMacro(<< "No bounds to mesh in: " << this->PiSurface->GetErrorMessage());
      return 0;
    }
  }
  const Evaluator evaluator{ kernel.get(), field.get() };

  int resolution = this->Resolution;
  const bool explicitDimensions = this->SampleDimensions[0] != 0 ||
    this->SampleDimensions[1] != 0 || this->SampleDimensions[2] != 0;
  if (this->AutomaticResolution && !explicitDimensions && !field)
  {
    resolution = this->ChooseResolution(bounds);
    if (resolution <= 0)
    {
      return 0;
    }
  }
  this->LastResolution = resolution;
  Grid g;
  if (!this->ComputeGrid(bounds, resolution, g.Dims, g.Spacing))
  {
    return 0;
  }
  for (int a = 0; a < 3; ++a)
  {
    g.Origin[a] = bounds[2 * a];
    // (dims − 1) / B + 1 blocks: the last point plane always lies in the last block at a
    // local index below BlockCells (that block may be a single plane without cells).
    g.Count[a] = (g.Dims[a] - 1) / BlockCells + 1;
  }
  // This piece's slab of block layers along z (all of them for one piece).
  const int slabBegin = static_cast<int>(vtkIdType(g.Count[2]) * piece / pieces);
  const int slabEnd = static_cast<int>(vtkIdType(g.Count[2]) * (piece + 1) / pieces);
  // A piece of several works on its slab: it classifies and samples only the block
  // layers [slabBegin, slabEnd] (the layer above the slab numbers the vertices on the
  // plane they share) and, with OuterEnvelope, classifies the layer below too (its
  // skipped blocks decide the shared plane's points, as in a serial run); the outer
  // envelope is then flooded slab by slab with the other pieces (FloodAcrossPieces),
  // which needs piece p of n on process p of the global controller's n (ParaView's MPI
  // mode). Otherwise (several pieces in one process, with OuterEnvelope) every piece
  // classifies and samples the whole grid, as the envelope is a global property.
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const bool distributed = pieces > 1 && this->OuterEnvelope && controller &&
    controller->GetNumberOfProcesses() == pieces && controller->GetLocalProcessId() == piece;
  const bool slabOnly = pieces > 1 && (!this->OuterEnvelope || distributed);
  const int classifyBegin =
    slabOnly ? std::max(0, slabBegin - (this->OuterEnvelope ? 1 : 0)) : 0;
  const int classifyEnd = slabOnly ? std::min(g.Count[2], slabEnd + 1) : g.Count[2];
  const int sampleBegin = slabOnly ? slabBegin : 0;

  // PASS 1: classify the blocks, coarse to fine: groups of 4³ blocks first, then the
  // 2³-block quarters of the undecided groups, then the blocks the surface may cross
  // (value 2 marks "still to classify").
  g.Sign.assign(vtkIdType(g.Count[0]) * g.Count[1] * g.Count[2], 0);
  {
    const int group = 4;
    int groups[3];
    for (int a = 0; a < 3; ++a)
    {
      groups[a] = (g.Count[a] + group - 1) / group;
    }
    const vtkIdType groupCount = vtkIdType(groups[0]) * groups[1] * groups[2];
    // The blocks [lo, hi) take `sign`.
    auto setSigns = [&g](const int lo[3], const int hi[3], int sign) {
      for (int z = lo[2]; z < hi[2]; ++z)
        for (int y = lo[1]; y < hi[1]; ++y)
          for (int x = lo[0]; x < hi[0]; ++x)
          {
            g.Sign[g.BlockId(x, y, z)] = static_cast<signed char>(sign);
          }
    };
    // Whether `inner` lies within octant o of `outer` (as OctantBox cuts it).
    auto insideOctant = [](const double inner[6], const double outer[6], int o) {
      double octant[6];
      pisurf::OctantBox(outer, o, octant);
      for (int a = 0; a < 3; ++a)
      {
        if (!(inner[2 * a] >= octant[2 * a] && inner[2 * a + 1] <= octant[2 * a + 1]))
        {
          return false;
        }
      }
      return true;
    };
    PiFor(0, groupCount, 1, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType q = begin; q < end; ++q)
      {
        const int c[3] = { int(q % groups[0]), int((q / groups[0]) % groups[1]),
          int(q / (vtkIdType(groups[0]) * groups[1])) };
        if (c[2] * group >= classifyEnd || c[2] * group + group <= classifyBegin)
        {
          continue; // no layer of this piece's (marked absent below)
        }
        int lo[3], hi[3];
        double box[6];
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = c[a] * group;
          hi[a] = std::min(lo[a] + group, g.Count[a]); // blocks [lo, hi)
          box[2 * a] = g.Origin[a] + lo[a] * BlockCells * g.Spacing[a];
          box[2 * a + 1] =
            g.Origin[a] + std::min(hi[a] * BlockCells, g.Dims[a] - 1) * g.Spacing[a];
        }
        // (A product of polynomials classifies the group's eight octants from the same
        // expansions; an octant that holds exactly a sub-group below decides it.)
        const bool octantsToo =
          evaluator.Kernel && !evaluator.Field && evaluator.Kernel->IsPolynomial();
        int groupOctants[8];
        const int sign = octantsToo
          ? evaluator.Kernel->ClassifyBoxAndOctants(box, groupOctants, true)
          : evaluator.ClassifyBox(box);
        setSigns(lo, hi, sign == 0 ? 2 : sign);
        if (sign != 0)
        {
          continue;
        }
        // An undecided group: its eight sub-groups of 2³ blocks, whose tighter
        // enclosures decide many more blocks at once.
        for (int o = 0; o < 8; ++o)
        {
          int sublo[3], subhi[3];
          double sub[6];
          for (int a = 0; a < 3; ++a)
          {
            sublo[a] = lo[a] + ((o >> a) & 1) * (group / 2);
            subhi[a] = std::min(sublo[a] + group / 2, hi[a]);
            sub[2 * a] = g.Origin[a] + sublo[a] * BlockCells * g.Spacing[a];
            sub[2 * a + 1] =
              g.Origin[a] + std::min(subhi[a] * BlockCells, g.Dims[a] - 1) * g.Spacing[a];
          }
          if (sublo[0] >= subhi[0] || sublo[1] >= subhi[1] || sublo[2] >= subhi[2])
          {
            continue;
          }
          if (octantsToo && groupOctants[o] != 0 && insideOctant(sub, box, o))
          {
            setSigns(sublo, subhi, groupOctants[o]);
            continue;
          }
          int subOctants[8];
          const int subSign = octantsToo
            ? evaluator.Kernel->ClassifyBoxAndOctants(sub, subOctants, true)
            : evaluator.ClassifyBox(sub);
          if (subSign != 0)
          {
            setSigns(sublo, subhi, subSign);
            continue;
          }
          // (Likewise the sub-group's octants: an octant that holds exactly one block
          // decides that block, which then skips its own classification below.)
          for (int so = 0; octantsToo && so < 8; ++so)
          {
            int bc[3];
            for (int a = 0; a < 3; ++a)
            {
              bc[a] = sublo[a] + ((so >> a) & 1);
            }
            if (subOctants[so] == 0 || bc[0] >= subhi[0] || bc[1] >= subhi[1] ||
              bc[2] >= subhi[2])
            {
              continue;
            }
            // The block's box as ClassifyBlocks forms it.
            double block[6];
            for (int a = 0; a < 3; ++a)
            {
              block[2 * a] = g.Origin[a] + g.First(bc, a) * g.Spacing[a];
              block[2 * a + 1] = g.Origin[a] + g.Last(bc, a) * g.Spacing[a];
            }
            if (insideOctant(block, sub, so))
            {
              g.Sign[g.BlockId(bc[0], bc[1], bc[2])] = static_cast<signed char>(subOctants[so]);
            }
          }
        }
      }
    });
  }
  if (slabOnly)
  {
    const size_t layer = size_t(g.Count[0]) * g.Count[1];
    std::fill(g.Sign.begin(), g.Sign.begin() + layer * classifyBegin, AbsentBlock);
    std::fill(g.Sign.begin() + layer * classifyEnd, g.Sign.end(), AbsentBlock);
  }
  std::vector<vtkIdType> undecided;
  for (size_t b = 0; b < g.Sign.size(); ++b)
  {
    if (g.Sign[b] == 2)
    {
      undecided.push_back(static_cast<vtkIdType>(b));
    }
  }
  ClassifyBlocks classify{ &evaluator, &g, &undecided };
  std::unique_ptr<std::atomic<signed char>[]> corners;
  // (Not for a field: a molecule's point evaluation costs more than the enclosures of
  // a block it would spare, 16 × 1ubq classified in 39 ms with it and 36 ms without.)
  if (evaluator.Kernel && !evaluator.Field)
  {
    const size_t lattice = size_t(g.Count[0] + 1) * (g.Count[1] + 1) * (g.Count[2] + 1);
    corners.reset(new std::atomic<signed char>[lattice]);
    for (size_t k = 0; k < lattice; ++k)
    {
      corners[k].store(ClassifyBlocks::Unknown, std::memory_order_relaxed);
    }
    classify.Corners = corners.get();
  }
  PiFor(0, static_cast<vtkIdType>(undecided.size()), 16, classify);
  g.Slot.assign(g.Sign.size(), -1);
  // (The layer below the slab is classified, not sampled: its blocks are never active.)
  const size_t firstSampled = size_t(g.Count[0]) * g.Count[1] * sampleBegin;
  for (size_t b = firstSampled; b < g.Sign.size(); ++b)
  {
    if (g.Sign[b] == 0)
    {
      g.Slot[b] = static_cast<int>(g.Active.size());
      g.Active.push_back(static_cast<int>(b));
    }
  }
  this->UpdateProgress(0.1);
  lap("classify");
  if (lap.IsEnabled())
  {
    std::cerr << g.Active.size() << " of " << g.Sign.size() << " blocks active ("
              << undecided.size() << " left undecided by their groups)\n";
  }

  // PASS 2: restrict the factors to the rows the active blocks need.
  pisurf::LargeVector<vtkIdType>& rowIndex = this->Internals->RowIndex;
  std::vector<vtkIdType>& rows = this->Internals->Rows;
  rowIndex.assign(vtkIdType(g.Dims[1]) * g.Dims[2], -1);
  rows.clear();
  // (Active is in block order: the blocks of one column along x are consecutive and
  // need the same rows, so each column is visited once.)
  int lastColumn = -1;
  for (int b : g.Active)
  {
    const int column = b / g.Count[0];
    if (column == lastColumn)
    {
      continue;
    }
    lastColumn = column;
    int c[3];
    g.BlockCoordinates(b, c);
    for (int k = g.First(c, 2); k <= g.Last(c, 2); ++k)
      for (int j = g.First(c, 1); j <= g.Last(c, 1); ++j)
      {
        vtkIdType& r = rowIndex[vtkIdType(k) * g.Dims[1] + j];
        if (r < 0)
        {
          r = static_cast<vtkIdType>(rows.size());
          rows.push_back(vtkIdType(k) * g.Dims[1] + j);
        }
      }
  }
  // The polynomial factors keep their row restrictions between executions (see
  // FactorCache): only new factors and new rows are restricted.
  std::vector<FactorCache*> caches =
    PrepareFactorCaches(this->Internals->CacheGrid, this->Internals->Factors, kernel.get(), g);
  // (Every entry is written below: resized, not cleared.)
  pisurf::LargeVector<double>& coefficients = this->Internals->Coefficients;
  if (!kernel)
  {
    coefficients.clear();
  }
  bool tooManyRows = false;
  if (kernel)
  {
    // Every polynomial factor restricted to every row: with many factors this, not the
    // grid, is the largest array. It shares the grid's cap.
    const double count = double(rows.size()) * kernel->GetLineCoefficientCount();
    tooManyRows = count > static_cast<double>(this->MaximumNumberOfSamples);
    if (tooManyRows)
    {
      vtkErrorMacro(<< "The " << kernel->GetNumberOfFactors() << " factors restricted to the "
                    << rows.size() << " grid rows the surface may cross need "
                    << count * sizeof(double) / (1 << 20) << " MiB; the limit is "
                    << this->MaximumNumberOfSamples * sizeof(double) / (1 << 20)
                    << " MiB (MaximumNumberOfSamples doubles): lower the Resolution or the "
                       "number of primitives");
      if (!distributed)
      {
        return 0;
      }
    }
    else
    {
      coefficients.resize(rows.size() * kernel->GetLineCoefficientCount());
    }
  }
  // (A distributed piece over the cap skips its restriction and sampling, then tells the
  // other pieces below.)
  if (!tooManyRows && kernel)
  {
    if (caches.empty())
    {
      RestrictRows restrict{ kernel.get(), &g, &rows, &coefficients };
      PiFor(0, static_cast<vtkIdType>(rows.size()), 256, restrict);
    }
    else
    {
      RestrictCachedRows restrict{ &g, &rows, &caches, kernel.get(), &coefficients };
      PiFor(0, static_cast<vtkIdType>(rows.size()), 256, restrict);
    }
  }
  lap("restrict rows");

  // PASS 3: evaluate the points of the active blocks.
  std::atomic<bool> abort{ false };
  if (!tooManyRows)
  {
    // Every entry is written below: no need to clear.
    const size_t valueCount = g.Active.size() * BlockPoints * BlockPoints * BlockPoints;
    if (this->Internals->Values.GetSize() < valueCount)
    {
      this->Internals->Values.Allocate(valueCount);
    }
    g.Values = this->Internals->Values.GetPointer();
    if (kernel && kernel->IsPolynomial())
    {
      SampleRows sample{ kernel.get(), &g, &rows, &coefficients, this, &abort, {} };
      sample.Prepare();
      PiFor(0, static_cast<vtkIdType>(rows.size()), 64, sample);
    }
    else
    {
      SampleBlocks sample{ kernel.get(), field.get(), &g, &rowIndex, &coefficients, this,
        &abort };
      PiFor(0, static_cast<vtkIdType>(g.Active.size()), 4, sample);
    }
  }
  {
    // 0: go on, 1: cancelled, 2: failed. With the pieces flooding together every
    // process must reach the flood, or none: a piece that stops here (an error of its
    // own, a cancel) tells the others, and all stop.
    int stop = tooManyRows ? 2 : (abort || this->CheckAbort()) ? 1 : 0;
    if (distributed)
    {
      const int mine = stop;
      controller->AllReduce(&mine, &stop, 1, vtkCommunicator::MAX_OP);
      if (stop == 2 && mine != 2)
      {
        vtkErrorMacro(<< "Another piece of the mesh failed (see its error): piece " << piece
                      << " of " << pieces << " stops too");
      }
    }
    if (stop != 0)
    {
      return stop == 2 ? 0 : 1;
    }
  }
  this->UpdateProgress(0.5);
  lap("sample");

  // PASS 4: the outer envelope (sign connectivity from the boundary).
  std::unique_ptr<Envelope> envelope;
  if (this->OuterEnvelope)
  {
    // The outside sign: the sign of F on most of the boundary of the grid.
    vtkIdType positive = 0, total = 0;
    const int* d = g.Dims;
    for (int a = 0; a < 3; ++a)
    {
      const int u = (a + 1) % 3, w = (a + 2) % 3;
      for (int side = 0; side < 2; ++side)
        for (int p = 0; p < d[u]; p += std::max(1, d[u] / 32))
          for (int q = 0; q < d[w]; q += std::max(1, d[w] / 32))
          {
            int idx[3];
            idx[a] = side ? d[a] - 1 : 0;
            idx[u] = p;
            idx[w] = q;
            // (A piece of several counts the points of its own slab; the pieces add up.)
            const int layer = std::min(idx[2] / BlockCells, g.Count[2] - 1);
            if (slabOnly && (layer < slabBegin || layer >= slabEnd))
            {
              continue;
            }
            const vtkIdType b = g.SkippedBlockOf(idx[0], idx[1], idx[2]);
            const double v = b >= 0 ? g.Sign[b] : g.ActiveValue(idx[0], idx[1], idx[2]);
            positive += v >= 0;
            ++total;
          }
    }
    if (distributed)
    {
      const vtkIdType mine[2] = { positive, total };
      vtkIdType sum[2] = { 0, 0 };
      controller->AllReduce(mine, sum, 2, vtkCommunicator::SUM_OP);
      positive = sum[0];
      total = sum[1];
    }
    envelope.reset(
      new Envelope(g, 2 * positive >= total ? 1 : -1, field.get(), this->Internals->EnvelopeFree,
        this->Internals->EnvelopeReached));
    lap("envelope states");
    if (distributed)
    {
      envelope->SetFloodLayers(slabBegin, slabEnd);
    }
    envelope->Flood();
    if (distributed)
    {
      const int rounds = envelope->FloodAcrossPieces(controller, piece, pieces);
      if (lap.IsEnabled())
      {
        std::cerr << "piece " << piece << " of " << pieces << ": block layers " << slabBegin
                  << " to " << slabEnd - 1 << " of " << g.Count[2]
                  << ", the envelope flooded with the other pieces in " << rounds
                  << " rounds\n";
      }
      if (slabBegin < slabEnd && slabEnd < g.Count[2])
      {
        envelope->CopyTopPlaneTo(slabEnd);
      }
    }
  }
  if (this->CheckAbort())
  {
    return 1;
  }
  this->UpdateProgress(0.6);
  lap("envelope");

  // PASS 5: count the crossing edges and triangles per active block; PASS 6: number and
  // write them.
  const vtkIdType activeCount = static_cast<vtkIdType>(g.Active.size());
  std::vector<vtkIdType> vertexCount(activeCount + 1, 0), triangleCount(activeCount + 1, 0);
  // (not initialized on allocation: the Write pass writes every entry)
  pisurf::Buffer<vtkIdType>& vertexEdge = this->Internals->VertexEdge;
  pisurf::Buffer<double>& vertexT = this->Internals->VertexT;
  pisurf::Buffer<double>& vertexEnds = this->Internals->VertexEnds;
  // Triangles per marching-cubes case.
  std::uint8_t trianglesOfCase[256];
  for (int index = 0; index < 256; ++index)
  {
    int count = 0;
    for (const int* e = vtkMarchingCubesTriangleCases::GetCases()[index].edges; *e >= 0; e += 3)
    {
      ++count;
    }
    trianglesOfCase[index] = static_cast<std::uint8_t>(count);
  }
  Contour contour{ &g, envelope.get(), vtkMarchingCubesTriangleCases::GetCases(), &vertexCount,
    &triangleCount, &vertexEdge, &vertexT, &vertexEnds, nullptr, nullptr, Contour::Count, slabBegin,
    slabEnd, nullptr, nullptr, nullptr, trianglesOfCase };
  pisurf::Buffer<std::uint16_t>& rowSigns = this->Internals->RowSigns;
  pisurf::Buffer<std::uint16_t>& edgeOffsets = this->Internals->EdgeOffsets;
  pisurf::Buffer<std::uint8_t>& edgeMasks = this->Internals->EdgeMasks;
  rowSigns.Reserve(size_t(activeCount) * Contour::Rows);
  edgeMasks.Reserve(size_t(activeCount) * Contour::EdgeRows);
  edgeOffsets.Reserve(size_t(activeCount) * Contour::EdgeRows);
  contour.RowSigns = rowSigns.GetPointer();
  contour.EdgeMasks = edgeMasks.GetPointer();
  contour.EdgeOffsets = edgeOffsets.GetPointer();
  PiFor(0, activeCount, 8, contour);
  vtkIdType vertices = 0, triangles = 0;
  if (lap.IsEnabled())
  {
    // How many active blocks the enclosures could not rule out but hold no surface.
    vtkIdType crossed = 0;
    for (vtkIdType s = 0; s < activeCount; ++s)
    {
      crossed += vertexCount[s] > 0 || triangleCount[s] > 0;
    }
    std::cerr << crossed << " of " << activeCount << " active blocks hold the surface\n";
  }
  for (vtkIdType s = 0; s < activeCount; ++s)
  {
    int c[3];
    g.BlockCoordinates(g.Active[s], c);
    const vtkIdType nv = vertexCount[s];
    const vtkIdType nt = c[2] >= slabBegin && c[2] < slabEnd ? triangleCount[s] : 0;
    vertexCount[s] = vertices;
    triangleCount[s] = triangles;
    vertices += nv;
    triangles += nt;
  }
  vertexCount[activeCount] = vertices;
  triangleCount[activeCount] = triangles;
  vertexEdge.Reserve(vertices);
  vertexT.Reserve(vertices);
  vertexEnds.Reserve(2 * vertices);
  // The cells in vtkCellArray's 32-bit storage when the ids fit (half the memory).
  const bool narrow = PiFitsInt32Cells(triangles, vertices);
  vtkNew<vtkIdTypeArray> connectivity;
  vtkNew<vtkTypeInt32Array> connectivity32;
  if (narrow)
  {
    PiAllocateLarge(connectivity32.GetPointer(), 3 * triangles);
    contour.TriangleIds32 = connectivity32->GetPointer(0);
  }
  else
  {
    PiAllocateLarge(connectivity.GetPointer(), 3 * triangles);
    contour.TriangleIds = connectivity->GetPointer(0);
  }
  // The vertices' edges and the triangles (which look up neighbours' Count tables).
  contour.Pass = Contour::Write;
  PiFor(0, activeCount, 8, contour);
  if (pieces > 1)
  {
    // Keep only the vertices this piece's triangles use (the seams' vertices are shared
    // with the neighbouring piece, at identical positions).
    std::vector<vtkIdType> renumber(vertices, -1);
    auto id = [&](vtkIdType t) -> vtkIdType {
      return narrow ? connectivity32->GetPointer(0)[t] : connectivity->GetPointer(0)[t];
    };
    for (vtkIdType t = 0; t < 3 * triangles; ++t)
    {
      renumber[id(t)] = 0;
    }
    vtkIdType used = 0;
    for (vtkIdType v = 0; v < vertices; ++v)
    {
      if (renumber[v] == 0)
      {
        vertexEdge[used] = vertexEdge[v];
        vertexT[used] = vertexT[v];
        vertexEnds[2 * used] = vertexEnds[2 * v];
        vertexEnds[2 * used + 1] = vertexEnds[2 * v + 1];
        renumber[v] = used++;
      }
    }
    for (vtkIdType t = 0; t < 3 * triangles; ++t)
    {
      if (narrow)
      {
        connectivity32->SetValue(t, static_cast<std::int32_t>(renumber[id(t)]));
      }
      else
      {
        connectivity->SetValue(t, renumber[id(t)]);
      }
    }
    vertices = used;
  }
  this->UpdateProgress(0.75);
  lap("contour");
  if (this->CheckAbort())
  {
    return 1;
  }

  // PASS 7: vertices.
  vtkNew<vtkPoints> points;
  PiAllocateLargePoints(points, vertices);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  PiAllocateLarge(normals.GetPointer(), vertices);
  vtkNew<vtkIntArray> factor;
  factor->SetName("Factor");
  PiAllocateLarge(factor.GetPointer(), vertices);
  vtkSmartPointer<vtkDoubleArray> gradientMagnitude;
  if (this->ComputeGradientMagnitude)
  {
    gradientMagnitude = vtkSmartPointer<vtkDoubleArray>::New();
    gradientMagnitude->SetName("GradientMagnitude");
    PiAllocateLarge(gradientMagnitude.GetPointer(), vertices);
  }
  const double size = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  std::atomic<vtkIdType> done{ 0 };
  VertexAttributes attributes{ &evaluator, &g, &vertexEdge, &vertexT, &vertexEnds, points,
    normals, factor, gradientMagnitude, this->ProjectVertices, 1e-13 * size,
    envelope && envelope->GetOutside() > 0, this, &abort, &done, vertices,
    kernel ? &rowIndex : nullptr, kernel ? &coefficients : nullptr,
    kernel ? kernel->GetLineCoefficientCount() : 0 };
  // Chunks of 4096 vertices: the main thread reports and checks for a cancel between them.
  PiFor(0, vertices, 4096, attributes);
  this->Internals->ReleaseLargeWork();
  if (abort || this->CheckAbort())
  {
    return 1;
  }
  lap("vertices");

  // Triangles face ∇F, like the Normals, so renderers light the side they see (the
  // Triangles pass wound them so). The offsets are written here: vtkCellArray takes both
  // arrays as they are (SetData with a cell size would copy the connectivity and fill the
  // offsets on one thread).
  vtkNew<vtkCellArray> polys;
  auto fillOffsets = [triangles](auto* offset) {
    using Id = typename std::remove_pointer<decltype(offset)>::type;
    PiFor(0, triangles + 1, 0, [offset](vtkIdType begin, vtkIdType end) {
      for (vtkIdType t = begin; t < end; ++t)
      {
        offset[t] = static_cast<Id>(3 * t);
      }
    });
  };
  if (narrow)
  {
    vtkNew<vtkTypeInt32Array> offsets;
    PiAllocateLarge(offsets.GetPointer(), triangles + 1);
    fillOffsets(offsets->GetPointer(0));
    polys->SetData(offsets, connectivity32);
  }
  else
  {
    vtkNew<vtkIdTypeArray> offsets;
    PiAllocateLarge(offsets.GetPointer(), triangles + 1);
    fillOffsets(offsets->GetPointer(0));
    polys->SetData(offsets, connectivity);
  }
  output->SetPoints(points);
  output->SetPolys(polys);
  output->GetPointData()->SetNormals(normals);
  output->GetPointData()->AddArray(factor);
  if (gradientMagnitude)
  {
    output->GetPointData()->AddArray(gradientMagnitude);
  }

  pisurf::Model model;
  if (!field && this->PiSurface->GetCoreModel(model))
  {
    if (!model.HasBounds)
    {
      // Downstream users rebuild the function and the region it was meshed in.
      model.HasBounds = true;
      std::copy(bounds, bounds + 6, model.Bounds);
    }
    vtkNew<vtkStringArray> json;
    json->SetName("PiSurfaceModel");
    json->InsertNextValue(pisurf::WriteModel(model));
    output->GetFieldData()->AddArray(json);
  }
  if (this->GeneratePrimitives && primitives && !field)
  {
    this->MeshPrimitives(bounds, g.Dims, piece, pieces, primitives);
  }
  // (One piece of several may be empty while the others are not: no warning then.)
  if (vertices == 0 && pieces == 1)
  {
    vtkWarningMacro(<< "The Pi-surface does not cross the bounds [" << bounds[0] << ", "
                    << bounds[1] << "] x [" << bounds[2] << ", " << bounds[3] << "] x ["
                    << bounds[4] << ", " << bounds[5] << "] at this resolution: empty mesh");
  }
  lap("output");
  lap.Total("total");
  this->UpdateProgress(1.0);
  return 1;
}

int vtkPiFlyingEdges::ChooseResolution(const double bounds[6])
{
  int previousComponents = -1;
  double previousArea = 0.0;
  int chosen = 0;
  for (int resolution = 32; resolution <= this->MaximumAutomaticResolution; resolution *= 2)
  {
    int dims[3];
    double spacing[3];
    const double side = std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2],
      bounds[5] - bounds[4] });
    double samples = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      samples *= std::ceil((bounds[2 * a + 1] - bounds[2 * a]) / side * resolution) + 1;
    }
    if (samples > static_cast<double>(this->MaximumNumberOfSamples) ||
      !this->ComputeGrid(bounds, resolution, dims, spacing))
    {
      break;
    }
    vtkNew<vtkPiFlyingEdges> mesher;
    mesher->SetPiSurface(this->PiSurface);
    mesher->SetBounds(bounds);
    mesher->SetResolution(resolution);
    mesher->SetOuterEnvelope(this->OuterEnvelope);
    mesher->SetProjectVertices(this->ProjectVertices);
    mesher->SetMaximumNumberOfSamples(this->MaximumNumberOfSamples);
    vtkNew<vtkCallbackCommand> quiet;
    mesher->AddObserver(vtkCommand::WarningEvent, quiet);
    mesher->Update();
    vtkNew<vtkPolyDataConnectivityFilter> connectivity;
    connectivity->SetInputConnection(mesher->GetOutputPort());
    connectivity->SetExtractionModeToAllRegions();
    connectivity->Update();
    const int components = connectivity->GetNumberOfExtractedRegions();
    vtkNew<vtkMassProperties> mass;
    mass->SetInputConnection(mesher->GetOutputPort());
    mass->Update();
    const double area = mesher->GetOutput()->GetNumberOfCells() > 0 ? mass->GetSurfaceArea() : 0.0;
    chosen = resolution;
    if (components > 0 && components == previousComponents &&
      std::fabs(area - previousArea) <= 0.01 * area)
    {
      return resolution;
    }
    previousComponents = components;
    previousArea = area;
    if (this->CheckAbort())
    {
      break;
    }
  }
  if (chosen == 0)
  {
    vtkErrorMacro(<< "AutomaticResolution: no resolution from 32 fits MaximumNumberOfSamples");
    return 0;
  }
  vtkWarningMacro(<< "AutomaticResolution: the mesh had not settled (components and area) by "
                  << chosen << " cells; using " << chosen);
  return chosen;
}

void vtkPiFlyingEdges::MeshPrimitives(
  const double bounds[6], const int dims[3], int piece, int pieces, vtkPolyData* out)
{
  vtkNew<vtkAppendPolyData> append;
  const int n = this->PiSurface->GetNumberOfFactors();
  for (int i = 0; i < n && !this->CheckAbort(); ++i)
  {
    vtkNew<vtkPiSurface> alone;
    alone->AddFactor(this->PiSurface->GetFactor(i));
    vtkNew<vtkPiFlyingEdges> mesher;
    // A primitive may have no real points (the paper's concavity uses the "sphere"
    // −x²−y²−z²−0.01): its empty mesh is expected, not worth a warning.
    vtkNew<vtkCallbackCommand> quiet;
    mesher->AddObserver(vtkCommand::WarningEvent, quiet);
    mesher->SetPiSurface(alone);
    mesher->SetBounds(bounds);
    mesher->SetSampleDimensions(dims[0], dims[1], dims[2]);
    mesher->SetOuterEnvelope(false);
    mesher->SetGeneratePrimitives(false);
    mesher->SetProjectVertices(this->ProjectVertices);
    mesher->UpdatePiece(piece, pieces, 0);
    vtkNew<vtkPolyData> mesh;
    mesh->ShallowCopy(mesher->GetOutput());
    mesh->GetFieldData()->Initialize();
    vtkDataArray* factor = mesh->GetPointData()->GetArray("Factor");
    if (factor)
    {
      factor->Fill(i);
    }
    append->AddInputData(mesh);
  }
  if (n > 0)
  {
    append->Update();
    out->ShallowCopy(append->GetOutput());
  }
}

void vtkPiFlyingEdges::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PiSurface: " << this->PiSurface << "\n";
  os << indent << "Field: " << (this->Internals->Field ? "set" : "(none)") << "\n";
  os << indent << "Bounds: (" << this->Bounds[0] << ", " << this->Bounds[1] << ", "
     << this->Bounds[2] << ", " << this->Bounds[3] << ", " << this->Bounds[4] << ", "
     << this->Bounds[5] << ")\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "SampleDimensions: (" << this->SampleDimensions[0] << ", "
     << this->SampleDimensions[1] << ", " << this->SampleDimensions[2] << ")\n";
  os << indent << "MaximumNumberOfSamples: " << this->MaximumNumberOfSamples << "\n";
  os << indent << "ProjectVertices: " << (this->ProjectVertices ? "On" : "Off") << "\n";
  os << indent << "OuterEnvelope: " << (this->OuterEnvelope ? "On" : "Off") << "\n";
  os << indent << "AutomaticResolution: " << (this->AutomaticResolution ? "On" : "Off") << "\n";
  os << indent << "MaximumAutomaticResolution: " << this->MaximumAutomaticResolution << "\n";
  os << indent << "LastResolution: " << this->LastResolution << "\n";
  os << indent << "GeneratePrimitives: " << (this->GeneratePrimitives ? "On" : "Off") << "\n";
  os << indent << "ComputeGradientMagnitude: " << (this->ComputeGradientMagnitude ? "On" : "Off")
     << "\n";
}
