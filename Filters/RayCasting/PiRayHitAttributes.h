// SPDX-License-Identifier: BSD-3-Clause
// The attributes pass of vtkPiRayCaster: each hit's point and exact attributes (unit
// normal, gradient magnitude, Singular, Factor from the product's gradient; Depth,
// PixelIndex, ViewIndex, HitIndex, Tangent from the cast), in arrays that list the
// hits row after row.
#ifndef PiRayHitAttributes_h
#define PiRayHitAttributes_h

#include "PiRayView.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"

#include <vector>

class vtkDataArray;

namespace pisurf
{
class RayCaster;

struct RayHitAttributes
{
  // Point k is hit k − RowOffsets[r] of row r (rows.size() + 1 entries).
  std::vector<vtkIdType> RowOffsets;
  vtkNew<vtkPoints> Points;
  vtkNew<vtkFloatArray> Normals;
  vtkNew<vtkDoubleArray> Gradient, Depth;
  vtkNew<vtkIntArray> Pixel, ViewIndex, HitIndex;
  vtkNew<vtkUnsignedCharArray> Singular, Tangent;
  vtkNew<vtkIntArray> Factor;

  /// The points and arrays of every hit of the rows, which lie within the bounds;
  /// `size` is the bounds' diagonal (the singularity probes step 1e-3 of it).
  void Compute(const std::vector<std::vector<RayHit>>& rows, RayCaster& caster,
    const double bounds[6], double size, double singularTolerance);

  vtkIdType GetNumberOfHits() const { return this->RowOffsets.back(); }

  /// The point arrays, in the output's order.
  std::vector<vtkDataArray*> Arrays() const;

  /// Keeps the rows' memory for the next execution up to 256 MiB of hits, frees it
  /// above.
  static void ReleaseLargeRows(std::vector<std::vector<RayHit>>& rows);
};
}

#endif
