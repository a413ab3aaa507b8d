// SPDX-License-Identifier: BSD-3-Clause
/**
 * PiImplicitBridge: the translation between VTK implicit functions and the exact model
 * of Filters/Core.
 *
 * - ExactFactor: the exact polynomial of a function (vtkPiPrimitive, and VTK's
 *   vtkSphere, vtkPlane, vtkCylinder, vtkCone and vtkQuadric, each with no transform or
 *   a linear one), or none: such a factor is evaluated through its virtual calls.
 * - MakeFunction: the implicit function that stands for a model's primitive (a
 *   vtkPiPrimitive).
 * - DescribeFactor: a factor's model entry (what GetModelJSON writes).
 * - SetFactorParameter: a model parameter passed on to a factor that takes parameters.
 *
 * vtkPiSurface is a container of vtkImplicitFunction and consults only this bridge for
 * concrete function types. Not VTK-wrapped.
 */
#ifndef PiImplicitBridge_h
#define PiImplicitBridge_h

#include "PiExpression.h"               // for pisurf::ParameterMap
#include "vtkPiSurfacesFiltersModule.h" // for export macro
#include "vtkSmartPointer.h"

#include <string>

class vtkImplicitFunction;

namespace pisurf
{
struct PolynomialFactor;
struct PrimitiveSpec;

/// What ExactFactor found.
enum class FactorKind
{
  Exact,   // `out` holds the polynomial, the function's transform folded in
  Generic, // no exact polynomial: evaluate the function through its virtual calls
  Invalid  // a primitive with invalid parameters: `error` says why
};

/// The exact polynomial of `f` (in world coordinates, its Transform applied).
VTKPISURFACESFILTERS_EXPORT FactorKind ExactFactor(
  vtkImplicitFunction* f, PolynomialFactor& out, std::string& error);

/// The implicit function of a model's primitive, with the model's parameters set.
VTKPISURFACESFILTERS_EXPORT vtkSmartPointer<vtkImplicitFunction> MakeFunction(
  const PrimitiveSpec& spec, const ParameterMap& parameters);

/// The model entry of factor `f`, whose exact polynomial is `exact`: the primitive's own
/// description when `f` is an untransformed primitive whose parameters agree with
/// `parameters` (its parameters missing there are added), else a Polynomial primitive
/// of the world polynomial, named after the primitive or the function's class.
VTKPISURFACESFILTERS_EXPORT PrimitiveSpec DescribeFactor(
  vtkImplicitFunction* f, const PolynomialFactor& exact, ParameterMap& parameters);

/// Sets parameter `name` of a factor that takes parameters (a primitive's expression);
/// with `onlyIfUnset`, only when the factor does not have it yet. Other factors ignore it.
VTKPISURFACESFILTERS_EXPORT void SetFactorParameter(
  vtkImplicitFunction* f, const std::string& name, double value, bool onlyIfUnset);
}

#endif
