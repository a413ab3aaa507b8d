// SPDX-License-Identifier: BSD-3-Clause
// PASS 2 of the mesher: the factors' row restrictions (see PiRowRestriction.h).
#include "PiRowRestriction.h"

#include "PiParallel.h"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace pisurf
{
namespace
{
// What a factor's restrictions and values depend on: its terms and its placement.
std::vector<double> FactorKey(const pisurf::PolynomialFactor& f)
{
  std::vector<double> key;
  for (const pisurf::Monomial& m : f.Poly.GetTerms())
  {
    key.insert(key.end(), { m.Coefficient, double(m.I), double(m.J), double(m.K) });
  }
  for (const auto& row : f.A)
  {
    key.insert(key.end(), row, row + 3);
  }
  key.insert(key.end(), f.B, f.B + 3);
  return key;
}

// PASS 2: the rows (j, k) that cross an active block get their factors restricted once,
// about the middle of the whole row, so every point evaluates identically whichever
// block asks for it (no cracks between blocks).
struct RestrictRows
{
  const pisurf::ProductKernel* Kernel;
  const BlockGrid* G;
  const std::vector<vtkIdType>* Rows;
  pisurf::LargeVector<double>* Coefficients;

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const size_t n = this->Kernel->GetLineCoefficientCount();
    const double step[3] = { this->G->Spacing[0], 0.0, 0.0 };
    for (vtkIdType r = begin; r < end; ++r)
    {
      const vtkIdType row = (*this->Rows)[r];
      double o[3];
      this->G->RowMiddle(row, o);
      this->Kernel->RestrictLine(o, step, this->Coefficients->data() + r * n);
    }
  }
};

// The factor caches of this execution: per factor of the kernel, its cache (null for a
// factor that is not a polynomial; factors of equal content share one), or none at all
// (empty) for a field or when the restrictions of every row would exceed 64 MiB.
std::vector<FactorCache*> PrepareFactorCaches(std::vector<double>& gridKey,
  std::vector<FactorCache>& store, const pisurf::ProductKernel* kernel, const BlockGrid& g)
{
  size_t polynomials = 0;
  for (size_t f = 0; kernel && f < kernel->GetNumberOfFactors(); ++f)
  {
    polynomials += kernel->GetFactor(f).IsPolynomial;
  }
  constexpr double MaximumCoefficients = double(1 << 23); // 64 MiB of doubles
  if (polynomials == 0 ||
    double(g.Dims[1]) * g.Dims[2] * kernel->GetLineCoefficientCount() > MaximumCoefficients)
  {
    store.clear();
    return {};
  }
  const std::vector<double> grid{ double(g.Dims[0]), double(g.Dims[1]), double(g.Dims[2]),
    g.Origin[0], g.Origin[1], g.Origin[2], g.Spacing[0], g.Spacing[1], g.Spacing[2] };
  if (grid != gridKey)
  {
    store.clear();
    gridKey = grid;
  }
  for (FactorCache& cache : store)
  {
    cache.Used = false;
  }
  const size_t rows = size_t(g.Dims[1]) * g.Dims[2];
  std::vector<std::ptrdiff_t> index(kernel->GetNumberOfFactors(), -1);
  for (size_t f = 0; f < kernel->GetNumberOfFactors(); ++f)
  {
    const pisurf::Factor& factor = kernel->GetFactor(f);
    if (!factor.IsPolynomial)
    {
      continue;
    }
    std::vector<double> key = FactorKey(factor.Polynomial);
    auto found =
      std::find_if(store.begin(), store.end(), [&](const FactorCache& c) { return c.Key == key; });
    if (found == store.end())
    {
      FactorCache cache;
      cache.Key = std::move(key);
      cache.Coefficients = std::max(factor.Polynomial.Poly.GetDegree(), 0) + 1;
      cache.Rows.resize(rows * cache.Coefficients);
      cache.RowDone.assign(rows, 0);
      store.push_back(std::move(cache));
      found = store.end() - 1;
    }
    found->Used = true;
    index[f] = found - store.begin();
  }
  // Factors no longer in the product (a moved primitive's old placement) are dropped.
  std::vector<FactorCache> kept;
  std::vector<std::ptrdiff_t> renumber(store.size(), -1);
  for (size_t c = 0; c < store.size(); ++c)
  {
    if (store[c].Used)
    {
      renumber[c] = static_cast<std::ptrdiff_t>(kept.size());
      kept.push_back(std::move(store[c]));
    }
  }
  store = std::move(kept);
  std::vector<FactorCache*> caches(kernel->GetNumberOfFactors(), nullptr);
  for (size_t f = 0; f < caches.size(); ++f)
  {
    if (index[f] >= 0)
    {
      caches[f] = &store[renumber[index[f]]];
    }
  }
  return caches;
}

// PASS 2, incremental: each factor is restricted to the rows it has not been restricted
// to on this grid yet, about the middle of the row as in RestrictRows; the row's
// coefficients are then gathered from the caches in RestrictRows's layout.
struct RestrictCachedRows
{
  const BlockGrid* G;
  const std::vector<vtkIdType>* Rows;
  const std::vector<FactorCache*>* Caches;
  const pisurf::ProductKernel* Kernel;
  pisurf::LargeVector<double>* Coefficients;

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const size_t n = this->Kernel->GetLineCoefficientCount();
    const double step[3] = { this->G->Spacing[0], 0.0, 0.0 };
    for (vtkIdType r = begin; r < end; ++r)
    {
      const vtkIdType row = (*this->Rows)[r];
      double o[3];
      this->G->RowMiddle(row, o);
      double* out = this->Coefficients->data() + r * n;
      for (size_t f = 0; f < this->Caches->size(); ++f)
      {
        FactorCache* cache = (*this->Caches)[f];
        if (!cache)
        {
          continue;
        }
        double* coefficients = cache->Rows.data() + row * cache->Coefficients;
        if (!cache->RowDone[row])
        {
          this->Kernel->GetFactor(f).Polynomial.RestrictToLine(o, step, coefficients);
          cache->RowDone[row] = 1;
        }
        std::copy(coefficients, coefficients + cache->Coefficients, out);
        out += cache->Coefficients;
      }
    }
  }
};
}

