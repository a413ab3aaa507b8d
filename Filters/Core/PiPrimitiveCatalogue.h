// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiPrimitiveCatalogue.h
 * @brief the primitive types, one entry each: the single source of truth
 *
 * Every place that treats primitive types one by one iterates this catalogue instead of
 * keeping its own list: the .pisurf reader and writer (PiModel.cxx), BuildFactor
 * (PiPrimitiveSpec.cxx: the constraints, then the entry's polynomial), vtkPiPrimitive's
 * defaults and IsBounded, vtkPiPrimitiveSource's automatic box, the Qt editor's field
 * table and row summary (pqPiPrimitiveListWidget), the 3D widget of the editor
 * (pqPiPrimitive3DWidget) and of the Pi Primitive panel (pqPiPrimitivePlacementWidget),
 * and the build tool Plugin/XML/PiCatalogueXML.cxx, which writes the Pi Primitive
 * proxy's Type enumeration and the types of its visibility decorators into the XML.
 * Testing/Core/TestPiPrimitiveCatalogue.cxx checks the catalogue's own consistency and
 * Testing/Python/TestPiPrimitiveCatalogue.py checks the ParaView XML and
 * Documentation/pisurf-format.md against it (vtkPiPrimitive::GetCatalogueJSON).
 *
 * An entry's index is its PrimitiveType value, which is also the Pi Primitive proxy's
 * `Type` enumeration value: entries are only ever appended.
 *
 * Parameters hold their values in PrimitiveSpec's members (Radius, Radii, ...); two
 * types whose parameters have the same key share the member, its property and its
 * default (a test checks it).
 */
#ifndef PiPrimitiveCatalogue_h
#define PiPrimitiveCatalogue_h

#include "PiPrimitiveSpec.h"

#include <memory>
#include <string>
#include <vector>

namespace pisurf
{

/// How a parameter's values are stored and typed.
enum class ParameterKind
{
  Number,  // Count doubles
  Integer, // one int
  Text     // one string
};

/// What every component of a parameter must satisfy. BuildFactor checks it, in the
/// order of the type's parameters, with the message "<key> must be <ConstraintText>".
enum class Constraint
{
  Positive,       // finite and > 0
  NonZeroVector,  // finite components, not all zero
  EvenExponent,   // an even integer from 2 to MaxDegree
  OpenRightAngle, // degrees strictly between 0 and 90
  Expression      // a polynomial expression (checked as the builder parses it)
};

/// The ParaView widget that places a primitive in a render view. The Pi Primitive
/// panel shows each kind; the editor of Pi Surface shows a sphere, a box for a bounded
/// type, and a handle at the centre otherwise (pqPiPrimitive3DWidget).
enum class WidgetKind
{
  Sphere,   // centre and WidgetSize (a radius)
  Cylinder, // centre, WidgetDirection (the axis) and WidgetSize (a radius)
  Plane,    // centre and WidgetDirection (the normal)
  Box,      // centre, orientation and WidgetSize (three semi-axes)
  Handle    // the centre only
};

/// One parameter of one primitive type.
struct ParameterInfo
{
  const char* Key;      // the .pisurf key, "major_radius"
  const char* Property; // the vtkPiPrimitive / Pi Primitive property, "MajorRadius"
  ParameterKind Kind;
  int Count;               // components read and written (radii: 2 or 3)
  double Default[3];       // Number: the first Count; Integer: Default[0]
  const char* DefaultText; // Text
  Constraint Rule;
  const char* Label;   // the editor's label, without the unit: "Major radius R"
  const char* Symbol;  // the editor's row summary: "R"; "a b c" names each component
  const char* Unit;    // "length", "degrees", or "" for none
  const char* Tooltip; // the editor's tooltip
  // Where a spec holds the values: exactly the one accessor of the kind is set.
  double* (*Numbers)(PrimitiveSpec&);
  int* (*Integer)(PrimitiveSpec&);
  std::string* (*Text)(PrimitiveSpec&);
};

/// The local polynomial of a primitive whose parameters passed their constraints.
struct PrimitiveShape
{
  Polynomial3 Poly;
  std::shared_ptr<const ExpressionNode> Natural; // a polynomial's expression tree
  double Shift[3] = { 0, 0, 0 };                 // the expression's variables are q + Shift
  double Half[3] = { -1, -1, -1 };               // local half extents; negative: unbounded
};

/// One primitive type.
struct PrimitiveInfo
{
  PrimitiveType Type;
  const char* Key;   // the .pisurf name, "hyperbolic_paraboloid"
  const char* Label; // the ParaView/VTK name and the XML's Type text, "HyperbolicParaboloid"
  std::vector<ParameterInfo> Parameters;
  bool Bounded; // the surface lies in a box given by the parameters (Half set)
  /// The canonical polynomial (Documentation/pisurf-format.md). Only called when every
  /// parameter satisfied its constraint; false with a message otherwise.
  bool (*Build)(const PrimitiveSpec& spec, const ParameterMap& parameters, PrimitiveShape& shape,
    std::string& error);
  WidgetKind Widget;
  const char* WidgetSize;      // the property the widget's radius or scale edits, or null
  const char* WidgetDirection; // the property the widget's axis or normal edits, or null
};

/// Every type, indexed by PrimitiveType.
const std::vector<PrimitiveInfo>& PrimitiveCatalogue();
/// The entry of `t` (t must be a valid type).
const PrimitiveInfo& CatalogueEntry(PrimitiveType t);
/// True if `t` has an entry.
bool IsPrimitiveType(int t);

/// The parameter of `entry` with this property name or key, or nullptr.
const ParameterInfo* FindParameter(const PrimitiveInfo& entry, const std::string& name);

/// "a positive finite number", ...: what a value must be.
std::string ConstraintText(Constraint rule);
/// True if one component value satisfies the rule (Expression: always; NonZeroVector:
/// finite, the vector as a whole is checked by CheckParameter).
bool Allows(Constraint rule, double value);
/// Checks the parameter's values in `spec` against its constraint; false with the
/// message BuildFactor gives ("radii[1] must be a positive finite number").
bool CheckParameter(const PrimitiveSpec& spec, const ParameterInfo& p, std::string& error);

/// Writes the parameter's default into `spec`.
void SetDefault(PrimitiveSpec& spec, const ParameterInfo& p);
/// A primitive of type `t` at the origin with its parameters at their defaults (what
/// the editor adds).
PrimitiveSpec DefaultPrimitive(PrimitiveType t);

/// The catalogue as JSON, for the tests of the XML and the documentation:
/// [{"type": 0, "key": "sphere", "label": "Sphere", "bounded": true, "widget": "sphere",
///   "widget_size": "Radius", "widget_direction": null, "parameters": [{"key": "radius",
///   "property": "Radius", "kind": "number", "count": 1, "default": [1], "unit":
///   "length", ...}]}, ...]
std::string CatalogueJSON();
}

#endif
