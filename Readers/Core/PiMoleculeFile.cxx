// SPDX-License-Identifier: BSD-3-Clause
#include "PiMoleculeFile.h"

#include <gemmi/gz.hpp>
#include <gemmi/mmread.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <fstream>
#include <iterator>

namespace pisurf
{
namespace
{
bool EndsWith(const std::string& s, const char* suffix)
{
  const size_t n = std::char_traits<char>::length(suffix);
  return s.size() > n && s.compare(s.size() - n, n, suffix) == 0;
}

std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// The atoms of one model, selected as the header says.
bool Select(const gemmi::Structure& structure, const std::string& name,
  const MoleculeReadOptions& options, MoleculeAtoms& out, std::string& error)
{
  out.NumberOfModels = static_cast<int>(structure.models.size());
  if (structure.models.empty())
  {
    error = "No atoms in " + name + " (no ATOM/HETATM records or mmCIF _atom_site table were found)";
    return false;
  }
  if (options.Model < 1 || options.Model > out.NumberOfModels)
  {
    error = "Model " + std::to_string(options.Model) + " requested but " + name + " has " +
      std::to_string(out.NumberOfModels) + " model(s)";
    return false;
  }
  const gemmi::Model& model = structure.models[options.Model - 1];
  for (const gemmi::Chain& chain : model.chains)
  {
    for (const gemmi::Residue& residue : chain.residues)
    {
      out.Records += residue.atoms.size();
    }
  }
  if (out.Records == 0)
  {
    error = "No atoms in model " + std::to_string(options.Model) + " of " + name +
      ": no ATOM/HETATM records (an empty, truncated or non-PDB file?)";
    return false;
  }
  if (out.Records > MaxMoleculeAtoms)
  {
    error = "Too many atoms in model " + std::to_string(options.Model) + " of " + name + ": " +
      std::to_string(out.Records) + " (at most " + std::to_string(MaxMoleculeAtoms) + ")";
    return false;
  }
  for (const gemmi::Chain& chain : model.chains)
  {
    for (const gemmi::Residue& residue : chain.residues)
    {
      const bool water = residue.is_water();
      if (water && !options.IncludeWaters)
      {
        continue;
      }
      if (!water && residue.het_flag == 'H' && !options.IncludeHetatm)
      {
        continue;
      }
      const std::vector<gemmi::Atom>& atoms = residue.atoms;
      for (size_t a = 0; a < atoms.size(); ++a)
      {
        const gemmi::Atom& atom = atoms[a];
        if (atom.is_hydrogen() && !options.IncludeHydrogens)
        {
          continue;
        }
        if (atom.has_altloc())
        {
          // Keep the conformer of highest occupancy (the first on ties): skip this one if
          // another location of the same atom is better. Quadratic in the residue's atoms
          // only when every atom has alternate locations.
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
        const double p[3] = { atom.pos.x, atom.pos.y, atom.pos.z };
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        {
          error = "Atom '" + atom.name + "' of residue " + residue.name + " " +
            residue.seqid.str() + " in " + name + " has a coordinate that is not a finite number";
          return false;
        }
        int z = atom.element.atomic_number();
        if (atom.element == gemmi::El::X)
        {
          z = 0;
          ++out.Unknown;
        }
        out.Coordinates.insert(out.Coordinates.end(), p, p + 3);
        out.AtomicNumbers.push_back(z);
      }
    }
  }
  if (out.AtomicNumbers.empty())
  {
    error = "No atoms left in model " + std::to_string(options.Model) + " of " + name + " (" +
      std::to_string(out.Records) +
      " atom records before the selection of hydrogens, waters and HETATM)";
    return false;
  }
  return true;
}

bool Parse(std::vector<char>& text, const std::string& name, MoleculeFormat format,
  const MoleculeReadOptions& options, MoleculeAtoms& atoms, std::string& error)
{
  atoms = MoleculeAtoms();
  bool ok = false;
  try
  {
    // gemmi's parsers read up to the given size; the terminating NUL is for the ones
    // that look one character ahead.
    const size_t size = text.size();
    text.push_back('\0');
    gemmi::Structure structure;
    switch (format)
    {
      case MoleculeFormat::Pdb:
        structure = gemmi::read_pdb_from_memory(text.data(), size, name);
        break;
      case MoleculeFormat::Mmcif:
        structure = gemmi::make_structure(gemmi::cif::read_memory(text.data(), size, name.c_str()));
        break;
      case MoleculeFormat::Detect:
        structure = gemmi::read_structure_from_char_array(text.data(), size, name);
        break;
    }
    ok = Select(structure, name, options, atoms, error);
  }
  catch (const std::exception& e)
  {
    error = "Cannot read " + name + ": " + e.what();
    ok = false;
  }
  if (!ok)
  {
    const int models = atoms.NumberOfModels;
    atoms = MoleculeAtoms();
    atoms.NumberOfModels = models;
  }
  return ok;
}
}

MoleculeFormat MoleculeFormatFromName(const std::string& fileName)
{
  std::string s = Lower(fileName);
  if (EndsWith(s, ".gz"))
  {
    s.resize(s.size() - 3);
  }
  if (EndsWith(s, ".pdb") || EndsWith(s, ".ent"))
  {
    return MoleculeFormat::Pdb;
  }
  if (EndsWith(s, ".cif") || EndsWith(s, ".mmcif"))
  {
    return MoleculeFormat::Mmcif;
  }
  return MoleculeFormat::Detect;
}

bool ReadMoleculeBuffer(const char* data, size_t size, const std::string& name,
  MoleculeFormat format, const MoleculeReadOptions& options, MoleculeAtoms& atoms,
  std::string& error)
{
  std::vector<char> text(data, data + size);
  return Parse(text, name, format, options, atoms, error);
}

bool ReadMoleculeFile(const std::string& path, const MoleculeReadOptions& options,
  MoleculeAtoms& atoms, std::string& error)
{
  atoms = MoleculeAtoms();
  if (!std::ifstream(path).good())
  {
    error = "Cannot open " + path;
    return false;
  }
  std::vector<char> text;
  try
  {
    gemmi::MaybeGzipped input(path);
    if (input.is_compressed())
    {
      gemmi::CharArray mem = input.uncompress_into_buffer();
      text.assign(mem.data(), mem.data() + mem.size());
    }
    else
    {
      // Not gemmi's reader: it refuses an empty file with a misleading system error.
      std::ifstream file(path, std::ios::binary);
      text.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
      if (file.bad())
      {
        error = "Cannot read " + path;
        return false;
      }
    }
  }
  catch (const std::exception& e)
  {
    error = "Cannot read " + path + ": " + e.what();
    return false;
  }
  return Parse(text, path, MoleculeFormatFromName(path), options, atoms, error);
}
}
