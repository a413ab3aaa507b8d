// SPDX-License-Identifier: BSD-3-Clause
// PASS 1 of the mesher: each block of the grid gets a sign from the interval enclosures
// of F (skipped, with that sign) or stays active, coarse to fine: groups of 4³ blocks,
// the 2³-block quarters of undecided groups, then single blocks.
#ifndef PiBlockClassifier_h
#define PiBlockClassifier_h

#include "PiBlockGrid.h"
#include "PiField.h"

#include <cstddef>

namespace pisurf
{
class BlockClassifier
{
public:
  /// Fills g.Sign for the block layers [classifyBegin, classifyEnd) along z (with
  /// `slabOnly`, the others are AbsentBlock; otherwise every layer is classified), then
  /// lists the active blocks from layer sampleBegin on in g.Active and g.Slot.
  /// Returns how many blocks their groups left undecided. With the field's product fast
  /// paths (Field::GetProductKernel), the groups' octants come from the same expansions
  /// and blocks whose corners differ in sign skip their enclosures.
  static size_t Run(const Field& field, BlockGrid& g, int classifyBegin, int classifyEnd,
    int sampleBegin, bool slabOnly);

private:
  // Groups of 4³ blocks and their quarters; blocks still undecided get the sign 2.
  static void ClassifyGroups(const Field& field, BlockGrid& g, int classifyBegin, int classifyEnd);
};
}

#endif
