// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiFuzzTargets.h
 * @brief the fuzzed entry points and the properties every input must keep
 *
 * Each target parses arbitrary bytes and aborts (a finding) if a property documented by
 * the parser fails; crashes, hangs, leaks and undefined behaviour are found by the
 * sanitizers around it. The same functions replay the seed corpus and every former
 * finding as a unit test (Core.FuzzRegression), so a finding fixed stays fixed.
 */
#ifndef PiFuzzTargets_h
#define PiFuzzTargets_h

#include <cstddef>
#include <cstdint>

namespace pisurf
{
namespace fuzz
{
/// .pisurf text: a model that parses writes back (WriteModel) to text that parses again
/// to the same model text; a refusal has a message.
void Model(const uint8_t* data, size_t size);
/// Expression text (parameters a = 2, b = -0.5): an accepted expression has finite
/// coefficients, degree <= MaxDegree, and its interval enclosure over a box contains
/// its value at the box's points; a refusal has a message with a position.
void Expression(const uint8_t* data, size_t size);
/// Molecule file bytes; the first byte picks the format (detect, PDB, mmCIF) and the
/// selection: atoms read have finite coordinates and one atomic number each.
void Molecule(const uint8_t* data, size_t size);
}
}

#endif
