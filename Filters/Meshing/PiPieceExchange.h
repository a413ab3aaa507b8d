// SPDX-License-Identifier: BSD-3-Clause
// What the mesher's pieces tell each other when they mesh together (ParaView's MPI
// mode): byte messages between neighbouring pieces and reductions over all of them.
// The passes see only this; PiPieceExchange.cxx implements it on VTK's global
// multi-process controller.
#ifndef PiPieceExchange_h
#define PiPieceExchange_h

#include "vtkType.h"

#include <memory>

namespace pisurf
{
class PieceExchange
{
public:
  /// The exchange of piece `piece` of `pieces` when the global controller runs exactly
  /// that: `pieces` processes, this one being process `piece`; null otherwise.
  static std::unique_ptr<PieceExchange> ForPiece(int piece, int pieces);

  virtual ~PieceExchange() = default;
  /// Blocking messages of `size` bytes to and from piece `other`.
  virtual void Send(const unsigned char* data, vtkIdType size, int other, int tag) = 0;
  virtual void Receive(unsigned char* data, vtkIdType size, int other, int tag) = 0;
  /// Reductions over every piece (every piece must call them, in the same order).
  virtual int Maximum(int value) = 0;
  virtual void Sum(const vtkIdType* values, vtkIdType* sums, vtkIdType count) = 0;
};
}

#endif
