// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiImageTriangulator
 * @brief triangulates the ray hits of vtkPiRayCaster, using the pixel grid as connectivity
 *
 * The paper's image-based reconstruction: the samples of a ray cast come on a pixel
 * grid, so neighbouring pixels give the connectivity, and the exact gradients tell
 * where the surface is smooth and where it is singular. The vertices of the output are
 * the exact ray hits of the input (plus, where the views could not see the surface,
 * points computed exactly on F = 0 along the same rays). Two ways to merge views
 * (MergeMode):
 *
 * - RAY_LATTICE (tri-dexel contouring). Axis views over one box (SIX_AXIS_VIEWS,
 *   THREE_AXIS_DIRECTIONS, or any set of ±X, ±Y, ±Z views covering the three axes
 *   with matching resolutions) cast their rays along the lines of one lattice: the
 *   pixel centres of the views, plus the planes of the box. Every crossing of the
 *   surface with a lattice edge is a ray hit of the view along that edge, and the sign
 *   of F at a lattice node is the parity of the hits before it on its ray. Each lattice
 *   cell is cut by the marching-cubes polygons of its eight signs with those hits as
 *   vertices; each polygon is split into triangles along the diagonals the surface
 *   bends least along (the exact normals tell: see EdgeFlipRounds), not along a fixed
 *   table, so neighbouring pixels of one view are connected where the surface
 *   faces that view, and the views meet without a seam where it turns: the mesh is
 *   closed and manifold wherever the surface is inside the box. A surface point takes
 *   its vertices from the views in proportion to |n·d|, i.e. mostly from the view that
 *   sees it best. First-hit views see only the first crossing from each side; the
 *   crossings they hide (the inside of the cup) are computed with the same certified
 *   root finder on the hidden part of the ray (this needs the input's `PiSurfaceModel`,
 *   or the molecule of a Molecular Pi Surface: its field, in either mode and at any
 *   size, as vtkPiRayCaster uses it).
 *   Limits: a feature that enters and leaves between two lattice nodes on every ray
 *   (thinner than one pixel) has no sign change and is left out; its hits are counted
 *   in the field `UnusedHits`, with tangent hits.
 * - BEST_VIEW. Any views (cameras included). Within a view, the hits of the four
 *   pixels of each pixel quad are linked when they lie on one sheet: the same facing
 *   (sign of n·d) and a depth within SheetTolerance pixel footprints (divided by
 *   max(|n·d|, ¼), as a tangent plane predicts worse where it turns away) of the
 *   tangent plane of one of them; so a silhouette, a depth jump, or two layers of an all-hits
 *   view are never bridged. A quad of four linked hits is split along the diagonal
 *   through a singular hit if there is one (so creases and apices stay vertices with
 *   their own triangles), else along the shorter diagonal. With several views each hit
 *   is kept only by the view that sees it best (largest |n·d| among the views whose
 *   ray reaches it unoccluded), and a triangle is kept by the view that owns its three
 *   vertices. The seams between views stay open.
 * - AUTOMATIC (default): RAY_LATTICE when the views allow it, else BEST_VIEW.
 *
 * Output: triangles (then EdgeFlipRounds rounds of edge flips towards the curvature),
 * with the points in the order the triangles first use them, in vtkCellArray's 32-bit
 * storage when the point and connectivity counts fit (else 64-bit); point data `Normals`
 * (the exact unit gradient), `Singular`,
 * `ViewIndex` (the view whose ray holds the vertex), `Factor`; field data
 * `PiSurfaceModel` or the molecule's arrays (passed on), `BoundaryEdges` (edges used by one
 * triangle: 0 for a closed mesh), `UnusedHits` (hits that are not vertices), both of the whole
 * mesh.
 *
 * Pieces (ParaView's MPI mode): the views are merged and their seams closed across the
 * whole lattice, so every piece asks for the whole cloud (piece 0 of 1 of the input),
 * triangulates it, and keeps the triangles [T p / n, T (p + 1) / n) of the T triangles
 * and the points they use. The union of the pieces is the one-piece mesh; the work is
 * not divided.
 *
 * @warning Needs the point arrays `PixelIndex`, `ViewIndex`, `Depth` and `Normals` and
 * the field data `PiRayViews` of vtkPiRayCaster; a cloud without them is an error.
 * Threaded with vtkSMPTools; the output does not depend on the number of threads.
 *
 * @sa vtkPiRayCaster vtkPiFlyingEdges
 */
#ifndef vtkPiImageTriangulator_h
#define vtkPiImageTriangulator_h

#include "vtkPiSurfacesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class VTKPISURFACESFILTERS_EXPORT vtkPiImageTriangulator : public vtkPolyDataAlgorithm
{
public:
  static vtkPiImageTriangulator* New();
  vtkTypeMacro(vtkPiImageTriangulator, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum MergeModes
  {
    AUTOMATIC = 0,
    RAY_LATTICE,
    BEST_VIEW
  };

  ///@{
  /// How views are merged (default AUTOMATIC).
  vtkSetClampMacro(MergeMode, int, AUTOMATIC, BEST_VIEW);
  vtkGetMacro(MergeMode, int);
  ///@}

  ///@{
  /// BEST_VIEW: two hits of neighbouring pixels are on one sheet when the depth of one
  /// is within this many pixel footprints of the tangent plane of the other,
  /// divided by max(|n·d|, 1/4) (default 2).
  vtkSetClampMacro(SheetTolerance, double, 0.0, 1e6);
  vtkGetMacro(SheetTolerance, double);
  ///@}

  ///@{
  /// The singular test of the points computed here, as vtkPiRayCaster's (default 0.1).
  vtkSetClampMacro(SingularTolerance, double, 0.0, 1.0);
  vtkGetMacro(SingularTolerance, double);
  ///@}

  ///@{
  /// Rounds of edge flips towards the curvature (default 1; 0: none). Where two
  /// triangles form a convex quad whose other diagonal the surface bends less along
  /// (measured with the exact normals: |(n_p − n_q)·(q − p)|, about 8 times the
  /// surface's deviation from the chord p–q), their shared edge is swapped; each round
  /// flips, in parallel, the edges that are the best choice of both their triangles.
  /// Vertices, boundary and topology are unchanged; the triangles follow the surface's
  /// directions of least bending and its creases instead of the lattice's. (Within a
  /// lattice cell the same measure already picks the diagonals of each polygon; with 0
  /// the polygons are fanned from their first corner, as marching cubes does.) The
  /// first round, with that choice, adds about a quarter to the time, further rounds
  /// under a tenth each.
  vtkSetClampMacro(EdgeFlipRounds, int, 0, 100);
  vtkGetMacro(EdgeFlipRounds, int);
  ///@}

protected:
  vtkPiImageTriangulator();
  ~vtkPiImageTriangulator() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  static void KeepShare(vtkPolyData* mesh, int piece, int pieces);

  int MergeMode = AUTOMATIC;
  double SheetTolerance = 2.0;
  double SingularTolerance = 0.1;
  int EdgeFlipRounds = 1;

private:
  vtkPiImageTriangulator(const vtkPiImageTriangulator&) = delete;
  void operator=(const vtkPiImageTriangulator&) = delete;
};

#endif
