// SPDX-License-Identifier: BSD-3-Clause
// RAY_LATTICE, pass 1: the samples of every lattice line. Lines are counted and filled
// by all threads, so a line's order is the threads' until the sort makes it the same
// every time.
#include "PiHitLattice.h"

#include "vtkSMPTools.h"

#include <algorithm>

namespace pisurf
{
namespace triangulator
{

HitLattice::HitLattice(Triangulation& t, const Lattice& l)
  : T(t)
  , L(l)
  , Tol(1e-9 * t.Size)
  , LineCount(l.LineStart[3])
{
}

bool HitLattice::Run(pisurf::PassTimer& lap)
{
  const vtkIdType lines = this->LineCount;
  this->FillLines();
  this->FindHiddenParts();
  lap("lines filled");
  this->HiddenCount.reset(new std::int32_t[lines]);
  this->PrepareGrids();
  pisurf::ParallelFor(
    0, lines, 2048, [&](vtkIdType begin, vtkIdType end) { this->CastHidden(begin, end); });
  lap("sorted lines, hidden parts cast");
  if (this->MissingModel)
  {
    vtkErrorWithObjectMacro(
      T.Algorithm, << "First-hit views hide part of the surface, and the input carries no "
                      "PiSurfaceModel to compute it: use all hits or keep the model field data");
    T.Abort = true;
  }
  if (T.Abort)
  {
    return false;
  }
  T.Algorithm->UpdateProgress(0.3);

  this->GatherHidden();
  // (small ranges of lines: the hidden roots, whose attributes cost most here, crowd on
  // the lines through the solid's hidden parts, and eight ranges per thread would leave
  // one thread working alone at the end)
  pisurf::ParallelFor(
    0, lines, 2048, [&](vtkIdType lb, vtkIdType le) { this->MergeLines(lb, le); });
  this->Hidden.reset();
  this->Samples.reset();
  lap("lines merged");
  return true;
}

void HitLattice::FillLines()
{
  const vtkIdType lines = this->LineCount;
  this->First.reset(new std::atomic<vtkIdType>[lines + 1]);
  auto& first = this->First;
  auto lineOf = [&](vtkIdType id)
  {
    const View& v = T.Views[T.C.ViewOf[id]];
    return L.Line(v.Axis, T.C.Pixel[2 * id] + 1, T.C.Pixel[2 * id + 1] + 1);
  };
  vtkSMPTools::For(0, lines + 1,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType l = b; l < e; ++l)
      {
        first[l].store(0, std::memory_order_relaxed);
      }
    });
  vtkSMPTools::For(0, T.C.N,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType id = b; id < e; ++id)
      {
        first[lineOf(id)].fetch_add(1, std::memory_order_relaxed);
      }
    });
  for (vtkIdType l = 1; l < lines; ++l)
  {
    first[l].store(
      first[l].load(std::memory_order_relaxed) + first[l - 1].load(std::memory_order_relaxed),
      std::memory_order_relaxed);
  }
  first[lines].store(T.C.N, std::memory_order_relaxed);
  this->Samples.reset(new Sample[T.C.N]);
  auto& samples = this->Samples;
  vtkSMPTools::For(0, T.C.N,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType id = b; id < e; ++id)
      {
        const View& v = T.Views[T.C.ViewOf[id]];
        samples[first[lineOf(id)].fetch_sub(1, std::memory_order_relaxed) - 1] = {
          T.C.P[3 * id + v.Axis], id, T.C.Tangent[id] != 0
        };
      }
    });
}

// Which part of each line the views have not seen: all-hits views see everything; a
// first-hit view looking along −a sees down to its first hit, one along +a up to its
// first hit. The hidden part is cast with the certified root finder.
void HitLattice::FindHiddenParts()
{
  for (const View& v : T.Views)
  {
    this->AllHits[v.Axis] |= v.AllHits;
    (v.Sense < 0 ? this->Minus : this->Plus)[v.Axis] = true;
  }
}

