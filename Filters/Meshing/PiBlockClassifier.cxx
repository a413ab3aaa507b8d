// SPDX-License-Identifier: BSD-3-Clause
// PASS 1 of the mesher: block classification by interval enclosures (see
// vtkPiFlyingEdges.h, pass 1).
#include "PiBlockClassifier.h"

#include "PiParallel.h"
#include "PiProductKernel.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <vector>

namespace pisurf
{
namespace
{
// PASS 1: interval bounds of F over each block still undecided.
//
// With `Corners` (a field with the product's fast paths), a block whose corners (grid points) have
// F of both signs, or 0 at one, holds the surface: it is active without its enclosures, which could
// not have decided it either (the same active blocks). Each corner is evaluated once, by whichever
// block asks first (`Corners` starts at Unknown; two threads that ask at once store the same sign).
struct ClassifyBlocks
{
  const Field* F;
  BlockGrid* G;
  const std::vector<vtkIdType>* Blocks;        // the blocks to classify
  std::atomic<signed char>* Corners = nullptr; // per corner of the block lattice
  static constexpr signed char Unknown = 2;

  // The sign of F at corner (x, y, z) of the block lattice: grid point
  // min(8·x, dims − 1) along each axis, the corner of the blocks that meet there.
  int CornerSign(const int corner[3]) const
  {
    const BlockGrid& g = *this->G;
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
      const double f = this->F->Evaluate(p);
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
      this->G->Sign[b] = static_cast<signed char>(this->ClassifyBlock(box));
    }
  }

  // A block: ClassifyBox, and where that cannot decide, its octants (enclosures
  // tighten on smaller boxes: if all eight exclude the surface, so does the block, F
  // having no zero in it and so one sign throughout).
  int ClassifyBlock(const double box[6]) const
  {
    int octants[8];
    const int sign = this->F->ClassifyBoxAndOctants(box, octants);
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
};
}

// Value 2 marks "still to classify".
void BlockClassifier::ClassifyGroups(
  const Field& field, BlockGrid& g, int classifyBegin, int classifyEnd)
{
  // (A product of polynomials classifies a group's eight octants from the same
  // expansions; an octant that holds exactly a sub-group below decides it.)
  const ProductKernel* kernel = field.GetProductKernel();
  const bool octantsToo = kernel && kernel->IsPolynomial();
  g.Sign.assign(vtkIdType(g.Count[0]) * g.Count[1] * g.Count[2], 0);
  const int group = 4;
  int groups[3];
  for (int a = 0; a < 3; ++a)
  {
    groups[a] = (g.Count[a] + group - 1) / group;
  }
  const vtkIdType groupCount = vtkIdType(groups[0]) * groups[1] * groups[2];
  // The blocks [lo, hi) take `sign`.
  auto setSigns = [&g](const int lo[3], const int hi[3], int sign)
  {
    for (int z = lo[2]; z < hi[2]; ++z)
      for (int y = lo[1]; y < hi[1]; ++y)
        for (int x = lo[0]; x < hi[0]; ++x)
        {
          g.Sign[g.BlockId(x, y, z)] = static_cast<signed char>(sign);
        }
  };
  // Whether `inner` lies within octant o of `outer` (as OctantBox cuts it).
  auto insideOctant = [](const double inner[6], const double outer[6], int o)
  {
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
  pisurf::ParallelFor(0, groupCount, 1,
    [&](vtkIdType begin, vtkIdType end)
    {
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
          box[2 * a + 1] = g.Origin[a] + std::min(hi[a] * BlockCells, g.Dims[a] - 1) * g.Spacing[a];
        }
        int groupOctants[8];
        const int sign = octantsToo ? kernel->ClassifyBoxAndOctants(box, groupOctants, true)
                                    : field.ClassifyBox(box);
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
          const int subSign = octantsToo ? kernel->ClassifyBoxAndOctants(sub, subOctants, true)
                                         : field.ClassifyBox(sub);
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
            if (subOctants[so] == 0 || bc[0] >= subhi[0] || bc[1] >= subhi[1] || bc[2] >= subhi[2])
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

size_t BlockClassifier::Run(const Field& field, BlockGrid& g, int classifyBegin, int classifyEnd,
  int sampleBegin, bool slabOnly)
{
  BlockClassifier::ClassifyGroups(field, g, classifyBegin, classifyEnd);
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
  ClassifyBlocks classify{ &field, &g, &undecided };
  std::unique_ptr<std::atomic<signed char>[]> corners;
  // (Only with the product's fast paths: a molecule's point evaluation costs more than
  // the enclosures of a block it would spare.)
  if (field.GetProductKernel())
  {
    const size_t lattice = size_t(g.Count[0] + 1) * (g.Count[1] + 1) * (g.Count[2] + 1);
    corners.reset(new std::atomic<signed char>[lattice]);
    for (size_t k = 0; k < lattice; ++k)
    {
      corners[k].store(ClassifyBlocks::Unknown, std::memory_order_relaxed);
    }
    classify.Corners = corners.get();
  }
  pisurf::ParallelFor(0, static_cast<vtkIdType>(undecided.size()), 16, classify);
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
  return undecided.size();
}
}
