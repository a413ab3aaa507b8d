// SPDX-License-Identifier: BSD-3-Clause
// The views pass of vtkPiRayCaster: the rays of each view of a ViewMode (the axis views
// over the bounds, or the camera's), and the memory cap of casting them.
#ifndef PiRayViews_h
#define PiRayViews_h

#include "PiRayView.h"

#include <string>
#include <vector>

namespace pisurf
{
// vtkPiRayCaster's camera settings (CAMERA mode).
struct RayCamera
{
  const double* Position;
  const double* FocalPoint;
  const double* ViewUp;
  double ViewAngle;
  bool ParallelProjection;
  double ParallelScale;
};

class RayViews
{
public:
  /// The views of `viewMode` (vtkPiRayCaster::ViewModes) at w × h pixels over the
  /// bounds; false, with the reason, for a degenerate camera.
  static bool Make(int viewMode, int w, int h, const double bounds[6], const RayCamera& camera,
    std::vector<RayView>& views, std::string& error);

  /// False, with the memory it would need, when casting `viewCount` views of w × h
  /// pixels exceeds the cap.
  static bool CheckMemory(int w, int h, size_t viewCount, std::string& error);

private:
  // Axis view along world axis `axis` (towards +axis when `plus`).
  static RayView AxisView(int axis, bool plus, int w, int h, const double b[6]);
  static bool CameraView(int w, int h, const RayCamera& camera, RayView& view, std::string& error);
};
}

#endif
