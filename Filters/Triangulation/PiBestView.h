// SPDX-License-Identifier: BSD-3-Clause
// BEST_VIEW: each hit is owned by the view that sees it best, and within each view the
// hits of neighbouring pixels on one sheet are linked into the triangles of the pixel
// quads; a triangle is kept by the view that owns its three corners.
#ifndef PiBestView_h
#define PiBestView_h

#include "PiTriangulation.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace pisurf
{
namespace triangulator
{

// Reads T.C and T.Views; fills T.Rows with input hit ids, three per triangle.
class BestView
{
public:
  BestView(Triangulation& t, double sheetTolerance);
  void Run();

private:
  void SortHits();
  void ComputeFacing();
  void Own(vtkIdType b, vtkIdType e);
  void Triangulate();
  void Row(vtkIdType r);
  double Facing(vtkIdType id) const { return this->FacingOf[id]; }
  bool Linked(vtkIdType a, vtkIdType b) const;
  vtkIdType Match(vtkIdType a, vtkIdType px) const;

  Triangulation& T;
  const Cloud& C;
  const double SheetTolerance;
  // Per view and pixel, the hits sorted by depth (CSR): view v's pixels start at
  // PixelStart[v], pixel p's hits are Hits[First[p] .. First[p + 1]).
  std::vector<vtkIdType> PixelStart, First, Hits;
  // n·d of every hit with its own ray, once (the links ask for it many times).
  std::vector<double> FacingOf;
  std::vector<int> Owner;
  // (view, image row) of each row of pixel quads, and its triangles.
  std::vector<std::pair<size_t, int>> QuadRows;
  std::vector<std::vector<std::int64_t>> RowTriangles;
};

} // namespace triangulator
} // namespace pisurf

#endif
