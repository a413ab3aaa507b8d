// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiModel.h
 * @brief the .pisurf model (JSON, version 1): strict reading and exact writing
 *
 * Top-level keys: "pisurf" (must be 1), "blending" (r), "primitives" (non-empty array),
 * and optionally "bounds" [x0,x1,y0,y1,z0,z1], "parameters" {name: number},
 * "name", "description". Each primitive has "type" and the keys of its type (see
 * PiPrimitiveSpec.h), plus optional "name", "center", "axis" or "rotation"
 * {"axis": [x,y,z], "angle": degrees}, "scale", "negate". Any other key is an error.
 * Reading never changes the output model unless the whole text is valid; errors name
 * the key (as a JSON path like primitives[2].radius) or the line and column.
 */
#ifndef PiModel_h
#define PiModel_h

#include "PiPrimitiveSpec.h"

#include <string>
#include <vector>

namespace pisurf
{

struct Model
{
  std::string Name;
  std::string Description;
  double Blending = 0.0;
  bool HasBounds = false;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  ParameterMap Parameters;
  std::vector<PrimitiveSpec> Primitives;
};

/// Nesting deeper than this in a model file is refused.
constexpr int MaxJsonDepth = 32;
/// At most this many primitives in one model file. Meshing costs O(primitives) per grid
/// block and per grid row (10^6 primitives took minutes before the row coefficients
/// were refused for memory); molecules, which have more atoms, are fields of their own
/// (vtkPiMoleculeSurface), not models.
constexpr size_t MaxPrimitives = 100000;

/// Parses and validates (every primitive is built) a .pisurf text.
bool ParseModel(const std::string& text, Model& model, std::string& error);
/// Writes a model as .pisurf JSON that ParseModel reads back to the same function.
std::string WriteModel(const Model& model);
/// Checks bounds: six finite numbers with x0 < x1, y0 < y1, z0 < z1 and finite sides.
bool ValidBounds(const double b[6]);
/// A filter's Bounds setting all zero: "use the data's own box".
bool UnsetBounds(const double requested[6]);
/// `requested` copied into `bounds` if it is a valid box; false with the reason in
/// `error` if not (naming `own`, what all-zero bounds stand for: "model's", ...).
bool TakeBounds(const double requested[6], const char* own, double bounds[6], std::string& error);

/// The product of several models (the ParaView "Pi Product"): their primitives in
/// order, the one blending r given, the parameters merged. A parameter name that a later
/// model gives another value is renamed in that model's expressions (a -> a_2, a_3 ...),
/// so every primitive keeps its own function. Bounds: the union of the bounds of the
/// models that have an unbounded primitive (those need them); none when every primitive
/// is bounded, so the product's automatic bounds grow with r. False with a reason for
/// an empty list, a model without primitives, or a product that does not validate.
bool MultiplyModels(
  const std::vector<Model>& models, double blending, Model& product, std::string& error);

/// `expression` with the parameter `from` renamed `to` (whole names only: renaming a
/// leaves ab and a2 alone).
std::string RenameParameter(
  const std::string& expression, const std::string& from, const std::string& to);
}

#endif
