// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiPrimitiveSpec.h
 * @brief the algebraic primitives: their parameters, validation and exact polynomials
 *
 * A primitive is a polynomial in local coordinates (u, v, w) = R·(p − center), w along
 * the primitive's axis. Canonical forms (Documentation/pisurf-format.md):
 *   sphere               u²+v²+w² − R²
 *   ellipsoid            (u/a)²+(v/b)²+(w/c)² − 1
 *   superellipsoid       (u/a)^n+(v/b)^n+(w/c)^n − 1        n even, >= 2
 *   torus                (u²+v²+w²+R²−ρ²)² − 4R²(u²+v²)
 *   plane                n̂·(u,v,w)                          n̂ = normal / |normal|
 *   cylinder             u²+v² − R²
 *   cone                 u²+v² − tan²θ·w²                    θ half-angle in degrees
 *   hyperboloid1         (u/a)²+(v/b)² − (w/c)² − 1
 *   hyperboloid2         (w/c)² − (u/a)² − (v/b)² − 1
 *   paraboloid           (u/a)²+(v/b)² − w
 *   hyperbolic_paraboloid (u/a)² − (v/b)² − w
 *   polynomial           the expression, x y z standing for u v w
 * The whole polynomial is multiplied by `scale` and by −1 when `negate` is set.
 */
#ifndef PiPrimitiveSpec_h
#define PiPrimitiveSpec_h

#include "PiExpression.h"
#include "PiPolynomialFactor.h"

#include <string>

namespace pisurf
{

/// The types, in the order of their entries in PrimitiveCatalogue() (PiPrimitiveCatalogue.h),
/// which says everything else about them.
enum class PrimitiveType
{
  Sphere = 0,
  Ellipsoid,
  Superellipsoid,
  Torus,
  Plane,
  Cylinder,
  Cone,
  Hyperboloid1,
  Hyperboloid2,
  Paraboloid,
  HyperbolicParaboloid,
  Polynomial,
  NumberOfTypes
};

/// The .pisurf name ("hyperbolic_paraboloid") and the ParaView/VTK name
/// ("HyperbolicParaboloid") of a type.
const char* TypeKey(PrimitiveType t);
const char* TypeLabel(PrimitiveType t);
/// Either spelling; false if unknown.
bool TypeFromString(const std::string& s, PrimitiveType& t);

/// The orientation of an axial primitive.
enum class Orientation
{
  Default, // identity: w along +z
  Axis,    // w along Axis
  Rotation // rotated by RotationAngle degrees about RotationAxis (right-handed)
};

struct PrimitiveSpec
{
  PrimitiveType Type = PrimitiveType::Sphere;
  std::string Name;
  double Center[3] = { 0, 0, 0 };
  Orientation Orient = Orientation::Default;
  double Axis[3] = { 0, 0, 1 };
  double RotationAxis[3] = { 0, 0, 1 };
  double RotationAngle = 0.0;
  double Radius = 1.0;
  double Radii[3] = { 1, 1, 1 };
  double MajorRadius = 1.0;
  double MinorRadius = 0.25;
  int Exponent = 4;
  double Normal[3] = { 0, 0, 1 };
  double Angle = 30.0;
  std::string Expression;
  double Scale = 1.0;
  bool Negate = false;
};

/// Checks every parameter of `spec` (centre, scale and orientation, then the type's
/// parameters against their constraints in PiPrimitiveCatalogue.h) and builds the type's
/// polynomial (its catalogue entry's builder). On failure returns false with a message
/// naming the parameter.
bool BuildFactor(const PrimitiveSpec& spec, const ParameterMap& parameters,
  PolynomialFactor& factor, std::string& error);

/// v / |v| for a non-zero finite v, without overflow for extreme components.
void UnitVector(const double v[3], double u[3]);
/// Rotation matrix of `angleDeg` degrees about `axis` (need not be unit), right-handed.
void RotationMatrix(const double axis[3], double angleDeg, double R[3][3]);
/// The primitive's local frame from its orientation: local = R·(p − center), so the
/// rows of R are the local axes in world coordinates. False, naming the parameter, for
/// a zero or non-finite axis or angle.
bool OrientationMatrix(const PrimitiveSpec& spec, double R[3][3], std::string& error);
}

#endif
