// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiRayCaster.h"
#include "PiLargeArrays.h"
#include "PiParallel.h"
#include "PiInputModel.h"
#include "PiPieces.h"
#include "PiTiming.h"

#include "PiModel.h"
#include "PiProduct.h"
#include "PiRayCast.h"
#include "vtkPiSurface.h"

#include "vtkCellArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkExtentTranslator.h"
#include "vtkGarbageCollector.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformationIntegerRequestKey.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTypeInt32Array.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <limits>
#include <memory>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkPiRayCaster);
vtkCxxSetObjectMacro(vtkPiRayCaster, PiSurface, vtkPiSurface);

namespace vtkPiRayCasterDetail
{
// The memory cap of a cast (the mesher's default cap too: 2^28 doubles). Per first hit:
// the Hit (56 bytes), the point and its nine arrays (about 90) and the image pixel.
constexpr double MaximumBytes = double(1u << 31);
constexpr double BytesPerRay = 160;

// One view: the ray of pixel (i, j) starts at O + i·U + j·V (axis and parallel views)
// or at O with direction D + i·U + j·V (perspective), t in [0, Length] for axis views.
struct View
{
  bool Perspective = false;
  bool Axis = false;
  int W = 0, H = 0;
  double O[3], U[3], V[3], D[3];
  double Length = 0.0;
};

struct Hit
{
  int I, J, View, Index;
  double T;
  bool Tangent;
  double P[3];
};

// [t0, t1] ∩ [0, ∞) of the line o + t·d inside the box; false if it misses.
bool Clip(const double o[3], const double d[3], const double b[6], double& t0, double& t1)
{
  t0 = 0.0;
  t1 = VTK_DOUBLE_MAX;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      if (o[a] < b[2 * a] || o[a] > b[2 * a + 1])
      {
        return false;
      }
      continue;
    }
    double ta = (b[2 * a] - o[a]) / d[a], tb = (b[2 * a + 1] - o[a]) / d[a];
    if (ta > tb)
    {
      std::swap(ta, tb);
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 < t1;
}

// Empty-space skipping for axis views and perspective cameras, an octree over each
// view's rays: a node is a square of 2^k × 2^k pixels and a depth range, whose rays lie
// in the bounding box of its corner rays at both depths. Where the kernel's enclosure
// (ProductKernel::ClassifyBox) says F > 0 or F < 0 on the whole box, no ray of the node
// has a root in that depth range. Tiles of TileSize pixels are first cut along the
// depth into boxes about as deep as they are wide; an undecided box is split into eight
// children (two pixel halves per image axis, two depth halves), down to squares of
// LeafSize pixels. In an axis view the children are the box's octants, classified at
// once from one Taylor expansion per factor (ClassifyBoxAndOctants), and a leaf is an
// undecided octant, not classified again; a camera's children are classified one by
// one (the octants of an oblique box are not their boxes). Each leaf column keeps the
// depth ranges of its undecided leaves, merged where they touch and F's monotony along
// the rays is the same (DepthRange::Monotone), in increasing depth: its rays search only
// there (the first hit stops at the first range holding a root), and a column with none
// casts nothing. Touching ranges of different monotony stay apart but joined
// (DepthRange::Joined): a ray searches such a run as one segment cut between them, each
// piece with its own monotony (FindRayRoots with cuts), so a monotone piece is decided
// by its ends where the merged range would have needed the product's Bernstein form
// (a ray through a thin part: rising into it, falling out), and a root on a cut is
// reported once. (Caster instructions at 512², against merging every touching range:
// 10 spheres' first hits −9.9 %, all hits −2.4 %; the cup −8.0 % and −2.7 %; the table
// −7.7 % and −4.9 %. Keeping the leaves of unproven monotony apart too cost 17 % more
// on the 10 spheres' all hits.) The boxes hold the rays' pixel centres (an octant's
// inner faces lie half a pixel beyond its rays), so no root is skipped.
// 8-pixel leaves and boxes as deep as wide measured best on the cup, the table and ten
// spheres at 1024² (4-pixel leaves, or classifying an axis view's leaves themselves,
// cost more in enclosures than they save in root finding). 128-pixel tiles: the empty
// space around a model is decided in a few large boxes; the leaves are the same as
// with smaller tiles, and the octree costs less (instructions over the gallery's 24
// models at 512²: 2.4 % fewer in all than with 32-pixel tiles, 6 % on the cup at 1024²).
constexpr int TileSize = 128;
constexpr int LeafSize = 8;

struct DepthRange
{
  double Start, End;
  // Axis views: +1 or −1 where F is strictly monotone along the rays over the whole
  // range (each leaf it joins so, in one direction, as the parent's
  // ProductKernel::ClassifyBoxAndOctants tells per octant), so a ray holds a root there
  // exactly where F changes sign between the range's ends; 0 where it may turn (and for
  // cameras).
  int Monotone;
  // Touches the column's range before it (its Start is that range's End): the two were
  // left apart only because F is monotone on them differently (see the merge in
  // RequestData), and a ray searches them as one segment cut in two.
  bool Joined;
};

// Per view: the leaf columns' depth ranges (CSR by column, row-major over columns).
struct ViewSkipping
{
  bool Active = false; // false: every ray searches its whole segment
  int Columns = 0;     // leaf columns per image row of columns
  std::vector<int> Offsets; // Columns·rows of columns + 1
  std::vector<DepthRange> Ranges;
};

struct TileOctree
{
  const pisurf::ProductKernel* Kernel;
  const View* V;
  // Axis views: the world axes of the depth, of i and of j (their boxes' octants are
  // their children). Camera views: Axis = −1 (each child's box is classified itself).
  int Axis, U, W;
  double PixelSize;         // the larger of the pixel's two world sizes (at depth 1)
  int RowBegin, RowEnd;     // the image rows this piece casts
  // The tile's undecided leaves as (column in the tile, range), in visiting order.
  std::vector<std::pair<int, DepthRange>> Leaves;
  int TileI = 0, TileJ = 0;
  // First hits only: per leaf column of the tile, the sign of F on the first (nearest)
  // decided box met (0: none yet) and the depth where a decided box of the other sign
  // begins (+inf: none yet). Every ray of the column changes sign between those two
  // boxes, so its first root lies before that depth, in an undecided range in between:
  // nothing beyond it is classified or searched. The visit is front to back (the front
  // half of every node before its back half), so the first decided box met in a column
  // is its nearest. Axis views only: their boxes lie within the bounds, where the rays
  // search.
  bool FirstHit = false;
  signed char FirstSign[(TileSize / LeafSize) * (TileSize / LeafSize)];
  double Cut[(TileSize / LeafSize) * (TileSize / LeafSize)];

  void ResetCuts()
  {
    std::fill(std::begin(this->FirstSign), std::end(this->FirstSign), 0);
    std::fill(std::begin(this->Cut), std::end(this->Cut), std::numeric_limits<double>::infinity());
  }

