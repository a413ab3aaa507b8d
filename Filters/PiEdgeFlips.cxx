// SPDX-License-Identifier: BSD-3-Clause
#include "PiEdgeFlips.h"
#include "PiBuffer.h"
#include "PiParallel.h"
#include "PiTiming.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace pisurf
{

namespace
{
using pisurf::Buffer;

// Half-edge h = 3·t + k of triangle t runs from its corner k to its corner k + 1.
// Id: half-edge and point ids inside; Conn: the connectivity's id type.
template <typename Id, typename Conn>
class FlipMesh
{
public:
  FlipMesh(Conn* c, vtkIdType triangles, vtkIdType points, const double* xyz, const float* n)
    : C(c)
    , T(static_cast<Id>(triangles))
    , N(static_cast<Id>(points))
    , X(xyz)
    , Normal(n)
  {
  }

  static Id Next(Id h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static Id Prev(Id h) { return h % 3 == 0 ? h + 2 : h - 1; }
  Id From(Id h) const { return static_cast<Id>(this->C[h]); }
  Id To(Id h) const { return static_cast<Id>(this->C[Next(h)]); }

  // Opposite half-edges (−1 on the boundary, at non-manifold edges and between
  // triangles of opposite orientation); returns the number of boundary edges.
  vtkIdType Build();
  // One round of flips; returns how many.
  vtkIdType Round();

private:
  double Bend(Id p, Id q) const
  {
    return pisurf::Bend(
      this->X + 3 * p, this->Normal + 3 * p, this->X + 3 * q, this->Normal + 3 * q);
  }
  // (b − a)×(c − a)
  void Cross(Id a, Id b, Id c, double out[3]) const
  {
    const double* pa = this->X + 3 * a;
    const double* pb = this->X + 3 * b;
    const double* pc = this->X + 3 * c;
    const double u[3] = { pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2] };
    const double v[3] = { pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2] };
    out[0] = u[1] * v[2] - u[2] * v[1];
    out[1] = u[2] * v[0] - u[0] * v[2];
    out[2] = u[0] * v[1] - u[1] * v[0];
  }
  // (b − a)×(c − a)·w
  double Facing(Id a, Id b, Id c, const double w[3]) const
  {
    double n[3];
    this->Cross(a, b, c, n);
    return n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
  }
  void NormalSum(Id a, Id b, Id c, double out[3]) const
  {
    for (int k = 0; k < 3; ++k)
    {
      out[k] = double(this->Normal[3 * a + k]) + this->Normal[3 * b + k] + this->Normal[3 * c + k];
    }
  }

  // The gain of flipping the edge of h (and its opposite o): 0 if not allowed.
  float Gain(Id h, Id o) const
  {
    const Id x = this->From(h), y = this->To(h), c = this->From(Prev(h)), d = this->From(Prev(o));
    if (c == d || c == x || c == y || d == x || d == y)
    {
      return 0;
    }
    const double gain = this->Bend(x, y) - this->Bend(c, d);
    if (!(gain > 0))
    {
      return 0;
    }
    // Convex quad: the new triangles (x, d, c) and (d, y, c) face the old quad's way and
    // agree with their vertices' normals.
    double n1[3], n2[3], quad[3], w[3];
    this->Cross(x, y, c, n1);
    this->Cross(y, x, d, n2);
    for (int k = 0; k < 3; ++k)
    {
      quad[k] = n1[k] + n2[k];
    }
    if (!(this->Facing(x, d, c, quad) > 0) || !(this->Facing(d, y, c, quad) > 0))
    {
      return 0;
    }
    this->NormalSum(x, d, c, w);
    if (!(this->Facing(x, d, c, w) > 0))
    {
      return 0;
    }
    this->NormalSum(d, y, c, w);
    if (!(this->Facing(d, y, c, w) > 0))
    {
      return 0;
    }
    return static_cast<float>(gain);
  }

  // The neighbours of From(h0), h0 leaving it, into out[0, count); false if the fan of
  // triangles around it does not close up (a boundary, or a non-manifold edge whose
  // other wedges this walk would not see) or has more than RingMax neighbours.
  static constexpr int RingMax = 48;
  bool Ring(Id h0, Id* out, int& count) const
  {
    count = 0;
    for (Id h = h0;;)
    {
      out[count++] = this->To(h);
      const Id o = this->Opp[Prev(h)];
      if (o < 0 || count >= RingMax)
      {
        return false;
      }
      h = o;
      if (h == h0)
      {
        return true;
      }
    }
  }

  // Whether the flip of h (opposite o) keeps the mesh manifold: c and d have closed
  // fans, c–d is no edge yet and x and y are the only common neighbours of c and d.
  bool KeepsManifold(Id h, Id o) const
  {
    const Id x = this->From(h), y = this->To(h), d = this->From(Prev(o));
    Id rc[RingMax], rd[RingMax];
    int nc, nd;
    if (!this->Ring(Prev(h), rc, nc) || !this->Ring(Prev(o), rd, nd))
    {
      return false;
    }
    for (int i = 0; i < nc; ++i)
    {
      const Id u = rc[i];
      if (u == d)
      {
        return false;
      }
      if (u != x && u != y && std::find(rd, rd + nd, u) != rd + nd)
      {
        return false;
      }
    }
    return true;
  }

  // Whether the edge of half-edge s (key: its pair's lower half-edge) has the largest
  // gain of the triangle of s (ties: the lower key wins).
  bool IsBest(Id s, Id key) const
  {
    const float g = this->Gains[s];
    for (Id h = 3 * (s / 3); h < 3 * (s / 3) + 3; ++h)
    {
      if (h == s)
      {
        continue;
      }
      const float other = this->Gains[h];
      if (other > g || (other == g && std::min(h, this->Opp[h]) < key))
      {
        return false;
      }
    }
    return true;
  }

  // No triangle flipped (RecH, RecO all −1), in parallel.
  void ClearRecords()
  {
    vtkSMPTools::For(0, this->T,
      [&](vtkIdType b, vtkIdType e)
      {
        std::fill(&this->RecH[b], &this->RecH[b] + (e - b), Id(-1));
        std::fill(&this->RecO[b], &this->RecO[b] + (e - b), Id(-1));
      });
  }

  // Where half-edge q of a flipped triangle is after the round's flips (q is not the
  // flipped edge itself: that one is only its own partner's partner).
  Id Moved(Id q) const
  {
    const Id H = this->RecH[q / 3], O = this->RecO[q / 3];
    const Id t1 = H / 3, t2 = O / 3;
    return q == Next(H) ? 3 * t2 + 1
      : q == Prev(H)    ? 3 * t1 + 2
      : q == Next(O)    ? 3 * t1
                        : 3 * t2; // Prev(O)
  }

  Conn* C;
  Id T, N;
  const double* X;
  const float* Normal;
  Buffer<Id> Opp;
  Buffer<float> Gains;
  Buffer<Id> RecH, RecO; // per triangle flipped this round: the flip's two half-edges
};

template <typename Id, typename Conn>
vtkIdType FlipMesh<Id, Conn>::Build()
{
  // Half-edges gathered by their lower vertex (CSR). Each thread owns a range of lower
  // vertices and reads the triangles (sequentially) to gather its own, skipping the
  // blocks of triangles whose vertex ids all lie outside its range: meshes whose points
  // are numbered in the order the triangles use them (the triangulator's) have narrow
  // blocks, and each thread reads about its share only.
  const Id parts = std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads());
  const Id n = this->N, h3 = 3 * this->T;
  constexpr Id BlockSize = 4096; // triangles
  const Id blocks = (this->T + BlockSize - 1) / BlockSize;
  std::vector<Id> blockLow(blocks), blockHigh(blocks);
  vtkSMPTools::For(0, blocks,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType k = b; k < e; ++k)
      {
        const Id h0 = static_cast<Id>(std::int64_t(3) * BlockSize * k);
        const Id h1 =
          static_cast<Id>(std::min<std::int64_t>(h3, std::int64_t(3) * BlockSize * (k + 1)));
        Id low = std::numeric_limits<Id>::max(), high = std::numeric_limits<Id>::min();
        for (Id h = h0; h < h1; ++h)
        {
          low = std::min(low, static_cast<Id>(this->C[h]));
          high = std::max(high, static_cast<Id>(this->C[h]));
        }
        blockLow[k] = low;
        blockHigh[k] = high;
      }
    });
  auto forEachOfPart = [&](Id part, auto&& visit)
  {
    const Id lo = static_cast<Id>(std::int64_t(n) * part / parts);
    const Id hi = static_cast<Id>(std::int64_t(n) * (part + 1) / parts);
    for (Id block = 0; block < blocks; ++block)
    {
      if (blockHigh[block] < lo || blockLow[block] >= hi)
      {
        continue; // (an edge's lower vertex is one of the block's ids)
      }
      const Id h1 =
        static_cast<Id>(std::min<std::int64_t>(h3, std::int64_t(3) * BlockSize * (block + 1)));
      for (Id h = static_cast<Id>(std::int64_t(3) * BlockSize * block); h < h1; h += 3)
      {
        for (Id k = 0; k < 3; ++k)
        {
          const Id a = static_cast<Id>(this->C[h + k]);
          const Id b = static_cast<Id>(this->C[h + (k == 2 ? 0 : k + 1)]);
          const Id low = std::min(a, b);
          if (low >= lo && low < hi)
          {
            visit(low, std::max(a, b), h + k);
          }
        }
      }
    }
  };
  std::vector<Id> start(n + 1, 0);
  ParallelFor(0, parts, 1,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType part = b; part < e; ++part)
      {
        forEachOfPart(static_cast<Id>(part), [&](Id low, Id, Id) { ++start[low + 1]; });
      }
    });
  for (Id k = 0; k < n; ++k)
  {
    start[k + 1] += start[k];
  }
  // (not initialized on allocation: the fill below writes every one)
  std::unique_ptr<Id[]> entries(new Id[h3]);
  ParallelFor(0, parts, 1,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType part = b; part < e; ++part)
      {
        const Id lo = static_cast<Id>(std::int64_t(n) * part / parts);
        const Id hi = static_cast<Id>(std::int64_t(n) * (part + 1) / parts);
        std::vector<Id> fill(start.begin() + lo, start.begin() + hi);
        forEachOfPart(
          static_cast<Id>(part), [&](Id low, Id, Id h) { entries[fill[low - lo]++] = h; });
      }
    });
  // Every half-edge is in one vertex's entries: its opposite (or −1) is written there.
  // The half-edges of a vertex that share their upper vertex are one edge: paired when
  // there are two of opposite orientation, a boundary edge when alone.
  this->Opp.Allocate(h3);
  std::atomic<vtkIdType> boundary{ 0 };
  vtkSMPTools::For(0, n,
    [&](vtkIdType b, vtkIdType e)
    {
      vtkIdType count = 0;
      std::vector<Id> upper;
      std::vector<unsigned char> grouped;
      for (vtkIdType v = b; v < e; ++v)
      {
        const Id* half = entries.get() + start[v];
        const Id k = start[v + 1] - start[v];
        upper.resize(k);
        grouped.assign(k, 0);
        for (Id i = 0; i < k; ++i)
        {
          upper[i] = std::max(this->From(half[i]), this->To(half[i]));
          this->Opp[half[i]] = -1;
        }
        for (Id i = 0; i < k; ++i)
        {
          if (grouped[i])
          {
            continue;
          }
          Id size = 1, other = -1;
          for (Id j = i + 1; j < k; ++j)
          {
            if (upper[j] == upper[i])
            {
              grouped[j] = 1;
              other = j;
              ++size;
            }
          }
          if (size == 1)
          {
            ++count;
          }
          else if (size == 2)
          {
            const Id h1 = half[i], h2 = half[other];
            if (this->From(h1) == this->To(h2) && this->To(h1) == this->From(h2))
            {
              this->Opp[h1] = h2;
              this->Opp[h2] = h1;
            }
          }
        }
      }
      boundary += count;
    });
  return boundary;
}

