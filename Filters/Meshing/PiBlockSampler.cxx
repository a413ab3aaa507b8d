// SPDX-License-Identifier: BSD-3-Clause
// PASS 3 of the mesher: sampling the active blocks (see PiBlockSampler.h).
#include "PiBlockSampler.h"

#include "PiParallel.h"
#include "vtkAlgorithm.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace pisurf
{
namespace
{
// PASS 3: the points of each active block: F, clamped to ±ValueLimit so that differences
// of neighbours stay finite (the sign of F is exact, whatever its magnitude).
struct SampleBlocks
{
  const pisurf::Field* Field;
  const pisurf::ProductKernel* Kernel; // the field's row restrictions, or null
  BlockGrid* G;
  const pisurf::LargeVector<vtkIdType>* RowIndex; // per row (j, k): its index in the coefficients
  const pisurf::LargeVector<double>* Coefficients;
  vtkAlgorithm* Algorithm;
  std::atomic<bool>* Abort;

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const bool single = pisurf::SingleThread();
    const size_t n = this->Kernel ? this->Kernel->GetLineCoefficientCount() : 0;
    const double mid = 0.5 * (this->G->Dims[0] - 1);
    for (vtkIdType s = begin; s < end; ++s)
    {
      if (single && this->Algorithm->CheckAbort())
      {
        *this->Abort = true;
      }
      if (*this->Abort)
      {
        return;
      }
      int c[3];
      this->G->BlockCoordinates(this->G->Active[s], c);
      double* v = this->G->Values + size_t(s) * BlockPoints * BlockPoints * BlockPoints;
      if (!this->Kernel)
      {
        // A field that evaluates a whole box at once (bit for bit as point by point).
        int first[3], last[3];
        this->G->Range(c, first, last);
        if (this->Field->EvaluateBox(this->G->Origin, this->G->Spacing, first, last, BlockPoints,
              BlockPoints * BlockPoints, v))
        {
          for (int k = 0; k <= last[2] - first[2]; ++k)
            for (int j = 0; j <= last[1] - first[1]; ++j)
              for (int i = 0; i <= last[0] - first[0]; ++i)
              {
                double& x = v[(k * BlockPoints + j) * BlockPoints + i];
                x = Limited(x);
              }
          continue;
        }
      }
      for (int k = this->G->First(c, 2); k <= this->G->Last(c, 2); ++k)
      {
        for (int j = this->G->First(c, 1); j <= this->G->Last(c, 1); ++j)
        {
          const double* coefficients = this->Kernel ? this->Coefficients->data() +
              (*this->RowIndex)[vtkIdType(k) * this->G->Dims[1] + j] * n
                                                    : nullptr;
          double* out = v +
            size_t((k - c[2] * BlockCells) * BlockPoints + (j - c[1] * BlockCells)) * BlockPoints;
          const int first = this->G->First(c, 0), last = this->G->Last(c, 0);
          if (this->Kernel && this->Kernel->IsPolynomial())
          {
            // The block's part of the row, several points at a time (the same values as
            // EvaluateRestricted point by point; the points are not needed).
            double* row = out + (first - c[0] * BlockCells);
            const double unused[3] = { 0, 0, 0 };
            this->Kernel->EvaluateRestrictedRow(
              coefficients, first - mid, last - first + 1, unused, unused, row);
            for (int i = 0; i <= last - first; ++i)
            {
              row[i] = Limited(row[i]);
            }
            continue;
          }
          for (int i = first; i <= last; ++i)
          {
            const double p[3] = { this->G->Origin[0] + i * this->G->Spacing[0],
              this->G->Origin[1] + j * this->G->Spacing[1],
              this->G->Origin[2] + k * this->G->Spacing[2] };
            const double F = this->Kernel
              ? this->Kernel->EvaluateRestricted(coefficients, i - mid, p)
              : this->Field->Evaluate(p);
            out[i - c[0] * BlockCells] = Limited(F);
          }
        }
      }
    }
  }
};

// PASS 3 for a product of polynomials: row by row. Each grid row (j, k) that crosses an
// active block is evaluated once over the runs of consecutive x blocks it needs (one
// call per run, several points at a time), and its values are copied into every active
// block that holds the row (up to four, where j or k is on a block boundary): each grid
// point is evaluated once, not once per block sharing it. The values are those of
// SampleBlocks (EvaluateRestrictedRow depends only on the coefficients and t).
struct SampleRows
{
  const pisurf::ProductKernel* Kernel;
  BlockGrid* G;
  const std::vector<vtkIdType>* Rows; // the rows (k·Dims[1] + j) in coefficient order
  const pisurf::LargeVector<double>* Coefficients;
  vtkAlgorithm* Algorithm;
  std::atomic<bool>* Abort;
  // Per block row (bz·Count[1] + by): its first and one past its last active x block.
  std::vector<std::pair<int, int>> Span;

  // (Not named Initialize: vtkSMPTools would take it for a per-thread initializer.)
  void Prepare()
  {
    const int* count = this->G->Count;
    this->Span.assign(size_t(count[1]) * count[2], { count[0], 0 });
    for (const int b : this->G->Active)
    {
      int c[3];
      this->G->BlockCoordinates(b, c);
      std::pair<int, int>& span = this->Span[size_t(c[2]) * count[1] + c[1]];
      span.first = std::min(span.first, c[0]);
      span.second = std::max(span.second, c[0] + 1);
    }
  }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const bool single = pisurf::SingleThread();
    const size_t n = this->Kernel->GetLineCoefficientCount();
    const int* d = this->G->Dims;
    const double mid = 0.5 * (d[0] - 1);
    const double unused[3] = { 0, 0, 0 };
    // Locals, not thread_local: a thread_local in a shared library costs a call to find
    // it at every use (several per row); one allocation per chunk of rows is nothing.
    std::vector<double> values(d[0]);
    std::vector<char> need(this->G->Count[0]);
    for (vtkIdType r = begin; r < end; ++r)
    {
      if (single && (r & 255) == 0 && this->Algorithm->CheckAbort())
      {
        *this->Abort = true;
      }
      if (*this->Abort)
      {
        return;
      }
      const vtkIdType row = (*this->Rows)[r];
      const int j = static_cast<int>(row % d[1]), k = static_cast<int>(row / d[1]);
      int ys[2], zs[2];
      const int ny = this->G->Containing(j, 1, ys), nz = this->G->Containing(k, 2, zs);
      // Only the x blocks between the first and last active ones of these block rows.
      int from = this->G->Count[0], to = 0;
      for (int a = 0; a < ny; ++a)
        for (int b = 0; b < nz; ++b)
        {
          const std::pair<int, int>& span = this->Span[size_t(zs[b]) * this->G->Count[1] + ys[a]];
          from = std::min(from, span.first);
          to = std::max(to, span.second);
        }
      for (int bx = from; bx < to; ++bx)
      {
        char any = 0;
        for (int a = 0; a < ny; ++a)
          for (int b = 0; b < nz; ++b)
          {
            any |= this->G->Slot[this->G->BlockId(bx, ys[a], zs[b])] >= 0;
          }
        need[bx] = any;
      }
      const double* coefficients = this->Coefficients->data() + r * n;
      for (int bx = from; bx < to;)
      {
        if (!need[bx])
        {
          ++bx;
          continue;
        }
        int last = bx;
        while (last + 1 < to && need[last + 1])
        {
          ++last;
        }
        const int first = bx * BlockCells;
        const int stop = std::min((last + 1) * BlockCells, d[0] - 1);
        this->Kernel->EvaluateRestrictedRow(
          coefficients, first - mid, stop - first + 1, unused, unused, values.data() + first);
        LimitRow(values.data() + first, stop - first + 1);
        bx = last + 1;
      }
      for (int bx = from; bx < to; ++bx)
      {
        if (!need[bx])
        {
          continue;
        }
        const int first = bx * BlockCells;
        const int count = std::min(first + BlockCells, d[0] - 1) - first + 1;
        for (int a = 0; a < ny; ++a)
          for (int b = 0; b < nz; ++b)
          {
            const int slot = this->G->Slot[this->G->BlockId(bx, ys[a], zs[b])];
            if (slot < 0)
            {
              continue;
            }
            double* out = this->G->Values + size_t(slot) * BlockPoints * BlockPoints * BlockPoints +
              size_t((k - zs[b] * BlockCells) * BlockPoints + (j - ys[a] * BlockCells)) *
                BlockPoints;
            // (A block row: at most 9 values, copied inline rather than by a call.)
            const double* in = values.data() + first;
            if (count == BlockPoints)
            {
              for (int i = 0; i < BlockPoints; ++i)
              {
                out[i] = in[i];
              }
            }
            else
            {
              for (int i = 0; i < count; ++i)
              {
                out[i] = in[i];
              }
            }
          }
      }
    }
  }
};
}

void BlockSampler::Run(const Field& field, BlockGrid& g, const RowRestriction& rows,
  Buffer<double>& values, vtkAlgorithm* algorithm, std::atomic<bool>& abort)
{
  const ProductKernel* kernel = field.GetProductKernel();
  // Every entry is written below: no need to clear.
  const size_t valueCount = g.Active.size() * BlockPoints * BlockPoints * BlockPoints;
  if (values.GetSize() < valueCount)
  {
    values.Allocate(valueCount);
  }
  g.Values = values.GetPointer();
  if (kernel && kernel->IsPolynomial())
  {
    SampleRows sample{ kernel, &g, &rows.Rows, &rows.Coefficients, algorithm, &abort, {} };
    sample.Prepare();
    pisurf::ParallelFor(0, static_cast<vtkIdType>(rows.Rows.size()), 64, sample);
  }
  else
  {
    SampleBlocks sample{ &field, kernel, &g, &rows.RowIndex, &rows.Coefficients, algorithm,
      &abort };
    pisurf::ParallelFor(0, static_cast<vtkIdType>(g.Active.size()), 4, sample);
  }
}
}