  // Calls visit(c) for each leaf column c of the tile that the node's pixels cover.
  template <class Visit>
  bool AllColumns(int i0, int j0, int size, Visit&& visit) const
  {
    const int per = TileSize / LeafSize;
    const int ci0 = (i0 - this->TileI) / LeafSize, cj0 = (j0 - this->TileJ) / LeafSize;
    const int n = std::max(1, size / LeafSize);
    for (int cj = cj0; cj < cj0 + n; ++cj)
    {
      for (int ci = ci0; ci < ci0 + n; ++ci)
      {
        if (!visit(cj * per + ci))
        {
          return false;
        }
      }
    }
    return true;
  }

  // A box decided with `sign` over the node's rays at depths [ta, tb]. (Columns beyond
  // the image or the piece hold no ray: what they record is never wrong.)
  void Decided(int i0, int j0, int size, double ta, int sign)
  {
    if (!this->FirstHit)
    {
      return;
    }
    this->AllColumns(i0, j0, size, [&](int c) {
      if (this->FirstSign[c] == 0)
      {
        this->FirstSign[c] = static_cast<signed char>(sign);
      }
      else if (this->FirstSign[c] != sign && ta < this->Cut[c])
      {
        this->Cut[c] = ta;
      }
      return true;
    });
  }

  // True when every ray of the node has its first root before depth ta.
  bool BeyondCut(int i0, int j0, int size, double ta) const
  {
    return this->FirstHit &&
      this->AllColumns(i0, j0, size, [&](int c) { return this->Cut[c] <= ta; });
  }

  // The point of pixel (i, j)'s ray at depth s: O + i·U + j·V + s·D (axis and parallel
  // views, s = t) or O + s·(D + i·U + j·V) (perspective: s is the depth along the view
  // direction, t = s·|D + i·U + j·V|).
  void PointAt(int i, int j, double s, double x[3]) const
  {
    const View& v = *this->V;
    for (int k = 0; k < 3; ++k)
    {
      x[k] = v.Perspective ? v.O[k] + s * (v.D[k] + i * v.U[k] + j * v.V[k])
                           : (v.O[k] + i * v.U[k] + j * v.V[k]) + s * v.D[k];
    }
  }

  // The axis-aligned box of the node's rays: the corner rays at both depths (the rays
  // of a square of pixels between two depths fill the convex hull of those 8 points).
  void Box(int i0, int j0, int size, double ta, double tb, double box[6]) const
  {
    for (int k = 0; k < 3; ++k)
    {
      box[2 * k] = VTK_DOUBLE_MAX;
      box[2 * k + 1] = -VTK_DOUBLE_MAX;
    }
    for (const int i : { i0, i0 + size - 1 })
    {
      for (const int j : { j0, j0 + size - 1 })
      {
        for (const double t : { ta, tb })
        {
          double x[3];
          this->PointAt(i, j, t, x);
          for (int k = 0; k < 3; ++k)
          {
            box[2 * k] = std::min(box[2 * k], x[k]);
            box[2 * k + 1] = std::max(box[2 * k + 1], x[k]);
          }
        }
      }
    }
  }

  // `monotone`: a leaf's direction of monotony along the rays (its parent's verdict).
  void Visit(int i0, int j0, int size, double ta, double tb, int level = 0, int monotone = 0)
  {
    const View& v = *this->V;
    if (i0 >= v.W || j0 >= v.H || j0 + size <= this->RowBegin || j0 >= this->RowEnd)
    {
      return; // no ray of this piece
    }
    if (this->BeyondCut(i0, j0, size, ta))
    {
      return; // every ray of the node has met its first root in front of it
    }
    double box[6];
    this->Box(i0, j0, size, ta, tb, box);
    // (a perspective node is as wide as its far end; at most 16 depth halvings, for a
    // frustum whose near end is at the eye)
    const double width = size * this->PixelSize * (v.Perspective ? tb : 1.0);
    if (tb - ta > width && level < 16)
    {
      // Deeper than wide: halve the depth first (front half first).
      const int sign = this->Kernel->ClassifyBox(box);
      if (sign != 0)
      {
        this->Decided(i0, j0, size, ta, sign);
        return;
      }
      const double mid = 0.5 * (ta + tb);
      this->Visit(i0, j0, size, ta, mid, level + 1);
      this->Visit(i0, j0, size, mid, tb, level + 1);
      return;
    }
    const int half = size / 2;
    const double mid = 0.5 * (ta + tb);
    if (this->Axis < 0)
    {
      // A camera view: the node's own box, then its eight children's.
      const int sign = this->Kernel->ClassifyBox(box);
      if (sign != 0)
      {
        this->Decided(i0, j0, size, ta, sign);
        return;
      }
      if (size <= LeafSize)
      {
        this->AddLeaf(i0, j0, ta, tb, 0);
        return;
      }
      for (int front = 1; front >= 0; --front)
      {
        for (int jh = 0; jh < 2; ++jh)
        {
          for (int ih = 0; ih < 2; ++ih)
          {
            this->Visit(i0 + ih * half, j0 + jh * half, half, front ? ta : mid, front ? mid : tb, level);
          }
        }
      }
      return;
    }
    if (size <= LeafSize)
    {
      this->AddLeaf(i0, j0, ta, tb, monotone);
      return;
    }
    // (children that are leaves: which of them F is monotone on along the rays)
    int octants[8], monotony[8];
    const bool leaves = half <= LeafSize;
    const int sign = this->Kernel->ClassifyBoxAndOctants(
      box, octants, true, leaves ? monotony : nullptr, this->Axis);
    if (sign != 0)
    {
      this->Decided(i0, j0, size, ta, sign);
      return;
    }
    // Octant bit a: the upper half of world axis a. i and j grow with their axes; t
    // grows with the depth axis when the view looks along +axis.
    const bool depthUp = v.D[this->Axis] > 0;
    for (int front = 1; front >= 0; --front)
    {
      const int depthBit = (front == 1) != depthUp ? 1 : 0;
      for (int jh = 0; jh < 2; ++jh)
      {
        for (int ih = 0; ih < 2; ++ih)
        {
          const int o = (ih << this->U) | (jh << this->W) | (depthBit << this->Axis);
          if (octants[o] == 0)
          {
            this->Visit(i0 + ih * half, j0 + jh * half, half, front ? ta : mid, front ? mid : tb,
              level, leaves ? monotony[o] : 0);
          }
          else
          {
            this->Decided(i0 + ih * half, j0 + jh * half, half, front ? ta : mid, octants[o]);
          }
        }
      }
    }
  }

  void AddLeaf(int i0, int j0, double ta, double tb, int monotone)
  {
    const int column =
      ((j0 - this->TileJ) / LeafSize) * (TileSize / LeafSize) + (i0 - this->TileI) / LeafSize;
    if (this->FirstHit && this->Cut[column] <= ta)
    {
      return;
    }
    this->Leaves.push_back({ column, { ta, tb, monotone, false } });
  }
};

// The roots of F along one ray segment, overflow-safe and certified for polynomials.
struct CastRows
{
  const std::vector<View>* Views;
  const double* Bounds;
  bool AllHits;
  double Tolerance;
  std::vector<std::vector<Hit>>* Rows; // per (view, j)
  const pisurf::RayCaster* Caster;
  const std::vector<std::unique_ptr<pisurf::RayGrid>>* Grids; // per view; null: per ray
  const std::vector<ViewSkipping>* Skipping; // per view
  vtkPiRayCaster* Algorithm;
  std::atomic<bool>* Abort;
  int RowBegin, RowEnd; // the image rows [RowBegin, RowEnd) of every view
  std::atomic<vtkIdType>* Finished; // rows cast so far, for the progress
  vtkIdType RowCount;

