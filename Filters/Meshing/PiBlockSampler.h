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
  /// Samples `field` at the points of g's active blocks into `values` (grown as needed),
  /// which g.Values then points to: from pass 2's row restrictions `rows` where the
  /// field has the product's fast paths, else box by box (Field::EvaluateBox) or point
  /// by point. The single thread checks `algorithm` for a cancel and sets `abort`.
  static void Run(const Field& field, BlockGrid& g, const RowRestriction& rows,
    Buffer<double>& values, vtkAlgorithm* algorithm, std::atomic<bool>& abort);
};
}

#endif
