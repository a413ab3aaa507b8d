// SPDX-License-Identifier: BSD-3-Clause
// The point output pass of vtkPiRayCaster: the piece's hits as vertices, the views and
// the model as field data.
#include "PiRayPointOutput.h"

#include "PiLargeArrays.h"
#include "PiModel.h"
#include "PiRayHitAttributes.h"
#include "PiRayPieceRows.h"
#include "vtkPiSurface.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTypeInt32Array.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace pisurf
{
void RayPointOutput::SetPoints(
  const RayHitAttributes& hits, const RayPieceRows& rows, vtkPolyData* output)
{
  vtkPointData* pd = output->GetPointData();
  const std::vector<vtkDataArray*> arrays = hits.Arrays();
  if (!rows.ExtraRows())
  {
    output->SetPoints(hits.Points);
    for (vtkDataArray* a : arrays)
    {
      pd->AddArray(a);
    }
  }
  else
  {
    // The image needed rows beyond this piece's: the points are the piece's rows only.
    vtkNew<vtkIdList> keep;
    const vtkIdType n = hits.GetNumberOfHits();
    const int pieceBegin = rows.PieceBegin, pieceEnd = rows.PieceEnd;
    const int* pixelOut = hits.Pixel->GetPointer(0);
    for (vtkIdType k = 0; k < n; ++k)
    {
      if (pixelOut[2 * k + 1] >= pieceBegin && pixelOut[2 * k + 1] < pieceEnd)
      {
        keep->InsertNextId(k);
      }
    }
    vtkNew<vtkPoints> kept;
    kept->SetDataTypeToDouble();
    kept->SetNumberOfPoints(keep->GetNumberOfIds()); // GetPoints fills, does not allocate
    hits.Points->GetPoints(keep, kept);
    output->SetPoints(kept);
    for (vtkDataArray* a : arrays)
    {
      vtkSmartPointer<vtkDataArray> part = vtk::TakeSmartPointer(a->NewInstance());
      part->SetName(a->GetName());
      part->SetNumberOfComponents(a->GetNumberOfComponents());
      part->SetNumberOfTuples(keep->GetNumberOfIds());
      a->GetTuples(keep, part);
      pd->AddArray(part);
    }
  }
  pd->SetActiveNormals("Normals");
  SetVerts(output);
}

void RayPointOutput::SetVerts(vtkPolyData* output)
{
  const vtkIdType kept = output->GetNumberOfPoints();
  // One vertex cell per point: offsets 0..kept and connectivity 0..kept−1, handed to
  // the cell array as they are (in its 32-bit storage when the ids fit).
  vtkNew<vtkCellArray> verts;
  auto fillVerts = [&](auto* offsets, auto* ids)
  {
    pisurf::AllocateLargeArray(offsets, kept + 1);
    pisurf::AllocateLargeArray(ids, kept);
    auto* offsetOut = offsets->GetPointer(0);
    auto* idOut = ids->GetPointer(0);
    using Id = typename std::remove_pointer<decltype(idOut)>::type;
    vtkSMPTools::For(0, kept + 1,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType k = begin; k < end; ++k)
        {
          offsetOut[k] = static_cast<Id>(k);
          if (k < kept)
          {
            idOut[k] = static_cast<Id>(k);
          }
        }
      });
    verts->SetData(offsets, ids);
  };
  if (kept < std::numeric_limits<std::int32_t>::max())
  {
    vtkNew<vtkTypeInt32Array> offsets, ids;
    fillVerts(offsets.GetPointer(), ids.GetPointer());
  }
  else
  {
    vtkNew<vtkIdTypeArray> offsets, ids;
    fillVerts(offsets.GetPointer(), ids.GetPointer());
  }
  output->SetVerts(verts);
}

void RayPointOutput::AddViews(const std::vector<RayView>& views, bool allHits, vtkPolyData* output)
{
  vtkNew<vtkDoubleArray> viewData;
  viewData->SetName("PiRayViews");
  viewData->SetNumberOfComponents(17);
  for (const RayView& v : views)
  {
    const double t[17] = { v.Perspective ? 1.0 : 0.0, double(v.W), double(v.H), v.O[0], v.O[1],
      v.O[2], v.U[0], v.U[1], v.U[2], v.V[0], v.V[1], v.V[2], v.D[0], v.D[1], v.D[2], v.Length,
      allHits ? 1.0 : 0.0 };
    viewData->InsertNextTuple(t);
  }
  output->GetFieldData()->AddArray(viewData);
}

void RayPointOutput::AddModel(vtkPiSurface& surface, const double b[6], vtkPolyData* output)
{
  Model model;
  if (surface.GetCoreModel(model))
  {
    if (!model.HasBounds)
    {
      model.HasBounds = true;
      std::copy(b, b + 6, model.Bounds);
    }
    vtkNew<vtkStringArray> json;
    json->SetName("PiSurfaceModel");
    json->InsertNextValue(WriteModel(model));
    output->GetFieldData()->AddArray(json);
  }
}
}
