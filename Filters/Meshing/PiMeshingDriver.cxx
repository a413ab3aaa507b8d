// SPDX-License-Identifier: BSD-3-Clause
// The mesher's passes in order (see PiMeshingDriver.h).
#include "PiMeshingDriver.h"

#include "PiBlockClassifier.h"
#include "PiBlockSampler.h"
#include "PiLargeArrays.h"
#include "PiOuterEnvelope.h"
#include "PiPieceExchange.h"
#include "PiTiming.h"
#include "PiTriangleAssembly.h"
#include "PiVertexAttributes.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <iostream>

namespace pisurf
{
MeshingDriver::MeshingDriver(vtkAlgorithm* algorithm, MeshingWork& work, pisurf::PassTimer& lap)
  : Algorithm(algorithm)
  , Work(work)
  , Lap(lap)
{
}

MeshingDriver::~MeshingDriver() = default;

MeshingDriver::Result MeshingDriver::Run(const Field& field, BlockGrid& g, int piece, int pieces,
  const Settings& settings, vtkPolyData* output)
{
  this->TheField = &field;
  this->G = &g;
  this->Options = settings;
  this->ChooseSlab(piece, pieces);
  const Result sampled = this->Sample();
  if (sampled != Meshed)
  {
    return sampled;
  }
  this->Algorithm->UpdateProgress(0.5);
  this->Lap("sample");

  const std::unique_ptr<OuterEnvelope> envelope = this->Envelope();
  if (this->Algorithm->CheckAbort())
  {
    return Cancelled;
  }
  this->Algorithm->UpdateProgress(0.6);
  this->Lap("envelope");

  // PASS 5: count the crossing edges and triangles per active block; PASS 6: number and
  // write them.
  TriangleAssembly triangles;
  triangles.Run(g, envelope.get(), this->Slab, this->Work, this->Lap);
  this->Algorithm->UpdateProgress(0.75);
  this->Lap("contour");
  if (this->Algorithm->CheckAbort())
  {
    return Cancelled;
  }
  return this->PlaceVertices(envelope.get(), triangles, output);
}

void MeshingDriver::ChooseSlab(int piece, int pieces)
{
  const BlockGrid& g = *this->G;
  // This piece's slab of block layers along z (all of them for one piece).
  this->Slab.Piece = piece;
  this->Slab.Pieces = pieces;
  this->Slab.SlabBegin = static_cast<int>(vtkIdType(g.Count[2]) * piece / pieces);
  this->Slab.SlabEnd = static_cast<int>(vtkIdType(g.Count[2]) * (piece + 1) / pieces);
  const int slabBegin = this->Slab.SlabBegin, slabEnd = this->Slab.SlabEnd;
  // A piece of several works on its slab: it classifies and samples only the block
  // layers [slabBegin, slabEnd] (the layer above the slab numbers the vertices on the
  // plane they share) and, with OuterEnvelope, classifies the layer below too (its
  // skipped blocks decide the shared plane's points, as in a serial run); the outer
  // envelope is then flooded slab by slab with the other pieces (FloodAcrossPieces),
  // which needs piece p of n on process p of the global controller's n (ParaView's MPI
  // mode). Otherwise (several pieces in one process, with OuterEnvelope) every piece
  // classifies and samples the whole grid, as the envelope is a global property.
  const bool outerEnvelope = this->Options.OuterEnvelope;
  if (pieces > 1 && outerEnvelope)
  {
    this->Exchange = PieceExchange::ForPiece(piece, pieces);
  }
  const bool distributed = this->Exchange != nullptr;
  const bool slabOnly = pieces > 1 && (!outerEnvelope || distributed);
  this->Slab.SlabOnly = slabOnly;
  this->ClassifyBegin = slabOnly ? std::max(0, slabBegin - (outerEnvelope ? 1 : 0)) : 0;
  this->ClassifyEnd = slabOnly ? std::min(g.Count[2], slabEnd + 1) : g.Count[2];
  this->SampleBegin = slabOnly ? slabBegin : 0;
}

MeshingDriver::Result MeshingDriver::Sample()
{
  BlockGrid& g = *this->G;
  const ProductKernel* kernel = this->TheField->GetProductKernel();
  const bool distributed = this->Exchange != nullptr;
  vtkAlgorithm* const algorithm = this->Algorithm;
  pisurf::PassTimer& lap = this->Lap;

  // PASS 1: classify the blocks, coarse to fine.
  const size_t undecided = BlockClassifier::Run(*this->TheField, g, this->ClassifyBegin,
    this->ClassifyEnd, this->SampleBegin, this->Slab.SlabOnly);
  algorithm->UpdateProgress(0.1);
  lap("classify");
  if (lap.IsEnabled())
  {
    std::cerr << g.Active.size() << " of " << g.Sign.size() << " blocks active (" << undecided
              << " left undecided by their groups)\n";
  }

  // PASS 2: restrict the factors to the rows the active blocks need.
  RowRestriction& rows = this->Work.Rows;
  rows.CollectRows(g);
  const double count =
    rows.Restrict(kernel, g, static_cast<double>(this->Options.MaximumNumberOfSamples));
  const bool tooManyRows = count > 0.0;
  if (tooManyRows)
  {
    const vtkIdType maximum = this->Options.MaximumNumberOfSamples;
    vtkErrorWithObjectMacro(algorithm,
      << "The " << kernel->GetNumberOfFactors() << " factors restricted to the " << rows.Rows.size()
      << " grid rows the surface may cross need " << count * sizeof(double) / (1 << 20)
      << " MiB; the limit is " << maximum * sizeof(double) / (1 << 20)
      << " MiB (MaximumNumberOfSamples doubles): lower the Resolution or the "
         "number of primitives");
    // (A distributed piece over the cap skips its sampling, then tells the other pieces
    // below.)
    if (!distributed)
    {
      return Failed;
    }
  }
  lap("restrict rows");

  // PASS 3: evaluate the points of the active blocks.
  if (!tooManyRows)
  {
    BlockSampler::Run(*this->TheField, g, rows, this->Work.Values, algorithm, this->Abort);
  }
  // 0: go on, 1: cancelled, 2: failed. With the pieces flooding together every
  // process must reach the flood, or none: a piece that stops here (an error of its
  // own, a cancel) tells the others, and all stop.
  int stop = tooManyRows ? 2 : (this->Abort || algorithm->CheckAbort()) ? 1 : 0;
  if (distributed)
  {
    const int mine = stop;
    stop = this->Exchange->Maximum(mine);
    if (stop == 2 && mine != 2)
    {
      vtkErrorWithObjectMacro(
        algorithm, << "Another piece of the mesh failed (see its error): piece " << this->Slab.Piece
                   << " of " << this->Slab.Pieces << " stops too");
    }
  }
  return stop == 0 ? Meshed : (stop == 2 ? Failed : Cancelled);
}

std::unique_ptr<OuterEnvelope> MeshingDriver::Envelope()
{
  // PASS 4: the outer envelope (sign connectivity from the boundary).
  if (!this->Options.OuterEnvelope)
  {
    return nullptr;
  }
  return OuterEnvelope::Build(*this->G, this->Slab, *this->TheField, this->Exchange.get(),
    this->Work.EnvelopeFree, this->Work.EnvelopeReached, this->Lap);
}

MeshingDriver::Result MeshingDriver::PlaceVertices(
  const OuterEnvelope* envelope, const TriangleAssembly& triangles, vtkPolyData* output)
{
  // PASS 7: vertices.
  const vtkIdType vertices = triangles.GetNumberOfVertices();
  this->Vertices = vertices;
  vtkNew<vtkPoints> points;
  pisurf::AllocateLargePoints(points, vertices);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  pisurf::AllocateLargeArray(normals.GetPointer(), vertices);
  vtkNew<vtkIntArray> factor;
  factor->SetName("Factor");
  pisurf::AllocateLargeArray(factor.GetPointer(), vertices);
  vtkSmartPointer<vtkDoubleArray> gradientMagnitude;
  if (this->Options.ComputeGradientMagnitude)
  {
    gradientMagnitude = vtkSmartPointer<vtkDoubleArray>::New();
    gradientMagnitude->SetName("GradientMagnitude");
    pisurf::AllocateLargeArray(gradientMagnitude.GetPointer(), vertices);
  }
  const VertexAttributes attributes{ this->TheField, this->G, &this->Work.VertexEdge,
    &this->Work.VertexT, &this->Work.VertexEnds, vertices, &this->Work.Rows,
    this->Options.ProjectVertices, 1e-13 * this->Options.Size,
    envelope && envelope->GetOutside() > 0, points, normals, factor, gradientMagnitude,
    this->Algorithm, &this->Abort };
  attributes.Run();
  this->Work.ReleaseLargeWork();
  if (this->Abort || this->Algorithm->CheckAbort())
  {
    return Cancelled;
  }
  this->Lap("vertices");

  output->SetPoints(points);
  output->SetPolys(triangles.NewCells());
  output->GetPointData()->SetNormals(normals);
  output->GetPointData()->AddArray(factor);
  if (gradientMagnitude)
  {
    output->GetPointData()->AddArray(gradientMagnitude);
  }
  return Meshed;
}
}
