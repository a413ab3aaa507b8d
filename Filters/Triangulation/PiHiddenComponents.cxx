// SPDX-License-Identifier: BSD-3-Clause
// Hits are all kept; a computed point is kept if it shares a triangle with a hit, or is
// joined to such a point by triangles of computed points only (a union-find over the
// computed points alone).
#include "PiHiddenComponents.h"

#include "vtkSMPTools.h"

#include <algorithm>

namespace pisurf
{
namespace triangulator
{

HiddenComponents::HiddenComponents(
  const std::vector<std::vector<std::int64_t>>& rows, vtkIdType usedHits, vtkIdType total)
  : Rows(rows)
  , UsedHits(usedHits)
  , Total(total)
  , ComputedCount(total - usedHits)
{
}

std::unique_ptr<vtkIdType[]> HiddenComponents::Run(vtkIdType& count)
{
  const vtkIdType computedCount = this->ComputedCount, usedHits = this->UsedHits,
                  total = this->Total;
  const vtkIdType rows = static_cast<vtkIdType>(this->Rows.size());
  this->Parent.reset(new std::atomic<vtkIdType>[computedCount]);
  this->Marked.reset(new std::atomic<unsigned char>[computedCount]);
  auto& parent = this->Parent;
  auto& marked = this->Marked;
  vtkSMPTools::For(0, computedCount,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType k = b; k < e; ++k)
      {
        parent[k].store(k, std::memory_order_relaxed);
        marked[k].store(0, std::memory_order_relaxed);
      }
    });
  // The computed points of triangles with a hit are visible; triangles of computed
  // points only join their points.
  vtkSMPTools::For(0, rows, [&](vtkIdType b, vtkIdType e) { this->Join(b, e); });
  // A component is kept if one of its points is marked (its root then is, below).
  std::vector<unsigned char> visible(computedCount, 0);
  for (vtkIdType k = 0; k < computedCount; ++k)
  {
    if (marked[k].load(std::memory_order_relaxed))
    {
      visible[this->Find(k)] = 1;
    }
  }
  marked.reset();
  // Output points in the order the triangles first use them (rows of the lattice), so
  // that neighbouring triangles have neighbouring points: every later pass (and the
  // user's filters) reads memory in order. newId: −1 for a point to number, −2 for a
  // point of a dropped component (negative: not in the output, as a point no triangle
  // uses).
  std::unique_ptr<vtkIdType[]> newId(new vtkIdType[total]);
  vtkSMPTools::For(0, total,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType k = b; k < e; ++k)
      {
        newId[k] = k < usedHits || visible[this->Find(k - usedHits)] ? -1 : -2;
      }
    });
  parent.reset();
  vtkIdType n = 0;
  for (const std::vector<std::int64_t>& row : this->Rows)
  {
    for (const std::int64_t k : row)
    {
      if (newId[k] == -1)
      {
        newId[k] = n++;
      }
    }
  }
  count = n;
  return newId;
}

inline vtkIdType HiddenComponents::Find(vtkIdType x)
{
  auto& parent = this->Parent;
  for (;;)
  {
    vtkIdType p = parent[x].load(std::memory_order_relaxed);
    if (p == x)
    {
      return x;
    }
    const vtkIdType g = parent[p].load(std::memory_order_relaxed);
    if (g != p)
    {
      // (an ancestor stays an ancestor: a lost race only skips the halving)
      parent[x].compare_exchange_weak(p, g, std::memory_order_relaxed);
    }
    x = g;
  }
}

inline void HiddenComponents::Unite(vtkIdType x, vtkIdType y)
{
  auto& parent = this->Parent;
  for (;;)
  {
    x = this->Find(x);
    y = this->Find(y);
    if (x == y)
    {
      return;
    }
    vtkIdType high = std::max(x, y);
    const vtkIdType low = std::min(x, y);
    if (parent[high].compare_exchange_strong(high, low, std::memory_order_relaxed))
    {
      return;
    }
  }
}

void HiddenComponents::Join(vtkIdType b, vtkIdType e)
{
  const vtkIdType usedHits = this->UsedHits;
  auto& marked = this->Marked;
  for (vtkIdType r = b; r < e; ++r)
  {
    const std::vector<std::int64_t>& row = this->Rows[r];
    for (size_t q = 0; q < row.size(); q += 3)
    {
      const std::int64_t* c = row.data() + q;
      if (c[0] >= usedHits && c[1] >= usedHits && c[2] >= usedHits)
      {
        this->Unite(c[0] - usedHits, c[1] - usedHits);
        this->Unite(c[0] - usedHits, c[2] - usedHits);
        continue;
      }
      for (int k = 0; k < 3; ++k)
      {
        if (c[k] >= usedHits)
        {
          marked[c[k] - usedHits].store(1, std::memory_order_relaxed);
        }
      }
    }
  }
}

} // namespace triangulator
} // namespace pisurf