// The lines of axis a are the rays of an orthographic grid (the pixels of the views
// along a): polynomial products restrict them from one composition per axis
// (pisurf::RayGrid) instead of a trivariate restriction per line.
void HitLattice::PrepareGrids()
{
  auto& grids = this->Grids;
  if (T.Kernel && T.Kernel->IsPolynomial())
  {
    for (int a = 0; a < 3; ++a)
    {
      const int ua = (a + 1) % 3, va = (a + 2) % 3;
      double o[3], u[3] = { 0, 0, 0 }, v[3] = { 0, 0, 0 }, d[3] = { 0, 0, 0 };
      o[a] = L.B0[a];
      o[ua] = L.X(ua, 1);
      o[va] = L.X(va, 1);
      u[ua] = L.H[ua];
      v[va] = L.H[va];
      d[a] = 1;
      grids[a] = std::make_unique<pisurf::RayGrid>(
        *T.Kernel, o, u, v, d, L.N[ua], L.N[va], L.B1[a] - L.B0[a]);
    }
  }
}

void HitLattice::CastHidden(vtkIdType begin, vtkIdType end)
{
  const double tol = this->Tol;
  const auto& samples = this->Samples;
  const auto& first = this->First;
  const bool* allHits = this->AllHits;
  const bool* minus = this->Minus;
  const bool* plus = this->Plus;
  std::int32_t* hiddenCount = this->HiddenCount.get();
  std::vector<pisurf::RayRoot> roots;
  std::vector<double> row, coefficients;
  std::vector<Sample> found;
  vtkIdType rowOf = -1; // the (axis, mv) whose row coefficients `row` holds
  std::fill(hiddenCount + begin, hiddenCount + end, 0);
  for (vtkIdType l = begin; l < end && !T.Abort; ++l)
  {
    const int a = l >= L.LineStart[2] ? 2 : l >= L.LineStart[1] ? 1 : 0;
    Sample* s0 = samples.get() + first[l];
    Sample* s1 = samples.get() + first[l + 1];
    std::sort(s0, s1);
    if (allHits[a])
    {
      continue;
    }
    double lo = L.B0[a], hi = L.B1[a];
    bool empty = false;
    for (int sense = -1; sense <= 1; sense += 2)
    {
      if (!(sense < 0 ? minus : plus)[a])
      {
        continue;
      }
      // The first hit of that view on this line.
      const Sample* hit = nullptr;
      for (Sample* s = s0; s != s1; ++s)
      {
        if (T.Views[T.C.ViewOf[s->Code()]].Sense == sense)
        {
          if (!hit || (sense < 0 ? s->X > hit->X : s->X < hit->X))
          {
            hit = s;
          }
        }
      }
      if (!hit)
      {
        empty = true; // the view's ray missed: no root anywhere on the line
      }
      else if (sense < 0)
      {
        hi = hit->X;
      }
      else
      {
        lo = hit->X;
      }
    }
    if (empty || hi - lo <= 2 * tol)
    {
      continue;
    }
    // The views' hits end the hidden part; roots within tol of them are those hits
    // (dropped below), so the cast leaves them out instead of refining them again.
    lo += tol;
    hi -= tol;
    if (!T.Caster)
    {
      this->MissingModel = true;
      continue;
    }
    const vtkIdType k = l - L.LineStart[a];
    const int mu = static_cast<int>(k % L.N[(a + 1) % 3]) + 1;
    const int mv = static_cast<int>(k / L.N[(a + 1) % 3]) + 1;
    pisurf::RayRootOptions options;
    options.Tolerance = 1e-10 * T.Size;
    double origin = lo; // roots come as X − origin
    if (const pisurf::RayGrid* grid = this->Grids[a].get())
    {
      const vtkIdType rowKey = 3 * vtkIdType(mv) + a;
      if (rowKey != rowOf)
      {
        grid->SetRow(mv - 1, row);
        rowOf = rowKey;
      }
      coefficients.resize(T.Caster->GetLineCoefficientCount());
      grid->Restrict(row, mu - 1, coefficients.data());
      origin = L.B0[a] + grid->GetHalfLength();
      T.Caster->CastRestricted(coefficients.data(), lo - origin, hi - origin, options, roots);
    }
    else
    {
      double o[3], d[3] = { 0, 0, 0 };
      o[a] = lo;
      o[(a + 1) % 3] = L.X((a + 1) % 3, mu);
      o[(a + 2) % 3] = L.X((a + 2) % 3, mv);
      d[a] = 1;
      T.Caster->Cast(o, d, hi - lo, options, roots);
    }
    for (const pisurf::RayRoot& r : roots)
    {
      const double x = origin + r.T;
      if (x > lo && x < hi)
      {
        found.push_back({ x, 0, r.Tangent });
        ++hiddenCount[l];
      }
    }
  }
  if (!found.empty())
  {
    std::lock_guard<std::mutex> lock(this->HiddenMutex);
    this->HiddenRanges.push_back({ begin, std::move(found) });
  }
}

