// SPDX-License-Identifier: BSD-3-Clause
// The mesher's passes in order, from a block grid to the output mesh: classify the
// blocks, restrict the factors to the rows, sample, flood the outer envelope, contour,
// place the vertices. Each pass is its own class in this folder; this one holds what
// they share for one execution (the grid, the piece's slab, the cancel flag).
#ifndef PiMeshingDriver_h
#define PiMeshingDriver_h

#include "PiBlockGrid.h"
#include "PiField.h"
#include "PiMeshingWork.h"

#include <atomic>
#include <memory>

namespace pisurf
{
class PassTimer;
}
class vtkAlgorithm;
class vtkPolyData;

namespace pisurf
{
class OuterEnvelope;
class PieceExchange;
class TriangleAssembly;

class MeshingDriver
{
public:
  struct Settings
  {
    bool OuterEnvelope;
    bool ProjectVertices;
    bool ComputeGradientMagnitude;
    vtkIdType MaximumNumberOfSamples; // the cap the row restrictions share
    double Size;                      // the diagonal of the bounds
  };
  enum Result
  {
    Failed,    // reported as an error on the algorithm
    Cancelled, // the output is left as it was
    Meshed
  };

  /// `algorithm` gets the progress, the errors and the cancel checks; `work` holds the
  /// buffers kept between executions; `lap` times the passes.
  MeshingDriver(vtkAlgorithm* algorithm, MeshingWork& work, pisurf::PassTimer& lap);
  ~MeshingDriver();

  /// Meshes `field` on g (Dims, Origin, Spacing and Count set) for piece `piece` of
  /// `pieces` into `output`'s points, triangles and point data. The passes take the
  /// field's product fast paths (Field::GetProductKernel) where it has them.
  Result Run(const Field& field, BlockGrid& g, int piece, int pieces, const Settings& settings,
    vtkPolyData* output);

  /// The vertices of the last mesh.
  vtkIdType GetNumberOfVertices() const { return this->Vertices; }

private:
  // The piece's slab of block layers and, when the pieces flood the envelope together,
  // their exchange.
  void ChooseSlab(int piece, int pieces);
  // PASSES 1 to 3, then the pieces agree to go on (or all stop).
  Result Sample();
  // PASS 4, with OuterEnvelope (else null).
  std::unique_ptr<OuterEnvelope> Envelope();
  // PASS 7 and the output arrays.
  Result PlaceVertices(
    const OuterEnvelope* envelope, const TriangleAssembly& triangles, vtkPolyData* output);

  vtkAlgorithm* Algorithm;
  MeshingWork& Work;
  pisurf::PassTimer& Lap;
  const Field* TheField = nullptr;
  BlockGrid* G = nullptr;
  Settings Options{};
  PieceSlab Slab;
  std::unique_ptr<PieceExchange> Exchange; // null unless the pieces flood together
  int ClassifyBegin = 0, ClassifyEnd = 0, SampleBegin = 0;
  std::atomic<bool> Abort{ false };
  vtkIdType Vertices = 0;
};
}

#endif
