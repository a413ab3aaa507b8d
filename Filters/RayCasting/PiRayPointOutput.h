// SPDX-License-Identifier: BSD-3-Clause
// The point output pass of vtkPiRayCaster (port 0): the hits of the piece's rows as
// points with their arrays and one vertex each, and the field data that describe the
// views and the model.
#ifndef PiRayPointOutput_h
#define PiRayPointOutput_h

#include "PiRayView.h"

#include <vector>

class vtkPiSurface;
class vtkPolyData;

namespace pisurf
{
struct RayHitAttributes;
struct RayPieceRows;

class RayPointOutput
{
public:
  /// The hits of the piece's rows (all of them when the cast holds no other rows) as
  /// the output's points, point data and vertices.
  static void SetPoints(
    const RayHitAttributes& hits, const RayPieceRows& rows, vtkPolyData* output);

  /// Field data `PiRayViews`: 17 numbers per view (see vtkPiRayCaster.h).
  static void AddViews(const std::vector<RayView>& views, bool allHits, vtkPolyData* output);

  /// Field data `PiSurfaceModel`: the surface's model, with the cast's bounds when it
  /// has none.
  static void AddModel(vtkPiSurface& surface, const double bounds[6], vtkPolyData* output);

private:
  // One vertex cell per point.
  static void SetVerts(vtkPolyData* output);
};
}

#endif