  // Work buffers of one thread's chunk of rows (locals of operator(), not thread_local:
  // a thread_local costs a call to find it at every ray).
  struct Buffers
  {
    std::vector<pisurf::RayRoot> Roots;
    std::vector<double> Coefficients, Row;
    std::vector<double> Cuts;  // a run of joined ranges: its cuts (in s) and
    std::vector<int> Monotony; // each piece's monotony (see Cast)
  };

  void Cast(const View& v, int viewIndex, int i, int j, std::vector<Hit>& out,
    Buffers& buffers, const pisurf::RayGrid* grid = nullptr) const
  {
    double o[3], d[3];
    double t0 = 0, t1 = v.Length;
    for (int k = 0; k < 3; ++k)
    {
      if (v.Perspective)
      {
        o[k] = v.O[k];
        d[k] = v.D[k] + i * v.U[k] + j * v.V[k];
      }
      else
      {
        o[k] = v.O[k] + i * v.U[k] + j * v.V[k];
        d[k] = v.D[k];
      }
    }
    // (a perspective ray's depth s along the view direction is t/|d|)
    const double norm = vtkMath::Normalize(d);
    if (!v.Axis && !Clip(o, d, this->Bounds, t0, t1))
    {
      return;
    }
    const ViewSkipping& skipping = (*this->Skipping)[viewIndex];
    const DepthRange* range = nullptr;
    const DepthRange* rangeEnd = nullptr;
    if (skipping.Active)
    {
      const int column = (j / LeafSize) * skipping.Columns + i / LeafSize;
      range = skipping.Ranges.data() + skipping.Offsets[column];
      rangeEnd = skipping.Ranges.data() + skipping.Offsets[column + 1];
      if (range == rangeEnd)
      {
        return; // no root for any ray of the column
      }
    }
    const double depthToT = v.Perspective ? norm : 1.0;
    std::vector<pisurf::RayRoot>& roots = buffers.Roots;
    pisurf::RayRootOptions options;
    options.Tolerance = this->Tolerance;
    options.AllRoots = this->AllHits;
    // Orthographic views: the factors restricted from the row's coefficients, in the
    // grid's parameter s = t − h (t from the view plane).
    std::vector<double>& coefficients = buffers.Coefficients;
    double h = 0.0;
    if (grid)
    {
      coefficients.resize(this->Caster->GetLineCoefficientCount());
      grid->Restrict(buffers.Row, i, coefficients.data());
      h = grid->GetHalfLength();
    }
    // The roots on the segment [a, b] of the ray, as hits: from the grid's restriction,
    // or from the factors restricted about the segment's start (t' = t − a).
    int index = 0;
    // (pieces > 1: the grid's segment [cuts[0], cuts[pieces]] searched piece by piece,
    // each with its own monotony; the cuts in the grid's parameter s)
    std::vector<double>& cuts = buffers.Cuts;
    std::vector<int>& monotony = buffers.Monotony;
    auto search = [&](double a, double b, int pieces = 1) {
      if (grid)
      {
        if (pieces > 1)
        {
          this->Caster->CastRestricted(
            coefficients.data(), cuts.data(), monotony.data(), pieces, options, roots);
        }
        else
        {
          this->Caster->CastRestricted(coefficients.data(), a - h, b - h, options, roots);
        }
        for (const pisurf::RayRoot& r : roots)
        {
          const double t = r.T + h;
          Hit hit{ i, j, viewIndex, index++, t, r.Tangent, {} };
          for (int k = 0; k < 3; ++k)
          {
            hit.P[k] = o[k] + t * d[k];
          }
          out.push_back(hit);
        }
        return;
      }
      const double start[3] = { o[0] + a * d[0], o[1] + a * d[1], o[2] + a * d[2] };
      this->Caster->Cast(start, d, b - a, options, roots);
      for (const pisurf::RayRoot& r : roots)
      {
        Hit hit{ i, j, viewIndex, index++, a + r.T, r.Tangent, {} };
        for (int k = 0; k < 3; ++k)
        {
          hit.P[k] = start[k] + r.T * d[k];
        }
        out.push_back(hit);
      }
    };
    if (!range)
    {
      search(t0, t1);
      return;
    }
    // The column's ranges in increasing depth (no root lies between them). A run of
    // joined ranges is one segment, cut where the monotony changes: on the grid's rays
    // its pieces are searched with their own monotony in one cluster (a root on a cut
    // once); elsewhere (cameras, whose ranges are never joined) as one segment.
    while (range != rangeEnd)
    {
      const DepthRange* last = range + 1;
      while (last != rangeEnd && last->Joined)
      {
        ++last;
      }
      const double a = std::max(t0, range->Start * depthToT);
      const double b = std::min(t1, (last - 1)->End * depthToT);
      int pieces = 0;
      if (a < b && grid && last - range > 1)
      {
        cuts.assign(1, a - h);
        monotony.clear();
        for (const DepthRange* p = range; p != last; ++p)
        {
          const double end = p + 1 == last ? b : std::min(b, p->End * depthToT);
          if (end - h > cuts.back())
          {
            monotony.push_back(p->Monotone != 0);
            cuts.push_back(end - h);
            ++pieces;
          }
        }
      }
      // (A joined run as one segment, where its pieces are not searched apart, is not
      // proven monotone: its ranges' monotony differs from one to the next.)
      options.Monotone = last - range == 1 && range->Monotone != 0;
      range = last;
      if (!(a < b))
      {
        continue;
      }
      search(a, b, std::max(pieces, 1));
      if (!this->AllHits && !roots.empty())
      {
        return;
      }
    }
  }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const bool single = PiSingleThread();
    Buffers buffers;
    for (vtkIdType row = begin; row < end; ++row)
    {
      if (single && this->Algorithm->CheckAbort())
      {
        *this->Abort = true;
      }
      if (*this->Abort)
      {
        return;
      }
      // Rows are numbered view by view, RowEnd − RowBegin of them per view.
      const vtkIdType perView = this->RowEnd - this->RowBegin;
      const size_t vi = static_cast<size_t>(row / perView);
      const vtkIdType r = this->RowBegin + row % perView;
      const View& v = (*this->Views)[vi];
      std::vector<Hit>& out = (*this->Rows)[row];
      out.reserve(static_cast<size_t>(v.W)); // (a hit per pixel, at first)
      const pisurf::RayGrid* grid = (*this->Grids)[vi].get();
      if (grid)
      {
        grid->SetRow(static_cast<int>(r), buffers.Row);
      }
      for (int i = 0; i < v.W; ++i)
      {
        this->Cast(v, static_cast<int>(vi), i, static_cast<int>(r), out, buffers, grid);
      }
      // Casting is 80 % of the progress, reported from the main thread about every
      // percent.
      const vtkIdType finished = ++*this->Finished;
      if (single && finished * 100 / this->RowCount != (finished - 1) * 100 / this->RowCount)
      {
        this->Algorithm->UpdateProgress(0.8 * (static_cast<double>(finished) / this->RowCount));
      }
    }
  }
};
}

