// SPDX-License-Identifier: BSD-3-Clause
// PASSES 5 and 6 of the mesher: marching cubes over the cells of the active blocks
// from row bit masks of the signs, each crossing edge's vertex numbered by the block
// that owns its lower end. A header: the functor runs per block inside pisurf::ParallelFor, and its
// per-row and per-cell loops stay inlined there.
#ifndef PiBlockContour_h
#define PiBlockContour_h

#include "PiBlockGrid.h"
#include "PiBuffer.h"
#include "PiMarchingCubes.h"
#include "PiOuterEnvelope.h"
#include "vtkMarchingCubesTriangleCases.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace pisurf
{
// PASS 5 and 6: marching cubes over the cells of the active blocks. Each crossing edge
// belongs to the block that holds its lower end point (half-open ranges, closed at the
// end of the grid), which numbers its vertex; triangles then find their edges' vertices
// in the owner's edge masks and row offsets. Mode Count builds the masks and counts
// both; Write then writes each block's vertices' edges and its triangles (a block's
// own edges' ids from a table it fills as it writes them, other blocks' edges from
// their masks: Count's, so the blocks need no order).
struct BlockContour
{
  enum Mode
  {
    Count,
    Write
  };
  const BlockGrid* G;
  const OuterEnvelope* Outer; // null: plain signs
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
  static int EdgeRow(int axis, int lk, int lj)
  {
    return (axis * BlockCells + lk) * BlockCells + lj;
  }
  // Where Write keeps the id of the owned edge at local lower end (li, lj, lk) on `axis`.
  static int OwnedSlot(int axis, int li, int lj, int lk)
  {
    return EdgeRow(axis, lk, lj) * BlockCells + li;
  }

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
        this->CountBlock(s, v, n, h, rows, masks, offsets);
      }
      // Write: the vertex id of each owned crossing edge, by its local lower end and
      // axis, for this block's triangles (an owned edge's id without the masks' sums).
      vtkIdType ids[3 * BlockCells * BlockCells * BlockCells];
      if (this->Pass == Write)
      {
        this->WriteVertices(s, end, v, f, rows, masks, ids);
      }
      if (c[2] < this->SlabBegin || c[2] >= this->SlabEnd)
      {
        if (this->Pass == Count)
        {
          (*this->TriangleCount)[s] = 0;
        }
        continue;
      }
      this->Triangles(s, f, n, rows, ids);
    }
  }

  // Count: the block's row signs, then its owned crossing edges, numbered in key order.
  void CountBlock(vtkIdType s, const double* v, const int n[3], const int h[3], std::uint16_t* rows,
    std::uint8_t* masks, std::uint16_t* offsets) const
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

  // Write: each owned crossing edge's vertex (its edge key, crossing parameter and end
  // values), its id kept in `ids` for the block's triangles.
  void WriteVertices(vtkIdType s, vtkIdType end, const double* v, const int f[3],
    const std::uint16_t* rows, const std::uint8_t* masks, vtkIdType* ids) const
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
            const double t =
              !(own0 && own1) ? (own0 ? 0.0 : 1.0) : (v0 == v1 ? 0.5 : v0 / (v0 - v1));
            (*this->VertexT)[vertex] = std::max(0.0, std::min(1.0, t));
            (*this->VertexEnds)[2 * vertex] = v0;
            (*this->VertexEnds)[2 * vertex + 1] = v1;
            ids[OwnedSlot(axis, li, lj, lk)] = vertex;
            ++vertex;
          }
        }
  }

  // The block's triangles (Count: how many; Write: their point ids).
  void Triangles(vtkIdType s, const int f[3], const int n[3], const std::uint16_t* rows,
    const vtkIdType* ids) const
  {
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
};
}

#endif
