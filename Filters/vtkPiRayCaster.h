// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiRayCaster
 * @brief casts rays at a Pi-surface and returns every hit as a point with exact attributes
 *
 * The paper's geometry evaluation: each pixel's ray meets F = 0, giving surface samples
 * with exact gradients, classified regular or singular. Along a ray o + t·d every
 * polynomial factor is an exact univariate polynomial, and the roots of
 * F(t) = Π p_i(t) − r are isolated by subdivision with Bernstein enclosures and a
 * monotonicity proof (short segments are first tried with the factors' centred forms;
 * see Filters/RayCasting/PiRayRoots.h): no root is ever skipped, however
 * thin the feature, to a tolerance of 1e-10 of the model size. Roots where F touches 0
 * without changing sign are reported and flagged `Tangent`. Factors that are not
 * polynomials fall back to a sign scan of 4096 samples per ray with bisection, which
 * can miss features thinner than one sample.
 *
 * Views (ViewMode):
 * - CAMERA: rays through the pixel centres of a `Resolution` [w, h] image, as a VTK
 *   renderer of that size would cast them: perspective with `ViewAngle` (degrees, as
 *   vtkCamera), or parallel with `ParallelScale` (half the image height).
 * - axis views over the bounds [x0,x1,y0,y1,z0,z1], orthographic. Pixel (i, j) has
 *   image coordinates u = u0 + (i+½)(u1−u0)/w, v = v0 + (j+½)(v1−v0)/h, and Depth runs
 *   from 0 where the ray enters the bounds:
 *
 *   | view | u | v | ray start | direction |
 *   |---|---|---|---|---|
 *   | −Z | x | y | z = z1 | (0, 0, −1) |
 *   | −X | y | z | x = x1 | (−1, 0, 0) |
 *   | −Y | z | x | y = y1 | (0, −1, 0) |
 *   | +Z | x | y | z = z0 | (0, 0, +1) |
 *   | +X | y | z | x = x0 | (+1, 0, 0) |
 *   | +Y | z | x | y = y0 | (0, +1, 0) |
 *
 * - SIX_AXIS_VIEWS: the six views above (ViewIndex 0..5 in the order −Z, −X, −Y, +Z,
 *   +X, +Y); THREE_AXIS_DIRECTIONS: −Z, −X, −Y with all hits.
 *
 * Empty-space skipping (axis views and perspective cameras, polynomial factors,
 * SkipEmptySpace on): the rays of 128 × 128 pixel tiles are cut into boxes as deep as
 * wide, and undecided boxes into eight children (pixel halves, depth halves) down to
 * 8 × 8 pixels, each classified by the kernel's rigorous enclosure of F over the box
 * holding its rays (ProductKernel::ClassifyBox; an axis view's children are its box's
 * octants, classified at once by ClassifyBoxAndOctants). A ray searches only the depth
 * ranges of its column's undecided boxes, in increasing depth: the same roots, found on
 * short segments (at 1024², axis views of the cup, the table and ten spheres: 1.4 to 1.7
 * times faster; at 512², perspective views of them: 1.1 to 1.5 times). First hits in
 * an axis view: once a column of 8 × 8 rays meets a decided box of one sign and, behind
 * it, one of the other, every ray of the column has a root in between, and nothing
 * behind is classified or searched (on the cup at 1024², the octree's work fell to a
 * third). Cameras do not stop so: their boxes reach beyond the bounds, where the
 * clipped rays do not search. An axis view's leaves also learn, from the same Taylor
 * expansions, whether F is strictly monotone along the rays on them (the product rule
 * over enclosures of each factor's derivative excludes 0, or the logarithmic derivative
 * Σ ∂f_i/f_i does where at most one factor may vanish); a depth range made of such
 * leaves, all of one direction, is then decided by F's signs at the ends of each ray's
 * segment and Newton's method, without the root finder's enclosures (13 % fewer
 * instructions on the cup at 1024², 5 to 16 % on the gallery's models at 512²). Parallel
 * cameras are not skipped: their rays restrict cheaply from the view's grid and their
 * oblique boxes are loose, so the octree cost about what it saved.
 *
 * Output (points with one vertex each), point data: `Normals` (unit gradient),
 * `GradientMagnitude`, `Depth`, `PixelIndex` (i, j), `ViewIndex`, `HitIndex`
 * (0 = nearest), `Singular` (the gradient vanishes: |∇F|·h is at most
 * SingularTolerance, default 0.1, times the largest |F| at the six points p ± h·e_i,
 * h = 1e-3 of the model size; F then grows faster than linearly away from p, as at
 * apices, creases and self-intersections; the test is scale-free, so it holds for
 * products whose |∇F| varies by orders of magnitude over the surface; for products of
 * up to 32 polynomial factors the six values are not computed where the factors'
 * values and gradients at p, with bounds of their higher derivatives over the cell of
 * the bounds that holds p, already prove the answer "regular"; where every factor is a
 * quadric or a quartic in the squares in a diagonal frame, four hits at a time, as the
 * lanes of vector instructions, with the same results), `Tangent` and
 * `Factor` (the primitive nearest to zero there). Field data: `PiSurfaceModel` and
 * `PiRayViews` (17 numbers per view: type (0 axis/parallel, 1 perspective), w, h, the
 * ray origin of pixel (0, 0) (the eye for perspective), the per-pixel steps along u
 * and v, the direction of pixel (0, 0)'s ray, the segment length, and 1 if the view
 * holds all hits, 0 if first hits only), so that vtkPiImageTriangulator can rebuild
 * the pixel grid.
 *
 * The Pi-surface comes from the input's `PiSurfaceModel` field data (the model reader,
 * the Pi Surface source) when an input is connected, otherwise from SetPiSurface.
 * A molecule (the output of vtkPiMoleculeSurface: field data `PiMoleculeCenters`,
 * `PiMoleculeRadii`, `PiMoleculeSettings`) is cast at its own field instead, in either
 * mode and at any size (pisurf::MoleculeField::CastRay): the ray is cut at the field's
 * 2 Å cells, each piece enclosed from the atoms near its cell (restricted exactly to
 * the ray) and, in Global mode, the far atoms' certified Taylor bound, and its
 * derivative likewise (a monotone piece holds one root at most), with the same
 * guarantees (every root to 1e-10 of the size, tangent roots flagged) at a cost per
 * ray that does not grow with the molecule (1ubq Global, six axis views of 64² on two
 * threads: 0.16 s; the product path took 7.7 s). Its `Factor` is the atom whose sphere is nearest
 * the hit, and `Singular` uses the field's far-field values, which lie within their bound of the
 * exact ones (a borderline hit may be classified differently). The molecule's arrays pass to the
 * output's field data. vtkPiImageTriangulator needs a `PiSurfaceModel` (Global, up to 10 000
 * atoms).
 *
 * Output port 1 (vtkImageData, w × h × number of views, one slice per view, unit
 * spacing): the paper's immediate visualization of the first hits, `Shading` (RGB: a
 * headlight, Lambert plus a Phong highlight from the exact normals; singular pixels
 * red; white where the ray misses) and `Depth` (−1 where it misses).
 *
 * Pieces (ParaView's MPI mode): piece p of n casts the image rows [h p / n, h (p + 1) / n)
 * of every view. Its points are the hits of those rows (the pieces' points together are
 * the one-piece output) and its image is that row slab (extent [0, w−1, row0, row1−1,
 * 0, views−1]; the image port splits in Y slabs). A request for image rows beyond the
 * piece widens the cast, never the points.
 *
 * Speed (polynomial products): orthographic views (axis and parallel camera) restrict
 * their rays from one composition of each factor per view (pisurf::RayGrid, about the
 * grid centre and the middle of the box, which is also more accurate than restricting
 * at the ray start); the octree above skips empty space; rows are threaded with
 * vtkSMPTools. `PISURF_TIMING=1` prints the CPU time of each pass and how many depth
 * ranges are searched. Its rays per second are measured by `./run bench`
 * (Documentation/benchmarks.md).
 *
 * @sa vtkPiSurface vtkPiFlyingEdges
 */
#ifndef vtkPiRayCaster_h
#define vtkPiRayCaster_h

#include "vtkPiSurfacesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class vtkPiSurface;
#ifndef __VTK_WRAP__
namespace pisurf
{
struct RayHitRows;
}
#endif

class VTKPISURFACESFILTERS_EXPORT vtkPiRayCaster : public vtkPolyDataAlgorithm
{
public:
  static vtkPiRayCaster* New();
  vtkTypeMacro(vtkPiRayCaster, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ViewModes
  {
    CAMERA = 0,
    PLUS_X,
    MINUS_X,
    PLUS_Y,
    MINUS_Y,
    PLUS_Z,
    MINUS_Z,
    SIX_AXIS_VIEWS,
    THREE_AXIS_DIRECTIONS
  };

  ///@{
  /// The Pi-surface, used when no input is connected.
  void SetPiSurface(vtkPiSurface* surface);
  vtkGetObjectMacro(PiSurface, vtkPiSurface);
  ///@}

  ///@{
  /// The views (default MINUS_Z).
  vtkSetClampMacro(ViewMode, int, CAMERA, THREE_AXIS_DIRECTIONS);
  vtkGetMacro(ViewMode, int);
  ///@}

  ///@{
  /// Image size in pixels, w × h (default 512 × 512). A cast needing more than 2 GiB
  /// (about 160 bytes per ray and view) is refused with the memory it would need.
  vtkSetVector2Macro(Resolution, int);
  vtkGetVector2Macro(Resolution, int);
  ///@}

  ///@{
  /// Every hit along each ray (on) or the nearest only (default off).
  vtkSetMacro(AllHits, bool);
  vtkGetMacro(AllHits, bool);
  vtkBooleanMacro(AllHits, bool);
  ///@}

  ///@{
  /// Region the rays are clipped to; all zero (default) = the model's bounds.
  vtkSetVector6Macro(Bounds, double);
  vtkGetVector6Macro(Bounds, double);
  ///@}

  ///@{
  /// The camera of CAMERA mode (defaults: position (0, 0, 10), focal point origin,
  /// view up +y, view angle 30°, perspective, parallel scale 1).
  vtkSetVector3Macro(CameraPosition, double);
  vtkGetVector3Macro(CameraPosition, double);
  vtkSetVector3Macro(CameraFocalPoint, double);
  vtkGetVector3Macro(CameraFocalPoint, double);
  vtkSetVector3Macro(CameraViewUp, double);
  vtkGetVector3Macro(CameraViewUp, double);
  vtkSetMacro(ViewAngle, double);
  vtkGetMacro(ViewAngle, double);
  vtkSetMacro(ParallelProjection, bool);
  vtkGetMacro(ParallelProjection, bool);
  vtkBooleanMacro(ParallelProjection, bool);
  vtkSetMacro(ParallelScale, double);
  vtkGetMacro(ParallelScale, double);
  ///@}

  ///@{
  /// A hit is Singular when |∇F|·h is at most this fraction of the largest |F| at
  /// p ± h·e_i, h = 1e-3 of the model size (default 0.1).
  vtkSetMacro(SingularTolerance, double);
  vtkGetMacro(SingularTolerance, double);
  ///@}

  ///@{
  /// Empty-space skipping for the axis views (default on): boxes of rays where the
  /// model's enclosure proves F > 0 or F < 0 are not searched (it never skips a root;
  /// see the class description). Off, every ray searches its whole segment: the same
  /// hits, slower; for comparisons and tests.
  vtkSetMacro(SkipEmptySpace, bool);
  vtkGetMacro(SkipEmptySpace, bool);
  vtkBooleanMacro(SkipEmptySpace, bool);
  ///@}

  vtkMTimeType GetMTime() override;

protected:
  vtkPiRayCaster();
  ~vtkPiRayCaster() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  void ReportReferences(vtkGarbageCollector*) override;

  vtkPiSurface* PiSurface = nullptr;
  int ViewMode = MINUS_Z;
  int Resolution[2] = { 512, 512 };
  bool AllHits = false;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  double CameraPosition[3] = { 0, 0, 10 };
  double CameraFocalPoint[3] = { 0, 0, 0 };
  double CameraViewUp[3] = { 0, 1, 0 };
  double ViewAngle = 30.0;
  bool ParallelProjection = false;
  double ParallelScale = 1.0;
  double SingularTolerance = 0.1;
  bool SkipEmptySpace = true;

private:
#ifndef __VTK_WRAP__
  // Per image row: its hits, kept (emptied, not freed) from one execution to the next,
  // so that casting again does not fault that memory in again (up to 256 MiB of them;
  // a larger cast releases them).
  pisurf::RayHitRows* Rows;
#endif
  vtkPiRayCaster(const vtkPiRayCaster&) = delete;
  void operator=(const vtkPiRayCaster&) = delete;
};

#endif