namespace vtkPiRayCasterDetail
{
struct HitRows
{
  std::vector<std::vector<Hit>> Rows;
};
}

using namespace vtkPiRayCasterDetail;

vtkPiRayCaster::vtkPiRayCaster()
  : Rows(new HitRows)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
}

int vtkPiRayCaster::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkImageData");
  return 1;
}

int vtkPiRayCaster::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // The image: w × h pixels, one slice per view (the number of views is known here).
  const int views = this->ViewMode == SIX_AXIS_VIEWS ? 6
    : this->ViewMode == THREE_AXIS_DIRECTIONS        ? 3
                                                      : 1;
  const int extent[6] = { 0, std::max(this->Resolution[0], 1) - 1, 0,
    std::max(this->Resolution[1], 1) - 1, 0, views - 1 };
  vtkInformation* info = outputVector->GetInformationObject(1);
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  // Pieces (ParaView's MPI mode) are slabs of image rows, the same rows of every view:
  // piece p of n casts rows [h p / n, h (p + 1) / n). The image port produces the same
  // row slabs as sub-extents.
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  info->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  info->Set(
    vtkExtentTranslator::UPDATE_SPLIT_MODE(), static_cast<int>(vtkExtentTranslator::Y_SLAB_MODE));
  return 1;
}

vtkPiRayCaster::~vtkPiRayCaster()
{
  this->SetPiSurface(nullptr);
  delete this->Rows;
}

int vtkPiRayCaster::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

vtkMTimeType vtkPiRayCaster::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->PiSurface)
  {
    t = std::max(t, this->PiSurface->GetMTime());
  }
  return t;
}

void vtkPiRayCaster::ReportReferences(vtkGarbageCollector* collector)
{
  this->Superclass::ReportReferences(collector);
  vtkGarbageCollectorReport(collector, this->PiSurface, "PiSurface");
}

