// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiMoleculeReader.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMolecule.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkDataSetAttributes.h"

#include <gemmi/gz.hpp>
#include <gemmi/mmread.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <string>

vtkStandardNewMacro(vtkPiMoleculeReader);

vtkPiMoleculeReader::vtkPiMoleculeReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkPiMoleculeReader::~vtkPiMoleculeReader() = default;

int vtkPiMoleculeReader::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkMolecule");
  return 1;
}

bool vtkPiMoleculeReader::CanReadFileName(const char* name)
{
  if (!name)
  {
    return false;
  }
  std::string s(name);
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  if (s.size() > 3 && s.compare(s.size() - 3, 3, ".gz") == 0)
  {
    s.resize(s.size() - 3);
  }
  for (const char* ext : { ".pdb", ".ent", ".cif", ".mmcif" })
  {
    const size_t n = std::char_traits<char>::length(ext);
    if (s.size() > n && s.compare(s.size() - n, n, ext) == 0)
    {
      return true;
    }
  }
  return false;
}

int vtkPiMoleculeReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkMolecule* output = vtkMolecule::GetData(outputVector, 0);
  this->NumberOfModels = 0;
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName");
    return 0;
  }
  if (!std::ifstream(this->FileName).good())
  {
    vtkErrorMacro(<< "Cannot open " << this->FileName);
    return 0;
  }
  std::string lower = this->FileName;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  gemmi::Structure structure;
  try
  {
    gemmi::MaybeGzipped input(this->FileName);
    // The format from the extension; an unknown extension is detected from the content.
    gemmi::CoorFormat format = gemmi::coor_format_from_ext(input.basepath());
    if (lower.size() > 4 && lower.compare(lower.size() - 4, 4, ".ent") == 0)
    {
      format = gemmi::CoorFormat::Pdb;
    }
    if (format == gemmi::CoorFormat::Unknown)
    {
      format = gemmi::CoorFormat::Detect;
    }
    structure = gemmi::read_structure(input, format);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Cannot read " << this->FileName << ": " << e.what());
    return 0;
  }
  this->NumberOfModels = static_cast<int>(structure.models.size());
  if (structure.models.empty())
  {
    vtkErrorMacro(<< "No atoms in " << this->FileName
                  << " (no ATOM/HETATM records or mmCIF _atom_site table were found)");
    return 0;
  }
  if (this->Model > this->NumberOfModels)
  {
    vtkErrorMacro(<< "Model " << this->Model << " requested but " << this->FileName << " has "
                  << this->NumberOfModels << " model(s)");
    return 0;
  }
  const gemmi::Model& model = structure.models[this->Model - 1];

  vtkNew<vtkMolecule> molecule;
  vtkNew<vtkIntArray> numbers;
  numbers->SetName("AtomicNumber");
  vtkIdType unknown = 0, records = 0;
  for (const gemmi::Chain& chain : model.chains)
  {
    for (const gemmi::Residue& residue : chain.residues)
    {
      const bool water = residue.is_water();
      if (water && !this->IncludeWaters)
      {
        continue;
      }
      if (!water && residue.het_flag == 'H' && !this->IncludeHetatm)
      {
        continue;
      }
      const std::vector<gemmi::Atom>& atoms = residue.atoms;
      for (size_t a = 0; a < atoms.size(); ++a)
      {
        const gemmi::Atom& atom = atoms[a];
        ++records;
        if (atom.is_hydrogen() && !this->IncludeHydrogens)
        {
          continue;
        }
        if (atom.has_altloc())
        {
          // Keep the conformer of highest occupancy (the first on ties): skip this one if
          // another location of the same atom is better.
          bool best = true;
          for (size_t b = 0; b < atoms.size() && best; ++b)
          {
            if (b != a && atoms[b].name == atom.name && atoms[b].has_altloc())
            {
              best = !(atoms[b].occ > atom.occ || (atoms[b].occ == atom.occ && b < a));
            }
          }
          if (!best)
          {
            continue;
          }
        }
        int z = atom.element.atomic_number();
        if (atom.element == gemmi::El::X)
        {
          z = 0;
          ++unknown;
        }
        molecule->AppendAtom(static_cast<unsigned short>(z), atom.pos.x, atom.pos.y, atom.pos.z);
        numbers->InsertNextValue(z);
      }
    }
  }
  if (records == 0)
  {
    vtkErrorMacro(<< "No atoms in model " << this->Model << " of " << this->FileName
                  << ": no ATOM/HETATM records (an empty, truncated or non-PDB file?)");
    return 0;
  }
  if (molecule->GetNumberOfAtoms() == 0)
  {
    vtkErrorMacro(<< "No atoms left in model " << this->Model << " of " << this->FileName << " ("
                  << records << " atom records before the selection of hydrogens, waters "
                  << "and HETATM)");
    return 0;
  }
  if (unknown > 0)
  {
    vtkWarningMacro(<< unknown << " atom(s) of unknown element in " << this->FileName
                    << " (element column and atom name both unrecognised): atomic number 0");
  }
  molecule->GetVertexData()->AddArray(numbers);
  output->ShallowCopy(molecule);
  return 1;
}

void vtkPiMoleculeReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Model: " << this->Model << "\n";
  os << indent << "IncludeHydrogens: " << (this->IncludeHydrogens ? "On" : "Off") << "\n";
  os << indent << "IncludeWaters: " << (this->IncludeWaters ? "On" : "Off") << "\n";
  os << indent << "IncludeHetatm: " << (this->IncludeHetatm ? "On" : "Off") << "\n";
  os << indent << "NumberOfModels: " << this->NumberOfModels << "\n";
}
