// SPDX-License-Identifier: BSD-3-Clause
// vtkPiFlyingEdges in pieces within one process (UpdatePiece, as a streaming pipeline
// asks): the union of the pieces is the serial mesh, with the outer envelope off (each
// piece classifies and samples only its slab of block layers and the layer above it)
// and on (each piece works on the whole grid, the envelope being global), with the
// primitives port too, including more pieces than block layers (empty pieces).
#include "PiTestUtilities.h"

#include "vtkPiFlyingEdges.h"
#include "vtkPiSurface.h"

#include "vtkMassProperties.h"
#include "vtkPolyData.h"

#include <string>

namespace
{
struct Mesh
{
  vtkIdType Triangles = 0;
  vtkIdType Primitives = 0;
  double Area = 0.0;
};

Mesh MeshPiece(vtkPiSurface* surface, int resolution, bool envelope, int piece, int pieces)
{
  vtkNew<vtkPiFlyingEdges> mesher;
  mesher->SetPiSurface(surface);
  mesher->SetResolution(resolution);
  mesher->SetOuterEnvelope(envelope);
  mesher->SetGeneratePrimitives(true);
  mesher->UpdatePiece(piece, pieces, 0);
  Mesh m;
  vtkPolyData* out = mesher->GetOutput();
  m.Triangles = out->GetNumberOfCells();
  m.Primitives = mesher->GetOutput(1)->GetNumberOfCells();
  if (m.Triangles > 0)
  {
    vtkNew<vtkMassProperties> mass;
    mass->SetInputData(out);
    mass->Update();
    m.Area = mass->GetSurfaceArea();
  }
  return m;
}
}

int TestPiPieces(int, char*[])
{
  int failures = 0;
  struct Case
  {
    const char* Model;
    int Resolution;
  };
  // formic acid: interior shells (the envelope matters); the cup: a cavity open at the
  // top; the table: thin legs; resolution 16: fewer block layers than pieces.
  for (const Case& c : { Case{ "formic_acid", 64 }, Case{ "cup_a1.0", 64 }, Case{ "table", 64 },
         Case{ "cup_a1.0", 16 } })
  {
    vtkSmartPointer<vtkPiSurface> surface = pitest::LoadModel(c.Model);
    for (bool envelope : { false, true })
    {
      const Mesh serial = MeshPiece(surface, c.Resolution, envelope, 0, 1);
      PI_CHECK(serial.Triangles > 100);
      for (int pieces : { 2, 3, 5 })
      {
        Mesh sum;
        int nonEmpty = 0;
        for (int piece = 0; piece < pieces; ++piece)
        {
          const Mesh m = MeshPiece(surface, c.Resolution, envelope, piece, pieces);
          sum.Triangles += m.Triangles;
          sum.Primitives += m.Primitives;
          sum.Area += m.Area;
          nonEmpty += m.Triangles > 0;
        }
        const std::string what = std::string(c.Model) + " at " + std::to_string(c.Resolution) +
          (envelope ? ", envelope on, " : ", envelope off, ") + std::to_string(pieces) + " pieces";
        if (sum.Triangles != serial.Triangles || sum.Primitives != serial.Primitives ||
          !(std::fabs(sum.Area - serial.Area) <= 1e-9 * serial.Area))
        {
          std::cerr << what << ": " << sum.Triangles << " triangles (serial " << serial.Triangles
                    << "), " << sum.Primitives << " primitive triangles (" << serial.Primitives
                    << "), area " << sum.Area << " (" << serial.Area << ")\n";
          ++failures;
        }
        // Several pieces hold triangles (a slab each), unless the grid has fewer block
        // layers than pieces.
        PI_CHECK(nonEmpty >= (c.Resolution >= 64 ? std::min(pieces, 3) : 1));
      }
    }
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
