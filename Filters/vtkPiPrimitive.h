// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiPrimitive
 * @brief an algebraic primitive of a Pi-surface (sphere, torus, quadric, polynomial...)
 *
 * vtkPiPrimitive is an implicit function whose value is an exact trivariate
 * polynomial in local coordinates (u, v, w) = R·(p − Center), w along the primitive's
 * axis. The types and their polynomials:
 *
 * | Type | parameters | polynomial |
 * |---|---|---|
 * | Sphere | Radius R | u²+v²+w² − R² |
 * | Ellipsoid | Radii a,b,c | (u/a)²+(v/b)²+(w/c)² − 1 |
 * | Superellipsoid | Radii a,b,c, Exponent n (even) | (u/a)^n+(v/b)^n+(w/c)^n − 1 |
 * | Torus | MajorRadius R, MinorRadius ρ | (u²+v²+w²+R²−ρ²)² − 4R²(u²+v²) |
 * | Plane | Normal n | n̂·(u,v,w) |
 * | Cylinder | Radius R | u²+v² − R² |
 * | Cone | Angle θ (half-angle, degrees) | u²+v² − tan²θ·w² |
 * | Hyperboloid1 | Radii a,b,c | (u/a)²+(v/b)² − (w/c)² − 1 |
 * | Hyperboloid2 | Radii a,b,c | (w/c)² − (u/a)² − (v/b)² − 1 |
 * | Paraboloid | Radii a,b | (u/a)²+(v/b)² − w |
 * | HyperbolicParaboloid | Radii a,b | (u/a)² − (v/b)² − w |
 * | Polynomial | Expression | the expression in x, y, z (= u, v, w) and parameters |
 *
 * Orientation: by default w is +z. Set Axis to point w elsewhere, or RotationAxis and
 * RotationAngle (degrees, right-handed, about Center) to rotate the primitive; not both.
 * Orientation (Euler angles, as a box widget's Rotation) turns it further.
 * Scale multiplies the polynomial and Negate flips its sign (the paper's inverted
 * primitives for depressions and concavities).
 *
 * Invalid parameters (a non-positive radius, an odd exponent, a malformed expression)
 * are reported through vtkErrorMacro when the primitive is next evaluated; IsValid()
 * tells, and the primitive keeps evaluating its last valid polynomial (NaN if it never
 * had one).
 *
 * @warning Evaluation is reentrant: several threads may evaluate one primitive at once.
 * Setting parameters while another thread evaluates is not allowed.
 *
 * @sa vtkPiSurface
 */
#ifndef vtkPiPrimitive_h
#define vtkPiPrimitive_h

#include "vtkImplicitFunction.h"
#include "vtkPiSurfacesFiltersModule.h" // for export macro

#include <map>    // for std::map
#include <memory> // for std::unique_ptr
#include <string> // for std::string

#ifndef __VTK_WRAP__
namespace pisurf
{
struct PrimitiveSpec;
struct PolynomialFactor;
}
#endif

class vtkDoubleArray;

class VTKPISURFACESFILTERS_EXPORT vtkPiPrimitive : public vtkImplicitFunction
{
public:
  static vtkPiPrimitive* New();
  vtkTypeMacro(vtkPiPrimitive, vtkImplicitFunction);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum PrimitiveTypes
  {
    SPHERE = 0,
    ELLIPSOID,
    SUPERELLIPSOID,
    TORUS,
    PLANE,
    CYLINDER,
    CONE,
    HYPERBOLOID1,
    HYPERBOLOID2,
    PARABOLOID,
    HYPERBOLIC_PARABOLOID,
    POLYNOMIAL
  };

  using vtkImplicitFunction::EvaluateFunction;
  double EvaluateFunction(double x[3]) override;
  void EvaluateGradient(double x[3], double g[3]) override;

  ///@{
  /// The primitive type (default SPHERE), clamped to the types of the primitive
  /// catalogue (Filters/Core/PiPrimitiveCatalogue.h), whose order the enum above names.
  /// SetTypeFromString accepts "Torus" or "torus".
  void SetType(int type);
  vtkGetMacro(Type, int);
  int GetTypeMinValue() { return SPHERE; }
  int GetTypeMaxValue() { return GetNumberOfTypes() - 1; }
  void SetTypeToSphere() { this->SetType(SPHERE); }
  void SetTypeToEllipsoid() { this->SetType(ELLIPSOID); }
  void SetTypeToSuperellipsoid() { this->SetType(SUPERELLIPSOID); }
  void SetTypeToTorus() { this->SetType(TORUS); }
  void SetTypeToPlane() { this->SetType(PLANE); }
  void SetTypeToCylinder() { this->SetType(CYLINDER); }
  void SetTypeToCone() { this->SetType(CONE); }
  void SetTypeToHyperboloid1() { this->SetType(HYPERBOLOID1); }
  void SetTypeToHyperboloid2() { this->SetType(HYPERBOLOID2); }
  void SetTypeToParaboloid() { this->SetType(PARABOLOID); }
  void SetTypeToHyperbolicParaboloid() { this->SetType(HYPERBOLIC_PARABOLOID); }
  void SetTypeToPolynomial() { this->SetType(POLYNOMIAL); }
  bool SetTypeFromString(const char* type);
  const char* GetTypeAsString();
  ///@}

  /// The number of primitive types (the catalogue's entries).
  static int GetNumberOfTypes();
  /// The primitive catalogue as JSON: each type's key, label, parameters (key, property,
  /// count, default, constraint, label, unit, tooltip) and widget. The tests read it to
  /// check the ParaView XML and the documentation against the catalogue.
  static std::string GetCatalogueJSON();

  ///@{
  /// Centre of the primitive (default 0,0,0).
  vtkSetVector3Macro(Center, double);
  vtkGetVector3Macro(Center, double);
  ///@}

  ///@{
  /// Local w axis of the primitive (default 0,0,1). Not together with a rotation.
  vtkSetVector3Macro(Axis, double);
  vtkGetVector3Macro(Axis, double);
  ///@}

  ///@{
  /// Rotation about Center: axis (default 0,0,1) and angle in degrees (default 0).
  vtkSetVector3Macro(RotationAxis, double);
  vtkGetVector3Macro(RotationAxis, double);
  vtkSetMacro(RotationAngle, double);
  vtkGetMacro(RotationAngle, double);
  ///@}

  ///@{
  /// A further turn about Center by Euler angles in degrees (default 0,0,0), as
  /// vtkProp3D's Orientation, ParaView's Transform and its box widget use them:
  /// R = Rz(z)·Rx(x)·Ry(y). It turns the
  /// primitive after Axis or RotationAxis/RotationAngle have placed it (the model then
  /// holds the composed rotation as one axis and angle).
  vtkSetVector3Macro(Orientation, double);
  vtkGetVector3Macro(Orientation, double);
  ///@}

  ///@{
  /// Radius of a sphere or cylinder (default 1).
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /// Semi-axes a, b, c of ellipsoids, superellipsoids, hyperboloids and paraboloids
  /// (default 1,1,1; paraboloids use a and b).
  vtkSetVector3Macro(Radii, double);
  vtkGetVector3Macro(Radii, double);
  ///@}

  ///@{
  /// Torus radii (default 1 and 0.25).
  vtkSetMacro(MajorRadius, double);
  vtkGetMacro(MajorRadius, double);
  vtkSetMacro(MinorRadius, double);
  vtkGetMacro(MinorRadius, double);
  ///@}

  ///@{
  /// Superellipsoid exponent: an even integer >= 2 (default 4).
  vtkSetMacro(Exponent, int);
  vtkGetMacro(Exponent, int);
  ///@}

  ///@{
  /// Plane normal (default 0,0,1; normalized when the polynomial is built).
  vtkSetVector3Macro(Normal, double);
  vtkGetVector3Macro(Normal, double);
  ///@}

  ///@{
  /// Cone half-angle in degrees, strictly between 0 and 90 (default 30).
  vtkSetMacro(Angle, double);
  vtkGetMacro(Angle, double);
  ///@}

  ///@{
  /// Polynomial expression in x, y, z and parameters (default empty).
  void SetExpression(const char* expression);
  const char* GetExpression();
  ///@}

  ///@{
  /// Named parameters usable in the expression (for example a model's "a").
  void SetParameter(const char* name, double value);
  double GetParameter(const char* name);
  void RemoveAllParameters();
  ///@}

  ///@{
  /// Multiplier of the polynomial (default 1; non-zero).
  vtkSetMacro(Scale, double);
  vtkGetMacro(Scale, double);
  ///@}

  ///@{
  /// Multiply the polynomial by −1 (default off).
  vtkSetMacro(Negate, bool);
  vtkGetMacro(Negate, bool);
  vtkBooleanMacro(Negate, bool);
  ///@}

  ///@{
  /// Name of the primitive in a model (default empty).
  void SetName(const char* name);
  const char* GetName();
  ///@}

  /// True if the current parameters define a valid primitive.
  bool IsValid();
  /// The reason the parameters are invalid (empty if valid).
  const char* GetErrorMessage();

  /// Total degree of the polynomial (-1 if invalid).
  int GetDegree();
  /// True for bounded types (the catalogue's: sphere, ellipsoid, superellipsoid, torus).
  bool IsBounded();
  /// World-space bounding box of a bounded primitive; false if unbounded or invalid.
  bool GetPrimitiveBounds(double bounds[6]);
  /// The polynomial expanded in world coordinates x, y, z, as expression text.
  std::string GetWorldPolynomial();
  /// Coefficients c0..cdeg of t -> f(origin + t·direction), ascending powers.
  void RestrictToLine(const double origin[3], const double direction[3], vtkDoubleArray* c);

#ifndef __VTK_WRAP__
  /// The parameters as a core description (what a .pisurf primitive holds).
  pisurf::PrimitiveSpec GetSpec();
  void SetSpec(const pisurf::PrimitiveSpec& spec);
  /// The current valid polynomial, or nullptr. Builds it if parameters changed.
  std::shared_ptr<const pisurf::PolynomialFactor> GetPolynomialFactor();
  /// The parameters the expression may use.
  const std::map<std::string, double>& GetParameters();
#endif

  void Modified() override;

protected:
  vtkPiPrimitive();
  ~vtkPiPrimitive() override;

  int Type = SPHERE;
  double Center[3] = { 0, 0, 0 };
  double Axis[3] = { 0, 0, 1 };
  double RotationAxis[3] = { 0, 0, 1 };
  double RotationAngle = 0.0;
  double Orientation[3] = { 0, 0, 0 };
  double Radius = 1.0;
  double Radii[3] = { 1, 1, 1 };
  double MajorRadius = 1.0;
  double MinorRadius = 0.25;
  int Exponent = 4;
  double Normal[3] = { 0, 0, 1 };
  double Angle = 30.0;
  double Scale = 1.0;
  bool Negate = false;

private:
  vtkPiPrimitive(const vtkPiPrimitive&) = delete;
  void operator=(const vtkPiPrimitive&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
