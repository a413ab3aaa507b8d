// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiFlyingEdges
 * @brief triangle mesh of a Pi-surface F = 0: block-pruned sampling fused with contouring
 *
 * vtkPiFlyingEdges meshes the zero set of a vtkPiSurface over a regular grid spanning
 * the model bounds, in passes threaded with vtkSMPTools:
 *
 * 1. The grid is cut into blocks of 8³ cells. Each block gets an enclosure of every
 *    factor from its Taylor expansion about the block's centre (f(c + h∘u) = Σ b_α u^α,
 *    each term over u ∈ [−1, 1]³, one-axis quadratic parts exactly; width about
 *    |∇f|·h, without the cancellation of the monomial form), intersected above degree
 *    2 with the expression as written (so (8z+5)^6 is bounded tightly); factors above
 *    degree 8 use term-wise interval arithmetic, the mean-value form and the
 *    expression. The factors' enclosures are multiplied in doubles where nothing can
 *    overflow, else combined in sign and log-magnitude. A block whose enclosure of
 *    F = Π f_i − r excludes 0 is skipped: its sign is known and nothing in it is
 *    evaluated or contoured. Groups of 4³ blocks are classified first, then the 2³
 *    quarters of undecided groups (for a product of polynomials, the octants of a
 *    group or quarter, bounded from its own expansions, decide the quarters or blocks
 *    they hold exactly); a block is kept only if one of its octants (bounded from the
 *    block's own expansion) may hold the surface. For a product of polynomials, a
 *    block still undecided whose eight corners show F of both signs (or 0 at one)
 *    holds the surface for certain: it is kept without its enclosures (each corner
 *    evaluated once; the same blocks are kept).
 * 2. Every polynomial factor is restricted once to each grid row that crosses an
 *    active block (an exact univariate polynomial about the row's middle), so no
 *    virtual call is paid per point per factor, and every grid point evaluates
 *    identically whichever block asks (no cracks between blocks).
 * 3. The points of the active blocks are evaluated by Horner's rule, with the product
 *    accumulated overflow-safely (see vtkPiSurface): row by row, each run of
 *    consecutive needed blocks along a row in one call, so a point shared by several
 *    blocks is evaluated once.
 * 4. With OuterEnvelope, a flood fill from the boundary of the grid finds the outside
 *    region (see SetOuterEnvelope): skipped blocks are single nodes; an active block
 *    floods its points as bit masks (one per row of 9 points: free and reached) and
 *    hands the points it reaches on a face to the neighbour across it. The fill runs in
 *    rounds over the blocks reached in the round before, threaded (reached bits are
 *    only added, atomically): the same fixed point as a serial fill.
 * 5. Marching cubes, with VTK's case table (vtkMarchingCubesTriangleCases, the one
 *    vtkFlyingEdges3D also uses, so the same triangles), over the cells of the active
 *    blocks only, from the same row bit masks of the signs: the crossing edges of a row
 *    are its mask XOR its neighbour's, the cells with both signs a few AND/OR of four
 *    rows. Each crossing edge gets exactly one vertex, numbered by the block that owns
 *    its lower end; a triangle finds its own block's vertices in a table the block
 *    fills as it numbers them, a neighbour's by counting the crossings before its edge
 *    in the owner's row (no search).
 * 6. Vertices: with ProjectVertices (default on) each moves to the exact root of F on
 *    its grid edge. The edge's end values have opposite signs (the sign of F is exact),
 *    so the root is bracketed. Newton's method, kept in the bracket, finds the root in
 *    two or three steps, on four vertices at a time. Where every factor is a quadric
 *    or a quartic in the squares in an axis-aligned frame (spheres, ellipsoids,
 *    cylinders, tori, superquadrics of exponent 4, centred expressions: see
 *    pisurf::ProductKernel::HasStarFactorsOnly), each step evaluates the factors and
 *    their gradients at the four vertices' points at once, as the lanes of vector
 *    instructions, and the normals and nearest factors follow the same way. For other
 *    polynomials in an axis-aligned frame, the factors are restricted to the edge's
 *    line once (one pass over their terms; an x edge takes its row's restriction from
 *    pass 2, where every polynomial factor in any frame is restricted) and the four
 *    vertices' Newton steps on the restricted products run side by side, so that each
 *    vertex's chain of dependent operations overlaps the others'. Where
 *    the plain product would leave the double range (thousands of factors, F beyond
 *    1e200), Newton steps on F with the product kept as a logarithm,
 *    (1 − r/P) / Σ f_i'/f_i, safeguarded by bisection; otherwise
 *    (rotated frames, r = 0) regula falsi (Illinois) on F, or on the overflow-free
 *    sign(F)·ln(1 + |F|) where F is beyond 1e200 at an end, with bisection as a
 *    fallback, finds it (|F| below 1e-12 of its end values, or a bracket below 1e-13 of
 *    the model size: |F|/|∇F| <= 1e-9 × size is tested), even where F spans thousands of
 *    orders of magnitude along the edge. Off, vertices are the linear interpolation of
 *    F along the edge, as vtkFlyingEdges3D would place them.
 *
 * Output port 1 (GeneratePrimitives): the primitives themselves, each meshed alone on
 * the mesh's grid, kept while the factors, the grid, ProjectVertices and the piece stay
 * the same (a change of the blending alone re-meshes port 0 only). With
 * PrimitivesOnDemand they are computed only when port 1 itself is
 * asked for (a view showing it, `UpdatePipeline(proxy=..., port=1)`, `Update(1)`), not
 * when only the mesh is.
 *
 * Output point data: `Normals` (unit analytic gradient, pointing towards increasing F),
 * `Factor` (index of the primitive whose zero set is nearest, so each primitive's patch
 * can be coloured) and, with ComputeGradientMagnitude, `GradientMagnitude` (|∇F|).
 * Field data: `PiSurfaceModel`, the model as .pisurf JSON (with the meshed bounds when
 * the model has none), when every factor is a polynomial. Triangles face ∇F. The
 * triangles are in vtkCellArray's 32-bit storage when the point ids and the
 * connectivity's length fit 32 bits (half the memory), else in its 64-bit storage.
 *
 * Grid: `Bounds` (all zero = the model's bounds, see vtkPiSurface::GetModelBounds);
 * `Resolution` cells along the longest side (default 128), the other sides get cells
 * of (nearly) the same size; or `SampleDimensions` (points per axis, each >= 2) for
 * exact control. Grids above `MaximumNumberOfSamples` (default 2^28 samples) are
 * refused with the memory they would need.
 *
 * Pieces (ParaView's MPI mode, or UpdatePiece): piece p of n produces the triangles of
 * the blocks in layers [p·Cz/n, (p+1)·Cz/n) along z (Cz layers of blocks), its slab; the
 * union of the pieces is the serial mesh, with the seam vertices present in both
 * neighbours. A piece classifies and samples only its slab and the block layer above it
 * (which numbers the vertices on the plane they share), and, with OuterEnvelope, also
 * classifies the layer below (its skipped blocks decide the points of the shared plane,
 * as in a serial run). The outer envelope is a global property: in ParaView's MPI mode
 * (piece p of n on process p of n of vtkMultiProcessController's global controller)
 * each process floods its own slab, and the processes then hand each other, in rounds,
 * the reached points of the planes their slabs share, flooding on from them until a
 * round adds nothing anywhere (two rounds for the cup on four processes): the serial
 * envelope, whichever slabs the outside region winds through. Every process must then
 * execute the mesher together, as with VTK's other parallel filters (pvbatch
 * --symmetric for VTK-level scripts). Several pieces in one process with OuterEnvelope
 * (a streaming pipeline) each classify and sample the whole grid instead.
 *
 * The largest work buffer (the active blocks' values) is kept between executions, so
 * re-meshing does not pay for fresh memory again; it is released with the object. So
 * are each polynomial factor's row restrictions (pass 2), keyed by the factor's terms
 * and placement and by the grid:
 * when an edit changes one factor, only that factor is restricted again, and the mesh
 * is bit-identical to a fresh execution's (up to 64 MiB of coefficients; beyond that
 * every execution restricts every factor). The envelope's and the contouring's work
 * arrays are kept too, up to 256 MiB in all (larger ones are released after each
 * execution).
 *
 * Factors that are not polynomials have no interval enclosure: every block is then
 * active and they are evaluated point by point through their virtual calls.
 *
 * @sa vtkPiSurface vtkFlyingEdges3D vtkSampleFunction vtkMarchingCubes
 */
#ifndef vtkPiFlyingEdges_h
#define vtkPiFlyingEdges_h

#include "vtkPiSurfacesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr

class vtkPiSurface;
class vtkPolyData;
#ifndef __VTK_WRAP__
namespace pisurf
{
class Field;
}
#endif

namespace pisurf
{
class LastValidOutput;
}

class VTKPISURFACESFILTERS_EXPORT vtkPiFlyingEdges : public vtkPolyDataAlgorithm
{
public:
  static vtkPiFlyingEdges* New();
  vtkTypeMacro(vtkPiFlyingEdges, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The Pi-surface to mesh (required).
  void SetPiSurface(vtkPiSurface* surface);
  vtkGetObjectMacro(PiSurface, vtkPiSurface);
  ///@}

#ifndef __VTK_WRAP__
  /// Mesh this field instead of the Pi-surface's product (null, the default: the
  /// product). For functions with their own evaluation structures, such as the
  /// molecules of vtkPiMoleculeSurface. The field is meshed in Bounds, which must then
  /// be set; AutomaticResolution, GeneratePrimitives and the `PiSurfaceModel` field data
  /// do not apply (the caller describes its own model).
  void SetField(std::shared_ptr<const pisurf::Field> field);
#endif

  ///@{
  /// Region to sample [x0,x1,y0,y1,z0,z1]; all zero (the default) = the model's bounds.
  vtkSetVector6Macro(Bounds, double);
  vtkGetVector6Macro(Bounds, double);
  ///@}

  ///@{
  /// Cells along the longest side of the bounds (default 128, at least 1).
  vtkSetMacro(Resolution, int);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /// Choose the resolution automatically (default off): mesh at 32, 64, 128, ... cells
  /// along the longest side and stop at the first resolution whose mesh has the same
  /// number of connected components as the previous one and an area within 1% of it,
  /// so that thin parts and small components have appeared and the surface has
  /// settled. At most MaximumAutomaticResolution (default 512) and within
  /// MaximumNumberOfSamples; if it has not settled by then, the largest is used with
  /// a warning. Ignored when SampleDimensions is set. LastResolution tells the choice.
  vtkSetMacro(AutomaticResolution, bool);
  vtkGetMacro(AutomaticResolution, bool);
  vtkBooleanMacro(AutomaticResolution, bool);
  vtkSetClampMacro(MaximumAutomaticResolution, int, 32, 4096);
  vtkGetMacro(MaximumAutomaticResolution, int);
  vtkGetMacro(LastResolution, int);
  ///@}

  ///@{
  /// Grid points per axis; all zero (the default) = derived from Resolution.
  vtkSetVector3Macro(SampleDimensions, int);
  vtkGetVector3Macro(SampleDimensions, int);
  ///@}

  ///@{
  /// Largest grid accepted, in samples (default 2^28, i.e. 2 GiB of doubles); the
  /// factors' row polynomials share this cap. Refusals state the memory needed.
  vtkSetMacro(MaximumNumberOfSamples, vtkIdType);
  vtkGetMacro(MaximumNumberOfSamples, vtkIdType);
  ///@}

  ///@{
  /// Move each vertex to the root of F on its grid edge (default on), to about 1e-12 of
  /// the edge; off, vertices are the linear interpolation of F along the edge, as
  /// vtkFlyingEdges3D places them.
  vtkSetMacro(ProjectVertices, bool);
  vtkGetMacro(ProjectVertices, bool);
  vtkBooleanMacro(ProjectVertices, bool);
  ///@}

  ///@{
  /// Keep only the outer envelope (default on): the sheets that bound the region(s)
  /// connected to the boundary of the bounds through points of the outside sign, the
  /// sign F has on most of that boundary (positive for ordinary models, negative for
  /// a product that is negative far away). Closed interior sheets, such as the lens
  /// shells where two atoms overlap, are dropped.
  vtkSetMacro(OuterEnvelope, bool);
  vtkGetMacro(OuterEnvelope, bool);
  vtkBooleanMacro(OuterEnvelope, bool);
  ///@}

  ///@{
  /// Also mesh each primitive on its own (its factor alone, r = 0; unbounded ones
  /// clipped to the bounds) into output port 1, with `Factor` = its index, so that the
  /// primitives can be shown in colour under the Pi-surface as in the paper's figures
  /// (default off here; on in vtkPiSurfaceSource and the model reader).
  vtkSetMacro(GeneratePrimitives, bool);
  vtkGetMacro(GeneratePrimitives, bool);
  vtkBooleanMacro(GeneratePrimitives, bool);
  ///@}

  ///@{
  /// With GeneratePrimitives: compute port 1 only when port 1 itself is updated
  /// (`Update(1)`, a consumer's request from port 1), not when port 0 is. Off by default
  /// (a VTK mapper updates its input algorithm's first port whichever port it shows,
  /// and `Update()` then `GetOutput(1)` expects both).
  vtkSetMacro(PrimitivesOnDemand, bool);
  vtkGetMacro(PrimitivesOnDemand, bool);
  vtkBooleanMacro(PrimitivesOnDemand, bool);
  ///@}

  ///@{
  /// Add the point array `GradientMagnitude` (|∇F|, clamped to VTK_DOUBLE_MAX; default off).
  vtkSetMacro(ComputeGradientMagnitude, bool);
  vtkGetMacro(ComputeGradientMagnitude, bool);
  vtkBooleanMacro(ComputeGradientMagnitude, bool);
  ///@}

  /// The grid the next execution uses: dims and spacing from bounds and settings.
  /// False (with an error) for invalid settings.
  bool ComputeGrid(const double bounds[6], int dims[3], double spacing[3]);
  /// The same for a given resolution.
  bool ComputeGrid(const double bounds[6], int resolution, int dims[3], double spacing[3]);

  vtkMTimeType GetMTime() override;

  ///@{
  /// When an execution fails on a bad setting (an error is reported), keep the outputs
  /// of the last valid execution instead of empty ones (default off, VTK's convention;
  /// ParaView's proxies turn it on: the last valid surface stays while the error is
  /// shown).
  vtkSetMacro(KeepLastValidOutput, bool);
  vtkGetMacro(KeepLastValidOutput, bool);
  vtkBooleanMacro(KeepLastValidOutput, bool);
  ///@}

  /// Runs REQUEST_DATA through the last-valid-output guard (see KeepLastValidOutput).
  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs) override;

protected:
  vtkPiFlyingEdges();
  ~vtkPiFlyingEdges() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  // RequestData's work; RequestData turns a failed allocation into an error.
  int GenerateMesh(vtkInformationVector* outputVector);
  void ReportReferences(vtkGarbageCollector*) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  // AutomaticResolution's search; 0 (with an error) if no resolution fits.
  int ChooseResolution(const double bounds[6]);
  // REQUEST_DATA_NOT_GENERATED: the Primitives port is left as it is when only the mesh
  // is asked for, and the mesh when only the primitives are and it is up to date.
  void MarkPortsNotGenerated(vtkInformation* request, vtkInformationVector* outputs);
  // Port 1 with GeneratePrimitives, on the grid of the last mesh: kept from the last
  // time when the factors, grid, ProjectVertices and piece are the same.
  void OutputPrimitives(vtkInformationVector* outputVector);
  // Meshes each factor alone into `out` (port 1), for the same piece.
  void MeshPrimitives(
    const double bounds[6], const int dims[3], int piece, int pieces, vtkPolyData* out);

  vtkPiSurface* PiSurface = nullptr;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  int Resolution = 128;
  int SampleDimensions[3] = { 0, 0, 0 };
  vtkIdType MaximumNumberOfSamples = vtkIdType(1) << 28;
  bool ProjectVertices = true;
  bool OuterEnvelope = true;
  bool ComputeGradientMagnitude = false;
  bool GeneratePrimitives = false;
  bool PrimitivesOnDemand = false;
  bool AutomaticResolution = false;
  int MaximumAutomaticResolution = 512;
  int LastResolution = 0;

  bool KeepLastValidOutput = false;
  std::unique_ptr<pisurf::LastValidOutput> LastValid;

private:
  vtkPiFlyingEdges(const vtkPiFlyingEdges&) = delete;
  void operator=(const vtkPiFlyingEdges&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
