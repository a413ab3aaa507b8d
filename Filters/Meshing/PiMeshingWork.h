// SPDX-License-Identifier: BSD-3-Clause
// The mesher's work buffers, kept between executions: interactive re-meshing (and every
// execution after the first) does not pay for fresh memory again.
#ifndef PiMeshingWork_h
#define PiMeshingWork_h

#include "PiBuffer.h"
#include "PiRowRestriction.h"

#include <cstddef>
#include <cstdint>

namespace pisurf
{
struct MeshingWork
{
  // The active blocks' values, grown (never shrunk) as executions need: uninitialized
  // (the sample pass writes every value; AllocateLarge).
  Buffer<double> Values;
  // The rows the active blocks need and their factors' restrictions.
  RowRestriction Rows;
  // The envelope's and the contouring's work arrays (per active block: free and reached
  // points, row signs, crossing-edge masks and offsets; per vertex: edge key, crossing
  // parameter, end values), kept between executions below WorkLimit bytes in all: a
  // re-execution then writes memory that is already mapped (at 256³ the cup's contouring faulted
  // ~20 MB in each time, a tenth of its time with two threads). Larger ones are released after use.
  Buffer<vtkIdType> VertexEdge;
  Buffer<double> VertexT, VertexEnds;
  Buffer<std::uint16_t> RowSigns, EdgeOffsets;
  Buffer<std::uint8_t> EdgeMasks;
  Buffer<std::uint16_t> EnvelopeFree, EnvelopeReached; // (see OuterEnvelope)
  static constexpr size_t WorkLimit = size_t(256) << 20;
  void ReleaseLargeWork()
  {
    const size_t bytes = this->VertexEdge.GetSize() * sizeof(vtkIdType) +
      (this->VertexT.GetSize() + this->VertexEnds.GetSize()) * sizeof(double) +
      (this->RowSigns.GetSize() + this->EdgeOffsets.GetSize() + this->EnvelopeFree.GetSize() +
        this->EnvelopeReached.GetSize()) *
        sizeof(std::uint16_t) +
      this->EdgeMasks.GetSize();
    if (bytes > WorkLimit)
    {
      this->VertexEdge.Release();
      this->VertexT.Release();
      this->VertexEnds.Release();
      this->RowSigns.Release();
      this->EdgeOffsets.Release();
      this->EdgeMasks.Release();
      this->EnvelopeFree.Release();
      this->EnvelopeReached.Release();
    }
  }
};
}

#endif
