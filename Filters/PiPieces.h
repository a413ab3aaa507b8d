// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiPieces.h
 * @brief the piece request of an output, and asking an input for all of it
 *
 * ParaView's MPI mode asks each rank's algorithms for piece p of n. The algorithms of
 * this module read that request the same way (absent: piece 0 of 1), and those that
 * need all of their input (a whole molecule, a whole ray-cast cloud, a model) ask their
 * input for piece 0 of 1 on every rank.
 */
#ifndef PiPieces_h
#define PiPieces_h

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>

namespace pisurf
{

struct Piece
{
  int Piece = 0;
  int Pieces = 1;
};

/// The piece an output information asks for (piece 0 of 1 when it asks for none).
inline Piece PieceOf(vtkInformation* info)
{
  Piece p;
  if (info && info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()))
  {
    p.Piece = info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
  }
  if (info && info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()))
  {
    p.Pieces = std::max(1, info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()));
  }
  return p;
}

/// Asks the first connection of an input port for all of its data (piece 0 of 1, no
/// ghost levels), whatever piece this algorithm produces.
inline void RequestWholeInput(vtkInformationVector* port)
{
  if (vtkInformation* in = port ? port->GetInformationObject(0) : nullptr)
  {
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
}

}

#endif
