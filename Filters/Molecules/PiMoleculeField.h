// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiMoleculeField.h
 * @brief molecular Π-surfaces: van der Waals radii and the atom-product field
 *
 * A molecule is a set of atom spheres f_i(p) = |p − c_i|² − R_i² (Raposo and Gomes,
 * "Π-surfaces", WSCG 2019, section "Molecular Π-surfaces"), and its surface is
 * F = Π g_i − level, in one of two modes:
 *
 * Global (the paper's surface): g_i = f_i, level = r. Every atom multiplies the product.
 *   Evaluation: space is cut into cubic cells of CellSize (2 Å; doubled until there are
 *   at most 2^21 cells, for atoms spread far apart). For a cell, the atoms
 *   whose centre lies within R_i + NearDistance (3 Å) of the cell's box are "near" and
 *   enter exactly; the others are "far" and enter through the second-order Taylor
 *   polynomial T of L(p) = Σ_far ln f_j(p) about the cell's centre (their f_j > 0, so
 *   the sign of the product is exactly the near atoms' sign). Two levels: far atoms
 *   beyond R_j + 8 Å of the cell's supercell (4³ cells, 8 Å) are expanded once per
 *   supercell about its centre (bound over the supercell, h its half-diagonal), and that
 *   quadratic is re-centred exactly on each cell; only the atoms in between are summed
 *   per cell, so building a cell costs the atoms within ~20 Å, not all atoms. The remainder is
 * bounded rigorously: along a direction δ, |d³/ds³ ln f_j| <= b_j = max(4/q^(3/2), e(4e² +
 * 12R_j²)/q³) with e the distance of c_j from the cell box and q = e² − R_j², so |L − T| <= B =
 * (h³/6)·Σ_far b_j with h the cell's half-diagonal. Where the approximate ln|P| is within B of ln r
 * (F's sign could depend on the approximation) the point is evaluated exactly over all atoms, so
 * the sign of F is always exact, the surface (and every vertex found by root finding) is the exact
 * one, and values away from the surface have a relative error below e^B − 1. Cost per point: the
 * near atoms (about 30 to 60 in a protein); per cell, the atoms within ~20 Å; per supercell (64
 * cells), all atoms. ClassifyBox uses only the atoms within R + NearDistance of the box (every
 * other factor is at least NearDistance²). A vertex usually costs one pass over its cell's near
 * atoms (FirstRoot). The product is accumulated with a separate binary exponent: 10^5 factors do
 * not overflow.
 *
 * Local: g_i = 1 + (f_i − 1)·w(u_i), with u_i = (|p − c_i|² − R_i²)/(ρ_i² − R_i²)
 *   clamped to [0, 1], ρ_i = R_i + InfluenceRadius and w(u) = 1 − u³(10 − 15u + 6u²)
 *   (the quintic smoothstep turned down). Properties: g_i = f_i inside the sphere (w = 1
 *   for |p − c_i| <= R_i), so the sign of g_i is the sign of f_i; outside, g_i is a
 *   convex combination of f_i > 0 and 1, hence positive; g_i = 1 beyond ρ_i; g_i is C²
 *   (w', w'' vanish at u = 0 and u = 1) and piecewise polynomial in p. As the influence
 *   radius grows, w → 1 at every fixed point and g_i → f_i: the Local surface tends to
 *   the Global one. The product is 1 far from the molecule, so the level must be below
 *   1: level = r/(1 + r), which is r to first order as r → 0 (the same limit of the
 *   union of spheres) and 1/2 at the paper's r = 1. Cost per point: the atoms within
 *   ρ_i, independent of the molecule's size. The mesher's boxes are evaluated at once
 *   (EvaluateBox: each atom visits only the points within its ρ, same bits as point by
 *   point) and its vertices on the atoms that reach their edge (RefineEdge).
 *
 * Radius tables (Å, by atomic number; 0 where the table has no value):
 *   Bondi: A. Bondi, "van der Waals Volumes and Radii", J. Phys. Chem. 68 (1964) 441–451
 *     (H 1.20, C 1.70, N 1.55, O 1.52, S 1.80, ...). These are the paper's 1.52 Å for O
 *     and 1.70 Å for C (the paper cites Batsanov for them, but they are Bondi's).
 *   Batsanov: S. S. Batsanov, "Van der Waals radii of elements", Inorganic Materials 37
 *     (2001) 871–885, the crystallographic radii (C 1.70, N 1.60, O 1.55, S 1.80, ...);
 *     that table has no hydrogen: H uses 1.10 Å (R. S. Rowland, R. Taylor, J. Phys. Chem.
 *     100 (1996) 7384–7391).
 */
#ifndef PiMoleculeField_h
#define PiMoleculeField_h

#include "PiField.h"
#include "PiRayRoots.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

namespace pisurf
{

/// Bondi (1964) van der Waals radius of element `z` in Å; 0 if the table has none.
double BondiRadius(int z);
/// Batsanov (2001) crystallographic van der Waals radius in Å (H: Rowland–Taylor 1.10);
/// 0 if the table has none.
double BatsanovRadius(int z);

enum class MoleculeMode
{
  Global = 0,
  Local = 1
};

struct MoleculeSettings
{
  MoleculeMode Mode = MoleculeMode::Global;
  double Blending = 1.0;        ///< r
  double InfluenceRadius = 2.0; ///< Local: g_i = 1 beyond R_i + InfluenceRadius (Å)
  double CellSize = 2.0;        ///< edge of the evaluation cells (Å)
  double NearDistance = 3.0;    ///< Global: atoms closer than R_i + this to a cell are exact
};

/// A Local-mode atom as MoleculeField's Local factor reads it, in one cache line: the
/// vertices' root finding reads a few dozen atoms per edge in no particular order, one
/// line each instead of one per array.
struct alignas(64) LocalAtom
{
  double C[3];        ///< the centre
  double R, R2;       ///< the radius and its square
  double Rho2;        ///< ρ² = (R + InfluenceRadius)²
  double InverseSpan; ///< 1/(ρ² − R²)
};

class MoleculeField : public Field
{
public:
  /// `centers` holds 3n coordinates, `radii` n positive radii. The cells cover `region`
  /// (where the field will be evaluated) and the molecule; the field is correct
  /// everywhere, but outside the cells Global mode evaluates every atom per point.
  MoleculeField(std::vector<double> centers, std::vector<double> radii,
    const MoleculeSettings& settings, const double region[6]);
  ~MoleculeField() override;

  int ClassifyBox(const double box[6]) const override;
  double Evaluate(const double p[3]) const override;
  double EvaluateCompressed(const double p[3]) const override;
  void EvaluateVertex(
    const double p[3], double normal[3], double& gradientNorm, int& nearest) const override;
  /// The same and ln|∇F| (−inf where ∇F = 0), which stays finite where |∇F| is clamped.
  void EvaluateVertex(const double p[3], double normal[3], double& gradientNorm, int& nearest,
    double& logGradientNorm) const;
  /// F(p) (clamped as Evaluate) and ln|F| without overflow.
  double EvaluateWithLog(const double p[3], double& logAbsF) const;
  /// The roots of F along the ray o + t·d for t in [t0, t1], in increasing t (only the
  /// first unless options.AllRoots), each within options.Tolerance (in units of t), none
  /// missed, at a cost that depends on the atoms near the ray and not on the molecule's
  /// size. The segment is cut where it crosses the cells; on each piece F is enclosed
  /// from its cell's atoms, each restricted exactly to the ray (f_i(t) is a quadratic:
  /// its exact range, and in Local mode g_i's by interval arithmetic on f_i, w(u) and
  /// f_i − 1), times the cell's far field (Global: e^(T(t) ± B), T's exact range). A
  /// piece whose enclosure excludes the level has no root; one whose derivative's
  /// enclosure excludes 0 holds one root at most, found by regula falsi where F changes
  /// sign; the others are halved down to the tolerance, where a piece is a root (a
  /// crossing if F changes sign across it, else Tangent), adjacent ones merged
  /// (RootCluster). Where only the far field's bound B keeps a piece undecided, every
  /// atom enters exactly instead. Global mode tries a shortcut first: where one sphere
  /// alone may vanish on a piece, the root is usually within rounding of where the ray
  /// crosses it (the other factors make the product huge), which enclosures on both
  /// sides of that crossing certify. Local mode drops an atom from a piece's halves once
  /// its influence no longer reaches the piece.
  void CastRay(const double o[3], const double d[3], double t0, double t1,
    const RayRootOptions& options, std::vector<RayRoot>& roots) const override;
  /// The six probes' test in logarithms, with ln|∇F| from EvaluateVertex and ln|F| from
  /// EvaluateWithLog: it holds at any size of the product.
  bool ProbeVertex(const double p[3], double probe, double tolerance, double normal[3],
    double& gradientNorm, int& nearest) const override;
  /// True inside any atom sphere (|p − c_i| < R_i), when the level is positive. On
  /// every sphere one factor vanishes (g_i = f_i there, in Local mode too), so P = 0 and
  /// F = −level < 0: no component of {F > 0} crosses a sphere. The outer one contains
  /// the far field, outside every sphere, so it and its closure (where P >= level > 0)
  /// stay outside every closed sphere.
  bool OffOuterSide(const double p[3]) const override;
  bool HasOffOuterSide() const override { return true; }
  /// Global mode: the first atom sphere the segment enters at s1 (where P = 0 < level);
  /// if a lower bound of |P| over [0, s1 − ε] (the near atoms' exact minima on the
  /// segment, times the far atoms' minima over the cell's box grown by 1 Å, kept per
  /// cell) exceeds the level, F > 0 there and the root is within ε of s1. True for most
  /// vertices of a protein, where the far atoms make P astronomically large off the
  /// spheres: the near atoms once per vertex instead of all atoms per root-finding step.
  bool FirstRoot(
    const double from[3], const double to[3], double tolerance, double& s) const override;
  /// Local mode: the atoms whose influence reaches the box are found once, and each one
  /// multiplies only the points within its ρ (the same products, in the same atom
  /// order, as Evaluate). Global mode: false.
  bool EvaluateBox(const double origin[3], const double spacing[3], const int first[3],
    const int last[3], long strideY, long strideZ, double* values) const override;
  /// Both modes: the atoms whose sphere meets the box are found once, and each marks
  /// the points strictly inside it (OffOuterSide's test, term by term).
  bool OffOuterSideBox(const double origin[3], const double spacing[3], const int first[3],
    const int last[3], long strideY, long strideZ, unsigned char* flags) const override;
  /// Local mode, for an edge along one axis no longer than a cell: the atoms whose ρ
  /// reaches the edge (from the cells of its two ends) are gathered once; the root is
  /// found on their product, and the vertex attributes and OffOuterSide come from them
  /// too. Global mode or other segments: false.
  bool RefineEdge(const double a[3], const double b[3], double va, double vb, int from,
    double tolerance, EdgeVertex& vertex) const override;

  /// ln|P(p)| over all atoms without any approximation, and the sign of P (−1, 0, 1).
  /// Cost O(atoms): for tests and reference values.
  int EvaluateExactSignAndLog(const double p[3], double& logAbs) const;
  /// The same with the cells' far-field approximation (what Evaluate uses away from the
  /// surface); `bound` receives the cell's bound B on the error of ln|P|.
  int EvaluateApproximateSignAndLog(const double p[3], double& logAbs, double& bound) const;

  /// The level the product is compared with: r (Global) or r/(1 + r) (Local).
  double GetLevel() const { return this->Level; }
  size_t GetNumberOfAtoms() const { return this->Radii.size(); }
  const MoleculeSettings& GetSettings() const { return this->Settings; }
  /// The largest far-field bound B of the cells used so far (0 in Local mode).
  double GetFarErrorBound() const { return this->MaxBound.load(); }
  /// Points evaluated exactly over all atoms because the approximation could not decide
  /// the sign (Global mode), since construction.
  long long GetNumberOfExactEvaluations() const { return this->ExactCount.load(); }

private:
  struct FarField;
  struct Cell;
  struct Expansion;
  struct Super;
  const Cell* CellAt(const double p[3]) const;
  // Calls visit(i) for each atom whose centre's bin lies within `margin` of the box,
  // until visit returns true; returns whether it did.
  template <class Visit>
  bool ForAtomsNear(const double box[6], double margin, Visit&& visit) const;
  const Super& SuperAt(const int cell[3]) const;
  void AddFar(const std::vector<int>& atoms, const double centre[3], const double box[6], double h,
    Expansion& out) const;
  void BuildCell(long id, Cell& cell) const;
  // The factor of atom i at p (f_i or the Local g_i) and, if g is not null, its gradient.
  double AtomFactor(size_t i, const double p[3], double* g) const;
  // Support of atom i: the distance from its centre beyond which it is "far" (Global)
  // or its factor is 1 (Local).
  double Reach(size_t i) const;
  // F(p) and ln|F| (for the compressed form).
  double Compute(const double p[3], double& logAbsF) const;
  // Local mode: F from the cell's atoms in plain doubles (|g_i| <= max(R_i², 1) and only
  // the few atoms whose sphere holds p are negative: no overflow), no logarithm.
  double ComputeLocal(const Cell* cell, const double p[3]) const;
  // Local mode: EvaluateVertex's answers at p over `atoms` (which must hold every atom
  // within its ρ of p) and, if `inside` is not null, OffOuterSide's (p strictly inside
  // one of their spheres).
  void LocalVertex(const double p[3], const int* atoms, size_t count, double normal[3],
    double& gradientNorm, int& nearest, bool* inside) const;
  double ComputeExact(const double p[3], double& logAbsF) const;
  // CastRay's search along one ray, chunk by chunk (see PiMoleculeFieldRays.cxx).
  struct RaySearch;

  std::vector<double> Centers;
  std::vector<double> Radii;
  // Local: per atom what its factor needs (see LocalAtom).
  std::vector<LocalAtom> Atoms;
  MoleculeSettings Settings;
  double Level;
  double MaxReach = 0.0;
  double MaxRadius = 0.0;
  double Origin[3];
  int Dims[3];
  std::vector<int> BinStart, BinAtoms; // atoms by cell (CSR)
  mutable std::vector<Cell> Cells;
  std::unique_ptr<std::once_flag[]> Once;
  // Per cell: set once the cell is built, so that CellAt costs one load afterwards.
  std::unique_ptr<std::atomic<char>[]> Ready;
  int SuperDims[3] = { 0, 0, 0 };
  mutable std::vector<Super> Supers;
  std::unique_ptr<std::once_flag[]> SuperOnce;
  mutable std::atomic<double> MaxBound{ 0.0 };
  mutable std::atomic<long long> ExactCount{ 0 };
};
}

#endif
