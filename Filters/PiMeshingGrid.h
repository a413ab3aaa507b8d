// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiMeshingGrid.h
 * @brief the sampling grid of a mesher from its settings
 *
 * The grid vtkPiFlyingEdges and vtkPiModelMesher mesh on: `resolution` cells along the
 * longest side of the bounds (the other sides get cells of nearly the same size), or
 * `sampleDimensions` points per axis when any is non-zero, refused above
 * `maximumNumberOfSamples`.
 */
#ifndef PiMeshingGrid_h
#define PiMeshingGrid_h

#include "vtkType.h"

#include <string>

namespace pisurf
{

/// Dims and spacing of the grid over `bounds`; false with `error` set for invalid
/// settings (each caller reports `error` as its own).
bool ComputeMeshingGrid(const double bounds[6], int resolution, const int sampleDimensions[3],
  vtkIdType maximumNumberOfSamples, int dims[3], double spacing[3], std::string& error);

}

#endif
