// SPDX-License-Identifier: BSD-3-Clause
#include "PiPrimitiveMeshes.h"

#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPiFlyingEdges.h"
#include "vtkPiSurface.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

namespace pisurf
{

void MeshPrimitives(vtkPiSurface* surface, const double bounds[6], const int dims[3], int piece,
  int pieces, bool projectVertices, vtkAlgorithm* owner, vtkPolyData* out)
{
  vtkNew<vtkAppendPolyData> append;
  const int n = surface->GetNumberOfFactors();
  for (int i = 0; i < n && !owner->CheckAbort(); ++i)
  {
    vtkNew<vtkPiSurface> alone;
    alone->AddFactor(surface->GetFactor(i));
    vtkNew<vtkPiFlyingEdges> mesher;
    // A primitive may have no real points (the paper's concavity uses the "sphere"
    // −x²−y²−z²−0.01): its empty mesh is expected, not worth a warning.
    vtkNew<vtkCallbackCommand> quiet;
    mesher->AddObserver(vtkCommand::WarningEvent, quiet);
    mesher->SetPiSurface(alone);
    mesher->SetBounds(bounds);
    mesher->SetSampleDimensions(dims[0], dims[1], dims[2]);
    mesher->SetOuterEnvelope(false);
    mesher->SetGeneratePrimitives(false);
    mesher->SetProjectVertices(projectVertices);
    mesher->UpdatePiece(piece, pieces, 0);
    vtkNew<vtkPolyData> mesh;
    mesh->ShallowCopy(mesher->GetOutput());
    mesh->GetFieldData()->Initialize();
    vtkDataArray* factor = mesh->GetPointData()->GetArray("Factor");
    if (factor)
    {
      factor->Fill(i);
    }
    append->AddInputData(mesh);
  }
  if (n > 0)
  {
    append->Update();
    out->ShallowCopy(append->GetOutput());
  }
}

}
