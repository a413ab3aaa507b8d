// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiCatalogueXML.cxx
 * @brief writes the parts of the server-manager XML that list primitive types
 *
 * ParaView reads its proxies from static XML; the primitive types come from the
 * primitive catalogue (Filters/Core/PiPrimitiveCatalogue.h). This build tool copies an
 * XML file and fills in two kinds of marker from the catalogue:
 *
 * - a line holding only `<!-- @PrimitiveTypes@ ... -->` becomes one
 *   `<Entry value="N" text="Label"/>` per catalogue entry, in catalogue order, at the
 *   marker's indentation (the Pi Primitive proxy's `Type` enumeration);
 * - `@TypesWith:Property@` inside a line becomes the space-separated type values whose
 *   parameters include that property (`values="@TypesWith:MinorRadius@"` of a
 *   visibility decorator on `Type`).
 *
 * A marker naming a property no type has, or an unterminated marker, stops the build
 * with a message naming the file and line.
 *
 * Usage: PiCatalogueXML <input.xml> <output.xml>
 */
#include "PiPrimitiveCatalogue.h"

#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace
{

const std::string TypesMarker = "<!-- @PrimitiveTypes@";
const std::string TypesWithMarker = "@TypesWith:";

std::string XmlEscaped(const std::string& text)
{
  std::string out;
  for (char c : text)
  {
    switch (c)
    {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// The type values whose parameters include `property`, space-separated ("" if none).
std::string TypesWith(const std::string& property)
{
  std::string values;
  for (const pisurf::PrimitiveInfo& entry : pisurf::PrimitiveCatalogue())
  {
    // (FindParameter also takes a .pisurf key; the markers name properties only)
    const pisurf::ParameterInfo* p = pisurf::FindParameter(entry, property);
    if (p && property == p->Property)
    {
      values += (values.empty() ? "" : " ") + std::to_string(static_cast<int>(entry.Type));
    }
  }
  return values;
}

/// Replaces every @TypesWith:Property@ of `line`; false with a message on a bad marker.
bool FillTypesWith(std::string& line, std::string& error)
{
  for (size_t at = line.find(TypesWithMarker); at != std::string::npos;
       at = line.find(TypesWithMarker, at))
  {
    const size_t nameStart = at + TypesWithMarker.size();
    const size_t end = line.find('@', nameStart);
    if (end == std::string::npos)
    {
      error = "unterminated " + TypesWithMarker + " marker";
      return false;
    }
    const std::string property = line.substr(nameStart, end - nameStart);
    const std::string values = TypesWith(property);
    if (values.empty())
    {
      error = "no primitive type of the catalogue has the parameter property '" + property + "'";
      return false;
    }
    line.replace(at, end + 1 - at, values);
    at += values.size();
  }
  return true;
}
}

int main(int argc, char* argv[])
{
  if (argc != 3)
  {
    std::cerr << "usage: PiCatalogueXML <input.xml> <output.xml>\n";
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in)
  {
    std::cerr << "PiCatalogueXML: cannot read " << argv[1] << "\n";
    return 1;
  }
  std::ostringstream out;
  std::string line;
  int number = 0;
  while (std::getline(in, line))
  {
    ++number;
    const size_t marker = line.find(TypesMarker);
    if (marker != std::string::npos && line.find_first_not_of(" \t") == marker)
    {
      const std::string indent = line.substr(0, marker);
      for (const pisurf::PrimitiveInfo& entry : pisurf::PrimitiveCatalogue())
      {
        out << indent << "<Entry value=\"" << static_cast<int>(entry.Type) << "\" text=\""
            << XmlEscaped(entry.Label) << "\"/>\n";
      }
      continue;
    }
    std::string error;
    if (!FillTypesWith(line, error))
    {
      std::cerr << argv[1] << ":" << number << ": " << error << "\n";
      return 1;
    }
    out << line << "\n";
  }
  // Written only when complete, so that a failed run leaves no half file for the build.
  std::ofstream result(argv[2]);
  result << out.str();
  if (!result)
  {
    std::cerr << "PiCatalogueXML: cannot write " << argv[2] << "\n";
    return 1;
  }
  return 0;
}
