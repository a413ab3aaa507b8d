// SPDX-License-Identifier: BSD-3-Clause
#include "PiFuzzTargets.h"

#include "PiExpression.h"
#include "PiModel.h"
#include "PiMoleculeFile.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace pisurf
{
namespace fuzz
{
namespace
{
[[noreturn]] void Finding(const char* what, const std::string& detail)
{
  std::fprintf(stderr, "FUZZ FINDING: %s: %s\n", what, detail.c_str());
  std::abort();
}
}

void Model(const uint8_t* data, size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  pisurf::Model model;
  std::string error;
  if (!ParseModel(text, model, error))
  {
    if (error.empty())
    {
      Finding("model refused without a message", text);
    }
    return;
  }
  const std::string written = WriteModel(model);
  pisurf::Model again;
  if (!ParseModel(written, again, error))
  {
    Finding("a written model does not parse", error + "\n" + written);
  }
  if (WriteModel(again) != written)
  {
    Finding("a written model does not read back to itself", written);
  }
}

void Expression(const uint8_t* data, size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  const ParameterMap parameters = { { "a", 2.0 }, { "b", -0.5 } };
  Polynomial3 p;
  std::string error;
  std::shared_ptr<const ExpressionNode> tree;
  if (!ParseExpression(text, parameters, p, error, &tree))
  {
    if (error.find("at position") == std::string::npos)
    {
      Finding("expression refused without a position", text + " -> " + error);
    }
    return;
  }
  if (!p.IsFinite() || p.GetDegree() > MaxDegree || !tree)
  {
    Finding("accepted expression with non-finite coefficients or too high a degree", text);
  }
  // The enclosure of the expression as written over [-1/2, 1/2]^3 (outward-rounded: it
  // holds the exact value) must contain the expanded polynomial's computed value at a
  // few points of the box, up to that polynomial's rounding bound (terms that cancel).
  const Interval box[3] = { { -0.5, 0.5 }, { -0.5, 0.5 }, { -0.5, 0.5 } };
  const Interval range = EvaluateInterval(*tree, box);
  double magnitude = 0.0;
  p.EvaluateInterval(box, &magnitude);
  const double rounding = p.RoundingBound(magnitude);
  const double points[3][3] = { { 0, 0, 0 }, { 0.5, -0.5, 0.25 }, { -0.3, 0.1, 0.5 } };
  for (const auto& q : points)
  {
    const double v = p.Evaluate(q);
    if (!std::isfinite(v) || !std::isfinite(range.Lo) || !std::isfinite(range.Hi))
    {
      continue; // overflow of huge coefficients: no containment to check
    }
    const double slack =
      rounding + 1e-9 * (std::fabs(range.Lo) + std::fabs(range.Hi) + std::fabs(v) + 1);
    if (v < range.Lo - slack || v > range.Hi + slack)
    {
      Finding("interval enclosure misses a value", text);
    }
  }
}

void Molecule(const uint8_t* data, size_t size)
{
  if (size < 1)
  {
    return;
  }
  const MoleculeFormat formats[3] = { MoleculeFormat::Detect, MoleculeFormat::Pdb,
    MoleculeFormat::Mmcif };
  MoleculeReadOptions options;
  options.Model = 1 + (data[0] >> 6);
  options.IncludeHydrogens = data[0] & 4;
  options.IncludeWaters = data[0] & 8;
  options.IncludeHetatm = data[0] & 16;
  MoleculeAtoms atoms;
  std::string error;
  const bool ok = ReadMoleculeBuffer(reinterpret_cast<const char*>(data) + 1, size - 1, "fuzz",
    formats[data[0] % 3], options, atoms, error);
  if (!ok)
  {
    if (error.empty() || !atoms.Coordinates.empty())
    {
      Finding("molecule refused without a message or with atoms", error);
    }
    return;
  }
  if (atoms.AtomicNumbers.empty() || atoms.Coordinates.size() != 3 * atoms.AtomicNumbers.size())
  {
    Finding("molecule read with inconsistent atoms", std::to_string(atoms.AtomicNumbers.size()));
  }
  for (double c : atoms.Coordinates)
  {
    if (!std::isfinite(c))
    {
      Finding("molecule read with a non-finite coordinate", "");
    }
  }
}
}
}