// The hidden roots become computed points on the rays of a view along their axis.
void HitLattice::GatherHidden()
{
  const vtkIdType lines = this->LineCount;
  const auto& first = this->First;
  auto& start = this->Out.Start;
  auto& hiddenStart = this->HiddenStart;
  auto& hiddenRanges = this->HiddenRanges;
  for (size_t v = T.Views.size(); v-- > 0;)
  {
    this->LineView[T.Views[v].Axis] = static_cast<int>(v);
  }
  start.Allocate(lines + 1);
  hiddenStart.Allocate(lines + 1);
  start[0] = hiddenStart[0] = 0;
  for (vtkIdType l = 0; l < lines; ++l)
  {
    const vtkIdType h = this->HiddenCount[l];
    start[l + 1] = start[l] + (first[l + 1] - first[l]) + h;
    hiddenStart[l + 1] = hiddenStart[l] + h;
  }
  this->HiddenCount.reset();
  // All hidden roots in line order: each range's roots go where its first line's go.
  this->Hidden.reset(new Sample[hiddenStart[lines]]);
  auto& hidden = this->Hidden;
  pisurf::ParallelFor(0, static_cast<vtkIdType>(hiddenRanges.size()), 1,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType k = b; k < e; ++k)
      {
        const HiddenRange& range = hiddenRanges[k];
        std::copy(range.Roots.begin(), range.Roots.end(), hidden.get() + hiddenStart[range.Begin]);
      }
    });
  hiddenRanges.clear();
  // (not initialized on allocation: the threads below write every sample)
  this->Out.Line.reset(new Sample[start[lines]]);
  this->Base = T.Points.size();
  T.Points.resize(this->Base + hiddenStart[lines]);
}

void HitLattice::MergeLines(vtkIdType lb, vtkIdType le)
{
  const double tol = this->Tol;
  const auto& samples = this->Samples;
  const auto& first = this->First;
  const auto& start = this->Out.Start;
  const auto& hiddenStart = this->HiddenStart;
  const auto& hidden = this->Hidden;
  const auto& line = this->Out.Line;
  const int* lineView = this->LineView;
  const size_t base = this->Base;
  for (vtkIdType l = lb; l < le; ++l)
  {
    const int a = l >= L.LineStart[2] ? 2 : l >= L.LineStart[1] ? 1 : 0;
    Sample* out = line.get() + start[l];
    std::copy(samples.get() + first[l], samples.get() + first[l + 1], out);
    Sample* o = out + (first[l + 1] - first[l]);
    const vtkIdType k = l - L.LineStart[a];
    size_t index = base + hiddenStart[l];
    for (vtkIdType q = hiddenStart[l]; q < hiddenStart[l + 1]; ++q)
    {
      Sample s = hidden[q];
      Computed& c = T.Points[index];
      c.Key = -static_cast<std::int64_t>(index) - 1;
      c.P[a] = s.X;
      c.P[(a + 1) % 3] = L.X((a + 1) % 3, static_cast<int>(k % L.N[(a + 1) % 3]) + 1);
      c.P[(a + 2) % 3] = L.X((a + 2) % 3, static_cast<int>(k / L.N[(a + 1) % 3]) + 1);
      c.View = lineView[a];
      T.Attributes(c);
      s.SetCode(c.Key);
      ++index;
      *o++ = s;
    }
    std::sort(out, o);
    // A root seen from both ends of the line is one sample; the other copy is marked
    // removed in place, so the line stays sorted.
    const Sample* kept = nullptr;
    for (Sample* s = out; s != o; ++s)
    {
      if (kept && s->X - kept->X <= tol)
      {
        s->Remove();
        continue;
      }
      kept = s;
    }
  }
}

} // namespace triangulator
} // namespace pisurf
