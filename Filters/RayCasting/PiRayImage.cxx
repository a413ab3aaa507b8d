// SPDX-License-Identifier: BSD-3-Clause
// The image pass of vtkPiRayCaster: a headlight shading of the first hits from their
// exact normals, and the ghost marks of rows cast beyond the piece.
#include "PiRayImage.h"

#include "PiLargeArrays.h"
#include "PiParallel.h"
#include "PiRayPieceRows.h"

#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>

namespace pisurf
{
void RayImage::Shade(const std::vector<RayView>& views, int w, int rowBegin, int rowEnd,
  const vtkIdType* rowOffsets, const double* hitDepth, const int* pixel, const int* hitIndex,
  vtkFloatArray* normals, vtkUnsignedCharArray* singular, vtkImageData* image)
{
  const int h = rowEnd - rowBegin;
  const int count = static_cast<int>(views.size());
  // Rows [rowBegin, rowEnd) of each view: the whole image, or this piece's slab of it.
  image->SetExtent(0, w - 1, rowBegin, rowEnd - 1, 0, count - 1);
  image->SetOrigin(0, 0, 0);
  image->SetSpacing(1, 1, 1);
  const vtkIdType pixels = vtkIdType(w) * h * count;
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("Shading");
  rgb->SetNumberOfComponents(3);
  pisurf::AllocateLargeArray(rgb.GetPointer(), pixels);
  vtkNew<vtkDoubleArray> depth;
  depth->SetName("Depth");
  pisurf::AllocateLargeArray(depth.GetPointer(), pixels);
  unsigned char* colour = rgb->GetPointer(0);
  double* depthOut = depth->GetPointer(0);
  const float* nrm = normals->GetPointer(0);
  const unsigned char* isSingular = singular->GetPointer(0);
  // Image row r (view r / h, row rowBegin + r % h) is hit row r: each row is filled with
  // the background (white, no hit) and then given its first hits, in one pass over the
  // image (a first hit is the only one of its pixel).
  pisurf::ParallelFor(0, vtkIdType(h) * count, 16,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType r = begin; r < end; ++r)
      {
        const RayView& v = views[static_cast<size_t>(r / h)];
        const vtkIdType first = r * w;
        std::fill(colour + 3 * first, colour + 3 * (first + w), static_cast<unsigned char>(255));
        std::fill(depthOut + first, depthOut + first + w, -1.0);
        for (vtkIdType k = rowOffsets[r]; k < rowOffsets[r + 1]; ++k)
        {
          if (hitIndex[k] != 0)
          {
            continue;
          }
          const int i = pixel[2 * k], j = pixel[2 * k + 1];
          const vtkIdType id = first + i;
          depthOut[id] = hitDepth[k];
          unsigned char* rgbOut = colour + 3 * id;
          if (isSingular[k])
          {
            rgbOut[0] = 220;
            rgbOut[1] = 30;
            rgbOut[2] = 30;
            continue;
          }
          // A headlight: light along the ray, Lambert plus a Phong highlight, two-sided.
          double d[3];
          for (int c = 0; c < 3; ++c)
          {
            d[c] = v.Perspective ? v.D[c] + i * v.U[c] + j * v.V[c] : v.D[c];
          }
          vtkMath::Normalize(d);
          const float* nf = nrm + 3 * k;
          const double lambert = std::fabs(nf[0] * d[0] + nf[1] * d[1] + nf[2] * d[2]);
          // (lambert^30 by squaring: a few multiplications instead of pow's logarithm)
          const double l2 = lambert * lambert, l4 = l2 * l2, l8 = l4 * l4, l16 = l8 * l8;
          const double value = 0.12 + 0.68 * lambert + 0.2 * (l16 * l8 * l4 * l2);
          const unsigned char c = static_cast<unsigned char>(std::min(255.0, 255.0 * value));
          rgbOut[0] = c;
          rgbOut[1] = c;
          rgbOut[2] = static_cast<unsigned char>(std::min(255, c + 12));
        }
      }
    });
  image->GetPointData()->SetScalars(rgb);
  image->GetPointData()->AddArray(depth);
}

void RayImage::MarkGhosts(const RayPieceRows& rows, int w, vtkImageData* image)
{
  // Rows beyond the piece (ghost rows asked by the image's consumer, or another split
  // of the rows) are marked as ghosts: each pixel belongs to one piece.
  const int rowBegin = rows.RowBegin, rowEnd = rows.RowEnd;
  const int pieceBegin = rows.PieceBegin, pieceEnd = rows.PieceEnd;
  vtkNew<vtkUnsignedCharArray> ghosts;
  ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
  ghosts->SetNumberOfTuples(image->GetNumberOfPoints());
  const vtkIdType rowsCast = rowEnd - rowBegin;
  for (vtkIdType id = 0; id < ghosts->GetNumberOfTuples(); ++id)
  {
    const int j = rowBegin + static_cast<int>((id / w) % rowsCast);
    ghosts->SetValue(
      id, j >= pieceBegin && j < pieceEnd ? 0 : vtkDataSetAttributes::DUPLICATEPOINT);
  }
  image->GetPointData()->AddArray(ghosts);
}
}