void RowRestriction::CollectRows(const BlockGrid& g)
{
  LargeVector<vtkIdType>& rowIndex = this->RowIndex;
  std::vector<vtkIdType>& rows = this->Rows;
  rowIndex.assign(vtkIdType(g.Dims[1]) * g.Dims[2], -1);
  rows.clear();
  // (Active is in block order: the blocks of one column along x are consecutive and
  // need the same rows, so each column is visited once.)
  int lastColumn = -1;
  for (int b : g.Active)
  {
    const int column = b / g.Count[0];
    if (column == lastColumn)
    {
      continue;
    }
    lastColumn = column;
    int c[3];
    g.BlockCoordinates(b, c);
    for (int k = g.First(c, 2); k <= g.Last(c, 2); ++k)
      for (int j = g.First(c, 1); j <= g.Last(c, 1); ++j)
      {
        vtkIdType& r = rowIndex[vtkIdType(k) * g.Dims[1] + j];
        if (r < 0)
        {
          r = static_cast<vtkIdType>(rows.size());
          rows.push_back(vtkIdType(k) * g.Dims[1] + j);
        }
      }
  }
}

double RowRestriction::Restrict(const ProductKernel* kernel, const BlockGrid& g, double maximum)
{
  // The polynomial factors keep their row restrictions between executions (see
  // FactorCache): only new factors and new rows are restricted.
  std::vector<FactorCache*> caches = PrepareFactorCaches(this->CacheGrid, this->Factors, kernel, g);
  // (Every entry is written below: resized, not cleared.)
  LargeVector<double>& coefficients = this->Coefficients;
  const std::vector<vtkIdType>& rows = this->Rows;
  if (!kernel)
  {
    coefficients.clear();
    return 0.0;
  }
  // Every polynomial factor restricted to every row: with many factors this, not the
  // grid, is the largest array. It shares the grid's cap.
  const double count = double(rows.size()) * kernel->GetLineCoefficientCount();
  if (count > maximum)
  {
    return count;
  }
  coefficients.resize(rows.size() * kernel->GetLineCoefficientCount());
  if (caches.empty())
  {
    RestrictRows restrict { kernel, &g, &rows, &coefficients };
    pisurf::ParallelFor(0, static_cast<vtkIdType>(rows.size()), 256, restrict);
  }
  else
  {
    RestrictCachedRows restrict { &g, &rows, &caches, kernel, &coefficients };
    pisurf::ParallelFor(0, static_cast<vtkIdType>(rows.size()), 256, restrict);
  }
  return 0.0;
}
}
