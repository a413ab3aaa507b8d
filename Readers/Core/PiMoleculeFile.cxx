// SPDX-License-Identifier: BSD-3-Clause
#include "PiMoleculeFile.h"

#include <gemmi/gz.hpp>
#include <gemmi/mmread.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
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
    error =
      "No atoms in " + name + " (no ATOM/HETATM records or mmCIF _atom_site table were found)";
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

// A coordinate field of a PDB record: blanks, then [-+]digits[.digits] (or .digits).
bool IsCoordinate(const char* f, size_t n)
{
  size_t i = 0;
  while (i < n && f[i] == ' ')
  {
    ++i;
  }
  if (i < n && (f[i] == '-' || f[i] == '+'))
  {
    ++i;
  }
  size_t digits = 0;
  while (i < n && std::isdigit(static_cast<unsigned char>(f[i])))
  {
    ++i;
    ++digits;
  }
  if (i < n && f[i] == '.')
  {
    ++i;
    while (i < n && std::isdigit(static_cast<unsigned char>(f[i])))
    {
      ++i;
      ++digits;
    }
  }
  return digits > 0 && i == n;
}

// gemmi reads PDB coordinates leniently ("x0.000" or a shifted column gives some
// number): a hand-edited file would silently give wrong atoms. Columns 31-54 of every
// ATOM/HETATM record must hold three numbers, and the text must have no NUL byte.
bool CheckPdbCoordinates(const std::vector<char>& text, const std::string& name, std::string& error)
{
  size_t line = 1;
  for (size_t start = 0; start < text.size(); ++line)
  {
    size_t end = start;
    while (end < text.size() && text[end] != '\n')
    {
      if (text[end] == '\0')
      {
        // gemmi keeps some records as C strings: a NUL would cut them short.
        error = "Cannot read " + name + ": line " + std::to_string(line) +
          ": a NUL byte (binary data, not PDB text)";
        return false;
      }
      ++end;
    }
    const char* l = text.data() + start;
    const size_t n = end - start - (end > start && text[end - 1] == '\r' ? 1 : 0);
    if (n >= 6 && (std::strncmp(l, "ATOM  ", 6) == 0 || std::strncmp(l, "HETATM", 6) == 0))
    {
      if (n < 54)
      {
        error = "Cannot read " + name + ": line " + std::to_string(line) +
          ": an atom record shorter than 54 characters (no x, y, z in columns 31-54)";
        return false;
      }
      for (int c = 0; c < 3; ++c)
      {
        if (!IsCoordinate(l + 30 + 8 * c, 8))
        {
          error = "Cannot read " + name + ": line " + std::to_string(line) + ": columns " +
            std::to_string(31 + 8 * c) + "-" + std::to_string(38 + 8 * c) + " ('" +
            std::string(l + 30 + 8 * c, 8) + "') must hold the " + "xyz"[c] +
            " coordinate (wrong columns?)";
          return false;
        }
      }
    }
    start = end + 1;
  }
  return true;
}

// PDB is a format of 80-column lines, and gemmi reads its fixed columns without
// checking the line's length (a 75-character LINK or SSBOND record made fast_float read
// past the end of the line: found by ./run fuzz molecule). Lines are cut or padded with
// blanks to exactly 80 columns, which the format defines as blank fields.
std::vector<char> PadPdbLines(const std::vector<char>& text)
{
  std::vector<char> padded;
  padded.reserve(text.size() + text.size() / 8 + 81);
  size_t start = 0;
  while (start < text.size())
  {
    size_t end = start;
    while (end < text.size() && text[end] != '\n')
    {
      ++end;
    }
    size_t length = end - start;
    if (length > 0 && text[end - 1] == '\r')
    {
      --length;
    }
    // Beyond column 80 nothing is defined; and gemmi, skipping the rest of a line longer
    // than 120 characters, stops at a byte >= 0x80 and reads the remainder as a new,
    // short record (a LINK there overran its buffer: found by fuzzing).
    length = std::min<size_t>(length, 80);
    const size_t first = padded.size();
    padded.insert(padded.end(), text.begin() + start, text.begin() + start + length);
    if (length < 80)
    {
      padded.insert(padded.end(), 80 - length, ' ');
    }
    // Connection records (SSBOND, LINK, CISPEP) are not used here, and gemmi's reading
    // of them still overran a line (found by fuzzing): they become blank records.
    const char* record = padded.data() + first;
    if (gemmi::pdb_impl::is_record_type(record, "SSBOND") ||
      gemmi::pdb_impl::is_record_type(record, "LINK") ||
      gemmi::pdb_impl::is_record_type(record, "CISPEP"))
    {
      std::fill(padded.begin() + first, padded.end(), ' ');
    }
    padded.push_back('\n');
    start = end + 1;
  }
  return padded;
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
    if (size == 0)
    {
      // Not given to gemmi: its format detection does arithmetic on the (null) data.
      error = "No atoms in " + name + ": the file is empty (no ATOM/HETATM records)";
      return false;
    }
    if (format == MoleculeFormat::Detect)
    {
      const gemmi::CoorFormat detected =
        gemmi::coor_format_from_content(text.data(), text.data() + size);
      format = detected == gemmi::CoorFormat::Pdb ? MoleculeFormat::Pdb : format;
    }
    if (format == MoleculeFormat::Pdb && !CheckPdbCoordinates(text, name, error))
    {
      atoms = MoleculeAtoms();
      return false;
    }
    if (format == MoleculeFormat::Pdb)
    {
      text = PadPdbLines(text);
    }
    const size_t parsed = text.size();
    text.push_back('\0');
    gemmi::Structure structure;
    switch (format)
    {
      case MoleculeFormat::Pdb:
        structure = gemmi::read_pdb_from_memory(text.data(), parsed, name);
        break;
      case MoleculeFormat::Mmcif:
        structure =
          gemmi::make_structure(gemmi::cif::read_memory(text.data(), parsed, name.c_str()));
        break;
      case MoleculeFormat::Detect:
        structure = gemmi::read_structure_from_char_array(text.data(), parsed, name);
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
