// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiEdgeFlips.h
 * @brief edge flips towards the curvature on a triangle mesh with exact normals
 *
 * Private to the Filters module (vtkPiImageTriangulator). Two triangles (x, y, c) and
 * (y, x, d) that share the edge x–y form a quad; its other diagonal c–d gives the
 * triangles (x, d, c) and (d, y, c). With exact unit normals n at the vertices, the
 * surface's deviation from a chord p–q at its middle is about |(n_p − n_q)·(q − p)| / 8
 * (the normal turns by κ·L along a chord of length L on a curve of curvature κ, and the
 * sagitta is κ·L²/8). A flip is worth it when that measure is smaller on c–d than on
 * x–y: the mesh then follows the surface's directions of least bending (and its
 * creases) instead of the lattice's.
 *
 * A flip is made only when the quad is convex (both new triangles face the old
 * quad's way and agree with their vertices' normals), when c and d are inside the mesh
 * (their fans of triangles close up), when c–d is not an edge yet, and when x and y
 * are the only common neighbours of c and d (so no two flips of one round
 * create the same edge and the mesh stays manifold). Each round flips, in parallel, the
 * edges that are the best candidate of both their triangles (an independent set, ties
 * broken by the pair's lower half-edge id); vertices never move, so the vertex count,
 * the edges on the boundary and the Euler characteristic are unchanged.
 */
#ifndef PiEdgeFlips_h
#define PiEdgeFlips_h

#include "vtkType.h"

#include <cstdint>

#include <cmath>

namespace pisurf
{

/// |(n_p − n_q)·(q − p)| for points p, q with unit normals np, nq: about 8 times the
/// surface's deviation from the chord p–q (see above). The measure of the triangulator's
/// choice of diagonals and of the flips.
inline double Bend(const double* p, const float* np, const double* q, const float* nq)
{
  double s = 0;
  for (int k = 0; k < 3; ++k)
  {
    s += (double(np[k]) - nq[k]) * (q[k] - p[k]);
  }
  return std::fabs(s);
}

struct EdgeFlipResult
{
  vtkIdType BoundaryEdges = 0; ///< edges used by one triangle
  vtkIdType Flips = 0;         ///< edges flipped, all rounds together
  int Rounds = 0;              ///< rounds that flipped something
};

/// Counts the boundary edges of the triangles `connectivity` (3 ids each, into `points`
/// points), then makes up to `rounds` rounds of flips, rewriting `connectivity` in
/// place. `xyz`: the points (3 doubles each); `normals`: unit normals (3 floats each).
/// Threaded with vtkSMPTools; the result does not depend on the number of threads.
EdgeFlipResult FlipEdgesToCurvature(vtkIdType* connectivity, vtkIdType triangles, vtkIdType points,
  const double* xyz, const float* normals, int rounds);
/// True when `triangles` triangles on `points` points fit vtkCellArray's 32-bit
/// storage (every id and the connectivity's length below 2^31 − 1): the filters then
/// store their cells in it, for half the memory.
bool FitsInt32Cells(vtkIdType triangles, vtkIdType points);
/// The same on 32-bit connectivity (vtkCellArray's 32-bit storage).
EdgeFlipResult FlipEdgesToCurvature(std::int32_t* connectivity, vtkIdType triangles,
  vtkIdType points, const double* xyz, const float* normals, int rounds);

}

#endif
