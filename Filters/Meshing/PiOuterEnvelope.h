// SPDX-License-Identifier: BSD-3-Clause
// PASS 4 of the mesher (OuterEnvelope): the points connected to the boundary of the
// grid through points of the outside sign, by a flood fill over the blocks (skipped
// blocks whole, active blocks as row bit masks), threaded in rounds and, for pieces
// meshing together, continued across the planes their slabs share.
#ifndef PiOuterEnvelope_h
#define PiOuterEnvelope_h

#include "PiBlockGrid.h"
#include "PiBuffer.h"
#include "PiField.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace pisurf
{
class PassTimer;
}

namespace pisurf
{
class PieceExchange;

// The outer envelope: which points are connected to the boundary of the grid through
// points of the outside sign ("free" points). Skipped blocks are handled whole; in an
// active block each point row along x is a bit mask (bit i: point i), the block's free
// points and the reached ones, so a block floods in a few sweeps of bit operations.
// Blocks share their face points: a block that reaches points on a face hands them to
// the neighbour across it, and the flood goes block by block until nothing changes.
class OuterEnvelope
{
public:
  static constexpr int Rows = BlockPoints * BlockPoints; // row (j, k) at k·9 + j

  /// PASS 4: the envelope of g's sampled signs, flooded from the boundary of the grid.
  /// The outside sign is the sign of F on most of the grid's boundary. With `exchange`
  /// (piece slab.Piece of slab.Pieces meshing together), each piece floods its slab and
  /// the pieces then flood on across their shared planes; without it, slab.SlabOnly
  /// still restricts the outside sign's count to the slab. `free` and `reached` are
  /// the envelope's work arrays (kept between executions). Where `field` can mark
  /// points off the outer side (Field::HasOffOuterSide), the flood does not pass them.
  static std::unique_ptr<OuterEnvelope> Build(const BlockGrid& g, const PieceSlab& slab,
    const Field& field, PieceExchange* exchange, Buffer<std::uint16_t>& free,
    Buffer<std::uint16_t>& reached, pisurf::PassTimer& lap);

  // `field` (may be null) marks points of bounded positive components, which the flood
  // fill does not pass (see pisurf::Field::OffOuterSide).
  // `free` and `reached`: its work arrays (the mesher keeps them between executions).
  OuterEnvelope(const BlockGrid& g, int outside, const pisurf::Field* field,
    pisurf::Buffer<std::uint16_t>& free, pisurf::Buffer<std::uint16_t>& reached);

  // The flood fill from the boundary, in rounds: each round processes the blocks the
  // last one reached (in parallel), each followed by up to 64 blocks it reaches
  // (depth first), and queues the rest of what it reaches for the next. A block's
  // reached rows only gain bits, by atomic ORs (several blocks may add to one
  // neighbour at once, and it may be flooding itself meanwhile), and a block that gains
  // any is queued for the next round: the rounds end at the fixed point, the set of free
  // points connected to the boundary, whatever the order (the same result as a serial
  // flood).
  void Flood();

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
  int FloodAcrossPieces(PieceExchange& exchange, int piece, int pieces);

  // The blocks of layer `ghost` (the layer above a piece's slab: contoured only to number
  // the vertices on the plane it shares with the slab) take the slab's reached points on
  // that plane, their bottom one. (Their other points stay unreached: no triangle of the
  // piece uses them.)
  void CopyTopPlaneTo(int ghost);

private:
  // Message tags of FloodAcrossPieces.
  static constexpr int PlaneUpTag = 924101;
  static constexpr int PlaneDownTag = 924102;

  // Flood's rounds from `frontier` to the fixed point.
  void Run(std::vector<vtkIdType>& frontier);

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
    const BlockGrid& g = this->G;
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
  void ReadPlane(int layer, bool topPlane, std::vector<unsigned char>& plane) const;

  // Adds the points set in `plane` (ReadPlane's layout) to the blocks of layer `layer`
  // on its bottom (or top) plane, queueing in `frontier` each block that gains any.
  void SeedPlane(int layer, bool topPlane, const std::vector<unsigned char>& plane,
    std::vector<vtkIdType>& frontier);

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
  static unsigned PointMask(int lo, int hi) { return ((1u << (hi + 1)) - 1u) & ~((1u << lo) - 1u); }

  // A row of reached bits, read and grown atomically (Flood's rounds are parallel).
  static unsigned LoadRow(const std::uint16_t* row)
  {
    return __atomic_load_n(row, __ATOMIC_RELAXED);
  }
  // Adds `bits` (not 0) to the row; true if any was not there yet.
  static bool AddToRow(std::uint16_t* row, unsigned bits)
  {
    const unsigned old = __atomic_fetch_or(row, static_cast<std::uint16_t>(bits), __ATOMIC_RELAXED);
    return (bits & ~old) != 0u;
  }

  // Queues blocks for the next round of the flood, each once per round.
  struct Pusher
  {
    OuterEnvelope* Self;
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
      __atomic_compare_exchange_n(
        &this->BlockState[b], &expected, ReachedBlock, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED))
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
      this->G.ForEachNeighbour(c,
        [&](vtkIdType nb, const int d[3])
        {
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
  bool PassFace(
    const std::uint16_t* reached, int a, int plane, const int n[3], int slot, int target)
  {
    const std::uint16_t* fr = this->Free.GetPointer() + size_t(slot) * Rows;
    std::uint16_t* rr = this->Reached.GetPointer() + size_t(slot) * Rows;
    bool added = false;
    auto pass = [&](unsigned in, int to)
    {
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
    auto pass = [&](unsigned from, int to)
    {
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

  const BlockGrid& G;
  int Outside;
  std::vector<char> BlockState;           // skipped blocks: FreeBlock, ReachedBlock or 0
  pisurf::Buffer<std::uint16_t>& Free;    // per active block: Rows masks each
  pisurf::Buffer<std::uint16_t>& Reached; // (the same)
  std::vector<char> Queued;               // per block: queued for the flood's next round
  int FloodBegin = 0, FloodEnd = 1 << 30; // the block layers flooded
};
}

#endif
