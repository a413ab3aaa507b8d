// SPDX-License-Identifier: BSD-3-Clause
// The cast pass of vtkPiRayCaster: every ray of every image row of every view, each
// row's hits in increasing depth, searched only in the depth ranges that empty-space
// skipping leaves (RaySkipping) and, in orthographic views of polynomial products,
// restricted from the view's grid (RayGrid).
#ifndef PiRayRowCaster_h
#define PiRayRowCaster_h

#include "PiRayCaster.h"
#include "PiRaySkipping.h"
#include "PiRayView.h"

#include "vtkType.h"

#include <atomic>
#include <memory>
#include <vector>

class vtkAlgorithm;

namespace pisurf
{
// The roots of F along one ray segment, overflow-safe and certified for polynomials.
struct RayRowCaster
{
  const std::vector<RayView>* Views;
  const double* Bounds;
  bool AllHits;
  double Tolerance;
  std::vector<std::vector<RayHit>>* Rows; // per (view, j)
  const RayCaster* Caster;
  const std::vector<std::unique_ptr<RayGrid>>* Grids; // per view; null: per ray
  const std::vector<RayViewSkipping>* Skipping;       // per view
  vtkAlgorithm* Algorithm;                            // for the progress and the abort check
  std::atomic<bool>* Abort;
  int RowBegin, RowEnd;             // the image rows [RowBegin, RowEnd) of every view
  std::atomic<vtkIdType>* Finished; // rows cast so far, for the progress
  vtkIdType RowCount;

  // Work buffers of one thread's chunk of rows (locals of operator(), not thread_local:
  // a thread_local costs a call to find it at every ray).
  struct Buffers
  {
    std::vector<RayRoot> Roots;
    std::vector<double> Coefficients, Row;
    std::vector<double> Cuts;  // a run of joined ranges: its cuts (in s) and
    std::vector<int> Monotony; // each piece's monotony (see Cast)
  };

  /// Casts the RowCount rows, threaded.
  void Run();

  /// Per view, the grid its rays restrict from: orthographic views of polynomial
  /// products; null for the others.
  static std::vector<std::unique_ptr<RayGrid>> MakeGrids(
    const ProductKernel& kernel, const std::vector<RayView>& views, const double bounds[6]);

  // Rows [begin, end) of the RowCount rows, view by view (the functor of Run).
  void operator()(vtkIdType begin, vtkIdType end);

private:
  void Cast(const RayView& v, int viewIndex, int i, int j, std::vector<RayHit>& out,
    Buffers& buffers, const RayGrid* grid = nullptr) const;
};
}

#endif
