// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiMoleculeSurface
 * @brief molecular Π-surface: the product of the atoms' van der Waals spheres, meshed
 *
 * Each atom is a sphere f_i = |p − c_i|² − R_i² with a van der Waals radius R_i, and the
 * molecule's surface is the Π-surface of the atoms (Raposo and Gomes, "Π-surfaces",
 * WSCG 2019, section "Molecular Π-surfaces"):
 *
 * - Mode Global (default): F = Π f_i − r, the paper's surface, with Blending r (default
 *   1, the paper's value). Small r hugs the union of the spheres. Works for proteins:
 *   the product is accumulated with its own binary exponent (no overflow, exact sign),
 *   and far atoms enter each 2 Å cell through a Taylor polynomial of their log-product
 *   with a rigorous error bound (the farthest ones through one expansion per 8 Å
 *   supercell); points where that bound could change the sign are evaluated exactly, so
 *   the surface is exact (see PiMoleculeField.h for the formulas). Vertices are certified in
 *   one pass where the far atoms make the product huge off the spheres.
 * - Mode Local: F = Π g_i − r/(1 + r) with g_i = 1 + (f_i − 1)·w(u_i), a factor with the
 *   sign of f_i, C², equal to f_i inside the atom and to 1 beyond InfluenceRadius from
 *   its sphere (u_i = (|p − c_i|² − R_i²)/(ρ_i² − R_i²), ρ_i = R_i + InfluenceRadius,
 *   w(u) = 1 − u³(10 − 15u + 6u²)). Far atoms do not flatten the blend, so large
 *   molecules keep blended crevices; the cost per point does not depend on the size of
 *   the molecule. As InfluenceRadius grows the surface tends to the Global one (with r
 *   replaced by r/(1 + r)).
 *
 * Radii (RadiusTable): Bondi (1964; the paper's O 1.52 Å, C 1.70 Å), Batsanov (2001,
 * crystallographic; H 1.10 Å from Rowland and Taylor 1996), Blue Obelisk (VTK's
 * vtkPeriodicTable), or a per-atom point array (the input array to process, by default
 * `radius`, first component). Every radius is multiplied by RadiusScale. An element
 * missing from the chosen table takes its Blue Obelisk radius, with a warning naming it.
 *
 * Input: a vtkMolecule (Pi Molecule Reader, VTK's CML, XYZ, PDB molecule readers) or a
 * vtkPolyData whose points are atoms with the atomic number in the point array
 * `atom_type` (ParaView's stock PDB reader), or `AtomicNumber`.
 *
 * Output: the triangle mesh of the outer envelope (OuterEnvelope, default on) or of all
 * sheets. Where two atoms overlap, the product of their two negative factors is positive:
 * F > 0 in a lens-shaped region inside both, bounded by a closed sheet. The envelope
 * never includes it, however thin the F < 0 wall between it and the outside (at small r,
 * thinner than the grid): every sphere has F = −r < 0, so the outside component of
 * {F > 0} lies outside every sphere, and the mesher's flood fill does not enter points
 * inside a sphere (pisurf::Field::OffOuterSide). Exact vertices (roots of F on the grid
 * edges; an edge that runs into such a wall gets the root nearest the outside; with
 * ProjectVertices off, the linear interpolation along the edge instead), point
 * data `Normals`, `Factor` (index of the nearest atom) and `AtomicNumber`, and field data:
 * `PiMoleculeCenters`, `PiMoleculeRadii` (the atoms, compact) and `PiMoleculeSettings`
 * (Mode 0/1, Blending, InfluenceRadius, then the bounds: vtkPiRayCaster casts at the
 * molecule's field from these, either mode, any size), `PiSurfaceModel` (the Global
 * model as .pisurf JSON, up to 10000 atoms, for vtkPiImageTriangulator and others),
 * `SurfaceArea` and `EnclosedVolume` of the mesh (one-piece runs only; the volume is
 * Σ p0·(p1 × p2)/6 over the triangles, which face ∇F: the volume of {F < 0} inside it).
 *
 * Pieces (ParaView's MPI mode): every piece reads the whole molecule (piece 0 of 1 of
 * the input) and meshes its own slab of the grid; the union of the pieces is the
 * one-piece mesh. A piece's field data has no SurfaceArea or EnclosedVolume then (a
 * share would mislead): integrate the mesh (Integrate Variables) instead.
 *
 * Grid: `Spacing` in Å (default 0: automatic, 0.25 Å unless the grid would exceed 2^24
 * points, then the smallest spacing that fits). Bounds: the atoms' boxes grown until F
 * is positive on the whole boundary.
 *
 * Limits (refused with an error that says why): a grid above the mesher's cap
 * (2^28 samples, 2 GiB; the message gives the memory needed), atoms spanning more than
 * 10^6 Å, radii above 10^6 Å, and in Global mode atoms x 2 Å cells above 10^10 (about
 * 10^5 atoms for a protein: use Local mode, whose cost per point is constant).
 *
 * @warning The far-field cells and the mesher run threaded with vtkSMPTools.
 *
 * @sa vtkPiFlyingEdges vtkPiSurface vtkPiMoleculeReader vtkMolecule
 */
#ifndef vtkPiMoleculeSurface_h
#define vtkPiMoleculeSurface_h

#include "vtkPiSurfacesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class VTKPISURFACESFILTERS_EXPORT vtkPiMoleculeSurface : public vtkPolyDataAlgorithm
{
public:
  static vtkPiMoleculeSurface* New();
  vtkTypeMacro(vtkPiMoleculeSurface, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum RadiusTables
  {
    BONDI = 0,
    BATSANOV = 1,
    BLUE_OBELISK = 2,
    POINT_ARRAY = 3
  };
  enum Modes
  {
    GLOBAL = 0,
    LOCAL = 1
  };

  ///@{
  /// Source of the van der Waals radii (default BONDI).
  vtkSetClampMacro(RadiusTable, int, BONDI, POINT_ARRAY);
  vtkGetMacro(RadiusTable, int);
  ///@}

  ///@{
  /// Factor applied to every radius (default 1, > 0).
  vtkSetClampMacro(RadiusScale, double, 1e-6, 1e6);
  vtkGetMacro(RadiusScale, double);
  ///@}

  ///@{
  /// GLOBAL (default, the paper's product over all atoms) or LOCAL.
  vtkSetClampMacro(Mode, int, GLOBAL, LOCAL);
  vtkGetMacro(Mode, int);
  ///@}

  ///@{
  /// The blending r (default 1, the paper's value; >= 0).
  vtkSetMacro(Blending, double);
  vtkGetMacro(Blending, double);
  ///@}

  ///@{
  /// Local mode: distance beyond an atom's sphere where its factor becomes 1 (default
  /// 2 Å, at least 0.001 Å: below, the factor would jump from the sphere's value to 1).
  vtkSetMacro(InfluenceRadius, double);
  vtkGetMacro(InfluenceRadius, double);
  ///@}

  ///@{
  /// Grid spacing in Å (default 0: automatic, see the class description).
  vtkSetMacro(Spacing, double);
  vtkGetMacro(Spacing, double);
  ///@}

  ///@{
  /// Keep only the outer envelope (default on); off keeps the interior sheets too.
  vtkSetMacro(OuterEnvelope, bool);
  vtkGetMacro(OuterEnvelope, bool);
  vtkBooleanMacro(OuterEnvelope, bool);
  ///@}

  ///@{
  /// Exact vertices (default on): each vertex is the root of F on its grid edge, to
  /// 1e-13 of the grid's diagonal (vtkPiFlyingEdges::ProjectVertices). Off, vertices are
  /// the linear interpolation of F along the edge, as vtkFlyingEdges3D would place them
  /// (normals still the unit analytic gradient there), in about half the vertices' time:
  /// a preview. F bends sharply along the edges near the atoms, so those vertices lie
  /// well off the surface (1ubq, Local, 0.5 Å: median 0.07 Å, up to 0.49 Å, the area
  /// 5 % larger).
  vtkSetMacro(ProjectVertices, bool);
  vtkGetMacro(ProjectVertices, bool);
  vtkBooleanMacro(ProjectVertices, bool);
  ///@}

  /// The spacing the last execution used (Å).
  vtkGetMacro(LastSpacing, double);

protected:
  vtkPiMoleculeSurface();
  ~vtkPiMoleculeSurface() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int RadiusTable = BONDI;
  double RadiusScale = 1.0;
  int Mode = GLOBAL;
  double Blending = 1.0;
  double InfluenceRadius = 2.0;
  double Spacing = 0.0;
  bool OuterEnvelope = true;
  bool ProjectVertices = true;
  double LastSpacing = 0.0;

private:
  vtkPiMoleculeSurface(const vtkPiMoleculeSurface&) = delete;
  void operator=(const vtkPiMoleculeSurface&) = delete;
};

#endif
