// SPDX-License-Identifier: BSD-3-Clause
// The data the ray caster's passes share: one view's rays, one hit along a ray, and the
// hits of every image row.
#ifndef PiRayView_h
#define PiRayView_h

#include <cstddef>
#include <vector>

namespace pisurf
{
// One view: the ray of pixel (i, j) starts at O + i·U + j·V (axis and parallel views)
// or at O with direction D + i·U + j·V (perspective), t in [0, Length] for axis views.
struct RayView
{
  bool Perspective = false;
  bool Axis = false;
  int W = 0, H = 0;
  double O[3], U[3], V[3], D[3];
  double Length = 0.0;
};

struct RayHit
{
  int I, J, View, Index;
  double T;
  bool Tangent;
  double P[3];
};

// Per image row (view by view): its hits. vtkPiRayCaster keeps them (emptied, not
// freed) from one execution to the next, so that casting again does not fault that
// memory in again.
struct RayHitRows
{
  std::vector<std::vector<RayHit>> Rows;

  // `count` empty rows, each keeping its memory from the last execution.
  std::vector<std::vector<RayHit>>& Reset(size_t count)
  {
    this->Rows.resize(count);
    for (std::vector<RayHit>& row : this->Rows)
    {
      row.clear();
    }
    return this->Rows;
  }
};
}

#endif
