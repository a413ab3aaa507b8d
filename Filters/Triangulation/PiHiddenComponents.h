// SPDX-License-Identifier: BSD-3-Clause
// Drops the components of the mesh that no ray of the views reaches (closed shells
// inside the solid, found on the hidden parts of first-hit rays), and numbers the
// output points in the order the triangles first use them.
#ifndef PiHiddenComponents_h
#define PiHiddenComponents_h

#include "vtkType.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace pisurf
{
namespace triangulator
{

// Reads the triangles as point ids (hits below usedHits, then the computed points, total
// in all); gives each point its output id, or a negative id if it is not in the output.
class HiddenComponents
{
public:
  HiddenComponents(
    const std::vector<std::vector<std::int64_t>>& rows, vtkIdType usedHits, vtkIdType total);
  // The output id of every point; `count`: the number of output points.
  std::unique_ptr<vtkIdType[]> Run(vtkIdType& count);

private:
  vtkIdType Find(vtkIdType x);
  void Unite(vtkIdType x, vtkIdType y);
  void Join(vtkIdType b, vtkIdType e);

  const std::vector<std::vector<std::int64_t>>& Rows;
  const vtkIdType UsedHits, Total, ComputedCount;
  // A union-find over the computed points that all threads share: a root is linked to
  // the smaller of the two roots by a compare-and-swap that fails if it stopped being a
  // root meanwhile (then the union is tried again); paths are halved on the way. The
  // components, and so the points kept, do not depend on the order of the unions.
  std::unique_ptr<std::atomic<vtkIdType>[]> Parent;
  std::unique_ptr<std::atomic<unsigned char>[]> Marked;
};

} // namespace triangulator
} // namespace pisurf

#endif
