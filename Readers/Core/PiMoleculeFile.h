// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiMoleculeFile.h
 * @brief reading PDB and mmCIF text into atoms (gemmi), with the reader's selection
 *
 * The plain C++ half of vtkPiMoleculeReader (no VTK), so that the parsing and the
 * selection of atoms can be tested and fuzzed on their own, from a file or a buffer.
 * Selection: one model (1-based), hydrogens, waters and HETATM records on request, and
 * for alternate locations the conformer of highest occupancy (the first on ties).
 * Atoms of unknown element get atomic number 0 and are counted.
 *
 * Every failure is reported as a message, never as an exception or a crash: a parser
 * error (gemmi's message, which names the line), no atom record, no such model, no atom
 * left after the selection, a non-finite coordinate, or more than MaxMoleculeAtoms atoms.
 */
#ifndef PiMoleculeFile_h
#define PiMoleculeFile_h

#include <cstddef>
#include <string>
#include <vector>

namespace pisurf
{

/// Files with more atom records than this are refused (vtkMolecule and the molecular
/// surface are not meant for them; the largest PDB entries have ~10^6 atoms).
constexpr size_t MaxMoleculeAtoms = 5000000;

enum class MoleculeFormat
{
  Detect, ///< from the content (PDB records, mmCIF `data_`, mmJSON)
  Pdb,
  Mmcif
};

struct MoleculeReadOptions
{
  int Model = 1; ///< 1-based position in the file
  bool IncludeHydrogens = true;
  bool IncludeWaters = false;
  bool IncludeHetatm = true;
};

struct MoleculeAtoms
{
  std::vector<double> Coordinates; ///< 3 per atom, Å
  std::vector<int> AtomicNumbers;  ///< 0 for an unknown element
  int NumberOfModels = 0;          ///< models in the file
  size_t Records = 0;              ///< atom records of the model before the selection
  size_t Unknown = 0;              ///< selected atoms of unknown element
};

/// The format a file name implies (.pdb, .ent, .cif, .mmcif, each optionally .gz);
/// Detect for any other name.
MoleculeFormat MoleculeFormatFromName(const std::string& name);

/// Parses `size` bytes at `data` (`name` only appears in messages). On failure returns
/// false, leaves `atoms` empty (NumberOfModels kept if known) and sets `error`.
bool ReadMoleculeBuffer(const char* data, size_t size, const std::string& name,
  MoleculeFormat format, const MoleculeReadOptions& options, MoleculeAtoms& atoms,
  std::string& error);

/// Reads a file, gzipped if its name ends in .gz; the format comes from the name, or
/// from the content for other names.
bool ReadMoleculeFile(const std::string& path, const MoleculeReadOptions& options,
  MoleculeAtoms& atoms, std::string& error);
}

#endif