template <typename Id, typename Conn>
vtkIdType FlipMesh<Id, Conn>::Round()
{
  const Id h3 = 3 * this->T;
  PassTimer lap("PiFlipEdgesToCurvature");
  // The gain of every edge, written by its lower half-edge into both. After the first
  // round only the edges of the triangles flipped last round change (a gain depends on
  // the edge's two triangles only); an edge between two of them is computed by its
  // lower half-edge.
  if (this->Gains.Empty())
  {
    this->Gains.Allocate(h3);
    this->RecH.Allocate(this->T);
    this->RecO.Allocate(this->T);
    this->ClearRecords();
    vtkSMPTools::For(0, h3,
      [&](vtkIdType b, vtkIdType e)
      {
        for (Id h = static_cast<Id>(b); h < static_cast<Id>(e); ++h)
        {
          const Id o = this->Opp[h];
          if (o < 0)
          {
            this->Gains[h] = 0;
          }
          else if (h < o)
          {
            this->Gains[h] = this->Gains[o] = this->Gain(h, o);
          }
        }
      });
  }
  else
  {
    vtkSMPTools::For(0, this->T,
      [&](vtkIdType b, vtkIdType e)
      {
        for (Id t = static_cast<Id>(b); t < static_cast<Id>(e); ++t)
        {
          if (this->RecH[t] < 0)
          {
            continue;
          }
          for (Id h = 3 * t; h < 3 * t + 3; ++h)
          {
            const Id o = this->Opp[h];
            if (o < 0)
            {
              this->Gains[h] = 0;
            }
            else if (h < o || this->RecH[o / 3] < 0)
            {
              this->Gains[h] = this->Gains[o] = this->Gain(h, o);
            }
          }
        }
      });
    this->ClearRecords();
  }
  lap("gains");
  // The flips: edges that are the best of both their triangles (so each triangle is in
  // one flip at most) and keep the mesh manifold, checked on the mesh before the round.
  std::atomic<vtkIdType> flips{ 0 };
  vtkSMPTools::For(0, h3,
    [&](vtkIdType b, vtkIdType e)
    {
      vtkIdType count = 0;
      for (Id h = static_cast<Id>(b); h < static_cast<Id>(e); ++h)
      {
        const Id o = this->Opp[h];
        if (o > h && this->Gains[h] > 0 && this->IsBest(h, h) && this->IsBest(o, h) &&
          this->KeepsManifold(h, o))
        {
          this->RecH[h / 3] = this->RecH[o / 3] = h;
          this->RecO[h / 3] = this->RecO[o / 3] = o;
          ++count;
        }
      }
      flips += count;
    });
  lap("chosen");
  if (flips == 0)
  {
    return 0;
  }
  // (x, y, c) and (y, x, d) become (x, d, c) and (d, y, c); the outer half-edges move to
  // their new slots and their partners follow (written here when the partner's
  // triangle is not flipped itself, else by its own flip).
  vtkSMPTools::For(0, this->T,
    [&](vtkIdType b, vtkIdType e)
    {
      for (Id t1 = static_cast<Id>(b); t1 < static_cast<Id>(e); ++t1)
      {
        const Id H = this->RecH[t1], O = this->RecO[t1];
        if (H < 0 || H / 3 != t1)
        {
          continue;
        }
        const Id t2 = O / 3;
        const Id x = this->From(H), y = this->To(H), c = this->From(Prev(H)),
                 d = this->From(Prev(O));
        const Id outer[4] = { Next(H), Prev(H), Next(O), Prev(O) };
        const Id slot[4] = { 3 * t2 + 1, 3 * t1 + 2, 3 * t1, 3 * t2 };
        Id partner[4];
        for (int k = 0; k < 4; ++k)
        {
          partner[k] = this->Opp[outer[k]];
        }
        this->C[3 * t1] = x;
        this->C[3 * t1 + 1] = d;
        this->C[3 * t1 + 2] = c;
        this->C[3 * t2] = d;
        this->C[3 * t2 + 1] = y;
        this->C[3 * t2 + 2] = c;
        for (int k = 0; k < 4; ++k)
        {
          const Id p = partner[k];
          if (p < 0)
          {
            this->Opp[slot[k]] = -1;
            continue;
          }
          const bool partnerFlipped = this->RecH[p / 3] >= 0;
          this->Opp[slot[k]] = partnerFlipped ? this->Moved(p) : p;
          if (!partnerFlipped)
          {
            this->Opp[p] = slot[k];
          }
        }
        this->Opp[3 * t1 + 1] = 3 * t2 + 2;
        this->Opp[3 * t2 + 2] = 3 * t1 + 1;
      }
    });
  lap("applied");
  return flips;
}

