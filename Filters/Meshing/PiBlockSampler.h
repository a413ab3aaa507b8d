// SPDX-License-Identifier: BSD-3-Clause
// PASS 3 of the mesher: F at every point of the active blocks, clamped to ±ValueLimit,
// into the blocks' value arrays: row by row over the factors' row restrictions for a
// product of polynomials, block by block otherwise.
#ifndef PiBlockSampler_h
#define PiBlockSampler_h

#include "PiBlockGrid.h"
#include "PiBuffer.h"
#include "PiField.h"
#include "PiProductKernel.h"
#include "PiRowRestriction.h"

#include <atomic>

class vtkAlgorithm;

namespace pisurf
{
class BlockSampler
{
public:
  /// Samples `kernel` (or, without one, `field`) at the points of g's active blocks into
  /// `values` (grown as needed), which g.Values then points to. `rows` holds pass 2's
  /// restrictions. The single thread checks `algorithm` for a cancel and sets `abort`.
  static void Run(const ProductKernel* kernel, const Field* field, BlockGrid& g,
    const RowRestriction& rows, Buffer<double>& values, vtkAlgorithm* algorithm,
    std::atomic<bool>& abort);
};
}

#endif
