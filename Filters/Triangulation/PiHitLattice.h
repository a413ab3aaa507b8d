// SPDX-License-Identifier: BSD-3-Clause
// RAY_LATTICE, pass 1: the hits of every lattice line sorted along it, the roots the
// first-hit views hide cast with the certified root finder and added as computed
// points, and a root seen from both ends of a line kept once.
#ifndef PiHitLattice_h
#define PiHitLattice_h

#include "PiLattice.h"
#include "PiTiming.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace pisurf
{
namespace triangulator
{

// The samples of every lattice line, sorted along it; a duplicate is marked removed in
// place, so a line stays sorted.
struct LatticeLines
{
  pisurf::Buffer<vtkIdType> Start; // line l holds Line[Start[l] .. Start[l + 1])
  std::unique_ptr<Sample[]> Line;

  const Sample* Begin(vtkIdType l) const { return this->Line.get() + this->Start[l]; }
  const Sample* End(vtkIdType l) const { return this->Line.get() + this->Start[l + 1]; }

  // The valid samples of line l with X in [x0, x1), and the first non-tangent one.
  const Sample* FirstCrossing(vtkIdType l, double x0, double x1) const
  {
    const Sample* b = this->Begin(l);
    const Sample* e = this->End(l);
    const Sample* s = std::lower_bound(b, e, Sample::Lowest(x0));
    for (; s != e && s->X < x1; ++s)
    {
      if (!s->Removed() && !s->Tangent())
      {
        return s;
      }
    }
    return nullptr;
  }
};

// Reads T.C and T.Views, appends the hidden roots to T.Points (keys −(index + 1)), and
// leaves the merged lines in Lines().
class HitLattice
{
public:
  HitLattice(Triangulation& t, const Lattice& l);
  // false (T.Abort set): canceled, or first-hit views hide roots and there is no model.
  bool Run(pisurf::PassTimer& lap);
  const LatticeLines& Lines() const { return this->Out; }

private:
  void FillLines();
  void FindHiddenParts();
  void PrepareGrids();
  void CastHidden(vtkIdType begin, vtkIdType end);
  void GatherHidden();
  void MergeLines(vtkIdType lb, vtkIdType le);

  Triangulation& T;
  const Lattice& L;
  const double Tol;
  const vtkIdType LineCount;

  // first[l]: where the samples of line l start (first[lines]: their number). It counts
  // each line's hits, becomes by the sums the end of each line, and the fill (from each
  // end backwards) leaves it at each line's start.
  std::unique_ptr<std::atomic<vtkIdType>[]> First;
  std::unique_ptr<Sample[]> Samples;
  bool AllHits[3] = { false, false, false }, Minus[3] = { false, false, false },
       Plus[3] = { false, false, false };
  // The hidden roots: their number per line, and the roots themselves per range of
  // lines that one call of CastHidden casts (in line order).
  std::unique_ptr<std::int32_t[]> HiddenCount;
  struct HiddenRange
  {
    vtkIdType Begin;
    std::vector<Sample> Roots;
  };
  std::vector<HiddenRange> HiddenRanges;
  std::mutex HiddenMutex;
  std::atomic<bool> MissingModel{ false };
  std::unique_ptr<pisurf::RayGrid> Grids[3];
  int LineView[3] = { -1, -1, -1 };
  pisurf::Buffer<vtkIdType> HiddenStart;
  std::unique_ptr<Sample[]> Hidden;
  size_t Base = 0;
  LatticeLines Out;
};

} // namespace triangulator
} // namespace pisurf

#endif
