// SPDX-License-Identifier: BSD-3-Clause
// The attributes pass of vtkPiRayCaster: the points and exact attributes of the hits.
#include "PiRayHitAttributes.h"

#include "PiLargeArrays.h"
#include "PiParallel.h"
#include "PiRayCaster.h"

#include <algorithm>

namespace pisurf
{
void RayHitAttributes::Compute(const std::vector<std::vector<RayHit>>& rows, RayCaster& caster,
  const double b[6], double size, double singularTolerance)
{
  // (the hits are read from the rows where they are)
  this->RowOffsets.assign(rows.size() + 1, 0);
  for (size_t r = 0; r < rows.size(); ++r)
  {
    this->RowOffsets[r + 1] = this->RowOffsets[r] + static_cast<vtkIdType>(rows[r].size());
  }
  const vtkIdType n = this->RowOffsets.back();
  pisurf::AllocateLargePoints(this->Points, n);
  this->Normals->SetName("Normals");
  this->Normals->SetNumberOfComponents(3);
  pisurf::AllocateLargeArray(this->Normals.GetPointer(), n);
  this->Gradient->SetName("GradientMagnitude");
  pisurf::AllocateLargeArray(this->Gradient.GetPointer(), n);
  this->Depth->SetName("Depth");
  pisurf::AllocateLargeArray(this->Depth.GetPointer(), n);
  this->Pixel->SetName("PixelIndex");
  this->Pixel->SetNumberOfComponents(2);
  pisurf::AllocateLargeArray(this->Pixel.GetPointer(), n);
  this->ViewIndex->SetName("ViewIndex");
  pisurf::AllocateLargeArray(this->ViewIndex.GetPointer(), n);
  this->HitIndex->SetName("HitIndex");
  pisurf::AllocateLargeArray(this->HitIndex.GetPointer(), n);
  this->Singular->SetName("Singular");
  pisurf::AllocateLargeArray(this->Singular.GetPointer(), n);
  this->Tangent->SetName("Tangent");
  pisurf::AllocateLargeArray(this->Tangent.GetPointer(), n);
  this->Factor->SetName("Factor");
  pisurf::AllocateLargeArray(this->Factor.GetPointer(), n);
  const double probe = 1e-3 * size;
  // Every ray segment lies in the bounds, and so do the hits: there the attributes may
  // skip the singularity probes where the factors prove a hit regular (a hit a rounding
  // outside takes the probes; RayCaster::PrepareProbes).
  caster.PrepareProbes(b, probe);
  double* xyz = vtkDoubleArray::FastDownCast(this->Points->GetData())->GetPointer(0);
  float* nrmOut = this->Normals->GetPointer(0);
  double* gradientOut = this->Gradient->GetPointer(0);
  double* depthOut = this->Depth->GetPointer(0);
  int* pixelOut = this->Pixel->GetPointer(0);
  int* viewOut = this->ViewIndex->GetPointer(0);
  int* hitOut = this->HitIndex->GetPointer(0);
  unsigned char* singularOut = this->Singular->GetPointer(0);
  unsigned char* tangentOut = this->Tangent->GetPointer(0);
  int* factorOut = this->Factor->GetPointer(0);
  const vtkIdType* rowOffsets = this->RowOffsets.data();
  // A row at a time (rows differ a lot in their number of hits: small chunks).
  pisurf::ParallelFor(0, static_cast<vtkIdType>(rows.size()), 4,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType r = begin; r < end; ++r)
      {
        const std::vector<RayHit>& row = rows[r];
        // Four hits at a time (RayCaster::Attributes evaluates them side by side).
        constexpr int Group = pisurf::ProductKernel::MaxVertices;
        for (size_t first = 0; first < row.size(); first += Group)
        {
          const int count = static_cast<int>(std::min<size_t>(Group, row.size() - first));
          double p[Group][3], nrm[Group][3], g[Group];
          int nearest[Group];
          bool isSingular[Group];
          for (int j = 0; j < count; ++j)
          {
            std::copy(row[first + j].P, row[first + j].P + 3, p[j]);
          }
          // Singular: F grows faster than linearly away from the hit.
          caster.Attributes(count, p, probe, singularTolerance, nrm, g, nearest, isSingular);
          for (int j = 0; j < count; ++j)
          {
            const RayHit& hit = row[first + j];
            const vtkIdType k = rowOffsets[r] + static_cast<vtkIdType>(first) + j;
            singularOut[k] = isSingular[j] ? 1 : 0;
            for (int c = 0; c < 3; ++c)
            {
              xyz[3 * k + c] = hit.P[c];
              nrmOut[3 * k + c] = static_cast<float>(nrm[j][c]);
            }
            gradientOut[k] = g[j];
            depthOut[k] = hit.T;
            pixelOut[2 * k] = hit.I;
            pixelOut[2 * k + 1] = hit.J;
            viewOut[k] = hit.View;
            hitOut[k] = hit.Index;
            tangentOut[k] = hit.Tangent ? 1 : 0;
            factorOut[k] = nearest[j];
          }
        }
      }
    });
}

std::vector<vtkDataArray*> RayHitAttributes::Arrays() const
{
  return { this->Normals, this->Gradient, this->Depth, this->Pixel, this->ViewIndex, this->HitIndex,
    this->Singular, this->Tangent, this->Factor };
}

void RayHitAttributes::ReleaseLargeRows(std::vector<std::vector<RayHit>>& rows)
{
  // Kept for the next execution up to 256 MiB of hits (4 M hits: six 1024² views of
  // first hits, or a few all-hit ones); more is released rather than held.
  size_t keptBytes = 0;
  for (const std::vector<RayHit>& row : rows)
  {
    keptBytes += row.capacity() * sizeof(RayHit);
  }
  if (keptBytes > (size_t(256) << 20))
  {
    std::vector<std::vector<RayHit>>().swap(rows);
  }
}
}
