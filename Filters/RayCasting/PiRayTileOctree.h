// SPDX-License-Identifier: BSD-3-Clause
// The octree of vtkPiRayCaster's empty-space skipping over one tile of a view's rays:
// its boxes classified by the product's enclosures, front to back, and the undecided
// leaves it keeps (see PiRaySkipping.h).
#ifndef PiRayTileOctree_h
#define PiRayTileOctree_h

#include "PiProductKernel.h"
#include "PiRaySkipping.h"

#include "vtkType.h"

#include <algorithm>
#include <iterator>
#include <limits>
#include <utility>
#include <vector>

namespace pisurf
{
struct RayTileOctree
{
  const ProductKernel* Kernel;
  const RayView* V;
  // Axis views: the world axes of the depth, of i and of j (their boxes' octants are
  // their children). Camera views: Axis = −1 (each child's box is classified itself).
  int Axis, U, W;
  double PixelSize;     // the larger of the pixel's two world sizes (at depth 1)
  int RowBegin, RowEnd; // the image rows this piece casts
  // The tile's undecided leaves as (column in the tile, range), in visiting order.
  std::vector<std::pair<int, RayDepthRange>> Leaves;
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
  signed char FirstSign[(RayTileSize / RayLeafSize) * (RayTileSize / RayLeafSize)];
  double Cut[(RayTileSize / RayLeafSize) * (RayTileSize / RayLeafSize)];

  void ResetCuts()
  {
    std::fill(std::begin(this->FirstSign), std::end(this->FirstSign), 0);
    std::fill(std::begin(this->Cut), std::end(this->Cut), std::numeric_limits<double>::infinity());
  }

  // Calls visit(c) for each leaf column c of the tile that the node's pixels cover.
  template <class Visit>
  bool AllColumns(int i0, int j0, int size, Visit&& visit) const
  {
    const int per = RayTileSize / RayLeafSize;
    const int ci0 = (i0 - this->TileI) / RayLeafSize, cj0 = (j0 - this->TileJ) / RayLeafSize;
    const int n = std::max(1, size / RayLeafSize);
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
    this->AllColumns(i0, j0, size,
      [&](int c)
      {
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
    const RayView& v = *this->V;
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
    const RayView& v = *this->V;
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
      if (size <= RayLeafSize)
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
            this->Visit(
              i0 + ih * half, j0 + jh * half, half, front ? ta : mid, front ? mid : tb, level);
          }
        }
      }
      return;
    }
    if (size <= RayLeafSize)
    {
      this->AddLeaf(i0, j0, ta, tb, monotone);
      return;
    }
    // (children that are leaves: which of them F is monotone on along the rays)
    int octants[8], monotony[8];
    const bool leaves = half <= RayLeafSize;
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
    const int column = ((j0 - this->TileJ) / RayLeafSize) * (RayTileSize / RayLeafSize) +
      (i0 - this->TileI) / RayLeafSize;
    if (this->FirstHit && this->Cut[column] <= ta)
    {
      return;
    }
    this->Leaves.push_back({ column, { ta, tb, monotone, false } });
  }
};
}

#endif