int vtkPiRayCaster::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // PISURF_TIMING=1: the time of each pass on stderr (PiTiming.h).
  PiPassTimer lap("vtkPiRayCaster");
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkImageData* image = vtkImageData::GetData(outputVector, 1);

  // The surface: a molecule's (Molecular Pi Surface output, any size or mode), else the
  // input's model, or the one set.
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  std::string error;
  PiInputSurface in;
  if (!in.Read(input, this->PiSurface, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const PiMoleculeInput& molecule = in.Molecule;
  const vtkSmartPointer<vtkPiSurface>& surface = in.Surface;
  const std::shared_ptr<const pisurf::ProductKernel>& kernel = in.Kernel;
  // Orthographic row restriction and the empty-space octree: polynomial products only.
  const bool polynomial = kernel && kernel->IsPolynomial();
  if (this->Resolution[0] < 1 || this->Resolution[1] < 1)
  {
    vtkErrorMacro(<< "Resolution must be at least 1 x 1 (got " << this->Resolution[0] << " x "
                  << this->Resolution[1] << ")");
    return 0;
  }
  if (!(this->SingularTolerance >= 0 && std::isfinite(this->SingularTolerance)))
  {
    vtkErrorMacro(<< "SingularTolerance must be a finite number >= 0, not "
                  << this->SingularTolerance);
    return 0;
  }
  double b[6];
  if (!in.ResolveBounds(this->Bounds, b, error))
  {
    vtkErrorMacro(<< "No bounds for the rays: " << error);
    return 0;
  }

  // The views.
  const int w = this->Resolution[0], h = this->Resolution[1];
  std::vector<View> views;
  auto axisView = [&](int axis, bool plus) {
    // Image axes: (x, y) for z, (y, z) for x, (z, x) for y; start on the far face for
    // the − directions, the near face for the + directions.
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    View view;
    view.Axis = true;
    view.W = w;
    view.H = h;
    for (int k = 0; k < 3; ++k)
    {
      view.U[k] = view.V[k] = view.D[k] = 0.0;
    }
    view.U[u] = (b[2 * u + 1] - b[2 * u]) / w;
    view.V[v] = (b[2 * v + 1] - b[2 * v]) / h;
    view.D[axis] = plus ? 1.0 : -1.0;
    view.O[u] = b[2 * u] + 0.5 * view.U[u];
    view.O[v] = b[2 * v] + 0.5 * view.V[v];
    view.O[axis] = plus ? b[2 * axis] : b[2 * axis + 1];
    view.Length = b[2 * axis + 1] - b[2 * axis];
    views.push_back(view);
  };
  switch (this->ViewMode)
  {
    case PLUS_X:
    case MINUS_X:
    case PLUS_Y:
    case MINUS_Y:
    case PLUS_Z:
    case MINUS_Z:
      // The enumeration runs +X, −X, +Y, −Y, +Z, −Z.
      axisView((this->ViewMode - PLUS_X) / 2, (this->ViewMode - PLUS_X) % 2 == 0);
      break;
    case SIX_AXIS_VIEWS:
    case THREE_AXIS_DIRECTIONS:
      axisView(2, false);
      axisView(0, false);
      axisView(1, false);
      if (this->ViewMode == SIX_AXIS_VIEWS)
      {
        axisView(2, true);
        axisView(0, true);
        axisView(1, true);
      }
      break;
    default:
    {
      double dir[3], up[3], right[3];
      for (int k = 0; k < 3; ++k)
      {
        if (!std::isfinite(this->CameraPosition[k]) || !std::isfinite(this->CameraFocalPoint[k]) ||
          !std::isfinite(this->CameraViewUp[k]))
        {
          vtkErrorMacro(<< "Degenerate camera: CameraPosition, CameraFocalPoint and "
                           "CameraViewUp must be finite");
          return 0;
        }
      }
      for (int k = 0; k < 3; ++k)
      {
        dir[k] = this->CameraFocalPoint[k] - this->CameraPosition[k];
        up[k] = this->CameraViewUp[k];
      }
      if (!(vtkMath::Normalize(dir) > 0) || !std::isfinite(dir[0] + dir[1] + dir[2]))
      {
        vtkErrorMacro(<< "Degenerate camera: CameraPosition equals CameraFocalPoint");
        return 0;
      }
      vtkMath::Cross(dir, up, right);
      if (!(vtkMath::Normalize(right) > 1e-12))
      {
        vtkErrorMacro(<< "Degenerate camera: CameraViewUp is parallel to the view direction");
        return 0;
      }
      vtkMath::Cross(right, dir, up);
      double hh;
      if (this->ParallelProjection)
      {
        hh = this->ParallelScale;
      }
      else
      {
        if (!(this->ViewAngle > 0 && this->ViewAngle < 180))
        {
          vtkErrorMacro(<< "ViewAngle must be in (0, 180) degrees");
          return 0;
        }
        hh = std::tan(vtkMath::RadiansFromDegrees(0.5 * this->ViewAngle));
      }
      if (!(hh > 0) || !std::isfinite(hh))
      {
        vtkErrorMacro(<< "ParallelScale must be positive");
        return 0;
      }
      const double hw = hh * w / h;
      View view;
      view.Perspective = !this->ParallelProjection;
      view.W = w;
      view.H = h;
      for (int k = 0; k < 3; ++k)
      {
        view.U[k] = right[k] * 2 * hw / w;
        view.V[k] = up[k] * 2 * hh / h;
        const double corner = -hw * right[k] - hh * up[k] + 0.5 * (view.U[k] + view.V[k]);
        if (view.Perspective)
        {
          view.O[k] = this->CameraPosition[k];
          view.D[k] = dir[k] + corner;
        }
        else
        {
          view.O[k] = this->CameraPosition[k] + corner;
          view.D[k] = dir[k];
        }
      }
      views.push_back(view);
    }
  }
  const bool allHits = this->AllHits || this->ViewMode == THREE_AXIS_DIRECTIONS;
  // The image cap: each ray's first hit costs about BytesPerRay in the hits, their
  // arrays and the shaded image (more with AllHits).
  const double rays = double(w) * h * views.size();
  if (rays * BytesPerRay > MaximumBytes)
  {
    vtkErrorMacro(<< "Casting " << w << " x " << h << " pixels in " << views.size()
                  << " view(s) needs at least " << rays * BytesPerRay / (1 << 20)
                  << " MiB (about " << BytesPerRay << " bytes per ray); the limit is "
                  << MaximumBytes / (1 << 20) << " MiB: lower the Resolution");
    return 0;
  }
  const double size = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));

  // This piece's rows of every view; the image port's requested rows widen the cast (the
  // points keep to the piece, so the pieces' points do not overlap).
  vtkInformation* pointInfo = outputVector->GetInformationObject(0);
  const PiPiece request = PiPieceOf(pointInfo);
  const int piece = request.Piece, pieces = request.Pieces;
  const int pieceBegin = static_cast<int>(vtkIdType(h) * piece / pieces);
  const int pieceEnd = static_cast<int>(vtkIdType(h) * (piece + 1) / pieces);
  int rowBegin = pieceBegin, rowEnd = pieceEnd;
  vtkInformation* imageInfo = outputVector->GetInformationObject(1);
  // Only a piece request on the image port itself (ParaView showing the image in
  // parallel) widens the cast; its extent otherwise defaults to the whole image.
  if (image && imageInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()) &&
    imageInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) &&
    imageInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) > 1)
  {
    int ue[6];
    imageInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ue);
    if (ue[2] <= ue[3])
    {
      rowBegin = std::min(rowBegin, std::max(ue[2], 0));
      rowEnd = std::max(rowEnd, std::min(ue[3] + 1, h));
    }
  }
  if (rowEnd <= rowBegin)
  {
    // More pieces than rows: this one is empty.
    if (image)
    {
      image->Initialize();
    }
    return 1;
  }

  // PASS 1: cast the rays, one image row per work item.
  const vtkIdType rowCount = static_cast<vtkIdType>(views.size()) * (rowEnd - rowBegin);
  // (Each row's vector emptied, its memory kept from the last execution.)
  std::vector<std::vector<Hit>>& rows = this->Rows->Rows;
  rows.resize(static_cast<size_t>(rowCount));
  for (std::vector<Hit>& row : rows)
  {
    row.clear();
  }
  std::atomic<bool> abort{ false };
  std::unique_ptr<pisurf::MoleculeField> field;
  std::unique_ptr<pisurf::RayCaster> casterPointer;
  if (molecule.Present)
  {
    field = molecule.MakeField(b, error);
    if (!field)
    {
      vtkErrorMacro(<< error);
      return 0;
    }
    casterPointer = std::make_unique<pisurf::RayCaster>(*field);
  }
  else
  {
    casterPointer = std::make_unique<pisurf::RayCaster>(*kernel);
  }
  pisurf::RayCaster& caster = *casterPointer;
  // Orthographic views of polynomial products restrict their rays from per-view
  // compositions (pisurf::RayGrid), about the middle of the box along the view.
  std::vector<std::unique_ptr<pisurf::RayGrid>> grids(views.size());
  if (polynomial)
  {
    for (size_t k = 0; k < views.size(); ++k)
    {
      const View& v = views[k];
      if (v.Perspective)
      {
        continue;
      }
      double d[3] = { v.D[0], v.D[1], v.D[2] };
      vtkMath::Normalize(d);
      double length = v.Length;
      if (!v.Axis)
      {
        // Twice the distance from the view plane to the box centre along the rays.
        length = 0.0;
        for (int c = 0; c < 3; ++c)
        {
          length += 2.0 * (0.5 * (b[2 * c] + b[2 * c + 1]) - v.O[c]) * d[c];
        }
      }
      grids[k] = std::make_unique<pisurf::RayGrid>(*kernel, v.O, v.U, v.V, d, v.W, v.H, length);
    }
  }
  // Per view, the depth ranges of each leaf column that may hold roots.
  std::vector<ViewSkipping> skipping(views.size());
  if (polynomial && this->SkipEmptySpace)
  {
    for (size_t k = 0; k < views.size(); ++k)
    {
      const View& v = views[k];
      if (!v.Axis && !v.Perspective)
      {
        // A parallel camera: its rays already restrict cheaply from the view's grid and
        // the boxes of its oblique tiles are loose; the octree cost about what it saved.
        continue;
      }
      // The depths [s0, s1] the rays can meet the bounds at: the whole segment of an
      // axis view; for a camera view, the bounds' corners along the view direction
      // (perspective: D + i·U + j·V has depth 1 along it).
      double s0 = 0.0, s1 = v.Length;
      int axis = -1;
      if (v.Axis)
      {
        axis = 0;
        while (axis < 2 && v.D[axis] == 0.0)
        {
          ++axis;
        }
      }
      else
      {
        double dir[3] = { v.D[0], v.D[1], v.D[2] };
        if (v.Perspective)
        {
          // The view direction: D without its parts along U and V (both orthogonal to it).
          for (const double* e : { v.U, v.V })
          {
            const double scale = vtkMath::Dot(dir, e) / vtkMath::Dot(e, e);
            for (int c = 0; c < 3; ++c)
            {
              dir[c] -= scale * e[c];
            }
          }
        }
        s0 = VTK_DOUBLE_MAX;
        s1 = -VTK_DOUBLE_MAX;
        for (int corner = 0; corner < 8; ++corner)
        {
          double depth = 0.0;
          for (int c = 0; c < 3; ++c)
          {
            depth += (b[2 * c + ((corner >> c) & 1)] - v.O[c]) * dir[c];
          }
          s0 = std::min(s0, depth);
          s1 = std::max(s1, depth);
        }
        s0 = std::max(s0, 0.0);
        if (!(s1 > s0))
        {
          continue; // the bounds are behind the camera: every ray misses them
        }
      }
      const int tw = (v.W + TileSize - 1) / TileSize;
      const int tileRowBegin = rowBegin / TileSize, tileRowEnd = (rowEnd - 1) / TileSize + 1;
      const int tileCount = tw * (tileRowEnd - tileRowBegin);
      constexpr int PerTile = (TileSize / LeafSize) * (TileSize / LeafSize);
      // Per tile, its columns' ranges (then gathered into the view's CSR).
      std::vector<std::vector<int>> tileOffsets(tileCount);
      std::vector<std::vector<DepthRange>> tileRanges(tileCount);
      // (one tile per task: a tile's cost depends on how much of the model it sees)
      PiFor(0, tileCount, 1, [&](vtkIdType begin, vtkIdType end) {
        TileOctree octree;
        octree.Kernel = kernel.get();
        octree.V = &v;
        octree.Axis = axis;
        octree.U = (axis + 1) % 3;
        octree.W = (axis + 2) % 3;
        octree.PixelSize = std::max(vtkMath::Norm(v.U), vtkMath::Norm(v.V));
        octree.RowBegin = rowBegin;
        octree.RowEnd = rowEnd;
        // (axis views only: a camera's boxes reach beyond the bounds, where its rays,
        // clipped to them, do not search, so a sign change there proves no hit)
        octree.FirstHit = !allHits && axis >= 0;
        for (vtkIdType id = begin; id < end; ++id)
        {
          octree.TileI = static_cast<int>(id % tw) * TileSize;
          octree.TileJ = (tileRowBegin + static_cast<int>(id / tw)) * TileSize;
          octree.Leaves.clear();
          octree.ResetCuts();
          octree.Visit(octree.TileI, octree.TileJ, TileSize, s0, s1);
          // Counting sort by column (stable: each column keeps increasing depth), merging
          // ranges that touch.
          std::vector<int>& offsets = tileOffsets[id];
          offsets.assign(PerTile + 1, 0);
          for (const auto& leaf : octree.Leaves)
          {
            ++offsets[leaf.first + 1];
          }
          for (int c = 0; c < PerTile; ++c)
          {
            offsets[c + 1] += offsets[c];
          }
          std::vector<int> fill(offsets.begin(), offsets.end() - 1);
          std::vector<DepthRange> sorted(octree.Leaves.size());
          for (const auto& leaf : octree.Leaves)
          {
            sorted[fill[leaf.first]++] = leaf.second;
          }
          std::vector<DepthRange>& ranges = tileRanges[id];
          ranges.clear();
          int kept = 0;
          for (int c = 0; c < PerTile; ++c)
          {
            const int first = kept;
            for (int m = offsets[c]; m < offsets[c + 1]; ++m)
            {
              // (Overlapping ranges are merged whatever their monotony.)
              const bool touches = kept > first && ranges.back().End >= sorted[m].Start;
              if (touches &&
                (ranges.back().Monotone == sorted[m].Monotone ||
                  ranges.back().End > sorted[m].Start))
              {
                ranges.back().End = std::max(ranges.back().End, sorted[m].End);
                // (F monotone the same way on both parts is so on their union)
                if (ranges.back().Monotone != sorted[m].Monotone)
                {
                  ranges.back().Monotone = 0;
                }
              }
              else
              {
                ranges.push_back(sorted[m]);
                ranges.back().Joined = touches;
                ++kept;
              }
            }
            offsets[c] = first;
          }
          offsets[PerTile] = kept;
        }
      });
      // The view's CSR over its leaf columns (rows of columns outside the piece: none).
      ViewSkipping& view = skipping[k];
      view.Active = true;
      view.Columns = tw * (TileSize / LeafSize);
      const int columnRows = ((v.H + TileSize - 1) / TileSize) * (TileSize / LeafSize);
      view.Offsets.assign(static_cast<size_t>(view.Columns) * columnRows + 1, 0);
      // The view's column of column c of tile `id`.
      auto column = [&](int id, int c) {
        const int ci = (id % tw) * (TileSize / LeafSize) + c % (TileSize / LeafSize);
        const int cj = (tileRowBegin + id / tw) * (TileSize / LeafSize) + c / (TileSize / LeafSize);
        return static_cast<size_t>(cj) * view.Columns + ci;
      };
      for (int id = 0; id < tileCount; ++id)
      {
        for (int c = 0; c < PerTile; ++c)
        {
          view.Offsets[column(id, c) + 1] = tileOffsets[id][c + 1] - tileOffsets[id][c];
        }
      }
      for (size_t c = 1; c < view.Offsets.size(); ++c)
      {
        view.Offsets[c] += view.Offsets[c - 1];
      }
      view.Ranges.resize(static_cast<size_t>(view.Offsets.back()));
      for (int id = 0; id < tileCount; ++id)
      {
        for (int c = 0; c < PerTile; ++c)
        {
          std::copy(tileRanges[id].begin() + tileOffsets[id][c],
            tileRanges[id].begin() + tileOffsets[id][c + 1],
            view.Ranges.begin() + view.Offsets[column(id, c)]);
        }
      }
    }
  }
  lap("tiles");
  if (lap.IsEnabled())
  {
    size_t ranges = 0, monotone = 0;
    for (const ViewSkipping& view : skipping)
    {
      ranges += view.Ranges.size();
      for (const DepthRange& r : view.Ranges)
      {
        monotone += r.Monotone != 0;
      }
    }
    std::cerr << ranges << " depth ranges to search, " << monotone << " of them monotone\n";
  }
  std::atomic<vtkIdType> finished{ 0 };
  CastRows cast{ &views, b, allHits, 1e-10 * size, &rows, &caster, &grids, &skipping, this,
    &abort, rowBegin, rowEnd, &finished, rowCount };
  lap("setup");
  // Rows differ a lot in cost (the model covers the middle of the image): small chunks
  // keep the threads balanced.
  PiFor(0, rowCount, 8, cast);
  lap("roots");
  if (abort || this->CheckAbort())
  {
    return 1;
  }
  this->UpdateProgress(0.8);

  // PASS 2: the hits' attributes from the exact gradient (of every hit the image
  // shows; the points are then this piece's rows).
  // Point k is hit k - rowOffsets[r] of row r (read from the rows where they are).
  std::vector<vtkIdType> rowOffsets(rows.size() + 1, 0);
  for (size_t r = 0; r < rows.size(); ++r)
  {
    rowOffsets[r + 1] = rowOffsets[r] + static_cast<vtkIdType>(rows[r].size());
  }
  const vtkIdType n = rowOffsets.back();
  // In the one-piece case every hit is a point.
  const bool extraRows = rowBegin != pieceBegin || rowEnd != pieceEnd;
  vtkNew<vtkPoints> points;
  PiAllocateLargePoints(points, n);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  PiAllocateLarge(normals.GetPointer(), n);
  vtkNew<vtkDoubleArray> gradient;
  gradient->SetName("GradientMagnitude");
  PiAllocateLarge(gradient.GetPointer(), n);
  vtkNew<vtkDoubleArray> depth;
  depth->SetName("Depth");
  PiAllocateLarge(depth.GetPointer(), n);
  vtkNew<vtkIntArray> pixel;
  pixel->SetName("PixelIndex");
  pixel->SetNumberOfComponents(2);
  PiAllocateLarge(pixel.GetPointer(), n);
  vtkNew<vtkIntArray> viewIndex;
  viewIndex->SetName("ViewIndex");
  PiAllocateLarge(viewIndex.GetPointer(), n);
  vtkNew<vtkIntArray> hitIndex;
  hitIndex->SetName("HitIndex");
  PiAllocateLarge(hitIndex.GetPointer(), n);
  vtkNew<vtkUnsignedCharArray> singular;
  singular->SetName("Singular");
  PiAllocateLarge(singular.GetPointer(), n);
  vtkNew<vtkUnsignedCharArray> tangent;
  tangent->SetName("Tangent");
  PiAllocateLarge(tangent.GetPointer(), n);
  vtkNew<vtkIntArray> factor;
  factor->SetName("Factor");
  PiAllocateLarge(factor.GetPointer(), n);
  const double probe = 1e-3 * size;
  // Every ray segment lies in the bounds, and so do the hits: there the attributes may
  // skip the singularity probes where the factors prove a hit regular (a hit a rounding
  // outside takes the probes; RayCaster::PrepareProbes).
  caster.PrepareProbes(b, probe);
  double* xyz = vtkDoubleArray::FastDownCast(points->GetData())->GetPointer(0);
  float* nrmOut = normals->GetPointer(0);
  double* gradientOut = gradient->GetPointer(0);
  double* depthOut = depth->GetPointer(0);
  int* pixelOut = pixel->GetPointer(0);
  int* viewOut = viewIndex->GetPointer(0);
  int* hitOut = hitIndex->GetPointer(0);
  unsigned char* singularOut = singular->GetPointer(0);
  unsigned char* tangentOut = tangent->GetPointer(0);
  int* factorOut = factor->GetPointer(0);
  // A row at a time (rows differ a lot in their number of hits: small chunks).
  PiFor(0, static_cast<vtkIdType>(rows.size()), 4, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType r = begin; r < end; ++r)
    {
      const std::vector<Hit>& row = rows[r];
      // Four hits at a time (RayCaster::Attributes evaluates them side by side).
      constexpr int Group = pisurf::ProductKernel::MaxVertices;
      for (size_t first = 0; first < row.size(); first += Group)
      {
        const int count = static_cast<int>(std::min<size_t>(Group, row.size() - first));
        double p[Group][3], nrm[Group][3], g[Group];
        int nearest[Group];
        bool isSingular[Group];
        for (int j = 0; j < count; ++j)
        {
          std::copy(row[first + j].P, row[first + j].P + 3, p[j]);
        }
        // Singular: F grows faster than linearly away from the hit.
        caster.Attributes(
          count, p, probe, this->SingularTolerance, nrm, g, nearest, isSingular);
        for (int j = 0; j < count; ++j)
        {
          const Hit& hit = row[first + j];
          const vtkIdType k = rowOffsets[r] + static_cast<vtkIdType>(first) + j;
          singularOut[k] = isSingular[j] ? 1 : 0;
          for (int c = 0; c < 3; ++c)
          {
            xyz[3 * k + c] = hit.P[c];
            nrmOut[3 * k + c] = static_cast<float>(nrm[j][c]);
          }
          gradientOut[k] = g[j];
          depthOut[k] = hit.T;
          pixelOut[2 * k] = hit.I;
          pixelOut[2 * k + 1] = hit.J;
          viewOut[k] = hit.View;
          hitOut[k] = hit.Index;
          tangentOut[k] = hit.Tangent ? 1 : 0;
          factorOut[k] = nearest[j];
        }
      }
    }
  });

  // Kept for the next execution up to 256 MiB of hits (4 M hits: six 1024² views of
  // first hits, or a few all-hit ones); more is released rather than held.
  size_t keptBytes = 0;
  for (const std::vector<Hit>& row : rows)
  {
    keptBytes += row.capacity() * sizeof(Hit);
  }
  if (keptBytes > (size_t(256) << 20))
  {
    std::vector<std::vector<Hit>>().swap(rows);
  }
  lap("attributes");
  if (this->CheckAbort())
  {
    return 1;
  }
  this->UpdateProgress(0.9);
  vtkPointData* pd = output->GetPointData();
  const std::vector<vtkDataArray*> arrays{ normals, gradient, depth, pixel, viewIndex, hitIndex,
    singular, tangent, factor };
  if (!extraRows)
  {
    output->SetPoints(points);
    for (vtkDataArray* a : arrays)
    {
      pd->AddArray(a);
    }
  }
  else
  {
    // The image needed rows beyond this piece's: the points are the piece's rows only.
    vtkNew<vtkIdList> keep;
    for (vtkIdType k = 0; k < n; ++k)
    {
      if (pixelOut[2 * k + 1] >= pieceBegin && pixelOut[2 * k + 1] < pieceEnd)
      {
        keep->InsertNextId(k);
      }
    }
    vtkNew<vtkPoints> kept;
    kept->SetDataTypeToDouble();
    kept->SetNumberOfPoints(keep->GetNumberOfIds()); // GetPoints fills, does not allocate
    points->GetPoints(keep, kept);
    output->SetPoints(kept);
    for (vtkDataArray* a : arrays)
    {
      vtkSmartPointer<vtkDataArray> part = vtk::TakeSmartPointer(a->NewInstance());
      part->SetName(a->GetName());
      part->SetNumberOfComponents(a->GetNumberOfComponents());
      part->SetNumberOfTuples(keep->GetNumberOfIds());
      a->GetTuples(keep, part);
      pd->AddArray(part);
    }
  }
  pd->SetActiveNormals("Normals");
  const vtkIdType kept = output->GetNumberOfPoints();
  // One vertex cell per point: offsets 0..kept and connectivity 0..kept−1, handed to
  // the cell array as they are (in its 32-bit storage when the ids fit).
  vtkNew<vtkCellArray> verts;
  auto fillVerts = [&](auto* offsets, auto* ids) {
    PiAllocateLarge(offsets, kept + 1);
    PiAllocateLarge(ids, kept);
    auto* offsetOut = offsets->GetPointer(0);
    auto* idOut = ids->GetPointer(0);
    using Id = typename std::remove_pointer<decltype(idOut)>::type;
    vtkSMPTools::For(0, kept + 1, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType k = begin; k < end; ++k)
      {
        offsetOut[k] = static_cast<Id>(k);
        if (k < kept)
        {
          idOut[k] = static_cast<Id>(k);
        }
      }
    });
    verts->SetData(offsets, ids);
  };
  if (kept < std::numeric_limits<std::int32_t>::max())
  {
    vtkNew<vtkTypeInt32Array> offsets, ids;
    fillVerts(offsets.GetPointer(), ids.GetPointer());
  }
  else
  {
    vtkNew<vtkIdTypeArray> offsets, ids;
    fillVerts(offsets.GetPointer(), ids.GetPointer());
  }
  output->SetVerts(verts);

  vtkNew<vtkDoubleArray> viewData;
  viewData->SetName("PiRayViews");
  viewData->SetNumberOfComponents(17);
  for (const View& v : views)
  {
    const double t[17] = { v.Perspective ? 1.0 : 0.0, double(v.W), double(v.H), v.O[0], v.O[1],
      v.O[2], v.U[0], v.U[1], v.U[2], v.V[0], v.V[1], v.V[2], v.D[0], v.D[1], v.D[2], v.Length,
      allHits ? 1.0 : 0.0 };
    viewData->InsertNextTuple(t);
  }
  output->GetFieldData()->AddArray(viewData);
  pisurf::Model model;
  if (molecule.Present)
  {
    molecule.Forward(input, output); // the molecule goes downstream
  }
  else if (surface->GetCoreModel(model))
  {
    if (!model.HasBounds)
    {
      model.HasBounds = true;
      std::copy(b, b + 6, model.Bounds);
    }
    vtkNew<vtkStringArray> json;
    json->SetName("PiSurfaceModel");
    json->InsertNextValue(pisurf::WriteModel(model));
    output->GetFieldData()->AddArray(json);
  }
  lap("output");
  if (image)
  {
    this->Shade(views, rowBegin, rowEnd, rowOffsets.data(), depthOut, pixelOut, hitOut, normals,
      singular, image);
    if (rowBegin != pieceBegin || rowEnd != pieceEnd)
    {
      // Rows beyond the piece (ghost rows asked by the image's consumer, or another
      // split of the rows) are marked as ghosts: each pixel belongs to one piece.
      vtkNew<vtkUnsignedCharArray> ghosts;
      ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
      ghosts->SetNumberOfTuples(image->GetNumberOfPoints());
      const vtkIdType rowsCast = rowEnd - rowBegin;
      for (vtkIdType id = 0; id < ghosts->GetNumberOfTuples(); ++id)
      {
        const int j = rowBegin + static_cast<int>((id / w) % rowsCast);
        ghosts->SetValue(id, j >= pieceBegin && j < pieceEnd ? 0
            : vtkDataSetAttributes::DUPLICATEPOINT);
      }
      image->GetPointData()->AddArray(ghosts);
    }
  }
  lap("shading");
  if (n == 0 && pieces == 1)
  {
    vtkWarningMacro(<< "No ray hits the Pi-surface");
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPiRayCaster::Shade(const std::vector<View>& views, int rowBegin, int rowEnd,
  const vtkIdType* rowOffsets, const double* hitDepth, const int* pixel, const int* hitIndex,
  vtkFloatArray* normals, vtkUnsignedCharArray* singular, vtkImageData* image)
{
  const int w = this->Resolution[0], h = rowEnd - rowBegin;
  const int count = static_cast<int>(views.size());
  // Rows [rowBegin, rowEnd) of each view: the whole image, or this piece's slab of it.
  image->SetExtent(0, w - 1, rowBegin, rowEnd - 1, 0, count - 1);
  image->SetOrigin(0, 0, 0);
  image->SetSpacing(1, 1, 1);
  const vtkIdType pixels = vtkIdType(w) * h * count;
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("Shading");
  rgb->SetNumberOfComponents(3);
  PiAllocateLarge(rgb.GetPointer(), pixels);
  vtkNew<vtkDoubleArray> depth;
  depth->SetName("Depth");
  PiAllocateLarge(depth.GetPointer(), pixels);
  unsigned char* colour = rgb->GetPointer(0);
  double* depthOut = depth->GetPointer(0);
  const float* nrm = normals->GetPointer(0);
  const unsigned char* isSingular = singular->GetPointer(0);
  // Image row r (view r / h, row rowBegin + r % h) is hit row r: each row is filled with
  // the background (white, no hit) and then given its first hits, in one pass over the
  // image (a first hit is the only one of its pixel).
  PiFor(0, vtkIdType(h) * count, 16, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType r = begin; r < end; ++r)
    {
      const View& v = views[static_cast<size_t>(r / h)];
      const vtkIdType first = r * w;
      std::fill(colour + 3 * first, colour + 3 * (first + w), static_cast<unsigned char>(255));
      std::fill(depthOut + first, depthOut + first + w, -1.0);
      for (vtkIdType k = rowOffsets[r]; k < rowOffsets[r + 1]; ++k)
      {
        if (hitIndex[k] != 0)
        {
          continue;
        }
        const int i = pixel[2 * k], j = pixel[2 * k + 1];
        const vtkIdType id = first + i;
        depthOut[id] = hitDepth[k];
        unsigned char* rgbOut = colour + 3 * id;
        if (isSingular[k])
        {
          rgbOut[0] = 220;
          rgbOut[1] = 30;
          rgbOut[2] = 30;
          continue;
        }
        // A headlight: light along the ray, Lambert plus a Phong highlight, two-sided.
        double d[3];
        for (int c = 0; c < 3; ++c)
        {
          d[c] = v.Perspective ? v.D[c] + i * v.U[c] + j * v.V[c] : v.D[c];
        }
        vtkMath::Normalize(d);
        const float* nf = nrm + 3 * k;
        const double lambert = std::fabs(nf[0] * d[0] + nf[1] * d[1] + nf[2] * d[2]);
        // (lambert^30 by squaring: a few multiplications instead of pow's logarithm)
        const double l2 = lambert * lambert, l4 = l2 * l2, l8 = l4 * l4, l16 = l8 * l8;
        const double value = 0.12 + 0.68 * lambert + 0.2 * (l16 * l8 * l4 * l2);
        const unsigned char c = static_cast<unsigned char>(std::min(255.0, 255.0 * value));
        rgbOut[0] = c;
        rgbOut[1] = c;
        rgbOut[2] = static_cast<unsigned char>(std::min(255, c + 12));
      }
    }
  });
  image->GetPointData()->SetScalars(rgb);
  image->GetPointData()->AddArray(depth);
}

