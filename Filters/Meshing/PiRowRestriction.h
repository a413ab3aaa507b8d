// SPDX-License-Identifier: BSD-3-Clause
// PASS 2 of the mesher: every polynomial factor restricted once to each grid row (j, k)
// that crosses an active block, about the middle of the row, so that every grid point
// evaluates identically whichever block asks for it. The restrictions are kept per
// factor between executions, keyed by the factor's content and the grid.
#ifndef PiRowRestriction_h
#define PiRowRestriction_h

#include "PiBlockGrid.h"
#include "PiLargeArrays.h"
#include "PiProductKernel.h"

#include <vector>

namespace pisurf
{
// Incremental re-meshing: each polynomial factor's restrictions to the grid rows are
// kept, keyed by the factor's content (terms and placement) and the grid. When a live
// edit changes one factor (a moved primitive), the others are not restricted again.
// The restrictions are the same numbers a fresh execution computes, so the mesh is
// bit-identical.
struct FactorCache
{
  std::vector<double> Key;   // the factor's content (see FactorKey)
  int Coefficients = 0;      // per row: degree + 1
  LargeVector<double> Rows;  // per grid row (j, k): the restricted coefficients
                             // (uninitialized until RowDone says so)
  std::vector<char> RowDone; // per grid row: Rows holds it
  bool Used = false;         // matched by a factor of the current execution
};

class RowRestriction
{
public:
  /// Lists the rows the active blocks of g need: Rows (k·Dims[1] + j, in coefficient
  /// order) and RowIndex (per row (j, k): its index in Rows, or −1).
  void CollectRows(const BlockGrid& g);

  /// Restricts every factor of `kernel` to each of Rows into Coefficients (Rows' order,
  /// GetLineCoefficientCount() each). Returns 0, or the number of coefficients needed
  /// when it exceeds `maximum` (then nothing is restricted). Without a kernel (a field)
  /// Coefficients is emptied.
  double Restrict(const ProductKernel* kernel, const BlockGrid& g, double maximum);

  // Kept between executions, like the sampled values, so that a re-execution does not
  // fault their pages in again (in AllocateLarge's memory, for a new mesher's sake: see
  // pisurf::DefaultInitAllocator).
  LargeVector<vtkIdType> RowIndex;
  std::vector<vtkIdType> Rows;
  LargeVector<double> Coefficients;

private:
  std::vector<double> CacheGrid; // the grid the factor caches belong to
  std::vector<FactorCache> Factors;
};
}

#endif
