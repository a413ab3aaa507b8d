// SPDX-License-Identifier: BSD-3-Clause
// The lattice of RAY_LATTICE (the pixel centres of axis views and the planes of their
// box), the samples on its lines, and the driver of the lattice passes.
#ifndef PiLattice_h
#define PiLattice_h

#include "PiTriangulation.h"

#include <climits>

namespace pisurf
{
namespace triangulator
{

// The lattice of RAY_LATTICE: per axis N pixel centres and the two planes of the box.
struct Lattice
{
  int N[3];
  double H[3], B0[3], B1[3];
  vtkIdType LineStart[4]; // first line of each axis, and the total

  double X(int a, int m) const
  {
    return m <= 0      ? this->B0[a]
      : m > this->N[a] ? this->B1[a]
                       : this->B0[a] + (m - 0.5) * this->H[a];
  }
  // The line of axis a through interior nodes mu (axis a+1) and mv (axis a+2), 1-based.
  vtkIdType Line(int a, int mu, int mv) const
  {
    return this->LineStart[a] + vtkIdType(mv - 1) * this->N[(a + 1) % 3] + (mu - 1);
  }
  bool HasLine(int a, int mu, int mv) const
  {
    return mu >= 1 && mu <= this->N[(a + 1) % 3] && mv >= 1 && mv <= this->N[(a + 2) % 3];
  }
};

// A root on a lattice line: 16 bytes (a line's few samples share a cache line).
struct Sample
{
  double X;            // coordinate along the line's axis
  std::int64_t Packed; // 2·(output key) + (1 if tangent); INT64_MIN: removed

  Sample() = default;
  Sample(double x, std::int64_t code, bool tangent)
    : X(x)
    , Packed(2 * code + (tangent ? 1 : 0))
  {
  }
  // The smallest sample at x (before every sample there).
  static Sample Lowest(double x)
  {
    Sample s;
    s.X = x;
    s.Packed = INT64_MIN;
    return s;
  }
  std::int64_t Code() const { return this->Packed >> 1; }
  bool Tangent() const { return (this->Packed & 1) != 0; }
  bool Removed() const { return this->Packed == INT64_MIN; }
  void Remove() { this->Packed = INT64_MIN; }
  void SetCode(std::int64_t code) { this->Packed = 2 * code + (this->Packed & 1); }
  // (by X, then by key: the key decides as before, since a line holds a key once)
  bool operator<(const Sample& o) const
  {
    return this->X < o.X || (this->X == o.X && this->Packed < o.Packed);
  }
};

// The lattice the views define, if they are axis views over one box covering the three
// axes with matching resolutions.
bool FindLattice(const Triangulation& T, Lattice& L);

// RAY_LATTICE: the triangles (T.Rows) and computed points (T.Points) of lattice L, by
// the HitLattice and LatticeCells passes; returns early with T.Abort set on a cancel
// or a missing model.
void RunLattice(Triangulation& T, const Lattice& L);

} // namespace triangulator
} // namespace pisurf

#endif
