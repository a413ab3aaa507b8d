// SPDX-License-Identifier: BSD-3-Clause
// The image pass of vtkPiRayCaster (output port 1): the shaded first hits and their
// depth, one slice per view, and the ghost marks of rows cast beyond the piece.
#ifndef PiRayImage_h
#define PiRayImage_h

#include "PiRayView.h"

#include "vtkType.h"

#include <vector>

class vtkFloatArray;
class vtkImageData;
class vtkUnsignedCharArray;

namespace pisurf
{
struct RayPieceRows;

class RayImage
{
public:
  /// The image of rows [rowBegin, rowEnd) of w pixels of every view, from the point
  /// arrays of the hits (all of them, also those of rows beyond the piece), which lie
  /// row after row: image row r (view by view) holds hits rowOffsets[r] to
  /// rowOffsets[r + 1] − 1.
  static void Shade(const std::vector<RayView>& views, int w, int rowBegin, int rowEnd,
    const vtkIdType* rowOffsets, const double* depth, const int* pixel, const int* hitIndex,
    vtkFloatArray* normals, vtkUnsignedCharArray* singular, vtkImageData* image);

  /// Marks the image's rows beyond the piece as ghosts.
  static void MarkGhosts(const RayPieceRows& rows, int w, vtkImageData* image);
};
}

#endif