void vtkPiRayCaster::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PiSurface: " << this->PiSurface << "\n";
  os << indent << "ViewMode: " << this->ViewMode << "\n";
  os << indent << "Resolution: " << this->Resolution[0] << " x " << this->Resolution[1] << "\n";
  os << indent << "AllHits: " << this->AllHits << "\n";
  os << indent << "Bounds: (" << this->Bounds[0] << ", " << this->Bounds[1] << ", "
     << this->Bounds[2] << ", " << this->Bounds[3] << ", " << this->Bounds[4] << ", "
     << this->Bounds[5] << ")\n";
  os << indent << "CameraPosition: (" << this->CameraPosition[0] << ", "
     << this->CameraPosition[1] << ", " << this->CameraPosition[2] << ")\n";
  os << indent << "CameraFocalPoint: (" << this->CameraFocalPoint[0] << ", "
     << this->CameraFocalPoint[1] << ", " << this->CameraFocalPoint[2] << ")\n";
  os << indent << "CameraViewUp: (" << this->CameraViewUp[0] << ", " << this->CameraViewUp[1]
     << ", " << this->CameraViewUp[2] << ")\n";
  os << indent << "ViewAngle: " << this->ViewAngle << "\n";
  os << indent << "ParallelProjection: " << this->ParallelProjection << "\n";
  os << indent << "ParallelScale: " << this->ParallelScale << "\n";
  os << indent << "SingularTolerance: " << this->SingularTolerance << "\n";
  os << indent << "SkipEmptySpace: " << this->SkipEmptySpace << "\n";
}
