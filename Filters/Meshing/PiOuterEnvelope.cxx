// SPDX-License-Identifier: BSD-3-Clause
// PASS 4 of the mesher: the outer envelope's flood fill (see PiOuterEnvelope.h).
#include "PiOuterEnvelope.h"

#include "PiParallel.h"
#include "PiPieceExchange.h"
#include "PiTiming.h"
#include "vtkSMPThreadLocal.h"

#include <algorithm>
#include <iostream>

namespace pisurf
{
namespace
{
// The outside sign: the sign of F on most of the boundary of the grid.
int OutsideSign(const BlockGrid& g, const PieceSlab& slab, PieceExchange* exchange)
{
  const bool slabOnly = slab.SlabOnly;
  const int slabBegin = slab.SlabBegin, slabEnd = slab.SlabEnd;
  const bool distributed = exchange != nullptr;
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
    exchange->Sum(mine, sum, 2);
    positive = sum[0];
    total = sum[1];
  }
  return 2 * positive >= total ? 1 : -1;
}
}

std::unique_ptr<OuterEnvelope> OuterEnvelope::Build(const BlockGrid& g, const PieceSlab& slab,
  const Field& field, PieceExchange* exchange, Buffer<std::uint16_t>& free,
  Buffer<std::uint16_t>& reached, pisurf::PassTimer& lap)
{
  const bool distributed = exchange != nullptr;
  const int slabBegin = slab.SlabBegin, slabEnd = slab.SlabEnd;
  std::unique_ptr<OuterEnvelope> envelope(new OuterEnvelope(
    g, OutsideSign(g, slab, exchange), field.HasOffOuterSide() ? &field : nullptr, free, reached));
  lap("envelope states");
  if (distributed)
  {
    envelope->SetFloodLayers(slabBegin, slabEnd);
  }
  envelope->Flood();
  if (distributed)
  {
    const int rounds = envelope->FloodAcrossPieces(*exchange, slab.Piece, slab.Pieces);
    if (lap.IsEnabled())
    {
      std::cerr << "piece " << slab.Piece << " of " << slab.Pieces << ": block layers " << slabBegin
                << " to " << slabEnd - 1 << " of " << g.Count[2]
                << ", the envelope flooded with the other pieces in " << rounds << " rounds\n";
    }
    if (slabBegin < slabEnd && slabEnd < g.Count[2])
    {
      envelope->CopyTopPlaneTo(slabEnd);
    }
  }
  return envelope;
}

OuterEnvelope::OuterEnvelope(const BlockGrid& g, int outside, const pisurf::Field* field,
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
  const BlockGrid* grid = &this->G;
  pisurf::ParallelFor(0, static_cast<vtkIdType>(g.Sign.size()), 0,
    [=](vtkIdType begin, vtkIdType end)
    {
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
            centre[a] =
              grid->Origin[a] + 0.5 * (grid->First(c, a) + grid->Last(c, a)) * grid->Spacing[a];
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
  pisurf::ParallelFor(0, static_cast<vtkIdType>(active), 0,
    [=](vtkIdType begin, vtkIdType end)
    {
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
          field->OffOuterSideBox(
            grid->Origin, grid->Spacing, first, last, BlockPoints, BlockPoints * BlockPoints, off);
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
          grid->ForEachNeighbour(c,
            [&](vtkIdType nb, const int d[3])
            {
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

void OuterEnvelope::Flood()
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

int OuterEnvelope::FloodAcrossPieces(PieceExchange& exchange, int piece, int pieces)
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
      exchange.Receive(fromBelow.data(), size, piece - 1, PlaneUpTag);
    }
    if (above)
    {
      exchange.Send(empty ? fromBelow.data() : top.data(), size, piece + 1, PlaneUpTag);
      exchange.Receive(fromAbove.data(), size, piece + 1, PlaneDownTag);
    }
    if (below)
    {
      exchange.Send(empty ? fromAbove.data() : bottom.data(), size, piece - 1, PlaneDownTag);
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
    const int added = frontier.empty() ? 0 : 1;
    const int anywhere = exchange.Maximum(added);
    if (!anywhere)
    {
      return round;
    }
    this->Run(frontier);
  }
}

void OuterEnvelope::CopyTopPlaneTo(int ghost)
{
  std::vector<unsigned char> plane;
  this->ReadPlane(this->FloodEnd - 1, true, plane);
  const BlockGrid& g = this->G;
  this->ForEachBlockOfLayer(ghost,
    [&](vtkIdType b, const int c[3], const int n[3])
    {
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

void OuterEnvelope::Run(std::vector<vtkIdType>& frontier)
{
  vtkSMPThreadLocal<std::vector<vtkIdType>> next;
  while (!frontier.empty())
  {
    // Blocks reached again from now on are queued for the next round.
    for (vtkIdType b : frontier)
    {
      this->Queued[b] = 0;
    }
    OuterEnvelope* self = this;
    const std::vector<vtkIdType>* blocks = &frontier;
    pisurf::ParallelFor(0, static_cast<vtkIdType>(frontier.size()), 8,
      [self, blocks, &next](vtkIdType begin, vtkIdType end)
      {
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

void OuterEnvelope::ReadPlane(int layer, bool topPlane, std::vector<unsigned char>& plane) const
{
  const BlockGrid& g = this->G;
  plane.assign(size_t(g.Dims[0]) * g.Dims[1], 0);
  this->ForEachBlockOfLayer(layer,
    [&](vtkIdType b, const int c[3], const int n[3])
    {
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

void OuterEnvelope::SeedPlane(int layer, bool topPlane, const std::vector<unsigned char>& plane,
  std::vector<vtkIdType>& frontier)
{
  const BlockGrid& g = this->G;
  Pusher push{ this, &frontier };
  this->ForEachBlockOfLayer(layer,
    [&](vtkIdType b, const int c[3], const int n[3])
    {
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
}
