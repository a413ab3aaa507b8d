// SPDX-License-Identifier: BSD-3-Clause
// The piece pass of vtkPiRayCaster: the image rows of this piece's points and cast.
#include "PiRayPieceRows.h"

#include "PiPieces.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>

namespace pisurf
{
RayPieceRows RayPieceRows::Of(vtkInformationVector* outputVector, bool hasImage, int h)
{
  // This piece's rows of every view; the image port's requested rows widen the cast (the
  // points keep to the piece, so the pieces' points do not overlap).
  RayPieceRows rows;
  const pisurf::Piece request = pisurf::PieceOf(outputVector->GetInformationObject(0));
  rows.Piece = request.Piece;
  rows.Pieces = request.Pieces;
  rows.PieceBegin = static_cast<int>(vtkIdType(h) * rows.Piece / rows.Pieces);
  rows.PieceEnd = static_cast<int>(vtkIdType(h) * (rows.Piece + 1) / rows.Pieces);
  rows.RowBegin = rows.PieceBegin;
  rows.RowEnd = rows.PieceEnd;
  vtkInformation* imageInfo = outputVector->GetInformationObject(1);
  // Only a piece request on the image port itself (ParaView showing the image in
  // parallel) widens the cast; its extent otherwise defaults to the whole image.
  if (hasImage && imageInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()) &&
    imageInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) &&
    imageInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) > 1)
  {
    int ue[6];
    imageInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ue);
    if (ue[2] <= ue[3])
    {
      rows.RowBegin = std::min(rows.RowBegin, std::max(ue[2], 0));
      rows.RowEnd = std::max(rows.RowEnd, std::min(ue[3] + 1, h));
    }
  }
  return rows;
}
}
