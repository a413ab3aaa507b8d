// SPDX-License-Identifier: BSD-3-Clause
// RAY_LATTICE, passes 2 and 3: the sign of F at the lattice nodes (parity of the
// crossings along each z column), then the marching-cubes polygons of every cell with
// the crossings on its edges as vertices, split along the diagonals the surface bends
// least along.
#ifndef PiLatticeCells_h
#define PiLatticeCells_h

#include "PiHitLattice.h"
#include "PiPolygonTable.h"
#include "PiTiming.h"

#include <array>
#include <cstdint>
#include <vector>

namespace pisurf
{
namespace triangulator
{

// Reads the merged lines of HitLattice; moves the triangles (keys) into T.Rows and
// appends the roots computed on lattice edges (EdgeBit keys) to T.Points.
class LatticeCells
{
public:
  LatticeCells(Triangulation& t, const Lattice& l, const LatticeLines& lines);
  // Returns with T.Rows untouched if canceled (T.Abort).
  void Run(pisurf::PassTimer& lap);

private:
  // A vertex of a cell: its key, position and normal.
  struct Ref
  {
    std::int64_t Key;
    const double* P;
    const float* N;
  };
  // Per row, the flips of the columns through (i, j) and (i, j + 1), as CSR lists.
  // (Side 1 of row j is side 0 of row j + 1: each column is computed once per chunk.)
  struct Sides
  {
    std::vector<int> Flips[2];
    std::vector<size_t> Offset[2];
    std::vector<unsigned char> StartSign[2];
    std::vector<pisurf::RayRoot> Roots;
  };

  void ClassifyFaces();
  int NodeSign(int i, int j, int m) const;
  int FlipLevel(double x) const;
  unsigned char ColumnFlips(
    int i, int j, std::vector<int>& flips, std::vector<pisurf::RayRoot>& roots) const;
  void FillSide(Sides& s, int side, int jn) const;
  void Rows(vtkIdType jb, vtkIdType je);
  void Row(int j, const Sides& s, std::vector<std::int64_t>& tris, std::vector<Computed>& pts);
  void EmitCell(int i, int j, int m, const unsigned char* bottom, const unsigned char* top,
    std::vector<std::int64_t>& tris, std::vector<Computed>& pts);
  Ref Vertex(int a, int i, int jn, int m, Computed& c, std::vector<Computed>& pts);
  static void SplitPolygon(const Ref* v, int size, std::vector<std::int64_t>& tris);

  Triangulation& T;
  const Lattice& L;
  const LatticeLines& Lines;
  // Nodes per axis: the pixel centres and the two planes of the box.
  const int nx, ny, nz;
  // The largest progress reported: the reporting thread takes its chunks of rows in no
  // particular order, and only a larger value is reported, so progress never goes back.
  double ReportedProgress = 0.0;
  // Per face of the box: its sign if certified constant, else −1.
  int FaceSign[6];
  const std::array<std::vector<std::vector<int>>, 256>& Polygons;
  std::vector<std::vector<std::int64_t>> RowTriangles;
  std::vector<std::vector<Computed>> RowPoints;
};

} // namespace triangulator
} // namespace pisurf

#endif
