// SPDX-License-Identifier: BSD-3-Clause
// The block lattice the mesher's passes share: the sample grid cut into blocks of
// BlockCells³ cells, each block's sign (skipped with a known sign, or active) and the
// active blocks' sampled values, with the index arithmetic every pass uses.
#ifndef PiBlockGrid_h
#define PiBlockGrid_h

#include "vtkType.h"

#include <algorithm>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace pisurf
{
// The grid is cut into blocks of BlockCells³ cells. A block whose interval bound
// excludes the surface is "skipped": its sign is known and nothing in it is evaluated
// or contoured. The others are "active".
constexpr int BlockCells = 8;
constexpr int BlockPoints = BlockCells + 1;
// BlockGrid::Sign of a block outside the layers a piece works on (see PieceSlab):
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

struct BlockGrid
{
  int Dims[3];
  double Origin[3];
  double Spacing[3];
  int Count[3];                  // blocks per axis
  std::vector<signed char> Sign; // per block: +1/−1 skipped with that sign, 0 active
  std::vector<int> Active;       // active block ids
  std::vector<int> Slot;         // per block: index in Active, or −1
  double* Values = nullptr;      // per active block: BlockPoints³ values of F (not owned)

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

// The block layers along z that piece Piece of Pieces works on: its slab
// [SlabBegin, SlabEnd) (every layer for one piece). With SlabOnly it classifies and
// samples only around its slab; otherwise the whole grid.
struct PieceSlab
{
  int Piece = 0, Pieces = 1;
  int SlabBegin = 0, SlabEnd = 0;
  bool SlabOnly = false;
};
}

#endif
