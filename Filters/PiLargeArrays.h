// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiLargeArrays.h
 * @brief VTK output arrays in pisurf::AllocateLarge's memory
 *
 * Output arrays that a filter fills completely right after allocating them (a sampled
 * grid, a mesh's points, normals and cells): uninitialized, from 512 KiB on in blocks
 * that pisurf::ReleaseLarge keeps for the next execution's arrays (up to
 * pisurf::LargeCacheBytes of idle memory), so that a re-execution writes memory that is
 * already faulted in (see pisurf::AllocateLarge). The array owns the memory and gives
 * it back with pisurf::ReleaseLarge.
 */
#ifndef PiLargeArrays_h
#define PiLargeArrays_h

#include "PiBuffer.h"

#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkType.h"

namespace pisurf
{

/// Sizes `array` (a vtkAOSDataArrayTemplate with its components set) to `tuples`
/// uninitialized tuples. Where the memory cannot be had, VTK's own allocation (and its
/// error) decides.
template <typename ArrayT>
void AllocateLargeArray(ArrayT* array, vtkIdType tuples)
{
  using Value = typename ArrayT::ValueType;
  const vtkIdType values = tuples * array->GetNumberOfComponents();
  void* data =
    values > 0 ? pisurf::AllocateLarge(sizeof(Value) * static_cast<size_t>(values)) : nullptr;
  if (!data)
  {
    array->SetNumberOfTuples(tuples);
    return;
  }
  // Given back through pisurf::ReleaseLarge (kept for a later execution, see there).
  array->SetArray(static_cast<Value*>(data), values, 0, ArrayT::VTK_DATA_ARRAY_USER_DEFINED);
  array->SetArrayFreeFunction(&pisurf::ReleaseLarge);
}

/// Gives `points` `count` uninitialized double-precision points in that memory.
inline void AllocateLargePoints(vtkPoints* points, vtkIdType count)
{
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  AllocateLargeArray(coordinates.GetPointer(), count);
  points->SetData(coordinates);
}

}

#endif
