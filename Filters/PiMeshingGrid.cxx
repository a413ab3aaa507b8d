// SPDX-License-Identifier: BSD-3-Clause
#include "PiMeshingGrid.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pisurf
{

bool ComputeMeshingGrid(const double b[6], int resolution, const int sd[3],
  vtkIdType maximumNumberOfSamples, int dims[3], double spacing[3], std::string& error)
{
  const double side[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
  std::ostringstream message;
  // Points per axis as doubles: checked against the cap before any cast to int.
  double points[3];
  if (sd[0] != 0 || sd[1] != 0 || sd[2] != 0)
  {
    if (sd[0] < 2 || sd[1] < 2 || sd[2] < 2)
    {
      message << "SampleDimensions must be at least 2 points per axis (got " << sd[0] << ", "
              << sd[1] << ", " << sd[2] << "); set all to 0 to use Resolution";
      error = message.str();
      return false;
    }
    std::copy(sd, sd + 3, points);
  }
  else
  {
    if (resolution < 1)
    {
      message << "Resolution must be at least 1 (got " << resolution << ")";
      error = message.str();
      return false;
    }
    const double h = std::max({ side[0], side[1], side[2] }) / resolution;
    for (int a = 0; a < 3; ++a)
    {
      points[a] = std::max(1.0, std::ceil(side[a] / h - 1e-9)) + 1;
    }
  }
  const double samples = points[0] * points[1] * points[2];
  if (!(samples <= static_cast<double>(maximumNumberOfSamples)) ||
    std::max({ points[0], points[1], points[2] }) > VTK_INT_MAX)
  {
    message << "A grid of " << points[0] << " x " << points[1] << " x " << points[2] << " = "
            << samples << " samples needs up to " << samples * sizeof(double) / (1 << 20)
            << " MiB; the limit is " << maximumNumberOfSamples * sizeof(double) / (1 << 20)
            << " MiB (MaximumNumberOfSamples = " << maximumNumberOfSamples << " samples)";
    error = message.str();
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = static_cast<int>(points[a]);
  }
  for (int a = 0; a < 3; ++a)
  {
    spacing[a] = side[a] / (dims[a] - 1);
  }
  return true;
}

}
