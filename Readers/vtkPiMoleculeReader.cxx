// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiMoleculeReader.h"

#include "vtkDataSetAttributes.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMolecule.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"

#include "PiMoleculeFile.h"

#include <algorithm>
#include <cctype>
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
  pisurf::MoleculeReadOptions options;
  options.Model = this->Model;
  options.IncludeHydrogens = this->IncludeHydrogens;
  options.IncludeWaters = this->IncludeWaters;
  options.IncludeHetatm = this->IncludeHetatm;
  pisurf::MoleculeAtoms atoms;
  std::string error;
  const bool ok = pisurf::ReadMoleculeFile(this->FileName, options, atoms, error);
  this->NumberOfModels = atoms.NumberOfModels;
  if (!ok)
  {
    vtkErrorMacro(<< error);
    return 0;
  }

  vtkNew<vtkMolecule> molecule;
  vtkNew<vtkIntArray> numbers;
  numbers->SetName("AtomicNumber");
  const vtkIdType n = static_cast<vtkIdType>(atoms.AtomicNumbers.size());
  numbers->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double* p = &atoms.Coordinates[3 * i];
    molecule->AppendAtom(static_cast<unsigned short>(atoms.AtomicNumbers[i]), p[0], p[1], p[2]);
    numbers->SetValue(i, atoms.AtomicNumbers[i]);
  }
  if (atoms.Unknown > 0)
  {
    vtkWarningMacro(<< atoms.Unknown << " atom(s) of unknown element in " << this->FileName
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
