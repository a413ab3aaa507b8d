// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file pqPiParaViewCompat.h
 * @brief what differs between the ParaView releases the plugin builds against, in one place.
 *
 * Supported: Debian 12's ParaView 5.11 and Debian 13's 5.13. Code outside this header
 * calls the pqPiCompat functions and never tests the ParaView version itself.
 *
 * - 5.12 moved the static scalar-colouring helpers of vtkSMPVRepresentationProxy
 *   (SetScalarColoring, GetUsingScalarColoring on a representation proxy) to
 *   vtkSMColorMapEditorHelper.
 */
#ifndef pqPiParaViewCompat_h
#define pqPiParaViewCompat_h

#include "vtkPVVersion.h"
#include "vtkSMPVRepresentationProxy.h"
#if PARAVIEW_VERSION_MAJOR > 5 || (PARAVIEW_VERSION_MAJOR == 5 && PARAVIEW_VERSION_MINOR >= 12)
#include "vtkSMColorMapEditorHelper.h"
#define PISURFACES_PARAVIEW_COLOR_MAP_EDITOR_HELPER 1
#endif

class vtkSMProxy;

namespace pqPiCompat
{
/// Colours `representation` by the array `name` of `association` (nullptr: solid colour).
inline bool SetScalarColoring(vtkSMProxy* representation, const char* name, int association)
{
#ifdef PISURFACES_PARAVIEW_COLOR_MAP_EDITOR_HELPER
  return vtkSMColorMapEditorHelper::SetScalarColoring(representation, name, association);
#else
  return vtkSMPVRepresentationProxy::SetScalarColoring(representation, name, association);
#endif
}

/// Whether `representation` is coloured by an array.
inline bool GetUsingScalarColoring(vtkSMProxy* representation)
{
#ifdef PISURFACES_PARAVIEW_COLOR_MAP_EDITOR_HELPER
  return vtkSMColorMapEditorHelper::GetUsingScalarColoring(representation);
#else
  return vtkSMPVRepresentationProxy::GetUsingScalarColoring(representation);
#endif
}
}

#endif