template <typename Id, typename Conn>
EdgeFlipResult Run(Conn* connectivity, vtkIdType triangles, vtkIdType points, const double* xyz,
  const float* normals, int rounds)
{
  EdgeFlipResult result;
  FlipMesh<Id, Conn> mesh(connectivity, triangles, points, xyz, normals);
  PassTimer lap("PiFlipEdgesToCurvature");
  result.BoundaryEdges = mesh.Build();
  lap("build");
  for (int r = 0; r < rounds; ++r)
  {
    const vtkIdType flips = mesh.Round();
    if (flips == 0)
    {
      break;
    }
    result.Flips += flips;
    ++result.Rounds;
  }
  return result;
}

}

bool FitsInt32Cells(vtkIdType triangles, vtkIdType points)
{
  return 3 * triangles < std::numeric_limits<std::int32_t>::max() &&
    points < std::numeric_limits<std::int32_t>::max();
}

EdgeFlipResult FlipEdgesToCurvature(vtkIdType* connectivity, vtkIdType triangles, vtkIdType points,
  const double* xyz, const float* normals, int rounds)
{
  // 32-bit half-edge ids when they fit: half the memory traffic.
  if (FitsInt32Cells(triangles, points))
  {
    return Run<std::int32_t>(connectivity, triangles, points, xyz, normals, rounds);
  }
  return Run<std::int64_t>(connectivity, triangles, points, xyz, normals, rounds);
}

EdgeFlipResult FlipEdgesToCurvature(std::int32_t* connectivity, vtkIdType triangles,
  vtkIdType points, const double* xyz, const float* normals, int rounds)
{
  if (FitsInt32Cells(triangles, points))
  {
    return Run<std::int32_t>(connectivity, triangles, points, xyz, normals, rounds);
  }
  return Run<std::int64_t>(connectivity, triangles, points, xyz, normals, rounds);
}
}
