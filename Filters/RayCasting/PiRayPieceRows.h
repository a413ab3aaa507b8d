// SPDX-License-Identifier: BSD-3-Clause
// The piece pass of vtkPiRayCaster (ParaView's MPI mode): which image rows of every view
// this piece's points hold, and which rows it casts (the image port may ask for more).
#ifndef PiRayPieceRows_h
#define PiRayPieceRows_h

class vtkInformationVector;

namespace pisurf
{
struct RayPieceRows
{
  int Piece = 0, Pieces = 1;
  // The rows [PieceBegin, PieceEnd) of the points, [RowBegin, RowEnd) of the cast.
  int PieceBegin = 0, PieceEnd = 0;
  int RowBegin = 0, RowEnd = 0;

  /// Piece p of n holds rows [h p / n, h (p + 1) / n); a piece request on the image
  /// port (`hasImage`) widens the cast to the rows it asks for.
  static RayPieceRows Of(vtkInformationVector* outputVector, bool hasImage, int h);

  /// The cast holds rows beyond the piece's points.
  bool ExtraRows() const
  {
    return this->RowBegin != this->PieceBegin || this->RowEnd != this->PieceEnd;
  }
};
}

#endif
