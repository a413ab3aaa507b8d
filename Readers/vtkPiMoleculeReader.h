// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiMoleculeReader
 * @brief reads PDB and mmCIF files (optionally gzipped) into a vtkMolecule
 *
 * Built on gemmi (Debian's gemmi-dev, header-only): `.pdb`, `.ent`, `.cif`, `.mmcif`,
 * each also as `.gz`. The output is a vtkMolecule with one atom per selected atom
 * record, and vertex data `AtomicNumber` (int), so it feeds vtkPiMoleculeSurface and
 * ParaView's molecule representation.
 *
 * Selection: the model `Model` (1-based position in the file, default 1: the first
 * model of an NMR ensemble); hydrogens (and deuterium) with IncludeHydrogens (default
 * on); waters (HOH, WAT, DOD, ...) with IncludeWaters (default off); HETATM records
 * other than waters (ligands, ions) with IncludeHetatm (default on). Alternate
 * locations: for each atom, the conformer of highest occupancy (the first one on ties).
 *
 * Elements: from the element column (PDB columns 77–78, mmCIF type_symbol); when it is
 * blank, gemmi's fallback from the atom name (columns 13–14: a name starting with H in
 * a 4-character name is hydrogen, else the letter in column 14 for 1-letter names, else
 * the two-letter symbol). Atoms whose element stays unknown are kept with atomic number
 * 0 and a warning that counts them.
 *
 * Errors (vtkErrorMacro, naming the file; the parser's message names the line): a file
 * that cannot be opened, malformed records, no model of that number, or no atom left
 * after the selection. The output is then empty.
 *
 * @sa vtkPiMoleculeSurface vtkMolecule vtkPDBReader
 */
#ifndef vtkPiMoleculeReader_h
#define vtkPiMoleculeReader_h

#include "vtkMoleculeAlgorithm.h"
#include "vtkPiSurfacesReadersModule.h" // for export macro

#include <string> // for std::string

class VTKPISURFACESREADERS_EXPORT vtkPiMoleculeReader : public vtkMoleculeAlgorithm
{
public:
  static vtkPiMoleculeReader* New();
  vtkTypeMacro(vtkPiMoleculeReader, vtkMoleculeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read (no default).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// Which model (1-based position in the file; default 1).
  vtkSetClampMacro(Model, int, 1, VTK_INT_MAX);
  vtkGetMacro(Model, int);
  ///@}

  ///@{
  /// Keep hydrogen atoms (default on).
  vtkSetMacro(IncludeHydrogens, bool);
  vtkGetMacro(IncludeHydrogens, bool);
  vtkBooleanMacro(IncludeHydrogens, bool);
  ///@}

  ///@{
  /// Keep water molecules (default off).
  vtkSetMacro(IncludeWaters, bool);
  vtkGetMacro(IncludeWaters, bool);
  vtkBooleanMacro(IncludeWaters, bool);
  ///@}

  ///@{
  /// Keep HETATM records other than waters: ligands, ions (default on).
  vtkSetMacro(IncludeHetatm, bool);
  vtkGetMacro(IncludeHetatm, bool);
  vtkBooleanMacro(IncludeHetatm, bool);
  ///@}

  /// The number of models in the file, after the last read (0 before).
  vtkGetMacro(NumberOfModels, int);

  /// True if the name ends with a supported extension (optionally followed by .gz).
  static bool CanReadFileName(const char* name);

protected:
  vtkPiMoleculeReader();
  ~vtkPiMoleculeReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  int Model = 1;
  bool IncludeHydrogens = true;
  bool IncludeWaters = false;
  bool IncludeHetatm = true;
  int NumberOfModels = 0;

private:
  vtkPiMoleculeReader(const vtkPiMoleculeReader&) = delete;
  void operator=(const vtkPiMoleculeReader&) = delete;
};

#endif
