// SPDX-License-Identifier: BSD-3-Clause
// The empty-space skipping pass of vtkPiRayCaster: per view, the depth ranges of each
// leaf column of rays that may hold roots, from an octree of boxes over the rays that
// the product's enclosures classify (RayTileOctree). The rays search only there.
#ifndef PiRaySkipping_h
#define PiRaySkipping_h

#include "PiRayView.h"

#include <iosfwd>
#include <utility>
#include <vector>

namespace pisurf
{
class ProductKernel;

// Empty-space skipping for axis views and perspective cameras, an octree over each
// view's rays: a node is a square of 2^k × 2^k pixels and a depth range, whose rays lie
// in the bounding box of its corner rays at both depths. Where the kernel's enclosure
// (ProductKernel::ClassifyBox) says F > 0 or F < 0 on the whole box, no ray of the node
// has a root in that depth range. Tiles of RayTileSize pixels are first cut along the
// depth into boxes about as deep as they are wide; an undecided box is split into eight
// children (two pixel halves per image axis, two depth halves), down to squares of
// RayLeafSize pixels. In an axis view the children are the box's octants, classified at
// once from one Taylor expansion per factor (ClassifyBoxAndOctants), and a leaf is an
// undecided octant, not classified again; a camera's children are classified one by
// one (the octants of an oblique box are not their boxes). Each leaf column keeps the
// depth ranges of its undecided leaves, merged where they touch and F's monotony along
// the rays is the same (RayDepthRange::Monotone), in increasing depth: its rays search only
// there (the first hit stops at the first range holding a root), and a column with none
// casts nothing. Touching ranges of different monotony stay apart but joined
// (RayDepthRange::Joined): a ray searches such a run as one segment cut between them, each
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
constexpr int RayTileSize = 128;
constexpr int RayLeafSize = 8;

struct RayDepthRange
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
  // RaySkipping::MergeColumns), and a ray searches them as one segment cut in two.
  bool Joined;
};

// Per view: the leaf columns' depth ranges (CSR by column, row-major over columns).
struct RayViewSkipping
{
  bool Active = false;      // false: every ray searches its whole segment
  int Columns = 0;          // leaf columns per image row of columns
  std::vector<int> Offsets; // Columns·rows of columns + 1
  std::vector<RayDepthRange> Ranges;
};

class RaySkipping
{
public:
  /// Per view, the depth ranges of the leaf columns of rows [rowBegin, rowEnd) (a view
  /// that is not skipped stays inactive). `kernel` must be polynomial.
  static void Build(const ProductKernel& kernel, const std::vector<RayView>& views,
    const double bounds[6], int rowBegin, int rowEnd, bool allHits,
    std::vector<RayViewSkipping>& skipping);

  /// How many depth ranges the rays search, and how many of them are monotone.
  static void PrintCounts(const std::vector<RayViewSkipping>& skipping, std::ostream& os);

private:
  // The depths [s0, s1] where the view's rays can meet the bounds, and the world axis of
  // an axis view's depth (−1 for a camera); false when no ray can.
  static bool DepthExtent(const RayView& v, const double b[6], double& s0, double& s1, int& axis);
  // Per tile of rows [rowBegin, rowEnd), its columns' ranges (CSR by column in the tile).
  static void Tiles(const ProductKernel& kernel, const RayView& v, int axis, double s0, double s1,
    int rowBegin, int rowEnd, bool allHits, std::vector<std::vector<int>>& tileOffsets,
    std::vector<std::vector<RayDepthRange>>& tileRanges);
  // A tile's leaves sorted by column (each column in increasing depth), touching ranges
  // merged: `offsets` and `ranges`, the tile's CSR.
  static void MergeColumns(const std::vector<std::pair<int, RayDepthRange>>& leaves,
    std::vector<int>& offsets, std::vector<RayDepthRange>& ranges);
  // The view's CSR over its leaf columns, gathered from its tiles'.
  static void Gather(const RayView& v, int rowBegin, int rowEnd,
    const std::vector<std::vector<int>>& tileOffsets,
    const std::vector<std::vector<RayDepthRange>>& tileRanges, RayViewSkipping& view);
};
}

#endif
