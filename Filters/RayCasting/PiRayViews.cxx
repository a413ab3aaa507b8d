// SPDX-License-Identifier: BSD-3-Clause
// The views pass of vtkPiRayCaster: the rays of each view of a ViewMode, and the memory
// cap of casting them.
#include "PiRayViews.h"

#include "vtkMath.h"
#include "vtkPiRayCaster.h"

#include <cmath>
#include <sstream>

namespace pisurf
{
namespace
{
// The memory cap of a cast (the mesher's default cap too: 2^28 doubles). Per first hit:
// the Hit (56 bytes), the point and its nine arrays (about 90) and the image pixel.
constexpr double MaximumBytes = double(1u << 31);
constexpr double BytesPerRay = 160;
}

bool RayViews::Make(int viewMode, int w, int h, const double b[6], const RayCamera& camera,
  std::vector<RayView>& views, std::string& error)
{
  switch (viewMode)
  {
    case vtkPiRayCaster::PLUS_X:
    case vtkPiRayCaster::MINUS_X:
    case vtkPiRayCaster::PLUS_Y:
    case vtkPiRayCaster::MINUS_Y:
    case vtkPiRayCaster::PLUS_Z:
    case vtkPiRayCaster::MINUS_Z:
      // The enumeration runs +X, −X, +Y, −Y, +Z, −Z.
      views.push_back(AxisView((viewMode - vtkPiRayCaster::PLUS_X) / 2,
        (viewMode - vtkPiRayCaster::PLUS_X) % 2 == 0, w, h, b));
      return true;
    case vtkPiRayCaster::SIX_AXIS_VIEWS:
    case vtkPiRayCaster::THREE_AXIS_DIRECTIONS:
      views.push_back(AxisView(2, false, w, h, b));
      views.push_back(AxisView(0, false, w, h, b));
      views.push_back(AxisView(1, false, w, h, b));
      if (viewMode == vtkPiRayCaster::SIX_AXIS_VIEWS)
      {
        views.push_back(AxisView(2, true, w, h, b));
        views.push_back(AxisView(0, true, w, h, b));
        views.push_back(AxisView(1, true, w, h, b));
      }
      return true;
    default:
    {
      RayView view;
      if (!CameraView(w, h, camera, view, error))
      {
        return false;
      }
      views.push_back(view);
      return true;
    }
  }
}

RayView RayViews::AxisView(int axis, bool plus, int w, int h, const double b[6])
{
  // Image axes: (x, y) for z, (y, z) for x, (z, x) for y; start on the far face for
  // the − directions, the near face for the + directions.
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  RayView view;
  view.Axis = true;
  view.W = w;
  view.H = h;
  for (int k = 0; k < 3; ++k)
  {
    view.U[k] = view.V[k] = view.D[k] = 0.0;
  }
  view.U[u] = (b[2 * u + 1] - b[2 * u]) / w;
  view.V[v] = (b[2 * v + 1] - b[2 * v]) / h;
  view.D[axis] = plus ? 1.0 : -1.0;
  view.O[u] = b[2 * u] + 0.5 * view.U[u];
  view.O[v] = b[2 * v] + 0.5 * view.V[v];
  view.O[axis] = plus ? b[2 * axis] : b[2 * axis + 1];
  view.Length = b[2 * axis + 1] - b[2 * axis];
  return view;
}

bool RayViews::CameraView(int w, int h, const RayCamera& camera, RayView& view, std::string& error)
{
  double dir[3], up[3], right[3];
  for (int k = 0; k < 3; ++k)
  {
    if (!std::isfinite(camera.Position[k]) || !std::isfinite(camera.FocalPoint[k]) ||
      !std::isfinite(camera.ViewUp[k]))
    {
      error = "Degenerate camera: CameraPosition, CameraFocalPoint and "
              "CameraViewUp must be finite";
      return false;
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    dir[k] = camera.FocalPoint[k] - camera.Position[k];
    up[k] = camera.ViewUp[k];
  }
  if (!(vtkMath::Normalize(dir) > 0) || !std::isfinite(dir[0] + dir[1] + dir[2]))
  {
    error = "Degenerate camera: CameraPosition equals CameraFocalPoint";
    return false;
  }
  vtkMath::Cross(dir, up, right);
  if (!(vtkMath::Normalize(right) > 1e-12))
  {
    error = "Degenerate camera: CameraViewUp is parallel to the view direction";
    return false;
  }
  vtkMath::Cross(right, dir, up);
  double hh;
  if (camera.ParallelProjection)
  {
    hh = camera.ParallelScale;
  }
  else
  {
    if (!(camera.ViewAngle > 0 && camera.ViewAngle < 180))
    {
      error = "ViewAngle must be in (0, 180) degrees";
      return false;
    }
    hh = std::tan(vtkMath::RadiansFromDegrees(0.5 * camera.ViewAngle));
  }
  if (!(hh > 0) || !std::isfinite(hh))
  {
    error = "ParallelScale must be positive";
    return false;
  }
  const double hw = hh * w / h;
  view.Perspective = !camera.ParallelProjection;
  view.W = w;
  view.H = h;
  for (int k = 0; k < 3; ++k)
  {
    view.U[k] = right[k] * 2 * hw / w;
    view.V[k] = up[k] * 2 * hh / h;
    const double corner = -hw * right[k] - hh * up[k] + 0.5 * (view.U[k] + view.V[k]);
    if (view.Perspective)
    {
      view.O[k] = camera.Position[k];
      view.D[k] = dir[k] + corner;
    }
    else
    {
      view.O[k] = camera.Position[k] + corner;
      view.D[k] = dir[k];
    }
  }
  return true;
}

bool RayViews::CheckMemory(int w, int h, size_t viewCount, std::string& error)
{
  // Each ray's first hit costs about BytesPerRay in the hits, their arrays and the
  // shaded image (more with AllHits).
  const double rays = double(w) * h * viewCount;
  if (rays * BytesPerRay > MaximumBytes)
  {
    std::ostringstream message;
    message << "Casting " << w << " x " << h << " pixels in " << viewCount
            << " view(s) needs at least " << rays * BytesPerRay / (1 << 20) << " MiB (about "
            << BytesPerRay << " bytes per ray); the limit is " << MaximumBytes / (1 << 20)
            << " MiB: lower the Resolution";
    error = message.str();
    return false;
  }
  return true;
}
}
