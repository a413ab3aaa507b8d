// SPDX-License-Identifier: BSD-3-Clause
// PASS 7 of the mesher: each vertex's position (with ProjectVertices, the root of F on
// its grid edge, else the linear interpolation), then the exact unit normal, |∇F| and
// the nearest factor there.
#ifndef PiVertexAttributes_h
#define PiVertexAttributes_h

#include "PiBlockGrid.h"
#include "PiBuffer.h"
#include "PiField.h"
#include "PiRowRestriction.h"

#include <atomic>

class vtkAlgorithm;
class vtkDoubleArray;
class vtkFloatArray;
class vtkIntArray;
class vtkPoints;

namespace pisurf
{
struct VertexAttributes
{
  const Field* TheField;
  const BlockGrid* G;
  // Per vertex, from the contouring: edge key (point id · 3 + axis), crossing parameter
  // and F at the edge's two ends.
  const Buffer<vtkIdType>* VertexEdge;
  const Buffer<double>* VertexT;
  const Buffer<double>* VertexEnds;
  vtkIdType Vertices;
  // Pass 2's row restrictions (used with the field's product fast paths only).
  const RowRestriction* Rows;
  bool Project;          // move each vertex to the root on its edge
  double Tolerance;      // stop when the bracket is shorter than this
  bool PositiveEnvelope; // the outer envelope is on and its outside sign is +
  // The outputs, allocated for Vertices tuples (GradientMagnitude may be null).
  vtkPoints* Points;
  vtkFloatArray* Normals;
  vtkIntArray* Factor;
  vtkDoubleArray* GradientMagnitude;
  // Progress from 0.75 to 1 and cancel, through the main thread (this pass is the
  // longest for a large molecule).
  vtkAlgorithm* Algorithm;
  std::atomic<bool>* Abort;

  void Run() const;
};
}

#endif
